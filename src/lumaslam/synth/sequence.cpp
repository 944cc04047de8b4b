#include "lumaslam/synth/sequence.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgcodecs.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/synth/motion_blur.h"
#include "lumaslam/synth/random.h"

namespace lumaslam::synth {

namespace {

Scene buildScene(const Preset& preset, const SynthOptions& options,
                 const CameraTrajectory& trajectory, std::uint64_t seed) {
  SceneOptions scene_options;
  scene_options.walkers = options.walkers.value_or(preset.walkers);
  scene_options.moving_boxes = options.moving_boxes.value_or(preset.moving_boxes);
  if (scene_options.walkers < 0 || scene_options.moving_boxes < 0)
    fail("synth: walkers ({}) and moving boxes ({}) must not be negative", scene_options.walkers,
         scene_options.moving_boxes);
  scene_options.spotlight = preset.spotlight;
  scene_options.view_origin = trajectory.viewOrigin();
  scene_options.view_direction = trajectory.viewDirection();
  scene_options.walkers_sitting = preset.walkers_sitting;
  if (preset.walkers_follow_view)
    scene_options.walkers_follow_view = [trajectory](double t) { return trajectory.pose(t); };
  for (const auto& path : options.texture_images) {
    cv::Mat image = cv::imread(path.string(), cv::IMREAD_COLOR);
    if (image.empty())
      fail("{}: cannot read this texture image (missing or not an image)", path.string());
    scene_options.posters.push_back(image);
  }
  scene_options.people = options.people;
  return Scene::build(scene_options, seed);
}

LightingSchedule effectiveLighting(const Preset& preset, const SynthOptions& options) {
  LightingSchedule lighting = preset.lighting;
  if (options.dark_level) {
    darkCurve(*options.dark_level);  // validates the level
    lighting.dark_level = *options.dark_level;
  }
  if (!options.sensor_noise) lighting.noise_scale = 0.0;
  if (!options.motion_blur) lighting.motion_blur = false;
  return lighting;
}

// The preset's depth sensor with the options' switches applied.
DepthSensorModel effectiveDepthModel(const Preset& preset, const SynthOptions& options) {
  DepthSensorModel model = preset.depth;
  if (!options.depth_noise) {
    model.noise = false;
    model.edge_hole_probability = 0.0f;
    model.dropout_blobs_per_megapixel = 0.0f;
    model.min_ir_albedo = 0.0f;
    model.max_incidence_deg = 90.0f;
    model.quantize_disparity = false;
  }
  if (!options.depth_misalignment) {
    model.registration_shift_px = {0.0f, 0.0f};
    model.registration_scale = 1.0f;
    model.max_time_offset_ms = 0.0;
  }
  if (!(model.max_time_offset_ms >= 0.0 && model.max_time_offset_ms <= 15.0))
    fail("synth preset '{}': depth time offset {} ms is outside 0..15 ms", preset.name,
         model.max_time_offset_ms);
  return model;
}

}  // namespace

SequenceRenderer::SequenceRenderer(const Preset& preset, int frames, std::uint64_t seed,
                                   const SynthOptions& options)
    : preset_(preset),
      rig_(preset.rig()),
      frames_(frames),
      seed_(seed),
      options_(options),
      // Realistic epochs: TUM fr1 (2011) for RGB-D, EuRoC (2014) for stereo, shifted by the seed.
      start_ns_(
          (preset.sensor == SensorKind::Stereo ? 1403715273262142976LL : 1305031102175304000LL) +
          static_cast<std::int64_t>(hashKey(seed, 0x71e) % 100000) * 1000000000LL),
      trajectory_(preset.trajectory, std::max(frames, 1) / preset.rig().fps, seed,
                  preset.motion_speed),
      scene_(buildScene(preset, options, trajectory_, seed)),
      depth_model_(effectiveDepthModel(preset, options)) {
  if (frames < 1)
    fail("synth preset '{}': frame count must be at least 1, got {}", preset.name, frames);
  if (!options.rolling_shutter) rig_.readout_ms = 0.0;
  if (!(rig_.readout_ms >= 0.0 && rig_.readout_ms <= 1000.0 / rig_.fps))
    fail("synth preset '{}': rolling-shutter readout {} ms is outside 0..{:.1f} ms (one frame)",
         preset.name, rig_.readout_ms, 1000.0 / rig_.fps);
  preset_.lighting = effectiveLighting(preset, options);
  exposures_ = planExposures(preset_.lighting, rig_, frames);
}

std::int64_t SequenceRenderer::timestampNs(int index) const {
  if (rig_.kind == SensorKind::Stereo)  // EuRoC: exact 20 Hz in nanoseconds
    return start_ns_ + static_cast<std::int64_t>(index) *
                           static_cast<std::int64_t>(std::llround(1e9 / rig_.fps));
  // TUM: 30 Hz with +-1 ms capture jitter, stamps in microseconds.
  const double jitter_us =
      (unitFromBits(hashKey(seed_, 0x7135, static_cast<std::uint64_t>(index))) - 0.5) * 2000.0;
  const std::int64_t us = std::llround(static_cast<double>(index) * 1e6 / rig_.fps + jitter_us);
  return start_ns_ + us * 1000;
}

std::int64_t SequenceRenderer::depthTimestampNs(int index) const {
  if (depth_model_.max_time_offset_ms <= 0.0) return timestampNs(index);
  const double u = unitFromBits(hashKey(seed_, 0xd7e1, static_cast<std::uint64_t>(index)));
  const std::int64_t offset_us =
      std::llround((2.0 * u - 1.0) * depth_model_.max_time_offset_ms * 1000.0);
  return timestampNs(index) + offset_us * 1000;  // whole microseconds, like TUM's stamps
}

double SequenceRenderer::secondsFromStart(std::int64_t timestamp_ns) const {
  return static_cast<double>(timestamp_ns - start_ns_) * 1e-9;
}

SE3 SequenceRenderer::poseAt(double timestamp) const {
  return trajectory_.pose(timestamp - static_cast<double>(start_ns_) * 1e-9);
}

const FrameExposure& SequenceRenderer::exposure(int index) const {
  if (index < 0 || index >= frames_)
    fail("synth: frame {} is out of range (0..{})", index, frames_ - 1);
  return exposures_[static_cast<size_t>(index)];
}

RowPoses SequenceRenderer::rowPosesAt(double t, const SE3& T_c0_c) const {
  return rowPoses([&](double s) { return trajectory_.pose(s) * T_c0_c; }, t, rig_.readout_ms * 1e-3,
                  rig_.camera.height);
}

RenderedView SequenceRenderer::renderAt(double t, const SE3& T_c0_c) const {
  const SceneSnapshot snapshot = scene_.at(t, trajectory_.pose(t).translation());
  return renderView(scene_, snapshot, rig_.camera, rowPosesAt(t, T_c0_c));
}

cv::Mat SequenceRenderer::blurred(const RenderedView& view, int index, double t,
                                  const SE3& T_c0_c) const {
  const FrameExposure& exposure = exposures_[static_cast<size_t>(index)];
  const double exposure_s = exposure.exposure_ms * exposure.jump * 1e-3;
  if (!preset_.lighting.motion_blur || exposure_s <= 1e-4) return view.radiance;
  return applyMotionBlur(view.radiance, view.depth, rig_.camera, rowPosesAt(t, T_c0_c),
                         rowPosesAt(t - exposure_s / 2, T_c0_c),
                         rowPosesAt(t + exposure_s / 2, T_c0_c));
}

CameraFrame SequenceRenderer::exposeCamera(int index, int camera, const RenderedView& view,
                                           const SE3& T_w_c, const cv::Mat& radiance) const {
  const FrameExposure& exposure = exposures_[static_cast<size_t>(index)];
  SensorModel sensor;
  sensor.noise_scale = preset_.lighting.noise_scale;
  CameraFrame frame;
  frame.image =
      exposeImage(radiance, exposure.signal(), exposure.gain, preset_.lighting.dark_level, sensor,
                  hashKey(seed_, 0x1a9e, static_cast<std::uint64_t>(index),
                          static_cast<std::uint64_t>(camera)));
  frame.depth = view.depth;
  frame.mask = view.object_ids > 0;
  frame.T_w_c = T_w_c;
  // Ground-truth boxes: tight bounds of each dynamic object's visible pixels.
  const int objects = scene_.dynamicObjectCount();
  if (objects > 0) {
    std::vector<cv::Rect> bounds(static_cast<size_t>(objects) + 1);
    std::vector<int> counts(static_cast<size_t>(objects) + 1, 0);
    for (int y = 0; y < view.object_ids.rows; ++y) {
      const auto* ids = view.object_ids.ptr<std::uint8_t>(y);
      for (int x = 0; x < view.object_ids.cols; ++x) {
        if (!ids[x]) continue;
        cv::Rect& b = bounds[ids[x]];
        b = counts[ids[x]]++ ? (b | cv::Rect(x, y, 1, 1)) : cv::Rect(x, y, 1, 1);
      }
    }
    for (int id = 1; id <= objects; ++id)
      if (counts[static_cast<size_t>(id)] >= 20)
        frame.boxes.push_back({scene_.objectClass(static_cast<std::uint8_t>(id)), id,
                               bounds[static_cast<size_t>(id)]});
  }
  return frame;
}

// The depth camera sees the scene at its own capture time, through the same readout as colour
// (assumed: the Kinect v1's IR camera is a CMOS sensor too), and is registered to colour.
cv::Mat SequenceRenderer::sensorDepth(int index, const RenderedView& colour_view) const {
  const std::int64_t depth_ns = depthTimestampNs(index);
  const bool same_time = depth_ns == timestampNs(index);
  const RenderedView depth_view =
      same_time ? RenderedView{} : renderAt(secondsFromStart(depth_ns), SE3::Identity());
  const RenderedView& seen = same_time ? colour_view : depth_view;
  return simulateDepthSensor(DepthSensorInput{seen.depth, seen.ir_albedo, seen.incidence_cos},
                             depth_model_,
                             hashKey(seed_, 0xde97, static_cast<std::uint64_t>(index)));
}

Frame SequenceRenderer::render(int index) const {
  exposure(index);  // range check
  Frame frame;
  frame.index = index;
  frame.timestamp_ns = timestampNs(index);
  frame.depth_timestamp_ns = depthTimestampNs(index);
  frame.exposure = exposures_[static_cast<size_t>(index)];
  const double t = secondsFromStart(frame.timestamp_ns);
  const SE3 T_w_c0 = trajectory_.pose(t);
  const RenderedView view0 = renderAt(t, SE3::Identity());
  frame.cam0 = exposeCamera(index, 0, view0, T_w_c0, blurred(view0, index, t, SE3::Identity()));
  if (rig_.kind == SensorKind::Stereo) {
    const RenderedView view1 = renderAt(t, rig_.T_c0_c1());
    frame.cam1 = exposeCamera(index, 1, view1, T_w_c0 * rig_.T_c0_c1(),
                              blurred(view1, index, t, rig_.T_c0_c1()));
  } else {
    frame.sensor_depth = sensorDepth(index, view0);
  }
  return frame;
}

}  // namespace lumaslam::synth
