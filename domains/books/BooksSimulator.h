// BooksSimulator.h — the Books domain behind the runtime's DomainSimulator contract: the home scene (robot
// on its mobile base, nine books, the user sitting in bed) plus BooksUser (hidden book taste and range of
// motion), speaking the names of domains/books/books.cbtl. Scene and Book entries come from the program
// (ProgramFacts: its `world` scene, its `items standardBooks : Book` catalogue, BookCatalog.h).
//
// Episode start (reset(seed), all draws from the simulator's RNG in this order):
//   1. the room of robot/HomeEpisode.h (base at the origin, arm at homeSceneInitial, duster on the main
//      table, books parked outside the room);
//   2. a uniform permutation of the books and one of the nine home.xml book slots (three on the middle
//      shelf layer, three on the top layer, one per side table);
//   3. with probability kHeldProbability the robot holds the permutation's last book (HomeEpisode.h
//      holdCarried: arm at retract, carry grasp) — a book the user could not reach last time — so
//      "stowThenHandOverBook" occurs;
//   4. how many books are on the furniture: uniform in [3, 9] (in [3, 8] when one is held) — the paper's "a
//      random subset of the books are available" — the permutation's first ones, in the shuffled slots.
// After a task ends the world goes on. Whenever no book is left on the furniture after a handover (the user
// took the last one, or the robot still holds it), the caregiver restocks the furniture by steps 2 and 4 with
// the other books (the user has finished reading); a book in the robot's hand stays there.
//
// Observations (books.cbtl): "pickable" (Names: the Book entries resting on one of the seven surfaces, in
// catalogue order),
// "handPose" (Vector SE3: robot/HomeSurfaces.h userHandFrame, whose z points at the scene's
// handover_center), "heldBody" (Name: "" or the body held).
// requestedTask(): "stowThenHandOverBook" while the robot holds anything, otherwise "handOverBook".
//
// Actions: the standard actions (robot/RobotActions.h; one step each, wait(n) n steps); another name or a
// wrong shape is UnknownAction (no step).
//   - handOver() of a held book: feedback handoverOutcome(book, handoverPoint = tool position, reached,
//     said, enjoyed); reached per BooksUser::reaches; enjoyed is the user's taste when reached and false
//     when not (they never got the book; books.cbtl learns `enjoyed if reached`). Satisfaction +1 iff
//     reached and enjoyed, otherwise -1 (an unreachable handover disappoints the user too, as in the
//     reference). Reached: the user takes the book (it is parked outside the room: no longer held, not
//     pickable). Not reached: the robot keeps holding it. The task ends (taskDone) when the robot then says
//     "Done" (the reference's missions complete on "Done"), after it has put its arm back.
//   - handOver() of something that is not a book (the duster): the user refuses it: status Ignored, taskDone,
//     no feedback, no satisfaction.
//   - A failed action (no path, no IK, ...) ends the task as failed: status Ignored, taskDone, no
//     satisfaction, the message says why; the world is as before that action.
// idle(): one step passes, nothing changes; after home::kCaregiverPatience idle steps in a row (the robot found no
// plan) a caregiver resets it (HomeEpisode.h caregiverReset: a held book is taken away; StepResult::caregiverReset).
// Options: none of SimulatorOptions applies (kept only for the evaluation twin).
// Lifetime state (not touched by reset): the user, the catalogue and the scene, shared with evaluation twins.
#pragma once

#include "domains/ProgramFacts.h"
#include "domains/books/BookCatalog.h"
#include "domains/books/BooksUser.h"
#include "robot/actions/RobotSimulator.h"
#include "runtime/sim/SimulatorBase.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace cbtl::domains::books {

inline constexpr double kHeldProbability = 0.25;
inline constexpr const char* kDoneUtterance = "Done";  // what the robot says when it has finished a task
// An evaluation task offers one book the user enjoys among four others (the reference's evaluation: one of the
// enjoyed books and half of the others removed from the nine), so a first handover can satisfy the user.
inline constexpr std::size_t kEvalEnjoyed = 1;
inline constexpr std::size_t kEvalOthers = 4;

// What a training world shares with its evaluation twins.
struct BooksShared {
  std::shared_ptr<const world::Scene> scene;
  BookCatalog catalog;
  BooksUser user;
};

// The step loop, idling and the caregiver are actions::RobotSimulator's; the evaluation twin is sim::SimulatorBase's.
class BooksSimulator final : public sim::SimulatorBase<BooksSimulator, const BooksShared, actions::RobotSimulator> {
 public:
  // The paper's user (BooksUser::paperDefault). Throws std::invalid_argument when `program` names no scene,
  // has no Book catalogue, or a book's body is not a movable object of the scene; std::runtime_error when the
  // scene cannot be loaded.
  BooksSimulator(const ProgramFacts& program, const sim::SimulatorOptions& options, std::uint64_t seed);
  BooksSimulator(const ProgramFacts& program, const sim::SimulatorOptions& options, std::uint64_t seed, BooksUser user);

  void reset(std::uint64_t seed) override;
  sim::Observation observe() const override;
  std::string requestedTask() const override;
  // makeEvaluationTwin(): shares the user; its own world and RNG, reset with seed 0 until the caller resets it. Its
  // tasks are evaluation tasks: the robot holds nothing, and the furniture holds kEvalEnjoyed books the user enjoys
  // and kEvalOthers others (fewer when the catalogue has fewer), in shuffled slots.

  const BooksUser& user() const { return shared().user; }
  const BookCatalog& catalog() const { return shared().catalog; }
  // The Book entries on the furniture now (the "pickable" observation), in catalogue order.
  std::vector<std::string> pickable() const;
  // The user's hand frame (the "handPose" observation).
  const world::Pose3& handFrame() const { return hand_; }

 private:
  friend class sim::SimulatorBase<BooksSimulator, const BooksShared, actions::RobotSimulator>;
  BooksSimulator(std::shared_ptr<const BooksShared> shared, const sim::SimulatorOptions& options, sim::WorldRole role,
                 std::uint64_t seed);

  sim::StepResult afterApplied(const sim::ActionCall& call, const actions::RobotActionResult& result,
                               sim::StepResult step) override;
  sim::StepResult afterFailure(sim::StepResult step) override;
  void caregiverReset() override;
  // Steps 2 and 4 of the episode start on `state` (step 3 too when `mayHold`).
  void stockShelves(world::WorldState& state, bool mayHold);
  // An evaluation task's furniture: kEvalEnjoyed books the user enjoys and kEvalOthers others, in shuffled slots.
  void stockForEvaluation(world::WorldState& state);
  // The caregiver restocks the furniture when no book is left on it (a book the robot holds stays in its hand).
  void restockWhenEmpty();
  sim::StepResult handOver(sim::StepResult r);

  world::Pose3 hand_;
  bool judged_ = false;  // the user has answered this task's handover; the robot's "Done" ends the task
};

}  // namespace cbtl::domains::books
