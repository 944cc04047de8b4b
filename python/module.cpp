#include "bindings.h"

PYBIND11_MODULE(lumaslam, module) {
  module.doc() =
      "lumaslam: visual SLAM for bad light and moving people (monocular, stereo, RGB-D).\n\n"
      "System tracks frames given as numpy arrays and returns 4x4 camera-to-world poses;\n"
      "Dataset reads TUM RGB-D, EuRoC, KITTI, image folders and videos; evaluate computes\n"
      "ATE and RPE as evo does. Errors raise RuntimeError (bad files, settings, calls),\n"
      "TypeError or ValueError (arrays of the wrong dtype or shape).";
  lumaslam::python::bindSystem(module);
  lumaslam::python::bindDataset(module);
  lumaslam::python::bindEvaluate(module);
}
