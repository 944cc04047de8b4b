#include "lumaslam/eval/series_plot.h"

#include <algorithm>
#include <cmath>

#include <spdlog/fmt/fmt.h>

#include "lumaslam/core/error.h"
#include "lumaslam/eval/plot_axes.h"

namespace lumaslam::eval {

namespace {

constexpr double kWidth = 1100.0;
const Eigen::Vector2d kOrigin(80, 40);

struct Bounds {
  Range x{INFINITY, -INFINITY};
  Range y{INFINITY, -INFINITY};
};

Bounds boundsOf(const std::vector<Series>& series) {
  Bounds bounds;
  for (const Series& s : series) {
    if (s.x.size() != s.y.size()) fail("plot '{}': x and y differ in size", s.label);
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      bounds.x = {std::min(bounds.x.min, s.x[i]), std::max(bounds.x.max, s.x[i])};
      bounds.y = {std::min(bounds.y.min, s.y[i]), std::max(bounds.y.max, s.y[i])};
    }
  }
  if (!(bounds.x.max >= bounds.x.min)) fail("plot: no point to draw");
  return bounds;
}

void drawSeriesLegend(SvgDocument& svg, const std::vector<Series>& series) {
  Eigen::Vector2d at = kOrigin + Eigen::Vector2d(12, 18);
  for (const Series& s : series) {
    svg.line(at, at + Eigen::Vector2d(24, 0), SvgStyle::stroked(s.colour, 2.0));
    svg.text(at + Eigen::Vector2d(30, 4), s.label, kPlotFontSize - 1);
    at.y() += 18;
  }
}

void requireValidStrip(const std::vector<double>& x, const std::vector<int>& states,
                       const std::vector<StripState>& legend) {
  if (x.empty()) fail("strip: no sample to draw");
  if (x.size() != states.size()) fail("strip: {} positions for {} states", x.size(), states.size());
  for (const int state : states) {
    if (state < 0 || state >= static_cast<int>(legend.size())) {
      fail("strip: state {} outside the legend's {} entries", state, legend.size());
    }
  }
}

// One rectangle per run of equal states, from the run's first x to the x after its last.
void drawStripCells(SvgDocument& svg, const Axes& axes, const std::vector<double>& x,
                    const std::vector<int>& states, const std::vector<StripState>& legend) {
  const double step = x.size() > 1 ? (x.back() - x.front()) / (x.size() - 1) : 1.0;
  std::size_t begin = 0;
  for (std::size_t i = 1; i <= x.size(); ++i) {
    if (i < x.size() && states[i] == states[begin]) continue;
    const double end_x = i < x.size() ? x[i] : x.back() + step;
    const Eigen::Vector2d top_left = axes.toPixel(x[begin], 1.0);
    const Eigen::Vector2d bottom_right = axes.toPixel(end_x, 0.0);
    const std::string& colour = legend[states[begin]].colour;
    svg.rect(top_left, bottom_right.x() - top_left.x(), bottom_right.y() - top_left.y(),
             SvgStyle::filled(colour, colour, 0.0));
    begin = i;
  }
}

void drawStripLegend(SvgDocument& svg, Eigen::Vector2d at, const std::vector<int>& states,
                     const std::vector<StripState>& legend) {
  for (std::size_t k = 0; k < legend.size(); ++k) {
    const auto count = std::count(states.begin(), states.end(), static_cast<int>(k));
    svg.rect(at - Eigen::Vector2d(0, 10), 12, 12,
             SvgStyle::filled(legend[k].colour, "#333333", 0.5));
    svg.text(at + Eigen::Vector2d(18, 0), fmt::format("{}: {}", legend[k].label, count),
             kPlotFontSize - 1);
    at.x() += 160;
  }
}

}  // namespace

SvgDocument plotSeries(const SeriesPlot& plot) {
  const Bounds bounds = boundsOf(plot.series);
  const Eigen::Vector2d size(kWidth - kOrigin.x() - 40, 240);
  const Range y{std::min(0.0, bounds.y.min), bounds.y.max > 0 ? 1.1 * bounds.y.max : 1.0};
  const Axes axes(kOrigin, size, padded(bounds.x.min, bounds.x.max), y);
  SvgDocument svg(kWidth, kOrigin.y() + size.y() + 60);
  axes.drawFrame(svg, plot.x_label, plot.y_label, plot.title);
  for (const Series& s : plot.series) {
    std::vector<Eigen::Vector2d> points;
    for (std::size_t i = 0; i < s.x.size(); ++i) points.push_back(axes.toPixel(s.x[i], s.y[i]));
    svg.polyline(points, SvgStyle::stroked(s.colour, 1.2));
  }
  drawSeriesLegend(svg, plot.series);
  return svg;
}

SvgDocument plotStateStrip(const std::string& title, const std::string& x_label,
                           const std::vector<double>& x, const std::vector<int>& states,
                           const std::vector<StripState>& legend) {
  requireValidStrip(x, states, legend);
  const Eigen::Vector2d size(kWidth - kOrigin.x() - 40, 40);
  const double step = x.size() > 1 ? (x.back() - x.front()) / (x.size() - 1) : 1.0;
  const Axes axes(kOrigin, size, {x.front(), x.back() + step}, {0.0, 1.0});
  SvgDocument svg(kWidth, kOrigin.y() + size.y() + 80);
  drawStripCells(svg, axes, x, states, legend);
  svg.rect(kOrigin, size.x(), size.y(), SvgStyle::stroked("black", 1.0));
  svg.text({kOrigin.x() + size.x() / 2, kOrigin.y() - 12}, title, kPlotFontSize + 2,
           TextAnchor::Middle);
  svg.text({kOrigin.x() + size.x() / 2, kOrigin.y() + size.y() + 20}, x_label, kPlotFontSize,
           TextAnchor::Middle);
  svg.text(axes.toPixel(x.front(), 0.0) + Eigen::Vector2d(0, 18), fmt::format("{:g}", x.front()),
           kPlotFontSize - 1, TextAnchor::Start);
  svg.text(axes.toPixel(x.back() + step, 0.0) + Eigen::Vector2d(0, 18),
           fmt::format("{:g}", x.back()), kPlotFontSize - 1, TextAnchor::End);
  drawStripLegend(svg, kOrigin + Eigen::Vector2d(0, size.y() + 50), states, legend);
  return svg;
}

}  // namespace lumaslam::eval
