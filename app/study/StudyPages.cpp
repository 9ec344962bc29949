#include "app/study/StudyPages.h"

#include "app/study/StudyRecords.h"
#include "domains/feeding/FeedingUser.h"
#include "domains/feeding/StudyWording.h"

#include <fmt/format.h>

#include <set>

namespace cbtl::app::study {

namespace feeding = domains::feeding;
using nlohmann::json;
using nlohmann::ordered_json;

std::string invalidIdMessage(const std::string& id) {
  return fmt::format("the participant id {} is not 1 to 64 characters of A-Z, a-z, 0-9, '_', '.', '-'", quotedText(id));
}

namespace {

// The length of UTF-8 text as a browser counts it for a field's maxlength: in UTF-16 code units (a character beyond
// U+FFFF, an emoji, counts two). Counting bytes refused answers the page had let through (100 letters of a
// non-Latin script are 200 or 300 bytes). The text is valid UTF-8: it came out of the JSON parser.
std::size_t utf16Length(const std::string& text) {
  std::size_t units = 0;
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if ((byte & 0xC0) != 0x80) units += byte >= 0xF0 ? 2 : 1;  // a lead byte: one code point
  }
  return units;
}

const feeding::MealOffer& offerOf(const feeding::MealPresentation& m, const std::string& approach) {
  return m.offers.at(approach);
}

// One approach's choices as a page shows them (`approach` empty: without naming it) or the records keep them.
ordered_json choicesJson(const feeding::MealOffer& offer, const std::string& approach) {
  ordered_json o;
  if (!approach.empty()) o["approach"] = approach;
  o["solved"] = offer.shown.ok;
  if (offer.shown.ok) {
    o["dip"] = offer.read.dip;
    o["signal"] = offer.read.signal;
    o["verbosity"] = offer.read.verbosity;
  }
  return o;
}

// "french fries with BBQ sauce or ketchup, alone, at a rectangular table": the meal as the report names it.
std::string mealDescription(const feeding::MealPresentation& m) {
  const feeding::Meal& meal = feeding::paperMeals().at(m.meal);
  std::string sauces;
  for (std::size_t i = 0; i < meal.dips.size(); ++i) {
    auto word = feeding::studyWords().find(meal.dips[i]);
    sauces += (i == 0 ? "" : " or ") + (word == feeding::studyWords().end() ? meal.dips[i] : word->second);
  }
  return fmt::format("{} with {}, {}, at a {} table", meal.food, sauces, feeding::settingInWords(meal.setting),
                     meal.table);
}

std::vector<std::string> dipChoices(const feeding::MealPresentation& m) {
  const feeding::Meal& meal = feeding::paperMeals().at(m.meal);
  return feeding::dipChoicesOf(feeding::BiteOffer{meal.food, meal.dips, "", "", ""});
}

// Whether `response` is an object with exactly these keys.
std::optional<std::string> checkKeys(const json& response, const std::set<std::string>& keys) {
  if (!response.is_object()) return "the response must be a JSON object";
  for (const auto& [key, value] : response.items())
    if (!keys.count(key)) return fmt::format("the response has an unknown field '{}'", key);
  for (const auto& key : keys)
    if (!response.contains(key)) return fmt::format("the response lacks the field '{}'", key);
  return std::nullopt;
}

std::optional<std::string> checkDemographics(const json& r) {
  // gender_other may be left out unless the gender is "other" (a client need not send an empty text).
  const bool other = r.is_object() && r.contains("gender") && r["gender"] == "other";
  std::set<std::string> keys = {"age", "gender", "robot_experience", "fed_experience"};
  if (other || (r.is_object() && r.contains("gender_other"))) keys.insert("gender_other");
  if (auto problem = checkKeys(r, keys)) return problem;
  const json& age = r["age"];
  if (!age.is_null() && !(age.is_number_integer() && age.get<std::int64_t>() >= 18 && age.get<std::int64_t>() <= 120))
    return std::string("age must be a whole number from 18 to 120, or null when not said");
  static const std::set<std::string> genders = {"male", "female", "non-binary", "prefer-not-to-say", "other"};
  if (!r["gender"].is_string() || !genders.count(r["gender"].get<std::string>()))
    return std::string("gender must be one of male, female, non-binary, prefer-not-to-say, other");
  if (r.contains("gender_other")) {
    if (!r["gender_other"].is_string() || utf16Length(r["gender_other"].get<std::string>()) > 100)
      return std::string("gender_other must be text of at most 100 characters");
    if (!other && !r["gender_other"].get<std::string>().empty())
      return std::string("gender_other is only for the gender 'other'");
  }
  for (const char* key : {"robot_experience", "fed_experience"})
    if (!r[key].is_boolean()) return fmt::format("{} must be true or false", key);
  return std::nullopt;
}

std::optional<std::string> checkAnswersShape(const json& r) {
  if (auto problem = checkKeys(r, {"dip", "signal", "verbosity", "blocked"})) return problem;
  for (const char* key : {"dip", "signal", "verbosity"})
    if (!r[key].is_string()) return fmt::format("{} must be one of the page's choices, as text", key);
  if (!r["blocked"].is_array()) return std::string("blocked must be a list of true/false, one per picture");
  for (const auto& b : r["blocked"])
    if (!b.is_boolean()) return std::string("blocked must be a list of true/false, one per picture");
  return std::nullopt;
}

}  // namespace

