#include "lumaslam/pipeline.h"

#include <algorithm>
#include <chrono>
#include <functional>

#include <spdlog/spdlog.h>
#include <opencv2/imgproc.hpp>

#include "lumaslam/camera/stereo_rectifier.h"
#include "lumaslam/core/error.h"
#include "lumaslam/core/gray_image.h"
#include "lumaslam/core/side_job.h"
#include "lumaslam/detect/detection_worker.h"
#include "lumaslam/detect/detector_factory.h"
#include "lumaslam/detect/detector_spec.h"
#include "lumaslam/detect/dynamic_mask.h"
#include "lumaslam/enhance/enhancer.h"
#include "lumaslam/io/dataset_reader.h"
#include "lumaslam/loop/bow_frame_relocalizer.h"
#include "lumaslam/loop/loop_closer.h"
#include "lumaslam/loop/place_recognition.h"
#include "lumaslam/loop/vocabulary_choice.h"
#include "lumaslam/loop/vocabulary_io.h"
#include "lumaslam/mapping/local_mapper.h"
#include "lumaslam/pipeline_params.h"
#include "lumaslam/track/feature_subset.h"
#include "lumaslam/track/frame_builder.h"

namespace lumaslam {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

track::FrameCamera frameCameraFrom(const io::Settings& settings,
                                   const camera::StereoRectifier* rectifier) {
  if (rectifier) {  // unrectified pair: track in the common camera of the rectified images
    return {rectifier->rectifiedCamera(), rectifier->bf(),
            settings.depth.thDepth * rectifier->baseline()};
  }
  return {camera::PinholeCamera::fromSettings(settings.camera), settings.bf(),
          settings.closeDepth()};
}

// Camera.newWidth/newHeight (ORB-SLAM3's resize): images of the calibrated size are resized
// to the working size the intrinsics were scaled to (camera::CameraSettings::atWorkingSize).
// Depth and masks take the nearest pixel: blending would invent depths across object edges.
// An image of any other size is passed on as it is, for the size checks to name.
SensorFrame atWorkingSize(const SensorFrame& input, const camera::CameraSettings& camera) {
  if (!camera.resizeTo) return input;
  const cv::Size calibrated(camera.size.width, camera.size.height);
  const cv::Size working(camera.resizeTo->width, camera.resizeTo->height);
  SensorFrame resized = input;
  const auto resize = [&](cv::Mat& image, int interpolation) {
    if (image.size() != calibrated) return;
    cv::Mat out;
    cv::resize(image, out, working, 0.0, 0.0, interpolation);
    image = out;
  };
  resize(resized.image, cv::INTER_LINEAR);
  resize(resized.right, cv::INTER_LINEAR);
  resize(resized.depth, cv::INTER_NEAREST);
  resize(resized.dynamic_mask, cv::INTER_NEAREST);
  return resized;
}

// The ORBextractor.* section, read by the one parser of it (feature/orb_settings.h).
feature::OrbSettings orbSettingsOf(const io::Settings& settings) {
  return settings.file ? feature::OrbSettings::fromSettings(*settings.file)
                       : feature::OrbSettings{};
}

// Run once every part of the Pipeline has read its keys.
void checkUnknownKeys(const core::SettingsFile& file, bool strict) {
  for (const auto& [key, suggestion] : core::unknownKeys(file)) {
    const std::string hint =
        suggestion.empty() ? "" : fmt::format("; did you mean '{}'?", suggestion);
    if (strict) fail("{}: unknown key '{}'{} (--strict-settings)", file.origin(), key, hint);
    spdlog::warn("{}: unknown key '{}' is ignored{}", file.origin(), key, hint);
  }
}

}  // namespace

Pipeline::Pipeline(const io::Settings& settings, const PipelineOptions& options)
    : settings_(settings),
      orb_settings_(orbSettingsOf(settings_)),
      sequential_(options.sequential.value_or(settings.system.sequential)),
      map_(std::make_shared<map::Map>()) {
  setUpStereoRectification();
  setUpEnhancement(options);
  setUpDetector(options);
  setUpPlaceRecognition(options);
  const auto camera = frameCameraFrom(settings_, rectifier_.get());
  frame_builder_ = std::make_unique<track::FrameBuilder>(camera, orb_settings_, !sequential_);
  spdlog::debug("ORB extractor: {}", orb_settings_.summary());
  setUpStages(camera, options);
  if (settings_.file) checkUnknownKeys(*settings_.file, options.strict_settings);
}

