// movingSection and mapFileSection of report_sections.h.
#include <algorithm>
#include <numeric>

#include <fmt/format.h>

#include "html_page.h"
#include "lumaslam/eval/error_stats.h"
#include "lumaslam/eval/series_plot.h"
#include "lumaslam/map/map_file.h"
#include "report_sections.h"

namespace lumaslam::cli {
namespace {

const nlohmann::json& objectAt(const nlohmann::json& summary, const char* key) {
  static const nlohmann::json kEmpty = nlohmann::json::object();
  return summary.contains(key) && summary[key].is_object() ? summary[key] : kEmpty;
}

std::string detectorNameOf(const nlohmann::json& summary) {
  return objectAt(summary, "detector").value("name", std::string("none"));
}

bool motionTestOn(const nlohmann::json& summary) {
  return objectAt(summary, "motion_evidence").value("on", false);
}

double mean(const std::vector<double>& values) {
  if (values.empty()) return 0.0;
  return std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
}

std::vector<Cell> textRow(const std::string& name, const std::string& text,
                          const std::string& key) {
  return {{name, "", std::nullopt}, {text, key, std::nullopt}};
}

std::vector<Cell> numberRow(const std::string& name, double value, const std::string& key,
                            int decimals) {
  return {{name, "", std::nullopt}, Cell::number(value, key, decimals)};
}

// Per-frame means and medians from timing.csv; throws Error for a missing column.
std::vector<std::vector<Cell>> timingRows(const TimingTable& timing) {
  return {
      numberRow("boxes per frame (mean)", mean(timing.numbers("boxes")), "moving.boxes_per_frame",
                3),
      numberRow("features dropped by boxes per frame (mean)",
                mean(timing.numbers("dropped_features")), "moving.dropped_per_frame", 3),
      numberRow("features the motion test flagged moving per frame (mean)",
                mean(timing.numbers("moving_features")), "moving.moving_per_frame", 3),
      numberRow("motion test ms (median)", eval::computeStats(timing.numbers("motion_ms")).median,
                "moving.motion_ms.median", 3),
      numberRow("detection wait ms (median)",
                eval::computeStats(timing.numbers("detection_wait_ms")).median,
                "moving.detection_wait_ms.median", 3)};
}

std::string movingPlot(const TimingTable& timing, bool detector, bool motion_test) {
  eval::SeriesPlot plot{"Features removed per frame", "frame", "features", {}};
  const auto frames = timing.numbers("frame");
  if (detector) {
    plot.series.push_back(
        {"dropped by boxes", "#d62728", frames, timing.numbers("dropped_features")});
  }
  if (motion_test) {
    plot.series.push_back(
        {"flagged moving (motion test)", "#ff7f0e", frames, timing.numbers("moving_features")});
  }
  return "<figure id=\"moving-plot\">" + eval::plotSeries(plot).element() + "</figure>\n";
}

// The timing.csv part: table rows and plot, or a note saying why there are none.
std::string fromTiming(const RunFolder& run, std::vector<std::vector<Cell>>& rows) {
  if (!run.timing || run.timing->rows.empty()) {
    return htmlNote("No per-frame numbers: " +
                    (run.timing ? std::string("timing.csv has no frames") : run.timing_problem));
  }
  try {
    auto timing_rows = timingRows(*run.timing);
    const std::string plot =
        movingPlot(*run.timing, detectorNameOf(run.summary) != "none", motionTestOn(run.summary));
    rows.insert(rows.end(), timing_rows.begin(), timing_rows.end());
    return plot;
  } catch (const std::exception& e) {
    return htmlNote(std::string("No per-frame numbers: ") + e.what());
  }
}

std::vector<Cell> countRow(const std::string& name, std::size_t value, const std::string& key) {
  return {{name, "", std::nullopt}, Cell::count(static_cast<long long>(value), key)};
}

// What the map was made with (the settings fingerprint a loading run must match).
std::vector<std::vector<Cell>> fingerprintRows(const map::MapFingerprint& f) {
  const std::string vocabulary = f.vocabulary_name.empty() ? "none" : f.vocabulary_name;
  return {textRow("sensor, image", fmt::format("{} {}x{}", f.sensor, f.image_width, f.image_height),
                  "map.sensor"),
          textRow("camera",
                  fmt::format("fx {:.6f} fy {:.6f} cx {:.6f} cy {:.6f} bf {:.6f}", f.camera.fx,
                              f.camera.fy, f.camera.cx, f.camera.cy, f.camera.bf),
                  "map.camera"),
          textRow("ORB",
                  fmt::format("{} features, scale {:.4f}, {} levels, fast {}/{}", f.orb_features,
                              f.orb_scale_factor, f.orb_levels, f.orb_ini_fast, f.orb_min_fast),
                  "map.orb"),
          textRow("vocabulary", fmt::format("{} ({:016x})", vocabulary, f.vocabulary),
                  "map.vocabulary")};
}

std::vector<std::vector<Cell>> infoRows(const map::MapFileInfo& info) {
  std::vector<std::vector<Cell>> rows = {
      countRow("format version", info.version, "map.version"),
      countRow("bytes", static_cast<std::size_t>(info.bytes), "map.bytes"),
      countRow("keyframes", info.keyframes, "map.keyframes"),
      countRow("points", info.points, "map.points"),
      countRow("maps", info.maps.size(), "map.maps")};
  for (const auto& [id, keyframes] : info.maps) {
    rows.push_back(countRow(fmt::format("map {} keyframes", id), keyframes,
                            fmt::format("map.{}.keyframes", id)));
  }
  rows.push_back(textRow(
      "time", fmt::format("{:.6f} .. {:.6f} s", info.first_timestamp, info.last_timestamp), ""));
  for (auto& row : fingerprintRows(info.fingerprint)) rows.push_back(std::move(row));
  return rows;
}

// The saved file as `lumaslam map info` reads it, or a note why it cannot be read.
std::string savedFile(const std::string& path) {
  std::string html = "<p>Saved to <code>" + escapeHtml(path) +
                     "</code>, read now as <code>lumaslam map info</code> does:</p>\n";
  try {
    return html + htmlTable({"", "value"}, infoRows(map::readMapFileInfo(path)));
  } catch (const std::exception& e) {
    return html + htmlNote(std::string("The map file cannot be read now: ") + e.what());
  }
}

std::string loadedFile(const nlohmann::json& map_file) {
  if (!map_file.contains("loaded") || !map_file["loaded"].is_string()) return {};
  return htmlTable(
      {"started from", "value"},
      {textRow("map file", map_file["loaded"].get<std::string>(), "map.loaded"),
       {{"keyframes loaded", "", std::nullopt},
        Cell::count(map_file.value("loaded_keyframes", 0LL), "map.loaded_keyframes")},
       {{"keyframes added", "", std::nullopt},
        Cell::count(map_file.value("keyframes_added", 0LL), "map.keyframes_added")},
       textRow("localization only", map_file.value("localization", false) ? "yes" : "no",
               "map.localization")});
}

}  // namespace

bool hadMovingThings(const nlohmann::json& summary) {
  return detectorNameOf(summary) != "none" || motionTestOn(summary);
}

std::string movingSection(const RunFolder& run) {
  const auto& motion = objectAt(run.summary, "motion_evidence");
  std::vector<std::vector<Cell>> rows = {
      textRow("detector", detectorNameOf(run.summary), "moving.detector"),
      textRow("motion test", motionTestOn(run.summary) ? "on" : "off", "moving.motion_test"),
      {{"map points moving at the end", "", std::nullopt},
       Cell::count(motion.value("moving_map_points", 0LL), "motion_evidence.moving_map_points")}};
  const std::string plot = fromTiming(run, rows);
  return "<p>Features removed before tracking: those inside a detector's boxes (dropped) and "
         "those whose map points the motion test found moving against the camera's pose.</p>\n" +
         htmlTable({"", "value"}, rows) + plot;
}

bool hadMapFile(const nlohmann::json& summary) {
  const auto& map_file = objectAt(summary, "map_file");
  return (map_file.contains("saved") && map_file["saved"].is_string()) ||
         map_file.contains("save_error") ||
         (map_file.contains("loaded") && map_file["loaded"].is_string());
}

std::string mapFileSection(const nlohmann::json& summary) {
  const auto& map_file = objectAt(summary, "map_file");
  std::string html = loadedFile(map_file);
  if (map_file.contains("save_error")) {
    const auto& error = map_file["save_error"];
    html += htmlNote("The map was not saved: " +
                     (error.is_string() ? error.get<std::string>() : error.dump()));
  }
  if (map_file.contains("saved") && map_file["saved"].is_string()) {
    html += savedFile(map_file["saved"].get<std::string>());
  }
  return html;
}

}  // namespace lumaslam::cli
