// StudyAnalysis.cpp — the study's analysis (see StudyAnalysis.h): each participant's records are first checked and
// read into what they answered (ParticipantPages), then those are summed up per meal, per question and per kind.
#include "app/study/StudyAnalysis.h"

#include "app/study/StudySequence.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <set>
#include <sstream>
#include <tuple>

namespace cbtl::app::study {

using json = nlohmann::json;

const std::vector<std::string>& studyApproaches() {
  static const std::vector<std::string> approaches{"cbtl", "no-personalization"};
  return approaches;
}

const std::vector<std::string>& studyQuestions() {
  static const std::vector<std::string> questions{"dip", "signal", "verbosity"};
  return questions;
}

const std::vector<std::string>& studyGenders() {
  static const std::vector<std::string> genders{"male", "female", "non-binary", "prefer-not-to-say", "other"};
  return genders;
}

const std::vector<std::string>& studyRecordKinds() {
  static const std::vector<std::string> kinds{"consent", "demographics", "rating", "answers", "complete"};
  return kinds;
}

std::optional<double> Share::share() const {
  if (total == 0) return std::nullopt;
  return static_cast<double>(hits) / static_cast<double>(total);
}

namespace {

constexpr double kNeutralPreference = 3;  // "no preference" on the 1..5 scale
constexpr int kAgeMin = 18, kAgeMax = 120;
constexpr std::int64_t kLastTrial = kStudyPages - 1;  // the `complete` page
constexpr const char* kPathSeparator = " > ";

// ---- Checking and reading one participant's records ----

std::string shown(const json& value) {
  constexpr std::size_t kShown = 60;
  const std::string text = value.dump(-1, ' ', false, json::error_handler_t::replace);
  return text.size() > kShown ? text.substr(0, kShown) + "..." : text;
}

// The page at each trial index, as docs/study-api.md fixes it.
// The page a stored record at `trial` must be (StudySequence.h); none past the `complete` page.
std::optional<StudyPage> expectedPage(std::int64_t trial) {
  if (trial < 0 || trial > kLastTrial) return std::nullopt;
  return pageOfTrial(trial);
}

// One record's response, parsed, with typed access by dotted path ("predicted.cbtl.dip") that throws a StudyError
// naming the participant, the trial and the field.
class Response {
 public:
  explicit Response(const StoredRecord& record) : record_(record) {
    try {
      root_ = json::parse(record.response);
    } catch (const json::exception&) {
      fail("the response is not JSON: " + quotedText(record.response));
    }
    if (!root_.is_object()) fail("the response " + shown(root_) + " is not a JSON object");
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw StudyError(fmt::format("participant {}, trial {} ({}, meal {}): {}", quotedText(record_.participant),
                                 record_.trialIndex, record_.kind, record_.meal, what));
  }

  bool has(const std::string& path) const { return find(path) != nullptr; }

  const json& at(const std::string& path) const {
    const json* value = find(path);
    if (!value) fail("the response has no " + path);
    return *value;
  }

  bool boolean(const std::string& path) const {
    const json& value = at(path);
    if (!value.is_boolean()) fail(fmt::format("{} is {}, not true or false", path, shown(value)));
    return value.get<bool>();
  }

  int integer(const std::string& path, int lo, int hi) const {
    const json& value = at(path);
    if (!value.is_number_integer() || value.get<std::int64_t>() < lo || value.get<std::int64_t>() > hi)
      fail(fmt::format("{} is {}, not an integer {}..{}", path, shown(value), lo, hi));
    return value.get<int>();
  }

  std::string text(const std::string& path) const {
    const json& value = at(path);
    if (!value.is_string() || value.get<std::string>().empty())
      fail(fmt::format("{} is {}, not a non-empty string", path, shown(value)));
    return value.get<std::string>();
  }

 private:
  // nullptr when a step of the path is missing; a step through a non-object is an error, not a missing field.
  const json* find(const std::string& path) const {
    const json* node = &root_;
    std::size_t start = 0;
    while (true) {
      const std::size_t dot = path.find('.', start);
      const std::string key = path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
      if (!node->is_object()) fail(fmt::format("{} is {}, not a JSON object", path.substr(0, start - 1), shown(*node)));
      const auto it = node->find(key);
      if (it == node->end()) return nullptr;
      node = &*it;
      if (dot == std::string::npos) return node;
      start = dot + 1;
    }
  }

