#include "lumaslam/system.h"

#include <chrono>
#include <cmath>
#include <mutex>

#include "lumaslam/camera_pose_conversion.h"
#include "lumaslam/core/bgr_order.h"
#include "lumaslam/core/error.h"
#include "lumaslam/io/settings.h"
#include "lumaslam/pipeline.h"

namespace lumaslam {

namespace {

PipelineOptions toPipelineOptions(const SystemConfig& config) {
  PipelineOptions options;
  options.enhance_preset = config.enhancement;
  options.sequential = config.sequential;
  options.detector = config.detector;
  options.vocabulary = config.vocabulary;
  options.loop_closing = config.loop_closing;
  options.motion_evidence = config.motion_evidence;
  options.strict_settings = config.strict_settings;
  return options;
}

Sensor toSensor(io::SensorType type) {
  switch (type) {
    case io::SensorType::Monocular:
      return Sensor::Monocular;
    case io::SensorType::Stereo:
      return Sensor::Stereo;
    case io::SensorType::Rgbd:
      return Sensor::Rgbd;
  }
  return Sensor::Monocular;
}

TrackState toTrackState(track::TrackingState state) {
  switch (state) {
    case track::TrackingState::NotInitialized:
      return TrackState::NotInitialized;
    case track::TrackingState::Ok:
      return TrackState::Tracking;
    case track::TrackingState::Lost:
      return TrackState::Lost;
  }
  return TrackState::Lost;
}

TrackResult toTrackResult(const track::TrackingOutcome& outcome, const SensorFrame& frame,
                          double time_ms) {
  TrackResult result;
  result.frame = frame.index;
  result.timestamp = frame.timestamp;
  result.state = toTrackState(outcome.state);
  if (outcome.T_w_c) result.T_w_c = outcome.T_w_c->matrix();
  result.inliers = outcome.inliers;
  result.keyframe = outcome.new_keyframe;
  result.relocalized = outcome.relocalized;
  result.new_map = outcome.new_map;
  result.map = outcome.map;
  result.time_ms = time_ms;
  return result;
}

}  // namespace

const char* toString(Sensor sensor) {
  switch (sensor) {
    case Sensor::Monocular:
      return "monocular";
    case Sensor::Stereo:
      return "stereo";
    case Sensor::Rgbd:
      return "rgbd";
  }
  return "unknown";
}

const char* toString(TrackState state) {
  switch (state) {
    case TrackState::NotInitialized:
      return "not initialized";
    case TrackState::Tracking:
      return "tracking";
    case TrackState::Lost:
      return "lost";
  }
  return "unknown";
}

struct System::Impl {
  Impl(const std::filesystem::path& settings_file, const SystemConfig& config)
      : settings(io::loadSettings(settings_file)),
        options(toPipelineOptions(config)),
        pipeline(std::make_unique<Pipeline>(settings, options)) {}

  // Frames numbered here; a timestamp must be finite and later than the last one.
  SensorFrame numberedFrame(Sensor called, double timestamp) {
    const Sensor configured = toSensor(settings.sensor);
    if (called != configured) {
      fail("System: track{} called, but the settings file is for a {} sensor",
           called == Sensor::Monocular ? "Monocular"
           : called == Sensor::Stereo  ? "Stereo"
                                       : "Rgbd",
           toString(configured));
    }
    if (!std::isfinite(timestamp)) fail("System: frame {}: timestamp is not finite", next_frame);
    if (last_timestamp && timestamp <= *last_timestamp) {
      fail("System: frame {}: timestamp {:.6f} is not after the last one ({:.6f})", next_frame,
           timestamp, *last_timestamp);
    }
    SensorFrame frame;
    frame.index = next_frame;
    frame.timestamp = timestamp;
    return frame;
  }

  // Camera.RGB describes the caller's images; every stage works in BGR order.
  cv::Mat inBgrOrder(const cv::Mat& image) const {
    return core::inBgrOrder(image, settings.camera.rgb);
  }

