// `lumaslam experiment PLAN.yaml --out DIR`: every dataset x configuration x run of a plan
// into DIR/runs/, resumable, and the tables of the results (docs/experiments.md).
#include <cstdio>
#include <memory>

#include <spdlog/spdlog.h>

#include "command_registry.h"
#include "experiment_cells.h"
#include "experiment_data.h"
#include "experiment_plan.h"
#include "experiment_results.h"
#include "lumaslam/io/output_file.h"

namespace lumaslam::cli {
namespace {

struct ExperimentOptions {
  std::filesystem::path plan;
  std::filesystem::path out;
};

int runExperiment(const ExperimentOptions& options) {
  Plan plan = readPlan(options.plan);
  io::requireWritableFolder(options.out);
  prepareSynthData(plan, options.out / "data");
  const auto runs = experimentRuns(plan, options.out / "runs");
  const RunsOutcome outcome = runMissing(runs);
  const auto rows = collectResults(runs, outcome.errors);
  writeResults(rows, options.out);
  std::printf("experiment: %d runs done now, %d kept from before; results in %s\n", outcome.done,
              outcome.kept, (options.out / "results.csv").string().c_str());
  return outcome.exit_code;
}

const bool registered = registerCommand(
    "experiment",
    "Run every dataset x configuration x run of a plan (resumable) and tabulate the results",
    [](CLI::App& cmd) -> Runner {
      auto options = std::make_shared<ExperimentOptions>();
      cmd.add_option("PLAN", options->plan, "Experiment plan (YAML, docs/experiments.md)")
          ->required();
      cmd.add_option("--out", options->out,
                     "Experiment folder: data/, runs/, results.csv, results.json, summary.csv")
          ->required();
      return [options] { return runExperiment(*options); };
    });

}  // namespace
}  // namespace lumaslam::cli
