#pragma once
// Person photos for synthetic walkers (`lumaslam synth --people-images`), from the label
// formats ../shared/data has: a box list, Pascal VOC annotations (LLVIP), or plain crops.
#include <filesystem>
#include <vector>

#include "lumaslam/synth/person_image.h"

namespace lumaslam::cli {

// Every source in order, each one of:
// - a box list (*.txt, "image class x1 y1 x2 y2"): its person boxes, cut out; images relative
//   to the list's folder or a folder above it;
// - a VOC annotation file (*.xml) or a folder of them: their person boxes, cut out of the
//   image each names (<filename>), looked for in `image_folders` in order (default: the
//   annotations' sibling folder JPEGImages, VOC's own layout);
// - an image, or a folder of person crops, used whole.
// Throws Error naming the source (and the image) when nothing can be read from it.
std::vector<synth::PersonImage> loadPeople(
    const std::vector<std::filesystem::path>& sources,
    const std::vector<std::filesystem::path>& image_folders = {});

}  // namespace lumaslam::cli
