// ResultsFigure.h — a figure made from experiments' results (summary.csv files): what `cbtl plot` draws and what a
// sweep's "plots" ask for. One request, two layouts:
//   panels    one panel per results folder (the paper's Figure 3: one per environment), a curve or bar per approach;
//   together  every results folder in one panel (Figure 5: the nonstationary variants side by side), a series per
//             folder and approach, labelled by the folder's label, or "Approach (label)" when the folder has
//             several approaches. Bars are labelled the same way.
#pragma once

#include "app/plot/Chart.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace cbtl::plot {

enum class Metric { Eval, TaskSuccess, PreferencesMet };

struct FigureRequest {
  std::vector<std::string> results;  // experiment folders (or their summary.csv)
  ChartKind kind = ChartKind::Lines;
  bool together = false;
  std::vector<std::string> titles;      // panels: one per results folder; empty: the folders' names
  std::vector<std::string> labels;      // together, and bars: one per results folder; empty: the folders' names
  std::vector<std::string> approaches;  // only these, in this order; empty: all, the paper's approaches first
  Metric metric = Metric::Eval;
  std::vector<double> marks;           // dashed vertical lines at these training steps
  std::optional<std::int64_t> atStep;  // bars: the checkpoint shown; unset: each series' last
  std::string title;
  std::optional<std::string> xLabel, yLabel;  // unset: "training steps" and the metric's name
  std::optional<double> yMin, yMax;
  std::optional<double> panelWidth, panelHeight;
};

// Throws ResultsError (a results file) or PlotError (a request that does not fit the results, e.g. three titles for
// two folders, an approach no folder has, a step that is not a checkpoint), each naming what is wrong.
FigureSpec figureFromResults(const FigureRequest& request);

// The name a figure gives an approach: the paper's ("CBTL", "No Personalization", "Free Explore", "Exploit Only",
// "Epsilon Greedy"); another name as it is.
std::string approachDisplayName(const std::string& approach);

// "eval", "success", "preferences"; nullopt for another name.
std::optional<Metric> parseMetric(const std::string& name);

}  // namespace cbtl::plot
