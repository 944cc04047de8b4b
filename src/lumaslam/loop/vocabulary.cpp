#include "lumaslam/loop/vocabulary.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "lumaslam/core/error.h"
#include "lumaslam/feature/hamming.h"

namespace lumaslam::loop {

namespace {

constexpr int kMaxDepth = 32;

void validate(const VocabularyData& d, std::string_view origin, std::vector<std::uint8_t>& level) {
  if (d.branching < 2) fail("{}: branching factor k = {} (must be >= 2)", origin, d.branching);
  if (d.depth < 1 || d.depth > kMaxDepth) {
    fail("{}: depth L = {} (must be 1..{})", origin, d.depth, kMaxDepth);
  }
  const std::size_t nodes = d.first_child.size();
  if (nodes == 0) fail("{}: no nodes (not even the root)", origin);
  if (d.child_count.size() != nodes || d.node_word.size() != nodes ||
      d.descriptors.size() != nodes * kDescriptorBytes) {
    fail("{}: per-node arrays disagree in length ({} nodes)", origin, nodes);
  }
  if (d.word_weight.size() != d.word_node.size()) {
    fail("{}: {} words but {} weights", origin, d.word_node.size(), d.word_weight.size());
  }
  std::vector<bool> has_parent(nodes, false);
  level.assign(nodes, 0);
  for (std::size_t n = 0; n < nodes; ++n) {
    const std::uint64_t first = d.first_child[n];
    const std::uint64_t count = d.child_count[n];
    if (n != 0 && !has_parent[n]) fail("{}: node {} has no parent", origin, n);
    if (count > static_cast<std::uint64_t>(d.branching)) {
      fail("{}: node {} has {} children (k = {})", origin, n, count, d.branching);
    }
    if (count == 0) {
      const std::uint32_t word = d.node_word[n];
      if (n == 0) {
        if (nodes != 1 || !d.word_node.empty()) fail("{}: root without children", origin);
        continue;
      }
      if (word >= d.word_node.size() || d.word_node[word] != n) {
        fail("{}: leaf node {} has word {} which does not map back to it", origin, n, word);
      }
      continue;
    }
    if (d.node_word[n] != kNoWord) fail("{}: inner node {} has a word id", origin, n);
    if (first <= n || first + count > nodes) {
      fail("{}: node {} has children [{}, {}) outside ({}, {})", origin, n, first, first + count, n,
           nodes);
    }
    if (level[n] >= d.depth) fail("{}: node {} is below depth L = {}", origin, n, d.depth);
    for (std::uint64_t c = first; c < first + count; ++c) {
      if (has_parent[c]) fail("{}: node {} has two parents", origin, c);
      has_parent[c] = true;
      level[c] = static_cast<std::uint8_t>(level[n] + 1);
    }
  }
  for (std::size_t w = 0; w < d.word_node.size(); ++w) {
    if (d.word_node[w] >= nodes || d.node_word[d.word_node[w]] != w) {
      fail("{}: word {} points to node {} which is not its leaf", origin, w, d.word_node[w]);
    }
    if (!std::isfinite(d.word_weight[w]) || d.word_weight[w] < 0.0F) {
      fail("{}: word {} has weight {} (must be finite and >= 0)", origin, w, d.word_weight[w]);
    }
  }
}

}  // namespace

Vocabulary::Vocabulary(VocabularyData data, std::string_view origin) : data_(std::move(data)) {
  validate(data_, origin, level_);
}

NodeId Vocabulary::descend(const std::uint8_t* descriptor, int level, NodeId& level_node) const {
  const std::uint32_t* first_child = data_.first_child.data();
  const std::uint32_t* child_count = data_.child_count.data();
  const std::uint8_t* centres = data_.descriptors.data();
  NodeId node = 0;
  int current = 0;
  level_node = 0;
  while (child_count[node] > 0) {
    const NodeId first = first_child[node];
    const NodeId end = first + child_count[node];
    NodeId best = first;
    int best_distance = feature::hammingDistance(
        descriptor, centres + static_cast<std::size_t>(first) * kDescriptorBytes);
    for (NodeId child = first + 1; child < end; ++child) {
      const int distance = feature::hammingDistance(
          descriptor, centres + static_cast<std::size_t>(child) * kDescriptorBytes);
      if (distance < best_distance) {
        best_distance = distance;
        best = child;
      }
    }
    node = best;
    if (++current == level) level_node = node;
  }
  if (current < level) level_node = node;
  return node;
}

WordId Vocabulary::wordOf(const std::uint8_t* descriptor) const {
  if (empty()) fail("vocabulary: wordOf() on an empty vocabulary");
  NodeId unused = 0;
  return data_.node_word[descend(descriptor, 0, unused)];
}

void Vocabulary::checkDescriptors(const cv::Mat& descriptors) const {
  if (descriptors.empty()) return;
  if (descriptors.type() != CV_8UC1 || descriptors.cols != kDescriptorBytes) {
    fail("vocabulary transform: descriptors must be N x {} CV_8UC1, got {} x {} type {}",
         kDescriptorBytes, descriptors.rows, descriptors.cols, descriptors.type());
  }
}

BowVector Vocabulary::transform(const cv::Mat& descriptors) const {
  BowVector bow;
  FeatureVector unused;
  transform(descriptors, data_.depth, bow, unused);
  return bow;
}

void Vocabulary::transform(const cv::Mat& descriptors, int levels_up, BowVector& bow,
                           FeatureVector& features) const {
  checkDescriptors(descriptors);
  bow.clear();
  features.clear();
  if (empty() || descriptors.empty()) return;
  const int level = std::clamp(data_.depth - levels_up, 1, data_.depth);
  std::vector<WordId> words;
  words.reserve(static_cast<std::size_t>(descriptors.rows));
  for (int i = 0; i < descriptors.rows; ++i) {
    NodeId level_node = 0;
    const WordId word =
        data_.node_word[descend(descriptors.ptr<std::uint8_t>(i), level, level_node)];
    if (data_.word_weight[word] <= 0.0F) continue;
    words.push_back(word);
    features[level_node].push_back(i);
  }
  // TF-IDF: each occurrence adds the word's IDF; the L1 normalisation supplies the 1/N of TF.
  std::sort(words.begin(), words.end());
  double total = 0.0;
  for (std::size_t i = 0; i < words.size();) {
    std::size_t j = i;
    while (j < words.size() && words[j] == words[i]) ++j;
    const double weight = static_cast<double>(j - i) * data_.word_weight[words[i]];
    bow.push_back({words[i], weight});
    total += weight;
    i = j;
  }
  if (total > 0.0) {
    for (auto& entry : bow) entry.weight /= total;
  }
}

}  // namespace lumaslam::loop
