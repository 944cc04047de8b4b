#pragma once
// A minimal SVG 1.1 writer (lines, polylines, circles, rectangles, text) for plots, so that
// plotting needs no extra dependency.
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace lumaslam::eval {

// Text for XML or HTML content and quoted attribute values: & < > " as entities.
std::string escapeXml(std::string_view text);

struct SvgStyle {
  std::string stroke = "black";
  double stroke_width = 1.0;
  std::string fill = "none";
  std::string dash;  // stroke-dasharray, e.g. "4 3"; empty for a solid line

  static SvgStyle stroked(std::string colour, double width, std::string dash_pattern = {}) {
    return {std::move(colour), width, "none", std::move(dash_pattern)};
  }
  static SvgStyle filled(std::string fill_colour, std::string outline, double width) {
    return {std::move(outline), width, std::move(fill_colour), {}};
  }
};

enum class TextAnchor { Start, Middle, End };

class SvgDocument {
 public:
  SvgDocument(double width, double height);

  void line(Eigen::Vector2d from, Eigen::Vector2d to, const SvgStyle& style);
  void polyline(const std::vector<Eigen::Vector2d>& points, const SvgStyle& style);
  void circle(Eigen::Vector2d centre, double radius, const SvgStyle& style);
  void rect(Eigen::Vector2d corner, double width, double height, const SvgStyle& style);
  // `rotate_deg` turns the text about its anchor point (e.g. -90 for a vertical axis label).
  void text(Eigen::Vector2d at, std::string_view content, double size,
            TextAnchor anchor = TextAnchor::Start, double rotate_deg = 0.0,
            std::string_view fill = "black");

  std::string str() const;  // a standalone SVG file: XML declaration, then element()
  // The <svg> element alone, e.g. to put inline into an HTML page.
  std::string element() const;
  // Written as an io::OutputFile (complete or not at all); throws Error naming the path when
  // it cannot be written.
  void save(const std::filesystem::path& path) const;

 private:
  double width_;
  double height_;
  std::vector<std::string> elements_;
};

}  // namespace lumaslam::eval