void describeMeal(json& state, const feeding::MealPresentation& m, const StudyPage& page,
                  const std::string& participant) {
  const feeding::Meal& meal = feeding::paperMeals().at(m.meal);
  state["context"] = {{"food", meal.food},
                      {"setting", meal.setting},
                      {"setting_text", feeding::settingInWords(meal.setting)},
                      {"table", meal.table},
                      {"sauces", meal.dips}};
  json options = json::array();
  for (std::size_t i = 0; i < m.options.size(); ++i) {
    json o = choicesJson(offerOf(m, m.options[i]), "");
    o["label"] = i == 0 ? "A" : "B";
    options.push_back(o);
  }
  state["options"] = options;
  state["choices"] = {{"dip", dipChoices(m)},
                      {"signal", feeding::FeedingUser::readySignals()},
                      {"verbosity", feeding::FeedingUser::verbosities()}};
  state["labels"] = feeding::studyWords();
  if (page.kind != "answers") return;
  json views = json::array();
  for (std::size_t k = 0; k < m.views.size(); ++k)
    views.push_back(fmt::format("/api/participants/{}/views/{}/{}.png", participant, page.meal, k));
  state["views"] = views;
}

std::optional<std::string> checkResponse(const std::string& kind, const json& r) {
  if (kind == "consent") {
    if (auto problem = checkKeys(r, {"agree"})) return problem;
    if (r["agree"] != true) return std::string("agree must be true (declining is not recorded)");
    return std::nullopt;
  }
  if (kind == "demographics") return checkDemographics(r);
  if (kind == "rating") {
    if (auto problem = checkKeys(r, {"likert"})) return problem;
    const json& k = r["likert"];
    if (!k.is_number_integer() || k.get<std::int64_t>() < 1 || k.get<std::int64_t>() > 5)
      return std::string("likert must be a whole number from 1 (strongly prefer A) to 5 (strongly prefer B)");
    return std::nullopt;
  }
  if (kind == "answers") return checkAnswersShape(r);
  if (kind == "complete") {
    if (auto problem = checkKeys(r, {"comments"})) return problem;
    if (!r["comments"].is_string() || utf16Length(r["comments"].get<std::string>()) > 2000)
      return std::string("comments must be text of at most 2,000 characters");
    return std::nullopt;
  }
  return fmt::format("no page is of kind '{}'", kind);
}

ordered_json storedRating(const json& response, const feeding::MealPresentation& m) {
  const int likert = response["likert"];
  ordered_json stored;
  stored["likert"] = likert;
  // Option A is the left end of the scale: when A was CBTL, "strongly prefer A" is "strongly prefer CBTL".
  stored["cbtl_preference"] = m.options[0] == feeding::studyApproaches()[0] ? 6 - likert : likert;
  stored["meal_description"] = mealDescription(m);
  ordered_json options = ordered_json::array();
  for (const auto& approach : m.options) options.push_back(choicesJson(offerOf(m, approach), approach));
  stored["options"] = options;
  return stored;
}

ordered_json storedAnswers(const json& response, const feeding::MealPresentation& m) {
  ordered_json stored;
  for (const char* key : {"dip", "signal", "verbosity", "blocked"}) stored[key] = response[key];
  ordered_json predicted, met;
  const feeding::MealOffer& cbtl = offerOf(m, feeding::studyApproaches()[0]);
  // The first picture is of the configuration CBTL's shown choice uses, when it has one (StudySession.h); the view
  // preference is met when that one is not called blocked (the other picture is a question, not a choice).
  const bool firstIsShown = cbtl.shown.ok && cbtl.read.abovePlateConf.has_value();
  const bool shownBlocked = firstIsShown && !response["blocked"].empty() && response["blocked"][0].get<bool>();
  for (const auto& approach : feeding::studyApproaches()) {
    const feeding::MealOffer& offer = offerOf(m, approach);
    predicted[approach] = choicesJson(offer, "");
    ordered_json judged;
    judged["dip"] = offer.shown.ok && offer.read.dip == response["dip"].get<std::string>();
    judged["signal"] = offer.shown.ok && offer.read.signal == response["signal"].get<std::string>();
    judged["verbosity"] = offer.shown.ok && offer.read.verbosity == response["verbosity"].get<std::string>();
    // Only CBTL's configurations were pictured; No Personalization's view was never asked about.
    if (approach == feeding::studyApproaches()[0]) judged["view"] = offer.shown.ok && !shownBlocked;
    met[approach] = judged;
  }
  stored["predicted"] = predicted;
  ordered_json views = ordered_json::array();
  for (std::size_t k = 0; k < m.views.size(); ++k)
    views.push_back({{"occlusion", m.views[k].occlusion}, {"shown_choice", k == 0 && firstIsShown}});
  stored["views"] = views;
  stored["met"] = met;
  return stored;
}

json sentPart(const std::string& kind, const json& stored) {
  if (kind == "rating" && stored.is_object() && stored.contains("likert")) return {{"likert", stored["likert"]}};
  if (kind == "answers" && stored.is_object()) {
    json sent = json::object();
    for (const char* key : {"dip", "signal", "verbosity", "blocked"})
      if (stored.contains(key)) sent[key] = stored[key];
    return sent;
  }
  return stored;
}

feeding::ParticipantAnswers participantAnswersOf(const json& r) {
  feeding::ParticipantAnswers a;
  a.ideals = feeding::BiteIdeals{r.at("dip").get<std::string>(), r.at("signal").get<std::string>(),
                                 r.at("verbosity").get<std::string>()};
  for (const auto& b : r.at("blocked")) a.blocked.push_back(b.get<bool>());
  return a;
}

}  // namespace cbtl::app::study
