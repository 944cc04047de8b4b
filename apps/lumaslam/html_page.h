#pragma once
// A self-contained HTML page for `lumaslam report`: inline CSS, sections, tables whose
// number cells carry data-key / data-value attributes (the exact value, for tools and tests).
// No scripts, no external resources.
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace lumaslam::cli {

std::string escapeHtml(std::string_view text);

struct Cell {
  std::string text;                  // shown, escaped on output
  std::string key = {};              // data-key attribute, e.g. "ate.rmse"; empty: none
  std::optional<double> value = {};  // data-value attribute, full precision
  // More attributes, e.g. {"data-run", "2"} or {"style", "background:#fff"}; escaped on output.
  std::vector<std::pair<std::string, std::string>> attributes = {};
  static Cell number(double value, std::string key, int decimals = 6);
  static Cell count(long long value, std::string key);
};

std::string htmlTable(const std::vector<std::string>& header,
                      const std::vector<std::vector<Cell>>& rows);
// A paragraph in the style of a notice (e.g. the dataset is gone), text escaped.
std::string htmlNote(std::string_view text);

class HtmlPage {
 public:
  explicit HtmlPage(std::string title);
  // `body` is HTML as is (escape text with escapeHtml); `id` names the <section>.
  void section(std::string_view id, std::string_view heading, std::string_view body);
  std::string str() const;

 private:
  std::string title_;
  std::string body_;
};

}  // namespace lumaslam::cli
