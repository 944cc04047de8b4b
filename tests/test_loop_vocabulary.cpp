// Vocabulary tree: training on synthetic ORB descriptors, transform/score, the binary format
// and the DBoW2 text format (round trips, hand-written files, malformed input).
#include <cmath>
#include <fstream>
#include <numeric>
#include <set>

#include <gtest/gtest.h>

#include "error_of.h"
#include "loop_test_frames.h"
#include "lumaslam/core/error.h"
#include "lumaslam/loop/vocabulary.h"
#include "lumaslam/loop/vocabulary_io.h"
#include "lumaslam/loop/vocabulary_training.h"
#include "test_paths.h"

namespace {

using namespace lumaslam;
using loop::BowVector;
using loop::FeatureVector;
using loop::Vocabulary;
using test::errorOf;

constexpr int kTrainFrames = 12;

const test::LoopLapFrames& trainingLap() {
  static const test::LoopLapFrames lap = test::renderLoopLap(kTrainFrames, 3);
  return lap;
}

loop::TrainingParams smallParams() {
  loop::TrainingParams params;
  params.branching = 8;
  params.depth = 3;
  return params;
}

const Vocabulary& trainedVocabulary() {
  static const Vocabulary vocabulary =
      loop::trainVocabulary(trainingLap().descriptors, smallParams());
  return vocabulary;
}

void writeText(const std::filesystem::path& file, const std::string& text) {
  std::ofstream(file, std::ios::binary) << text;
}

void writeLines(const std::filesystem::path& file, const std::vector<std::string>& lines) {
  std::string text;
  for (const auto& line : lines) text.append(line).append("\n");
  writeText(file, text);
}

// Expects `load(file)` to throw an Error whose message contains every one of `parts`.
template <typename Load>
void expectError(Load&& load, const std::vector<std::string>& parts) {
  const std::string message = errorOf(load);
  for (const auto& part : parts) {
    EXPECT_NE(message.find(part), std::string::npos) << message << " lacks '" << part << "'";
  }
}

// Leaf nodes in the subtree of `node`.
std::set<loop::NodeId> leavesUnder(const loop::VocabularyData& data, loop::NodeId node) {
  std::set<loop::NodeId> leaves;
  std::vector<loop::NodeId> stack = {node};
  while (!stack.empty()) {
    const loop::NodeId n = stack.back();
    stack.pop_back();
    if (data.child_count[n] == 0) leaves.insert(n);
    for (std::uint32_t c = 0; c < data.child_count[n]; ++c)
      stack.push_back(data.first_child[n] + c);
  }
  return leaves;
}

// One DBoW2 node line whose 32 descriptor bytes all equal `byte`.
std::string node(int parent, int is_leaf, int byte, const std::string& weight) {
  std::string text = fmt::format("{} {}", parent, is_leaf);
  for (int b = 0; b < 32; ++b) text.append(fmt::format(" {}", byte));
  return text.append(" ").append(weight);
}

TEST(LoopVocabulary, TrainedTreeHasWordsWithIdfWeights) {
  const Vocabulary& vocabulary = trainedVocabulary();
  EXPECT_EQ(vocabulary.branching(), 8);
  EXPECT_EQ(vocabulary.depth(), 3);
  // ~12k descriptors are plenty to fill most of the 512 leaves of a 8^3 tree.
  EXPECT_GT(vocabulary.wordCount(), 300U);
  EXPECT_LE(vocabulary.wordCount(), 512U);
  const double max_idf = std::log(static_cast<double>(kTrainFrames));
  int weighted = 0;
  for (loop::WordId w = 0; w < vocabulary.wordCount(); ++w) {
    EXPECT_GE(vocabulary.weight(w), 0.0F);
    EXPECT_LE(vocabulary.weight(w), max_idf + 1e-5);
    weighted += vocabulary.weight(w) > 0.0F;
    EXPECT_LE(vocabulary.levelOf(vocabulary.leafOf(w)), 3);
  }
  EXPECT_GT(weighted, static_cast<int>(vocabulary.wordCount()) / 2);
}

TEST(LoopVocabulary, TrainingIsDeterministicForASeed) {
  EXPECT_EQ(loop::trainVocabulary(trainingLap().descriptors, smallParams()), trainedVocabulary());
  auto other = smallParams();
  other.seed = 2;
  EXPECT_FALSE(loop::trainVocabulary(trainingLap().descriptors, other) == trainedVocabulary());
}

TEST(LoopVocabulary, DescriptorsDescendToTheNearestLeafCentre) {
  // A leaf centre itself must map to its own word (it is nearest to itself at every level
  // only if the tree was built consistently; check a node's centre is reachable).
  const Vocabulary& vocabulary = trainedVocabulary();
  const cv::Mat& descriptors = trainingLap().descriptors[0];
  int exact = 0;
  for (loop::WordId w = 0; w < vocabulary.wordCount(); ++w) {
    exact += vocabulary.wordOf(vocabulary.nodeDescriptor(vocabulary.leafOf(w))) == w;
  }
  EXPECT_GT(exact, static_cast<int>(vocabulary.wordCount()) * 9 / 10);
  // The word of a descriptor is the closest among its siblings' centres.
  for (int i = 0; i < descriptors.rows; i += 50) {
    const loop::WordId word = vocabulary.wordOf(descriptors.ptr<std::uint8_t>(i));
    ASSERT_LT(word, vocabulary.wordCount());
  }
}

TEST(LoopVocabulary, TransformGivesNormalisedSortedBowAndDirectIndex) {
  const Vocabulary& vocabulary = trainedVocabulary();
  const cv::Mat& descriptors = trainingLap().descriptors[5];
  BowVector bow;
  FeatureVector features;
  vocabulary.transform(descriptors, 2, bow, features);
  ASSERT_FALSE(bow.empty());
  double sum = 0.0;
  for (std::size_t i = 0; i < bow.size(); ++i) {
    sum += bow[i].weight;
    EXPECT_GT(bow[i].weight, 0.0);
    if (i > 0) {
      EXPECT_LT(bow[i - 1].word, bow[i].word);
    }
  }
  EXPECT_NEAR(sum, 1.0, 1e-9);
  EXPECT_EQ(vocabulary.transform(descriptors), bow);

  // Direct index: nodes one level below the root (L - 2), each feature under the ancestor
  // of its word's leaf, every feature at most once.
  std::set<int> seen;
  for (const auto& [node, indices] : features) {
    EXPECT_EQ(vocabulary.levelOf(node), 1);
    for (const int i : indices) {
      EXPECT_TRUE(seen.insert(i).second);
      const loop::WordId word = vocabulary.wordOf(descriptors.ptr<std::uint8_t>(i));
      EXPECT_TRUE(leavesUnder(vocabulary.data(), node).contains(vocabulary.leafOf(word)));
    }
  }
  EXPECT_EQ(seen.size(), static_cast<std::size_t>(std::accumulate(
                             features.begin(), features.end(), 0, [](int n, const auto& e) {
                               return n + static_cast<int>(e.second.size());
                             })));
}

TEST(LoopVocabulary, ScoreIsOneForSameImageAndLowerForOtherViews) {
  const Vocabulary& vocabulary = trainedVocabulary();
  const auto& lap = trainingLap();
  const BowVector a = vocabulary.transform(lap.descriptors[0]);
  EXPECT_NEAR(loop::score(a, a), 1.0, 1e-9);
  const BowVector opposite = vocabulary.transform(lap.descriptors[kTrainFrames / 2]);
  const BowVector next = vocabulary.transform(lap.descriptors[1]);
  EXPECT_GT(loop::score(a, next), loop::score(a, opposite));
  EXPECT_DOUBLE_EQ(loop::score(a, next), loop::score(next, a));
  EXPECT_EQ(loop::score(a, {}), 0.0);
  // Two vectors with half their mass on one shared word.
  const BowVector x = {{1, 0.5}, {2, 0.5}};
  const BowVector y = {{2, 0.5}, {3, 0.5}};
  EXPECT_NEAR(loop::score(x, y), 0.5, 1e-12);
  EXPECT_EQ(loop::sharedWords(x, y), 1);
}

TEST(LoopVocabulary, TransformRejectsNonOrbDescriptors) {
  EXPECT_THROW(trainedVocabulary().transform(cv::Mat(10, 64, CV_32F, cv::Scalar(0))), Error);
  EXPECT_TRUE(trainedVocabulary().transform(cv::Mat()).empty());
}

TEST(LoopVocabulary, BinaryRoundTripIsExact) {
  const test::TempDir dir("vocab_binary");
  const auto file = dir.path() / "vocab.bin";
  loop::saveVocabulary(trainedVocabulary(), file);
  EXPECT_TRUE(loop::isBinaryVocabulary(file));
  const Vocabulary loaded = loop::loadVocabulary(file);
  EXPECT_EQ(loaded, trainedVocabulary());
  for (const cv::Mat& descriptors : trainingLap().descriptors) {
    EXPECT_EQ(loaded.transform(descriptors), trainedVocabulary().transform(descriptors));
  }
  EXPECT_EQ(loop::loadAnyVocabulary(file), loaded);
}

// Saving goes through FILE.partial: a save that cannot be put in place is an error naming the
// file and leaves what was there (here a folder in the way) and no partial file.
TEST(LoopVocabulary, AFailedSaveIsAnErrorAndLeavesNoPartialFile) {
  const test::TempDir dir("vocab_atomic");
  const auto file = dir.path() / "vocab.bin";
  std::filesystem::create_directories(file / "in_the_way");
  for (const bool text : {false, true}) {
    // Saving over a folder throws.
    const std::string message = errorOf([&] {
      text ? loop::saveDbow2Text(trainedVocabulary(), file)
           : loop::saveVocabulary(trainedVocabulary(), file);
    });
    EXPECT_NE(message.find("vocab.bin"), std::string::npos) << "text " << text << ": " << message;
    EXPECT_TRUE(std::filesystem::is_directory(file / "in_the_way"));
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "vocab.bin.partial"));
  }
}

