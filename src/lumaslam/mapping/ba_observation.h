#pragma once
#include <cstddef>
#include <cstdint>

#include "lumaslam/map/keyframe.h"
#include "lumaslam/optimize/local_ba.h"

namespace lumaslam::mapping {

// Keypoint `index` of `keyframe` as a bundle-adjustment observation of point `point_id`:
// undistorted pixel, right u (negative when monocular) and the inverse variance of its octave.
optimize::BAObservation baObservation(const map::KeyFrame& keyframe, std::size_t index,
                                      std::uint64_t point_id);

}  // namespace lumaslam::mapping
