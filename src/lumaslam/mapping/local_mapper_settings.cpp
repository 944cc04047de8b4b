#include "lumaslam/mapping/local_mapper_settings.h"

#include "lumaslam/core/settings_section.h"

namespace lumaslam::mapping {
namespace {

using core::Range;

template <typename Keys>
void visitLocalMappingKeys(Keys& keys, LocalMapperParams& p) {
  keys("triangulationNeighbours", p.triangulation_neighbours, Range::atLeast(1));
  keys("fusionNeighbours", p.fusion_neighbours, Range::atLeast(0));
  keys("bundleAdjustment", p.bundle_adjustment);
  keys("baIterations", p.ba_iterations, Range::atLeast(1));
  keys("keyframeCulling", p.keyframe_culling);
  keys("redundancy", p.redundancy, Range{0.0, 1.0, false});
}

}  // namespace

void readLocalMappingSettings(const core::SettingsFile& file, LocalMapperParams& params) {
  const core::SectionReader reader(file, "LocalMapping");
  visitLocalMappingKeys(reader, params);
}

std::string printLocalMappingSettings(const LocalMapperParams& params) {
  core::SectionPrinter printer("LocalMapping");
  LocalMapperParams copy = params;
  visitLocalMappingKeys(printer, copy);
  return printer.text();
}

}  // namespace lumaslam::mapping
