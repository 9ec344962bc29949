#include "runtime/approach/Checkpoint.h"

#include "runtime/approach/GzipMember.h"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace cbtl::approach {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr int kVersion = 3;  // 2: competence counters, the open plan's flags; 3: every evaluation starts afresh

// Doubles exactly: finite ones as JSON numbers (nlohmann writes the shortest text that reads back to the same
// double), the others as text.
json num(double v) {
  if (std::isfinite(v)) return v;
  return std::isnan(v) ? "nan" : (v > 0 ? "inf" : "-inf");
}
double numFrom(const json& j) {
  if (j.is_number()) return j.get<double>();
  const std::string s = j.get<std::string>();
  if (s == "nan") return NAN;
  if (s == "inf") return INFINITY;
  if (s == "-inf") return -INFINITY;
  throw std::runtime_error(fmt::format("'{}' is not a number", s));
}

json toJson(const sim::Value& v) {
  switch (v.kind) {
    case sim::Value::Kind::Number:
      return {{"n", num(v.number)}};
    case sim::Value::Kind::Vector: {
      json a = json::array();
      for (double x : v.vector) a.push_back(num(x));
      return {{"v", a}};
    }
    case sim::Value::Kind::Name:
      return {{"t", v.text}};
    case sim::Value::Kind::Names:
      return {{"m", v.members}};
  }
  return {};
}

sim::Value valueFromJson(const json& j) {
  if (j.contains("n")) return sim::Value::num(numFrom(j.at("n")));
  if (j.contains("v")) {
    std::vector<double> v;
    for (const auto& x : j.at("v")) v.push_back(numFrom(x));
    return sim::Value::vec(std::move(v));
  }
  if (j.contains("t")) return sim::Value::name(j.at("t").get<std::string>());
  return sim::Value::names(j.at("m").get<std::vector<std::string>>());
}

// What a replayed call must reproduce.
json digest(const sim::StepResult& r) {
  return {{"status", static_cast<int>(r.status)},
          {"step", r.consumedStep},
          {"done", r.taskDone},
          {"failed", r.taskFailed},
          {"sat", r.hasSatisfaction ? num(r.satisfaction) : json(nullptr)},
          {"feedback", r.feedback.size()},
          {"shift", r.preferencesChanged}};
}

std::string readWhole(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw RunDirectoryError(fmt::format("cannot read '{}'", path));
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

json readJsonFile(const std::string& path) {
  try {
    return json::parse(readWhole(path));
  } catch (const json::exception& e) {
    throw RunDirectoryError(fmt::format("'{}' is not valid JSON ({}); remove the run with --force", path, e.what()));
  }
}

void flattenInto(const json& j, const std::string& prefix, std::map<std::string, json>& out) {
  if (j.is_object()) {
    for (const auto& [k, v] : j.items()) flattenInto(v, prefix.empty() ? k : prefix + "." + k, out);
  } else {
    out[prefix] = j;
  }
}

}  // namespace

json toJson(const sim::ActionCall& call) {
  json args = json::array();
  for (const auto& a : call.args) args.push_back(toJson(a));
  json j{{"name", call.name}, {"args", args}};
  // Only calls inside an `allow` carry exceptions; others keep the shape they always had.
  if (!call.exceptions.empty()) {
    json allow = json::array();
    for (const auto& e : call.exceptions)
      allow.push_back(
          {{"part", e.part}, {"names", e.names}, {"separation", e.separation}, {"declared_at", e.declaredAt}});
    j["allow"] = std::move(allow);
  }
  return j;
}

sim::ActionCall actionCallFromJson(const json& j) {
  sim::ActionCall call;
  call.name = j.at("name").get<std::string>();
  for (const auto& a : j.at("args")) call.args.push_back(valueFromJson(a));
  if (j.contains("allow")) {
    for (const auto& e : j.at("allow"))
      call.exceptions.push_back({e.at("part").get<std::string>(), e.at("names").get<std::vector<std::string>>(),
                                 e.at("separation").get<double>(), e.at("declared_at").get<std::string>()});
  }
  return call;
}

static json toJson(const Competence& c) {
  return {{"requests", c.requests},
          {"solved", c.solved},
          {"executed", c.executed},
          {"failed", c.failed},
          {"dry_run_mismatches", c.dryRunMismatches},
          {"caregiver_resets", c.caregiverResets}};
}

