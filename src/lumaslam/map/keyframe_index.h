#pragma once
// Something that keeps a per-keyframe index in step with the Map's keyframes (the
// place-recognition database: loop::PlaceRecognition). The Map calls it after a keyframe
// joins, after one is retired and on clear(), so that every creator of keyframes (RGB-D /
// stereo tracking, monocular initialisation) and every culler (local mapping) keeps it in
// step without knowing it exists.
#include <memory>

#include "lumaslam/map/ids.h"

namespace lumaslam::map {

class KeyFrame;

class KeyFrameIndex {
 public:
  virtual ~KeyFrameIndex() = default;
  // Called with no Map lock held; may read the keyframe's features (immutable).
  virtual void add(const std::shared_ptr<const KeyFrame>& keyframe) = 0;
  virtual void erase(Id keyframe) = 0;
  virtual void clear() = 0;
};

}  // namespace lumaslam::map
