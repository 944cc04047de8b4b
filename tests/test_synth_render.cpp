// Synthetic frames: determinism, texture richness, depth and dynamic-object ground truth.
#include <gtest/gtest.h>

#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "error_of.h"
#include "lumaslam/core/error.h"
#include "lumaslam/synth/sequence.h"

using namespace lumaslam::synth;
using lumaslam::test::errorOf;

namespace {

bool sameBytes(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0.0;
}

int orbFeatures(const cv::Mat& bgr) {
  cv::Mat gray;
  cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
  std::vector<cv::KeyPoint> keypoints;
  cv::ORB::create(2000)->detect(gray, keypoints);
  return static_cast<int>(keypoints.size());
}

}  // namespace

TEST(SynthRender, SameSeedGivesSameBytesOtherSeedDiffers) {
  const Preset& preset = findPreset("walking-xyz-rgbd");
  const SequenceRenderer a(preset, 60, 11), b(preset, 60, 11), c(preset, 60, 12);
  const Frame fa = a.render(37), fb = b.render(37), fc = c.render(37);
  EXPECT_TRUE(sameBytes(fa.cam0.image, fb.cam0.image));
  EXPECT_TRUE(sameBytes(fa.sensor_depth, fb.sensor_depth));
  EXPECT_TRUE(sameBytes(fa.cam0.mask, fb.cam0.mask));
  EXPECT_EQ(fa.timestamp_ns, fb.timestamp_ns);
  EXPECT_FALSE(sameBytes(fa.cam0.image, fc.cam0.image));
  // Rendering again (other thread interleaving) gives the same bytes too.
  EXPECT_TRUE(sameBytes(a.render(37).cam0.image, fa.cam0.image));
}

TEST(SynthRender, LitPresetsAreRichEnoughForOrb) {
  for (const char* name : {"xyz-rgbd", "walking-rpy-rgbd", "loop-stereo"}) {
    const Preset& preset = findPreset(name);
    const SequenceRenderer sequence(preset, preset.frames, 3);
    for (const int index : {0, preset.frames / 3, preset.frames - 1}) {
      const Frame frame = sequence.render(index);
      ASSERT_EQ(frame.cam0.image.type(), CV_8UC3);
      // Scale to 640x480 for the stereo rig so the threshold means the same thing.
      cv::Mat image;
      cv::resize(frame.cam0.image, image, {640, 480}, 0, 0, cv::INTER_AREA);
      EXPECT_GE(orbFeatures(image), 500) << name << " frame " << index;
      cv::Scalar mean, stddev;
      cv::meanStdDev(image, mean, stddev);
      EXPECT_GT(mean[1], 60.0) << name;  // lit, not dark
      EXPECT_LT(mean[1], 200.0) << name;
      EXPECT_GT(stddev[1], 25.0) << name;  // textured, not flat
    }
  }
}

TEST(SynthRender, DepthIsPositiveAndSensorDepthLooksLikeAKinect) {
  const SequenceRenderer sequence(findPreset("xyz-rgbd"), 30, 5);
  const Frame frame = sequence.render(10);
  double min_depth = 0, max_depth = 0;
  cv::minMaxLoc(frame.cam0.depth, &min_depth, &max_depth);
  EXPECT_GT(min_depth, 0.3);
  EXPECT_LT(max_depth, 8.0);
  const cv::Mat valid = frame.sensor_depth > 0;
  const double valid_fraction = cv::countNonZero(valid) / static_cast<double>(valid.total());
  EXPECT_GT(valid_fraction, 0.8);  // mostly valid ...
  EXPECT_LT(valid_fraction, 1.0);  // ... with some holes
  cv::Mat error;
  cv::absdiff(frame.sensor_depth, frame.cam0.depth, error);
  EXPECT_LT(cv::mean(error, valid)[0], 0.03);  // noise of a few mm to cm
  EXPECT_GT(cv::mean(error, valid)[0], 0.0005);
}

