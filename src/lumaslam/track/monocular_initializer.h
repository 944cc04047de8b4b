#pragma once
// The monocular start-up of tracking (ORB-SLAM's MonocularInitialization): the first frame
// with enough features becomes the reference; each following frame is matched to it with a
// window search around where each reference feature was last matched
// (SearchForInitialization) and handed to the TwoViewInitializer. Too few matches replace the
// reference with the current frame. The tracker turns a success into the initial map.
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "lumaslam/track/frame.h"
#include "lumaslam/track/frame_camera.h"
#include "lumaslam/track/two_view_initializer.h"

namespace lumaslam::track {

struct MonocularInitParams {
  int min_features = 100;          // a reference (and a current) frame needs more features
  int min_matches = 100;           // fewer matches with the reference: start again from the current
  float search_window = 100;       // pixels around the last matched position
  float ratio = 0.9F;              // Lowe ratio of the window search
  double max_reference_age = 1.0;  // seconds; an older reference is replaced (ORB-SLAM3)
  TwoViewParams two_view{};
};

struct InitialPoint {
  std::size_t reference_index = 0;                  // feature in the reference frame
  std::size_t current_index = 0;                    // feature in the current frame
  Eigen::Vector3d X_ref = Eigen::Vector3d::Zero();  // in the reference camera
};

struct InitialPair {
  SE3 T_cur_ref = SE3::Identity();  // translation of arbitrary scale
  std::vector<InitialPoint> points;
  TwoViewModel model = TwoViewModel::None;
};

class MonocularInitializer {
 public:
  MonocularInitializer(const FrameCamera& camera, const MonocularInitParams& params = {});

  // Tries to initialise from the held reference and `current`; nullopt while that is not yet
  // possible (the reference may be replaced by `current`).
  std::optional<InitialPair> tryInitialize(const Frame& current);
  bool hasReference() const { return reference_.features != nullptr; }
  const Frame& reference() const { return reference_; }
  void reset() { reference_ = Frame{}; }

 private:
  void setReference(const Frame& frame);

  MonocularInitParams params_;
  TwoViewInitializer two_view_;
  Frame reference_;
  std::vector<cv::Point2f> last_matched_;  // per reference feature
};

}  // namespace lumaslam::track
