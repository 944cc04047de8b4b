#pragma once
// A vocabulary tree for 256-bit ORB descriptors (Galvez-Lopez & Tardos, DBoW2): a k-ary tree
// of binary cluster centres, depth <= L; its leaves are the words, each with an IDF weight.
// Stored flat (one array per field, children of a node contiguous) so that transform() walks
// cache-friendly memory and loading is a handful of bulk reads (vocabulary_io.h).
#include <cstdint>
#include <limits>
#include <string_view>
#include <vector>

#include <opencv2/core.hpp>

#include "lumaslam/loop/bow_vector.h"

namespace lumaslam::loop {

inline constexpr int kDescriptorBytes = 32;
inline constexpr std::uint32_t kNoWord = std::numeric_limits<std::uint32_t>::max();

// The tree as flat arrays. Node 0 is the root (no descriptor of its own, all zero). Every
// node's children are the contiguous range [first_child, first_child + child_count) and have
// larger ids than their parent. Leaves have child_count 0 and a word id.
struct VocabularyData {
  int branching = 0;                       // k
  int depth = 0;                           // L
  std::vector<std::uint32_t> first_child;  // per node
  std::vector<std::uint32_t> child_count;  // per node
  std::vector<std::uint32_t> node_word;    // per node: word id, kNoWord for inner nodes
  std::vector<std::uint8_t> descriptors;   // per node, kDescriptorBytes each
  std::vector<NodeId> word_node;           // per word: its leaf node
  std::vector<float> word_weight;          // per word: IDF weight

  std::size_t nodeCount() const { return first_child.size(); }
  std::size_t wordCount() const { return word_node.size(); }
  bool operator==(const VocabularyData&) const = default;
};

class Vocabulary {
 public:
  Vocabulary() = default;  // empty: transform() gives empty vectors
  // Checks the structure (sizes, child ranges, word <-> leaf mapping, finite weights) and
  // throws Error naming `origin` (a file name, or "vocabulary") and the first problem.
  Vocabulary(VocabularyData data, std::string_view origin);

  int branching() const { return data_.branching; }
  int depth() const { return data_.depth; }
  std::size_t wordCount() const { return data_.wordCount(); }
  std::size_t nodeCount() const { return data_.nodeCount(); }
  bool empty() const { return data_.wordCount() == 0; }
  const VocabularyData& data() const { return data_; }
  float weight(WordId word) const { return data_.word_weight[word]; }
  // Node id of a word's leaf and the descriptor of a node (cluster centre).
  NodeId leafOf(WordId word) const { return data_.word_node[word]; }
  const std::uint8_t* nodeDescriptor(NodeId node) const {
    return data_.descriptors.data() + static_cast<std::size_t>(node) * kDescriptorBytes;
  }
  // Depth of a node below the root (root = 0).
  int levelOf(NodeId node) const { return level_[node]; }

  // The word of one descriptor (descend to the nearest child by Hamming distance).
  WordId wordOf(const std::uint8_t* descriptor) const;

  // BoW vector of an image's descriptors (N x 32 CV_8U): TF-IDF weights, L1-normalised.
  // Words with zero weight (seen in every training image) are left out, as in DBoW2.
  BowVector transform(const cv::Mat& descriptors) const;
  // Also fills the direct index with the node `levels_up` levels above the leaves (DBoW2's
  // convention; ORB-SLAM uses 4 with L = 6, i.e. nodes at level 2 below the root). Levels are
  // clamped to [1, L]. Features whose word has zero weight are left out of both.
  void transform(const cv::Mat& descriptors, int levels_up, BowVector& bow,
                 FeatureVector& features) const;

  bool operator==(const Vocabulary& other) const { return data_ == other.data_; }

 private:
  // Leaf node of `descriptor`; `level_node` receives the node passed at `level` (or the
  // leaf, if the leaf is shallower).
  NodeId descend(const std::uint8_t* descriptor, int level, NodeId& level_node) const;
  void checkDescriptors(const cv::Mat& descriptors) const;

  VocabularyData data_;
  std::vector<std::uint8_t> level_;  // per node, derived at construction
};

}  // namespace lumaslam::loop
