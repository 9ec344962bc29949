#include "app/plot/Chart.h"

#include <cairo.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

namespace cbtl::plot {

namespace {

// Points: panel margins, fonts, legend.
constexpr double kMarginLeft = 60, kMarginRight = 18, kMarginTop = 30, kMarginBottom = 46;
constexpr double kFigureTitle = 30, kLegendRow = 24, kLegendPad = 10, kSwatch = 24;
constexpr double kLegendFont = 12.5;
constexpr const char* kFont = "DejaVu Sans";

using Surface = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
using Context = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

// A step of 1, 2 or 5 times a power of ten that divides `span` into about `count` intervals.
double niceStep(double span, int count) {
  const double raw = span / count;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (raw <= m * power * 1.0000001) return m * power;
  return 10 * power;
}

std::vector<double> ticksBetween(double lo, double hi, double step) {
  std::vector<double> ticks;
  for (double t = std::ceil(lo / step - 1e-9) * step; t <= hi + step * 1e-9; t += step)
    ticks.push_back(std::abs(t) < step * 1e-9 ? 0.0 : t);
  return ticks;
}

void checkFinite(const std::vector<double>& v, const std::string& what) {
  for (double x : v)
    if (!std::isfinite(x)) throw PlotError(what + " holds a value that is not finite");
}

// The data's y extent in a panel, standard errors included (bars from zero).
std::pair<double, double> yExtent(const FigureSpec& spec) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Panel& p : spec.panels) {
    for (const Curve& c : p.curves)
      for (std::size_t i = 0; i < c.mean.size(); ++i) {
        lo = std::min(lo, c.mean[i] - c.se[i]);
        hi = std::max(hi, c.mean[i] + c.se[i]);
      }
    for (const Bar& b : p.bars) {
      lo = std::min({lo, 0.0, b.mean - b.se});
      hi = std::max({hi, 0.0, b.mean + b.se});
    }
  }
  return {lo, hi};
}

void validate(const FigureSpec& spec) {
  if (spec.panels.empty()) throw PlotError("a figure needs at least one panel");
  for (const Panel& p : spec.panels) {
    const std::string name = p.title.empty() ? "a panel" : "panel '" + p.title + "'";
    if (spec.kind == ChartKind::Lines && p.curves.empty()) throw PlotError(name + " has no curve to draw");
    if (spec.kind == ChartKind::Bars && p.bars.empty()) throw PlotError(name + " has no bar to draw");
    for (const Curve& c : p.curves) {
      if (c.x.empty() || c.x.size() != c.mean.size() || c.x.size() != c.se.size())
        throw PlotError(
            fmt::format("curve '{}' of {}: x, mean and se must be non-empty and of one length", c.label, name));
      checkFinite(c.x, "curve '" + c.label + "'");
      checkFinite(c.mean, "curve '" + c.label + "'");
      checkFinite(c.se, "curve '" + c.label + "'");
    }
    for (const Bar& b : p.bars)
      if (!std::isfinite(b.mean) || !std::isfinite(b.se))
        throw PlotError("bar '" + b.label + "' holds a value that is not finite");
    checkFinite(p.marks, "the marks of " + name);
  }
  if ((spec.yMin && !std::isfinite(*spec.yMin)) || (spec.yMax && !std::isfinite(*spec.yMax)) ||
      (spec.yMin && spec.yMax && *spec.yMin >= *spec.yMax))
    throw PlotError("the y range is empty or not finite");
}

double textWidth(cairo_t* cr, const std::string& text, double size, bool bold = false) {
  cairo_select_font_face(cr, kFont, CAIRO_FONT_SLANT_NORMAL, bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
  cairo_text_extents_t e;
  cairo_text_extents(cr, text.c_str(), &e);
  return e.x_advance;
}

// Legend entries in rows centred under the panels; returns the legend's height.
double layoutLegend(const FigureSpec& spec, double width, double top, std::vector<LegendEntry>& out) {
  Surface probe(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 1, 1), cairo_surface_destroy);
  Context cr(cairo_create(probe.get()), cairo_destroy);
  const auto labels = seriesLabels(spec);
  std::vector<std::vector<std::pair<std::string, double>>> rows(1);
  double rowWidth = 0;
  for (const auto& label : labels) {
    const double w = kSwatch + 6 + textWidth(cr.get(), label, kLegendFont) + 22;
    if (rowWidth + w > width - 2 * kLegendPad && !rows.back().empty()) {
      rows.emplace_back();
      rowWidth = 0;
    }
    rows.back().emplace_back(label, w);
    rowWidth += w;
  }
  for (std::size_t r = 0; r < rows.size(); ++r) {
    double total = 0;
    for (const auto& [label, w] : rows[r]) total += w;
    double x = (width - total) / 2 + 11;
    for (const auto& [label, w] : rows[r]) {
      out.push_back(LegendEntry{label, x, top + kLegendPad + kLegendRow * (static_cast<double>(r) + 0.5)});
      x += w;
    }
  }
  return labels.empty() ? 0 : kLegendPad * 2 + kLegendRow * static_cast<double>(rows.size());
}

}  // namespace

