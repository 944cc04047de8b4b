#include "experiment_settings.h"

#include <map>

#include "lumaslam/io/dataset_reader.h"
#include "lumaslam/io/output_file.h"
#include "settings_copy.h"

namespace lumaslam::cli {
namespace {

std::filesystem::path settingsOf(const PlanDataset& dataset) {
  if (!dataset.settings.empty()) return dataset.settings;
  return io::datasetPathOf(dataset.spec) / "settings.yaml";
}

std::map<std::string, std::string> valuesOf(const PlanConfig& config) {
  std::map<std::string, std::string> values;
  if (config.detector_classes) values["Detector.classes"] = *config.detector_classes;
  if (config.sensor) values["System.sensor"] = *config.sensor;
  return values;
}

}  // namespace

std::filesystem::path configSettingsFile(const std::filesystem::path& dir,
                                         const std::string& dataset, const std::string& config) {
  return dir / "settings" / dataset / (config + ".yaml");
}

void writeConfigSettings(const Plan& plan, const std::filesystem::path& dir) {
  for (const auto& dataset : plan.datasets) {
    for (const auto& config : plan.configs) {
      if (!config.changesSettings()) continue;
      const auto file = configSettingsFile(dir, dataset.name, config.name);
      std::filesystem::create_directories(file.parent_path());
      io::OutputFile out(file);
      out.stream() << settingsWithValues(config.settings.value_or(settingsOf(dataset)),
                                         valuesOf(config));
      out.commit();
    }
  }
}

}  // namespace lumaslam::cli
