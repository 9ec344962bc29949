// DomainSimulator.h — the contract between the runtime and a domain's simulated world and user.
//
// The runtime executes a solved CSP's skill actions one call at a time; the simulator applies them to its
// world, advances its clock when a call consumes a step, and reports what the (simulated) user said as
// feedback events whose names and argument lists match the `feedback` declarations of the domain's .cbtl
// file. Values cross this boundary by kind, not by the runtime's internal layout: enum members and items
// travel by name, so a simulator never depends on declaration order.
//
// Determinism: a simulator owns its RNG; reset(seed) reseeds it completely, so the same seed gives the same
// task. A simulator is used by one thread. `--resume` (approach/Checkpoint.h) relies on more: a training world
// constructed with a seed and given the same sequence of reset/act/idle calls ends in the same state with the
// same results; observe(), worldState() and requestedTask() change nothing; and an evaluation twin's calls never
// change its training world (the shared user is only read by the twin).
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace cbtl::world {
struct WorldState;
}

namespace cbtl::sim {

// One argument or observation value. `kind` tells which member is meaningful:
//   Number: real, int and bool (0/1) in `number`;  Vector: vec<N>, SE2 (x y yaw), SE3 (x y z qx qy qz qw),
//   Conf (joint angles, rad) in `vector`;  Name: enum member, item entry or text in `text`;  Names: a set of
//   enum members or item entries (observations such as `observe available : set<Item>`) in `members`.
struct Value {
  enum class Kind { Number, Vector, Name, Names };
  Kind kind = Kind::Number;
  double number = 0;
  std::vector<double> vector;
  std::string text;
  std::vector<std::string> members;

  static Value num(double v) { return Value{Kind::Number, v, {}, {}, {}}; }
  static Value vec(std::vector<double> v) { return Value{Kind::Vector, 0, std::move(v), {}, {}}; }
  static Value name(std::string s) { return Value{Kind::Name, 0, {}, std::move(s), {}}; }
  static Value names(std::vector<std::string> m) { return Value{Kind::Names, 0, {}, {}, std::move(m)}; }
};

// A skill's exception to the world's clearances (`allow` in the .cbtl file), in force for a call made inside it:
// `part` ("robot", "gripper" or "held") may come to `separation` metres of the named scene bodies (with the bodies
// below them) or geoms; a negative separation lets it touch them and sink in by that much.
struct ClearanceException {
  std::string part;
  std::vector<std::string> names;
  double separation = 0;
  std::string declaredAt;  // "file:line:col" of the `allow`
  bool operator==(const ClearanceException&) const = default;
};

struct ActionCall {
  std::string name;                                 // the extern action's name in the .cbtl file
  std::vector<Value> args;                          // in declaration order
  std::vector<ClearanceException> exceptions = {};  // innermost `allow` last; empty outside any
};

struct FeedbackEvent {
  std::string name;         // a declared `feedback` event
  std::vector<Value> args;  // in declaration order
};

enum class ActionStatus {
  Applied,        // the world changed as asked
  Ignored,        // legal call the world refused (e.g. a pot that would overlap); the step still passes
  UnknownAction,  // the simulator has no action of that name or the arguments do not fit: a domain bug
};

struct StepResult {
  ActionStatus status = ActionStatus::Applied;
  bool consumedStep = false;            // did the world's clock advance by one step?
  bool taskDone = false;                // the episode's task ended (e.g. the meal was served)
  bool taskFailed = false;              // with taskDone: it ended because the world could not carry out the plan
  bool hasSatisfaction = false;         // the user scored the outcome on this step
  double satisfaction = 0;              // +1 / -1 when hasSatisfaction
  bool preferencesChanged = false;      // the user announced that their preferences changed
  bool caregiverReset = false;          // a person put the robot back to a safe start (it was stuck)
  std::vector<FeedbackEvent> feedback;  // what the user said on this step
  // With hasSatisfaction, optionally: each of the user's preferences this outcome was judged on, by name, and
  // whether it was met (e.g. {"dip", true}, {"view", false}); evaluation reports each one's rate apart.
  std::vector<std::pair<std::string, bool>> preferences;
  // With taskDone, optionally: numbers the domain measured over the task, by name (e.g. {"userClearance", 0.034}:
  // the closest the robot came to the user, metres); evaluation reports each one's minimum and mean.
  std::vector<std::pair<std::string, double>> measures;
  std::string message;  // human-readable detail (why an action was ignored, ...)
  // What the robot's body did, for the run's record of executed motions (motions.jsonl): one JSON object per
  // motion, written by the domain (robot domains: robot/world/MotionRecord.h) and never read by the runtime.
  std::vector<std::string> motions;
};

// Observations by the name declared with `observe`; families by "name[member]" (e.g. "stock[salt]").
using Observation = std::map<std::string, Value>;

class DomainSimulator {
 public:
  virtual ~DomainSimulator() = default;

  // Starts a new episode from a fresh random world drawn with `seed` (the RNG is reseeded).
  virtual void reset(std::uint64_t seed) = 0;

  // The world state that a CSP reads when it is generated.
  virtual Observation observe() const = 0;

  // Applies one action call of a skill.
  virtual StepResult act(const ActionCall& call) = 0;

  // Lets one step pass without an action (the robot had no plan, e.g. its CSP was infeasible).
  virtual StepResult idle() = 0;

  // Robot domains: the kinematic state of the simulated scene (arm, base, objects, grasp). The runtime copies
  // it into the robot world its built-ins read (confCollisionFree, ikSample, ...) before it builds a CSP, so
  // the CSP is checked against the world it will act in. nullptr for domains without a robot scene.
  virtual const world::WorldState* worldState() const { return nullptr; }

  // The task (its name in the .cbtl file) the world asks for now, e.g. a "put away, then ..." task while the robot
  // still holds something; empty: the task the run was configured with.
  virtual std::string requestedTask() const { return {}; }

  // The names StepResult::preferences uses, in the order evaluation reports them (one eval.csv column each);
  // empty: the domain judges outcomes by satisfaction only.
  virtual std::vector<std::string> judgedPreferences() const { return {}; }

  // A second world for evaluation that shares this world's simulated user (so an evaluation sees the
  // user's current, possibly shifted, preferences) but has its own world state and RNG.
  virtual std::unique_ptr<DomainSimulator> makeEvaluationTwin() const = 0;
};

// Experiment switches a domain may honour; a domain ignores those that do not apply to it.
struct SimulatorOptions {
  // Paper's Figure 5: every `shiftEvery` steps of the training world, each preference range of the user
  // is rescaled around its centre by a factor drawn from U[shiftLo, shiftHi]. 0 disables.
  std::int64_t shiftEvery = 0;
  double shiftLo = 0.9, shiftHi = 1.1;
  // The user says so when their preferences shift (enables the "User Reset" variant).
  bool announceShifts = false;
  // Paper's Table 1: after every restock, with this probability the stock cannot satisfy the user.
  double unsatisfiableStockProbability = 0;
  // The simulated user: -1 the domain's default user; n >= 0 the domain's n-th drawn participant, with their own
  // preferences (the same n, the same person; Feeding).
  std::int64_t participant = -1;
};

}  // namespace cbtl::sim
