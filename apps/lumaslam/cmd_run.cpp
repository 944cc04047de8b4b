#include <cstdio>
#include <memory>
#include <string>

#include <spdlog/spdlog.h>

#include "cli_checks.h"
#include "command_registry.h"
#include "lumaslam/core/error.h"
#include "run_command_line.h"
#include "run_pipeline.h"
#include "run_repeat.h"
#include "run_report.h"

namespace lumaslam::cli {
namespace {

// What `run` reads from its command line: the options, and the overrides that take effect only
// when given (empty or 0 keeps the settings file's value).
struct RunFlags {
  RunOptions options;
  std::size_t max_frames = 0;
  std::string enhance;
  std::string detector;
  std::string vocabulary;
  std::string on_bad_frame = "skip";
  int repeats = 1;
  bool report = false;
  bool print_settings = false;
  bool print_command = false;
};

// After every result (manifest.json included), so a report that fails costs no result.
int reportAfterRun(const std::filesystem::path& out, int code) {
  try {
    writeReport(out, out / "report.html");
    std::printf("report in %s\n", (out / "report.html").string().c_str());
  } catch (const std::exception& e) {
    spdlog::error("report: {}", e.what());
    return code == 0 ? 1 : code;
  }
  return code;
}

// What to read and how: dataset, settings and the overrides of settings-file keys.
void addInputOptions(CLI::App& cmd, const std::shared_ptr<RunFlags>& flags) {
  cmd.add_option("--dataset", flags->options.dataset,
                 "tum:PATH, euroc:PATH, kitti:PATH, folder:PATH or video:FILE (the settings "
                 "say mono, stereo or RGB-D), e.g. a dataset or the output of `lumaslam synth`")
      ->required();
  cmd.add_option("--settings", flags->options.settings,
                 "ORB-SLAM3-style settings YAML (default: PATH/settings.yaml)");
  cmd.add_option("--enhance", flags->enhance,
                 "Enhancement preset overriding Enhancement.preset (off, clahe, paper, best, ...)");
  cmd.add_option("--detector", flags->detector,
                 "Dynamic-object detector overriding Detector.*: yolo:MODEL.onnx, boxes:FILE "
                 "(e.g. a synthetic dataset's detections.txt) or none");
  cmd.add_option("--max-frames", flags->max_frames, "Stop after this many frames (0: all)")
      ->check(wholeNumber(0, 1'000'000'000));
  cmd.add_flag("--sequential", flags->options.sequential,
               "Run every stage (local mapping, loop closing, detection, the right "
               "image's jobs) in the caller's thread (deterministic)");
  cmd.add_option("--vocabulary", flags->vocabulary,
                 "Place-recognition vocabulary for relocalization and loop closing, "
                 "overriding Loop.vocabulary (`lumaslam vocab train/convert` output, or "
                 "ORBvoc.txt), or 'none'; default: the vocabulary shipped with lumaslam");
  cmd.add_flag("--no-loop-closing", flags->options.no_loop_closing,
               "Keep relocalization but do not close loops (overrides Loop.closing)");
  cmd.add_flag("--no-motion-evidence", flags->options.no_motion_evidence,
               "Keep map points that keep moving against the camera's pose (the class-free "
               "motion test, docs/dynamic.md; overrides Dynamic.motionEvidence)");
  cmd.add_flag("--strict-settings", flags->options.strict_settings,
               "Fail on settings keys nothing reads (typos); default: a warning naming the "
               "closest known key");
  cmd.add_option("--on-bad-frame", flags->on_bad_frame,
                 "A frame that cannot be read or tracked (unreadable image, wrong size, "
                 "missing depth): skip it with a warning, or stop there; what was tracked is "
                 "written either way")
      ->check(CLI::IsMember({"skip", "stop"}))
      ->capture_default_str();
}

// Maps saved and loaded (docs/maps.md).
void addMapOptions(CLI::App& cmd, const std::shared_ptr<RunFlags>& flags) {
  cmd.add_option("--load-map", flags->options.load_map,
                 "Start from a map saved by --save-map (same camera, ORB settings and "
                 "vocabulary): the first frame relocalizes in it");
  cmd.add_flag("--localization", flags->options.localization,
               "With --load-map: track against the loaded map, add no keyframes or maps");
  cmd.add_option("--save-map", flags->options.save_map,
                 "Write the map (every map of the atlas) to this file at the end, after the "
                 "results");
  cmd.add_option("--save-map-every", flags->options.save_map_every,
                 "With --save-map: also save every N frames (each save atomic), so that a "
                 "crash or a killed run keeps the map of the last save")
      ->check(wholeNumber(1, 1'000'000'000));
}

// The live viewer (docs/viewer.md).
void addViewerOptions(CLI::App& cmd, const std::shared_ptr<RunFlags>& flags) {
  cmd.add_option("--viewer", flags->options.viewer_port,
                 "Serve a live view of the run on this port (0: any free port; the page is "
                 "at http://127.0.0.1:PORT/, docs/viewer.md)")
      ->expected(0, 1)
      ->default_str("7878")
      ->check(CLI::Range(0, 65535));
  cmd.add_option("--viewer-address", flags->options.viewer_address,
                 "Address the viewer listens on; anything but 127.0.0.1 shows the run to "
                 "the network (a warning says so)")
      ->capture_default_str();
  cmd.add_flag("--viewer-paused", flags->options.viewer_paused,
               "Start the viewer paused: frames advance with the page's Step / Resume");
  cmd.add_flag("--viewer-keep", flags->options.viewer_keep,
               "Keep serving the viewer after the run, until Ctrl-C");
}

// Where results go, and the runs that only print.
void addOutputOptions(CLI::App& cmd, const std::shared_ptr<RunFlags>& flags) {
  cmd.add_option("--out", flags->options.out, "Output folder")->capture_default_str();
  cmd.add_option("--repeat", flags->repeats,
                 "Run N times into OUT/run_K and report the min/median/max spread")
      ->check(wholeNumber(1, 1000));
  cmd.add_flag("--print-settings", flags->print_settings,
               "Print the settings the run would use (Camera, Camera2, Stereo, RGBD, "
               "ORBextractor, System, Enhancement, Detector, Tracking, Initializer, Dynamic, "
               "LocalMapping, Loop; docs/settings.md) as a settings file and exit");
  cmd.add_flag("--report", flags->report,
               "At the end, write OUT/report.html (`lumaslam report OUT`, docs/report.md)");
  cmd.add_flag("--print-command", flags->print_command,
               "Print this run as one `lumaslam run` command line (every option that is not "
               "at its default, quoted for sh) and exit without running");
}

// The overrides given, into the options.
RunOptions optionsOf(const RunFlags& flags) {
  RunOptions options = flags.options;
  options.on_bad_frame =
      flags.on_bad_frame == "stop" ? RunOptions::BadFrame::Stop : RunOptions::BadFrame::Skip;
  if (flags.max_frames > 0) options.max_frames = flags.max_frames;
  if (!flags.enhance.empty()) options.enhance_preset = flags.enhance;
  if (!flags.detector.empty()) options.detector = flags.detector;
  if (!flags.vocabulary.empty()) options.vocabulary = flags.vocabulary;
  return options;
}

// Flags that need another flag, or that one run at a time cannot honour.
void checkFlagCombinations(const RunOptions& options, int repeats) {
  if (options.localization && !options.load_map) {
    fail("--localization needs a map to localize in (--load-map FILE)");
  }
  const bool viewer_flags =
      options.viewer_paused || options.viewer_keep || options.viewer_address != "127.0.0.1";
  if (viewer_flags && !options.viewer_port) {
    fail("--viewer-paused, --viewer-keep and --viewer-address need --viewer");
  }
  if (options.viewer_port && repeats > 1) fail("--viewer with --repeat: one run at a time");
  if (options.save_map_every > 0 && !options.save_map) {
    fail("--save-map-every needs --save-map FILE");
  }
  if (options.save_map && repeats > 1) {
    fail("--save-map with --repeat: every run would write the same file");
  }
}

int runCommand(const RunFlags& flags) {
  const RunOptions options = optionsOf(flags);
  if (flags.print_settings) return printEffectiveSettings(options);
  checkFlagCombinations(options, flags.repeats);
  if (flags.print_command) {
    std::printf("%s\n", runCommandLine(options).c_str());
    return 0;
  }
  const int code = flags.repeats > 1 ? runRepeated(options, flags.repeats) : runPipeline(options);
  return flags.report ? reportAfterRun(options.out, code) : code;
}

const bool registered =
    registerCommand("run", "Run SLAM on a dataset; write trajectory, keyframes, timing and summary",
                    [](CLI::App& cmd) -> Runner {
                      auto flags = std::make_shared<RunFlags>();
                      addInputOptions(cmd, flags);
                      addMapOptions(cmd, flags);
                      addViewerOptions(cmd, flags);
                      addOutputOptions(cmd, flags);
                      return [flags] { return runCommand(*flags); };
                    });

}  // namespace
}  // namespace lumaslam::cli
