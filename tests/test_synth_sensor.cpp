// Real-sensor effects of synth (issue 15), each against ground truth: depth/colour
// misregistration, depth stream time offsets, no depth on dark and grazing surfaces, disparity
// quantisation and grazing-angle noise, rolling shutter, and the hand-held trajectory.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include <Eigen/Geometry>
#include <opencv2/imgcodecs.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/synth/dataset_writer.h"
#include "lumaslam/synth/depth_sensor.h"
#include "lumaslam/synth/renderer.h"
#include "lumaslam/synth/sequence.h"
#include "test_paths.h"

using namespace lumaslam::synth;
namespace fs = std::filesystem;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A depth model with every random effect off: what is left is deterministic geometry.
DepthSensorModel exactSensor() {
  DepthSensorModel m;
  m.noise = false;
  m.edge_hole_probability = 0.0f;
  m.dropout_blobs_per_megapixel = 0.0f;
  return m;
}

// 640x480 depth: `near` left of column `edge`, `far` from it on.
cv::Mat stepDepth(int edge, float near, float far) {
  cv::Mat depth(480, 640, CV_32F, cv::Scalar(far));
  depth.colRange(0, edge).setTo(near);
  return depth;
}

// First column of row y whose depth is the far side's (within 1 cm).
int firstFarColumn(const cv::Mat& depth, int y, float far) {
  for (int x = 0; x < depth.cols; ++x)
    if (std::abs(depth.at<float>(y, x) - far) < 0.01f) return x;
  return -1;
}

// handheld-rgbd with the effects a test does not look at switched off.
Preset handheldWith(double readout_ms, DepthSensorModel depth) {
  Preset p = findPreset("handheld-rgbd");
  p.readout_ms = readout_ms;
  p.depth = depth;
  return p;
}

SynthOptions cleanImages() {
  SynthOptions o;
  o.motion_blur = false;
  o.sensor_noise = false;
  return o;
}

// Global-shutter render of the scene at trajectory time t (the frame's own snapshot time
// `scene_t`, as the sequence takes the scene once per image).
RenderedView renderAtTime(const SequenceRenderer& s, double scene_t, double t) {
  const auto snapshot = s.scene().at(scene_t, s.trajectory().pose(scene_t).translation());
  return renderView(s.scene(), snapshot, s.rig().camera, s.trajectory().pose(t));
}

double maxAbsDifference(const cv::Mat& a, const cv::Mat& b) {
  return cv::norm(a, b, cv::NORM_INF);
}

std::vector<std::string> dataLines(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);)
    if (!line.empty() && line[0] != '#') lines.push_back(line);
  return lines;
}

}  // namespace

TEST(SynthSensor, MisregistrationShiftsTheDepthEdgeByTheShift) {
  DepthSensorModel model = exactSensor();
  model.registration_shift_px = {2.0f, 0.0f};
  const cv::Mat ideal = stepDepth(300, 1.0f, 2.0f);
  const cv::Mat sensed = simulateDepthSensor(ideal, model, 1);
  for (const int y : {0, 240, 479}) {
    EXPECT_EQ(firstFarColumn(ideal, y, 2.0f), 300);
    EXPECT_EQ(firstFarColumn(sensed, y, 2.0f), 302) << "row " << y;
  }
  // Columns that come from outside the image have no reading.
  EXPECT_EQ(cv::countNonZero(sensed.colRange(0, 2)), 0);
  EXPECT_EQ(cv::countNonZero(sensed.colRange(2, 640)), 638 * 480);
}

TEST(SynthSensor, MisregistrationScaleMovesEdgesAwayFromTheCentre) {
  DepthSensorModel model = exactSensor();
  model.registration_scale = 1.01f;
  // An edge 200 px right of the centre (319.5) moves 2 px out; one at the centre stays.
  const cv::Mat sensed = simulateDepthSensor(stepDepth(520, 1.0f, 2.0f), model, 1);
  EXPECT_EQ(firstFarColumn(sensed, 240, 2.0f), 522);
  const cv::Mat centred = simulateDepthSensor(stepDepth(320, 1.0f, 2.0f), model, 1);
  EXPECT_EQ(firstFarColumn(centred, 240, 2.0f), 320);
  model.registration_scale = 3.0f;
  EXPECT_THROW(simulateDepthSensor(stepDepth(320, 1.0f, 2.0f), model, 1), lumaslam::Error);
}

