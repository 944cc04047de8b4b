#pragma once
// A frame's numbers as the viewer's page shows them (the "frame" part of /status.json).
#include <nlohmann/json.hpp>

#include "lumaslam/viewer/frame_view.h"

namespace lumaslam::viewer {

nlohmann::json frameInfoJson(const FrameView& view);

}  // namespace lumaslam::viewer
