// DIR/report.html of `lumaslam experiment` and `experiment collect` on a small plan (2 synthetic
// datasets x 2 configurations x 2 sequential runs, `baseline:` the second configuration): its
// numbers are results.csv's (data attributes), the improvement vs the baseline is the formula,
// the heatmap has one cell per run, a missing run is grey and listed, collect writes the same
// page, a bad `baseline` is an error naming the key, and the page opens in headless Chromium
// without console errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <numeric>
#include <regex>
#include <string>
#include <vector>

#include "chromium_page.h"
#include "experiment_tables.h"
#include "test_cli.h"

namespace {

using lumaslam::test::haveChromium;
using lumaslam::test::openInChromium;
using lumaslam::test::readCsv;
using lumaslam::test::readTextFile;
using lumaslam::test::runCli;
using lumaslam::test::TempDir;
using lumaslam::test::writeFile;
namespace fs = std::filesystem;

constexpr const char* kPlan = R"(runs: 2
baseline: default
datasets:
  - spec: "synth:xyz-rgbd"
    seeds: [1, 2]
    frames: 30
configurations:
  - name: enhance-off
    enhance: off
    sequential: true
  - name: default
    sequential: true
)";

using Attributes = std::map<std::string, std::string>;
using Row = std::map<std::string, std::string>;

// Every <td> of `html` that has attributes: its attributes plus "text" (its content).
std::vector<Attributes> dataCells(const std::string& html) {
  static const std::regex td(R"(<td ([^>]*)>([^<]*)</td>)");
  static const std::regex attribute(R"re(([a-z-]+)="([^"]*)")re");
  std::vector<Attributes> cells;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), td); it != std::sregex_iterator();
       ++it) {
    Attributes cell{{"text", (*it)[2].str()}};
    const std::string attributes = (*it)[1].str();
    for (auto a = std::sregex_iterator(attributes.begin(), attributes.end(), attribute);
         a != std::sregex_iterator(); ++a) {
      cell[(*a)[1].str()] = (*a)[2].str();
    }
    cells.push_back(cell);
  }
  return cells;
}

// The <section id="ID"> of the page.
std::string section(const std::string& html, const std::string& id) {
  const auto begin = html.find("<section id=\"" + id + "\">");
  if (begin == std::string::npos) return {};
  return html.substr(begin, html.find("</section>", begin) - begin);
}

std::string millimetres(double metres) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", 1000.0 * metres);
  return text;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// A results.csv column over the complete runs of one dataset x config.
std::vector<double> cellValues(const std::vector<Row>& rows, const std::string& dataset,
                               const std::string& config, const std::string& column) {
  std::vector<double> values;
  for (const auto& row : rows) {
    if (row.at("dataset") == dataset && row.at("config") == config &&
        row.at("status") == "complete") {
      values.push_back(std::stod(row.at(column)));
    }
  }
  return values;
}

double cellMedian(const std::vector<Row>& rows, const std::string& dataset,
                  const std::string& config, const std::string& column) {
  return median(cellValues(rows, dataset, config, column));
}

double cellSum(const std::vector<Row>& rows, const std::string& dataset, const std::string& config,
               const std::string& column) {
  const auto values = cellValues(rows, dataset, config, column);
  return std::accumulate(values.begin(), values.end(), 0.0);
}

class CliExperimentReport : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<TempDir>("cli_experiment_report");
    const auto plan = writeFile(dir_->path() / "plan.yaml", kPlan);
    const auto result = runCli("experiment " + plan.string() + " --out " + out().string());
    ASSERT_EQ(result.exit_code, 0) << result.output;
  }
  static void TearDownTestSuite() { dir_.reset(); }
  static fs::path out() { return dir_->path() / "out"; }

  static std::unique_ptr<TempDir> dir_;
};

std::unique_ptr<TempDir> CliExperimentReport::dir_;

TEST_F(CliExperimentReport, EveryRunsAteIsResultsCsvsOneHeatmapCellEach) {
  const std::string html = readTextFile(out() / "report.html");
  ASSERT_FALSE(html.empty());
  const auto rows = readCsv(out() / "results.csv");
  ASSERT_EQ(rows.size(), 8U);
  const auto heatmap = dataCells(section(html, "heatmap"));
  const auto runs = std::count_if(heatmap.begin(), heatmap.end(),
                                  [](const Attributes& c) { return c.count("data-run") == 1; });
  EXPECT_EQ(runs, 8);
  int compared = 0;
  for (const auto& cell : heatmap) {
    if (cell.count("data-run") == 0) continue;
    ASSERT_EQ(cell.at("data-key"), "ate_rmse");
    for (const auto& row : rows) {
      if (row.at("dataset") != cell.at("data-dataset") ||
          row.at("config") != cell.at("data-config") || row.at("run") != cell.at("data-run")) {
        continue;
      }
      EXPECT_EQ(std::stod(cell.at("data-value")), std::stod(row.at("ate_rmse")));
      EXPECT_EQ(cell.at("text"), millimetres(std::stod(row.at("ate_rmse"))));
      ++compared;
    }
  }
  EXPECT_EQ(compared, 8);
}

