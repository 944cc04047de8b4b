#include "lumaslam/loop/vocabulary_training.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstring>
#include <random>

#include <opencv2/core/utility.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/feature/hamming.h"

namespace lumaslam::loop {

namespace {

using Descriptor = std::array<std::uint8_t, kDescriptorBytes>;

// kSpread[b] has byte j equal to bit j of b: adding it to a uint64 counts 8 bits at once.
constexpr std::array<std::uint64_t, 256> makeSpread() {
  std::array<std::uint64_t, 256> table{};
  for (int b = 0; b < 256; ++b) {
    for (int j = 0; j < 8; ++j) {
      if (b & (1 << j)) table[b] |= std::uint64_t{1} << (8 * j);
    }
  }
  return table;
}
constexpr auto kSpread = makeSpread();

// Bitwise majority of the member descriptors (the binary "mean" of k-majority).
Descriptor majority(const std::uint8_t* all, const std::vector<std::uint32_t>& members) {
  std::array<int, kDescriptorBytes * 8> counts{};
  std::array<std::uint64_t, kDescriptorBytes> packed{};
  int pending = 0;
  const auto flush = [&] {
    for (int byte = 0; byte < kDescriptorBytes; ++byte) {
      for (int bit = 0; bit < 8; ++bit) {
        counts[byte * 8 + bit] += static_cast<int>((packed[byte] >> (8 * bit)) & 0xFF);
      }
      packed[byte] = 0;
    }
    pending = 0;
  };
  for (const std::uint32_t m : members) {
    const std::uint8_t* d = all + static_cast<std::size_t>(m) * kDescriptorBytes;
    for (int byte = 0; byte < kDescriptorBytes; ++byte) packed[byte] += kSpread[d[byte]];
    if (++pending == 255) flush();  // each byte lane holds at most 255
  }
  flush();
  Descriptor centre{};
  const int n = static_cast<int>(members.size());
  for (int i = 0; i < kDescriptorBytes * 8; ++i) {
    if (2 * counts[i] > n) centre[i / 8] |= static_cast<std::uint8_t>(1 << (i % 8));
  }
  return centre;
}

// Calls body(begin, end) over [0, n): split across threads when n is large (the top levels
// of the tree see every descriptor), inline otherwise. Each index's result must not depend
// on the others, so the outcome is the same for any thread count.
template <typename Body>
void forRanges(std::size_t n, Body&& body) {
  constexpr std::size_t kParallelMin = 20000;
  if (n < kParallelMin) {
    body(std::size_t{0}, n);
    return;
  }
  cv::parallel_for_(cv::Range(0, static_cast<int>(n)), [&](const cv::Range& range) {
    body(static_cast<std::size_t>(range.start), static_cast<std::size_t>(range.end));
  });
}

struct Clusters {
  std::vector<Descriptor> centres;
  std::vector<std::vector<std::uint32_t>> members;
};

class TreeBuilder {
 public:
  TreeBuilder(const std::vector<std::uint8_t>& all, const TrainingParams& params,
              const TrainingProgress& on_progress)
      : all_(all.data()), params_(params), on_progress_(on_progress), rng_(params.seed) {}

  VocabularyData build(std::vector<std::uint32_t> members) {
    total_ = members.size();
    data_.branching = params_.branching;
    data_.depth = params_.depth;
    addNode(Descriptor{});
    split(0, std::move(members), 0);
    for (NodeId n = 0; n < data_.nodeCount(); ++n) {
      if (data_.child_count[n] > 0 || n == 0) continue;
      data_.node_word[n] = static_cast<WordId>(data_.word_node.size());
      data_.word_node.push_back(n);
    }
    data_.word_weight.assign(data_.word_node.size(), 0.0F);
    return std::move(data_);
  }

 private:
  void settled(std::size_t count) {
    done_ += count;
    if (on_progress_) on_progress_(done_, total_);
  }

  const std::uint8_t* at(std::uint32_t m) const {
    return all_ + static_cast<std::size_t>(m) * kDescriptorBytes;
  }

