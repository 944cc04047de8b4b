#include "lumaslam/eval/evaluation.h"

#include <spdlog/fmt/fmt.h>

#include "lumaslam/eval/association.h"

namespace lumaslam::eval {

namespace {

nlohmann::json statsJson(const ErrorStats& stats) {
  return {{"rmse", stats.rmse}, {"mean", stats.mean}, {"median", stats.median}, {"std", stats.std},
          {"min", stats.min},   {"max", stats.max},   {"count", stats.count}};
}

std::string statsRow(const std::string& name, const std::string& unit, const ErrorStats& s) {
  return fmt::format("{:<16} {:>10.6f} {:>10.6f} {:>10.6f} {:>10.6f} {:>10.6f} {:>10.6f} {:>7}\n",
                     name + " [" + unit + "]", s.rmse, s.mean, s.median, s.std, s.min, s.max,
                     s.count);
}

}  // namespace

EvaluationReport evaluate(const Trajectory& estimate, const Trajectory& ground_truth,
                          const EvaluationOptions& options) {
  const AssociatedTrajectories matched = associate(estimate, ground_truth, options.max_dt);
  EvaluationReport report;
  report.options = options;
  report.estimate_poses = estimate.size();
  report.ground_truth_poses = ground_truth.size();
  report.matched_poses = matched.size();
  report.ground_truth_in_span = matched.ground_truth_in_span;
  report.coverage = matched.coverage();
  report.alignment = align(matched.estimate, matched.ground_truth, options.align);
  report.aligned_estimate = report.alignment.apply(matched.estimate);
  report.ground_truth = matched.ground_truth;
  report.ate = computeAte(report.aligned_estimate, report.ground_truth);
  report.rpe = computeRpe(report.aligned_estimate, report.ground_truth, options.rpe);
  return report;
}

nlohmann::json toJson(const EvaluationReport& report) {
  nlohmann::json ate = statsJson(report.ate.stats);
  ate["coverage"] = report.coverage;

  nlohmann::json rotation = nlohmann::json::array();
  for (int r = 0; r < 3; ++r) {
    rotation.push_back(
        {report.alignment.R(r, 0), report.alignment.R(r, 1), report.alignment.R(r, 2)});
  }
  const Eigen::Vector3d& t = report.alignment.t;
  return {
      {"ate", ate},
      {"rpe",
       {{"trans", statsJson(report.rpe.translation)},
        {"rot", statsJson(report.rpe.rotation)},
        {"delta", report.options.rpe.delta},
        {"unit", toString(report.options.rpe.unit)},
        {"all_pairs", report.options.rpe.all_pairs}}},
      {"alignment",
       {{"mode", toString(report.alignment.mode)},
        {"scale", report.alignment.scale},
        {"rotation", rotation},
        {"translation", {t.x(), t.y(), t.z()}}}},
      {"association",
       {{"max_dt", report.options.max_dt},
        {"estimate_poses", report.estimate_poses},
        {"ground_truth_poses", report.ground_truth_poses},
        {"matched", report.matched_poses},
        {"ground_truth_in_span", report.ground_truth_in_span}}},
  };
}

std::string formatTable(const EvaluationReport& report) {
  const auto& rpe = report.options.rpe;
  std::string table = fmt::format(
      "matched {} of {} estimate poses to {} ground-truth poses (max dt {} s); coverage "
      "{:.1f}% ({} ground-truth poses in the estimate's span)\n",
      report.matched_poses, report.estimate_poses, report.ground_truth_poses, report.options.max_dt,
      100.0 * report.coverage, report.ground_truth_in_span);
  table += fmt::format("alignment {}: scale {:.6f}, translation [{:.4f} {:.4f} {:.4f}]\n",
                       toString(report.alignment.mode), report.alignment.scale,
                       report.alignment.t.x(), report.alignment.t.y(), report.alignment.t.z());
  table += fmt::format("RPE over {} pose pairs {} {} apart ({})\n\n", report.rpe.pairs.size(),
                       rpe.delta, toString(rpe.unit),
                       rpe.all_pairs ? "all pairs" : "consecutive pairs, as evo's default");
  table += fmt::format("{:<16} {:>10} {:>10} {:>10} {:>10} {:>10} {:>10} {:>7}\n", "metric", "rmse",
                       "mean", "median", "std", "min", "max", "count");
  table += statsRow("ATE", "m", report.ate.stats);
  table += statsRow("RPE trans", "m", report.rpe.translation);
  table += statsRow("RPE rot", "deg", report.rpe.rotation);
  return table;
}

}  // namespace lumaslam::eval
