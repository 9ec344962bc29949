// BiteAnswers.h — what a person's answers after a bite say, as the feedback events feeding.cbtl declares. One
// definition for the simulated user (FeedingSimulator, when a bite is done) and for a study participant who types
// or clicks their answers (the web study), so the two can never teach the learner differently.
//
// The study's three questions name the ideal: which dip (a sauce on the table, or noDip), which ready signal, which
// verbosity. Each answer says `<answer>(leading..., offered, ideal)` and, for every other choice the person neither
// got nor named, `<turnedDown>(leading..., choice)`: naming the ideal among the choices turns the rest down, and
// the ideal is labelled once even when it was the one offered. In order: the dip (leading argument: the food's
// catalogue entry), then the signal, then the verbosity.
#pragma once

#include "robot/world/Pose.h"
#include "runtime/sim/DomainSimulator.h"

#include <optional>
#include <string>
#include <vector>

namespace cbtl::domains::feeding {

// What the robot did in one bite: the dip it took (noDip for none), the ready signal it waited for, and the
// verbosity the person perceived (FeedingUser::perceivedVerbosity).
struct BiteOffer {
  std::string food;                 // a food's name as the meals give it ("french fries")
  std::vector<std::string> sauces;  // the meal's sauces on the table (Dip entries)
  std::string dip, signal, verbosity;
};

// The person's answers: their ideal dip (a sauce on the table or noDip), ready signal and verbosity.
struct BiteIdeals {
  std::string dip, signal, verbosity;
};

// The dips a person can name for the meal: its sauces, then noDip.
std::vector<std::string> dipChoicesOf(const BiteOffer& offer);

// Why the answers cannot be taken (an ideal that is not one of its question's choices, naming the choices), or
// nothing when they can.
std::optional<std::string> checkIdeals(const BiteOffer& offer, const BiteIdeals& ideals);

// "Would the arm at q block your view?" answered: viewBlocked(q) or viewClear(q).
sim::FeedbackEvent viewAnswerEvent(const world::ArmConfig& q, bool blocked);

// The events the answers say, in the order above. The answers must pass checkIdeals (std::invalid_argument
// otherwise); the offer is taken as the robot's record of the bite.
std::vector<sim::FeedbackEvent> biteAnswerEvents(const BiteOffer& offer, const BiteIdeals& ideals);

}  // namespace cbtl::domains::feeding
