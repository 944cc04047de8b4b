// Issue 17 item 1: map files. A room mapped on one trajectory, saved, and localized in on
// another trajectory through the same room (same seed: same room; halfsphere starts where
// the xyz shake is); a map saved, loaded and saved again is the same bytes; bad map files are
// clear errors and load nothing.
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>

#include "lumaslam/core/error.h"
#include "test_paths.h"
#include "test_system_run.h"
#include "threaded_run_checks.h"

namespace lumaslam::test {
namespace {

struct MappedRoom {
  std::filesystem::path file;
  SE3 T_gt_world;  // the map's world (first camera) in the generator's world
};

PipelineOptions quietOptions() {
  PipelineOptions options;
  options.enhance_preset = "off";
  options.sequential = true;
  return options;
}

MappedRoom mapRoom(const std::filesystem::path& file, int frames) {
  const synth::SequenceRenderer sequence(synth::findPreset("halfsphere-rgbd"), frames, 1);
  Pipeline system(presetSettings(sequence), quietOptions());
  for (int i = 0; i < frames; ++i) system.track(sensorFrame(sequence.render(i)));
  system.saveMap(file);
  return {file, sequence.render(0).cam0.T_w_c};
}

std::string readBytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const std::filesystem::path& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary) << bytes;
}

io::Settings xyzSettings(const SettingsEdit& edit = {}) {
  const synth::SequenceRenderer sequence(synth::findPreset("xyz-rgbd"), 1, 1);
  return presetSettings(sequence, edit);
}

// The error loadMap throws (empty if none); the Pipeline must stay usable and empty.
std::string loadError(const std::filesystem::path& file, const io::Settings& settings,
                      PipelineOptions options = quietOptions()) {
  Pipeline system(settings, options);
  try {
    system.loadMap(file);
  } catch (const Error& e) {
    EXPECT_EQ(system.keyFrameCount(), 0U) << "half-loaded after: " << e.what();
    EXPECT_EQ(system.mapPointCount(), 0U);
    return e.what();
  }
  return {};
}

TEST(SystemMapFile, SaveLoadSaveIsByteIdentical) {
  TempDir dir("map_file");
  const auto room = mapRoom(dir.path() / "room.map", 60);
  Pipeline system(xyzSettings(), quietOptions());
  system.loadMap(room.file);
  EXPECT_GT(system.keyFrameCount(), 2U);
  EXPECT_GT(system.mapPointCount(), 500U);
  system.saveMap(dir.path() / "again.map");
  const std::string first = readBytes(room.file);
  EXPECT_GT(first.size(), 10000U);
  EXPECT_TRUE(first == readBytes(dir.path() / "again.map"));
}

TEST(SystemMapFile, LocalizesOnAnotherTrajectoryWithoutAddingKeyframes) {
  TempDir dir("map_file");
  const auto room = mapRoom(dir.path() / "room.map", 300);
  const int frames = 300;
  const synth::SequenceRenderer sequence(synth::findPreset("xyz-rgbd"), frames, 1);
  Pipeline system(presetSettings(sequence), quietOptions());
  system.loadMap(room.file);
  system.setLocalizationMode(true);
  const std::size_t keyframes = system.keyFrameCount();
  Trajectory ground_truth;  // in the first run's world
  std::size_t localized = 0;
  for (int i = 0; i < frames; ++i) {
    const auto frame = sequence.render(i);
    const auto result = system.track(sensorFrame(frame));
    if (result.outcome.state == track::TrackingState::Ok) ++localized;
    EXPECT_FALSE(result.outcome.new_keyframe) << "frame " << i;
    ground_truth.push_back({frame.timestamp(), room.T_gt_world.inverse() * frame.cam0.T_w_c});
  }
  system.shutdown();
  EXPECT_GE(static_cast<double>(localized), 0.95 * frames);
  EXPECT_EQ(system.keyFrameCount(), keyframes);
  eval::EvaluationOptions no_alignment;
  no_alignment.align = eval::AlignMode::None;
  const auto report = eval::evaluate(system.frameTrajectory(), ground_truth, no_alignment);
  spdlog::info("localized {}/{}, ATE {:.4f} m in the map's frame", localized, frames,
               report.ate.stats.rmse);
  // ~2x the measured ATE (issue 22; was 1 cm): 3.7 mm on 2026-12-04 (sequential,
  // deterministic; logged above).
  EXPECT_LE(report.ate.stats.rmse, 0.008);
}

