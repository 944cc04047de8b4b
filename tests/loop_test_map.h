#pragma once
// Keyframes for the loop tests built straight from the synthetic `loop-rgbd` room: features
// from the renderer's images, poses given by the test (ground truth or drifted), one map point
// per feature with a plausible depth.
#include <memory>

#include <opencv2/imgproc.hpp>

#include "lumaslam/map/keyframe.h"
#include "lumaslam/map/map.h"
#include "lumaslam/map/map_point.h"
#include "lumaslam/synth/preset.h"
#include "lumaslam/synth/sequence.h"
#include "lumaslam/track/frame_builder.h"

namespace lumaslam::test {

inline track::FrameCamera rgbdCameraOf(const synth::Rig& rig) {
  const auto& k = rig.camera;
  return {camera::PinholeCamera(k.fx, k.fy, k.cx, k.cy, {k.width, k.height}),
          0.08 * k.fx,  // TUM's virtual 8 cm baseline
          40 * 0.08};
}

inline track::Frame buildRgbdFrame(const track::FrameBuilder& builder,
                                   const synth::SequenceRenderer& from, int index) {
  const synth::Frame frame = from.render(index);
  cv::Mat gray;
  cv::cvtColor(frame.cam0.image, gray, cv::COLOR_BGR2GRAY);
  return builder.build(static_cast<std::size_t>(index), frame.timestamp(), gray, frame.cam0.depth);
}

// Adds a keyframe at `T_w_c` (to map `map_id` of the atlas) with a new map point for every
// feature measured 0.1-8 m away.
inline std::shared_ptr<map::KeyFrame> addKeyFrameWithPoints(map::Map& map,
                                                            const track::FrameBuilder& builder,
                                                            const track::Frame& frame,
                                                            const SE3& T_w_c,
                                                            map::MapId map_id = 0) {
  auto keyframe = std::make_shared<map::KeyFrame>(map.nextKeyFrameId(), frame.index,
                                                  frame.timestamp, T_w_c.inverse(), frame.features,
                                                  builder.pyramid(), builder.camera().intrinsics());
  keyframe->setMapId(map_id);
  map.addKeyFrame(keyframe);
  for (std::size_t i = 0; i < frame.size(); ++i) {
    const float z = frame.features->depth[i];
    if (!(z > 0.1F && z < 8.0F)) continue;
    const Eigen::Vector3d X_w = T_w_c * frame.unprojectCamera(i, builder.camera().intrinsics());
    auto point = std::make_shared<map::MapPoint>(map.nextMapPointId(), X_w, keyframe);
    keyframe->setMapPoint(i, point);
    point->addObservation(keyframe, static_cast<int>(i));
    point->updateNormalAndDepth();
    point->computeDistinctiveDescriptor();
    map.addMapPoint(point);
  }
  return keyframe;
}

}  // namespace lumaslam::test
