// app/plot: summaries read back, figures laid out and drawn where the layout says, every format written, every
// bad input refused with a message naming it.
#include "app/plot/Chart.h"
#include "app/plot/ResultsFigure.h"
#include "app/plot/SummaryTable.h"

#include <cairo.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include <unistd.h>

namespace cbtl::plot {
namespace {

namespace fs = std::filesystem;

class PlotTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("cbtl-plot-test-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // An experiment folder with a summary.csv of the given rows (after the header).
  std::string experiment(const std::string& name, const std::string& rows) {
    const fs::path folder = dir_ / name;
    fs::create_directories(folder);
    std::ofstream(folder / "summary.csv")
        << "approach,training_step,seeds,eval_mean,eval_se,task_success_mean,preferences_met_mean\n"
        << rows;
    return folder.string();
  }
  fs::path dir_;
};

// The colour of the pixel at a point of the figure (points, as the layout gives them).
Rgb pixel(const std::string& png, double x, double y) {
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> s(cairo_image_surface_create_from_png(png.c_str()),
                                                                       cairo_surface_destroy);
  EXPECT_EQ(cairo_surface_status(s.get()), CAIRO_STATUS_SUCCESS);
  const int px = static_cast<int>(std::lround(x * kPngScale)), py = static_cast<int>(std::lround(y * kPngScale));
  const int stride = cairo_image_surface_get_stride(s.get());
  const auto* data = cairo_image_surface_get_data(s.get());
  const auto* p = reinterpret_cast<const std::uint32_t*>(data + py * stride) + px;
  return Rgb{((*p >> 16) & 0xff) / 255.0, ((*p >> 8) & 0xff) / 255.0, (*p & 0xff) / 255.0};
}

bool near(const Rgb& a, const Rgb& b, double tolerance = 0.06) {
  return std::abs(a.r - b.r) < tolerance && std::abs(a.g - b.g) < tolerance && std::abs(a.b - b.b) < tolerance;
}

TEST_F(PlotTest, ReadsASummaryAndSaysWhereOneIsWrong) {
  const auto folder =
      experiment("fig", "no-personalization,0,3,-1,0,1,0\ncbtl,100,3,0.5,0.1,1,0.5\ncbtl,0,3,-1,0,1,0\n");
  const SummaryTable t = readSummary(folder);
  ASSERT_EQ(t.approaches, (std::vector<std::string>{"no-personalization", "cbtl"}));
  ASSERT_EQ(t.byApproach.at("cbtl").size(), 2u);
  EXPECT_EQ(t.byApproach.at("cbtl")[0].step, 0) << "checkpoints are sorted by step";
  EXPECT_DOUBLE_EQ(t.byApproach.at("cbtl")[1].evalSe, 0.1);

  EXPECT_THROW(readSummary((dir_ / "nothing").string()), ResultsError);
  const auto bad = experiment("bad", "cbtl,0,3,nan,0,1,0\n");
  try {
    readSummary(bad);
    FAIL() << "a NaN was accepted";
  } catch (const ResultsError& e) {
    EXPECT_NE(std::string(e.what()).find("summary.csv:2: eval_mean is not a finite number: 'nan'"), std::string::npos)
        << e.what();
  }
  const auto shortRow = experiment("short", "cbtl,0,3\n");
  EXPECT_THROW(readSummary(shortRow), ResultsError);
  std::ofstream(dir_ / "other.csv") << "a,b\n1,2\n";
  EXPECT_THROW(readSummary((dir_ / "other.csv").string()), ResultsError);

  // A single run's folder: its eval.csv, named by its approach.
  fs::create_directories(dir_ / "run");
  std::ofstream(dir_ / "run" / "config.json") << "{\n  \"approach\": \"free-explore\",\n  \"seed\": 3\n}\n";
  std::ofstream(dir_ / "run" / "eval.csv")
      << "training_step,eval_mean_user_satisfaction,eval_task_success_rate,eval_preferences_met_rate\n0,-1,1,0\n"
         "100,0.4,1,0.7\n";
  const SummaryTable run = readSummary((dir_ / "run").string());
  ASSERT_EQ(run.approaches, std::vector<std::string>{"free-explore"});
  ASSERT_EQ(run.byApproach.at("free-explore").size(), 2u);
  EXPECT_DOUBLE_EQ(run.byApproach.at("free-explore")[1].preferencesMet, 0.7);
}

TEST_F(PlotTest, CurvesAreDrawnWhereTheLayoutPutsThemInTheirApproachColour) {
  FigureSpec spec;
  Panel panel;
  panel.title = "Cooking";
  panel.curves.push_back(Curve{"cbtl", {0, 1000}, {0.5, 0.5}, {0.2, 0.2}});
  panel.curves.push_back(Curve{"no-personalization", {0, 1000}, {-0.5, -0.5}, {0, 0}});
  spec.panels = {panel};
  spec.yMin = -1;
  spec.yMax = 1;
  const std::string png = (dir_ / "curves.png").string();
  renderFigure(spec, png);
  const FigureLayout layout = layoutFigure(spec);
  const PanelGeometry& g = layout.panels.at(0);
  const auto labels = seriesLabels(spec);
  EXPECT_TRUE(near(pixel(png, g.px(500), g.py(0.5)), seriesColor("cbtl", labels)));
  EXPECT_TRUE(near(pixel(png, g.px(500), g.py(-0.5)), seriesColor("no-personalization", labels)));
  // Inside cbtl's standard-error band (0.3 .. 0.7), away from its line: a light tint of its colour.
  const Rgb band = pixel(png, g.px(500), g.py(0.62));
  const Rgb blue = seriesColor("cbtl", labels);
  EXPECT_TRUE(near(band, Rgb{1 - 0.2 * (1 - blue.r), 1 - 0.2 * (1 - blue.g), 1 - 0.2 * (1 - blue.b)}, 0.04));
  EXPECT_TRUE(near(pixel(png, g.px(500), g.py(0.85)), Rgb{1, 1, 1}, 0.02)) << "above the band: white";
  // The approaches keep their colours in every figure; other labels take free palette colours.
  EXPECT_TRUE(near(seriesColor("first", {"first", "second"}), seriesColor("cbtl", {}), 1e-9));
  EXPECT_FALSE(near(seriesColor("first", {"cbtl", "first"}), seriesColor("cbtl", {}), 1e-9));
}

TEST_F(PlotTest, BarsStandOnZeroInTheirSeriesColour) {
  FigureSpec spec;
  spec.kind = ChartKind::Bars;
  Panel panel;
  panel.bars = {Bar{"with replanning", "cbtl", 0.8, 0.05}, Bar{"no personalization", "no-personalization", -0.6, 0.1}};
  spec.panels = {panel};
  const std::string png = (dir_ / "bars.png").string();
  renderFigure(spec, png);
  const FigureLayout layout = layoutFigure(spec);
  const PanelGeometry& g = layout.panels.at(0);
  const auto labels = seriesLabels(spec);
  EXPECT_LE(g.yMin, -0.7);
  EXPECT_GE(g.yMax, 0.85);
  EXPECT_TRUE(near(pixel(png, g.px(0.5) - 10, g.py(0.4)), seriesColor("cbtl", labels)));
  EXPECT_TRUE(near(pixel(png, g.px(1.5) - 10, g.py(-0.3)), seriesColor("no-personalization", labels)));
  EXPECT_TRUE(near(pixel(png, g.px(0.5) - 10, g.py(-0.3)), Rgb{1, 1, 1}, 0.02)) << "no bar below zero there";
}

TEST_F(PlotTest, EveryFormatIsWrittenAndBadRequestsAreRefused) {
  FigureSpec spec;
  spec.panels = {Panel{"", {Curve{"cbtl", {0, 1}, {0, 1}, {0, 0}}}, {}, {0.5}}};
  for (const char* ext : {".png", ".svg", ".pdf"}) {
    const fs::path out = dir_ / (std::string("figure") + ext);
    renderFigure(spec, out.string());
    std::ifstream in(out, std::ios::binary);
    std::string head(8, '\0');
    in.read(head.data(), 8);
    const std::string expected = std::string(ext) == ".png"   ? "\x89PNG"
                                 : std::string(ext) == ".svg" ? "<?xml"
                                                              : "%PDF-";
    EXPECT_EQ(head.substr(0, expected.size()), expected) << ext;
  }
  EXPECT_THROW(renderFigure(spec, (dir_ / "figure.jpg").string()), PlotError);
  EXPECT_THROW(renderFigure(spec, (dir_ / "no" / "such" / "folder.png").string()), PlotError);
  FigureSpec empty;
  EXPECT_THROW(layoutFigure(empty), PlotError);
  FigureSpec ragged = spec;
  ragged.panels[0].curves[0].se = {0};
  EXPECT_THROW(layoutFigure(ragged), PlotError);
  FigureSpec infinite = spec;
  infinite.panels[0].curves[0].mean[1] = INFINITY;
  EXPECT_THROW(layoutFigure(infinite), PlotError);
  FigureSpec inverted = spec;
  inverted.yMin = 1;
  inverted.yMax = -1;
  EXPECT_THROW(layoutFigure(inverted), PlotError);
}

TEST_F(PlotTest, FiguresFromResultsFollowTheRequest) {
  const auto a = experiment("no-adapt", "cbtl,0,2,-1,0,1,0\ncbtl,100,2,0.5,0.1,1,0.5\n");
  const auto b = experiment("user-reset",
                            "cbtl,0,2,-1,0,1,0\ncbtl,100,2,0.9,0.05,1,0.9\nno-personalization,0,2,-1,0,1,0\n"
                            "no-personalization,100,2,-1,0,1,0\n");
  FigureRequest r;
  r.results = {a, b};
  FigureSpec spec = figureFromResults(r);
  ASSERT_EQ(spec.panels.size(), 2u);
  EXPECT_EQ(spec.panels[0].title, "no-adapt");
  EXPECT_EQ(spec.panels[1].curves.size(), 2u);
  r.together = true;
  r.labels = {"no adaptation", "user reset"};
  r.marks = {50};
  spec = figureFromResults(r);
  ASSERT_EQ(spec.panels.size(), 1u);
  ASSERT_EQ(spec.panels[0].curves.size(), 3u);
  EXPECT_EQ(spec.panels[0].curves[0].label, "no adaptation");
  EXPECT_EQ(spec.panels[0].curves[1].label, "CBTL (user reset)");
  EXPECT_EQ(spec.panels[0].marks, std::vector<double>{50});
  r.kind = ChartKind::Bars;
  r.atStep = 100;
  r.metric = Metric::PreferencesMet;
  spec = figureFromResults(r);
  ASSERT_EQ(spec.panels[0].bars.size(), 3u);
  EXPECT_DOUBLE_EQ(spec.panels[0].bars[1].mean, 0.9);
  EXPECT_EQ(spec.panels[0].bars[2].series, "No Personalization");
  EXPECT_EQ(spec.panels[0].bars[0].label, "CBTL (no adaptation)") << "a bar names its approach";
  EXPECT_EQ(spec.panels[0].title, "at training step 100") << "a bar chart says which checkpoint it shows";
  r.atStep = 50;
  EXPECT_THROW(figureFromResults(r), PlotError) << "50 is no checkpoint";
  r.atStep.reset();
  r.labels = {"one"};
  EXPECT_THROW(figureFromResults(r), PlotError) << "one label for two folders";
  r.labels.clear();
  r.approaches = {"epsilon-greedy"};
  EXPECT_THROW(figureFromResults(r), PlotError) << "no such approach";
}

}  // namespace
}  // namespace cbtl::plot
