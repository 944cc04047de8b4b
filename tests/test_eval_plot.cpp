#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "lumaslam/core/error.h"
#include "lumaslam/eval/evaluation.h"
#include "lumaslam/eval/series_plot.h"
#include "lumaslam/eval/svg_document.h"
#include "lumaslam/eval/trajectory_plot.h"
#include "test_eval_synthetic.h"
#include "test_paths.h"

namespace lumaslam::eval {
namespace {

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(SvgDocument, WritesWellFormedElementsAndEscapesText) {
  SvgDocument svg(200, 100);
  svg.line({0, 0}, {10, 10}, SvgStyle::stroked("red", 2.0, "4 3"));
  svg.polyline({{0, 0}, {5, 5}, {10, 0}}, SvgStyle::stroked("blue", 1.0));
  svg.text({5, 5}, "a < b & \"c\"", 12, TextAnchor::Middle, -90.0);
  const std::string text = svg.str();
  EXPECT_EQ(text.rfind("<?xml", 0), 0u);
  EXPECT_NE(text.find(R"(width="200" height="100")"), std::string::npos);
  EXPECT_NE(text.find(R"(stroke-dasharray="4 3")"), std::string::npos);
  EXPECT_NE(text.find(R"(points="0.00,0.00 5.00,5.00 10.00,0.00")"), std::string::npos);
  EXPECT_NE(text.find("a &lt; b &amp; &quot;c&quot;"), std::string::npos);
  EXPECT_NE(text.find(R"re(transform="rotate(-90.0 5.00 5.00)")re"), std::string::npos);
  EXPECT_EQ(text.substr(text.size() - 7), "</svg>\n");
}

TEST(TrajectoryPlot, ChoosesThePlaneOfLargestExtent) {
  // KITTI-like: the camera drives along z and x, y (down) barely changes.
  Trajectory drive = test::straightLine(50, 1.0);
  for (std::size_t i = 0; i < drive.size(); ++i) {
    drive[i].T_w_c.translation().x() = 0.2 * static_cast<double>(i);
    drive[i].T_w_c.translation().y() = 0.01 * std::sin(static_cast<double>(i));
  }
  EXPECT_EQ(planeOfLargestExtent(drive, drive), (std::array<int, 2>{0, 2}));
  // The helix spreads 4 m in x and y and 1.5 m in z.
  const Trajectory helix = test::helix(300);
  EXPECT_EQ(planeOfLargestExtent(helix, helix), (std::array<int, 2>{0, 1}));
}

TEST(TrajectoryPlot, DrawsBothPanelsWithLabelsAndBreaksAtTrackingGaps) {
  Trajectory ground_truth = test::helix(300);
  Trajectory estimate = test::withPositionNoise(ground_truth, 0.02, 3);
  estimate.erase(estimate.begin() + 100, estimate.begin() + 150);  // tracking lost for 2.5 s
  const EvaluationReport report = evaluate(estimate, ground_truth, {});

  const std::string svg = plotEvaluation(report).str();
  EXPECT_NE(svg.find(">x [m]<"), std::string::npos);
  EXPECT_NE(svg.find(">y [m]<"), std::string::npos);
  EXPECT_NE(svg.find(">time [s]<"), std::string::npos);
  EXPECT_NE(svg.find(">ATE [m]<"), std::string::npos);
  EXPECT_NE(svg.find(">ground truth<"), std::string::npos);
  EXPECT_NE(svg.find(">estimate<"), std::string::npos);
  // Ground truth, estimate and ATE curves, each in two runs around the gap.
  EXPECT_EQ(count(svg, "<polyline"), 6u);
  // Every coordinate the plot writes is a finite number inside the canvas.
  const std::regex coordinate(R"re((?:x|y|x1|y1|x2|y2|cx|cy)="(-?[0-9.]+)")re");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), coordinate);
       it != std::sregex_iterator(); ++it) {
    const double value = std::stod((*it)[1]);
    EXPECT_GE(value, 0.0);
    EXPECT_LE(value, 1100.0);
  }

  test::TempDir dir("eval_plot");
  const auto path = dir.path() / "plot.svg";
  writeEvaluationPlot(path, report);
  std::ifstream file(path);
  std::stringstream written;
  written << file.rdbuf();
  EXPECT_EQ(written.str(), svg);
  // Written as an io::OutputFile: missing folders are created, a file in the way is an Error.
  writeEvaluationPlot(dir.path() / "new_dir" / "plot.svg", report);
  EXPECT_TRUE(std::filesystem::is_regular_file(dir.path() / "new_dir" / "plot.svg"));
  EXPECT_THROW(writeEvaluationPlot(path / "plot.svg", report), Error);
}

