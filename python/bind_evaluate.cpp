#include <string>

#include "bindings.h"
#include "lumaslam/evaluate.h"
#include "numpy_conversion.h"

namespace lumaslam::python {

namespace {

Alignment parseAlignment(const std::string& name) {
  if (name == "none") return Alignment::None;
  if (name == "se3") return Alignment::SE3;
  if (name == "sim3") return Alignment::Sim3;
  throw py::value_error("alignment: expected 'se3', 'sim3' or 'none', got '" + name + "'");
}

py::dict summaryDict(const ErrorSummary& s) {
  py::dict d;
  d["rmse"] = s.rmse;
  d["mean"] = s.mean;
  d["median"] = s.median;
  d["std"] = s.std;
  d["min"] = s.min;
  d["max"] = s.max;
  d["count"] = s.count;
  return d;
}

py::dict errorsDict(const TrajectoryErrors& errors) {
  py::dict d;
  d["ate"] = summaryDict(errors.ate);
  d["rpe_translation"] = summaryDict(errors.rpe_translation);
  d["rpe_rotation_deg"] = summaryDict(errors.rpe_rotation_deg);
  d["matched_poses"] = errors.matched_poses;
  d["coverage"] = errors.coverage;
  d["scale"] = errors.scale;
  return d;
}

}  // namespace

void bindEvaluate(py::module_& module) {
  module.def(
      "evaluate",
      [](const py::object& estimate, const py::object& ground_truth, const std::string& alignment,
         double max_dt, double rpe_delta) {
        ErrorOptions options;
        options.alignment = parseAlignment(alignment);
        options.max_dt = max_dt;
        options.rpe_delta = rpe_delta;
        const CameraTrajectory est = trajectoryFromArrays(estimate, "estimate");
        const CameraTrajectory gt = trajectoryFromArrays(ground_truth, "ground_truth");
        TrajectoryErrors errors;
        {
          const py::gil_scoped_release no_gil;
          errors = evaluate(est, gt, options);
        }
        return errorsDict(errors);
      },
      py::arg("estimate"), py::arg("ground_truth"), py::kw_only(), py::arg("alignment") = "se3",
      py::arg("max_dt") = 0.02, py::arg("rpe_delta") = 1.0, R"doc(
ATE and RPE of an estimate against ground truth, as `lumaslam eval` and evo compute them.

Both are (timestamps (N,), poses (N, 4, 4)) as System.trajectory() returns. alignment: "se3"
(stereo, RGB-D), "sim3" (monocular) or "none"; max_dt: association window in seconds;
rpe_delta: frames between the poses of an RPE pair. Returns a dict: ate, rpe_translation
(metres), rpe_rotation_deg, each {rmse, mean, median, std, min, max, count}, plus
matched_poses, coverage and scale.)doc");
}

}  // namespace lumaslam::python
