#pragma once
// Synthetic frames for the place-recognition tests: one lap of the `loop-rgbd` room (the
// camera faces outwards, so frames far apart on the lap see different walls) and their ORB
// descriptors.
#include <vector>

#include <opencv2/imgproc.hpp>

#include "lumaslam/feature/orb_extractor.h"
#include "lumaslam/synth/preset.h"
#include "lumaslam/synth/sequence.h"

namespace lumaslam::test {

struct LoopLapFrames {
  std::vector<cv::Mat> gray;
  std::vector<cv::Mat> descriptors;
  std::vector<SE3> T_w_c;
};

// `frames` evenly spaced frames of one lap (frame i at 360 * i / frames degrees).
inline LoopLapFrames renderLoopLap(int frames, std::uint64_t seed, int features = 1000) {
  const synth::SequenceRenderer sequence(synth::findPreset("loop-rgbd"), frames, seed);
  feature::OrbSettings settings;
  settings.nFeatures = features;
  const feature::OrbExtractor extractor(settings);
  LoopLapFrames lap;
  for (int i = 0; i < frames; ++i) {
    const synth::Frame frame = sequence.render(i);
    cv::Mat gray;
    cv::cvtColor(frame.cam0.image, gray, cv::COLOR_BGR2GRAY);
    lap.descriptors.push_back(extractor.extract(gray).descriptors);
    lap.gray.push_back(gray);
    lap.T_w_c.push_back(frame.cam0.T_w_c);
  }
  return lap;
}

}  // namespace lumaslam::test
