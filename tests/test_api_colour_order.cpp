// Camera.RGB through the public API (docs/settings.md "Colour order"), on real Kinect frames
// (7-Scenes redkitchen in ../shared/data): RGB arrays declared RGB must give exactly the run of
// BGR arrays declared BGR, since enhancement, ORB's gray image and the detector must all see the
// true colours; BGR arrays declared RGB (ORB-SLAM3's TUM files say 1, its examples feed
// cv::imread's BGR) must not, which shows that the key reaches them.
#include <cstddef>
#include <fstream>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "lumaslam/dataset.h"
#include "lumaslam/system.h"
#include "test_paths.h"

namespace lumaslam {
namespace {

constexpr std::size_t kFrames = 40;

std::filesystem::path redKitchen() {
  return test::dataDir() / "7scenes_redkitchen";
}

// The sequence's own settings file with `Camera.RGB: value`.
std::filesystem::path settingsWithColourOrder(const test::TempDir& dir, int value) {
  std::ifstream in(redKitchen() / "settings.yaml");
  std::stringstream text;
  text << in.rdbuf();
  const std::regex key(R"((^|\n)Camera\.RGB: *[01])");
  EXPECT_TRUE(std::regex_search(text.str(), key)) << "7-Scenes settings.yaml has no Camera.RGB";
  const auto path = dir.path() / ("settings_rgb" + std::to_string(value) + ".yaml");
  std::ofstream(path) << std::regex_replace(text.str(), key,
                                            "$1Camera.RGB: " + std::to_string(value));
  return path;
}

cv::Mat swapRedAndBlue(const cv::Mat& bgr) {
  std::vector<cv::Mat> channels;
  cv::split(bgr, channels);
  std::swap(channels[0], channels[2]);
  cv::Mat rgb;
  cv::merge(channels, rgb);
  return rgb;
}

// Poses of the first kFrames frames (nullopt where not tracked), sequential so that runs are
// deterministic; `as_rgb`: hand the frames over in RGB order.
std::vector<std::optional<Eigen::Matrix4d>> track(const std::filesystem::path& settings,
                                                  bool as_rgb) {
  SystemConfig config;
  config.sequential = true;
  System system(settings, config);
  Dataset dataset("tum:" + redKitchen().string(), kFrames);
  std::vector<std::optional<Eigen::Matrix4d>> poses;
  while (auto frame = dataset.next()) {
    EXPECT_EQ(frame->image.channels(), 3);
    const cv::Mat image = as_rgb ? swapRedAndBlue(frame->image) : frame->image;
    poses.push_back(system.trackRgbd(image, frame->depth, frame->timestamp).T_w_c);
  }
  return poses;
}

std::size_t trackedCount(const std::vector<std::optional<Eigen::Matrix4d>>& poses) {
  return static_cast<std::size_t>(
      std::count_if(poses.begin(), poses.end(), [](const auto& pose) { return pose.has_value(); }));
}

TEST(ApiColourOrder, RgbArraysDeclaredRgbTrackExactlyAsBgrArraysDeclaredBgr) {
  const test::TempDir dir("api_colour_order");
  const auto bgr_settings = settingsWithColourOrder(dir, 0);
  const auto rgb_settings = settingsWithColourOrder(dir, 1);

  const auto bgr = track(bgr_settings, /*as_rgb=*/false);
  const auto rgb = track(rgb_settings, /*as_rgb=*/true);
  ASSERT_EQ(bgr.size(), kFrames);
  ASSERT_EQ(rgb.size(), kFrames);
  EXPECT_EQ(trackedCount(bgr), kFrames);
  for (std::size_t i = 0; i < kFrames; ++i) {
    ASSERT_EQ(rgb[i].has_value(), bgr[i].has_value()) << "frame " << i;
    if (bgr[i]) EXPECT_EQ(*rgb[i], *bgr[i]) << "frame " << i;
  }

  // Declared RGB but handed over as BGR: red and blue are swapped on the way in, so the gray
  // image differs and with it the features and the poses.
  const auto swapped = track(rgb_settings, /*as_rgb=*/false);
  ASSERT_EQ(swapped.size(), kFrames);
  double largest_difference = 0.0;
  for (std::size_t i = 0; i < kFrames; ++i) {
    if (swapped[i] && bgr[i]) {
      largest_difference =
          std::max(largest_difference, (*swapped[i] - *bgr[i]).cwiseAbs().maxCoeff());
    }
  }
  EXPECT_GT(largest_difference, 0.0) << "Camera.RGB: 1 did not change what the stages see";
}

}  // namespace
}  // namespace lumaslam
