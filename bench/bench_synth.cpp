// Synthetic frame rendering speed (render only, no PNG writing). The target is >= 50 frames/s
// at 640x480 on a 2-core machine: see items_per_second.
#include <benchmark/benchmark.h>

#include "lumaslam/synth/sequence.h"

namespace {

void renderPreset(benchmark::State& state, const char* preset_name) {
  using namespace lumaslam::synth;
  const Preset& preset = findPreset(preset_name);
  const SequenceRenderer sequence(preset, preset.frames, 7);
  int frame = 0;
  for (auto _ : state) {
    Frame f = sequence.render(frame);
    benchmark::DoNotOptimize(f.cam0.image.data);
    frame = (frame + 7) % sequence.frameCount();
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_SynthRenderWalkingXyzRgbd(benchmark::State& state) {
  renderPreset(state, "walking-xyz-rgbd");
}
void BM_SynthRenderXyzRgbd(benchmark::State& state) {
  renderPreset(state, "xyz-rgbd");
}
void BM_SynthRenderDarkRgbd(benchmark::State& state) {
  renderPreset(state, "dark-rgbd");
}
void BM_SynthRenderXyzStereo(benchmark::State& state) {
  renderPreset(state, "xyz-stereo");
}

BENCHMARK(BM_SynthRenderWalkingXyzRgbd)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SynthRenderXyzRgbd)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SynthRenderDarkRgbd)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SynthRenderXyzStereo)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
