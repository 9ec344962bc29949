#include "runtime/sim/ExternalSimulator.h"

#include "runtime/sim/ChildProcess.h"
#include "runtime/sim/SimulatorProtocol.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <mutex>
#include <set>
#include <stdexcept>

namespace cbtl::sim {

using nlohmann::json;

// The running program and the conversation with it, shared by the training world and its twins.
class Connection {
 public:
  Connection(const ExternalSimulatorConfig& config, std::shared_ptr<const ProtocolSchema> schema)
      : config_(config), schema_(std::move(schema)), name_(config.command) {
    try {
      process_ = std::make_unique<ChildProcess>(config.command, config.workingDirectory, "simulator| ");
    } catch (const std::runtime_error& e) {
      throw ExternalSimulatorError(config_.origin, fmt::format("simulator: {}", e.what()));
    }
  }

  ~Connection() {
    if (!broken_) {
      try {
        std::lock_guard lock(mutex_);
        json bye = {{"op", "bye"}};
        exchange(bye, 1000);
      } catch (const std::exception&) {
        // Leaving: the program is stopped below whatever it answered.
      }
    }
    process_->stop(1000);
  }

  // Greets the program and checks its manifest; throws listing every mismatch.
  void greet(const SimulatorOptions& options) {
    json hello = {{"op", "hello"},
                  {"protocol", protocol::kVersion},
                  {"domain", schema_->domain},
                  {"options", protocol::optionsJson(options)}};
    const json answer = request(hello, "hello");
    protocol::ManifestCheck check = protocol::checkManifest(*schema_, answer);
    if (!check.simulatorName.empty()) name_ = check.simulatorName;
    if (!check.errors.empty()) {
      std::string text = fmt::format("simulator '{}' does not fit the program ({} problem{}):", name_,
                                     check.errors.size(), check.errors.size() == 1 ? "" : "s");
      for (const auto& e : check.errors) text += "\n  - " + e;
      broken_ = true;
      process_->stop(200);
      throw ExternalSimulatorError(config_.origin, text);
    }
    warnings_ = std::move(check.warnings);
    preferences_ = std::move(check.preferences);
    worlds_.insert(0);
  }

  // Sends `message` (an "id" is added) and returns the answer, which said "ok": true.
  json request(json message, const std::string& what) {
    std::lock_guard lock(mutex_);
    if (broken_)
      throw ExternalSimulatorError(config_.origin,
                                   fmt::format("simulator '{}' was stopped after an earlier error", name_));
    return exchange(message, config_.timeoutMs, what);
  }

  // Creates a world that shares world `of`'s user; returns its number.
  int twin(int of) {
    const json answer = request({{"op", "twin"}, {"world", of}}, "twin");
    const auto it = answer.find("world");
    std::lock_guard lock(mutex_);
    if (it == answer.end() || !it->is_number_integer() || it->get<int>() < 0 || worlds_.count(it->get<int>()) > 0)
      fail(
          fmt::format("its answer to request {} (twin) must name a new world (\"world\": an unused number >= 0), "
                      "got {}",
                      nextId_, answer.dump()));
    worlds_.insert(it->get<int>());
    return it->get<int>();
  }

  void close(int world) noexcept {
    try {
      if (!broken_) request({{"op", "close"}, {"world", world}}, "close");
    } catch (const std::exception&) {
      // A world that could not be closed is gone with the program anyway.
    }
    std::lock_guard lock(mutex_);
    worlds_.erase(world);
  }

  // Throws the error for a wrong answer to the last request (`what`: the reason), stopping the program.
  [[noreturn]] void fail(const std::string& what) {
    broken_ = true;
    process_->stop(200);
    std::string text = fmt::format("simulator '{}': {}", name_, what);
    const std::string tail = process_->stderrTail();
    if (!tail.empty()) text += "\nits last lines on stderr:\n" + tail.substr(0, tail.size() - 1);
    throw ExternalSimulatorError(config_.origin, text);
  }

  // fail(), for callers outside a request (the lock is taken).
  [[noreturn]] void failLocked(const std::string& what) {
    std::lock_guard lock(mutex_);
    fail(what);
  }

  const ProtocolSchema& schema() const { return *schema_; }
  const std::vector<std::string>& warnings() const { return warnings_; }
  const std::vector<std::string>& preferences() const { return preferences_; }
  const std::string& name() const { return name_; }
  std::uint64_t lastId() const { return nextId_; }
  std::uint64_t lastLine() const { return linesRead_; }

