#include "compiler/diag/DiagnosticRenderer.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <algorithm>
#include <cstdlib>

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

// ANSI escapes, or nothing when colour is off.
struct Palette {
  bool on = false;
  std::string paint(std::string_view text, const char* code) const {
    return on ? fmt::format("\x1b[{}m{}\x1b[0m", code, text) : std::string(text);
  }
};
const char* kBold = "1";
const char* kGutter = "1;34";
const char* severityColor(Severity s) { return s == Severity::Error ? "1;31" : "1;33"; }
const char* childColor(ChildKind k) { return k == ChildKind::Note ? "1;36" : "1;32"; }

void appendExcerpt(std::string& out, const SourceRange& range, const SourceManager& sources, const Palette& p,
                   const char* caretColor) {
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
  out += p.paint(fmt::format(" {} |", gutter), kGutter) + "\n";
  out += p.paint(fmt::format(" {} |", number), kGutter) + fmt::format(" {}\n", untab(line));
  out += p.paint(fmt::format(" {} |", gutter), kGutter) + " " + std::string(start.column - 1, ' ') +
         p.paint("^" + std::string(width - 1, '~'), caretColor) + "\n";
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

std::string renderDiagnosticText(const Diagnostic& d, const SourceManager& sources, bool color) {
  const Palette p{color};
  const char* severity = severityColor(d.severity);
  std::string out;
  out += p.paint(location(d.range, sources) + ":", kBold) + " " +
         p.paint(fmt::format("{}[{}]", severityName(d.severity), d.code), severity) + p.paint(": " + d.message, kBold) +
         "\n";
  appendExcerpt(out, d.range, sources, p, severity);
  for (const auto& child : d.children) {
    const char* kind = childColor(child.kind);
    if (child.range.valid()) {
      out += p.paint(location(child.range, sources) + ":", kBold) + " " + p.paint(childName(child.kind), kind) + ": " +
             child.message + "\n";
      appendExcerpt(out, child.range, sources, p, kind);
    } else {
      out += "  " + p.paint("=", kGutter) + " " + p.paint(childName(child.kind), kind) + ": " + child.message + "\n";
    }
  }
  return out;
}

bool useColor(const std::string& mode, int fd) {
  if (mode == "always") return true;
  if (mode == "never") return false;
  const char* noColor = std::getenv("NO_COLOR");
  return ::isatty(fd) != 0 && (noColor == nullptr || *noColor == '\0');
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
