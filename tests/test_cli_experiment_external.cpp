// `external:` rows of `lumaslam experiment` (docs/experiments.md): another system's
// trajectories of a plan dataset evaluated against its ground truth as rows of the tables. The
// oracle: the synthetic ground truth with every pose moved by +-c along one direction chosen so
// that the SE3 alignment is exactly the identity, hence ATE = c at every pose (RMSE = mean =
// median = c, std = 0). Also: the external configuration as the baseline (improvement % is the
// formula), --emit writes no job for it and collect keeps it, errors name the plan and key.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "experiment_tables.h"
#include "test_cli.h"

namespace {

using lumaslam::test::readCsv;
using lumaslam::test::readTextFile;
using lumaslam::test::runCli;
using lumaslam::test::TempDir;
using lumaslam::test::writeFile;
namespace fs = std::filesystem;

constexpr const char* kPlan = R"(baseline: orb
datasets:
  - spec: "synth:xyz-rgbd"
    frames: 30
configurations:
  - name: default
    sequential: true
external:
  - name: orb                  # ORB-SLAM3 stand-in: runs 1 and 2
    dataset: xyz-rgbd-s1
    trajectory: [orb_1cm.txt, orb_2cm.txt]
    format: tum
)";

using Fields = std::vector<std::string>;

std::vector<Fields> tumLines(const fs::path& file) {
  std::ifstream in(file);
  std::vector<Fields> lines;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    Fields fields;
    for (std::string w; words >> w;) fields.push_back(w);
    lines.push_back(fields);
  }
  return lines;
}

// Pose i moved by (-1)^i c d, over an even number of poses, with d along
// w = sum (-1)^i (p_i - mean p): the moves have zero mean and add c/|w| w w^T to the
// cross-covariance of the alignment, which stays symmetric positive definite, so the best
// rotation is the identity and the best translation zero: every pose is off by exactly c.
void writeMovedTrajectory(const std::vector<Fields>& truth, double c, const fs::path& file) {
  const std::size_t n = truth.size() / 2 * 2;
  std::vector<Eigen::Vector3d> p;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    p.emplace_back(std::stod(truth[i][1]), std::stod(truth[i][2]), std::stod(truth[i][3]));
    mean += p.back() / static_cast<double>(n);
  }
  Eigen::Vector3d w = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) w += (i % 2 == 0 ? 1.0 : -1.0) * (p[i] - mean);
  const Eigen::Vector3d d = w.normalized() * c;
  std::ofstream out(file);
  out.precision(17);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d q = p[i] + (i % 2 == 0 ? 1.0 : -1.0) * d;
    out << truth[i][0] << ' ' << q.x() << ' ' << q.y() << ' ' << q.z();
    for (std::size_t k = 4; k < 8; ++k) out << ' ' << truth[i][k];
    out << '\n';
  }
}

const std::map<std::string, std::string>& rowOf(
    const std::vector<std::map<std::string, std::string>>& rows, const std::string& config,
    const std::string& run) {
  for (const auto& row : rows) {
    if (row.at("config") == config && row.at("run") == run) return row;
  }
  static const std::map<std::string, std::string> none;
  ADD_FAILURE() << "no row " << config << " " << run;
  return none;
}

// data-value of the report.html cell with this data-key and data-config.
double reportValue(const std::string& html, const std::string& key, const std::string& config) {
  const std::regex cell("data-key=\"" + key + "\" data-value=\"([^\"]*)\"[^>]*data-config=\"" +
                        config + "\"");
  std::smatch match;
  if (!std::regex_search(html, match, cell)) {
    ADD_FAILURE() << "no " << key << " cell for " << config;
    return NAN;
  }
  return std::stod(match[1].str());
}

