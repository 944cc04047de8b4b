#include "experiment_run_list.h"

#include <fstream>

#include <nlohmann/json.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/io/output_file.h"

namespace lumaslam::cli {
namespace {

constexpr const char* kRunList = "plan_runs.json";

ExperimentRun runOf(const nlohmann::json& entry, const std::filesystem::path& dir) {
  ExperimentRun run;
  run.dataset = entry.at("dataset").get<std::string>();
  run.config = entry.at("config").get<std::string>();
  run.run = entry.at("run").get<int>();
  run.options.out = runFolder(dir / "runs", run.dataset, run.config, run.run);
  return run;
}

}  // namespace

void writeRunList(const std::filesystem::path& plan_file, const std::vector<ExperimentRun>& runs,
                  const std::filesystem::path& dir) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& run : runs) {
    list.push_back({{"dataset", run.dataset}, {"config", run.config}, {"run", run.run}});
  }
  io::OutputFile out(dir / kRunList);
  out.stream() << nlohmann::json{{"plan", plan_file.string()}, {"runs", list}}.dump(2) << '\n';
  out.commit();
}

std::vector<ExperimentRun> readRunList(const std::filesystem::path& dir) {
  const auto file = dir / kRunList;
  std::ifstream in(file);
  if (!in) {
    fail("{}: not an experiment folder: no {} (written by `lumaslam experiment PLAN --out {}`)",
         dir.string(), kRunList, dir.string());
  }
  const auto json = nlohmann::json::parse(in, nullptr, false);
  std::vector<ExperimentRun> runs;
  try {
    for (const auto& entry : json.at("runs")) runs.push_back(runOf(entry, dir));
  } catch (const nlohmann::json::exception& e) {
    fail("{}: not a list of runs: {}", file.string(), e.what());
  }
  return runs;
}

}  // namespace lumaslam::cli
