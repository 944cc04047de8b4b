#pragma once
// What `lumaslam run` left in a folder (docs/results.md), read back for `lumaslam report`:
// summary.json (required), timing.csv (columns by header name) and the repeat layout.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

namespace lumaslam::cli {

struct TimingTable {
  std::vector<std::string> columns;            // the header
  std::vector<std::vector<std::string>> rows;  // one per frame, columns.size() fields each

  bool has(std::string_view column) const;
  // The column's fields; throw Error naming the column when it is absent (numbers(): or when
  // a field is not a number).
  std::vector<std::string> texts(std::string_view column) const;
  std::vector<double> numbers(std::string_view column) const;
};

// timing.csv (any file of its layout), or the problem found in it (missing, empty, a line
// with another number of fields than the header).
std::variant<TimingTable, std::string> readTimingTable(const std::filesystem::path& file);

struct RunFolder {
  std::filesystem::path dir;
  nlohmann::json summary;
  std::optional<TimingTable> timing;  // nullopt when timing.csv is missing or malformed
  std::string timing_problem;         // why, when timing is nullopt
};

// Throws Error naming the folder when it does not exist, and naming summary.json when it is
// missing, not JSON, or lacks status / frames / tracked / lost.
RunFolder readRunFolder(const std::filesystem::path& dir);

// A `run --repeat` folder: repeatability.json and no summary.json of its own.
bool isRepeatFolder(const std::filesystem::path& dir);

// repeatability.json of a repeat folder; throws Error naming it when missing or malformed.
nlohmann::json readRepeatability(const std::filesystem::path& dir);

}  // namespace lumaslam::cli
