#pragma once
// `lumaslam vocab eval`: place-recognition recall and precision of a vocabulary on a dataset
// with ground-truth poses. Every `keyframe_every`-th frame goes into a keyframe database
// (BoW + direct index, as the Pipeline adds keyframes); every other frame queries it with the
// relocalization query (ORB-SLAM's DetectRelocalizationCandidates, no covisibility grouping).
// A keyframe is a correct answer when its ground-truth pose is within `max_distance` metres
// and `max_angle_deg` degrees of the query's; keyframes within `exclude_window` frames of the
// query are hidden from it (0: none; > 0 asks for revisits, as loop detection does).
#include <filesystem>
#include <string>

namespace lumaslam::cli {

struct VocabEvalOptions {
  std::filesystem::path vocabulary;
  std::string dataset;
  int keyframe_every = 10;
  double max_distance = 0.3;
  double max_angle_deg = 20.0;
  int exclude_window = 0;
  int features = 1000;
  int top = 5;  // also report whether a correct keyframe is among the first `top`
};

// Prints the counts, recall@1, precision@1, recall@top and the load / transform times.
int runVocabEval(const VocabEvalOptions& options);

}  // namespace lumaslam::cli
