// `lumaslam run --report` and `lumaslam report` on a short synthetic sequence: the HTML is
// self-contained, its numbers are summary.json's, its sample frames decode, and it opens in
// headless Chromium without console errors; a folder without a run is a clear error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "base64_text.h"
#include "chromium_page.h"
#include "test_cli.h"

namespace {

using lumaslam::test::decodeBase64;
using lumaslam::test::haveChromium;
using lumaslam::test::openInChromium;
using lumaslam::test::readRunSummary;
using lumaslam::test::readTextFile;
using lumaslam::test::runCli;
using lumaslam::test::TempDir;

// The text of the element carrying data-key="KEY"; empty when there is none. (Found without
// std::regex: its recursion overflows the stack on a page of base64 images.)
std::string cellText(const std::string& html, const std::string& key) {
  const auto at = html.find("data-key=\"" + key + "\"");
  if (at == std::string::npos) return {};
  const auto begin = html.find('>', at) + 1;
  return html.substr(begin, html.find('<', begin) - begin);
}

// The values of every ATTRIBUTE="..." in the page.
std::vector<std::string> attributeValues(const std::string& html, const std::string& attribute) {
  std::vector<std::string> values;
  const std::string opening = " " + attribute + "=\"";
  for (auto at = html.find(opening); at != std::string::npos; at = html.find(opening, at + 1)) {
    const auto begin = at + opening.size();
    values.push_back(html.substr(begin, html.find('"', begin) - begin));
  }
  return values;
}

std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

std::string sixDecimals(double value) {
  char text[64];
  std::snprintf(text, sizeof text, "%.6f", value);
  return text;
}

std::string threeDecimals(double value) {
  char text[64];
  std::snprintf(text, sizeof text, "%.3f", value);
  return text;
}

// The numbers of timing.csv's column NAME, one per frame.
std::vector<double> timingColumn(const std::filesystem::path& file, const std::string& name) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  std::stringstream header(line);
  std::size_t index = 0;
  for (std::string field; std::getline(header, field, ',') && field != name;) ++index;
  std::vector<double> values;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::string field;
    for (std::size_t k = 0; k <= index; ++k) std::getline(row, field, ',');
    values.push_back(std::stod(field));
  }
  return values;
}

double mean(const std::vector<double>& values) {
  double sum = 0.0;
  for (const double value : values) sum += value;
  return sum / static_cast<double>(values.size());
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t middle = values.size() / 2;
  return values.size() % 2 ? values[middle] : 0.5 * (values[middle - 1] + values[middle]);
}

std::vector<std::string> imageSources(const std::string& html) {
  std::vector<std::string> sources;
  for (auto at = html.find("<img "); at != std::string::npos; at = html.find("<img ", at + 1)) {
    const auto end = html.find('>', at);
    const auto src = attributeValues(html.substr(at, end - at), "src");
    if (!src.empty()) sources.push_back(src.front());
  }
  return sources;
}

// One synthetic run (60 frames, with ground truth), reported by `run --report`.
class CliReport : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<TempDir>("cli_report");
    const auto synth =
        runCli("synth " + data().string() + " --preset xyz-rgbd --frames 60 --seed 3");
    ASSERT_EQ(synth.exit_code, 0) << synth.output;
    const auto run = runCli("run --dataset tum:" + data().string() +
                            " --sequential --report --out " + out().string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
  }
  static void TearDownTestSuite() { dir_.reset(); }

  static std::filesystem::path data() { return dir_->path() / "data"; }
  static std::filesystem::path out() { return dir_->path() / "out"; }

  static std::unique_ptr<TempDir> dir_;
};

std::unique_ptr<TempDir> CliReport::dir_;

