#pragma once
#include <array>
#include <cstdint>

namespace lumaslam::map {

using Id = std::uint64_t;
// A 256-bit ORB/BRIEF descriptor by value: cheap to copy, safe to hand across threads.
using Descriptor = std::array<std::uint8_t, 32>;

int hammingDistance(const Descriptor& a, const Descriptor& b);

}  // namespace lumaslam::map
