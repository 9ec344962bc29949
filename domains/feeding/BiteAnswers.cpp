#include "domains/feeding/BiteAnswers.h"

#include "domains/feeding/FeedingUser.h"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace cbtl::domains::feeding {

namespace {

bool contains(const std::vector<std::string>& choices, const std::string& value) {
  return std::find(choices.begin(), choices.end(), value) != choices.end();
}

std::string listed(const std::vector<std::string>& choices) {
  std::string out;
  for (const auto& c : choices) out += (out.empty() ? "" : ", ") + c;
  return out;
}

void answerAmong(std::vector<sim::FeedbackEvent>& out, const std::vector<sim::Value>& leading, const char* answer,
                 const char* turnedDown, const std::vector<std::string>& choices, const std::string& offered,
                 const std::string& ideal) {
  std::vector<sim::Value> args = leading;
  args.push_back(sim::Value::name(offered));
  args.push_back(sim::Value::name(ideal));
  out.push_back({answer, std::move(args)});
  for (const auto& choice : choices) {
    if (choice == offered || choice == ideal) continue;
    std::vector<sim::Value> other = leading;
    other.push_back(sim::Value::name(choice));
    out.push_back({turnedDown, std::move(other)});
  }
}

}  // namespace

std::vector<std::string> dipChoicesOf(const BiteOffer& offer) {
  std::vector<std::string> choices = offer.sauces;
  choices.push_back("noDip");
  return choices;
}

std::optional<std::string> checkIdeals(const BiteOffer& offer, const BiteIdeals& ideals) {
  const std::vector<std::string> dips = dipChoicesOf(offer);
  if (!contains(dips, ideals.dip))
    return fmt::format("the ideal dip '{}' is not one of this meal's choices ({})", ideals.dip, listed(dips));
  if (!contains(FeedingUser::readySignals(), ideals.signal))
    return fmt::format("the ideal ready signal '{}' is not one of {}", ideals.signal,
                       listed(FeedingUser::readySignals()));
  if (!contains(FeedingUser::verbosities(), ideals.verbosity))
    return fmt::format("the ideal verbosity '{}' is not one of {}", ideals.verbosity,
                       listed(FeedingUser::verbosities()));
  return std::nullopt;
}

sim::FeedbackEvent viewAnswerEvent(const world::ArmConfig& q, bool blocked) {
  return sim::FeedbackEvent{blocked ? "viewBlocked" : "viewClear",
                            {sim::Value::vec(std::vector<double>(q.begin(), q.end()))}};
}

std::vector<sim::FeedbackEvent> biteAnswerEvents(const BiteOffer& offer, const BiteIdeals& ideals) {
  if (auto problem = checkIdeals(offer, ideals)) throw std::invalid_argument(*problem);
  std::vector<sim::FeedbackEvent> events;
  answerAmong(events, {sim::Value::name(foodEntry(offer.food))}, "dipAnswer", "dipNotWanted", dipChoicesOf(offer),
              offer.dip, ideals.dip);
  answerAmong(events, {}, "signalAnswer", "signalNotWanted", FeedingUser::readySignals(), offer.signal, ideals.signal);
  answerAmong(events, {}, "verbosityAnswer", "verbosityNotWanted", FeedingUser::verbosities(), offer.verbosity,
              ideals.verbosity);
  return events;
}

}  // namespace cbtl::domains::feeding
