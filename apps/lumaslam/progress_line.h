#pragma once
// A one-line progress display for long work (`run`, `synth`): frames done, rate, ETA and a
// state word, redrawn in place on a terminal (stderr) and silent in pipes, files and CI.
#include <chrono>
#include <cstddef>
#include <string>
#include <string_view>

namespace lumaslam::cli {

// "frame 120/497  41.2 fps  ETA 9 s  ok" (total 0: unknown, no ETA).
std::string progressText(std::string_view unit, std::size_t done, std::size_t total,
                         double elapsed_s, std::string_view state);

class ProgressLine {
 public:
  // Shown only when stderr is a terminal (or `force`, for tests).
  explicit ProgressLine(std::string unit, std::size_t total = 0, bool force = false);
  ~ProgressLine();  // ends the line
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  // Redraws at most 10 times a second; the last item (done == total) ends the line.
  void update(std::size_t done, std::string_view state = {});
  bool shown() const { return shown_; }

 private:
  const std::string unit_;
  const std::size_t total_;
  const bool shown_;
  const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::chrono::steady_clock::time_point last_draw_{};
  bool drawn_ = false;  // a line is on the terminal, not yet ended
  bool ended_ = false;  // the last item was drawn and the line ended
};

}  // namespace lumaslam::cli
