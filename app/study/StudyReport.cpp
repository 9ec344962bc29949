// StudyReport.cpp — the analysis's renderings (see StudyAnalysis.h): the text report and the CSV files. Fixed number
// formats, so that the same database always gives the same bytes.
#include "app/study/StudyAnalysis.h"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace cbtl::app::study {

// ---- The text report ----

namespace {

std::string orDash(const std::optional<double>& v, int decimals) {
  return v ? fmt::format("{:.{}f}", *v, decimals) : "-";
}

std::string yesNo(const Share& s) { return fmt::format("yes {}, no {}", s.hits, s.total - s.hits); }

void printParticipants(const StudyAnalysis& a, std::ostream& out) {
  const auto& p = a.participants;
  const auto& d = a.demographics;
  out << fmt::format("participants: {} begun, {} consented, {} completed\n", p.begun, p.consented, p.completed);
  std::string genders;
  for (const auto& g : studyGenders())
    genders += fmt::format("{}{} {}", genders.empty() ? "" : ", ", g, d.genders.at(g));
  const std::string age = d.agesGiven == 0 ? "none given"
                                           : fmt::format("{}..{}, mean {:.1f} ({} of {} gave it)", *d.ageMin, *d.ageMax,
                                                         *d.ageMean, d.agesGiven, d.answered);
  out << fmt::format("demographics ({} answered): age {}\n  gender: {}\n  robot experience: {}; fed as an adult: {}\n",
                     d.answered, age, genders, yesNo(d.robotExperience), yesNo(d.fedExperience));
  out << "meals:\n";
  for (int m = 1; m <= kMeals; ++m) {
    const std::string& meal = a.mealDescriptions.at(static_cast<std::size_t>(m - 1));
    out << fmt::format("  {} {}\n", m, meal.empty() ? "(no rating recorded)" : meal);
  }
}

// Below this many non-neutral ratings a meal's signed-rank test comes with a warning.
constexpr std::size_t kFewestForTest = 20;

// A p-value as the report shows it: four decimals, or two significant digits below 0.0001 (the paper's claim is
// p < 0.005; "0.0000" would hide how far below).
std::string pValue(double p) { return p < 1e-4 ? fmt::format("{:.1e}", p) : fmt::format("{:.4f}", p); }

void printRatings(const StudyAnalysis& a, std::ostream& out) {
  out << "\nCBTL preference per meal (1 strongly prefers No Personalization .. 5 strongly prefers CBTL), Wilcoxon "
         "signed-rank test against 3:\n";
  out << fmt::format("{:>4} | {:>3} | {:>25} | {:>7} | {:>6} | {:>13} | {:>18} | {:>6} | {}\n", "meal", "n",
                     "CBTL preference mean ± sd", "W+", "z", "p (two-sided)", "p (CBTL preferred)", "r", "test");
  for (const auto& r : a.ratings) {
    const std::string meanSd = fmt::format("{} ± {}", orDash(r.mean, 2), orDash(r.sd, 2));
    if (!r.test.tested) {
      out << fmt::format("{:>4} | {:>3} | {:>25} | {:>7} | {:>6} | {:>13} | {:>18} | {:>6} | none, {} neutral\n",
                         r.meal, r.n(), meanSd, "-", "-", "-", "-", "-", r.test.zeros);
      continue;
    }
    const char* method = r.test.method == SignedRankResult::Method::Exact ? "exact" : "normal";
    out << fmt::format(
        "{:>4} | {:>3} | {:>25} | {:>7.1f} | {:>6.3f} | {:>13} | {:>18} | {:>6.3f} | {}, {} neutral dropped\n", r.meal,
        r.n(), meanSd, r.test.wPlus, r.test.z, pValue(r.test.pTwoSided), pValue(r.test.pGreater), r.test.effectSize,
        method, r.test.zeros);
  }
  // Too few participants for the test to mean much: with n non-neutral ratings the exact two-sided p is at least
  // 2 / 2^n (n = 5: 0.0625, never below 0.05), and under about 20 even a real preference is often missed.
  std::string few;
  std::size_t fewest = 0;
  for (const auto& r : a.ratings) {
    const std::size_t n = r.n() >= r.test.zeros ? r.n() - r.test.zeros : 0;
    if (n >= kFewestForTest) continue;
    few += fmt::format("{}{}", few.empty() ? "" : ", ", r.meal);
    fewest = few.find(',') == std::string::npos ? n : std::min(fewest, n);
  }
  if (!few.empty())
    out << fmt::format(
        "warning: meal{} {} {} fewer than {} non-neutral ratings (as few as {}): the exact test cannot reach p < 0.05 "
        "below 6, and its power is low below {}; read these p-values as a pilot's, not as a finding\n",
        few.find(',') == std::string::npos ? "" : "s", few, few.find(',') == std::string::npos ? "has" : "have",
        kFewestForTest, fewest, kFewestForTest);
}

void printAccuracy(const StudyAnalysis& a, std::ostream& out) {
  out << "\noffers that matched the answers per meal (predicted; an unsolved offer is wrong) and answers met:\n";
  out << fmt::format("{:>4} | {:>7} | {:<18} | {:>4} | {:>6} | {:>9} | {:>8} | {:>10} | {:>13} | {:>8}\n", "meal",
                     "answers", "approach", "dip", "signal", "verbosity", "met dip", "met signal", "met verbosity",
                     "met view");
  for (const auto& acc : a.accuracy) {
    for (const auto& approach : studyApproaches()) {
      const auto& predicted = acc.predicted.at(approach);
      const auto& met = acc.met.at(approach);
      const auto share = [](const std::map<std::string, Share>& m, const std::string& q) {
        const auto it = m.find(q);
        return it == m.end() ? std::string("-") : orDash(it->second.share(), 2);
      };
      out << fmt::format("{:>4} | {:>7} | {:<18} | {:>4} | {:>6} | {:>9} | {:>8} | {:>10} | {:>13} | {:>8}\n", acc.meal,
                         acc.answers, approach, share(predicted, "dip"), share(predicted, "signal"),
                         share(predicted, "verbosity"), share(met, "dip"), share(met, "signal"),
                         share(met, "verbosity"), share(met, "view"));
    }
  }
  std::string pictures;
  for (const auto& acc : a.accuracy)
    pictures += fmt::format("{}meal {} {} ({} of {})", pictures.empty() ? "" : "; ", acc.meal,
                            orDash(acc.notBlocked.share(), 2), acc.notBlocked.hits, acc.notBlocked.total);
  out << "pictures answered not blocked: " << pictures << "\n";
}

void printSankeys(const StudyAnalysis& a, std::ostream& out) {
  constexpr std::size_t kTopPaths = 5;
  const std::size_t all = a.sankeys.empty() ? 0 : a.sankeys.front().participants.size();
  out << fmt::format("\nanswer paths over meals 1..{} ({} participants answered every meal):\n", kMeals, all);
  for (const auto& s : a.sankeys) {
    out << fmt::format("  {}: {} distinct paths\n", s.question, s.paths.size());
    for (std::size_t i = 0; i < s.paths.size() && i < kTopPaths; ++i)
      out << fmt::format("    {:>4}  {}\n", s.paths[i].count, s.paths[i].text);
    if (s.paths.size() > kTopPaths) out << fmt::format("    ... and {} more\n", s.paths.size() - kTopPaths);
  }
}

void printTimes(const StudyAnalysis& a, std::ostream& out) {
  out << "\ntime on a page (rt_ms), median and 90th percentile:\n";
  for (const auto& t : a.rtByKind) {
    const auto seconds = [](const std::optional<double>& ms) {
      return ms ? fmt::format("{:.1f} s", *ms / 1000) : std::string("-");
    };
    out << fmt::format("  {:<12} {:>9} {:>9}  (n {})\n", t.measure, seconds(t.medianMs), seconds(t.p90Ms), t.n);
  }
  const auto minutes = [](const std::optional<double>& ms) {
    return ms ? fmt::format("{:.1f} min", *ms / 60000) : std::string("-");
  };
  out << fmt::format("whole study (completed participants): median {}, 90th percentile {} (n {})\n",
                     minutes(a.totalDuration.medianMs), minutes(a.totalDuration.p90Ms), a.totalDuration.n);
}

}  // namespace

