// The public API (system.h, dataset.h, evaluate.h) as a user of the installed library sees it:
// this test links only lumaslam::lumaslam (the shared library) and reads a sequence that
// `lumaslam synth` wrote, as a user's own camera code would hand frames over.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "lumaslam/dataset.h"
#include "lumaslam/evaluate.h"
#include "lumaslam/system.h"
#include "test_cli.h"
#include "test_paths.h"

namespace lumaslam {
namespace {

constexpr int kFrames = 120;

class PublicApi : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<test::TempDir>("public_api");
    const auto synth = test::runCli("synth --preset xyz-rgbd --frames " + std::to_string(kFrames) +
                                    " --seed 1 " + (dir_->path() / "seq").string());
    ASSERT_EQ(synth.exit_code, 0) << synth.output;
  }
  static void TearDownTestSuite() { dir_.reset(); }

  static std::filesystem::path sequence() { return dir_->path() / "seq"; }
  static std::filesystem::path settings() { return sequence() / "settings.yaml"; }
  static std::string spec() { return "tum:" + sequence().string(); }

  static SystemConfig sequentialConfig() {
    SystemConfig config;
    config.sequential = true;
    return config;
  }

  // Feeds the whole sequence; returns how many frames were tracked.
  static int trackAll(System& system, Dataset& dataset, std::size_t first_frame_number) {
    int tracked = 0;
    std::size_t expected = first_frame_number;
    while (auto frame = dataset.next()) {
      const TrackResult result = system.trackRgbd(frame->image, frame->depth, frame->timestamp);
      EXPECT_EQ(result.frame, expected++);
      EXPECT_EQ(result.timestamp, frame->timestamp);
      EXPECT_EQ(result.T_w_c.has_value(), result.state == TrackState::Tracking);
      if (result.state == TrackState::Tracking) ++tracked;
    }
    return tracked;
  }

  static inline std::unique_ptr<test::TempDir> dir_;
};

// `lumaslam run`'s trajectory.txt (TUM format) as public poses.
CameraTrajectory readTumTrajectory(const std::filesystem::path& file) {
  std::ifstream in(file);
  CameraTrajectory trajectory;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    double t, x, y, z, qx, qy, qz, qw;
    fields >> t >> x >> y >> z >> qx >> qy >> qz >> qw;
    CameraPose pose;
    pose.timestamp = t;
    pose.T_w_c.topLeftCorner<3, 3>() = Eigen::Quaterniond(qw, qx, qy, qz).toRotationMatrix();
    pose.T_w_c.topRightCorner<3, 1>() = Eigen::Vector3d(x, y, z);
    trajectory.push_back(pose);
  }
  return trajectory;
}

TEST_F(PublicApi, TracksASyntheticRgbdSequenceWithinOneCentimetre) {
  System system(settings(), sequentialConfig());
  Dataset dataset(spec());
  ASSERT_EQ(system.sensor(), Sensor::Rgbd);
  ASSERT_EQ(dataset.size(), static_cast<std::size_t>(kFrames));
  const int tracked = trackAll(system, dataset, 0);
  system.shutdown();

  EXPECT_GE(tracked, kFrames * 95 / 100);
  EXPECT_EQ(system.frameCount(), static_cast<std::size_t>(kFrames));
  EXPECT_GT(system.keyframeCount(), 0u);
  EXPECT_GT(system.mapPointCount(), 100u);
  const CameraTrajectory trajectory = system.trajectory();
  EXPECT_EQ(trajectory.size(), static_cast<std::size_t>(tracked));
  const TrajectoryErrors errors = evaluate(trajectory, dataset.groundTruth());
  const TrajectoryErrors keyframes = evaluate(system.keyframeTrajectory(), dataset.groundTruth());
  std::printf("public API, xyz-rgbd %d frames: ATE rmse %.2f mm (frames), %.2f mm (keyframes)\n",
              kFrames, 1000.0 * errors.ate.rmse, 1000.0 * keyframes.ate.rmse);
  // ~2x the measured ATE (issue 22; the name's centimetre was the first bound): 2.61 mm
  // (frames) and 1.99 mm (keyframes), sequential; 2026-12-08, `build/tests/test_api_system
  // --gtest_filter=*WithinOneCentimetre`, the "public API" line.
  EXPECT_LE(errors.ate.rmse, 0.0055);
  EXPECT_GE(errors.coverage, 0.95);
  EXPECT_EQ(errors.scale, 1.0);
  EXPECT_LE(keyframes.ate.rmse, 0.004);
}