TEST_F(CliExperimentReport, TableIsTheMedianOfResultsCsvAndTheImprovementVsTheBaseline) {
  const std::string html = readTextFile(out() / "report.html");
  const auto rows = readCsv(out() / "results.csv");
  std::map<std::string, int> seen;
  for (const auto& cell : dataCells(section(html, "results"))) {
    const std::string key = cell.at("data-key");
    const std::string dataset = cell.at("data-dataset"), config = cell.at("data-config");
    const double value = std::stod(cell.at("data-value"));
    ++seen[key];
    if (key.starts_with("cell.ate_")) {
      const double expected = cellMedian(rows, dataset, config, key.substr(5));
      EXPECT_EQ(value, expected) << key << " " << dataset << " " << config;
      EXPECT_EQ(cell.at("text"), millimetres(expected)) << key;
    } else if (key == "cell.improvement_pct") {
      const double base = cellMedian(rows, dataset, "default", "ate_rmse");
      const double ate = cellMedian(rows, dataset, config, "ate_rmse");
      EXPECT_NEAR(value, (base - ate) / base * 100.0, 1e-9) << dataset << " " << config;
    } else if (key == "cell.tracked_pct") {
      EXPECT_EQ(value, 100.0 * cellSum(rows, dataset, config, "tracked") /
                           cellSum(rows, dataset, config, "frames"));
    } else if (key == "cell.complete") {
      EXPECT_EQ(value, 2);
      EXPECT_EQ(cell.at("data-runs"), "2");
    }
  }
  for (const char* key : {"cell.ate_rmse", "cell.ate_mean", "cell.ate_median", "cell.ate_std",
                          "cell.tracked_pct", "cell.complete", "cell.improvement_pct"}) {
    EXPECT_EQ(seen[key], 4) << key;
  }
  EXPECT_NE(html.find("default (baseline)"), std::string::npos);
  // The total and each module: the cell's median of the results.csv column of the same name.
  int timing_cells = 0;
  for (const auto& cell : dataCells(section(html, "timing"))) {
    const std::string column = cell.at("data-key").substr(std::string("cell.").size());
    EXPECT_EQ(std::stod(cell.at("data-value")),
              cellMedian(rows, cell.at("data-dataset"), cell.at("data-config"), column))
        << column;
    ++timing_cells;
  }
  EXPECT_EQ(timing_cells, 4 * 7);  // 4 cells x (total + 6 modules)
  EXPECT_NE(section(html, "failures").find("every run is complete"), std::string::npos);
}

TEST_F(CliExperimentReport, CollectWritesTheSamePageAndGreysAMissingRun) {
  const auto copy = dir_->path() / "copy";
  fs::copy(out(), copy, fs::copy_options::recursive);
  fs::remove(copy / "report.html");
  const auto collected = runCli("experiment collect " + copy.string());
  ASSERT_EQ(collected.exit_code, 0) << collected.output;
  const std::string page = readTextFile(out() / "report.html");
  std::string renamed = readTextFile(copy / "report.html");  // only the title names the folder
  for (auto at = renamed.find("Experiment copy"); at != std::string::npos;
       at = renamed.find("Experiment copy")) {
    renamed.replace(at, 15, "Experiment out");
  }
  EXPECT_EQ(renamed, page);

  fs::remove(copy / "runs" / "xyz-rgbd-s2" / "default" / "run_2" / "summary.json");
  ASSERT_EQ(runCli("experiment collect " + copy.string()).exit_code, 0);
  const std::string html = readTextFile(copy / "report.html");
  int grey = 0;
  for (const auto& cell : dataCells(section(html, "heatmap"))) {
    if (cell.count("data-status") == 0) continue;
    ++grey;
    EXPECT_EQ(cell.at("data-status"), "not run");
    EXPECT_EQ(cell.at("data-run"), "2");
    EXPECT_NE(cell.at("style").find("#cccccc"), std::string::npos);
  }
  EXPECT_EQ(grey, 1);
  EXPECT_NE(section(html, "failures").find("runs/xyz-rgbd-s2/default/run_2"), std::string::npos);
}

TEST_F(CliExperimentReport, OpensInHeadlessChromiumWithoutConsoleErrors) {
  ASSERT_TRUE(haveChromium()) << "no /usr/bin/chromium: scripts/install-deps.sh installs it";
  const auto browser = openInChromium(out() / "report.html", dir_->path());
  ASSERT_EQ(browser.exit_code, 0);
  EXPECT_TRUE(browser.console.empty()) << browser.console.front();
  for (const char* element : {"id=\"heatmap\"", "data-key=\"cell.improvement_pct\"", "data-run"}) {
    EXPECT_NE(browser.dom.find(element), std::string::npos) << element;
  }
}

TEST(CliExperimentReportPlan, ABadBaselineIsAnErrorNamingTheKey) {
  TempDir dir("cli_experiment_report_bad");
  std::string text = kPlan;
  text.replace(text.find("baseline: default"), 17, "baseline: nope");
  const auto plan = writeFile(dir.path() / "plan.yaml", text);
  const auto result =
      runCli("experiment " + plan.string() + " --out " + (dir.path() / "out").string());
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find(plan.string() + ": baseline: 'nope' is not a configuration"),
            std::string::npos)
      << result.output;
  EXPECT_FALSE(fs::exists(dir.path() / "out" / "runs"));
}

}  // namespace
