#pragma once
// Graceful stop on SIGINT / SIGTERM for the long-running commands: while a StopOnSignal
// lives, the first signal only sets a flag that the frame loop polls (the command then writes
// what it has, marked partial, and exits 128 + signal); a second signal exits at once.
#include <csignal>

namespace lumaslam::cli {

class StopOnSignal {
 public:
  StopOnSignal();  // installs the handlers (the previous ones come back on destruction)
  ~StopOnSignal();
  StopOnSignal(const StopOnSignal&) = delete;
  StopOnSignal& operator=(const StopOnSignal&) = delete;

  bool requested() const;
  int signal() const;    // the signal received, 0 for none
  int exitCode() const;  // 128 + signal (130 for SIGINT, 143 for SIGTERM)
  const char* name() const;

 private:
  struct sigaction previous_int_ {};
  struct sigaction previous_term_ {};
};

}  // namespace lumaslam::cli
