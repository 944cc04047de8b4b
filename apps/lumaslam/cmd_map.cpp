// `lumaslam map info FILE`: what a map file (`lumaslam run --save-map`) holds and what it was
// made with, after checking it completely (docs/maps.md).
#include <cstdio>
#include <memory>
#include <string>

#include "command_registry.h"
#include "lumaslam/map/map_file.h"

namespace lumaslam::cli {
namespace {

void printFingerprint(const map::MapFingerprint& f) {
  std::printf("sensor %s\nimage %dx%d\n", f.sensor.c_str(), f.image_width, f.image_height);
  std::printf("camera fx %.6f fy %.6f cx %.6f cy %.6f bf %.6f\n", f.camera.fx, f.camera.fy,
              f.camera.cx, f.camera.cy, f.camera.bf);
  std::printf("orb features %d scale %.4f levels %d fast %d/%d\n", f.orb_features,
              f.orb_scale_factor, f.orb_levels, f.orb_ini_fast, f.orb_min_fast);
  std::printf("vocabulary %s (%016llx)\n",
              f.vocabulary_name.empty() ? "none" : f.vocabulary_name.c_str(),
              static_cast<unsigned long long>(f.vocabulary));
}

int runInfo(const std::string& file) {
  const auto info = map::readMapFileInfo(file);
  std::printf("format lumaslam-map version %u\nbytes %ju\n", info.version, info.bytes);
  std::printf("keyframes %zu\npoints %zu\nmaps %zu\n", info.keyframes, info.points,
              info.maps.size());
  for (const auto& [id, keyframes] : info.maps) std::printf("map %u: %zu keyframes\n", id, keyframes);
  const Eigen::Vector3d extent = info.centre_max - info.centre_min;
  std::printf("keyframe extent %.3f x %.3f x %.3f m\n", extent.x(), extent.y(), extent.z());
  std::printf("time %.6f .. %.6f s\n", info.first_timestamp, info.last_timestamp);
  printFingerprint(info.fingerprint);
  return 0;
}

const bool registered = registerCommand(
    "map", "Map files written by `run --save-map`: info", [](CLI::App& cmd) -> Runner {
      auto file = std::make_shared<std::string>();
      cmd.require_subcommand(1);
      CLI::App* info = cmd.add_subcommand("info", "Check a map file and describe it");
      info->add_option("FILE", *file, "Map file")->required();
      return [file] { return runInfo(*file); };
    });

}  // namespace
}  // namespace lumaslam::cli
