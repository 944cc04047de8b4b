#include "stop_signal.h"

#include <unistd.h>

namespace lumaslam::cli {
namespace {

volatile std::sig_atomic_t received = 0;

extern "C" void onStopSignal(int signal_number) {
  if (received != 0) _exit(128 + signal_number);  // the second signal: stop now
  received = signal_number;
}

}  // namespace

StopOnSignal::StopOnSignal() {
  received = 0;
  struct sigaction action {};
  action.sa_handler = onStopSignal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, &previous_int_);
  sigaction(SIGTERM, &action, &previous_term_);
}

StopOnSignal::~StopOnSignal() {
  sigaction(SIGINT, &previous_int_, nullptr);
  sigaction(SIGTERM, &previous_term_, nullptr);
}

bool StopOnSignal::requested() const {
  return received != 0;
}

int StopOnSignal::signal() const {
  return received;
}

int StopOnSignal::exitCode() const {
  return received == 0 ? 0 : 128 + received;
}

const char* StopOnSignal::name() const {
  return received == SIGINT ? "SIGINT" : received == SIGTERM ? "SIGTERM" : "none";
}

}  // namespace lumaslam::cli
