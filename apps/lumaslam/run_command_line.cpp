#include "run_command_line.h"

#include <system_error>

namespace lumaslam::cli {
namespace {

// One word, so that a value starting with '-' stays a value.
void addOption(std::vector<std::string>& words, const char* flag, const std::string& value) {
  words.push_back(std::string(flag) + "=" + value);
}

void addFlag(std::vector<std::string>& words, const char* flag, bool set) {
  if (set) words.emplace_back(flag);
}

void addDatasetOptions(std::vector<std::string>& words, const RunOptions& o) {
  addOption(words, "--dataset", o.dataset);
  if (!o.settings.empty()) addOption(words, "--settings", o.settings.string());
  addOption(words, "--out", o.out.string());
  if (o.max_frames) addOption(words, "--max-frames", std::to_string(*o.max_frames));
  if (o.on_bad_frame == RunOptions::BadFrame::Stop) addOption(words, "--on-bad-frame", "stop");
  addFlag(words, "--strict-settings", o.strict_settings);
}

void addPipelineOptions(std::vector<std::string>& words, const RunOptions& o) {
  if (o.enhance_preset) addOption(words, "--enhance", *o.enhance_preset);
  if (o.detector) addOption(words, "--detector", *o.detector);
  if (o.vocabulary) addOption(words, "--vocabulary", o.vocabulary->string());
  addFlag(words, "--sequential", o.sequential);
  addFlag(words, "--no-loop-closing", o.no_loop_closing);
  addFlag(words, "--no-motion-evidence", o.no_motion_evidence);
}

void addMapOptions(std::vector<std::string>& words, const RunOptions& o) {
  if (o.load_map) addOption(words, "--load-map", o.load_map->string());
  addFlag(words, "--localization", o.localization);
  if (o.save_map) addOption(words, "--save-map", o.save_map->string());
  if (o.save_map_every > 0) addOption(words, "--save-map-every", std::to_string(o.save_map_every));
}

void addViewerOptions(std::vector<std::string>& words, const RunOptions& o) {
  if (!o.viewer_port) return;
  addOption(words, "--viewer", std::to_string(*o.viewer_port));
  if (o.viewer_address != RunOptions().viewer_address) {
    addOption(words, "--viewer-address", o.viewer_address);
  }
  addFlag(words, "--viewer-paused", o.viewer_paused);
  addFlag(words, "--viewer-keep", o.viewer_keep);
}

}  // namespace

std::vector<std::string> runArguments(const RunOptions& options) {
  std::vector<std::string> words;
  addDatasetOptions(words, options);
  addPipelineOptions(words, options);
  addMapOptions(words, options);
  addViewerOptions(words, options);
  return words;
}

std::string shellQuote(const std::string& word) {
  constexpr const char* kSafe =
      "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-+=/.,:@%";
  if (!word.empty() && word.find_first_not_of(kSafe) == std::string::npos) return word;
  std::string quoted = "'";
  for (const char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string shellCommandLine(const std::vector<std::string>& words) {
  std::string line;
  for (const auto& word : words) {
    if (!line.empty()) line += ' ';
    line += shellQuote(word);
  }
  return line;
}

std::filesystem::path thisExecutable() {
  std::error_code error;
  const auto path = std::filesystem::read_symlink("/proc/self/exe", error);
  return error ? std::filesystem::path("lumaslam") : path;
}

std::string runCommandLine(const RunOptions& options) {
  std::vector<std::string> words{thisExecutable().string(), "run"};
  const auto arguments = runArguments(options);
  words.insert(words.end(), arguments.begin(), arguments.end());
  return shellCommandLine(words);
}

}  // namespace lumaslam::cli
