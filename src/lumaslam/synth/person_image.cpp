#include "lumaslam/synth/person_image.h"

#include <algorithm>
#include <string>

#include <opencv2/imgcodecs.hpp>

#include "lumaslam/core/error.h"

namespace lumaslam::synth {

namespace {

PersonImage readPersonImage(const std::filesystem::path& file) {
  PersonImage person;
  person.image = cv::imread(file.string(), cv::IMREAD_COLOR);
  if (person.image.empty()) fail("{}: cannot read this person image", file.string());
  return person;
}

}  // namespace

std::vector<PersonImage> loadPersonImages(const std::filesystem::path& dir_or_file) {
  namespace fs = std::filesystem;
  if (!fs::exists(dir_or_file)) fail("{}: no such person image or folder", dir_or_file.string());
  if (!fs::is_directory(dir_or_file)) return {readPersonImage(dir_or_file)};
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir_or_file))
    if (entry.is_regular_file() && cv::haveImageReader(entry.path().string()))
      files.push_back(entry.path());
  if (files.empty()) fail("{}: folder holds no image to use as a person", dir_or_file.string());
  std::sort(files.begin(), files.end());
  std::vector<PersonImage> people;
  for (const auto& file : files) people.push_back(readPersonImage(file));
  return people;
}

std::vector<PersonImage> cropPersonImages(const cv::Mat& image,
                                          const std::vector<cv::Rect>& boxes) {
  std::vector<PersonImage> people;
  for (const cv::Rect& box : boxes) {
    const cv::Rect clipped = box & cv::Rect(0, 0, image.cols, image.rows);
    if (clipped.area() > 0 && clipped.width <= clipped.height)
      people.push_back({image(clipped).clone(), {}});
  }
  return people;
}

void checkPersonImage(const PersonImage& person, const std::string& what) {
  if (person.image.empty() || person.image.type() != CV_8UC3)
    fail("{}: a person image must be a non-empty 8-bit BGR image", what);
  if (!person.alpha.empty() &&
      (person.alpha.type() != CV_8U || person.alpha.size() != person.image.size()))
    fail("{}: a person alpha must be 8-bit with the image's size", what);
}

}  // namespace lumaslam::synth
