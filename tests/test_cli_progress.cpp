// Progress lines (issue 18): `run`, `synth` and `vocab train` show frames, rate and ETA on a
// terminal (here a pseudo-terminal made by util-linux `script`) and print no progress at all into a
// pipe.
#include <gtest/gtest.h>

#include "test_cli.h"

namespace {

using lumaslam::test::cliPath;
using lumaslam::test::runCli;
using lumaslam::test::TempDir;

// Runs the CLI with stdout and stderr on a pseudo-terminal; returns what it printed.
std::string runOnTerminal(const std::string& arguments) {
  const std::string command =
      "script -qec '" + cliPath().string() + " " + arguments + "' /dev/null";
  std::string output;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return output;
  std::array<char, 4096> buffer{};
  while (fgets(buffer.data(), buffer.size(), pipe)) output += buffer.data();
  pclose(pipe);
  return output;
}

class CliProgress : public ::testing::Test {
 protected:
  TempDir dir_{"cli_progress"};
  std::string data_ = (dir_.path() / "data").string();
};

TEST_F(CliProgress, OnATerminalSynthAndRunShowFramesRateAndEta) {
  const std::string synth = runOnTerminal("synth " + data_ + " --preset xyz-rgbd --frames 80");
  EXPECT_NE(synth.find("\rframe 80/80"), std::string::npos) << synth;
  EXPECT_NE(synth.find(" fps"), std::string::npos) << synth;
  const std::string run =
      runOnTerminal("run --dataset tum:" + data_ + " --out " + (dir_.path() / "out").string());
  EXPECT_NE(run.find("\rframe 80/80"), std::string::npos) << run;
  EXPECT_NE(run.find("  ok"), std::string::npos) << "the tracking state: " << run;
  EXPECT_NE(run.find("ETA"), std::string::npos) << run;
}

TEST_F(CliProgress, OnATerminalVocabTrainShowsImagesExtracted) {
  ASSERT_EQ(runCli("synth " + data_ + " --preset xyz-rgbd --frames 12").exit_code, 0);
  const std::string train =
      runOnTerminal("vocab train " + data_ + "/rgb --out " + (dir_.path() / "v.bin").string() +
                    " --k 4 --levels 2 --max-images 12");
  EXPECT_NE(train.find("\rimage 12/12"), std::string::npos) << train;
  EXPECT_NE(train.find("extracting"), std::string::npos) << train;
  // The k-majority clustering: every descriptor ends in a leaf ("descriptors N" is printed).
  const auto printed = train.find("\ndescriptors ");
  ASSERT_NE(printed, std::string::npos) << train;
  const auto digits = printed + 13;
  const std::string count = train.substr(digits, train.find_first_of("\r\n", digits) - digits);
  EXPECT_NE(train.find("\rdescriptor " + count + "/" + count), std::string::npos) << train;
  EXPECT_NE(train.find("clustering"), std::string::npos) << train;
  const auto piped = runCli("vocab train " + data_ + "/rgb --out " +
                            (dir_.path() / "w.bin").string() + " --k 4 --levels 2");
  ASSERT_EQ(piped.exit_code, 0) << piped.output;
  EXPECT_EQ(piped.output.find('\r'), std::string::npos) << piped.output;
}

TEST_F(CliProgress, OnATerminalPerturbShowsImagesDone) {
  ASSERT_EQ(runCli("synth " + data_ + " --preset xyz-rgbd --frames 12").exit_code, 0);
  const std::string perturb = runOnTerminal(
      "perturb " + data_ + " " + (dir_.path() / "dark").string() + " --model dark --level 3");
  EXPECT_NE(perturb.find("\rimage 12/12"), std::string::npos) << perturb;
  EXPECT_NE(perturb.find("perturbing"), std::string::npos) << perturb;
  const auto piped = runCli("perturb " + data_ + " " + (dir_.path() / "dark2").string() +
                            " --model dark --level 3");
  ASSERT_EQ(piped.exit_code, 0) << piped.output;
  EXPECT_EQ(piped.output.find('\r'), std::string::npos) << piped.output;
}

TEST_F(CliProgress, InAPipeThereIsNoProgressLine) {
  const auto synth = runCli("synth " + data_ + " --preset xyz-rgbd --frames 20");
  ASSERT_EQ(synth.exit_code, 0) << synth.output;
  EXPECT_EQ(synth.output.find('\r'), std::string::npos) << synth.output;
  const auto run =
      runCli("run --dataset tum:" + data_ + " --out " + (dir_.path() / "out").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_EQ(run.output.find('\r'), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find(" fps"), std::string::npos) << run.output;
}

}  // namespace
