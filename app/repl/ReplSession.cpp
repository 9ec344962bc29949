#include "app/repl/ReplSession.h"

#include "app/ObservationFile.h"
#include "app/PlanReport.h"
#include "app/SimulatorFacts.h"
#include "app/SimulatorSource.h"
#include "app/SolutionJson.h"
#include "app/repl/ValueSyntax.h"
#include "compiler/util/Suggest.h"
#include "domains/DomainRegistry.h"
#include "ir/Counted.h"
#include "runtime/approach/Experiment.h"
#include "runtime/approach/ValueBridge.h"
#include "runtime/model/ModelSummary.h"
#include "runtime/solver/Recheck.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <sstream>

namespace cbtl::app::repl {

namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return {};
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

std::vector<std::string> words(const std::string& s) {
  std::istringstream in(s);
  std::vector<std::string> w;
  for (std::string x; in >> x;) w.push_back(x);
  return w;
}

// "name = value" → {name, value}; nullopt without an '='.
std::optional<std::pair<std::string, std::string>> assignmentOf(const std::string& args) {
  const auto eq = args.find('=');
  if (eq == std::string::npos) return std::nullopt;
  return std::pair{trim(args.substr(0, eq)), trim(args.substr(eq + 1))};
}

}  // namespace

ReplSession::ReplSession(ReplConfig config, std::FILE* out) : config_(std::move(config)), out_(out) {}

ReplSession::~ReplSession() = default;

bool ReplSession::fail(const std::string& message) {
  fmt::print(out_, "error: {}\n", message);
  return false;
}

bool ReplSession::requireProgram() {
  if (lp_) return true;
  return fail("no program is loaded (load FILE)");
}

ReplSession::Outcome ReplSession::execute(const std::string& input) {
  std::string text = trim(input);
  // Continuation lines were joined with their '\'; what is left of them is white space.
  text.erase(std::remove(text.begin(), text.end(), '\\'), text.end());
  if (text.empty() || text[0] == '#') return Outcome::Ok;
  if (text.rfind(":eval", 0) != 0 && text[0] == ':') text = text.substr(1);  // :help, :quit, as in GHCi
  const auto space = text.find_first_of(" \t");
  const std::string name = text.substr(0, space);
  const std::string args = space == std::string::npos ? std::string() : trim(text.substr(space));
  if (name == "quit" || name == "exit" || name == "q") return Outcome::Quit;
  using Handler = bool (ReplSession::*)(const std::string&);
  static const std::map<std::string, Handler> handlers = {
      {"help", &ReplSession::cmdHelp},         {"load", &ReplSession::cmdLoad},
      {"reload", &ReplSession::cmdReload},     {"list", &ReplSession::cmdList},
      {"show", &ReplSession::cmdShow},         {"observe", &ReplSession::cmdObserve},
      {"solve", &ReplSession::cmdSolve},       {"explain", &ReplSession::cmdExplain},
      {"why-not", &ReplSession::cmdWhyNot},    {"act", &ReplSession::cmdAct},
      {"feedback", &ReplSession::cmdFeedback}, {"learn", &ReplSession::cmdLearn},
      {"profile", &ReplSession::cmdProfile},   {"undo", &ReplSession::cmdUndo},
      {"reset", &ReplSession::cmdReset},       {":eval", &ReplSession::cmdEval},
      {"eval", &ReplSession::cmdEval}};
  const auto it = handlers.find(name);
  if (it == handlers.end()) {
    std::vector<std::string> names = {"quit", "exit"};
    for (const auto& [command, handler] : handlers) names.push_back(command);
    const std::string nearest = closestMatch(name, names);
    fail(fmt::format("unknown command '{}'{} (help lists the commands)", name,
                     nearest.empty() ? "" : fmt::format("; did you mean '{}'?", nearest)));
    return Outcome::Failed;
  }
  if (config_.interrupt != nullptr) config_.interrupt->store(false);  // a Ctrl-C at the prompt stops nothing later
  try {
    const bool ok = (this->*(it->second))(args);
    if (config_.interrupt != nullptr) config_.interrupt->store(false);
    return ok ? Outcome::Ok : Outcome::Failed;
  } catch (const std::logic_error& e) {
    if (config_.interrupt != nullptr) config_.interrupt->store(false);
    fail(fmt::format("internal error: {} (this is a bug; please report it with the session's commands)", e.what()));
    return Outcome::Failed;
  } catch (const std::exception& e) {
    if (config_.interrupt != nullptr) config_.interrupt->store(false);
    // A runtime error (a world that does not fit the scene, a text model that fails) ends the command, never
    // the session.
    fail(e.what());
    return Outcome::Failed;
  }
}

