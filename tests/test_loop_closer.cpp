// Loop closing on a map built from a synthetic room with injected drift: one lap of 36
// keyframes (10 degrees apart), then the start of a second lap from a renderer with other
// viewpoints (9 degrees apart). Consecutive keyframes share points (fused with ground-truth
// poses), the laps do not: only place recognition can connect them. Then every keyframe and
// its points are moved by a drift growing along the trajectory (yaw + translation), as
// odometry drifts. The loop closer must find the loop, correct it, and bring the keyframes
// closer to the ground truth; a wrong candidate must be rejected without touching the map.
// The monocular variant adds a scale drift (the map grows by 0.8 % per keyframe) and closes
// the loop with a Sim3. The global BA, in its own thread, must stop at shutdown or at a new
// loop and leave the map as the loop correction left it. A threaded closer corrects while
// another thread reads the map as tracking does (the ThreadSanitizer check of that locking).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <future>
#include <numeric>
#include <thread>

#include <gtest/gtest.h>

#include "loop_test_map.h"

#include "lumaslam/loop/loop_closer.h"
#include "lumaslam/loop/vocabulary_training.h"
#include "lumaslam/mapping/point_fusion.h"

namespace {

using namespace lumaslam;

constexpr int kLapFrames = 36;
constexpr int kSecondLapFrames = 40;
constexpr int kSecondLapKeyFrames = 7;                          // 9 .. 63 degrees
constexpr double kYawDriftDeg = 0.25;                           // per keyframe
const Eigen::Vector3d kTranslationDrift(0.004, -0.003, 0.001);  // metres per keyframe

constexpr double kScaleDrift = 0.008;  // per keyframe (monocular)

// World drift at keyframe k: X -> s R X + t (s = 1 without scale drift).
optimize::Sim3 driftAt(int k, double scale_drift = 0.0) {
  const Eigen::Quaterniond yaw(
      Eigen::AngleAxisd(k * kYawDriftDeg * M_PI / 180.0, Eigen::Vector3d::UnitZ()));
  return {std::pow(1.0 + scale_drift, k), yaw, k * kTranslationDrift};
}

// The camera pose that sees drifted points where the true pose saw the true ones.
SE3 driftedPose(const optimize::Sim3& drift, const SE3& T_w_c) {
  SE3 drifted = SE3::Identity();
  drifted.linear() = drift.rotation.toRotationMatrix() * T_w_c.linear();
  drifted.translation() = drift * Eigen::Vector3d(T_w_c.translation());
  return drifted;
}

struct DriftedLoopMap {
  synth::SequenceRenderer lap{synth::findPreset("loop-rgbd"), kLapFrames, 3};
  synth::SequenceRenderer second_lap{synth::findPreset("loop-rgbd"), kSecondLapFrames, 3};
  track::FrameBuilder builder{test::rgbdCameraOf(lap.rig()), feature::OrbSettings{}};
  std::shared_ptr<map::Map> map = std::make_shared<map::Map>();
  loop::Vocabulary vocabulary;
  loop::KeyFrameDatabase database;
  std::vector<std::shared_ptr<map::KeyFrame>> keyframes;
  std::vector<SE3> truth;  // T_w_c per keyframe

  double scale_drift;

