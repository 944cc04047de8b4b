// Map files (`run --map`, `map info`): header, size and checksum, then the cereal archive and
// its structure check. A random mutation almost never keeps the checksum right, so the target
// rewrites it over the declared payload: the archive decoder, the structure check and
// the loading into a Map are what gets fuzzed.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>

#include "input_file.h"
#include "lumaslam/core/checksum.h"
#include "lumaslam/feature/scale_levels.h"
#include "lumaslam/map/map.h"
#include "lumaslam/map/map_file.h"
#include "rejected_input.h"

namespace {

// map_file.h: char[8] magic | u32 version | u32 reserved | u64 payload size | u64 checksum.
constexpr std::size_t kHeaderBytes = 32;
constexpr std::size_t kSizeOffset = 16;
constexpr std::size_t kChecksumOffset = 24;

void fixChecksum(std::string& bytes) {
  if (bytes.size() < kHeaderBytes) return;
  std::uint64_t payload_size = 0;
  std::memcpy(&payload_size, bytes.data() + kSizeOffset, sizeof(payload_size));
  if (payload_size > bytes.size() - kHeaderBytes) return;
  lumaslam::core::Checksum checksum;
  checksum.update(bytes.data() + kHeaderBytes, payload_size);
  const std::uint64_t value = checksum.value();
  std::memcpy(bytes.data() + kChecksumOffset, &value, sizeof(value));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  fixChecksum(bytes);
  const lumaslam::fuzz::InputFile input("fuzz.map", bytes);
  lumaslam::fuzz::parseOrReject([&] {
    const auto info = lumaslam::map::readMapFileInfo(input.path());
    // Loading also builds keyframes, points and feature grids; a run only loads a map whose
    // fingerprint is its own, so the map's ORB settings (checked by readMapFileInfo) stand in.
    const auto& orb = info.fingerprint;
    lumaslam::map::Map map;
    lumaslam::map::loadMapFile(
        input.path(), info.fingerprint,
        std::make_shared<lumaslam::feature::ScaleLevels>(orb.orb_levels, orb.orb_scale_factor),
        map);
  });
  return 0;
}
