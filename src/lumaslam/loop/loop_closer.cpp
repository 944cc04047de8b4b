#include "lumaslam/loop/loop_closer.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <tuple>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include <spdlog/spdlog.h>

#include "lumaslam/loop/map_merge.h"
#include "lumaslam/map/keyframe.h"
#include "lumaslam/map/map_point.h"
#include "lumaslam/mapping/ba_observation.h"
#include "lumaslam/mapping/point_fusion.h"
#include "lumaslam/optimize/local_ba.h"
#include "lumaslam/optimize/pose_graph.h"
#include "lumaslam/optimize/sim3_alignment.h"

namespace lumaslam::loop {

namespace {

using KeyFramePtr = std::shared_ptr<map::KeyFrame>;
using PosesById = std::unordered_map<map::Id, SE3>;
using Sim3 = optimize::Sim3;
using SimsById = std::unordered_map<map::Id, Sim3>;

// The map points of a keyframe and its covisible neighbours, each once.
std::vector<std::shared_ptr<map::MapPoint>> groupPoints(const KeyFramePtr& keyframe) {
  std::vector<KeyFramePtr> group = keyframe->covisibles();
  group.push_back(keyframe);
  std::unordered_set<map::Id> seen;
  std::vector<std::shared_ptr<map::MapPoint>> points;
  for (const auto& kf : group) {
    for (const auto& point : kf->mapPoints()) {
      if (point && !point->isBad() && seen.insert(point->id()).second) points.push_back(point);
    }
  }
  return points;
}

double invSigma2Of(const map::KeyFrame& keyframe, std::size_t feature) {
  const auto& pyramid = keyframe.pyramid();
  const int octave =
      std::clamp(keyframe.features().keypoints[feature].octave, 0, pyramid.count() - 1);
  return pyramid.inverseSigma2(octave);
}

// 3D-3D pairs for the Sim3 between `current` (1) and `loop` (2): each feature of `current`
// with a map point of its own matched (in `slots`) to a point the loop keyframe observes.
struct Sim3Pairs {
  std::vector<optimize::Sim3Pair> pairs;
  std::vector<std::size_t> feature;  // per pair: the feature of `current`
};

Sim3Pairs sim3PairsOf(const map::KeyFrame& current, const map::KeyFrame& loop,
                      const PointSlots& slots) {
  Sim3Pairs out;
  const SE3 T_1w = current.T_c_w();
  const SE3 T_2w = loop.T_c_w();
  const auto& f1 = current.features();
  const auto& f2 = loop.features();
  for (std::size_t i = 0; i < slots.size(); ++i) {
    const auto& p2 = slots[i];
    if (!p2 || p2->isBad()) continue;
    const auto p1 = current.mapPoint(i);
    if (!p1 || p1->isBad()) continue;
    const int j = p2->featureIndexIn(loop.id());
    if (j < 0) continue;
    const auto uj = static_cast<std::size_t>(j);
    optimize::Sim3Pair pair;
    pair.X1 = T_1w * p1->position();
    pair.X2 = T_2w * p2->position();
    pair.uv1 = {f1.undistorted[i].x, f1.undistorted[i].y};
    pair.uv2 = {f2.undistorted[uj].x, f2.undistorted[uj].y};
    pair.invSigma2_1 = invSigma2Of(current, i);
    pair.invSigma2_2 = invSigma2Of(loop, uj);
    out.pairs.push_back(pair);
    out.feature.push_back(i);
  }
  return out;
}

// The keyframes a loop moves (the current one and its covisible neighbours), with their poses
// before and after the loop transform.
struct LoopGroup {
  std::vector<KeyFramePtr> keyframes;
  SimsById uncorrected;
  SimsById corrected;
  std::unordered_map<map::Id, map::Id> corrected_by;  // point -> keyframe it moved with
};

LoopGroup loopGroupOf(const KeyFramePtr& current, const SE3& T_w_cur, const Sim3& S_c_w) {
  LoopGroup group;
  group.keyframes = current->covisibles();
  group.keyframes.push_back(current);
  for (const auto& kf : group.keyframes) {
    group.uncorrected[kf->id()] = Sim3::fromSE3(kf->T_c_w());
    group.corrected[kf->id()] = Sim3::fromSE3(kf->T_c_w() * T_w_cur) * S_c_w;
  }
  return group;
}

ClosedLoop closedLoopOf(const LoopMatch& match, const SE3& T_w_cur) {
  ClosedLoop closed;
  closed.current = match.current->id();
  closed.loop = match.loop->id();
  closed.inliers = match.inliers;
  const SE3 move = T_w_cur * match.T_c_w;
  closed.correction_m = move.translation().norm();
  closed.correction_deg = Eigen::AngleAxisd(move.linear()).angle() * 180.0 / M_PI;
  closed.correction_scale = match.S_c_w.scale;
  return closed;
}

// Each keyframe of the group takes its corrected pose, each of its points (once) moves with it.
void moveGroup(LoopGroup& group) {
  std::vector<std::shared_ptr<map::MapPoint>> moved;
  for (const auto& kf : group.keyframes) {
    const Sim3 to_corrected = group.corrected[kf->id()].inverse() * group.uncorrected[kf->id()];
    for (const auto& point : kf->mapPoints()) {
      if (!point || point->isBad() || group.corrected_by.contains(point->id())) continue;
      point->setPosition(to_corrected * point->position());
      group.corrected_by[point->id()] = kf->id();
      moved.push_back(point);
    }
    kf->setPose(group.corrected[kf->id()].toSE3());
  }
  for (const auto& point : moved) point->updateNormalAndDepth();
}

using NeighboursById = std::map<map::Id, std::set<map::Id>>;

NeighboursById neighboursOf(const std::vector<KeyFramePtr>& keyframes) {
  NeighboursById neighbours;
  for (const auto& kf : keyframes) {
    for (const auto& n : kf->covisibles()) neighbours[kf->id()].insert(n->id());
  }
  return neighbours;
}

// The current keyframe's matched features take the loop points.
void takeLoopPoints(map::Map& map, const LoopMatch& match) {
  const KeyFramePtr& current = match.current;
  for (std::size_t i = 0; i < match.points.size(); ++i) {
    const auto& loop_point = match.points[i];
    if (!loop_point || loop_point->isBad()) continue;
    const auto existing = current->mapPoint(i);
    if (existing && !existing->isBad()) {
      if (existing != loop_point) map.replaceMapPoint(existing, loop_point);
    } else if (loop_point->featureIndexIn(current->id()) < 0) {
      current->setMapPoint(i, loop_point);
      loop_point->addObservation(current, static_cast<int>(i));
      loop_point->computeDistinctiveDescriptor();
    }
  }
}

using LoopLinks = std::set<std::pair<map::Id, map::Id>>;

// New links the fusion created between the group and the loop side.
LoopLinks newLoopLinks(const std::vector<KeyFramePtr>& group, NeighboursById& neighbours_before,
                       const LoopMatch& match, int strong_covisibility) {
  LoopLinks loop_links;
  std::unordered_set<map::Id> group_ids;
  for (const auto& kf : group) group_ids.insert(kf->id());
  for (const auto& kf : group) {
    kf->updateConnections();
    for (const auto& n : kf->covisibles()) {
      if (group_ids.contains(n->id()) || neighbours_before[kf->id()].contains(n->id())) continue;
      const bool the_loop = kf == match.current && n == match.loop;
      if (!the_loop && kf->weight(n->id()) < strong_covisibility) continue;
      loop_links.insert({kf->id(), n->id()});
    }
  }
  loop_links.insert({match.current->id(), match.loop->id()});
  return loop_links;
}

struct EssentialGraph {
  SimsById initial;      // per vertex: the corrected pose, or the pose as it is
  SimsById before_loop;  // per vertex: the pose before the loop correction
  std::vector<map::Id> vertex_ids;
  std::vector<std::tuple<map::Id, map::Id, Sim3>> edges;  // i, j, S_i_j
};

// The vertices: every good keyframe of the current map.
EssentialGraph essentialGraphVertices(const std::vector<KeyFramePtr>& keyframes, map::MapId map_id,
                                      const LoopGroup& group) {
  EssentialGraph graph;
  for (const auto& kf : keyframes) {
    if (kf->isBad() || kf->mapId() != map_id) continue;
    const auto corrected = group.corrected.find(kf->id());
    const Sim3 S =
        corrected != group.corrected.end() ? corrected->second : Sim3::fromSE3(kf->T_c_w());
    graph.initial[kf->id()] = S;
    const auto uncorrected = group.uncorrected.find(kf->id());
    graph.before_loop[kf->id()] = uncorrected != group.uncorrected.end() ? uncorrected->second : S;
    graph.vertex_ids.push_back(kf->id());
  }
  return graph;
}

// The edges, each pair once: the loop links, then the spanning tree, earlier loop edges and
// strong covisibility of every keyframe.
void addEssentialGraphEdges(EssentialGraph& graph, const std::vector<KeyFramePtr>& keyframes,
                            const LoopLinks& loop_links, int strong_covisibility) {
  std::set<std::pair<map::Id, map::Id>> added;
  const auto add_edge = [&](map::Id i, map::Id j, const SimsById& poses) {
    if (i == j || !poses.contains(i) || !poses.contains(j)) return;
    if (!added.insert({std::min(i, j), std::max(i, j)}).second) return;
    graph.edges.emplace_back(i, j, poses.at(i) * poses.at(j).inverse());
  };
  for (const auto& [i, j] : loop_links) add_edge(i, j, graph.initial);
  for (const auto& kf : keyframes) {
    if (kf->isBad()) continue;
    if (const auto parent = kf->parent()) add_edge(kf->id(), parent->id(), graph.before_loop);
    for (const auto& other : kf->loopEdges()) add_edge(kf->id(), other->id(), graph.before_loop);
    for (const auto& n : kf->covisiblesWithMinWeight(strong_covisibility)) {
      add_edge(kf->id(), n->id(), graph.before_loop);
    }
  }
}

SimsById optimiseSE3Graph(const EssentialGraph& graph, map::Id fixed_id,
                          const optimize::PoseGraphOptions& options) {
  optimize::PoseGraphProblem problem;
  for (const map::Id id : graph.vertex_ids) {
    problem.vertices.push_back({id, graph.initial.at(id).toSE3(), id == fixed_id});
  }
  for (const auto& [i, j, S_i_j] : graph.edges) {
    optimize::PoseGraphEdge edge;
    edge.fromId = i;
    edge.toId = j;
    edge.T_i_j = S_i_j.toSE3();
    problem.edges.push_back(edge);
  }
  const auto result = optimize::optimizePoseGraph(problem, options);
  SimsById optimised;
  for (std::size_t v = 0; v < graph.vertex_ids.size(); ++v) {
    optimised[graph.vertex_ids[v]] = Sim3::fromSE3(result.T_c_w[v]);
  }
  return optimised;
}

SimsById optimiseSim3Graph(const EssentialGraph& graph, map::Id fixed_id,
                           const optimize::PoseGraphOptions& options) {
  optimize::Sim3PoseGraphProblem problem;
  for (const map::Id id : graph.vertex_ids) {
    problem.vertices.push_back({id, graph.initial.at(id), id == fixed_id});
  }
  for (const auto& [i, j, S_i_j] : graph.edges) {
    optimize::Sim3PoseGraphEdge edge;
    edge.fromId = i;
    edge.toId = j;
    edge.S_i_j = S_i_j;
    problem.edges.push_back(edge);
  }
  const auto result = optimize::optimizeSim3PoseGraph(problem, options);
  SimsById optimised;
  for (std::size_t v = 0; v < graph.vertex_ids.size(); ++v) {
    optimised[graph.vertex_ids[v]] = result.S_c_w[v];
  }
  return optimised;
}

// Each point moves with its anchor keyframe: X' = S_optimised^-1 * S_initial * X.
void movePointsWithGraph(const std::vector<std::shared_ptr<map::MapPoint>>& points,
                         const SimsById& initial, const SimsById& optimised,
                         const std::unordered_map<map::Id, map::Id>& corrected_by) {
  for (const auto& point : points) {
    if (point->isBad()) continue;
    map::Id anchor = point->referenceKeyFrameId();
    if (const auto by = corrected_by.find(point->id()); by != corrected_by.end()) {
      anchor = by->second;
    }
    if (!optimised.contains(anchor)) {
      const auto observations = point->observations();
      if (observations.empty() || !optimised.contains(observations.front().first->id())) continue;
      anchor = observations.front().first->id();
    }
    const Sim3 shift = optimised.at(anchor).inverse() * initial.at(anchor);
    point->setPosition(shift * point->position());
    point->updateNormalAndDepth();
  }
}

// The global adjustment's snapshot of the atlas: every good keyframe of a map (each map's
// origin fixed) and every point they observe.
struct GlobalBASnapshot {
  optimize::LocalBAProblem problem;
  PosesById T_c_w;                                     // per keyframe of the problem
  std::vector<std::shared_ptr<map::MapPoint>> points;  // per point of the problem
};

GlobalBASnapshot globalBASnapshotOf(const map::Map& map,
                                    const std::vector<KeyFramePtr>& keyframes) {
  GlobalBASnapshot out;
  optimize::LocalBAProblem& problem = out.problem;
  PosesById& snapshot = out.T_c_w;
  const auto& k = keyframes.front()->intrinsics();
  problem.camera = {k.fx, k.fy, k.cx, k.cy, k.bf};
  for (const auto& kf : keyframes) {
    if (kf->isBad() || kf->mapId() == map::kDiscardedMap) continue;
    snapshot[kf->id()] = kf->T_c_w();
    problem.keyFrames.push_back({kf->id(), snapshot[kf->id()], map.isMapOrigin(*kf)});
  }
  for (const auto& point : map.mapPoints()) {
    if (point->isBad()) continue;
    bool observed = false;
    for (const auto& [kf, index] : point->observations()) {
      if (!snapshot.contains(kf->id())) continue;
      problem.observations.push_back(
          mapping::baObservation(*kf, static_cast<std::size_t>(index), point->id()));
      observed = true;
    }
    if (!observed) continue;
    problem.points.push_back({point->id(), point->position()});
    out.points.push_back(point);
  }
  return out;
}

// World correction of each adjusted keyframe: X' = T_w_c(new) * T_c_w(snapshot) * X.
PosesById keyFrameCorrections(const GlobalBASnapshot& snapshot,
                              const optimize::LocalBAResult& result) {
  PosesById correction;
  for (std::size_t v = 0; v < snapshot.problem.keyFrames.size(); ++v) {
    const map::Id id = snapshot.problem.keyFrames[v].id;
    correction[id] = result.T_c_w[v].inverse() * snapshot.T_c_w.at(id);
  }
  return correction;
}

// Every keyframe moves by its correction; one added during the adjustment follows its nearest
// adjusted ancestor (at most max_steps up the spanning tree) and takes its correction.
void moveKeyFrames(const map::Map& map, PosesById& correction, std::size_t max_steps) {
  for (const auto& kf : map.keyFrames()) {
    if (kf->isBad()) continue;
    if (const auto own = correction.find(kf->id()); own != correction.end()) {
      kf->setPose((own->second * kf->T_w_c()).inverse());
      continue;
    }
    // Added during the adjustment: follow the nearest adjusted ancestor.
    std::size_t steps = 0;  // bounded even if the spanning tree were broken
    for (auto ancestor = kf->parent(); ancestor && steps < max_steps;
         ancestor = ancestor->parent(), ++steps) {
      if (const auto found = correction.find(ancestor->id()); found != correction.end()) {
        kf->setPose((found->second * kf->T_w_c()).inverse());
        correction[kf->id()] = found->second;
        break;
      }
    }
  }
}

// The adjusted points take their positions, every other one moves with its reference keyframe.
void movePoints(const map::Map& map, const std::vector<std::shared_ptr<map::MapPoint>>& adjusted,
                const std::vector<Eigen::Vector3d>& X_w, const PosesById& correction) {
  std::unordered_set<map::Id> adjusted_ids;
  for (std::size_t p = 0; p < adjusted.size(); ++p) {
    adjusted[p]->setPosition(X_w[p]);
    adjusted_ids.insert(adjusted[p]->id());
  }
  for (const auto& point : map.mapPoints()) {
    if (point->isBad()) continue;
    if (!adjusted_ids.contains(point->id())) {
      const auto found = correction.find(point->referenceKeyFrameId());
      if (found == correction.end()) continue;
      point->setPosition(found->second * point->position());
    }
    point->updateNormalAndDepth();
  }
}

}  // namespace

LoopCloser::LoopCloser(std::shared_ptr<map::Map> map, const Vocabulary& vocabulary,
                       const KeyFrameDatabase& database, const LoopCloserParams& params,
                       PauseMapping pause_mapping)
    : map_(std::move(map)),
      vocabulary_(vocabulary),
      database_(database),
      params_(params),
      pause_mapping_(std::move(pause_mapping)),
      detector_(database_, *map_, params.detector),
      global_ba_([this](GlobalBARun&) { runGlobalBundleAdjustment(); },
                 {.threaded = params.threaded, .capacity = 1}),
      queue_([this](const auto& keyframe) { process(keyframe); },
             {.threaded = params.threaded, .capacity = params.queue_capacity}) {}

LoopCloser::~LoopCloser() {
  shutdown();
}

void LoopCloser::shutdown() {
  stopping_ = true;
  abort_global_ba_ = true;
  queue_.shutdown();
  global_ba_.shutdown();  // a run still queued returns at once: aborted
}

void LoopCloser::stopGlobalBundleAdjustment() {
  if (global_ba_.idle()) return;
  abort_global_ba_ = true;
  global_ba_.waitUntilIdle();
}

void LoopCloser::startGlobalBundleAdjustment() {
  stopGlobalBundleAdjustment();  // never two at once (correctLoop has normally stopped it)
  {
    std::lock_guard lock(global_ba_mutex_);
    if (stopping_ && params_.threaded) return;
    abort_global_ba_ = false;
    ++global_ba_stats_.started;
  }
  global_ba_.push(GlobalBARun{});
  if (!params_.threaded) global_ba_.processPending();
}

void LoopCloser::runGlobalBundleAdjustment() {
  const bool done = globalBundleAdjustment();
  std::lock_guard lock(global_ba_mutex_);
  if (done) {
    ++global_ba_stats_.completed;
  } else if (abort_global_ba_) {
    ++global_ba_stats_.aborted;
  }
}

GlobalBAStats LoopCloser::globalBundleAdjustmentStats() const {
  std::lock_guard lock(global_ba_mutex_);
  return global_ba_stats_;
}

void LoopCloser::insertKeyFrame(std::shared_ptr<map::KeyFrame> keyframe) {
  queue_.push(std::move(keyframe));
}

void LoopCloser::processPending() {
  queue_.processPending();
}

void LoopCloser::waitUntilIdle() {
  queue_.waitUntilIdle();  // a keyframe being handled may have started a global BA
  global_ba_.waitUntilIdle();
}

std::vector<ClosedLoop> LoopCloser::closedLoops() const {
  std::lock_guard lock(closed_mutex_);
  return closed_;
}

std::optional<KeyFrameBow> LoopCloser::bowOf(const map::KeyFrame& keyframe) const {
  if (auto entry = database_.entry(keyframe.id())) return entry;
  if (vocabulary_.empty()) return std::nullopt;
  KeyFrameBow entry;
  vocabulary_.transform(keyframe.features().descriptors, params_.direct_index_levels_up, entry.bow,
                        entry.features);
  return entry;
}

void LoopCloser::process(const std::shared_ptr<map::KeyFrame>& keyframe) {
  if (!keyframe || keyframe->isBad()) return;
  // No loop right after the start or the last loop (ORB-SLAM: 10 keyframes).
  const auto since =
      static_cast<long long>(keyframe->id()) - static_cast<long long>(last_loop_keyframe_);
  if (since < params_.min_keyframes_between_loops) return;
  const auto detection = detector_.detect(keyframe);
  if (detection.consistent.empty()) return;
  const auto match = computeLoop(keyframe, detection.consistent);
  if (!match) {
    rejected_ += static_cast<int>(detection.consistent.size());
    return;
  }
  const bool across_maps = match->loop->mapId() != keyframe->mapId();
  const ClosedLoop closed = across_maps ? mergeMaps(*match) : correctLoop(*match);
  if (closed.merged_map) {
    spdlog::info(
        "maps merged: map {} into map {} (keyframe {} -> {}, {} inliers), moved {:.1f} mm / "
        "{:.2f} deg, scale {:.3f}",
        *closed.merged_map, closed.into_map, closed.current, closed.loop, closed.inliers,
        1000.0 * closed.correction_m, closed.correction_deg, closed.correction_scale);
  } else {
    spdlog::info(
        "loop closed: keyframe {} -> {}, {} inliers, moved {:.1f} mm / {:.2f} deg, scale {:.3f}",
        closed.current, closed.loop, closed.inliers, 1000.0 * closed.correction_m,
        closed.correction_deg, closed.correction_scale);
  }
  {
    std::lock_guard lock(closed_mutex_);
    closed_.push_back(closed);
  }
  last_loop_keyframe_ = keyframe->id();
  detector_.reset();
  if (params_.global_bundle_adjustment) startGlobalBundleAdjustment();
}

bool LoopCloser::globalBundleAdjustment() {
  // Snapshot of the whole atlas (no lock across objects: each accessor copies); each map's
  // origin fixes its gauge.
  const auto keyframes = map_->keyFrames();
  if (keyframes.size() < 2) return false;
  GlobalBASnapshot snapshot = globalBASnapshotOf(*map_, keyframes);
  const optimize::LocalBAProblem& problem = snapshot.problem;
  if (problem.observations.empty() || abort_global_ba_) return false;
  optimize::LocalBAOptions options;
  options.maxIterations = params_.global_ba_iterations;
  options.refinementIterations = params_.global_ba_iterations;  // without the outliers
  options.abort = &abort_global_ba_;
  if (params_.on_global_ba_start) params_.on_global_ba_start();
  const auto result = optimize::optimizeLocalBundle(problem, options);
  spdlog::info(
      "global BA after the loop: {} keyframes, {} points, {} iterations, cost {:.4g} -> {:.4g}{}",
      problem.keyFrames.size(), problem.points.size(), result.iterations, result.initialCost,
      result.finalCost, result.aborted ? " (aborted)" : "");
  if (result.aborted) return false;

  std::unique_lock<std::mutex> mapping_paused;
  if (pause_mapping_) mapping_paused = pause_mapping_();
  std::lock_guard update(map_->updateMutex());
  PosesById correction = keyFrameCorrections(snapshot, result);
  moveKeyFrames(*map_, correction, keyframes.size() + 1);
  movePoints(*map_, snapshot.points, result.X_w, correction);
  return true;
}

std::optional<LoopMatch> LoopCloser::computeLoop(
    const std::shared_ptr<map::KeyFrame>& current,
    const std::vector<std::shared_ptr<map::KeyFrame>>& candidates) const {
  const auto current_bow = bowOf(*current);
  if (!current_bow || !current->features().grid) return std::nullopt;
  const MatchingFrame frame = matchingFrameOf(*current);
  for (const auto& candidate : candidates) {
    if (!candidate || candidate->isBad() || candidate == current) continue;
    const auto candidate_bow = bowOf(*candidate);
    if (!candidate_bow) continue;
    if (!params_.fix_scale) {
      if (auto match =
              computeSim3Loop(current, current_bow->features, candidate, candidate_bow->features))
        return match;
      continue;
    }
    PointSlots slots =
        searchByBow(*candidate, candidate_bow->features, current->features(), current_bow->features,
                    params_.bow_ratio, params_.bow_max_distance);
    if (countMatches(slots) < params_.min_bow_matches) continue;
    SE3 T_c_w;
    if (!solvePnpRansac(frame, params_.pnp, slots, T_c_w)) continue;
    if (refinePose(frame, slots, T_c_w) < params_.pnp.min_inliers) continue;
    // Guided matching against the whole loop neighbourhood with the loop pose, refine again.
    searchByProjection(frame, groupPoints(candidate), {}, T_c_w, params_.projection_radius_px,
                       params_.bow_max_distance, slots);
    const int inliers = refinePose(frame, slots, T_c_w);
    if (inliers < params_.min_inliers) continue;
    return LoopMatch{current, candidate, T_c_w, Sim3::fromSE3(T_c_w), std::move(slots), inliers};
  }
  return std::nullopt;
}

std::optional<LoopMatch> LoopCloser::computeSim3Loop(const KeyFramePtr& current,
                                                     const FeatureVector& current_nodes,
                                                     const KeyFramePtr& candidate,
                                                     const FeatureVector& candidate_nodes) const {
  const PointSlots bow = searchByBow(*candidate, candidate_nodes, current->features(),
                                     current_nodes, params_.bow_ratio, params_.bow_max_distance);
  if (countMatches(bow) < params_.min_bow_matches) return std::nullopt;
  const CameraIntrinsics camera = current->intrinsics();
  const Sim3Pairs bow_pairs = sim3PairsOf(*current, *candidate, bow);
  const auto ransac = estimateSim3Ransac(bow_pairs.pairs, camera, params_.sim3);
  if (!ransac) return std::nullopt;

  // Guided matching (ORB-SLAM's SearchBySim3): the loop keyframe's points projected with the
  // hypothesis, starting from the RANSAC inliers; then the Ceres refinement of S_12.
  const MatchingFrame frame = matchingFrameOf(*current);
  const Sim3 S_2w = Sim3::fromSE3(candidate->T_c_w());
  PointSlots slots(bow.size());
  for (std::size_t p = 0; p < bow_pairs.pairs.size(); ++p) {
    if (ransac->inlier[p]) slots[bow_pairs.feature[p]] = bow[bow_pairs.feature[p]];
  }
  std::vector<std::shared_ptr<map::MapPoint>> loop_points;
  for (const auto& point : candidate->mapPoints()) {
    if (point && !point->isBad()) loop_points.push_back(point);
  }
  searchByProjection(frame, loop_points, {}, (ransac->S_12 * S_2w).toSE3(),
                     params_.sim3_projection_radius_px, params_.bow_max_distance, slots);
  const Sim3Pairs pairs = sim3PairsOf(*current, *candidate, slots);
  const auto refined = optimize::refineSim3(pairs.pairs, ransac->S_12, camera);
  if (refined.inliers < params_.sim3.min_inliers) return std::nullopt;

  // Every point of the loop neighbourhood projected with the refined Sim3 (ORB-SLAM's final
  // SearchByProjection); enough matches accept the loop.
  const Sim3 S_cw = refined.S_12 * S_2w;
  const SE3 T_c_w = S_cw.toSE3();
  PointSlots matched(bow.size());
  for (std::size_t p = 0; p < pairs.pairs.size(); ++p) {
    if (refined.inlier[p]) matched[pairs.feature[p]] = slots[pairs.feature[p]];
  }
  searchByProjection(frame, groupPoints(candidate), {}, T_c_w, params_.projection_radius_px,
                     params_.bow_max_distance, matched);
  const int inliers = countMatches(matched);
  if (inliers < params_.min_inliers) return std::nullopt;
  return LoopMatch{current, candidate, T_c_w, S_cw, std::move(matched), inliers};
}

ClosedLoop LoopCloser::mergeMaps(const LoopMatch& match) {
  stopGlobalBundleAdjustment();
  const MapMerge merge = mergeFor(match);
  {
    std::unique_lock<std::mutex> mapping_paused;
    if (pause_mapping_) mapping_paused = pause_mapping_();
    std::lock_guard update(map_->updateMutex());
    moveMapInto(*map_, merge);
  }
  // Both keyframes are in one world now: join them as a loop with no further correction.
  LoopMatch joined = match;
  joined.T_c_w = match.current->T_c_w();
  joined.S_c_w = Sim3::fromSE3(joined.T_c_w);
  ClosedLoop closed = correctLoop(joined);
  closed.merged_map = merge.moved;
  closed.into_map = merge.into;
  const SE3 move = merge.S_wmoved_winto.toSE3();
  closed.correction_m = move.translation().norm();
  closed.correction_deg = Eigen::AngleAxisd(move.linear()).angle() * 180.0 / M_PI;
  closed.correction_scale = merge.S_wmoved_winto.scale;
  return closed;
}

ClosedLoop LoopCloser::correctLoop(const LoopMatch& match) {
  stopGlobalBundleAdjustment();  // a new loop: the running adjustment is out of date
  std::unique_lock<std::mutex> mapping_paused;
  if (pause_mapping_) mapping_paused = pause_mapping_();
  std::lock_guard update(map_->updateMutex());
  const KeyFramePtr& current = match.current;

  // 1. The current keyframe and its neighbours follow the loop transform (ORB-SLAM's
  //    CorrectedSim3: S_i_w' = T_i_w * T_w_cur * S_cur_w'; the scale is 1 for SE3 loops).
  current->updateConnections();
  const SE3 T_w_cur = current->T_w_c();
  LoopGroup group = loopGroupOf(current, T_w_cur, match.S_c_w);
  const ClosedLoop closed = closedLoopOf(match, T_w_cur);
  moveGroup(group);

  // 2. Loop fusion: the current keyframe's matched features take the loop points, then the
  //    loop neighbourhood's points are fused into every keyframe of the group.
  NeighboursById neighbours_before = neighboursOf(group.keyframes);
  takeLoopPoints(*map_, match);
  const auto loop_points = groupPoints(match.loop);
  for (const auto& kf : group.keyframes) {
    mapping::fusePointsInto(*map_, kf, loop_points, params_.fusion_radius_px);
  }
  const auto loop_links =
      newLoopLinks(group.keyframes, neighbours_before, match, params_.strong_covisibility);

  // 3. Essential graph (ORB-SLAM's OptimizeEssentialGraph), loop keyframe fixed. Loop links
  //    are measured with the corrected poses, every other edge with the poses before the loop.
  const auto keyframes = map_->keyFrames();
  EssentialGraph graph = essentialGraphVertices(keyframes, current->mapId(), group);
  addEssentialGraphEdges(graph, keyframes, loop_links, params_.strong_covisibility);
  optimize::PoseGraphOptions options;
  options.maxIterations = params_.pose_graph_iterations;
  SimsById optimised = params_.fix_scale ? optimiseSE3Graph(graph, match.loop->id(), options)
                                         : optimiseSim3Graph(graph, match.loop->id(), options);

  // 4. Keyframes take the optimised poses; points move with the keyframe that corrected
  //    them, or their reference keyframe (the first observer if that one is gone):
  //    X' = S_optimised^-1 * S_initial * X (a Sim3 also rescales the point's depth).
  for (const auto& kf : keyframes) {
    if (optimised.contains(kf->id())) kf->setPose(optimised[kf->id()].toSE3());
  }
  movePointsWithGraph(map_->mapPoints(), graph.initial, optimised, group.corrected_by);

  current->addLoopEdge(match.loop);
  match.loop->addLoopEdge(current);
  return closed;
}

}  // namespace lumaslam::loop