 private:
  json exchange(json& message, int timeoutMs, const std::string& what = "") {
    const std::uint64_t id = ++nextId_;
    message["id"] = id;
    const std::string request =
        fmt::format("request {} ({})", id, what.empty() ? message["op"].get<std::string>() : what);
    // A program that no longer reads may still have said something (a usage text, say): that is read below, and
    // its end is reported as such, before anything else.
    const bool delivered = process_->writeLine(message.dump());
    for (;;) {
      std::string line;
      switch (process_->readLine(line, delivered ? timeoutMs : std::min(timeoutMs, 1000))) {
        case ChildProcess::ReadOutcome::Line:
          break;
        case ChildProcess::ReadOutcome::Closed:
          fail(fmt::format("it {} before answering {}", process_->exitDescription(), request));
        case ChildProcess::ReadOutcome::TimedOut:
          if (!delivered) fail(fmt::format("it no longer reads its input (it closed it before {})", request));
          fail(fmt::format("it did not answer {} within {} ms; it was stopped", request, timeoutMs));
        case ChildProcess::ReadOutcome::TooLong:
          fail(fmt::format("its output line {} (the answer to {}) is longer than 64 MiB", linesRead_ + 1, request));
      }
      ++linesRead_;
      if (line.find_first_not_of(" \t") == std::string::npos) continue;  // blank lines carry nothing
      json answer;
      try {
        answer = json::parse(line);
      } catch (const json::exception&) {
        std::string shown = line.size() > 120 ? line.substr(0, 117) + "..." : line;
        fail(
            fmt::format("its output line {} is not JSON: '{}' (stdout carries the protocol only; write other text "
                        "to stderr)",
                        linesRead_, shown));
      }
      if (!answer.is_object())
        fail(fmt::format("its output line {} is not a JSON object: {}", linesRead_, answer.dump().substr(0, 120)));
      const auto idIt = answer.find("id");
      if (idIt == answer.end() || !idIt->is_number_unsigned() || idIt->get<std::uint64_t>() != id)
        fail(fmt::format("its output line {} should answer {} (\"id\": {}), but has \"id\": {}", linesRead_, request,
                         id, idIt == answer.end() ? std::string("(none)") : idIt->dump()));
      const auto okIt = answer.find("ok");
      if (okIt == answer.end() || !okIt->is_boolean())
        fail(fmt::format("its output line {} (the answer to {}) must say \"ok\": true or false", linesRead_, request));
      if (!okIt->get<bool>()) {
        const auto errIt = answer.find("error");
        fail(fmt::format("it refused {} (its output line {}): {}", request, linesRead_,
                         errIt != answer.end() && errIt->is_string() ? errIt->get<std::string>()
                                                                     : std::string("(no \"error\" given)")));
      }
      return answer;
    }
  }

  ExternalSimulatorConfig config_;
  std::shared_ptr<const ProtocolSchema> schema_;
  std::unique_ptr<ChildProcess> process_;
  std::string name_;
  std::vector<std::string> warnings_, preferences_;
  std::set<int> worlds_;
  std::uint64_t nextId_ = 0, linesRead_ = 0;
  bool broken_ = false;
  std::recursive_mutex mutex_;
};

ExternalSimulator::ExternalSimulator(const ExternalSimulatorConfig& config,
                                     std::shared_ptr<const ProtocolSchema> schema, const SimulatorOptions& options,
                                     std::uint64_t seed)
    : connection_(std::make_shared<Connection>(config, std::move(schema))) {
  connection_->greet(options);
  reset(seed);
}

ExternalSimulator::ExternalSimulator(std::shared_ptr<Connection> connection, int world)
    : connection_(std::move(connection)), world_(world) {}

ExternalSimulator::~ExternalSimulator() {
  if (world_ != 0) connection_->close(world_);
}

void ExternalSimulator::reset(std::uint64_t seed) {
  const json answer = connection_->request({{"op", "reset"}, {"world", world_}, {"seed", seed}}, "reset");
  try {
    task_ = protocol::requestedTaskOf(connection_->schema(), answer);
  } catch (const std::runtime_error& e) {
    connection_->failLocked(fmt::format("its answer to request {} (reset), output line {}: {}", connection_->lastId(),
                                        connection_->lastLine(), e.what()));
  }
}

Observation ExternalSimulator::observe() const {
  const json answer = connection_->request({{"op", "observe"}, {"world", world_}}, "observe");
  const auto it = answer.find("observation");
  std::string error = "the answer has no \"observation\"";
  if (it != answer.end())
    if (auto o = decodeObservation(connection_->schema(), *it, error)) return std::move(*o);
  connection_->failLocked(fmt::format("its answer to request {} (observe), output line {}: {}", connection_->lastId(),
                                      connection_->lastLine(), error));
}

StepResult ExternalSimulator::act(const ActionCall& call) { return step("act", &call); }

StepResult ExternalSimulator::idle() { return step("idle", nullptr); }

StepResult ExternalSimulator::step(const char* op, const ActionCall* call) {
  json message = {{"op", op}, {"world", world_}};
  std::string what = op;
  if (call != nullptr) {
    const auto sig = connection_->schema().actions.find(call->name);
    if (sig == connection_->schema().actions.end() || sig->second.params.size() != call->args.size())
      throw ExternalSimulatorError("", fmt::format("the program called '{}', which its simulator protocol schema "
                                                   "does not describe",
                                                   call->name));
    message["action"] = call->name;
    message["args"] = encodeArguments(sig->second, call->args);
    what += " " + call->name;
  }
  const json answer = connection_->request(message, what);
  StepResult r;
  try {
    r = protocol::decodeStep(connection_->schema(), answer, task_);
  } catch (const std::runtime_error& e) {
    connection_->failLocked(fmt::format("its answer to request {} ({}), output line {}: {}", connection_->lastId(),
                                        what, connection_->lastLine(), e.what()));
  }
  if (r.status == ActionStatus::UnknownAction)
    connection_->failLocked(
        fmt::format("it answered request {} ({}) with \"status\": \"unknown\"{}; its manifest "
                    "lists the action",
                    connection_->lastId(), what, r.message.empty() ? "" : " (" + r.message + ")"));
  return r;
}

std::vector<std::string> ExternalSimulator::judgedPreferences() const { return connection_->preferences(); }

std::unique_ptr<DomainSimulator> ExternalSimulator::makeEvaluationTwin() const {
  const int world = connection_->twin(world_);
  return std::unique_ptr<DomainSimulator>(new ExternalSimulator(connection_, world));
}

const std::vector<std::string>& ExternalSimulator::manifestWarnings() const { return connection_->warnings(); }

const std::string& ExternalSimulator::simulatorName() const { return connection_->name(); }

}  // namespace cbtl::sim
