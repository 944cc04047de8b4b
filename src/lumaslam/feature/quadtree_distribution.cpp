#include "lumaslam/feature/quadtree_distribution.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace lumaslam::feature {

namespace {

struct Node {
  cv::Rect2f area;
  std::vector<int> members;  // indices into the candidates
  bool alive = true;

  // A node with one keypoint, or too small to separate integer pixel positions, is final.
  bool splittable() const {
    return members.size() > 1 && (area.width > 1.0f || area.height > 1.0f);
  }
};

std::array<Node, 4> splitInFour(const Node& node, const std::vector<cv::KeyPoint>& candidates) {
  const float halfWidth = node.area.width / 2;
  const float halfHeight = node.area.height / 2;
  const float midX = node.area.x + halfWidth;
  const float midY = node.area.y + halfHeight;
  std::array<Node, 4> children;
  for (int quadrant = 0; quadrant < 4; ++quadrant) {
    children[quadrant].area = cv::Rect2f(quadrant % 2 ? midX : node.area.x,
                                         quadrant / 2 ? midY : node.area.y, halfWidth, halfHeight);
  }
  for (const int index : node.members) {
    const cv::Point2f& p = candidates[index].pt;
    children[(p.x >= midX ? 1 : 0) + (p.y >= midY ? 2 : 0)].members.push_back(index);
  }
  return children;
}

class Quadtree {
 public:
  Quadtree(const std::vector<cv::KeyPoint>& candidates, const cv::Rect2f& area)
      : candidates_(candidates) {
    // Start with roughly square root nodes side by side (wide images give several).
    const int roots = std::max(1, static_cast<int>(std::lround(area.width / area.height)));
    const float rootWidth = area.width / roots;
    std::vector<Node> rootNodes(roots);
    for (int i = 0; i < roots; ++i) {
      rootNodes[i].area = cv::Rect2f(area.x + i * rootWidth, area.y, rootWidth, area.height);
    }
    for (int index = 0; index < static_cast<int>(candidates.size()); ++index) {
      const int root =
          std::clamp(static_cast<int>((candidates[index].pt.x - area.x) / rootWidth), 0, roots - 1);
      rootNodes[root].members.push_back(index);
    }
    for (Node& node : rootNodes) add(std::move(node));
  }

  int aliveCount() const { return alive_; }

  // Splits every splittable node once; returns the indices of new splittable children.
  std::vector<int> splitAll() {
    std::vector<int> splittableChildren;
    const int existing = static_cast<int>(nodes_.size());
    for (int i = 0; i < existing; ++i) {
      if (nodes_[i].alive && nodes_[i].splittable()) split(i, splittableChildren);
    }
    return splittableChildren;
  }

  // Splits the given nodes largest first until `target` nodes exist; returns new splittable
  // children (to continue with) or an empty list once the target is reached.
  std::vector<int> splitLargestFirst(std::vector<int> nodes, int target) {
    std::stable_sort(nodes.begin(), nodes.end(), [&](int a, int b) {
      return nodes_[a].members.size() > nodes_[b].members.size();
    });
    std::vector<int> splittableChildren;
    for (const int i : nodes) {
      split(i, splittableChildren);
      if (alive_ >= target) return {};
    }
    return splittableChildren;
  }

  // The strongest keypoint of every alive node.
  std::vector<cv::KeyPoint> winners() const {
    std::vector<cv::KeyPoint> result;
    result.reserve(alive_);
    for (const Node& node : nodes_) {
      if (!node.alive) continue;
      const int best = *std::max_element(
          node.members.begin(), node.members.end(),
          [&](int a, int b) { return candidates_[a].response < candidates_[b].response; });
      result.push_back(candidates_[best]);
    }
    return result;
  }

 private:
  void add(Node node) {
    if (node.members.empty()) return;
    nodes_.push_back(std::move(node));
    ++alive_;
  }

  void split(int index, std::vector<int>& splittableChildren) {
    auto children = splitInFour(nodes_[index], candidates_);
    nodes_[index].alive = false;
    nodes_[index].members.clear();
    --alive_;
    for (Node& child : children) {
      const bool splittable = child.splittable();
      const bool nonEmpty = !child.members.empty();
      add(std::move(child));
      if (nonEmpty && splittable) splittableChildren.push_back(static_cast<int>(nodes_.size()) - 1);
    }
  }

  const std::vector<cv::KeyPoint>& candidates_;
  std::vector<Node> nodes_;
  int alive_ = 0;
};

}  // namespace

std::vector<cv::KeyPoint> distributeByQuadtree(const std::vector<cv::KeyPoint>& candidates,
                                               const cv::Rect2f& area, int target) {
  if (candidates.empty() || target <= 0 || area.width <= 0 || area.height <= 0) return {};
  Quadtree tree(candidates, area);
  // Breadth-first rounds while a full round cannot overshoot the target; then split the most
  // crowded nodes first so the last splits go where keypoints are densest (ORB-SLAM's rule).
  while (tree.aliveCount() < target) {
    const int before = tree.aliveCount();
    std::vector<int> frontier = tree.splitAll();
    if (tree.aliveCount() >= target || tree.aliveCount() == before) break;
    if (tree.aliveCount() + 3 * static_cast<int>(frontier.size()) > target) {
      while (!frontier.empty() && tree.aliveCount() < target) {
        frontier = tree.splitLargestFirst(std::move(frontier), target);
      }
      break;
    }
  }
  std::vector<cv::KeyPoint> result = tree.winners();
  if (static_cast<int>(result.size()) > target) {
    // cv::KeyPointsFilter::retainBest keeps ties with the cut-off response; we need <= target.
    std::stable_sort(
        result.begin(), result.end(),
        [](const cv::KeyPoint& a, const cv::KeyPoint& b) { return a.response > b.response; });
    result.resize(target);
  }
  return result;
}

}  // namespace lumaslam::feature