TEST_F(CliReport, RunWritesOneSelfContainedPage) {
  ASSERT_TRUE(std::filesystem::exists(out() / "report.html"));
  const std::string html = readTextFile(out() / "report.html");
  EXPECT_NE(html.find("<!DOCTYPE html>"), std::string::npos);
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_EQ(html.find("<link"), std::string::npos);
  EXPECT_EQ(html.find("url("), std::string::npos);
  for (const char* attribute : {"src", "href"}) {
    for (const std::string& value : attributeValues(html, attribute)) {
      EXPECT_TRUE(value.starts_with("data:image/")) << attribute << "=" << value.substr(0, 60);
    }
  }
  // The only http:// is the SVG namespace name (never fetched).
  EXPECT_EQ(occurrences(html, "http://"),
            occurrences(html, "xmlns=\"http://www.w3.org/2000/svg\""));
  // trajectory views, ATE, timeline, timing, features removed (the motion test is on)
  EXPECT_EQ(occurrences(html, "<svg"), 5U);
  EXPECT_EQ(html.find("https://"), std::string::npos);
  for (const char* section :
       {"id=\"run\"", "id=\"evaluation\"", "id=\"tracking\"", "id=\"timing\"", "id=\"frames\"",
        "id=\"trajectory-views\"", "id=\"ate-over-time\"", "id=\"timing-plot\"",
        "id=\"tracking-timeline\"", "id=\"moving\"", "id=\"moving-plot\""}) {
    EXPECT_NE(html.find(section), std::string::npos) << section;
  }
  EXPECT_EQ(html.find("id=\"map\""), std::string::npos) << "no map saved, no map section";
  EXPECT_EQ(html.find("class=\"note\""), std::string::npos) << "a section says something failed";
}

TEST_F(CliReport, NumbersAreTheSummarys) {
  const std::string html = readTextFile(out() / "report.html");
  const auto summary = readRunSummary(out());
  ASSERT_TRUE(summary.contains("evaluation"));
  const auto& evaluation = summary["evaluation"];
  for (const char* stat : {"rmse", "mean", "median", "std", "min", "max"}) {
    EXPECT_EQ(cellText(html, std::string("ate.") + stat),
              sixDecimals(evaluation["ate"][stat].get<double>()))
        << stat;
    EXPECT_EQ(cellText(html, std::string("rpe.trans.") + stat),
              sixDecimals(evaluation["rpe"]["trans"][stat].get<double>()))
        << stat;
  }
  EXPECT_EQ(cellText(html, "ate.count"), std::to_string(evaluation["ate"]["count"].get<int>()));
  const auto tracked = std::to_string(summary["tracked"].get<int>());
  const auto lost = std::to_string(summary["lost"].get<int>());
  EXPECT_EQ(cellText(html, "tracked"), tracked);
  EXPECT_EQ(cellText(html, "lost"), lost);
  EXPECT_EQ(cellText(html, "timeline.tracked"), tracked);  // counted from timing.csv
  EXPECT_EQ(cellText(html, "timeline.lost"), lost);
  EXPECT_EQ(cellText(html, "status"), summary["status"].get<std::string>());
  EXPECT_EQ(cellText(html, "keyframes"), std::to_string(summary["keyframes"].get<int>()));
}

