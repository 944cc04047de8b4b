// Runs the built `lumaslam vocab eval` (docs/place_recognition.md, "CLI" and "Default
// vocabulary") with the shipped default vocabulary, trained on real images only, on a synthetic
// lap it has never seen (`lumaslam synth --preset loop-rgbd`): the counts and ratios it prints
// agree with each other, each flag moves them in the documented direction, and bad input
// (missing vocabulary, missing dataset, no ground truth, bad values) exits 1 naming the cause.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>

#include "lumaslam/loop/vocabulary_choice.h"
#include "lumaslam/loop/vocabulary_io.h"
#include "test_cli.h"
#include "test_paths.h"

namespace {

namespace fs = std::filesystem;
using lumaslam::test::runCli;
using lumaslam::test::TempDir;

// One lap in kFrames frames: the camera turns 5 deg (3.75-6.25 deg) and moves ~75 mm per frame.
constexpr int kFrames = 72;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

fs::path defaultVocabulary() {
  return lumaslam::test::sourceDir() / "data/vocabulary" / lumaslam::loop::defaultVocabularyName();
}

// The "key value" lines of `vocab eval` (the value after the last space), e.g. "recall@1" ->
// "0.957", "recall at precision 0.9" -> "0.652". Log lines end up as keys nobody asks for.
struct Report {
  std::string output;
  std::map<std::string, std::string> values;

  bool has(const std::string& key) const { return values.count(key) > 0; }
  std::size_t count(const std::string& key) const {
    EXPECT_TRUE(has(key)) << "no '" << key << "' line in:\n" << output;
    return has(key) ? std::stoul(values.at(key)) : 0;
  }
  double number(const std::string& key) const {
    EXPECT_TRUE(has(key)) << "no '" << key << "' line in:\n" << output;
    return has(key) ? std::stod(values.at(key)) : -1.0;
  }
  // How many lines start with "key ".
  std::size_t lines(const std::string& key) const {
    std::size_t n = 0;
    std::istringstream in(output);
    for (std::string line; std::getline(in, line);) n += line.rfind(key + " ", 0) == 0;
    return n;
  }
};

double ratio(std::size_t part, std::size_t whole) {
  return whole == 0 ? 0.0 : static_cast<double>(part) / static_cast<double>(whole);
}

class CliVocabEval : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto synth = runCli("synth " + sequence().string() + " --preset loop-rgbd --frames " +
                              std::to_string(kFrames) + " --seed 1");
    ASSERT_EQ(synth.exit_code, 0) << synth.output;
  }

  fs::path sequence() const { return dir_.path() / "lap"; }

  // `vocab eval` of the default vocabulary on the lap with `flags`; exit 0 expected.
  Report eval(const std::string& flags = "") const {
    const auto result = runCli("vocab eval " + defaultVocabulary().string() +
                               " --dataset tum:" + sequence().string() + " " + flags);
    EXPECT_EQ(result.exit_code, 0) << flags << "\n" << result.output;
    Report report{result.output, {}};
    std::istringstream in(result.output);
    for (std::string line; std::getline(in, line);) {
      const auto space = line.rfind(' ');
      if (space != std::string::npos) report.values[line.substr(0, space)] = line.substr(space + 1);
    }
    return report;
  }

  // The printed ratios are the printed counts divided (3 decimals), recall@top >= recall@1.
  static void expectConsistent(const Report& r, int top) {
    const std::size_t correct = r.count("correct@1");
    const std::size_t answerable = r.count("answerable");
    const std::size_t answered = r.count("answered");
    EXPECT_EQ(r.count("frames"), r.count("keyframes") + r.count("queries")) << r.output;
    EXPECT_LE(answerable, r.count("queries")) << r.output;
    EXPECT_LE(answered, r.count("queries")) << r.output;
    EXPECT_LE(correct, std::min(answerable, answered)) << r.output;
    EXPECT_NEAR(r.number("recall@1"), ratio(correct, answerable), 0.0006) << r.output;
    EXPECT_NEAR(r.number("precision@1"), ratio(correct, answered), 0.0006) << r.output;
    const double recall_top = r.number("recall@" + std::to_string(top));
    EXPECT_GE(recall_top, r.number("recall@1")) << r.output;
    EXPECT_LE(recall_top, 1.0) << r.output;
    EXPECT_LE(r.number("recall at precision 0.9"), r.number("recall@1") + 0.0006) << r.output;
    EXPECT_GE(r.number("average precision"), 0.0) << r.output;
    EXPECT_LE(r.number("average precision"), 1.0) << r.output;
  }

  TempDir dir_{"cli_vocab_eval"};
};

