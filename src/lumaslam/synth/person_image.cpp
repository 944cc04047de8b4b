#include "lumaslam/synth/person_image.h"

#include <algorithm>
#include <string>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "lumaslam/core/error.h"

namespace lumaslam::synth {

namespace {

PersonImage readPersonImage(const std::filesystem::path& file) {
  const cv::Mat raw = cv::imread(file.string(), cv::IMREAD_UNCHANGED);
  if (raw.empty() || raw.depth() != CV_8U)
    fail("{}: cannot read this person image (8-bit image expected)", file.string());
  PersonImage person;
  if (raw.channels() == 4) {
    cv::extractChannel(raw, person.alpha, 3);
    cv::cvtColor(raw, person.image, cv::COLOR_BGRA2BGR);
  } else {
    person.image = cv::imread(file.string(), cv::IMREAD_COLOR);
  }
  return person;
}

// GrabCut alpha (255 = person) of `box` in `image`, or empty when it cannot be cut.
cv::Mat segmentPerson(const cv::Mat& image, const cv::Rect& box) {
  const int mx = box.width / 8 + 4, my = box.height / 8 + 4;
  const cv::Rect region =
      cv::Rect(box.x - mx, box.y - my, box.width + 2 * mx, box.height + 2 * my) &
      cv::Rect(0, 0, image.cols, image.rows);
  if (region.area() - box.area() < 200) return {};  // too little background to model
  cv::Mat labels, background_model, foreground_model;
  // GrabCut seeds its k-means from OpenCV's thread-local RNG: fix it so crops are reproducible.
  const cv::RNG saved = cv::theRNG();
  cv::theRNG() = cv::RNG(0x9e0e);
  cv::grabCut(image(region), labels, box - region.tl(), background_model, foreground_model, 4,
              cv::GC_INIT_WITH_RECT);
  cv::theRNG() = saved;
  cv::Mat alpha = (labels == cv::GC_FGD) | (labels == cv::GC_PR_FGD);
  alpha = alpha(box - region.tl()).clone();
  cv::medianBlur(alpha, alpha, 5);  // no speckles: they would flicker as walker pixels
  if (cv::countNonZero(alpha) < box.area() / 5) return {};
  return alpha;
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

std::vector<PersonImage> cropPersonImages(const cv::Mat& image, const std::vector<cv::Rect>& boxes,
                                          bool segment) {
  if (image.empty() || image.type() != CV_8UC3)
    fail("cropPersonImages: expected a non-empty 8-bit BGR image");
  std::vector<PersonImage> people;
  for (const cv::Rect& box : boxes) {
    const cv::Rect clipped = box & cv::Rect(0, 0, image.cols, image.rows);
    if (clipped.area() > 0 && clipped.width <= clipped.height)
      people.push_back(
          {image(clipped).clone(), segment ? segmentPerson(image, clipped) : cv::Mat()});
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