TEST(SystemMapFile, BadFilesAreClearErrorsAndLoadNothing) {
  TempDir dir("map_file");
  const auto room = mapRoom(dir.path() / "room.map", 30);
  const std::string bytes = readBytes(room.file);
  const auto settings = xyzSettings();

  std::string corrupt = bytes;
  corrupt[bytes.size() / 2] = static_cast<char>(corrupt[bytes.size() / 2] ^ 0x5A);
  writeBytes(dir.path() / "corrupt.map", corrupt);
  EXPECT_NE(loadError(dir.path() / "corrupt.map", settings).find("checksum mismatch"),
            std::string::npos);

  writeBytes(dir.path() / "truncated.map", bytes.substr(0, bytes.size() - 100));
  EXPECT_NE(loadError(dir.path() / "truncated.map", settings).find("truncated"), std::string::npos);

  writeBytes(dir.path() / "foreign.map", "# TUM trajectory\n1.0 0 0 0 0 0 0 1\n");
  EXPECT_NE(loadError(dir.path() / "foreign.map", settings).find("not a lumaslam map file"),
            std::string::npos);

  EXPECT_NE(loadError(dir.path() / "missing.map", settings).find("cannot open"), std::string::npos);

  const auto other_camera = xyzSettings([](std::string yaml) {
    const auto at = yaml.find("Camera.fx:");
    return yaml.replace(at, yaml.find('\n', at) - at, "Camera.fx: 500.0");
  });
  const std::string camera_error = loadError(room.file, other_camera);
  EXPECT_NE(camera_error.find("camera fx"), std::string::npos) << camera_error;

  PipelineOptions no_vocabulary = quietOptions();
  no_vocabulary.vocabulary = "none";
  const std::string vocabulary_error = loadError(room.file, settings, no_vocabulary);
  EXPECT_NE(vocabulary_error.find("vocabulary"), std::string::npos) << vocabulary_error;
  EXPECT_TRUE(loadError(room.file, settings).empty());
}

// Stereo and monocular maps: saved, loaded (same bytes when saved again) and localized in on
// the frames they were made from. Monocular poses are compared after Sim3 alignment (the map
// has its own scale), stereo with SE3.
struct SensorCase {
  const char* preset;
  io::SensorType sensor;
  eval::AlignMode align;
  double max_ate;  // ~2x the measured ATE (issue 22; was 1 cm), sequential, logged below
};

class SystemMapFileSensors : public ::testing::TestWithParam<SensorCase> {};

TEST_P(SystemMapFileSensors, RoundTripAndLocalization) {
  const SensorCase c = GetParam();
  TempDir dir("map_file_sensor");
  const int frames = 120;
  const synth::SequenceRenderer sequence(synth::findPreset(c.preset), frames, 1);
  const io::Settings settings = presetSettings(sequence, {}, c.sensor);
  {
    Pipeline mapping(settings, quietOptions());
    for (int i = 0; i < frames; ++i) mapping.track(sensorFrame(sequence.render(i), c.sensor));
    mapping.saveMap(dir.path() / "room.map");
  }
  Pipeline reloaded(settings, quietOptions());
  reloaded.loadMap(dir.path() / "room.map");
  EXPECT_GT(reloaded.keyFrameCount(), 2U);
  reloaded.saveMap(dir.path() / "again.map");
  EXPECT_TRUE(readBytes(dir.path() / "room.map") == readBytes(dir.path() / "again.map"));

  Pipeline localizing(settings, quietOptions());
  localizing.loadMap(dir.path() / "room.map");
  localizing.setLocalizationMode(true);
  const std::size_t keyframes = localizing.keyFrameCount();
  Trajectory ground_truth;
  std::size_t localized = 0;
  for (int i = 0; i < frames; ++i) {
    const auto frame = sequence.render(i);
    const auto result = localizing.track(sensorFrame(frame, c.sensor));
    if (result.outcome.state == track::TrackingState::Ok) ++localized;
    ground_truth.push_back({frame.timestamp(), frame.cam0.T_w_c});
  }
  localizing.shutdown();
  EXPECT_GE(static_cast<double>(localized), 0.95 * frames);
  EXPECT_EQ(localizing.keyFrameCount(), keyframes);
  eval::EvaluationOptions options;
  options.align = c.align;
  const auto report = eval::evaluate(localizing.frameTrajectory(), ground_truth, options);
  spdlog::info("{}: localized {}/{}, ATE {:.4f} m", c.preset, localized, frames,
               report.ate.stats.rmse);
  EXPECT_LE(report.ate.stats.rmse, c.max_ate);
}

// max_ate measured on 2026-12-04: 2.6 mm (stereo) and 2.8 mm (monocular, Sim3).
constexpr SensorCase kStereo{"xyz-stereo", io::SensorType::Stereo, eval::AlignMode::SE3, 0.0055};
constexpr SensorCase kMono{"xyz-rgbd", io::SensorType::Monocular, eval::AlignMode::Sim3, 0.006};

