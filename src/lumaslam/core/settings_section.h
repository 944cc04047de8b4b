#pragma once
// One module's section of the settings file ("Tracking.*"), read and printed from one list of
// keys, as Kimera-VIO's parseYAML/print pair but written once. A module lists its keys in one
// function template,
//   template <typename Keys>
//   void visitKeys(Keys& keys, TrackerParams& p) {
//     keys("minLocalMapInliers", p.min_local_map_inliers, core::Range::atLeast(1));
//   }
// and a SectionReader applies that list to a file (values over the defaults, each checked
// against its range), a SectionPrinter turns it into settings lines that read back to the
// same values (`lumaslam run --print-settings`).
#include <cstddef>
#include <limits>
#include <string>
#include <string_view>
#include <type_traits>

#include "lumaslam/core/settings_file.h"

namespace lumaslam::core {

// The values a numeric key may take; the one validation rule of every settings section.
struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_inclusive = true;

  static Range any() { return {}; }
  static Range atLeast(double low) { return {low}; }
  static Range above(double low) { return {low, std::numeric_limits<double>::infinity(), false}; }
  static Range between(double low, double high) { return {low, high}; }

  bool contains(double value) const;
  std::string describe() const;  // ">= 1", "> 0", "in [0, 1]"
};

// Throws the file's "key: must be ..." Error when `value` is outside `range`.
void requireInRange(const SettingsFile& file, std::string_view key, double value,
                    const Range& range);

class SectionReader {
 public:
  SectionReader(const SettingsFile& file, std::string section)
      : file_(file), section_(std::move(section)) {}

  template <typename T>
  void operator()(std::string_view name, T& value, const Range& range = {}) const {
    const std::string key = section_ + "." + std::string(name);
    if constexpr (std::is_same_v<T, std::size_t>) {
      int as_int = static_cast<int>(value);
      (*this)(name, as_int, range);
      value = static_cast<std::size_t>(as_int);
    } else if (const auto found = file_.find<T>(key)) {
      if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
        requireInRange(file_, key, static_cast<double>(*found), range);
      }
      value = *found;
    }
  }

 private:
  const SettingsFile& file_;
  std::string section_;
};

class SectionPrinter {
 public:
  explicit SectionPrinter(std::string section) : section_(std::move(section)) {}

  template <typename T>
  void operator()(std::string_view name, const T& value, const Range& = {}) {
    text_ += section_ + "." + std::string(name) + ": " + settingsValue(value) + "\n";
  }

  const std::string& text() const { return text_; }

 private:
  // Values as the reader reads them back: bools as true/false, reals with a decimal point
  // and every digit needed to round-trip.
  static std::string settingsValue(bool value);
  static std::string settingsValue(int value);
  static std::string settingsValue(std::size_t value);
  static std::string settingsValue(double value);
  static std::string settingsValue(float value);
  static std::string settingsValue(const std::string& value);

  std::string section_;
  std::string text_;
};

// A module's read and print functions from its key list `visit(keys, params)`, e.g.
//   readSection(file, "Tracking", params, [](auto& keys, auto& p) { visitTrackingKeys(keys, p); })
template <typename Params, typename Visit>
void readSection(const SettingsFile& file, std::string section, Params& params, Visit visit) {
  const SectionReader reader(file, std::move(section));
  visit(reader, params);
}

template <typename Params, typename Visit>
std::string printSection(std::string section, Params params, Visit visit) {
  SectionPrinter printer(std::move(section));
  visit(printer, params);
  return printer.text();
}

}  // namespace lumaslam::core
