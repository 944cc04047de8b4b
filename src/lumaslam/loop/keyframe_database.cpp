#include "lumaslam/loop/keyframe_database.h"

#include <algorithm>

namespace lumaslam::loop {

void KeyFrameDatabase::add(KeyFrameId id, KeyFrameBow entry) {
  std::lock_guard lock(mutex_);
  if (entries_.contains(id)) {
    for (const auto& word : entries_[id].bow) std::erase(inverted_[word.word], id);
  }
  for (const auto& word : entry.bow) inverted_[word.word].push_back(id);
  entries_[id] = std::move(entry);
}

void KeyFrameDatabase::erase(KeyFrameId id) {
  std::lock_guard lock(mutex_);
  const auto found = entries_.find(id);
  if (found == entries_.end()) return;
  for (const auto& word : found->second.bow) {
    auto list = inverted_.find(word.word);
    if (list == inverted_.end()) continue;
    std::erase(list->second, id);
    if (list->second.empty()) inverted_.erase(list);
  }
  entries_.erase(found);
}

void KeyFrameDatabase::clear() {
  std::lock_guard lock(mutex_);
  entries_.clear();
  inverted_.clear();
}

std::size_t KeyFrameDatabase::size() const {
  std::lock_guard lock(mutex_);
  return entries_.size();
}

bool KeyFrameDatabase::contains(KeyFrameId id) const {
  std::lock_guard lock(mutex_);
  return entries_.contains(id);
}

std::optional<KeyFrameBow> KeyFrameDatabase::entry(KeyFrameId id) const {
  std::lock_guard lock(mutex_);
  const auto found = entries_.find(id);
  if (found == entries_.end()) return std::nullopt;
  return found->second;
}

std::vector<PlaceCandidate> KeyFrameDatabase::query(const BowVector& query,
                                                    const PlaceQuery& options) const {
  std::unordered_map<KeyFrameId, PlaceCandidate> scored;
  {
    std::lock_guard lock(mutex_);
    // 1. Keyframes sharing words with the query, and how many.
    std::unordered_map<KeyFrameId, int> shared;
    for (const auto& word : query) {
      const auto list = inverted_.find(word.word);
      if (list == inverted_.end()) continue;
      for (const KeyFrameId id : list->second) {
        if (!options.excluded.contains(id)) ++shared[id];
      }
    }
    int max_shared = 0;
    for (const auto& [id, count] : shared) max_shared = std::max(max_shared, count);
    const int min_shared = static_cast<int>(options.min_shared_ratio * max_shared);
    // 2. Score those sharing enough words.
    for (const auto& [id, count] : shared) {
      if (count < min_shared) continue;
      const double s = score(query, entries_.at(id).bow);
      if (s < options.min_score) continue;
      scored[id] = PlaceCandidate{id, count, s, s};
    }
  }
  // 3. Accumulate over covisibility groups; each group is represented by its best keyframe.
  std::vector<PlaceCandidate> groups;
  double best_accumulated = 0.0;
  for (const auto& [id, candidate] : scored) {
    PlaceCandidate best = candidate;
    double accumulated = candidate.score;
    if (options.neighbours) {
      for (const KeyFrameId neighbour : options.neighbours(id)) {
        const auto found = scored.find(neighbour);
        if (found == scored.end()) continue;
        accumulated += found->second.score;
        if (found->second.score > best.score) best = found->second;
      }
    }
    best.accumulated_score = accumulated;
    best_accumulated = std::max(best_accumulated, accumulated);
    groups.push_back(best);
  }
  const double min_accumulated = options.min_accumulated_ratio * best_accumulated;
  std::vector<PlaceCandidate> result;
  std::unordered_set<KeyFrameId> returned;
  // Several groups may elect the same keyframe: keep it once, with its best group score.
  std::sort(groups.begin(), groups.end(), [](const auto& a, const auto& b) {
    if (a.accumulated_score != b.accumulated_score)
      return a.accumulated_score > b.accumulated_score;
    if (a.score != b.score) return a.score > b.score;
    return a.id < b.id;
  });
  for (const auto& group : groups) {
    if (group.accumulated_score < min_accumulated) break;
    if (!returned.insert(group.id).second) continue;
    result.push_back(group);
    if (options.max_candidates > 0 && result.size() >= options.max_candidates) break;
  }
  return result;
}

}  // namespace lumaslam::loop
