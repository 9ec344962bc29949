// FeedingUser.h — the hidden user of the Feeding domain: how much arm in their view they tolerate, which
// dip they want with each food, how they like to signal that they are ready, and how much the robot should
// talk. The robot never reads these; it learns them from the feedback events the simulator derives here.
//
// Names are those of domains/feeding/feeding.cbtl: Dip entries (ketchup, bbqSauce, ranch, hummus, noDip),
// ReadySignal members (mouthOpen, button, autoContinue), Verbosity members (silent, brief, chatty), MealSetting
// members (alone, withFriend, withTv, withFriendAndTv).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace cbtl::domains::feeding {

class FeedingUser {
 public:
  // The user of our experiments (documented in docs/domains-feeding.md): complains from an occlusion score
  // of 0.05 (the reference user's threshold), likes ketchup with fries and tater tots, BBQ sauce with potato
  // wedges, hummus with carrot sticks, ranch with raw vegetables, ranch as the second choice with fries and
  // carrots, hummus with raw vegetables; presses the button; wants brief talk, and silence when a friend is there
  // to talk to.
  static FeedingUser paperDefault();
  // Simulated participant `n` of a study (the same n, the same person), with diverse preferences drawn from n
  // alone: an occlusion threshold in [0.02, 0.08]; per kind of food (potato: french fries, potato wedges, tater
  // tots; vegetables: raw vegetables, carrot sticks) a ranking of none, one or two of the four sauces (uniform
  // order; none 0.2, one 0.5, two 0.3), which each food of the kind keeps except with probability kOwnDipTaste,
  // where it has its own ranking drawn the same way; with a friend at the table, for each food with probability
  // 0.3, no dip at all; a ready signal and a verbosity, each replaced in some settings (the TV on: signal,
  // probability 0.3; a friend there: verbosity, probability 0.4) by another drawn one.
  static FeedingUser participant(std::uint64_t n);
  // How often a participant's dip with one food is not the one they take with its kind (see participant()).
  static constexpr double kOwnDipTaste = 0.25;

  double occlusionThreshold = 0.05;                            // view blocked at score >= this, in [0, 1]
  std::map<std::string, std::vector<std::string>> dipRanking;  // food -> Dip entries, best first
  // food|setting -> Dip entries, best first: where the setting changes the dip (e.g. nothing messy with a friend)
  std::map<std::string, std::vector<std::string>> dipRankingInSetting;
  std::string readySignal = "button";                       // ReadySignal member
  std::map<std::string, std::string> readySignalInSetting;  // MealSetting member -> ReadySignal member
  std::string verbosity = "brief";                          // Verbosity member
  std::map<std::string, std::string> verbosityInSetting;    // MealSetting member -> Verbosity member

  // The dip the user wants with `food` in `setting` among those on the table: the best-ranked one there (the
  // setting's ranking for that food if there is one, else the food's), else noDip.
  std::string idealDip(const std::string& food, const std::string& setting,
                       const std::vector<std::string>& onTable) const;
  std::string idealSignal(const std::string& setting) const;
  std::string idealVerbosity(const std::string& setting) const;
  bool viewBlocked(double occlusionScore) const { return occlusionScore >= occlusionThreshold; }
  // The verbosity the user perceived from how many times the robot spoke during one bite.
  static std::string perceivedVerbosity(int utterances);
  // Every ReadySignal member and every Verbosity member, in feeding.cbtl's order.
  static const std::vector<std::string>& readySignals();
  static const std::vector<std::string>& verbosities();
};

// Dip entry of the sauce name a plan passes to dipInto ("ketchup", "BBQ sauce", "ranch dressing", "hummus");
// empty for an unknown name.
std::string dipEntryOfSauce(const std::string& sauce);

// Food entry of one of the paper's foods ("french fries" -> "frenchFries"), the value of the foodOnPlate
// observation and of the feedback's food argument; an unknown food is returned as it is.
std::string foodEntry(const std::string& food);

}  // namespace cbtl::domains::feeding
