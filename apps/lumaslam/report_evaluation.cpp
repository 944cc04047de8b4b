#include "report_evaluation.h"

#include "lumaslam/core/error.h"
#include "lumaslam/io/dataset_reader.h"
#include "lumaslam/io/settings.h"
#include "lumaslam/io/trajectory_io.h"

namespace lumaslam::cli {
namespace {

// As run_pipeline.cpp's evaluateAgainstGroundTruth: default options, Sim3 for monocular.
eval::EvaluationOptions evaluationOptions(const nlohmann::json& summary) {
  const auto settings = io::loadSettings(summary.at("settings").get<std::string>());
  eval::EvaluationOptions options;
  if (settings.sensor == io::SensorType::Monocular) options.align = eval::AlignMode::Sim3;
  return options;
}

}  // namespace

Reevaluation reevaluate(const RunFolder& run) {
  if (!run.summary.contains("evaluation")) {
    return {std::nullopt, "summary.json has no evaluation (the dataset has no ground truth)"};
  }
  try {
    const auto options = evaluationOptions(run.summary);
    const auto dataset = run.summary.at("dataset").get<std::string>();
    const Trajectory ground_truth = io::openDataset(dataset)->groundTruth();
    if (ground_truth.empty()) fail("{}: no ground truth any more", dataset);
    const Trajectory estimate = io::readTrajectory(run.dir / "trajectory.txt");
    return {eval::evaluate(estimate, ground_truth, options), {}};
  } catch (const std::exception& e) {
    return {std::nullopt, e.what()};
  }
}

}  // namespace lumaslam::cli
