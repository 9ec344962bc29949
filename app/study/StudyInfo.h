// StudyInfo.h — what the people running a study tell its participants: the study's title, who runs it, how to reach
// them, the ethics approval, and the consent text, from a JSON file (`cbtl study serve --study-info FILE`):
//
//   {"title": "Robot-assisted feeding preferences", "researcher": "Dr. A. Researcher", "institution": "...",
//    "contact": "feeding-study@example.org", "ethics_approval": "IRB-2026-123",
//    "consent": ["First paragraph of the consent text.", "Second paragraph."]}
//
// Every field is optional; without a file (or a field) the consent page shows the built-in text and no contact.
// The page shows the texts as text (never as HTML). Limits keep a mistaken file from filling the page: each text
// at most 2,000 characters, at most 20 consent paragraphs; an unknown field is refused (a typo would otherwise be
// silently missing from every participant's page).
#pragma once

#include <nlohmann/json.hpp>

#include <stdexcept>
#include <string>

namespace cbtl::app::study {

struct StudyInfoError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Reads and checks the file; the result is what the participants' state carries as "study". Throws StudyInfoError
// naming the file and the field.
nlohmann::json readStudyInfo(const std::string& path);

// Checks a study-info document (`source` names it in messages); returns it unchanged. Throws StudyInfoError.
nlohmann::json checkStudyInfo(const nlohmann::json& info, const std::string& source);

}  // namespace cbtl::app::study
