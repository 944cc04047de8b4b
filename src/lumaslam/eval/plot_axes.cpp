#include "lumaslam/eval/plot_axes.h"

#include <algorithm>
#include <cmath>

#include <spdlog/fmt/fmt.h>

namespace lumaslam::eval {

namespace {

// Tick spacing of 1, 2 or 5 times a power of ten giving about `count` ticks.
double niceStep(double span, int count) {
  const double raw = span / count;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double factor : {1.0, 2.0, 5.0}) {
    if (factor * power >= raw) return factor * power;
  }
  return 10.0 * power;
}

// Prints 0 instead of -1.38778e-17 for the tick at zero.
double cleanZero(double value, double step) {
  return std::abs(value) < 1e-9 * step ? 0.0 : value;
}

}  // namespace

Range padded(double min, double max) {
  if (!(max > min)) return {min - 0.5, max + 0.5};
  const double margin = 0.05 * (max - min);
  return {min - margin, max + margin};
}

void Axes::drawFrame(SvgDocument& svg, const std::string& x_label, const std::string& y_label,
                     const std::string& title) const {
  const SvgStyle grid = SvgStyle::stroked("#dddddd", 1.0);
  const SvgStyle tick = SvgStyle::stroked("black", 1.0);
  const double x_step = niceStep(x_.span(), 6);
  for (double x = std::ceil(x_.min / x_step) * x_step; x <= x_.max; x += x_step) {
    const Eigen::Vector2d bottom = toPixel(x, y_.min);
    svg.line(bottom, toPixel(x, y_.max), grid);
    svg.line(bottom, bottom + Eigen::Vector2d(0, 5), tick);
    svg.text(bottom + Eigen::Vector2d(0, 19), fmt::format("{:g}", cleanZero(x, x_step)),
             kPlotFontSize - 1, TextAnchor::Middle);
  }
  const double y_step = niceStep(y_.span(), 6);
  for (double y = std::ceil(y_.min / y_step) * y_step; y <= y_.max; y += y_step) {
    const Eigen::Vector2d left = toPixel(x_.min, y);
    svg.line(left, toPixel(x_.max, y), grid);
    svg.line(left, left - Eigen::Vector2d(5, 0), tick);
    svg.text(left + Eigen::Vector2d(-8, 4), fmt::format("{:g}", cleanZero(y, y_step)),
             kPlotFontSize - 1, TextAnchor::End);
  }
  svg.rect(origin_, size_.x(), size_.y(), tick);
  svg.text({origin_.x() + size_.x() / 2, origin_.y() + size_.y() + 40}, x_label, kPlotFontSize,
           TextAnchor::Middle);
  svg.text({origin_.x() - 55, origin_.y() + size_.y() / 2}, y_label, kPlotFontSize,
           TextAnchor::Middle, -90.0);
  svg.text({origin_.x() + size_.x() / 2, origin_.y() - 12}, title, kPlotFontSize + 2,
           TextAnchor::Middle);
}

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

}  // namespace lumaslam::eval
