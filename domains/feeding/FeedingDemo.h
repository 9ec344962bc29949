// FeedingDemo.h — the paper's real-robot demonstration (its Section 5.3 and Figure 1) in simulation.
//
// A participant has had meals 1-4 in the study (FeedingStudy.h: CBTL learned from their answers, No
// Personalization did not) and then has meal 5 with the robot. The plate starts in front of them. The robot
// serves two bites; then the caregiver puts a drink on the table, also in front of them (a drink was in no
// earlier meal), the robot prepares it and holds it out: requests bite 1, bite 2, prepare, drink 1. Every request
// is solved as the robot acts when it exploits what it has learned (approach::evaluationChoice) and carried out in
// the simulated world, whose user complains ("You're blocking my view!") when a configuration the robot moved to
// reaches their occlusion threshold. CBTL keeps learning from what happens in meal 5, as a deployed robot would;
// its choice at bite 1 rests on meals 1-4 alone. The drink's configuration is judged by the occlusion constraint
// learned from bites (the same generator, a new task).
//
// The reference's real-robot record (5 trials): complaints at (bite 1, bite 2, drink 1) were (1, 0, 0) with CBTL
// and (1, 1, 1) without learning.
#pragma once

#include "domains/feeding/FeedingPlanReading.h"
#include "domains/feeding/FeedingStudy.h"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace cbtl::domains::feeding {

struct DemoOptions {
  int participant = 0;
  int trials = 5;  // trial t uses seed + t (the study's meals 1-4 included)
  std::uint64_t seed = 0;
  // Where the caregiver puts the plate at the start of meal 5 and the drink before the prepare request: in front
  // of the user (their eyes are at y = 0.5), metres on the table.
  double plateX = 0.34, plateY = 0.45;
  double drinkX = 0.32, drinkY = 0.67;
  StudyOptions study;  // solver, text backend (participants and seed are the demo's)
};

// The four requests of meal 5.
inline const std::vector<std::string>& demoRequests() {
  static const std::vector<std::string> names = {"bite 1", "bite 2", "prepare", "drink 1"};
  return names;
}

struct DemoStep {
  std::string request;                                         // demoRequests()
  std::string task;                                            // the .cbtl task solved
  bool solved = false;                                         // solved and carried out to the request's end
  std::vector<double> plateFrom, plateTo, drinkFrom, drinkTo;  // (x, y); To empty when the task does not choose it
  std::string dip, signal, verbosity;
  std::optional<world::ArmConfig> conf;  // the configuration the user's view is judged at (above-plate / drink)
  double occlusion = 0;                  // its occlusion score
  int complaints = 0;                    // "You're blocking my view!" during the request
};

struct DemoTrial {
  std::map<std::string, std::vector<DemoStep>> steps;  // by approach (studyApproaches()), in request order
};

struct DemoResult {
  Meal meal;
  double threshold = 0;  // the participant's occlusion threshold (hidden from the robot)
  std::vector<DemoTrial> trials;
};

// Called before each request is carried out, with the world in the request's start state and the step's
// choices read (for pictures); may change the world only if it restores it.
using DemoObserver =
    std::function<void(int trial, const std::string& approach, const DemoStep& step, FeedingSimulator& world)>;

// Throws std::runtime_error when the options' plate or drink spot is not on meal 5's table (FeedingSimulator::
// placeOnTable), and what runStudyMeal throws.
DemoResult runDemo(const approach::PreparedProgram& lp, const ProgramFacts& facts, const DemoOptions& options,
                   const DemoObserver& observer = {});

// The world state of `step`'s choices: the plate and drink where the robot puts them and the arm at its
// configuration (the arm as it is when the step has none) holding what it holds there (the utensil for a bite, the
// drink for a drink), for pictures and the occlusion score. Leaves `world` unchanged.
world::WorldState demoStepState(FeedingSimulator& world, const DemoStep& step);

}  // namespace cbtl::domains::feeding