static Competence competenceFromJson(const json& j) {
  Competence c;
  c.requests = j.at("requests").get<std::int64_t>();
  c.solved = j.at("solved").get<std::int64_t>();
  c.executed = j.at("executed").get<std::int64_t>();
  c.failed = j.at("failed").get<std::int64_t>();
  c.dryRunMismatches = j.at("dry_run_mismatches").get<std::int64_t>();
  c.caregiverResets = j.at("caregiver_resets").get<std::int64_t>();
  return c;
}

static json numbers(const std::vector<double>& values) {
  json out = json::array();
  for (double v : values) out.push_back(num(v));
  return out;
}

json toJson(const ExperimentResult& r) {
  json evals = json::array();
  for (const auto& e : r.evals) {
    json sat = json::array();
    for (double s : e.satisfaction) sat.push_back(num(s));
    json preferences = json::object();
    for (const auto& [name, t] : e.preferences) preferences[name] = {t.met, t.judged};
    json measures = json::object();
    for (const auto& [name, t] : e.measures) measures[name] = {num(t.min), num(t.sum), t.count};
    evals.push_back({{"step", e.step},
                     {"preferences", preferences},
                     {"measures", measures},
                     {"satisfaction", sat},
                     {"mean", num(e.mean)},
                     {"task_success_rate", num(e.taskSuccessRate)},
                     {"preferences_met_rate", num(e.preferencesMetRate)},
                     {"replans", e.replans},
                     {"competence", toJson(e.competence)}});
  }
  return {{"evals", evals},
          {"meals_served", r.mealsServed},
          {"train_satisfaction", num(r.trainSatisfaction)},
          {"train_solves", r.trainSolves},
          {"train_solve_failures", r.trainSolveFailures},
          {"train_replans", r.trainReplans},
          {"train_competence", toJson(r.train)},
          {"eval_competence", toJson(r.eval)},
          {"solver_iterations", r.solverIterations},
          {"text_model_errors", r.textModelErrors},
          {"first_text_model_error", r.firstTextModelError},
          {"rechecks", r.rechecks},
          {"recheck_violations", r.recheckViolations},
          {"first_recheck_violation", r.firstRecheckViolation},
          // Written for people reading complete.json; not read back (a resumed process counts its own faults).
          {"llm_faults", r.llmFaults.toJson()}};
}

ExperimentResult experimentResultFromJson(const json& j) {
  ExperimentResult r;
  for (const auto& e : j.at("evals")) {
    EvalPoint p;
    p.step = e.at("step").get<std::int64_t>();
    for (const auto& s : e.at("satisfaction")) p.satisfaction.push_back(numFrom(s));
    p.mean = numFrom(e.at("mean"));
    p.taskSuccessRate = numFrom(e.at("task_success_rate"));
    p.preferencesMetRate = numFrom(e.at("preferences_met_rate"));
    p.replans = e.at("replans").get<int>();
    p.competence = competenceFromJson(e.at("competence"));
    if (e.contains("preferences")) {  // absent in checkpoints written before preferences were tallied
      for (const auto& [name, t] : e.at("preferences").items())
        p.preferences[name] = PreferenceTally{t.at(0).get<int>(), t.at(1).get<int>()};
    }
    if (e.contains("measures")) {
      for (const auto& [name, t] : e.at("measures").items())
        p.measures[name] = MeasureTally{numFrom(t.at(0)), numFrom(t.at(1)), t.at(2).get<int>()};
    }
    r.evals.push_back(std::move(p));
  }
  r.mealsServed = j.at("meals_served").get<std::int64_t>();
  r.trainSatisfaction = numFrom(j.at("train_satisfaction"));
  r.trainSolves = j.at("train_solves").get<std::int64_t>();
  r.trainSolveFailures = j.at("train_solve_failures").get<std::int64_t>();
  r.trainReplans = j.at("train_replans").get<std::int64_t>();
  r.train = competenceFromJson(j.at("train_competence"));
  r.eval = competenceFromJson(j.at("eval_competence"));
  r.solverIterations = j.at("solver_iterations").get<std::uint64_t>();
  r.textModelErrors = j.at("text_model_errors").get<std::int64_t>();
  r.firstTextModelError = j.at("first_text_model_error").get<std::string>();
  r.rechecks = j.at("rechecks").get<std::int64_t>();
  r.recheckViolations = j.at("recheck_violations").get<std::int64_t>();
  r.firstRecheckViolation = j.at("first_recheck_violation").get<std::string>();
  return r;
}

