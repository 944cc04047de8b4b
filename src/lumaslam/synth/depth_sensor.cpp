#include "lumaslam/synth/depth_sensor.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>
#include <opencv2/imgproc.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/synth/depth_registration.h"
#include "lumaslam/synth/random.h"

namespace lumaslam::synth {

namespace {

constexpr float kPi = 3.14159265f;
// Kinect v1: focal length of the IR camera x projector-camera baseline, and the 1/8-pixel
// disparity step of its 11-bit output (Khoshelham & Elberink 2012).
constexpr float kFocalTimesBaseline = 580.0f * 0.075f;
constexpr float kDisparityStep = 1.0f / 8.0f;

// Probability that no speckle comes back from a surface of this reflectance and view angle.
float returnLossProbability(float albedo, float incidence_cos, const DepthSensorModel& m) {
  float p = 0.0f;
  if (m.min_ir_albedo > 0.0f)
    p = std::clamp((2.0f * m.min_ir_albedo - albedo) / m.min_ir_albedo, 0.0f, 1.0f);
  if (m.max_incidence_deg < 90.0f) {
    const float angle_deg = std::acos(std::clamp(incidence_cos, 0.0f, 1.0f)) * (180.0f / kPi);
    p = std::max(p, std::clamp((angle_deg - (m.max_incidence_deg - 5.0f)) / 5.0f, 0.0f, 1.0f));
  }
  return p;
}

// Axial standard deviation at depth z and incidence cosine c (Nguyen et al. 2012).
float axialSigma(float z, float incidence_cos, bool grazing) {
  float sigma = 0.0012f + 0.0019f * (z - 0.4f) * (z - 0.4f);
  if (grazing) {
    const float theta = std::acos(std::clamp(incidence_cos, 0.0f, 1.0f));
    const float rest = std::max(kPi / 2.0f - theta, 0.05f);  // capped: 0.3 m at 87 degrees
    sigma += 0.0001f / std::sqrt(z) * theta * theta / (rest * rest);
  }
  return sigma;
}

float quantizeDisparity(float z) {
  const float disparity = kFocalTimesBaseline / z;
  const float steps = std::round(disparity / kDisparityStep);
  return steps > 0.0f ? kFocalTimesBaseline / (steps * kDisparityStep) : 0.0f;
}

void addDropoutBlobs(cv::Mat& depth, const DepthSensorModel& model, std::uint64_t key) {
  Rng rng(key, 0xb10b);
  const int blobs = static_cast<int>(model.dropout_blobs_per_megapixel * depth.total() / 1e6f);
  for (int i = 0; i < blobs; ++i) {
    const cv::Point centre(rng.uniformInt(0, depth.cols - 1), rng.uniformInt(0, depth.rows - 1));
    cv::ellipse(depth, centre, {rng.uniformInt(2, 9), rng.uniformInt(2, 7)}, rng.uniform(0, 180), 0,
                360, cv::Scalar(0.0), cv::FILLED);
  }
}

}  // namespace

cv::Mat simulateDepthSensor(const cv::Mat& depth_m, const DepthSensorModel& model,
                            std::uint64_t key) {
  return simulateDepthSensor(DepthSensorInput{depth_m, {}, {}}, model, key);
}

cv::Mat simulateDepthSensor(const DepthSensorInput& ideal, const DepthSensorModel& model,
                            std::uint64_t key) {
  if (ideal.depth_m.type() != CV_32F) fail("simulateDepthSensor: expected CV_32F depth");
  for (const cv::Mat* map : {&ideal.ir_albedo, &ideal.incidence_cos})
    if (!map->empty() && (map->type() != CV_32F || map->size() != ideal.depth_m.size()))
      fail("simulateDepthSensor: albedo and incidence maps must be CV_32F of the depth's size");
  const DepthSensorInput input =
      misregister(ideal, model.registration_shift_px, model.registration_scale);
  const cv::Mat& depth_m = input.depth_m;
  const bool returns = !input.ir_albedo.empty() && !input.incidence_cos.empty() &&
                       (model.min_ir_albedo > 0.0f || model.max_incidence_deg < 90.0f);
  const bool angles = !input.incidence_cos.empty() && model.grazing_noise;
  // Local depth range over a 5x5 neighbourhood marks discontinuities (the Kinect's shadows).
  cv::Mat local_max, local_min;
  const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_RECT, {5, 5});
  cv::dilate(depth_m, local_max, kernel);
  cv::erode(depth_m, local_min, kernel);
  cv::Mat out(depth_m.size(), CV_32F);
  tbb::parallel_for(0, depth_m.rows, [&](int y) {
    const float* z = depth_m.ptr<float>(y);
    const float* hi = local_max.ptr<float>(y);
    const float* lo = local_min.ptr<float>(y);
    const float* albedo = returns ? input.ir_albedo.ptr<float>(y) : nullptr;
    const float* cosine = returns || angles ? input.incidence_cos.ptr<float>(y) : nullptr;
    float* o = out.ptr<float>(y);
    for (int x = 0; x < depth_m.cols; ++x) {
      const std::uint64_t bits =
          hashKey(key, static_cast<std::uint64_t>(y), static_cast<std::uint64_t>(x));
      float d = z[x];
      if (d < model.min_depth_m || d > model.max_depth_m) d = 0.0f;
      if (d > 0.0f && hi[x] - lo[x] > 0.04f * d && unitFromBits(bits) < model.edge_hole_probability)
        d = 0.0f;
      if (d > 0.0f && returns &&
          unitFromBits(mix64(bits ^ 0x1e7u)) < returnLossProbability(albedo[x], cosine[x], model))
        d = 0.0f;
      if (d > 0.0f && model.noise)
        d += axialSigma(d, angles ? cosine[x] : 1.0f, angles) * gaussianFromBits(mix64(bits));
      if (d > 0.0f && model.quantize_disparity) d = quantizeDisparity(d);
      o[x] = d;
    }
  });
  addDropoutBlobs(out, model, key);
  return out;
}

}  // namespace lumaslam::synth
