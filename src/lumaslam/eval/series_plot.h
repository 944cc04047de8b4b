#pragma once
// SVG plots of per-frame quantities: lines of y over x (e.g. ms per frame), and a strip of
// one coloured cell per frame for a state (e.g. tracked / lost). Used by `lumaslam report`.
#include <string>
#include <vector>

#include "lumaslam/eval/svg_document.h"

namespace lumaslam::eval {

struct Series {
  std::string label;
  std::string colour;  // SVG colour
  std::vector<double> x;
  std::vector<double> y;  // same size as x
};

struct SeriesPlot {
  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<Series> series;
};

// Throws Error when there is no point to draw or a series' x and y differ in size.
SvgDocument plotSeries(const SeriesPlot& plot);

struct StripState {
  std::string label;   // e.g. "ok"
  std::string colour;  // SVG colour
};

// states[i] indexes `legend` for sample i at x[i] (increasing); each sample's cell reaches to
// the next sample's x. The legend shows every state with its sample count. Throws Error for
// an empty strip, sizes that differ or a state outside `legend`.
SvgDocument plotStateStrip(const std::string& title, const std::string& x_label,
                           const std::vector<double>& x, const std::vector<int>& states,
                           const std::vector<StripState>& legend);

}  // namespace lumaslam::eval
