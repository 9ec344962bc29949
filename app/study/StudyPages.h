// StudyPages.h — the web study's pages as data (docs/study-api.md; their order is StudySequence.h's): what each
// page's state shows, how each answer is checked, and what is stored of it. Pure functions over
// JSON and a StudySession's MealPresentation: no database, no HTTP, no locks.
#pragma once

#include "app/study/StudySequence.h"
#include "domains/feeding/StudySession.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>

namespace cbtl::app::study {

// "the participant id '...' is not ..." for an id that isParticipantId() refuses.
std::string invalidIdMessage(const std::string& id);

// Adds what a rating or answers page shows of the meal to `state`: context, options (Option A and B, without
// saying which approach is which), choices, labels and, on an answers page, the pictures' URLs.
void describeMeal(nlohmann::json& state, const domains::feeding::MealPresentation& meal, const StudyPage& page,
                  const std::string& participant);

// Why a page's response is not what docs/study-api.md says it must be (naming the field), or nothing. For answers
// this checks the shape only; whether the answers are among the meal's choices is the StudySession's check.
std::optional<std::string> checkResponse(const std::string& kind, const nlohmann::json& response);

// What is stored of a checked rating or answers response: the answer with what the page showed (docs/study-api.md).
nlohmann::ordered_json storedRating(const nlohmann::json& response, const domains::feeding::MealPresentation& meal);
nlohmann::ordered_json storedAnswers(const nlohmann::json& response, const domains::feeding::MealPresentation& meal);

// The part of a stored response the participant sent (for a rating: the likert; for answers: the four answers; for
// the other pages, all of it), to recognize a resent request.
nlohmann::json sentPart(const std::string& kind, const nlohmann::json& stored);

// The answers in a checked or stored answers response.
domains::feeding::ParticipantAnswers participantAnswersOf(const nlohmann::json& response);

}  // namespace cbtl::app::study
