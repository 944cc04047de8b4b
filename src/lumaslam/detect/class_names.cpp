#include "lumaslam/detect/class_names.h"

#include <algorithm>
#include <fstream>

#include "lumaslam/core/error.h"

namespace lumaslam::detect {

std::vector<std::string> readClassNames(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) fail("{}: cannot open class-name file", file.string());
  std::vector<std::string> names;
  std::string line;
  while (std::getline(in, line)) {
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    names.push_back(line);
  }
  while (!names.empty() && names.back().empty()) names.pop_back();
  if (names.empty()) fail("{}: class-name file holds no name", file.string());
  return names;
}

std::vector<int> classIds(const std::vector<std::string>& names,
                          const std::vector<std::string>& wanted, const std::string& origin) {
  std::vector<int> ids;
  for (const auto& name : wanted) {
    const auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end()) fail("{}: unknown class '{}'", origin, name);
    ids.push_back(static_cast<int>(it - names.begin()));
  }
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  return ids;
}

}  // namespace lumaslam::detect
