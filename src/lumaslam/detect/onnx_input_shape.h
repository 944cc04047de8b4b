#pragma once
// The shape of an ONNX model's first graph input, read straight from the protobuf file.
// OpenCV 4.6's dnn::Net does not expose input shapes of an imported ONNX graph, and the
// YOLOv5 input size (320, 640, ...) must come from the model, not from a guess.
#include <cstdint>
#include <filesystem>
#include <vector>

namespace lumaslam::detect {

// Dimensions of the first graph input that is not an initializer (weights), e.g.
// {1, 3, 640, 640}; a symbolic dimension ("batch", "height") is -1. Throws Error naming the
// file when it is unreadable or not an ONNX model with a tensor input.
std::vector<std::int64_t> onnxInputShape(const std::filesystem::path& model);

}  // namespace lumaslam::detect
