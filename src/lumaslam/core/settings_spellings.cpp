#include "lumaslam/core/settings_spellings.h"

#include <algorithm>
#include <array>

namespace lumaslam::core {
namespace {

constexpr std::array<KeySpelling, 18> kSpellings{{
    {"Enhancement.clahe.tiles_x", "Enhancement.clahe.tilesX"},
    {"Enhancement.clahe.tiles_y", "Enhancement.clahe.tilesY"},
    {"Enhancement.clahe.limit_mode", "Enhancement.clahe.limitMode"},
    {"Enhancement.clahe.fixed_limit", "Enhancement.clahe.fixedLimit"},
    {"Enhancement.clahe.sigma_max", "Enhancement.clahe.sigmaMax"},
    {"Enhancement.clahe.d_max", "Enhancement.clahe.dMax"},
    {"Detector.input_size", "Detector.inputSize"},
    {"Detector.box_file", "Detector.boxFile"},
    {"Detector.box_file_tolerance", "Detector.boxFileTolerance"},
    {"Detector.queue_capacity", "Detector.queueCapacity"},
    {"Detector.propagation_features", "Detector.propagationFeatures"},
    {"Detector.propagation_inner_fraction", "Detector.propagationInnerFraction"},
    {"Detector.mask_margin", "Detector.maskMargin"},
    {"Detector.depth_tolerance", "Detector.depthTolerance"},
    {"Detector.depth_edge", "Detector.depthEdge"},
    {"Detector.depth_percentile", "Detector.depthPercentile"},
    {"Detector.memory_frames", "Detector.memoryFrames"},
    {"Detector.memory_strikes", "Detector.memoryStrikes"},
}};

}  // namespace

std::span<const KeySpelling> keySpellings() {
  return kSpellings;
}

std::optional<std::string_view> oldSpellingOf(std::string_view new_key) {
  const auto it = std::find_if(kSpellings.begin(), kSpellings.end(),
                               [&](const KeySpelling& s) { return s.new_key == new_key; });
  if (it == kSpellings.end()) return std::nullopt;
  return it->old_key;
}

std::optional<std::string_view> newSpellingOf(std::string_view old_key) {
  const auto it = std::find_if(kSpellings.begin(), kSpellings.end(),
                               [&](const KeySpelling& s) { return s.old_key == old_key; });
  if (it == kSpellings.end()) return std::nullopt;
  return it->new_key;
}

}  // namespace lumaslam::core