bool ReplSession::needsMoreInput(const std::string& text) {
  int depth = 0;
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        quoted = false;
      continue;
    }
    if (c == '"')
      quoted = true;
    else if (c == '(' || c == '{' || c == '[')
      ++depth;
    else if (c == ')' || c == '}' || c == ']')
      --depth;
  }
  const std::string t = trim(text);
  return quoted || depth > 0 || (!t.empty() && t.back() == '\\');
}

// --- loading -----------------------------------------------------------------------------------------------------

bool ReplSession::load(const std::string& path) {
  auto lp = LoadedProgram::load(path, config_.stdlibDir);
  if (!lp->ok()) {
    fmt::print(out_, "{}", lp->errors());
    return fail(fmt::format("'{}' was not loaded{}", path, lp_ ? fmt::format(" (still loaded: {})", path_) : ""));
  }
  dropProgram();
  lp_ = std::move(lp);
  path_ = path;
  user_ = std::make_unique<model::UserModel>(lp_->graph(), config_.textBackend);
  const std::string& domain = lp_->graph().domain;
  try {
    loadStoredProfile();
  } catch (const std::exception& e) {
    dropProgram();
    return fail(fmt::format("{}; '{}' was not loaded", e.what(), path));
  }
  makeSolver();
  resetWorld(config_.seed);
  const auto& g = lp_->graph();
  fmt::print(out_, "loaded {}: domain {}, {}, {}, {}, {}{}\n", path, domain,
             ir::counted(g.variables.size(), "variable"), ir::counted(g.constraints.size(), "constraint"),
             ir::counted(g.generators.size(), "personalized generator"), ir::counted(g.tasks.size(), "task"),
             world_ ? fmt::format("; the {} simulator's world (seed {})", domain, worldSeed_)
                    : "; no simulator: observations are zero until set");
  return true;
}

void ReplSession::dropProgram() {
  plan_.reset();  // its CSP points into the program and the user model
  pending_.clear();
  learned_.clear();
  typedObservations_.clear();
  world_.reset();
  solver_.reset();
  user_.reset();
  lp_.reset();
}

void ReplSession::resetWorld(std::uint64_t seed) {
  worldSeed_ = seed;
  typedObservations_.clear();
  world_ =
      createSimulator(*lp_, externalSimulator(*lp_, config_.simulatorCommand, config_.simulatorTimeoutMs), {}, seed);
  observation_ = world_ ? approach::observationVector(lp_->program(), world_->observe())
                        : std::vector<double>(lp_->program().observationWidth(), 0.0);
}

void ReplSession::makeSolver() {
  solver::SolverOptions options = config_.solverOptions(lp_->graph().domain);
  options.interrupt = config_.interrupt;
  solver_ = std::make_unique<solver::Solver>(options, approach::deriveSeed(config_.seed, 1));
}

approach::StepWorld ReplSession::stepWorld() const {
  if (plan_ && plan_->ok) return {plan_->solve.assignment, planObservation_};
  return {{}, observation_};
}

bool ReplSession::cmdLoad(const std::string& args) {
  if (args.empty()) return fail("load FILE: which .cbtl file?");
  return load(args);
}

bool ReplSession::cmdReload(const std::string& args) {
  if (!args.empty()) return fail("reload takes no arguments (load FILE loads another file)");
  if (!requireProgram()) return false;
  const std::string keep = user_->toJson();
  const std::string path = path_;
  if (!load(path)) return false;
  // The model learned so far survives a reload when it still fits the program.
  try {
    user_->fromJson(keep, "the model before reload");
    fmt::print(out_, "kept what was learned ({} labels)\n", user_->dataCount());
  } catch (const model::ProfileError& e) {
    fmt::print(out_, "note: what was learned does not fit the reloaded program and was dropped: {}\n", e.what());
  }
  return true;
}

