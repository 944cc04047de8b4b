#include "report_frames.h"

#include <algorithm>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/core/gray_image.h"
#include "lumaslam/enhance/enhancer.h"
#include "lumaslam/feature/orb_extractor.h"
#include "lumaslam/io/dataset_reader.h"
#include "lumaslam/io/settings.h"
#include "report_extraction_mask.h"
#include "report_frame_marks.h"
#include "report_tracked_image.h"

namespace lumaslam::cli {
namespace {

constexpr int kMaxWidth = 480;

struct Pick {
  std::string role;
  std::size_t index = 0;
  std::optional<std::size_t> previous;  // the frame tracked before it (timing.csv's row above)
};

// First, middle and last tracked frame (timing.csv "state" ok); without any tracked frame,
// the first and last frame read. Duplicates (a short run) are dropped.
std::vector<Pick> pickFrames(const TimingTable& timing) {
  const auto indices = timing.numbers("frame");
  const auto states = timing.texts("state");
  std::vector<Pick> tracked;
  const auto pick = [&](std::size_t row) {
    tracked.push_back(
        {"", static_cast<std::size_t>(indices[row]),
         row > 0 ? std::optional(static_cast<std::size_t>(indices[row - 1])) : std::nullopt});
  };
  for (std::size_t row = 0; row < indices.size(); ++row) {
    if (states[row] == "ok") pick(row);
  }
  const bool any = !tracked.empty();
  if (!any) {
    for (std::size_t row = 0; row < indices.size(); ++row) pick(row);
  }
  if (tracked.empty()) return {};
  const auto named = [](Pick pick, const char* role) {
    pick.role = role;
    return pick;
  };
  std::vector<Pick> picks = {
      named(tracked.front(), any ? "first tracked" : "first (none tracked)")};
  if (any) picks.push_back(named(tracked[tracked.size() / 2], "middle tracked"));
  picks.push_back(named(tracked.back(), any ? "last tracked" : "last (none tracked)"));
  std::vector<Pick> unique;
  for (const Pick& pick : picks) {
    const bool seen = std::any_of(unique.begin(), unique.end(),
                                  [&](const Pick& p) { return p.index == pick.index; });
    if (!seen) unique.push_back(pick);
  }
  return unique;
}

// As the pipeline chooses: the preset `run --enhance` gave (summary "enhance_preset") on its
// own, else Enhancement.* of the settings.
enhance::EnhancerParams enhancerParams(const nlohmann::json& summary,
                                       const io::Settings& settings) {
  if (summary.contains("enhance_preset") && summary["enhance_preset"].is_string()) {
    return enhance::EnhancerParams::forPreset(summary["enhance_preset"].get<std::string>());
  }
  return settings.file ? enhance::EnhancerParams::fromSettings(*settings.file)
                       : enhance::EnhancerParams{};
}

io::FrameData readFrame(const std::string& dataset, std::size_t index) {
  io::ReaderOptions options;
  options.first_frame = index;
  options.max_frames = 1;
  auto frame = io::openDataset(dataset, options)->next();
  if (!frame) fail("{}: frame {} not found", dataset, index);
  return std::move(*frame);
}

// The gray image tracking extracts ORB from, and its colour version to draw on.
std::pair<cv::Mat, cv::Mat> asTracked(const cv::Mat& image, const enhance::EnhancerParams& params) {
  if (params.preset == "off") return {toGray(image), image};
  enhance::Enhancer enhancer(params);  // fresh: the run's online statistics are not kept
  auto enhanced = enhancer.enhance(image);
  return {enhanced.gray, enhanced.colour};
}

// The run's moving_features.txt, or why nothing is marked (in `samples`).
std::optional<MovingFeatures> readMarks(const std::filesystem::path& run_dir,
                                        SampleFrames& samples) {
  try {
    auto marks = readMovingFeatures(run_dir / kMovingFeaturesFile);
    if (!marks) {
      samples.unmarked = fmt::format("the run folder has no {} (a run from before it was written)",
                                     kMovingFeaturesFile);
    }
    return marks;
  } catch (const std::exception& e) {
    samples.unmarked = e.what();
    samples.marks_broken = true;
    return std::nullopt;
  }
}

const FrameMarks* marksOf(const std::optional<MovingFeatures>& marks, std::size_t index) {
  if (!marks) return nullptr;
  const auto it = marks->frames.find(index);
  return it == marks->frames.end() ? nullptr : &it->second;
}

SampleFrame::Marked countsOf(const FrameMarks& marks) {
  const std::size_t dropped = marks.dropped.size() + marks.moving.size();
  return {marks.features - dropped, marks.dropped.size(), marks.moving.size(), marks.boxes.size()};
}

// What the sample frames are made with.
struct Sampling {
  std::string dataset;
  io::Settings settings;
  enhance::EnhancerParams params;
  feature::OrbExtractor extractor;
  TrackedImage tracked_image;
  std::optional<MovingFeatures> marks;
};

// The run took no feature where the previous frame's dynamic mask was
// (report_extraction_mask.h); empty without marks of that frame.
cv::Mat extractionMaskOf(const Pick& pick, const Sampling& sampling, cv::Size image_size) {
  const FrameMarks* previous = pick.previous ? marksOf(sampling.marks, *pick.previous) : nullptr;
  if (!previous || previous->boxes.empty()) return {};
  return previousDynamicMask(*previous, readFrame(sampling.dataset, *pick.previous),
                             sampling.settings, sampling.marks->image, image_size);
}

SampleFrame sampleFrame(const Pick& pick, const Sampling& sampling) {
  const io::FrameData frame = readFrame(sampling.dataset, pick.index);
  const cv::Mat image = sampling.tracked_image.of(frame.image);
  const auto [gray, colour] = asTracked(image, sampling.params);
  const auto keypoints =
      sampling.extractor.extract(gray, extractionMaskOf(pick, sampling, gray.size())).keypoints;
  const auto& marks = sampling.marks;
  const FrameMarks* frame_marks = marksOf(marks, frame.index);
  const cv::Size marks_image = marks ? marks->image : cv::Size();
  const DrawnFrame drawn = drawFrameMarks(colour, keypoints, frame_marks, marks_image, kMaxWidth);
  SampleFrame sample{pick.role,
                     frame.index,
                     frame.timestamp,
                     jpegDataUri(image, kMaxWidth),
                     jpegDataUri(drawn.canvas),
                     keypoints.size(),
                     drawn.green,
                     std::nullopt};
  if (frame_marks) sample.marked = countsOf(*frame_marks);
  return sample;
}

std::string base64(const std::vector<uchar>& bytes) {
  static constexpr char kDigits[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string text;
  text.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t block = bytes[i] << 16;
    if (n > 1) block |= bytes[i + 1] << 8;
    if (n > 2) block |= bytes[i + 2];
    for (std::size_t k = 0; k < 4; ++k) {
      text += k <= n ? kDigits[(block >> (18 - 6 * k)) & 63] : '=';
    }
  }
  return text;
}

}  // namespace

std::string jpegDataUri(const cv::Mat& image, int max_width) {
  cv::Mat scaled = image;
  if (image.cols > max_width) {
    const double scale = static_cast<double>(max_width) / image.cols;
    cv::resize(image, scaled, cv::Size(), scale, scale, cv::INTER_AREA);
  }
  if (scaled.depth() != CV_8U) scaled.convertTo(scaled, CV_8U);
  std::vector<uchar> bytes;
  if (!cv::imencode(".jpg", scaled, bytes, {cv::IMWRITE_JPEG_QUALITY, 85})) {
    fail("cannot encode a {}x{} image as JPEG", scaled.cols, scaled.rows);
  }
  return "data:image/jpeg;base64," + base64(bytes);
}

SampleFrames loadSampleFrames(const std::filesystem::path& run_dir, const nlohmann::json& summary,
                              const TimingTable& timing) {
  SampleFrames samples;
  auto marks = readMarks(run_dir, samples);
  try {
    auto settings = io::loadSettings(summary.at("settings").get<std::string>());
    auto params = enhancerParams(summary, settings);
    samples.enhancement = params.preset;
    TrackedImage tracked_image(settings);
    samples.geometry = tracked_image.description();
    const feature::OrbExtractor extractor(settings.file
                                              ? feature::OrbSettings::fromSettings(*settings.file)
                                              : feature::OrbSettings{});
    const Sampling sampling{summary.at("dataset").get<std::string>(),
                            std::move(settings),
                            std::move(params),
                            extractor,
                            std::move(tracked_image),
                            std::move(marks)};
    for (const Pick& pick : pickFrames(timing)) {
      samples.frames.push_back(sampleFrame(pick, sampling));
    }
  } catch (const std::exception& e) {
    samples.problem = e.what();
  }
  return samples;
}

}  // namespace lumaslam::cli
