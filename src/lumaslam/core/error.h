#pragma once
// Error convention (docs/architecture.md): library code throws lumaslam::Error with a
// message that names the file/key/value that was wrong; the CLI prints it and exits non-zero.
#include <stdexcept>
#include <string>

#include <spdlog/fmt/fmt.h>

namespace lumaslam {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws Error with a fmt-formatted message: fail("{}: line {}: bad number '{}'", file, n, s).
template <typename... Args>
[[noreturn]] void fail(fmt::format_string<Args...> format, Args&&... args) {
  throw Error(fmt::format(format, std::forward<Args>(args)...));
}

}  // namespace lumaslam
