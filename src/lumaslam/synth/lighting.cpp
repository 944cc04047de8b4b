#include "lumaslam/synth/lighting.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "lumaslam/core/error.h"
#include "lumaslam/synth/random.h"

namespace lumaslam::synth {

namespace {

constexpr int kLutSize = 65536;

// Linear value (quantised to 16 bits) -> 8-bit output, one table per dark level.
const std::vector<std::uint8_t>& outputTable(int dark_level) {
  static const std::array<std::vector<std::uint8_t>, 6> tables = [] {
    std::array<std::vector<std::uint8_t>, 6> t;
    for (int level = 0; level < 6; ++level) {
      const DarkCurve curve = darkCurve(level);
      auto& table = t[static_cast<size_t>(level)];
      table.resize(kLutSize);
      for (int i = 0; i < kLutSize; ++i) {
        const double display = std::sqrt(static_cast<double>(i) / (kLutSize - 1));
        const double out = curve.a * std::pow(display, curve.inv_gamma);
        table[static_cast<size_t>(i)] =
            static_cast<std::uint8_t>(std::lround(std::clamp(out, 0.0, 1.0) * 255.0));
      }
    }
    return t;
  }();
  return tables[static_cast<size_t>(dark_level)];
}

}  // namespace

DarkCurve darkCurve(int level) {
  // Chosen so that level 3 looks like EuRoC MH04/MH05 dark parts (mean grey ~25-40).
  static constexpr std::array<DarkCurve, 6> curves{
      {{1.0, 1.0}, {0.8, 1.3}, {0.62, 1.6}, {0.47, 2.0}, {0.34, 2.4}, {0.22, 3.0}}};
  if (level < 0 || level > 5) fail("dark level {} is out of range (expected 0..5)", level);
  return curves[static_cast<size_t>(level)];
}

std::vector<FrameExposure> planExposures(const LightingSchedule& schedule, const Rig& rig,
                                         int frames) {
  if (frames < 0) fail("planExposures: negative frame count {}", frames);
  std::vector<FrameExposure> plan(static_cast<size_t>(frames));
  double observed = schedule.light_start;  // what auto-exposure believes the light is
  for (int i = 0; i < frames; ++i) {
    const double progress = frames > 1 ? static_cast<double>(i) / (frames - 1) : 0.0;
    const double t = i / rig.fps;
    double light = schedule.light_start + (schedule.light_end - schedule.light_start) * progress;
    if (schedule.flicker_amplitude > 0.0)
      light *= 1.0 + schedule.flicker_amplitude *
                         std::sin(2.0 * 3.14159265358979 * schedule.flicker_hz * t);
    FrameExposure& e = plan[static_cast<size_t>(i)];
    e.scene_light = std::max(light, 1e-4);
    e.nominal_ms = rig.nominal_exposure_ms;
    e.exposure_ms = std::clamp(rig.nominal_exposure_ms / observed, 0.05, rig.max_exposure_ms);
    e.gain = std::clamp(rig.nominal_exposure_ms / (observed * e.exposure_ms), 1.0, rig.max_gain);
    for (const auto& jump : schedule.jumps)
      if (i >= jump.first_frame && i < jump.first_frame + jump.frames) e.jump *= jump.factor;
    observed += 0.5 * (e.scene_light * e.jump - observed);
  }
  return plan;
}

cv::Mat exposeImage(const cv::Mat& radiance, double signal, double gain, int dark_level,
                    const SensorModel& sensor, std::uint64_t noise_key,
                    const cv::Mat& light_field) {
  if (radiance.depth() != CV_32F) fail("exposeImage: expected a CV_32F radiance image");
  if (!light_field.empty() &&
      (light_field.size() != radiance.size() || light_field.type() != CV_32F))
    fail("exposeImage: light field must be CV_32F of the image size");
  const auto& table = outputTable(dark_level);
  const int channels = radiance.channels();
  cv::Mat out(radiance.size(), CV_MAKETYPE(CV_8U, channels));
  const float electrons_per_unit = static_cast<float>(signal * sensor.full_well_e);
  const float to_output = static_cast<float>(gain / sensor.full_well_e) * (kLutSize - 1);
  const float read2 = static_cast<float>(sensor.read_noise_e * sensor.read_noise_e);
  const float noise = static_cast<float>(sensor.noise_scale);
  tbb::parallel_for(
      tbb::blocked_range<int>(0, radiance.rows, 16), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y) {
          const float* in = radiance.ptr<float>(y);
          const float* field = light_field.empty() ? nullptr : light_field.ptr<float>(y);
          std::uint8_t* o = out.ptr<std::uint8_t>(y);
          const std::uint64_t row_key = hashKey(noise_key, static_cast<std::uint64_t>(y));
          for (int x = 0; x < radiance.cols; ++x) {
            const float local = field ? field[x] : 1.0f;
            // One hash per pixel: 21 bits per channel, each the sum of a 10- and an 11-bit uniform
            // (triangular, variance-normalised): close enough to Gaussian for sensor noise.
            const std::uint64_t bits = mix64(row_key ^ static_cast<std::uint64_t>(x));
            // Shot-noise scale from the pixel's mean signal: one square root per pixel.
            float mean_e = 0.0f;
            for (int c = 0; c < channels; ++c)
              mean_e += std::max(0.0f, in[x * channels + c] * local);
            mean_e *= electrons_per_unit / static_cast<float>(channels);
            const float sigma = noise * std::sqrt(mean_e + read2);
            for (int c = 0; c < channels; ++c) {
              const int i = x * channels + c;
              const std::uint64_t part = bits >> (21 * c);
              const float triangular =
                  (static_cast<float>(part & 0x3ff) * (1.0f / 1024.0f) +
                   static_cast<float>((part >> 10) & 0x7ff) * (1.0f / 2048.0f) - 1.0f) *
                  2.449f;
              float e = std::max(0.0f, in[i] * local) * electrons_per_unit;
              if (noise > 0.0f) e += sigma * triangular;
              const float v = std::clamp(e * to_output, 0.0f, static_cast<float>(kLutSize - 1));
              o[i] = table[static_cast<size_t>(v + 0.5f)];
            }
          }
        }
      });
  return out;
}

cv::Mat displayToLinear(const cv::Mat& image) {
  if (image.depth() != CV_8U) fail("displayToLinear: expected an 8-bit image");
  cv::Mat out;
  image.convertTo(out, CV_32F, 1.0 / 255.0);
  return out.mul(out);
}

}  // namespace lumaslam::synth
