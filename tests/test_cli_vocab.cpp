// Runs the built `lumaslam vocab` (train / convert / info) on synthetic images and the
// shared EuRoC excerpt, and on bad input.
#include <fstream>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "loop_test_frames.h"
#include "lumaslam/io/dataset_reader.h"
#include "lumaslam/loop/vocabulary_io.h"
#include "test_cli.h"
#include "test_paths.h"

namespace lumaslam {
namespace {

using test::runCli;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(CliVocab, TrainInfoConvertRoundTrip) {
  const test::TempDir dir("cli_vocab");
  // Six synthetic frames as PNGs in a folder, plus frames of a real EuRoC sequence.
  const auto images = dir.path() / "images";
  std::filesystem::create_directories(images);
  const auto lap = test::renderLoopLap(6, 5);
  for (std::size_t i = 0; i < lap.gray.size(); ++i) {
    cv::imwrite((images / ("frame" + std::to_string(i) + ".png")).string(), lap.gray[i]);
  }
  const auto euroc = test::dataDir() / "euroc" / "V1_01_easy_micro";
  const auto vocab = dir.path() / "vocab.bin";
  const auto train = runCli("vocab train --k 6 --levels 3 --features 500 --stride 10 --out " +
                            vocab.string() + " " + images.string() + " euroc:" + euroc.string());
  ASSERT_EQ(train.exit_code, 0) << train.output;
  const std::size_t euroc_frames = io::openDataset("euroc:" + euroc.string())->size();
  // --stride 10 applies to each input.
  const std::size_t expected_images = (lap.gray.size() + 9) / 10 + (euroc_frames + 9) / 10;
  EXPECT_TRUE(contains(train.output, "images " + std::to_string(expected_images) + "\n"))
      << train.output;
  EXPECT_TRUE(contains(train.output, "k 6\nL 3")) << train.output;
  const loop::Vocabulary trained = loop::loadVocabulary(vocab);
  EXPECT_EQ(trained.branching(), 6);
  EXPECT_GT(trained.wordCount(), 100U);

  const auto info = runCli("vocab info " + vocab.string());
  ASSERT_EQ(info.exit_code, 0) << info.output;
  EXPECT_TRUE(contains(info.output, "format lumaslam-binary"));
  EXPECT_TRUE(contains(info.output, "words " + std::to_string(trained.wordCount()) + "\n"));

  // DBoW2 text -> convert -> the same vocabulary.
  const auto text = dir.path() / "voc.txt";
  loop::saveDbow2Text(trained, text);
  const auto converted = dir.path() / "converted.bin";
  const auto convert = runCli("vocab convert " + text.string() + " --out " + converted.string());
  ASSERT_EQ(convert.exit_code, 0) << convert.output;
  EXPECT_EQ(loop::loadVocabulary(converted), trained);
  EXPECT_TRUE(contains(runCli("vocab info " + text.string()).output, "format dbow2-text"));

  // --max-images caps the total over all inputs.
  const auto capped = runCli("vocab train --k 4 --levels 2 --max-images 3 --out " +
                             (dir.path() / "capped.bin").string() + " " + images.string() +
                             " euroc:" + euroc.string());
  ASSERT_EQ(capped.exit_code, 0) << capped.output;
  EXPECT_TRUE(contains(capped.output, "images 3\n")) << capped.output;
}

TEST(CliVocab, BadInputExitsNonZeroWithAMessage) {
  const test::TempDir dir("cli_vocab_bad");
  const auto out = (dir.path() / "v.bin").string();

  auto result = runCli("vocab train --out " + out + " " + (dir.path() / "nowhere").string());
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_TRUE(contains(result.output, "nowhere: no such image file or folder")) << result.output;

  result = runCli("vocab train --k 1 --out " + out + " " + dir.path().string());
  EXPECT_NE(result.exit_code, 0);  // empty folder or bad k: both are errors

  const auto bad_text = dir.path() / "ORBvoc.txt";
  std::ofstream(bad_text) << "10 6 0 0\n0 1 1 2 3\n";
  result = runCli("vocab convert " + bad_text.string() + " --out " + out);
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_TRUE(contains(result.output, "ORBvoc.txt:2: expected 35 fields")) << result.output;
  EXPECT_FALSE(std::filesystem::exists(out));

  result = runCli("vocab info " + bad_text.string());
  EXPECT_EQ(result.exit_code, 1);

  result = runCli("vocab convert " + bad_text.string());  // --out missing
  EXPECT_NE(result.exit_code, 0);
  result = runCli("vocab");  // no subcommand
  EXPECT_NE(result.exit_code, 0);
}

}  // namespace
}  // namespace lumaslam
