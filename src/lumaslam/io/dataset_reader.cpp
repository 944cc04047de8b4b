#include "lumaslam/io/dataset_reader.h"

#include <algorithm>
#include <array>

#include "lumaslam/core/error.h"
#include "lumaslam/io/euroc_reader.h"
#include "lumaslam/io/folder_reader.h"
#include "lumaslam/io/kitti_reader.h"
#include "lumaslam/io/trajectory_io.h"
#include "lumaslam/io/tum_rgbd_reader.h"
#include "lumaslam/io/video_reader.h"

namespace lumaslam::io {

namespace {
constexpr std::array<std::string_view, 8> kKinds = {"tum",   "tum-mono",   "euroc",  "euroc-mono",
                                                    "kitti", "kitti-mono", "folder", "video"};
constexpr std::string_view kKindList =
    "tum, tum-mono, euroc, euroc-mono, kitti, kitti-mono, folder, video";

struct DatasetSpec {
  std::string kind;
  std::filesystem::path path;
};

// "kind:PATH"; nullopt when there is no known kind before the first ':'.
std::optional<DatasetSpec> splitSpec(const std::string& spec) {
  const auto colon = spec.find(':');
  if (colon == std::string::npos) return std::nullopt;
  const std::string kind = spec.substr(0, colon);
  if (std::find(kKinds.begin(), kKinds.end(), kind) == kKinds.end()) return std::nullopt;
  return DatasetSpec{kind, spec.substr(colon + 1)};
}

DatasetSpec requireKnownKind(const std::string& spec) {
  auto parsed = splitSpec(spec);
  if (!parsed) fail("dataset '{}': expected KIND:PATH with KIND one of {}", spec, kKindList);
  return *parsed;
}

DatasetSpec parseSpec(const std::string& spec) {
  DatasetSpec parsed = requireKnownKind(spec);
  if (parsed.path.empty()) fail("dataset '{}': the path after '{}:' is empty", spec, parsed.kind);
  std::error_code ec;
  if (!std::filesystem::exists(parsed.path, ec))
    fail("{}: dataset path not found (from '{}')", parsed.path.string(), spec);
  return parsed;
}
}  // namespace

std::filesystem::path datasetPathOf(const std::string& spec) {
  return requireKnownKind(spec).path;
}

std::unique_ptr<DatasetReader> openDataset(const std::string& spec, const ReaderOptions& options) {
  const auto [kind, path] = parseSpec(spec);
  if (kind == "tum" || kind == "tum-mono")
    return std::make_unique<TumRgbdReader>(path, kind == "tum", options);
  if (kind == "euroc" || kind == "euroc-mono")
    return std::make_unique<EurocReader>(path, kind == "euroc", options);
  if (kind == "kitti" || kind == "kitti-mono")
    return std::make_unique<KittiReader>(path, kind == "kitti", options);
  if (kind == "folder") return std::make_unique<FolderReader>(path, options);
  return std::make_unique<VideoReader>(path, options);
}

Trajectory loadGroundTruth(const std::string& spec) {
  const auto split = splitSpec(spec);
  if (!split) return readTrajectory(spec);
  const auto [kind, path] = parseSpec(spec);
  Trajectory trajectory;
  if (kind == "tum" || kind == "tum-mono") {
    trajectory = TumRgbdReader::readGroundTruth(path);
  } else if (kind == "euroc" || kind == "euroc-mono") {
    trajectory = EurocReader::readGroundTruth(path);
  } else if (kind == "kitti" || kind == "kitti-mono") {
    trajectory = KittiReader::readGroundTruth(path);
  } else {
    fail("dataset '{}': a {} has no ground truth", spec, kind);
  }
  if (trajectory.empty()) fail("dataset '{}': no ground-truth file found", spec);
  return trajectory;
}

}  // namespace lumaslam::io
