// Issue 20, keeping the user's results in `lumaslam run`: a bad frame mid-sequence is skipped
// and counted (or, with --on-bad-frame stop, ends the run with what was tracked written);
// SIGINT / SIGTERM mid-run write the partial results, marked so, and exit 130 / 143; a write
// failure is an error naming the file (the other results are still written); an output folder
// that cannot be written fails before the first frame; an earlier run's files do not survive
// a new run in the same folder. Synthetic TUM RGB-D datasets, sequential mapping.
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fcntl.h>

#include <chrono>
#include <fstream>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "lumaslam/io/trajectory_io.h"
#include "test_cli.h"

extern char** environ;

namespace {

using lumaslam::test::readRunSummary;
using lumaslam::test::runCli;
using lumaslam::test::TempDir;

// The image files a TUM dataset lists in rgb.txt, in order.
std::vector<std::filesystem::path> rgbFiles(const std::filesystem::path& data) {
  std::ifstream list(data / "rgb.txt");
  std::vector<std::filesystem::path> files;
  for (std::string line; std::getline(list, line);) {
    if (line.empty() || line[0] == '#') continue;
    files.push_back(data / line.substr(line.find(' ') + 1));
  }
  return files;
}

void synthesize(const std::filesystem::path& data, int frames) {
  const auto synth = runCli("synth " + data.string() + " --preset xyz-rgbd --frames " +
                            std::to_string(frames) + " --seed 2");
  ASSERT_EQ(synth.exit_code, 0) << synth.output;
}

std::size_t trajectoryPoses(const std::filesystem::path& file) {
  return lumaslam::io::readTrajectory(file).size();
}

bool anyPartialFileIn(const std::filesystem::path& folder) {
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.path().extension() == ".partial") return true;
  }
  return false;
}

class CliRunSafeOutput : public ::testing::Test {
 protected:
  static constexpr int kFrames = 30;
  static constexpr int kBadFrame = 10;
  void SetUp() override { synthesize(data_, kFrames); }
  std::filesystem::path badImage() const { return rgbFiles(data_)[kBadFrame]; }
  lumaslam::test::CliResult run(const std::string& extra = "") const {
    return runCli("run --dataset tum:" + data_.string() + " --sequential --out " + out_.string() +
                  " " + extra);
  }
  TempDir dir_{"cli_run_safe_output"};
  std::filesystem::path data_ = dir_.path() / "data";
  std::filesystem::path out_ = dir_.path() / "out";
};

TEST_F(CliRunSafeOutput, AnUnreadableFrameIsSkippedNamingTheFileAndCounted) {
  std::ofstream(badImage(), std::ios::trunc) << "not a png";
  const auto result = run();
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find(badImage().filename().string()), std::string::npos) << result.output;
  const auto summary = readRunSummary(out_);
  EXPECT_EQ(summary["status"], "complete");
  EXPECT_EQ(summary["skipped_frames"].get<int>(), 1);
  EXPECT_NE(summary["skipped"][0].get<std::string>().find(badImage().filename().string()),
            std::string::npos);
  EXPECT_EQ(summary["frames"].get<int>(), kFrames - 1);
  EXPECT_GE(summary["tracked"].get<int>(), kFrames - 2);
  EXPECT_EQ(trajectoryPoses(out_ / "trajectory.txt"), summary["tracked"].get<std::size_t>());
}

TEST_F(CliRunSafeOutput, AFrameOfAnotherSizeIsSkippedNamingTheFile) {
  cv::imwrite(badImage().string(), cv::Mat(240, 320, CV_8UC3, cv::Scalar(90, 120, 60)));
  const auto result = run();
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const auto summary = readRunSummary(out_);
  EXPECT_EQ(summary["skipped_frames"].get<int>(), 1) << result.output;
  EXPECT_NE(summary["skipped"][0].get<std::string>().find(badImage().filename().string()),
            std::string::npos)
      << summary["skipped"][0];
  EXPECT_GE(summary["tracked"].get<int>(), kFrames - 2);
}

TEST_F(CliRunSafeOutput, OnBadFrameStopEndsTheRunWithWhatWasTrackedWritten) {
  std::ofstream(badImage(), std::ios::trunc) << "not a png";
  const auto result = run("--on-bad-frame stop");
  EXPECT_NE(result.exit_code, 0) << result.output;
  const auto summary = readRunSummary(out_);
  EXPECT_EQ(summary["status"], "stopped at a bad frame");
  EXPECT_EQ(summary["frames"].get<int>(), kBadFrame);
  EXPECT_EQ(trajectoryPoses(out_ / "trajectory.txt"), summary["tracked"].get<std::size_t>());
  EXPECT_GE(summary["tracked"].get<int>(), kBadFrame - 1);
}

// A directory where summary.json must go: the rename fails. The error names the file, the
// exit code is non-zero, and the trajectory (written first) is complete.
TEST_F(CliRunSafeOutput, AWriteFailureIsAnErrorNamingTheFile) {
  std::filesystem::create_directories(out_ / "summary.json" / "in_the_way");
  const auto result = run();
  EXPECT_NE(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("summary.json"), std::string::npos) << result.output;
  ASSERT_TRUE(std::filesystem::exists(out_ / "trajectory.txt"));
  EXPECT_GE(trajectoryPoses(out_ / "trajectory.txt"), static_cast<std::size_t>(kFrames - 1));
  EXPECT_FALSE(anyPartialFileIn(out_));
  EXPECT_FALSE(std::filesystem::exists(out_ / "manifest.json"));  // the run did not finish
}

