#include "experiment_settings.h"

#include "lumaslam/io/dataset_reader.h"
#include "lumaslam/io/output_file.h"
#include "settings_with_classes.h"

namespace lumaslam::cli {
namespace {

std::filesystem::path settingsOf(const PlanDataset& dataset) {
  if (!dataset.settings.empty()) return dataset.settings;
  return io::datasetPathOf(dataset.spec) / "settings.yaml";
}

}  // namespace

std::filesystem::path classSettingsFile(const std::filesystem::path& dir,
                                        const std::string& dataset, const std::string& config) {
  return dir / "settings" / dataset / (config + ".yaml");
}

void writeClassSettings(const Plan& plan, const std::filesystem::path& dir) {
  for (const auto& dataset : plan.datasets) {
    for (const auto& config : plan.configs) {
      if (!config.detector_classes) continue;
      const auto file = classSettingsFile(dir, dataset.name, config.name);
      std::filesystem::create_directories(file.parent_path());
      io::OutputFile out(file);
      out.stream() << settingsWithClasses(settingsOf(dataset), *config.detector_classes);
      out.commit();
    }
  }
}

}  // namespace lumaslam::cli