std::vector<std::string> differingKeys(const json& now, const json& saved) {
  std::map<std::string, json> a, b;
  flattenInto(now, "", a);
  flattenInto(saved, "", b);
  std::vector<std::string> out;
  auto show = [](const std::map<std::string, json>& m, const std::string& k) {
    return m.count(k) ? m.at(k).dump() : "absent";
  };
  for (const auto& [k, v] : a) {
    if (!b.count(k) || b.at(k) != v)
      out.push_back(fmt::format("{} (this command: {}, the run: {})", k, v.dump(), show(b, k)));
  }
  for (const auto& [k, v] : b) {
    if (!a.count(k)) out.push_back(fmt::format("{} (this command: absent, the run: {})", k, v.dump()));
  }
  return out;
}

json Checkpoint::toJson() const {
  json calls = json::array();
  for (const auto& c : pending) calls.push_back(approach::toJson(c));
  return {{"format", "cbtl-checkpoint"},
          {"version", kVersion},
          {"step", step},
          {"files",
           {{"train.csv", trainCsvBytes},
            {"eval.csv", evalCsvBytes},
            {"world-calls.jsonl", worldLogBytes},
            {"motions.jsonl.gz", motionsBytes}}},
          {"world_calls", worldCalls},
          {"train_solver", trainSolver},
          {"approach_rng", approachRng},
          {"strings", strings},
          {"profile", profile},
          {"plan",
           {{"calls", calls},
            {"next", next},
            {"open", planOpen},
            {"dry_run", planDryRun},
            {"assignment", numbers(planWorld.assignment)},
            {"observation", numbers(planWorld.observation)}}},
          {"result", approach::toJson(result)}};
}

Checkpoint Checkpoint::fromJson(const json& j, const std::string& source) {
  try {
    if (j.at("format") != "cbtl-checkpoint" || j.at("version") != kVersion) {
      throw RunDirectoryError(fmt::format("'{}' is not a version-{} cbtl checkpoint", source, kVersion));
    }
    Checkpoint cp;
    cp.step = j.at("step").get<std::int64_t>();
    cp.trainCsvBytes = j.at("files").at("train.csv").get<std::uint64_t>();
    cp.evalCsvBytes = j.at("files").at("eval.csv").get<std::uint64_t>();
    cp.worldLogBytes = j.at("files").at("world-calls.jsonl").get<std::uint64_t>();
    cp.motionsBytes = j.at("files").value("motions.jsonl.gz", std::uint64_t{0});
    cp.worldCalls = j.at("world_calls").get<std::uint64_t>();
    cp.trainSolver = j.at("train_solver");
    cp.profile = j.at("profile");
    cp.approachRng = j.at("approach_rng").get<std::string>();
    cp.strings = j.at("strings").get<std::vector<std::string>>();
    for (const auto& c : j.at("plan").at("calls")) cp.pending.push_back(actionCallFromJson(c));
    cp.next = j.at("plan").at("next").get<std::size_t>();
    cp.planOpen = j.at("plan").at("open").get<bool>();
    cp.planDryRun = j.at("plan").at("dry_run").get<bool>();
    for (const auto& v : j.at("plan").at("assignment")) cp.planWorld.assignment.push_back(numFrom(v));
    for (const auto& v : j.at("plan").at("observation")) cp.planWorld.observation.push_back(numFrom(v));
    if (cp.next > cp.pending.size())
      throw RunDirectoryError(fmt::format("'{}': the plan cursor is past its calls", source));
    cp.result = experimentResultFromJson(j.at("result"));
    return cp;
  } catch (const json::exception& e) {
    throw RunDirectoryError(fmt::format("'{}' is not a complete checkpoint: {}", source, e.what()));
  } catch (const std::runtime_error& e) {
    if (dynamic_cast<const RunDirectoryError*>(&e)) throw;
    throw RunDirectoryError(fmt::format("'{}' is not a complete checkpoint: {}", source, e.what()));
  }
}

void RecordingSimulator::log(json entry, const sim::StepResult& r) {
  entry["r"] = digest(r);
  log_ += entry.dump();
  log_ += '\n';
  ++calls_;
}

