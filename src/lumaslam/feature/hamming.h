#pragma once
// Hamming distance between 256-bit ORB descriptors, and ORB-SLAM's distance thresholds.
#include <bit>
#include <cstdint>
#include <cstring>

#include <opencv2/core.hpp>

#include "lumaslam/feature/steered_brief.h"

namespace lumaslam::feature {

inline constexpr int kThHigh = 100;  // loose: projection search (tracking)
inline constexpr int kThLow = 50;    // strict: matching without a position prior

namespace detail {

// Sum of `popcount` over the four 64-bit words of a ^ b.
template <typename Popcount>
inline int hammingWords(const std::uint8_t* a, const std::uint8_t* b, Popcount popcount) {
  int distance = 0;
  for (int offset = 0; offset < kDescriptorBytes; offset += 8) {
    std::uint64_t wordA;
    std::uint64_t wordB;
    std::memcpy(&wordA, a + offset, 8);
    std::memcpy(&wordB, b + offset, 8);
    distance += popcount(wordA ^ wordB);
  }
  return distance;
}

inline int hammingPortable(const std::uint8_t* a, const std::uint8_t* b) {
  return hammingWords(a, b, [](std::uint64_t word) { return std::popcount(word); });
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__POPCNT__)
// The x86-64 baseline has no POPCNT instruction, so std::popcount becomes a call to libgcc's
// table-based __popcountdi2: that was 58% of the run time of monocular KITTI (epipolar
// matching). Use the instruction when the CPU has it (every x86-64 CPU since 2008).
__attribute__((target("popcnt"))) inline int hammingPopcnt(const std::uint8_t* a,
                                                           const std::uint8_t* b) {
  return hammingWords(a, b, [](std::uint64_t word) { return __builtin_popcountll(word); });
}

inline const bool kCpuHasPopcnt = [] {
  __builtin_cpu_init();
  return __builtin_cpu_supports("popcnt") != 0;
}();
#endif

}  // namespace detail

// Number of differing bits between two 32-byte descriptors (popcount on 64-bit words).
inline int hammingDistance(const std::uint8_t* a, const std::uint8_t* b) {
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__POPCNT__)
  if (detail::kCpuHasPopcnt) return detail::hammingPopcnt(a, b);
#endif
  return detail::hammingPortable(a, b);
}

// Rows `rowA` of `a` and `rowB` of `b` (both CV_8UC1 with 32 columns).
inline int hammingDistance(const cv::Mat& a, int rowA, const cv::Mat& b, int rowB) {
  return hammingDistance(a.ptr<std::uint8_t>(rowA), b.ptr<std::uint8_t>(rowB));
}

}  // namespace lumaslam::feature
