#include "lumaslam/system.h"

#include <chrono>

#include <opencv2/imgproc.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/detect/detection_worker.h"
#include "lumaslam/detect/detector_factory.h"
#include "lumaslam/detect/detector_spec.h"
#include "lumaslam/detect/dynamic_mask.h"
#include "lumaslam/enhance/enhancer.h"
#include "lumaslam/mapping/local_mapper.h"
#include "lumaslam/track/feature_subset.h"
#include "lumaslam/track/frame_builder.h"

namespace lumaslam {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

track::FrameCamera frameCameraFrom(const io::Settings& settings) {
  const auto camera = settings.camera.atWorkingSize();
  track::FrameCamera result;
  result.fx = camera.fx;
  result.fy = camera.fy;
  result.cx = camera.cx;
  result.cy = camera.cy;
  result.distortion = camera.distortion;
  result.size = cv::Size(camera.size.width, camera.size.height);
  result.bf = settings.bf();
  result.close_depth = settings.closeDepth();
  return result;
}

feature::OrbSettings orbSettingsFrom(const io::Settings& settings) {
  feature::OrbSettings orb;
  orb.nFeatures = settings.orb.nFeatures;
  orb.scaleFactor = settings.orb.scaleFactor;
  orb.nLevels = settings.orb.nLevels;
  orb.iniThFAST = settings.orb.iniThFAST;
  orb.minThFAST = settings.orb.minThFAST;
  return orb;
}

}  // namespace

System::System(const io::Settings& settings, const SystemOptions& options)
    : settings_(settings),
      sequential_(options.sequential.value_or(settings.system.sequential)),
      map_(std::make_shared<map::Map>()) {
  if (settings_.sensor != io::SensorType::Rgbd) {
    fail("{}: sensor '{}' is not supported yet (RGB-D is; stereo and monocular are in progress)",
         settings_.path.string(), io::toString(settings_.sensor));
  }
  auto enhancer_params = settings_.file ? enhance::EnhancerParams::fromSettings(*settings_.file)
                                        : enhance::EnhancerParams{};
  if (options.enhance_preset) {
    enhancer_params = enhance::EnhancerParams::forPreset(*options.enhance_preset);
  }
  if (enhancer_params.preset != "off") {
    enhancer_ = std::make_unique<enhance::Enhancer>(enhancer_params);
  }
  if (auto params = detect::detectorParamsFor(settings_.file.get(), options.detector)) {
    // makeDetector fails here, at startup, for a missing or invalid model / box file.
    detector_ = std::make_unique<detect::DetectionWorker>(detect::makeDetector(*params),
                                                          detect::WorkerParams::from(*params));
    detector_description_ = detect::describeChoice(params);
    detector_params_ = std::make_unique<detect::DetectorParams>(std::move(*params));
  }

  const auto camera = frameCameraFrom(settings_);
  frame_builder_ = std::make_unique<track::FrameBuilder>(camera, orbSettingsFrom(settings_));
  mapping::LocalMapperParams mapper_params;
  mapper_params.threaded = !sequential_;
  mapper_ = std::make_unique<mapping::LocalMapper>(map_, camera, frame_builder_->pyramid(),
                                                   mapper_params);
  track::TrackerParams tracker_params;
  tracker_params.max_frames_between_keyframes = std::max(1, static_cast<int>(settings_.camera.fps));
  if (detector_params_) {
    tracker_params.dynamic_memory.frames = detector_params_->memory_frames;
    tracker_params.dynamic_memory.strikes = detector_params_->memory_strikes;
  }
  tracker_ = std::make_unique<track::Tracker>(map_, *mapper_, camera, frame_builder_->pyramid(),
                                              frame_builder_->extractor().levels(), tracker_params);
}

System::~System() {
  shutdown();
}

void System::shutdown() {
  if (detector_) detector_->stop();
  if (mapper_) mapper_->shutdown();
}

