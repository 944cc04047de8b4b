// perturb: the synth lighting models on existing TUM / EuRoC folders.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "error_of.h"
#include "lumaslam/core/error.h"
#include "lumaslam/synth/dataset_writer.h"
#include "lumaslam/synth/perturb.h"
#include "test_paths.h"

using namespace lumaslam::synth;
using lumaslam::test::errorOf;
namespace fs = std::filesystem;

namespace {

std::string readBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

std::vector<fs::path> filesUnder(const fs::path& root) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(root))
    if (entry.is_regular_file()) files.push_back(fs::relative(entry.path(), root));
  std::sort(files.begin(), files.end());
  return files;
}

cv::Mat realEurocImage() {
  const fs::path dir =
      lumaslam::test::dataDir() / "euroc" / "V1_01_easy_micro" / "mav0" / "cam0" / "data";
  return cv::imread((dir / "1403715273262142976.png").string(), cv::IMREAD_UNCHANGED);
}

}  // namespace

TEST(SynthPerturb, LevelZeroIsTheIdentityForEveryModel) {
  const cv::Mat image = realEurocImage();
  ASSERT_FALSE(image.empty());
  for (const char* name : {"dark", "flash", "flicker", "spotlight", "noise"}) {
    const cv::Mat out = perturbImage(image, perturbModelFromName(name), 0, 15, 1.0, 7);
    EXPECT_EQ(cv::norm(out, image, cv::NORM_INF), 0.0) << name;
  }
}

TEST(SynthPerturb, DarkLevelsDarkenRealImagesMonotonically) {
  const cv::Mat image = realEurocImage();
  double previous = cv::mean(image)[0];
  for (int level = 1; level <= 5; ++level) {
    const double mean = cv::mean(perturbImage(image, PerturbModel::Dark, level, 0, 0.0, 3))[0];
    EXPECT_LT(mean, 0.92 * previous) << "level " << level;
    previous = mean;
  }
  EXPECT_LT(previous, 25.0);
  EXPECT_THROW(perturbImage(image, PerturbModel::Dark, 6, 0, 0.0, 3), lumaslam::Error);
  EXPECT_THROW(perturbModelFromName("fog"), lumaslam::Error);
}

TEST(SynthPerturb, FlashHitsTheScheduledFramesOnly) {
  const cv::Mat image = realEurocImage();
  const double base = cv::mean(image)[0];
  EXPECT_EQ(cv::mean(perturbImage(image, PerturbModel::Flash, 3, 14, 0.0, 1))[0], base);
  EXPECT_GT(cv::mean(perturbImage(image, PerturbModel::Flash, 3, 15, 0.0, 1))[0], 1.2 * base);
  EXPECT_EQ(cv::mean(perturbImage(image, PerturbModel::Flash, 3, 18, 0.0, 1))[0], base);
  EXPECT_LT(cv::mean(perturbImage(image, PerturbModel::Flash, 3, 45, 0.0, 1))[0], 0.7 * base);
}

TEST(SynthPerturb, SpotlightAndNoiseChangeTheImageTheWayTheySay) {
  const cv::Mat image = realEurocImage();
  const cv::Mat spot = perturbImage(image, PerturbModel::Spotlight, 5, 0, 0.0, 1);
  // At t = 0 the light disc sits left-right centred; the corners fall to 10% of the light.
  const cv::Rect corner(0, 0, 60, 60), centre(image.cols / 2 - 30, image.rows / 2 + 20, 60, 60);
  EXPECT_LT(cv::mean(spot(corner))[0], 0.5 * cv::mean(image(corner))[0]);
  EXPECT_GT(cv::mean(spot(centre))[0], 0.9 * cv::mean(image(centre))[0]);
  const cv::Mat noisy1 = perturbImage(image, PerturbModel::Noise, 2, 0, 0.0, 1);
  const cv::Mat noisy5 = perturbImage(image, PerturbModel::Noise, 5, 0, 0.0, 1);
  EXPECT_NEAR(cv::mean(noisy5)[0], cv::mean(image)[0], 2.0);  // gain-compensated
  EXPECT_GT(cv::norm(noisy5, image, cv::NORM_L1), 1.3 * cv::norm(noisy1, image, cv::NORM_L1));
}

