#pragma once
// The heatmap of report.html (experiment_report.h): one row per dataset x configuration, one
// column per run index, each cell coloured by its ATE RMSE on one log scale for the whole table
// (green: best, red: worst; legend in mm), failed and not-run cells grey with their status.
#include <string>
#include <utility>
#include <vector>

#include "experiment_results.h"

namespace lumaslam::cli {

// An ATE in metres as report.html shows it: mm with 2 decimals.
std::string millimetres(double metres);

// data-dataset / data-config attributes of a number of one dataset x configuration.
std::vector<std::pair<std::string, std::string>> cellAttributes(const std::string& dataset,
                                                                const std::string& config);

// An HTML fragment: the legend and the table. Every run's cell carries data-dataset,
// data-config and data-run; one with an ATE also data-key="ate_rmse" and data-value (metres,
// as results.csv), the others data-status.
std::string ateHeatmap(const std::vector<ResultRow>& rows);

}  // namespace lumaslam::cli
