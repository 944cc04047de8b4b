#pragma once
// RunOptions as the `lumaslam run` command line that gives them back: `run`'s own CLI parses
// the words of runArguments(o) into RunOptions equal to o (`lumaslam run ... --print-command`
// prints that line, which is how the round trip is tested). Used by `lumaslam experiment
// --emit` to write one job per run (docs/experiments.md).
#include <filesystem>
#include <string>
#include <vector>

#include "run_pipeline.h"

namespace lumaslam::cli {

// The words after `lumaslam run`; options at their default are left out.
std::vector<std::string> runArguments(const RunOptions& options);

// `word` as sh reads it back unchanged: as is when it holds only safe characters, else in
// single quotes.
std::string shellQuote(const std::string& word);

// The words quoted one by one and joined by spaces: one line for sh.
std::string shellCommandLine(const std::vector<std::string>& words);

// The absolute path of the running lumaslam binary (/proc/self/exe).
std::filesystem::path thisExecutable();

// shellCommandLine of thisExecutable() run runArguments(options).
std::string runCommandLine(const RunOptions& options);

}  // namespace lumaslam::cli
