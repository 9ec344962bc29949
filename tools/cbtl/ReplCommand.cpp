// `cbtl repl [FILE] [--profile P] [--seed S] [--echo]`: the interactive loop over app/repl/ReplSession.h.
//
// On a terminal (stdin and stdout both ttys) lines are read with libedit: history kept in
// $XDG_STATE_HOME/cbtl/repl_history (default ~/.local/state/cbtl/repl_history), tab completion of commands and the
// loaded program's names, a "cbtl> " prompt and "  ...> " for continuation lines. Ctrl-C stops a running solve
// (it ends Interrupted) and otherwise abandons the line being typed; Ctrl-D or quit ends the session.
// Piped, no prompt is printed and the session reads stdin to its end; --echo prints each command after "cbtl> "
// so that a transcript shows input and output in order. Exit code: 0, or 1 when any command failed while piped
// (an interactive session exits 0: errors were seen).
#include "tools/cbtl/CommandRegistry.h"
#include "tools/cbtl/ErrorHandling.h"
#include "tools/cbtl/RuntimeSupport.h"

#include "app/repl/ReplSession.h"

#include <editline/readline.h>
#include <fmt/core.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>

namespace {

struct ReplArgs {
  std::string file, profile, profileDb, user, stdlibDir;
  std::uint64_t seed = 0;
  bool echo = false;
  cbtl::cli::SolverArgs solver;
  cbtl::cli::TextBackendArgs text;
  cbtl::cli::ExternalSimulatorArgs external;
};

std::atomic<bool> gInterrupt{false};
cbtl::app::repl::ReplSession* gSession = nullptr;  // for libedit's completion callbacks, which take no context

void onInterrupt(int) { gInterrupt.store(true); }

std::filesystem::path historyFile() {
  namespace fs = std::filesystem;
  fs::path state;
  if (const char* xdg = std::getenv("XDG_STATE_HOME"); xdg != nullptr && *xdg == '/')
    state = xdg;
  else if (const char* home = std::getenv("HOME"); home != nullptr && *home != '\0')
    state = fs::path(home) / ".local" / "state";
  else
    return {};
  return state / "cbtl" / "repl_history";
}

// libedit asks for one candidate at a time (state 0 first); the list is computed once per completion.
char* nextCandidate(const char*, int state) {
  static std::vector<std::string> candidates;
  static std::size_t next = 0;
  if (state == 0) {
    candidates = gSession->completions(std::string(rl_line_buffer, static_cast<std::size_t>(rl_point)));
    next = 0;
    // An event's name completes to "name(": the arguments follow it directly, so no space after the parenthesis.
    const bool call =
        !candidates.empty() && std::all_of(candidates.begin(), candidates.end(),
                                           [](const std::string& c) { return !c.empty() && c.back() == '('; });
    rl_completion_append_character = call ? '\0' : ' ';
  }
  if (next >= candidates.size()) return nullptr;
  return strdup(candidates[next++].c_str());  // libedit frees it
}

char** complete(const char* text, int, int) { return rl_completion_matches(text, nextCandidate); }

// One line, or nullopt at the end of the input. Interactive: libedit with `prompt`.
std::optional<std::string> readLine(bool interactive, const char* prompt) {
  if (!interactive) {
    std::string line;
    if (!std::getline(std::cin, line)) return std::nullopt;
    return line;
  }
  char* raw = readline(prompt);
  if (raw == nullptr) {
    // libedit gives up on the line when Ctrl-C interrupts its read; that abandons the line, not the session.
    if (gInterrupt.load()) {
      fmt::print("\n");
      return std::string();
    }
    return std::nullopt;
  }
  std::string line(raw);
  std::free(raw);
  return line;
}

int runRepl(const ReplArgs& a) {
  using namespace cbtl;
  const auto textBackend = cli::makeTextBackend("repl", a.text);
  if (!textBackend) return 2;
  app::repl::ReplConfig config;
  config.stdlibDir = a.stdlibDir;
  config.textBackend = *textBackend;
  config.seed = a.seed;
  config.solverOptions = [solverArgs = a.solver](const std::string& domain) {
    return cli::solverOptionsFor(solverArgs, domain);
  };
  config.interrupt = &gInterrupt;
  config.simulatorCommand = a.external.command;
  config.simulatorTimeoutMs = a.external.timeoutMs;
  if (!a.profileDb.empty()) {
    config.store = std::make_shared<app::profile::ProfileStore>(a.profileDb);
    config.user = a.user;
  }
  app::repl::ReplSession session(config, stdout);
  gSession = &session;

  const bool interactive = isatty(0) && isatty(1);
  struct sigaction action {};
  action.sa_handler = onInterrupt;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);

