#include "lumaslam/synth/motion_blur.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <opencv2/core/hal/intrin.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/synth/spare_row.h"

namespace lumaslam::synth {

namespace {

// Pixel (x, y) of a CV_32FC3 image as lanes 0-2 (lane 3 is the next pixel's first channel).
inline cv::v_float32x4 pixel(const cv::Mat& img, int x, int y) {
  return cv::v_load(img.ptr<float>(y) + 3 * x);
}

// `img` must have a spare row in memory after its last one (see withSpareRow).
inline cv::v_float32x4 bilinear(const cv::Mat& img, float x, float y) {
  x = std::clamp(x, 0.0f, static_cast<float>(img.cols - 1));
  y = std::clamp(y, 0.0f, static_cast<float>(img.rows - 1));
  const int x0 = std::min(static_cast<int>(x), img.cols - 2),
            y0 = std::min(static_cast<int>(y), img.rows - 2);
  const cv::v_float32x4 fx = cv::v_setall_f32(x - static_cast<float>(x0));
  const cv::v_float32x4 fy = cv::v_setall_f32(y - static_cast<float>(y0));
  const cv::v_float32x4 one = cv::v_setall_f32(1.0f);
  return (pixel(img, x0, y0) * (one - fx) + pixel(img, x0 + 1, y0) * fx) * (one - fy) +
         (pixel(img, x0, y0 + 1) * (one - fx) + pixel(img, x0 + 1, y0 + 1) * fx) * fy;
}

inline void storeBgr(cv::Vec3f& out, const cv::v_float32x4& value) {
  float lanes[4];
  cv::v_store(lanes, value);
  out = {lanes[0], lanes[1], lanes[2]};
}

}  // namespace

cv::Mat applyMotionBlur(const cv::Mat& radiance, const cv::Mat& depth, const PinholeCamera& cam,
                        const SE3& T_w_mid, const SE3& T_w_start, const SE3& T_w_end) {
  return applyMotionBlur(radiance, depth, cam, RowPoses(T_w_mid), RowPoses(T_w_start),
                         RowPoses(T_w_end));
}

cv::Mat applyMotionBlur(const cv::Mat& radiance, const cv::Mat& depth, const PinholeCamera& cam,
                        const RowPoses& T_w_mid, const RowPoses& T_w_start,
                        const RowPoses& T_w_end) {
  if (radiance.type() != CV_32FC3 || depth.type() != CV_32F || radiance.size() != depth.size())
    fail("applyMotionBlur: expected CV_32FC3 radiance and CV_32F depth of the same size");
  const bool global = T_w_mid.global() && T_w_start.global() && T_w_end.global();
  std::vector<Eigen::Isometry3f> start_mid(global ? 1 : static_cast<size_t>(radiance.rows));
  std::vector<Eigen::Isometry3f> end_mid(start_mid.size());
  for (int r = 0; r < static_cast<int>(start_mid.size()); ++r) {
    start_mid[static_cast<size_t>(r)] = (T_w_start[r].inverse() * T_w_mid[r]).cast<float>();
    end_mid[static_cast<size_t>(r)] = (T_w_end[r].inverse() * T_w_mid[r]).cast<float>();
  }
  const float fx = static_cast<float>(cam.fx), fy = static_cast<float>(cam.fy);
  const float cx = static_cast<float>(cam.cx), cy = static_cast<float>(cam.cy);
  const cv::Mat source = withSpareRow(radiance);  // 4-float loads of the last pixel stay inside
  cv::Mat out(radiance.size(), CV_32FC3);
  tbb::parallel_for(
      tbb::blocked_range<int>(0, radiance.rows, 8), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y) {
          const size_t pose_row = global ? 0 : static_cast<size_t>(y);
          const Eigen::Isometry3f& T_start_mid = start_mid[pose_row];
          const Eigen::Isometry3f& T_end_mid = end_mid[pose_row];
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
            int taps = static_cast<int>(length);  // ceil(length), without a libm call
            taps = std::clamp(taps + (static_cast<float>(taps) < length ? 1 : 0), 1, 32);
            if (taps == 1) {
              storeBgr(o[x], bilinear(source, 0.5f * (ax + bx), 0.5f * (ay + by)));
              continue;
            }
            cv::v_float32x4 sum = cv::v_setzero_f32();
            for (int k = 0; k < taps; ++k) {
              const float s = (static_cast<float>(k) + 0.5f) / static_cast<float>(taps);
              sum = sum + bilinear(source, ax + s * (bx - ax), ay + s * (by - ay));
            }
            storeBgr(o[x], sum * cv::v_setall_f32(1.0f / static_cast<float>(taps)));
          }
        }
      });
  return out;
}

}  // namespace lumaslam::synth