TEST_F(CliVocabEval, ReportsRecallAndPrecisionAndFlagsMoveThemAsDocumented) {
  // Defaults: every 10th frame a keyframe, 0.3 m / 20 deg, no exclusion, 1000 features, top 5.
  const Report base = eval();
  EXPECT_TRUE(contains(base.output, "vocabulary " + defaultVocabulary().string() + "\n"))
      << base.output;
  EXPECT_EQ(base.count("words"),
            lumaslam::loop::loadAnyVocabulary(defaultVocabulary()).wordCount());
  EXPECT_TRUE(base.has("load seconds") && base.has("transform ms per frame")) << base.output;
  EXPECT_EQ(base.count("frames"), static_cast<std::size_t>(kFrames));  // all have a GT pose
  EXPECT_EQ(base.count("keyframes"), static_cast<std::size_t>((kFrames + 9) / 10));
  EXPECT_EQ(base.count("queries"), static_cast<std::size_t>(kFrames - (kFrames + 9) / 10));
  expectConsistent(base, 5);
  // No score threshold: every query gets an answer.
  EXPECT_EQ(base.count("answered"), base.count("queries")) << base.output;
  // Keyframes are ~50 deg and ~0.75 m apart: the queries next to one are answerable, those
  // half-way between two (5 frames, ~25 deg, ~0.37 m from both) are not.
  EXPECT_GT(base.count("answerable"), 0U) << base.output;
  EXPECT_LT(base.count("answerable"), base.count("queries")) << base.output;
  // With W = 0 the neighbouring keyframes answer almost every query (the docs: ~100 %).
  EXPECT_GE(base.number("recall@1"), 0.8) << base.output;
  EXPECT_GT(base.count("correct@1"), 0U) << base.output;

  // --top N: the "recall@N" line; the ranking and the top answer do not change.
  const Report top1 = eval("--top 1");
  EXPECT_EQ(top1.lines("recall@1"), 2U) << top1.output;
  EXPECT_FALSE(top1.has("recall@5")) << top1.output;
  EXPECT_EQ(top1.count("correct@1"), base.count("correct@1"));
  const Report top10 = eval("--top 10");
  expectConsistent(top10, 10);
  EXPECT_FALSE(top10.has("recall@5")) << top10.output;
  EXPECT_EQ(top10.count("correct@1"), base.count("correct@1"));
  EXPECT_GE(top10.number("recall@10"), base.number("recall@5"));
  EXPECT_GE(base.number("recall@5"), top1.number("recall@1"));

  // --keyframe-every 6: 12 keyframes (frames 0, 6, ..., 66), 60 queries, the nearest keyframe at
  // most 3 frames away: more queries are answerable, and a larger share of them.
  const Report every6 = eval("--keyframe-every 6");
  expectConsistent(every6, 5);
  EXPECT_EQ(every6.count("frames"), static_cast<std::size_t>(kFrames));
  EXPECT_EQ(every6.count("keyframes"), static_cast<std::size_t>(kFrames / 6));
  EXPECT_EQ(every6.count("queries"), static_cast<std::size_t>(kFrames - kFrames / 6));
  EXPECT_GT(every6.count("answerable"), base.count("answerable"));
  EXPECT_GT(ratio(every6.count("answerable"), every6.count("queries")),
            ratio(base.count("answerable"), base.count("queries")));

  // --max-distance / --max-angle: a correct answer must lie within both. Loosening both to
  // everything makes every top answer correct; the answers themselves do not change.
  const Report anything = eval("--max-distance 100 --max-angle 180");
  expectConsistent(anything, 5);
  EXPECT_EQ(anything.count("answerable"), anything.count("queries")) << anything.output;
  EXPECT_EQ(anything.count("correct@1"), anything.count("answered")) << anything.output;
  EXPECT_EQ(anything.count("answered"), base.count("answered"));
  EXPECT_DOUBLE_EQ(anything.number("recall@1"), 1.0);
  EXPECT_DOUBLE_EQ(anything.number("precision@1"), 1.0);
  // 0 m: no two frames share a position, nothing is correct (but every query is still answered).
  const Report no_distance = eval("--max-distance 0");
  expectConsistent(no_distance, 5);
  EXPECT_EQ(no_distance.count("answerable"), 0U) << no_distance.output;
  EXPECT_EQ(no_distance.count("correct@1"), 0U) << no_distance.output;
  EXPECT_EQ(no_distance.count("answered"), base.count("answered"));
  // 10 deg instead of 20: queries 3-4 frames (~15-20 deg) from their keyframe drop out.
  const Report narrow = eval("--max-angle 10");
  expectConsistent(narrow, 5);
  EXPECT_GT(narrow.count("answerable"), 0U) << narrow.output;
  EXPECT_LT(narrow.count("answerable"), base.count("answerable")) << narrow.output;
  EXPECT_LE(narrow.count("correct@1"), base.count("correct@1")) << narrow.output;

  // --exclude-window 30: neighbouring keyframes are hidden, only the lap's return to its start
  // (last frames against keyframe 0, first frames against keyframe 70) can answer.
  const Report window = eval("--exclude-window 30");
  expectConsistent(window, 5);
  EXPECT_EQ(window.count("queries"), base.count("queries"));
  EXPECT_GT(window.count("answerable"), 0U) << window.output;
  EXPECT_LT(window.count("answerable"), base.count("answerable")) << window.output;
  EXPECT_LT(window.number("precision@1"), base.number("precision@1")) << window.output;
  // Hiding keyframes within kFrames - 1 frames hides all of them: no answers at all.
  const Report hidden = eval("--exclude-window " + std::to_string(kFrames - 1));
  expectConsistent(hidden, 5);
  EXPECT_EQ(hidden.count("queries"), base.count("queries"));
  EXPECT_EQ(hidden.count("answered"), 0U) << hidden.output;
  EXPECT_EQ(hidden.count("answerable"), 0U) << hidden.output;
  EXPECT_EQ(hidden.count("correct@1"), 0U) << hidden.output;
  EXPECT_DOUBLE_EQ(hidden.number("recall@5"), 0.0);

  // --features 1: one descriptor (one word) per frame: most queries share no word with any
  // keyframe and get no answer; the poses (frames, answerable) are the same.
  const Report one_feature = eval("--features 1");
  expectConsistent(one_feature, 5);
  EXPECT_EQ(one_feature.count("frames"), base.count("frames"));
  EXPECT_EQ(one_feature.count("answerable"), base.count("answerable"));
  EXPECT_LT(one_feature.count("answered"), base.count("answered")) << one_feature.output;
  EXPECT_LT(one_feature.count("correct@1"), base.count("correct@1")) << one_feature.output;
  EXPECT_LT(one_feature.number("recall@5"), base.number("recall@5")) << one_feature.output;

  // --dataset: a copy of the lap without its groundtruth.txt cannot be evaluated.
  const fs::path no_truth = dir_.path() / "no_truth";
  fs::copy(sequence(), no_truth, fs::copy_options::recursive);
  ASSERT_TRUE(fs::remove(no_truth / "groundtruth.txt"));
  const auto result =
      runCli("vocab eval " + defaultVocabulary().string() + " --dataset tum:" + no_truth.string());
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_TRUE(contains(result.output, "lumaslam vocab: error: tum:" + no_truth.string() +
                                          ": the dataset has no ground-truth poses"))
      << result.output;
}

