#include "experiment_plan.h"

#include <algorithm>
#include <cctype>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <opencv2/core.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/core/read_file.h"
#include "lumaslam/core/settings_lines.h"
#include "lumaslam/io/trajectory_io.h"
#include "lumaslam/synth/preset.h"

namespace lumaslam::cli {
namespace {

// One map of the plan and the key path that names it in errors ("datasets[1]").
struct Section {
  const Plan& plan;
  cv::FileNode node;
  std::string path;

  std::string key(const std::string& name) const { return path.empty() ? name : path + "." + name; }
  [[noreturn]] void invalid(const std::string& name, const std::string& why) const {
    fail("{}: {}: {}", plan.file.string(), key(name), why);
  }
  cv::FileNode operator[](const std::string& name) const { return node[name]; }
};

// cv::FileStorage keeps a comment after an unquoted value as part of it ("off  # no
// enhancement"), or reads it as a map when the comment holds ": ". YAML ends a value at " #".
std::string withoutComments(const std::string& yaml) {
  std::string out;
  std::istringstream lines(yaml);
  for (std::string line; std::getline(lines, line);) {
    std::string_view kept = core::withoutComment(line);
    while (!kept.empty() && std::isspace(static_cast<unsigned char>(kept.back()))) {
      kept.remove_suffix(1);
    }
    out.append(kept).push_back('\n');
  }
  return out;
}

cv::FileStorage openPlan(const std::filesystem::path& file) {
  std::string yaml = withoutComments(core::readWholeFile(file, "plan file"));
  core::requireUtf8Text(yaml, file.string());
  core::requireBlankAfterDocumentMarkers(yaml, file.string());
  // cv::FileStorage needs the header that hand-written files usually leave out.
  if (!yaml.starts_with("%YAML")) yaml = "%YAML:1.0\n" + yaml;
  cv::FileStorage storage;
  try {
    storage.open(yaml, cv::FileStorage::READ | cv::FileStorage::MEMORY);
  } catch (const cv::Exception& e) {
    fail("{}: not a valid YAML plan: {}", file.string(), e.err);
  } catch (const std::exception& e) {  // OpenCV's parser lets some std::length_error escape
    fail("{}: not a valid YAML plan ({})", file.string(), e.what());
  }
  if (!storage.isOpened()) fail("{}: not a valid YAML plan", file.string());
  return storage;
}

void requireKnownKeys(const Section& s, const std::vector<std::string>& known) {
  if (!s.node.isMap()) fail("{}: {}: expected a map of keys", s.plan.file.string(), s.path);
  for (const auto& name : s.node.keys()) {
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      s.invalid(name, fmt::format("unknown key (known: {})", fmt::join(known, ", ")));
    }
  }
}

std::optional<std::string> findString(const Section& s, const std::string& name) {
  const cv::FileNode n = s[name];
  if (n.empty()) return std::nullopt;
  if (n.isString()) return static_cast<std::string>(n);
  if (n.isInt()) return std::to_string(static_cast<int>(n));
  s.invalid(name, "expected a string");
}

std::string requiredString(const Section& s, const std::string& name) {
  auto value = findString(s, name);
  if (!value || value->empty()) s.invalid(name, "missing (expected a string)");
  return *value;
}

std::optional<int> findInt(const Section& s, const std::string& name, int min) {
  const cv::FileNode n = s[name];
  if (n.empty()) return std::nullopt;
  if (!n.isInt() || static_cast<int>(n) < min) {
    s.invalid(name, fmt::format("expected an integer >= {}", min));
  }
  return static_cast<int>(n);
}

bool boolOr(const Section& s, const std::string& name, bool fallback) {
  const cv::FileNode n = s[name];
  if (n.empty()) return fallback;
  if (n.isInt() && (static_cast<int>(n) == 0 || static_cast<int>(n) == 1)) {
    return static_cast<int>(n) == 1;
  }
  const std::string text = n.isString() ? static_cast<std::string>(n) : std::string();
  if (text == "true" || text == "on") return true;
  if (text == "false" || text == "off") return false;
  s.invalid(name, "expected true or false");
}

std::vector<int> seedsOf(const Section& s) {
  const cv::FileNode n = s["seeds"];
  if (n.empty()) return {1};
  if (n.isInt() && static_cast<int>(n) >= 0) return {static_cast<int>(n)};
  if (!n.isSeq()) s.invalid("seeds", "expected a list of non-negative integers");
  std::vector<int> seeds;
  for (const auto& item : n) {
    if (!item.isInt() || static_cast<int>(item) < 0) {
      s.invalid("seeds", "expected a list of non-negative integers");
    }
    seeds.push_back(static_cast<int>(item));
  }
  if (seeds.empty()) s.invalid("seeds", "empty list");
  return seeds;
}

// Names become folder names: nothing that could leave DIR/runs/.
void requireFolderName(const Section& s, const std::string& key, const std::string& name) {
  const bool safe = std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.';
  });
  if (name.empty() || !safe || name == "." || name == "..") {
    s.invalid(key, fmt::format("'{}' is not a folder name (letters, digits, '-', '_', '.')", name));
  }
}

