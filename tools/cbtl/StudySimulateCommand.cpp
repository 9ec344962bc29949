// `cbtl study simulate` through HTTP: a study server on 127.0.0.1 (any free port) over a new database, simulated
// participants (app/study/SimulatedParticipant.h) taking the study through its API as the pages do, then the
// paper's analysis of the database (app/study/StudyAnalysis.h): Figure 4(c, d) and the Sankey counts.
//
// Participants are named sim-<n> for n = --first-participant ..; they begin in that order (the server numbers them
// in the order they begin, which seeds their worlds), so --jobs changes nothing in the results.
#include "tools/cbtl/StudyCommands.h"

#include "app/SimulatorFacts.h"
#include "app/study/ParticipantAccess.h"
#include "app/study/SimulatedParticipant.h"
#include "app/study/StudyAnalysis.h"
#include "app/study/StudyHttpServer.h"
#include "app/study/StudyService.h"

#include <fmt/core.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <thread>
#include <vector>

namespace cbtl::cli {

namespace {

namespace fs = std::filesystem;

// Where the database goes: --db, else <out>/study.sqlite, else a temporary folder removed at the end. An existing
// database is never added to: with --out and --force the old one is replaced; otherwise it is refused.
bool chooseDatabase(const StudyArgs& a, std::string& db, std::optional<fs::path>& temporary) {
  if (!a.db.empty()) {
    db = a.db;
  } else if (!a.out.empty()) {
    fs::create_directories(a.out);
    db = (fs::path(a.out) / "study.sqlite").string();
  } else {
    temporary = fs::temp_directory_path() / fmt::format("cbtl-study-simulate-{}", ::getpid());
    fs::create_directories(*temporary);
    db = (*temporary / "study.sqlite").string();
  }
  if (!fs::exists(db)) return true;
  if (a.db.empty() && a.force) {
    for (const char* suffix : {"", "-wal", "-shm"}) fs::remove(db + suffix);
    return true;
  }
  fmt::print(stderr, "cbtl study simulate: error: {} already exists: a simulation writes a new study database{}\n", db,
             a.db.empty() ? " (use --force to replace it)" : "");
  return false;
}

// Runs participants first .. first + count - 1 on `jobs` threads; the first failure stops the others.
void takeAll(const StudyArgs& a, int port) {
  std::vector<std::string> keys;
  for (int n = a.firstParticipant; n < a.firstParticipant + a.participants; ++n)
    keys.push_back(app::study::beginStudy("127.0.0.1", port, fmt::format("sim-{}", n)));
  std::atomic<int> next{a.firstParticipant};
  std::mutex failureMutex;
  std::string failure;
  auto worker = [&] {
    for (int n = next++; n < a.firstParticipant + a.participants; n = next++) {
      {
        std::lock_guard<std::mutex> lock(failureMutex);
        if (!failure.empty()) return;
      }
      try {
        app::study::takeStudy("127.0.0.1", port, fmt::format("sim-{}", n), static_cast<std::uint64_t>(n),
                              keys.at(static_cast<std::size_t>(n - a.firstParticipant)));
      } catch (const std::exception& e) {
        std::lock_guard<std::mutex> lock(failureMutex);
        if (failure.empty()) failure = e.what();
      }
    }
  };
  std::vector<std::thread> threads;
  for (int j = 0; j < a.jobs; ++j) threads.emplace_back(worker);
  for (auto& t : threads) t.join();
  if (!failure.empty()) throw std::runtime_error(failure);
}

}  // namespace

int runStudySimulateOverHttp(const StudyArgs& a) {
  app::study::StudyServiceOptions options;
  auto lp = loadFeedingStudy("study simulate", a, options.study);
  if (!lp) return 1;
  options.pictures = false;  // simulated participants judge the pictures by their measure, not by looking
  std::string db;
  std::optional<fs::path> temporary;
  if (!chooseDatabase(a, db, temporary)) return 1;
  const domains::ProgramFacts facts = app::simulatorFacts(*lp);
  int code = 0;
  {
    app::study::StudyService service(*lp, facts, options, db);
    // Simulated participants all begin at once, on loopback: no admission limit.
    app::study::ParticipantAccess access(service, db, app::study::AdmissionOptions{0, 0, 0});
    app::study::StudyHttpServer server(access);
    std::string error;
    const int port = server.bind("127.0.0.1", 0, error);
    if (port < 0) {
      fmt::print(stderr, "cbtl study simulate: error: {}\n", error);
      return 1;
    }
    std::thread listening([&] { server.listen(); });
    try {
      takeAll(a, port);
    } catch (const std::exception& e) {
      fmt::print(stderr, "cbtl study simulate: error: {}\n", e.what());
      code = 1;
    }
    server.stop();
    listening.join();
  }
  if (code == 0) {
    const app::study::StudyRecords records(db, false);
    const app::study::StudyAnalysis analysis = app::study::analyzeStudy(records);
    fmt::print("study: {} simulated participants (sim-{} ..) took the study through its HTTP API{}\n", a.participants,
               a.firstParticipant, options.study.askExploringView ? "" : " (CBTL without its exploring view)");
    app::study::printStudyAnalysis(analysis, std::cout);
    std::cout.flush();
    if (!a.out.empty()) {
      app::study::writeStudyAnalysisCsv(analysis, a.out);
      std::ofstream jsonl(fs::path(a.out) / "records.jsonl", std::ios::binary | std::ios::trunc);
      records.exportJsonLines(jsonl);
      fmt::print(
          "wrote {}: study.sqlite (unless --db), records.jsonl, ratings.csv, accuracy.csv, paths.csv, "
          "flows.csv, times.csv\n",
          a.out);
    }
  }
  if (temporary) fs::remove_all(*temporary);
  return code;
}

}  // namespace cbtl::cli
