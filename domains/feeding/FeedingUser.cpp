#include "domains/feeding/FeedingUser.h"

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

}  // namespace cbtl::domains::feeding