TEST(CliVocabEvalBadInput, ExitsNonZeroNamingTheFile) {
  const TempDir dir("cli_vocab_eval_bad");
  const std::string vocab = defaultVocabulary().string();
  const fs::path missing_vocab = dir.path() / "missing_vocab.bin";
  const fs::path missing_data = dir.path() / "missing_sequence";

  // The vocabulary is read first: its error names it, even when the dataset is missing too.
  auto result =
      runCli("vocab eval " + missing_vocab.string() + " --dataset tum:" + missing_data.string());
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_TRUE(contains(result.output, missing_vocab.string() + ": cannot open vocabulary file"))
      << result.output;

  result = runCli("vocab eval " + vocab + " --dataset tum:" + missing_data.string());
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_TRUE(contains(result.output, "lumaslam vocab: error: " + missing_data.string() +
                                          ": dataset path not found"))
      << result.output;

  result = runCli("vocab eval " + vocab);  // --dataset is required
  EXPECT_NE(result.exit_code, 0) << result.output;
  EXPECT_TRUE(contains(result.output, "--dataset is required")) << result.output;

  // Values out of range are refused before any frame is read.
  const std::string spec = " --dataset tum:" + missing_data.string();
  result = runCli("vocab eval " + vocab + spec + " --keyframe-every 1");
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_TRUE(contains(result.output, "--keyframe-every must be >= 2")) << result.output;
  result = runCli("vocab eval " + vocab + spec + " --top 0");
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_TRUE(contains(result.output, "--top must be >= 1")) << result.output;
}

}  // namespace
