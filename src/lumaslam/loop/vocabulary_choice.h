#pragma once
// Which vocabulary a Pipeline loads: the file the settings or options name, none at all
// ("none"), or, when nothing is named, the default vocabulary shipped with lumaslam
// (data/vocabulary/, installed to share/lumaslam/). The default is looked for in
// $LUMASLAM_VOCABULARY, then next to the executable (../share/lumaslam/), then in the source
// tree this build was configured from, then under the configured install prefix.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace lumaslam::loop {

// Loop.vocabulary: none / --vocabulary none / LUMASLAM_VOCABULARY=none: no vocabulary.
inline constexpr std::string_view kNoVocabulary = "none";
inline constexpr const char* kVocabularyEnvironment = "LUMASLAM_VOCABULARY";

bool isNoVocabulary(const std::filesystem::path& name);

// File name of the default vocabulary (data/vocabulary/<name>).
std::string defaultVocabularyName();

// Where the default vocabulary is looked for, in order (without the environment override).
std::vector<std::filesystem::path> defaultVocabularyLocations();

struct VocabularyChoice {
  std::filesystem::path file;  // empty: no vocabulary (relocalization and loop closing off)
  // Where the choice came from, for the startup log: "Loop.vocabulary / --vocabulary",
  // "LUMASLAM_VOCABULARY", "default", "none", or why no default was found.
  std::string origin;
  bool default_missing = false;  // nothing named and no default found (warn, run without)
};

// `named`: what Loop.vocabulary / PipelineOptions::vocabulary say; empty = nothing named. A
// named file or one from the environment is returned even if it does not exist (loading it
// then fails, naming it); the default locations are only taken when the file is there.
VocabularyChoice chooseVocabulary(const std::filesystem::path& named);

}  // namespace lumaslam::loop
