// Writes the seeds of the binary formats into OUT/<target>/ (`make fuzz` and the replay
// ctests run it): map files and binary vocabularies would be opaque blobs in git, so they are
// made from tiny synthetic data by the code that writes them for real.
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <memory>

#include <opencv2/core.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/loop/vocabulary.h"
#include "lumaslam/loop/vocabulary_io.h"
#include "lumaslam/map/keyframe.h"
#include "lumaslam/map/map.h"
#include "lumaslam/map/map_file.h"
#include "lumaslam/map/map_point.h"

namespace {

using namespace lumaslam;

constexpr int kFeatures = 4;

// k = 2, L = 1: a root and two leaves (words) with descriptors 0x00.. and 0xff...
loop::Vocabulary twoWordVocabulary() {
  loop::VocabularyData data;
  data.branching = 2;
  data.depth = 1;
  data.first_child = {1, 0, 0};
  data.child_count = {2, 0, 0};
  data.node_word = {loop::kNoWord, 0, 1};
  data.descriptors.assign(3 * loop::kDescriptorBytes, 0);
  std::fill(data.descriptors.begin() + 2 * loop::kDescriptorBytes, data.descriptors.end(), 0xff);
  data.word_node = {1, 2};
  data.word_weight = {0.5F, 0.25F};
  return loop::Vocabulary(std::move(data), "seed vocabulary");
}

std::shared_ptr<const map::FeatureSet> featuresWithDepth() {
  auto features = std::make_shared<map::FeatureSet>();
  cv::RNG random(7);
  features->descriptors = cv::Mat(kFeatures, loop::kDescriptorBytes, CV_8U);
  random.fill(features->descriptors, cv::RNG::UNIFORM, 0, 256);
  for (int i = 0; i < kFeatures; ++i) {
    const cv::Point2f pixel(100.0F + 20.0F * i, 80.0F + 10.0F * i);
    features->keypoints.emplace_back(pixel, 31.0F, 45.0F, 1.0F, 0);
    features->undistorted.push_back(pixel);
    features->u_right.push_back(pixel.x - 30.0F);
    features->depth.push_back(2.0F + 0.5F * i);
  }
  return features;
}

// Two keyframes of one map seeing two points.
void writeMap(const std::filesystem::path& file) {
  const auto pyramid = std::make_shared<feature::ScaleLevels>(8, 1.2F);
  const CameraIntrinsics camera{525.0, 525.0, 319.5, 239.5};
  map::Map map;
  std::vector<std::shared_ptr<map::KeyFrame>> keyframes;
  for (int k = 0; k < 2; ++k) {
    SE3 T_c_w = SE3::Identity();
    T_c_w.translation().x() = -0.1 * k;
    keyframes.push_back(std::make_shared<map::KeyFrame>(map.nextKeyFrameId(), k, 0.1 * k, T_c_w,
                                                        featuresWithDepth(), pyramid, camera));
    map.addKeyFrame(keyframes.back());
  }
  keyframes[1]->setParent(keyframes[0]);
  for (int p = 0; p < 2; ++p) {
    auto point = std::make_shared<map::MapPoint>(map.nextMapPointId(),
                                                 Eigen::Vector3d(0.1 * p, 0.0, 2.0), keyframes[0]);
    for (const auto& keyframe : keyframes) {
      keyframe->setMapPoint(p, point);
      point->addObservation(keyframe, p);
    }
    map.addMapPoint(point);
  }
  map::MapFingerprint fingerprint;
  fingerprint.sensor = "rgbd";
  fingerprint.image_width = 640;
  fingerprint.image_height = 480;
  fingerprint.camera = camera;
  fingerprint.orb_features = 1000;
  fingerprint.orb_scale_factor = 1.2F;
  fingerprint.orb_levels = 8;
  fingerprint.orb_ini_fast = 20;
  fingerprint.orb_min_fast = 7;
  map::saveMapFile(map, fingerprint, file);
  map::saveMapFile(map::Map{}, fingerprint, file.parent_path() / "empty.map");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: fuzz_seeds OUT_FOLDER\n";
    return 2;
  }
  const std::filesystem::path out = argv[1];
  try {
    std::filesystem::create_directories(out / "map_file");
    std::filesystem::create_directories(out / "vocabulary");
    writeMap(out / "map_file" / "two_keyframes.map");
    const auto vocabulary = twoWordVocabulary();
    loop::saveVocabulary(vocabulary, out / "vocabulary" / "two_words.lumavoc");
    loop::saveDbow2Text(vocabulary, out / "vocabulary" / "two_words.txt");
  } catch (const Error& e) {
    std::cerr << e.what() << '\n';
    return 1;
  }
  return 0;
}
