#pragma once
// Length fields of map files, bounded by the bytes left in the payload. cereal's own
// std::vector / std::string loads resize to whatever count the file claims, so a few bad bytes
// made a 2 KB file allocate gigabytes before the read failed. sized() writes exactly the bytes
// cereal's own serialization writes (size tag, then the elements), so files stay compatible.
#include <cstddef>
#include <cstdint>
#include <istream>
#include <sstream>
#include <type_traits>

#include <spdlog/fmt/fmt.h>
#include <cereal/archives/portable_binary.hpp>
#include <cereal/cereal.hpp>

namespace lumaslam::map {

// The archive map files are read with: it knows how many bytes of the payload are left.
class BoundedInputArchive : public cereal::PortableBinaryInputArchive {
 public:
  BoundedInputArchive(std::istream& in, std::uint64_t size)
      : cereal::PortableBinaryInputArchive(in), in_(in), size_(size) {}

  std::uint64_t bytesLeft() const {
    const auto position = in_.tellg();
    if (position < 0) return 0;
    const auto read = static_cast<std::uint64_t>(position);
    return read < size_ ? size_ - read : 0;
  }

 private:
  std::istream& in_;
  std::uint64_t size_;
};

// The fewest bytes one T takes in a file: an empty T{} (every vector a bare size tag).
template <typename T>
std::size_t minimumSerializedBytes() {
  if constexpr (std::is_arithmetic_v<T>) {
    return sizeof(T);
  } else {
    static const std::size_t bytes = [] {
      std::ostringstream out(std::ios::binary);
      {
        cereal::PortableBinaryOutputArchive archive(out);
        T value{};
        archive(value);
      }
      const std::size_t endianness_byte = 1;  // written by the archive itself
      return std::max<std::size_t>(1, out.str().size() - endianness_byte);
    }();
    return bytes;
  }
}

template <typename Container>  // std::vector or std::string
struct Sized {
  Container& value;

  template <class Archive>
  void save(Archive& archive) const {
    archive(cereal::make_size_tag(static_cast<cereal::size_type>(value.size())));
    using Element = typename Container::value_type;
    if constexpr (std::is_arithmetic_v<Element>) {
      archive(cereal::binary_data(value.data(), value.size() * sizeof(Element)));
    } else {
      for (const auto& element : value) archive(element);
    }
  }

  template <class Archive>
  void load(Archive& archive) {
    cereal::size_type count = 0;
    archive(cereal::make_size_tag(count));
    using Element = typename Container::value_type;
    // cereal hands serializers its own archive type; the object is the BoundedInputArchive.
    const auto* bounded = dynamic_cast<const BoundedInputArchive*>(&archive);
    if (bounded == nullptr)
      throw cereal::Exception("map records are read with BoundedInputArchive");
    const std::uint64_t left = bounded->bytesLeft();
    if (count > left / minimumSerializedBytes<Element>()) {
      throw cereal::Exception(
          fmt::format("a length field says {} entries where only {} bytes are left", count, left));
    }
    value.resize(static_cast<std::size_t>(count));
    if constexpr (std::is_arithmetic_v<Element>) {
      archive(cereal::binary_data(value.data(), value.size() * sizeof(Element)));
    } else {
      for (auto& element : value) archive(element);
    }
  }
};

template <typename Container>
Sized<Container> sized(Container& value) {
  return {value};
}

}  // namespace lumaslam::map
