#include "lumaslam/eval/svg_document.h"

#include <spdlog/fmt/fmt.h>

#include "lumaslam/core/error.h"
#include "lumaslam/io/output_file.h"

namespace lumaslam::eval {

std::string escapeXml(std::string_view text) {
  std::string escaped;
  for (const char c : text) {
    switch (c) {
      case '&':
        escaped += "&amp;";
        break;
      case '<':
        escaped += "&lt;";
        break;
      case '>':
        escaped += "&gt;";
        break;
      case '"':
        escaped += "&quot;";
        break;
      default:
        escaped += c;
    }
  }
  return escaped;
}

namespace {

std::string styleAttributes(const SvgStyle& style) {
  std::string attributes =
      fmt::format(R"svg(stroke="{}" stroke-width="{:.3g}" fill="{}")svg", escapeXml(style.stroke),
                  style.stroke_width, escapeXml(style.fill));
  if (!style.dash.empty()) attributes += fmt::format(R"svg( stroke-dasharray="{}")svg", style.dash);
  return attributes;
}

}  // namespace

SvgDocument::SvgDocument(double width, double height) : width_(width), height_(height) {}

void SvgDocument::line(Eigen::Vector2d from, Eigen::Vector2d to, const SvgStyle& style) {
  elements_.push_back(
      fmt::format(R"svg(<line x1="{:.2f}" y1="{:.2f}" x2="{:.2f}" y2="{:.2f}" {}/>)svg", from.x(),
                  from.y(), to.x(), to.y(), styleAttributes(style)));
}

void SvgDocument::polyline(const std::vector<Eigen::Vector2d>& points, const SvgStyle& style) {
  if (points.empty()) return;
  std::string coordinates;
  for (const Eigen::Vector2d& p : points)
    coordinates += fmt::format("{:.2f},{:.2f} ", p.x(), p.y());
  coordinates.pop_back();
  elements_.push_back(fmt::format(R"svg(<polyline points="{}" stroke-linejoin="round" {}/>)svg",
                                  coordinates, styleAttributes(style)));
}

void SvgDocument::circle(Eigen::Vector2d centre, double radius, const SvgStyle& style) {
  elements_.push_back(fmt::format(R"svg(<circle cx="{:.2f}" cy="{:.2f}" r="{:.2f}" {}/>)svg",
                                  centre.x(), centre.y(), radius, styleAttributes(style)));
}

void SvgDocument::rect(Eigen::Vector2d corner, double width, double height, const SvgStyle& style) {
  elements_.push_back(
      fmt::format(R"svg(<rect x="{:.2f}" y="{:.2f}" width="{:.2f}" height="{:.2f}" {}/>)svg",
                  corner.x(), corner.y(), width, height, styleAttributes(style)));
}

void SvgDocument::text(Eigen::Vector2d at, std::string_view content, double size, TextAnchor anchor,
                       double rotate_deg, std::string_view fill) {
  const char* anchor_name = anchor == TextAnchor::Start    ? "start"
                            : anchor == TextAnchor::Middle ? "middle"
                                                           : "end";
  std::string transform;
  if (rotate_deg != 0.0) {
    transform = fmt::format(R"svg( transform="rotate({:.1f} {:.2f} {:.2f})")svg", rotate_deg,
                            at.x(), at.y());
  }
  elements_.push_back(fmt::format(
      R"svg(<text x="{:.2f}" y="{:.2f}" font-family="sans-serif" font-size="{:.1f}" fill="{}" text-anchor="{}"{}>{}</text>)svg",
      at.x(), at.y(), size, escapeXml(fill), anchor_name, transform, escapeXml(content)));
}

std::string SvgDocument::str() const {
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n" + element();
}

std::string SvgDocument::element() const {
  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"{0:.0f}\" "
      "height=\"{1:.0f}\" viewBox=\"0 0 {0:.0f} {1:.0f}\">\n"
      "<rect x=\"0\" y=\"0\" width=\"{0:.0f}\" height=\"{1:.0f}\" fill=\"white\"/>\n",
      width_, height_);
  for (const std::string& element : elements_) svg += element + "\n";
  svg += "</svg>\n";
  return svg;
}

void SvgDocument::save(const std::filesystem::path& path) const {
  io::OutputFile file(path);
  file.stream() << str();
  file.commit();
}

}  // namespace lumaslam::eval
