#pragma once
// The place-recognition state a running Pipeline shares between tracking (relocalization) and
// loop closing: the vocabulary and the keyframe database. It is the Map's KeyFrameIndex, so
// every keyframe gets its BoW and direct index once, when it joins the map, and leaves the
// database when it is retired. Thread-safe (the database has its own leaf lock, see map.h).
#include <filesystem>
#include <memory>

#include "lumaslam/loop/keyframe_database.h"
#include "lumaslam/loop/vocabulary.h"
#include "lumaslam/map/keyframe_index.h"

namespace lumaslam::loop {

class PlaceRecognition : public map::KeyFrameIndex {
 public:
  // Direct-index level of the keyframe entries (ORB-SLAM: 4 levels above the leaves); the
  // Relocalizer and loop detection must transform their queries with the same value.
  static constexpr int kDirectIndexLevelsUp = 4;

  explicit PlaceRecognition(Vocabulary vocabulary);
  // Loads a vocabulary file (our binary format or DBoW2 text); throws Error naming the file.
  static std::shared_ptr<PlaceRecognition> fromFile(const std::filesystem::path& file);

  const Vocabulary& vocabulary() const { return vocabulary_; }
  const KeyFrameDatabase& database() const { return database_; }

  void add(const std::shared_ptr<const map::KeyFrame>& keyframe) override;
  void erase(map::Id keyframe) override;
  void clear() override;

 private:
  const Vocabulary vocabulary_;
  KeyFrameDatabase database_;
};

}  // namespace lumaslam::loop
