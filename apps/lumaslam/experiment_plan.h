#pragma once
// The plan of `lumaslam experiment PLAN.yaml` (docs/experiments.md): datasets, configurations
// and runs per cell, read with cv::FileStorage. Every unknown key, missing key or wrong value
// is an Error naming the plan file and the key ("plan.yaml: datasets[1].seeds: ...").
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace lumaslam::cli {

struct PlanDataset {
  std::string name;                // folder under DIR/runs/
  std::string spec;                // what `run --dataset` takes; synth: DIR/data/... once made
  std::filesystem::path settings;  // empty: the dataset's settings.yaml
  std::optional<std::size_t> max_frames;
  // synth:PRESET datasets: generated into DIR/data/<folder> before the runs.
  struct Synth {
    std::string preset;
    std::uint64_t seed = 1;
    int frames = 0;
    std::string folder;   // under DIR/data/
    bool stereo = false;  // EuRoC layout (euroc:), else TUM RGB-D (tum:)
  };
  std::optional<Synth> synth;
  // `perturb: MODEL` with `levels: [...]`: one dataset per level, a copy of the dataset (of the
  // synth one once generated) made as `lumaslam perturb` makes it, into DIR/data/<folder>.
  struct Perturb {
    std::string model;        // a synth::PerturbModel name, checked by checkPerturbModels
    int level = 0;            // 0..5
    std::string folder;       // under DIR/data/
    std::string source_spec;  // the dataset copied (a synth one: its generated folder instead)
    std::string key;          // "datasets[i].perturb", for errors
  };
  std::optional<Perturb> perturb;
};

struct PlanConfig {
  std::string name;  // folder under DIR/runs/<dataset>/
  std::optional<std::string> enhance;
  std::optional<std::string> detector;  // "{dataset}" is replaced by the dataset's folder
  // A settings file replacing the dataset's for this configuration's runs.
  std::optional<std::filesystem::path> settings;
  // Detector.classes for this configuration's runs, e.g. "person" (a copy of the settings).
  std::optional<std::string> detector_classes;
  // System.sensor for this configuration's runs, e.g. "mono" for the rgb stream of an RGB-D
  // dataset (a copy of the settings).
  std::optional<std::string> sensor;
  bool changesSettings() const { return detector_classes || sensor; }
  std::optional<std::filesystem::path> vocabulary;
  bool sequential = false;
  bool loop_closing = true;
  bool motion_evidence = true;
};

// `external:` entries: another system's trajectories of one plan dataset, evaluated against its
// ground truth as rows of the tables (configuration `name`, one run per file).
struct PlanExternal {
  std::string key;      // "external[i]", for errors
  std::string name;     // shown as a configuration; folder under DIR/runs/<dataset>/
  std::string dataset;  // a dataset name of the plan (synth: NAME-sSEED)
  std::vector<std::filesystem::path> trajectories;  // run k = trajectories[k - 1]
  std::string format = "auto";                      // as `lumaslam eval --est-format`
  std::filesystem::path times;                      // KITTI timestamps (times.txt), optional
};

struct Plan {
  std::filesystem::path file;
  int runs = 1;
  std::vector<PlanDataset> datasets;  // synth seeds already expanded, one entry each
  std::vector<PlanConfig> configs;
  std::vector<PlanExternal> externals;
  std::string baseline;  // `baseline: NAME`, the configuration (or external name)
                         // report.html compares with; default: the first configuration
};

// Throws Error naming the file and key for anything the plan gets wrong. Relative paths in the
// plan are taken from the plan file's folder.
Plan readPlan(const std::filesystem::path& file);

}  // namespace lumaslam::cli