TEST(TrajectoryPlot, TopAndSideViewsAndErrorAlongTime) {
  EXPECT_EQ(sidePlane({0, 1}), (std::array<int, 2>{0, 2}));
  EXPECT_EQ(sidePlane({0, 2}), (std::array<int, 2>{0, 1}));
  EXPECT_EQ(sidePlane({1, 2}), (std::array<int, 2>{1, 0}));
  const Trajectory ground_truth = test::helix(300);
  const EvaluationReport report =
      evaluate(test::withPositionNoise(ground_truth, 0.02, 3), ground_truth, {});

  const SvgDocument views = plotTrajectoryViews(report);
  const std::string svg = views.element();
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);  // no XML declaration: for inline use
  EXPECT_EQ(views.str(), "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n" + svg);
  EXPECT_NE(svg.find(">Top view (x-y plane, aligned se3)<"), std::string::npos);
  EXPECT_NE(svg.find(">Side view (x-z plane, aligned se3)<"), std::string::npos);
  EXPECT_EQ(count(svg, "<polyline"), 4u);  // ground truth and estimate in each view
  const std::string errors = plotErrorOverTime(report).element();
  EXPECT_NE(errors.find(">ATE [m]<"), std::string::npos);
  EXPECT_EQ(count(errors, "<polyline"), 1u);
  EXPECT_THROW(plotTrajectoryViews(EvaluationReport{}), Error);
}

TEST(SeriesPlot, DrawsEverySeriesAndRefusesMismatchedSizes) {
  SeriesPlot plot{"Total", "frame", "ms", {{"total", "#1f77b4", {0, 1, 2}, {5, 7, 6}}}};
  const std::string svg = plotSeries(plot).element();
  EXPECT_EQ(count(svg, "<polyline"), 1u);
  EXPECT_NE(svg.find(">Total<"), std::string::npos);
  EXPECT_NE(svg.find(">total<"), std::string::npos);
  plot.series.front().y.pop_back();
  EXPECT_THROW(plotSeries(plot), Error);
  EXPECT_THROW(plotSeries(SeriesPlot{}), Error);
}

TEST(SeriesPlot, StateStripHasOneCellPerRunOfEqualStates) {
  const std::vector<StripState> legend = {{"ok", "green"}, {"lost", "red"}};
  const std::vector<double> x = {0, 1, 2, 3, 4, 5};
  const std::string svg = plotStateStrip("State", "frame", x, {0, 0, 1, 1, 1, 0}, legend).element();
  EXPECT_EQ(count(svg, R"(fill="green")"), 3u);  // two runs and the legend's square
  EXPECT_EQ(count(svg, R"(fill="red")"), 2u);    // one run and the legend's square
  EXPECT_NE(svg.find(">ok: 3<"), std::string::npos);
  EXPECT_NE(svg.find(">lost: 3<"), std::string::npos);
  EXPECT_THROW(plotStateStrip("State", "frame", x, {0, 2, 0, 0, 0, 0}, legend), Error);
  EXPECT_THROW(plotStateStrip("State", "frame", x, {0}, legend), Error);
}

}  // namespace
}  // namespace lumaslam::eval
