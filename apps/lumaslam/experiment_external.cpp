#include "experiment_external.h"

#include <algorithm>

#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "experiment_cells.h"
#include "lumaslam/core/error.h"
#include "lumaslam/eval/evaluation.h"
#include "lumaslam/eval/trajectory_plot.h"
#include "lumaslam/io/dataset_reader.h"
#include "lumaslam/io/output_file.h"
#include "lumaslam/io/settings.h"
#include "lumaslam/io/trajectory_io.h"

namespace lumaslam::cli {
namespace {

const PlanDataset& datasetNamed(const Plan& plan, const std::string& name) {
  const auto it = std::find_if(plan.datasets.begin(), plan.datasets.end(),
                               [&](const PlanDataset& d) { return d.name == name; });
  if (it == plan.datasets.end()) fail("no dataset '{}' in the plan", name);
  return *it;
}

// As `lumaslam run` evaluates: default options, Sim3 for a monocular dataset. Synthetic
// datasets are RGB-D or stereo; others say it in their settings.
eval::EvaluationOptions evaluationOptionsFor(const PlanDataset& dataset) {
  eval::EvaluationOptions options;
  if (dataset.synth) return options;
  const auto settings_path = dataset.settings.empty()
                                 ? io::datasetPathOf(dataset.spec) / "settings.yaml"
                                 : dataset.settings;
  if (io::loadSettings(settings_path).sensor == io::SensorType::Monocular) {
    options.align = eval::AlignMode::Sim3;
  }
  return options;
}

struct DatasetTruth {
  Trajectory ground_truth;
  eval::EvaluationOptions options;
};

DatasetTruth truthOf(const Plan& plan, const PlanExternal& external) {
  const PlanDataset& dataset = datasetNamed(plan, external.dataset);
  try {
    DatasetTruth truth{io::openDataset(dataset.spec)->groundTruth(), evaluationOptionsFor(dataset)};
    if (truth.ground_truth.empty()) fail("{} has no ground truth", dataset.spec);
    return truth;
  } catch (const Error& e) {
    fail("{}: {}.dataset: '{}': {}", plan.file.string(), external.key, external.dataset, e.what());
  }
}

void writeSummary(const std::filesystem::path& folder, const PlanExternal& external,
                  const std::filesystem::path& file, const std::string& spec,
                  const eval::EvaluationReport& report) {
  const nlohmann::json summary = {
      {"status", "complete"},
      {"external", {{"trajectory", file.string()}, {"format", external.format}}},
      {"dataset", spec},
      {"frames", report.estimate_poses},
      {"tracked", report.matched_poses},
      {"evaluation", eval::toJson(report)}};
  io::OutputFile out(folder / "summary.json");
  out.stream() << summary.dump(2) << '\n';
  out.commit();
}

void evaluateExternal(const Plan& plan, const PlanExternal& external,
                      const std::filesystem::path& runs_dir) {
  const DatasetTruth truth = truthOf(plan, external);
  const auto format = io::parseTrajectoryFormat(external.format);
  const std::string& spec = datasetNamed(plan, external.dataset).spec;
  for (std::size_t k = 0; k < external.trajectories.size(); ++k) {
    const auto& file = external.trajectories[k];
    const Trajectory estimate = io::readTrajectory(file, format, external.times);
    eval::EvaluationReport report;
    try {
      report = eval::evaluate(estimate, truth.ground_truth, truth.options);
    } catch (const Error& e) {
      fail("{}: {}.trajectory: {} against {}: {}", plan.file.string(), external.key, file.string(),
           spec, e.what());
    }
    const auto folder = runFolder(runs_dir, external.dataset, external.name, int(k) + 1);
    std::filesystem::create_directories(folder);
    io::writeTrajectory(folder / "trajectory.txt", estimate);
    eval::writeEvaluationPlot(folder / "evaluation.svg", report);
    writeSummary(folder, external, file, spec, report);
    spdlog::info("experiment: external {} on {} run {}: ATE RMSE {:.4f} m over {} poses",
                 external.name, external.dataset, k + 1, report.ate.stats.rmse,
                 report.matched_poses);
  }
}

}  // namespace

void evaluateExternals(const Plan& plan, const std::filesystem::path& runs_dir) {
  for (const auto& external : plan.externals) evaluateExternal(plan, external, runs_dir);
}

}  // namespace lumaslam::cli
