// System.sequential runs every stage in the caller's thread (issue 21): tracking a synthetic
// stereo sequence, a monocular one through its two-view initialisation and an RGB-D one with
// the box-file detector starts no thread at all, while the threaded mode starts several (so the
// count can fail). Threads are counted by interposing pthread_create, which std::thread and
// std::async go through. OpenCV's and TBB's own pools are kept out (core::SerialLibraries):
// they are the libraries' business, not a stage of ours (docs/architecture.md).
#include <dlfcn.h>
#include <pthread.h>

#include <atomic>
#include <vector>

#include <gtest/gtest.h>

#include "lumaslam/core/serial_libraries.h"
#include "test_paths.h"
#include "test_system_dynamic.h"

#if defined(__SANITIZE_THREAD__) || defined(__SANITIZE_ADDRESS__)
#define LUMASLAM_COUNTS_THREADS 0  // the sanitizer runtimes define pthread_create themselves
#else
#define LUMASLAM_COUNTS_THREADS 1

namespace {
std::atomic<int> threads_started{0};
}  // namespace

extern "C" int pthread_create(pthread_t* thread, const pthread_attr_t* attributes,
                              void* (*start)(void*), void* argument) noexcept {
  using Create = int (*)(pthread_t*, const pthread_attr_t*, void* (*)(void*), void*);
  static const auto real_create = reinterpret_cast<Create>(dlsym(RTLD_NEXT, "pthread_create"));
  ++threads_started;
  return real_create(thread, attributes, start, argument);
}
#endif

namespace {

using namespace lumaslam;

struct Sequence {
  std::string preset;
  int frames = 0;
  std::optional<io::SensorType> sensor;  // nullopt: the preset's own
  bool with_detector = false;            // the generator's boxes through the box-file detector
};

// Threads started while a Pipeline is built, tracks the frames (rendered beforehand) and
// shuts down.
int threadsStartedWhileTracking(const Sequence& run, bool sequential) {
  const core::SerialLibraries serial_libraries;
  const synth::SequenceRenderer sequence(synth::findPreset(run.preset), run.frames, 1);
  std::vector<synth::Frame> frames;
  test::GroundTruthBoxes boxes;
  for (int i = 0; i < run.frames; ++i) {
    frames.push_back(sequence.render(i));
    boxes.add(frames.back());
  }
  test::TempDir dir("sequential_threads");
  PipelineOptions options;
  options.enhance_preset = "off";
  options.sequential = sequential;
  options.detector = "none";
  if (run.with_detector) {
    boxes.write(dir.path() / "boxes.txt");
    options.detector = "boxes:" + (dir.path() / "boxes.txt").string();
  }
  const auto settings = test::presetSettings(sequence, {}, run.sensor);

  const int before = threads_started.load();
  std::size_t tracked = 0;
  {
    Pipeline pipeline(settings, options);
    for (const auto& frame : frames) {
      const auto result = pipeline.track(test::sensorFrame(frame, settings.sensor));
      if (result.outcome.state == track::TrackingState::Ok) ++tracked;
    }
    pipeline.shutdown();
    EXPECT_GE(pipeline.keyFrameCount(), 1U) << run.preset << ": local mapping ran";
  }
  const int started = threads_started.load() - before;
  EXPECT_GT(tracked, frames.size() / 2) << run.preset << ": tracking ran";
  return started;
}

const Sequence kStereo{"xyz-stereo", 40, std::nullopt, false};
// Enough frames for the two-view initialisation (its homography job) and a few keyframes.
const Sequence kMonocular{"xyz-rgbd", 40, io::SensorType::Monocular, false};
const Sequence kRgbdWithDetector{"walking-xyz-rgbd", 30, std::nullopt, true};

class SequentialThreads : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!LUMASLAM_COUNTS_THREADS) GTEST_SKIP() << "pthread_create is the sanitizer's";
  }
};

TEST_F(SequentialThreads, StereoStartsNoThread) {
  EXPECT_EQ(threadsStartedWhileTracking(kStereo, true), 0);
}

TEST_F(SequentialThreads, MonocularInitialisationStartsNoThread) {
  EXPECT_EQ(threadsStartedWhileTracking(kMonocular, true), 0);
}

TEST_F(SequentialThreads, RgbdWithDetectorStartsNoThread) {
  EXPECT_EQ(threadsStartedWhileTracking(kRgbdWithDetector, true), 0);
}

// The count works: the threaded mode starts the mapper's and detector's threads and the
// per-frame stereo jobs.
TEST_F(SequentialThreads, ThreadedModeStartsThreads) {
  EXPECT_GE(threadsStartedWhileTracking(kStereo, false), kStereo.frames);
  EXPECT_GE(threadsStartedWhileTracking(kRgbdWithDetector, false), 2);
}

}  // namespace
