#include "app/plot/SummaryTable.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

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

// The column of `name` in a CSV header; throws when it has none.
std::size_t columnOf(const std::vector<std::string>& header, const std::string& name, const std::string& where) {
  const auto it = std::find(header.begin(), header.end(), name);
  if (it == header.end()) throw ResultsError(fmt::format("{}: no column {}", where, name));
  return static_cast<std::size_t>(it - header.begin());
}

// One run's folder (`cbtl run --out DIR`): its eval.csv as a summary of one seed, named by config.json's approach.
SummaryTable readRun(const std::filesystem::path& dir) {
  SummaryTable t;
  t.path = (dir / "eval.csv").string();
  std::string approach = "run";
  if (std::ifstream config(dir / "config.json"); config) {
    const auto j = nlohmann::json::parse(config, nullptr, false);
    if (j.is_object() && j.contains("approach") && j["approach"].is_string())
      approach = j["approach"].get<std::string>();
  }
  std::ifstream in(t.path);
  std::string line;
  if (!std::getline(in, line)) throw ResultsError(t.path + ":1: empty");
  const auto header = cells(line);
  const std::size_t step = columnOf(header, "training_step", t.path + ":1");
  const std::size_t mean = columnOf(header, "eval_mean_user_satisfaction", t.path + ":1");
  const std::size_t success = columnOf(header, "eval_task_success_rate", t.path + ":1");
  const std::size_t prefs = columnOf(header, "eval_preferences_met_rate", t.path + ":1");
  for (int n = 2; std::getline(in, line); ++n) {
    if (line.empty()) continue;
    const std::string where = fmt::format("{}:{}", t.path, n);
    const auto c = cells(line);
    if (c.size() != header.size())
      throw ResultsError(fmt::format("{}: {} columns, the header has {}", where, c.size(), header.size()));
    Checkpoint p;
    p.step = static_cast<std::int64_t>(number(c[step], where, "training_step"));
    p.seeds = 1;
    p.evalMean = number(c[mean], where, "eval_mean_user_satisfaction");
    p.taskSuccess = number(c[success], where, "eval_task_success_rate");
    p.preferencesMet = number(c[prefs], where, "eval_preferences_met_rate");
    t.byApproach[approach].push_back(p);
  }
  if (t.byApproach.empty()) throw ResultsError(t.path + ": no checkpoints");
  t.approaches = {approach};
  return t;
}

}  // namespace

SummaryTable readSummary(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path file(path);
  if (fs::is_directory(file, ec) && !fs::exists(file / "summary.csv", ec) && fs::is_regular_file(file / "eval.csv", ec))
    return readRun(file);
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
