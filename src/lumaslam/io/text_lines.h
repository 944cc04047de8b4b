#pragma once
// Line-oriented text files (trajectories, TUM/EuRoC/KITTI lists): read the data lines of a
// file and parse their fields, with errors that name file, line number and text.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace lumaslam::io {

struct TextLine {
  std::size_t number = 0;  // 1-based line number in the file
  std::string text;        // without trailing '\r' / whitespace
};

// Every non-empty line not starting with '#' (after leading whitespace). Throws Error if the
// file is missing or unreadable.
std::vector<TextLine> readDataLines(const std::filesystem::path& file);

// Fields separated by any of `separators` (runs of whitespace count as one separator; with
// ',' each comma separates, and spaces around fields are trimmed).
std::vector<std::string_view> splitFields(std::string_view text, std::string_view separators);

// A finite double; throws "FILE:LINE: bad number 'TOKEN' in 'TEXT'".
double parseNumber(std::string_view token, const std::filesystem::path& file, const TextLine& line);

// An integer nanosecond timestamp, optionally written with a fractional part
// ("1403715274312143104.0000000000" as in ORB-SLAM3's files); returns seconds.
std::int64_t parseNanoseconds(std::string_view token, const std::filesystem::path& file,
                              const TextLine& line);
double parseNanosecondsAsSeconds(std::string_view token, const std::filesystem::path& file,
                                 const TextLine& line);
double nanosecondsToSeconds(std::int64_t nanoseconds);
std::int64_t secondsToNanoseconds(double seconds);

}  // namespace lumaslam::io
