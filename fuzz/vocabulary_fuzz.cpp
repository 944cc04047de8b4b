// Vocabulary files (`Loop.vocabulary`, `vocab convert`): our binary format when the bytes
// start with its magic, DBoW2 text (ORBvoc.txt) otherwise.
#include <cstddef>
#include <cstdint>

#include "input_file.h"
#include "lumaslam/loop/vocabulary_io.h"
#include "rejected_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const lumaslam::fuzz::InputFile input("fuzz.voc", data, size);
  lumaslam::fuzz::parseOrReject([&] { lumaslam::loop::loadAnyVocabulary(input.path()); });
  return 0;
}
