// Lighting and camera models: dark curve, auto-exposure, exposure jumps, noise, spotlight.
#include <gtest/gtest.h>

#include <cstdio>

#include <opencv2/imgproc.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/synth/lighting.h"
#include "lumaslam/synth/sequence.h"

using namespace lumaslam::synth;

namespace {

cv::Mat gradientImage() {
  cv::Mat image(64, 256, CV_8UC3);
  for (int y = 0; y < image.rows; ++y)
    for (int x = 0; x < image.cols; ++x)
      image.at<cv::Vec3b>(y, x) = cv::Vec3b(x, (x + 80) % 256, 255 - x);
  return image;
}

double meanGray(const cv::Mat& bgr) {
  cv::Mat gray;
  cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
  return cv::mean(gray)[0];
}

SensorModel noiseless() {
  SensorModel sensor;
  sensor.noise_scale = 0.0;
  return sensor;
}

}  // namespace

TEST(SynthLighting, LevelZeroIsTheIdentity) {
  const cv::Mat image = gradientImage();
  const cv::Mat out = exposeImage(displayToLinear(image), 1.0, 1.0, 0, noiseless(), 1);
  EXPECT_EQ(cv::norm(out, image, cv::NORM_INF), 0.0);
  EXPECT_EQ(darkCurve(0).a, 1.0);
  EXPECT_EQ(darkCurve(0).inv_gamma, 1.0);
}

TEST(SynthLighting, DarkLevelsDarkenMonotonically) {
  const cv::Mat linear = displayToLinear(gradientImage());
  cv::Mat previous = exposeImage(linear, 1.0, 1.0, 0, noiseless(), 1);
  for (int level = 1; level <= 5; ++level) {
    const cv::Mat out = exposeImage(linear, 1.0, 1.0, level, noiseless(), 1);
    cv::Mat brighter;
    cv::compare(out, previous, brighter, cv::CMP_GT);
    EXPECT_EQ(cv::countNonZero(brighter.reshape(1)), 0) << "level " << level;
    EXPECT_LT(cv::mean(out)[0], 0.9 * cv::mean(previous)[0]) << "level " << level;
    previous = out;
  }
  EXPECT_LT(cv::mean(previous)[0], 30.0);  // level 5 is very dark
  EXPECT_THROW(darkCurve(6), lumaslam::Error);
  EXPECT_THROW(darkCurve(-1), lumaslam::Error);
}

TEST(SynthLighting, NoiseGrowsWhenTheLightFalls) {
  const cv::Mat linear(64, 64, CV_32F, cv::Scalar(0.25));
  const auto relativeNoise = [&](double signal) {
    // Auto-exposure brings the image to the same brightness: gain = 1 / signal.
    cv::Mat out;
    exposeImage(linear, signal, 1.0 / signal, 0, SensorModel{}, 3).convertTo(out, CV_32F);
    cv::Scalar mean, stddev;
    cv::meanStdDev(out, mean, stddev);
    EXPECT_NEAR(mean[0], 127.5, 3.0);
    return stddev[0] / mean[0];
  };
  const double bright = relativeNoise(1.0), dim = relativeNoise(0.2), dark = relativeNoise(0.03);
  EXPECT_GT(bright, 0.0);
  EXPECT_GT(dim, 1.8 * bright);
  EXPECT_GT(dark, 1.8 * dim);
}

TEST(SynthLighting, AutoExposureLengthensExposureThenRaisesGainAsTheLightFades) {
  LightingSchedule fade;
  fade.light_end = 0.02;
  const Rig rig = tumRgbdRig();
  const auto plan = planExposures(fade, rig, 100);
  for (size_t i = 1; i < plan.size(); ++i) {
    EXPECT_GE(plan[i].exposure_ms, plan[i - 1].exposure_ms);
    EXPECT_GE(plan[i].gain, plan[i - 1].gain - 1e-9);
  }
  EXPECT_NEAR(plan.front().exposure_ms, rig.nominal_exposure_ms, 1e-9);
  EXPECT_NEAR(plan.back().exposure_ms, rig.max_exposure_ms, 1e-9);
  EXPECT_NEAR(plan.back().gain, rig.max_gain, 1e-9);
  EXPECT_LT(plan.back().brightness(), 0.5);  // auto-exposure ran out
  EXPECT_NEAR(plan.front().brightness(), 1.0, 1e-9);
}

