#include "lumaslam/core/settings_file.h"

#include <algorithm>
#include <cctype>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>

#include <spdlog/spdlog.h>

#include "lumaslam/core/error.h"
#include "lumaslam/core/settings_spellings.h"

namespace lumaslam::core {
namespace {

template <typename T>
constexpr const char* typeName() {
  if constexpr (std::is_same_v<T, bool>) return "bool (0/1 or true/false)";
  if constexpr (std::is_same_v<T, int>) return "integer";
  if constexpr (std::is_same_v<T, double> || std::is_same_v<T, float>) return "number";
  if constexpr (std::is_same_v<T, std::string>) return "string";
  if constexpr (std::is_same_v<T, std::vector<double>>) return "list of numbers";
  return "value";
}

std::string describe(const cv::FileNode& n) {
  if (n.isInt()) return std::to_string(static_cast<int>(n));
  if (n.isReal()) return std::to_string(static_cast<double>(n));
  if (n.isString()) return fmt::format("'{}'", static_cast<std::string>(n));
  if (n.isSeq()) return "a list";
  if (n.isMap()) return "a map";
  return "an empty value";
}

// Returns nullopt when the node does not hold a T.
template <typename T>
std::optional<T> convert(const cv::FileNode& n) {
  if constexpr (std::is_same_v<T, std::string>) {
    if (n.isString()) return static_cast<std::string>(n);
    return std::nullopt;
  } else if constexpr (std::is_same_v<T, bool>) {
    if (n.isInt()) {
      const int v = static_cast<int>(n);
      if (v == 0 || v == 1) return v == 1;
    } else if (n.isString()) {
      const auto s = static_cast<std::string>(n);
      if (s == "true" || s == "True") return true;
      if (s == "false" || s == "False") return false;
    }
    return std::nullopt;
  } else if constexpr (std::is_same_v<T, int>) {
    if (n.isInt()) return static_cast<int>(n);
    if (n.isReal()) {
      const double v = static_cast<double>(n);
      if (std::floor(v) == v) return static_cast<int>(v);
    }
    return std::nullopt;
  } else if constexpr (std::is_same_v<T, double> || std::is_same_v<T, float>) {
    if (n.isInt() || n.isReal()) {
      const double v = static_cast<double>(n);
      if (std::isfinite(v)) return static_cast<T>(v);
    }
    return std::nullopt;
  } else if constexpr (std::is_same_v<T, std::vector<double>>) {
    if (!n.isSeq()) return std::nullopt;
    std::vector<double> values;
    for (const auto& item : n) {
      if (!item.isInt() && !item.isReal()) return std::nullopt;
      values.push_back(static_cast<double>(item));
    }
    return values;
  }
}

}  // namespace

SettingsFile::SettingsFile(cv::FileStorage storage, std::string origin,
                           std::map<std::string, KeyLine> key_lines)
    : storage_(std::move(storage)), origin_(std::move(origin)), key_lines_(std::move(key_lines)) {}

SettingsFile SettingsFile::open(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    fail("{}: settings file not found", path.string());
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  if (!in && !in.eof()) fail("{}: cannot read settings file", path.string());
  return fromString(text.str(), path.string());
}

namespace {

constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF";

bool isYaml(const std::string& text) {
  return text.rfind("<?xml", 0) != 0 && text.rfind("{", 0) != 0;
}

// cv::FileStorage puts "(LINE): problem" in the exception's func field (or its message).
[[noreturn]] void failParse(const cv::Exception& e, const std::string& origin, int line_offset) {
  static const std::regex kLine(R"(\((\d+)\): ([^'\n]*))");
  std::smatch match;
  const std::string text = e.func + "\n" + e.msg;
  if (std::regex_search(text, match, kLine)) {
    fail("{}: line {}: not a valid settings file: {}", origin, std::stoi(match[1]) - line_offset,
         match[2].str());
  }
  fail("{}: not a valid settings file: {}", origin, e.err);
}

}  // namespace

SettingsFile SettingsFile::fromString(const std::string& yaml, const std::string& origin) {
  std::string text = yaml;
  if (text.starts_with(kUtf8Bom)) text.erase(0, kUtf8Bom.size());
  std::map<std::string, KeyLine> key_lines;
  if (isYaml(text)) {
    requireUtf8Text(text, origin);
    requireBlankAfterDocumentMarkers(text, origin);
    key_lines = scanKeyLines(text, origin);
  }
  // cv::FileStorage needs the %YAML header; ORB-SLAM files have it, hand-written ones may not.
  const bool add_header = isYaml(text) && !text.starts_with("%YAML");
  if (add_header) text = "%YAML:1.0\n" + text;
  cv::FileStorage storage;
  try {
    storage.open(text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
  } catch (const cv::Exception& e) {
    failParse(e, origin, add_header ? 1 : 0);
  } catch (const std::exception& e) {  // OpenCV's parser lets some std::length_error escape
    fail("{}: not a valid settings file ({})", origin, e.what());
  }
  if (!storage.isOpened()) fail("{}: not a valid settings file", origin);
  // Every lookup indexes the top level, which cv::FileNode asserts is a map.
  if (!storage.root().isMap()) {
    fail("{}: not a valid settings file: the top level is not a map of 'key: value' lines", origin);
  }
  return SettingsFile(std::move(storage), origin, std::move(key_lines));
}

cv::FileNode SettingsFile::writtenNode(const std::string& key) const {
  cv::FileNode n = storage_[key];
  if (!n.empty() || key.find('.') == std::string::npos) return n;
  n = storage_.root();
  std::string_view rest = key;
  while (!rest.empty()) {
    const auto dot = rest.find('.');
    // "Camera: 500" holds no Camera.fx; cv::FileNode::operator[] asserts on a non-map.
    if (!n.isMap()) return cv::FileNode();
    n = n[std::string(rest.substr(0, dot))];
    if (n.empty()) return n;
    rest = dot == std::string_view::npos ? std::string_view{} : rest.substr(dot + 1);
  }
  return n;
}

SettingsFile::FoundKey SettingsFile::resolve(std::string_view key) const {
  const std::string k(key);
  {
    std::lock_guard lock(asked_->mutex);
    asked_->keys.insert(k);
  }
  FoundKey found{writtenNode(k), k};
  const auto old_spelling = oldSpellingOf(key);
  if (!old_spelling) return found;
  const std::string old_key(*old_spelling);
  const cv::FileNode old_node = writtenNode(old_key);
  if (old_node.empty()) return found;
  if (!found.node.empty()) {
    fail("{}: both '{}' and its old spelling '{}' are set; keep only '{}'", origin_, k, old_key, k);
  }
  warnOldSpelling(old_key, k);
  return {old_node, old_key};
}

// Once per file and key, however many modules read it.
void SettingsFile::warnOldSpelling(const std::string& old_key, const std::string& new_key) const {
  {
    std::lock_guard lock(asked_->mutex);
    if (!asked_->warned.insert(old_key).second) return;
  }
  spdlog::warn("{}: '{}' is an old spelling; use '{}'", origin_, old_key, new_key);
}

cv::FileNode SettingsFile::node(std::string_view key) const {
  return resolve(key).node;
}

bool SettingsFile::has(std::string_view key) const {
  const auto n = node(key);
  return !n.empty() && !n.isNone();
}

std::vector<std::string> SettingsFile::keys() const {
  return storage_.root().keys();
}

std::set<std::string> SettingsFile::askedKeys() const {
  std::lock_guard lock(asked_->mutex);
  return asked_->keys;
}

namespace {

bool isMatrix(const cv::FileNode& n) {
  return n.isMap() && !n["data"].empty() && !n["rows"].empty();
}

// An old spelling counts as asked when its new name was (SettingsFile::resolve read it).
bool wasAsked(const std::set<std::string>& asked, const std::string& key) {
  if (asked.contains(key)) return true;
  const auto new_spelling = newSpellingOf(key);
  return new_spelling && asked.contains(std::string(*new_spelling));
}

void flattenKeys(const cv::FileNode& n, const std::string& prefix,
                 const std::set<std::string>& asked, std::vector<std::string>& out) {
  for (const auto& key : n.keys()) {
    const std::string flat = prefix.empty() ? key : prefix + "." + key;
    const cv::FileNode child = n[key];
    if (child.isMap() && !isMatrix(child) && !asked.contains(flat)) {
      flattenKeys(child, flat, asked, out);
    } else if (!wasAsked(asked, flat)) {
      out.push_back(flat);
    }
  }
}

std::size_t editDistance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      const bool same = std::tolower(a[i - 1]) == std::tolower(b[j - 1]);
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// Keys of ORB-SLAM3 and of our generator that lumaslam reads no value from on purpose.
constexpr std::string_view kIgnoredPrefixes[] = {"Viewer.",
                                                 "IMU.",
                                                 "Synth.",
                                                 "Dataset.",
                                                 "LEFT.",
                                                 "RIGHT.",
                                                 "Camera.type",
                                                 "Camera2.type",
                                                 "System.LoadAtlasFromFile",
                                                 "System.SaveAtlasToFile",
                                                 "System.thFarPoints",
                                                 "Camera.newWidth",
                                                 "Camera.newHeight",
                                                 "Stereo.b",
                                                 "Camera.bf"};

}  // namespace

std::vector<std::string> SettingsFile::unaskedKeys() const {
  std::vector<std::string> keys;
  flattenKeys(storage_.root(), "", askedKeys(), keys);
  return keys;
}

std::vector<UnknownKey> unknownKeys(const SettingsFile& file) {
  const auto asked = file.askedKeys();
  std::vector<UnknownKey> unknown;
  for (const auto& key : file.unaskedKeys()) {
    const bool ignored = std::any_of(std::begin(kIgnoredPrefixes), std::end(kIgnoredPrefixes),
                                     [&](std::string_view p) { return key.starts_with(p); });
    if (ignored) continue;
    UnknownKey entry{key, {}};
    std::size_t best = std::max<std::size_t>(2, key.size() / 5) + 1;
    for (const auto& candidate : asked) {
      const std::size_t d = editDistance(key, candidate);
      if (d < best) {
        best = d;
        entry.suggestion = candidate;
      }
    }
    unknown.push_back(std::move(entry));
  }
  return unknown;
}

void SettingsFile::invalid(std::string_view key, std::string_view why) const {
  fail("{}: key '{}': {}", origin_, key, why);
}

// cv::FileStorage keeps integers in 32 bits: 3000000000 would be read as -1294967296.
void SettingsFile::requireIntRange(std::string_view key) const {
  const auto it = key_lines_.find(std::string(key));
  if (it == key_lines_.end()) return;
  const std::string& written = it->second.value;
  char* end = nullptr;
  const double value = std::strtod(written.c_str(), &end);
  if (end == written.c_str() || *end != '\0') return;
  constexpr int kMin = std::numeric_limits<int>::min();
  constexpr int kMax = std::numeric_limits<int>::max();
  if (value < kMin || value > kMax) {
    invalid(key, fmt::format("{} is out of range (expected an integer from {} to {})", written,
                             kMin, kMax));
  }
}

template <typename T>
std::optional<T> SettingsFile::find(std::string_view key) const {
  const auto [n, written_key] = resolve(key);
  if (n.empty() || n.isNone()) return std::nullopt;
  if constexpr (std::is_same_v<T, int>) requireIntRange(written_key);
  auto value = convert<T>(n);
  if (!value) {
    invalid(written_key, fmt::format("expected {}, found {}", typeName<T>(), describe(n)));
  }
  return value;
}

template <typename T>
T SettingsFile::get(std::string_view key) const {
  auto value = find<T>(key);
  if (!value) fail("{}: key '{}' is missing (expected {})", origin_, key, typeName<T>());
  return *value;
}

template <typename T>
T SettingsFile::get(std::string_view key, T fallback) const {
  return find<T>(key).value_or(std::move(fallback));
}

std::optional<cv::Mat> SettingsFile::findMatrix(std::string_view key, int rows, int cols) const {
  const auto n = node(key);
  if (n.empty() || n.isNone()) return std::nullopt;
  cv::Mat m;
  if (n.isMap()) {
    // cv::read allocates rows x cols before it looks at the data: check the shape first.
    const cv::FileNode n_rows = n["rows"];
    const cv::FileNode n_cols = n["cols"];
    if (!n_rows.isInt() || !n_cols.isInt())
      invalid(key, fmt::format("expected a {}x{} opencv-matrix", rows, cols));
    if (static_cast<int>(n_rows) != rows || static_cast<int>(n_cols) != cols) {
      invalid(key, fmt::format("expected a {}x{} matrix, found {}x{}", rows, cols,
                               static_cast<int>(n_rows), static_cast<int>(n_cols)));
    }
    try {
      n >> m;
    } catch (const cv::Exception&) {
      m.release();
    }
  } else if (auto values = convert<std::vector<double>>(n)) {
    if (static_cast<int>(values->size()) == rows * cols)
      m = cv::Mat(*values, true).reshape(1, rows);
  }
  if (m.empty()) invalid(key, fmt::format("expected a {}x{} opencv-matrix", rows, cols));
  if (m.rows != rows || m.cols != cols) {
    invalid(key, fmt::format("expected a {}x{} matrix, found {}x{}", rows, cols, m.rows, m.cols));
  }
  cv::Mat out;
  m.convertTo(out, CV_64F);
  return out;
}

cv::Mat SettingsFile::getMatrix(std::string_view key, int rows, int cols) const {
  auto m = findMatrix(key, rows, cols);
  if (!m)
    fail("{}: key '{}' is missing (expected a {}x{} opencv-matrix)", origin_, key, rows, cols);
  return *m;
}

#define LUMASLAM_SETTINGS_INSTANTIATE(T)                                   \
  template std::optional<T> SettingsFile::find<T>(std::string_view) const; \
  template T SettingsFile::get<T>(std::string_view) const;                 \
  template T SettingsFile::get<T>(std::string_view, T) const;
LUMASLAM_SETTINGS_INSTANTIATE(int)
LUMASLAM_SETTINGS_INSTANTIATE(double)
LUMASLAM_SETTINGS_INSTANTIATE(float)
LUMASLAM_SETTINGS_INSTANTIATE(bool)
LUMASLAM_SETTINGS_INSTANTIATE(std::string)
LUMASLAM_SETTINGS_INSTANTIATE(std::vector<double>)
#undef LUMASLAM_SETTINGS_INSTANTIATE

}  // namespace lumaslam::core
