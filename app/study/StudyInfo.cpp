#include "app/study/StudyInfo.h"

#include "support/InputFile.h"

#include <fmt/format.h>

#include <array>
#include <fstream>
#include <sstream>

namespace cbtl::app::study {
namespace {

constexpr std::size_t kMaxText = 2000, kMaxParagraphs = 20;
constexpr std::array<const char*, 5> kTextFields = {"title", "researcher", "institution", "contact", "ethics_approval"};

void checkText(const nlohmann::json& value, const std::string& where) {
  if (!value.is_string()) throw StudyInfoError(fmt::format("{} must be a text", where));
  if (value.get<std::string>().size() > kMaxText)
    throw StudyInfoError(fmt::format("{} is longer than {} characters", where, kMaxText));
}

}  // namespace

nlohmann::json checkStudyInfo(const nlohmann::json& info, const std::string& source) {
  if (!info.is_object()) throw StudyInfoError(fmt::format("{}: a study-info file is one JSON object", source));
  for (const auto& [key, value] : info.items()) {
    const std::string where = fmt::format("{}: \"{}\"", source, key);
    if (key == "consent") {
      if (!value.is_array() || value.empty() || value.size() > kMaxParagraphs)
        throw StudyInfoError(fmt::format("{} must be a list of 1 to {} paragraphs (texts)", where, kMaxParagraphs));
      for (std::size_t i = 0; i < value.size(); ++i) checkText(value[i], fmt::format("{} paragraph {}", where, i + 1));
      continue;
    }
    bool known = false;
    for (const char* field : kTextFields) known = known || key == field;
    if (!known)
      throw StudyInfoError(fmt::format(
          "{}: unknown field \"{}\" (the fields are title, researcher, institution, contact, ethics_approval, "
          "consent)",
          source, key));
    checkText(value, where);
  }
  return info;
}

nlohmann::json readStudyInfo(const std::string& path) {
  std::string text;
  try {
    text = support::readInputFile(path, support::kMaxDataBytes, "study-info file");
  } catch (const support::InputFileError& e) {
    throw StudyInfoError(e.kind == support::InputFileError::Kind::CannotOpen
                             ? fmt::format("cannot read the study-info file '{}'", path)
                             : std::string(e.what()));
  }
  const nlohmann::json info = nlohmann::json::parse(text, nullptr, false);
  if (info.is_discarded()) throw StudyInfoError(fmt::format("{}: not JSON", path));
  return checkStudyInfo(info, path);
}

}  // namespace cbtl::app::study
