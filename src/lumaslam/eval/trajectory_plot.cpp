#include "lumaslam/eval/trajectory_plot.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <spdlog/fmt/fmt.h>

#include "lumaslam/core/error.h"

namespace lumaslam::eval {

namespace {

constexpr double kWidth = 1100.0;
constexpr double kHeight = 520.0;
constexpr double kFontSize = 13.0;
const char* const kAxisNames[] = {"x", "y", "z"};

struct Range {
  double min = 0.0;
  double max = 1.0;
  double span() const { return max - min; }
};

// Tick spacing of 1, 2 or 5 times a power of ten giving about `count` ticks.
double niceStep(double span, int count) {
  const double raw = span / count;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double factor : {1.0, 2.0, 5.0}) {
    if (factor * power >= raw) return factor * power;
  }
  return 10.0 * power;
}

Range padded(double min, double max) {
  if (!(max > min)) return {min - 0.5, max + 0.5};
  const double margin = 0.05 * (max - min);
  return {min - margin, max + margin};
}

// A data rectangle drawn into a pixel rectangle (y grows upwards in data, downwards in SVG).
class Axes {
 public:
  Axes(Eigen::Vector2d origin, Eigen::Vector2d size, Range x, Range y)
      : origin_(origin), size_(size), x_(x), y_(y) {}

  Eigen::Vector2d toPixel(double x, double y) const {
    return {origin_.x() + (x - x_.min) / x_.span() * size_.x(),
            origin_.y() + size_.y() - (y - y_.min) / y_.span() * size_.y()};
  }

  void drawFrame(SvgDocument& svg, const std::string& x_label, const std::string& y_label,
                 const std::string& title) const {
    const SvgStyle grid = SvgStyle::stroked("#dddddd", 1.0);
    const SvgStyle tick = SvgStyle::stroked("black", 1.0);
    const double x_step = niceStep(x_.span(), 6);
    for (double x = std::ceil(x_.min / x_step) * x_step; x <= x_.max; x += x_step) {
      const Eigen::Vector2d bottom = toPixel(x, y_.min);
      svg.line(bottom, toPixel(x, y_.max), grid);
      svg.line(bottom, bottom + Eigen::Vector2d(0, 5), tick);
      svg.text(bottom + Eigen::Vector2d(0, 19), fmt::format("{:g}", cleanZero(x, x_step)),
               kFontSize - 1, TextAnchor::Middle);
    }
    const double y_step = niceStep(y_.span(), 6);
    for (double y = std::ceil(y_.min / y_step) * y_step; y <= y_.max; y += y_step) {
      const Eigen::Vector2d left = toPixel(x_.min, y);
      svg.line(left, toPixel(x_.max, y), grid);
      svg.line(left, left - Eigen::Vector2d(5, 0), tick);
      svg.text(left + Eigen::Vector2d(-8, 4), fmt::format("{:g}", cleanZero(y, y_step)),
               kFontSize - 1, TextAnchor::End);
    }
    svg.rect(origin_, size_.x(), size_.y(), tick);
    svg.text({origin_.x() + size_.x() / 2, origin_.y() + size_.y() + 40}, x_label, kFontSize,
             TextAnchor::Middle);
    svg.text({origin_.x() - 55, origin_.y() + size_.y() / 2}, y_label, kFontSize,
             TextAnchor::Middle, -90.0);
    svg.text({origin_.x() + size_.x() / 2, origin_.y() - 12}, title, kFontSize + 2,
             TextAnchor::Middle);
  }

 private:
  // Prints 0 instead of -1.38778e-17 for the tick at zero.
  static double cleanZero(double value, double step) {
    return std::abs(value) < 1e-9 * step ? 0.0 : value;
  }

