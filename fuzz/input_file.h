#pragma once
// For parsers that take a path: the fuzzer's bytes written to a file that is removed again.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string_view>

namespace lumaslam::fuzz {

// A folder of this process under the system temp folder, created on first use.
const std::filesystem::path& scratchFolder();

// Writes `bytes` to scratchFolder()/name (name may contain a subfolder) and removes the file
// when it goes out of scope.
class InputFile {
 public:
  InputFile(std::string_view name, std::string_view bytes);
  InputFile(std::string_view name, const std::uint8_t* data, std::size_t size);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace lumaslam::fuzz
