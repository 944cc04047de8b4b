#include "report_tracked_image.h"

#include <opencv2/imgproc.hpp>

#include "lumaslam/camera/stereo_rectifier.h"

namespace lumaslam::cli {
namespace {

// As Pipeline::setUpStereoRectification decides: a stereo pair with Camera2.*.
std::unique_ptr<camera::StereoRectifier> rectifierOf(const io::Settings& settings) {
  const bool unrectified_pair =
      settings.sensor == io::SensorType::Stereo && settings.stereo && settings.stereo->right;
  if (!unrectified_pair) return nullptr;
  return std::make_unique<camera::StereoRectifier>(
      camera::StereoRectifier::fromSettings(settings.camera, *settings.stereo, settings.origin()));
}

}  // namespace

TrackedImage::TrackedImage(const io::Settings& settings)
    : calibrated_(settings.camera.size.width, settings.camera.size.height),
      rectifier_(rectifierOf(settings)) {
  if (settings.camera.resizeTo) {
    working_ = cv::Size(settings.camera.resizeTo->width, settings.camera.resizeTo->height);
  }
}

TrackedImage::~TrackedImage() = default;
TrackedImage::TrackedImage(TrackedImage&&) noexcept = default;
TrackedImage& TrackedImage::operator=(TrackedImage&&) noexcept = default;

cv::Mat TrackedImage::of(const cv::Mat& as_read) const {
  cv::Mat image = as_read;
  // Like the Pipeline's resize: only an image of the calibrated size (another size is the
  // run's error to name, not the report's).
  if (!working_.empty() && image.size() == calibrated_) {
    cv::resize(as_read, image, working_, 0.0, 0.0, cv::INTER_LINEAR);
  }
  return rectifier_ ? rectifier_->rectifyLeft(image) : image;
}

std::string TrackedImage::description() const {
  std::string text;
  if (!working_.empty()) {
    text = "resized to " + std::to_string(working_.width) + "x" + std::to_string(working_.height);
  }
  if (rectifier_) text += text.empty() ? "rectified" : ", rectified";
  return text;
}

}  // namespace lumaslam::cli
