// Place recognition: loading a 1M-word vocabulary (our binary format vs DBoW2 text), transform
// of one frame's 1000 ORB descriptors, training on real KITTI frames, and database queries.
// The 1M-word vocabulary is a synthetic complete tree (k = 10, L = 6, random centres): load
// and transform cost depend on the size and shape of the tree, not on what the centres are.
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <opencv2/imgcodecs.hpp>

#include "lumaslam/feature/orb_extractor.h"
#include "lumaslam/loop/keyframe_database.h"
#include "lumaslam/loop/vocabulary_io.h"
#include "lumaslam/loop/vocabulary_training.h"

namespace {

namespace fs = std::filesystem;
using namespace lumaslam;

// Complete k-ary tree of depth L, nodes in breadth-first order, random centres and weights.
loop::Vocabulary randomVocabulary(int k, int depth) {
  loop::VocabularyData data;
  data.branching = k;
  data.depth = depth;
  std::size_t inner = 0;
  std::size_t level_size = 1;
  for (int l = 0; l < depth; ++l, level_size *= static_cast<std::size_t>(k)) inner += level_size;
  const std::size_t nodes = inner + level_size;
  data.first_child.assign(nodes, 0);
  data.child_count.assign(nodes, 0);
  data.node_word.assign(nodes, loop::kNoWord);
  data.descriptors.resize(nodes * loop::kDescriptorBytes);
  std::mt19937_64 rng(7);
  for (auto& byte : data.descriptors) byte = static_cast<std::uint8_t>(rng());
  std::fill_n(data.descriptors.begin(), loop::kDescriptorBytes, 0);  // root
  std::uniform_real_distribution<float> weight(0.0F, 5.0F);
  for (std::size_t n = 0; n < nodes; ++n) {
    if (n < inner) {
      data.first_child[n] = static_cast<std::uint32_t>(n * k + 1);
      data.child_count[n] = static_cast<std::uint32_t>(k);
    } else {
      data.node_word[n] = static_cast<loop::WordId>(data.word_node.size());
      data.word_node.push_back(static_cast<loop::NodeId>(n));
      data.word_weight.push_back(weight(rng));
    }
  }
  return loop::Vocabulary(std::move(data), "random vocabulary");
}

const loop::Vocabulary& millionWords() {
  static const loop::Vocabulary vocabulary = randomVocabulary(10, 6);
  return vocabulary;
}

fs::path benchFile(const std::string& name) {
  return fs::temp_directory_path() / ("lumaslam_bench_" + name);
}

const fs::path& millionWordsBinary() {
  static const fs::path file = [] {
    const auto path = benchFile("vocab_1M.bin");
    loop::saveVocabulary(millionWords(), path);
    return path;
  }();
  return file;
}

const fs::path& millionWordsText() {
  static const fs::path file = [] {
    const auto path = benchFile("vocab_1M.txt");
    loop::saveDbow2Text(millionWords(), path);
    return path;
  }();
  return file;
}

cv::Mat kittiImage(int index) {
  char name[32];
  std::snprintf(name, sizeof(name), "%06d.png", index);
  return cv::imread((fs::path(LUMASLAM_SHARED_DIR) /
                     "data/kitti/odometry_07_first160/sequences/07/image_0" / name)
                        .string(),
                    cv::IMREAD_GRAYSCALE);
}

// ORB descriptors (1000 features) of every `stride`-th KITTI frame.
std::vector<cv::Mat> kittiDescriptors(int stride) {
  const feature::OrbExtractor extractor{feature::OrbSettings{}};
  std::vector<cv::Mat> descriptors;
  for (int i = 0; i < 160; i += stride) {
    const cv::Mat image = kittiImage(i);
    if (image.empty()) break;
    descriptors.push_back(extractor.extract(image).descriptors);
  }
  return descriptors;
}

void BM_VocabularyLoadBinary1M(benchmark::State& state) {
  const auto& file = millionWordsBinary();
  for (auto _ : state) benchmark::DoNotOptimize(loop::loadVocabulary(file));
  state.counters["words"] = static_cast<double>(millionWords().wordCount());
  state.counters["MB"] = static_cast<double>(fs::file_size(file)) / 1e6;
}
BENCHMARK(BM_VocabularyLoadBinary1M)->Unit(benchmark::kMillisecond)->Iterations(5);

void BM_VocabularyLoadDbow2Text1M(benchmark::State& state) {
  const auto& file = millionWordsText();
  for (auto _ : state) benchmark::DoNotOptimize(loop::loadDbow2Text(file));
  state.counters["MB"] = static_cast<double>(fs::file_size(file)) / 1e6;
}
BENCHMARK(BM_VocabularyLoadDbow2Text1M)->Unit(benchmark::kMillisecond)->Iterations(1);

// One frame's 1000 ORB descriptors (KITTI) through the 1M-word tree; arg 1 also builds the
// direct index at ORB-SLAM's level (4 levels up).
void BM_Transform1M(benchmark::State& state) {
  const feature::OrbExtractor extractor{feature::OrbSettings{}};
  const cv::Mat descriptors = extractor.extract(kittiImage(0)).descriptors;
  const auto& vocabulary = millionWords();
  loop::BowVector bow;
  loop::FeatureVector features;
  for (auto _ : state) {
    if (state.range(0) == 1) {
      vocabulary.transform(descriptors, 4, bow, features);
    } else {
      bow = vocabulary.transform(descriptors);
    }
    benchmark::DoNotOptimize(bow.data());
  }
  state.counters["descriptors"] = descriptors.rows;
  state.counters["words"] = static_cast<double>(bow.size());
}
BENCHMARK(BM_Transform1M)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// Training on 40 KITTI frames (every 4th of 160; ~40k descriptors), k = 10, L = 6.
void BM_TrainKitti40(benchmark::State& state) {
  const auto descriptors = kittiDescriptors(4);
  loop::TrainingParams params;
  std::size_t words = 0;
  for (auto _ : state) words = loop::trainVocabulary(descriptors, params).wordCount();
  state.counters["images"] = static_cast<double>(descriptors.size());
  state.counters["words"] = static_cast<double>(words);
}
BENCHMARK(BM_TrainKitti40)->Unit(benchmark::kMillisecond)->Iterations(1);

// Query of a database holding the 160 KITTI frames (vocabulary trained on every 4th),
// querying each frame in turn; counter: fraction of frames that find themselves first.
void BM_DatabaseQueryKitti160(benchmark::State& state) {
  const auto all = kittiDescriptors(1);
  std::vector<cv::Mat> training;
  for (std::size_t i = 0; i < all.size(); i += 4) training.push_back(all[i]);
  const auto vocabulary = loop::trainVocabulary(training, loop::TrainingParams{});
  loop::KeyFrameDatabase db;
  std::vector<loop::BowVector> bows;
  for (std::size_t i = 0; i < all.size(); ++i) {
    loop::KeyFrameBow entry;
    vocabulary.transform(all[i], 4, entry.bow, entry.features);
    bows.push_back(entry.bow);
    db.add(i, std::move(entry));
  }
  std::size_t self_first = 0;
  std::size_t queries = 0;
  std::size_t next = 0;
  for (auto _ : state) {
    const auto result = db.query(bows[next]);
    self_first += !result.empty() && result[0].id == next;
    ++queries;
    next = (next + 1) % bows.size();
  }
  state.counters["keyframes"] = static_cast<double>(db.size());
  state.counters["self_first"] = static_cast<double>(self_first) / static_cast<double>(queries);
}
BENCHMARK(BM_DatabaseQueryKitti160)->Unit(benchmark::kMicrosecond)->Iterations(160);

// Place recognition across data sets: vocabulary trained on the EuRoC excerpt (indoor, 95
// frames), database = every 10th KITTI frame (outdoor), queries = frames 3 after each of
// them. Counters: fraction whose nearest keyframe (3 frames back) ranks first, and of
// inserted frames that find themselves first.
void BM_PlaceRecognitionEurocVocabKitti(benchmark::State& state) {
  const feature::OrbExtractor extractor{feature::OrbSettings{}};
  std::vector<cv::Mat> training;
  const fs::path euroc =
      fs::path(LUMASLAM_SHARED_DIR) / "data/euroc/V1_01_easy_micro/mav0/cam0/data";
  for (const auto& entry : fs::directory_iterator(euroc)) {
    training.push_back(
        extractor.extract(cv::imread(entry.path().string(), cv::IMREAD_GRAYSCALE)).descriptors);
  }
  loop::TrainingParams params;
  params.depth = 5;
  const auto vocabulary = loop::trainVocabulary(training, params);
  const auto kitti = kittiDescriptors(1);
  loop::KeyFrameDatabase db;
  for (std::size_t i = 0; i < kitti.size(); i += 10) {
    loop::KeyFrameBow entry;
    vocabulary.transform(kitti[i], 4, entry.bow, entry.features);
    db.add(i, std::move(entry));
  }
  std::size_t nearest_first = 0;
  std::size_t self_first = 0;
  std::size_t queries = 0;
  for (auto _ : state) {
    nearest_first = self_first = queries = 0;
    for (std::size_t i = 0; i + 3 < kitti.size(); i += 10) {
      const auto near = db.query(vocabulary.transform(kitti[i + 3]));
      nearest_first += !near.empty() && near[0].id == i;
      const auto self = db.query(vocabulary.transform(kitti[i]));
      self_first += !self.empty() && self[0].id == i;
      ++queries;
    }
  }
  state.counters["words"] = static_cast<double>(vocabulary.wordCount());
  state.counters["nearest_first"] =
      static_cast<double>(nearest_first) / static_cast<double>(queries);
  state.counters["self_first"] = static_cast<double>(self_first) / static_cast<double>(queries);
}
BENCHMARK(BM_PlaceRecognitionEurocVocabKitti)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
