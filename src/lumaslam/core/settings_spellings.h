#pragma once
// Keys once spelled in snake_case (`Detector.queue_capacity`) and their camelCase names
// (`Detector.queueCapacity`, issue 21), the spelling of ORB-SLAM3 and of every other section.
// core::SettingsFile reads an old spelling in place of its new name with one warning, and
// refuses a file that sets both (docs/settings.md "Old spellings").
#include <optional>
#include <span>
#include <string_view>

namespace lumaslam::core {

struct KeySpelling {
  std::string_view old_key;
  std::string_view new_key;
};

// Every renamed key, in the order docs/settings.md lists them.
std::span<const KeySpelling> keySpellings();

// The old spelling of `new_key`, or nullopt when it never had one.
std::optional<std::string_view> oldSpellingOf(std::string_view new_key);
// The new name of `old_key`, or nullopt when it is not an old spelling.
std::optional<std::string_view> newSpellingOf(std::string_view old_key);

}  // namespace lumaslam::core
