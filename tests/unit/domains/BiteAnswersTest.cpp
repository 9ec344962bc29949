// A bite's answers as feedback events (BiteAnswers.h): the same events for the simulated user and for a study
// participant, each choice of each question accounted for exactly once, and answers outside the choices refused.
#include "domains/feeding/BiteAnswers.h"

#include "domains/feeding/FeedingUser.h"

#include <gtest/gtest.h>

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using cbtl::domains::feeding::biteAnswerEvents;
using cbtl::domains::feeding::BiteIdeals;
using cbtl::domains::feeding::BiteOffer;
using cbtl::domains::feeding::checkIdeals;

std::vector<std::string> rendered(const std::vector<cbtl::sim::FeedbackEvent>& events) {
  std::vector<std::string> out;
  for (const auto& e : events) {
    std::string s = e.name + "(";
    for (std::size_t i = 0; i < e.args.size(); ++i) s += (i ? ", " : "") + e.args[i].text;
    out.push_back(s + ")");
  }
  return out;
}

const BiteOffer kFries{"french fries", {"bbqSauce", "ketchup"}, "bbqSauce", "button", "brief"};

}  // namespace

TEST(BiteAnswers, NamingTheIdealTurnsTheOtherChoicesDown) {
  const auto events = rendered(biteAnswerEvents(kFries, BiteIdeals{"ketchup", "mouthOpen", "brief"}));
  const std::string fries = cbtl::domains::feeding::foodEntry("french fries");
  const std::vector<std::string> expected = {
      "dipAnswer(" + fries + ", bbqSauce, ketchup)",
      "dipNotWanted(" + fries + ", noDip)",
      "signalAnswer(button, mouthOpen)",
      "signalNotWanted(autoContinue)",
      "verbosityAnswer(brief, brief)",  // the offered one was the ideal: labelled once, not turned down
      "verbosityNotWanted(silent)",
      "verbosityNotWanted(chatty)",
  };
  EXPECT_EQ(events, expected);
}

TEST(BiteAnswers, EveryChoiceIsAccountedForExactlyOnce) {
  for (const char* ideal : {"bbqSauce", "ketchup", "noDip"}) {
    for (const char* offered : {"bbqSauce", "ketchup", "noDip"}) {
      BiteOffer offer = kFries;
      offer.dip = offered;
      std::map<std::string, int> mentioned;
      for (const auto& e : biteAnswerEvents(offer, BiteIdeals{ideal, "button", "silent"})) {
        if (e.name == "dipAnswer") {
          ++mentioned[e.args[1].text];
          if (e.args[2].text != e.args[1].text) ++mentioned[e.args[2].text];
        }
        if (e.name == "dipNotWanted") ++mentioned[e.args[1].text];
      }
      EXPECT_EQ(mentioned, (std::map<std::string, int>{{"bbqSauce", 1}, {"ketchup", 1}, {"noDip", 1}}))
          << "offered " << offered << ", ideal " << ideal;
    }
  }
}

TEST(BiteAnswers, AnswersOutsideTheChoicesAreRefusedWithTheChoicesNamed) {
  const auto problem = checkIdeals(kFries, BiteIdeals{"ranch", "button", "brief"});
  ASSERT_TRUE(problem.has_value());
  EXPECT_EQ(*problem, "the ideal dip 'ranch' is not one of this meal's choices (bbqSauce, ketchup, noDip)");
  EXPECT_EQ(checkIdeals(kFries, BiteIdeals{"noDip", "wave", "brief"}).value_or(""),
            "the ideal ready signal 'wave' is not one of mouthOpen, button, autoContinue");
  EXPECT_EQ(checkIdeals(kFries, BiteIdeals{"noDip", "button", "loud"}).value_or(""),
            "the ideal verbosity 'loud' is not one of silent, brief, chatty");
  EXPECT_FALSE(checkIdeals(kFries, BiteIdeals{"noDip", "autoContinue", "chatty"}).has_value());
  EXPECT_THROW(biteAnswerEvents(kFries, BiteIdeals{"ranch", "button", "brief"}), std::invalid_argument);
}
