#include "app/SimulatorServer.h"

#include "app/SimulatorFacts.h"
#include "domains/DomainRegistry.h"
#include "runtime/sim/SimulatorProtocol.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <istream>
#include <map>
#include <memory>
#include <ostream>
#include <stdexcept>

namespace cbtl::app {

namespace {

using nlohmann::json;

class Server {
 public:
  explicit Server(const LoadedProgram& program) : program_(program), schema_(schemaOf(program)) {}

  // The answer's fields for one request; throws std::runtime_error for a request it refuses.
  json handle(const json& request, bool& bye) {
    const std::string op = request.value("op", "");
    if (op == "hello") return hello(request);
    if (op == "bye") {
      bye = true;
      return json::object();
    }
    if (worlds_.empty()) throw std::runtime_error("say hello first");
    if (op == "reset") {
      sim::DomainSimulator& w = world(request);
      const auto seed = request.find("seed");
      if (seed == request.end() || !seed->is_number_unsigned()) throw std::runtime_error("reset needs \"seed\" >= 0");
      w.reset(seed->get<std::uint64_t>());
      return {{"task", w.requestedTask()}};
    }
    if (op == "observe") return {{"observation", sim::encodeObservation(schema_, world(request).observe())}};
    if (op == "act") return act(request);
    if (op == "idle") {
      sim::DomainSimulator& w = world(request);
      const sim::StepResult r = w.idle();
      return sim::protocol::encodeStep(schema_, r, w.requestedTask());
    }
    if (op == "twin") {
      auto twin = world(request).makeEvaluationTwin();
      const int id = nextWorld_++;
      worlds_[id] = std::move(twin);
      return {{"world", id}};
    }
    if (op == "close") {
      world(request);
      worlds_.erase(request["world"].get<int>());
      return json::object();
    }
    throw std::runtime_error(
        fmt::format("no request \"{}\" in protocol {} (hello, reset, observe, act, idle, twin, "
                    "close, bye)",
                    op, sim::protocol::kVersion));
  }

  // Twins first: they may read what their training world owns.
  void closeAll() {
    for (auto it = worlds_.rbegin(); it != worlds_.rend(); ++it) it->second.reset();
    worlds_.clear();
  }

 private:
  static sim::ProtocolSchema schemaOf(const LoadedProgram& program) {
    std::vector<std::string> keys;
    for (const auto& [key, _] : program.program().observationSlots()) keys.push_back(key);
    return sim::ProtocolSchema::fromProgram(program.graph(), keys);
  }

  json hello(const json& request) {
    if (request.value("protocol", -1) != sim::protocol::kVersion)
      throw std::runtime_error(fmt::format("this server speaks protocol {}", sim::protocol::kVersion));
    if (!worlds_.empty()) throw std::runtime_error("hello was said already");
    const sim::SimulatorOptions options =
        sim::protocol::optionsFrom(request.contains("options") ? request["options"] : json::object());
    auto world = domains::createSimulator(program_.graph().domain, simulatorFacts(program_), options, 0);
    if (!world)
      throw std::runtime_error(
          fmt::format("cbtl has no in-process simulator for domain '{}'", program_.graph().domain));
    json manifest = sim::protocol::manifestFor(schema_, world->judgedPreferences(),
                                               fmt::format("cbtl simulator serve ({})", program_.graph().domain));
    worlds_[0] = std::move(world);
    return manifest;
  }

  json act(const json& request) {
    sim::DomainSimulator& w = world(request);
    const std::string name = request.value("action", "");
    const auto sig = schema_.actions.find(name);
    if (sig == schema_.actions.end()) throw std::runtime_error(fmt::format("the program calls no action '{}'", name));
    std::string error;
    auto args = sim::decodeArguments(sig->second, request.contains("args") ? request["args"] : json::object(), error);
    if (!args) throw std::runtime_error(error);
    const sim::StepResult r = w.act(sim::ActionCall{name, std::move(*args)});
    return sim::protocol::encodeStep(schema_, r, w.requestedTask());
  }

  sim::DomainSimulator& world(const json& request) {
    const auto it = request.find("world");
    if (it == request.end() || !it->is_number_integer())
      throw std::runtime_error("the request needs \"world\": a world's number");
    const auto w = worlds_.find(it->get<int>());
    if (w == worlds_.end()) throw std::runtime_error(fmt::format("there is no world {}", it->get<int>()));
    return *w->second;
  }

  const LoadedProgram& program_;
  sim::ProtocolSchema schema_;
  std::map<int, std::unique_ptr<sim::DomainSimulator>> worlds_;
  int nextWorld_ = 1;
};

}  // namespace

int serveSimulator(const LoadedProgram& program, std::istream& in, std::ostream& out) {
  Server server(program);
  std::string line;
  bool bye = false;
  int status = 0;
  while (!bye && std::getline(in, line)) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    json answer;
    json request;
    try {
      request = json::parse(line);
      if (!request.is_object()) throw std::runtime_error("a request is a JSON object");
      answer = server.handle(request, bye);
      answer["ok"] = true;
    } catch (const std::exception& e) {
      answer = {{"ok", false}, {"error", e.what()}};
      if (request.is_object() && request.value("op", "") == "hello") status = 1;
    }
    if (request.is_object() && request.contains("id")) answer["id"] = request["id"];
    out << answer.dump() << '\n' << std::flush;
  }
  server.closeAll();
  return status;
}

}  // namespace cbtl::app