void Pipeline::setUpStereoRectification() {
  const bool stereo = settings_.sensor == io::SensorType::Stereo;
  if (stereo && settings_.stereo && !settings_.stereo->right && settings_.camera.hasDistortion()) {
    fail(
        "{}: a stereo pair without Camera2.* is taken as rectified, but camera 1 has distortion; "
        "give Camera2.* and Stereo.T_c1_c2 so that the Pipeline rectifies it, or rectified images "
        "with zero distortion",
        settings_.path.string());
  }
  if (!stereo || !settings_.stereo || !settings_.stereo->right) return;
  rectifier_ = std::make_unique<camera::StereoRectifier>(camera::StereoRectifier::fromSettings(
      settings_.camera, *settings_.stereo, settings_.origin()));
  const auto& k = rectifier_->rectifiedCamera();
  spdlog::info(
      "{}: stereo pair rectified: fx={:.3f} fy={:.3f} cx={:.3f} cy={:.3f}, baseline {:.4f} m, "
      "bf {:.3f}",
      settings_.file ? settings_.file->origin() : settings_.path.string(), k.fx(), k.fy(), k.cx(),
      k.cy(), rectifier_->baseline(), rectifier_->bf());
}

void Pipeline::setUpEnhancement(const PipelineOptions& options) {
  const auto enhancer_params = enhancerParamsFor(settings_, options);
  if (enhancer_params.preset == "off") return;
  enhancer_ = std::make_unique<enhance::Enhancer>(enhancer_params);
  // Enhancement.stereo "independent": the right image gets its own enhancer (and online
  // statistics); otherwise it is enhanced with the left image's plan (rightGray).
  if (settings_.sensor == io::SensorType::Stereo &&
      enhancer_params.stereo == enhance::StereoMapping::kIndependent) {
    right_enhancer_ = std::make_unique<enhance::Enhancer>(enhancer_params);
  }
}

void Pipeline::setUpDetector(const PipelineOptions& options) {
  auto params = detect::detectorParamsFor(settings_.file.get(), options.detector);
  if (!params) return;
  // makeDetector fails here, at startup, for a missing or invalid model / box file.
  auto worker_params = detect::WorkerParams::from(*params);
  worker_params.threaded = !sequential_;
  detector_ =
      std::make_unique<detect::DetectionWorker>(detect::makeDetector(*params), worker_params);
  detector_description_ = detect::describeChoice(params);
  detector_params_ = std::make_unique<detect::DetectorParams>(std::move(*params));
}

void Pipeline::setUpPlaceRecognition(const PipelineOptions& options) {
  const loop::VocabularyChoice vocabulary =
      loop::chooseVocabulary(options.vocabulary.value_or(settings_.loop.vocabulary));
  if (vocabulary.file.empty()) {
    const auto log_level = vocabulary.default_missing ? spdlog::level::warn : spdlog::level::info;
    spdlog::log(log_level,
                "no vocabulary ({}): relocalization is off, no loop closing (name one with "
                "Loop.vocabulary / --vocabulary or {})",
                vocabulary.origin, loop::kVocabularyEnvironment);
    return;
  }
  const auto start = Clock::now();
  try {
    places_ = loop::PlaceRecognition::fromFile(vocabulary.file);
  } catch (const Error& e) {
    fail("{} (vocabulary from {}; 'none' runs without one)", e.what(), vocabulary.origin);
  }
  spdlog::info(
      "{}: vocabulary ({}) with {} words (k {}, L {}), loaded in {:.0f} ms: "
      "relocalization is on",
      vocabulary.file.string(), vocabulary.origin, places_->vocabulary().wordCount(),
      places_->vocabulary().branching(), places_->vocabulary().depth(), msSince(start));
  map_->setKeyFrameIndex(places_);
  vocabulary_description_ = vocabulary.file.string();
  vocabulary_fingerprint_ = loop::vocabularyFingerprint(places_->vocabulary());
}

