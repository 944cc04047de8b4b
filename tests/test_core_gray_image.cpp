// toGray takes colour images in OpenCV's BGR(A) order (what cv::imread and the readers give)
// and weights the channels as ITU-R BT.601 luma does: Y = 0.299 R + 0.587 G + 0.114 B. Pure
// blue, green and red pixels tell the channel order apart (a swapped order gives 76 for blue).
#include <gtest/gtest.h>

#include "lumaslam/core/gray_image.h"

namespace lumaslam {
namespace {

int grayOf(const cv::Scalar& colour, int type) {
  const cv::Mat image(4, 4, type, colour);
  const cv::Mat gray = toGray(image);
  EXPECT_EQ(gray.type(), CV_8UC1);
  return gray.at<std::uint8_t>(1, 1);
}

TEST(GrayImage, WeightsBgrChannelsAsBt601Luma) {
  EXPECT_EQ(grayOf({255, 0, 0}, CV_8UC3), 29);   // blue: 0.114 * 255
  EXPECT_EQ(grayOf({0, 255, 0}, CV_8UC3), 150);  // green: 0.587 * 255
  EXPECT_EQ(grayOf({0, 0, 255}, CV_8UC3), 76);   // red: 0.299 * 255
  EXPECT_EQ(grayOf({255, 0, 0, 255}, CV_8UC4), 29);
  EXPECT_EQ(grayOf({0, 0, 255, 0}, CV_8UC4), 76);
}

TEST(GrayImage, GrayIsReturnedAsItIs) {
  const cv::Mat gray(3, 5, CV_8UC1, cv::Scalar(77));
  const cv::Mat same = toGray(gray);
  EXPECT_EQ(same.data, gray.data);
}

}  // namespace
}  // namespace lumaslam