TEST(SynthRender, WalkersAreMaskedAndBoxesCoverTheirPixels) {
  const Preset& preset = findPreset("walking-static-rgbd");
  const SequenceRenderer sequence(preset, preset.frames, 2);
  ASSERT_EQ(sequence.scene().dynamicObjectCount(), 2);
  int frames_with_person = 0;
  double max_box_fraction = 0.0;
  for (int index = 0; index < preset.frames; index += 25) {
    const Frame frame = sequence.render(index);
    const cv::Mat& mask = frame.cam0.mask;
    cv::Mat covered = cv::Mat::zeros(mask.size(), CV_8U);
    double box_area = 0.0;
    for (const auto& box : frame.cam0.boxes) {
      EXPECT_EQ(box.class_name, "person");
      covered(box.box).setTo(255);
      box_area += box.box.area();
      frames_with_person++;
    }
    max_box_fraction = std::max(max_box_fraction, box_area / static_cast<double>(mask.total()));
    cv::Mat outside;
    cv::bitwise_and(mask, ~covered, outside);
    EXPECT_EQ(cv::countNonZero(outside), 0) << "masked pixels outside every box, frame " << index;
    // Dynamic pixels have the walker's depth: in front of the static scene behind them.
    if (cv::countNonZero(mask) > 0) {
      EXPECT_LT(cv::mean(frame.cam0.depth, mask)[0], cv::mean(frame.cam0.depth, ~mask)[0]);
    }
  }
  EXPECT_GE(frames_with_person, 5);
  EXPECT_GT(max_box_fraction, 0.12);  // people come close enough to fill a good part of the view
}

TEST(SynthRender, MovingBoxesAreLabelledDynamicObjects) {
  const SequenceRenderer sequence(findPreset("walking-xyz-rgbd"), 150, 1);
  const auto snapshot = sequence.scene().at(1.0, Eigen::Vector3d::Zero());
  int labelled = 0;
  for (const auto& box : snapshot.boxes) {
    if (box.object_id == 0) continue;
    ++labelled;
    EXPECT_EQ(sequence.scene().objectClass(box.object_id), "box");
    for (const int lightmap : box.lightmaps) EXPECT_EQ(lightmap, -1);  // lit per pixel
  }
  EXPECT_EQ(labelled, 1);
  // Seed 1 drives the box through the view around frame 40: it is masked and boxed.
  const Frame frame = sequence.render(40);
  int boxes = 0;
  for (const auto& box : frame.cam0.boxes) {
    if (box.class_name != "box") continue;
    ++boxes;
    EXPECT_GT(cv::countNonZero(frame.cam0.mask(box.box)), box.box.area() / 4);
  }
  EXPECT_EQ(boxes, 1);
}

TEST(SynthRender, StereoRigHasBaselineAndRightImage) {
  const SequenceRenderer sequence(findPreset("xyz-stereo"), 20, 4);
  const Frame frame = sequence.render(5);
  ASSERT_TRUE(frame.cam1.has_value());
  EXPECT_EQ(frame.cam0.image.cols, 752);
  EXPECT_EQ(frame.cam0.image.rows, 480);
  const lumaslam::SE3 T_c0_c1 = frame.cam0.T_w_c.inverse() * frame.cam1->T_w_c;
  EXPECT_NEAR(T_c0_c1.translation().x(), 0.11, 1e-9);
  EXPECT_NEAR(T_c0_c1.translation().tail<2>().norm(), 0.0, 1e-9);
  EXPECT_FALSE(sameBytes(frame.cam0.image, frame.cam1->image));
  // EuRoC clock: exact 20 Hz in nanoseconds.
  EXPECT_EQ(sequence.timestampNs(6) - sequence.timestampNs(5), 50000000);
}

TEST(SynthRender, BadInputGivesClearErrors) {
  EXPECT_THROW(findPreset("no-such-preset"), lumaslam::Error);
  const std::string unknown = errorOf([&] { findPreset("no-such-preset"); });
  EXPECT_NE(unknown.find("no-such-preset"), std::string::npos);
  EXPECT_NE(unknown.find("walking-xyz-rgbd"), std::string::npos);
  SynthOptions options;
  options.texture_images = {"/nonexistent/poster.png"};
  const std::string no_poster =
      errorOf([&] { SequenceRenderer(findPreset("xyz-rgbd"), 10, 1, options); });
  EXPECT_NE(no_poster.find("/nonexistent/poster.png"), std::string::npos);
  EXPECT_THROW(SequenceRenderer(findPreset("xyz-rgbd"), 0, 1), lumaslam::Error);
  const SequenceRenderer sequence(findPreset("xyz-rgbd"), 10, 1);
  EXPECT_THROW(sequence.render(10), lumaslam::Error);
  SynthOptions bad_level;
  bad_level.dark_level = 9;
  EXPECT_THROW(SequenceRenderer(findPreset("xyz-rgbd"), 10, 1, bad_level), lumaslam::Error);
}
