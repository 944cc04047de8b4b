// `lumaslam enhance` end to end: enhance one real dark image, write outputs, report per frame,
// fail clearly on a missing or corrupt input, and the --evaluate-pairs/-darkened/-stereo tables.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "test_cli.h"
#include "test_paths.h"

namespace {

using lumaslam::test::runCli;
using RunResult = lumaslam::test::CliResult;
using Rows = std::vector<std::vector<std::string>>;

// The cells after the key columns of the row whose first `key.size()` cells are `key`.
std::vector<std::string> rowOf(const Rows& rows, const std::vector<std::string>& key) {
  for (const auto& row : rows)
    if (row.size() >= key.size() && std::equal(key.begin(), key.end(), row.begin()))
      return {row.begin() + static_cast<long>(key.size()), row.end()};
  ADD_FAILURE() << "no row " << key.front() << (key.size() > 1 ? " " + key.back() : "");
  return {};
}

// The candidates every --evaluate-* table scores: raw (= preset off), OpenCV's CLAHE at fixed
// limits, then every preset (docs/enhancement.md).
const std::vector<std::string> kCandidates = {"raw",
                                              "cv::CLAHE clip 2",
                                              "cv::CLAHE clip 4",
                                              "cv::CLAHE clip 8",
                                              "cv::CLAHE clip 12",
                                              "cv::CLAHE clip 40",
                                              "off",
                                              "clahe",
                                              "paper",
                                              "best",
                                              "brightness",
                                              "adaptive_clahe",
                                              "value_clahe",
                                              "brightness_clahe",
                                              "full"};

TEST(CliEnhance, EnhancesADarkImageAndReportsTheDecision) {
  const auto dark = lumaslam::test::dataDir() / "mefb/exposure_pairs_43/input/Church/Church_A.png";
  lumaslam::test::TempDir out("cli_enhance");
  const RunResult run =
      runCli("enhance " + dark.string() + " --preset paper --out " + out.path().string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("Church_A Q=1"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("limit="), std::string::npos) << run.output;
  const cv::Mat input = cv::imread(dark.string());
  const cv::Mat enhanced = cv::imread((out.path() / "Church_A.png").string());
  ASSERT_FALSE(enhanced.empty());
  EXPECT_EQ(enhanced.size(), input.size());
  EXPECT_GT(cv::mean(enhanced)[1], cv::mean(input)[1]);
  const cv::Mat preview = cv::imread((out.path() / "Church_A_preview.jpg").string());
  EXPECT_EQ(preview.cols, 2 * input.cols);
  EXPECT_GT(preview.rows, input.rows);
}

TEST(CliEnhance, MissingAndCorruptInputsNameTheFile) {
  lumaslam::test::TempDir dir("cli_enhance_bad");
  const RunResult missing = runCli("enhance " + (dir.path() / "nothing.png").string());
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.output.find("nothing.png"), std::string::npos) << missing.output;
  const auto corrupt = dir.path() / "corrupt.png";
  std::ofstream(corrupt) << "not an image";
  const RunResult bad = runCli("enhance " + corrupt.string());
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.output.find("corrupt.png"), std::string::npos) << bad.output;

  // -1 is not "all frames" (issue 20).
  const RunResult negative = runCli("enhance " + corrupt.string() + " --max-frames -1");
  EXPECT_NE(negative.exit_code, 0);
  EXPECT_NE(negative.output.find("--max-frames: expected a whole number from 0 to 1000000000, "
                                 "found '-1'"),
            std::string::npos)
      << negative.output;
}

TEST(CliEnhance, CalibrateWritesSettingsThatReadBack) {
  lumaslam::test::TempDir out("cli_enhance_calibrate");
  const auto folder = lumaslam::test::dataDir() / "mefb/exposure_pairs_43/input/Arno";
  const RunResult run =
      runCli("enhance --calibrate " + folder.string() + " --out " + out.path().string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("Enhancement.clahe.sigmaMax"), std::string::npos) << run.output;
  const auto file = out.path() / "enhancement_calibrated.yaml";
  const RunResult reuse =
      runCli("enhance " + (folder / "Arno_A.png").string() + " --settings " + file.string());
  EXPECT_EQ(reuse.exit_code, 0) << reuse.output;
}

