// Feeds an RGB-D sequence to lumaslam frame by frame, as a camera driver would, and prints
// how many frames were tracked and the ATE against the sequence's ground truth.
//   track_rgbd SETTINGS.yaml tum:DATASET_FOLDER
#include <cstdio>
#include <exception>

#include <lumaslam/dataset.h>
#include <lumaslam/evaluate.h>
#include <lumaslam/system.h>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s SETTINGS.yaml tum:DATASET_FOLDER\n", argv[0]);
    return 2;
  }
  try {
    lumaslam::System slam(argv[1]);
    lumaslam::Dataset dataset(argv[2]);
    int tracked = 0;
    while (auto frame = dataset.next()) {
      const auto result = slam.trackRgbd(frame->image, frame->depth, frame->timestamp);
      if (result.state == lumaslam::TrackState::Tracking) ++tracked;
    }
    slam.shutdown();
    std::printf("tracked %d of %zu frames, %zu keyframes\n", tracked, slam.frameCount(),
                slam.keyframeCount());
    if (const auto truth = dataset.groundTruth(); !truth.empty()) {
      const auto errors = lumaslam::evaluate(slam.trajectory(), truth);
      std::printf("ATE %.4f m over %zu poses\n", errors.ate.rmse, errors.ate.count);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "track_rgbd: %s\n", e.what());
    return 1;
  }
  return 0;
}
