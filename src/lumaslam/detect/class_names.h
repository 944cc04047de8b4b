#pragma once
// Class-name lists (one name per line, line i = class id i, as in coco80.names).
#include <filesystem>
#include <string>
#include <vector>

namespace lumaslam::detect {

// Throws Error naming the file when it is missing or holds no name.
std::vector<std::string> readClassNames(const std::filesystem::path& file);

// Ids of `wanted` in `names`, sorted; throws Error naming `origin` and the unknown class.
std::vector<int> classIds(const std::vector<std::string>& names,
                          const std::vector<std::string>& wanted, const std::string& origin);

}  // namespace lumaslam::detect
