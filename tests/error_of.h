#pragma once
// The message of the lumaslam::Error that `action` throws; a test failure if it throws none.
#include <string>

#include <gtest/gtest.h>

#include "lumaslam/core/error.h"

namespace lumaslam::test {

template <typename Action>
std::string errorOf(Action&& action) {
  try {
    action();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected lumaslam::Error";
  return {};
}

}  // namespace lumaslam::test
