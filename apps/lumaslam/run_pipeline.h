#pragma once
// The main job shared by `lumaslam run` and `lumaslam demo`: read a dataset, track every
// frame, write trajectory.txt, keyframes.txt, timing.csv, moving_features.txt and summary.json
// into `out`, and evaluate against the dataset's ground truth when it has one.
#include <filesystem>
#include <optional>
#include <string>

namespace lumaslam::cli {

struct RunOptions {
  std::filesystem::path settings;  // empty: DATASET_PATH/settings.yaml (synthetic datasets)
  std::string dataset;             // tum:PATH, euroc:PATH, ...
  std::optional<std::string> enhance_preset;
  std::optional<std::string> detector;  // yolo:MODEL.onnx | boxes:FILE | none (else settings)
  std::filesystem::path out = "lumaslam_out";
  std::optional<std::size_t> max_frames;
  bool sequential = false;
  std::optional<std::filesystem::path> vocabulary;  // overrides Loop.vocabulary
  bool no_loop_closing = false;                     // overrides Loop.closing
  bool no_motion_evidence = false;                  // overrides Dynamic.motionEvidence
  bool strict_settings = false;                     // unknown settings keys are an error
  // Map files (docs/maps.md): start from a saved map, track without mapping, save at the end.
  std::optional<std::filesystem::path> load_map;
  bool localization = false;  // needs load_map
  std::optional<std::filesystem::path> save_map;
  // With save_map: also save every this many frames (0: only at the end), so that a crash or
  // a killed run leaves the map of its last save (each save is atomic, docs/maps.md).
  std::size_t save_map_every = 0;
  // A frame that cannot be read or tracked (unreadable image, wrong size, missing depth):
  // skip it with a warning (default), or stop there; either way what was tracked is written.
  enum class BadFrame { Skip, Stop };
  BadFrame on_bad_frame = BadFrame::Skip;
  // The live viewer (docs/viewer.md): serve the page on this port (0: any free port).
  std::optional<int> viewer_port;
  std::string viewer_address = "127.0.0.1";
  bool viewer_paused = false;  // wait for the page's Step / Resume before the first frame
  bool viewer_keep = false;    // after the results are written, serve until Ctrl-C
};

// Removes the files an earlier run left in `out` (trajectory*.txt, keyframes.txt, timing.csv,
// moving_features.txt, summary.json, evaluation.svg, repeatability.json, manifest.json,
// report.html): a folder holds one run's results.
void removeEarlierOutputs(const std::filesystem::path& out);

// Returns the process exit code: 0, 1 when stopped at a bad frame, 128 + signal when stopped
// by SIGINT / SIGTERM (results written and marked partial). Throws lumaslam::Error for bad
// input found before the first frame and for output that cannot be written.
int runPipeline(const RunOptions& options);

// `run --print-settings`: prints the settings the run would use (the file's values over the
// defaults for its sensor, with the command line's overrides) as settings-file lines; runs
// nothing. Returns 0.
int printEffectiveSettings(const RunOptions& options);

}  // namespace lumaslam::cli