TEST(SynthPerturb, DatasetCopyKeepsEveryFileAndGroundTruth) {
  lumaslam::test::TempDir dir("synth_perturb");
  const fs::path in = dir.path() / "in", out = dir.path() / "out";
  writeSequence(in, "walking-xyz-rgbd", 3, 2);
  EXPECT_EQ(perturbDataset(in, out, PerturbModel::Dark, 3, 1), 3);
  const auto in_files = filesUnder(in);
  auto out_files = filesUnder(out);
  out_files.erase(std::remove(out_files.begin(), out_files.end(), fs::path("perturbation.txt")),
                  out_files.end());
  EXPECT_EQ(in_files, out_files);
  for (const auto& file : in_files) {
    const bool is_rgb = file.begin()->string() == "rgb";
    if (is_rgb) {
      const cv::Mat a = cv::imread((in / file).string()), b = cv::imread((out / file).string());
      ASSERT_EQ(a.size(), b.size());
      EXPECT_LT(cv::mean(b)[0], 0.7 * cv::mean(a)[0]) << file;
    } else {
      EXPECT_EQ(readBytes(in / file), readBytes(out / file)) << file;  // depth, GT, lists untouched
    }
  }
}

TEST(SynthPerturb, EurocDatasetBothCamerasAndBadInput) {
  lumaslam::test::TempDir dir("synth_perturb_euroc");
  const fs::path in = dir.path() / "in", out = dir.path() / "out";
  writeSequence(in, "xyz-stereo", 2, 2);
  EXPECT_EQ(perturbDataset(in, out, PerturbModel::Flicker, 4, 1), 4);
  EXPECT_EQ(readBytes(in / "mav0/state_groundtruth_estimate0/data.csv"),
            readBytes(out / "mav0/state_groundtruth_estimate0/data.csv"));
  const std::string missing =
      errorOf([&] { perturbDataset(dir.path() / "missing", out, PerturbModel::Dark, 1, 1); });
  EXPECT_NE(missing.find("missing"), std::string::npos);
  fs::create_directories(dir.path() / "plain");
  EXPECT_THROW(perturbDataset(dir.path() / "plain", out, PerturbModel::Dark, 1, 1),
               lumaslam::Error);
  // A corrupt image is reported by name.
  for (const auto& entry : fs::directory_iterator(in / "mav0/cam0/data")) {
    std::ofstream(entry.path(), std::ios::trunc) << "not a png";
    break;
  }
  const std::string message =
      errorOf([&] { perturbDataset(in, dir.path() / "out2", PerturbModel::Dark, 1, 1); });
  EXPECT_NE(message.find("cam0"), std::string::npos) << message;
}

// A perturb that fails half way (one corrupt image) leaves no half-perturbed dataset: the
// earlier output stays as it was and no OUT.partial is left behind; a perturb that succeeds
// replaces the earlier output whole.
TEST(SynthPerturb, AFailedRunLeavesTheEarlierOutputAndNoPartialFolder) {
  lumaslam::test::TempDir dir("synth_perturb_atomic");
  const fs::path in = dir.path() / "in", out = dir.path() / "out";
  writeSequence(in, "xyz-rgbd", 4, 2);
  fs::create_directories(out);
  std::ofstream(out / "earlier.txt") << "an earlier result\n";
  for (const auto& entry : fs::directory_iterator(in / "rgb")) {
    std::ofstream(entry.path(), std::ios::trunc) << "not a png";
    break;
  }
  EXPECT_THROW(perturbDataset(in, out, PerturbModel::Dark, 2, 1), lumaslam::Error);
  EXPECT_EQ(filesUnder(out), std::vector<fs::path>{"earlier.txt"});
  EXPECT_FALSE(fs::exists(dir.path() / "out.partial"));

  writeSequence(in, "xyz-rgbd", 4, 2);  // repaired input
  EXPECT_EQ(perturbDataset(in, out, PerturbModel::Dark, 2, 1), 4);
  EXPECT_FALSE(fs::exists(out / "earlier.txt"));
  EXPECT_TRUE(fs::exists(out / "rgb.txt"));
  EXPECT_TRUE(fs::exists(out / "perturbation.txt"));
  EXPECT_FALSE(fs::exists(dir.path() / "out.partial"));
}
