#include "experiment_heatmap.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "html_page.h"

namespace lumaslam::cli {
namespace {

constexpr const char* kGrey = "#cccccc";
constexpr int kLegendSteps = 5;

bool hasAte(const ResultRow& row) {
  return row.status == "complete" && row.ate.has_value();
}

// log(ATE) from the best (green) to the worst (red) run of the whole table.
struct ColourScale {
  double best = 0, worst = 0;

  std::string colour(double ate) const {
    const double span = std::log(worst) - std::log(best);
    const double t = span > 0 ? (std::log(std::max(ate, best)) - std::log(best)) / span : 0.0;
    return fmt::format("hsl({:.0f}, 70%, 62%)", 120.0 * (1.0 - std::clamp(t, 0.0, 1.0)));
  }
  double step(int i) const {  // the legend's i-th value, geometric from best to worst
    return best * std::pow(worst / best, static_cast<double>(i) / (kLegendSteps - 1));
  }
};

std::optional<ColourScale> scaleOf(const std::vector<ResultRow>& rows) {
  std::optional<ColourScale> scale;
  for (const auto& row : rows) {
    if (!hasAte(row)) continue;
    const double ate = std::max(row.ate->rmse, 1e-12);  // log scale: no zero
    if (!scale) scale = ColourScale{ate, ate};
    scale->best = std::min(scale->best, ate);
    scale->worst = std::max(scale->worst, ate);
  }
  return scale;
}

std::string legend(const ColourScale& scale) {
  std::vector<Cell> swatches;
  for (int i = 0; i < kLegendSteps; ++i) {
    const double ate = scale.step(i);
    swatches.push_back(
        {millimetres(ate), "legend.ate_rmse", ate, {{"style", "background:" + scale.colour(ate)}}});
  }
  swatches.push_back(
      {"failed / not run", "", std::nullopt, {{"style", "background:" + std::string(kGrey)}}});
  return "<p>ATE RMSE (mm), log scale from the best to the worst run:</p>\n" +
         htmlTable({"best", "", "", "", "worst", ""}, {swatches});
}

Cell runCell(const ResultRow& row, const std::optional<ColourScale>& scale) {
  auto attributes = cellAttributes(row.dataset, row.config);
  attributes.emplace_back("data-run", std::to_string(row.run));
  if (hasAte(row) && scale) {
    attributes.emplace_back("style", "background:" + scale->colour(row.ate->rmse));
    return {millimetres(row.ate->rmse), "ate_rmse", row.ate->rmse, attributes};
  }
  attributes.emplace_back("data-status", row.status);
  attributes.emplace_back("style", "background:" + std::string(kGrey));
  return {row.status, "", std::nullopt, attributes};
}

// One table row per dataset x configuration (rows are grouped so), one column per run index.
std::vector<std::vector<Cell>> heatmapRows(const std::vector<ResultRow>& rows, int runs,
                                           const std::optional<ColourScale>& scale) {
  std::vector<std::vector<Cell>> table;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (i == 0 || !sameCell(rows[i], rows[i - 1])) {
      table.push_back({{rows[i].dataset + " / " + rows[i].config}});
      table.back().resize(1 + runs, Cell{});
    }
    if (rows[i].run >= 1 && rows[i].run <= runs) {
      table.back()[rows[i].run] = runCell(rows[i], scale);
    }
  }
  return table;
}

}  // namespace

std::string millimetres(double metres) {
  return fmt::format("{:.2f}", 1000.0 * metres);
}

std::vector<std::pair<std::string, std::string>> cellAttributes(const std::string& dataset,
                                                                const std::string& config) {
  return {{"data-dataset", dataset}, {"data-config", config}};
}

std::string ateHeatmap(const std::vector<ResultRow>& rows) {
  int runs = 0;
  for (const auto& row : rows) runs = std::max(runs, row.run);
  const auto scale = scaleOf(rows);
  std::vector<std::string> header = {"dataset / configuration"};
  for (int k = 1; k <= runs; ++k) header.push_back(fmt::format("run {}", k));
  const std::string html = htmlTable(header, heatmapRows(rows, runs, scale));
  if (!scale) return htmlNote("No run has an ATE (no complete run with ground truth).") + html;
  return legend(*scale) + html;
}

}  // namespace lumaslam::cli