TEST_F(CliReport, SampleFramesAreInlineImages) {
  const auto sources = imageSources(readTextFile(out() / "report.html"));
  ASSERT_EQ(sources.size(), 6U);  // first, middle, last tracked frame: raw and enhanced
  for (const std::string& source : sources) {
    const std::string prefix = "data:image/jpeg;base64,";
    ASSERT_EQ(source.rfind(prefix, 0), 0U) << source.substr(0, 40);
    const auto bytes = decodeBase64(source.substr(prefix.size()));
    const cv::Mat image = cv::imdecode(bytes, cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(image.empty());
    EXPECT_LE(image.cols, 480);
    EXPECT_GT(image.rows, 0);
  }
}

TEST_F(CliReport, ReportCommandWritesTheSamePageElsewhere) {
  const auto other = dir_->path() / "elsewhere" / "page.html";
  const auto report = runCli("report " + out().string() + " --out " + other.string());
  ASSERT_EQ(report.exit_code, 0) << report.output;
  EXPECT_EQ(readTextFile(other), readTextFile(out() / "report.html"));
}

TEST_F(CliReport, AGoneDatasetCostsOnlyTheFramesAndPlots) {
  const auto copy = dir_->path() / "moved";
  std::filesystem::create_directories(copy);
  for (const char* name : {"trajectory.txt", "timing.csv"}) {
    std::filesystem::copy_file(out() / name, copy / name);
  }
  auto summary = readRunSummary(out());
  summary["dataset"] = "tum:" + (dir_->path() / "gone").string();
  std::ofstream(copy / "summary.json") << summary.dump(2);
  const auto report = runCli("report " + copy.string());
  ASSERT_EQ(report.exit_code, 0) << report.output;
  const std::string html = readTextFile(copy / "report.html");
  EXPECT_TRUE(imageSources(html).empty());
  EXPECT_NE(html.find("Sample frames unavailable"), std::string::npos);
  EXPECT_NE(html.find("gone"), std::string::npos);
  EXPECT_EQ(cellText(html, "ate.rmse"),
            sixDecimals(summary["evaluation"]["ate"]["rmse"].get<double>()));
}

TEST_F(CliReport, PlotsOfAnotherEvaluationThanTheSummarysAreSaidSo) {
  const auto copy = dir_->path() / "edited";
  std::filesystem::create_directories(copy);
  for (const char* name : {"trajectory.txt", "timing.csv"}) {
    std::filesystem::copy_file(out() / name, copy / name);
  }
  auto summary = readRunSummary(out());
  summary["evaluation"]["ate"]["rmse"] = 1.0;
  std::ofstream(copy / "summary.json") << summary.dump(2);
  const auto report = runCli("report " + copy.string());
  ASSERT_EQ(report.exit_code, 0) << report.output;
  const std::string html = readTextFile(copy / "report.html");
  EXPECT_EQ(cellText(html, "ate.rmse"), "1.000000");  // the summary's, as it says
  EXPECT_NE(html.find("not summary.json's 1.000000 m"), std::string::npos);
  EXPECT_NE(html.find("id=\"trajectory-views\""), std::string::npos);
}

// timing.csv as a run with a second map would write it: the report draws which frames each
// map holds (no such strip for the one-map run above).
TEST_F(CliReport, ARunWithSeveralMapsShowsTheMapOfEachFrame) {
  EXPECT_EQ(readTextFile(out() / "report.html").find("id=\"map-timeline\""), std::string::npos);
  const auto copy = dir_->path() / "two_maps";
  std::filesystem::create_directories(copy);
  std::filesystem::copy_file(out() / "trajectory.txt", copy / "trajectory.txt");
  std::filesystem::copy_file(out() / "summary.json", copy / "summary.json");
  std::ifstream timing(out() / "timing.csv");
  std::ofstream edited(copy / "timing.csv");
  std::string line;
  std::getline(timing, line);
  edited << line << '\n';
  const std::regex map_field("^((?:[^,]*,){13})0,");  // the 14th column, "map"
  for (int row = 0; std::getline(timing, line); ++row) {
    edited << (row < 40 ? line : std::regex_replace(line, map_field, "$013,")) << '\n';
  }
  edited.close();
  const auto report = runCli("report " + copy.string());
  ASSERT_EQ(report.exit_code, 0) << report.output;
  const std::string html = readTextFile(copy / "report.html");
  EXPECT_NE(html.find("id=\"map-timeline\""), std::string::npos);
  EXPECT_NE(html.find(">map 0: 40<"), std::string::npos);
  EXPECT_NE(html.find(">map 3: 20<"), std::string::npos);
}

// A synthetic walking run with the generator's boxes and the motion test, saving a map: the
// "Moving things" section's numbers are timing.csv's means and medians and summary.json's,
// and the "Map file" section shows what `lumaslam map info` reads from the file.
class CliReportMoving : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<TempDir>("cli_report_moving");
    const auto synth =
        runCli("synth " + data().string() + " --preset walking-xyz-rgbd --frames 40 --seed 5");
    ASSERT_EQ(synth.exit_code, 0) << synth.output;
    const auto run = runCli("run --dataset tum:" + data().string() + " --detector boxes:" +
                            (data() / "detections.txt").string() + " --sequential --save-map " +
                            map().string() + " --report --out " + out().string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
  }
  static void TearDownTestSuite() { dir_.reset(); }

  static std::filesystem::path data() { return dir_->path() / "data"; }
  static std::filesystem::path out() { return dir_->path() / "out"; }
  static std::filesystem::path map() { return dir_->path() / "walking.map"; }

  static std::unique_ptr<TempDir> dir_;
};

std::unique_ptr<TempDir> CliReportMoving::dir_;

