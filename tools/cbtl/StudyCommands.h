// StudyCommands.h — what the `cbtl study` subcommands share (StudyCommand.cpp registers them all): their options,
// loading the Feeding program with the study's options, and the commands that live in their own files
// (`study serve`, StudyServeCommand.cpp;
// `study simulate` through HTTP, StudySimulateCommand.cpp).
#pragma once

#include "tools/cbtl/RuntimeSupport.h"

#include "domains/feeding/FeedingStudy.h"

#include <cstdint>
#include <memory>
#include <string>

namespace cbtl::cli {

struct StudyArgs {
  std::string file, out, stdlibDir, db, host = "127.0.0.1", studyInfo;
  int participants = 60, firstParticipant = 0, participant = 0, trials = 5, width = 480, height = 360, port = 8080,
      jobs = 1, maxSessions = 256, connections = 128, maxParticipants = 1000, planners = 0;
  double newParticipantsPerMinute = 120;
  std::uint64_t seed = 0;
  bool noExploringView = false, force = false, noPictures = false, inProcess = false;
  SolverArgs solver;
  TextBackendArgs text;
};

// Loads the Feeding program and sets the study options from the arguments, or prints why not (nullptr).
std::unique_ptr<app::LoadedProgram> loadFeedingStudy(const char* command, const StudyArgs& a,
                                                     domains::feeding::StudyOptions& options);

// `cbtl study serve`: answers until SIGINT or SIGTERM. Exit code 0 after a signal, 1 when it cannot start.
int runStudyServe(const StudyArgs& a);

// `cbtl study simulate` (without --in-process): simulated participants take the study through the HTTP API of a
// server this command starts on 127.0.0.1, then the study is analysed from its database (StudySimulateCommand.cpp).
int runStudySimulateOverHttp(const StudyArgs& a);

}  // namespace cbtl::cli
