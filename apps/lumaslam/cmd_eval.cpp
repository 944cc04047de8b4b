// `lumaslam eval EST GT`: ATE/RPE of an estimated trajectory against ground truth, with the
// definitions of the evo tool (see docs/evaluation.md).
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "command_registry.h"
#include "lumaslam/core/error.h"
#include "lumaslam/eval/evaluation.h"
#include "lumaslam/eval/trajectory_plot.h"
#include "lumaslam/io/dataset_reader.h"
#include "lumaslam/io/output_file.h"
#include "lumaslam/io/trajectory_io.h"

namespace {

using namespace lumaslam;

struct EvalOptions {
  std::string estimate;
  std::string ground_truth;
  std::string estimate_format = "auto";
  std::string estimate_times;
  std::string align = "se3";
  double max_dt = 0.02;
  double rpe_delta = 1.0;
  std::string rpe_unit = "frames";
  bool rpe_all_pairs = false;
  std::string json_path;
  std::string plot_path;
};

void writeJson(const std::filesystem::path& path, const nlohmann::json& json) {
  io::OutputFile file(path);
  file.stream() << json.dump(2) << '\n';
  file.commit();
}

int runEval(const EvalOptions& options) {
  eval::EvaluationOptions settings;
  settings.align = eval::parseAlignMode(options.align);
  settings.max_dt = options.max_dt;
  settings.rpe = {.delta = options.rpe_delta,
                  .unit = eval::parseDeltaUnit(options.rpe_unit),
                  .all_pairs = options.rpe_all_pairs};

  const Trajectory estimate = io::readTrajectory(
      options.estimate, io::parseTrajectoryFormat(options.estimate_format), options.estimate_times);
  const Trajectory ground_truth = io::loadGroundTruth(options.ground_truth);
  spdlog::info("eval: {} estimate poses from {}, {} ground-truth poses from {}", estimate.size(),
               options.estimate, ground_truth.size(), options.ground_truth);

  eval::EvaluationReport report;
  try {
    report = eval::evaluate(estimate, ground_truth, settings);
  } catch (const Error& e) {
    fail("{} against {}: {}", options.estimate, options.ground_truth, e.what());
  }

  std::fputs(eval::formatTable(report).c_str(), stdout);
  if (!options.json_path.empty()) {
    nlohmann::json json = eval::toJson(report);
    json["estimate"] = options.estimate;
    json["ground_truth"] = options.ground_truth;
    writeJson(options.json_path, json);
    spdlog::info("eval: wrote {}", options.json_path);
  }
  if (!options.plot_path.empty()) {
    eval::writeEvaluationPlot(options.plot_path, report);
    spdlog::info("eval: wrote {}", options.plot_path);
  }
  return 0;
}

const bool registered = cli::registerCommand(
    "eval", "Compare an estimated trajectory with ground truth (ATE, RPE)",
    [](CLI::App& cmd) -> cli::Runner {
      auto options = std::make_shared<EvalOptions>();
      cmd.add_option("EST", options->estimate,
                     "Estimated trajectory file (TUM, EuRoC csv or KITTI; see --est-format)")
          ->required();
      cmd.add_option("GT", options->ground_truth,
                     "Ground truth: a trajectory file, or a dataset spec tum:PATH, euroc:PATH, "
                     "kitti:PATH (KITTI poses take their times from times.txt)")
          ->required();
      cmd.add_option("--align", options->align,
                     "Alignment before ATE: se3 (stereo, RGB-D), sim3 (monocular, with scale) "
                     "or none")
          ->check(CLI::IsMember({"none", "se3", "sim3"}))
          ->capture_default_str();
      cmd.add_option("--max-dt", options->max_dt,
                     "Largest timestamp difference [s] for an estimate/ground-truth pair")
          ->check(CLI::NonNegativeNumber)
          ->capture_default_str();
      cmd.add_option("--rpe-delta", options->rpe_delta,
                     "RPE pose-pair distance, in --rpe-unit (a whole number for frames)")
          ->check(CLI::PositiveNumber)
          ->capture_default_str();
      cmd.add_option("--rpe-unit", options->rpe_unit,
                     "frames: pairs delta matched poses apart; m: delta metres of ground-truth "
                     "path apart (evo --delta_unit m)")
          ->check(CLI::IsMember({"frames", "m"}))
          ->capture_default_str();
      cmd.add_flag("--rpe-all-pairs", options->rpe_all_pairs,
                   "Use every pose as an RPE start (evo --all_pairs), not consecutive pairs");
      cmd.add_option("--est-format", options->estimate_format,
                     "Format of EST: auto, tum, euroc or kitti")
          ->check(CLI::IsMember({"auto", "tum", "euroc", "kitti"}))
          ->capture_default_str();
      cmd.add_option("--est-times", options->estimate_times,
                     "times.txt giving the timestamps of a KITTI-format EST");
      cmd.add_option("--json", options->json_path, "Write the report as JSON to this file");
      cmd.add_option("--plot", options->plot_path,
                     "Write an SVG plot (trajectories seen from above, ATE along time)");
      return [options] { return runEval(*options); };
    });

}  // namespace