// manifest.json is written last: every result file with its size and the run's status; a run
// that failed while writing its results has none.
TEST_F(CliRunSafeOutput, TheManifestListsEveryResultFileWithItsSize) {
  const auto result = run("--max-frames 10");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  std::ifstream in(out_ / "manifest.json");
  ASSERT_TRUE(in) << "no manifest.json";
  const auto manifest = nlohmann::json::parse(in);
  EXPECT_EQ(manifest["status"], "complete");
  EXPECT_TRUE(manifest["errors"].empty());
  std::set<std::string> listed;
  for (const auto& file : manifest["files"]) {
    const std::string name = file["name"];
    listed.insert(name);
    EXPECT_EQ(file["bytes"].get<std::uintmax_t>(), std::filesystem::file_size(out_ / name)) << name;
  }
  for (const char* name : {"trajectory.txt", "keyframes.txt", "timing.csv", "summary.json"}) {
    EXPECT_TRUE(listed.count(name)) << name << " not in the manifest";
  }
  EXPECT_FALSE(listed.count("manifest.json"));
}

TEST_F(CliRunSafeOutput, AnOutputFolderThatCannotBeCreatedFailsBeforeTheFirstFrame) {
  const auto result = runCli("run --dataset tum:" + data_.string() +
                             " --sequential --out /proc/lumaslam_no_such_folder");
  EXPECT_NE(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("/proc/lumaslam_no_such_folder"), std::string::npos)
      << result.output;
  EXPECT_EQ(result.output.find("map 0 initialised"), std::string::npos) << result.output;
}

TEST_F(CliRunSafeOutput, AnEarlierRunsFilesDoNotSurviveANewRun) {
  std::filesystem::create_directories(out_);
  std::ofstream(out_ / "trajectory_map7.txt") << "# stale\n1 0 0 0 0 0 0 1\n";
  std::ofstream(out_ / "evaluation.svg") << "<svg/>";
  std::ofstream(out_ / "report.html") << "<!DOCTYPE html>";  // `lumaslam report` of that run
  std::filesystem::remove(data_ / "groundtruth.txt");  // nothing to evaluate: no new plot
  const auto result = run("--max-frames 5");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_FALSE(std::filesystem::exists(out_ / "trajectory_map7.txt"));
  EXPECT_FALSE(std::filesystem::exists(out_ / "evaluation.svg"));
  EXPECT_FALSE(std::filesystem::exists(out_ / "report.html"));
  EXPECT_TRUE(std::filesystem::exists(out_ / "summary.json"));
}

// SIGINT and SIGTERM once the run is past frame 20 of 150: partial results, marked so, every
// file complete (no .partial left), exit 128 + signal.
class CliRunSignal : public ::testing::TestWithParam<int> {};

TEST_P(CliRunSignal, StopsAndWritesThePartialResults) {
  const int signal_number = GetParam();
  TempDir dir("cli_run_signal");
  const auto data = dir.path() / "data";
  const auto out = dir.path() / "out";
  constexpr int kFrames = 150;
  synthesize(data, kFrames);
  const std::string cli = lumaslam::test::cliPath().string();
  const std::string dataset = "tum:" + data.string();
  const std::string out_arg = out.string();
  std::vector<std::string> args = {cli,     "run",  "--dataset", dataset, "--sequential",
                                   "--out", out_arg};
  std::vector<char*> argv;
  for (auto& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, (dir.path() / "log").c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, cli.c_str(), &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);

  // Wait (polling, no timing asserted) until timing.csv holds 20 frames.
  const auto partial_timing = out / "timing.csv.partial";
  int rows = 0;
  for (int attempt = 0; attempt < 6000 && rows <= 20; ++attempt) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    std::ifstream timing(partial_timing);
    rows = 0;
    for (std::string line; std::getline(timing, line);) ++rows;
  }
  ASSERT_GT(rows, 20) << "the run never got past frame 20";
  ASSERT_EQ(kill(pid, signal_number), 0);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 128 + signal_number);

  const auto summary = readRunSummary(out);
  EXPECT_EQ(summary["status"], "partial");
  std::ifstream manifest(out / "manifest.json");
  ASSERT_TRUE(manifest) << "no manifest.json";
  EXPECT_EQ(nlohmann::json::parse(manifest)["status"], "partial");
  const int frames = summary["frames"].get<int>();
  EXPECT_GE(frames, 20);
  EXPECT_LT(frames, kFrames);
  EXPECT_EQ(trajectoryPoses(out / "trajectory.txt"), summary["tracked"].get<std::size_t>());
  EXPECT_GE(summary["tracked"].get<int>(), frames - 1);
  EXPECT_FALSE(anyPartialFileIn(out));
  std::ifstream timing(out / "timing.csv");
  int timing_rows = -1;  // the header
  for (std::string line; std::getline(timing, line);) ++timing_rows;
  EXPECT_EQ(timing_rows, frames);
}

INSTANTIATE_TEST_SUITE_P(Signals, CliRunSignal, ::testing::Values(SIGINT, SIGTERM),
                         [](const auto& info) {
                           return info.param == SIGINT ? std::string("Sigint")
                                                       : std::string("Sigterm");
                         });

}  // namespace