// --evaluate-pairs on two MEFB pairs (Church, Cave), each alone and both together: one row per
// candidate plus the --extra file; the totals are the sums of the single-pair runs and
// "pairs better than raw" counts the pairs whose correct matches beat raw's (the docs'
// definitions); off equals raw, clahe equals cv::CLAHE clip 2 (its fixed limit 2, 8x8), the
// --extra file holding only "Enhancement.preset: best" equals best.
TEST(CliEnhance, EvaluatePairsSumsOverThePairsWithOneRowPerCandidate) {
  lumaslam::test::TempDir dir("cli_enhance_pairs");
  const auto mefb = lumaslam::test::dataDir() / "mefb/exposure_pairs_43/input";
  const auto extra = dir.path() / "mine.yaml";
  std::ofstream(extra) << "Enhancement.preset: \"best\"\n";
  const auto evaluate = [&](const std::vector<std::string>& scenes) {
    const auto folder = dir.path() / ("pairs_" + std::to_string(scenes.size()) + scenes.front());
    std::filesystem::create_directories(folder);
    for (const auto& scene : scenes)
      std::filesystem::copy(mefb / scene, folder / scene, std::filesystem::copy_options::recursive);
    const RunResult run =
        runCli("enhance --evaluate-pairs " + folder.string() + " --extra " + extra.string());
    EXPECT_EQ(run.exit_code, 0) << run.output;
    return lumaslam::test::markdownRows(run.output);
  };
  const Rows both = evaluate({"Church", "Cave"});
  const Rows church = evaluate({"Church"});
  const Rows cave = evaluate({"Cave"});

  std::vector<std::string> names = kCandidates;
  names.push_back("mine");
  ASSERT_EQ(both.size(), names.size());
  for (std::size_t i = 0; i < names.size(); ++i) EXPECT_EQ(both[i][0], names[i]);
  const auto correct = [](const Rows& rows, const std::string& name) {
    return std::stol(rowOf(rows, {name})[0]);
  };
  for (const auto& name : names) {
    SCOPED_TRACE(name);
    const auto row = rowOf(both, {name});
    ASSERT_EQ(row.size(), 4u);
    for (int column = 0; column < 3; ++column)
      EXPECT_EQ(std::stol(row[column]),
                std::stol(rowOf(church, {name})[column]) + std::stol(rowOf(cave, {name})[column]));
    EXPECT_LE(std::stol(row[0]), std::stol(row[1]));  // correct ones are among the matches
    EXPECT_LE(std::stol(row[2]), 2 * 1000);           // ORB keeps at most 1000 per image
    const int better = (correct(church, name) > correct(church, "raw")) +
                       (correct(cave, name) > correct(cave, "raw"));
    EXPECT_EQ(row[3], std::to_string(better) + "/2");
  }
  EXPECT_EQ(rowOf(both, {"off"}), rowOf(both, {"raw"}));
  EXPECT_EQ(rowOf(both, {"clahe"}), rowOf(both, {"cv::CLAHE clip 2"}));
  EXPECT_EQ(rowOf(both, {"mine"}), rowOf(both, {"best"}));
  EXPECT_GT(correct(both, "best"), 2 * correct(both, "raw"));  // the docs: best wins 43/43
}

