#include "run_repeat.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/io/output_file.h"

namespace lumaslam::cli {
namespace {

struct Spread {
  double min = 0, median = 0, max = 0;
};

Spread spreadOf(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  const double median = n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
  return {values.front(), median, values.back()};
}

nlohmann::json toJson(const Spread& s) {
  return {{"min", s.min}, {"median", s.median}, {"max", s.max}};
}

nlohmann::json readSummary(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) fail("{}: run summary not found", path.string());
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    fail("{}: unreadable run summary: {}", path.string(), e.what());
  }
}

}  // namespace

int runRepeated(const RunOptions& options, int repeats) {
  if (repeats < 1) fail("--repeat must be at least 1, got {}", repeats);
  io::requireWritableFolder(options.out);
  removeEarlierOutputs(options.out);  // no single run's files beside run_K/
  std::vector<double> tracked, ms_median, ate_rmse;
  nlohmann::json runs = nlohmann::json::array();
  for (int k = 1; k <= repeats; ++k) {
    RunOptions run = options;
    run.out = options.out / fmt::format("run_{}", k);
    std::printf("run %d/%d -> %s\n", k, repeats, run.out.string().c_str());
    if (const int code = runPipeline(run); code != 0) return code;
    const auto summary = readSummary(run.out / "summary.json");
    tracked.push_back(summary.at("tracked").get<double>());
    ms_median.push_back(summary.at("ms_per_frame").at("median").get<double>());
    nlohmann::json entry = {{"out", run.out.string()},
                            {"tracked", summary.at("tracked")},
                            {"ms_per_frame_median", summary.at("ms_per_frame").at("median")}};
    if (summary.contains("evaluation")) {
      const double rmse = summary["evaluation"].at("ate").at("rmse").get<double>();
      ate_rmse.push_back(rmse);
      entry["ate_rmse"] = rmse;
    }
    runs.push_back(entry);
  }

  nlohmann::json report = {{"dataset", options.dataset},
                           {"repeats", repeats},
                           {"runs", runs},
                           {"tracked", toJson(spreadOf(tracked))},
                           {"ms_per_frame_median", toJson(spreadOf(ms_median))}};
  std::printf("\n%d runs            min      median   max\n", repeats);
  const auto print = [](const char* name, const Spread& s, double scale) {
    std::printf("%-16s %8.3f %8.3f %8.3f\n", name, s.min * scale, s.median * scale, s.max * scale);
  };
  print("tracked frames", spreadOf(tracked), 1.0);
  print("ms/frame median", spreadOf(ms_median), 1.0);
  // ATE only when every run could be evaluated; a partial spread would mislead.
  if (ate_rmse.size() == static_cast<std::size_t>(repeats)) {
    report["ate_rmse"] = toJson(spreadOf(ate_rmse));
    print("ATE RMSE [mm]", spreadOf(ate_rmse), 1000.0);
  }
  io::OutputFile file(options.out / "repeatability.json");
  file.stream() << report.dump(2) << '\n';
  file.commit();
  std::printf("spread in %s\n", (options.out / "repeatability.json").string().c_str());
  return 0;
}

}  // namespace lumaslam::cli
