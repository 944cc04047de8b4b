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

namespace {

struct ExposeParams {
  const std::vector<std::uint8_t>* table;
  float electrons_per_unit;
  float mean_electrons_per_unit;  // per unit of the channel sum
  float to_output;
  float read2;
  float noise;
};

// One row of exposeImage for C channels (C known at compile time: the channel loops unroll).
template <int C>
void exposeRow(const float* in, const float* field, std::uint8_t* o, int cols,
               std::uint64_t row_key, const ExposeParams& p) {
  const std::uint8_t* table = p.table->data();
  constexpr float kMax = static_cast<float>(kLutSize - 1);
  for (int x = 0; x < cols; ++x) {
    const float local = field ? field[x] : 1.0f;
    float e[C];
    float sum = 0.0f;
    for (int c = 0; c < C; ++c) {
      const float value = std::max(0.0f, in[x * C + c] * local);
      sum += value;
      e[c] = value * p.electrons_per_unit;
    }
    if (p.noise > 0.0f) {
      // One hash per pixel: 21 bits per channel, each the sum of a 10- and an 11-bit uniform
      // (triangular, variance-normalised): close enough to Gaussian for sensor noise.
      const std::uint64_t bits = mix64(row_key ^ static_cast<std::uint64_t>(x));
      // Shot-noise scale from the pixel's mean signal: one square root per pixel.
      const float sigma = p.noise * std::sqrt(sum * p.mean_electrons_per_unit + p.read2);
      for (int c = 0; c < C; ++c) {
        const std::uint64_t part = bits >> (21 * c);
        const float triangular =
            (static_cast<float>(part & 0x3ff) * (1.0f / 1024.0f) +
             static_cast<float>((part >> 10) & 0x7ff) * (1.0f / 2048.0f) - 1.0f) *
            2.449f;
        e[c] += sigma * triangular;
      }
    }
    for (int c = 0; c < C; ++c) {
      const float v = std::min(std::max(e[c] * p.to_output, 0.0f), kMax);
      o[x * C + c] = table[static_cast<int>(v + 0.5f)];
    }
  }
}

}  // namespace

cv::Mat exposeImage(const cv::Mat& radiance, double signal, double gain, int dark_level,
                    const SensorModel& sensor, std::uint64_t noise_key,
                    const cv::Mat& light_field) {
  if (radiance.depth() != CV_32F) fail("exposeImage: expected a CV_32F radiance image");
  if (!light_field.empty() &&
      (light_field.size() != radiance.size() || light_field.type() != CV_32F))
    fail("exposeImage: light field must be CV_32F of the image size");
  const int channels = radiance.channels();
  if (channels != 1 && channels != 3)
    fail("exposeImage: expected 1 or 3 channels, got {}", channels);
  cv::Mat out(radiance.size(), CV_MAKETYPE(CV_8U, channels));
  ExposeParams params;
  params.table = &outputTable(dark_level);
  params.electrons_per_unit = static_cast<float>(signal * sensor.full_well_e);
  params.mean_electrons_per_unit = params.electrons_per_unit / static_cast<float>(channels);
  params.to_output = static_cast<float>(gain / sensor.full_well_e) * (kLutSize - 1);
  params.read2 = static_cast<float>(sensor.read_noise_e * sensor.read_noise_e);
  params.noise = static_cast<float>(sensor.noise_scale);
  tbb::parallel_for(
      tbb::blocked_range<int>(0, radiance.rows, 16), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y) {
          const float* field = light_field.empty() ? nullptr : light_field.ptr<float>(y);
          const std::uint64_t row_key = hashKey(noise_key, static_cast<std::uint64_t>(y));
          if (channels == 3)
            exposeRow<3>(radiance.ptr<float>(y), field, out.ptr<std::uint8_t>(y), radiance.cols,
                         row_key, params);
          else
            exposeRow<1>(radiance.ptr<float>(y), field, out.ptr<std::uint8_t>(y), radiance.cols,
                         row_key, params);
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
