// timingSection and trackingSection of report_sections.h.
#include <algorithm>
#include <cmath>
#include <iterator>

#include <fmt/format.h>

#include "html_page.h"
#include "lumaslam/eval/error_stats.h"
#include "lumaslam/eval/series_plot.h"
#include "report_sections.h"

namespace lumaslam::cli {
namespace {

// Nearest-rank 90th percentile.
double p90(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const auto rank = static_cast<std::size_t>(std::ceil(0.9 * static_cast<double>(values.size())));
  return values[std::max<std::size_t>(rank, 1) - 1];
}

std::vector<Cell> timingRow(const TimingTable& timing, const std::string& column) {
  const std::vector<double> values = timing.numbers(column);
  const eval::ErrorStats stats = eval::computeStats(values);
  const std::string stage = column.substr(0, column.size() - 3);  // without "_ms"
  return {{stage, "", std::nullopt},
          Cell::number(stats.median, "timing." + stage + ".median", 3),
          Cell::number(stats.mean, "timing." + stage + ".mean", 3),
          Cell::number(p90(values), "timing." + stage + ".p90", 3),
          Cell::number(stats.max, "timing." + stage + ".max", 3)};
}

std::string totalPlot(const TimingTable& timing) {
  eval::SeriesPlot plot{"Total time per frame", "frame", "ms", {}};
  plot.series.push_back({"total", "#1f77b4", timing.numbers("frame"), timing.numbers("total_ms")});
  return "<figure id=\"timing-plot\">" + eval::plotSeries(plot).element() + "</figure>\n";
}

// Index into kStates of a timing.csv state.
int stateIndex(const std::string& state) {
  if (state == "ok") return 0;
  if (state == "lost") return 1;
  return 2;
}

const std::vector<eval::StripState> kStates = {
    {"ok", "#2ca02c"}, {"lost", "#d62728"}, {"not initialized / other", "#bbbbbb"}};

// The map of every frame (timing.csv "map", empty when lost) when the run made more than one:
// where the atlas started new maps and which frames each holds. Empty otherwise.
std::string mapStrip(const TimingTable& timing, const std::vector<double>& frames) {
  if (!timing.has("map")) return {};
  static const char* const kPalette[] = {"#1f77b4", "#ff7f0e", "#9467bd", "#8c564b",
                                         "#e377c2", "#17becf", "#bcbd22", "#7f7f7f"};
  std::vector<eval::StripState> legend = {{"lost", "#ffffff"}};
  std::vector<int> states;
  for (const std::string& map : timing.texts("map")) {
    const std::string label = map.empty() ? "lost" : "map " + map;
    auto at = std::find_if(legend.begin(), legend.end(),
                           [&](const eval::StripState& entry) { return entry.label == label; });
    if (at == legend.end()) {
      legend.push_back({label, kPalette[(legend.size() - 1) % std::size(kPalette)]});
      at = legend.end() - 1;
    }
    states.push_back(static_cast<int>(at - legend.begin()));
  }
  if (legend.size() <= 2) return {};  // one map (and maybe lost frames): the strip above
  return "<figure id=\"map-timeline\">" +
         eval::plotStateStrip("Map of each frame", "frame", frames, states, legend).element() +
         "</figure>\n";
}

}  // namespace

std::string timingSection(const RunFolder& run) {
  if (!run.timing) return htmlNote("No timing: " + run.timing_problem);
  const TimingTable& timing = *run.timing;
  if (timing.rows.empty()) return htmlNote("timing.csv has no frames.");
  try {
    std::vector<std::vector<Cell>> rows;
    for (const std::string& column : timing.columns) {
      if (column.ends_with("_ms")) rows.push_back(timingRow(timing, column));
    }
    return "<p>Milliseconds per frame, " + std::to_string(timing.rows.size()) + " frames.</p>\n" +
           htmlTable({"stage", "median", "mean", "p90", "max"}, rows) + totalPlot(timing);
  } catch (const std::exception& e) {
    return htmlNote(std::string("No timing: ") + e.what());
  }
}

std::string trackingSection(const RunFolder& run) {
  if (!run.timing || run.timing->rows.empty()) {
    return htmlNote("No tracking timeline: " +
                    (run.timing ? std::string("timing.csv has no frames") : run.timing_problem));
  }
  try {
    const auto frames = run.timing->numbers("frame");
    std::vector<int> states;
    for (const std::string& state : run.timing->texts("state")) states.push_back(stateIndex(state));
    const auto tracked = std::count(states.begin(), states.end(), 0);
    const auto others = static_cast<long long>(states.size()) - tracked;
    const std::string counts =
        htmlTable({"timing.csv", "frames"},
                  {{{"tracked (ok)", "", std::nullopt}, Cell::count(tracked, "timeline.tracked")},
                   {{"not tracked", "", std::nullopt}, Cell::count(others, "timeline.lost")}});
    return counts + "<figure id=\"tracking-timeline\">" +
           eval::plotStateStrip("Tracking state per frame", "frame", frames, states, kStates)
               .element() +
           "</figure>\n" + mapStrip(*run.timing, frames);
  } catch (const std::exception& e) {
    return htmlNote(std::string("No tracking timeline: ") + e.what());
  }
}

}  // namespace lumaslam::cli
