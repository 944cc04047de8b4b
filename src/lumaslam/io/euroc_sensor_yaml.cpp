#include "lumaslam/io/euroc_sensor_yaml.h"

#include <algorithm>
#include <array>

#include "lumaslam/core/error.h"
#include "lumaslam/core/settings_file.h"
#include "lumaslam/io/rotation_projection.h"

namespace lumaslam::io {

namespace {
std::vector<double> listOfSize(const core::SettingsFile& yaml, std::string_view key,
                               std::size_t size) {
  const auto values = yaml.get<std::vector<double>>(key);
  if (values.size() != size)
    yaml.invalid(key, fmt::format("expected {} numbers, found {}", size, values.size()));
  return values;
}

SE3 readTransform(const core::SettingsFile& yaml, std::string_view key) {
  const std::string prefix(key);
  if (yaml.get<int>(prefix + ".rows") != 4 || yaml.get<int>(prefix + ".cols") != 4)
    yaml.invalid(key, "expected a 4x4 matrix (rows: 4, cols: 4)");
  const auto data = listOfSize(yaml, prefix + ".data", 16);
  const Eigen::Matrix4d M =
      Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(data.data());
  if (!M.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1)))
    yaml.invalid(key, "last row must be 0 0 0 1");
  const auto rotation = projectToRotation(M.topLeftCorner<3, 3>(), 1e-3);
  if (!rotation) yaml.invalid(key, "the 3x3 part is not a rotation");
  SE3 T = SE3::Identity();
  T.linear() = *rotation;
  T.translation() = M.topRightCorner<3, 1>();
  return T;
}

// The coefficients k1 k2 p1 p2 [k3] of a radial-tangential model; nullopt for another model.
std::optional<std::array<double, 5>> radialTangential(const core::SettingsFile& yaml,
                                                      const std::string& model) {
  std::array<double, 5> distortion{};
  if (model == "none") return distortion;
  if (model != "radial-tangential") return std::nullopt;
  const auto values = yaml.get<std::vector<double>>("distortion_coefficients");
  if (values.size() != 4 && values.size() != 5) {
    yaml.invalid(
        "distortion_coefficients",
        fmt::format("expected 4 or 5 numbers (k1 k2 p1 p2 [k3]), found {}", values.size()));
  }
  std::copy(values.begin(), values.end(), distortion.begin());
  return distortion;
}
}  // namespace

EurocCamera readEurocCameraYaml(const std::filesystem::path& file) {
  const auto yaml = core::SettingsFile::open(file);
  const auto model = yaml.get<std::string>("camera_model", "pinhole");
  if (model != "pinhole")
    yaml.invalid("camera_model", fmt::format("'{}' is not supported (only pinhole)", model));

  EurocCamera result;
  camera::CameraSettings camera;
  const auto intrinsics = listOfSize(yaml, "intrinsics", 4);
  camera.fx = intrinsics[0];
  camera.fy = intrinsics[1];
  camera.cx = intrinsics[2];
  camera.cy = intrinsics[3];
  const auto resolution = listOfSize(yaml, "resolution", 2);
  camera.size = {static_cast<int>(resolution[0]), static_cast<int>(resolution[1])};
  camera.fps = yaml.get<double>("rate_hz", camera.fps);
  result.distortion_model = yaml.get<std::string>("distortion_model", "none");
  if (const auto distortion = radialTangential(yaml, result.distortion_model)) {
    camera.distortion = *distortion;
    result.camera = camera;
  }
  if (yaml.has("T_BS")) result.T_body_cam = readTransform(yaml, "T_BS");
  return result;
}

}  // namespace lumaslam::io