  NodeId addNode(const Descriptor& centre) {
    data_.first_child.push_back(0);
    data_.child_count.push_back(0);
    data_.node_word.push_back(kNoWord);
    data_.descriptors.insert(data_.descriptors.end(), centre.begin(), centre.end());
    return static_cast<NodeId>(data_.nodeCount() - 1);
  }

  void split(NodeId node, std::vector<std::uint32_t> members, int level) {
    if (level >= params_.depth || members.size() <= 1) return settled(members.size());
    const std::size_t count = members.size();
    Clusters clusters = kMajority(members);
    members = {};
    if (clusters.centres.size() <= 1 && node != 0) return settled(count);  // nothing to separate
    const auto first = static_cast<NodeId>(data_.nodeCount());
    for (const auto& centre : clusters.centres) addNode(centre);
    data_.first_child[node] = first;
    data_.child_count[node] = static_cast<std::uint32_t>(clusters.centres.size());
    for (std::size_t c = 0; c < clusters.centres.size(); ++c) {
      split(first + static_cast<NodeId>(c), std::move(clusters.members[c]), level + 1);
    }
  }

  // k-means++ seeding: each next centre drawn with probability proportional to the squared
  // distance to the nearest centre so far; stops early when every member is a centre.
  std::vector<Descriptor> seed(const std::vector<std::uint32_t>& members) {
    std::vector<Descriptor> centres;
    std::uniform_int_distribution<std::size_t> pick(0, members.size() - 1);
    const auto add = [&](std::uint32_t m) {
      Descriptor d;
      std::memcpy(d.data(), at(m), kDescriptorBytes);
      centres.push_back(d);
    };
    add(members[pick(rng_)]);
    std::vector<double> nearest(members.size());
    for (std::size_t i = 0; i < members.size(); ++i) {
      nearest[i] = feature::hammingDistance(at(members[i]), centres[0].data());
    }
    while (static_cast<int>(centres.size()) < params_.branching) {
      double total = 0.0;
      for (const double d : nearest) total += d * d;
      if (total <= 0.0) break;
      double target = std::uniform_real_distribution<double>(0.0, total)(rng_);
      std::size_t chosen = members.size() - 1;
      for (std::size_t i = 0; i < members.size(); ++i) {
        target -= nearest[i] * nearest[i];
        if (target < 0.0 && nearest[i] > 0.0) {
          chosen = i;
          break;
        }
      }
      if (nearest[chosen] <= 0.0) break;
      add(members[chosen]);
      forRanges(members.size(), [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
          nearest[i] = std::min<double>(
              nearest[i], feature::hammingDistance(at(members[i]), centres.back().data()));
        }
      });
    }
    return centres;
  }

  // Nearest centre of every member; true if any assignment changed.
  bool assign(const std::vector<std::uint32_t>& members, const std::vector<Descriptor>& centres,
              std::vector<std::uint32_t>& assignment) const {
    std::atomic<bool> changed{false};
    forRanges(members.size(), [&](std::size_t begin, std::size_t end) {
      bool range_changed = false;
      for (std::size_t i = begin; i < end; ++i) {
        const std::uint8_t* d = at(members[i]);
        std::uint32_t best = 0;
        int best_distance = feature::hammingDistance(d, centres[0].data());
        for (std::uint32_t c = 1; c < centres.size(); ++c) {
          const int distance = feature::hammingDistance(d, centres[c].data());
          if (distance < best_distance) {
            best_distance = distance;
            best = c;
          }
        }
        range_changed |= assignment[i] != best;
        assignment[i] = best;
      }
      if (range_changed) changed = true;
    });
    return changed;
  }

