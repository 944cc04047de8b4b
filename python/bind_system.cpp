#include <optional>
#include <string>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include "lumaslam/system.h"
#include "numpy_conversion.h"

namespace lumaslam::python {

namespace {

SystemConfig makeConfig(std::optional<bool> sequential, std::optional<std::string> enhancement,
                        std::optional<std::string> detector,
                        std::optional<std::filesystem::path> vocabulary,
                        std::optional<bool> loop_closing, std::optional<bool> motion_evidence,
                        bool strict_settings) {
  SystemConfig config;
  config.sequential = sequential;
  config.enhancement = std::move(enhancement);
  config.detector = std::move(detector);
  config.vocabulary = std::move(vocabulary);
  config.loop_closing = loop_closing;
  config.motion_evidence = motion_evidence;
  config.strict_settings = strict_settings;
  return config;
}

std::unique_ptr<System> makeSystem(const std::filesystem::path& settings,
                                   const SystemConfig& config) {
  const py::gil_scoped_release no_gil;  // loads the vocabulary, starts threads
  return std::make_unique<System>(settings, config);
}

// Copies are made with the GIL held; tracking then runs without it.
template <typename Track>
TrackResult trackWithoutGil(const Track& track) {
  const py::gil_scoped_release no_gil;
  return track();
}

void bindEnums(py::module_& module) {
  py::enum_<Sensor>(module, "Sensor", "The sensor a settings file describes.")
      .value("MONOCULAR", Sensor::Monocular)
      .value("STEREO", Sensor::Stereo)
      .value("RGBD", Sensor::Rgbd);
  py::enum_<TrackState>(module, "TrackState", "Whether a frame was tracked.")
      .value("NOT_INITIALIZED", TrackState::NotInitialized)
      .value("TRACKING", TrackState::Tracking)
      .value("LOST", TrackState::Lost);
}

void bindTrackResult(py::module_& module) {
  py::class_<TrackResult>(module, "TrackResult", "The outcome of one frame.")
      .def_readonly("frame", &TrackResult::frame, "Frame number given by the System, from 0.")
      .def_readonly("timestamp", &TrackResult::timestamp, "Seconds, as fed.")
      .def_readonly("state", &TrackResult::state, "TrackState.")
      .def_property_readonly(
          "T_w_c",
          [](const TrackResult& r) -> py::object {
            return r.T_w_c ? py::object(poseArray(*r.T_w_c)) : py::none();
          },
          "4x4 float64 camera-to-world pose, or None when not tracked.")
      .def_readonly("inliers", &TrackResult::inliers, "Map points the pose rests on.")
      .def_readonly("keyframe", &TrackResult::keyframe, "The frame became a keyframe.")
      .def_readonly("relocalized", &TrackResult::relocalized, "Recovered from LOST.")
      .def_readonly("new_map", &TrackResult::new_map, "Started a new map of the atlas.")
      .def_readonly("map", &TrackResult::map, "The map it was tracked in.")
      .def_readonly("time_ms", &TrackResult::time_ms, "Wall time of the call.")
      .def("__repr__", [](const TrackResult& r) {
        return "<TrackResult frame " + std::to_string(r.frame) + " " + toString(r.state) + ", " +
               std::to_string(r.inliers) + " inliers>";
      });
}

}  // namespace

void bindSystem(py::module_& module) {
  bindEnums(module);
  bindTrackResult(module);
  py::class_<System>(module, "System", R"doc(
The SLAM system: build it from a settings file, feed it frames, get poses back.

Every method may be called from any Python thread; tracking, saving and loading release the
GIL. Frames are numbered by the System. Images: uint8 HxW (gray) or HxWx3, BGR when the
settings say Camera.RGB: 0 (lumaslam.Dataset, cv2.imread), RGB when they say 1 (PIL, imageio);
depth:
uint16 (raw, divided by the settings' DepthMapFactor) or float32 metres. Timestamps are
seconds, finite and increasing.)doc")
      .def(py::init([](const std::filesystem::path& settings, std::optional<bool> sequential,
                       std::optional<std::string> enhancement, std::optional<std::string> detector,
                       std::optional<std::filesystem::path> vocabulary,
                       std::optional<bool> loop_closing, std::optional<bool> motion_evidence,
                       bool strict_settings) {
             return makeSystem(
                 settings,
                 makeConfig(sequential, std::move(enhancement), std::move(detector),
                            std::move(vocabulary), loop_closing, motion_evidence, strict_settings));
           }),
           py::arg("settings"), py::kw_only(), py::arg("sequential") = py::none(),
           py::arg("enhancement") = py::none(), py::arg("detector") = py::none(),
           py::arg("vocabulary") = py::none(), py::arg("loop_closing") = py::none(),
           py::arg("motion_evidence") = py::none(), py::arg("strict_settings") = false,
           R"doc(
settings: ORB-SLAM3-style YAML file. The keyword arguments override it (None keeps it):
sequential (every stage in the caller's thread: deterministic), enhancement (preset name or
"off"), detector ("yolo:MODEL.onnx", "boxes:FILE" or "none"), vocabulary (file or "none";
default: the vocabulary installed with lumaslam), loop_closing, motion_evidence,
strict_settings (unknown settings keys are an error).)doc")
      .def_property_readonly("sensor", &System::sensor, "The settings file's Sensor.")
      .def(
          "track_monocular",
          [](System& s, const py::array& image, double timestamp) {
            const cv::Mat mat = imageFromArray(image, "image");
            return trackWithoutGil([&] { return s.trackMonocular(mat, timestamp); });
          },
          py::arg("image"), py::arg("timestamp"), "Tracks one image; returns a TrackResult.")
      .def(
          "track_stereo",
          [](System& s, const py::array& left, const py::array& right, double timestamp) {
            const cv::Mat l = imageFromArray(left, "left");
            const cv::Mat r = imageFromArray(right, "right");
            return trackWithoutGil([&] { return s.trackStereo(l, r, timestamp); });
          },
          py::arg("left"), py::arg("right"), py::arg("timestamp"),
          "Tracks one stereo pair (rectified or as calibrated); returns a TrackResult.")
      .def(
          "track_rgbd",
          [](System& s, const py::array& image, const py::array& depth, double timestamp) {
            const cv::Mat i = imageFromArray(image, "image");
            const cv::Mat d = depthFromArray(depth, "depth");
            return trackWithoutGil([&] { return s.trackRgbd(i, d, timestamp); });
          },
          py::arg("image"), py::arg("depth"), py::arg("timestamp"),
          "Tracks one colour/gray image with its registered depth; returns a TrackResult.")
      .def("save_map", &System::saveMap, py::arg("file"), py::call_guard<py::gil_scoped_release>(),
           "Lets mapping handle every queued keyframe, then writes the map file atomically; "
           "tracking goes on after it.")
      .def("load_map", &System::loadMap, py::arg("file"), py::call_guard<py::gil_scoped_release>(),
           "Before the first frame: loads a map made with this camera, ORB settings and "
           "vocabulary; the first frame relocalizes in it.")
      .def("set_localization_mode", &System::setLocalizationMode, py::arg("on"),
           "Track against the map and relocalize, but add no keyframes.")
      .def_property_readonly("localization_mode", &System::localizationMode)
      .def("reset", &System::reset, py::call_guard<py::gil_scoped_release>(),
           "Drops the map and starts afresh with the same settings.")
      .def("shutdown", &System::shutdown, py::call_guard<py::gil_scoped_release>(),
           "Finishes local mapping and loop closing; poses stay readable.")
      .def(
          "trajectory", [](const System& s) { return trajectoryArrays(s.trajectory()); },
          "Tracked frames of the main map: (timestamps (N,), poses (N, 4, 4)).")
      .def(
          "keyframe_trajectory",
          [](const System& s) { return trajectoryArrays(s.keyframeTrajectory()); },
          "Keyframes of the main map: (timestamps (N,), poses (N, 4, 4)).")
      .def_property_readonly("frame_count", &System::frameCount)
      .def_property_readonly("keyframe_count", &System::keyframeCount)
      .def_property_readonly("map_point_count", &System::mapPointCount)
      .def("__enter__", [](System& s) -> System& { return s; })
      .def("__exit__", [](System& s, const py::args&) {
        const py::gil_scoped_release no_gil;
        s.shutdown();
      });
}

}  // namespace lumaslam::python
