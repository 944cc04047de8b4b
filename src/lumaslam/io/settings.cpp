#include "lumaslam/io/settings.h"

#include <cmath>
#include <initializer_list>

#include <spdlog/spdlog.h>
#include <Eigen/Core>

#include "lumaslam/core/error.h"
#include "lumaslam/core/settings_section.h"

namespace lumaslam::io {
namespace {

using core::SettingsFile;
using Keys = std::initializer_list<std::string_view>;

// Reads one value that may be stored under its ORB-SLAM3 name or its older ORB-SLAM2 name
// (`keys`, newest first) and remembers which key held it, so checks can name that key.
class KeyReader {
 public:
  explicit KeyReader(const SettingsFile& file) : file_(file) {}

  const SettingsFile& file() const { return file_; }

  // The first of `keys` the file has; every one is asked (core::unknownKeys), so that an old
  // name beside the new one is not reported as unknown.
  std::optional<std::string_view> presentKey(Keys keys) const {
    std::optional<std::string_view> present;
    for (const auto key : keys) {
      if (file_.has(key) && !present) present = key;
    }
    return present;
  }
  bool hasAny(Keys keys) const { return presentKey(keys).has_value(); }

  template <typename T>
  std::optional<T> find(Keys keys, std::string_view* used = nullptr) const {
    const auto key = presentKey(keys);
    if (!key) return std::nullopt;
    if (used) *used = *key;
    return file_.get<T>(*key);
  }

  template <typename T>
  T get(Keys keys, std::string_view* used = nullptr) const {
    if (auto value = find<T>(keys, used)) return *value;
    try {
      (void)file_.get<T>(*keys.begin());  // throws "key K is missing (expected T)"
    } catch (const Error& e) {
      if (keys.size() < 2) throw;
      fail("{} (old name: '{}')", e.what(), *std::next(keys.begin()));
    }
    fail("{}: key '{}' is missing", file_.origin(), *keys.begin());
  }

  template <typename T>
  T get(Keys keys, T fallback, std::string_view* used = nullptr) const {
    return find<T>(keys, used).value_or(fallback);
  }

  template <typename T>
  void requireAbove(std::string_view key, T value, T bound) const {
    if (!(value > bound)) file_.invalid(key, fmt::format("must be > {}, found {}", bound, value));
  }