// --evaluate-darkened on 2 EuRoC V1_01 frames: one row per candidate at each of the three
// documented levels (A, gamma, noise); raw loses correct matches as the frames darken, the
// enhanced `best` keeps far more than raw at the darkest level; off equals raw, clahe equals
// cv::CLAHE clip 2; keypoints (ORB 1000) and 8x8 coverage are means per frame.
TEST(CliEnhance, EvaluateDarkenedScoresEveryCandidateAtEachLevel) {
  const auto euroc = lumaslam::test::dataDir() / "euroc/V1_01_easy_micro";
  const RunResult run = runCli("enhance --evaluate-darkened euroc-mono:" + euroc.string() +
                               " --max-frames 2 --stride 9");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const Rows rows = lumaslam::test::markdownRows(run.output);
  const std::vector<std::string> levels = {"0.50, 0.8, 0.010", "0.25, 0.6, 0.010",
                                           "0.12, 0.5, 0.015"};
  ASSERT_EQ(rows.size(), levels.size() * kCandidates.size()) << run.output;
  std::vector<double> raw_correct;
  for (const auto& level : levels) {
    SCOPED_TRACE(level);
    for (const auto& name : kCandidates) {
      const auto row = rowOf(rows, {level, name});
      ASSERT_EQ(row.size(), 3u) << name;
      EXPECT_LE(std::stod(row[0]), 1000.0) << name;
      EXPECT_GE(std::stod(row[1]), 0.0) << name;
      EXPECT_LE(std::stod(row[1]), 1.0) << name;
      EXPECT_LE(std::stod(row[2]), std::stod(row[0])) << name;
    }
    EXPECT_EQ(rowOf(rows, {level, "off"}), rowOf(rows, {level, "raw"}));
    EXPECT_EQ(rowOf(rows, {level, "clahe"}), rowOf(rows, {level, "cv::CLAHE clip 2"}));
    raw_correct.push_back(std::stod(rowOf(rows, {level, "raw"})[2]));
  }
  EXPECT_GT(raw_correct[0], raw_correct[1]);
  EXPECT_GT(raw_correct[1], raw_correct[2]);
  EXPECT_GT(std::stod(rowOf(rows, {levels[2], "best"})[2]), 3.0 * raw_correct[2]);
}

// --evaluate-stereo on 2 EuRoC V1_01 frames: off and each of best, paper, clahe with the
// independent, decisions and shared right-image mappings; clahe decisions equals clahe
// independent (a fixed limit and no gate: nothing to share, as the docs say). A dataset
// without a stereo calibration is an error naming it.
TEST(CliEnhance, EvaluateStereoCountsMatchesPerFrameForEveryMapping) {
  const auto euroc = lumaslam::test::dataDir() / "euroc/V1_01_easy_micro";
  const RunResult run =
      runCli("enhance --evaluate-stereo euroc:" + euroc.string() + " --max-frames 2");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("stereo matches per frame (2 frames)"), std::string::npos)
      << run.output;
  const Rows rows = lumaslam::test::markdownRows(run.output);
  std::vector<std::string> modes = {"off"};
  for (const char* preset : {"best", "paper", "clahe"})
    for (const char* how : {"independent", "decisions", "shared"})
      modes.push_back(std::string(preset) + " " + how);
  ASSERT_EQ(rows.size(), modes.size()) << run.output;
  for (std::size_t i = 0; i < modes.size(); ++i) {
    EXPECT_EQ(rows[i][0], modes[i]);
    EXPECT_GT(std::stod(rows[i][1]), 100.0) << modes[i];   // a textured room: hundreds
    EXPECT_LE(std::stod(rows[i][1]), 1000.0) << modes[i];  // at most one per ORB feature
  }
  EXPECT_EQ(rowOf(rows, {"clahe decisions"}), rowOf(rows, {"clahe independent"}));

  const RunResult mono =
      runCli("enhance --evaluate-stereo euroc-mono:" + euroc.string() + " --max-frames 1");
  EXPECT_EQ(mono.exit_code, 1);
  EXPECT_NE(mono.output.find("euroc-mono:" + euroc.string() + ": no stereo calibration"),
            std::string::npos)
      << mono.output;
}

}  // namespace
