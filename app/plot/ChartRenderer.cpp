// renderFigure (Chart.h): draws the layout of layoutFigure with cairo.
#include "app/plot/Chart.h"

#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <sstream>
#include <vector>

namespace cbtl::plot {

namespace {

constexpr double kTickFont = 11.5, kLabelFont = 13, kTitleFont = 14, kLegendFont = 12.5, kBarLabelFont = 11;
constexpr const char* kFont = "DejaVu Sans";
constexpr double kAxisGrey = 0.25, kGridGrey = 0.88, kBandAlpha = 0.2, kLineWidth = 2.0;

using Surface = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
using Context = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

void font(cairo_t* cr, double size, bool bold = false) {
  cairo_select_font_face(cr, kFont, CAIRO_FONT_SLANT_NORMAL, bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
}

// Draws `text` with its anchor at (x, y): ax 0 left, 0.5 centre, 1 right; ay the same from top to bottom.
void text(cairo_t* cr, const std::string& s, double x, double y, double ax, double ay) {
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  cairo_font_extents_t f;
  cairo_font_extents(cr, &f);
  cairo_move_to(cr, x - e.x_advance * ax, y + f.ascent - ay * (f.ascent + f.descent));
  cairo_show_text(cr, s.c_str());
}

void colour(cairo_t* cr, const Rgb& c, double alpha = 1) { cairo_set_source_rgba(cr, c.r, c.g, c.b, alpha); }

std::string tickLabel(double v, const std::vector<double>& ticks) {
  const double step = ticks.size() > 1 ? ticks[1] - ticks[0] : 1;
  const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
  if (decimals == 0 && std::abs(v) >= 10000 && std::fmod(v, 1000) == 0) return fmt::format("{:.0f}k", v / 1000);
  return fmt::format("{:.{}f}", v, decimals);
}

// Grid, axes, ticks and their labels, and the panel's title and axis labels.
void drawAxes(cairo_t* cr, const FigureSpec& spec, const Panel& panel, const PanelGeometry& g, bool yLabel) {
  cairo_set_line_width(cr, 0.8);
  cairo_set_source_rgb(cr, kGridGrey, kGridGrey, kGridGrey);
  for (double t : g.yTicks) {
    cairo_move_to(cr, g.left, g.py(t));
    cairo_line_to(cr, g.left + g.width, g.py(t));
  }
  cairo_stroke(cr);
  cairo_set_source_rgb(cr, kAxisGrey, kAxisGrey, kAxisGrey);
  cairo_set_line_width(cr, 1.0);
  cairo_move_to(cr, g.left, g.top);
  cairo_line_to(cr, g.left, g.top + g.height);
  cairo_line_to(cr, g.left + g.width, g.top + g.height);
  cairo_stroke(cr);
  font(cr, kTickFont);
  for (double t : g.yTicks) {
    cairo_move_to(cr, g.left - 4, g.py(t));
    cairo_line_to(cr, g.left, g.py(t));
    cairo_stroke(cr);
    text(cr, tickLabel(t, g.yTicks), g.left - 7, g.py(t), 1, 0.5);
  }
  for (double t : g.xTicks) {
    cairo_move_to(cr, g.px(t), g.top + g.height);
    cairo_line_to(cr, g.px(t), g.top + g.height + 4);
    cairo_stroke(cr);
    text(cr, tickLabel(t, g.xTicks), g.px(t), g.top + g.height + 7, 0.5, 0);
  }
  cairo_set_source_rgb(cr, 0, 0, 0);
  font(cr, kTitleFont, true);
  if (!panel.title.empty()) text(cr, panel.title, g.left + g.width / 2, g.top - 10, 0.5, 1);
  font(cr, kLabelFont);
  if (spec.kind == ChartKind::Lines) text(cr, spec.xLabel, g.left + g.width / 2, g.top + g.height + 25, 0.5, 0);
  if (yLabel) {
    cairo_save(cr);
    cairo_translate(cr, g.left - 46, g.top + g.height / 2);
    cairo_rotate(cr, -M_PI / 2);
    text(cr, spec.yLabel, 0, 0, 0.5, 0.5);
    cairo_restore(cr);
  }
}

constexpr std::size_t kMarkersPerCurve = 10;
constexpr double kMarkerSize = 3.6;

std::size_t seriesIndex(const std::string& label, const std::vector<std::string>& labels) {
  return static_cast<std::size_t>(std::find(labels.begin(), labels.end(), label) - labels.begin());
}

// Shape `series % 5` centred at (x, y), in the current colour: circle, square, triangle, diamond, cross.
void marker(cairo_t* cr, std::size_t series, double x, double y) {
  const double r = kMarkerSize;
  switch (series % 5) {
    case 0:
      cairo_arc(cr, x, y, r, 0, 2 * M_PI);
      break;
    case 1:
      cairo_rectangle(cr, x - r * 0.9, y - r * 0.9, r * 1.8, r * 1.8);
      break;
    case 2:
      cairo_move_to(cr, x, y - r * 1.15);
      cairo_line_to(cr, x + r, y + r * 0.75);
      cairo_line_to(cr, x - r, y + r * 0.75);
      cairo_close_path(cr);
      break;
    case 3:
      cairo_move_to(cr, x, y - r * 1.2);
      cairo_line_to(cr, x + r, y);
      cairo_line_to(cr, x, y + r * 1.2);
      cairo_line_to(cr, x - r, y);
      cairo_close_path(cr);
      break;
    default:
      cairo_set_line_width(cr, 1.8);
      cairo_move_to(cr, x - r, y - r);
      cairo_line_to(cr, x + r, y + r);
      cairo_move_to(cr, x - r, y + r);
      cairo_line_to(cr, x + r, y - r);
      cairo_stroke(cr);
      cairo_set_line_width(cr, kLineWidth);
      return;
  }
  cairo_fill(cr);
}

void drawCurves(cairo_t* cr, const Panel& panel, const PanelGeometry& g, const std::vector<std::string>& labels) {
  cairo_save(cr);
  // Clipped to the plot area, with room for half a line at its edges (a curve along y = 1 at the top).
  cairo_rectangle(cr, g.left, g.top - kLineWidth, g.width + kLineWidth, g.height + 2 * kLineWidth);
  cairo_clip(cr);
  cairo_set_source_rgb(cr, 0.45, 0.45, 0.45);
  cairo_set_line_width(cr, 1.2);
  const double dash[] = {5, 4};
  cairo_set_dash(cr, dash, 2, 0);
  for (double m : panel.marks) {
    cairo_move_to(cr, g.px(m), g.top);
    cairo_line_to(cr, g.px(m), g.top + g.height);
  }
  cairo_stroke(cr);
  cairo_set_dash(cr, nullptr, 0, 0);
  for (const Curve& c : panel.curves) {  // bands first, so that no band covers a line
    colour(cr, seriesColor(c.label, labels), kBandAlpha);
    for (std::size_t i = 0; i < c.x.size(); ++i) cairo_line_to(cr, g.px(c.x[i]), g.py(c.mean[i] + c.se[i]));
    for (std::size_t i = c.x.size(); i-- > 0;) cairo_line_to(cr, g.px(c.x[i]), g.py(c.mean[i] - c.se[i]));
    cairo_close_path(cr);
    cairo_fill(cr);
  }
  cairo_set_line_width(cr, kLineWidth);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  for (const Curve& c : panel.curves) {
    colour(cr, seriesColor(c.label, labels));
    for (std::size_t i = 0; i < c.x.size(); ++i) cairo_line_to(cr, g.px(c.x[i]), g.py(c.mean[i]));
    if (c.x.size() == 1) cairo_arc(cr, g.px(c.x[0]), g.py(c.mean[0]), 2.5, 0, 2 * M_PI);
    cairo_stroke(cr);
  }
  // Markers, each series its own shape at its own points (staggered by series), so that a curve drawn exactly over
  // another (two approaches that learn alike) still shows: up to kMarkersPerCurve per curve.
  for (const Curve& c : panel.curves) {
    const std::size_t series = seriesIndex(c.label, labels);
    const std::size_t every = std::max<std::size_t>(1, c.x.size() / kMarkersPerCurve);
    colour(cr, seriesColor(c.label, labels));
    for (std::size_t i = (series * every / std::max<std::size_t>(1, labels.size())) % every; i < c.x.size(); i += every)
      marker(cr, series, g.px(c.x[i]), g.py(c.mean[i]));
  }
  cairo_restore(cr);
}

// `s` in lines no wider than `width` (a word longer than that gets a line of its own), in the current font.
std::vector<std::string> wrapped(cairo_t* cr, const std::string& s, double width) {
  std::vector<std::string> lines;
  std::string line, word;
  std::istringstream words(s);
  while (words >> word) {
    const std::string candidate = line.empty() ? word : line + " " + word;
    cairo_text_extents_t e;
    cairo_text_extents(cr, candidate.c_str(), &e);
    if (e.x_advance > width && !line.empty()) {
      lines.push_back(line);
      line = word;
    } else {
      line = candidate;
    }
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

void drawBars(cairo_t* cr, const Panel& panel, const PanelGeometry& g, const std::vector<std::string>& labels) {
  const double slot = g.width / static_cast<double>(panel.bars.size());
  cairo_set_source_rgb(cr, kAxisGrey, kAxisGrey, kAxisGrey);
  cairo_set_line_width(cr, 1.0);
  cairo_move_to(cr, g.left, g.py(0));
  cairo_line_to(cr, g.left + g.width, g.py(0));
  cairo_stroke(cr);
  for (std::size_t i = 0; i < panel.bars.size(); ++i) {
    const Bar& b = panel.bars[i];
    const double centre = g.px(static_cast<double>(i) + 0.5);
    const double half = slot * 0.3;
    colour(cr, seriesColor(b.series, labels));
    cairo_rectangle(cr, centre - half, std::min(g.py(0), g.py(b.mean)), 2 * half, std::abs(g.py(b.mean) - g.py(0)));
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1.3);
    const double lo = g.py(b.mean - b.se), hi = g.py(b.mean + b.se);
    cairo_move_to(cr, centre, lo);
    cairo_line_to(cr, centre, hi);
    for (double y : {lo, hi}) {
      cairo_move_to(cr, centre - half * 0.35, y);
      cairo_line_to(cr, centre + half * 0.35, y);
    }
    cairo_stroke(cr);
    font(cr, kBarLabelFont);
    const auto lines = wrapped(cr, b.label, slot - 8);
    for (std::size_t l = 0; l < lines.size(); ++l)
      text(cr, lines[l], centre, g.top + g.height + 8 + kBarLabelFont * 1.25 * static_cast<double>(l), 0.5, 0);
  }
}

void drawLegend(cairo_t* cr, const FigureSpec& spec, const FigureLayout& layout,
                const std::vector<std::string>& labels) {
  font(cr, kLegendFont);
  for (const LegendEntry& e : layout.legend) {
    const Rgb c = seriesColor(e.label, labels);
    if (spec.kind == ChartKind::Bars) {
      colour(cr, c);
      cairo_rectangle(cr, e.x + 4, e.y - 6, 16, 12);
      cairo_fill(cr);
    } else {
      colour(cr, c, kBandAlpha);
      cairo_rectangle(cr, e.x, e.y - 6, 24, 12);
      cairo_fill(cr);
      colour(cr, c);
      cairo_set_line_width(cr, kLineWidth);
      cairo_move_to(cr, e.x, e.y);
      cairo_line_to(cr, e.x + 24, e.y);
      cairo_stroke(cr);
      marker(cr, seriesIndex(e.label, labels), e.x + 12, e.y);
    }
    cairo_set_source_rgb(cr, 0, 0, 0);
    text(cr, e.label, e.x + 30, e.y, 0, 0.5);
  }
}

void draw(cairo_t* cr, const FigureSpec& spec, const FigureLayout& layout) {
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  const auto labels = seriesLabels(spec);
  if (!spec.title.empty()) {
    cairo_set_source_rgb(cr, 0, 0, 0);
    font(cr, kTitleFont + 1, true);
    text(cr, spec.title, layout.width / 2, 8, 0.5, 0);
  }
  for (std::size_t i = 0; i < spec.panels.size(); ++i) {
    // Every panel shows the same y range (layoutFigure): the first one names it.
    drawAxes(cr, spec, spec.panels[i], layout.panels[i], i == 0);
    if (spec.kind == ChartKind::Bars)
      drawBars(cr, spec.panels[i], layout.panels[i], labels);
    else
      drawCurves(cr, spec.panels[i], layout.panels[i], labels);
  }
  drawLegend(cr, spec, layout, labels);
}

}  // namespace

void renderFigure(const FigureSpec& spec, const std::string& path) {
  const FigureLayout layout = layoutFigure(spec);
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  Surface surface(nullptr, cairo_surface_destroy);
  if (ext == ".png") {
    surface.reset(cairo_image_surface_create(CAIRO_FORMAT_RGB24, static_cast<int>(std::ceil(layout.width * kPngScale)),
                                             static_cast<int>(std::ceil(layout.height * kPngScale))));
  } else if (ext == ".svg") {
    surface.reset(cairo_svg_surface_create(path.c_str(), layout.width, layout.height));
  } else if (ext == ".pdf") {
    surface.reset(cairo_pdf_surface_create(path.c_str(), layout.width, layout.height));
  } else {
    throw PlotError(fmt::format("{}: unknown image format '{}' (use .png, .svg or .pdf)", path, ext));
  }
  if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS)
    throw PlotError(
        fmt::format("{}: cannot be written: {}", path, cairo_status_to_string(cairo_surface_status(surface.get()))));
  {
    Context cr(cairo_create(surface.get()), cairo_destroy);
    if (ext == ".png") cairo_scale(cr.get(), kPngScale, kPngScale);
    draw(cr.get(), spec, layout);
    if (cairo_status(cr.get()) != CAIRO_STATUS_SUCCESS)
      throw PlotError(fmt::format("{}: drawing failed: {}", path, cairo_status_to_string(cairo_status(cr.get()))));
  }
  cairo_status_t status = CAIRO_STATUS_SUCCESS;
  if (ext == ".png") {
    status = cairo_surface_write_to_png(surface.get(), path.c_str());
  } else {
    cairo_surface_finish(surface.get());
    status = cairo_surface_status(surface.get());
  }
  if (status != CAIRO_STATUS_SUCCESS)
    throw PlotError(fmt::format("{}: cannot be written: {}", path, cairo_status_to_string(status)));
}

}  // namespace cbtl::plot
