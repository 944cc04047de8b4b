#pragma once
// Keyframe database for place recognition: the inverted index word -> keyframes (DBoW2 /
// ORB-SLAM KeyFrameDatabase), plus each keyframe's BoW and direct index so that callers
// (relocalization, loop closing) can score and match without the keyframe object carrying
// them. Keyed by keyframe id, so it can be tested without a map. Thread-safe: tracking
// (relocalization) and loop closing query it while local mapping adds and culls keyframes.
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "lumaslam/loop/bow_vector.h"

namespace lumaslam::loop {

using KeyFrameId = std::uint64_t;

struct KeyFrameBow {
  BowVector bow;
  FeatureVector features;
};

struct PlaceCandidate {
  KeyFrameId id = 0;
  int shared_words = 0;
  double score = 0.0;              // L1 score against the query
  double accumulated_score = 0.0;  // sum over its covisibility group (= score without one)
};

struct PlaceQuery {
  // Keyframes sharing fewer than this fraction of the best candidate's shared-word count
  // are not scored (ORB-SLAM: 0.8).
  double min_shared_ratio = 0.8;
  // Keyframes scoring below this are dropped (ORB-SLAM's loop detection passes the lowest
  // score of the keyframe's covisibles; relocalization uses 0).
  double min_score = 0.0;
  // Groups whose accumulated score is below this fraction of the best group's are dropped
  // (ORB-SLAM: 0.75).
  double min_accumulated_ratio = 0.75;
  // Covisibility neighbours of a keyframe (ORB-SLAM: its 10 best); empty function = no
  // grouping, every keyframe is its own group.
  std::function<std::vector<KeyFrameId>(KeyFrameId)> neighbours;
  // Keyframes never returned nor counted (e.g. the querying keyframe and its neighbours
  // for loop detection).
  std::unordered_set<KeyFrameId> excluded;
  std::size_t max_candidates = 0;  // 0 = no limit
};

class KeyFrameDatabase {
 public:
  // Adds (or replaces) a keyframe's BoW entry.
  void add(KeyFrameId id, KeyFrameBow entry);
  void erase(KeyFrameId id);
  void clear();
  std::size_t size() const;
  bool contains(KeyFrameId id) const;
  // Copy of a keyframe's entry (nullopt if unknown), e.g. for guided matching.
  std::optional<KeyFrameBow> entry(KeyFrameId id) const;

  // ORB-SLAM's DetectRelocalizationCandidates / DetectLoopCandidates: keyframes sharing words
  // with `query`, kept if they share >= min_shared_ratio of the maximum, scored, accumulated
  // over their covisibility group, and for every group above min_accumulated_ratio of the
  // best the group's best-scoring keyframe. Sorted by accumulated score, then score
  // (descending), then id.
  std::vector<PlaceCandidate> query(const BowVector& query, const PlaceQuery& options = {}) const;

 private:
  mutable std::mutex mutex_;
  std::unordered_map<KeyFrameId, KeyFrameBow> entries_;
  std::unordered_map<WordId, std::vector<KeyFrameId>> inverted_;
};

}  // namespace lumaslam::loop
