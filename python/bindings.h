#pragma once
// The parts of the Python module `lumaslam` (docs/api.md, "Python"), one file each.
#include <pybind11/pybind11.h>

namespace lumaslam::python {

void bindSystem(pybind11::module_& module);    // System, SystemConfig options, TrackResult
void bindDataset(pybind11::module_& module);   // Dataset, DatasetFrame
void bindEvaluate(pybind11::module_& module);  // evaluate()

}  // namespace lumaslam::python
