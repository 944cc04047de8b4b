#include "people_sources.h"

#include <algorithm>
#include <string>

#include <opencv2/imgcodecs.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/detect/box_labels.h"

namespace lumaslam::cli {
namespace {

namespace fs = std::filesystem;

std::vector<cv::Rect> personBoxes(const std::vector<detect::LabeledBox>& labels) {
  std::vector<cv::Rect> boxes;
  for (const auto& label : labels)
    if (label.class_name == "person") boxes.push_back(label.box);
  return boxes;
}

std::vector<synth::PersonImage> cropsOf(const fs::path& image_file,
                                        const std::vector<cv::Rect>& boxes) {
  const cv::Mat bgr = cv::imread(image_file.string(), cv::IMREAD_COLOR);
  if (bgr.empty()) fail("{}: cannot read this image", image_file.string());
  return synth::cropPersonImages(bgr, boxes);
}

// An image named in a box list, relative to the list's folder or one of its ancestors
// (shared/data/labels/person_boxes.txt names its images relative to shared/data).
fs::path resolveListedImage(const fs::path& list, const std::string& image) {
  for (auto dir = fs::absolute(list).parent_path(); !dir.empty(); dir = dir.parent_path()) {
    if (fs::exists(dir / image)) return dir / image;
    if (dir == dir.parent_path()) break;
  }
  fail("{}: image '{}' not found next to the list or in a folder above it", list.string(), image);
}

std::vector<synth::PersonImage> fromBoxList(const fs::path& list) {
  std::vector<synth::PersonImage> people;
  for (const auto& [image, labels] : detect::readBoxList(list)) {
    const auto boxes = personBoxes(labels);
    if (boxes.empty()) continue;
    const auto crops = cropsOf(resolveListedImage(list, image), boxes);
    people.insert(people.end(), crops.begin(), crops.end());
  }
  return people;
}

bool isVocAnnotation(const fs::path& path) {
  return path.extension() == ".xml";
}

// The annotation files of a VOC source: the file itself, or a folder's *.xml sorted by name.
std::vector<fs::path> vocFiles(const fs::path& source) {
  if (!fs::is_directory(source)) return {source};
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(source))
    if (entry.is_regular_file() && isVocAnnotation(entry.path())) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

bool holdsVocAnnotations(const fs::path& source) {
  return isVocAnnotation(source) || (fs::is_directory(source) && !vocFiles(source).empty());
}

fs::path findVocImage(const fs::path& xml, const std::string& name,
                      const std::vector<fs::path>& folders) {
  std::string searched;
  for (const auto& folder : folders) {
    if (fs::exists(folder / name)) return folder / name;
    searched += (searched.empty() ? "" : ", ") + folder.string();
  }
  fail("{}: image '{}' not found in {} (--people-image-folder)", xml.string(), name, searched);
}

std::vector<synth::PersonImage> fromVoc(const fs::path& source,
                                        const std::vector<fs::path>& image_folders) {
  const fs::path annotations = fs::is_directory(source) ? source : source.parent_path();
  const std::vector<fs::path> folders =
      image_folders.empty() ? std::vector<fs::path>{annotations.parent_path() / "JPEGImages"}
                            : image_folders;
  std::vector<synth::PersonImage> people;
  for (const auto& xml : vocFiles(source)) {
    const auto annotation = detect::readVocAnnotation(xml);
    const auto boxes = personBoxes(annotation.boxes);
    if (boxes.empty()) continue;
    const auto crops = cropsOf(findVocImage(xml, annotation.filename, folders), boxes);
    people.insert(people.end(), crops.begin(), crops.end());
  }
  return people;
}

std::vector<synth::PersonImage> fromSource(const fs::path& source,
                                           const std::vector<fs::path>& image_folders) {
  if (source.extension() == ".txt") return fromBoxList(source);
  if (holdsVocAnnotations(source)) return fromVoc(source, image_folders);
  return synth::loadPersonImages(source);
}

}  // namespace

std::vector<synth::PersonImage> loadPeople(const std::vector<fs::path>& sources,
                                           const std::vector<fs::path>& image_folders) {
  std::vector<synth::PersonImage> people;
  for (const auto& source : sources) {
    const auto found = fromSource(source, image_folders);
    if (found.empty()) fail("{}: no person box in these labels", source.string());
    people.insert(people.end(), found.begin(), found.end());
  }
  return people;
}

}  // namespace lumaslam::cli