std::vector<std::string> seriesLabels(const FigureSpec& spec) {
  std::vector<std::string> labels;
  const auto add = [&](const std::string& l) {
    if (std::find(labels.begin(), labels.end(), l) == labels.end()) labels.push_back(l);
  };
  for (const Panel& p : spec.panels) {
    for (const Curve& c : p.curves) add(c.label);
    for (const Bar& b : p.bars) add(b.series);
  }
  return labels;
}

Rgb seriesColor(const std::string& label, const std::vector<std::string>& labels) {
  // The Tableau 10 palette: distinguishable, and readable by most colour-blind readers in its first five.
  static const Rgb kPalette[] = {{0.122, 0.467, 0.706}, {1.000, 0.498, 0.055}, {0.173, 0.627, 0.173},
                                 {0.839, 0.153, 0.157}, {0.580, 0.404, 0.741}, {0.549, 0.337, 0.294},
                                 {0.890, 0.467, 0.761}, {0.498, 0.498, 0.498}, {0.737, 0.741, 0.133},
                                 {0.090, 0.745, 0.812}};
  constexpr std::size_t kReserved = 5, kColours = 10;
  // An approach by its name or the name figures give it (ResultsFigure.h approachDisplayName).
  static const char* kApproaches[2][kReserved] = {
      {"cbtl", "no-personalization", "free-explore", "exploit-only", "epsilon-greedy"},
      {"CBTL", "No Personalization", "Free Explore", "Exploit Only", "Epsilon Greedy"}};
  const auto approachIndex = [&](const std::string& l) -> std::size_t {
    for (std::size_t i = 0; i < kReserved; ++i)
      if (l == kApproaches[0][i] || l == kApproaches[1][i]) return i;
    return kReserved;
  };
  if (approachIndex(label) < kReserved) return kPalette[approachIndex(label)];
  // Other labels take, in order, the palette's colours that no approach of the figure uses.
  std::vector<bool> used(kColours, false);
  for (const auto& l : labels)
    if (approachIndex(l) < kReserved) used[approachIndex(l)] = true;
  std::size_t next = 0;
  for (const auto& l : labels) {
    if (approachIndex(l) < kReserved) continue;
    while (used[next % kColours] && next < 2 * kColours) ++next;
    if (l == label) return kPalette[next % kColours];
    ++next;
  }
  return kPalette[next % kColours];
}

FigureLayout layoutFigure(const FigureSpec& spec) {
  validate(spec);
  FigureLayout layout;
  const double top = spec.title.empty() ? 0 : kFigureTitle;
  layout.width = spec.panelWidth * static_cast<double>(spec.panels.size());
  auto [lo, hi] = yExtent(spec);
  if (spec.yMin) lo = *spec.yMin;
  if (spec.yMax) hi = *spec.yMax;
  if (!(hi > lo)) {
    lo -= 1;
    hi += 1;
  }
  const double yStep = niceStep(hi - lo, 5);
  if (!spec.yMin) lo = std::floor(lo / yStep + 1e-9) * yStep;
  if (!spec.yMax) hi = std::ceil(hi / yStep - 1e-9) * yStep;
  for (std::size_t i = 0; i < spec.panels.size(); ++i) {
    const Panel& p = spec.panels[i];
    PanelGeometry g;
    g.left = spec.panelWidth * static_cast<double>(i) + kMarginLeft;
    g.top = top + kMarginTop;
    g.width = spec.panelWidth - kMarginLeft - kMarginRight;
    g.height = spec.panelHeight - kMarginTop - kMarginBottom;
    g.yMin = lo;
    g.yMax = hi;
    g.yTicks = ticksBetween(lo, hi, yStep);
    if (spec.kind == ChartKind::Bars) {
      g.xMin = 0;
      g.xMax = static_cast<double>(p.bars.size());
    } else {
      g.xMin = std::numeric_limits<double>::infinity();
      g.xMax = -g.xMin;
      for (const Curve& c : p.curves)
        for (double x : c.x) g.xMin = std::min(g.xMin, x), g.xMax = std::max(g.xMax, x);
      if (!(g.xMax > g.xMin)) g.xMax = g.xMin + 1;
      g.xTicks = ticksBetween(g.xMin, g.xMax, niceStep(g.xMax - g.xMin, 5));
    }
    layout.panels.push_back(std::move(g));
  }
  layout.height = top + spec.panelHeight;
  layout.height += layoutLegend(spec, layout.width, layout.height, layout.legend);
  return layout;
}

}  // namespace cbtl::plot
