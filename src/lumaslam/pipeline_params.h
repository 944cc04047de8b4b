#pragma once
// The parameters of the tracking, local-mapping and loop-closing stages of a Pipeline: the
// defaults for the sensor and mode, then the settings file's Tracking.*, LocalMapping.* and
// Loop.* keys over them (docs/settings.md). `lumaslam run --print-settings` prints them.
#include <string>

#include "lumaslam/enhance/enhancer_params.h"
#include "lumaslam/io/settings.h"
#include "lumaslam/loop/loop_closer.h"
#include "lumaslam/mapping/local_mapper.h"
#include "lumaslam/pipeline.h"
#include "lumaslam/track/tracker.h"

namespace lumaslam {

struct StageParams {
  track::TrackerParams tracker;
  mapping::LocalMapperParams mapper;
  loop::LoopCloserParams loop;
};

StageParams stageParamsFor(const io::Settings& settings, bool sequential, bool motion_evidence);

// The keys of stageParamsFor as settings-file lines, one section after another.
std::string printStageParams(const StageParams& params);

// Enhancement.* of the file (preset "best" without one), or the preset of options.enhance_preset
// (`--enhance`) in its place; preset "off" means no enhancement.
enhance::EnhancerParams enhancerParamsFor(const io::Settings& settings,
                                          const PipelineOptions& options);

// What a Pipeline built from `settings` and `options` runs with, as settings-file lines that
// read back to the same values: Camera.*/Camera1.*, for stereo and RGB-D Camera2.*, Stereo.*
// and RGBD.*, ORBextractor.*, System.*, Enhancement.*, Detector.* and the stage sections
// (Tracking.*, Initializer.*, Dynamic.*, LocalMapping.*, Loop.*) (`lumaslam run
// --print-settings`); for a stereo or RGB-D file they are a complete settings file.
std::string effectiveSettings(const io::Settings& settings, const PipelineOptions& options);

}  // namespace lumaslam