  Clusters kMajority(const std::vector<std::uint32_t>& members) {
    Clusters result;
    result.centres = seed(members);
    const std::size_t k = result.centres.size();
    std::vector<std::uint32_t> assignment(members.size(), k);  // k = unassigned
    for (int iteration = 0; iteration < params_.max_iterations; ++iteration) {
      const bool changed = assign(members, result.centres, assignment);
      result.members.assign(k, {});
      for (std::size_t i = 0; i < members.size(); ++i) {
        result.members[assignment[i]].push_back(members[i]);
      }
      if (!changed) break;
      for (std::size_t c = 0; c < k; ++c) {
        if (!result.members[c].empty()) result.centres[c] = majority(all_, result.members[c]);
      }
    }
    // Drop clusters that lost all their members.
    Clusters kept;
    for (std::size_t c = 0; c < k; ++c) {
      if (result.members[c].empty()) continue;
      kept.centres.push_back(result.centres[c]);
      kept.members.push_back(std::move(result.members[c]));
    }
    return kept;
  }

  const std::uint8_t* all_;
  TrainingParams params_;
  const TrainingProgress& on_progress_;
  std::mt19937_64 rng_;
  std::size_t total_ = 0;  // descriptors to place
  std::size_t done_ = 0;   // descriptors settled in a leaf
  VocabularyData data_;
};

void checkParams(const TrainingParams& params) {
  if (params.branching < 2 || params.branching > 256) {
    fail("vocabulary training: k = {} (must be 2..256)", params.branching);
  }
  if (params.depth < 1 || params.depth > 16) {
    fail("vocabulary training: L = {} (must be 1..16)", params.depth);
  }
  if (params.max_iterations < 1) {
    fail("vocabulary training: max_iterations = {} (must be >= 1)", params.max_iterations);
  }
}

}  // namespace

Vocabulary trainVocabulary(const std::vector<cv::Mat>& images, const TrainingParams& params,
                           const TrainingProgress& on_progress) {
  checkParams(params);
  std::vector<std::uint8_t> all;
  std::vector<std::uint32_t> image_of;
  for (std::size_t i = 0; i < images.size(); ++i) {
    const cv::Mat& d = images[i];
    if (d.empty()) continue;
    if (d.type() != CV_8UC1 || d.cols != kDescriptorBytes) {
      fail("vocabulary training: image {}: descriptors must be N x {} CV_8UC1, got {} x {}", i,
           kDescriptorBytes, d.rows, d.cols);
    }
    for (int r = 0; r < d.rows; ++r) {
      all.insert(all.end(), d.ptr<std::uint8_t>(r), d.ptr<std::uint8_t>(r) + kDescriptorBytes);
      image_of.push_back(static_cast<std::uint32_t>(i));
    }
  }
  if (image_of.empty()) fail("vocabulary training: no descriptors in {} images", images.size());

  std::vector<std::uint32_t> members(image_of.size());
  for (std::uint32_t m = 0; m < members.size(); ++m) members[m] = m;
  VocabularyData data = TreeBuilder(all, params, on_progress).build(std::move(members));
  Vocabulary unweighted(data, "trained vocabulary");

  // IDF (DBoW2 TF_IDF): log(N / n_i), n_i = training images in which word i occurs.
  std::vector<std::uint32_t> last_image(data.wordCount(), UINT32_MAX);
  std::vector<std::uint32_t> image_count(data.wordCount(), 0);
  std::vector<WordId> word_of(image_of.size());
  forRanges(image_of.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t m = begin; m < end; ++m) {
      word_of[m] = unweighted.wordOf(all.data() + m * kDescriptorBytes);
    }
  });
  for (std::size_t m = 0; m < image_of.size(); ++m) {
    const WordId word = word_of[m];
    if (last_image[word] != image_of[m]) {
      last_image[word] = image_of[m];
      ++image_count[word];
    }
  }
  const double n_images = static_cast<double>(images.size());
  for (std::size_t w = 0; w < data.wordCount(); ++w) {
    // A word no training descriptor reaches by descent (possible after majority updates)
    // gets the largest weight, as if seen once.
    data.word_weight[w] =
        static_cast<float>(std::log(n_images / std::max<std::uint32_t>(image_count[w], 1)));
  }
  return Vocabulary(std::move(data), "trained vocabulary");
}

}  // namespace lumaslam::loop
