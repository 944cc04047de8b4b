// Linked into every test executable of a -DLUMASLAM_SANITIZE=thread build (see
// tests/CMakeLists.txt and src/lumaslam/core/serial_libraries.h): OpenCV and TBB run
// single-threaded for the whole test program, so ThreadSanitizer reports only races between
// our own threads.
#include <gtest/gtest.h>

#include <optional>

#include "lumaslam/core/serial_libraries.h"

namespace {

class SerialLibrariesEnvironment : public testing::Environment {
 public:
  void SetUp() override { serial_.emplace(); }
  void TearDown() override { serial_.reset(); }

 private:
  std::optional<lumaslam::core::SerialLibraries> serial_;
};

[[maybe_unused]] testing::Environment* const environment =
    testing::AddGlobalTestEnvironment(new SerialLibrariesEnvironment);

}  // namespace