// --- observations --------------------------------------------------------------------------------------------------

bool ReplSession::cmdObserve(const std::string& args) {
  if (!requireProgram()) return false;
  if (args.empty()) {
    printObservation(out_, lp_->program(), observation_);
    return true;
  }
  const auto w = words(args);
  if (w[0] == "simulator") {
    if (!world_) return fail(fmt::format("the domain '{}' has no simulator", lp_->graph().domain));
    std::uint64_t seed = worldSeed_;
    if (w.size() > 2) return fail("observe simulator [SEED]");
    if (w.size() == 2) {
      try {
        std::size_t used = 0;
        seed = std::stoull(w[1], &used);
        if (used != w[1].size()) throw std::invalid_argument("");
      } catch (const std::exception&) {
        return fail(fmt::format("'{}' is not a seed (an unsigned integer)", w[1]));
      }
    }
    resetWorld(seed);
    fmt::print(out_, "a new {} world (seed {}); its observations:\n", lp_->graph().domain, seed);
    printObservation(out_, lp_->program(), observation_);
    return true;
  }
  if (w[0] == "file") {
    if (w.size() != 2) return fail("observe file PATH (a JSON object of observations by name)");
    return observeFile(w[1]);
  }
  const auto a = assignmentOf(args);
  if (!a)
    return fail("observe NAME = VALUE, observe file PATH, observe simulator [SEED], or observe alone to show them");
  const auto& slots = lp_->program().observationSlots();
  const auto slot = slots.find(a->first);
  if (slot == slots.end()) return fail(fmt::format("no observation named '{}' (list observations)", a->first));
  SyntaxError syntax;
  auto value = parseLiteral(a->second, syntax);
  if (!value) return fail(fmt::format("{} (at '{}')", syntax.message, a->second.substr(syntax.column)));
  std::string error;
  if (!coerceTo(lp_->program(), slot->second.type, *value, error) ||
      !approach::fromSimValue(lp_->program(), slot->second.type, *value, observation_.data() + slot->second.offset,
                              error))
    return fail(fmt::format("{}: {}", a->first, error));
  typedObservations_[a->first] = a->second;
  fmt::print(out_, "{} = {}\n", a->first,
             renderObserved(lp_->program(), slot->second.type, observation_.data() + slot->second.offset));
  return true;
}

bool ReplSession::observeFile(const std::string& path) {
  const rt::Program& program = lp_->program();
  const sim::Observation entries = readObservationEntries(path, program);
  std::vector<double> updated = observation_;  // all or nothing: a bad entry changes no observation
  for (const auto& [name, value] : entries) {
    const auto& slot = program.observationSlots().at(name);
    std::string error;
    if (!approach::fromSimValue(program, slot.type, value, updated.data() + slot.offset, error))
      return fail(fmt::format("{}: {}: {}", path, name, error));
  }
  observation_ = std::move(updated);
  for (const auto& [name, value] : entries) {
    const auto& slot = program.observationSlots().at(name);
    typedObservations_[name] = renderObserved(program, slot.type, observation_.data() + slot.offset);
    fmt::print(out_, "{} = {}\n", name, typedObservations_[name]);
  }
  return true;
}

// --- solving -------------------------------------------------------------------------------------------------------

bool ReplSession::cmdSolve(const std::string& args) {
  if (!requireProgram()) return false;
  std::string taskName, mode = "exploit";
  bool replan = false;
  for (const auto& w : words(args)) {
    if (w == "exploit" || w == "explore" || w == "hard")
      mode = w;
    else if (w == "--replan")
      replan = true;
    else if (lp_->program().findTask(w) != nullptr && taskName.empty())
      taskName = w;
    else {
      std::vector<std::string> candidates = {"exploit", "explore", "hard", "--replan"};
      for (const auto& t : lp_->graph().tasks) candidates.push_back(t.name);
      const std::string nearest = closestMatch(w, candidates);
      return fail(fmt::format("solve [TASK] [exploit|explore|hard] [--replan]: '{}' is none of them{}", w,
                              nearest.empty() ? "" : fmt::format("; did you mean '{}'?", nearest)));
    }
  }
  const auto choice = approach::cspChoiceNamed(mode);
  int task = lp_->taskIndex(taskName);
  if (task < 0) return fail("the program has no task");
  if (world_) {
    lp_->syncWorld(*world_);
    if (taskName.empty()) task = static_cast<int>(lp_->taskFor(*world_, static_cast<std::size_t>(task)));
  }
  plan_.reset();
  auto plan = std::make_unique<approach::Plan>(
      approach::makePlan(*lp_, static_cast<std::size_t>(task), observation_, *choice, replan, *solver_, *user_));
  printSolution(out_, *plan);
  if (!plan->ok) printSolveStatistics(out_, *plan);
  printRecheck(out_, *plan);
  fmt::print(out_, "status: {}\n", solveStatus(*plan));
  planObservation_ = observation_;
  planActed_ = false;
  const bool ok = plan->ok;
  plan_ = std::move(plan);
  return ok || !plan_->refused();  // no solution within the budget is an answer, not an error
}

