#include "lumaslam/synth/dataset_writer.h"

#include <fstream>
#include <mutex>
#include <vector>

#include <spdlog/spdlog.h>
#include <tbb/parallel_for.h>
#include <Eigen/Geometry>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/io/output_file.h"

namespace lumaslam::synth {

namespace fs = std::filesystem;

namespace {

struct FrameRecord {
  std::int64_t timestamp_ns = 0;
  std::int64_t depth_timestamp_ns = 0;  // TUM: depth.txt lists the depth camera's own stamps
  std::vector<ObjectBox> boxes;
};

void makeDirectory(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) fail("{}: cannot create directory: {}", dir.string(), ec.message());
}

void writeImage(const fs::path& path, const cv::Mat& image) {
  bool ok = false;
  try {
    ok = cv::imwrite(path.string(), image);
  } catch (const cv::Exception& e) {
    fail("{}: cannot write image: {}", path.string(), e.what());
  }
  if (!ok) fail("{}: cannot write image", path.string());
}

// A list file, checked and put in place atomically (io::OutputFile) when it goes out of scope
// without an exception: the lists are written after the images, so a dataset folder has its
// rgb.txt / data.csv only once it is complete.
class TextFile {
 public:
  explicit TextFile(fs::path path) : file_(std::move(path)) {}
  template <typename... Args>
  void line(fmt::format_string<Args...> format, Args&&... args) {
    file_.stream() << fmt::format(format, std::forward<Args>(args)...) << '\n';
  }
  ~TextFile() noexcept(false) {
    if (std::uncaught_exceptions() == 0) file_.commit();
  }