 private:
  const SettingsFile& file_;
};

camera::CameraModel readCameraModel(const KeyReader& in) {
  const auto type = in.file().get<std::string>("Camera.type", "PinHole");
  if (type == "PinHole" || type == "Pinhole" || type == "pinhole")
    return camera::CameraModel::Pinhole;
  if (type == "Rectified" || type == "rectified") return camera::CameraModel::Rectified;
  if (type == "KannalaBrandt8") {
    in.file().invalid("Camera.type",
                      "fisheye model 'KannalaBrandt8' is not supported; use "
                      "'PinHole' or 'Rectified'");
  }
  in.file().invalid("Camera.type",
                    fmt::format("expected 'PinHole' or 'Rectified', found '{}'", type));
}

// Image size, fps and colour order are shared by both cameras (Camera.* in both formats).
void readImageFormat(const KeyReader& in, camera::CameraSettings& camera) {
  camera.size.width = in.get<int>({"Camera.width"});
  camera.size.height = in.get<int>({"Camera.height"});
  in.requireAbove("Camera.width", camera.size.width, 0);
  in.requireAbove("Camera.height", camera.size.height, 0);
  camera.fps = in.get<double>({"Camera.fps"}, 30.0);
  in.requireAbove("Camera.fps", camera.fps, 0.0);
  camera.rgb = in.get<bool>({"Camera.RGB"}, false);

  const auto newWidth = in.find<int>({"Camera.newWidth"});
  const auto newHeight = in.find<int>({"Camera.newHeight"});
  if (newWidth.has_value() != newHeight.has_value()) {
    in.file().invalid(newWidth ? "Camera.newHeight" : "Camera.newWidth",
                      "is missing: Camera.newWidth and Camera.newHeight go together");
  }
  if (newWidth) {
    in.requireAbove("Camera.newWidth", *newWidth, 0);
    in.requireAbove("Camera.newHeight", *newHeight, 0);
    camera.resizeTo = camera::ImageSize{*newWidth, *newHeight};
  }
}

// Intrinsics of camera `index` (1 or 2); camera 1 also answers to the old Camera.* keys.
camera::CameraSettings readCamera(const KeyReader& in, int index, camera::CameraModel model,
                                  const camera::CameraSettings& format) {
  camera::CameraSettings camera = format;
  camera.model = model;
  const std::string prefix = fmt::format("Camera{}.", index);
  const std::string oldPrefix = index == 1 ? "Camera." : prefix;
  // Returns the value and the key that held it (the new name when it came from `fallback`).
  const auto number = [&](std::string_view name, std::optional<double> fallback) {
    const std::string newKey = prefix + std::string(name);
    const std::string oldKey = oldPrefix + std::string(name);
    std::string_view used = newKey;
    const double value = fallback ? in.get<double>({newKey, oldKey}, *fallback, &used)
                                  : in.get<double>({newKey, oldKey}, &used);
    return std::pair{value, std::string(used)};
  };

  std::string key;
  std::tie(camera.fx, key) = number("fx", std::nullopt);
  in.requireAbove(key, camera.fx, 0.0);
  std::tie(camera.fy, key) = number("fy", std::nullopt);
  in.requireAbove(key, camera.fy, 0.0);
  std::tie(camera.cx, key) = number("cx", std::nullopt);
  if (camera.cx < 0.0 || camera.cx > camera.size.width) {
    in.file().invalid(key, fmt::format("principal point x must lie in [0, Camera.width={}], "
                                       "found {}",
                                       camera.size.width, camera.cx));
  }
  std::tie(camera.cy, key) = number("cy", std::nullopt);
  if (camera.cy < 0.0 || camera.cy > camera.size.height) {
    in.file().invalid(key, fmt::format("principal point y must lie in [0, Camera.height={}], "
                                       "found {}",
                                       camera.size.height, camera.cy));
  }
  const std::array<std::string_view, 5> names{"k1", "k2", "p1", "p2", "k3"};
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (model == camera::CameraModel::Pinhole) {
      camera.distortion[i] = number(names[i], 0.0).first;
    } else {  // a rectified camera has none (ORB-SLAM3): known keys, values not used
      (void)in.hasAny({prefix + std::string(names[i]), oldPrefix + std::string(names[i])});
    }
  }
  return camera;
}

SE3 readPose(const KeyReader& in, std::string_view key) {
  const cv::Mat m = in.file().getMatrix(key, 4, 4);
  Eigen::Matrix4d T;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) T(r, c) = m.at<double>(r, c);
  }
  if (!T.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1), 1e-6)) {
    in.file().invalid(key, "last row must be [0, 0, 0, 1]");
  }
  const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
  // Files store float ("dt: f"), so allow float round-off, then snap to the nearest rotation.
  const double error = (R.transpose() * R - Eigen::Matrix3d::Identity()).norm();
  if (error > 1e-4 || R.determinant() < 0.0) {
    in.file().invalid(key,
                      fmt::format("top-left 3x3 is not a rotation (|R^T R - I| = {:.2g})", error));
  }
  SE3 pose = SE3::Identity();
  pose.linear() = Eigen::Quaterniond(R).normalized().toRotationMatrix();
  pose.translation() = T.topRightCorner<3, 1>();
  return pose;
}

// Baseline of a rectified pair or RGB-D camera: Stereo.b, or the old Camera.bf divided by fx.
double readBaseline(const KeyReader& in, double fx, std::string_view why) {
  std::string_view key;
  if (const auto b = in.find<double>({"Stereo.b"}, &key)) {
    in.requireAbove(key, *b, 0.0);
    return *b;
  }
  if (const auto bf = in.find<double>({"Camera.bf"}, &key)) {
    in.requireAbove(key, *bf, 0.0);
    return *bf / fx;
  }
  fail(
      "{}: key 'Stereo.b' is missing (expected number, metres; old name: 'Camera.bf' = "
      "baseline * fx): {}",
      in.file().origin(), why);
}

