#include "lumaslam/eval/trajectory_plot.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <spdlog/fmt/fmt.h>

#include "lumaslam/core/error.h"
#include "lumaslam/eval/plot_axes.h"

namespace lumaslam::eval {

namespace {

constexpr double kWidth = 1100.0;
constexpr double kHeight = 520.0;
constexpr double kFontSize = kPlotFontSize;
const char* const kAxisNames[] = {"x", "y", "z"};
const Eigen::Vector2d kLeftPanel(80, 60);
const Eigen::Vector2d kRightPanel(640, 60);
const Eigen::Vector2d kPanelSize(420, 400);

std::vector<double> stampsOf(const Trajectory& trajectory) {
  std::vector<double> stamps;
  for (const StampedPose& pose : trajectory) stamps.push_back(pose.timestamp);
  return stamps;
}

void drawPath(SvgDocument& svg, const Axes& axes, const Trajectory& trajectory,
              const std::array<int, 2>& plane, const SvgStyle& style) {
  for (const auto& [begin, end] : continuousRuns(stampsOf(trajectory))) {
    std::vector<Eigen::Vector2d> points;
    for (std::size_t i = begin; i < end; ++i) {
      const Eigen::Vector3d p = trajectory[i].T_w_c.translation();
      points.push_back(axes.toPixel(p(plane[0]), p(plane[1])));
    }
    svg.polyline(points, style);
  }
}

void drawLegendEntry(SvgDocument& svg, Eigen::Vector2d at, const SvgStyle& style,
                     const std::string& label) {
  svg.line(at, at + Eigen::Vector2d(24, 0), style);
  svg.text(at + Eigen::Vector2d(30, 4), label, kFontSize - 1);
}

// Both trajectories' ranges along the plane's axes, widened to one scale on both axes.
std::array<Range, 2> equalScaleRanges(const EvaluationReport& report,
                                      const std::array<int, 2>& plane) {
  std::array<Range, 2> ranges;
  for (int k = 0; k < 2; ++k) {
    double min = INFINITY;
    double max = -INFINITY;
    for (const Trajectory* trajectory : {&report.ground_truth, &report.aligned_estimate}) {
      for (const StampedPose& pose : *trajectory) {
        min = std::min(min, pose.T_w_c.translation()(plane[k]));
        max = std::max(max, pose.T_w_c.translation()(plane[k]));
      }
    }
    ranges[k] = padded(min, max);
  }
  const double metres_per_pixel =
      std::max(ranges[0].span() / kPanelSize.x(), ranges[1].span() / kPanelSize.y());
  for (int k = 0; k < 2; ++k) {
    const double centre = 0.5 * (ranges[k].min + ranges[k].max);
    const double half = 0.5 * metres_per_pixel * kPanelSize(k);
    ranges[k] = {centre - half, centre + half};
  }
  return ranges;
}

void drawLegend(SvgDocument& svg, Eigen::Vector2d origin, const SvgStyle& ground_truth_style,
                const SvgStyle& estimate_style) {
  const Eigen::Vector2d legend = origin + Eigen::Vector2d(12, 18);
  svg.rect(legend - Eigen::Vector2d(6, 12), 150, 62, SvgStyle::filled("white", "#999999", 0.8));
  drawLegendEntry(svg, legend, ground_truth_style, "ground truth");
  drawLegendEntry(svg, legend + Eigen::Vector2d(0, 18), estimate_style, "estimate");
  svg.circle(legend + Eigen::Vector2d(12, 36), 4, SvgStyle::filled("#2ca02c", "black", 1.0));
  svg.text(legend + Eigen::Vector2d(30, 40), "start", kFontSize - 1);
}

// The aligned estimate over ground truth projected on `plane` (axis indices), equal scale.
void drawPlaneView(SvgDocument& svg, const EvaluationReport& report,
                   const std::array<int, 2>& plane, Eigen::Vector2d origin,
                   const std::string& title) {
  const std::array<Range, 2> ranges = equalScaleRanges(report, plane);
  const Axes axes(origin, kPanelSize, ranges[0], ranges[1]);
  axes.drawFrame(svg, fmt::format("{} [m]", kAxisNames[plane[0]]),
                 fmt::format("{} [m]", kAxisNames[plane[1]]),
                 fmt::format("{} ({}-{} plane, aligned {})", title, kAxisNames[plane[0]],
                             kAxisNames[plane[1]], toString(report.alignment.mode)));

  const SvgStyle ground_truth_style = SvgStyle::stroked("#555555", 2.0, "6 3");
  const SvgStyle estimate_style = SvgStyle::stroked("#1f77b4", 1.6);
  drawPath(svg, axes, report.ground_truth, plane, ground_truth_style);
  drawPath(svg, axes, report.aligned_estimate, plane, estimate_style);
  const Eigen::Vector3d start = report.ground_truth.front().T_w_c.translation();
  svg.circle(axes.toPixel(start(plane[0]), start(plane[1])), 4,
             SvgStyle::filled("#2ca02c", "black", 1.0));
  drawLegend(svg, origin, ground_truth_style, estimate_style);
}

void drawErrorOverTime(SvgDocument& svg, const EvaluationReport& report, Eigen::Vector2d origin) {
  const std::vector<double>& stamps = report.ate.timestamps;
  const std::vector<double>& errors = report.ate.errors;
  const double t0 = stamps.front();
  const double max_error = *std::max_element(errors.begin(), errors.end());
  const Range time_range = padded(0.0, stamps.back() - t0);
  const Range error_range{0.0, max_error > 0.0 ? 1.1 * max_error : 1.0};
  const Axes axes(origin, kPanelSize, time_range, error_range);
  axes.drawFrame(svg, "time [s]", "ATE [m]",
                 fmt::format("ATE along time (rmse {:.4g} m, {} poses)", report.ate.stats.rmse,
                             report.ate.stats.count));

  const SvgStyle error_style = SvgStyle::stroked("#d62728", 1.4);
  for (const auto& [begin, end] : continuousRuns(stamps)) {
    std::vector<Eigen::Vector2d> points;
    for (std::size_t i = begin; i < end; ++i) {
      points.push_back(axes.toPixel(stamps[i] - t0, errors[i]));
    }
    svg.polyline(points, error_style);
  }
  const double rmse = report.ate.stats.rmse;
  svg.line(axes.toPixel(time_range.min, rmse), axes.toPixel(time_range.max, rmse),
           SvgStyle::stroked("#333333", 1.0, "4 3"));
  svg.text(axes.toPixel(time_range.max, rmse) + Eigen::Vector2d(-4, -5), "rmse", kFontSize - 1,
           TextAnchor::End);
}

void requireMatchedPoses(const EvaluationReport& report) {
  if (report.ground_truth.empty() || report.ate.errors.empty()) {
    fail("plot: the evaluation report has no matched poses");
  }
}

}  // namespace

std::array<int, 2> planeOfLargestExtent(const Trajectory& a, const Trajectory& b) {
  Eigen::Vector3d min = Eigen::Vector3d::Constant(INFINITY);
  Eigen::Vector3d max = Eigen::Vector3d::Constant(-INFINITY);
  for (const Trajectory* trajectory : {&a, &b}) {
    for (const StampedPose& pose : *trajectory) {
      min = min.cwiseMin(pose.T_w_c.translation());
      max = max.cwiseMax(pose.T_w_c.translation());
    }
  }
  const Eigen::Vector3d extent = (max - min).cwiseMax(0.0);
  // Drop the axis of least extent; ties keep x-y (z-up convention).
  int smallest = 2;
  for (int axis = 1; axis >= 0; --axis) {
    if (extent(axis) < extent(smallest)) smallest = axis;
  }
  if (smallest == 0) return {1, 2};
  if (smallest == 1) return {0, 2};
  return {0, 1};
}

std::array<int, 2> sidePlane(const std::array<int, 2>& top) {
  const int dropped = 3 - top[0] - top[1];
  return {top[0], dropped};
}

SvgDocument plotEvaluation(const EvaluationReport& report) {
  requireMatchedPoses(report);
  SvgDocument svg(kWidth, kHeight);
  drawPlaneView(svg, report, planeOfLargestExtent(report.ground_truth, report.aligned_estimate),
                kLeftPanel, "Trajectory");
  drawErrorOverTime(svg, report, kRightPanel);
  return svg;
}

SvgDocument plotTrajectoryViews(const EvaluationReport& report) {
  requireMatchedPoses(report);
  const std::array<int, 2> top = planeOfLargestExtent(report.ground_truth, report.aligned_estimate);
  SvgDocument svg(kWidth, kHeight);
  drawPlaneView(svg, report, top, kLeftPanel, "Top view");
  drawPlaneView(svg, report, sidePlane(top), kRightPanel, "Side view");
  return svg;
}

SvgDocument plotErrorOverTime(const EvaluationReport& report) {
  requireMatchedPoses(report);
  SvgDocument svg(kRightPanel.x(), kHeight);
  drawErrorOverTime(svg, report, kLeftPanel);
  return svg;
}

void writeEvaluationPlot(const std::filesystem::path& path, const EvaluationReport& report) {
  plotEvaluation(report).save(path);
}

}  // namespace lumaslam::eval
