#include "lumaslam/detect/onnx_input_shape.h"

#include <fstream>
#include <iterator>
#include <optional>
#include <set>
#include <string>
#include <string_view>

#include "lumaslam/core/error.h"

namespace lumaslam::detect {
namespace {

// Field numbers from onnx.proto (ModelProto, GraphProto, ValueInfoProto, TypeProto, ...).
constexpr int kModelGraph = 7;
constexpr int kGraphInitializer = 5;
constexpr int kGraphInput = 11;
constexpr int kTensorName = 8;
constexpr int kValueInfoName = 1;
constexpr int kValueInfoType = 2;
constexpr int kTypeTensor = 1;
constexpr int kTensorTypeShape = 2;
constexpr int kShapeDim = 1;
constexpr int kDimValue = 1;

constexpr int kVarint = 0;
constexpr int kFixed64 = 1;
constexpr int kLengthDelimited = 2;
constexpr int kFixed32 = 5;

struct Field {
  int number = 0;
  int wire_type = 0;
  std::uint64_t value = 0;  // varint value
  std::string_view bytes;   // length-delimited payload
};

// Walks the fields of one protobuf message; returns nullopt at the end, throws on garbage.
class MessageReader {
 public:
  MessageReader(std::string_view bytes, const std::filesystem::path& file)
      : bytes_(bytes), file_(file) {}

  std::optional<Field> next() {
    if (pos_ >= bytes_.size()) return std::nullopt;
    const std::uint64_t key = varint();
    Field field;
    field.number = static_cast<int>(key >> 3);
    field.wire_type = static_cast<int>(key & 7);
    switch (field.wire_type) {
      case kVarint:
        field.value = varint();
        break;
      case kFixed64:
        skip(8);
        break;
      case kLengthDelimited: {
        const std::uint64_t length = varint();
        if (length > bytes_.size() - pos_) corrupt();
        field.bytes = bytes_.substr(pos_, length);
        pos_ += length;
        break;
      }
      case kFixed32:
        skip(4);
        break;
      default:
        corrupt();
    }
    if (field.number <= 0) corrupt();
    return field;
  }

 private:
  std::uint64_t varint() {
    std::uint64_t result = 0;
    for (int shift = 0; shift < 64; shift += 7) {
      if (pos_ >= bytes_.size()) corrupt();
      const auto byte = static_cast<std::uint8_t>(bytes_[pos_++]);
      result |= static_cast<std::uint64_t>(byte & 0x7f) << shift;
      if ((byte & 0x80) == 0) return result;
    }
    corrupt();
  }
  void skip(std::size_t n) {
    if (n > bytes_.size() - pos_) corrupt();
    pos_ += n;
  }
  [[noreturn]] void corrupt() const {
    fail("{}: not a valid ONNX model (corrupt protobuf)", file_.string());
  }

  std::string_view bytes_;
  std::size_t pos_ = 0;
  const std::filesystem::path& file_;
};

std::string_view findBytes(std::string_view message, int number,
                           const std::filesystem::path& file) {
  MessageReader reader(message, file);
  while (auto field = reader.next()) {
    if (field->number == number && field->wire_type == kLengthDelimited) return field->bytes;
  }
  return {};
}

std::vector<std::int64_t> dimsOf(std::string_view value_info, const std::filesystem::path& file) {
  const auto type = findBytes(value_info, kValueInfoType, file);
  const auto tensor = findBytes(type, kTypeTensor, file);
  const auto shape = findBytes(tensor, kTensorTypeShape, file);
  std::vector<std::int64_t> dims;
  MessageReader reader(shape, file);
  while (auto field = reader.next()) {
    if (field->number != kShapeDim || field->wire_type != kLengthDelimited) continue;
    std::int64_t dim = -1;
    MessageReader dim_reader(field->bytes, file);
    while (auto dim_field = dim_reader.next()) {
      if (dim_field->number == kDimValue && dim_field->wire_type == kVarint) {
        dim = static_cast<std::int64_t>(dim_field->value);
      }
    }
    dims.push_back(dim);
  }
  return dims;
}

}  // namespace

std::vector<std::int64_t> onnxInputShape(const std::filesystem::path& model) {
  std::ifstream in(model, std::ios::binary);
  if (!in) fail("{}: cannot open model file", model.string());
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.empty()) fail("{}: model file is empty", model.string());

  const auto graph = findBytes(bytes, kModelGraph, model);
  if (graph.empty()) fail("{}: not an ONNX model (no graph)", model.string());

  std::set<std::string_view> initializers;
  std::vector<std::string_view> inputs;
  MessageReader reader(graph, model);
  while (auto field = reader.next()) {
    if (field->wire_type != kLengthDelimited) continue;
    if (field->number == kGraphInitializer)
      initializers.insert(findBytes(field->bytes, kTensorName, model));
    if (field->number == kGraphInput) inputs.push_back(field->bytes);
  }
  for (const auto input : inputs) {
    if (initializers.count(findBytes(input, kValueInfoName, model)) != 0) continue;
    auto dims = dimsOf(input, model);
    if (!dims.empty()) return dims;
  }
  fail("{}: ONNX graph has no tensor input with a shape", model.string());
}

}  // namespace lumaslam::detect
