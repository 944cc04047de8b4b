#include "lumaslam/loop/place_recognition.h"

#include "lumaslam/core/error.h"
#include "lumaslam/loop/vocabulary_io.h"
#include "lumaslam/map/keyframe.h"

namespace lumaslam::loop {

PlaceRecognition::PlaceRecognition(Vocabulary vocabulary) : vocabulary_(std::move(vocabulary)) {
  if (vocabulary_.empty()) fail("vocabulary: it has no words");
}

std::shared_ptr<PlaceRecognition> PlaceRecognition::fromFile(const std::filesystem::path& file) {
  if (!std::filesystem::is_regular_file(file)) fail("{}: vocabulary file not found", file.string());
  Vocabulary vocabulary = loadAnyVocabulary(file);
  if (vocabulary.empty()) fail("{}: the vocabulary has no words", file.string());
  return std::make_shared<PlaceRecognition>(std::move(vocabulary));
}

void PlaceRecognition::add(const std::shared_ptr<const map::KeyFrame>& keyframe) {
  KeyFrameBow entry;
  vocabulary_.transform(keyframe->features().descriptors, kDirectIndexLevelsUp, entry.bow,
                        entry.features);
  database_.add(keyframe->id(), std::move(entry));
}

void PlaceRecognition::erase(map::Id keyframe) {
  database_.erase(keyframe);
}

void PlaceRecognition::clear() {
  database_.clear();
}

}  // namespace lumaslam::loop
