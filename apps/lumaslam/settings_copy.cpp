#include "settings_copy.h"

#include <array>
#include <map>
#include <sstream>

#include <fmt/format.h>

#include "lumaslam/core/read_file.h"
#include "lumaslam/core/settings_lines.h"

namespace lumaslam::cli {
namespace {

// Detector.box_file: the old spelling of Detector.boxFile (core/settings_spellings.h).
constexpr std::array<const char*, 6> kPathKeys = {"System.datasetRoot", "Loop.vocabulary",
                                                  "Detector.model",     "Detector.boxFile",
                                                  "Detector.box_file",  "Detector.names"};

// "Key: value  # comment" -> "value" without quotes and spaces.
std::string valueOf(const std::string& line) {
  std::string value(core::withoutComment(line.substr(line.find(':') + 1)));
  const auto first = value.find_first_not_of(" \t\r");
  const auto last = value.find_last_not_of(" \t\r");
  value = first == std::string::npos ? std::string() : value.substr(first, last - first + 1);
  if (value.size() >= 2 && (value.front() == '"' || value.front() == '\'')) {
    value = value.substr(1, value.size() - 2);
  }
  return value;
}

bool hasKey(const std::string& line, const std::string& key) {
  return line.rfind(key + ":", 0) == 0;
}

// The line with a relative path value made absolute from `folder`; other lines unchanged.
std::string withAbsolutePath(const std::string& line, const std::filesystem::path& folder) {
  for (const char* key : kPathKeys) {
    if (!hasKey(line, key)) continue;
    const std::string value = valueOf(line);
    if (value.empty() || value == "none" || std::filesystem::path(value).is_absolute()) {
      return line;
    }
    return fmt::format("{}: \"{}\"", key, (folder / value).string());
  }
  return line;
}

// The key a "Key: value" line sets, or "" for other lines.
std::string keyOf(const std::string& line) {
  const auto colon = line.find(':');
  if (colon == std::string::npos || line.empty() || line[0] == '#' || line[0] == ' ') return {};
  return line.substr(0, colon);
}

}  // namespace

std::string settingsWithValues(const std::filesystem::path& source,
                               const std::map<std::string, std::string>& values) {
  std::istringstream in(core::readWholeFile(source, "settings file"));
  std::ostringstream text;
  std::map<std::string, std::string> missing = values;
  for (std::string line; std::getline(in, line);) {
    const auto it = values.find(keyOf(line));
    if (it != values.end()) {
      text << fmt::format("{}: \"{}\"\n", it->first, it->second);
      missing.erase(it->first);
    } else {
      text << withAbsolutePath(line, source.parent_path()) << '\n';
    }
  }
  for (const auto& [key, value] : missing) text << fmt::format("{}: \"{}\"\n", key, value);
  return text.str();
}

}  // namespace lumaslam::cli
