#include "run_manifest.h"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "lumaslam/io/output_file.h"

namespace lumaslam::cli {

namespace fs = std::filesystem;

namespace {

constexpr const char* kManifest = "manifest.json";

nlohmann::json fileEntry(const fs::path& file, const std::string& name) {
  std::error_code ec;
  const auto bytes = fs::file_size(file, ec);
  return {{"name", name}, {"bytes", ec ? 0 : bytes}};
}

std::vector<std::string> resultFilesIn(const fs::path& out) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(out, ec)) {
    const std::string name = entry.path().filename().string();
    if (!entry.is_regular_file(ec) || name == kManifest || entry.path().extension() == ".partial") {
      continue;
    }
    names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

void writeRunManifest(const fs::path& out, const std::string& status,
                      const std::vector<fs::path>& extra_files,
                      const std::vector<std::string>& errors) {
  nlohmann::json files = nlohmann::json::array();
  for (const auto& name : resultFilesIn(out)) files.push_back(fileEntry(out / name, name));
  for (const auto& file : extra_files) files.push_back(fileEntry(file, file.string()));
  const nlohmann::json manifest = {{"status", status}, {"files", files}, {"errors", errors}};
  io::OutputFile file(out / kManifest);
  file.stream() << manifest.dump(2) << '\n';
  file.commit();
}

}  // namespace lumaslam::cli
