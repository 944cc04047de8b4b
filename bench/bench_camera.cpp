// Camera kernels on the real EuRoC V1_01 calibration (read from the dataset's sensor.yaml):
// keypoint undistortion (ours: iterated to convergence, vs OpenCV's default 5 iterations),
// building the stereo rectification maps, rectifying a 752x480 pair, and depth conversion.
#include <filesystem>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>

#include "lumaslam/camera/pinhole_camera.h"
#include "lumaslam/camera/stereo_geometry.h"
#include "lumaslam/camera/stereo_rectifier.h"
#include "lumaslam/core/settings_file.h"

namespace {

namespace fs = std::filesystem;
using lumaslam::camera::PinholeCamera;
using lumaslam::camera::StereoRectifier;

const fs::path kMav = fs::path(LUMASLAM_SHARED_DIR) / "data/euroc/V1_01_easy_micro/mav0";

struct Sensor {
  PinholeCamera camera;
  Eigen::Isometry3d T_b_s;
};

Sensor readSensor(const std::string& name) {
  const auto file = lumaslam::core::SettingsFile::open(kMav / name / "sensor.yaml");
  const auto k = file.get<std::vector<double>>("intrinsics");
  const auto d = file.get<std::vector<double>>("distortion_coefficients");
  const auto t = file.get<std::vector<double>>("T_BS.data");
  Eigen::Matrix4d T;
  for (int i = 0; i < 16; ++i) T(i / 4, i % 4) = t.at(i);
  return {PinholeCamera(k[0], k[1], k[2], k[3], {752, 480}, {d[0], d[1], d[2], d[3], 0.0}),
          Eigen::Isometry3d(T)};
}

StereoRectifier eurocRectifier() {
  const Sensor left = readSensor("cam0"), right = readSensor("cam1");
  return StereoRectifier(left.camera, right.camera, left.T_b_s.inverse() * right.T_b_s);
}

std::vector<cv::Point2f> randomPixels(int count) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(0.0f, 751.0f), v(0.0f, 479.0f);
  std::vector<cv::Point2f> points(count);
  for (auto& p : points) p = {u(rng), v(rng)};
  return points;
}

void BM_UndistortKeypointsOurs(benchmark::State& state) {
  const PinholeCamera camera = readSensor("cam0").camera;
  const auto raw = randomPixels(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(camera.undistortPoints(raw));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_UndistortKeypointsOurs)->Arg(1000)->Unit(benchmark::kMicrosecond);

void BM_UndistortKeypointsOpenCvDefault(benchmark::State& state) {
  const PinholeCamera camera = readSensor("cam0").camera;
  const auto raw = randomPixels(static_cast<int>(state.range(0)));
  const cv::Matx33d K = camera.K();
  const cv::Mat D = camera.distortionCoefficients();
  std::vector<cv::Point2f> out;
  for (auto _ : state) {
    cv::undistortPoints(raw, out, K, D, cv::noArray(), K);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_UndistortKeypointsOpenCvDefault)->Arg(1000)->Unit(benchmark::kMicrosecond);

void BM_StereoRectifierBuild(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(eurocRectifier().baseline());
}
BENCHMARK(BM_StereoRectifierBuild)->Unit(benchmark::kMillisecond);

void BM_StereoRectifyPair(benchmark::State& state) {
  const StereoRectifier rectifier = eurocRectifier();
  const cv::Mat left =
      cv::imread((kMav / "cam0/data/1403715274312143104.png").string(), cv::IMREAD_GRAYSCALE);
  const cv::Mat right =
      cv::imread((kMav / "cam1/data/1403715274312143104.png").string(), cv::IMREAD_GRAYSCALE);
  if (left.empty() || right.empty()) return state.SkipWithError("EuRoC images missing");
  for (auto _ : state) benchmark::DoNotOptimize(rectifier.rectify(left, right).first.data);
}
BENCHMARK(BM_StereoRectifyPair)->Unit(benchmark::kMicrosecond);

void BM_DepthToMetres(benchmark::State& state) {
  cv::Mat raw(480, 640, CV_16U);
  cv::randu(raw, 0, 40000);
  for (auto _ : state) benchmark::DoNotOptimize(lumaslam::camera::depthToMetres(raw, 5000.0).data);
}
BENCHMARK(BM_DepthToMetres)->Unit(benchmark::kMicrosecond);

}  // namespace
