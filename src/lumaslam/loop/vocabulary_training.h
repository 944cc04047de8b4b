#pragma once
// Training a vocabulary tree from ORB descriptors: hierarchical k-majority clustering
// (k-means with Hamming distance and the bitwise majority as centre, k-means++ seeding), then
// IDF weights log(N / n_i) over the training images (DBoW2's HKmeansStep + setNodeWeights).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include <opencv2/core.hpp>

#include "lumaslam/loop/vocabulary.h"

namespace lumaslam::loop {

struct TrainingParams {
  int branching = 10;       // k (ORB-SLAM's ORBvoc: 10)
  int depth = 6;            // L (ORBvoc: 6)
  int max_iterations = 10;  // k-majority iterations per split (stops earlier when stable)
  std::uint64_t seed = 1;   // seeding is random; same seed + same input = same vocabulary
};

// `images`: one N_i x 32 CV_8U descriptor matrix per training image (empty ones are allowed
// and count as images for the IDF). Throws Error for bad parameters, a malformed matrix, or
// no descriptors at all.
// `on_progress(done, total)`: descriptors settled in a leaf of the tree so far, of all of them,
// called from the training thread as the clustering goes (e.g. for a progress line).
using TrainingProgress = std::function<void(std::size_t done, std::size_t total)>;
Vocabulary trainVocabulary(const std::vector<cv::Mat>& images, const TrainingParams& params,
                           const TrainingProgress& on_progress = {});

}  // namespace lumaslam::loop
