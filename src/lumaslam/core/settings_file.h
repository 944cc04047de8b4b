#pragma once
// Typed access to an ORB-SLAM3-style settings file (%YAML:1.0, read with cv::FileStorage).
// Keys are flat ("Camera.fx", "Enhancement.preset"); a key that is not found flat is also
// looked up as a nested path (Camera: {fx: ...}). A key renamed to camelCase (issue 21) is
// also read under its old snake_case spelling, with a warning (core/settings_spellings.h).
// Every failure names file, key and the expected type.
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <opencv2/core.hpp>

#include "lumaslam/core/settings_lines.h"

namespace lumaslam::core {

class SettingsFile {
 public:
  // Throws Error if the file is missing, is not a YAML/XML/JSON file cv::FileStorage reads
  // (naming the line when OpenCV gives one) or sets a key twice. A UTF-8 BOM is skipped.
  static SettingsFile open(const std::filesystem::path& path);
  // Parses settings from text (tests, embedded defaults); `origin` names it in errors.
  static SettingsFile fromString(const std::string& yaml, const std::string& origin = "<string>");

  const std::string& origin() const { return origin_; }
  bool has(std::string_view key) const;
  std::vector<std::string> keys() const;  // top-level keys, in file order

  // Required value: throws Error "FILE: key 'K' is missing (expected T)" or "... is not a T".
  template <typename T>
  T get(std::string_view key) const;
  // Optional value: fallback when absent, Error when present but of the wrong type.
  template <typename T>
  T get(std::string_view key, T fallback) const;
  template <typename T>
  std::optional<T> find(std::string_view key) const;

  // An `!!opencv-matrix` of the given shape (rows/cols checked), as CV_64F.
  cv::Mat getMatrix(std::string_view key, int rows, int cols) const;
  std::optional<cv::Mat> findMatrix(std::string_view key, int rows, int cols) const;

  [[noreturn]] void invalid(std::string_view key, std::string_view why) const;

  // Every key asked for so far (found or not), in flat form.
  std::set<std::string> askedKeys() const;
  // Keys of the file (nested maps flattened to "A.b"; matrices are values) that nothing has
  // asked for: typos and keys of other programs.
  std::vector<std::string> unaskedKeys() const;

 private:
  SettingsFile(cv::FileStorage storage, std::string origin,
               std::map<std::string, KeyLine> key_lines);
  struct FoundKey {
    cv::FileNode node;  // empty when the file has neither spelling
    std::string key;    // as the file spells it: `key` or its old spelling
  };
  // The node of `key`, or of its old spelling (core/settings_spellings.h) with one warning;
  // Error when the file sets both. Remembers `key` as asked.
  FoundKey resolve(std::string_view key) const;
  cv::FileNode node(std::string_view key) const;
  cv::FileNode writtenNode(const std::string& key) const;  // flat, then as a nested path
  void warnOldSpelling(const std::string& old_key, const std::string& new_key) const;
  void requireIntRange(std::string_view key) const;

  cv::FileStorage storage_;
  std::string origin_;
  std::map<std::string, KeyLine> key_lines_;  // empty for XML/JSON
  struct AskedKeys {
    std::mutex mutex;
    std::set<std::string> keys;
    std::set<std::string> warned;  // old spellings already warned about
  };
  std::shared_ptr<AskedKeys> asked_ = std::make_shared<AskedKeys>();  // shared by copies
};

// The keys of `file` no code asked for, except those of other programs that lumaslam reads no
// value from on purpose (ORB-SLAM3's Viewer.*, IMU.*, Camera.type, ...; the generator's
// Synth.* and Dataset.*), each with the closest asked key when one is a likely typo of it.
struct UnknownKey {
  std::string key;
  std::string suggestion;  // empty: nothing close
};
std::vector<UnknownKey> unknownKeys(const SettingsFile& file);

// Supported T for get/find: bool (0/1, true/false), int, double, float, std::string,
// std::vector<double>.
extern template int SettingsFile::get<int>(std::string_view) const;
extern template double SettingsFile::get<double>(std::string_view) const;
extern template float SettingsFile::get<float>(std::string_view) const;
extern template bool SettingsFile::get<bool>(std::string_view) const;
extern template std::string SettingsFile::get<std::string>(std::string_view) const;
extern template std::vector<double> SettingsFile::get<std::vector<double>>(std::string_view) const;

}  // namespace lumaslam::core
