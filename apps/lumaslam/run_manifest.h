#pragma once
// manifest.json, the last file `lumaslam run` writes (docs/results.md): every result file of
// the run with its size, and the run's status. A folder without it holds no finished run (the
// run failed or was killed before its results were all written).
#include <filesystem>
#include <string>
#include <vector>

namespace lumaslam::cli {

// Lists the regular files in `out` (not *.partial) and `extra_files` (e.g. a map file saved
// elsewhere); `status` as summary.json says it; `errors` (may be empty) say what failed.
void writeRunManifest(const std::filesystem::path& out, const std::string& status,
                      const std::vector<std::filesystem::path>& extra_files,
                      const std::vector<std::string>& errors);

}  // namespace lumaslam::cli
