#include "run_folder.h"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <variant>

#include "lumaslam/core/error.h"
#include "lumaslam/core/read_file.h"

namespace lumaslam::cli {
namespace {

std::vector<std::string> splitFields(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream stream(line);
  std::string field;
  while (std::getline(stream, field, ',')) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();  // an empty last field
  return fields;
}

// Reads FILE as JSON; throws Error "FILE: WHAT not found" / "FILE: malformed WHAT: ...".
nlohmann::json readJsonFile(const std::filesystem::path& file, std::string_view what) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) fail("{}: {} not found", file.string(), what);
  const std::string text = core::readWholeFile(file, what);
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    fail("{}: malformed {} (not JSON): {}", file.string(), what, e.what());
  }
}

void requireSummaryKeys(const nlohmann::json& summary, const std::filesystem::path& file) {
  if (!summary.is_object()) fail("{}: malformed run summary: not a JSON object", file.string());
  if (!summary.contains("status") || !summary["status"].is_string()) {
    fail("{}: malformed run summary: no \"status\" text", file.string());
  }
  for (const char* key : {"frames", "tracked", "lost"}) {
    if (!summary.contains(key) || !summary[key].is_number_unsigned()) {
      fail("{}: malformed run summary: no \"{}\" count", file.string(), key);
    }
  }
}

}  // namespace

std::variant<TimingTable, std::string> readTimingTable(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) return file.string() + ": not found";
  TimingTable table;
  std::string line;
  if (!std::getline(in, line)) return file.string() + ": empty";
  table.columns = splitFields(line);
  for (std::size_t number = 2; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    auto fields = splitFields(line);
    if (fields.size() != table.columns.size()) {
      return fmt::format("{}: line {}: {} fields, the header has {}", file.string(), number,
                         fields.size(), table.columns.size());
    }
    table.rows.push_back(std::move(fields));
  }
  return table;
}

bool TimingTable::has(std::string_view column) const {
  return std::find(columns.begin(), columns.end(), column) != columns.end();
}

std::vector<std::string> TimingTable::texts(std::string_view column) const {
  const auto at = std::find(columns.begin(), columns.end(), column);
  if (at == columns.end()) fail("timing.csv: no column \"{}\"", column);
  const auto index = static_cast<std::size_t>(at - columns.begin());
  std::vector<std::string> values;
  for (const auto& row : rows) values.push_back(row[index]);
  return values;
}

std::vector<double> TimingTable::numbers(std::string_view column) const {
  std::vector<double> values;
  for (const std::string& text : texts(column)) {
    try {
      std::size_t used = 0;
      values.push_back(std::stod(text, &used));
      if (used != text.size()) throw std::invalid_argument(text);
    } catch (const std::exception&) {
      fail("timing.csv: column \"{}\": '{}' is not a number", column, text);
    }
  }
  return values;
}

RunFolder readRunFolder(const std::filesystem::path& dir) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) fail("{}: no such run folder", dir.string());
  RunFolder run;
  run.dir = dir;
  run.summary = readJsonFile(dir / "summary.json", "run summary");
  requireSummaryKeys(run.summary, dir / "summary.json");
  auto timing = readTimingTable(dir / "timing.csv");
  if (auto* table = std::get_if<TimingTable>(&timing)) {
    run.timing = std::move(*table);
  } else {
    run.timing_problem = std::get<std::string>(timing);
  }
  return run;
}

bool isRepeatFolder(const std::filesystem::path& dir) {
  std::error_code ec;
  return std::filesystem::is_regular_file(dir / "repeatability.json", ec) &&
         !std::filesystem::exists(dir / "summary.json", ec);
}

nlohmann::json readRepeatability(const std::filesystem::path& dir) {
  auto report = readJsonFile(dir / "repeatability.json", "repeat summary");
  if (!report.is_object() || !report.contains("runs") || !report["runs"].is_array()) {
    fail("{}: malformed repeat summary: no \"runs\" list", (dir / "repeatability.json").string());
  }
  return report;
}

}  // namespace lumaslam::cli
