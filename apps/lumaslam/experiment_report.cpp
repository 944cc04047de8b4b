#include "experiment_report.h"

#include <map>
#include <optional>

#include <fmt/format.h>

#include "experiment_heatmap.h"
#include "html_page.h"
#include "lumaslam/eval/error_stats.h"
#include "lumaslam/io/output_file.h"

namespace lumaslam::cli {
namespace {

// The complete runs of one dataset x configuration and what report.html shows of them.
struct CellRuns {
  std::string dataset, config;
  const ResultRow* first = nullptr;
  int runs = 0;
  std::vector<const ResultRow*> complete;
};

std::vector<CellRuns> cellsOf(const std::vector<ResultRow>& rows) {
  std::vector<CellRuns> cells;
  for (const auto& row : rows) {
    if (cells.empty() || !sameCell(*cells.back().first, row)) {
      cells.push_back({row.dataset, row.config, &row, 0, {}});
    }
    ++cells.back().runs;
    if (row.status == "complete") cells.back().complete.push_back(&row);
  }
  return cells;
}

std::optional<double> median(const std::vector<double>& values) {
  if (values.empty()) return std::nullopt;
  return eval::computeStats(values).median;
}

// Median of an ATE statistic over the complete runs; none unless each of them has an ATE.
std::optional<double> medianAte(const CellRuns& cell, double AteStats::*field) {
  std::vector<double> values;
  for (const ResultRow* r : cell.complete) {
    if (!r->ate) return std::nullopt;
    values.push_back((*r->ate).*field);
  }
  return median(values);
}

std::optional<double> medianMsPerFrame(const CellRuns& cell) {
  std::vector<double> values;
  for (const ResultRow* r : cell.complete) {
    if (r->ms_per_frame_median) values.push_back(*r->ms_per_frame_median);
  }
  return median(values);
}

// Median over the complete runs of a stage's per-run median; none unless each run has it.
std::optional<double> medianStageMs(const CellRuns& cell, const std::string& column) {
  std::vector<double> values;
  for (const ResultRow* r : cell.complete) {
    const auto it = r->stage_ms_median.find(column);
    if (it == r->stage_ms_median.end()) return std::nullopt;
    values.push_back(it->second);
  }
  return median(values);
}

// 100 x frames tracked / frames, over the complete runs.
std::optional<double> trackedPercent(const CellRuns& cell) {
  long long tracked = 0, frames = 0;
  for (const ResultRow* r : cell.complete) {
    tracked += r->tracked.value_or(0);
    frames += r->frames.value_or(0);
  }
  if (frames == 0) return std::nullopt;
  return 100.0 * static_cast<double>(tracked) / static_cast<double>(frames);
}

// A number of `cell` shown as `text`, with its data attributes; "–" without a value.
Cell numberCell(const CellRuns& cell, const std::string& key, std::optional<double> value,
                std::string text) {
  if (!value) return {"–"};
  return {std::move(text), key, value, cellAttributes(cell.dataset, cell.config)};
}

Cell mmCell(const CellRuns& cell, const std::string& key, std::optional<double> metres) {
  return numberCell(cell, key, metres, metres ? millimetres(*metres) : "");
}

Cell fixedCell(const CellRuns& cell, const std::string& key, std::optional<double> value,
               int decimals) {
  return numberCell(cell, key, value, value ? fmt::format("{:.{}f}", *value, decimals) : "");
}

// (baseline - config) / baseline x 100 of the median ATE RMSE in the same dataset.
std::optional<double> improvement(const CellRuns& cell, const std::vector<CellRuns>& cells,
                                  const std::string& baseline) {
  const auto ate = medianAte(cell, &AteStats::rmse);
  for (const auto& other : cells) {
    if (other.dataset != cell.dataset || other.config != baseline) continue;
    const auto base = medianAte(other, &AteStats::rmse);
    if (!ate || !base || *base <= 0) return std::nullopt;
    return (*base - *ate) / *base * 100.0;
  }
  return std::nullopt;
}

std::vector<Cell> resultRow(const CellRuns& cell, const std::vector<CellRuns>& cells,
                            const std::string& baseline) {
  Cell complete = Cell::count(static_cast<long long>(cell.complete.size()), "cell.complete");
  complete.text += fmt::format(" / {}", cell.runs);
  complete.attributes = cellAttributes(cell.dataset, cell.config);
  complete.attributes.emplace_back("data-runs", std::to_string(cell.runs));
  return {{cell.dataset},
          {cell.config == baseline ? cell.config + " (baseline)" : cell.config},
          mmCell(cell, "cell.ate_rmse", medianAte(cell, &AteStats::rmse)),
          mmCell(cell, "cell.ate_mean", medianAte(cell, &AteStats::mean)),
          mmCell(cell, "cell.ate_median", medianAte(cell, &AteStats::median)),
          mmCell(cell, "cell.ate_std", medianAte(cell, &AteStats::std)),
          fixedCell(cell, "cell.tracked_pct", trackedPercent(cell), 1),
          complete,
          fixedCell(cell, "cell.improvement_pct", improvement(cell, cells, baseline), 1)};
}

std::string resultsSection(const std::vector<CellRuns>& cells, const std::string& baseline) {
  std::vector<std::vector<Cell>> rows;
  for (const auto& cell : cells) rows.push_back(resultRow(cell, cells, baseline));
  return fmt::format(
             "<p>ATE in mm: the median over each cell's complete runs of their RMSE, mean, "
             "median and std. Tracked: frames tracked / frames of the complete runs. "
             "Improvement: (baseline &minus; configuration) / baseline &times; 100 of the median "
             "ATE RMSE, baseline <b>{}</b>.</p>\n",
             escapeHtml(baseline)) +
         htmlTable({"dataset", "configuration", "ATE RMSE (mm)", "mean", "median", "std",
                    "tracked %", "complete / runs", "improvement vs baseline %"},
                   rows);
}

std::string timingSection(const std::vector<CellRuns>& cells) {
  std::vector<std::vector<Cell>> rows;
  for (const auto& cell : cells) {
    std::vector<Cell> row{{cell.dataset},
                          {cell.config},
                          fixedCell(cell, "cell.ms_per_frame_median", medianMsPerFrame(cell), 2)};
    for (const char* column : kStageColumns) {
      row.push_back(
          fixedCell(cell, fmt::format("cell.{}_median", column), medianStageMs(cell, column), 2));
    }
    rows.push_back(std::move(row));
  }
  return "<p>Median over the complete runs of each run's median time per frame, in total and "
         "per module (timing.csv; detection wait: the tracking thread blocked on the detector; "
         "motion: the motion test).</p>\n" +
         htmlTable({"dataset", "configuration", "ms / frame", "enhance", "features", "tracking",
                    "mapping", "detection wait", "motion"},
                   rows);
}

std::string failuresSection(const std::vector<ResultRow>& rows) {
  std::vector<std::vector<Cell>> failed;
  for (const auto& r : rows) {
    if (r.status == "complete") continue;
    failed.push_back({{fmt::format("runs/{}/{}/run_{}", r.dataset, r.config, r.run)}, {r.status}});
  }
  if (failed.empty()) return "<p>None: every run is complete.</p>\n";
  return htmlTable({"run folder", "status"}, failed);
}

}  // namespace

void writeExperimentReport(const std::vector<ResultRow>& rows, const std::string& baseline,
                           const std::filesystem::path& dir) {
  const auto cells = cellsOf(rows);
  HtmlPage page("Experiment " + dir.filename().string());
  page.section("results", "Results per dataset and configuration", resultsSection(cells, baseline));
  page.section("heatmap", "ATE RMSE of every run", ateHeatmap(rows));
  page.section("timing", "Time per frame", timingSection(cells));
  page.section("failures", "Failures", failuresSection(rows));
  io::OutputFile out(dir / "report.html");
  out.stream() << page.str();
  out.commit();
}

}  // namespace lumaslam::cli
