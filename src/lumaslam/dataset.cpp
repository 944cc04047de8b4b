#include "lumaslam/dataset.h"

#include "lumaslam/camera_pose_conversion.h"
#include "lumaslam/io/dataset_reader.h"

namespace lumaslam {

struct Dataset::Impl {
  std::unique_ptr<io::DatasetReader> reader;
};

namespace {

io::ReaderOptions readerOptions(std::optional<std::size_t> max_frames) {
  io::ReaderOptions options;
  options.max_frames = max_frames;
  return options;
}

}  // namespace

Dataset::Dataset(const std::string& spec, std::optional<std::size_t> max_frames)
    : impl_(std::make_unique<Impl>(Impl{io::openDataset(spec, readerOptions(max_frames))})) {}

Dataset::~Dataset() = default;
Dataset::Dataset(Dataset&&) noexcept = default;
Dataset& Dataset::operator=(Dataset&&) noexcept = default;

std::optional<DatasetFrame> Dataset::next() {
  auto frame = impl_->reader->next();
  if (!frame) return std::nullopt;
  return DatasetFrame{frame->index, frame->timestamp, std::move(frame->image),
                      std::move(frame->right), std::move(frame->depth)};
}

std::size_t Dataset::size() const {
  return impl_->reader->size();
}
std::string Dataset::name() const {
  return impl_->reader->name();
}
bool Dataset::isStereo() const {
  return impl_->reader->isStereo();
}
bool Dataset::hasDepth() const {
  return impl_->reader->hasDepth();
}
CameraTrajectory Dataset::groundTruth() const {
  return toCameraTrajectory(impl_->reader->groundTruth());
}

}  // namespace lumaslam
