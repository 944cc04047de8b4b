#pragma once
// numpy arrays <-> cv::Mat and 4x4 poses for the Python module. Images come in as numpy
// arrays (uint8 HxW or HxWx3 in Camera.RGB's order, depth uint16 or float32 HxW) and are copied, so
// that tracking can run without the GIL while Python may free or change the array.
#include <string>

#include <pybind11/numpy.h>
#include <opencv2/core/mat.hpp>

#include "lumaslam/camera_pose.h"

namespace lumaslam::python {

namespace py = pybind11;

// Throws py::type_error / py::value_error naming `what` and the shape or dtype that is wrong.
cv::Mat imageFromArray(const py::array& array, const std::string& what);
cv::Mat depthFromArray(const py::array& array, const std::string& what);

py::object arrayFromMat(const cv::Mat& mat);  // None for an empty Mat
py::array_t<double> poseArray(const Eigen::Matrix4d& pose);

// A trajectory as (timestamps (N,), poses (N, 4, 4)) and back.
py::tuple trajectoryArrays(const CameraTrajectory& trajectory);
CameraTrajectory trajectoryFromArrays(const py::handle& trajectory, const std::string& what);

}  // namespace lumaslam::python
