#include <gtest/gtest.h>

#include "lumaslam/camera/pinhole_camera.h"
#include "lumaslam/camera/stereo_geometry.h"
#include "lumaslam/camera/stereo_rectifier.h"
#include "lumaslam/core/error.h"
#include "lumaslam/io/settings.h"
#include "test_paths.h"

using lumaslam::Error;
using lumaslam::camera::depthToMetres;
using lumaslam::camera::PinholeCamera;
using lumaslam::camera::StereoGeometry;
using lumaslam::camera::StereoRectifier;

namespace {

lumaslam::io::Settings config(const std::string& name) {
  return lumaslam::io::loadSettings(lumaslam::test::sourceDir() / "configs" / name);
}

StereoGeometry geometryOf(const lumaslam::io::Settings& settings) {
  return StereoGeometry::fromSettings(settings.camera, settings.stereo.value(),
                                      settings.depth.thDepth);
}

StereoRectifier rectifierOf(const lumaslam::io::Settings& settings) {
  return StereoRectifier::fromSettings(settings.camera, settings.stereo.value(),
                                       settings.file->origin());
}

TEST(DepthToMetres, ScalesRawDepthAndKeepsHoles) {
  cv::Mat raw(2, 3, CV_16U, cv::Scalar(0));
  raw.at<uint16_t>(0, 0) = 5000;
  raw.at<uint16_t>(1, 2) = 65535;
  raw.at<uint16_t>(0, 1) = 7500;
  const cv::Mat metres = depthToMetres(raw, config("tum_fr1_rgbd.yaml").depth.depthMapFactor);
  ASSERT_EQ(metres.type(), CV_32F);
  EXPECT_FLOAT_EQ(metres.at<float>(0, 0), 1.0f);
  EXPECT_FLOAT_EQ(metres.at<float>(0, 1), 1.5f);
  EXPECT_FLOAT_EQ(metres.at<float>(1, 2), 13.107f);
  EXPECT_FLOAT_EQ(metres.at<float>(1, 0), 0.0f);

  cv::Mat floats(1, 2, CV_32F);
  floats.at<float>(0, 0) = 2.5f;
  floats.at<float>(0, 1) = std::numeric_limits<float>::quiet_NaN();
  const cv::Mat same = depthToMetres(floats, 1.0);
  EXPECT_FLOAT_EQ(same.at<float>(0, 0), 2.5f);
  EXPECT_FLOAT_EQ(same.at<float>(0, 1), 0.0f);  // NaN hole becomes "no measurement"

  EXPECT_THROW((void)depthToMetres(cv::Mat(2, 2, CV_8U, cv::Scalar(1)), 5000.0), Error);
  EXPECT_THROW((void)depthToMetres(raw, 0.0), Error);
  EXPECT_THROW((void)depthToMetres(cv::Mat(), 5000.0), Error);
}

// u_r = u - bf / z must be where the point really projects in a camera shifted by the baseline.
TEST(StereoGeometry, VirtualRightColumnMatchesAShiftedCamera) {
  const auto settings = config("kitti_00-02_stereo.yaml");
  const StereoGeometry geometry = geometryOf(settings);
  const PinholeCamera cam = PinholeCamera::fromSettings(settings.camera);
  const Eigen::Vector3d right_in_left(settings.baseline(), 0.0, 0.0);
  for (const Eigen::Vector3d& p_l :
       {Eigen::Vector3d(1.0, -0.5, 4.0), Eigen::Vector3d(-3.0, 1.0, 25.0),
        Eigen::Vector3d(0.2, 0.1, 60.0)}) {
    const Eigen::Vector2d left = cam.project(p_l);
    const Eigen::Vector2d right = cam.project(p_l - right_in_left);
    EXPECT_NEAR(geometry.rightU(static_cast<float>(left.x()), static_cast<float>(p_l.z())),
                right.x(), 1e-3);
    EXPECT_NEAR(geometry.depthFromDisparity(left.x() - right.x()), p_l.z(), 1e-9 * p_l.z());
  }
  EXPECT_NEAR(geometry.closeDepth(), 35.0 * 0.53716, 1e-9);
  EXPECT_TRUE(geometry.isClose(10.0));
  EXPECT_FALSE(geometry.isClose(19.0));
  EXPECT_FALSE(geometry.isClose(0.0));
}

TEST(StereoGeometry, RgbdUsesTheProjectorBaseline) {
  const StereoGeometry g = geometryOf(config("tum_fr1_rgbd.yaml"));
  EXPECT_NEAR(g.bf(), 40.0, 0.01);
  EXPECT_NEAR(g.closeDepth(), 40.0 * 0.07732, 1e-9);
  EXPECT_TRUE(g.isClose(3.0));
  EXPECT_FALSE(g.isClose(3.2));
}

TEST(StereoGeometry, UnrectifiedPairNeedsTheRectifier) {
  const auto euroc = config("euroc_stereo.yaml");
  EXPECT_THROW((void)geometryOf(euroc), Error);
  EXPECT_FALSE(config("euroc_mono.yaml").stereo);  // a monocular file has no baseline at all
  const auto rectifier = rectifierOf(euroc);
  const StereoGeometry g = StereoGeometry::fromRectifier(rectifier, euroc.depth.thDepth);
  EXPECT_NEAR(g.bf(), rectifier.rectifiedCamera().fx() * 0.11008, 0.01);
  EXPECT_NEAR(g.closeDepth(), 60.0 * rectifier.baseline(), 1e-9);
  EXPECT_THROW(StereoGeometry(40.0, 0.0, 40.0), Error);
}

}  // namespace
