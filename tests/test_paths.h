#pragma once
// Where tests find ../shared (data/, models/). CMake passes LUMASLAM_SHARED_DIR; the
// environment variable of the same name overrides it for a run.
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace lumaslam::test {

inline std::filesystem::path sharedDir() {
  if (const char* env = std::getenv("LUMASLAM_SHARED_DIR"); env && *env) return env;
  return LUMASLAM_SHARED_DIR;
}
inline std::filesystem::path dataDir() {
  return sharedDir() / "data";
}
inline std::filesystem::path modelsDir() {
  return sharedDir() / "models";
}
inline std::filesystem::path sourceDir() {
  return LUMASLAM_SOURCE_DIR;
}
inline std::filesystem::path cliPath() {
  return LUMASLAM_CLI;
}

// A fresh empty folder under the system temp dir, removed when the object dies. The name holds
// the process id and a per-process count: ctest runs every test in its own process, several
// at once, and two tests of one fixture must never share (and delete) each other's folder.
class TempDir {
 public:
  explicit TempDir(const std::string& name) {
    static std::atomic<int> count{0};
    path_ = std::filesystem::temp_directory_path() /
            ("lumaslam_test_" + name + "_" + std::to_string(::getpid()) + "_" +
             std::to_string(count++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace lumaslam::test
