#include "lumaslam/synth/motion_blur.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "lumaslam/core/error.h"

namespace lumaslam::synth {

namespace {

cv::Vec3f bilinear(const cv::Mat& img, float x, float y) {
  x = std::clamp(x, 0.0f, static_cast<float>(img.cols - 1));
  y = std::clamp(y, 0.0f, static_cast<float>(img.rows - 1));
  const int x0 = std::min(static_cast<int>(x), img.cols - 2),
            y0 = std::min(static_cast<int>(y), img.rows - 2);
  const float fx = x - static_cast<float>(x0), fy = y - static_cast<float>(y0);
  const auto* r0 = img.ptr<cv::Vec3f>(y0);
  const auto* r1 = img.ptr<cv::Vec3f>(y0 + 1);
  return (r0[x0] * (1 - fx) + r0[x0 + 1] * fx) * (1 - fy) +
         (r1[x0] * (1 - fx) + r1[x0 + 1] * fx) * fy;
}

}  // namespace

cv::Mat applyMotionBlur(const cv::Mat& radiance, const cv::Mat& depth, const PinholeCamera& cam,
                        const SE3& T_w_mid, const SE3& T_w_start, const SE3& T_w_end) {
  if (radiance.type() != CV_32FC3 || depth.type() != CV_32F || radiance.size() != depth.size())
    fail("applyMotionBlur: expected CV_32FC3 radiance and CV_32F depth of the same size");
  const Eigen::Isometry3f T_start_mid = (T_w_start.inverse() * T_w_mid).cast<float>();
  const Eigen::Isometry3f T_end_mid = (T_w_end.inverse() * T_w_mid).cast<float>();
  const float fx = static_cast<float>(cam.fx), fy = static_cast<float>(cam.fy);
  const float cx = static_cast<float>(cam.cx), cy = static_cast<float>(cam.cy);
  cv::Mat out(radiance.size(), CV_32FC3);
  tbb::parallel_for(
      tbb::blocked_range<int>(0, radiance.rows, 8), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y) {
          const float* z = depth.ptr<float>(y);
          auto* o = out.ptr<cv::Vec3f>(y);
          for (int x = 0; x < radiance.cols; ++x) {
            const Eigen::Vector3f X((static_cast<float>(x) - cx) / fx * z[x],
                                    (static_cast<float>(y) - cy) / fy * z[x], z[x]);
            const Eigen::Vector3f a = T_start_mid * X, b = T_end_mid * X;
            if (a.z() <= 0.01f || b.z() <= 0.01f) {
              o[x] = radiance.at<cv::Vec3f>(y, x);
              continue;
            }
            const float ax = fx * a.x() / a.z() + cx, ay = fy * a.y() / a.z() + cy;
            const float bx = fx * b.x() / b.z() + cx, by = fy * b.y() / b.z() + cy;
            const float length = std::sqrt((bx - ax) * (bx - ax) + (by - ay) * (by - ay));
            const int taps = std::clamp(static_cast<int>(std::ceil(length)), 1, 32);
            if (taps == 1) {
              o[x] = bilinear(radiance, 0.5f * (ax + bx), 0.5f * (ay + by));
              continue;
            }
            cv::Vec3f sum(0, 0, 0);
            for (int k = 0; k < taps; ++k) {
              const float s = (static_cast<float>(k) + 0.5f) / static_cast<float>(taps);
              sum += bilinear(radiance, ax + s * (bx - ax), ay + s * (by - ay));
            }
            o[x] = sum * (1.0f / static_cast<float>(taps));
          }
        }
      });
  return out;
}

}  // namespace lumaslam::synth
