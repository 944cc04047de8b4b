#pragma once
// Option checks with messages in words, and the shortening of what errors echo back.
#include <cstddef>
#include <string>
#include <string_view>

#include <CLI/CLI.hpp>

namespace lumaslam::cli {

// Accepts a plain whole number in [min, max]: "-1", "1e20" or "1.5" give "--NAME: expected a
// whole number from MIN to MAX, found '1e20'" (CLI::Range would print float bounds, or
// nothing useful once the value does not fit the option's type).
CLI::Validator wholeNumber(long long min, long long max);

// `message` with every run of non-blank characters longer than `keep` + 40 cut to its first
// `keep` characters and "...": a 1 MB file name in an error is not echoed whole.
std::string shortenLongWords(std::string_view message, std::size_t keep = 200);

}  // namespace lumaslam::cli
