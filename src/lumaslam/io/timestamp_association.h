#pragma once
// One-to-one association of two timestamp lists, as TUM's associate.py does it: every pair
// closer than max_dt is a candidate, candidates are taken closest first, each timestamp is
// used at most once.
#include <cstddef>
#include <vector>

namespace lumaslam::io {

struct TimestampMatch {
  std::size_t first = 0;   // index into the first list
  std::size_t second = 0;  // index into the second list
};

// Matches sorted by the first list's timestamps.
std::vector<TimestampMatch> associateTimestamps(const std::vector<double>& first,
                                                const std::vector<double>& second, double max_dt);

}  // namespace lumaslam::io
