#include <gtest/gtest.h>

#include "lumaslam/feature/hamming.h"

TEST(FeatureMatchers, Placeholder) {
  SUCCEED();
}