bool ReplSession::cmdExplain(const std::string& args) {
  if (!args.empty()) return fail("explain takes no arguments (why-not VARIABLE = VALUE asks about one value)");
  if (!requireProgram()) return false;
  if (!plan_) return fail("nothing to explain: solve first");
  printSolveStatistics(out_, *plan_);
  printObservation(out_, lp_->program(), planObservation_);
  if (plan_->ok) printPersonal(out_, *plan_, plan_->solve.assignment, "personalized constraints at the solution");
  return true;
}

bool ReplSession::cmdWhyNot(const std::string& args) {
  if (!requireProgram()) return false;
  if (!plan_ || !plan_->ok) return fail("why-not asks about a solution: solve first");
  const auto a = assignmentOf(args);
  if (!a) return fail("why-not VARIABLE = VALUE");
  const rt::Program& program = lp_->program();
  const ir::Task& task = *plan_->csp.task;
  // A skill's variable may be named without its instance (dip for acquireBite.dip) when that is unambiguous.
  auto v = std::find_if(task.vars.begin(), task.vars.end(),
                        [&](ir::VarId id) { return program.graph().variables[id].name == a->first; });
  if (v == task.vars.end()) {
    std::vector<std::vector<ir::VarId>::const_iterator> bySuffix;
    for (auto it = task.vars.begin(); it != task.vars.end(); ++it) {
      const std::string& name = program.graph().variables[*it].name;
      if (name.size() > a->first.size() &&
          name.compare(name.size() - a->first.size(), a->first.size(), a->first) == 0 &&
          name[name.size() - a->first.size() - 1] == '.')
        bySuffix.push_back(it);
    }
    if (bySuffix.size() != 1) {
      std::vector<std::string> names;
      for (ir::VarId id : task.vars) names.push_back(program.graph().variables[id].name);
      const std::string nearest = bySuffix.empty() ? closestMatch(a->first, names) : std::string();
      return fail(fmt::format("task {} has {} variable named '{}'{} (list variables)", task.name,
                              bySuffix.empty() ? "no" : "more than one", a->first,
                              nearest.empty() ? "" : fmt::format("; did you mean '{}'?", nearest)));
    }
    v = bySuffix.front();
  }
  const rt::VarSlot& slot = program.slot(*v);
  SyntaxError syntax;
  auto value = parseLiteral(a->second, syntax);
  if (!value) return fail(fmt::format("{} (at '{}')", syntax.message, a->second.substr(syntax.column)));
  std::vector<double> assignment = plan_->solve.assignment;
  std::string error;
  if (!coerceTo(program, slot.type, *value, error) ||
      !approach::fromSimValue(program, slot.type, *value, assignment.data() + slot.offset, error))
    return fail(fmt::format("{}: {}", a->first, error));
  const std::string was = program.render(slot.type, plan_->solve.assignment.data() + slot.offset);
  fmt::print(out_, "why not {} = {} (solved: {}; every other variable as solved):\n",
             program.graph().variables[*v].name, program.render(slot.type, assignment.data() + slot.offset), was);
  const solver::RecheckResult r = solver::recheck(plan_->csp, assignment);
  if (r.holds())
    fmt::print(out_, "  every constraint of the CSP holds ({} checked): the solver preferred the other value\n",
               r.constraintsChecked);
  for (const auto& violation : r.violations) fmt::print(out_, "  {}\n", violation);
  printPersonal(out_, *plan_, assignment, "personalized constraints at that assignment");
  return true;
}

