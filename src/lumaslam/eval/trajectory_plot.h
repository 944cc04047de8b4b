#pragma once
// SVG figure of an evaluation: the aligned estimate over ground truth seen from above (the
// two axes of largest extent, x-y for a ground vehicle in z-up coordinates), and the ATE
// along time.
#include <array>
#include <filesystem>

#include "lumaslam/eval/evaluation.h"
#include "lumaslam/eval/svg_document.h"

namespace lumaslam::eval {

// Indices (0 = x, 1 = y, 2 = z, ascending) of the two axes along which the positions of
// both trajectories spread the most.
std::array<int, 2> planeOfLargestExtent(const Trajectory& a, const Trajectory& b);

// Both throw Error when the report has no matched poses.
SvgDocument plotEvaluation(const EvaluationReport& report);  // top view and ATE along time

// The plane of the top view with its first axis kept and the dropped (least-extent) axis
// instead of the second: x-z for the top view x-y.
std::array<int, 2> sidePlane(const std::array<int, 2>& top);
// Top view (planeOfLargestExtent) beside the side view (sidePlane), equal scales.
SvgDocument plotTrajectoryViews(const EvaluationReport& report);
// The ATE of every matched pose along time, with the rmse line.
SvgDocument plotErrorOverTime(const EvaluationReport& report);

// Throws Error naming the path when it cannot be written.
void writeEvaluationPlot(const std::filesystem::path& path, const EvaluationReport& report);

}  // namespace lumaslam::eval
