// StudyAnalysis.h — the paper's analysis of the web study (`cbtl study analyze`), rebuilt from the records that
// `cbtl study serve` stored (StudyRecords.h; the record kinds and their JSON responses are docs/study-api.md's
// "Requests and what is stored"), and its renderings as a text report and CSV files.
//
// What is computed, from the records alone:
// - participants: begun (every participant), consented (a `consent` record), completed (Participant::completed);
//   the demographics as the paper's appendix reports them (age over those who gave one; every gender option, 0 when
//   nobody chose it; the two prior experiences as yes / no).
// - per meal 1..kMeals (the paper's Figure 4c): the `rating` records' cbtl_preference (1 strongly prefers No
//   Personalization .. 5 strongly prefers CBTL): n, mean, sample standard deviation (n - 1), and the one-sample
//   Wilcoxon signed-rank test against neutral, signedRank(values, 3) (SignedRank.h).
// - per meal (Figure 4d), over its `answers` records: per approach ("cbtl", "no-personalization") and question (dip,
//   signal, verbosity), how often what the approach offered before the answers (predicted.<approach>) equals the
//   answer, an unsolved offer counting as wrong; how often met.<approach>.<q> is true (q also "view", counted over
//   the records that have it); and how many pictures were answered not blocked.
// - Sankey data (Figure 6) per question: over the participants who answered all kMeals meals, each one's path (their
//   answers to meals 1..kMeals), the distinct paths with their counts (most frequent first, ties by path text), and
//   the flows meal k answer -> meal k + 1 answer with their counts (by meal, then answers as text).
// - time (the paper did not record it): per record kind, the median and 90th percentile of rt_ms, and over the
//   completed participants with a `complete` record, the median and 90th percentile of its elapsed_ms (the study's
//   whole duration). Percentiles interpolate linearly between order statistics (numpy's default: the p-quantile of
//   sorted x[0..n-1] is at position (n - 1) p). Milliseconds, as the browser measured them.
// Incomplete participants count for every page they answered.
//
// Checked, as docs/study-api.md says: each participant's pages come in the fixed sequence (trial 0 consent, 1
// demographics, 2 + 2(m - 1) rating and 3 + 2(m - 1) answers of meal m, 12 complete), every field the analysis
// reads is there with its type and range, and a rating's cbtl_preference is its likert answer seen from CBTL's side.
// Fields the analysis does not read are not checked. Anything else throws StudyError naming the participant, the
// trial index and what is wrong; analyzing a StudyRecords prefixes its path.
#pragma once

#include "app/study/SignedRank.h"
#include "app/study/StudyRecords.h"

#include <cstddef>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace cbtl::app::study {

// The approaches and the answers' questions, in the order reports list them.
const std::vector<std::string>& studyApproaches();   // "cbtl", "no-personalization"
const std::vector<std::string>& studyQuestions();    // "dip", "signal", "verbosity"
const std::vector<std::string>& studyGenders();      // the paper's options, as the demographics page stores them
const std::vector<std::string>& studyRecordKinds();  // consent, demographics, rating, answers, complete

// `hits` of `total` cases; the share hits / total exists when total > 0.
struct Share {
  std::size_t hits = 0, total = 0;
  std::optional<double> share() const;
};

struct ParticipantCounts {
  std::size_t begun = 0, consented = 0, completed = 0;
};

struct Demographics {
  std::size_t answered = 0;  // `demographics` records
  std::size_t agesGiven = 0;
  std::optional<int> ageMin, ageMax;  // years, over those who gave their age
  std::optional<double> ageMean;
  std::map<std::string, std::size_t> genders;  // every option of studyGenders()
  Share robotExperience, fedExperience;        // hits: answered yes; total: answered
};

struct MealRatings {
  int meal = 0;
  std::vector<double> cbtlPreferences;  // 1..5, by participant creation
  std::optional<double> mean;           // when n >= 1
  std::optional<double> sd;             // sample (n - 1), when n >= 2
  SignedRankResult test;                // signedRank(cbtlPreferences, 3)
  std::size_t n() const { return cbtlPreferences.size(); }
};

struct MealAccuracy {
  int meal = 0;
  std::size_t answers = 0;                                        // `answers` records of the meal
  std::map<std::string, std::map<std::string, Share>> predicted;  // [approach][question]: offer == answer
  std::map<std::string, std::map<std::string, Share>> met;        // [approach][question or "view"]: met.* true
  Share notBlocked;                                               // pictures answered "would not block my view"
};

struct SankeyPath {
  std::vector<std::string> answers;  // meals 1..kMeals
  std::string text;                  // the answers joined by " > "
  std::size_t count = 0;
};

struct SankeyFlow {
  int mealFrom = 0;  // the flow goes to mealFrom + 1
  std::string answerFrom, answerTo;
  std::size_t count = 0;
};

struct Sankey {
  std::string question;
  std::vector<std::pair<std::string, SankeyPath>> participants;  // (id, path with count 1), by participant creation
  std::vector<SankeyPath> paths;                                 // distinct: most frequent first, ties by text
  std::vector<SankeyFlow> flows;                                 // by mealFrom, answerFrom, answerTo
};

struct TimeSummary {
  std::string measure;  // a record kind, or "total" for the study's whole duration
  std::size_t n = 0;
  std::optional<double> medianMs, p90Ms;  // when n >= 1
};

struct StudyAnalysis {
  ParticipantCounts participants;
  std::vector<std::string> mealDescriptions;  // meals 1..kMeals: the first rating record's meal_description, or ""
  Demographics demographics;
  std::vector<MealRatings> ratings;    // meals 1..kMeals
  std::vector<MealAccuracy> accuracy;  // meals 1..kMeals
  std::vector<Sankey> sankeys;         // one per studyQuestions()
  std::vector<TimeSummary> rtByKind;   // one per studyRecordKinds()
  TimeSummary totalDuration;           // elapsed_ms of completed participants' `complete` records
};

// `records` in any order; every record's participant must be one of `participants`.
StudyAnalysis analyzeStudy(const std::vector<Participant>& participants, const std::vector<StoredRecord>& records);
StudyAnalysis analyzeStudy(const StudyRecords& study);

// The human-readable report: participants, demographics, the per-meal ratings and accuracy tables, the Sankey paths,
// the times.
void printStudyAnalysis(const StudyAnalysis& analysis, std::ostream& out);

// The CSV files (name, content): ratings.csv, accuracy.csv, paths.csv, flows.csv, times.csv. A header row, "\n" line
// ends, fields quoted as RFC 4180 says when needed; fixed number formats, empty fields for numbers that do not exist.
std::vector<std::pair<std::string, std::string>> studyAnalysisCsv(const StudyAnalysis& analysis);
// Writes them into `dir` (created when missing), replacing files of the same names. StudyError naming a file that
// cannot be written.
void writeStudyAnalysisCsv(const StudyAnalysis& analysis, const std::string& dir);

}  // namespace cbtl::app::study
