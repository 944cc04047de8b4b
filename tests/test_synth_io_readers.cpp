// The project's dataset readers load synth's TUM and EuRoC folders without special cases.
#include <gtest/gtest.h>

#include "lumaslam/io/dataset_reader.h"
#include "lumaslam/io/trajectory_io.h"
#include "lumaslam/synth/dataset_writer.h"
#include "test_paths.h"

using namespace lumaslam;

TEST(SynthIoReaders, TumReaderLoadsSynthRgbd) {
  test::TempDir dir("synth_io_tum");
  const synth::SequenceRenderer sequence(synth::findPreset("walking-xyz-rgbd"), 5, 4);
  synth::writeDataset(sequence, dir.path());
  const auto reader = io::openDataset("tum:" + dir.path().string());
  ASSERT_EQ(reader->size(), 5u);
  EXPECT_TRUE(reader->hasDepth());
  int frames = 0;
  while (auto frame = reader->next()) {
    const synth::Frame rendered = sequence.render(frames);
    EXPECT_NEAR(frame->timestamp, rendered.timestamp(), 1e-6);
    EXPECT_EQ(frame->image.size(), rendered.cam0.image.size());
    ASSERT_EQ(frame->depth.type(), CV_16U);
    cv::Mat metres;
    frame->depth.convertTo(metres, CV_32F, 1.0 / 5000.0);
    EXPECT_LT(cv::norm(metres, rendered.sensor_depth, cv::NORM_INF), 1.0 / 5000.0);
    ++frames;
  }
  EXPECT_EQ(frames, 5);
  const Trajectory gt = reader->groundTruth();
  ASSERT_EQ(gt.size(), 5u);
  for (size_t i = 0; i < gt.size(); ++i) {
    const SE3 expected = sequence.render(static_cast<int>(i)).cam0.T_w_c;
    EXPECT_LT((gt[i].T_w_c.translation() - expected.translation()).norm(), 2e-6);
  }
  EXPECT_EQ(io::readTrajectory(dir.path() / "groundtruth.txt").size(), 5u);
}

TEST(SynthIoReaders, EurocReaderLoadsSynthStereo) {
  test::TempDir dir("synth_io_euroc");
  const synth::SequenceRenderer sequence(synth::findPreset("xyz-stereo"), 4, 4);
  synth::writeDataset(sequence, dir.path());
  const auto reader = io::openDataset("euroc:" + dir.path().string());
  ASSERT_EQ(reader->size(), 4u);
  EXPECT_TRUE(reader->isStereo());
  const auto frame = reader->next();
  ASSERT_TRUE(frame.has_value());
  EXPECT_EQ(frame->image.cols, 752);
  EXPECT_FALSE(frame->right.empty());
  EXPECT_NEAR(frame->timestamp, sequence.timestampNs(0) * 1e-9, 1e-6);
  const auto calibration = reader->calibration();
  ASSERT_TRUE(calibration.has_value());
  EXPECT_DOUBLE_EQ(calibration->left.fx, 458.654);
  EXPECT_NEAR(calibration->baseline(), 0.11, 1e-9);
  const Trajectory gt = reader->groundTruth();
  ASSERT_GE(gt.size(), 4u);
  const SE3 first = sequence.render(0).cam0.T_w_c;
  EXPECT_LT((gt.front().T_w_c.translation() - first.translation()).norm(), 2e-6);
}