  Eigen::Vector2d origin_;
  Eigen::Vector2d size_;
  Range x_;
  Range y_;
};

// Index ranges [begin, end) of the runs without a time gap (lost tracking) longer than five
// times the median step, so that plots do not draw straight lines across gaps.
std::vector<std::pair<std::size_t, std::size_t>> continuousRuns(const std::vector<double>& stamps) {
  if (stamps.size() < 3) return {{0, stamps.size()}};
  std::vector<double> steps;
  for (std::size_t i = 1; i < stamps.size(); ++i) steps.push_back(stamps[i] - stamps[i - 1]);
  std::vector<double> sorted = steps;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double gap = 5.0 * sorted[sorted.size() / 2];
  std::vector<std::pair<std::size_t, std::size_t>> runs;
  std::size_t begin = 0;
  for (std::size_t i = 1; i < stamps.size(); ++i) {
    if (steps[i - 1] > gap) {
      runs.emplace_back(begin, i);
      begin = i;
    }
  }
  runs.emplace_back(begin, stamps.size());
  return runs;
}

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

void drawTopView(SvgDocument& svg, const EvaluationReport& report) {
  const std::array<int, 2> plane =
      planeOfLargestExtent(report.ground_truth, report.aligned_estimate);
  Range ranges[2];
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
  // Equal scale on both axes: widen the narrower range about its centre.
  const Eigen::Vector2d origin(80, 60);
  const Eigen::Vector2d size(420, 400);
  const double metres_per_pixel =
      std::max(ranges[0].span() / size.x(), ranges[1].span() / size.y());
  for (int k = 0; k < 2; ++k) {
    const double centre = 0.5 * (ranges[k].min + ranges[k].max);
    const double half = 0.5 * metres_per_pixel * size(k);
    ranges[k] = {centre - half, centre + half};
  }
  const Axes axes(origin, size, ranges[0], ranges[1]);
  axes.drawFrame(svg, fmt::format("{} [m]", kAxisNames[plane[0]]),
                 fmt::format("{} [m]", kAxisNames[plane[1]]),
                 fmt::format("Trajectory ({}-{} plane, aligned {})", kAxisNames[plane[0]],
                             kAxisNames[plane[1]], toString(report.alignment.mode)));

  const SvgStyle ground_truth_style = SvgStyle::stroked("#555555", 2.0, "6 3");
  const SvgStyle estimate_style = SvgStyle::stroked("#1f77b4", 1.6);
  drawPath(svg, axes, report.ground_truth, plane, ground_truth_style);
  drawPath(svg, axes, report.aligned_estimate, plane, estimate_style);
  const Eigen::Vector3d start = report.ground_truth.front().T_w_c.translation();
  svg.circle(axes.toPixel(start(plane[0]), start(plane[1])), 4,
             SvgStyle::filled("#2ca02c", "black", 1.0));

  const Eigen::Vector2d legend = origin + Eigen::Vector2d(12, 18);
  svg.rect(legend - Eigen::Vector2d(6, 12), 150, 62, SvgStyle::filled("white", "#999999", 0.8));
  drawLegendEntry(svg, legend, ground_truth_style, "ground truth");
  drawLegendEntry(svg, legend + Eigen::Vector2d(0, 18), estimate_style, "estimate");
  svg.circle(legend + Eigen::Vector2d(12, 36), 4, SvgStyle::filled("#2ca02c", "black", 1.0));
  svg.text(legend + Eigen::Vector2d(30, 40), "start", kFontSize - 1);
}

void drawErrorOverTime(SvgDocument& svg, const EvaluationReport& report) {
  const std::vector<double>& stamps = report.ate.timestamps;
  const std::vector<double>& errors = report.ate.errors;
  const double t0 = stamps.front();
  const double max_error = *std::max_element(errors.begin(), errors.end());
  const Range time_range = padded(0.0, stamps.back() - t0);
  const Range error_range{0.0, max_error > 0.0 ? 1.1 * max_error : 1.0};
  const Axes axes({640, 60}, {420, 400}, time_range, error_range);
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

SvgDocument plotEvaluation(const EvaluationReport& report) {
  if (report.ground_truth.empty() || report.ate.errors.empty()) {
    fail("plot: the evaluation report has no matched poses");
  }
  SvgDocument svg(kWidth, kHeight);
  drawTopView(svg, report);
  drawErrorOverTime(svg, report);
  return svg;
}

void writeEvaluationPlot(const std::filesystem::path& path, const EvaluationReport& report) {
  plotEvaluation(report).save(path);
}

}  // namespace lumaslam::eval