  explicit DriftedLoopMap(double scale_drift = 0.0) : scale_drift(scale_drift) {
    std::vector<track::Frame> frames;
    for (int i = 0; i < kLapFrames; ++i) {
      frames.push_back(test::buildRgbdFrame(builder, lap, i));
      truth.push_back(lap.render(i).cam0.T_w_c);
    }
    for (int i = 1; i <= kSecondLapKeyFrames; ++i) {
      frames.push_back(test::buildRgbdFrame(builder, second_lap, i));
      truth.push_back(second_lap.render(i).cam0.T_w_c);
    }
    std::vector<cv::Mat> descriptors;
    for (const auto& f : frames) descriptors.push_back(f.features->descriptors);
    loop::TrainingParams params;
    params.depth = 4;
    vocabulary = loop::trainVocabulary(descriptors, params);

    for (std::size_t k = 0; k < frames.size(); ++k) {
      auto keyframe = test::addKeyFrameWithPoints(*map, builder, frames[k], truth[k]);
      // Share points with the two previous keyframes (ground-truth poses: exact projections).
      for (std::size_t back = 1; back <= 2 && back <= k; ++back) {
        mapping::fusePointsInto(*map, keyframe, keyframes[k - back]->mapPoints());
      }
      keyframe->updateConnections();
      keyframes.push_back(keyframe);
      loop::KeyFrameBow entry;
      vocabulary.transform(frames[k].features->descriptors, 4, entry.bow, entry.features);
      database.add(keyframe->id(), std::move(entry));
    }
    for (const auto& kf : keyframes) kf->updateConnections();
    // Drift: keyframe k is seen where drift(k) puts it; points move with their reference.
    for (const auto& point : map->mapPoints()) {
      point->setPosition(driftAt(static_cast<int>(point->referenceKeyFrameId()), scale_drift) *
                         point->position());
    }
    for (std::size_t k = 0; k < keyframes.size(); ++k) {
      keyframes[k]->setPose(
          driftedPose(driftAt(static_cast<int>(k), scale_drift), truth[k]).inverse());
    }
    for (const auto& point : map->mapPoints()) point->updateNormalAndDepth();
  }

