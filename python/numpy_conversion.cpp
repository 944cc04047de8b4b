#include "numpy_conversion.h"

#include <cstring>

#include <opencv2/core.hpp>

namespace lumaslam::python {

namespace {

std::string shapeOf(const py::array& array) {
  std::string shape = "(";
  for (py::ssize_t i = 0; i < array.ndim(); ++i) {
    shape += (i ? ", " : "") + std::to_string(array.shape(i));
  }
  return shape + (array.ndim() == 1 ? ",)" : ")");
}

// A copy of a C-contiguous 2-D or 3-D array as a Mat of `depth` (CV_8U, CV_16U, CV_32F).
cv::Mat copyToMat(const py::array& array, int depth) {
  const py::array contiguous =
      py::array::ensure(array, py::array::c_style);  // a view when already contiguous
  const int rows = static_cast<int>(contiguous.shape(0));
  const int cols = static_cast<int>(contiguous.shape(1));
  const int channels = contiguous.ndim() == 3 ? static_cast<int>(contiguous.shape(2)) : 1;
  cv::Mat mat(rows, cols, CV_MAKETYPE(depth, channels));
  std::memcpy(mat.data, contiguous.data(), mat.total() * mat.elemSize());
  return mat;
}

}  // namespace

cv::Mat imageFromArray(const py::array& array, const std::string& what) {
  const bool gray = array.ndim() == 2;
  const bool colour = array.ndim() == 3 && array.shape(2) == 3;
  if (!gray && !colour) {
    throw py::value_error(what + ": expected an HxW (gray) or HxWx3 (colour) image, got shape " +
                          shapeOf(array));
  }
  if (!array.dtype().is(py::dtype::of<std::uint8_t>())) {
    throw py::type_error(what + ": expected dtype uint8, got " +
                         std::string(py::str(array.dtype())));
  }
  return copyToMat(array, CV_8U);
}

cv::Mat depthFromArray(const py::array& array, const std::string& what) {
  if (array.ndim() != 2) {
    throw py::value_error(what + ": expected an HxW depth image, got shape " + shapeOf(array));
  }
  if (array.dtype().is(py::dtype::of<std::uint16_t>())) return copyToMat(array, CV_16U);
  if (array.dtype().is(py::dtype::of<float>())) return copyToMat(array, CV_32F);
  throw py::type_error(what + ": expected dtype uint16 (raw, divided by DepthMapFactor) or " +
                       "float32 (metres), got " + std::string(py::str(array.dtype())));
}

py::object arrayFromMat(const cv::Mat& mat) {
  if (mat.empty()) return py::none();
  const cv::Mat m = mat.isContinuous() ? mat : mat.clone();
  std::vector<py::ssize_t> shape{m.rows, m.cols};
  if (m.channels() > 1) shape.push_back(m.channels());
  py::dtype dtype;
  switch (m.depth()) {
    case CV_8U:
      dtype = py::dtype::of<std::uint8_t>();
      break;
    case CV_16U:
      dtype = py::dtype::of<std::uint16_t>();
      break;
    case CV_32F:
      dtype = py::dtype::of<float>();
      break;
    default:
      throw py::type_error("image of an OpenCV type with no numpy counterpart");
  }
  py::array array(dtype, shape);
  std::memcpy(array.mutable_data(), m.data, m.total() * m.elemSize());
  return array;
}

py::array_t<double> poseArray(const Eigen::Matrix4d& pose) {
  py::array_t<double> array({4, 4});
  auto view = array.mutable_unchecked<2>();
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) view(r, c) = pose(r, c);
  }
  return array;
}

py::tuple trajectoryArrays(const CameraTrajectory& trajectory) {
  const auto n = static_cast<py::ssize_t>(trajectory.size());
  py::array_t<double> timestamps(n);
  py::array_t<double> poses({n, py::ssize_t{4}, py::ssize_t{4}});
  auto t = timestamps.mutable_unchecked<1>();
  auto p = poses.mutable_unchecked<3>();
  for (py::ssize_t i = 0; i < n; ++i) {
    t(i) = trajectory[i].timestamp;
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) p(i, r, c) = trajectory[i].T_w_c(r, c);
    }
  }
  return py::make_tuple(timestamps, poses);
}

CameraTrajectory trajectoryFromArrays(const py::handle& trajectory, const std::string& what) {
  const auto pair = py::reinterpret_borrow<py::sequence>(trajectory);
  if (py::len(pair) != 2) {
    throw py::value_error(what + ": expected (timestamps (N,), poses (N, 4, 4))");
  }
  const auto timestamps = py::array_t<double, py::array::c_style | py::array::forcecast>(pair[0]);
  const auto poses = py::array_t<double, py::array::c_style | py::array::forcecast>(pair[1]);
  if (timestamps.ndim() != 1 || poses.ndim() != 3 || poses.shape(1) != 4 || poses.shape(2) != 4 ||
      poses.shape(0) != timestamps.shape(0)) {
    throw py::value_error(what + ": expected timestamps (N,) and poses (N, 4, 4), got " +
                          shapeOf(timestamps) + " and " + shapeOf(poses));
  }
  const auto t = timestamps.unchecked<1>();
  const auto p = poses.unchecked<3>();
  CameraTrajectory out(static_cast<std::size_t>(t.shape(0)));
  for (py::ssize_t i = 0; i < t.shape(0); ++i) {
    out[i].timestamp = t(i);
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) out[i].T_w_c(r, c) = p(i, r, c);
    }
  }
  return out;
}

}  // namespace lumaslam::python
