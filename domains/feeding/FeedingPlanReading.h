// FeedingPlanReading.h — what the study and the demonstration read from a solved Feeding CSP (the choices by
// variable name, feeding.cbtl) and how they carry a plan out in a FeedingSimulator, one request to its end.
#pragma once

#include "domains/feeding/FeedingSimulator.h"
#include "runtime/approach/PreparedProgram.h"

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace cbtl::domains::feeding {

// feeding.cbtl's variable names, as the CSP of a task qualifies them.
inline constexpr const char* kAbovePlateConf = "acquireBite.robotAbovePlateConf";
inline constexpr const char* kDrinkConf = "holdDrinkOut.drinkPostGraspConf";

// The value of the task's variable `name` in `assignment` at the simulator boundary (sim::Value: a vector, a
// name, ...); nullopt when the task has no such variable.
std::optional<sim::Value> readVariable(const approach::PreparedProgram& lp, std::size_t task,
                                       const std::vector<double>& assignment, const std::string& name);
// A Conf<gen3> variable's joint angles; nullopt when the task has none of that name.
std::optional<world::ArmConfig> readConf(const approach::PreparedProgram& lp, std::size_t task,
                                         const std::vector<double>& assignment, const std::string& name);

// The Feeding choices of a solution; empty strings and nullopt for what the task does not choose.
struct PlanChoices {
  std::optional<std::vector<double>> plate, drink;  // platePos, drinkPos (x, y), metres
  std::string dip, signal, verbosity;
  std::optional<world::ArmConfig> abovePlateConf, drinkConf;
};
PlanChoices readPlanChoices(const approach::PreparedProgram& lp, std::size_t task,
                            const std::vector<double>& assignment);

// A plan carried out: every call until the request ends (or the calls run out).
struct PlanRun {
  bool done = false, failed = false;
  std::vector<sim::FeedbackEvent> feedback;
  std::vector<std::pair<std::string, bool>> preferences;
  std::vector<std::pair<std::string, double>> measures;
  int complaints = 0;  // viewBlocked events
};
// Called after every call that gave feedback, with that call's events, while the world is as the user judged it.
using FeedbackHandler = std::function<void(const std::vector<sim::FeedbackEvent>&)>;
// Throws std::runtime_error when the simulator does not know a call (a program that does not fit Feeding).
PlanRun runPlan(FeedingSimulator& world, const std::vector<sim::ActionCall>& calls,
                const FeedbackHandler& onFeedback = {});

}  // namespace cbtl::domains::feeding
