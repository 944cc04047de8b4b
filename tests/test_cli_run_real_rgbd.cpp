// `lumaslam run` on real Kinect v1 RGB-D as a user runs it: 7-Scenes redkitchen (497 frames,
// ../shared/data, see its SOURCE.md), default settings and flags, threaded mapping; and the
// same frames at a quarter of the frame rate, which turns the hand-held motion into a fast one
// (median 1.8 deg and 3.4 cm between frames, up to 5 deg). Threaded runs differ from run to
// run, so these assert properties that hold under any scheduling: no frame lost for long, and
// an ATE bound.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "test_cli.h"
#include "threaded_run_checks.h"

namespace {

using lumaslam::test::readRunSummary;
using lumaslam::test::runCli;
using lumaslam::test::TempDir;

std::filesystem::path redKitchen() {
  return lumaslam::test::dataDir() / "7scenes_redkitchen";
}

// A TUM folder with every `stride`-th line of the sequence's lists (images linked, not copied).
void writeSubsampled(const std::filesystem::path& dir, int stride) {
  for (const char* folder : {"rgb", "depth"}) {
    std::filesystem::create_directory_symlink(redKitchen() / folder, dir / folder);
  }
  std::filesystem::copy_file(redKitchen() / "settings.yaml", dir / "settings.yaml");
  for (const char* list : {"rgb.txt", "depth.txt", "groundtruth.txt"}) {
    std::ifstream in(redKitchen() / list);
    std::ofstream out(dir / list);
    std::string line;
    int row = 0;
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '#' || row++ % stride == 0) out << line << '\n';
    }
  }
}

// Longest run of consecutive lost frames after the first tracked one (timing.csv).
int longestLostRun(const std::filesystem::path& out) {
  bool started = false;
  int run = 0;
  int longest = 0;
  for (const auto& row : lumaslam::test::readTimingRows(out)) {
    if (row.state == "ok") {
      started = true;
      run = 0;
    } else if (started) {
      longest = std::max(longest, ++run);
    }
  }
  return longest;
}

int countTrajectoryLines(const std::filesystem::path& file) {
  std::ifstream in(file);
  int lines = 0;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line[0] != '#') ++lines;
  }
  return lines;
}

struct RealRun {
  int stride;
  double max_ate_m;
};

class CliRunRealRgbd : public ::testing::TestWithParam<RealRun> {};

// Measured with `lumaslam run --dataset tum:DIR --repeat 5` (threaded, default flags): see
// docs/accuracy.md, "Real data".
TEST_P(CliRunRealRgbd, TracksEveryFrameWithDefaultFlags) {
  const auto [stride, max_ate_m] = GetParam();
  ASSERT_TRUE(std::filesystem::exists(redKitchen()))
      << redKitchen() << " is missing: the shared data is a required test input";
  TempDir dir("cli_run_real_rgbd");
  const auto data = dir.path() / "data";
  std::filesystem::path dataset = redKitchen();
  if (stride > 1) {
    std::filesystem::create_directories(data);
    writeSubsampled(data, stride);
    dataset = data;
  }
  const auto out = dir.path() / "out";
  const auto run = runCli("run --dataset tum:" + dataset.string() + " --out " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto summary = readRunSummary(out);
  const auto frames = summary["frames"].get<int>();
  EXPECT_EQ(frames, (497 + stride - 1) / stride);
  // Issue 15: every frame after initialisation tracked, or relocalized within 10 frames.
  EXPECT_LE(longestLostRun(out), 10) << run.output;
  EXPECT_GE(summary["tracked"].get<int>(), frames - 10) << run.output;
  ASSERT_TRUE(summary.contains("evaluation")) << run.output;
  std::printf("stride %d: tracked %d/%d, ATE rmse %.1f mm\n", stride, summary["tracked"].get<int>(),
              frames, 1000.0 * summary["evaluation"]["ate"]["rmse"].get<double>());
  EXPECT_LT(summary["evaluation"]["ate"]["rmse"].get<double>(), max_ate_m);
  // The atlas in the summary: every tracked frame in one of its maps, the main one being
  // trajectory.txt (the others, if tracking ever started one, in trajectory_map<ID>.txt).
  ASSERT_TRUE(summary.contains("maps")) << run.output;
  int in_maps = 0;
  for (const auto& map : summary["maps"]) {
    in_maps += map["frames"].get<int>();
    EXPECT_EQ(countTrajectoryLines(out / map["trajectory"].get<std::string>()),
              map["frames"].get<int>());
  }
  EXPECT_EQ(in_maps, summary["tracked"].get<int>());
}

// 6 cm is already within 2x (issue 22): 32.1-34.4 mm (stride 1) and 33.7-34.6 mm (stride 4),
// 3 runs each on 2026-12-04 (threaded; logged above).
INSTANTIATE_TEST_SUITE_P(SevenScenes, CliRunRealRgbd,
                         ::testing::Values(RealRun{1, 0.06}, RealRun{4, 0.06}),
                         [](const auto& info) {
                           return "stride" + std::to_string(info.param.stride);
                         });

}  // namespace
