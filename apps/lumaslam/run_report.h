#pragma once
// `lumaslam report`: one self-contained HTML file (inline SVG and JPEG, no script, nothing
// fetched) showing what `lumaslam run` wrote into a folder (docs/report.md).
#include <filesystem>

namespace lumaslam::cli {

// The report of the run in `run_dir`, written to `out` (io::OutputFile). Throws Error naming
// the folder or summary.json when there is no readable run; a dataset that cannot be read
// again only costs the sample frames and plots, said so in the report.
void writeRunReport(const std::filesystem::path& run_dir, const std::filesystem::path& out);

// A `run --repeat` folder: each run_K gets its own run_K/report.html, and `out` holds the
// table across runs (repeatability.json) linking to them.
void writeRepeatReport(const std::filesystem::path& dir, const std::filesystem::path& out);

// One of the two, by what `dir` holds (isRepeatFolder).
void writeReport(const std::filesystem::path& dir, const std::filesystem::path& out);

}  // namespace lumaslam::cli