  // Root mean square distance of the keyframe centres to the ground truth (the first keyframe
  // carries no drift, so the frames agree without alignment).
  double keyframeRmse() const {
    double sum = 0.0;
    for (std::size_t k = 0; k < keyframes.size(); ++k) {
      sum += (keyframes[k]->center() - truth[k].translation()).squaredNorm();
    }
    return std::sqrt(sum / static_cast<double>(keyframes.size()));
  }
};

loop::LoopCloserParams sequentialParams() {
  loop::LoopCloserParams params;
  params.threaded = false;
  return params;
}

std::vector<SE3> posesOf(const DriftedLoopMap& world) {
  std::vector<SE3> poses;
  for (const auto& kf : world.keyframes) poses.push_back(kf->T_c_w());
  return poses;
}

TEST(LoopCloser, DetectsAndClosesTheLoopTowardsGroundTruth) {
  DriftedLoopMap world;
  const double before = world.keyframeRmse();
  loop::LoopCloser closer(world.map, world.vocabulary, world.database, sequentialParams());
  for (const auto& kf : world.keyframes) {
    closer.insertKeyFrame(kf);
    closer.processPending();
  }
  const auto loops = closer.closedLoops();
  ASSERT_EQ(loops.size(), 1U) << closer.rejectedCandidates() << " candidates rejected";
  const auto& loop = loops.front();
  // The loop is closed from the second lap to the start of the first.
  EXPECT_GE(loop.current, static_cast<map::Id>(kLapFrames));
  EXPECT_LE(loop.loop, 8U);
  EXPECT_GE(loop.inliers, 40);
  const double after = world.keyframeRmse();
  std::printf(
      "loop %llu -> %llu: %d inliers, correction %.1f mm %.2f deg; keyframe RMSE %.1f mm "
      "before, %.1f mm after\n",
      static_cast<unsigned long long>(loop.current), static_cast<unsigned long long>(loop.loop),
      loop.inliers, 1000.0 * loop.correction_m, loop.correction_deg, 1000.0 * before,
      1000.0 * after);
  // The injected drift at the current keyframe is what the loop corrects.
  const auto drift = driftAt(static_cast<int>(loop.current));
  EXPECT_NEAR(loop.correction_deg, Eigen::AngleAxisd(drift.rotation).angle() * 180.0 / M_PI, 1.0);
  EXPECT_EQ(loop.correction_scale, 1.0);
  EXPECT_LT(after, 0.5 * before);
  // The loop keyframes are linked in the essential graph and now share points.
  const auto current = world.map->keyFrame(loop.current);
  const auto loop_kf = world.map->keyFrame(loop.loop);
  ASSERT_TRUE(current && loop_kf);
  const auto edges = current->loopEdges();
  EXPECT_TRUE(
      std::any_of(edges.begin(), edges.end(), [&](const auto& kf) { return kf == loop_kf; }));
  EXPECT_GE(current->weight(loop.loop), map::KeyFrame::kMinCovisibilityWeight);
}

TEST(LoopCloser, RejectsAWrongPlaceWithoutChangingTheMap) {
  DriftedLoopMap world;
  loop::LoopCloser closer(world.map, world.vocabulary, world.database, sequentialParams());
  std::vector<SE3> poses;
  for (const auto& kf : world.keyframes) poses.push_back(kf->T_c_w());
  const std::size_t points = world.map->mapPointCount();
  // The last keyframe (second lap, ~63 degrees) against the far side of the room.
  const auto current = world.keyframes.back();
  const auto far_side = world.keyframes[kLapFrames / 2 + 2];
  EXPECT_FALSE(closer.computeLoop(current, {far_side}).has_value());
  EXPECT_FALSE(closer.computeLoop(current, {}).has_value());
  EXPECT_FALSE(closer.computeLoop(current, {current}).has_value());
  for (std::size_t k = 0; k < poses.size(); ++k) {
    EXPECT_TRUE(world.keyframes[k]->T_c_w().isApprox(poses[k])) << "keyframe " << k;
  }
  EXPECT_EQ(world.map->mapPointCount(), points);
  // While the right place is found from the same keyframe.
  const auto match = closer.computeLoop(current, {world.keyframes[6]});
  ASSERT_TRUE(match.has_value());
  EXPECT_GE(match->inliers, 40);
  // In the loop keyframe's map, which carries that keyframe's drift.
  const SE3 error = match->T_c_w * driftedPose(driftAt(6), world.truth.back());
  EXPECT_LT(error.translation().norm(), 0.05);
}

TEST(LoopCloser, ClosesAMonocularLoopWithSim3AndCorrectsTheScaleDrift) {
  DriftedLoopMap world(kScaleDrift);
  const double before = world.keyframeRmse();
  std::vector<double> scales;  // per keyframe: median drift scale of its points
  for (const auto& kf : world.keyframes) {
    std::vector<double> of_points;
    for (const auto& point : kf->mapPoints()) {
      if (point) {
        of_points.push_back(
            driftAt(static_cast<int>(point->referenceKeyFrameId()), kScaleDrift).scale);
      }
    }
    std::nth_element(of_points.begin(), of_points.begin() + of_points.size() / 2, of_points.end());
    scales.push_back(of_points[of_points.size() / 2]);
  }
  auto params = sequentialParams();
  params.fix_scale = false;
  loop::LoopCloser closer(world.map, world.vocabulary, world.database, params);
  for (const auto& kf : world.keyframes) {
    closer.insertKeyFrame(kf);
    closer.processPending();
  }
  const auto loops = closer.closedLoops();
  ASSERT_EQ(loops.size(), 1U) << closer.rejectedCandidates() << " candidates rejected";
  const auto& loop = loops.front();
  const double after = world.keyframeRmse();
  std::printf(
      "Sim3 loop %llu -> %llu: %d inliers, correction %.1f mm %.2f deg scale %.4f; keyframe "
      "RMSE %.1f mm before, %.1f mm after; point scales %.4f / %.4f\n",
      static_cast<unsigned long long>(loop.current), static_cast<unsigned long long>(loop.loop),
      loop.inliers, 1000.0 * loop.correction_m, loop.correction_deg, loop.correction_scale,
      1000.0 * before, 1000.0 * after, scales[loop.current], scales[loop.loop]);
  EXPECT_GE(loop.current, static_cast<map::Id>(kLapFrames));
  EXPECT_LE(loop.loop, 8U);
  EXPECT_GE(loop.inliers, 40);
  // S_c_w takes the loop keyframe's map into the current keyframe's scale: that of the points
  // each sees (points live over many keyframes, so their drift is that of older keyframes).
  // Only half of the excess is required: the Ceres refinement moves the RANSAC scale (1.315
  // for 1.322 expected) to 1.19, because this map is not self-consistent (a point carries
  // its reference keyframe's drift into later keyframes with another drift) and the two
  // keyframes are close, so reprojections observe the scale weakly. Measured 2026-12-08
  // (sequential, 2 runs identical; `build/tests/test_loop_closer --gtest_filter=*Sim3*`, the
  // "Sim3 loop" line): scale 1.1931 for 1.3216 expected, 60 % of the excess; keyframe RMSE
  // 419.6 -> 26.0 mm (6.2 %), bounded at ~2x (issue 22; it was 50 %).
  const double expected_scale = scales[loop.current] / scales[loop.loop];
  EXPECT_GT(loop.correction_scale, 1.0 + 0.5 * (expected_scale - 1.0));
  EXPECT_LT(loop.correction_scale, expected_scale * 1.03);
  EXPECT_LT(after, 0.125 * before);
  EXPECT_EQ(closer.globalBundleAdjustmentStats().completed, 1);
}

TEST(LoopCloser, ShutdownAbortsTheGlobalBundleAdjustmentAndLeavesTheMapAsCorrected) {
  DriftedLoopMap world;
  auto params = sequentialParams();
  params.threaded = true;
  params.queue_capacity = world.keyframes.size();
  std::promise<void> started;
  std::vector<SE3> corrected;
  loop::LoopCloser* closer_of_hook = nullptr;
  // The hook runs in the adjustment's thread after the loop correction: it records the map
  // and holds the adjustment until the abort is requested, so the shutdown surely meets it.
  params.on_global_ba_start = [&] {
    if (!corrected.empty()) return;  // only the first adjustment is held
    corrected = posesOf(world);
    started.set_value();
    while (!closer_of_hook->globalBundleAdjustmentAbortRequested()) std::this_thread::yield();
  };
  loop::LoopCloser closer(world.map, world.vocabulary, world.database, params);
  closer_of_hook = &closer;
  for (const auto& kf : world.keyframes) closer.insertKeyFrame(kf);
  // A guard against hanging if no loop were closed, not a speed requirement.
  ASSERT_EQ(started.get_future().wait_for(std::chrono::minutes(10)), std::future_status::ready);
  closer.shutdown();
  const auto stats = closer.globalBundleAdjustmentStats();
  EXPECT_EQ(stats.started, 1);
  EXPECT_EQ(stats.aborted, 1);
  EXPECT_EQ(stats.completed, 0);
  ASSERT_EQ(closer.closedLoops().size(), 1U);
  const auto poses = posesOf(world);
  for (std::size_t k = 0; k < poses.size(); ++k) {
    EXPECT_TRUE(poses[k].isApprox(corrected[k])) << "keyframe " << k;
  }
  for (const auto& point : world.map->mapPoints()) EXPECT_TRUE(point->position().allFinite());
}

}  // namespace

