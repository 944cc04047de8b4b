// Cost of the class-free motion test (issue 16's budget: <= 2 ms per 640x480 frame) on
// hand-built RGB-D frames of the size tracking hands it: 1000 features, all matched to map
// points, 850 on a static room 1.5-4 m away and 150 on a person 1.5 m away walking 3 cm a
// frame, Kinect-like depth noise, the camera moving 1 cm and turning 0.3 degrees a frame.
// MotionEvidence::update is what timing.csv's motion_ms measures (with rigidConsensus when
// Dynamic.rigidConsensus is on); BM_OrbOpenCvRgbdSequence (bench_tracking.cpp) is the
// reference in the same process: cv::ORB, 1000 features, on a 640x480 frame.
#include <memory>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "lumaslam/feature/scale_levels.h"
#include "lumaslam/track/motion_evidence.h"
#include "lumaslam/track/rigid_consensus.h"

namespace {

using namespace lumaslam;

constexpr int kStatic = 850;
constexpr int kPerson = 150;
constexpr int kFrames = 30;
constexpr double kBf = 40.0;  // Kinect-like virtual baseline x fx

track::FrameCamera benchCamera() {
  return {camera::PinholeCamera(525, 525, 319.5, 239.5, camera::ImageSize{640, 480}), kBf, 3.0};
}

struct Scene {
  std::vector<Eigen::Vector3d> points;  // world, at frame 0
  std::vector<bool> moves;
};

Scene scene() {
  Scene s;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_real_distribution<double> depth(1.5, 4.0);
  for (int i = 0; i < kStatic + kPerson; ++i) {
    const bool person = i >= kStatic;
    const double z = person ? 1.5 : depth(rng);
    // Inside the 60 x 46 degree view: x within +-0.55 z, y within +-0.4 z.
    s.points.emplace_back(unit(rng) * (person ? 0.2 : 0.5 * z),
                          unit(rng) * (person ? 0.5 : 0.38 * z), z);
    s.moves.push_back(person);
  }
  return s;
}

SE3 cameraPose(std::size_t index) {
  const double t = static_cast<double>(index);
  return SE3(Eigen::AngleAxisd(0.005 * t, Eigen::Vector3d::UnitY())) *
         SE3(Eigen::Translation3d(-0.01 * t, 0, 0));
}

struct Sequence {
  Scene scene;
  track::FrameCamera camera;
  std::vector<std::shared_ptr<map::MapPoint>> points;
  std::vector<track::Frame> frames;
};

track::Frame render(const Sequence& q, std::size_t index, const cv::Mat& descriptors,
                    std::mt19937& rng) {
  std::normal_distribution<double> noise(0.0, 1.0);
  track::Frame frame;
  frame.index = index;
  frame.timestamp = static_cast<double>(index) / 30.0;
  frame.T_c_w = cameraPose(index);
  auto features = std::make_shared<map::FeatureSet>();
  features->descriptors = descriptors.clone();
  for (std::size_t i = 0; i < q.scene.points.size(); ++i) {
    Eigen::Vector3d X = q.scene.points[i];
    if (q.scene.moves[i]) X.x() += 0.03 * static_cast<double>(index);
    const Eigen::Vector3d X_c = *frame.T_c_w * X;
    const Eigen::Vector2d uv = q.camera.pinhole.project(X_c);
    const cv::Point2f p(static_cast<float>(uv.x()), static_cast<float>(uv.y()));
    const double z = X_c.z() + 1.4e-3 * X_c.z() * X_c.z() * noise(rng);
    features->keypoints.emplace_back(p, 31.0F, 0.0F, 0.0F, 0);
    features->undistorted.push_back(p);
    features->depth.push_back(static_cast<float>(z));
    features->u_right.push_back(static_cast<float>(uv.x() - kBf / z));
  }
  features->grid =
      std::make_shared<const feature::FeatureGrid>(features->keypoints, cv::Rect2f(0, 0, 640, 480));
  frame.features = features;
  frame.clearMatches();
  if (index == 0) return frame;
  frame.points = q.points;
  // Pose optimisation rejected the person's points (their residual is tens of pixels).
  for (std::size_t i = 0; i < q.scene.points.size(); ++i) frame.outliers[i] = q.scene.moves[i];
  return frame;
}

const Sequence& sequence() {
  static const Sequence q = [] {
    Sequence s{scene(), benchCamera(), {}, {}};
    const int n = kStatic + kPerson;
    cv::Mat descriptors(n, 32, CV_8U);
    cv::randu(descriptors, 0, 256);
    std::mt19937 rng(9);
    s.frames.push_back(render(s, 0, descriptors, rng));
    auto keyframe = std::make_shared<map::KeyFrame>(
        0, 0, 0.0, *s.frames[0].T_c_w, s.frames[0].features,
        std::make_shared<feature::ScaleLevels>(8, 1.2F), s.camera.intrinsics());
    for (int i = 0; i < n; ++i) {
      auto point = std::make_shared<map::MapPoint>(i, s.scene.points[i], keyframe);
      point->addObservation(keyframe, i);
      s.points.push_back(point);
    }
    for (int index = 1; index <= kFrames; ++index)
      s.frames.push_back(render(s, index, descriptors, rng));
    return s;
  }();
  return q;
}

const feature::ScaleLevels& pyramid() {
  static const feature::ScaleLevels levels(8, 1.2F);
  return levels;
}

// One iteration = frames 1..30 through one MotionEvidence (the time shown is for the 30;
// items_per_second is frames per second).
// Argument: Dynamic.rigidConsensus (0 / 1).
void BM_MotionEvidenceRgbdFrame(benchmark::State& state) {
  const Sequence& q = sequence();
  const bool rigidity = state.range(0) != 0;
  std::vector<track::Frame> frames = q.frames;
  std::size_t moving = 0;
  for (auto _ : state) {
    track::MotionEvidence evidence;
    for (std::size_t index = 1; index < frames.size(); ++index) {
      const auto verdict_rigid = rigidity
                                     ? track::rigidConsensus(frames[index], q.camera.intrinsics())
                                     : track::RigidVerdict{};
      const auto verdict =
          evidence.update(frames[index], frames[index - 1], q.camera, pyramid(), verdict_rigid);
      moving = verdict.moving_features;
      benchmark::DoNotOptimize(verdict.dynamic_points.data());
    }
  }
  state.SetItemsProcessed(state.iterations() * kFrames);  // frames per second
  state.counters["moving_features_last_frame"] = static_cast<double>(moving);
}
BENCHMARK(BM_MotionEvidenceRgbdFrame)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// The rigid consensus alone, once per frame of the 30 (the tracker runs it up to three times a
// frame: after the motion model or reference keyframe match and after the local map search).
void BM_RigidConsensusRgbdFrame(benchmark::State& state) {
  const Sequence& q = sequence();
  int broken = 0;
  for (auto _ : state) {
    for (std::size_t index = 1; index < q.frames.size(); ++index) {
      const auto verdict = track::rigidConsensus(q.frames[index], q.camera.intrinsics());
      broken = verdict.broken;
      benchmark::DoNotOptimize(verdict.per_feature.data());
    }
  }
  state.SetItemsProcessed(state.iterations() * kFrames);
  state.counters["broken_last_frame"] = broken;
}
BENCHMARK(BM_RigidConsensusRgbdFrame)->Unit(benchmark::kMillisecond);

}  // namespace