  const std::filesystem::path history = interactive ? historyFile() : std::filesystem::path();
  if (interactive) {
    rl_readline_name = "cbtl";
    rl_basic_word_break_characters = " \t(,={";
    rl_attempted_completion_function = complete;
    stifle_history(1000);
    if (!history.empty()) read_history(history.c_str());
    fmt::print("cbtl repl: help lists the commands; Ctrl-D or quit ends the session\n");
  }
  int failures = 0;
  auto run = [&](const std::string& input) {
    if (a.echo && !interactive) fmt::print("cbtl> {}\n", input);
    const auto outcome = session.execute(input);
    std::fflush(stdout);
    if (outcome == app::repl::ReplSession::Outcome::Failed) ++failures;
    return outcome != app::repl::ReplSession::Outcome::Quit;
  };
  bool going = true;
  if (!a.file.empty()) going = run("load " + a.file);
  if (going && !a.profile.empty()) going = run("profile load " + a.profile);
  while (going) {
    std::string input;
    std::optional<std::string> line = readLine(interactive, "cbtl> ");
    if (!line) break;
    input = *line;
    while (app::repl::ReplSession::needsMoreInput(input)) {
      line = readLine(interactive, "  ...> ");
      if (!line) break;
      input += "\n" + *line;
    }
    if (gInterrupt.exchange(false) && interactive) continue;  // Ctrl-C abandoned the line
    if (interactive && input.find_first_not_of(" \t\n") != std::string::npos) {
      add_history(input.c_str());
      if (!history.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(history.parent_path(), ec);
        write_history(history.c_str());  // after every line: a killed session keeps its history
      }
    }
    going = run(input);
  }
  if (interactive) fmt::print("\n");
  gSession = nullptr;
  return interactive || failures == 0 ? 0 : 1;
}

void addRepl(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<ReplArgs>();
  CLI::App* cmd = app.add_subcommand(
      "repl", "an interactive session: load a domain, set observations, solve, explain, give feedback, learn");
  cmd->add_option("file", args->file, "a .cbtl file to load first");
  cmd->add_option("--profile", args->profile,
                  "a profile (JSON) to load after the file (with --profile-db: imported as a new version)");
  CLI::Option* db = cmd->add_option("--profile-db", args->profileDb,
                                    "a profile store (SQLite): start from --user's stored profile, store every "
                                    "learn, undo, profile load and reset as a new version");
  CLI::Option* user = cmd->add_option("--user", args->user, "whose profile, in --profile-db");
  db->needs(user);
  user->needs(db);
  cmd->add_option("--seed", args->seed, "seed of the simulator's world and the solver")
      ->capture_default_str()
      ->check(cbtl::cli::unsignedIn(0));
  cmd->add_flag("--echo", args->echo, "piped: print each command after \"cbtl> \" before its output (transcripts)");
  cmd->add_option("--stdlib", args->stdlibDir, "standard library folder (default: embedded)");
  cbtl::cli::addExternalSimulatorOptions(cmd, args->external);
  cbtl::cli::addSolverOptions(cmd, args->solver);
  cbtl::cli::addTextBackendOptions(cmd, args->text);
  cmd->callback([args, &exitCode]() { cbtl::cli::runCommand("repl", exitCode, [&] { return runRepl(*args); }); });
}

const cbtl::cli::RegisterCommand registerRepl(22, addRepl);

}  // namespace
