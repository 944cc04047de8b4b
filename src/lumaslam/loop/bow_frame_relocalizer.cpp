#include "lumaslam/loop/bow_frame_relocalizer.h"

namespace lumaslam::loop {
namespace {

RelocalizerParams relocalizerParams() {
  RelocalizerParams params;
  params.direct_index_levels_up = PlaceRecognition::kDirectIndexLevelsUp;
  return params;
}

}  // namespace

BowFrameRelocalizer::BowFrameRelocalizer(std::shared_ptr<const PlaceRecognition> places,
                                         std::shared_ptr<const map::Map> map,
                                         const track::FrameCamera& camera,
                                         std::shared_ptr<const feature::ScaleLevels> pyramid)
    : places_(std::move(places)),
      map_(std::move(map)),
      pyramid_(std::move(pyramid)),
      intrinsics_(camera.intrinsics()),
      bounds_(camera.pinhole.undistortedBounds()),
      relocalizer_(places_->vocabulary(), places_->database(), *map_, relocalizerParams()) {}

std::optional<track::Relocalization> BowFrameRelocalizer::relocalize(
    const track::Frame& frame) const {
  if (!frame.features || !frame.features->grid) return std::nullopt;
  const auto result =
      relocalizer_.relocalize({frame.features.get(), intrinsics_, pyramid_.get(), bounds_});
  if (!result.success) return std::nullopt;
  return track::Relocalization{result.T_c_w, result.points, result.inliers};
}

}  // namespace lumaslam::loop