  TrackResult track(const SensorFrame& frame) {
    const auto start = std::chrono::steady_clock::now();
    const FrameResult result = pipeline->track(frame);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    ++next_frame;
    last_timestamp = frame.timestamp;
    return toTrackResult(result.outcome, frame, ms);
  }

  mutable std::mutex mutex;
  io::Settings settings;
  PipelineOptions options;
  std::unique_ptr<Pipeline> pipeline;
  std::size_t next_frame = 0;
  std::optional<double> last_timestamp;
};

System::System(const std::filesystem::path& settings_file, const SystemConfig& config)
    : impl_(std::make_unique<Impl>(settings_file, config)) {}

System::~System() = default;
System::System(System&&) noexcept = default;
System& System::operator=(System&&) noexcept = default;

Sensor System::sensor() const {
  return toSensor(impl_->settings.sensor);
}

TrackResult System::trackMonocular(const cv::Mat& image, double timestamp) {
  const std::scoped_lock lock(impl_->mutex);
  SensorFrame frame = impl_->numberedFrame(Sensor::Monocular, timestamp);
  frame.image = impl_->inBgrOrder(image);
  return impl_->track(frame);
}

TrackResult System::trackStereo(const cv::Mat& left, const cv::Mat& right, double timestamp) {
  const std::scoped_lock lock(impl_->mutex);
  SensorFrame frame = impl_->numberedFrame(Sensor::Stereo, timestamp);
  frame.image = impl_->inBgrOrder(left);
  frame.right = impl_->inBgrOrder(right);
  return impl_->track(frame);
}

TrackResult System::trackRgbd(const cv::Mat& image, const cv::Mat& depth, double timestamp) {
  const std::scoped_lock lock(impl_->mutex);
  SensorFrame frame = impl_->numberedFrame(Sensor::Rgbd, timestamp);
  frame.image = impl_->inBgrOrder(image);
  frame.depth = depth;
  return impl_->track(frame);
}

void System::saveMap(const std::filesystem::path& file) {
  const std::scoped_lock lock(impl_->mutex);
  impl_->pipeline->saveMap(file);
}

void System::loadMap(const std::filesystem::path& file) {
  const std::scoped_lock lock(impl_->mutex);
  impl_->pipeline->loadMap(file);
}

void System::setLocalizationMode(bool on) {
  const std::scoped_lock lock(impl_->mutex);
  impl_->pipeline->setLocalizationMode(on);
}

bool System::localizationMode() const {
  const std::scoped_lock lock(impl_->mutex);
  return impl_->pipeline->localizationMode();
}

void System::reset() {
  const std::scoped_lock lock(impl_->mutex);
  impl_->pipeline->shutdown();
  impl_->pipeline.reset();  // one pipeline's threads at a time
  impl_->pipeline = std::make_unique<Pipeline>(impl_->settings, impl_->options);
  impl_->last_timestamp.reset();
}

void System::shutdown() {
  const std::scoped_lock lock(impl_->mutex);
  impl_->pipeline->shutdown();
}

CameraTrajectory System::trajectory() const {
  const std::scoped_lock lock(impl_->mutex);
  return toCameraTrajectory(impl_->pipeline->frameTrajectory());
}

CameraTrajectory System::keyframeTrajectory() const {
  const std::scoped_lock lock(impl_->mutex);
  return toCameraTrajectory(impl_->pipeline->keyFrameTrajectory());
}

std::size_t System::frameCount() const {
  const std::scoped_lock lock(impl_->mutex);
  return impl_->next_frame;
}

std::size_t System::keyframeCount() const {
  const std::scoped_lock lock(impl_->mutex);
  return impl_->pipeline->keyFrameCount();
}

std::size_t System::mapPointCount() const {
  const std::scoped_lock lock(impl_->mutex);
  return impl_->pipeline->mapPointCount();
}

}  // namespace lumaslam
