#include "tools/cbtlc/FormatCommand.h"

#include "compiler/diag/DiagnosticRenderer.h"
#include "compiler/format/SourceFormatter.h"
#include "compiler/parse/Parser.h"
#include "support/InputFile.h"

#include <fmt/core.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace cbtl::cli {

namespace {

struct FormatOptions {
  std::vector<std::string> files;
  bool write = false;
  bool check = false;
  std::string color = "auto";
};

// The file's text, or nullopt with `why` set when it exists but is not one to read (not regular, too large).
std::optional<std::string> readFile(const std::string& path, std::string& why) {
  try {
    return support::readInputFile(path, support::kMaxSourceBytes, "source file");
  } catch (const support::InputFileError& e) {
    if (e.kind != support::InputFileError::Kind::CannotOpen) why = e.reason;
    return std::nullopt;
  }
}

// Writes `text` to a temporary file beside `path` and renames it over `path`, keeping its permissions, so that an
// interrupted write never leaves a half-written source file. False (with a message) when it cannot.
bool replaceFile(const std::string& path, const std::string& text) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path temporary = target.parent_path() / ("." + target.filename().string() + ".cbtlc-fmt.tmp");
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out << text;
    out.flush();
    if (!out) {
      fmt::print(stderr, "cbtlc: error: cannot write '{}'\n", temporary.string());
      std::error_code ignored;
      fs::remove(temporary, ignored);
      return false;
    }
  }
  std::error_code ec;
  fs::permissions(temporary, fs::status(target, ec).permissions(), ec);
  fs::rename(temporary, target, ec);
  if (ec) {
    fmt::print(stderr, "cbtlc: error: cannot replace '{}': {}\n", path, ec.message());
    fs::remove(temporary, ec);
    return false;
  }
  return true;
}

// The formatted text of `text`, or nullopt after printing its syntax errors.
std::optional<std::string> formatted(const std::string& path, const std::string& text, const FormatOptions& o) {
  // The file alone is parsed: its imports need not exist to lay it out.
  SourceManager sources;
  DiagnosticEngine diags;
  const FileId file = sources.add(path, text);
  const ParseOutput parsed = parseModule(sources, file, diags);
  if (parsed.hadSyntaxErrors || diags.errorCount() > 0) {
    const bool color = useColor(o.color, 2);
    for (const auto& d : diags.sorted()) fmt::print(stderr, "{}", renderDiagnosticText(d, sources, color));
    fmt::print(stderr, "{}: not formatted: {} error{}\n", path, diags.errorCount(), diags.errorCount() == 1 ? "" : "s");
    return std::nullopt;
  }
  return formatSource(text);
}

int run(const FormatOptions& o) {
  if (o.write && o.check) {
    fmt::print(stderr, "cbtlc fmt: error: --write and --check exclude each other\n");
    return 2;
  }
  std::vector<std::string> files = o.files;
  if (files.empty()) files.push_back("-");
  const bool toStdout = !o.write && !o.check;
  if (toStdout && files.size() > 1) {
    fmt::print(stderr, "cbtlc fmt: error: {} files given: print one at a time, or use --write or --check\n",
               files.size());
    return 2;
  }
  int exitCode = 0;
  for (const std::string& path : files) {
    const bool fromStdin = path == "-";
    if (fromStdin && o.write) {
      fmt::print(stderr, "cbtlc fmt: error: --write needs files, not standard input\n");
      return 2;
    }
    std::optional<std::string> text;
    std::string why;
    if (fromStdin) {
      std::ostringstream in;
      in << std::cin.rdbuf();
      text = in.str();
    } else {
      text = readFile(path, why);
    }
    if (!text) {
      fmt::print(stderr, "cbtlc: error: cannot read file '{}'{}\n", path, why.empty() ? "" : ": " + why);
      exitCode = 1;
      continue;
    }
    const std::string name = fromStdin ? "<stdin>" : path;
    const std::optional<std::string> out = formatted(name, *text, o);
    if (!out) {
      exitCode = 1;
      continue;
    }
    if (toStdout) {
      fmt::print("{}", *out);
    } else if (*out != *text) {
      if (o.check) {
        fmt::print("{}\n", name);
        exitCode = 1;
      } else if (!replaceFile(path, *out)) {
        exitCode = 1;
      }
    }
  }
  return exitCode;
}

}  // namespace

void addFormatCommand(CLI::App& app, int& exitCode) {
  auto options = std::make_shared<FormatOptions>();
  auto* cmd = app.add_subcommand("fmt", "lay out .cbtl files canonically (stdout, or --write in place, or --check)");
  cmd->add_option("files", options->files, "the .cbtl files; `-` or none: standard input");
  cmd->add_flag("--write,-w", options->write, "rewrite the files that are not formatted");
  cmd->add_flag("--check", options->check, "list the files that are not formatted (exit 1 if any); change nothing");
  cmd->add_option("--color", options->color, "colour diagnostics: auto, always or never")
      ->check(CLI::IsMember({"auto", "always", "never"}))
      ->capture_default_str();
  cmd->callback([options, &exitCode] { exitCode = run(*options); });
}

}  // namespace cbtl::cli