// --- acting and feedback -------------------------------------------------------------------------------------------

bool ReplSession::cmdAct(const std::string& args) {
  if (!args.empty()) return fail("act takes no arguments");
  if (!requireProgram()) return false;
  if (!world_)
    return fail(fmt::format("the domain '{}' has no simulator to act in; give the user's feedback with feedback",
                            lp_->graph().domain));
  if (!plan_ || !plan_->ok) return fail("nothing to carry out: solve first");
  if (planActed_) return fail("this plan was carried out already: solve again");
  if (!typedObservations_.empty())
    return fail(
        "the plan was solved against observations set by hand, not the simulator's world: observe "
        "simulator, then solve");
  planActed_ = true;
  std::size_t events = 0;
  for (const auto& call : plan_->calls) {
    const sim::StepResult r = world_->act(call);
    if (r.status == sim::ActionStatus::UnknownAction)
      return fail(fmt::format("the simulator rejected {}: {}", renderCall(call), r.message));
    const bool notable = r.status == sim::ActionStatus::Ignored || !r.feedback.empty() || r.hasSatisfaction ||
                         r.taskDone || !r.message.empty();
    if (notable) {
      fmt::print(out_, "  {}{}{}\n", renderCall(call), r.status == sim::ActionStatus::Ignored ? ": ignored" : "",
                 r.message.empty() ? "" : " (" + r.message + ")");
    }
    for (const auto& f : r.feedback) {
      fmt::print(out_, "    the user: {}\n", renderEvent(f, &lp_->graph()));
      pending_.push_back({f, "simulated user"});
      ++events;
    }
    if (r.hasSatisfaction) {
      std::string judged;
      for (const auto& [name, met] : r.preferences) judged += fmt::format(" {}={}", name, met ? "met" : "unmet");
      fmt::print(out_, "    satisfaction {:+g}{}\n", r.satisfaction,
                 judged.empty() ? "" : " (" + judged.substr(1) + ")");
    }
    if (r.taskDone) {
      fmt::print(out_, "    the task {}\n", r.taskFailed ? "failed" : "is done");
      break;
    }
  }
  observation_ = approach::observationVector(lp_->program(), world_->observe());
  fmt::print(out_, "carried out {} calls; {} feedback event{} queued (learn applies them)\n", plan_->calls.size(),
             events, events == 1 ? "" : "s");
  return true;
}

bool ReplSession::cmdFeedback(const std::string& args) {
  if (!requireProgram()) return false;
  if (args.empty()) {
    showPending();
    return true;
  }
  std::string error;
  std::optional<sim::FeedbackEvent> e = checkedEvent(lp_->program(), args, error);
  if (!e) return fail(error);
  fmt::print(out_, "queued {} ({} pending; learn applies them)\n", renderEvent(*e, &lp_->graph()), pending_.size() + 1);
  pending_.push_back({std::move(*e), "typed"});
  return true;
}

bool ReplSession::cmdLearn(const std::string& args) {
  if (!args.empty()) return fail("learn takes no arguments");
  if (!requireProgram()) return false;
  if (pending_.empty()) return fail("nothing to learn: no feedback since the last learn");
  LearnedBatch batch;
  batch.modelBefore = user_->toJson();
  for (const auto& p : pending_) batch.events.push_back(p.event);
  // A label's feature may query the world (an occlusion score): it is read in the world as it is now.
  if (world_) lp_->syncWorld(*world_);
  const approach::LearnReport report = lp_->learner().learn(batch.events, *user_, stepWorld());
  batch.what = fmt::format("learn of {} event{}", batch.events.size(), batch.events.size() == 1 ? "" : "s");
  try {
    batch.version = storeModel(pending_, "learn");
  } catch (const std::exception& e) {
    user_->fromJson(batch.modelBefore, "the model before the learn");
    return fail(fmt::format("{}; nothing was learned (the feedback stays queued)", e.what()));
  }
  for (const auto& p : report.problems) fmt::print(out_, "warning: not learned: {}\n", p);
  for (const auto& m : report.modelErrors) fmt::print(out_, "warning: {}\n", m);
  fmt::print(out_, "learned {} label{} from {} event{} ({} labels in the model){}\n", report.labels,
             report.labels == 1 ? "" : "s", batch.events.size(), batch.events.size() == 1 ? "" : "s",
             user_->dataCount(), storedNote(batch.version));
  learned_.push_back(std::move(batch));
  pending_.clear();
  return true;
}

