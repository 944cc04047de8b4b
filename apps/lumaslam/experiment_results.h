#pragma once
// The tables of an experiment, read back from each run's summary.json: DIR/results.csv and
// DIR/results.json (one row per run) and DIR/summary.csv (one row per dataset x config).
#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "experiment_cells.h"

namespace lumaslam::cli {

struct AteStats {
  double rmse = 0, mean = 0, median = 0, std = 0;
};

// The per-module time columns of timing.csv that the tables carry (medians over frames).
inline constexpr std::array<const char*, 6> kStageColumns = {
    "enhance_ms", "features_ms", "tracking_ms", "mapping_ms", "detection_wait_ms", "motion_ms"};

struct ResultRow {
  std::string dataset;
  std::string config;
  int run = 1;
  std::string status;  // the summary's, else the error, else "not run"
  std::optional<int> frames;
  std::optional<int> tracked;
  std::optional<AteStats> ate;  // only with ground truth
  std::optional<double> ms_per_frame_median;
  // kStageColumns -> median over the run's frames (a column timing.csv lacks is absent).
  std::map<std::string, double> stage_ms_median;
};

// True when both rows are runs of the same dataset x configuration (rows come grouped so).
bool sameCell(const ResultRow& a, const ResultRow& b);

std::vector<ResultRow> collectResults(const std::vector<ExperimentRun>& runs,
                                      const std::map<std::filesystem::path, std::string>& errors);

// Writes results.csv, results.json and summary.csv into `dir` (io::OutputFile each).
void writeResults(const std::vector<ResultRow>& rows, const std::filesystem::path& dir);

}  // namespace lumaslam::cli
