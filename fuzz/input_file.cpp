#include "input_file.h"

#include <unistd.h>

#include <fstream>
#include <stdexcept>
#include <string>

namespace lumaslam::fuzz {

const std::filesystem::path& scratchFolder() {
  static const std::filesystem::path folder = [] {
    auto path =
        std::filesystem::temp_directory_path() / ("lumaslam-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(path);
    return path;
  }();
  return folder;
}

InputFile::InputFile(std::string_view name, std::string_view bytes)
    : path_(scratchFolder() / name) {
  std::filesystem::create_directories(path_.parent_path());
  std::ofstream out(path_, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  // Not a parser failure: the harness itself cannot run.
  if (!out) throw std::logic_error("fuzz harness: cannot write " + path_.string());
}

InputFile::InputFile(std::string_view name, const std::uint8_t* data, std::size_t size)
    : InputFile(name, std::string_view(reinterpret_cast<const char*>(data), size)) {}

InputFile::~InputFile() {
  std::error_code ignored;
  std::filesystem::remove(path_, ignored);
}

}  // namespace lumaslam::fuzz
