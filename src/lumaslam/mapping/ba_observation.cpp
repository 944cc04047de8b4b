#include "lumaslam/mapping/ba_observation.h"

#include <algorithm>

namespace lumaslam::mapping {

optimize::BAObservation baObservation(const map::KeyFrame& keyframe, std::size_t index,
                                      std::uint64_t point_id) {
  const auto& f = keyframe.features();
  optimize::BAObservation obs;
  obs.keyFrameId = keyframe.id();
  obs.pointId = point_id;
  obs.uv = {f.undistorted[index].x, f.undistorted[index].y};
  obs.uRight = f.hasStereo(index) ? f.u_right[index] : -1.0;
  obs.invSigma2 = keyframe.pyramid().inverseSigma2(std::max(0, f.keypoints[index].octave));
  return obs;
}

}  // namespace lumaslam::mapping
