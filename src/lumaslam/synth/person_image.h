#pragma once
// Photos of people for the walker billboards (`lumaslam synth --people-images`): a walker
// textured from a real person crop looks like a person to a detector such as YOLO, where the
// procedural walker texture barely does.
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace lumaslam::synth {

struct PersonImage {
  cv::Mat image;  // CV_8UC3 BGR crop, head at the top, feet at the bottom
  cv::Mat alpha;  // CV_8U of image's size, >= 128 where the person is; empty = the whole crop
};

// One image file, or every image file in a folder (sorted by file name), each used whole as a
// person crop; an image's own alpha channel (e.g. a cut-out PNG) becomes its alpha. Throws Error
// naming the path when it is missing, a file is not a readable image, or a folder holds no image.
std::vector<PersonImage> loadPersonImages(const std::filesystem::path& dir_or_file);

// The crops of `boxes` in `image`, clipped to it. Boxes wider than tall are skipped: they are
// not standing people, and stretched to a walker's height they would be metres wide. With
// `segment`, each crop's alpha is the person cut out by GrabCut (initialised with the box, the
// pixels around it as background; deterministic), so the walker is person-shaped instead of a
// photo rectangle; a crop GrabCut cannot cut (no room around the box, or it keeps < 20% of
// the box) stays a rectangle.
std::vector<PersonImage> cropPersonImages(const cv::Mat& image, const std::vector<cv::Rect>& boxes,
                                          bool segment = true);

// Throws Error (naming `what`) unless `person` has a non-empty CV_8UC3 image and an empty or
// matching CV_8U alpha.
void checkPersonImage(const PersonImage& person, const std::string& what);

}  // namespace lumaslam::synth
