#include "progress_line.h"

#include <unistd.h>

#include <cstdio>

#include <fmt/format.h>

namespace lumaslam::cli {

std::string progressText(std::string_view unit, std::size_t done, std::size_t total,
                         double elapsed_s, std::string_view state) {
  std::string text =
      total > 0 ? fmt::format("{} {}/{}", unit, done, total) : fmt::format("{} {}", unit, done);
  // A rate from the first fraction of a second would be noise.
  constexpr double kMinElapsedForRate = 0.25;
  const double rate = elapsed_s >= kMinElapsedForRate ? static_cast<double>(done) / elapsed_s : 0.0;
  if (rate > 0.0) text += fmt::format("  {:.1f} fps", rate);
  if (rate > 0.0 && total > done) {
    text += fmt::format("  ETA {:.0f} s", static_cast<double>(total - done) / rate);
  }
  if (!state.empty()) text += fmt::format("  {}", state);
  return text;
}

ProgressLine::ProgressLine(std::string unit, std::size_t total, bool force)
    : unit_(std::move(unit)), total_(total), shown_(force || isatty(STDERR_FILENO) != 0) {}

ProgressLine::~ProgressLine() {
  if (drawn_) std::fprintf(stderr, "\n");
}

void ProgressLine::update(std::size_t done, std::string_view state) {
  if (!shown_ || ended_) return;
  const auto now = std::chrono::steady_clock::now();
  const bool last = total_ > 0 && done >= total_;
  if (drawn_ && !last && now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_draw_ = now;
  drawn_ = true;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  // Clear to the end of the line: the text can get shorter.
  std::fprintf(stderr, "\r%s\033[K", progressText(unit_, done, total_, elapsed, state).c_str());
  if (last) {  // the line is complete: what is printed next starts on a new one
    std::fprintf(stderr, "\n");
    drawn_ = false;
    ended_ = true;
  }
  std::fflush(stderr);
}

}  // namespace lumaslam::cli
