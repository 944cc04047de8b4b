#include "vocab_eval.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include <spdlog/spdlog.h>

#include "lumaslam/core/error.h"
#include "lumaslam/core/gray_image.h"
#include "lumaslam/eval/association.h"
#include "lumaslam/feature/orb_extractor.h"
#include "lumaslam/io/dataset_reader.h"
#include "lumaslam/loop/keyframe_database.h"
#include "lumaslam/loop/place_recognition.h"
#include "lumaslam/loop/vocabulary_io.h"

namespace lumaslam::cli {
namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

struct Sample {
  std::size_t frame = 0;  // dataset frame index
  SE3 T_w_c;
  cv::Mat descriptors;
};

// Frames with a ground-truth pose (nearest stamp within 20 ms) and their ORB descriptors.
std::vector<Sample> readSamples(const VocabEvalOptions& options) {
  auto reader = io::openDataset(options.dataset);
  const Trajectory ground_truth = reader->groundTruth();
  if (ground_truth.empty()) fail("{}: the dataset has no ground-truth poses", options.dataset);
  feature::OrbSettings settings;
  settings.nFeatures = options.features;
  const feature::OrbExtractor extractor(settings);
  std::vector<Sample> frames;
  Trajectory stamps;
  while (auto frame = reader->next()) {
    frames.push_back(
        {frame->index, SE3::Identity(), extractor.extract(toGray(frame->image)).descriptors});
    stamps.push_back({frame->timestamp, SE3::Identity()});
  }
  if (frames.empty()) fail("{}: the dataset delivered no frames", options.dataset);
  const auto pairs = eval::associate(stamps, ground_truth, 0.02);
  std::vector<Sample> samples;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    Sample sample = std::move(frames[pairs.estimate_indices[i]]);
    sample.T_w_c = pairs.ground_truth[i].T_w_c;
    samples.push_back(std::move(sample));
  }
  std::sort(samples.begin(), samples.end(),
            [](const Sample& a, const Sample& b) { return a.frame < b.frame; });
  return samples;
}

bool samePlace(const SE3& a, const SE3& b, const VocabEvalOptions& options) {
  const SE3 relative = a.inverse() * b;
  const double angle = Eigen::AngleAxisd(relative.rotation()).angle() * 180.0 / M_PI;
  return relative.translation().norm() <= options.max_distance && angle <= options.max_angle_deg;
}

double ratio(std::size_t part, std::size_t whole) {
  return whole == 0 ? 0.0 : static_cast<double>(part) / static_cast<double>(whole);
}

struct Answer {
  double score = 0.0;  // L1 score of the top candidate
  bool correct = false;
};

struct Curve {
  double recall_at_precision = 0.0;  // the most recall with precision >= kPrecision
  double average_precision = 0.0;
};
constexpr double kPrecision = 0.9;

// Accepting only top answers scoring at least s, for every s: scores differ between
// vocabularies (a deeper tree scores lower), so a fixed threshold would not compare them.
Curve precisionRecall(std::vector<Answer> answers, std::size_t answerable) {
  std::sort(answers.begin(), answers.end(),
            [](const Answer& a, const Answer& b) { return a.score > b.score; });
  Curve curve;
  std::size_t tp = 0;
  for (std::size_t i = 0; i < answers.size(); ++i) {
    if (!answers[i].correct) continue;
    ++tp;
    const double precision = ratio(tp, i + 1);
    curve.average_precision +=
        precision / static_cast<double>(std::max<std::size_t>(answerable, 1));
    if (precision >= kPrecision) curve.recall_at_precision = ratio(tp, answerable);
  }
  return curve;
}

}  // namespace

int runVocabEval(const VocabEvalOptions& options) {
  if (options.keyframe_every < 2) fail("--keyframe-every must be >= 2");
  if (options.top < 1) fail("--top must be >= 1");
  const auto load_start = Clock::now();
  const loop::Vocabulary vocabulary = loop::loadAnyVocabulary(options.vocabulary);
  const double load_seconds = secondsSince(load_start);
  const std::vector<Sample> samples = readSamples(options);

  const auto transform_start = Clock::now();
  std::vector<loop::KeyFrameBow> bows(samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) {
    vocabulary.transform(samples[i].descriptors, loop::PlaceRecognition::kDirectIndexLevelsUp,
                         bows[i].bow, bows[i].features);
  }
  const double transform_ms = 1000.0 * secondsSince(transform_start) / samples.size();

  loop::KeyFrameDatabase database;
  std::vector<std::size_t> keyframes;
  for (std::size_t i = 0; i < samples.size(); i += options.keyframe_every) {
    database.add(i, bows[i]);
    keyframes.push_back(i);
  }
  std::size_t queries = 0, answerable = 0, answered = 0, correct = 0, correct_in_top = 0;
  std::vector<Answer> answers;
  for (std::size_t q = 0; q < samples.size(); ++q) {
    if (q % options.keyframe_every == 0) continue;
    ++queries;
    loop::PlaceQuery query;
    bool has_answer = false;
    for (const std::size_t k : keyframes) {
      const auto gap = std::max(samples[k].frame, samples[q].frame) -
                       std::min(samples[k].frame, samples[q].frame);
      if (gap <= static_cast<std::size_t>(options.exclude_window)) {
        query.excluded.insert(k);
      } else {
        has_answer |= samePlace(samples[k].T_w_c, samples[q].T_w_c, options);
      }
    }
    answerable += has_answer;
    const auto candidates = database.query(bows[q].bow, query);
    if (candidates.empty()) continue;
    ++answered;
    const bool right = samePlace(samples[candidates[0].id].T_w_c, samples[q].T_w_c, options);
    correct += right;
    answers.push_back({candidates[0].score, right});
    for (std::size_t c = 0; c < std::min<std::size_t>(candidates.size(), options.top); ++c) {
      if (samePlace(samples[candidates[c].id].T_w_c, samples[q].T_w_c, options)) {
        ++correct_in_top;
        break;
      }
    }
  }
  std::printf("vocabulary %s\nwords %zu\nload seconds %.3f\ntransform ms per frame %.2f\n",
              options.vocabulary.string().c_str(), vocabulary.wordCount(), load_seconds,
              transform_ms);
  std::printf("frames %zu\nkeyframes %zu\nqueries %zu\nanswerable %zu\nanswered %zu\n",
              samples.size(), keyframes.size(), queries, answerable, answered);
  std::printf("correct@1 %zu\nrecall@1 %.3f\nprecision@1 %.3f\nrecall@%d %.3f\n", correct,
              ratio(correct, answerable), ratio(correct, answered), options.top,
              ratio(correct_in_top, answerable));
  const Curve curve = precisionRecall(std::move(answers), answerable);
  std::printf("recall at precision %.1f %.3f\naverage precision %.3f\n", kPrecision,
              curve.recall_at_precision, curve.average_precision);
  return 0;
}

}  // namespace lumaslam::cli
