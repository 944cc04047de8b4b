// `lumaslam demo`: the main job on data anyone can make. Generates a synthetic RGB-D sequence
// with ground truth (default: people and a crate moving through the view), runs SLAM on it as
// a plain ORB-SLAM-style baseline (no enhancement, no dynamic-object removal, no motion test),
// as lumaslam (enhancement, features on moving objects dropped using the sequence's boxes)
// and, when a YOLO model is found, as lumaslam with YOLO in the loop; prints the evaluations
// side by side.
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "command_registry.h"
#include "lumaslam/core/error.h"
#include "lumaslam/io/output_file.h"
#include "lumaslam/synth/sequence.h"
#include "run_pipeline.h"
#include "settings_copy.h"

namespace lumaslam::cli {
namespace {

struct DemoOptions {
  std::filesystem::path out = "lumaslam_demo";
  std::string preset = "walking-xyz-rgbd";
  int frames = 300;
  std::uint64_t seed = 1;
  bool baseline = true;
  std::optional<std::filesystem::path> model;  // --model: must exist
};

constexpr const char* kModelName = "yolov5n-320.onnx";

// Where the demo looks for a YOLO model without --model: $LUMASLAM_SHARED_DIR/models when the
// variable is set, else ../shared/models (relative to the working directory).
std::filesystem::path defaultModelPath() {
  if (const char* shared = std::getenv("LUMASLAM_SHARED_DIR"); shared && *shared) {
    return std::filesystem::path(shared) / "models" / kModelName;
  }
  return std::filesystem::path("..") / "shared" / "models" / kModelName;
}

// The model of the YOLO row, or nullopt (row skipped, said on stdout). A --model that does not
// exist is an error.
std::optional<std::filesystem::path> findModel(const DemoOptions& options) {
  if (options.model) {
    if (!std::filesystem::is_regular_file(*options.model)) {
      fail("--model {}: no such file", options.model->string());
    }
    return options.model;
  }
  const auto path = defaultModelPath();
  if (std::filesystem::is_regular_file(path)) return path;
  std::printf(
      "YOLO row skipped: no model at %s; get YOLOv5n exported to ONNX at 320 px (README, \"Data "
      "and models\") and pass --model FILE, or set LUMASLAM_SHARED_DIR to the folder holding "
      "models/%s\n",
      path.string().c_str(), kModelName);
  return std::nullopt;
}

struct RunSummary {
  std::string name;
  nlohmann::json summary;
};

nlohmann::json readSummary(const std::filesystem::path& out) {
  std::ifstream in(out / "summary.json");
  if (!in) fail("{}: the run wrote no summary", (out / "summary.json").string());
  return nlohmann::json::parse(in);
}

void printComparison(const std::vector<RunSummary>& runs) {
  std::printf("\n%-34s %8s %8s %12s %12s\n", "run", "tracked", "frames", "ATE RMSE [m]",
              "ms/frame");
  for (const auto& run : runs) {
    const auto& s = run.summary;
    const double ate =
        s.contains("evaluation") ? s["evaluation"]["ate"]["rmse"].get<double>() : -1.0;
    std::printf("%-34s %8d %8d %12.4f %12.1f\n", run.name.c_str(), s["tracked"].get<int>(),
                s["frames"].get<int>(), ate, s["ms_per_frame"]["median"].get<double>());
  }
}

// A copy of the dataset's settings in `out` with Detector.classes "person": YOLO knows no "box"
// (docs/dynamic.md); the motion-evidence test (on by default for RGB-D) catches the crate.
std::filesystem::path personOnlySettings(const std::filesystem::path& data,
                                         const std::filesystem::path& out) {
  const auto path = out / "settings.yaml";
  io::OutputFile file(path);  // creates `out`
  file.stream() << settingsWithValues(data / "settings.yaml", {{"Detector.classes", "person"}});
  file.commit();
  return path;
}

RunOptions runOn(const std::filesystem::path& data, const std::filesystem::path& out) {
  RunOptions run;
  run.dataset = "tum:" + data.string();
  run.out = out;
  return run;
}

RunOptions baselineRun(const std::filesystem::path& data, const std::filesystem::path& out) {
  auto run = runOn(data, out / "baseline");
  run.enhance_preset = "off";
  run.detector = "none";
  run.no_motion_evidence = true;  // on by default for RGB-D: it removes moving things too
  std::printf("\n== baseline: no enhancement, no dynamic-object removal (no motion test)\n");
  return run;
}

// The settings' Enhancement.preset; the generator's boxes when the preset writes them.
RunOptions boxesRun(const std::filesystem::path& data, const std::filesystem::path& out,
                    bool has_boxes) {
  auto run = runOn(data, out / "lumaslam");
  run.detector = has_boxes ? "boxes:" + (data / "detections.txt").string() : "none";
  std::printf("\n== lumaslam: enhancement%s\n",
              has_boxes ? " + features on moving objects dropped (boxes from detections.txt)" : "");
  return run;
}

RunOptions yoloRun(const std::filesystem::path& data, const std::filesystem::path& out,
                   const std::filesystem::path& model) {
  auto run = runOn(data, out / "yolo");
  run.settings = personOnlySettings(data, run.out);
  run.detector = "yolo:" + model.string();
  std::printf("\n== lumaslam + YOLO: enhancement + features in the person boxes of %s dropped\n",
              model.string().c_str());
  return run;
}

// Runs; its summary becomes the table's row `name`. Returns the run's exit code.
int runInto(const RunOptions& run, const std::string& name, std::vector<RunSummary>& runs) {
  if (const int code = runPipeline(run); code != 0) return code;
  runs.push_back({name, readSummary(run.out)});
  return 0;
}

int runDemo(const DemoOptions& options) {
  const auto model = findModel(options);
  const auto data = options.out / "data";
  std::printf("generating %d frames of '%s' in %s ...\n", options.frames, options.preset.c_str(),
              data.string().c_str());
  synth::writeSequence(data, options.preset, options.frames, options.seed);
  const bool has_boxes = std::filesystem::exists(data / "detections.txt");

  std::vector<RunSummary> runs;
  int code = 0;
  if (options.baseline) {
    code = runInto(baselineRun(data, options.out), "baseline (no enhance, no removal)", runs);
  }
  if (code == 0) {
    code = runInto(boxesRun(data, options.out, has_boxes),
                   has_boxes ? "lumaslam (enhance + removal)" : "lumaslam (enhance)", runs);
  }
  if (code == 0 && model) {
    code = runInto(yoloRun(data, options.out, *model), "lumaslam (enhance + YOLO persons)", runs);
  }
  if (code != 0) return code;
  printComparison(runs);
  std::printf("results in %s (trajectories, timing.csv, summary.json, evaluation.svg)\n",
              options.out.string().c_str());
  return 0;
}

const bool registered = registerCommand(
    "demo",
    "Generate a synthetic RGB-D sequence with ground truth and people walking, run SLAM on it "
    "with and without lumaslam's enhancement and dynamic-object removal, compare",
    [](CLI::App& cmd) -> Runner {
      auto options = std::make_shared<DemoOptions>();
      cmd.add_option("--out", options->out, "Output folder")->capture_default_str();
      cmd.add_option("--preset", options->preset, "Synthetic preset (lumaslam synth --list)")
          ->capture_default_str();
      cmd.add_option("--frames", options->frames, "Frames to generate")->capture_default_str();
      cmd.add_option("--seed", options->seed, "Generator seed")->capture_default_str();
      cmd.add_flag("!--no-baseline", options->baseline, "Skip the baseline run");
      cmd.add_option("--model", options->model,
                     "YOLO ONNX model for a third run with YOLO in the loop (default: "
                     "$LUMASLAM_SHARED_DIR/models/yolov5n-320.onnx, else "
                     "../shared/models/yolov5n-320.onnx; skipped when not found)");
      return [options] { return runDemo(*options); };
    });

}  // namespace
}  // namespace lumaslam::cli
