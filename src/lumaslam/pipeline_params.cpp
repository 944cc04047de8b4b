#include "lumaslam/pipeline_params.h"

#include <algorithm>
#include <filesystem>

#include <fmt/format.h>

#include "lumaslam/camera/stereo_rectifier.h"
#include "lumaslam/core/settings_section.h"
#include "lumaslam/detect/detector_spec.h"
#include "lumaslam/enhance/enhancer_params.h"
#include "lumaslam/feature/orb_settings.h"
#include "lumaslam/io/camera_settings_text.h"
#include "lumaslam/loop/loop_closer_settings.h"
#include "lumaslam/loop/place_recognition.h"
#include "lumaslam/loop/vocabulary_choice.h"
#include "lumaslam/mapping/local_mapper_settings.h"
#include "lumaslam/track/tracker_settings.h"

namespace lumaslam {
namespace {

track::TrackerParams trackerDefaults(const io::Settings& settings, bool sequential,
                                     bool motion_evidence) {
  track::TrackerParams p;
  p.max_frames_between_keyframes = std::max(1, static_cast<int>(settings.camera.fps));
  p.inlier_reference_half_life = p.max_frames_between_keyframes;
  p.new_map_after_s = settings.system.newMapAfter;
  p.monocular.two_view.threaded = !sequential;
  // Only monocular keyframes depend on the mapper for all their new points; RGB-D and stereo
  // ones bring their own from depth (docs/tracking.md "Keyframes while the mapper is busy").
  p.wait_for_busy_mapper = settings.sensor == io::SensorType::Monocular;
  p.motion_evidence.enabled = motion_evidence;
  if (settings.sensor == io::SensorType::Stereo) {
    // ORB-SLAM starts a stereo map from a frame with > 500 keypoints, of which typically half
    // have a stereo match; 500 matches would delay EuRoC V1_01 by 6 frames with enhancement
    // (~480 matches of 1200 features per frame, against ~580 without).
    p.min_initial_features = 250;
  }
  return p;
}

mapping::LocalMapperParams mapperDefaults(const io::Settings& settings, bool sequential) {
  mapping::LocalMapperParams p;
  p.threaded = !sequential;
  if (settings.sensor == io::SensorType::Monocular) p.triangulation_neighbours = 20;
  return p;
}

loop::LoopCloserParams loopDefaults(const io::Settings& settings, bool sequential) {
  loop::LoopCloserParams p;
  p.threaded = !sequential;
  // Monocular: Sim3 loops, which also correct the scale drift.
  p.fix_scale = settings.sensor != io::SensorType::Monocular;
  p.direct_index_levels_up = loop::PlaceRecognition::kDirectIndexLevelsUp;
  return p;
}

}  // namespace

StageParams stageParamsFor(const io::Settings& settings, bool sequential, bool motion_evidence) {
  StageParams params{trackerDefaults(settings, sequential, motion_evidence),
                     mapperDefaults(settings, sequential), loopDefaults(settings, sequential)};
  if (settings.file) {
    track::readTrackingSettings(*settings.file, params.tracker);
    track::readInitializerSettings(*settings.file, params.tracker.monocular);
    track::readDynamicSettings(*settings.file, params.tracker.motion_evidence);
    mapping::readLocalMappingSettings(*settings.file, params.mapper);
    loop::readLoopClosingSettings(*settings.file, params.loop);
  }
  return params;
}

std::string printStageParams(const StageParams& params) {
  return track::printTrackingSettings(params.tracker) +
         track::printInitializerSettings(params.tracker.monocular) +
         track::printDynamicSettings(params.tracker.motion_evidence) +
         mapping::printLocalMappingSettings(params.mapper) +
         loop::printLoopClosingSettings(params.loop);
}

enhance::EnhancerParams enhancerParamsFor(const io::Settings& settings,
                                          const PipelineOptions& options) {
  if (options.enhance_preset) return enhance::EnhancerParams::forPreset(*options.enhance_preset);
  return settings.file ? enhance::EnhancerParams::fromSettings(*settings.file)
                       : enhance::EnhancerParams{};
}

namespace {

// The vocabulary a run loads (named by the file or the command line, LUMASLAM_VOCABULARY, or
// the default vocabulary found) as an absolute path that reads back anywhere, and whether it
// closes loops.
std::string printLoopSources(const io::Settings& settings, const PipelineOptions& options) {
  const auto choice = loop::chooseVocabulary(options.vocabulary.value_or(settings.loop.vocabulary));
  core::SectionPrinter keys("Loop");
  keys("vocabulary", choice.file.empty() ? std::string(loop::kNoVocabulary)
                                         : std::filesystem::absolute(choice.file).string());
  keys("closing", options.loop_closing.value_or(settings.loop.closing));
  return keys.text();
}

// An unrectified pair is tracked in the rectified images: their common camera is not a key
// (the Pipeline computes it), so it is shown as a comment.
std::string printRectifiedCamera(const io::Settings& settings) {
  if (settings.sensor != io::SensorType::Stereo || !settings.stereo || !settings.stereo->right) {
    return {};
  }
  const auto rectifier =
      camera::StereoRectifier::fromSettings(settings.camera, *settings.stereo, settings.origin());
  const auto& camera = rectifier.rectifiedCamera();
  return fmt::format(
      "# rectified pair, as tracked: fx {} fy {} cx {} cy {}, no distortion, baseline {} m, "
      "bf {}\n",
      camera.fx(), camera.fy(), camera.cx(), camera.cy(), rectifier.baseline(), rectifier.bf());
}

}  // namespace

std::string effectiveSettings(const io::Settings& settings, const PipelineOptions& options) {
  const bool sequential = options.sequential.value_or(settings.system.sequential);
  const bool motion_evidence =
      options.motion_evidence.value_or(settings.dynamic.motionEvidenceFor(settings.sensor));
  const auto orb =
      settings.file ? feature::OrbSettings::fromSettings(*settings.file) : feature::OrbSettings{};
  io::SystemSettings system = settings.system;
  system.sequential = sequential;
  const auto detector = detect::detectorParamsFor(settings.file.get(), options.detector);
  return io::printCameraSettings(settings.camera) + io::printStereoSettings(settings) +
         printRectifiedCamera(settings) + orb.settingsLines() +
         io::printSystemSettings(settings.sensor, system) +
         enhancerParamsFor(settings, options).toSettingsText() +
         (detector ? detector->settingsLines() : "Detector.type: \"none\"\n") +
         printStageParams(stageParamsFor(settings, sequential, motion_evidence)) +
         printLoopSources(settings, options);
}

}  // namespace lumaslam
