#pragma once
// Bag-of-words image representations produced by a Vocabulary (DBoW2's BowVector and
// FeatureVector) and the L1 similarity score between two of them.
#include <cstdint>
#include <map>
#include <vector>

namespace lumaslam::loop {

using WordId = std::uint32_t;
using NodeId = std::uint32_t;

struct BowWord {
  WordId word = 0;
  double weight = 0.0;
  bool operator==(const BowWord&) const = default;
};

// Words of one image, sorted by word id, weights TF-IDF and L1-normalised (sum = 1).
using BowVector = std::vector<BowWord>;

// Direct index: vocabulary node at a fixed level -> indices of the features that fall under
// it. Two images' features only need to be compared within the same node (guided matching).
using FeatureVector = std::map<NodeId, std::vector<int>>;

// DBoW2's L1 score: 1 - 0.5 * |a - b|_1 for L1-normalised vectors, in [0, 1] (1 = same
// words in the same proportions, 0 = no word in common).
double score(const BowVector& a, const BowVector& b);

// Number of words the two vectors have in common.
int sharedWords(const BowVector& a, const BowVector& b);

}  // namespace lumaslam::loop