std::filesystem::path fromPlanFolder(const Plan& plan, const std::filesystem::path& path) {
  return path.is_absolute() ? path : plan.file.parent_path() / path;
}

// "tum:rel/path" -> "tum:PLAN_FOLDER/rel/path"; the path must exist.
std::string resolveSpec(const Section& s, const std::string& spec) {
  const auto colon = spec.find(':');
  if (colon == std::string::npos) s.invalid("spec", fmt::format("'{}' is not KIND:PATH", spec));
  const auto path = fromPlanFolder(s.plan, spec.substr(colon + 1));
  if (!std::filesystem::exists(path)) {
    s.invalid("spec", fmt::format("'{}': {} not found", spec, path.string()));
  }
  return spec.substr(0, colon + 1) + path.string();
}

std::string defaultName(const std::string& spec) {
  auto name = std::filesystem::path(spec.substr(spec.find(':') + 1)).filename().string();
  if (name.empty()) name = std::filesystem::path(spec).parent_path().filename().string();
  return name;
}

void readSynthDatasets(const Section& s, const std::string& preset_name,
                       std::vector<PlanDataset>& out) {
  const synth::Preset* preset = nullptr;
  try {
    preset = &synth::findPreset(preset_name);
  } catch (const Error& e) {
    s.invalid("spec", e.what());
  }
  const int frames = findInt(s, "frames", 1).value_or(preset->frames);
  const std::string base = findString(s, "name").value_or(preset_name);
  for (const int seed : seedsOf(s)) {
    PlanDataset d;
    d.name = fmt::format("{}-s{}", base, seed);
    requireFolderName(s, "name", d.name);
    d.synth = PlanDataset::Synth{preset_name, static_cast<std::uint64_t>(seed), frames,
                                 fmt::format("{}-s{}-f{}", preset_name, seed, frames),
                                 preset->sensor == synth::SensorKind::Stereo};
    out.push_back(std::move(d));
  }
}

// cv::FileStorage reads an unquoted `spec: tum:/data/x` as the map {tum: /data/x}.
std::string specOf(const Section& s) {
  const cv::FileNode n = s["spec"];
  if (n.isMap() && n.size() == 1 && n[n.keys().front()].isString()) {
    return n.keys().front() + ":" + static_cast<std::string>(n[n.keys().front()]);
  }
  return requiredString(s, "spec");
}

std::vector<int> levelsOf(const Section& s) {
  const cv::FileNode n = s["levels"];
  if (n.empty()) s.invalid("levels", "missing (perturb needs a list of levels 0..5)");
  std::vector<int> levels;
  const auto add = [&](const cv::FileNode& item) {
    if (!item.isInt() || static_cast<int>(item) < 0 || static_cast<int>(item) > 5) {
      s.invalid("levels", "expected a list of integers 0..5");
    }
    levels.push_back(static_cast<int>(item));
  };
  if (n.isSeq()) {
    for (const auto& item : n) add(item);
  } else {
    add(n);
  }
  if (levels.empty()) s.invalid("levels", "empty list");
  return levels;
}

// `perturb:` and `levels:`: each dataset read from this section becomes one per level,
// named NAME-MODELLEVEL.
void expandPerturbed(const Section& s, std::vector<PlanDataset>& datasets) {
  const auto model = findString(s, "perturb");
  if (!model) {
    if (!s["levels"].empty()) s.invalid("levels", "only with perturb: MODEL");
    return;
  }
  std::vector<PlanDataset> expanded;
  for (const auto& dataset : datasets) {
    for (const int level : levelsOf(s)) {
      PlanDataset d = dataset;
      d.name = fmt::format("{}-{}{}", dataset.name, *model, level);
      requireFolderName(s, "perturb", d.name);
      const std::string source = dataset.synth ? dataset.synth->folder : dataset.name;
      d.perturb = PlanDataset::Perturb{*model, level,
                                       fmt::format("perturbed/{}-{}{}", source, *model, level),
                                       dataset.spec, s.key("perturb")};
      expanded.push_back(std::move(d));
    }
  }
  datasets = std::move(expanded);
}

