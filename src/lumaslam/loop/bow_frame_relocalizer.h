#pragma once
// The tracker's FrameRelocalizer backed by loop::Relocalizer (BoW candidates from the
// keyframe database, SearchByBoW, EPnP + RANSAC, pose-only refinement): how the Pipeline
// plugs place recognition into tracking without track/ depending on loop/.
#include <memory>

#include "lumaslam/loop/place_recognition.h"
#include "lumaslam/loop/relocalizer.h"
#include "lumaslam/track/frame_camera.h"
#include "lumaslam/track/frame_relocalizer.h"

namespace lumaslam::loop {

class BowFrameRelocalizer : public track::FrameRelocalizer {
 public:
  BowFrameRelocalizer(std::shared_ptr<const PlaceRecognition> places,
                      std::shared_ptr<const map::Map> map, const track::FrameCamera& camera,
                      std::shared_ptr<const feature::ScaleLevels> pyramid);

  std::optional<track::Relocalization> relocalize(const track::Frame& frame) const override;

 private:
  std::shared_ptr<const PlaceRecognition> places_;
  std::shared_ptr<const map::Map> map_;
  std::shared_ptr<const feature::ScaleLevels> pyramid_;
  CameraIntrinsics intrinsics_;
  cv::Rect2f bounds_;
  Relocalizer relocalizer_;
};

}  // namespace lumaslam::loop
