// Gate decisions, Eq. 4 values, the adaptive limit at its extremes, the HSV rebuild, odd
// inputs and settings, on constructed images with known answers.
#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "error_of.h"
#include "lumaslam/core/error.h"
#include "lumaslam/core/settings_file.h"
#include "lumaslam/enhance/adaptive_limit.h"
#include "lumaslam/enhance/brightness_compensation.h"
#include "lumaslam/enhance/enhancer.h"
#include "lumaslam/enhance/quality_gate.h"
#include "lumaslam/enhance/value_channel.h"

namespace lumaslam::enhance {
namespace {

// Half the pixels at `low`, half at `high`: mean and std are known exactly.
cv::Mat twoLevelImage(int low, int high) {
  cv::Mat image(64, 64, CV_8UC1, cv::Scalar(low));
  image(cv::Rect(0, 0, 32, 64)).setTo(high);
  return image;
}

TEST(EnhanceGate, MeasuresMeanAndStdInUnitRange) {
  const BrightnessStats stats = measureBrightness(twoLevelImage(51, 204));
  EXPECT_NEAR(stats.mean, 0.5, 1e-9);
  EXPECT_NEAR(stats.std, 0.3, 1e-9);
}

TEST(EnhanceGate, LeavesOnlyWellExposedContrastyFramesAlone) {
  const QualityGate gate(QualityGateParams{});
  EXPECT_FALSE(gate.needsCompensation(measureBrightness(twoLevelImage(51, 204))));  // 0.5, 0.3
  EXPECT_TRUE(gate.needsCompensation({0.5, 0.2}));     // too flat (theta 0.22)
  EXPECT_TRUE(gate.needsCompensation({0.2, 0.3}));     // too dark (|0.2-0.5| >= 0.12)
  EXPECT_TRUE(gate.needsCompensation({0.85, 0.3}));    // too bright
  EXPECT_FALSE(gate.needsCompensation({0.61, 0.23}));  // just inside both thresholds
  EXPECT_TRUE(gate.needsCompensation(measureBrightness(twoLevelImage(5, 40))));
  QualityGateParams off;
  off.enabled = false;
  EXPECT_TRUE(QualityGate(off).needsCompensation({0.5, 0.3}));
}

TEST(EnhanceCompensation, PaperAndSwappedWeightsFollowEquation4) {
  CompensationParams params;
  const BrightnessCompensation paper(params);
  // The example: Lmean = 0.1, L = 0.2 gives 0.203 with the printed weights.
  const double expected_paper = 0.1 * std::pow(0.2, 0.2) + 0.9 * std::pow(0.2, 1.2);
  EXPECT_NEAR(paper.map(0.2, 0.1), expected_paper, 1e-12);
  EXPECT_NEAR(paper.map(0.2, 0.1), 0.203, 0.001);
  params.weights = CompensationWeights::kSwapped;
  const BrightnessCompensation swapped(params);
  EXPECT_NEAR(swapped.map(0.2, 0.1), 0.9 * std::pow(0.2, 0.2) + 0.1 * std::pow(0.2, 1.2), 1e-12);
  EXPECT_GT(swapped.map(0.2, 0.1), 0.6);  // the swapped form lifts a dark frame
  for (const auto* model : {&paper, &swapped}) {
    EXPECT_DOUBLE_EQ(model->map(0.0, 0.3), 0.0);
    EXPECT_DOUBLE_EQ(model->map(1.0, 0.3), 1.0);
    const cv::Mat table = model->lookupTable(0.1);
    for (int i = 1; i < 256; ++i) EXPECT_GE(table.at<uchar>(i), table.at<uchar>(i - 1));
    EXPECT_EQ(table.at<uchar>(51), cv::saturate_cast<uchar>(255.0 * model->map(0.2, 0.1)));
  }
}

TEST(EnhanceAdaptiveLimit, EqualsBaseAtTheMaximaAndBasePlusTwoForFlatImages) {
  ClaheParams params;
  params.sigma_max = 40.0;
  params.d_max = 900.0;
  const ClipLimitModel model(params);
  EXPECT_DOUBLE_EQ(model.limit({40.0, 900.0}), 1.0);   // = c
  EXPECT_DOUBLE_EQ(model.limit({80.0, 5000.0}), 1.0);  // beyond the maxima: clamped
  EXPECT_DOUBLE_EQ(model.limit({0.0, 0.0}), 3.0);
  EXPECT_DOUBLE_EQ(model.limit({20.0, 450.0}), 2.0);
  params.base = 2.5;
  params.gain = 3.0;
  EXPECT_DOUBLE_EQ(ClipLimitModel(params).limit({20.0, 900.0}), 2.5 + 1.5);
}

TEST(EnhanceAdaptiveLimit, OnlineMaximaGrowFromTheirSeeds) {
  ClaheParams params;
  params.maxima = MaximaSource::kOnline;
  params.sigma_max = 10.0;
  params.d_max = 100.0;
  ClipLimitModel model(params);
  model.observe({5.0, 50.0});
  EXPECT_DOUBLE_EQ(model.sigmaMax(), 10.0);
  model.observe({30.0, 400.0});
  EXPECT_DOUBLE_EQ(model.sigmaMax(), 30.0);
  EXPECT_DOUBLE_EQ(model.dMax(), 400.0);
  EXPECT_DOUBLE_EQ(model.limit({30.0, 400.0}), 1.0);
}

TEST(EnhanceAdaptiveLimit, StatisticsMatchTheirDefinitions) {
  const cv::Mat image = twoLevelImage(51, 204);
  EXPECT_NEAR(measureContrast(image, SigmaSource::kIntensity).sigma, 76.5, 1e-9);
  // A vertical step edge: the Laplacian is +-153 on the two columns next to it.
  const ContrastStats stats = measureContrast(image, SigmaSource::kGradient);
  EXPECT_GT(stats.sigma, 0.0);
  const double n = 64.0 * 64.0;
  const double lap_mean = 0.0;  // +153 and -153 columns cancel
  EXPECT_NEAR(stats.d, 2 * 64 * 153.0 * 153.0 / n - lap_mean, 1e-6);
  const cv::Mat flat(32, 32, CV_8UC1, cv::Scalar(90));
  EXPECT_DOUBLE_EQ(measureContrast(flat, SigmaSource::kGradient).sigma, 0.0);
  EXPECT_DOUBLE_EQ(measureContrast(flat, SigmaSource::kGradient).d, 0.0);
}

// Hue in degrees and saturation of one BGR pixel (Eq. 5-7).
std::pair<double, double> hueSaturation(const cv::Vec3b& bgr) {
  const double b = bgr[0], g = bgr[1], r = bgr[2];
  const double max = std::max({r, g, b});
  const double c = max - std::min({r, g, b});
  if (c == 0.0) return {0.0, 0.0};
  double h = max == r   ? std::fmod((g - b) / c + 6.0, 6.0)
             : max == g ? (b - r) / c + 2.0
                        : (r - g) / c + 4.0;
  return {60.0 * h, c / max};
}

TEST(EnhanceValueChannel, RebuildKeepsHueAndSaturation) {
  cv::Mat bgr(40, 60, CV_8UC3);
  cv::RNG rng(5);
  rng.fill(bgr, cv::RNG::UNIFORM, 20, 120);
  const cv::Mat value = valueChannel(bgr);
  for (int y = 0; y < bgr.rows; ++y) {
    for (int x = 0; x < bgr.cols; ++x) {
      const auto p = bgr.at<cv::Vec3b>(y, x);
      ASSERT_EQ(value.at<uchar>(y, x), std::max({p[0], p[1], p[2]}));
    }
  }
  cv::Mat brighter;
  value.convertTo(brighter, CV_8U, 2.0);
  const cv::Mat rebuilt = rebuildColour(bgr, value, brighter);
  EXPECT_EQ(cv::countNonZero(valueChannel(rebuilt) != brighter), 0);
  for (int y = 0; y < bgr.rows; ++y) {
    for (int x = 0; x < bgr.cols; ++x) {
      const auto [h0, s0] = hueSaturation(bgr.at<cv::Vec3b>(y, x));
      const auto [h1, s1] = hueSaturation(rebuilt.at<cv::Vec3b>(y, x));
      // Rounding to 8 bits moves hue by at most a few degrees for low-chroma pixels.
      const double dh = std::min(std::abs(h0 - h1), 360.0 - std::abs(h0 - h1));
      ASSERT_LT(dh, 3.0) << x << "," << y;
      ASSERT_NEAR(s0, s1, 0.02) << x << "," << y;
    }
  }
}

TEST(EnhanceEnhancer, GrayAndColourPathsAgreeOnTheWorkChannel) {
  cv::Mat gray(120, 160, CV_8UC1);
  cv::RNG(3).fill(gray, cv::RNG::UNIFORM, 5, 60);
  cv::Mat bgr;
  cv::cvtColor(gray, bgr, cv::COLOR_GRAY2BGR);  // V = gray for a gray-valued colour image
  for (const auto& preset : EnhancerParams::presetNames()) {
    Enhancer enhancer(EnhancerParams::forPreset(preset));
    const EnhancedFrame from_gray = enhancer.enhance(gray);
    const EnhancedFrame from_colour = Enhancer(EnhancerParams::forPreset(preset)).enhance(bgr);
    ASSERT_EQ(from_gray.gray.type(), CV_8UC1);
    ASSERT_EQ(from_colour.colour.type(), CV_8UC3);
    cv::Mat diff;
    cv::absdiff(from_gray.gray, from_colour.gray, diff);
    double max_diff = 0.0;
    cv::minMaxLoc(diff, nullptr, &max_diff);
    EXPECT_LE(max_diff, 1.0) << preset;
  }
}

TEST(EnhanceEnhancer, DarkFramesGetBrighterAndReportWhatWasDone) {
  cv::Mat dark(96, 128, CV_8UC1);
  cv::RNG(9).fill(dark, cv::RNG::UNIFORM, 0, 40);
  Enhancer enhancer(EnhancerParams::forPreset("paper"));
  const EnhancedFrame frame = enhancer.enhance(dark);
  EXPECT_TRUE(frame.report.compensated);
  ASSERT_TRUE(frame.report.limit.has_value());
  EXPECT_GE(*frame.report.limit, 1.0);
  EXPECT_LE(*frame.report.limit, 3.0);
  EXPECT_GT(cv::mean(frame.gray)[0], cv::mean(dark)[0] + 20.0);
  EXPECT_FALSE(Enhancer(EnhancerParams::forPreset("off")).enhance(dark).report.compensated);
  EXPECT_EQ(cv::countNonZero(Enhancer(EnhancerParams::forPreset("off")).enhance(dark).gray != dark),
            0);
}

// The right image of a stereo pair with the left plan: Enhancement.stereo picks the rule.
TEST(EnhanceEnhancer, RightImageFollowsTheStereoMapping) {
  cv::Mat left(96, 128, CV_8UC1);
  cv::Mat right(96, 128, CV_8UC1);
  cv::randu(left, 0, 60);
  cv::randu(right, 10, 90);
  const auto enhanced = [&](StereoMapping mapping) {
    EnhancerParams params = EnhancerParams::forPreset("best");
    params.stereo = mapping;
    Enhancer enhancer(params);
    const EnhancementPlan plan = enhancer.plan(left);
    const cv::Mat expected = mapping == StereoMapping::kShared
                                 ? enhancer.apply(right, plan).gray
                                 : enhancer.enhanceWith(right, plan).gray;
    return std::pair{enhancer.enhanceRightWith(right, plan).gray, expected};
  };
  for (const auto mapping : {StereoMapping::kShared, StereoMapping::kDecisions}) {
    const auto [got, expected] = enhanced(mapping);
    EXPECT_EQ(cv::norm(got, expected, cv::NORM_INF), 0.0);
  }
  EXPECT_GT(cv::norm(enhanced(StereoMapping::kShared).first,
                     enhanced(StereoMapping::kDecisions).first, cv::NORM_INF),
            0.0);  // the two rules differ on this pair
  EnhancerParams independent = EnhancerParams::forPreset("best");
  independent.stereo = StereoMapping::kIndependent;
  Enhancer enhancer(independent);
  const EnhancementPlan plan = enhancer.plan(left);
  EXPECT_THROW((void)enhancer.enhanceRightWith(right, plan), Error);
}

TEST(EnhanceEnhancer, LocalLimitsStayInRange) {
  EnhancerParams params = EnhancerParams::forPreset("full");
  params.clahe.limit_mode = ClipLimitMode::kLocal;
  cv::Mat image(100, 130, CV_8UC1);
  cv::RNG(4).fill(image, cv::RNG::UNIFORM, 0, 255);
  image(cv::Rect(0, 0, 60, 50)).setTo(20);
  const EnhancedFrame frame = Enhancer(params).enhance(image);
  ASSERT_TRUE(frame.report.limit.has_value());
  EXPECT_GE(*frame.report.limit, 1.0);
  EXPECT_LE(*frame.report.limit, 3.0);
  EXPECT_EQ(Enhancer(params).contrastOf(image).size(), 64u);
}

TEST(EnhanceEnhancer, OddInputsGiveAnErrorOrADefinedResult) {
  Enhancer enhancer(EnhancerParams::forPreset("paper"));
  EXPECT_THROW(enhancer.enhance(cv::Mat()), Error);
  EXPECT_THROW(enhancer.enhance(cv::Mat(8, 8, CV_16UC1, cv::Scalar(1000))), Error);
  EXPECT_THROW(enhancer.enhance(cv::Mat(8, 8, CV_32FC1, cv::Scalar(0.5))), Error);
  EXPECT_THROW(enhancer.enhance(cv::Mat(8, 8, CV_8UC2, cv::Scalar(1, 2))), Error);
  const std::string message = test::errorOf([&] { enhancer.enhance(cv::Mat(8, 8, CV_16UC1)); });
  EXPECT_NE(message.find("8-bit"), std::string::npos) << message;
  for (const auto& preset : EnhancerParams::presetNames()) {
    Enhancer each(EnhancerParams::forPreset(preset));
    for (const cv::Mat& image :
         {cv::Mat(1, 1, CV_8UC1, cv::Scalar(7)), cv::Mat(50, 40, CV_8UC1, cv::Scalar(0)),
          cv::Mat(50, 40, CV_8UC1, cv::Scalar(255)), cv::Mat(30, 30, CV_8UC1, cv::Scalar(128)),
          cv::Mat(1, 1, CV_8UC3, cv::Scalar(1, 2, 3))}) {
      const EnhancedFrame frame = each.enhance(image);
      ASSERT_EQ(frame.gray.size(), image.size()) << preset;
      EXPECT_FALSE(std::isnan(frame.report.brightness.mean));
      if (frame.report.limit) {
        EXPECT_TRUE(std::isfinite(*frame.report.limit)) << preset;
      }
    }
    const EnhancedFrame bgra = each.enhance(cv::Mat(20, 20, CV_8UC4, cv::Scalar(10, 20, 30, 255)));
    EXPECT_EQ(bgra.colour.type(), CV_8UC3) << preset;
  }
}

TEST(EnhanceSettings, MissingKeysTakePresetDefaultsAndEveryKeyIsRead) {
  const auto defaults = EnhancerParams::fromSettings(core::SettingsFile::fromString("Other: 1\n"));
  EXPECT_EQ(defaults.preset, "best");
  const auto paper = EnhancerParams::fromSettings(core::SettingsFile::fromString(
      "Enhancement.preset: \"paper\"\nEnhancement.clahe.tilesX: 4\n"
      "Enhancement.brightness.weights: \"swapped\"\nEnhancement.clahe.limitMode: \"local\"\n"));
  EXPECT_EQ(paper.clahe.tiles_x, 4);
  EXPECT_EQ(paper.clahe.tiles_y, 8);
  EXPECT_EQ(paper.compensation.weights, CompensationWeights::kSwapped);
  EXPECT_EQ(paper.clahe.limit_mode, ClipLimitMode::kLocal);
  EXPECT_EQ(paper.channel, WorkChannel::kValue);
  for (const auto& [name, mapping] : {std::pair{"independent", StereoMapping::kIndependent},
                                      std::pair{"decisions", StereoMapping::kDecisions},
                                      std::pair{"shared", StereoMapping::kShared}}) {
    EXPECT_EQ(
        EnhancerParams::fromSettings(
            core::SettingsFile::fromString(std::string("Enhancement.stereo: \"") + name + "\"\n"))
            .stereo,
        mapping);
  }
  // Round trip: every parameter written by toSettingsText reads back unchanged.
  EnhancerParams custom = EnhancerParams::forPreset("full");
  custom.gate.epsilon = 0.07;
  custom.compensation.alpha = 0.31;
  custom.clahe.gain = 2.5;
  custom.clahe.maxima = MaximaSource::kOnline;
  custom.clahe.sigma_max = 55.5;
  custom.clahe.d_max = 1234.0;
  custom.channel = WorkChannel::kGray;
  custom.stereo = StereoMapping::kDecisions;
  const auto back = EnhancerParams::fromSettings(
      core::SettingsFile::fromString(custom.toSettingsText(), "roundtrip"));
  EXPECT_EQ(back.toSettingsText(), custom.toSettingsText());
}

// Every real of toSettingsText is written in its shortest round-trip form (issue 21): values
// with more than 6 decimals read back bit for bit.
TEST(EnhanceSettings, RealsReadBackBitForBit) {
  EnhancerParams custom = EnhancerParams::forPreset("paper");
  custom.gate.epsilon = 0.1 + 1e-12;
  custom.gate.theta = 1.0 / 3.0;
  custom.compensation.alpha = 0.2000000001;
  custom.compensation.beta = 1.2345678901234567;
  custom.clahe.fixed_limit = 2.0000000123;
  custom.clahe.base = 6.1e-7;
  custom.clahe.gain = 3.141592653589793;
  custom.clahe.sigma_max = 98.76543210987654;
  custom.clahe.d_max = 1295.0000001;
  const std::string text = custom.toSettingsText();
  const auto back = EnhancerParams::fromSettings(core::SettingsFile::fromString(text, "bits"));
  EXPECT_EQ(back.gate.epsilon, custom.gate.epsilon) << text;
  EXPECT_EQ(back.gate.theta, custom.gate.theta);
  EXPECT_EQ(back.compensation.alpha, custom.compensation.alpha);
  EXPECT_EQ(back.compensation.beta, custom.compensation.beta);
  EXPECT_EQ(back.clahe.fixed_limit, custom.clahe.fixed_limit) << text;
  EXPECT_EQ(back.clahe.base, custom.clahe.base) << text;
  EXPECT_EQ(back.clahe.gain, custom.clahe.gain);
  EXPECT_EQ(back.clahe.sigma_max, custom.clahe.sigma_max) << text;
  EXPECT_EQ(back.clahe.d_max, custom.clahe.d_max) << text;
  EXPECT_EQ(back.toSettingsText(), text);
}

TEST(EnhanceSettings, WrongValuesNameTheFileAndKey) {
  const auto expectError = [](const std::string& yaml, const std::string& key) {
    const std::string message = test::errorOf(
        [&] { EnhancerParams::fromSettings(core::SettingsFile::fromString(yaml, "my.yaml")); });
    EXPECT_NE(message.find("my.yaml"), std::string::npos) << "for " << yaml << ": " << message;
    EXPECT_NE(message.find(key), std::string::npos) << "for " << yaml << ": " << message;
  };
  expectError("Enhancement.preset: \"shiny\"\n", "Enhancement.preset");
  expectError("Enhancement.stereo: \"both\"\n", "Enhancement.stereo");
  expectError("Enhancement.gate.epsilon: \"small\"\n", "Enhancement.gate.epsilon");
  expectError("Enhancement.clahe.tilesX: 2.5\n", "Enhancement.clahe.tilesX");
  expectError("Enhancement.clahe.tilesY: 0\n", "Enhancement.clahe.tilesY");
  expectError("Enhancement.clahe.sigma: \"laplace\"\n", "Enhancement.clahe.sigma");
  expectError("Enhancement.brightness.alpha: -1\n", "Enhancement.brightness.alpha");
  expectError("Enhancement.channel: 3\n", "Enhancement.channel");
}

}  // namespace
}  // namespace lumaslam::enhance