TEST(SynthSensor, RenderedDepthIsTheColourFramesDepthShifted) {
  DepthSensorModel depth = exactSensor();
  depth.registration_shift_px = {2.0f, 1.0f};
  SynthOptions options = cleanImages();
  const SequenceRenderer sequence(handheldWith(0.0, depth), 30, 4, options);
  const Frame frame = sequence.render(12);
  ASSERT_EQ(frame.depth_timestamp_ns, frame.timestamp_ns);
  // sensor(x, y) = true depth registered to colour at (x - 2, y - 1), inside the range limits.
  const cv::Mat expected = frame.cam0.depth(cv::Rect(0, 0, 638, 479));
  cv::Mat sensed = frame.sensor_depth(cv::Rect(2, 1, 638, 479)).clone();
  const cv::Mat in_range = (expected >= depth.min_depth_m) & (expected <= depth.max_depth_m);
  EXPECT_GT(cv::countNonZero(in_range), 0.9 * static_cast<double>(in_range.total()));
  cv::Mat expected_in_range = cv::Mat::zeros(expected.size(), CV_32F);
  expected.copyTo(expected_in_range, in_range);
  EXPECT_EQ(maxAbsDifference(sensed, expected_in_range), 0.0);
  // Unshifted, the depth does not match colour at depth edges: the test can fail.
  cv::Mat unshifted = cv::Mat::zeros(expected.size(), CV_32F);
  frame.cam0.depth(cv::Rect(2, 1, 638, 479)).copyTo(unshifted, in_range);
  EXPECT_GT(maxAbsDifference(sensed, unshifted), 0.3);
}

TEST(SynthSensor, DepthIsCapturedAtItsOwnJitteredTimestamp) {
  DepthSensorModel depth = exactSensor();
  depth.max_time_offset_ms = 15.0;
  const SequenceRenderer sequence(handheldWith(0.0, depth), 60, 2, cleanImages());
  std::int64_t lowest = 0, highest = 0;
  for (int i = 0; i < 60; ++i) {
    const std::int64_t offset = sequence.depthTimestampNs(i) - sequence.timestampNs(i);
    EXPECT_LE(std::abs(offset), 15000000) << "frame " << i;
    EXPECT_EQ(offset % 1000, 0);  // whole microseconds, as TUM writes them
    if (i > 0) {
      EXPECT_GT(sequence.depthTimestampNs(i), sequence.depthTimestampNs(i - 1));
    }
    lowest = std::min(lowest, offset), highest = std::max(highest, offset);
  }
  EXPECT_GT(highest - lowest, 20000000);  // spread over most of +-15 ms, not a constant offset
  for (const int i : {7, 31}) {
    const Frame frame = sequence.render(i);
    ASSERT_NE(frame.depth_timestamp_ns, frame.timestamp_ns);
    const double t_depth = sequence.secondsFromStart(frame.depth_timestamp_ns);
    const RenderedView at_depth_time = renderAtTime(sequence, t_depth, t_depth);
    cv::Mat in_range =
        (at_depth_time.depth >= depth.min_depth_m) & (at_depth_time.depth <= depth.max_depth_m);
    cv::Mat expected = cv::Mat::zeros(at_depth_time.depth.size(), CV_32F);
    at_depth_time.depth.copyTo(expected, in_range);
    EXPECT_EQ(maxAbsDifference(frame.sensor_depth, expected), 0.0) << "frame " << i;
    // ... and not the colour frame's depth: the camera moved in between.
    cv::Mat at_colour_time = cv::Mat::zeros(expected.size(), CV_32F);
    frame.cam0.depth.copyTo(at_colour_time, in_range);
    EXPECT_GT(maxAbsDifference(frame.sensor_depth, at_colour_time), 0.1) << "frame " << i;
  }
  SynthOptions synced = cleanImages();
  synced.depth_misalignment = false;
  const SequenceRenderer synced_sequence(handheldWith(0.0, depth), 60, 2, synced);
  EXPECT_EQ(synced_sequence.depthTimestampNs(7), synced_sequence.timestampNs(7));
  depth.max_time_offset_ms = 20.0;
  EXPECT_THROW(SequenceRenderer(handheldWith(0.0, depth), 10, 2), lumaslam::Error);
}

