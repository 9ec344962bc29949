// Chart.h — figures as the paper draws them, rendered with cairo to PNG, SVG or PDF: learning curves (mean line,
// shaded standard error, one colour per series, one panel per environment, optional vertical marks such as the
// steps where preferences shift) and bar charts with standard-error bars.
//
// Units: a figure is laid out in points (1/72 in); a PNG is rendered at kPngScale pixels per point, so a three-panel
// figure is about 2300 x 800 pixels: sharp when a README shows it at half that width.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace cbtl::plot {

struct PlotError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// One learning curve: x (training steps), the mean and its standard error at each x.
struct Curve {
  std::string label;
  std::vector<double> x, mean, se;
};

// One bar: its label under the axis, the series that colours it, its value and standard error.
struct Bar {
  std::string label;
  std::string series;
  double mean = 0, se = 0;
};

struct Panel {
  std::string title;
  std::vector<Curve> curves;  // a line chart
  std::vector<Bar> bars;      // a bar chart
  std::vector<double> marks;  // x positions of dashed vertical lines (line charts)
};

enum class ChartKind { Lines, Bars };

struct FigureSpec {
  ChartKind kind = ChartKind::Lines;
  std::string title;  // above every panel; empty: none
  std::string xLabel = "training steps", yLabel = "evaluation satisfaction";
  std::vector<Panel> panels;
  std::optional<double> yMin, yMax;            // the y range; unset: from the data, padded to whole ticks
  double panelWidth = 380, panelHeight = 290;  // points
};

// Where a panel's plot area is on the figure, in points, and the data range it shows.
struct PanelGeometry {
  double left = 0, top = 0, width = 0, height = 0;
  double xMin = 0, xMax = 1, yMin = 0, yMax = 1;
  std::vector<double> yTicks, xTicks;
  double px(double x) const { return left + (x - xMin) / (xMax - xMin) * width; }
  double py(double y) const { return top + height - (y - yMin) / (yMax - yMin) * height; }
};

struct LegendEntry {
  std::string label;
  double x = 0, y = 0;  // the swatch's left end and vertical centre, points
};

struct FigureLayout {
  double width = 0, height = 0;
  std::vector<PanelGeometry> panels;
  std::vector<LegendEntry> legend;
};

inline constexpr double kPngScale = 2.0;

// The layout renderFigure draws (tests use it to find a curve's pixels). Throws PlotError for a figure with no
// panel, a panel with nothing to draw, a curve whose x, mean and se differ in length or are not finite, or an empty
// y range.
FigureLayout layoutFigure(const FigureSpec& spec);

// Colour of a series (0..1 RGB): the paper's approaches, by name or display name, always get the same colour (cbtl
// blue, no-personalization orange, free-explore green, exploit-only red, epsilon-greedy purple); other labels take, in
// the order `labels` (every series of the figure, in order of appearance) names them, the palette's colours no approach
// of the figure uses.
struct Rgb {
  double r = 0, g = 0, b = 0;
};
Rgb seriesColor(const std::string& label, const std::vector<std::string>& labels);

// Every series label of the figure in order of first appearance (curves' labels, bars' series).
std::vector<std::string> seriesLabels(const FigureSpec& spec);

// Renders `spec` to `path`; the format follows the extension: .png, .svg or .pdf. Throws PlotError for another
// extension, a figure layoutFigure refuses, or a file that cannot be written (the message names it).
void renderFigure(const FigureSpec& spec, const std::string& path);

}  // namespace cbtl::plot
