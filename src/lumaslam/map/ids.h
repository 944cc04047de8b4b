#pragma once
#include <array>
#include <cstdint>

namespace lumaslam::map {

using Id = std::uint64_t;
using MapId = std::uint32_t;  // one map of the atlas (map.h)
// The id of keyframes of a map that was reset (Map::discardMap): in no map of the atlas.
inline constexpr MapId kDiscardedMap = 0xFFFFFFFFU;
// A 256-bit ORB/BRIEF descriptor by value: cheap to copy, safe to hand across threads.
using Descriptor = std::array<std::uint8_t, 32>;

int hammingDistance(const Descriptor& a, const Descriptor& b);

}  // namespace lumaslam::map