// Loop closer, local mapper and tracker, each fed by the next (docs/architecture.md), with the
// parameters of stageParamsFor (Tracking.*, LocalMapping.*, Loop.*).
void Pipeline::setUpStages(const track::FrameCamera& camera, const PipelineOptions& options) {
  StageParams params = stageParamsFor(
      settings_, sequential_,
      options.motion_evidence.value_or(settings_.dynamic.motionEvidenceFor(settings_.sensor)));
  if (places_ && options.loop_closing.value_or(settings_.loop.closing)) {
    // The mapper exists before the first keyframe reaches the closer.
    loop_closer_ = std::make_unique<loop::LoopCloser>(
        map_, places_->vocabulary(), places_->database(), params.loop,
        [this] { return mapper_->pauseProcessing(); });
    params.mapper.on_keyframe_processed = [closer = loop_closer_.get()](const auto& keyframe) {
      closer->insertKeyFrame(keyframe);
    };
    spdlog::info("loop closing is on");
  }
  mapper_ = std::make_unique<mapping::LocalMapper>(map_, camera, frame_builder_->pyramid(),
                                                   params.mapper);
  wait_for_busy_mapper_ = params.tracker.wait_for_busy_mapper;
  if (detector_params_) {
    params.tracker.dynamic_memory.frames = detector_params_->memory_frames;
    params.tracker.dynamic_memory.strikes = detector_params_->memory_strikes;
  }
  tracker_ = std::make_unique<track::Tracker>(map_, *mapper_, camera, frame_builder_->pyramid(),
                                              params.tracker);
  if (places_) {
    tracker_->setRelocalizer(std::make_shared<loop::BowFrameRelocalizer>(
        places_, map_, camera, frame_builder_->pyramid()));
  }
}

Pipeline::~Pipeline() {
  shutdown();
}

void Pipeline::shutdown() {
  shut_down_ = true;
  if (detector_) detector_->stop();
  if (mapper_) mapper_->shutdown();
  if (loop_closer_) loop_closer_->shutdown();  // after the mapper: it feeds the closer
}

// The file then holds everything tracked so far: keyframes still queued are in the map, loops
// found among them are closed and a running global bundle adjustment is written back. The
// tracker is not running meanwhile (one caller), so no new keyframe can arrive.
void Pipeline::finishQueuedMapWork() {
  if (mapper_) mapper_->waitUntilIdle();
  if (loop_closer_) loop_closer_->waitUntilIdle();  // after the mapper: it feeds the closer
}

Pipeline::Images Pipeline::prepareImages(const cv::Mat& image, FrameTiming& timing,
                                         const enhance::EnhancementPlan* plan) {
  if (image.empty()) fail("empty image");
  if (image.depth() != CV_8U) fail("expected an 8-bit image, got depth {}", image.depth());
  const bool enhanced_for_detector = detector_params_ && detector_params_->image == "enhanced";
  if (enhancer_) {
    const auto start = Clock::now();
    auto enhanced = plan ? enhancer_->apply(image, *plan) : enhancer_->enhance(image);
    timing.enhance += msSince(start);
    return {enhanced.gray, enhanced_for_detector ? enhanced.colour : image};
  }
  return {toGray(image), image};
}

// Runs beside prepareImages() of the left image: without enhancement, that touches no state;
// with the left image's plan, only const (thread-safe) Enhancer calls.
cv::Mat Pipeline::rightGray(const cv::Mat& image, FrameTiming& timing,
                            const enhance::EnhancementPlan* left_plan) {
  if (left_plan) {
    const auto start = Clock::now();
    auto enhanced = enhancer_->enhanceRightWith(image, *left_plan);
    timing.enhance += msSince(start);
    return enhanced.gray;
  }
  if (!right_enhancer_) {
    FrameTiming unused;
    return prepareImages(image, unused).gray;
  }
  const auto start = Clock::now();
  auto enhanced = right_enhancer_->enhance(image);
  timing.enhance += msSince(start);
  return enhanced.gray;
}

