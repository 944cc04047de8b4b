// Which vocabulary is loaded: a named file, "none", $LUMASLAM_VOCABULARY, or the default
// vocabulary committed in data/vocabulary/ (found in the source tree of this build).
#include <filesystem>

#include <gtest/gtest.h>

#include "lumaslam/loop/vocabulary_choice.h"
#include "lumaslam/loop/vocabulary_io.h"
#include "scoped_env.h"
#include "test_paths.h"

namespace {

using namespace lumaslam;
namespace fs = std::filesystem;

TEST(LoopVocabularyChoice, NamedFileAndNoneWinOverTheEnvironmentAndTheDefault) {
  const test::ScopedEnv env(loop::kVocabularyEnvironment, "/elsewhere/env.bin");
  const auto named = loop::chooseVocabulary("/data/my_vocab.bin");
  EXPECT_EQ(named.file, fs::path("/data/my_vocab.bin"));
  EXPECT_FALSE(named.default_missing);
  const auto none = loop::chooseVocabulary("none");
  EXPECT_TRUE(none.file.empty());
  EXPECT_FALSE(none.default_missing);
  EXPECT_NE(none.origin.find("none"), std::string::npos) << none.origin;
}

TEST(LoopVocabularyChoice, EnvironmentOverridesTheDefaultLocations) {
  {
    const test::ScopedEnv env(loop::kVocabularyEnvironment, "/elsewhere/env.bin");
    const auto choice = loop::chooseVocabulary({});
    // Returned even though it does not exist: loading it fails naming it, not silently.
    EXPECT_EQ(choice.file, fs::path("/elsewhere/env.bin"));
    EXPECT_EQ(choice.origin, loop::kVocabularyEnvironment);
  }
  const test::ScopedEnv env(loop::kVocabularyEnvironment, "none");
  const auto off = loop::chooseVocabulary({});
  EXPECT_TRUE(off.file.empty());
  EXPECT_FALSE(off.default_missing);
}

TEST(LoopVocabularyChoice, DefaultIsTheCommittedFileWhichLoadsAndIsSmall) {
  const test::ScopedEnv env(loop::kVocabularyEnvironment, std::nullopt);
  const fs::path committed = test::sourceDir() / "data/vocabulary" / loop::defaultVocabularyName();
  ASSERT_TRUE(fs::is_regular_file(committed)) << committed;
  EXPECT_LE(fs::file_size(committed), 4U << 20);
  const auto choice = loop::chooseVocabulary({});
  EXPECT_FALSE(choice.default_missing) << choice.origin;
  EXPECT_TRUE(fs::equivalent(choice.file, committed)) << choice.file;
  const loop::Vocabulary vocabulary = loop::loadVocabulary(choice.file);
  EXPECT_GE(vocabulary.wordCount(), 5000U);
}

TEST(LoopVocabularyChoice, LooksNextToTheExecutableFirstThenTheSourceTree) {
  const auto locations = loop::defaultVocabularyLocations();
  ASSERT_GE(locations.size(), 3U);
  // This test runs from the build tree: ../share/lumaslam next to it holds nothing.
  EXPECT_NE(locations[0].string().find("share/lumaslam"), std::string::npos) << locations[0];
  EXPECT_TRUE(fs::equivalent(locations[1].parent_path(), test::sourceDir() / "data/vocabulary"));
  for (const auto& location : locations) {
    EXPECT_EQ(location.filename(), loop::defaultVocabularyName());
  }
}

}  // namespace
