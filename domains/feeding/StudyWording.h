// StudyWording.h — how the web study puts Feeding's names into words for its participants: a Dip entry, a
// ReadySignal or Verbosity member, a MealSetting member ("withFriend" -> "with a friend"). The pages show these
// words; the records keep the names, so the analysis never depends on the wording.
#pragma once

#include <map>
#include <string>

namespace cbtl::domains::feeding {

// Every name the study's questions and options use (Dip entries incl. noDip, ReadySignal and Verbosity members)
// -> the words a participant reads.
const std::map<std::string, std::string>& studyWords();

// A MealSetting member in words ("with a friend and the TV on"); the name itself for an unknown one.
std::string settingInWords(const std::string& setting);

}  // namespace cbtl::domains::feeding
