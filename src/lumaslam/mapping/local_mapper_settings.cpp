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
  core::readSection(file, "LocalMapping", params,
                    [](auto& keys, auto& p) { visitLocalMappingKeys(keys, p); });
}

std::string printLocalMappingSettings(const LocalMapperParams& params) {
  return core::printSection("LocalMapping", params,
                            [](auto& keys, auto& p) { visitLocalMappingKeys(keys, p); });
}

}  // namespace lumaslam::mapping
