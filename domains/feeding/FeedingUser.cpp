#include "domains/feeding/FeedingUser.h"

#include "runtime/core/Rng.h"

#include <algorithm>

namespace cbtl::domains::feeding {

FeedingUser FeedingUser::paperDefault() {
  FeedingUser u;
  u.occlusionThreshold = 0.05;
  u.dipRanking = {{"french fries", {"ketchup", "ranch"}},
                  {"potato wedges", {"bbqSauce"}},
                  {"tater tots", {"ketchup"}},
                  {"carrot sticks", {"hummus", "ranch"}},
                  {"raw vegetables", {"ranch", "hummus"}}};
  u.readySignal = "button";
  u.verbosity = "brief";
  u.verbosityInSetting = {{"withFriend", "silent"}, {"withFriendAndTv", "silent"}};
  return u;
}

const std::vector<std::string>& FeedingUser::readySignals() {
  static const std::vector<std::string> signals = {"mouthOpen", "button", "autoContinue"};
  return signals;
}

const std::vector<std::string>& FeedingUser::verbosities() {
  static const std::vector<std::string> levels = {"silent", "brief", "chatty"};
  return levels;
}

FeedingUser FeedingUser::participant(std::uint64_t n) {
  // The paper's five foods by kind (fried or baked potato; raw vegetables), the order the taste is drawn in.
  static const std::vector<std::vector<std::string>> kFoodsByKind = {{"french fries", "potato wedges", "tater tots"},
                                                                     {"raw vegetables", "carrot sticks"}};
  static const std::vector<std::string> kSauces = {"ketchup", "bbqSauce", "ranch", "hummus"};
  const std::vector<std::string>& kSignals = readySignals();
  const std::vector<std::string>& kVerbosities = verbosities();
  rt::Rng rng(rt::splitMix64(n ^ 0x66656564696e67ULL));  // "feeding": participants apart from other streams
  FeedingUser u;
  u.occlusionThreshold = rng.uniform(0.02, 0.08);
  const auto drawRanking = [&rng] {
    std::vector<std::string> sauces = kSauces;
    rng.shuffle(sauces.begin(), sauces.end());
    const double r = rng.uniform();
    const std::size_t liked = r < 0.2 ? 0 : r < 0.7 ? 1 : 2;
    return std::vector<std::string>(sauces.begin(), sauces.begin() + static_cast<long>(liked));
  };
  for (const auto& kind : kFoodsByKind) {
    const std::vector<std::string> kindRanking = drawRanking();
    for (const auto& food : kind) {
      std::vector<std::string> own = drawRanking();  // drawn for every food, so the stream does not branch
      u.dipRanking[food] = rng.coin(kOwnDipTaste) ? std::move(own) : kindRanking;
      for (const char* setting : {"withFriend", "withFriendAndTv"})
        if (rng.coin(0.3)) u.dipRankingInSetting[food + "|" + setting] = {};
    }
  }
  u.readySignal = kSignals[rng.index(kSignals.size())];
  for (const char* setting : {"withTv", "withFriendAndTv"})
    if (rng.coin(0.3)) u.readySignalInSetting[setting] = kSignals[rng.index(kSignals.size())];
  u.verbosity = kVerbosities[rng.index(kVerbosities.size())];
  for (const char* setting : {"withFriend", "withFriendAndTv"})
    if (rng.coin(0.4)) u.verbosityInSetting[setting] = kVerbosities[rng.index(kVerbosities.size())];
  return u;
}

namespace {

const std::string& inSetting(const std::map<std::string, std::string>& overrides, const std::string& setting,
                             const std::string& otherwise) {
  auto it = overrides.find(setting);
  return it == overrides.end() ? otherwise : it->second;
}

}  // namespace

std::string FeedingUser::idealDip(const std::string& food, const std::string& setting,
                                  const std::vector<std::string>& onTable) const {
  auto it = dipRankingInSetting.find(food + "|" + setting);
  if (it == dipRankingInSetting.end()) it = dipRanking.find(food);
  if (it == dipRanking.end()) return "noDip";
  for (const auto& dip : it->second) {
    if (std::find(onTable.begin(), onTable.end(), dip) != onTable.end()) return dip;
  }
  return "noDip";
}

std::string FeedingUser::idealSignal(const std::string& setting) const {
  return inSetting(readySignalInSetting, setting, readySignal);
}

std::string FeedingUser::idealVerbosity(const std::string& setting) const {
  return inSetting(verbosityInSetting, setting, verbosity);
}

std::string FeedingUser::perceivedVerbosity(int utterances) {
  if (utterances <= 0) return "silent";
  return utterances == 1 ? "brief" : "chatty";
}

std::string dipEntryOfSauce(const std::string& sauce) {
  static const std::map<std::string, std::string> entries = {
      {"ketchup", "ketchup"}, {"BBQ sauce", "bbqSauce"}, {"ranch dressing", "ranch"}, {"hummus", "hummus"}};
  auto it = entries.find(sauce);
  return it == entries.end() ? std::string() : it->second;
}

std::string foodEntry(const std::string& food) {
  static const std::map<std::string, std::string> entries = {{"french fries", "frenchFries"},
                                                             {"raw vegetables", "rawVegetables"},
                                                             {"potato wedges", "potatoWedges"},
                                                             {"carrot sticks", "carrotSticks"},
                                                             {"tater tots", "taterTots"}};
  auto it = entries.find(food);
  return it == entries.end() ? food : it->second;
}

}  // namespace cbtl::domains::feeding
