#include "lumaslam/io/text_lines.h"

#include <charconv>
#include <cmath>
#include <fstream>

#include "lumaslam/core/error.h"

namespace lumaslam::io {

namespace {
constexpr std::string_view kWhitespace = " \t\r\n\v\f";

std::string_view trim(std::string_view text) {
  const auto begin = text.find_first_not_of(kWhitespace);
  if (begin == std::string_view::npos) return {};
  const auto end = text.find_last_not_of(kWhitespace);
  return text.substr(begin, end - begin + 1);
}

[[noreturn]] void badNumber(std::string_view token, const std::filesystem::path& file,
                            const TextLine& line) {
  fail("{}:{}: bad number '{}' in '{}'", file.string(), line.number, token, line.text);
}
}  // namespace

std::vector<TextLine> readDataLines(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) fail("{}: file not found", file.string());
  std::ifstream stream(file);
  if (!stream) fail("{}: cannot open file", file.string());
  std::vector<TextLine> lines;
  std::string raw;
  for (std::size_t number = 1; std::getline(stream, raw); ++number) {
    const std::string_view text = trim(raw);
    if (text.empty() || text.front() == '#') continue;
    lines.push_back({number, std::string(text)});
  }
  if (stream.bad()) fail("{}: read error", file.string());
  return lines;
}

std::vector<std::string_view> splitFields(std::string_view text, std::string_view separators) {
  std::vector<std::string_view> fields;
  const bool comma_separated = separators.find(',') != std::string_view::npos;
  std::size_t position = 0;
  while (position <= text.size()) {
    const auto end = std::min(text.find_first_of(separators, position), text.size());
    const std::string_view field = trim(text.substr(position, end - position));
    // Whitespace runs collapse; with commas, an empty field between two commas is kept.
    if (!field.empty() || (comma_separated && end < text.size() && text[end] == ','))
      fields.push_back(field);
    position = end + 1;
  }
  return fields;
}

double parseNumber(std::string_view token, const std::filesystem::path& file,
                   const TextLine& line) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  double value = 0.0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (token.empty() || error != std::errc() || end != token.data() + token.size() ||
      !std::isfinite(value))
    badNumber(token, file, line);
  return value;
}

std::int64_t parseNanoseconds(std::string_view token, const std::filesystem::path& file,
                              const TextLine& line) {
  const auto dot = token.find('.');
  const std::string_view integer_part = token.substr(0, dot);
  std::int64_t nanoseconds = 0;
  const auto [end, error] =
      std::from_chars(integer_part.data(), integer_part.data() + integer_part.size(), nanoseconds);
  if (integer_part.empty() || error != std::errc() ||
      end != integer_part.data() + integer_part.size() || nanoseconds < 0)
    badNumber(token, file, line);
  if (dot != std::string_view::npos) {
    const std::string_view fraction = token.substr(dot + 1);
    if (fraction.find_first_not_of("0123456789") != std::string_view::npos)
      badNumber(token, file, line);
  }
  return nanoseconds;
}

double parseNanosecondsAsSeconds(std::string_view token, const std::filesystem::path& file,
                                 const TextLine& line) {
  return nanosecondsToSeconds(parseNanoseconds(token, file, line));
}

double nanosecondsToSeconds(std::int64_t nanoseconds) {
  // long double holds every int64 exactly, so only the final conversion rounds.
  return static_cast<double>(static_cast<long double>(nanoseconds) / 1e9L);
}

std::int64_t secondsToNanoseconds(double seconds) {
  return std::llround(static_cast<long double>(seconds) * 1e9L);
}

}  // namespace lumaslam::io
