#pragma once
// DIR/report.html of `lumaslam experiment` and `experiment collect` (docs/experiments.md): per
// dataset x configuration the ATE (median over its complete runs), tracked %, complete runs and
// the improvement vs the baseline configuration; the heatmap of every run's ATE
// (experiment_heatmap.h); the median time per frame; the failures. Self-contained (html_page.h).
// Numbers carry data-key, data-value (exact; ATE in metres as results.csv) and data-dataset /
// data-config (/ data-run) attributes.
#include <filesystem>
#include <string>
#include <vector>

#include "experiment_results.h"

namespace lumaslam::cli {

// Writes DIR/report.html (io::OutputFile); `rows` as collectResults gives them (grouped by
// dataset x configuration), `baseline` the configuration compared with.
void writeExperimentReport(const std::vector<ResultRow>& rows, const std::string& baseline,
                           const std::filesystem::path& dir);

}  // namespace lumaslam::cli
