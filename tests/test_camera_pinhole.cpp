#include <gtest/gtest.h>

#include <random>

#include "lumaslam/camera/pinhole_camera.h"
#include "lumaslam/core/error.h"
#include "lumaslam/io/settings.h"
#include "test_paths.h"

using lumaslam::Error;
using lumaslam::camera::PinholeCamera;

namespace {

// EuRoC cam0: strong barrel distortion (k1 = -0.28), the hard case for undistortion.
PinholeCamera eurocCam0() {
  return PinholeCamera(458.654, 457.296, 367.215, 248.375, {752, 480},
                       {-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05, 0.0});
}

// The radial-tangential model written out (OpenCV's documented formula), as ground truth.
cv::Point2f distortByFormula(const PinholeCamera& cam, cv::Point2f ideal) {
  const auto& d = cam.distortion();
  const double x = (ideal.x - cam.cx()) / cam.fx(), y = (ideal.y - cam.cy()) / cam.fy();
  const double r2 = x * x + y * y;
  const double radial = 1 + d[0] * r2 + d[1] * r2 * r2 + d[4] * r2 * r2 * r2;
  const double xd = x * radial + 2 * d[2] * x * y + d[3] * (r2 + 2 * x * x);
  const double yd = y * radial + d[2] * (r2 + 2 * y * y) + 2 * d[3] * x * y;
  return {static_cast<float>(cam.fx() * xd + cam.cx()),
          static_cast<float>(cam.fy() * yd + cam.cy())};
}

TEST(PinholeCamera, ProjectUnprojectRoundTrip) {
  const PinholeCamera cam = eurocCam0();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> xy(-2.0, 2.0), z(0.5, 10.0);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d p(xy(rng), xy(rng), z(rng));
    const Eigen::Vector2d uv = cam.project(p);
    EXPECT_TRUE(cam.unproject(uv, p.z()).isApprox(p, 1e-12));
  }
  EXPECT_TRUE(cam.project({0.0, 0.0, 3.0}).isApprox(Eigen::Vector2d(cam.cx(), cam.cy())));
  EXPECT_TRUE(cam.inImage({0.0, 0.0}));
  EXPECT_FALSE(cam.inImage({752.0, 10.0}));
}

TEST(PinholeCamera, UndistortInvertsTheDistortionModelOverTheWholeImage) {
  const PinholeCamera cam = eurocCam0();
  std::vector<cv::Point2f> ideal, raw;
  for (float v = 10; v < 480; v += 20) {
    for (float u = 10; u < 752; u += 20) {
      const cv::Point2f d = distortByFormula(cam, {u, v});
      if (d.x < 0 || d.y < 0 || d.x >= 752 || d.y >= 480) continue;  // not visible
      ideal.emplace_back(u, v);
      raw.push_back(d);
    }
  }
  ASSERT_GT(ideal.size(), 500u);
  const auto undistorted = cam.undistortPoints(raw);
  const auto redistorted = cam.distortPoints(ideal);
  double worst = 0.0, worstModel = 0.0, largestShift = 0.0;
  for (std::size_t i = 0; i < ideal.size(); ++i) {
    worst = std::max(worst, cv::norm(undistorted[i] - ideal[i]));
    worstModel = std::max(worstModel, cv::norm(redistorted[i] - raw[i]));
    largestShift = std::max(largestShift, cv::norm(raw[i] - ideal[i]));
  }
  EXPECT_GT(largestShift, 20.0);  // the distortion is real: tens of pixels at the corners
  EXPECT_LT(worst, 0.01);
  EXPECT_LT(worstModel, 1e-3);
}

TEST(PinholeCamera, UndistortKeypointsKeepsTheirAttributes) {
  const PinholeCamera cam = eurocCam0();
  const cv::Point2f ideal(60.0f, 50.0f);
  cv::KeyPoint kp(distortByFormula(cam, ideal), 31.0f, 45.0f, 0.5f, 3, 9);
  const auto out = cam.undistortKeypoints({kp});
  ASSERT_EQ(out.size(), 1u);
  EXPECT_LT(cv::norm(out[0].pt - ideal), 0.01);
  EXPECT_EQ(out[0].octave, 3);
  EXPECT_FLOAT_EQ(out[0].angle, 45.0f);
  EXPECT_FLOAT_EQ(out[0].size, 31.0f);

  const PinholeCamera plain = cam.undistorted();
  EXPECT_FALSE(plain.hasDistortion());
  EXPECT_EQ(plain.undistortPoints({kp.pt})[0], kp.pt);
}

TEST(PinholeCamera, FromSettingsUsesTheWorkingSize) {
  const auto settings =
      lumaslam::io::loadSettings(lumaslam::test::sourceDir() / "configs/euroc_mono.yaml");
  const PinholeCamera cam = PinholeCamera::fromSettings(settings.camera);
  EXPECT_DOUBLE_EQ(cam.fx(), 458.654);
  EXPECT_DOUBLE_EQ(cam.K()(1, 2), 248.375);
  EXPECT_DOUBLE_EQ(cam.distortionCoefficients().at<double>(0, 0), -0.28340811);
  EXPECT_EQ(cam.size().width, 752);

  auto half = settings.camera;
  half.resizeTo = lumaslam::camera::ImageSize{376, 240};
  const PinholeCamera small = PinholeCamera::fromSettings(half);
  EXPECT_DOUBLE_EQ(small.fx(), 458.654 / 2);
  EXPECT_DOUBLE_EQ(small.cy(), 248.375 / 2);
  EXPECT_EQ(small.size().height, 240);
}

TEST(PinholeCamera, RejectsImpossibleIntrinsics) {
  EXPECT_THROW(PinholeCamera(0.0, 500.0, 320.0, 240.0, {640, 480}), Error);
  EXPECT_THROW(PinholeCamera(500.0, 500.0, 320.0, 240.0, {0, 480}), Error);
}

}  // namespace