 private:
  io::OutputFile file_;
};

cv::Mat depthToPng(const cv::Mat& depth_m) {
  cv::Mat out;
  depth_m.convertTo(out, CV_16U, 5000.0);  // saturates at 65535 (13.1 m)
  return out;
}

Eigen::Quaterniond unitQuaternion(const SE3& T) {
  Eigen::Quaterniond q(T.linear());
  q.normalize();
  if (q.w() < 0) q.coeffs() *= -1.0;
  return q;
}

std::vector<FrameRecord> renderAll(const SequenceRenderer& sequence,
                                   const std::function<void(const Frame&)>& writeFrame,
                                   const FrameProgress& progress) {
  std::vector<FrameRecord> records(static_cast<size_t>(sequence.frameCount()));
  std::mutex progress_mutex;
  int done = 0;
  tbb::parallel_for(0, sequence.frameCount(), [&](int i) {
    const Frame frame = sequence.render(i);
    writeFrame(frame);
    records[static_cast<size_t>(i)] = {frame.timestamp_ns, frame.depth_timestamp_ns,
                                       frame.cam0.boxes};
    if (progress) {
      const std::lock_guard lock(progress_mutex);
      progress(++done, sequence.frameCount());
    }
  });
  return records;
}

void writeDetections(const fs::path& path, const std::vector<FrameRecord>& records,
                     bool nanoseconds) {
  TextFile file(path);
  file.line("# ground-truth boxes of moving objects in cam0, one line per box");
  file.line(
      "# timestamp class x y w h   (timestamp as in the image names; pixels, top-left corner)");
  for (const auto& r : records)
    for (const auto& b : r.boxes)
      file.line("{} {} {} {} {} {}",
                nanoseconds ? std::to_string(r.timestamp_ns) : tumTimestamp(r.timestamp_ns),
                b.class_name, b.box.x, b.box.y, b.box.width, b.box.height);
}

void writeTum(const SequenceRenderer& sequence, const fs::path& out,
              const FrameProgress& progress) {
  for (const char* dir : {"rgb", "depth", "mask"}) makeDirectory(out / dir);
  const auto records = renderAll(
      sequence,
      [&](const Frame& frame) {
        const std::string stamp = tumTimestamp(frame.timestamp_ns);
        writeImage(out / "rgb" / (stamp + ".png"), frame.cam0.image);
        writeImage(out / "depth" / (tumTimestamp(frame.depth_timestamp_ns) + ".png"),
                   depthToPng(frame.sensor_depth));
        writeImage(out / "mask" / (stamp + ".png"), frame.cam0.mask);
      },
      progress);
  const std::string origin =
      fmt::format("# file: 'lumaslam_synth_{}_seed{}'", sequence.preset().name, sequence.seed());
  {
    TextFile rgb(out / "rgb.txt"), depth(out / "depth.txt"), gt(out / "groundtruth.txt");
    TextFile assoc(out / "associations.txt");
    rgb.line("# color images");
    rgb.line("{}", origin);
    rgb.line("# timestamp filename");
    depth.line("# depth maps");
    depth.line("{}", origin);
    depth.line("# timestamp filename");
    gt.line("# ground truth trajectory");
    gt.line("{}", origin);
    gt.line("# timestamp tx ty tz qx qy qz qw");
    for (const auto& r : records) {
      const std::string stamp = tumTimestamp(r.timestamp_ns);
      const std::string depth_stamp = tumTimestamp(r.depth_timestamp_ns);
      rgb.line("{} rgb/{}.png", stamp, stamp);
      depth.line("{} depth/{}.png", depth_stamp, depth_stamp);
      assoc.line("{} rgb/{}.png {} depth/{}.png", stamp, stamp, depth_stamp, depth_stamp);
      const SE3 T = sequence.poseAt(static_cast<double>(r.timestamp_ns) * 1e-9);
      const Eigen::Quaterniond q = unitQuaternion(T);
      const Eigen::Vector3d p = T.translation();
      gt.line("{} {:.6f} {:.6f} {:.6f} {:.6f} {:.6f} {:.6f} {:.6f}", stamp, p.x(), p.y(), p.z(),
              q.x(), q.y(), q.z(), q.w());
    }
  }
  writeDetections(out / "detections.txt", records, false);
}

std::string eurocSensorYaml(const SequenceRenderer& sequence, int camera) {
  const Rig& rig = sequence.rig();
  const PinholeCamera& c = rig.camera;
  const double tx = camera == 0 ? 0.0 : rig.baseline_m;
  return fmt::format(
      "%YAML:1.0\n"
      "# General sensor definitions.\n"
      "sensor_type: camera\n"
      "comment: lumaslam synthetic cam{} (rectified pinhole, no distortion)\n"
      "\n"
      "# Sensor extrinsics wrt. the body-frame.\n"
      "T_BS:\n"
      "  cols: 4\n"
      "  rows: 4\n"
      "  data: [1.0, 0.0, 0.0, {},\n"
      "         0.0, 1.0, 0.0, 0.0,\n"
      "         0.0, 0.0, 1.0, 0.0,\n"
      "         0.0, 0.0, 0.0, 1.0]\n"
      "\n"
      "# Camera specific definitions.\n"
      "rate_hz: {}\n"
      "resolution: [{}, {}]\n"
      "camera_model: pinhole\n"
      "intrinsics: [{}, {}, {}, {}] #fu, fv, cu, cv\n"
      "distortion_model: radial-tangential\n"
      "distortion_coefficients: [0.0, 0.0, 0.0, 0.0]\n",
      camera, tx, static_cast<int>(rig.fps), c.width, c.height, c.fx, c.fy, c.cx, c.cy);
}

void writeEuroc(const SequenceRenderer& sequence, const fs::path& out,
                const FrameProgress& progress) {
  const fs::path mav = out / "mav0";
  for (const fs::path& dir : {mav / "cam0" / "data", mav / "cam1" / "data",
                              mav / "state_groundtruth_estimate0", out / "mask"})
    makeDirectory(dir);
  const auto records = renderAll(
      sequence,
      [&](const Frame& frame) {
        const std::string name = std::to_string(frame.timestamp_ns) + ".png";
        cv::Mat gray;
        cv::cvtColor(frame.cam0.image, gray, cv::COLOR_BGR2GRAY);
        writeImage(mav / "cam0" / "data" / name, gray);
        cv::cvtColor(frame.cam1->image, gray, cv::COLOR_BGR2GRAY);
        writeImage(mav / "cam1" / "data" / name, gray);
        writeImage(out / "mask" / name, frame.cam0.mask);
      },
      progress);
  for (int camera = 0; camera < 2; ++camera) {
    const fs::path dir = mav / fmt::format("cam{}", camera);
    TextFile csv(dir / "data.csv");
    csv.line("#timestamp [ns],filename");
    for (const auto& r : records) csv.line("{},{}.png", r.timestamp_ns, r.timestamp_ns);
    TextFile yaml(dir / "sensor.yaml");
    yaml.line("{}", eurocSensorYaml(sequence, camera));
  }
  {
    TextFile body(mav / "body.yaml");
    body.line("%YAML:1.0");
    body.line("comment: lumaslam synthetic stereo rig; body frame = cam0");
  }
  // Ground truth at 200 Hz like EuRoC's; every camera timestamp is on this grid.
  TextFile gt(mav / "state_groundtruth_estimate0" / "data.csv");
  gt.line(
      "#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], q_RS_y [], "
      "q_RS_z [], "
      "v_RS_R_x [m s^-1], v_RS_R_y [m s^-1], v_RS_R_z [m s^-1], b_w_RS_S_x [rad s^-1], b_w_RS_S_y "
      "[rad s^-1], "
      "b_w_RS_S_z [rad s^-1], b_a_RS_S_x [m s^-2], b_a_RS_S_y [m s^-2], b_a_RS_S_z [m s^-2]");
  const std::int64_t step_ns = 5000000;
  for (std::int64_t ns = records.front().timestamp_ns; ns <= records.back().timestamp_ns;
       ns += step_ns) {
    const double t = static_cast<double>(ns) * 1e-9;
    const SE3 T = sequence.poseAt(t);
    const Eigen::Vector3d v =
        (sequence.poseAt(t + 1e-3).translation() - sequence.poseAt(t - 1e-3).translation()) / 2e-3;
    const Eigen::Quaterniond q = unitQuaternion(T);
    const Eigen::Vector3d p = T.translation();
    gt.line(
        "{},{:.6f},{:.6f},{:.6f},{:.7f},{:.7f},{:.7f},{:.7f},{:.6f},{:.6f},{:.6f},0.0,0.0,0.0,0.0,"
        "0.0,0.0",
        ns, p.x(), p.y(), p.z(), q.w(), q.x(), q.y(), q.z(), v.x(), v.y(), v.z());
  }
  writeDetections(out / "detections.txt", records, true);
}

}  // namespace

