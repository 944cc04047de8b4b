#pragma once
// FNV-1a over 8-byte little-endian chunks (then the tail bytes): fast enough to check 50 MB in
// a few milliseconds. The checksum of vocabulary and map files.
#include <cstdint>
#include <cstring>

namespace lumaslam::core {

class Checksum {
 public:
  void update(const void* data, std::size_t size) {
    const auto* bytes = static_cast<const std::uint8_t*>(data);
    std::size_t i = 0;
    for (; i + 8 <= size; i += 8) {
      std::uint64_t chunk;
      std::memcpy(&chunk, bytes + i, 8);
      mix(chunk);
    }
    for (; i < size; ++i) mix(bytes[i]);
  }
  std::uint64_t value() const { return hash_; }

 private:
  void mix(std::uint64_t value) { hash_ = (hash_ ^ value) * 0x100000001b3ULL; }
  std::uint64_t hash_ = 0xcbf29ce484222325ULL;
};

}  // namespace lumaslam::core
