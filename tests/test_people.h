#pragma once
// The labelled people of ../shared/data (bus.jpg, zidane.jpg; labels/person_boxes.txt) as
// GrabCut-cut person crops for synthetic walkers (synth::SynthOptions::people).
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "lumaslam/detect/box_labels.h"
#include "lumaslam/synth/person_image.h"
#include "test_paths.h"

namespace lumaslam::test {

inline std::vector<synth::PersonImage> labelledPeople() {
  std::vector<synth::PersonImage> people;
  for (const auto& [image, labels] :
       detect::readBoxList(dataDir() / "labels" / "person_boxes.txt")) {
    std::vector<cv::Rect> boxes;
    for (const auto& label : labels)
      if (label.class_name == "person") boxes.push_back(label.box);
    const auto crops = synth::cropPersonImages(cv::imread((dataDir() / image).string()), boxes);
    people.insert(people.end(), crops.begin(), crops.end());
  }
  return people;
}

}  // namespace lumaslam::test
