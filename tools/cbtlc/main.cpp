// cbtlc — the .cbtl compiler: check files, emit the constraint graph, dump any pass, explain codes, format files.
// Exit codes: 0 ok, 1 errors in the input, 2 usage, 70 internal error.
#include "compiler/diag/DiagnosticCodes.h"
#include "compiler/diag/DiagnosticExamples.h"
#include "compiler/diag/DiagnosticRenderer.h"
#include "compiler/driver/Pipeline.h"
#include "compiler/util/Suggest.h"
#include "ir/Counted.h"
#include "ir/GraphPrinter.h"
#include "tools/cbtlc/FormatCommand.h"
#include "tools/common/UnknownOption.h"

#include <fmt/core.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string_view>
#include <tuple>

namespace {

struct CommonOptions {
  std::string format = "text";
  std::size_t errorLimit = 50;
  bool warningsAsErrors = false;
  std::string stdlibDir;
  std::string color = "auto";
};

void addCommon(CLI::App* cmd, CommonOptions& o) {
  cmd->add_option("--diagnostics-format", o.format, "how diagnostics are printed: text or json (one object per line)")
      ->check(CLI::IsMember({"text", "json"}));
  cmd->add_option("--error-limit", o.errorLimit, "stop showing errors after this many (default 50)");
  cmd->add_flag("--warnings-as-errors,-W", o.warningsAsErrors, "treat warnings as errors");
  cmd->add_option("--stdlib", o.stdlibDir, "read std.* modules from DIR/std/ instead of the embedded standard library");
  cmd->add_option("--color", o.color,
                  "colour text diagnostics: auto (on a terminal, unless NO_COLOR is set), always or never")
      ->check(CLI::IsMember({"auto", "always", "never"}))
      ->capture_default_str();
}

// Prints the diagnostics of one translation unit; returns the exit code for its outcome.
int report(const cbtl::TranslationUnit& tu, const cbtl::PipelineResult& result, const CommonOptions& o,
           const std::string& path) {
  if (result.rootUnread) {
    const std::string message =
        "cannot read file '" + path + "'" + (result.inputError.empty() ? "" : ": " + result.inputError);
    if (o.format == "json") {
      // Built with the JSON library so that any path (quotes, backslashes, invalid UTF-8) stays valid JSON.
      const nlohmann::json j{{"severity", "error"}, {"code", "E0204"}, {"message", message}};
      fmt::print(stderr, "{}\n", j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
    } else {
      fmt::print(stderr, "cbtlc: error: {}\n", message);
    }
    return 1;
  }
  const bool color = o.format == "text" && cbtl::useColor(o.color, 2);
  for (const auto& d : tu.diags.sorted()) {
    if (o.format == "json")
      fmt::print(stderr, "{}\n", cbtl::renderDiagnosticJson(d, tu.sources));
    else
      fmt::print(stderr, "{}", cbtl::renderDiagnosticText(d, tu.sources, color));
  }
  if (o.format == "text" && (tu.diags.errorCount() > 0 || tu.diags.warningCount() > 0)) {
    fmt::print(stderr, "{}: {} error{}, {} warning{}{}\n", path, tu.diags.errorCount(),
               tu.diags.errorCount() == 1 ? "" : "s", tu.diags.warningCount(), tu.diags.warningCount() == 1 ? "" : "s",
               tu.diags.droppedCount() ? fmt::format(" ({} not shown: error limit)", tu.diags.droppedCount()) : "");
  }
  if (result.outcome == cbtl::PipelineOutcome::InternalError) return 70;
  return result.outcome == cbtl::PipelineOutcome::Ok ? 0 : 1;
}

cbtl::CompileOptions compileOptions(const CommonOptions& o) {
  cbtl::CompileOptions c;
  c.stdlibDir = o.stdlibDir;
  c.errorLimit = o.errorLimit;
  c.warningsAsErrors = o.warningsAsErrors;
  return c;
}

// "Wrong:" and "Right:", each a whole file (and the file it imports, where the code needs one), indented.
void printExample(const cbtl::DiagnosticExample& e) {
  auto indented = [](std::string_view text) {
    std::string out;
    std::size_t start = 0;
    while (start < text.size()) {
      const std::size_t end = text.find('\n', start);
      const std::string_view line =
          text.substr(start, end == std::string_view::npos ? text.size() - start : end - start);
      out += line.empty() ? "\n" : "    " + std::string(line) + "\n";
      if (end == std::string_view::npos) break;
      start = end + 1;
    }
    return out;
  };
  for (const auto& [title, text, imported] :
       {std::tuple{"Wrong", e.wrong, e.importedWrong}, std::tuple{"Right", e.right, e.importedRight}}) {
    fmt::print("\n{}:   (example.cbtl)\n{}", title, indented(text));
    if (!e.imported.empty())
      fmt::print("  {}:\n{}", e.imported, imported.empty() ? "    (no such file)\n" : indented(imported));
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"cbtlc: the CBTL compiler. Checks .cbtl files and emits their constraint graph."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "cbtlc 0.1.0");
  int exitCode = 0;

  CommonOptions checkOpts;
  std::vector<std::string> checkFiles;
  bool summary = false;
  auto* check = app.add_subcommand("check", "check files and report diagnostics");
  check->add_option("files", checkFiles, "the .cbtl files")->required();
  check->add_flag("--summary", summary, "print a one-line summary of each file's constraint graph");
  addCommon(check, checkOpts);
  check->callback([&] {
    for (const auto& path : checkFiles) {
      cbtl::TranslationUnit tu(compileOptions(checkOpts));
      const cbtl::PipelineResult r = cbtl::compileFile(tu, path);
      const int code = report(tu, r, checkOpts, path);
      if (code == 0 && summary) {
        const auto& g = tu.graph;
        auto counted = [](std::size_t n, const char* noun) {
          return fmt::format("{} {}{}", n, noun, n == 1 ? "" : "s");
        };
        fmt::print("{}: ok — domain {}, {}, {}, {}, {}, {}\n", path, g.domain.empty() ? "<unnamed>" : g.domain,
                   counted(g.tasks.size(), "task"), counted(g.variables.size(), "variable"),
                   counted(g.constraints.size(), "constraint"), counted(g.samplers.size(), "sampler"),
                   counted(g.generators.size(), "generator"));
      }
      exitCode = std::max(exitCode, code);
    }
  });

  CommonOptions emitOpts;
  std::string emitFile, emitFormat = "text", dumpAfter;
  auto* emit = app.add_subcommand("emit", "print the constraint graph, or the representation after one pass");
  emit->add_option("file", emitFile, "the .cbtl file")->required();
  emit->add_option("--format", emitFormat, "graph format: text, json or dot")
      ->check(CLI::IsMember({"text", "json", "dot"}));
  emit->add_option("--dump-after", dumpAfter, "print the representation after this pass instead of the graph")
      ->check(CLI::IsMember(cbtl::passNames()));
  addCommon(emit, emitOpts);
  emit->callback([&] {
    cbtl::TranslationUnit tu(compileOptions(emitOpts));
    const cbtl::PipelineResult r = cbtl::compileFile(tu, emitFile, dumpAfter, dumpAfter);
    exitCode = report(tu, r, emitOpts, emitFile);
    if (exitCode != 0) return;
    if (!dumpAfter.empty()) {
      fmt::print("{}", r.dump);
    } else if (emitFormat == "json") {
      fmt::print("{}", cbtl::ir::toJson(tu.graph));
    } else if (emitFormat == "dot") {
      fmt::print("{}", cbtl::ir::toDot(tu.graph));
    } else {
      fmt::print("{}", cbtl::ir::toText(tu.graph));
    }
  });

  std::string code;
  bool listAll = false;
  auto* explain = app.add_subcommand("explain", "explain a diagnostic code, e.g. cbtlc explain E0201");
  explain->add_option("code", code, "the code");
  explain->add_flag("--list", listAll, "list every code with its summary");
  explain->callback([&] {
    if (listAll || code.empty()) {
      for (const auto& info : cbtl::diagnosticCodes()) fmt::print("{}  {}\n", info.code, info.summary);
      return;
    }
    const auto* info = cbtl::findDiagnosticCode(code);
    if (info == nullptr) {
      fmt::print(stderr, "cbtlc: error: unknown diagnostic code '{}'; `cbtlc explain --list` lists them\n", code);
      exitCode = 2;
      return;
    }
    fmt::print("{}: {}\n\n{}\n", info->code, info->summary, info->explanation);
    if (const auto* example = cbtl::exampleFor(info->code)) printExample(*example);
  });

  cbtl::cli::addFormatCommand(app, exitCode);

  // An unknown command is named, with the nearest known one, before CLI11 calls it an unexpected argument.
  if (argc > 1 && argv[1][0] != '-') {
    std::vector<std::string> names;
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
      names.push_back(sub->get_name());
    if (const std::string message = cbtl::unknownCommandMessage("cbtlc", argv[1], names); !message.empty()) {
      fmt::print(stderr, "{}", message);
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (dynamic_cast<const CLI::ExtrasError*>(&e) != nullptr) {
      // A mistyped option, named with the nearest one (CLI11 lists only the words it did not expect).
      std::string command = "cbtlc";
      const CLI::App* deepest = &app;
      while (!deepest->get_subcommands().empty()) {
        deepest = deepest->get_subcommands().front();
        command += " " + deepest->get_name();
      }
      if (const std::string unknown = cbtl::cli::unknownOptionMessage(*deepest, argc, argv); !unknown.empty()) {
        fmt::print(stderr, "{}: error: {}\nRun '{} --help' for more information.\n", command, unknown, command);
        return 2;
      }
    }
    const int c = app.exit(e);
    return c == 0 ? 0 : 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "cbtlc: internal error: {}\nthis is a bug in cbtlc; please report it with the input file.\n",
               e.what());
    return 70;
  }
  return exitCode;
}
