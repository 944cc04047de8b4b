#include "cli_checks.h"

#include <charconv>

#include <fmt/format.h>

namespace lumaslam::cli {

CLI::Validator wholeNumber(long long min, long long max) {
  const auto check = [min, max](std::string& text) -> std::string {
    long long value = 0;
    const char* end = text.data() + text.size();
    const auto [stop, error] = std::from_chars(text.data(), end, value);
    if (error == std::errc{} && stop == end && value >= min && value <= max) return {};
    return fmt::format("expected a whole number from {} to {}, found '{}'", min, max,
                       shortenLongWords(text));
  };
  return CLI::Validator(check, fmt::format("INT in {}..{}", min, max));
}

std::string shortenLongWords(std::string_view message, std::size_t keep) {
  std::string out;
  std::size_t start = 0;
  while (start < message.size()) {
    const bool blank = message[start] == ' ' || message[start] == '\n';
    std::size_t end = start;
    while (end < message.size() && (message[end] == ' ' || message[end] == '\n') == blank) ++end;
    const std::string_view run = message.substr(start, end - start);
    if (!blank && run.size() > keep + 40) {
      out += run.substr(0, keep);
      out += "...";
    } else {
      out += run;
    }
    start = end;
  }
  return out;
}

}  // namespace lumaslam::cli
