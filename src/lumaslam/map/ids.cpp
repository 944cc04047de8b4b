#include "lumaslam/map/ids.h"

#include <bit>
#include <cstring>

namespace lumaslam::map {

int hammingDistance(const Descriptor& a, const Descriptor& b) {
  int distance = 0;
  for (std::size_t i = 0; i < a.size(); i += 8) {
    std::uint64_t wa = 0;
    std::uint64_t wb = 0;
    std::memcpy(&wa, a.data() + i, 8);
    std::memcpy(&wb, b.data() + i, 8);
    distance += std::popcount(wa ^ wb);
  }
  return distance;
}

}  // namespace lumaslam::map
