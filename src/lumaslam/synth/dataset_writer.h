#pragma once
// Writes a SequenceRenderer's frames to disk as a benchmark-format dataset folder:
// TUM RGB-D (rgb/, depth/, rgb.txt, depth.txt, groundtruth.txt, associations.txt) for RGB-D
// rigs, EuRoC ASL (mav0/cam0, mav0/cam1, mav0/state_groundtruth_estimate0) for stereo rigs;
// both also get settings.yaml (ORB-SLAM3 style), detections.txt and mask/ (dynamic objects).
#include <filesystem>
#include <functional>
#include <string>

#include "lumaslam/synth/sequence.h"

namespace lumaslam::synth {

// Told after every frame written (frames done, frames in all); called from the rendering
// threads, one call at a time.
using FrameProgress = std::function<void(int done, int total)>;

void writeDataset(const SequenceRenderer& sequence, const std::filesystem::path& out,
                  const FrameProgress& progress = {});

// The ORB-SLAM3-style settings file text for the sequence's rig.
std::string settingsYaml(const SequenceRenderer& sequence);

// TUM's timestamp text for a time in nanoseconds: seconds with 6 decimals.
std::string tumTimestamp(std::int64_t timestamp_ns);

}  // namespace lumaslam::synth