void printStudyAnalysis(const StudyAnalysis& analysis, std::ostream& out) {
  printParticipants(analysis, out);
  printRatings(analysis, out);
  printAccuracy(analysis, out);
  printSankeys(analysis, out);
  printTimes(analysis, out);
}

// ---- CSV ----

namespace {

std::string csvField(const std::string& field) {
  if (field.find_first_of(",\"\r\n") == std::string::npos) return field;
  std::string out = "\"";
  for (char c : field) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string orEmpty(const std::optional<double>& v, int decimals) {
  return v ? fmt::format("{:.{}f}", *v, decimals) : "";
}

std::string ratingsCsv(const StudyAnalysis& a) {
  std::string csv = "meal,n,mean,sd,method,n_ranked,zeros,w_plus,w_minus,z,p_two_sided,p_greater,r\n";
  for (const auto& r : a.ratings) {
    csv += fmt::format("{},{},{},{},", r.meal, r.n(), orEmpty(r.mean, 4), orEmpty(r.sd, 4));
    const auto& t = r.test;
    if (!t.tested) {
      csv += fmt::format("none,0,{},,,,,,\n", t.zeros);
      continue;
    }
    csv += fmt::format("{},{},{},{:.1f},{:.1f},{:.4f},{:.6g},{:.6g},{:.4f}\n",
                       t.method == SignedRankResult::Method::Exact ? "exact" : "normal", t.n, t.zeros, t.wPlus,
                       t.wMinus, t.z, t.pTwoSided, t.pGreater, t.effectSize);
  }
  return csv;
}

std::string shareRow(int meal, const std::string& measure, const std::string& approach, const std::string& question,
                     const Share& s) {
  return fmt::format("{},{},{},{},{},{},{}\n", meal, measure, approach, question, s.hits, s.total,
                     orEmpty(s.share(), 4));
}

std::string accuracyCsv(const StudyAnalysis& a) {
  std::string csv = "meal,measure,approach,question,hits,total,share\n";
  for (const auto& acc : a.accuracy) {
    for (const auto& approach : studyApproaches())
      for (const auto& [q, s] : acc.predicted.at(approach)) csv += shareRow(acc.meal, "predicted", approach, q, s);
    for (const auto& approach : studyApproaches())
      for (const auto& [q, s] : acc.met.at(approach)) csv += shareRow(acc.meal, "met", approach, q, s);
    csv += shareRow(acc.meal, "not_blocked", "", "", acc.notBlocked);
  }
  return csv;
}

std::string pathsCsv(const StudyAnalysis& a) {
  std::string csv = "question,path,count\n";
  for (const auto& s : a.sankeys)
    for (const auto& p : s.paths) csv += fmt::format("{},{},{}\n", s.question, csvField(p.text), p.count);
  return csv;
}

std::string flowsCsv(const StudyAnalysis& a) {
  std::string csv = "question,meal_from,answer_from,meal_to,answer_to,count\n";
  for (const auto& s : a.sankeys)
    for (const auto& f : s.flows)
      csv += fmt::format("{},{},{},{},{},{}\n", s.question, f.mealFrom, csvField(f.answerFrom), f.mealFrom + 1,
                         csvField(f.answerTo), f.count);
  return csv;
}

std::string timesCsv(const StudyAnalysis& a) {
  std::string csv = "measure,n,median_ms,p90_ms\n";
  std::vector<TimeSummary> rows = a.rtByKind;
  rows.push_back(a.totalDuration);
  for (const auto& t : rows)
    csv += fmt::format("{},{},{},{}\n", t.measure, t.n, orEmpty(t.medianMs, 1), orEmpty(t.p90Ms, 1));
  return csv;
}

}  // namespace

std::vector<std::pair<std::string, std::string>> studyAnalysisCsv(const StudyAnalysis& analysis) {
  return {{"ratings.csv", ratingsCsv(analysis)},
          {"accuracy.csv", accuracyCsv(analysis)},
          {"paths.csv", pathsCsv(analysis)},
          {"flows.csv", flowsCsv(analysis)},
          {"times.csv", timesCsv(analysis)}};
}

void writeStudyAnalysisCsv(const StudyAnalysis& analysis, const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw StudyError(fmt::format("{}: cannot create the folder: {}", dir, ec.message()));
  for (const auto& [name, content] : studyAnalysisCsv(analysis)) {
    const std::string path = (std::filesystem::path(dir) / name).string();
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    f << content;
    f.close();
    if (!f) throw StudyError(path + ": cannot write");
  }
}

}  // namespace cbtl::app::study
