// `cbtl plot RESULTS... --out FILE.{png,svg,pdf}`: figures of experiments' results (app/plot/ResultsFigure.h):
// learning curves with shaded standard errors, one panel per results folder or all together, marks at given steps,
// or bars at one checkpoint. Exit codes: 0 ok, 1 bad results or an unwritable file, 2 usage.
#include "tools/cbtl/CommandRegistry.h"
#include "tools/cbtl/ErrorHandling.h"

#include "app/plot/ResultsFigure.h"
#include "app/plot/SummaryTable.h"

#include <fmt/core.h>

#include <memory>
#include <sstream>
#include <string>

namespace {

struct PlotArgs {
  std::vector<std::string> results;
  std::string out, kind = "lines", layout = "panels", metric = "eval", title, xLabel, yLabel;
  std::vector<std::string> titles, labels, approaches;
  std::vector<double> marks;
  std::int64_t atStep = -1;
  double yMin = 0, yMax = 0, width = 0, height = 0;
};

int runPlot(const PlotArgs& a, const CLI::App& cmd) {
  using namespace cbtl::plot;
  FigureRequest r;
  r.results = a.results;
  r.kind = a.kind == "bars" ? ChartKind::Bars : ChartKind::Lines;
  r.together = a.layout == "together";
  r.titles = a.titles;
  r.labels = a.labels;
  r.approaches = a.approaches;
  r.metric = *parseMetric(a.metric);  // CLI11 checked the name
  r.marks = a.marks;
  if (a.atStep >= 0) r.atStep = a.atStep;
  r.title = a.title;
  if (cmd.count("--xlabel")) r.xLabel = a.xLabel;
  if (cmd.count("--ylabel")) r.yLabel = a.yLabel;
  if (cmd.count("--ymin")) r.yMin = a.yMin;
  if (cmd.count("--ymax")) r.yMax = a.yMax;
  if (cmd.count("--width")) r.panelWidth = a.width;
  if (cmd.count("--height")) r.panelHeight = a.height;
  try {
    renderFigure(figureFromResults(r), a.out);
  } catch (const ResultsError& e) {
    fmt::print(stderr, "cbtl plot: error: {}\n", e.what());
    return 1;
  } catch (const PlotError& e) {
    fmt::print(stderr, "cbtl plot: error: {}\n", e.what());
    return 1;
  }
  fmt::print("wrote {}\n", a.out);
  return 0;
}

void addPlot(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<PlotArgs>();
  CLI::App* cmd = app.add_subcommand("plot", "draw experiments' results: learning curves or bars (PNG, SVG, PDF)");
  cmd->add_option("results", args->results, "experiment folders (with summary.csv) or summary.csv files")->required();
  cmd->add_option("--out", args->out, "the figure: FILE.png, FILE.svg or FILE.pdf")->required();
  cmd->add_option("--kind", args->kind, "lines (learning curves) or bars (one checkpoint)")
      ->check(CLI::IsMember({"lines", "bars"}))
      ->capture_default_str();
  cmd->add_option("--layout", args->layout, "panels (one per results folder) or together (one panel)")
      ->check(CLI::IsMember({"panels", "together"}))
      ->capture_default_str();
  cmd->add_option("--metric", args->metric, "eval (satisfaction, with standard error), success or preferences")
      ->check(CLI::IsMember({"eval", "success", "preferences"}))
      ->capture_default_str();
  // One title or label per occurrence, so that they may hold commas: --label "CBTL, replanning" --label ...
  cmd->add_option("--panel-title", args->titles, "a panel's title; give one per results folder, in order")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  cmd->add_option("--label", args->labels, "a series' label; give one per results folder, in order (together, bars)")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  cmd->add_option("--approaches", args->approaches, "only these approaches, in this order")->delimiter(',');
  cmd->add_option("--marks", args->marks, "dashed vertical lines at these training steps")->delimiter(',');
  cmd->add_option("--at-step", args->atStep, "bars: the checkpoint to show (default: the last)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--title", args->title, "a title above the figure");
  cmd->add_option("--xlabel", args->xLabel, "the x axis' label");
  cmd->add_option("--ylabel", args->yLabel, "the y axis' label");
  cmd->add_option("--ymin", args->yMin, "the y axis' lower end (default: from the data)");
  cmd->add_option("--ymax", args->yMax, "the y axis' upper end (default: from the data)");
  cmd->add_option("--width", args->width, "width of one panel, points (default 380)")->check(CLI::Range(120.0, 4000.0));
  cmd->add_option("--height", args->height, "height of a panel, points (default 290)")
      ->check(CLI::Range(120.0, 4000.0));
  cmd->callback(
      [args, cmd, &exitCode]() { cbtl::cli::runCommand("plot", exitCode, [&] { return runPlot(*args, *cmd); }); });
}

const cbtl::cli::RegisterCommand registerPlot(17, addPlot);

}  // namespace