TEST_F(CliReportMoving, MovingThingsAreTimingsMeansAndTheSummarys) {
  const std::string html = readTextFile(out() / "report.html");
  const auto summary = readRunSummary(out());
  const auto timing = out() / "timing.csv";
  EXPECT_NE(html.find("id=\"moving-plot\""), std::string::npos);
  EXPECT_EQ(cellText(html, "moving.detector"), summary["detector"]["name"].get<std::string>());
  EXPECT_EQ(cellText(html, "moving.motion_test"), "on");
  const double boxes = mean(timingColumn(timing, "boxes"));
  const double dropped = mean(timingColumn(timing, "dropped_features"));
  const double moving = mean(timingColumn(timing, "moving_features"));
  EXPECT_GT(boxes, 0.0);
  EXPECT_GT(dropped, 0.0);
  EXPECT_EQ(cellText(html, "moving.boxes_per_frame"), threeDecimals(boxes));
  EXPECT_EQ(cellText(html, "moving.dropped_per_frame"), threeDecimals(dropped));
  EXPECT_EQ(cellText(html, "moving.moving_per_frame"), threeDecimals(moving));
  EXPECT_EQ(cellText(html, "moving.dropped_per_frame"),
            threeDecimals(summary["detector"]["dropped_features_per_frame"].get<double>()));
  EXPECT_EQ(cellText(html, "moving.moving_per_frame"),
            threeDecimals(summary["motion_evidence"]["moving_features_per_frame"].get<double>()));
  EXPECT_EQ(cellText(html, "motion_evidence.moving_map_points"),
            std::to_string(summary["motion_evidence"]["moving_map_points"].get<int>()));
  EXPECT_EQ(cellText(html, "moving.motion_ms.median"),
            threeDecimals(median(timingColumn(timing, "motion_ms"))));
  EXPECT_EQ(cellText(html, "moving.detection_wait_ms.median"),
            threeDecimals(median(timingColumn(timing, "detection_wait_ms"))));
}

// The number after "NAME " on its own line of `lumaslam map info`'s output.
std::string infoLine(const std::string& output, const std::string& name) {
  const auto at = output.find("\n" + name + " ");
  if (at == std::string::npos) return {};
  const auto begin = at + name.size() + 2;
  return output.substr(begin, output.find('\n', begin) - begin);
}

TEST_F(CliReportMoving, MapFileIsWhatMapInfoReads) {
  const std::string html = readTextFile(out() / "report.html");
  const auto info = runCli("map info " + map().string());
  ASSERT_EQ(info.exit_code, 0) << info.output;
  const std::string keyframes = infoLine(info.output, "keyframes");
  ASSERT_FALSE(keyframes.empty()) << info.output;
  EXPECT_EQ(cellText(html, "map.keyframes"), keyframes);
  EXPECT_EQ(cellText(html, "map.points"), infoLine(info.output, "points"));
  EXPECT_EQ(cellText(html, "map.maps"), infoLine(info.output, "maps"));
  EXPECT_EQ(cellText(html, "map.sensor"), infoLine(info.output, "sensor") + " 640x480");
  EXPECT_NE(html.find(map().string()), std::string::npos);
  EXPECT_EQ(html.find("class=\"note\""), std::string::npos) << "a section says something failed";
}

TEST_F(CliReportMoving, AGoneMapFileIsSaid) {
  const auto copy = dir_->path() / "map_gone";
  std::filesystem::create_directories(copy);
  for (const char* name : {"trajectory.txt", "timing.csv"}) {
    std::filesystem::copy_file(out() / name, copy / name);
  }
  auto summary = readRunSummary(out());
  summary["map_file"]["saved"] = (dir_->path() / "gone.map").string();
  std::ofstream(copy / "summary.json") << summary.dump(2);
  const auto report = runCli("report " + copy.string());
  ASSERT_EQ(report.exit_code, 0) << report.output;
  const std::string html = readTextFile(copy / "report.html");
  EXPECT_NE(html.find("id=\"map\""), std::string::npos);
  EXPECT_NE(html.find("The map file cannot be read now"), std::string::npos);
  EXPECT_NE(html.find("gone.map"), std::string::npos);
  EXPECT_TRUE(cellText(html, "map.keyframes").empty());
}

