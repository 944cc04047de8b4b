#pragma once
// Detections read from a text file instead of a network, so any external detector (or the
// synthetic generator's detections.txt) can drive dynamic-object removal. One box per line:
//   timestamp class x y w h      ('#' starts a comment; class is a name or a numeric id)
// A frame gets the boxes of the nearest listed timestamp within the tolerance, else none.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "lumaslam/detect/detector.h"
#include "lumaslam/detect/detector_params.h"

namespace lumaslam::detect {

class BoxFileDetector : public Detector {
 public:
  // Reads params.box_file; keeps only params.classes. Numeric class ids need params.names
  // (line i = id i). Throws Error "FILE:LINE: ..." for a malformed line.
  explicit BoxFileDetector(const DetectorParams& params);

  Detections detect(const cv::Mat& image, double timestamp) override;
  std::string describe() const override;

  std::size_t frameCount() const { return frames_.size(); }

 private:
  std::filesystem::path file_;
  double tolerance_ = 0.0;
  std::map<double, Detections> frames_;  // by timestamp
};

}  // namespace lumaslam::detect