TEST(SynthSensor, TumFilesCarryTheDepthStreamsOwnStamps) {
  lumaslam::test::TempDir dir("synth_handheld");
  const SequenceRenderer sequence(findPreset("handheld-rgbd"), 5, 3);
  writeDataset(sequence, dir.path());
  const auto rgb = dataLines(dir.path() / "rgb.txt");
  const auto depth = dataLines(dir.path() / "depth.txt");
  const auto pairs = dataLines(dir.path() / "associations.txt");
  ASSERT_EQ(depth.size(), 5u);
  ASSERT_EQ(pairs.size(), 5u);
  int differing = 0;
  for (int i = 0; i < 5; ++i) {
    const std::string rgb_stamp = tumTimestamp(sequence.timestampNs(i));
    const std::string depth_stamp = tumTimestamp(sequence.depthTimestampNs(i));
    differing += rgb_stamp != depth_stamp;
    EXPECT_EQ(rgb[static_cast<size_t>(i)], rgb_stamp + " rgb/" + rgb_stamp + ".png");
    EXPECT_EQ(depth[static_cast<size_t>(i)], depth_stamp + " depth/" + depth_stamp + ".png");
    EXPECT_EQ(pairs[static_cast<size_t>(i)], rgb_stamp + " rgb/" + rgb_stamp + ".png " +
                                                 depth_stamp + " depth/" + depth_stamp + ".png");
    const cv::Mat png =
        cv::imread((dir.path() / "depth" / (depth_stamp + ".png")).string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(png.type(), CV_16U) << depth_stamp;
    cv::Mat expected;
    sequence.render(i).sensor_depth.convertTo(expected, CV_16U, 5000.0);
    EXPECT_EQ(maxAbsDifference(png, expected), 0.0);
  }
  EXPECT_GE(differing, 4);
}

TEST(SynthSensor, NoDepthOnDarkSurfaces) {
  DepthSensorModel model = exactSensor();
  model.min_ir_albedo = 0.02f;
  const cv::Mat depth(480, 640, CV_32F, cv::Scalar(2.0f));
  cv::Mat albedo(480, 640, CV_32F, cv::Scalar(0.3f));
  const cv::Rect black(100, 100, 80, 60), grey(400, 100, 80, 60);
  albedo(black).setTo(0.005f);  // black cloth / plastic
  albedo(grey).setTo(0.03f);    // in the ramp: some readings
  const cv::Mat facing(480, 640, CV_32F, cv::Scalar(1.0f));
  const cv::Mat sensed = simulateDepthSensor({depth, albedo, facing}, model, 7);
  EXPECT_EQ(cv::countNonZero(sensed(black)), 0);
  const double grey_valid = cv::countNonZero(sensed(grey)) / static_cast<double>(grey.area());
  EXPECT_GT(grey_valid, 0.3);
  EXPECT_LT(grey_valid, 0.7);
  cv::Mat bright = cv::Mat(sensed.size(), CV_8U, cv::Scalar(255));
  bright(black).setTo(0);
  bright(grey).setTo(0);
  EXPECT_EQ(cv::countNonZero(sensed > 0),
            cv::countNonZero(bright) + cv::countNonZero(sensed(grey)));
}

TEST(SynthSensor, NoDepthAtGrazingViewAngles) {
  DepthSensorModel model = exactSensor();
  model.max_incidence_deg = 80.0f;
  const cv::Mat depth(480, 640, CV_32F, cv::Scalar(2.0f));
  const cv::Mat albedo(480, 640, CV_32F, cv::Scalar(0.3f));
  cv::Mat cosine(480, 640, CV_32F, cv::Scalar(std::cos(60.0 * kPi / 180.0)));
  const cv::Rect grazing(0, 0, 640, 100);
  cosine(grazing).setTo(std::cos(84.0 * kPi / 180.0));
  const cv::Mat sensed = simulateDepthSensor({depth, albedo, cosine}, model, 7);
  EXPECT_EQ(cv::countNonZero(sensed(grazing)), 0);
  EXPECT_EQ(cv::countNonZero(sensed.rowRange(100, 480)), 640 * 380);
}

TEST(SynthSensor, RenderedFramesHaveNoDepthWhereTheSurfaceIsDark) {
  DepthSensorModel depth = exactSensor();
  depth.min_ir_albedo = 0.02f;
  const SequenceRenderer sequence(handheldWith(0.0, depth), 30, 1, cleanImages());
  const Frame frame = sequence.render(10);
  const double t = sequence.secondsFromStart(frame.timestamp_ns);
  const RenderedView truth = renderAtTime(sequence, t, t);
  const cv::Mat dark = truth.ir_albedo <= 0.02f;
  EXPECT_GT(cv::countNonZero(dark), 0.005 * static_cast<double>(dark.total()));  // posters, text
  cv::Mat sensed_on_dark;
  frame.sensor_depth.copyTo(sensed_on_dark, dark);
  EXPECT_EQ(cv::countNonZero(sensed_on_dark), 0);
  // Bright surfaces keep their depth.
  const cv::Mat bright = (truth.ir_albedo >= 0.04f) & (truth.depth <= depth.max_depth_m);
  EXPECT_EQ(cv::countNonZero((frame.sensor_depth > 0) & bright), cv::countNonZero(bright));
}

TEST(SynthSensor, DisparityQuantisationStepsGrowWithDepthSquared) {
  DepthSensorModel model = exactSensor();
  model.quantize_disparity = true;
  cv::Mat ramp(1, 2000, CV_32F);
  for (int i = 0; i < ramp.cols; ++i) ramp.at<float>(0, i) = 0.5f + 0.002f * static_cast<float>(i);
  const cv::Mat sensed = simulateDepthSensor(ramp, model, 1);
  std::set<float> near_levels, far_levels;
  for (int i = 0; i < ramp.cols; ++i) {
    const float z = ramp.at<float>(0, i), q = sensed.at<float>(0, i);
    // Half a 1/8-pixel disparity step at f x b = 43.5 px m: z^2 / 43.5 / 16.
    EXPECT_LE(std::abs(q - z), z * z / 43.5f / 16.0f * 1.01f) << "z " << z;
    (z < 1.5f ? near_levels : far_levels).insert(q);
  }
  // 0.5-1.5 m and 1.5-4.5 m: ~3x as many levels over a 3x shorter span near the camera.
  EXPECT_GT(near_levels.size(), 3 * far_levels.size() / 2);
  EXPECT_LT(far_levels.size(), 200u);
}

TEST(SynthSensor, GrazingAngleAddsAxialNoise) {
  DepthSensorModel model;
  model.edge_hole_probability = 0.0f;
  model.dropout_blobs_per_megapixel = 0.0f;
  model.grazing_noise = true;
  const cv::Mat depth(480, 640, CV_32F, cv::Scalar(2.0f));
  const cv::Mat albedo(480, 640, CV_32F, cv::Scalar(0.3f));
  cv::Mat cosine(480, 640, CV_32F, cv::Scalar(std::cos(30.0 * kPi / 180.0)));
  cosine.rowRange(0, 240).setTo(std::cos(85.0 * kPi / 180.0));
  const cv::Mat sensed = simulateDepthSensor({depth, albedo, cosine}, model, 3);
  cv::Scalar mean, oblique, facing;
  cv::meanStdDev(sensed.rowRange(0, 240), mean, oblique);
  cv::meanStdDev(sensed.rowRange(240, 480), mean, facing);
  // Nguyen et al. 2012 at 2 m: 6.1 mm facing, + 20 mm at 85 degrees.
  EXPECT_NEAR(facing[0], 0.0061, 0.001);
  EXPECT_GT(oblique[0], 3.0 * facing[0]);
}

TEST(SynthSensor, RollingShutterRowsSeeTheSceneAtTheirReadoutTime) {
  // Row r is exposed at t0 + r * readout / rows with t0 = stamp - readout / 2 + half a row.
  for (const int r : {0, 100, 479})
    EXPECT_NEAR(rowTimeOffset(0.03, r, 480), -0.015 + (r + 0.5) * 0.03 / 480.0, 1e-12);
  SynthOptions options = cleanImages();
  options.depth_noise = false;
  const Preset preset = handheldWith(30.0, exactSensor());
  const SequenceRenderer sequence(preset, 90, 5, options);
  const int index = 70;
  const Frame frame = sequence.render(index);
  const double t = sequence.secondsFromStart(frame.timestamp_ns);
  const Eigen::AngleAxisd turned(sequence.trajectory().pose(t - 0.015).linear().transpose() *
                                 sequence.trajectory().pose(t + 0.015).linear());
  EXPECT_GT(turned.angle(), 0.5 * kPi / 180.0);  // the camera turns during the readout
  const FrameExposure& exposure = sequence.exposure(index);
  SensorModel noiseless;
  noiseless.noise_scale = 0.0;
  const auto expose = [&](const cv::Mat& radiance) {
    return exposeImage(radiance, exposure.signal(), exposure.gain, preset.lighting.dark_level,
                       noiseless, 0);
  };
  const RenderedView at_stamp = renderAtTime(sequence, t, t);
  const cv::Mat global_image = expose(at_stamp.radiance);
  for (const int r : {0, 60, 240, 420, 479}) {
    const RenderedView at_row = renderAtTime(sequence, t, t + rowTimeOffset(0.03, r, 480));
    EXPECT_LE(maxAbsDifference(frame.cam0.depth.row(r), at_row.depth.row(r)), 1e-5) << r;
    EXPECT_LE(maxAbsDifference(frame.cam0.image.row(r), expose(at_row.radiance).row(r)), 1.0) << r;
  }
  // Top and bottom differ from the global-shutter image at the stamp; the middle does not.
  cv::Mat error;
  cv::absdiff(frame.cam0.depth.rowRange(0, 20), at_stamp.depth.rowRange(0, 20), error);
  EXPECT_GT(cv::mean(error)[0], 0.005);
  EXPECT_LE(maxAbsDifference(frame.cam0.image.row(239), global_image.row(239)), 30.0);
  EXPECT_GT(maxAbsDifference(frame.cam0.image.row(0), global_image.row(0)), 60.0);
  // The global-shutter switch renders the whole image at the stamp.
  SynthOptions global = options;
  global.rolling_shutter = false;
  const SequenceRenderer global_sequence(preset, 90, 5, global);
  EXPECT_LE(maxAbsDifference(global_sequence.render(index).cam0.depth, at_stamp.depth), 1e-5);
}

TEST(SynthSensor, HandheldTrajectoryMovesLikeTumFr1) {
  for (const int seed : {1, 2, 3}) {
    const SequenceRenderer s(findPreset("handheld-rgbd"), 300, static_cast<std::uint64_t>(seed));
    std::vector<double> degrees;
    double distance = 0.0;
    for (int i = 1; i < 300; ++i) {
      const auto a = s.trajectory().pose(s.secondsFromStart(s.timestampNs(i - 1)));
      const auto b = s.trajectory().pose(s.secondsFromStart(s.timestampNs(i)));
      degrees.push_back(Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle() * 180.0 /
                        kPi);
      distance += (b.translation() - a.translation()).norm();
    }
    std::sort(degrees.begin(), degrees.end());
    const double p90 = degrees[degrees.size() * 9 / 10];
    EXPECT_GE(p90, 1.5) << "seed " << seed;  // peaks of 1.5-3 degrees per frame ...
    EXPECT_LE(p90, 3.0) << "seed " << seed;
    EXPECT_GE(degrees.back(), 4.5) << "seed " << seed;  // ... and quick turns of ~5
    EXPECT_LE(degrees.back(), 6.5) << "seed " << seed;
    const double speed = distance / (299.0 / 30.0);
    EXPECT_GT(speed, 0.2) << "seed " << seed;  // TUM fr1 desk 0.41 m/s, room 0.33
    EXPECT_LT(speed, 0.45) << "seed " << seed;
  }
}

TEST(SynthSensor, HandheldPresetIsDeterministic) {
  const Preset& preset = findPreset("handheld-rgbd");
  const SequenceRenderer a(preset, 40, 8), b(preset, 40, 8);
  const Frame fa = a.render(21), fb = b.render(21);
  EXPECT_EQ(maxAbsDifference(fa.cam0.image, fb.cam0.image), 0.0);
  EXPECT_EQ(maxAbsDifference(fa.sensor_depth, fb.sensor_depth), 0.0);
  EXPECT_EQ(fa.depth_timestamp_ns, fb.depth_timestamp_ns);
  const double holes = cv::countNonZero(fa.sensor_depth == 0) / static_cast<double>(307200);
  EXPECT_GT(holes, 0.03);  // edges, dark and grazing surfaces, blobs
  EXPECT_LT(holes, 0.3);
}
