#include "compiler/diag/DiagnosticRenderer.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>

namespace cbtl {
namespace {

const char* severityName(Severity s) { return s == Severity::Error ? "error" : "warning"; }
const char* childName(ChildKind k) { return k == ChildKind::Note ? "note" : "help"; }

std::size_t codePoints(std::string_view s) {
  return static_cast<std::size_t>(
      std::count_if(s.begin(), s.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
}

// Tabs become single spaces so the caret line stays aligned in any terminal.
std::string untab(std::string_view s) {
  std::string out(s);
  std::replace(out.begin(), out.end(), '\t', ' ');
  return out;
}

void appendExcerpt(std::string& out, const SourceRange& range, const SourceManager& sources) {
  const LineCol start = sources.position(range.file, range.begin);
  const LineCol stop = sources.position(range.file, range.end);
  const std::string_view line = sources.lineText(range.file, start.line);
  const std::string number = std::to_string(start.line);
  const std::string gutter(number.size(), ' ');
  std::size_t width = 1;
  const std::size_t lineWidth = codePoints(line);
  if (stop.line == start.line && stop.column > start.column) {
    width = stop.column - start.column;
  } else if (stop.line > start.line) {
    width = lineWidth >= start.column ? lineWidth - start.column + 1 : 1;
  }
  out += fmt::format(" {} |\n", gutter);
  out += fmt::format(" {} | {}\n", number, untab(line));
  out += fmt::format(" {} | {}^{}\n", gutter, std::string(start.column - 1, ' '), std::string(width - 1, '~'));
}

std::string location(const SourceRange& range, const SourceManager& sources) {
  const LineCol p = sources.position(range.file, range.begin);
  return fmt::format("{}:{}:{}", sources.file(range.file).path, p.line, p.column);
}

nlohmann::json spanJson(const SourceRange& range, const SourceManager& sources) {
  const LineCol a = sources.position(range.file, range.begin);
  const LineCol b = sources.position(range.file, range.end);
  return nlohmann::json{{"file", sources.file(range.file).path},
                        {"line", a.line},
                        {"column", a.column},
                        {"end_line", b.line},
                        {"end_column", b.column},
                        {"byte_start", range.begin},
                        {"byte_end", range.end}};
}

}  // namespace

std::string renderDiagnosticText(const Diagnostic& d, const SourceManager& sources) {
  std::string out;
  out += fmt::format("{}: {}[{}]: {}\n", location(d.range, sources), severityName(d.severity), d.code, d.message);
  appendExcerpt(out, d.range, sources);
  for (const auto& child : d.children) {
    if (child.range.valid()) {
      out += fmt::format("{}: {}: {}\n", location(child.range, sources), childName(child.kind), child.message);
      appendExcerpt(out, child.range, sources);
    } else {
      out += fmt::format("  = {}: {}\n", childName(child.kind), child.message);
    }
  }
  return out;
}

std::string renderDiagnosticJson(const Diagnostic& d, const SourceManager& sources) {
  nlohmann::json j;
  j["severity"] = severityName(d.severity);
  j["code"] = d.code;
  j["message"] = d.message;
  j["span"] = spanJson(d.range, sources);
  nlohmann::json children = nlohmann::json::array();
  for (const auto& child : d.children) {
    nlohmann::json c{{"kind", childName(child.kind)}, {"message", child.message}};
    if (child.range.valid()) c["span"] = spanJson(child.range, sources);
    children.push_back(std::move(c));
  }
  j["children"] = std::move(children);
  j["rendered"] = renderDiagnosticText(d, sources);
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace cbtl
