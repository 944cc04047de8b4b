#pragma once
// The contract of every parser under fuzzing: it returns, or rejects the input with
// lumaslam::Error. Anything else (another exception, a crash, a sanitizer report) escapes and
// is a finding.
#include <cstdlib>
#include <iostream>

#include "lumaslam/core/error.h"

namespace lumaslam::fuzz {

// Runs parse(); an Error is an accepted outcome, printed when LUMASLAM_FUZZ_VERBOSE is set
// (to check that a seed is accepted rather than rejected early).
template <typename Parse>
void parseOrReject(Parse&& parse) {
  try {
    parse();
    if (std::getenv("LUMASLAM_FUZZ_VERBOSE")) std::cerr << "accepted\n";
  } catch (const Error& e) {
    if (std::getenv("LUMASLAM_FUZZ_VERBOSE")) std::cerr << "rejected: " << e.what() << '\n';
  }
}

}  // namespace lumaslam::fuzz