class CliExperimentExternal : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<TempDir>("cli_experiment_external");
    // The same preset, seed and frames as the plan's dataset: the same ground truth.
    const auto truth = dir_->path() / "truth";
    const auto synth =
        runCli("synth " + truth.string() + " --preset xyz-rgbd --frames 30 --seed 1");
    ASSERT_EQ(synth.exit_code, 0) << synth.output;
    const auto lines = tumLines(truth / "groundtruth.txt");
    poses_ = lines.size() / 2 * 2;
    writeMovedTrajectory(lines, 0.01, dir_->path() / "orb_1cm.txt");
    writeMovedTrajectory(lines, 0.02, dir_->path() / "orb_2cm.txt");
    plan_ = writeFile(dir_->path() / "plan.yaml", kPlan);
    const auto result = runCli("experiment " + plan_.string() + " --out " + out().string());
    ASSERT_EQ(result.exit_code, 0) << result.output;
  }
  static void TearDownTestSuite() { dir_.reset(); }
  static fs::path out() { return dir_->path() / "out"; }

  static std::unique_ptr<TempDir> dir_;
  static fs::path plan_;
  static std::size_t poses_;
};

std::unique_ptr<TempDir> CliExperimentExternal::dir_;
fs::path CliExperimentExternal::plan_;
std::size_t CliExperimentExternal::poses_ = 0;

TEST_F(CliExperimentExternal, ResultsRowsAreTheOracle) {
  const auto rows = readCsv(out() / "results.csv");
  ASSERT_EQ(rows.size(), 3U);
  EXPECT_EQ(rowOf(rows, "default", "1").at("status"), "complete");
  for (const auto& [run, c] : {std::pair{"1", 0.01}, std::pair{"2", 0.02}}) {
    const auto& row = rowOf(rows, "orb", run);
    EXPECT_EQ(row.at("dataset"), "xyz-rgbd-s1");
    EXPECT_EQ(row.at("status"), "complete");
    EXPECT_EQ(row.at("frames"), std::to_string(poses_));
    EXPECT_EQ(row.at("tracked"), std::to_string(poses_));
    for (const char* column : {"ate_rmse", "ate_mean", "ate_median"}) {
      EXPECT_NEAR(std::stod(row.at(column)), c, 1e-9) << column << " run " << run;
    }
    EXPECT_NEAR(std::stod(row.at("ate_std")), 0.0, 1e-9);
    EXPECT_EQ(row.count("ms_per_frame_median") ? row.at("ms_per_frame_median") : "", "");
  }
  const auto summary = readCsv(out() / "summary.csv");
  ASSERT_EQ(summary.size(), 2U);
  EXPECT_EQ(summary[1].at("config"), "orb");
  EXPECT_EQ(summary[1].at("runs"), "2");
  EXPECT_EQ(summary[1].at("complete"), "2");
  EXPECT_NEAR(std::stod(summary[1].at("ate_rmse_median")), 0.015, 1e-9);
}

TEST_F(CliExperimentExternal, TheExternalBaselinesImprovementIsTheFormula) {
  const std::string html = readTextFile(out() / "report.html");
  EXPECT_NE(html.find("orb (baseline)"), std::string::npos);
  const double slam =
      std::stod(rowOf(readCsv(out() / "results.csv"), "default", "1").at("ate_rmse"));
  const double base = 0.015;  // median of the two external runs
  EXPECT_NEAR(reportValue(html, "cell.improvement_pct", "default"), (base - slam) / base * 100.0,
              1e-6);
  EXPECT_NEAR(reportValue(html, "cell.improvement_pct", "orb"), 0.0, 1e-12);
  EXPECT_NEAR(reportValue(html, "cell.ate_rmse", "orb"), base, 1e-9);
}

TEST_F(CliExperimentExternal, EmitWritesNoJobForItAndCollectKeepsIt) {
  const auto emitted = dir_->path() / "emitted";
  const auto emit =
      runCli("experiment " + plan_.string() + " --out " + emitted.string() + " --emit parallel");
  ASSERT_EQ(emit.exit_code, 0) << emit.output;
  const auto jobs = readTextFile(emitted / "jobs.txt");
  EXPECT_EQ(std::count(jobs.begin(), jobs.end(), '\n'), 1) << jobs;
  EXPECT_EQ(jobs.find("orb"), std::string::npos);
  const auto collect = runCli("experiment collect " + emitted.string());
  ASSERT_EQ(collect.exit_code, 0) << collect.output;
  const auto rows = readCsv(emitted / "results.csv");
  ASSERT_EQ(rows.size(), 3U);
  EXPECT_EQ(rowOf(rows, "default", "1").at("status"), "not run");
  EXPECT_EQ(rowOf(rows, "orb", "1").at("status"), "complete");
  EXPECT_NEAR(std::stod(rowOf(rows, "orb", "2").at("ate_rmse")), 0.02, 1e-9);
}

