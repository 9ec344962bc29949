// RobotSimulator.h — the part of the DomainSimulator contract every robot domain (Cleaning, Books, Feeding) implements
// the same way: one robot world built from the program's scene, the executor of the standard actions (and the
// domain's own, RobotActions.h), the step loop around it, and idling with a caregiver who steps in when the robot has
// been stuck too long. A domain supplies what differs through the hooks below: what its user says about an action
// the world carried out, how a failed action ends its task, and what its caregiver does.
//
// act(call), in order:
//   1. actOnSimulatorState(call): a domain action that reads the simulator's own state rather than the world's
//      (Feeding's dipInto checks this meal's sauces); a result is returned as it is.
//   2. RobotActions::execute: a name neither standard nor the domain's is UnknownAction "<domain> has no action
//      '<name>'" (no step); an ill-formed call is UnknownAction with the executor's detail (no step).
//   3. A well-formed call the world could not carry out (no IK, no path, ...): status Ignored, taskDone and
//      taskFailed set, then afterFailure(step) (the world is as before the call; the domain ends its task).
//   4. A call the world carried out: afterApplied(call, result, step).
// Every act() ends a run of idle steps.
// idle(): one step passes (idleStep "idle: the robot waits"); with caregiverPatience > 0, the patience-th idle step
// in a row is also a caregiver reset: caregiverReset() runs, the step reports caregiverReset and says so.
//
// Units and frames: those of the world (robot/world/WorldOperations.h): metres, radians, the scene's world frame.
#pragma once

#include "robot/actions/RobotActions.h"
#include "robot/world/WorldOperations.h"
#include "runtime/sim/DomainSimulator.h"

#include <map>
#include <memory>
#include <optional>
#include <string>

namespace cbtl::actions {

class RobotSimulator : public sim::DomainSimulator {
 public:
  struct Setup {
    std::string domain;                         // the domain's name, for messages ("cleaning")
    std::shared_ptr<const world::Scene> scene;  // the program's scene, shared with evaluation twins
    RobotActions actions;                       // standard actions plus the domain's own
    int caregiverPatience = 0;                  // idle steps in a row before a caregiver reset; 0: never
  };

  sim::StepResult act(const sim::ActionCall& call) final;
  sim::StepResult idle() final;
  const world::WorldState* worldState() const final { return &world_->workspace().state(); }

  // The robot world (tests and tools may inspect or arrange it).
  world::World& world() { return *world_; }
  const world::World& world() const { return *world_; }

 protected:
  explicit RobotSimulator(Setup setup);

  const world::Scene& scene() const { return *scene_; }
  // The movable objects' poses as the scene file puts them.
  const std::map<std::string, world::Pose3>& scenePoses() const { return scenePoses_; }
  // Makes `state` the world's state at an episode start and forgets what the robot said and how long it idled. A
  // state the world rejects is a bug of the domain: std::logic_error naming the domain.
  void startEpisode(const world::WorldState& state);
  // Makes `state` the world's state (an episode start, a caregiver's reset); an object it has in hand is gripped as
  // a grasp would grip it (world/GraspClosure.h gripHeld: the fingers closed to where they touch it). A state the
  // world rejects, or a held object the fingers cannot hold, is a bug of the domain: std::logic_error.
  void setWorldState(const world::WorldState& state);

  // Step 1 of act(): nullopt when `call` is not such an action.
  virtual std::optional<sim::StepResult> actOnSimulatorState(const sim::ActionCall&) { return std::nullopt; }
  // Step 4 of act(): `step` is the executor's result as a StepResult (Applied, its steps, its detail).
  virtual sim::StepResult afterApplied(const sim::ActionCall& call, const RobotActionResult& result,
                                       sim::StepResult step) = 0;
  // Step 3 of act(), and for a domain action of step 1 that fails: the task ended as failed.
  virtual sim::StepResult afterFailure(sim::StepResult step) = 0;
  // Puts a stuck robot back to a safe start (idle(), after caregiverPatience idle steps in a row).
  virtual void caregiverReset() {}

  // Marks `step` as the failure of its task (Ignored, taskDone, taskFailed) and hands it to afterFailure.
  sim::StepResult failTask(sim::StepResult step);

 private:
  std::string domain_;
  std::shared_ptr<const world::Scene> scene_;
  std::unique_ptr<world::World> world_;
  std::map<std::string, world::Pose3> scenePoses_;
  RobotActions actions_;
  int caregiverPatience_ = 0;
  int idleRun_ = 0;  // idle steps in a row
};

}  // namespace cbtl::actions
