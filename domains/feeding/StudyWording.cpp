#include "domains/feeding/StudyWording.h"

namespace cbtl::domains::feeding {

const std::map<std::string, std::string>& studyWords() {
  // The signals are worded as what the participant does, since the question is "how should the robot know you
  // are ready?"; the verbosities as what the participant hears.
  static const std::map<std::string, std::string> words = {
      {"ketchup", "ketchup"},
      {"bbqSauce", "BBQ sauce"},
      {"ranch", "ranch dressing"},
      {"hummus", "hummus"},
      {"noDip", "no dip"},
      {"mouthOpen", "I open my mouth"},
      {"button", "I press a button"},
      {"autoContinue", "no signal: the robot goes on by itself"},
      {"silent", "silent"},
      {"brief", "a few words"},
      {"chatty", "chatty"},
  };
  return words;
}

std::string settingInWords(const std::string& setting) {
  static const std::map<std::string, std::string> words = {
      {"alone", "alone"},
      {"withFriend", "with a friend"},
      {"withTv", "with the TV on"},
      {"withFriendAndTv", "with a friend and the TV on"},
  };
  auto it = words.find(setting);
  return it == words.end() ? setting : it->second;
}

}  // namespace cbtl::domains::feeding
