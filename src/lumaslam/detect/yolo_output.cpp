#include "lumaslam/detect/yolo_output.h"

#include <algorithm>
#include <map>

#include <opencv2/dnn.hpp>

#include "lumaslam/core/error.h"

namespace lumaslam::detect {
namespace {

constexpr int kBoxColumns = 5;  // cx, cy, w, h, objectness

// The output as an N x (5 + C) float matrix (no copy).
cv::Mat rowsOf(const cv::Mat& output, std::size_t class_count) {
  if (output.type() != CV_32F) fail("YOLO output: expected float32, found type {}", output.type());
  cv::Mat rows;
  if (output.dims == 3 && output.size[0] == 1) {
    rows = cv::Mat(output.size[1], output.size[2], CV_32F, const_cast<uchar*>(output.ptr()));
  } else if (output.dims == 2) {
    rows = output;
  } else {
    fail("YOLO output: expected a 1xNx(5+C) tensor, found {} dimensions", output.dims);
  }
  if (rows.cols != static_cast<int>(kBoxColumns + class_count)) {
    fail("YOLO output: rows have {} values but {} class names give {}", rows.cols, class_count,
         kBoxColumns + class_count);
  }
  return rows;
}

}  // namespace

Detections decodeYoloOutput(const cv::Mat& output, const LetterboxTransform& transform,
                            const std::vector<std::string>& names, const YoloDecodeParams& params) {
  const cv::Mat rows = rowsOf(output, names.size());
  std::vector<bool> wanted(names.size(), params.class_ids.empty());
  for (const int id : params.class_ids) {
    if (id >= 0 && id < static_cast<int>(names.size())) wanted[id] = true;
  }

  // Candidates grouped by class for class-wise NMS (OpenCV 4.6 has no NMSBoxesBatched).
  struct Candidates {
    std::vector<cv::Rect2d> boxes;
    std::vector<float> scores;
  };
  std::map<int, Candidates> by_class;
  for (int r = 0; r < rows.rows; ++r) {
    const float* row = rows.ptr<float>(r);
    const float objectness = row[4];
    if (objectness < params.confidence_threshold) continue;
    const float* class_scores = row + kBoxColumns;
    const int best = static_cast<int>(std::max_element(class_scores, class_scores + names.size()) -
                                      class_scores);
    const float confidence = objectness * class_scores[best];
    if (confidence < params.confidence_threshold || !wanted[best]) continue;
    const cv::Rect2f box = transform.toImage(row[0], row[1], row[2], row[3]);
    if (box.area() <= 0.0f) continue;
    by_class[best].boxes.emplace_back(box);
    by_class[best].scores.push_back(confidence);
  }

  Detections detections;
  for (const auto& [class_id, candidates] : by_class) {
    std::vector<int> keep;
    cv::dnn::NMSBoxes(candidates.boxes, candidates.scores, params.confidence_threshold,
                      params.nms_threshold, keep);
    for (const int k : keep) {
      detections.push_back(
          {class_id, names[class_id], candidates.scores[k], cv::Rect2f(candidates.boxes[k])});
    }
  }
  std::sort(detections.begin(), detections.end(),
            [](const Detection& a, const Detection& b) { return a.score > b.score; });
  return detections;
}

}  // namespace lumaslam::detect
