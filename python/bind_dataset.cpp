#include <optional>
#include <string>

#include <pybind11/stl.h>

#include "bindings.h"
#include "lumaslam/dataset.h"
#include "numpy_conversion.h"

namespace lumaslam::python {

namespace {

// A frame with its images as numpy arrays (None where the dataset has none).
struct PyFrame {
  std::size_t index = 0;
  double timestamp = 0.0;
  py::object image, right, depth;
};

std::optional<PyFrame> nextFrame(Dataset& dataset) {
  std::optional<DatasetFrame> frame;
  {
    const py::gil_scoped_release no_gil;  // reads and decodes the image files
    frame = dataset.next();
  }
  if (!frame) return std::nullopt;
  return PyFrame{frame->index, frame->timestamp, arrayFromMat(frame->image),
                 arrayFromMat(frame->right), arrayFromMat(frame->depth)};
}

}  // namespace

void bindDataset(py::module_& module) {
  py::class_<PyFrame>(module, "DatasetFrame", "One frame of a Dataset.")
      .def_readonly("index", &PyFrame::index)
      .def_readonly("timestamp", &PyFrame::timestamp, "Seconds.")
      .def_readonly("image", &PyFrame::image,
                    "Left / rgb image: uint8 BGR (TUM, folders, videos) or gray (EuRoC, KITTI).")
      .def_readonly("right", &PyFrame::right, "Right image (stereo), else None.")
      .def_readonly("depth", &PyFrame::depth, "uint16 depth as stored (RGB-D), else None.");

  py::class_<Dataset>(module, "Dataset", R"doc(
A dataset on disk, read one frame at a time; iterate over it for DatasetFrame objects.

spec as `lumaslam run --dataset`: "tum:PATH", "euroc:PATH", "kitti:PATH", "folder:PATH",
"video:FILE", ... Raises RuntimeError naming the missing or malformed file.)doc")
      .def(py::init<const std::string&, std::optional<std::size_t>>(), py::arg("spec"),
           py::arg("max_frames") = py::none())
      .def("__len__", &Dataset::size)
      .def("__iter__", [](Dataset& d) -> Dataset& { return d; })
      .def("__next__",
           [](Dataset& d) {
             auto frame = nextFrame(d);
             if (!frame) throw py::stop_iteration();
             return std::move(*frame);
           })
      .def_property_readonly("name", &Dataset::name)
      .def_property_readonly("is_stereo", &Dataset::isStereo)
      .def_property_readonly("has_depth", &Dataset::hasDepth)
      .def(
          "ground_truth", [](const Dataset& d) { return trajectoryArrays(d.groundTruth()); },
          "Camera poses (timestamps (N,), poses (N, 4, 4)); empty arrays when there are none.");
}

}  // namespace lumaslam::python
