#pragma once
// The axes the SVG plots of this module share: a data rectangle drawn into a pixel rectangle
// with ticks, grid, labels and title (trajectory_plot, series_plot).
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "lumaslam/eval/svg_document.h"

namespace lumaslam::eval {

inline constexpr double kPlotFontSize = 13.0;

struct Range {
  double min = 0.0;
  double max = 1.0;
  double span() const { return max - min; }
};

// [min, max] widened by 5% on each side; an empty range becomes one unit wide.
Range padded(double min, double max);

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
                 const std::string& title) const;

  Range x() const { return x_; }
  Range y() const { return y_; }

 private:
  Eigen::Vector2d origin_;
  Eigen::Vector2d size_;
  Range x_;
  Range y_;
};

// Index ranges [begin, end) of the runs without a time gap (lost tracking) longer than five
// times the median step, so that plots do not draw straight lines across gaps.
std::vector<std::pair<std::size_t, std::size_t>> continuousRuns(const std::vector<double>& stamps);

}  // namespace lumaslam::eval
