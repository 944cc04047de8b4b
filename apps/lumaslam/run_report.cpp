#include "run_report.h"

#include <fmt/format.h>

#include "html_page.h"
#include "lumaslam/io/output_file.h"
#include "report_sections.h"
#include "run_folder.h"

namespace lumaslam::cli {
namespace {

void save(const HtmlPage& page, const std::filesystem::path& out) {
  io::OutputFile file(out);
  file.stream() << page.str();
  file.commit();
}

std::string titleOf(const nlohmann::json& summary) {
  return "lumaslam run: " + summary.value("dataset", std::string("(dataset not recorded)"));
}

SampleFrames samplesOf(const RunFolder& run) {
  if (!run.timing) {
    SampleFrames none;
    none.problem = "no frame list: " + run.timing_problem;
    return none;
  }
  return loadSampleFrames(run.dir, run.summary, *run.timing);
}

std::vector<Cell> repeatRow(const nlohmann::json& entry, std::size_t k) {
  const std::string run = fmt::format("run_{}", k);
  const auto number_or_blank = [&](const char* key, int decimals) -> Cell {
    if (!entry.contains(key) || !entry[key].is_number()) return {"", run + "." + key, {}};
    return Cell::number(entry[key].get<double>(), run + "." + key, decimals);
  };
  return {{run, "", std::nullopt},
          Cell::count(entry.value("tracked", 0LL), run + ".tracked"),
          number_or_blank("ms_per_frame_median", 3),
          number_or_blank("ate_rmse", 6)};
}

// Links to each run's report, relative to the page at `out` (wherever --out put it).
std::string repeatLinks(const std::filesystem::path& dir, const std::filesystem::path& out,
                        std::size_t runs) {
  const auto from = std::filesystem::absolute(out).parent_path().lexically_normal();
  std::string html = "<ul>\n";
  for (std::size_t k = 1; k <= runs; ++k) {
    const auto target = std::filesystem::absolute(dir / fmt::format("run_{}", k) / "report.html");
    html += fmt::format("<li><a href=\"{}\">run_{}</a></li>\n",
                        escapeHtml(target.lexically_normal().lexically_relative(from).string()), k);
  }
  return html + "</ul>\n";
}

}  // namespace

void writeRunReport(const std::filesystem::path& run_dir, const std::filesystem::path& out) {
  const RunFolder run = readRunFolder(run_dir);
  HtmlPage page(titleOf(run.summary));
  page.section("run", "Run", runSection(run.summary));
  page.section("evaluation", "Accuracy against ground truth",
               evaluationSection(run.summary, reevaluate(run)));
  page.section("tracking", "Tracking", trackingSection(run));
  page.section("timing", "Timing", timingSection(run));
  if (hadMovingThings(run.summary)) page.section("moving", "Moving things", movingSection(run));
  if (hadMapFile(run.summary)) page.section("map", "Map file", mapFileSection(run.summary));
  page.section("frames", "Sample frames", framesSection(samplesOf(run)));
  save(page, out);
}

void writeRepeatReport(const std::filesystem::path& dir, const std::filesystem::path& out) {
  const nlohmann::json repeat = readRepeatability(dir);
  const auto& runs = repeat["runs"];
  std::vector<std::vector<Cell>> rows;
  for (std::size_t k = 1; k <= runs.size(); ++k) {
    writeRunReport(dir / fmt::format("run_{}", k), dir / fmt::format("run_{}", k) / "report.html");
    rows.push_back(repeatRow(runs[k - 1], k));
  }
  HtmlPage page("lumaslam run --repeat: " + repeat.value("dataset", std::string("?")));
  page.section("repeat", "Runs",
               htmlTable({"run", "tracked", "ms/frame median", "ATE rmse [m]"}, rows) +
                   "<p>Each run's own report:</p>\n" + repeatLinks(dir, out, runs.size()));
  save(page, out);
}

void writeReport(const std::filesystem::path& dir, const std::filesystem::path& out) {
  if (isRepeatFolder(dir)) {
    writeRepeatReport(dir, out);
  } else {
    writeRunReport(dir, out);
  }
}

}  // namespace lumaslam::cli
