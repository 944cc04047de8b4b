#include "settings_with_classes.h"

#include <array>
#include <sstream>

#include <fmt/format.h>

#include "lumaslam/core/read_file.h"
#include "lumaslam/core/settings_lines.h"

namespace lumaslam::cli {
namespace {

constexpr std::array<const char*, 5> kPathKeys = {"System.datasetRoot", "Loop.vocabulary",
                                                  "Detector.model", "Detector.box_file",
                                                  "Detector.names"};

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

}  // namespace

std::string settingsWithClasses(const std::filesystem::path& source, const std::string& classes) {
  std::istringstream in(core::readWholeFile(source, "settings file"));
  std::ostringstream text;
  bool replaced = false;
  for (std::string line; std::getline(in, line);) {
    const bool is_classes = hasKey(line, "Detector.classes");
    text << (is_classes ? fmt::format("Detector.classes: \"{}\"", classes)
                        : withAbsolutePath(line, source.parent_path()))
         << '\n';
    replaced = replaced || is_classes;
  }
  if (!replaced) text << fmt::format("Detector.classes: \"{}\"\n", classes);
  return text.str();
}

}  // namespace lumaslam::cli