System::Images System::prepareImages(const cv::Mat& image, FrameTiming& timing) {
  if (image.empty()) fail("empty image");
  if (image.depth() != CV_8U) fail("expected an 8-bit image, got depth {}", image.depth());
  const bool enhanced_for_detector = detector_params_ && detector_params_->image == "enhanced";
  if (enhancer_) {
    const auto start = Clock::now();
    auto enhanced = enhancer_->enhance(image);
    timing.enhance = msSince(start);
    return {enhanced.gray, enhanced_for_detector ? enhanced.colour : image};
  }
  if (image.channels() == 1) return {image, image};
  cv::Mat gray;
  cv::cvtColor(image, gray, image.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  return {gray, image};
}

FrameResult System::trackRgbd(std::size_t index, double timestamp, const cv::Mat& image,
                              const cv::Mat& depth, const cv::Mat& dynamic_mask) {
  SensorFrame frame;
  frame.index = index;
  frame.timestamp = timestamp;
  frame.image = image;
  frame.depth = depth;
  frame.dynamic_mask = dynamic_mask;
  return track(frame);
}

cv::Mat System::depthInMetres(const SensorFrame& frame) const {
  if (frame.depth.empty()) fail("frame {}: RGB-D tracking needs a depth image", frame.index);
  cv::Mat depth_m;
  if (frame.depth.type() == CV_16UC1) {
    frame.depth.convertTo(depth_m, CV_32F, 1.0 / settings_.depth.depthMapFactor);
  } else if (frame.depth.type() == CV_32FC1) {
    depth_m = frame.depth;
  } else {
    fail("frame {}: depth must be 16-bit raw or 32-bit float metres", frame.index);
  }
  return depth_m;
}

// ORB extraction; with a detector, the detection of this frame runs meanwhile on its thread
// (paper section 3.2) and the features on moving objects are dropped afterwards.
track::Frame System::buildFrame(const SensorFrame& input, const cv::Mat& gray,
                                const cv::Mat& depth_m, FrameResult& result) {
  auto stage = Clock::now();
  try {
    auto frame =
        frame_builder_->build(input.index, input.timestamp, gray, depth_m, input.dynamic_mask);
    result.timing.features = msSince(stage);
    if (detector_) removeDynamicFeatures(frame, depth_m, result);
    return frame;
  } catch (...) {
    if (detector_) {
      try {
        detector_->take(static_cast<std::int64_t>(input.index));  // not left pending
      } catch (const Error&) {
      }
    }
    throw;
  }
}

void System::removeDynamicFeatures(track::Frame& frame, const cv::Mat& depth_m,
                                   FrameResult& result) {
  const auto wait = Clock::now();
  const auto detections = detector_->take(static_cast<std::int64_t>(frame.index));
  result.timing.detection_wait = msSince(wait);
  result.timing.detection = detections.compute_ms;
  result.dynamic_boxes = detect::boxesOf(detections.detections);
  frame.dynamic_boxes = result.dynamic_boxes;
  if (result.dynamic_boxes.empty()) return;

  const auto& mask_params = detector_params_->mask;
  cv::Mat mask = detect::makeDynamicMask(frame_builder_->camera().size, result.dynamic_boxes,
                                         mask_params.margin_px);
  // RGB-D: the background seen behind a person keeps its features.
  if (!depth_m.empty())
    mask = detect::refineMaskWithDepth(mask, depth_m, result.dynamic_boxes, mask_params);
  const auto& keypoints = frame.features->keypoints;
  const auto kept = detect::filterKeypoints(keypoints, mask);
  if (kept.size() == keypoints.size()) return;
  std::size_t next_kept = 0;
  for (std::size_t i = 0; i < keypoints.size(); ++i) {
    if (next_kept < kept.size() && kept[next_kept] == static_cast<int>(i)) {
      ++next_kept;
    } else {
      result.dropped_features.push_back(keypoints[i].pt);
    }
  }
  track::keepFeatures(frame, kept);
}

FrameResult System::track(const SensorFrame& input) {
  const auto start = Clock::now();
  FrameResult result;
  const auto images = prepareImages(input.image, result.timing);
  const cv::Mat depth_m = depthInMetres(input);
  if (detector_) {
    detector_->push(static_cast<std::int64_t>(input.index), input.timestamp, images.detector);
  }
  auto frame = buildFrame(input, images.gray, depth_m, result);
  auto stage = Clock::now();
  result.outcome = tracker_->track(std::move(frame));
  result.timing.tracking = msSince(stage);
  if (sequential_) {
    stage = Clock::now();
    mapper_->processPending();
    result.timing.mapping = msSince(stage);
  }
  result.timing.total = msSince(start);
  return result;
}

Trajectory System::frameTrajectory() const {
  return tracker_->trajectory().frames();
}

Trajectory System::keyFrameTrajectory() const {
  return track::keyFrameTrajectory(map_->keyFrames());
}

std::size_t System::keyFrameCount() const {
  return map_->keyFrameCount();
}

std::size_t System::mapPointCount() const {
  return map_->mapPointCount();
}

}  // namespace lumaslam
