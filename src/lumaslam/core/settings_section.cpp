#include "lumaslam/core/settings_section.h"

#include <cmath>

#include <fmt/format.h>

namespace lumaslam::core {
namespace {

// fmt's shortest round-trip form, with ".0" added to whole numbers so that the settings file
// reads a real, not an int.
template <typename Real>
std::string realText(Real value) {
  std::string text = fmt::format("{}", value);
  if (std::isfinite(value) && text.find_first_of(".e") == std::string::npos) text += ".0";
  return text;
}

}  // namespace

bool Range::contains(double value) const {
  const bool above_min = min_inclusive ? value >= min : value > min;
  return above_min && value <= max;
}

std::string Range::describe() const {
  const bool has_max = max != std::numeric_limits<double>::infinity();
  if (!has_max) return fmt::format("{} {}", min_inclusive ? ">=" : ">", min);
  return fmt::format("in {}{}, {}]", min_inclusive ? "[" : "(", min, max);
}

void requireInRange(const SettingsFile& file, std::string_view key, double value,
                    const Range& range) {
  if (!range.contains(value)) {
    file.invalid(key, fmt::format("must be {}, found {}", range.describe(), value));
  }
}

std::string SectionPrinter::settingsValue(bool value) {
  return value ? "true" : "false";
}
std::string SectionPrinter::settingsValue(int value) {
  return fmt::format("{}", value);
}
std::string SectionPrinter::settingsValue(std::size_t value) {
  return fmt::format("{}", value);
}
std::string SectionPrinter::settingsValue(double value) {
  return realText(value);
}
std::string SectionPrinter::settingsValue(float value) {
  return realText(value);
}
std::string SectionPrinter::settingsValue(const std::string& value) {
  return fmt::format("\"{}\"", value);
}

}  // namespace lumaslam::core
