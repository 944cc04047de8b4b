#include "lumaslam/loop/vocabulary_choice.h"

#include <dlfcn.h>

#include <cstdlib>
#include <system_error>

#include <spdlog/fmt/fmt.h>

// Set by loop/CMakeLists.txt for this file only, so that moving the source tree or changing
// the install prefix recompiles nothing else.
#ifndef LUMASLAM_DEFAULT_VOCABULARY_NAME
#error "LUMASLAM_DEFAULT_VOCABULARY_NAME must be defined (loop/CMakeLists.txt)"
#endif

namespace lumaslam::loop {
namespace {

namespace fs = std::filesystem;

fs::path executableFolder() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path() : exe.parent_path();
}

// The file this code was loaded from: the installed shared library for a consumer of the
// package (lib/liblumaslam.so), the executable when linked statically.
fs::path loadedObjectFolder() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<const void*>(&executableFolder), &info) == 0 || !info.dli_fname) {
    return {};
  }
  std::error_code ec;
  const fs::path object = fs::canonical(info.dli_fname, ec);
  return ec ? fs::path() : object.parent_path();
}

bool isFile(const fs::path& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

}  // namespace

bool isNoVocabulary(const fs::path& name) {
  return name.native() == kNoVocabulary;
}

std::string defaultVocabularyName() {
  return LUMASLAM_DEFAULT_VOCABULARY_NAME;
}

std::vector<fs::path> defaultVocabularyLocations() {
  const std::string name = defaultVocabularyName();
  std::vector<fs::path> locations;
  if (const fs::path exe = executableFolder(); !exe.empty()) {
    locations.push_back((exe / LUMASLAM_BIN_TO_VOCABULARY_DIR / name).lexically_normal());
  }
  if (const fs::path lib = loadedObjectFolder(); !lib.empty() && lib != executableFolder()) {
    locations.push_back((lib / LUMASLAM_LIB_TO_VOCABULARY_DIR / name).lexically_normal());
  }
  locations.push_back(fs::path(LUMASLAM_SOURCE_VOCABULARY_DIR) / name);
  locations.push_back(fs::path(LUMASLAM_INSTALL_VOCABULARY_DIR) / name);
  return locations;
}

VocabularyChoice chooseVocabulary(const fs::path& named) {
  if (isNoVocabulary(named)) return {{}, "Loop.vocabulary / --vocabulary none", false};
  if (!named.empty()) return {named, "Loop.vocabulary / --vocabulary", false};
  if (const char* env = std::getenv(kVocabularyEnvironment); env && *env) {
    if (isNoVocabulary(env)) return {{}, fmt::format("{}=none", kVocabularyEnvironment), false};
    return {env, kVocabularyEnvironment, false};
  }
  std::string tried;
  for (const fs::path& location : defaultVocabularyLocations()) {
    if (isFile(location)) return {location, "default vocabulary", false};
    tried += (tried.empty() ? "" : ", ") + location.string();
  }
  return {{},
          fmt::format("default vocabulary {} not found in {}", defaultVocabularyName(), tried),
          true};
}

}  // namespace lumaslam::loop