bool ReplSession::cmdUndo(const std::string& args) {
  if (!args.empty()) return fail("undo takes no arguments");
  if (!requireProgram()) return false;
  if (!pending_.empty()) {
    fmt::print(out_, "dropped the queued {} (not learned yet)\n", renderEvent(pending_.back().event, &lp_->graph()));
    pending_.pop_back();
    return true;
  }
  if (learned_.empty()) return fail("nothing to undo");
  const std::string after = user_->toJson();
  user_->fromJson(learned_.back().modelBefore, "the model before the last learn");
  std::int64_t stored = 0;
  try {
    const LearnedBatch& b = learned_.back();
    stored = storeModel({}, b.version > 0 ? fmt::format("undo of version {}", b.version) : "undo of " + b.what);
  } catch (const std::exception& e) {
    user_->fromJson(after, "the model before the undo");
    return fail(fmt::format("{}; nothing was undone", e.what()));
  }
  fmt::print(out_, "undid the {} ({} labels in the model){}\n", learned_.back().what, user_->dataCount(),
             storedNote(stored));
  learned_.pop_back();
  return true;
}

bool ReplSession::cmdReset(const std::string& args) {
  if (!args.empty()) return fail("reset takes no arguments");
  if (!requireProgram()) return false;
  const std::string before = user_->toJson();
  const bool hadData = user_->dataCount() > 0;
  user_->reset();
  std::int64_t stored = 0;
  try {
    if (hadData) stored = storeModel({}, "reset to the prior");
  } catch (const std::exception& e) {
    user_->fromJson(before, "the model before the reset");
    return fail(fmt::format("{}; nothing was reset", e.what()));
  }
  if (stored > 0) fmt::print(out_, "the prior model{}\n", storedNote(stored));
  pending_.clear();
  learned_.clear();
  plan_.reset();
  makeSolver();
  resetWorld(config_.seed);
  fmt::print(out_, "reset: the prior user model, a fresh solver and world (seed {})\n", config_.seed);
  return true;
}

bool ReplSession::cmdProfile(const std::string& args) {
  if (!requireProgram()) return false;
  const auto w = words(args);
  const std::string sub = w.empty() ? "show" : w[0];
  const std::string file = w.size() > 1 ? trim(args.substr(args.find(w[1]))) : std::string();
  if (sub == "show" && w.size() <= 1) {
    fmt::print(out_, "{}", model::describeModel(*user_));  // in words; `profile show json` for the file's JSON
    return true;
  }
  if (sub == "show" && w.size() == 2 && w[1] == "json") {
    fmt::print(out_, "{}\n", nlohmann::json::parse(user_->toJson()).dump(2));
    return true;
  }
  if (sub == "save" && !file.empty()) {
    user_->save(file);
    fmt::print(out_, "saved the profile ({} labels) to {}\n", user_->dataCount(), file);
    return true;
  }
  if (sub == "load" && !file.empty()) {
    LearnedBatch batch;
    batch.modelBefore = user_->toJson();
    try {
      user_->load(file);
    } catch (const std::exception& e) {
      user_->fromJson(batch.modelBefore, "the model before the failed load");
      return fail(fmt::format("{} (the model is unchanged)", e.what()));
    }
    batch.what = "profile load of " + file;
    try {
      batch.version = storeModel({}, "import of " + file);
    } catch (const std::exception& e) {
      user_->fromJson(batch.modelBefore, "the model before the load");
      return fail(fmt::format("{} (the model is unchanged)", e.what()));
    }
    const std::int64_t version = batch.version;
    learned_.push_back(std::move(batch));
    fmt::print(out_, "loaded the profile {} ({} labels){}\n", file, user_->dataCount(), storedNote(version));
    return true;
  }
  return fail("profile show | profile save FILE | profile load FILE");
}

}  // namespace cbtl::app::repl