TEST(SynthLighting, FlashFramesAreWhereTheyAreScheduled) {
  const Preset& preset = findPreset("flash-rgbd");
  ASSERT_FALSE(preset.lighting.jumps.empty());
  const SequenceRenderer sequence(preset, preset.frames, 4);
  for (const auto& jump : preset.lighting.jumps) {
    const double before = meanGray(sequence.render(jump.first_frame - 1).cam0.image);
    const double during = meanGray(sequence.render(jump.first_frame).cam0.image);
    EXPECT_EQ(sequence.exposure(jump.first_frame).jump, jump.factor);
    EXPECT_EQ(sequence.exposure(jump.first_frame - 1).jump, 1.0);
    if (jump.factor > 1.0) {
      EXPECT_GT(during, before * 1.3) << "frame " << jump.first_frame;
    } else {
      EXPECT_LT(during, before * 0.6) << "frame " << jump.first_frame;
    }
    if (jump.first_frame > 150) break;  // two jumps are enough for the test's time budget
  }
}

TEST(SynthLighting, DarkPresetIsDarkBlurredAndNoisy) {
  const SequenceRenderer dark(findPreset("dark-rgbd"), 60, 6), lit(findPreset("xyz-rgbd"), 60, 6);
  const Frame dark_frame = dark.render(40), lit_frame = lit.render(40);
  EXPECT_LT(meanGray(dark_frame.cam0.image), 0.5 * meanGray(lit_frame.cam0.image));
  EXPECT_GT(dark_frame.exposure.exposure_ms,
            3.0 * lit_frame.exposure.exposure_ms);  // long = blurred
  EXPECT_GT(dark_frame.exposure.gain, 2.0);         // high gain = noisy
  // Blur: without noise, the same view has weaker gradients than when rendered without blur.
  SynthOptions no_noise, no_blur;
  no_noise.sensor_noise = no_blur.sensor_noise = false;
  no_blur.motion_blur = false;
  const SequenceRenderer blurred(findPreset("dark-rgbd"), 60, 6, no_noise),
      sharp(findPreset("dark-rgbd"), 60, 6, no_blur);
  const auto sharpness = [](const cv::Mat& bgr) {
    cv::Mat gray, laplacian;
    cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
    cv::Laplacian(gray, laplacian, CV_32F);
    cv::Scalar mean, stddev;
    cv::meanStdDev(laplacian, mean, stddev);
    return stddev[0];
  };
  const double blurred_sharpness = sharpness(blurred.render(40).cam0.image);
  const double sharp_sharpness = sharpness(sharp.render(40).cam0.image);
  std::printf("laplacian std: blurred %.2f, sharp %.2f\n", blurred_sharpness, sharp_sharpness);
  EXPECT_LT(blurred_sharpness, 0.8 * sharp_sharpness);
}

TEST(SynthLighting, SpotlightLightsTheSceneUnevenly) {
  const auto unevenness = [](const char* name) {
    const SequenceRenderer sequence(findPreset(name), 30, 2);
    cv::Mat gray, blocks;
    cv::cvtColor(sequence.render(15).cam0.image, gray, cv::COLOR_BGR2GRAY);
    cv::resize(gray, blocks, {16, 12}, 0, 0, cv::INTER_AREA);
    std::vector<std::uint8_t> values(blocks.begin<std::uint8_t>(), blocks.end<std::uint8_t>());
    std::sort(values.begin(), values.end());
    return (values[values.size() * 9 / 10] + 1.0) / (values[values.size() / 10] + 1.0);
  };
  const double spot = unevenness("spotlight-rgbd"), uniform = unevenness("xyz-rgbd");
  EXPECT_GT(spot, 4.0);
  EXPECT_LT(uniform, 3.0);
}
