// The `synth` and `perturb` subcommands of the CLI binary.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "test_paths.h"

namespace fs = std::filesystem;

namespace {

int run(const std::string& arguments, const fs::path& log) {
  const std::string command =
      lumaslam::test::cliPath().string() + " " + arguments + " > " + log.string() + " 2>&1";
  return std::system(command.c_str());
}

std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

}  // namespace

TEST(SynthCli, SynthWritesADatasetAndPerturbLevelZeroCopiesIt) {
  lumaslam::test::TempDir dir("synth_cli");
  const fs::path out = dir.path() / "stereo", log = dir.path() / "log.txt";
  ASSERT_EQ(run("synth " + out.string() + " --preset xyz-stereo --frames 2 --seed 4", log), 0)
      << readText(log);
  EXPECT_TRUE(fs::exists(out / "mav0/cam0/data.csv"));
  EXPECT_TRUE(fs::exists(out / "mav0/cam1/sensor.yaml"));
  EXPECT_TRUE(fs::exists(out / "settings.yaml"));

  const fs::path copy = dir.path() / "copy";
  ASSERT_EQ(run("perturb " + out.string() + " " + copy.string() + " --model dark --level 0", log),
            0)
      << readText(log);
  for (const auto& entry : fs::directory_iterator(out / "mav0/cam0/data"))
    EXPECT_EQ(readText(entry.path()), readText(copy / "mav0/cam0/data" / entry.path().filename()));
}

TEST(SynthCli, BadArgumentsFailWithAClearMessage) {
  lumaslam::test::TempDir dir("synth_cli_bad");
  const fs::path log = dir.path() / "log.txt";
  EXPECT_NE(run("synth " + (dir.path() / "x").string() + " --preset nope", log), 0);
  EXPECT_NE(readText(log).find("preset 'nope' is unknown"), std::string::npos) << readText(log);
  EXPECT_NE(run("perturb " + (dir.path() / "missing").string() + " " + (dir.path() / "y").string() +
                    " --model dark --level 2",
                log),
            0);
  EXPECT_NE(readText(log).find("missing"), std::string::npos) << readText(log);
}

TEST(SynthCli, PeopleImagesTextureTheWalkersFromABoxList) {
  lumaslam::test::TempDir dir("synth_cli_people");
  const fs::path log = dir.path() / "log.txt";
  const fs::path labels = lumaslam::test::dataDir() / "labels" / "person_boxes.txt";
  const std::string common = " --preset walking-xyz-rgbd --frames 3 --seed 2";
  ASSERT_EQ(run("synth " + (dir.path() / "photo").string() + common + " --people-images " +
                    labels.string(),
                log),
            0)
      << readText(log);
  ASSERT_EQ(run("synth " + (dir.path() / "plain").string() + common, log), 0) << readText(log);
  EXPECT_NE(readText(dir.path() / "photo/detections.txt").find("person"), std::string::npos);
  EXPECT_EQ(readText(dir.path() / "photo/rgb.txt"), readText(dir.path() / "plain/rgb.txt"));
  EXPECT_NE(readText(dir.path() / "photo/detections.txt"),
            readText(dir.path() / "plain/detections.txt"));  // photo walkers have their own shape

  EXPECT_NE(run("synth " + (dir.path() / "x").string() + common + " --people-images " +
                    (dir.path() / "nobody").string(),
                log),
            0);
  EXPECT_NE(readText(log).find("nobody"), std::string::npos) << readText(log);
}

// Mean grey level of the walkers' own pixels (mask/, 255 = dynamic) over a synth output.
double walkerBrightness(const fs::path& out) {
  double sum = 0.0;
  double pixels = 0.0;
  for (const auto& entry : fs::directory_iterator(out / "mask")) {
    const cv::Mat mask = cv::imread(entry.path().string(), cv::IMREAD_GRAYSCALE);
    const cv::Mat grey =
        cv::imread((out / "rgb" / entry.path().filename()).string(), cv::IMREAD_GRAYSCALE);
    const double n = cv::countNonZero(mask);
    if (n > 0) sum += cv::mean(grey, mask)[0] * n;
    pixels += n;
  }
  return pixels > 0 ? sum / pixels : -1.0;
}

