// `lumaslam run --print-settings` of a stereo or RGB-D file (issue 21): the printed lines are a
// complete settings file (Camera.*, Camera1.*, Stereo.*, RGBD.*, System.*, every module's
// section). Read back alone they print the same text again, and a sequential run from them
// tracks exactly as a run from the original file.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "lumaslam/core/settings_file.h"
#include "lumaslam/pipeline_params.h"
#include "test_system_run.h"

namespace lumaslam {
namespace {

PipelineOptions sequentialOptions() {
  PipelineOptions options;
  options.enhance_preset = "off";
  options.sequential = true;
  return options;
}

io::Settings settingsFromText(const std::string& text, const std::string& origin) {
  return io::Settings::fromFile(
      std::make_shared<const core::SettingsFile>(core::SettingsFile::fromString(text, origin)));
}

Trajectory run(const synth::SequenceRenderer& sequence, const io::Settings& settings) {
  Pipeline system(settings, sequentialOptions());
  test::feedFrames(
      system, sequence.frameCount(), [&](int i) { return sequence.render(i); }, settings.sensor);
  return system.frameTrajectory();
}

void expectSameTrajectory(const Trajectory& a, const Trajectory& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].timestamp, b[i].timestamp) << "pose " << i;
    EXPECT_TRUE(a[i].T_w_c.matrix() == b[i].T_w_c.matrix()) << "pose " << i;
  }
}

void expectPrintedFileRunsTheSame(const std::string& preset, int frames) {
  const synth::SequenceRenderer sequence(synth::findPreset(preset), frames, 1);
  const auto original = test::presetSettings(sequence);
  const std::string printed = effectiveSettings(original, sequentialOptions());
  const auto reread = settingsFromText(printed, "printed.yaml");
  EXPECT_EQ(reread.sensor, original.sensor);
  EXPECT_EQ(effectiveSettings(reread, sequentialOptions()), printed);

  const Trajectory from_original = run(sequence, original);
  EXPECT_EQ(from_original.size(), static_cast<std::size_t>(frames));
  expectSameTrajectory(run(sequence, reread), from_original);
  // Every printed key was read, but Enhancement.*: the runs' enhance_preset takes its place.
  for (const auto& unknown : core::unknownKeys(*reread.file)) {
    if (!unknown.key.starts_with("Enhancement.")) {
      ADD_FAILURE() << "printed a key nothing reads: " << unknown.key;
    }
  }
}

TEST(PrintSettingsRuns, StereoPrintedFileRunsTheSame) {
  expectPrintedFileRunsTheSame("xyz-stereo", 30);
}

TEST(PrintSettingsRuns, RgbdPrintedFileRunsTheSame) {
  expectPrintedFileRunsTheSame("xyz-rgbd", 30);
}

}  // namespace
}  // namespace lumaslam
