#include "lumaslam/core/read_file.h"

#include <fstream>

#include "lumaslam/core/error.h"

namespace lumaslam::core {

std::string readWholeFile(const std::filesystem::path& file, std::string_view what) {
  std::ifstream in(file, std::ios::binary);
  if (!in) fail("{}: cannot open {}", file.string(), what);
  std::string bytes;
  in.seekg(0, std::ios::end);
  bytes.resize(static_cast<std::size_t>(in.tellg()));
  in.seekg(0);
  in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!in) fail("{}: cannot read {}", file.string(), what);
  return bytes;
}

}  // namespace lumaslam::core