std::string tumTimestamp(std::int64_t timestamp_ns) {
  return fmt::format("{}.{:06d}", timestamp_ns / 1000000000, (timestamp_ns % 1000000000) / 1000);
}

std::string settingsYaml(const SequenceRenderer& sequence) {
  const Rig& rig = sequence.rig();
  const PinholeCamera& c = rig.camera;
  const bool stereo = rig.kind == SensorKind::Stereo;
  std::string text = fmt::format(
      "%YAML:1.0\n"
      "# ORB-SLAM3-style settings for lumaslam synth preset '{}' (seed {}); images are "
      "undistorted.\n"
      "Synth.preset: \"{}\"\n"
      "Synth.seed: {}\n"
      "Dataset.format: \"{}\"\n"
      "\n"
      // The stereo pair is rendered row-aligned, so it is an already rectified pair.
      "Camera.type: \"{}\"\n"
      "Camera.fx: {}\n"
      "Camera.fy: {}\n"
      "Camera.cx: {}\n"
      "Camera.cy: {}\n"
      "Camera.k1: 0.0\n"
      "Camera.k2: 0.0\n"
      "Camera.p1: 0.0\n"
      "Camera.p2: 0.0\n"
      "Camera.k3: 0.0\n"
      "Camera.width: {}\n"
      "Camera.height: {}\n"
      "Camera.fps: {:.1f}\n"
      // Colour images are written as image files: readers decode them in BGR (docs/settings.md).
      "Camera.RGB: 0\n"
      "Camera.bf: {:.6f}\n"
      "ThDepth: {:.1f}\n",
      sequence.preset().name, sequence.seed(), sequence.preset().name, sequence.seed(),
      stereo ? "euroc" : "tum", stereo ? "Rectified" : "PinHole", c.fx, c.fy, c.cx, c.cy, c.width,
      c.height, rig.fps, c.fx * (stereo ? rig.baseline_m : 0.075), stereo ? 35.0 : 40.0);
  if (stereo) {
    const std::string K =
        fmt::format("[{}, 0.0, {}, 0.0, {}, {}, 0.0, 0.0, 1.0]", c.fx, c.cx, c.fy, c.cy);
    text += fmt::format(
        "Stereo.b: {}\n"
        "Stereo.ThDepth: 35.0\n"
        "Stereo.T_c1_c2: !!opencv-matrix\n"
        "  rows: 4\n  cols: 4\n  dt: d\n"
        "  data: [1.0, 0.0, 0.0, {}, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0]\n",
        rig.baseline_m, rig.baseline_m);
    for (const char* side : {"LEFT", "RIGHT"}) {
      const double shift = std::string(side) == "RIGHT" ? -c.fx * rig.baseline_m : 0.0;
      text += fmt::format(
          "{0}.height: {1}\n{0}.width: {2}\n"
          "{0}.D: !!opencv-matrix\n  rows: 1\n  cols: 5\n  dt: d\n  data: [0.0, 0.0, 0.0, 0.0, "
          "0.0]\n"
          "{0}.K: !!opencv-matrix\n  rows: 3\n  cols: 3\n  dt: d\n  data: {3}\n"
          "{0}.R: !!opencv-matrix\n  rows: 3\n  cols: 3\n  dt: d\n  data: [1.0, 0.0, 0.0, 0.0, "
          "1.0, 0.0, 0.0, 0.0, 1.0]\n"
          "{0}.P: !!opencv-matrix\n  rows: 3\n  cols: 4\n  dt: d\n"
          "  data: [{4}, 0.0, {5}, {6}, 0.0, {7}, {8}, 0.0, 0.0, 0.0, 1.0, 0.0]\n",
          side, c.height, c.width, K, c.fx, c.cx, shift, c.fy, c.cy);
    }
  } else {
    text += "DepthMapFactor: 5000.0\n";
  }
  text +=
      "\n"
      "ORBextractor.nFeatures: 1000\n"
      "ORBextractor.scaleFactor: 1.2\n"
      "ORBextractor.nLevels: 8\n"
      "ORBextractor.iniThFAST: 20\n"
      "ORBextractor.minThFAST: 7\n";
  // The classes detections.txt uses, so `lumaslam run --detector boxes:detections.txt`
  // removes every moving object (YOLO knows no "box": use "person" for it).
  std::string classes;
  for (int id = 1; id <= sequence.scene().dynamicObjectCount(); ++id) {
    const auto& name = sequence.scene().objectClass(static_cast<std::uint8_t>(id));
    if (("," + classes + ",").find("," + name + ",") == std::string::npos)
      classes += (classes.empty() ? "" : ",") + name;
  }
  if (!classes.empty()) text += fmt::format("\nDetector.classes: \"{}\"\n", classes);
  return text;
}

void writeDataset(const SequenceRenderer& sequence, const fs::path& out,
                  const FrameProgress& progress) {
  makeDirectory(out);
  if (sequence.rig().kind == SensorKind::Stereo)
    writeEuroc(sequence, out, progress);
  else
    writeTum(sequence, out, progress);
  TextFile settings(out / "settings.yaml");
  settings.line("{}", settingsYaml(sequence));
  spdlog::info("synth: wrote {} frames of '{}' (seed {}) to {}", sequence.frameCount(),
               sequence.preset().name, sequence.seed(), out.string());
}

void writeSequence(const fs::path& out, const std::string& preset, int frames, std::uint64_t seed,
                   const SynthOptions& options, const FrameProgress& progress) {
  const Preset& p = findPreset(preset);
  const SequenceRenderer sequence(p, frames > 0 ? frames : p.frames, seed, options);
  writeDataset(sequence, out, progress);
}

}  // namespace lumaslam::synth
