// Vocabulary files (`Loop.vocabulary`, `vocab convert`): our binary format when the bytes
// start with its magic, DBoW2 text (ORBvoc.txt) otherwise. As for map files, the target
// rewrites the binary checksum so that mutations reach the tree's structure check.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

#include "input_file.h"
#include "lumaslam/core/checksum.h"
#include "lumaslam/loop/vocabulary_io.h"
#include "rejected_input.h"

namespace {

// vocabulary_io.h: a 40-byte header whose u32 node count N and word count W are at 28 and 32,
// then arrays of 4N, 4N, 4N, 32N, 4W and 4W bytes (checksummed one by one), then the checksum.
constexpr std::size_t kHeaderBytes = 40;

void fixChecksum(std::string& bytes) {
  if (bytes.size() < kHeaderBytes + 8) return;
  std::uint32_t nodes = 0;
  std::uint32_t words = 0;
  std::memcpy(&nodes, bytes.data() + 28, 4);
  std::memcpy(&words, bytes.data() + 32, 4);
  const std::uint64_t n = nodes;
  const std::uint64_t w = words;
  if (kHeaderBytes + 44 * n + 8 * w + 8 != bytes.size()) return;
  lumaslam::core::Checksum checksum;
  std::size_t offset = kHeaderBytes;
  for (const std::uint64_t array : {4 * n, 4 * n, 4 * n, 32 * n, 4 * w, 4 * w}) {
    checksum.update(bytes.data() + offset, array);
    offset += array;
  }
  const std::uint64_t value = checksum.value();
  std::memcpy(bytes.data() + offset, &value, sizeof(value));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  fixChecksum(bytes);
  const lumaslam::fuzz::InputFile input("fuzz.voc", bytes);
  lumaslam::fuzz::parseOrReject([&] { lumaslam::loop::loadAnyVocabulary(input.path()); });
  return 0;
}