// As `lumaslam run`: Sim3 for a monocular dataset (settings say so), so the ground truth at
// twice the scale has ATE 0 there and not with SE3 on the same images as RGB-D.
TEST_F(CliExperimentExternal, AMonocularDatasetIsAlignedWithSim3) {
  std::ofstream scaled(dir_->path() / "scaled.txt");
  scaled.precision(17);
  for (const auto& pose : tumLines(dir_->path() / "truth" / "groundtruth.txt")) {
    scaled << pose[0];
    for (int k = 1; k < 4; ++k) scaled << ' ' << 2.0 * std::stod(pose[k]);
    for (int k = 4; k < 8; ++k) scaled << ' ' << pose[k];
    scaled << '\n';
  }
  scaled.close();
  const auto configs = lumaslam::test::sourceDir() / "configs";
  for (const auto& [kind, settings] :
       {std::pair{"tum-mono", "tum_fr3_mono.yaml"}, std::pair{"tum", "tum_fr3_rgbd.yaml"}}) {
    const auto plan = writeFile(dir_->path() / "scaled.yaml",
                                std::string("datasets:\n  - name: d\n    spec: \"") + kind +
                                    ":truth\"\n    settings: " + (configs / settings).string() +
                                    "\nconfigurations:\n  - name: a\nexternal:\n  - name: b\n"
                                    "    dataset: d\n    trajectory: scaled.txt\n");
    const auto out = dir_->path() / (std::string("scaled_") + kind);
    const auto emit =
        runCli("experiment " + plan.string() + " --out " + out.string() + " --emit parallel");
    ASSERT_EQ(emit.exit_code, 0) << emit.output;
    const auto summary = lumaslam::test::readRunSummary(out / "runs" / "d" / "b" / "run_1");
    const std::string mode = summary["evaluation"]["alignment"]["mode"];
    const double rmse = summary["evaluation"]["ate"]["rmse"];
    if (std::string(kind) == "tum-mono") {
      EXPECT_EQ(mode, "sim3");
      EXPECT_LT(rmse, 1e-9);
    } else {
      EXPECT_EQ(mode, "se3");
      EXPECT_GT(rmse, 0.01);
    }
  }
}

// `plan.yaml` with `from` replaced by `to`, run: the error output, and that nothing ran.
std::string planError(const fs::path& dir, const std::string& from, const std::string& to) {
  std::string text = kPlan;
  text.replace(text.find(from), from.size(), to);
  const auto plan = writeFile(dir / "bad.yaml", text);
  const auto result = runCli("experiment " + plan.string() + " --out " + (dir / "bad").string());
  EXPECT_NE(result.exit_code, 0);
  EXPECT_FALSE(fs::exists(dir / "bad" / "runs"));
  return result.output;
}

TEST_F(CliExperimentExternal, BadEntriesAreErrorsNamingThePlanAndKeyBeforeAnyRun) {
  const fs::path& dir = dir_->path();
  const std::string plan = (dir / "bad.yaml").string();
  auto output = planError(dir, "orb_2cm.txt", "missing.txt");
  EXPECT_NE(output.find(plan + ": external[0].trajectory: " + (dir / "missing.txt").string() +
                        " not found"),
            std::string::npos)
      << output;
  output = planError(dir, "dataset: xyz-rgbd-s1", "dataset: xyz-rgbd");
  EXPECT_NE(output.find(plan + ": external[0].dataset: 'xyz-rgbd' is not a dataset of the plan "
                               "(datasets: xyz-rgbd-s1)"),
            std::string::npos)
      << output;
  output = planError(dir, "format: tum", "format: euroc");
  EXPECT_NE(output.find(plan + ": external[0].trajectory: "), std::string::npos) << output;
  output = planError(dir, "format: tum", "format: orb");
  EXPECT_NE(output.find(plan + ": external[0].format: 'orb'"), std::string::npos) << output;
  output = planError(dir, "name: orb ", "name: default ");
  EXPECT_NE(output.find(plan + ": external[0].name: 'default' is a configuration"),
            std::string::npos)
      << output;
}

}  // namespace
