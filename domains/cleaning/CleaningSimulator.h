// CleaningSimulator.h — the Cleaning domain behind the runtime's DomainSimulator contract: the home scene
// (robot on its mobile base, duster, books as obstacles) plus CleaningUser (hidden preference), speaking
// the names of domains/cleaning/cleaning.cbtl.
//
// Episode start (reset(seed), all draws from the simulator's RNG in this order):
//   1. the room of robot/HomeEpisode.h (base at the origin, arm at homeSceneInitial, duster on the main
//      table, books parked outside the room);
//   2. a uniform permutation of the nine books;
//   3. what the robot holds: nothing, the duster or a book (the permutation's second book), 1/3 each, so
//      the three tasks occur equally often; holding puts the arm at the carry configuration (HomeEpisode holdCarried);
//   4. the first task's obstacle (coverOneSurface).
// Every task (the paper: "for each task, we randomly sample one surface to cover with obstacles"): the books
// lying on the furniture (one the robot put away) are tidied away, and one surface is covered by one upright
// book (the permutation's first, unless the robot holds it) at a uniform spot and yaw, kept
// kObstacleClearance from other objects: the surfaces are tried in a uniform random order and the first with
// room for the book (world::builtins::samplePlacement, 100 tries) is covered — the main table often has no room
// while the duster lies on it. A task ends with the user's reaction to a wipe or with a failed action; the next
// one starts from the robot's state (base, arm, what it holds), with a new surface covered.
//
// Observations (cleaning.cbtl): "clearSurfaces" (Names: the Surface members on which no object rests —
// SurfaceGeometry.h restsOn; the duster does not count, as every plan picks it up before it wipes),
// "heldBody" (Name: "", "duster" or "book_k"), "basePose" (Vector x, y, yaw).
// requestedTask(): "cleanWithDusterInHand" holding the duster, "cleanSurface" empty-handed, otherwise
// "stowThenClean".
//
// Actions: the standard actions (robot/RobotActions.h; every well-formed action takes one step, wait(n)
// n steps). A call of another name, or one of the wrong shape, is UnknownAction (no step).
//   - A completed wipe of one of the seven surfaces is judged by the user: feedback
//     cleaningReaction(surface, welcome), satisfaction +1 (welcome) or -1. The task ends (taskDone) when the
//     robot then says "Done" (the reference's missions complete on "Done"), after it has put its arm back.
//   - A failed action (no path, no IK, not holding, ...) ends the task as failed: status Ignored, taskDone,
//     no satisfaction (the user did not see a cleaning to judge), the message says why; the world is as
//     before that action.
// idle(): one step passes, nothing changes; after home::kCaregiverPatience idle steps in a row (the robot found no
// plan) a caregiver resets it (HomeEpisode.h caregiverReset; StepResult::caregiverReset), and a new task begins.
// Options: none of SimulatorOptions applies (the user has no ranges to shift and there is no stock); they are
// kept only for the evaluation twin.
// Lifetime state (not touched by reset): the user, shared with evaluation twins.
#pragma once

#include "domains/ProgramFacts.h"
#include "domains/cleaning/CleaningUser.h"
#include "robot/actions/RobotSimulator.h"
#include "runtime/sim/SimulatorBase.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace cbtl::domains::cleaning {

inline constexpr double kObstacleClearance = 0.02;     // metres between an obstacle book and other objects
inline constexpr const char* kDoneUtterance = "Done";  // what the robot says when it has finished a task

// What a training world shares with its evaluation twins.
struct CleaningShared {
  std::shared_ptr<const world::Scene> scene;
  CleaningUser user;
};

// The step loop, idling and the caregiver are actions::RobotSimulator's; the evaluation twin is sim::SimulatorBase's
// (it shares the user; its own world and RNG, reset with seed 0 until the caller resets it).
class CleaningSimulator final
    : public sim::SimulatorBase<CleaningSimulator, const CleaningShared, actions::RobotSimulator> {
 public:
  // The paper's user (CleaningUser::paperDefault) in the program's scene (home.xml). Throws
  // std::invalid_argument when `program` names no scene, std::runtime_error when it cannot be loaded.
  CleaningSimulator(const ProgramFacts& program, const sim::SimulatorOptions& options, std::uint64_t seed);
  CleaningSimulator(const ProgramFacts& program, const sim::SimulatorOptions& options, std::uint64_t seed,
                    CleaningUser user);

  void reset(std::uint64_t seed) override;
  sim::Observation observe() const override;
  std::string requestedTask() const override;

  const CleaningUser& user() const { return shared().user; }
  // The Surface members that are clear now (the "clearSurfaces" observation).
  std::vector<std::string> clearSurfaces() const;

 private:
  friend class sim::SimulatorBase<CleaningSimulator, const CleaningShared, actions::RobotSimulator>;
  CleaningSimulator(std::shared_ptr<const CleaningShared> shared, const sim::SimulatorOptions& options,
                    sim::WorldRole role, std::uint64_t seed);

  sim::StepResult afterApplied(const sim::ActionCall& call, const actions::RobotActionResult& result,
                               sim::StepResult step) override;
  sim::StepResult afterFailure(sim::StepResult step) override;
  void caregiverReset() override;
  // Tidies the furniture and covers one surface with the obstacle book (the header's "Every task").
  void coverOneSurface();

  std::string obstacle_;  // the book that covers a surface
  bool judged_ = false;   // the user has judged this task's wipe; the robot's "Done" ends the task
};

}  // namespace cbtl::domains::cleaning
