// Dynamic.rigidConsensus (issue 16; off by default, docs/dynamic.md "Rigid consensus"): the
// pose-free test of matched points with depth, beside the residual test of motion evidence.
// Synthetic RGB-D sequences, no detector, sequential mapping (deterministic).
#include <gtest/gtest.h>

#include "test_people.h"
#include "test_system_dynamic.h"

namespace {

using namespace lumaslam;

constexpr const char* kRigid = "\nDynamic.rigidConsensus: 1\n";

// With the map-start test off (test_system_map_start.cpp has it): these measure the rigid
// consensus alone.
test::SyntheticRun runWithoutDetector(const synth::SequenceRenderer& sequence,
                                      const std::string& extra = {}) {
  return test::runWithoutDetector(sequence, "\nDynamic.mapStartSegmentation: 0\n" + extra);
}

// Seed 3 of walking_xyz: the crate is large and close in frame 0 and the residual test alone
// lets the pose follow it (docs/dynamic.md). Measured 2026-12-08: 156.1 -> 32.2 mm, a ratio of
// 0.206 (sequential, 2 runs identical; `build/tests/test_system_rigid_consensus
// --gtest_filter=*Crate*`, the two "ATE rmse" lines; 154.8 -> 83.1 mm on 2026-12-06). The bounds
// are ~2x that (issue 22). Issue 16's target (<= 3 cm) is NOT met here.
TEST(SystemRigidConsensus, KeepsThePoseOffACrateThatResidualsMiss) {
  const synth::SequenceRenderer sequence(synth::findPreset("walking-xyz-rgbd"), 150, 3);
  const auto residuals_only = runWithoutDetector(sequence);
  const auto rigid = runWithoutDetector(sequence, kRigid);
  EXPECT_EQ(rigid.tracked, rigid.frames);
  EXPECT_LE(rigid.ate(), 0.065);
  EXPECT_LE(rigid.ate(), 0.42 * residuals_only.ate()) << "without " << residuals_only.ate();
}

// Nothing moves, or people sit and shift slowly: no more than 10 % above the run without it
// (+ 0.5 mm for a few-mm ATE), issue 16's rule for the motion test.
void expectNoHarm(const synth::SequenceRenderer& sequence) {
  const auto before = runWithoutDetector(sequence);
  const auto rigid = runWithoutDetector(sequence, kRigid);
  EXPECT_EQ(rigid.tracked, rigid.frames);
  EXPECT_LE(rigid.ate(), 1.1 * before.ate() + 0.0005) << "without " << before.ate();
}

TEST(SystemRigidConsensus, DoesNoHarmOnAStaticScene) {
  expectNoHarm(synth::SequenceRenderer(synth::findPreset("xyz-rgbd"), 100, 1));
}

TEST(SystemRigidConsensus, DoesNoHarmWithPeopleSittingInView) {
  synth::SynthOptions people;
  people.moving_boxes = 0;
  people.people = test::labelledPeople();
  expectNoHarm(synth::SequenceRenderer(synth::findPreset("sitting-xyz-rgbd"), 100, 1, people));
}

}  // namespace