SensorFrame toSensorFrame(const io::FrameData& frame) {
  SensorFrame input;
  input.index = frame.index;
  input.timestamp = frame.timestamp;
  input.image = frame.image;
  input.right = frame.right;
  input.depth = frame.depth;
  return input;
}

FrameResult Pipeline::trackRgbd(std::size_t index, double timestamp, const cv::Mat& image,
                                const cv::Mat& depth, const cv::Mat& dynamic_mask) {
  SensorFrame frame;
  frame.index = index;
  frame.timestamp = timestamp;
  frame.image = image;
  frame.depth = depth;
  frame.dynamic_mask = dynamic_mask;
  return track(frame);
}

cv::Mat Pipeline::depthInMetres(const SensorFrame& frame) const {
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

track::Frame Pipeline::buildStereoFrame(const SensorFrame& frame, FrameResult& result) {
  FrameTiming& timing = result.timing;
  if (frame.image.empty()) fail("frame {}: the left image is empty", frame.index);
  if (frame.right.empty()) fail("frame {}: stereo tracking needs a right image", frame.index);
  if (frame.right.size() != frame.image.size() || frame.right.type() != frame.image.type()) {
    fail("frame {}: right image {}x{} ({}) differs from the left {}x{} ({})", frame.index,
         frame.right.cols, frame.right.rows, cv::typeToString(frame.right.type()), frame.image.cols,
         frame.image.rows, cv::typeToString(frame.image.type()));
  }
  if (!frame.dynamic_mask.empty() && frame.dynamic_mask.size() != frame.image.size()) {
    fail("frame {}: the dynamic mask is {}x{}, the image {}x{}", frame.index,
         frame.dynamic_mask.cols, frame.dynamic_mask.rows, frame.image.cols, frame.image.rows);
  }
  const auto start = Clock::now();
  // The right image is rectified and enhanced beside the left one: with its own enhancer, or,
  // for a plan shared with the left image, once the left plan is made.
  const bool shared_plan = enhancer_ && !right_enhancer_;
  FrameTiming right_timing;
  auto right_job = core::startSideJob(!sequential_, [&] {
    const cv::Mat right = rectifier_ ? rectifier_->rectifyRight(frame.right) : frame.right;
    return shared_plan ? right : rightGray(right, right_timing);
  });
  const cv::Mat left = rectifier_ ? rectifier_->rectifyLeft(frame.image) : frame.image;
  const cv::Mat mask = rectifier_ && !frame.dynamic_mask.empty()
                           ? rectifier_->rectifyLeft(frame.dynamic_mask)
                           : frame.dynamic_mask;
  std::optional<enhance::EnhancementPlan> plan;
  std::future<cv::Mat> right_enhanced;
  if (shared_plan) {
    const auto plan_start = Clock::now();
    plan = enhancer_->plan(left);
    timing.enhance += msSince(plan_start);
    right_enhanced = core::startSideJob(!sequential_, [&, right = right_job.get()] {
      return rightGray(right, right_timing, &*plan);
    });
  }
  const auto images = prepareImages(left, timing, plan ? &*plan : nullptr);
  pushForDetection(frame, images.detector);
  const double left_enhance_ms = timing.enhance;
  const cv::Mat gray_right = shared_plan ? right_enhanced.get() : right_job.get();
  timing.enhance += right_timing.enhance;  // work of both, partly overlapped

  result.feature_image = images.gray;
  return withoutDynamicFeatures(frame, cv::Mat(), result, [&] {
    auto built = frame_builder_->buildStereo(frame.index, frame.timestamp, images.gray, gray_right,
                                             extractionMask(mask));
    timing.features = msSince(start) - left_enhance_ms;
    return built;
  });
}

// The detector's boxes of this frame come after its features (they run side by side), so the
// features are taken outside the last frame's dynamic mask: the feature budget goes to what
// is likely static instead of to people whose features are dropped anyway (two people sitting
// close to the camera took 60-70 % of it, too few were left to start a map; docs/dynamic.md).
// `given`: a mask of the caller, kept.
cv::Mat Pipeline::extractionMask(const cv::Mat& given) const {
  if (previous_dynamic_mask_.empty()) return given;
  if (given.empty()) return previous_dynamic_mask_;
  cv::Mat both;
  cv::bitwise_or(given, previous_dynamic_mask_, both);
  return both;
}

// Monocular / RGB-D: enhanced images and depth in metres, the detector's image pushed.
Pipeline::PreparedFrame Pipeline::prepareFrame(const SensorFrame& input, FrameTiming& timing) {
  // Depth first: a frame refused for its depth must not reach the (stateful) enhancer.
  cv::Mat depth_m = settings_.sensor == io::SensorType::Rgbd ? depthInMetres(input) : cv::Mat();
  PreparedFrame prepared{input.index, prepareImages(input.image, timing), std::move(depth_m), 0.0};
  pushForDetection(input, prepared.images.detector);
  return prepared;
}

void Pipeline::prepareAhead(const SensorFrame& next) {
  if (!detector_ || settings_.sensor == io::SensorType::Stereo || shut_down_) return;
  constexpr std::size_t kMaxAhead = 2;  // the frame tracked next and the one after it
  const bool in_order = ahead_.empty() || next.index > ahead_.back().index;
  if (ahead_.size() >= kMaxAhead || !in_order) return;
  try {
    FrameTiming timing;
    ahead_.push_back(prepareFrame(atWorkingSize(next, settings_.camera), timing));
    ahead_.back().enhance_ms = timing.enhance;
  } catch (const Error&) {
    // not pushed: track() of this frame refuses it with the same message
  }
}

// The frame prepareAhead() prepared, or prepared now. Prepared frames before this one (the
// caller skipped them) have their detections taken and dropped, so none is left pending.
Pipeline::PreparedFrame Pipeline::preparedFrame(const SensorFrame& input, FrameTiming& timing) {
  while (!ahead_.empty() && ahead_.front().index < input.index) {
    const auto skipped = static_cast<std::int64_t>(ahead_.front().index);
    ahead_.pop_front();
    try {
      detector_->take(skipped);
    } catch (const Error&) {
    }
  }
  if (!ahead_.empty() && ahead_.front().index == input.index) {
    PreparedFrame prepared = std::move(ahead_.front());
    ahead_.pop_front();
    timing.enhance += prepared.enhance_ms;
    timing.enhance_ahead = prepared.enhance_ms;
    return prepared;
  }
  if (!ahead_.empty()) {
    fail("frame {} tracked after frame {} was prepared ahead (indices must increase)", input.index,
         ahead_.front().index);
  }
  return prepareFrame(input, timing);
}

void Pipeline::pushForDetection(const SensorFrame& input, const cv::Mat& detector_image) {
  if (detector_) {
    detector_->push(static_cast<std::int64_t>(input.index), input.timestamp, detector_image);
  }
}

// ORB extraction (`build`); with a detector, the detection of this frame runs meanwhile on its
// thread (paper section 3.2) and the features on moving objects are dropped afterwards.
track::Frame Pipeline::withoutDynamicFeatures(const SensorFrame& input, const cv::Mat& depth_m,
                                              FrameResult& result,
                                              const std::function<track::Frame()>& build) {
  try {
    auto frame = build();
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

void Pipeline::removeDynamicFeatures(track::Frame& frame, const cv::Mat& depth_m,
                                     FrameResult& result) {
  const auto wait = Clock::now();
  const auto detections = detector_->take(static_cast<std::int64_t>(frame.index));
  result.timing.detection_wait = msSince(wait);
  result.timing.detection = detections.compute_ms;
  result.dynamic_boxes = detect::boxesOf(detections.detections);
  frame.dynamic_boxes = result.dynamic_boxes;
  if (result.dynamic_boxes.empty()) return;

  const auto& mask_params = detector_params_->mask;
  cv::Mat mask = detect::makeDynamicMask(frame_builder_->camera().size(), result.dynamic_boxes,
                                         mask_params.margin_px);
  // RGB-D: the background seen behind a person keeps its features.
  if (!depth_m.empty())
    mask = detect::refineMaskWithDepth(mask, depth_m, result.dynamic_boxes, mask_params);
  result.dynamic_mask = mask;
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

FrameResult Pipeline::track(const SensorFrame& sensor_input) {
  if (shut_down_) fail("frame {}: track() after shutdown()", sensor_input.index);
  const SensorFrame input = atWorkingSize(sensor_input, settings_.camera);
  const auto start = Clock::now();
  FrameResult result;
  std::optional<track::Frame> frame;
  if (settings_.sensor == io::SensorType::Stereo) {
    frame = buildStereoFrame(input, result);
  } else {
    const PreparedFrame prepared = preparedFrame(input, result.timing);
    result.feature_image = prepared.images.gray;
    frame = withoutDynamicFeatures(input, prepared.depth_m, result, [&] {
      const auto stage = Clock::now();
      auto built = frame_builder_->build(input.index, input.timestamp, prepared.images.gray,
                                         prepared.depth_m, extractionMask(input.dynamic_mask));
      result.timing.features = msSince(stage);
      return built;
    });
  }
  result.kept_features.reserve(frame->features->keypoints.size());
  for (const auto& keypoint : frame->features->keypoints) {
    result.kept_features.push_back(keypoint.pt);
  }
  auto stage = Clock::now();
  result.outcome = tracker_->track(std::move(*frame));
  result.timing.tracking = msSince(stage);
  if (result.outcome.T_w_c) result.centre_in_map = result.outcome.T_w_c->translation();
  if (rectifier_ && result.outcome.T_w_c) {
    result.outcome.T_w_c = toCalibratedCamera(*result.outcome.T_w_c);
  }
  stage = Clock::now();
  if (sequential_) {
    mapper_->processPending();
    if (loop_closer_) loop_closer_->processPending();
  } else if (result.outcome.keyframe_waits_for_mapper ||
             (result.outcome.new_keyframe && wait_for_busy_mapper_)) {
    waitForBusyMapper(input.timestamp, start);
  }
  result.timing.mapping = msSince(stage);
  result.timing.total = msSince(start) + result.timing.enhance_ahead;
  previous_timestamp_ = input.timestamp;
  previous_dynamic_mask_ = result.dynamic_mask;
  return result;
}

// A keyframe is due and the mapper still busy: give it what is left of this frame's interval,
// as a camera would, so that a run faster than the camera makes the keyframes a live one makes
// (TrackerParams::wait_for_busy_mapper). Outside the tracker's map lock: the mapper may need it.
void Pipeline::waitForBusyMapper(double timestamp, Clock::time_point frame_start) {
  if (!previous_timestamp_) return;
  constexpr double kMaxInterval = 0.2;  // s: a gap in the stream is not a frame interval
  const double interval = std::clamp(timestamp - *previous_timestamp_, 0.0, kMaxInterval);
  const auto budget = std::chrono::duration<double>(interval) - (Clock::now() - frame_start);
  if (budget.count() <= 0) return;
  mapper_->waitUntilIdleFor(std::chrono::duration_cast<std::chrono::microseconds>(budget));
}

// Tracking runs in the rectified left camera, p_rect = R_rect_c1 * p_c1 (same centre): the
// calibrated camera's pose is T_c1_rect * T_w_rect * T_rect_c1, its world being the calibrated
// camera at the first keyframe instead of the rectified one.
SE3 Pipeline::toCalibratedCamera(const SE3& T_w_c) const {
  if (!rectifier_) return T_w_c;
  SE3 T_rect_c1 = SE3::Identity();
  T_rect_c1.linear() = rectifier_->R_rect_c1();
  return T_rect_c1.inverse() * T_w_c * T_rect_c1;
}

Trajectory Pipeline::toCalibratedCamera(Trajectory trajectory) const {
  for (auto& pose : trajectory) pose.T_w_c = toCalibratedCamera(pose.T_w_c);
  return trajectory;
}

std::map<map::MapId, Trajectory> Pipeline::mapTrajectories() const {
  auto by_map = tracker_->trajectory().framesByMap();
  for (auto& [id, trajectory] : by_map) trajectory = toCalibratedCamera(std::move(trajectory));
  return by_map;
}

namespace {

// The map with most frames (the lowest id on a tie; 0 when nothing was tracked).
map::MapId mapWithMostFrames(const std::map<map::MapId, Trajectory>& by_map) {
  map::MapId main = 0;
  std::size_t most = 0;
  for (const auto& [id, trajectory] : by_map) {
    if (trajectory.size() > most) {
      most = trajectory.size();
      main = id;
    }
  }
  return main;
}

}  // namespace

map::MapId Pipeline::mainMap() const {
  return mapWithMostFrames(tracker_->trajectory().framesByMap());
}

Trajectory Pipeline::frameTrajectory() const {
  auto by_map = mapTrajectories();
  const auto main = by_map.find(mapWithMostFrames(by_map));
  return main == by_map.end() ? Trajectory{} : std::move(main->second);
}

Trajectory Pipeline::keyFrameTrajectory() const {
  return toCalibratedCamera(track::keyFrameTrajectory(map_->keyFramesOf(mainMap())));
}

const feature::OrbSettings& Pipeline::orbSettings() const {
  return frame_builder_->extractor().settings();
}

const track::FrameCamera& Pipeline::frameCamera() const {
  return frame_builder_->camera();
}

std::size_t Pipeline::keyFrameCount() const {
  return map_->keyFrameCount();
}

std::size_t Pipeline::mapPointCount() const {
  return map_->mapPointCount();
}

map::MapFingerprint Pipeline::mapFingerprint() const {
  const auto& camera = frameCamera();
  map::MapFingerprint fingerprint;
  fingerprint.sensor = std::string(io::toString(settings_.sensor));
  fingerprint.image_width = camera.size().width;
  fingerprint.image_height = camera.size().height;
  fingerprint.camera = camera.intrinsics();
  const auto& orb = orbSettings();
  fingerprint.orb_features = orb.nFeatures;
  fingerprint.orb_scale_factor = orb.scaleFactor;
  fingerprint.orb_levels = orb.nLevels;
  fingerprint.orb_ini_fast = orb.iniThFAST;
  fingerprint.orb_min_fast = orb.minThFAST;
  fingerprint.vocabulary = vocabulary_fingerprint_;
  if (places_) {
    fingerprint.vocabulary_name =
        std::filesystem::path(vocabulary_description_).filename().string();
  }
  return fingerprint;
}

void Pipeline::saveMap(const std::filesystem::path& file) {
  finishQueuedMapWork();
  const auto start = Clock::now();
  std::lock_guard lock(map_->updateMutex());
  map::saveMapFile(*map_, mapFingerprint(), file);
  spdlog::info("{}: map saved in {:.0f} ms ({} keyframes, {} points)", file.string(),
               msSince(start), map_->keyFrameCount(), map_->mapPointCount());
}

void Pipeline::loadMap(const std::filesystem::path& file) {
  if (shut_down_) fail("{}: loadMap() after shutdown()", file.string());
  if (tracker_->state() != track::TrackingState::NotInitialized || map_->keyFrameCount() > 0) {
    fail("{}: loadMap() must come before the first frame", file.string());
  }
  const auto start = Clock::now();
  std::lock_guard lock(map_->updateMutex());
  map::loadMapFile(file, mapFingerprint(), frame_builder_->pyramid(), *map_);
  tracker_->startInLoadedMap();
  spdlog::info("{}: map loaded in {:.0f} ms ({} keyframes, {} points){}", file.string(),
               msSince(start), map_->keyFrameCount(), map_->mapPointCount(),
               places_ ? "" : "; no vocabulary: relocalization is off");
}

void Pipeline::setLocalizationMode(bool on) {
  std::lock_guard lock(map_->updateMutex());
  tracker_->setLocalizationMode(on);
}

bool Pipeline::localizationMode() const {
  return tracker_->localizationMode();
}

}  // namespace lumaslam
