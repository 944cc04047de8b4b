// Settings YAML (`run --settings`): cv::FileStorage, the key-line scan and every typed key of
// io::Settings, then the unknown-key check.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "lumaslam/core/settings_file.h"
#include "lumaslam/io/settings.h"
#include "rejected_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string yaml(reinterpret_cast<const char*>(data), size);
  lumaslam::fuzz::parseOrReject([&] {
    const auto file = std::make_shared<const lumaslam::core::SettingsFile>(
        lumaslam::core::SettingsFile::fromString(yaml, "fuzz.yaml"));
    lumaslam::io::Settings::fromFile(file);
    lumaslam::core::unknownKeys(*file);
  });
  return 0;
}
