#include "lumaslam/viewer/frame_info.h"

namespace lumaslam::viewer {

nlohmann::json frameInfoJson(const FrameView& view) {
  nlohmann::json boxes = nlohmann::json::array();
  for (const auto& box : view.boxes) boxes.push_back({box.x, box.y, box.width, box.height});
  const auto& t = view.timing;
  return {{"frame", view.index},
          {"timestamp", view.timestamp},
          {"state", view.state},
          {"step", view.step},
          {"inliers", view.inliers},
          {"keyframe", view.keyframe},
          {"relocalized", view.relocalized},
          {"map", view.map},
          {"kept", view.kept.size()},
          {"dropped", view.dropped.size()},
          {"moving", view.moving_features},
          {"boxes", boxes},
          {"right", !view.right.empty()},
          {"timing",
           {{"enhance", t.enhance},
            {"features", t.features},
            {"tracking", t.tracking},
            {"mapping", t.mapping},
            {"detection_wait", t.detection_wait},
            {"total", t.total}}}};
}

}  // namespace lumaslam::viewer
