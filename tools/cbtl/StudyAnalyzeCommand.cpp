// `cbtl study analyze` and `cbtl study export`: the web study's database (what `cbtl study serve` stored, see
// docs/study-api.md) turned into the paper's analysis (app/study/StudyAnalysis.h) or exported as it is (JSON Lines
// or CSV, StudyRecords::exportJsonLines / exportCsv). Both join the `study` subcommand that StudyCommand.cpp
// registers (order 25), so they register after it.
//
// Exit codes: 0 ok; 1 for a missing or unreadable database (the message starts with its path), records that are
// not what the API stores (the message names the participant and trial), or an output file that is already there
// without --force.
#include "tools/cbtl/CommandRegistry.h"
#include "tools/cbtl/ErrorHandling.h"

#include "app/study/StudyAnalysis.h"
#include "app/study/StudyRecords.h"

#include <fmt/core.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

namespace {

namespace study = cbtl::app::study;

struct AnalyzeArgs {
  std::string database, out;
  bool force = false;
};

struct ExportArgs {
  std::string database, out, format = "jsonl";
  bool force = false;
};

// The database as the study left it: never created here, since a mistyped path must not become an empty study.
study::StudyRecords openExisting(const std::string& path) { return study::StudyRecords(path, /*create=*/false); }

int runAnalyze(const AnalyzeArgs& a) {
  const study::StudyRecords records = openExisting(a.database);
  const study::StudyAnalysis analysis = study::analyzeStudy(records);
  std::string names;
  for (const auto& [name, content] : study::studyAnalysisCsv(analysis)) {
    if (!a.out.empty() && !a.force && std::filesystem::exists(std::filesystem::path(a.out) / name)) {
      fmt::print(stderr, "cbtl study analyze: error: {} already holds {} (use --force to replace it)\n", a.out, name);
      return cbtl::cli::kExitBadInput;
    }
    names += (names.empty() ? "" : ", ") + name;
  }
  std::ostringstream report;
  study::printStudyAnalysis(analysis, report);
  std::cout << report.str() << std::flush;
  if (!a.out.empty()) {
    study::writeStudyAnalysisCsv(analysis, a.out);
    fmt::print("wrote {} in {}\n", names, a.out);
  }
  return cbtl::cli::kExitOk;
}

int runExport(const ExportArgs& a) {
  const study::StudyRecords records = openExisting(a.database);
  if (!a.out.empty() && std::filesystem::exists(a.out) && !a.force) {
    fmt::print(stderr, "cbtl study export: error: {} already exists (use --force to replace it)\n", a.out);
    return cbtl::cli::kExitBadInput;
  }
  // Exported whole before anything is written, so that a failing export leaves no half-written file behind.
  std::ostringstream text;
  if (a.format == "csv")
    records.exportCsv(text);
  else
    records.exportJsonLines(text);
  if (a.out.empty()) {
    std::cout << text.str() << std::flush;
    return cbtl::cli::kExitOk;
  }
  std::ofstream file(a.out, std::ios::binary | std::ios::trunc);
  file << text.str();
  file.close();
  if (!file) throw std::runtime_error(a.out + ": cannot write");
  return cbtl::cli::kExitOk;
}

void addStudyAnalyze(CLI::App& app, int& exitCode) {
  CLI::App* studyCommand = app.get_subcommand("study");
  auto analyzeArgs = std::make_shared<AnalyzeArgs>();
  CLI::App* analyze = studyCommand->add_subcommand(
      "analyze", "the web study's results from its database: ratings, prediction accuracy, answer paths, times");
  analyze->add_option("database", analyzeArgs->database, "the study's SQLite file (cbtl study serve)")->required();
  analyze->add_option("--out", analyzeArgs->out,
                      "folder for ratings.csv, accuracy.csv, paths.csv, flows.csv and times.csv");
  analyze->add_flag("--force", analyzeArgs->force, "replace those files in --out");
  analyze->callback([analyzeArgs, &exitCode] {
    cbtl::cli::runCommand("study analyze", exitCode, [&] { return runAnalyze(*analyzeArgs); });
  });

  auto exportArgs = std::make_shared<ExportArgs>();
  CLI::App* exportCommand =
      studyCommand->add_subcommand("export", "every stored record of the web study, one per page answered");
  exportCommand->add_option("database", exportArgs->database, "the study's SQLite file (cbtl study serve)")->required();
  exportCommand->add_option("--format", exportArgs->format, "jsonl (one JSON object a line) or csv (RFC 4180)")
      ->check(CLI::IsMember({"jsonl", "csv"}))
      ->capture_default_str();
  exportCommand->add_option("--out", exportArgs->out, "output file (default: standard output)");
  exportCommand->add_flag("--force", exportArgs->force, "replace the --out file");
  exportCommand->callback([exportArgs, &exitCode] {
    cbtl::cli::runCommand("study export", exitCode, [&] { return runExport(*exportArgs); });
  });
}

}  // namespace

const cbtl::cli::RegisterCommand registerStudyAnalyze(26, addStudyAnalyze);