namespace {

// The loop is detected and corrected on the closer's thread while another thread uses the map
// as tracking does: a frame at a time under Map::updateMutex, reading poses, covisibility and
// point positions. Under ThreadSanitizer this is the race check of the correction's locking.
TEST(LoopCloser, CorrectsOnItsOwnThreadWhileATrackingThreadReadsTheMap) {
  DriftedLoopMap world;
  const double before = world.keyframeRmse();
  auto params = sequentialParams();
  params.threaded = true;
  params.queue_capacity = world.keyframes.size();
  loop::LoopCloser closer(world.map, world.vocabulary, world.database, params);
  std::atomic<bool> stop{false};
  int frames = 0;
  bool all_finite = true;
  std::thread tracking([&] {
    while (!stop) {
      const std::lock_guard frame(world.map->updateMutex());
      for (const auto& kf : world.map->keyFrames()) {
        all_finite = all_finite && kf->center().allFinite();
        for (const auto& covisible : kf->covisibles(10)) {
          all_finite = all_finite && covisible->T_c_w().matrix().allFinite();
        }
        for (const auto& point : kf->mapPoints()) {
          if (point && !point->isBad()) all_finite = all_finite && point->position().allFinite();
        }
      }
      ++frames;
    }
  });
  for (const auto& kf : world.keyframes) closer.insertKeyFrame(kf);
  closer.waitUntilIdle();
  stop = true;
  tracking.join();
  closer.shutdown();
  EXPECT_GT(frames, 0);
  EXPECT_TRUE(all_finite);
  ASSERT_EQ(closer.closedLoops().size(), 1U) << closer.rejectedCandidates() << " rejected";
  EXPECT_EQ(closer.globalBundleAdjustmentStats().completed, 1);
  EXPECT_LT(world.keyframeRmse(), 0.5 * before);
}

// A second loop arriving while the global BA of the first runs aborts that adjustment (it is
// out of date) before the map is corrected again; the adjustment after the last loop completes.
TEST(LoopCloser, ANewLoopAbortsTheRunningGlobalBundleAdjustment) {
  DriftedLoopMap world;
  const double before = world.keyframeRmse();
  // The database grows with the keyframes handed to the closer, as in the Pipeline (the
  // world's database already knows the second lap: a first-lap keyframe would find it).
  loop::KeyFrameDatabase database;
  auto params = sequentialParams();
  params.threaded = true;
  params.queue_capacity = world.keyframes.size();
  params.min_keyframes_between_loops = 1;  // let the later second-lap keyframes close again
  params.detector.consistency_threshold = 1;
  std::atomic<bool> first_started{false};
  loop::LoopCloser* closer_of_hook = nullptr;
  // Holds the first adjustment until something asks it to stop: the next loop (or the
  // shutdown below, if none came).
  params.on_global_ba_start = [&] {
    if (first_started.exchange(true)) return;
    while (!closer_of_hook->globalBundleAdjustmentAbortRequested()) std::this_thread::yield();
  };
  loop::LoopCloser closer(world.map, world.vocabulary, database, params);
  closer_of_hook = &closer;
  const auto feed = [&](std::size_t k) {
    const auto& kf = world.keyframes[k];
    database.add(kf->id(), *world.database.entry(kf->id()));
    closer.insertKeyFrame(kf);
  };
  // One keyframe at a time until the first loop's adjustment is held, so that the next
  // keyframes surely meet it running. (Futures of std::async wait in their destructor: kept.)
  std::vector<std::future<void>> idle;
  std::size_t fed = 0;
  while (fed < world.keyframes.size() && !first_started) {
    feed(fed++);
    idle.push_back(std::async(std::launch::async, [&] { closer.waitUntilIdle(); }));
    while (!first_started &&
           idle.back().wait_for(std::chrono::milliseconds(1)) != std::future_status::ready) {
    }
  }
  ASSERT_TRUE(first_started) << "no loop closed";
  while (fed < world.keyframes.size()) feed(fed++);
  idle.push_back(std::async(std::launch::async, [&] { closer.waitUntilIdle(); }));
  // A guard against hanging if no second loop came, not a speed requirement.
  const bool released = idle.back().wait_for(std::chrono::minutes(10)) == std::future_status::ready;
  closer.shutdown();
  for (auto& wait : idle) wait.wait();
  const auto loops = closer.closedLoops();
  ASSERT_TRUE(released) << loops.size() << " loops closed";
  ASSERT_GE(loops.size(), 2U);
  const auto stats = closer.globalBundleAdjustmentStats();
  EXPECT_EQ(stats.started, static_cast<int>(loops.size()));
  EXPECT_GE(stats.aborted, 1);  // the held first one
  EXPECT_EQ(stats.completed + stats.aborted, stats.started);
  EXPECT_GE(stats.completed, 1);  // the one after the last loop
  EXPECT_LT(world.keyframeRmse(), 0.5 * before);
  for (const auto& point : world.map->mapPoints()) EXPECT_TRUE(point->position().allFinite());
}

}  // namespace