void RecordingSimulator::reset(std::uint64_t seed) {
  inner_->reset(seed);
  log_ += json{{"reset", std::to_string(seed)}}.dump() + "\n";
  ++calls_;
}

sim::StepResult RecordingSimulator::act(const sim::ActionCall& call) {
  sim::StepResult r = inner_->act(call);
  log({{"act", approach::toJson(call)}}, r);
  return r;
}

sim::StepResult RecordingSimulator::idle() {
  sim::StepResult r = inner_->idle();
  log({{"idle", true}}, r);
  return r;
}

std::string RecordingSimulator::takeLog() {
  std::string out;
  out.swap(log_);
  return out;
}

void RecordingSimulator::replay(const std::string& lines, const std::string& source) {
  std::istringstream in(lines);
  std::string line;
  std::uint64_t n = 0;
  while (std::getline(in, line)) {
    ++n;
    try {
      const json e = json::parse(line);
      if (e.contains("reset")) {
        inner_->reset(std::stoull(e.at("reset").get<std::string>()));
      } else {
        const sim::StepResult r = e.contains("act") ? inner_->act(actionCallFromJson(e.at("act"))) : inner_->idle();
        if (digest(r) != e.at("r")) {
          throw RunDirectoryError(
              fmt::format("{}:{}: replaying the training world gave another result than the logged one "
                          "(the simulator is not deterministic from its seed); the run cannot be resumed",
                          source, n));
        }
      }
    } catch (const json::exception& e) {
      throw RunDirectoryError(fmt::format("{}:{}: not a logged world call: {}", source, n, e.what()));
    }
    ++calls_;
  }
}

RunOutput::RunOutput(const std::string& dir, RunMode mode, const json& config, const std::string& trainHeader,
                     const std::string& evalHeader)
    : dir_(dir) {
  if (dir_.empty()) return;
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec) throw RunDirectoryError(fmt::format("cannot create '{}': {}", dir_, ec.message()));
  lock_ = std::make_unique<DirectoryLock>(dir_);
  const std::vector<std::string> existing = runFilesIn(dir_);
  if (!existing.empty() && mode == RunMode::Fresh) throw RunDirectoryError(refusalMessage(dir_, existing));
  if (!existing.empty() && mode == RunMode::Resume && fs::exists(path("config.json"))) {
    removeTemporaries(dir_);  // a killed process's half-written files: never part of a run
    openForResume(config);
    if (completed_ || checkpoint_) return;
  }
  removeRunFiles(dir_);
  startFresh(config, trainHeader, evalHeader);
}

std::string RunOutput::path(const std::string& name) const { return (fs::path(dir_) / name).string(); }

std::string RunOutput::worldLogPath() const { return path("world-calls.jsonl"); }

void RunOutput::startFresh(const json& config, const std::string& trainHeader, const std::string& evalHeader) {
  writeFileAtomic(path("config.json"), config.dump(2) + "\n");
  std::error_code ec;
  fs::create_directories(path("models"), ec);
  if (ec) throw RunDirectoryError(fmt::format("cannot create '{}': {}", path("models"), ec.message()));
  train_.open(path("train.csv"));
  eval_.open(path("eval.csv"));
  world_.open(worldLogPath());
  train_.append(trainHeader);
  eval_.append(evalHeader);
  train_.flush();  // the CSVs are never empty: a killed run leaves at least their headers
  eval_.flush();
}

