#include "app/plot/ResultsFigure.h"

#include "app/plot/SummaryTable.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <filesystem>
#include <set>

namespace cbtl::plot {

namespace {

double value(const Checkpoint& c, Metric m) {
  switch (m) {
    case Metric::Eval:
      return c.evalMean;
    case Metric::TaskSuccess:
      return c.taskSuccess;
    case Metric::PreferencesMet:
      return c.preferencesMet;
  }
  return c.evalMean;
}

// summary.csv holds the standard error of the evaluation satisfaction only.
double stderrOf(const Checkpoint& c, Metric m) { return m == Metric::Eval ? c.evalSe : 0.0; }

const char* metricName(Metric m) {
  switch (m) {
    case Metric::Eval:
      return "evaluation satisfaction";
    case Metric::TaskSuccess:
      return "task success rate";
    case Metric::PreferencesMet:
      return "preferences met";
  }
  return "";
}

// A results folder's name: the folder itself, or the one holding summary.csv.
std::string folderName(const std::string& path) {
  std::filesystem::path p(path);
  if (p.filename() == "summary.csv") p = p.parent_path();
  if (p.filename().empty()) p = p.parent_path();
  return p.filename().string();
}

std::vector<std::string> namesOrDefault(const std::vector<std::string>& given, const std::vector<std::string>& results,
                                        const char* option) {
  if (given.empty()) {
    std::vector<std::string> out;
    for (const auto& r : results) out.push_back(folderName(r));
    return out;
  }
  if (given.size() != results.size())
    throw PlotError(fmt::format("{} {} for {} results folder{} (give one per folder)", given.size(), option,
                                results.size(), results.size() == 1 ? "" : "s"));
  return given;
}

// The paper's approaches in the order it lists them; others follow in the file's order.
std::vector<std::string> paperOrder(std::vector<std::string> names) {
  static const std::vector<std::string> kOrder = {"cbtl", "no-personalization", "free-explore", "exploit-only",
                                                  "epsilon-greedy"};
  const auto rank = [&](const std::string& n) {
    return static_cast<std::size_t>(std::find(kOrder.begin(), kOrder.end(), n) - kOrder.begin());
  };
  std::stable_sort(names.begin(), names.end(), [&](const auto& a, const auto& b) { return rank(a) < rank(b); });
  return names;
}

std::vector<std::string> approachesOf(const SummaryTable& t, const std::vector<std::string>& wanted) {
  if (wanted.empty()) return paperOrder(t.approaches);
  std::vector<std::string> out;
  for (const auto& a : wanted)
    if (t.byApproach.count(a)) out.push_back(a);
  return out;
}

const Checkpoint& checkpointAt(const SummaryTable& t, const std::string& approach, std::optional<std::int64_t> step) {
  const auto& points = t.byApproach.at(approach);
  if (!step) return points.back();
  for (const auto& p : points)
    if (p.step == *step) return p;
  std::string steps;
  for (const auto& p : points) steps += (steps.empty() ? "" : ", ") + std::to_string(p.step);
  throw PlotError(fmt::format("{}: {} has no checkpoint at step {} (it has {})", t.path, approach, *step, steps));
}

Curve curveOf(const SummaryTable& t, const std::string& approach, const std::string& label, Metric m) {
  Curve c;
  c.label = label;
  for (const auto& p : t.byApproach.at(approach)) {
    c.x.push_back(static_cast<double>(p.step));
    c.mean.push_back(value(p, m));
    c.se.push_back(stderrOf(p, m));
  }
  return c;
}

}  // namespace

std::string approachDisplayName(const std::string& approach) {
  static const std::pair<const char*, const char*> kNames[] = {{"cbtl", "CBTL"},
                                                               {"no-personalization", "No Personalization"},
                                                               {"free-explore", "Free Explore"},
                                                               {"exploit-only", "Exploit Only"},
                                                               {"epsilon-greedy", "Epsilon Greedy"}};
  for (const auto& [name, display] : kNames)
    if (approach == name) return display;
  return approach;
}

std::optional<Metric> parseMetric(const std::string& name) {
  if (name == "eval") return Metric::Eval;
  if (name == "success") return Metric::TaskSuccess;
  if (name == "preferences") return Metric::PreferencesMet;
  return std::nullopt;
}

FigureSpec figureFromResults(const FigureRequest& r) {
  if (r.results.empty()) throw PlotError("no results to plot");
  std::vector<SummaryTable> tables;
  for (const auto& path : r.results) tables.push_back(readSummary(path));
  const auto titles = namesOrDefault(r.titles, r.results, "panel titles");
  const auto labels = namesOrDefault(r.labels, r.results, "labels");
  FigureSpec spec;
  spec.kind = r.kind;
  spec.title = r.title;
  spec.xLabel = r.xLabel.value_or("training steps");
  spec.yLabel = r.yLabel.value_or(metricName(r.metric));
  spec.yMin = r.yMin;
  spec.yMax = r.yMax;
  if (r.panelWidth) spec.panelWidth = *r.panelWidth;
  if (r.panelHeight) spec.panelHeight = *r.panelHeight;
  const bool onePanel = r.together || r.kind == ChartKind::Bars;
  if (onePanel) spec.panels.emplace_back();
  if (onePanel && r.results.size() == 1 && r.titles.size() == 1) spec.panels[0].title = r.titles[0];
  if (onePanel && r.panelWidth == std::nullopt && r.kind == ChartKind::Bars)
    spec.panelWidth =
        std::max(380.0, 110.0 * static_cast<double>(r.results.size() * std::max<std::size_t>(1, r.approaches.size())));
  std::set<std::int64_t> barSteps;  // the checkpoints the bars show, for the axis label
  for (std::size_t i = 0; i < tables.size(); ++i) {
    const auto approaches = approachesOf(tables[i], r.approaches);
    if (approaches.empty())
      throw PlotError(fmt::format("{}: none of the approaches asked for (it has: {})", tables[i].path,
                                  fmt::format("{}", fmt::join(tables[i].approaches, ", "))));
    if (!onePanel) {
      spec.panels.emplace_back();
      spec.panels.back().title = titles[i];
    }
    Panel& panel = spec.panels.back();
    panel.marks = r.marks;
    for (const auto& a : approaches) {
      // Together: the folder's label names the series; with several approaches in a folder, the approach too.
      // A bar always names its approach: "Approach (label)" when folders have labels.
      const bool labelled = onePanel && (r.together || r.results.size() > 1 || !r.labels.empty());
      const std::string series = !labelled ? approachDisplayName(a)
                                 : approaches.size() > 1 || r.kind == ChartKind::Bars
                                     ? fmt::format("{} ({})", approachDisplayName(a), labels[i])
                                     : labels[i];
      if (r.kind == ChartKind::Bars) {
        const Checkpoint& c = checkpointAt(tables[i], a, r.atStep);
        barSteps.insert(c.step);
        panel.bars.push_back(Bar{series, approachDisplayName(a), value(c, r.metric), stderrOf(c, r.metric)});
      } else {
        panel.curves.push_back(curveOf(tables[i], a, series, r.metric));
      }
    }
  }
  // Bars say which checkpoint they show, in their panel's title (bar charts have no x axis label).
  if (r.kind == ChartKind::Bars) {
    const std::string at = barSteps.size() == 1
                               ? fmt::format("at training step {}", *barSteps.begin())
                               : fmt::format("at each result's last checkpoint (steps {})", fmt::join(barSteps, ", "));
    std::string& title = spec.panels[0].title;
    title = title.empty() ? at : fmt::format("{}, {}", title, at);
  }
  // Bars: room for each bar's label under it.
  if (r.kind == ChartKind::Bars && !r.panelWidth)
    spec.panelWidth = std::max(spec.panelWidth, 80.0 + 130.0 * static_cast<double>(spec.panels[0].bars.size()));
  return spec;
}

}  // namespace cbtl::plot