INSTANTIATE_TEST_SUITE_P(
    Sensors, SystemMapFileSensors, ::testing::Values(kStereo, kMono), [](const auto& info) {
      return std::string(info.param.sensor == io::SensorType::Stereo ? "Stereo" : "Monocular");
    });

TEST(SystemMapFile, LoadAfterTheFirstFrameIsAnError) {
  TempDir dir("map_file");
  const auto room = mapRoom(dir.path() / "room.map", 30);
  const synth::SequenceRenderer sequence(synth::findPreset("xyz-rgbd"), 1, 1);
  Pipeline system(presetSettings(sequence), quietOptions());
  system.track(sensorFrame(sequence.render(0)));
  EXPECT_THROW(system.loadMap(room.file), Error);
}

// Keyframes of a map file, as a fresh Pipeline loads them.
std::size_t keyFramesIn(const std::filesystem::path& file, const io::Settings& settings) {
  Pipeline reader(settings, quietOptions());
  reader.loadMap(file);
  return reader.keyFrameCount();
}

// A map saved mid-run holds every keyframe made so far, and the run goes on exactly as it
// would have without the save (sequential: the same poses to the bit).
TEST(SystemMapFile, SavingMidRunChangesNothingAndTrackingGoesOn) {
  TempDir dir("map_file");
  const int frames = 120;
  const int save_at = 60;
  const synth::SequenceRenderer sequence(synth::findPreset("xyz-rgbd"), frames, 1);
  const auto settings = presetSettings(sequence);
  Pipeline unsaved(settings, quietOptions());
  Pipeline saved(settings, quietOptions());
  std::size_t keyframes_at_save = 0;
  for (int i = 0; i < frames; ++i) {
    if (i == save_at) {
      keyframes_at_save = unsaved.keyFrameCount();
      saved.saveMap(dir.path() / "mid.map");
    }
    const auto frame = sensorFrame(sequence.render(i));
    const auto expected = unsaved.track(frame);
    const auto result = saved.track(frame);
    EXPECT_EQ(result.outcome.state, expected.outcome.state) << "frame " << i;
  }
  saved.saveMap(dir.path() / "end.map");
  const auto a = unsaved.frameTrajectory();
  const auto b = saved.frameTrajectory();
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(a.size(), static_cast<std::size_t>(frames));
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_TRUE(a[i].T_w_c.matrix() == b[i].T_w_c.matrix()) << "frame " << i;
  }
  EXPECT_EQ(keyFramesIn(dir.path() / "mid.map", settings), keyframes_at_save);
  EXPECT_GT(keyframes_at_save, 2U);
  EXPECT_EQ(keyFramesIn(dir.path() / "end.map", settings), saved.keyFrameCount());
  EXPECT_GT(saved.keyFrameCount(), keyframes_at_save);
}

// Threaded: saveMap waits for the mapper's queue, so the file has every keyframe the run has at
// that moment, and tracking goes on after it (properties, not a count: which frames a threaded
// run tracks depends on the scheduling).
TEST(SystemMapFile, ThreadedSaveHoldsEveryQueuedKeyframe) {
  TempDir dir("map_file");
  const int frames = 120;
  const synth::SequenceRenderer sequence(synth::findPreset("xyz-rgbd"), frames, 1);
  const auto settings = presetSettings(sequence);
  PipelineOptions threaded = quietOptions();
  threaded.sequential = false;
  Pipeline system(settings, threaded);
  std::vector<track::TrackingOutcome> outcomes;
  std::vector<double> timestamps;
  std::vector<std::size_t> saved_keyframes;
  for (int i = 0; i < frames; ++i) {
    const auto input = sensorFrame(sequence.render(i));
    outcomes.push_back(system.track(input).outcome);
    timestamps.push_back(input.timestamp);
    if (i == 40 || i == 80) {
      const auto file = dir.path() / ("at_" + std::to_string(i) + ".map");
      system.saveMap(file);
      const std::size_t in_run = system.keyFrameCount();
      saved_keyframes.push_back(keyFramesIn(file, settings));
      EXPECT_EQ(saved_keyframes.back(), in_run) << file;
    }
  }
  system.shutdown();
  // Tracking goes on after each save: never more than kThreadedMaxLostRun frames lost in a row.
  expectThreadedRun(outcomes, timestamps, system.frameTrajectory());
  ASSERT_EQ(saved_keyframes.size(), 2U);
  EXPECT_GT(saved_keyframes[1], saved_keyframes[0]);
}

}  // namespace
}  // namespace lumaslam::test