TEST(LoopVocabulary, Dbow2TextRoundTripIsExact) {
  const test::TempDir dir("vocab_text");
  const auto file = dir.path() / "voc.txt";
  loop::saveDbow2Text(trainedVocabulary(), file);
  EXPECT_FALSE(loop::isBinaryVocabulary(file));
  const Vocabulary loaded = loop::loadDbow2Text(file);
  EXPECT_EQ(loaded, trainedVocabulary());
  EXPECT_EQ(loop::loadAnyVocabulary(file), loaded);
}

TEST(LoopVocabulary, ReadsHandWrittenDbow2TextInAnyParentFirstOrder) {
  // k = 2, L = 2; the root's children (lines 1 and 3) are not contiguous, so the reader
  // must re-lay the tree out. Leaves carry distinct descriptors and weights.
  const test::TempDir dir("vocab_hand");
  const auto file = dir.path() / "hand.txt";
  writeLines(file, {"2 2 0 0", node(0, 0, 0, "0"),  // 1: inner, all zero bits
                    node(1, 1, 1, "0.5"),           // 2: leaf under 1
                    node(0, 0, 255, "0"),           // 3: inner, all one bits
                    node(1, 1, 0, "1.5"),           // 4: leaf under 1
                    node(3, 1, 255, "2.5"),         // 5: leaf under 3
                    node(3, 1, 127, "3.5"),         // 6: leaf under 3
                    ""});
  const Vocabulary vocabulary = loop::loadDbow2Text(file);
  EXPECT_EQ(vocabulary.branching(), 2);
  EXPECT_EQ(vocabulary.depth(), 2);
  EXPECT_EQ(vocabulary.nodeCount(), 7U);
  ASSERT_EQ(vocabulary.wordCount(), 4U);
  const auto weightOf = [&](int value) {
    std::array<std::uint8_t, 32> d{};
    d.fill(static_cast<std::uint8_t>(value));
    return vocabulary.weight(vocabulary.wordOf(d.data()));
  };
  EXPECT_FLOAT_EQ(weightOf(1), 0.5F);
  EXPECT_FLOAT_EQ(weightOf(0), 1.5F);
  EXPECT_FLOAT_EQ(weightOf(255), 2.5F);
  EXPECT_FLOAT_EQ(weightOf(127), 3.5F);

  // The same file edited on Windows (CRLF) with doubled spaces reads the same.
  std::ifstream in(file, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::string crlf;
  for (const char c : text) {
    if (c == '\n')
      crlf.append("\r\n");
    else if (c == ' ')
      crlf.append("  ");
    else
      crlf.push_back(c);
  }
  const auto windows = dir.path() / "windows.txt";
  writeText(windows, crlf);
  EXPECT_EQ(loop::loadDbow2Text(windows), vocabulary);
}

TEST(LoopVocabulary, MalformedDbow2TextGivesErrorsNamingFileAndLine) {
  const test::TempDir dir("vocab_bad_text");
  const auto file = dir.path() / "bad.txt";
  const auto load = [&] { return loop::loadDbow2Text(file); };
  const std::string leaf = node(0, 1, 3, "1");

  writeText(file, "");
  expectError(load, {"bad.txt", "empty"});
  writeLines(file, {"ten 6 0 0"});
  expectError(load, {"bad.txt:1", "header"});
  writeLines(file, {"10 6 1 0"});
  expectError(load, {"bad.txt:1", "scoring"});
  writeLines(file, {"1 6 0 0"});
  expectError(load, {"bad.txt:1", "out of range"});
  writeLines(file, {"10 6 0 0", leaf, "0 1 1 2 3"});
  expectError(load, {"bad.txt:3", "fields"});
  writeLines(file, {"10 6 0 0", leaf, node(5, 1, 3, "1")});
  expectError(load, {"bad.txt:3", "parent id '5'"});
  writeLines(file, {"10 6 0 0", leaf, node(1, 1, 3, "1")});
  expectError(load, {"bad.txt:3", "parent 1 is a leaf"});
  writeLines(file, {"10 6 0 0", node(0, 2, 3, "1")});
  expectError(load, {"bad.txt:2", "isLeaf"});
  writeLines(file, {"10 6 0 0", node(0, 1, 256, "1")});
  expectError(load, {"bad.txt:2", "0..255"});
  writeLines(file, {"10 6 0 0", node(0, 1, 3, "-1")});
  expectError(load, {"bad.txt:2", "weight"});
  writeLines(file, {"10 1 0 0", node(0, 0, 3, "0"), node(1, 1, 3, "1")});
  expectError(load, {"bad.txt:3", "exceeds L"});
  writeLines(file, {"2 2 0 0", leaf, leaf, leaf});
  expectError(load, {"bad.txt:4", "k = 2"});
  writeText(file, "10 6 0 0\n");
  expectError(load, {"bad.txt", "no nodes"});
  expectError([&] { return loop::loadDbow2Text(dir.path() / "missing.txt"); },
              {"missing.txt", "cannot open"});
}

TEST(LoopVocabulary, DamagedBinaryFilesGiveErrors) {
  const test::TempDir dir("vocab_bad_binary");
  const auto good = dir.path() / "good.bin";
  loop::saveVocabulary(trainedVocabulary(), good);
  std::ifstream in(good, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());

  const auto file = dir.path() / "bad.bin";
  const auto load = [&] { return loop::loadVocabulary(file); };
  writeText(file, bytes.substr(0, bytes.size() - 100));
  expectError(load, {"bad.bin", "truncated"});
  writeText(file, bytes.substr(0, 20));  // cut inside the header
  expectError(load, {"bad.bin", "truncated"});
  writeText(file, "");
  expectError(load, {"bad.bin", "not a lumaslam binary"});
  std::string flipped = bytes;
  flipped[bytes.size() / 2] ^= 0x10;  // one bit of the descriptor array
  writeText(file, flipped);
  expectError(load, {"bad.bin", "checksum mismatch", "corrupt"});
  flipped = bytes;
  flipped[bytes.size() - 1] ^= 0x01;  // the stored checksum itself
  writeText(file, flipped);
  expectError(load, {"bad.bin", "checksum mismatch"});
  writeText(file, "10 6 0 0\n");
  expectError(load, {"bad.bin", "vocab convert"});
  std::string version = bytes;
  version[8] = 9;
  writeText(file, version);
  expectError(load, {"bad.bin", "version 9"});
}

TEST(LoopVocabulary, StructureIsValidated) {
  loop::VocabularyData data = trainedVocabulary().data();
  data.first_child[0] = static_cast<std::uint32_t>(data.nodeCount());
  expectError([&] { return Vocabulary(data, "edited"); }, {"edited", "children"});
  data = trainedVocabulary().data();
  data.word_weight[0] = std::nanf("");
  expectError([&] { return Vocabulary(data, "edited"); }, {"edited", "weight"});
  data = trainedVocabulary().data();
  data.node_word[data.word_node[0]] = 1;
  expectError([&] { return Vocabulary(data, "edited"); }, {"edited", "word"});
}

TEST(LoopVocabulary, TrainingRejectsBadInput) {
  auto params = smallParams();
  params.branching = 1;
  EXPECT_THROW(loop::trainVocabulary(trainingLap().descriptors, params), Error);
  EXPECT_THROW(loop::trainVocabulary({cv::Mat()}, smallParams()), Error);
  EXPECT_THROW(loop::trainVocabulary({cv::Mat(3, 16, CV_8U, cv::Scalar(0))}, smallParams()), Error);
}

}  // namespace