// Neither a detector nor the motion test, no map saved: neither section.
TEST_F(CliReportMoving, ARunWithoutDetectorOrMotionTestHasNoMovingSection) {
  const auto plain = dir_->path() / "plain";
  const auto run = runCli("run --dataset tum:" + data().string() +
                          " --no-motion-evidence --sequential --report --out " + plain.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::string html = readTextFile(plain / "report.html");
  EXPECT_NE(html.find("id=\"timing\""), std::string::npos);
  EXPECT_EQ(html.find("id=\"moving\""), std::string::npos);
  EXPECT_EQ(html.find("id=\"map\""), std::string::npos);
  EXPECT_TRUE(cellText(html, "moving.dropped_per_frame").empty());
}

TEST(CliReportErrors, AFolderWithoutARunIsAClearError) {
  TempDir dir("cli_report_errors");
  const auto missing = runCli("report " + (dir.path() / "nothing").string());
  EXPECT_NE(missing.exit_code, 0);
  EXPECT_NE(missing.output.find("nothing: no such run folder"), std::string::npos)
      << missing.output;

  const auto empty = runCli("report " + dir.path().string());
  EXPECT_NE(empty.exit_code, 0);
  EXPECT_NE(empty.output.find("summary.json: run summary not found"), std::string::npos)
      << empty.output;

  std::ofstream(dir.path() / "summary.json") << "{ \"status\": \"complete\", \"frames\": ";
  const auto broken = runCli("report " + dir.path().string());
  EXPECT_NE(broken.exit_code, 0);
  EXPECT_NE(broken.output.find("summary.json: malformed run summary (not JSON)"), std::string::npos)
      << broken.output;

  std::ofstream(dir.path() / "summary.json") << R"({"status": "complete", "frames": 3})";
  const auto incomplete = runCli("report " + dir.path().string());
  EXPECT_NE(incomplete.exit_code, 0);
  EXPECT_NE(incomplete.output.find("summary.json: malformed run summary: no \"tracked\" count"),
            std::string::npos)
      << incomplete.output;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "report.html"));
}

TEST(CliReportRepeat, ReportsEachRunAndLinksThem) {
  TempDir dir("cli_report_repeat");
  const auto data = dir.path() / "data";
  const auto out = dir.path() / "out";
  ASSERT_EQ(runCli("synth " + data.string() + " --preset xyz-rgbd --frames 30 --seed 4").exit_code,
            0);
  const auto run =
      runCli("run --dataset tum:" + data.string() + " --repeat 2 --out " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto report = runCli("report " + out.string());
  ASSERT_EQ(report.exit_code, 0) << report.output;
  const std::string html = readTextFile(out / "report.html");
  for (int k = 1; k <= 2; ++k) {
    const std::string run_k = "run_" + std::to_string(k);
    EXPECT_NE(html.find("href=\"" + run_k + "/report.html\""), std::string::npos) << run_k;
    EXPECT_EQ(cellText(html, run_k + ".tracked"),
              std::to_string(readRunSummary(out / run_k)["tracked"].get<int>()));
    EXPECT_FALSE(imageSources(readTextFile(out / run_k / "report.html")).empty()) << run_k;
  }
}

TEST_F(CliReport, OpensInHeadlessChromiumWithoutConsoleErrors) {
  ASSERT_TRUE(haveChromium()) << "no /usr/bin/chromium: scripts/install-deps.sh installs it";
  const auto browser = openInChromium(out() / "report.html", dir_->path());
  ASSERT_EQ(browser.exit_code, 0);
  EXPECT_TRUE(browser.console.empty()) << browser.console.front();
  for (const char* element : {"id=\"evaluation\"", "data-key=\"ate.rmse\"", "id=\"moving\"",
                              "id=\"frames\"", "<svg", "<img"}) {
    EXPECT_NE(browser.dom.find(element), std::string::npos) << element;
  }
}

// The check above can fail: a page with a script error is caught.
TEST(CliReportBrowser, TheConsoleCheckCatchesAScriptError) {
  ASSERT_TRUE(haveChromium()) << "no /usr/bin/chromium: scripts/install-deps.sh installs it";
  TempDir dir("cli_report_browser");
  std::ofstream(dir.path() / "bad.html")
      << "<!DOCTYPE html><html><body><p>x</p><script>notDefined();</script></body></html>";
  const auto browser = openInChromium(dir.path() / "bad.html", dir.path());
  ASSERT_EQ(browser.exit_code, 0);
  ASSERT_FALSE(browser.console.empty());
  EXPECT_NE(browser.console.front().find("Uncaught ReferenceError"), std::string::npos);
}

}  // namespace