void readDatasetsOfSpec(const Section& s, std::vector<PlanDataset>& out) {
  const std::string spec = specOf(s);
  if (spec.starts_with("synth:")) {
    if (!s["settings"].empty()) s.invalid("settings", "synth datasets bring their own");
    readSynthDatasets(s, spec.substr(6), out);
    return;
  }
  if (!s["seeds"].empty()) s.invalid("seeds", "only synth: datasets have seeds");
  PlanDataset d;
  d.spec = resolveSpec(s, spec);
  d.name = findString(s, "name").value_or(defaultName(spec));
  requireFolderName(s, "name", d.name);
  if (const auto settings = findString(s, "settings")) {
    d.settings = fromPlanFolder(s.plan, *settings);
    if (!std::filesystem::is_regular_file(d.settings)) {
      s.invalid("settings", fmt::format("{} not found", d.settings.string()));
    }
  }
  if (const auto frames = findInt(s, "frames", 1)) d.max_frames = *frames;
  out.push_back(std::move(d));
}

void readDataset(const Section& s, std::vector<PlanDataset>& out) {
  requireKnownKeys(s, {"name", "spec", "settings", "seeds", "frames", "perturb", "levels"});
  std::vector<PlanDataset> read;
  readDatasetsOfSpec(s, read);
  expandPerturbed(s, read);
  out.insert(out.end(), read.begin(), read.end());
}

// "yolo:rel/model.onnx" -> "yolo:PLAN_FOLDER/rel/model.onnx"; likewise boxes:FILE unless it
// names the run's dataset folder ({dataset}). "none" and absolute paths are kept.
std::string resolveDetector(const Section& s, const std::string& detector) {
  const auto colon = detector.find(':');
  if (colon == std::string::npos || detector.find("{dataset}") != std::string::npos) {
    return detector;
  }
  return detector.substr(0, colon + 1) +
         fromPlanFolder(s.plan, detector.substr(colon + 1)).string();
}

PlanConfig readConfig(const Section& s) {
  requireKnownKeys(s, {"name", "settings", "enhance", "detector", "detector_classes", "sensor",
                       "vocabulary", "sequential", "loop_closing", "motion_evidence"});
  PlanConfig c;
  c.name = requiredString(s, "name");
  requireFolderName(s, "name", c.name);
  c.enhance = findString(s, "enhance");
  if (const auto detector = findString(s, "detector")) c.detector = resolveDetector(s, *detector);
  if (const auto settings = findString(s, "settings")) {
    c.settings = fromPlanFolder(s.plan, *settings);
    if (!std::filesystem::is_regular_file(*c.settings)) {
      s.invalid("settings", fmt::format("{} not found", c.settings->string()));
    }
  }
  c.sensor = findString(s, "sensor");
  if (c.sensor && *c.sensor != "mono" && *c.sensor != "stereo" && *c.sensor != "rgbd") {
    s.invalid("sensor", fmt::format("'{}' (expected mono, stereo or rgbd)", *c.sensor));
  }
  c.detector_classes = findString(s, "detector_classes");
  if (c.detector_classes && c.detector_classes->empty()) {
    s.invalid("detector_classes", "empty (expected class names, e.g. \"person\")");
  }
  if (const auto vocabulary = findString(s, "vocabulary")) {
    c.vocabulary = *vocabulary == "none" ? std::filesystem::path(*vocabulary)
                                         : fromPlanFolder(s.plan, *vocabulary);
  }
  c.sequential = boolOr(s, "sequential", false);
  c.loop_closing = boolOr(s, "loop_closing", true);
  c.motion_evidence = boolOr(s, "motion_evidence", true);
  return c;
}

// `trajectory: FILE` or `trajectory: [FILE, ...]` (one run each), from the plan's folder.
std::vector<std::filesystem::path> trajectoriesOf(const Section& s) {
  const cv::FileNode n = s["trajectory"];
  std::vector<std::string> names;
  if (n.isSeq()) {
    for (const auto& item : n) {
      if (!item.isString()) s.invalid("trajectory", "expected a file or a list of files");
      names.push_back(static_cast<std::string>(item));
    }
    if (names.empty()) s.invalid("trajectory", "empty list");
  } else {
    names.push_back(requiredString(s, "trajectory"));
  }
  std::vector<std::filesystem::path> files;
  for (const auto& name : names) files.push_back(fromPlanFolder(s.plan, name));
  return files;
}

// Reads each file now, so that a missing or malformed one is an error before any run.
void requireReadableTrajectories(const Section& s, const PlanExternal& e) {
  try {
    const auto format = io::parseTrajectoryFormat(e.format);
    for (const auto& file : e.trajectories) {
      if (!std::filesystem::is_regular_file(file)) fail("{} not found", file.string());
      io::readTrajectory(file, format, e.times);
    }
  } catch (const Error& error) {
    s.invalid("trajectory", error.what());
  }
}

void requireKnownDataset(const Section& s, const std::string& dataset) {
  std::vector<std::string> names;
  for (const auto& d : s.plan.datasets) names.push_back(d.name);
  if (std::find(names.begin(), names.end(), dataset) == names.end()) {
    s.invalid("dataset", fmt::format("'{}' is not a dataset of the plan (datasets: {})", dataset,
                                     fmt::join(names, ", ")));
  }
}

