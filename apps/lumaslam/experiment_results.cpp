#include "experiment_results.h"

#include <algorithm>
#include <fstream>
#include <variant>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/eval/error_stats.h"
#include "lumaslam/io/output_file.h"
#include "run_folder.h"

namespace lumaslam::cli {
namespace {

// Medians over frames of the stage columns of a run's timing.csv (none when it is unreadable).
std::map<std::string, double> stageMedians(const std::filesystem::path& timing_csv) {
  std::map<std::string, double> medians;
  const auto read = readTimingTable(timing_csv);
  const auto* table = std::get_if<TimingTable>(&read);
  if (!table || table->rows.empty()) return medians;
  for (const char* column : kStageColumns) {
    if (!table->has(column)) continue;
    try {
      medians[column] = eval::computeStats(table->numbers(column)).median;
    } catch (const Error&) {  // a field that is not a number: no median for the column
    }
  }
  return medians;
}

ResultRow rowOf(const ExperimentRun& run,
                const std::map<std::filesystem::path, std::string>& errors) {
  ResultRow row;
  row.dataset = run.dataset;
  row.config = run.config;
  row.run = run.run;
  row.status = "not run";
  if (const auto error = errors.find(run.options.out); error != errors.end()) {
    row.status = "error: " + error->second;
    return row;  // a summary.json there is from an earlier run
  }
  std::ifstream in(run.options.out / "summary.json");
  const auto summary = in ? nlohmann::json::parse(in, nullptr, false) : nlohmann::json();
  if (!summary.is_object()) return row;
  row.status = summary.value("status", "unknown");
  row.frames = summary.value("frames", 0);
  row.tracked = summary.value("tracked", 0);
  if (summary.contains("ms_per_frame")) {
    row.ms_per_frame_median = summary["ms_per_frame"].value("median", 0.0);
  }
  row.stage_ms_median = stageMedians(run.options.out / "timing.csv");
  if (summary.contains("evaluation")) {
    const auto& ate = summary["evaluation"]["ate"];
    row.ate = AteStats{ate.value("rmse", 0.0), ate.value("mean", 0.0), ate.value("median", 0.0),
                       ate.value("std", 0.0)};
  }
  return row;
}

std::optional<double> stageOf(const ResultRow& row, const char* column) {
  const auto it = row.stage_ms_median.find(column);
  return it == row.stage_ms_median.end() ? std::nullopt : std::optional<double>(it->second);
}

// Shortest text that reads back to the same double; empty when there is no value.
template <typename T>
std::string cell(const std::optional<T>& value) {
  return value ? fmt::format("{}", *value) : std::string();
}

std::string csvField(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

void writeResultsCsv(const std::vector<ResultRow>& rows, const std::filesystem::path& file) {
  io::OutputFile out(file);
  out.stream() << "dataset,config,run,status,frames,tracked,ate_rmse,ate_mean,ate_median,ate_std,"
                  "ms_per_frame_median";
  for (const char* column : kStageColumns) out.stream() << ',' << column << "_median";
  out.stream() << '\n';
  for (const auto& r : rows) {
    const auto ate = [&](double AteStats::*field) {
      return r.ate ? fmt::format("{}", (*r.ate).*field) : std::string();
    };
    out.stream() << fmt::format("{},{},{},{},{},{},{},{},{},{},{}", csvField(r.dataset),
                                csvField(r.config), r.run, csvField(r.status), cell(r.frames),
                                cell(r.tracked), ate(&AteStats::rmse), ate(&AteStats::mean),
                                ate(&AteStats::median), ate(&AteStats::std),
                                cell(r.ms_per_frame_median));
    for (const char* column : kStageColumns) out.stream() << ',' << cell(stageOf(r, column));
    out.stream() << '\n';
  }
  out.commit();
}

template <typename T>
nlohmann::json orNull(const std::optional<T>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

void writeResultsJson(const std::vector<ResultRow>& rows, const std::filesystem::path& file) {
  nlohmann::json table = nlohmann::json::array();
  for (const auto& r : rows) {
    nlohmann::json ate = nullptr;
    if (r.ate) {
      ate = {{"rmse", r.ate->rmse},
             {"mean", r.ate->mean},
             {"median", r.ate->median},
             {"std", r.ate->std}};
    }
    table.push_back({{"dataset", r.dataset},
                     {"config", r.config},
                     {"run", r.run},
                     {"status", r.status},
                     {"frames", orNull(r.frames)},
                     {"tracked", orNull(r.tracked)},
                     {"ate", ate},
                     {"ms_per_frame_median", orNull(r.ms_per_frame_median)},
                     {"stage_ms_median", r.stage_ms_median}});
  }
  io::OutputFile out(file);
  out.stream() << nlohmann::json{{"runs", table}}.dump(2) << '\n';
  out.commit();
}

struct Spread {
  std::optional<double> min, median, max;
};

Spread spreadOf(std::vector<double> values) {
  if (values.empty()) return {};
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  const double median = n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
  return {values.front(), median, values.back()};
}

// One line per (dataset, config), over its complete runs; ATE only when each of them has one
// (a spread over some of the runs would mislead).
std::string summaryLine(const std::vector<const ResultRow*>& cell_rows) {
  std::size_t complete = 0;
  std::vector<double> ate, tracked;
  for (const ResultRow* r : cell_rows) {
    if (r->status != "complete") continue;
    ++complete;
    if (r->ate) ate.push_back(r->ate->rmse);
    if (r->tracked) tracked.push_back(*r->tracked);
  }
  const Spread a = ate.size() == complete ? spreadOf(ate) : Spread{};
  const Spread t = spreadOf(tracked);
  return fmt::format("{},{},{},{},{},{},{},{},{},{}\n", csvField(cell_rows.front()->dataset),
                     csvField(cell_rows.front()->config), cell_rows.size(), complete, cell(a.min),
                     cell(a.median), cell(a.max), cell(t.min), cell(t.median), cell(t.max));
}

void writeSummaryCsv(const std::vector<ResultRow>& rows, const std::filesystem::path& file) {
  io::OutputFile out(file);
  out.stream() << "dataset,config,runs,complete,ate_rmse_min,ate_rmse_median,ate_rmse_max,"
                  "tracked_min,tracked_median,tracked_max\n";
  std::vector<const ResultRow*> cell_rows;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    cell_rows.push_back(&rows[i]);
    if (i + 1 < rows.size() && sameCell(rows[i + 1], rows[i])) continue;
    out.stream() << summaryLine(cell_rows);
    cell_rows.clear();
  }
  out.commit();
}

}  // namespace

bool sameCell(const ResultRow& a, const ResultRow& b) {
  return a.dataset == b.dataset && a.config == b.config;
}

std::vector<ResultRow> collectResults(const std::vector<ExperimentRun>& runs,
                                      const std::map<std::filesystem::path, std::string>& errors) {
  std::vector<ResultRow> rows;
  for (const auto& run : runs) rows.push_back(rowOf(run, errors));
  return rows;
}

void writeResults(const std::vector<ResultRow>& rows, const std::filesystem::path& dir) {
  writeResultsCsv(rows, dir / "results.csv");
  writeResultsJson(rows, dir / "results.json");
  writeSummaryCsv(rows, dir / "summary.csv");
}

}  // namespace lumaslam::cli
