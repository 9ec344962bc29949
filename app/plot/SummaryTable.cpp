#include "app/plot/SummaryTable.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace cbtl::plot {

namespace {

constexpr const char* kHeader = "approach,training_step,seeds,eval_mean,eval_se,task_success_mean,preferences_met_mean";

std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) out.push_back(cell);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

double number(const std::string& text, const std::string& where, const char* column) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(v))
    throw ResultsError(fmt::format("{}: {} is not a finite number: '{}'", where, column, text));
  return v;
}

}  // namespace

SummaryTable readSummary(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path file(path);
  if (fs::is_directory(file, ec)) file /= "summary.csv";
  if (!fs::is_regular_file(file, ec))
    throw ResultsError(
        fmt::format("{}: no results here (an experiment's folder holds summary.csv once it has "
                    "finished; `cbtl sweep CONFIG --collect` writes it for a sweep)",
                    file.string()));
  std::ifstream in(file);
  if (!in) throw ResultsError(fmt::format("{}: cannot be read", file.string()));
  SummaryTable t;
  t.path = file.string();
  std::string line;
  if (!std::getline(in, line) || line != kHeader)
    throw ResultsError(fmt::format("{}:1: not an experiment summary (its header should be: {})", t.path, kHeader));
  for (int n = 2; std::getline(in, line); ++n) {
    if (line.empty()) continue;
    const std::string where = fmt::format("{}:{}", t.path, n);
    const auto c = cells(line);
    if (c.size() != 7) throw ResultsError(fmt::format("{}: {} columns, the header has 7", where, c.size()));
    if (c[0].empty()) throw ResultsError(where + ": no approach");
    Checkpoint p;
    const double step = number(c[1], where, "training_step");
    if (step < 0 || step != std::floor(step))
      throw ResultsError(fmt::format("{}: training_step must be a whole number >= 0, not '{}'", where, c[1]));
    p.step = static_cast<std::int64_t>(step);
    p.seeds = static_cast<int>(number(c[2], where, "seeds"));
    p.evalMean = number(c[3], where, "eval_mean");
    p.evalSe = number(c[4], where, "eval_se");
    p.taskSuccess = number(c[5], where, "task_success_mean");
    p.preferencesMet = number(c[6], where, "preferences_met_mean");
    if (!t.byApproach.count(c[0])) t.approaches.push_back(c[0]);
    t.byApproach[c[0]].push_back(p);
  }
  if (t.approaches.empty()) throw ResultsError(fmt::format("{}: no checkpoints", t.path));
  for (auto& [name, points] : t.byApproach)
    std::stable_sort(points.begin(), points.end(),
                     [](const Checkpoint& a, const Checkpoint& b) { return a.step < b.step; });
  return t;
}

}  // namespace cbtl::plot