// LLVIP's night street people: Pascal VOC annotations, images in visible/test and visible/train.
TEST(SynthCli, PeopleImagesFromVocAnnotationsAndFromSeveralSources) {
  lumaslam::test::TempDir dir("synth_cli_voc_people");
  const fs::path log = dir.path() / "log.txt";
  const fs::path llvip = lumaslam::test::dataDir() / "llvip" / "night_people_sample";
  const std::string night = " --people-images " + (llvip / "Annotations").string();
  const std::string folders = " --people-image-folder " + (llvip / "visible" / "test").string() +
                              " --people-image-folder " + (llvip / "visible" / "train").string();
  const std::string daylight =
      " --people-images " + (lumaslam::test::dataDir() / "labels" / "person_boxes.txt").string();
  const std::string common = " --preset walking-xyz-rgbd --frames 3 --seed 2 --moving-boxes 0";
  ASSERT_EQ(run("synth " + (dir.path() / "night").string() + common + night + folders, log), 0)
      << readText(log);
  ASSERT_EQ(run("synth " + (dir.path() / "day").string() + common + daylight, log), 0)
      << readText(log);
  ASSERT_EQ(
      run("synth " + (dir.path() / "both").string() + common + daylight + night + folders, log), 0)
      << readText(log);
  EXPECT_NE(readText(dir.path() / "night/detections.txt").find("person"), std::string::npos);
  EXPECT_NE(readText(dir.path() / "both/detections.txt").find("person"), std::string::npos);
  // The walkers wear the night photos: far darker than the daylight bus/zidane people.
  const double night_grey = walkerBrightness(dir.path() / "night");
  const double day_grey = walkerBrightness(dir.path() / "day");
  EXPECT_GT(night_grey, 0.0);
  EXPECT_LT(night_grey, 0.8 * day_grey) << "night " << night_grey << ", daylight " << day_grey;

  // VOC's own layout is the default: LLVIP has no JPEGImages folder, so the images are not found.
  EXPECT_NE(run("synth " + (dir.path() / "x").string() + common + night, log), 0);
  EXPECT_NE(readText(log).find("010005.xml: image '010005.jpg' not found"), std::string::npos)
      << readText(log);
}

TEST(SynthCli, SyncedDepthWritesDepthAtTheColourStamps) {
  lumaslam::test::TempDir dir("synth_cli_synced");
  const fs::path log = dir.path() / "log.txt";
  const auto stamps = [](const fs::path& list) {
    std::vector<std::string> out;
    std::ifstream in(list);
    for (std::string line; std::getline(in, line);)
      if (!line.empty() && line[0] != '#') out.push_back(line.substr(0, line.find(' ')));
    return out;
  };
  const fs::path jittered = dir.path() / "jittered", synced = dir.path() / "synced";
  ASSERT_EQ(run("synth " + jittered.string() + " --preset handheld-rgbd --frames 3 --seed 2", log),
            0)
      << readText(log);
  ASSERT_EQ(run("synth " + synced.string() +
                    " --preset handheld-rgbd --frames 3 --seed 2 --synced-depth --global-shutter",
                log),
            0)
      << readText(log);
  EXPECT_EQ(stamps(jittered / "rgb.txt"), stamps(synced / "rgb.txt"));
  EXPECT_NE(stamps(jittered / "depth.txt"), stamps(jittered / "rgb.txt"));
  EXPECT_EQ(stamps(synced / "depth.txt"), stamps(synced / "rgb.txt"));
  EXPECT_NE(readText(jittered / "rgb" / (stamps(jittered / "rgb.txt")[1] + ".png")),
            readText(synced / "rgb" / (stamps(synced / "rgb.txt")[1] + ".png")));
}

// --list against two independent sources: the preset table of docs/synthetic.md (name, rig,
// frames) and what `synth --preset NAME` accepts. Every documented preset is listed with its
// frame count and renders one frame in its rig's layout; a name not listed is refused.
TEST(SynthCli, ListNamesEveryPresetThatSynthAccepts) {
  lumaslam::test::TempDir dir("synth_cli_list");
  const fs::path log = dir.path() / "log.txt";
  ASSERT_EQ(run("synth --list", log), 0) << readText(log);
  // Lines "NAME (N frames): description".
  std::map<std::string, std::string> listed;  // name -> frames
  std::istringstream lines(readText(log));
  for (std::string line; std::getline(lines, line);) {
    const auto open = line.find(" (");
    ASSERT_NE(open, std::string::npos) << line;
    listed[line.substr(0, open)] = line.substr(open + 2, line.find(' ', open + 2) - open - 2);
  }

  // The docs table "| preset | rig | trajectory | frames | what it tests |" under "## Presets".
  std::map<std::string, std::pair<std::string, std::string>> documented;  // name -> rig, frames
  std::istringstream docs(readText(lumaslam::test::sourceDir() / "docs/synthetic.md"));
  bool in_presets = false;
  for (std::string line; std::getline(docs, line);) {
    if (line.rfind("## ", 0) == 0) in_presets = line == "## Presets";
    if (!in_presets || line.rfind("| ", 0) != 0 || line.rfind("| preset ", 0) == 0) continue;
    std::vector<std::string> cells;
    std::istringstream row(line.substr(1));
    for (std::string cell; std::getline(row, cell, '|');)
      cells.push_back(cell.substr(1, cell.size() - 2));
    ASSERT_GE(cells.size(), 4u) << line;
    documented[cells[0]] = {cells[1], cells[3]};
  }
  ASSERT_GE(documented.size(), 10u);
  ASSERT_EQ(listed.size(), documented.size());

  for (const auto& [name, doc] : documented) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(listed.count(name));
    EXPECT_EQ(listed[name], doc.second);
    const fs::path out = dir.path() / name;
    ASSERT_EQ(run("synth " + out.string() + " --preset " + name + " --frames 1", log), 0)
        << readText(log);
    EXPECT_TRUE(fs::exists(out / (doc.first == "stereo" ? "mav0/cam1/data.csv" : "rgb.txt")));
    fs::remove_all(out);
  }
  EXPECT_FALSE(listed.count("stereo-xyz"));
  EXPECT_NE(run("synth " + (dir.path() / "x").string() + " --preset stereo-xyz --frames 1", log),
            0);
}
