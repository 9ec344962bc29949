// The external simulator protocol's pieces: wire values checked by declared type, step results read strictly,
// manifests checked with every mismatch listed, and the child process that never hangs.
#include "runtime/sim/ChildProcess.h"
#include "runtime/sim/ExternalSimulator.h"
#include "runtime/sim/ProtocolSchema.h"
#include "runtime/sim/SimulatorProtocol.h"
#include "tests/unit/runtime/TestPrograms.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>

namespace cbtl::sim {
namespace {

using nlohmann::json;

const char* kProgram = R"(domain proto;
enum Size { small, large }
observe stock[Size] : real;
observe hour : int;
observe open : bool;
feedback verdict(size: Size, temp: real, good: bool, spot: vec<2>);
var size : Size;
var temp : real in 0 .. 10;
sample size ~ uniform;
sample temp ~ uniform;
personal likesTemp(t: real) {
  when t ~ "temp";
  model interval(t, 0 .. 10);
  learn verdict(_, t, good, _) => good;
}
extern action brew(size: Size, temp: real);
extern action unused(n: int);
skill brewCup { do { brew(size, temp); } }
task cup = brewCup;
)";

ProtocolSchema schemaOf(const app::LoadedProgram& lp) {
  std::vector<std::string> keys;
  for (const auto& [key, _] : lp.program().observationSlots()) keys.push_back(key);
  return ProtocolSchema::fromProgram(lp.graph(), keys);
}

TEST(ProtocolSchema, ReadsTheProgramsDeclarations) {
  auto lp = test::compileOrFail("proto.cbtl", kProgram);
  const ProtocolSchema s = schemaOf(*lp);
  EXPECT_EQ(s.observations.size(), 4u);  // stock[small], stock[large], hour, open
  EXPECT_EQ(s.observations.at("stock[large]").kind, WireType::Kind::Real);
  EXPECT_EQ(s.observations.at("hour").kind, WireType::Kind::Int);
  EXPECT_EQ(s.actions.count("brew"), 1u);
  EXPECT_EQ(s.actions.count("unused"), 0u);  // no task calls it
  ASSERT_EQ(s.feedback.at("verdict").params.size(), 4u);
  EXPECT_EQ(s.feedback.at("verdict").params[0].type.members, (std::vector<std::string>{"small", "large"}));
  EXPECT_EQ(s.feedback.at("verdict").params[3].type.width, 2u);
  EXPECT_EQ(s.learnedEvents.count("verdict"), 1u);
  EXPECT_EQ(s.tasks, std::vector<std::string>{"cup"});
}

TEST(ProtocolSchema, ValuesAreCheckedByDeclaredType) {
  auto lp = test::compileOrFail("proto.cbtl", kProgram);
  const ProtocolSchema s = schemaOf(*lp);
  const WireSignature& sig = s.feedback.at("verdict");
  std::string error;
  auto args = decodeArguments(sig, json{{"size", "large"}, {"temp", 3.5}, {"good", true}, {"spot", {1, 2}}}, error);
  ASSERT_TRUE(args) << error;
  EXPECT_EQ((*args)[0].text, "large");
  EXPECT_EQ((*args)[2].number, 1.0);
  EXPECT_EQ(encodeArguments(sig, *args),
            (json{{"size", "large"}, {"temp", 3.5}, {"good", true}, {"spot", {1.0, 2.0}}}));
  // The same in declaration order.
  EXPECT_TRUE(decodeArguments(sig, json::array({"small", 1, false, {0, 0}}), error));

  EXPECT_FALSE(decodeArguments(sig, json{{"size", "huge"}, {"temp", 3.5}, {"good", true}, {"spot", {1, 2}}}, error));
  EXPECT_NE(error.find("'huge' is not a Size (expected small or large)"), std::string::npos) << error;
  EXPECT_FALSE(decodeArguments(sig, json{{"size", "small"}, {"temp", "hot"}, {"good", true}, {"spot", {1, 2}}}, error));
  EXPECT_NE(error.find("argument 'temp': expected a finite number"), std::string::npos) << error;
  EXPECT_FALSE(decodeArguments(sig, json{{"size", "small"}, {"temp", 1}, {"good", 1}, {"spot", {1, 2}}}, error));
  EXPECT_NE(error.find("expected true or false"), std::string::npos) << error;
  EXPECT_FALSE(decodeArguments(sig, json{{"size", "small"}, {"temp", 1}, {"good", true}, {"spot", {1}}}, error));
  EXPECT_NE(error.find("expected an array of 2 numbers"), std::string::npos) << error;
  EXPECT_FALSE(decodeArguments(sig, json{{"size", "small"}, {"temp", 1}, {"good", true}}, error));
  EXPECT_NE(error.find("missing its argument 'spot'"), std::string::npos) << error;
  EXPECT_FALSE(decodeArguments(sig, json{{"size", "small"}, {"tmp", 1}, {"good", true}, {"spot", {1, 2}}}, error));
  EXPECT_NE(error.find("no parameter 'tmp'"), std::string::npos) << error;
  EXPECT_FALSE(decodeArguments(sig, json::array({"small"}), error));
  EXPECT_NE(error.find("takes 4 argument(s), got 1"), std::string::npos) << error;
}

TEST(ProtocolSchema, ObservationsReadFamiliesAndListEveryProblem) {
  auto lp = test::compileOrFail("proto.cbtl", kProgram);
  const ProtocolSchema s = schemaOf(*lp);
  const json good = {{"stock", {{"small", 1.5}, {"large", 2}}}, {"hour", 7}, {"open", true}};
  std::string error;
  auto o = decodeObservation(s, good, error);
  ASSERT_TRUE(o) << error;
  EXPECT_EQ(o->at("stock[large]").number, 2.0);
  EXPECT_EQ(encodeObservation(s, *o), (json{{"stock", {{"small", 1.5}, {"large", 2.0}}}, {"hour", 7}, {"open", true}}));

  const json bad = {{"stock", {{"small", 1.5}, {"medium", 2}}}, {"hour", 7.5}, {"weather", "rain"}};
  EXPECT_FALSE(decodeObservation(s, bad, error));
  for (const char* part : {"'stock' has no member 'medium'", "'hour': expected an integer",
                           "'weather' is not an "
                           "observation of the program",
                           "'stock[large]' is missing", "'open' is missing"})
    EXPECT_NE(error.find(part), std::string::npos) << part << " in: " << error;
}

TEST(SimulatorProtocol, StepResultsAreReadStrictly) {
  auto lp = test::compileOrFail("proto.cbtl", kProgram);
  const ProtocolSchema s = schemaOf(*lp);
  std::string task;
  const json answer = {{"id", 3},
                       {"ok", true},
                       {"status", "applied"},
                       {"step", true},
                       {"done", true},
                       {"satisfaction", -1},
                       {"feedback", {{{"event", "verdict"}, {"args", {"small", 2, false, {0, 1}}}}}},
                       {"preferences", {{"temp", false}}},
                       {"measures", {{"ml", 150}}},
                       {"task", "cup"}};
  const StepResult r = protocol::decodeStep(s, answer, task);
  EXPECT_TRUE(r.consumedStep && r.taskDone && r.hasSatisfaction);
  EXPECT_EQ(r.satisfaction, -1);
  ASSERT_EQ(r.feedback.size(), 1u);
  EXPECT_EQ(r.feedback[0].args[1].number, 2.0);
  EXPECT_EQ(task, "cup");
  // Round trip through the server's encoding.
  std::string again;
  const StepResult back = protocol::decodeStep(s, protocol::encodeStep(s, r, task), again);
  EXPECT_EQ(back.feedback[0].args[3].vector, (std::vector<double>{0, 1}));
  EXPECT_EQ(again, "cup");

  auto throwsWith = [&](json a, const std::string& part) {
    try {
      protocol::decodeStep(s, a, task);
      ADD_FAILURE() << "accepted " << a.dump();
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  throwsWith({{"satisfation", 1}}, "no field \"satisfation\"");
  throwsWith({{"status", "done"}}, "\"status\" must be");
  throwsWith({{"failed", true}}, "needs \"done\": true");
  throwsWith({{"feedback", {{{"event", "spilled"}}}}}, "'spilled' is not declared");
  throwsWith({{"task", "tea"}}, "no task 'tea'");
  throwsWith({{"satisfaction", "great"}}, "finite number");
}

TEST(SimulatorProtocol, ManifestMismatchesAreListedTogether) {
  auto lp = test::compileOrFail("proto.cbtl", kProgram);
  const ProtocolSchema s = schemaOf(*lp);
  const json fits = protocol::manifestFor(s, {"temp"}, "test");
  EXPECT_TRUE(protocol::checkManifest(s, fits).errors.empty());
  json bad = fits;
  bad["observations"] = {"stock", "wind"};
  bad["actions"] = json::array();
  bad["feedback"] = {"grumble"};
  bad["tasks"] = {"tea"};
  const auto c = protocol::checkManifest(s, bad);
  EXPECT_EQ(c.errors.size(), 6u);    // hour, open, wind, brew, grumble, tea
  ASSERT_EQ(c.warnings.size(), 1u);  // verdict is learned but never sent
  EXPECT_NE(c.warnings[0].find("'verdict'"), std::string::npos);
  json newer = fits;
  newer["protocol"] = 2;
  EXPECT_EQ(protocol::checkManifest(s, newer).errors.size(), 1u);
}

TEST(ChildProcess, ReadsLinesAndReportsHowItEnded) {
  ChildProcess p("read line; echo \"got $line\"; echo 'on stderr' >&2; exit 4", "", "test| ");
  ASSERT_TRUE(p.writeLine("hello"));
  std::string line;
  ASSERT_EQ(p.readLine(line, 5000), ChildProcess::ReadOutcome::Line);
  EXPECT_EQ(line, "got hello");
  EXPECT_EQ(p.readLine(line, 5000), ChildProcess::ReadOutcome::Closed);
  EXPECT_EQ(p.exitDescription(), "exited with status 4");
  EXPECT_NE(p.stderrTail().find("on stderr"), std::string::npos);
  EXPECT_FALSE(p.writeLine("nobody listens"));  // no SIGPIPE: this test would die of it
}

TEST(ChildProcess, ATimeoutIsATimeoutAndStopKillsTheGroup) {
  ChildProcess p("sleep 30; echo late", "", "test| ");
  std::string line;
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(p.readLine(line, 200), ChildProcess::ReadOutcome::TimedOut);
  p.stop(50);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
  EXPECT_NE(p.exitDescription().find("killed by signal 9"), std::string::npos) << p.exitDescription();
}

TEST(ExternalSimulator, AProgramThatIsNotASimulatorIsBadInputNamingTheRequest) {
  auto lp = test::compileOrFail("proto.cbtl", kProgram);
  auto schema = std::make_shared<const ProtocolSchema>(schemaOf(*lp));
  ExternalSimulatorConfig c;
  c.command = "echo 'Usage: sim [options]'";
  c.timeoutMs = 5000;
  try {
    ExternalSimulator s(c, schema, {}, 1);
    ADD_FAILURE() << "accepted a program that is not a simulator";
  } catch (const ExternalSimulatorError& e) {
    EXPECT_NE(std::string(e.what()).find("its output line 1 is not JSON: 'Usage: sim [options]'"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace cbtl::sim
