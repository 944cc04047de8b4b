// `lumaslam enhance` end to end: enhance one real dark image, write outputs, report per frame,
// and fail clearly on a missing or corrupt input.
#include <array>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>

#include <sys/wait.h>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "test_paths.h"

namespace {

struct RunResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

RunResult runCli(const std::string& arguments) {
  const std::string command = lumaslam::test::cliPath().string() + " " + arguments + " 2>&1";
  RunResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return result;
  std::array<char, 512> buffer{};
  while (fgets(buffer.data(), buffer.size(), pipe)) result.output += buffer.data();
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

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
  EXPECT_NE(run.output.find("Enhancement.clahe.sigma_max"), std::string::npos) << run.output;
  const auto file = out.path() / "enhancement_calibrated.yaml";
  const RunResult reuse =
      runCli("enhance " + (folder / "Arno_A.png").string() + " --settings " + file.string());
  EXPECT_EQ(reuse.exit_code, 0) << reuse.output;
}

}  // namespace
