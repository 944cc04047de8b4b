#include "lumaslam/io/timestamp_association.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>

namespace lumaslam::io {

std::vector<TimestampMatch> associateTimestamps(const std::vector<double>& first,
                                                const std::vector<double>& second, double max_dt) {
  std::vector<std::size_t> second_by_time(second.size());
  std::iota(second_by_time.begin(), second_by_time.end(), 0);
  std::sort(second_by_time.begin(), second_by_time.end(),
            [&](std::size_t a, std::size_t b) { return second[a] < second[b]; });

  struct Candidate {
    double dt;
    std::size_t first;
    std::size_t second;
  };
  std::vector<Candidate> candidates;
  for (std::size_t i = 0; i < first.size(); ++i) {
    auto it = std::lower_bound(second_by_time.begin(), second_by_time.end(), first[i] - max_dt,
                               [&](std::size_t j, double t) { return second[j] < t; });
    for (; it != second_by_time.end() && second[*it] < first[i] + max_dt; ++it) {
      const double dt = std::abs(first[i] - second[*it]);
      if (dt < max_dt) candidates.push_back({dt, i, *it});
    }
  }
  // Same order as associate.py's sort of (dt, a, b) tuples.
  std::sort(candidates.begin(), candidates.end(), [&](const Candidate& a, const Candidate& b) {
    return std::tie(a.dt, first[a.first], second[a.second]) <
           std::tie(b.dt, first[b.first], second[b.second]);
  });

  std::vector<bool> first_used(first.size(), false), second_used(second.size(), false);
  std::vector<TimestampMatch> matches;
  for (const auto& candidate : candidates) {
    if (first_used[candidate.first] || second_used[candidate.second]) continue;
    first_used[candidate.first] = second_used[candidate.second] = true;
    matches.push_back({candidate.first, candidate.second});
  }
  std::sort(matches.begin(), matches.end(), [&](const TimestampMatch& a, const TimestampMatch& b) {
    return first[a.first] < first[b.first];
  });
  return matches;
}

}  // namespace lumaslam::io
