#include "html_page.h"

#include <fmt/format.h>

#include "lumaslam/eval/svg_document.h"

namespace lumaslam::cli {
namespace {

constexpr std::string_view kStyle = R"css(
body { font-family: sans-serif; margin: 2em; color: #222; max-width: 1200px; }
h1 { font-size: 1.5em; } h2 { font-size: 1.2em; border-bottom: 1px solid #ccc; }
table { border-collapse: collapse; margin: 0.5em 0; }
th, td { border: 1px solid #ccc; padding: 0.2em 0.6em; text-align: right; }
th:first-child, td:first-child { text-align: left; }
.note { background: #fff4d6; border-left: 4px solid #e0a800; padding: 0.4em 0.8em; }
figure { display: inline-block; margin: 0.5em; vertical-align: top; }
figcaption { font-size: 0.9em; color: #555; }
svg { max-width: 100%; height: auto; }
)css";

std::string cellHtml(const Cell& cell) {
  std::string attributes;
  if (!cell.key.empty()) attributes += fmt::format(" data-key=\"{}\"", escapeHtml(cell.key));
  if (cell.value) attributes += fmt::format(" data-value=\"{:.17g}\"", *cell.value);
  for (const auto& [name, value] : cell.attributes) {
    attributes += fmt::format(" {}=\"{}\"", escapeHtml(name), escapeHtml(value));
  }
  return fmt::format("<td{}>{}</td>", attributes, escapeHtml(cell.text));
}

}  // namespace

std::string escapeHtml(std::string_view text) {
  return eval::escapeXml(text);
}

Cell Cell::number(double value, std::string key, int decimals) {
  return {fmt::format("{:.{}f}", value, decimals), std::move(key), value};
}

Cell Cell::count(long long value, std::string key) {
  return {std::to_string(value), std::move(key), static_cast<double>(value)};
}

std::string htmlTable(const std::vector<std::string>& header,
                      const std::vector<std::vector<Cell>>& rows) {
  std::string html = "<table>\n<tr>";
  for (const std::string& name : header) html += "<th>" + escapeHtml(name) + "</th>";
  html += "</tr>\n";
  for (const auto& row : rows) {
    html += "<tr>";
    for (const Cell& cell : row) html += cellHtml(cell);
    html += "</tr>\n";
  }
  return html + "</table>\n";
}

std::string htmlNote(std::string_view text) {
  return "<p class=\"note\">" + escapeHtml(text) + "</p>\n";
}

HtmlPage::HtmlPage(std::string title) : title_(std::move(title)) {}

void HtmlPage::section(std::string_view id, std::string_view heading, std::string_view body) {
  body_ += fmt::format("<section id=\"{}\">\n<h2>{}</h2>\n{}</section>\n", escapeHtml(id),
                       escapeHtml(heading), body);
}

std::string HtmlPage::str() const {
  return fmt::format(
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<title>{0}</title>\n<style>{1}</style>\n</head>\n<body>\n<h1>{0}</h1>\n{2}</body>\n"
      "</html>\n",
      escapeHtml(title_), kStyle, body_);
}

}  // namespace lumaslam::cli
