#pragma once
// What the tracker needs of local mapping, so that track/ does not depend on mapping/.
#include <cstddef>
#include <memory>

#include "lumaslam/map/keyframe.h"

namespace lumaslam::track {

class KeyFrameSink {
 public:
  virtual ~KeyFrameSink() = default;
  virtual void insertKeyFrame(std::shared_ptr<map::KeyFrame> keyframe) = 0;
  // True when the mapper is idle and would take a keyframe at once.
  virtual bool acceptsKeyFrames() const = 0;
  virtual std::size_t queuedKeyFrames() const = 0;
  // Asks a running local bundle adjustment to stop early (a keyframe is waiting).
  virtual void interruptBundleAdjustment() = 0;
};

}  // namespace lumaslam::track