  const StoredRecord& record_;
  json root_;
};

struct DemographicsAnswer {
  std::optional<int> age;
  std::string gender;
  bool robotExperience = false, fedExperience = false;
};

struct MealAnswers {
  std::map<std::string, std::string> answer;                          // [question]
  std::vector<bool> blocked;                                          // per picture
  std::map<std::string, std::map<std::string, bool>> predictedRight;  // [approach][question]
  std::map<std::string, std::map<std::string, bool>> met;             // [approach][question or "view"]
};

// What one participant answered, checked.
struct ParticipantPages {
  std::string id;
  bool completed = false;
  bool consented = false;
  std::optional<DemographicsAnswer> demographics;
  std::array<std::optional<int>, kMeals> cbtlPreference;
  std::array<std::string, kMeals> mealDescription;  // as the rating record gives it; empty when it gives none
  std::array<std::optional<MealAnswers>, kMeals> answers;
  std::optional<std::int64_t> completeElapsedMs;
};

void readConsent(const Response& r, ParticipantPages& pages) {
  if (!r.boolean("agree")) r.fail("agree is false, but declining records nothing");
  pages.consented = true;
}

void readDemographics(const Response& r, ParticipantPages& pages) {
  DemographicsAnswer d;
  if (!r.at("age").is_null()) d.age = r.integer("age", kAgeMin, kAgeMax);
  d.gender = r.text("gender");
  const auto& genders = studyGenders();
  if (std::find(genders.begin(), genders.end(), d.gender) == genders.end())
    r.fail(fmt::format("gender is {}, not one of male, female, non-binary, prefer-not-to-say, other",
                       quotedText(d.gender)));
  d.robotExperience = r.boolean("robot_experience");
  d.fedExperience = r.boolean("fed_experience");
  pages.demographics = d;
}

// The stored cbtl_preference must be the likert answer turned toward CBTL, which depends on which option CBTL was.
void readRating(const Response& r, int meal, ParticipantPages& pages) {
  const int likert = r.integer("likert", 1, 5);
  const int preference = r.integer("cbtl_preference", 1, 5);
  const json& options = r.at("options");
  if (!options.is_array() || options.size() != 2) r.fail("options is not an array of the two options shown");
  std::array<std::string, 2> approach;
  for (std::size_t i = 0; i < 2; ++i) {
    const json& option = options[i];
    if (!option.is_object() || !option.contains("approach") || !option["approach"].is_string())
      r.fail(fmt::format("option {} is {}, not an object with an approach", i == 0 ? "A" : "B", shown(option)));
    approach[i] = option["approach"].get<std::string>();
  }
  if (std::set<std::string>{approach[0], approach[1]} != std::set<std::string>{"cbtl", "no-personalization"})
    r.fail(fmt::format("the options' approaches are {} and {}, not cbtl and no-personalization",
                       quotedText(approach[0]), quotedText(approach[1])));
  const int expected = approach[1] == "cbtl" ? likert : 6 - likert;
  if (preference != expected)
    r.fail(fmt::format("cbtl_preference is {}, but likert {} with CBTL as option {} means {}", preference, likert,
                       approach[1] == "cbtl" ? "B" : "A", expected));
  pages.cbtlPreference[static_cast<std::size_t>(meal - 1)] = preference;
  if (r.has("meal_description")) pages.mealDescription[static_cast<std::size_t>(meal - 1)] = r.text("meal_description");
}

void readAnswers(const Response& r, int meal, ParticipantPages& pages) {
  MealAnswers a;
  for (const auto& q : studyQuestions()) a.answer[q] = r.text(q);
  const json& blocked = r.at("blocked");
  if (!blocked.is_array()) r.fail(fmt::format("blocked is {}, not an array", shown(blocked)));
  for (const json& b : blocked) {
    if (!b.is_boolean()) r.fail(fmt::format("blocked is {}, not an array of true or false", shown(blocked)));
    a.blocked.push_back(b.get<bool>());
  }
  for (const auto& approach : studyApproaches()) {
    const std::string offer = "predicted." + approach;
    const bool solved = r.boolean(offer + ".solved");
    for (const auto& q : studyQuestions()) {
      a.predictedRight[approach][q] = solved && r.text(offer + "." + q) == a.answer[q];
      a.met[approach][q] = r.boolean("met." + approach + "." + q);
    }
    if (r.has("met." + approach + ".view")) a.met[approach]["view"] = r.boolean("met." + approach + ".view");
  }
  pages.answers[static_cast<std::size_t>(meal - 1)] = std::move(a);
}

void readRecord(const StoredRecord& record, ParticipantPages& pages) {
  const Response r(record);
  const std::optional<StudyPage> page = expectedPage(record.trialIndex);
  if (!page) r.fail(fmt::format("no page has trial index {} (the last is {})", record.trialIndex, kLastTrial));
  if (record.kind != page->kind || record.meal != page->meal)
    r.fail(fmt::format("expected the {} page{}", page->kind,
                       page->meal == 0 ? std::string() : fmt::format(" of meal {}", page->meal)));
  if (record.rtMs < 0 || record.elapsedMs < 0)
    r.fail(fmt::format("a negative time: elapsed_ms {}, rt_ms {}", record.elapsedMs, record.rtMs));
  if (record.kind == "consent") readConsent(r, pages);
  if (record.kind == "demographics") readDemographics(r, pages);
  if (record.kind == "rating") readRating(r, record.meal, pages);
  if (record.kind == "answers") readAnswers(r, record.meal, pages);
  if (record.kind == "complete") pages.completeElapsedMs = record.elapsedMs;
}

// Every participant's pages, by participant creation; throws for a record of an unknown participant or a gap.
std::vector<ParticipantPages> readParticipants(const std::vector<Participant>& participants,
                                               const std::vector<StoredRecord>& records) {
  std::map<std::string, std::size_t> index;
  std::vector<ParticipantPages> pages(participants.size());
  std::vector<std::vector<const StoredRecord*>> recordsOf(participants.size());
  for (std::size_t i = 0; i < participants.size(); ++i) {
    index[participants[i].id] = i;
    pages[i].id = participants[i].id;
    pages[i].completed = participants[i].completed.has_value();
  }
  for (const auto& record : records) {
    const auto it = index.find(record.participant);
    if (it == index.end())
      throw StudyError(fmt::format("participant {}, trial {}: a record of no known participant",
                                   quotedText(record.participant), record.trialIndex));
    recordsOf[it->second].push_back(&record);
  }
  for (std::size_t i = 0; i < participants.size(); ++i) {
    auto& own = recordsOf[i];
    std::sort(own.begin(), own.end(), [](auto* a, auto* b) { return a->trialIndex < b->trialIndex; });
    for (std::size_t k = 0; k < own.size(); ++k) {
      const auto expected = static_cast<std::int64_t>(k);
      if (own[k]->trialIndex > expected)
        throw StudyError(fmt::format("participant {}, trial {}: no record of trial {} before it",
                                     quotedText(pages[i].id), own[k]->trialIndex, expected));
      if (own[k]->trialIndex < expected)
        throw StudyError(fmt::format("participant {}, trial {}: a second record of it", quotedText(pages[i].id),
                                     own[k]->trialIndex));
      readRecord(*own[k], pages[i]);
    }
  }
  return pages;
}

// ---- Summing up ----

std::optional<double> mean(const std::vector<double>& x) {
  if (x.empty()) return std::nullopt;
  return std::accumulate(x.begin(), x.end(), 0.0) / static_cast<double>(x.size());
}

std::optional<double> sampleSd(const std::vector<double>& x) {
  if (x.size() < 2) return std::nullopt;
  const double m = *mean(x);
  double squares = 0;
  for (double v : x) squares += (v - m) * (v - m);
  return std::sqrt(squares / static_cast<double>(x.size() - 1));
}

// Linear interpolation between order statistics at (n - 1) p (numpy's default).
std::optional<double> percentile(std::vector<double> x, double p) {
  if (x.empty()) return std::nullopt;
  std::sort(x.begin(), x.end());
  const double position = static_cast<double>(x.size() - 1) * p;
  const auto below = static_cast<std::size_t>(std::floor(position));
  const std::size_t above = std::min(below + 1, x.size() - 1);
  return x[below] + (position - static_cast<double>(below)) * (x[above] - x[below]);
}

TimeSummary timeSummary(const std::string& measure, const std::vector<double>& ms) {
  return {measure, ms.size(), percentile(ms, 0.5), percentile(ms, 0.9)};
}

void count(Share& share, bool hit) {
  ++share.total;
  if (hit) ++share.hits;
}

void sumParticipants(const std::vector<ParticipantPages>& pages, StudyAnalysis& out) {
  out.participants.begun = pages.size();
  Demographics& d = out.demographics;
  for (const auto& g : studyGenders()) d.genders[g] = 0;
  std::vector<double> ages;
  for (const auto& p : pages) {
    if (p.consented) ++out.participants.consented;
    if (p.completed) ++out.participants.completed;
    if (!p.demographics) continue;
    ++d.answered;
    if (p.demographics->age) {
      ages.push_back(*p.demographics->age);
      d.ageMin = std::min(d.ageMin.value_or(*p.demographics->age), *p.demographics->age);
      d.ageMax = std::max(d.ageMax.value_or(*p.demographics->age), *p.demographics->age);
    }
    ++d.genders[p.demographics->gender];
    count(d.robotExperience, p.demographics->robotExperience);
    count(d.fedExperience, p.demographics->fedExperience);
  }
  d.agesGiven = ages.size();
  d.ageMean = mean(ages);
}

MealRatings sumRatings(const std::vector<ParticipantPages>& pages, int meal) {
  MealRatings r;
  r.meal = meal;
  for (const auto& p : pages)
    if (const auto& v = p.cbtlPreference[static_cast<std::size_t>(meal - 1)]) r.cbtlPreferences.push_back(*v);
  r.mean = mean(r.cbtlPreferences);
  r.sd = sampleSd(r.cbtlPreferences);
  r.test = signedRank(r.cbtlPreferences, kNeutralPreference);
  return r;
}

MealAccuracy sumAccuracy(const std::vector<ParticipantPages>& pages, int meal) {
  MealAccuracy acc;
  acc.meal = meal;
  // Every cell exists, so that tables and CSV rows do not depend on which fields the records happened to have.
  for (const auto& approach : studyApproaches()) {
    for (const auto& q : studyQuestions()) {
      acc.predicted[approach][q] = Share{};
      acc.met[approach][q] = Share{};
    }
    acc.met[approach]["view"] = Share{};
  }
  for (const auto& p : pages) {
    const auto& a = p.answers[static_cast<std::size_t>(meal - 1)];
    if (!a) continue;
    ++acc.answers;
    for (const auto& [approach, right] : a->predictedRight)
      for (const auto& [q, hit] : right) count(acc.predicted[approach][q], hit);
    for (const auto& [approach, met] : a->met)
      for (const auto& [q, hit] : met) count(acc.met[approach][q], hit);
    for (bool blocked : a->blocked) count(acc.notBlocked, !blocked);
  }
  return acc;
}

Sankey sumSankey(const std::vector<ParticipantPages>& pages, const std::string& question) {
  Sankey s;
  s.question = question;
  std::map<std::string, SankeyPath> distinct;
  std::map<std::tuple<int, std::string, std::string>, std::size_t> flows;
  for (const auto& p : pages) {
    const bool answeredAll =
        std::all_of(p.answers.begin(), p.answers.end(), [](const auto& a) { return a.has_value(); });
    if (!answeredAll) continue;
    SankeyPath path;
    for (const auto& a : p.answers) path.answers.push_back(a->answer.at(question));
    for (std::size_t k = 0; k < path.answers.size(); ++k) path.text += (k == 0 ? "" : kPathSeparator) + path.answers[k];
    path.count = 1;
    for (std::size_t k = 0; k + 1 < path.answers.size(); ++k)
      ++flows[{static_cast<int>(k) + 1, path.answers[k], path.answers[k + 1]}];
    auto [it, added] = distinct.try_emplace(path.text, path);
    if (!added) ++it->second.count;
    s.participants.emplace_back(p.id, std::move(path));
  }
  for (auto& [text, path] : distinct) s.paths.push_back(std::move(path));
  std::stable_sort(s.paths.begin(), s.paths.end(), [](const auto& a, const auto& b) { return a.count > b.count; });
  for (const auto& [key, n] : flows) s.flows.push_back({std::get<0>(key), std::get<1>(key), std::get<2>(key), n});
  return s;
}

void sumTimes(const std::vector<ParticipantPages>& pages, const std::vector<StoredRecord>& records,
              StudyAnalysis& out) {
  for (const auto& kind : studyRecordKinds()) {
    std::vector<double> ms;
    for (const auto& r : records)
      if (r.kind == kind) ms.push_back(static_cast<double>(r.rtMs));
    out.rtByKind.push_back(timeSummary(kind, ms));
  }
  std::vector<double> total;
  for (const auto& p : pages)
    if (p.completed && p.completeElapsedMs) total.push_back(static_cast<double>(*p.completeElapsedMs));
  out.totalDuration = timeSummary("total", total);
}

}  // namespace

StudyAnalysis analyzeStudy(const std::vector<Participant>& participants, const std::vector<StoredRecord>& records) {
  const std::vector<ParticipantPages> pages = readParticipants(participants, records);
  StudyAnalysis out;
  sumParticipants(pages, out);
  for (int meal = 1; meal <= kMeals; ++meal) {
    std::string description;
    for (const auto& p : pages)
      if (description.empty()) description = p.mealDescription[static_cast<std::size_t>(meal - 1)];
    out.mealDescriptions.push_back(description);
    out.ratings.push_back(sumRatings(pages, meal));
    out.accuracy.push_back(sumAccuracy(pages, meal));
  }
  for (const auto& q : studyQuestions()) out.sankeys.push_back(sumSankey(pages, q));
  sumTimes(pages, records, out);
  return out;
}

StudyAnalysis analyzeStudy(const StudyRecords& study) {
  const std::vector<Participant> participants = study.participants();
  std::vector<StoredRecord> records;
  for (const auto& p : participants) {
    auto own = study.records(p.id);
    records.insert(records.end(), std::make_move_iterator(own.begin()), std::make_move_iterator(own.end()));
  }
  try {
    return analyzeStudy(participants, records);
  } catch (const StudyError& e) {
    throw StudyError(study.path() + ": " + e.what());
  }
}

}  // namespace cbtl::app::study
