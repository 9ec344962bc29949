#include "robot/actions/RobotSimulator.h"

#include "robot/world/GraspClosure.h"
#include "runtime/sim/SimulatorBase.h"

#include <stdexcept>
#include <utility>

namespace cbtl::actions {

RobotSimulator::RobotSimulator(Setup setup)
    : domain_(std::move(setup.domain)),
      scene_(std::move(setup.scene)),
      world_(std::make_unique<world::World>(scene_)),
      actions_(std::move(setup.actions)),
      caregiverPatience_(setup.caregiverPatience) {
  scenePoses_ = world_->workspace().state().objects;
  world_->setRecording(true);
}

void RobotSimulator::startEpisode(const world::WorldState& state) {
  idleRun_ = 0;
  world_->utterances().clear();
  setWorldState(state);
}

void RobotSimulator::setWorldState(const world::WorldState& state) {
  world::Workspace& ws = world_->workspace();
  if (ws.setState(state) != world::StateStatus::Ok) throw std::logic_error(domain_ + ": the world state is invalid");
  if (ws.heldObject() < 0) return;
  const world::GraspClosure grip = world::gripHeld(ws);
  if (!grip.holds())
    throw std::logic_error(domain_ + ": the gripper cannot hold " + state.held->object + ": " + grip.detail);
}

sim::StepResult RobotSimulator::failTask(sim::StepResult step) {
  step.status = sim::ActionStatus::Ignored;
  step.taskDone = true;
  step.taskFailed = true;
  return afterFailure(std::move(step));
}

sim::StepResult RobotSimulator::act(const sim::ActionCall& call) {
  idleRun_ = 0;
  if (auto own = actOnSimulatorState(call)) return std::move(*own);
  world_->takeMotions();
  const auto result = actions_.execute(*world_, call);
  // A failed action leaves the world as it was: the motions it tried were never carried out.
  std::vector<world::ExecutedMotion> motions = world_->takeMotions();
  if (!result) return sim::unknownActionStep(domain_ + " has no action '" + call.name + "'");
  sim::StepResult step = result->toStepResult(call.name);
  if (!result->wellFormed) return step;
  if (!result->done()) return failTask(std::move(step));
  for (const auto& m : motions) step.motions.push_back(world::motionToJson(*scene_, m));
  return afterApplied(call, *result, std::move(step));
}

sim::StepResult RobotSimulator::idle() {
  sim::StepResult step = sim::idleStep("idle: the robot waits");
  if (caregiverPatience_ > 0 && ++idleRun_ >= caregiverPatience_) {
    idleRun_ = 0;
    caregiverReset();
    step.caregiverReset = true;
    step.message = "the robot was stuck: the caregiver put it back at its start";
  }
  return step;
}

}  // namespace cbtl::actions
