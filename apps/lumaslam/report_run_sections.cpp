// runSection and evaluationSection of report_sections.h.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "html_page.h"
#include "lumaslam/eval/trajectory_plot.h"
#include "report_sections.h"

namespace lumaslam::cli {
namespace {

// The summary's value at `key` as shown: text as is, numbers as JSON prints them.
Cell valueCell(const nlohmann::json& summary, const std::string& key) {
  if (!summary.contains(key)) return {"(not recorded)", key, std::nullopt};
  const auto& value = summary[key];
  if (value.is_string()) return {value.get<std::string>(), key, std::nullopt};
  if (value.is_null()) return {"(not set)", key, std::nullopt};
  if (value.is_number()) return {value.dump(), key, value.get<double>()};
  return {value.dump(), key, std::nullopt};
}

std::string detectorName(const nlohmann::json& summary) {
  if (!summary.contains("detector") || !summary["detector"].is_object()) return "(not recorded)";
  return summary["detector"].value("name", "(not recorded)");
}

std::string mapsTable(const nlohmann::json& maps) {
  std::vector<std::vector<Cell>> rows;
  for (const auto& map : maps) {
    const std::string id = map.value("id", nlohmann::json()).dump();
    rows.push_back({{id + (map.value("main", false) ? " (main)" : ""), "", std::nullopt},
                    Cell::count(map.value("frames", 0LL), "maps." + id + ".frames"),
                    Cell::number(map.value("first_timestamp", 0.0), "", 3),
                    Cell::number(map.value("last_timestamp", 0.0), "", 3),
                    {map.value("trajectory", ""), "", std::nullopt}});
  }
  return htmlTable({"map", "frames", "first timestamp", "last timestamp", "trajectory"}, rows);
}

std::string skippedList(const nlohmann::json& summary) {
  if (!summary.contains("skipped") || summary["skipped"].empty()) return {};
  std::string html = "<p>Skipped frames:</p>\n<ul>\n";
  for (const auto& what : summary["skipped"]) {
    html +=
        "<li>" + escapeHtml(what.is_string() ? what.get<std::string>() : what.dump()) + "</li>\n";
  }
  return html + "</ul>\n";
}

std::vector<Cell> statsRow(const std::string& name, const nlohmann::json& stats,
                           const std::string& key) {
  std::vector<Cell> row = {{name, "", std::nullopt}};
  for (const char* field : {"rmse", "mean", "median", "std", "min", "max"}) {
    row.push_back(Cell::number(stats.value(field, 0.0), key + "." + field));
  }
  row.push_back(Cell::count(stats.value("count", 0LL), key + ".count"));
  return row;
}

std::string statsTable(const nlohmann::json& evaluation) {
  const auto& rpe = evaluation.value("rpe", nlohmann::json::object());
  return htmlTable(
      {"metric", "rmse", "mean", "median", "std", "min", "max", "pairs"},
      {statsRow("ATE [m]", evaluation.value("ate", nlohmann::json::object()), "ate"),
       statsRow("RPE trans [m]", rpe.value("trans", nlohmann::json::object()), "rpe.trans"),
       statsRow("RPE rot [deg]", rpe.value("rot", nlohmann::json::object()), "rpe.rot")});
}

std::string alignmentLine(const nlohmann::json& evaluation) {
  const auto& alignment = evaluation.value("alignment", nlohmann::json::object());
  const auto& ate = evaluation.value("ate", nlohmann::json::object());
  return fmt::format(
      "<p>Alignment {} (scale {:.6f}); coverage {:.1f}% of the ground truth in the "
      "estimate's span.</p>\n",
      escapeHtml(alignment.value("mode", "?")), alignment.value("scale", 1.0),
      100.0 * ate.value("coverage", 0.0));
}

std::string plots(const Reevaluation& again) {
  if (!again.report) return htmlNote("No trajectory plots: " + again.problem);
  return "<figure id=\"trajectory-views\">" + eval::plotTrajectoryViews(*again.report).element() +
         "<figcaption>Trajectory against ground truth, aligned as in summary.json</figcaption>"
         "</figure>\n<figure id=\"ate-over-time\">" +
         eval::plotErrorOverTime(*again.report).element() +
         "<figcaption>ATE of every matched pose</figcaption></figure>\n";
}

// Said when the plots' evaluation is not the one summary.json holds.
std::string consistencyNote(const nlohmann::json& evaluation, const Reevaluation& again) {
  if (!again.report) return {};
  const double recorded = evaluation.value("ate", nlohmann::json::object()).value("rmse", 0.0);
  const double recomputed = again.report->ate.stats.rmse;
  if (std::abs(recorded - recomputed) <= 1e-6 * std::max(1e-3, std::abs(recorded))) return {};
  return htmlNote(fmt::format(
      "The plots are of trajectory.txt evaluated again, with ATE rmse {:.6f} m, not "
      "summary.json's {:.6f} m: trajectory.txt or the ground truth changed after the run.",
      recomputed, recorded));
}

}  // namespace

std::string runSection(const nlohmann::json& summary) {
  std::vector<std::vector<Cell>> rows;
  for (const char* key : {"status", "dataset", "settings", "enhance_preset", "frames", "tracked",
                          "lost", "relocalized", "skipped_frames", "keyframes", "map_points",
                          "loops", "merges", "vocabulary"}) {
    rows.push_back({{key, "", std::nullopt}, valueCell(summary, key)});
  }
  rows.push_back({{"detector", "", std::nullopt}, {detectorName(summary), "detector", {}}});
  std::string html = htmlTable({"", "value"}, rows) + skippedList(summary);
  if (summary.contains("maps") && summary["maps"].is_array()) {
    html += "<h3>Maps of the atlas</h3>\n" + mapsTable(summary["maps"]);
  }
  return html;
}

std::string evaluationSection(const nlohmann::json& summary, const Reevaluation& again) {
  if (!summary.contains("evaluation") || !summary["evaluation"].is_object()) {
    return htmlNote(
        "summary.json has no evaluation: the dataset has no ground truth, or the "
        "run tracked fewer than 3 frames.");
  }
  const auto& evaluation = summary["evaluation"];
  return statsTable(evaluation) + alignmentLine(evaluation) + consistencyNote(evaluation, again) +
         plots(again);
}

}  // namespace lumaslam::cli
