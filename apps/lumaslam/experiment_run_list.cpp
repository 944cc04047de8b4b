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
  run.external = entry.value("external", false);
  run.options.out = runFolder(dir / "runs", run.dataset, run.config, run.run);
  return run;
}

}  // namespace

void writeRunList(const Plan& plan, const std::vector<ExperimentRun>& runs,
                  const std::filesystem::path& dir) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& run : runs) {
    nlohmann::json entry{{"dataset", run.dataset}, {"config", run.config}, {"run", run.run}};
    if (run.external) entry["external"] = true;
    list.push_back(std::move(entry));
  }
  io::OutputFile out(dir / kRunList);
  const nlohmann::json json{
      {"plan", plan.file.string()}, {"baseline", plan.baseline}, {"runs", list}};
  out.stream() << json.dump(2) << '\n';
  out.commit();
}

RunList readRunList(const std::filesystem::path& dir) {
  const auto file = dir / kRunList;
  std::ifstream in(file);
  if (!in) {
    fail("{}: not an experiment folder: no {} (written by `lumaslam experiment PLAN --out {}`)",
         dir.string(), kRunList, dir.string());
  }
  const auto json = nlohmann::json::parse(in, nullptr, false);
  RunList list;
  try {
    for (const auto& entry : json.at("runs")) list.runs.push_back(runOf(entry, dir));
    const std::string first = list.runs.empty() ? std::string() : list.runs.front().config;
    list.baseline = json.value("baseline", first);
  } catch (const nlohmann::json::exception& e) {
    fail("{}: not a list of runs: {}", file.string(), e.what());
  }
  return list;
}

}  // namespace lumaslam::cli