void RunOutput::openForResume(const json& config) {
  const json saved = readJsonFile(path("config.json"));
  if (const auto diff = differingKeys(config, saved); !diff.empty()) {
    std::string list;
    for (const auto& d : diff) list += (list.empty() ? "" : "; ") + d;
    throw RunDirectoryError(fmt::format("cannot resume '{}': its options differ from this command's: {}", dir_, list));
  }
  if (fs::exists(path("complete.json"))) {
    const json done = readJsonFile(path("complete.json"));
    // An earlier format's evaluation is not comparable with this one's (version 3: each checkpoint's evaluation
    // no longer carries the previous one's solver state), so its numbers are not reused.
    if (done.value("version", 0) != kVersion) {
      throw RunDirectoryError(fmt::format(
          "'{}' was written by an earlier cbtl (format version {}, this one writes {}): its results are not "
          "comparable with this version's; run it again in a new folder (or with --force)",
          path("complete.json"), done.value("version", 0), kVersion));
    }
    try {
      completed_ = experimentResultFromJson(done.at("result"));
    } catch (const json::exception& e) {
      throw RunDirectoryError(fmt::format("'{}' is not a completion marker: {}", path("complete.json"), e.what()));
    }
    // Only a report of how long the run took: a timing.json that is missing or unreadable costs nothing else.
    std::ifstream timing(path("timing.json"));
    const json t = json::parse(timing, nullptr, false);
    if (!t.is_discarded() && t.is_object() && t.value("seconds", json()).is_number())
      recordedSeconds_ = t.at("seconds").get<double>();
    return;
  }
  if (!fs::exists(path("checkpoint.json"))) return;  // killed before its first checkpoint: start afresh
  const json cp = readJsonFile(path("checkpoint.json"));
  checkpoint_ = Checkpoint::fromJson(cp, path("checkpoint.json"));
  if (cp.is_object() && cp.value("elapsed_seconds", json()).is_number())
    priorSeconds_ = cp.at("elapsed_seconds").get<double>();
  std::error_code ec;
  fs::create_directories(path("models"), ec);
  train_.open(path("train.csv"), checkpoint_->trainCsvBytes);
  eval_.open(path("eval.csv"), checkpoint_->evalCsvBytes);
  world_.open(worldLogPath(), checkpoint_->worldLogBytes);
  if (checkpoint_->motionsBytes > 0 || fs::exists(path("motions.jsonl.gz")))
    motions_.open(path("motions.jsonl.gz"), checkpoint_->motionsBytes);
}

void RunOutput::motionLine(const std::string& line) {
  if (enabled()) motionText_ += line;
}

void RunOutput::flushMotions() {
  if (motionText_.empty()) return;
  if (!motions_.isOpen()) motions_.open(path("motions.jsonl.gz"));
  motions_.append(gzipMember(motionText_));
  motionText_.clear();
}

std::string RunOutput::worldLog() const {
  if (!checkpoint_) return {};
  std::string text = readWhole(worldLogPath());
  text.resize(std::min<std::size_t>(text.size(), checkpoint_->worldLogBytes));  // open() truncated it already
  return text;
}

void RunOutput::writeModel(std::int64_t step, const std::string& profileJson) {
  if (!enabled()) return;
  writeFileAtomic(path(fmt::format("models/{}.json", step)), profileJson);
}

void RunOutput::checkpoint(Checkpoint& cp, const std::string& worldLines) {
  if (!enabled()) return;
  world_.append(worldLines);
  flushMotions();
  train_.sync();
  eval_.sync();
  world_.sync();
  if (motions_.isOpen()) motions_.sync();
  cp.trainCsvBytes = train_.size();
  cp.evalCsvBytes = eval_.size();
  cp.worldLogBytes = world_.size();
  cp.motionsBytes = motions_.isOpen() ? motions_.size() : 0;
  if (hook) hook("checkpoint", cp.step);
  json j = cp.toJson();
  j["elapsed_seconds"] = elapsedSeconds();
  writeFileAtomic(path("checkpoint.json"), j.dump() + "\n");
}

double RunOutput::elapsedSeconds() const {
  return priorSeconds_ + std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
}

void RunOutput::finish(const std::string& profileJson, const ExperimentResult& result) {
  if (!enabled()) return;
  train_.close();
  eval_.close();
  world_.close();
  flushMotions();
  if (motions_.isOpen()) motions_.close();
  writeFileAtomic(path("profile.json"), profileJson);
  if (hook) hook("finish", result.evals.empty() ? 0 : result.evals.back().step);
  writeFileAtomic(path("timing.json"),
                  json{{"format", "cbtl-run-timing"}, {"seconds", elapsedSeconds()}}.dump() + "\n");
  const json marker = {{"format", "cbtl-run-complete"},
                       {"version", kVersion},
                       {"mean_eval", num(result.meanEval())},
                       {"checkpoints", result.evals.size()},
                       {"result", approach::toJson(result)}};
  writeFileAtomic(path("complete.json"), marker.dump(2) + "\n");
  // The run is complete: its resume state is no longer needed (a kill here leaves it, which is harmless).
  std::error_code ec;
  fs::remove(path("checkpoint.json"), ec);
  fs::remove(worldLogPath(), ec);
}

}  // namespace cbtl::approach
