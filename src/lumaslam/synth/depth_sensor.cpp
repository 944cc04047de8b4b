#include "lumaslam/synth/depth_sensor.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>
#include <opencv2/imgproc.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/synth/random.h"

namespace lumaslam::synth {

cv::Mat simulateDepthSensor(const cv::Mat& depth_m, const DepthSensorModel& model,
                            std::uint64_t key) {
  if (depth_m.type() != CV_32F) fail("simulateDepthSensor: expected CV_32F depth");
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
    float* o = out.ptr<float>(y);
    for (int x = 0; x < depth_m.cols; ++x) {
      const std::uint64_t bits =
          hashKey(key, static_cast<std::uint64_t>(y), static_cast<std::uint64_t>(x));
      float d = z[x];
      if (d < model.min_depth_m || d > model.max_depth_m) d = 0.0f;
      if (d > 0.0f && hi[x] - lo[x] > 0.04f * d && unitFromBits(bits) < model.edge_hole_probability)
        d = 0.0f;
      if (d > 0.0f && model.noise) {
        const float sigma = 0.0012f + 0.0019f * (d - 0.4f) * (d - 0.4f);
        d += sigma * gaussianFromBits(mix64(bits));
      }
      o[x] = d;
    }
  });
  Rng rng(key, 0xb10b);
  const int blobs = static_cast<int>(model.dropout_blobs_per_megapixel * depth_m.total() / 1e6f);
  for (int i = 0; i < blobs; ++i) {
    const cv::Point centre(rng.uniformInt(0, depth_m.cols - 1),
                           rng.uniformInt(0, depth_m.rows - 1));
    cv::ellipse(out, centre, {rng.uniformInt(2, 9), rng.uniformInt(2, 7)}, rng.uniform(0, 180), 0,
                360, cv::Scalar(0.0), cv::FILLED);
  }
  return out;
}

}  // namespace lumaslam::synth