void requireNotAConfiguration(const Section& s, const std::string& name) {
  for (const auto& c : s.plan.configs) {
    if (c.name == name) s.invalid("name", fmt::format("'{}' is a configuration's name", name));
  }
}

PlanExternal readExternal(const Section& s) {
  requireKnownKeys(s, {"name", "dataset", "trajectory", "format", "times"});
  PlanExternal e;
  e.key = s.path;
  e.name = requiredString(s, "name");
  requireFolderName(s, "name", e.name);
  requireNotAConfiguration(s, e.name);
  e.dataset = requiredString(s, "dataset");
  requireKnownDataset(s, e.dataset);
  e.format = findString(s, "format").value_or("auto");
  if (e.format != "auto" && e.format != "tum" && e.format != "euroc" && e.format != "kitti") {
    s.invalid("format", fmt::format("'{}': expected auto, tum, euroc or kitti", e.format));
  }
  if (const auto times = findString(s, "times")) {
    e.times = fromPlanFolder(s.plan, *times);
    if (!std::filesystem::is_regular_file(e.times)) {
      s.invalid("times", fmt::format("{} not found", e.times.string()));
    }
  }
  e.trajectories = trajectoriesOf(s);
  requireReadableTrajectories(s, e);
  return e;
}

// Each external name appears once per dataset.
void requireUniqueExternals(const Plan& plan) {
  std::set<std::pair<std::string, std::string>> seen;
  for (const auto& e : plan.externals) {
    if (!seen.insert({e.name, e.dataset}).second) {
      fail("{}: external: '{}' is given twice for dataset '{}'", plan.file.string(), e.name,
           e.dataset);
    }
  }
}

void readExternals(const Section& top, Plan& plan) {
  const cv::FileNode externals = top["external"];
  if (externals.empty()) return;
  if (!externals.isSeq()) top.invalid("external", "expected a list");
  for (int i = 0; i < static_cast<int>(externals.size()); ++i) {
    plan.externals.push_back(readExternal({plan, externals[i], fmt::format("external[{}]", i)}));
  }
  requireUniqueExternals(plan);
}

cv::FileNode requiredList(const Section& top, const std::string& name) {
  const cv::FileNode n = top[name];
  if (n.empty()) top.invalid(name, "missing (expected a list)");
  if (!n.isSeq() || n.size() == 0) top.invalid(name, "expected a non-empty list");
  return n;
}

template <typename T>
void requireUniqueNames(const Plan& plan, const std::vector<T>& items, const char* list) {
  std::set<std::string> seen;
  for (const auto& item : items) {
    if (!seen.insert(item.name).second) {
      fail("{}: {}: the name '{}' is used twice", plan.file.string(), list, item.name);
    }
  }
}

// `baseline: NAME` names one of the configurations or external names; without it, the first
// configuration.
std::string baselineOf(const Section& top) {
  const auto name = findString(top, "baseline");
  if (!name) return top.plan.configs.front().name;
  std::vector<std::string> names;
  for (const auto& c : top.plan.configs) names.push_back(c.name);
  for (const auto& e : top.plan.externals) {
    if (std::find(names.begin(), names.end(), e.name) == names.end()) names.push_back(e.name);
  }
  if (std::find(names.begin(), names.end(), *name) == names.end()) {
    top.invalid("baseline", fmt::format("'{}' is not a configuration (configurations: {})", *name,
                                        fmt::join(names, ", ")));
  }
  return *name;
}

}  // namespace

Plan readPlan(const std::filesystem::path& file) {
  Plan plan;
  plan.file = file;
  const cv::FileStorage storage = openPlan(file);
  const Section top{plan, storage.root(), ""};
  requireKnownKeys(top, {"runs", "datasets", "configurations", "external", "baseline"});
  plan.runs = findInt(top, "runs", 1).value_or(1);
  const cv::FileNode datasets = requiredList(top, "datasets");
  for (int i = 0; i < static_cast<int>(datasets.size()); ++i) {
    readDataset({plan, datasets[i], fmt::format("datasets[{}]", i)}, plan.datasets);
  }
  const cv::FileNode configs = requiredList(top, "configurations");
  for (int i = 0; i < static_cast<int>(configs.size()); ++i) {
    plan.configs.push_back(readConfig({plan, configs[i], fmt::format("configurations[{}]", i)}));
  }
  requireUniqueNames(plan, plan.datasets, "datasets");
  requireUniqueNames(plan, plan.configs, "configurations");
  readExternals(top, plan);
  plan.baseline = baselineOf(top);
  return plan;
}

}  // namespace lumaslam::cli
