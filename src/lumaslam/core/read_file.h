#pragma once
#include <filesystem>
#include <string>
#include <string_view>

namespace lumaslam::core {

// The whole file as bytes; throws Error "FILE: cannot open WHAT" / "FILE: cannot read WHAT"
// (what: e.g. "map file").
std::string readWholeFile(const std::filesystem::path& file, std::string_view what);

}  // namespace lumaslam::core
