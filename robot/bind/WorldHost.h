// WorldHost.h — the robot world as the language's built-ins see it: one world::World (a Workspace over the
// domain's shared Scene, FCL shapes, occlusion spec) plus the *observed state*, the world as the simulator
// showed it when the current CSP was made, and the *reference state* the built-ins read: the observed state,
// or during a staged evaluation the state the earlier skills of the plan leave (enterStage).
//
// Contract: every built-in starts from the reference state and changes only what its arguments say (the
// arm, the base, a held object, one body's pose); nothing a built-in does is visible to the next one. The
// runtime sets the observed state from the domain simulator before it builds a CSP (Planner), so constraints
// are checked against the world the plan will run in; without a simulator it is the scene's initial state
// with the arm at `retract`.
//
// It is also the runtime's world model (runtime/sim/ExecutionModel.h): enterStage applies the end effects of a
// plan's earlier actions (the executor's Effects mode) to the observed state, and dryRun runs a whole plan with
// the executor's every check in a private world. The executor is the domain's (setExecutor; by default the
// standard actions only). Both are cached by (observed state, calls) fingerprints; the executor is pure, so a
// cached verdict equals a fresh one.
//
// Thread safety: one WorldHost per Program, used by one thread (the Program's contract). Frames: world,
// metres, radians.
#pragma once

#include "robot/actions/RobotActions.h"
#include "robot/world/SurfaceFace.h"
#include "robot/world/WorldOperations.h"  // world::World
#include "runtime/core/Builtins.h"        // rt::BuiltinHost
#include "runtime/sim/ExecutionModel.h"

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>

namespace cbtl::bind {

inline constexpr double kSideGraspDepth = 0.03;  // metres from the tool frame to the grasped box centre

class WorldHost final : public rt::BuiltinHost, public sim::ExecutionModel {
 public:
  explicit WorldHost(std::shared_ptr<const world::Scene> scene);

  world::World& world() { return world_; }
  world::Workspace& workspace() { return world_.workspace(); }
  const world::Scene& scene() const { return world_.workspace().scene(); }

  // Replaces the observed state (and makes it the reference). Returns false (nothing changed) when the state
  // does not fit the scene.
  bool setReference(const world::WorldState& state);
  const world::WorldState& reference() const { return reference_; }
  const world::WorldState& observed() const { return observed_; }

  // The executor of dry runs and stage effects: the domain's actions plus the standard ones.
  void setExecutor(std::shared_ptr<const actions::RobotActions> executor) { executor_ = std::move(executor); }

  sim::ExecutionModel* executionModel() override { return this; }
  sim::PlanVerdict enterStage(std::span<const sim::ActionCall> prefix) override;
  // The executor later finds the dry run's plans in the scene's motion cache, whatever its own larger budget.
  sim::PlanVerdict dryRun(std::span<const sim::ActionCall> calls, int motionIterations) override;
  bool models(std::string_view action) const override { return executor_->knows(action); }

  // Puts the workspace at the reference state with `base` and arm `q` (and, when `held` names an object, that
  // object attached at nominalGrasp(held) instead of the reference's grasp). false when q is out of limits
  // or `held` is not a movable object.
  bool pose(const world::Pose2& base, const world::ArmConfig& q, const std::string* held = nullptr);
  // Moves one movable object for a query; the next pose() call puts it back.
  bool moveObject(const std::string& object, const world::Pose3& pose);

  // The grasp of `object`: the reference's when the robot holds it; else the scene's standard grasp, the site
  // "<object>_tool" whose frame is the tool frame at that grasp (home.xml's duster_tool); else the side grasp
  // sideGrasp(object, -pi/2). The object's frame in the tool frame.
  std::optional<world::Pose3> nominalGrasp(const std::string& object);
  // Tool pose grasping the box of `object` (at `objectPose`) from the side: with yaw = -pi/2 the tool z (the
  // approach) runs along the object's +y, tool x along its x (the fingers close across it) and tool y along
  // its -z; other yaws turn that about the object's z by yaw + pi/2. The box centre lies kSideGraspDepth
  // ahead of the tool frame (between the finger tips). With yaw = -pi/2 this is the carry grasp of the home
  // scene's books (robot/actions/StandardGrasps.h bookToolInBody).
  std::optional<world::Pose3> sideGrasp(const std::string& object, const world::Pose3& objectPose, double yaw);

  // A named arm configuration (world/NamedConfigurations.h: the scene's conf_<name>, else the standard table).
  std::optional<world::ArmConfig> namedConf(const std::string& name) const;
  std::optional<world::SurfaceFace> surfaceTop(const std::string& geom) const;
  // The box geom whose top face the object at its reference pose rests on (bottom within 1 cm, centre over
  // the face); empty when none.
  std::string supportSurface(const std::string& object);
  // The object's lowest point and footprint (world AABB half-extents in x, y) at `pose`.
  struct Footprint {
    double bottom = 0, centerX = 0, centerY = 0, halfX = 0, halfY = 0;
  };
  std::optional<Footprint> footprint(const std::string& object, const world::Pose3& pose) const;

  int planIterations = 3000;  // budgets of the feasibility built-ins (WorldBuiltins.h)
  int ikAttempts = 10;

 private:
  // Runs `calls` on dryWorld_ from the observed state in `mode`; the first failure, if any.
  sim::PlanVerdict runCalls(std::span<const sim::ActionCall> calls, actions::ExecutionMode mode);
  void useReference(const world::WorldState& state);

  world::World world_;
  world::World dryWorld_;  // dry runs and stage effects, so the built-ins' workspace is never disturbed
  std::shared_ptr<const actions::RobotActions> executor_;
  world::WorldState observed_;
  std::uint64_t observedFingerprint_ = 0;
  std::uint64_t stage_ = 0;  // fingerprint of the stage the reference shows; 0: the observed state
  world::WorldState reference_;
  bool dirty_ = true;  // the workspace's objects or grasp differ from the reference

  // Verdicts and stage states by fingerprint of (observed state, calls), first in first out.
  struct StageEntry {
    sim::PlanVerdict verdict;
    world::WorldState state;
  };
  std::unordered_map<std::uint64_t, StageEntry> stages_;
  std::deque<std::uint64_t> stageOrder_;
  std::unordered_map<std::uint64_t, sim::PlanVerdict> verdicts_;
  std::deque<std::uint64_t> verdictOrder_;
};

}  // namespace cbtl::bind