TEST_F(PublicApi, MatchesTheCliTrajectoryInSequentialMode) {
  const auto out = dir_->path() / "cli";
  const auto run = test::runCli("run --dataset " + spec() + " --sequential --out " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const CameraTrajectory cli = readTumTrajectory(out / "trajectory.txt");

  System system(settings(), sequentialConfig());
  Dataset dataset(spec());
  trackAll(system, dataset, 0);
  system.shutdown();
  const CameraTrajectory api = system.trajectory();

  ASSERT_EQ(api.size(), cli.size());
  for (std::size_t i = 0; i < api.size(); ++i) {
    EXPECT_NEAR(api[i].timestamp, cli[i].timestamp, 1e-6) << i;
    EXPECT_LE((api[i].T_w_c - cli[i].T_w_c).cwiseAbs().maxCoeff(), 1e-9) << i;
  }
}

TEST_F(PublicApi, ResetStartsAFreshMapAndKeepsNumberingFrames) {
  System system(settings(), sequentialConfig());
  {
    Dataset first(spec(), 30);
    trackAll(system, first, 0);
  }
  EXPECT_GT(system.keyframeCount(), 0u);
  system.setLocalizationMode(true);
  system.reset();
  EXPECT_FALSE(system.localizationMode());
  EXPECT_EQ(system.keyframeCount(), 0u);
  EXPECT_TRUE(system.trajectory().empty());
  Dataset again(spec(), 30);  // the same timestamps again: a new map may restart the clock
  const int tracked = trackAll(system, again, 30);
  EXPECT_GE(tracked, 28);
  EXPECT_EQ(system.frameCount(), 60u);
}

TEST_F(PublicApi, LocalizesInASavedMapWithoutAddingKeyframes) {
  const auto map_file = dir_->path() / "room.lmap";
  std::size_t mapped_keyframes = 0;
  {
    System mapping(settings(), sequentialConfig());
    Dataset dataset(spec());
    trackAll(mapping, dataset, 0);
    mapping.saveMap(map_file);
    mapped_keyframes = mapping.keyframeCount();
    EXPECT_THROW(mapping.trackRgbd(cv::Mat(), cv::Mat(), 1e12), std::runtime_error);
  }
  ASSERT_TRUE(std::filesystem::exists(map_file));

  System localizing(settings(), sequentialConfig());
  localizing.loadMap(map_file);
  localizing.setLocalizationMode(true);
  EXPECT_EQ(localizing.keyframeCount(), mapped_keyframes);
  Dataset dataset(spec());
  const int tracked = trackAll(localizing, dataset, 0);
  EXPECT_GE(tracked, kFrames * 95 / 100);
  EXPECT_EQ(localizing.keyframeCount(), mapped_keyframes);
  localizing.shutdown();
  const TrajectoryErrors errors = evaluate(localizing.trajectory(), dataset.groundTruth());
  std::printf("public API, localization in the saved map: ATE rmse %.2f mm\n",
              1000.0 * errors.ate.rmse);
  // ~2x the measured ATE (issue 22): 2.21 mm, sequential; 2026-12-08,
  // `build/tests/test_api_system --gtest_filter=*LocalizesInASavedMap*`.
  EXPECT_LE(errors.ate.rmse, 0.0045);
}

TEST_F(PublicApi, WrongSensorAndBadTimestampsAreErrors) {
  System system(settings(), sequentialConfig());
  Dataset dataset(spec(), 2);
  const auto frame = dataset.next();
  ASSERT_TRUE(frame);
  try {
    system.trackMonocular(frame->image, frame->timestamp);
    FAIL() << "trackMonocular on an RGB-D System did not throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("trackMonocular"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("rgbd"), std::string::npos) << e.what();
  }
  EXPECT_THROW(system.trackStereo(frame->image, frame->image, frame->timestamp),
               std::runtime_error);
  system.trackRgbd(frame->image, frame->depth, frame->timestamp);
  EXPECT_THROW(system.trackRgbd(frame->image, frame->depth, frame->timestamp), std::runtime_error);
  EXPECT_THROW(
      system.trackRgbd(frame->image, frame->depth, std::numeric_limits<double>::quiet_NaN()),
      std::runtime_error);
  EXPECT_EQ(system.frameCount(), 1u);  // rejected frames are not numbered
}

TEST_F(PublicApi, BadFilesAndPosesAreErrorsNamingTheProblem) {
  try {
    System system(dir_->path() / "missing.yaml");
    FAIL() << "a missing settings file did not throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("missing.yaml"), std::string::npos) << e.what();
  }
  EXPECT_THROW(Dataset("tum:" + (dir_->path() / "nowhere").string()), std::runtime_error);
  CameraTrajectory bent(3);
  for (std::size_t i = 0; i < bent.size(); ++i) bent[i].timestamp = static_cast<double>(i);
  bent[1].T_w_c(0, 1) = 0.5;  // not a rotation
  try {
    evaluate(bent, bent);
    FAIL() << "a non-rigid pose did not throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("pose 1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lumaslam
