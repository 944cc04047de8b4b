// Timestamps files of image folders (`--timestamps`): one timestamp per line for the folder's
// images in name order, or "timestamp filename" per line. The folder holds three empty .png
// files (the reader lists them; images are only decoded frame by frame, after the parse).
#include <cstddef>
#include <cstdint>

#include "input_file.h"
#include "lumaslam/io/folder_reader.h"
#include "rejected_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const lumaslam::fuzz::InputFile images[] = {{"folder/images/000000.png", ""},
                                                     {"folder/images/000001.png", ""},
                                                     {"folder/images/000002.png", ""}};
  const lumaslam::fuzz::InputFile input("folder/times.txt", data, size);
  lumaslam::io::ReaderOptions options;
  options.timestamps = input.path();
  lumaslam::fuzz::parseOrReject(
      [&] { lumaslam::io::FolderReader reader(images[0].path().parent_path(), options); });
  return 0;
}