camera::StereoSettings readStereo(const KeyReader& in, const camera::CameraSettings& left,
                                  const camera::CameraSettings& format) {
  camera::StereoSettings stereo;
  const bool hasRight = in.hasAny({"Camera2.fx"});
  if (left.model == camera::CameraModel::Pinhole && (hasRight || in.hasAny({"Stereo.T_c1_c2"}))) {
    if (!hasRight) {
      fail(
          "{}: key 'Camera2.fx' is missing (expected number): a PinHole stereo pair with "
          "Stereo.T_c1_c2 needs the second camera's calibration Camera2.*",
          in.file().origin());
    }
    stereo.right = readCamera(in, 2, camera::CameraModel::Pinhole, format);
    stereo.T_c1_c2 = readPose(in, "Stereo.T_c1_c2");
    const double norm = stereo.T_c1_c2.translation().norm();
    std::string_view key = "Stereo.T_c1_c2";
    stereo.baseline = in.get<double>({"Stereo.b"}, norm, &key);
    in.requireAbove(key, stereo.baseline, 0.0);
    return stereo;
  }
  // A row-aligned pair: Camera.type Rectified, or an ORB-SLAM2 file with Camera.bf.
  if (left.hasDistortion()) {
    spdlog::warn(
        "{}: stereo without Camera2.* is treated as rectified; the distortion of "
        "camera 1 is applied to both images",
        in.file().origin());
  }
  stereo.baseline = readBaseline(in, left.fx, "a stereo sensor needs its baseline");
  stereo.T_c1_c2.translation() = Eigen::Vector3d(stereo.baseline, 0.0, 0.0);
  return stereo;
}

SensorType parseSensor(const KeyReader& in, const std::string& name) {
  if (name == "mono" || name == "monocular") return SensorType::Monocular;
  if (name == "stereo") return SensorType::Stereo;
  if (name == "rgbd" || name == "rgb-d" || name == "RGBD" || name == "RGB-D")
    return SensorType::Rgbd;
  in.file().invalid("System.sensor",
                    fmt::format("expected 'mono', 'stereo' or 'rgbd', found '{}'", name));
}

SensorType chooseSensor(const KeyReader& in, std::optional<SensorType> requested) {
  if (requested) return *requested;
  if (const auto name = in.find<std::string>({"System.sensor"})) return parseSensor(in, *name);
  SensorType inferred = SensorType::Monocular;
  if (in.hasAny({"RGBD.DepthMapFactor", "DepthMapFactor"})) {
    inferred = SensorType::Rgbd;
  } else if (in.hasAny({"Camera2.fx", "Stereo.T_c1_c2", "Stereo.b", "Camera.bf"}) ||
             in.file().get<std::string>("Camera.type", "") == "Rectified") {
    inferred = SensorType::Stereo;
  }
  spdlog::debug("{}: no System.sensor, inferred '{}' from the keys present", in.file().origin(),
                toString(inferred));
  return inferred;
}

// System.queueCapacity sized no queue (the detection queue has Detector.queueCapacity, the
// keyframe queues their own rules) and is no longer read (issue 21): files that set it still
// load, with a warning instead of the unknown-key one.
void warnAboutRetiredKeys(const KeyReader& in) {
  if (in.hasAny({"System.queueCapacity"})) {
    spdlog::warn(
        "{}: key 'System.queueCapacity' is ignored: it never sized a queue and is no longer "
        "read; the detection queue's size is Detector.queueCapacity (docs/settings.md)",
        in.file().origin());
  }
}

// The System.* keys read over the defaults and printed by printSystemSettings.
template <typename Keys>
void visitSystemKeys(Keys& keys, SystemSettings& system) {
  keys("sequential", system.sequential);
  keys("newMapAfter", system.newMapAfter);  // negative: stay lost
}

SystemSettings readSystem(const KeyReader& in) {
  SystemSettings system;
  core::readSection(in.file(), "System", system,
                    [](auto& keys, auto& s) { visitSystemKeys(keys, s); });
  warnAboutRetiredKeys(in);
  if (const auto root = in.find<std::string>({"System.datasetRoot"})) {
    if (root->empty()) in.file().invalid("System.datasetRoot", "must not be empty");
    system.datasetRoot = *root;
  }
  return system;
}

DynamicSettings readDynamic(const KeyReader& in) {
  DynamicSettings dynamic;
  dynamic.motionEvidence = in.find<bool>({"Dynamic.motionEvidence"});
  return dynamic;
}

LoopSettings readLoop(const KeyReader& in) {
  LoopSettings loop;
  if (const auto vocabulary = in.find<std::string>({"Loop.vocabulary"})) {
    if (vocabulary->empty()) in.file().invalid("Loop.vocabulary", "must not be empty");
    loop.vocabulary = *vocabulary;
  }
  loop.closing = in.get<bool>({"Loop.closing"}, loop.closing);
  return loop;
}

