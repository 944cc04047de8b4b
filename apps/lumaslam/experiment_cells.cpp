#include "experiment_cells.h"

#include <fstream>

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "experiment_settings.h"
#include "lumaslam/core/error.h"

namespace lumaslam::cli {
namespace {

std::string replaceAll(std::string text, const std::string& from, const std::string& to) {
  for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

RunOptions runOptions(const PlanDataset& dataset, const PlanConfig& config,
                      const std::filesystem::path& dir) {
  RunOptions o;
  o.dataset = dataset.spec;
  o.settings = config.settings.value_or(dataset.settings);
  if (config.changesSettings()) o.settings = configSettingsFile(dir, dataset.name, config.name);
  o.max_frames = dataset.max_frames;
  o.enhance_preset = config.enhance;
  if (config.detector) {
    const std::string folder = dataset.spec.substr(dataset.spec.find(':') + 1);
    o.detector = replaceAll(*config.detector, "{dataset}", folder);
  }
  o.vocabulary = config.vocabulary;
  o.sequential = config.sequential;
  o.no_loop_closing = !config.loop_closing;
  o.no_motion_evidence = !config.motion_evidence;
  return o;
}

void appendExternalRuns(const Plan& plan, const std::string& dataset,
                        const std::filesystem::path& runs_dir, std::vector<ExperimentRun>& runs) {
  for (const auto& external : plan.externals) {
    if (external.dataset != dataset) continue;
    for (int k = 1; k <= static_cast<int>(external.trajectories.size()); ++k) {
      ExperimentRun run{dataset, external.name, k, {}, true};
      run.options.out = runFolder(runs_dir, dataset, external.name, k);
      runs.push_back(std::move(run));
    }
  }
}

bool stoppedBySignal(int exit_code) {
  return exit_code > 128;
}

}  // namespace

std::filesystem::path runFolder(const std::filesystem::path& runs_dir, const std::string& dataset,
                                const std::string& config, int run) {
  return runs_dir / dataset / config / fmt::format("run_{}", run);
}

std::vector<ExperimentRun> experimentRuns(const Plan& plan, const std::filesystem::path& runs_dir) {
  std::vector<ExperimentRun> runs;
  for (const auto& dataset : plan.datasets) {
    for (const auto& config : plan.configs) {
      for (int k = 1; k <= plan.runs; ++k) {
        ExperimentRun run{dataset.name, config.name, k,
                          runOptions(dataset, config, runs_dir.parent_path())};
        run.options.out = runFolder(runs_dir, dataset.name, config.name, k);
        runs.push_back(std::move(run));
      }
    }
    appendExternalRuns(plan, dataset.name, runs_dir, runs);
  }
  return runs;
}

bool isComplete(const std::filesystem::path& run_folder) {
  std::ifstream in(run_folder / "summary.json");
  if (!in) return false;
  const auto summary = nlohmann::json::parse(in, nullptr, false);
  return summary.is_object() && summary.value("status", "") == "complete";
}

RunsOutcome runMissing(const std::vector<ExperimentRun>& runs) {
  RunsOutcome outcome;
  std::vector<const ExperimentRun*> missing;
  for (const auto& run : runs) {
    if (run.external) continue;
    if (isComplete(run.options.out)) {
      ++outcome.kept;
    } else {
      missing.push_back(&run);
    }
  }
  spdlog::info("experiment: {} runs, {} complete from before, {} to run",
               outcome.kept + missing.size(), outcome.kept, missing.size());
  if (missing.empty()) spdlog::info("experiment: every run is complete; no SLAM work to do");
  for (const ExperimentRun* run : missing) {
    spdlog::info("experiment: run {}/{} -> {}", outcome.done + 1, missing.size(),
                 run->options.out.string());
    try {
      const int code = runPipeline(run->options);
      if (code != 0) outcome.exit_code = code;
      if (stoppedBySignal(code)) return outcome;
    } catch (const Error& e) {
      spdlog::error("{}: {}", run->options.out.string(), e.what());
      outcome.errors[run->options.out] = e.what();
      outcome.exit_code = 1;
    }
    ++outcome.done;
  }
  return outcome;
}

}  // namespace lumaslam::cli
