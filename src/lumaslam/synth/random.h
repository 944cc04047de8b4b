#pragma once
// Counter-based random numbers: every value is a pure function of (seed, stream, counter), so
// results never depend on thread scheduling nor on the standard library's distributions
// (which differ between libstdc++ and libc++).
#include <cmath>
#include <cstdint>

namespace lumaslam::synth {

// SplitMix64 finaliser: a strong 64-bit bit mixer.
constexpr std::uint64_t mix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

constexpr std::uint64_t hashKey(std::uint64_t a, std::uint64_t b, std::uint64_t c = 0,
                                std::uint64_t d = 0) {
  return mix64(mix64(mix64(mix64(a) ^ b) ^ c) ^ d);
}

// Uniform in [0, 1) from the top 53 bits.
inline double unitFromBits(std::uint64_t bits) {
  return static_cast<double>(bits >> 11) * 0x1.0p-53;
}

// Approximately standard normal from one hash: the sum of four 16-bit uniforms (Irwin-Hall),
// shifted and scaled to mean 0, variance 1. Cheap enough for per-pixel sensor noise.
inline float gaussianFromBits(std::uint64_t bits) {
  const float sum = static_cast<float>(bits & 0xffff) + static_cast<float>((bits >> 16) & 0xffff) +
                    static_cast<float>((bits >> 32) & 0xffff) + static_cast<float>(bits >> 48);
  return (sum - 131070.0f) * (1.0f / 37837.23f);
}

// A sequential generator for scene construction (single-threaded use).
class Rng {
 public:
  explicit Rng(std::uint64_t seed, std::uint64_t stream = 0) : key_(hashKey(seed, stream)) {}

  std::uint64_t next() { return mix64(key_ ^ mix64(counter_++)); }
  double uniform() { return unitFromBits(next()); }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // Integer in [lo, hi] inclusive.
  int uniformInt(int lo, int hi) {
    return lo + static_cast<int>(next() % static_cast<std::uint64_t>(hi - lo + 1));
  }
  bool chance(double probability) { return uniform() < probability; }
  double gaussian() { return gaussianFromBits(next()); }
  // A child generator for an independent sub-task (e.g. one texture).
  Rng fork() { return Rng(next(), 0x5eed); }

 private:
  std::uint64_t key_;
  std::uint64_t counter_ = 0;
};

}  // namespace lumaslam::synth