void checkFileVersion(const KeyReader& in) {
  if (const auto version = in.find<std::string>({"File.version"}); version && *version != "1.0") {
    in.file().invalid("File.version", fmt::format("expected \"1.0\", found \"{}\"", *version));
  }
}

}  // namespace

std::string printSystemSettings(SensorType sensor, const SystemSettings& system) {
  core::SectionPrinter keys("System");
  keys("sensor", std::string(toString(sensor)));
  SystemSettings copy = system;
  visitSystemKeys(keys, copy);
  // Absolute: a relative root was resolved against the settings file's folder.
  if (!system.datasetRoot.empty()) {
    keys("datasetRoot", std::filesystem::absolute(system.datasetRoot).string());
  }
  return keys.text();
}

std::string_view toString(SensorType sensor) {
  switch (sensor) {
    case SensorType::Monocular:
      return "mono";
    case SensorType::Stereo:
      return "stereo";
    case SensorType::Rgbd:
      return "rgbd";
  }
  return "?";
}

std::string Settings::summary() const {
  const camera::CameraSettings c = camera.atWorkingSize();
  std::string text = fmt::format("{}, {} {}x{} @{} Hz, fx={} fy={} cx={} cy={}{}", toString(sensor),
                                 toString(c.model), c.size.width, c.size.height, c.fps, c.fx, c.fy,
                                 c.cx, c.cy, c.hasDistortion() ? ", distorted" : "");
  if (stereo) {
    text += fmt::format(", b={:.4f} m, ThDepth={}", stereo->baseline, depth.thDepth);
    if (stereo->right) text += ", unrectified pair";
  }
  if (sensor == SensorType::Rgbd) text += fmt::format(", DepthMapFactor={}", depth.depthMapFactor);
  if (system.sequential) text += ", sequential";
  return text;
}

Settings Settings::fromFile(std::shared_ptr<const core::SettingsFile> file,
                            std::optional<SensorType> sensor) {
  if (!file) fail("Settings::fromFile: no settings file given");
  const KeyReader in(*file);
  checkFileVersion(in);

  Settings settings;
  settings.file = file;
  settings.sensor = chooseSensor(in, sensor);

  camera::CameraSettings format;
  readImageFormat(in, format);
  settings.camera = readCamera(in, 1, readCameraModel(in), format);

  if (settings.sensor != SensorType::Monocular) {
    std::string_view key = "Stereo.ThDepth";
    settings.depth.thDepth = in.get<double>({"Stereo.ThDepth", "ThDepth"}, &key);
    in.requireAbove(key, settings.depth.thDepth, 0.0);
  }
  if (settings.sensor == SensorType::Stereo) {
    settings.stereo = readStereo(in, settings.camera, format);
  } else if (settings.sensor == SensorType::Rgbd) {
    camera::StereoSettings projector;
    projector.baseline =
        readBaseline(in, settings.camera.fx, "RGB-D needs the IR projector baseline");
    projector.T_c1_c2.translation() = Eigen::Vector3d(projector.baseline, 0.0, 0.0);
    settings.stereo = projector;
    std::string_view key = "RGBD.DepthMapFactor";
    settings.depth.depthMapFactor = in.get<double>({"RGBD.DepthMapFactor", "DepthMapFactor"}, &key);
    in.requireAbove(key, settings.depth.depthMapFactor, 0.0);
  }
  settings.system = readSystem(in);
  settings.loop = readLoop(in);
  settings.dynamic = readDynamic(in);
  return settings;
}

Settings Settings::fromFile(const core::SettingsFile& file, std::optional<SensorType> sensor) {
  return fromFile(std::make_shared<const core::SettingsFile>(file), sensor);
}

Settings loadSettings(const std::filesystem::path& path, std::optional<SensorType> sensor) {
  auto file = std::make_shared<const core::SettingsFile>(core::SettingsFile::open(path));
  Settings settings = Settings::fromFile(std::move(file), sensor);
  settings.path = path;
  for (auto* relative : {&settings.system.datasetRoot, &settings.loop.vocabulary}) {
    // "none" (Loop.vocabulary: none) is a keyword, not a file next to the settings.
    if (relative->empty() || relative->is_absolute() || *relative == "none") continue;
    *relative = path.parent_path() / *relative;
  }
  return settings;
}

}  // namespace lumaslam::io
