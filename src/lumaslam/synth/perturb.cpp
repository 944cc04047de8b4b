#include "lumaslam/synth/perturb.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <mutex>
#include <vector>

#include <spdlog/spdlog.h>
#include <tbb/parallel_for.h>
#include <opencv2/imgcodecs.hpp>

#include "lumaslam/core/error.h"
#include "lumaslam/io/output_file.h"
#include "lumaslam/synth/lighting.h"
#include "lumaslam/synth/random.h"

namespace lumaslam::synth {

namespace fs = std::filesystem;

namespace {

constexpr double kPi = 3.14159265358979323846;

void checkLevel(int level) {
  if (level < 0 || level > 5) fail("perturb: level {} is out of range (expected 0..5)", level);
}

// Photons relative to a nominal frame for the noise models: less light, more noise.
double noiseSignal(int level) {
  return 1.0 / (1.0 + level);
}

// Flash: every 30 frames from frame 15, 3 frames over-exposed, then 30 later 3 frames dark.
double flashFactor(int level, int index) {
  if (index < 15 || (index - 15) % 30 >= 3) return 1.0;
  const bool up = ((index - 15) / 30) % 2 == 0;
  return up ? 1.0 + 0.4 * level : 1.0 / (1.0 + 0.8 * level);
}

double flickerFactor(int level, double time_s) {
  return 1.0 + 0.07 * level * std::sin(2.0 * kPi * 1.7 * time_s);
}

// A soft disc of light (radius 30% of the diagonal) wandering over the image; outside it the
// light falls to 1 - 0.18 * level of normal.
cv::Mat spotlightField(cv::Size size, int level, double time_s) {
  const double outside = 1.0 - 0.18 * level, centre_gain = 1.0 + 0.1 * level;
  const double cx = size.width * (0.5 + 0.3 * std::sin(0.45 * time_s));
  const double cy = size.height * (0.5 + 0.2 * std::sin(0.7 * time_s + 1.0));
  const double radius = 0.3 * std::hypot(size.width, size.height);
  cv::Mat field(size, CV_32F);
  for (int y = 0; y < size.height; ++y) {
    float* row = field.ptr<float>(y);
    for (int x = 0; x < size.width; ++x) {
      const double r = std::hypot(x - cx, y - cy) / radius;
      const double s = std::clamp(1.5 - r, 0.0, 1.0);  // 1 inside 0.5 radius, 0 beyond 1.5
      row[x] = static_cast<float>(outside + (centre_gain - outside) * s * s * (3.0 - 2.0 * s));
    }
  }
  return field;
}

struct ImageJob {
  fs::path source;
  fs::path target;
  int index = 0;
  double time_s = 0.0;
  int camera = 0;
};

// Image files of one camera folder, sorted by name (= by timestamp for TUM and EuRoC).
void addCameraJobs(const fs::path& in_dir, const fs::path& out_dir, int camera, bool nanoseconds,
                   std::vector<ImageJob>& jobs) {
  if (!fs::is_directory(in_dir)) fail("{}: camera image folder is missing", in_dir.string());
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(in_dir))
    if (entry.is_regular_file() && entry.path().extension() == ".png")
      files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  for (size_t i = 0; i < files.size(); ++i) {
    const std::string stem = files[i].stem().string();
    double time_s = 0.0;
    try {
      time_s = nanoseconds ? static_cast<double>(std::stoll(stem)) * 1e-9 : std::stod(stem);
    } catch (const std::exception&) {
      fail("{}: image name is not a timestamp", files[i].string());
    }
    jobs.push_back({files[i], out_dir / files[i].filename(), static_cast<int>(i), time_s, camera});
  }
}

}  // namespace

PerturbModel perturbModelFromName(std::string_view name) {
  if (name == "dark") return PerturbModel::Dark;
  if (name == "flash") return PerturbModel::Flash;
  if (name == "flicker") return PerturbModel::Flicker;
  if (name == "spotlight") return PerturbModel::Spotlight;
  if (name == "noise") return PerturbModel::Noise;
  fail("perturb model '{}' is unknown (expected dark, flash, flicker, spotlight or noise)", name);
}

std::string perturbModelName(PerturbModel model) {
  switch (model) {
    case PerturbModel::Dark:
      return "dark";
    case PerturbModel::Flash:
      return "flash";
    case PerturbModel::Flicker:
      return "flicker";
    case PerturbModel::Spotlight:
      return "spotlight";
    case PerturbModel::Noise:
      return "noise";
  }
  return "?";
}

std::string describePerturbation(PerturbModel model, int level) {
  checkLevel(level);
  const DarkCurve curve = darkCurve(level);
  switch (model) {
    case PerturbModel::Dark:
      return fmt::format(
          "dark level {}: V_out = {} * V_in^{} plus shot+read noise at {:.3f} of the light", level,
          curve.a, curve.inv_gamma, noiseSignal(level));
    case PerturbModel::Flash:
      return fmt::format(
          "flash level {}: from frame 15, every 30 frames 3 frames alternately x{:.2f} and x{:.3f}",
          level, 1.0 + 0.4 * level, 1.0 / (1.0 + 0.8 * level));
    case PerturbModel::Flicker:
      return fmt::format("flicker level {}: gain 1 + {:.2f} * sin(2 pi 1.7 Hz t)", level,
                         0.07 * level);
    case PerturbModel::Spotlight:
      return fmt::format(
          "spotlight level {}: wandering light disc (x{:.1f} at its centre), x{:.2f} outside",
          level, 1.0 + 0.1 * level, 1.0 - 0.18 * level);
    case PerturbModel::Noise:
      return fmt::format(
          "noise level {}: shot+read noise as if {:.3f} of the light, gain compensated", level,
          noiseSignal(level));
  }
  return "?";
}

cv::Mat perturbImage(const cv::Mat& image, PerturbModel model, int level, int index, double time_s,
                     std::uint64_t noise_key) {
  checkLevel(level);
  if (image.empty() || image.depth() != CV_8U || (image.channels() != 1 && image.channels() != 3))
    fail("perturb: expected an 8-bit grey or colour image");
  if (level == 0) return image.clone();
  SensorModel sensor;
  sensor.noise_scale = 0.0;
  double signal = 1.0, gain = 1.0;
  int dark_level = 0;
  cv::Mat field;
  switch (model) {
    case PerturbModel::Dark:
      dark_level = level;
      sensor.noise_scale = 1.0;
      signal = noiseSignal(level);
      gain = 1.0 / signal;
      break;
    case PerturbModel::Flash:
      signal = flashFactor(level, index);
      break;
    case PerturbModel::Flicker:
      signal = flickerFactor(level, time_s);
      break;
    case PerturbModel::Spotlight:
      field = spotlightField(image.size(), level, time_s);
      break;
    case PerturbModel::Noise:
      sensor.noise_scale = 1.0;
      signal = noiseSignal(level);
      gain = 1.0 / signal;
      break;
  }
  return exposeImage(displayToLinear(image), signal, gain, dark_level, sensor, noise_key, field);
}

namespace {

// The perturbed copy is made in OUT.partial and renamed to OUT when every image is written, so
// that an interrupted or failed run never leaves a dataset with half of its images perturbed.
fs::path workFolderFor(const fs::path& out) {
  fs::path work = out;
  work += ".partial";
  return work;
}

void replaceFolder(const fs::path& work, const fs::path& out) {
  std::error_code ec;
  fs::remove_all(out, ec);
  if (ec) fail("{}: cannot replace the earlier output: {}", out.string(), ec.message());
  fs::rename(work, out, ec);
  if (ec) fail("{}: cannot put the perturbed dataset in place: {}", out.string(), ec.message());
}

std::vector<ImageJob> imageJobs(const fs::path& in, const fs::path& out) {
  std::vector<ImageJob> jobs;
  if (fs::exists(in / "rgb.txt")) {
    addCameraJobs(in / "rgb", out / "rgb", 0, false, jobs);
  } else if (fs::is_directory(in / "mav0")) {
    for (int camera = 0; camera < 2; ++camera) {
      const fs::path dir = in / "mav0" / fmt::format("cam{}", camera) / "data";
      if (camera == 1 && !fs::exists(dir)) break;
      addCameraJobs(dir, out / "mav0" / fmt::format("cam{}", camera) / "data", camera, true, jobs);
    }
  } else {
    fail("{}: not a TUM RGB-D folder (rgb.txt) nor an EuRoC folder (mav0/)", in.string());
  }
  if (jobs.empty()) fail("{}: no camera images found", in.string());
  return jobs;
}

void perturbImages(const std::vector<ImageJob>& jobs, PerturbModel model, int level,
                   std::uint64_t seed, const PerturbProgress& on_image) {
  std::mutex progress_mutex;
  std::size_t done = 0;
  tbb::parallel_for(size_t{0}, jobs.size(), [&](size_t i) {
    const ImageJob& job = jobs[i];
    const cv::Mat image = cv::imread(job.source.string(), cv::IMREAD_UNCHANGED);
    if (image.empty()) fail("{}: cannot read image (missing or corrupt)", job.source.string());
    if (image.depth() != CV_8U) fail("{}: expected an 8-bit image", job.source.string());
    cv::Mat input = image;
    if (image.channels() == 4) cv::extractChannel(image, input, 0);  // never in TUM/EuRoC; be safe
    const cv::Mat result = perturbImage(input, model, level, job.index, job.time_s,
                                        hashKey(seed, static_cast<std::uint64_t>(job.camera),
                                                static_cast<std::uint64_t>(job.index)));
    if (!cv::imwrite(job.target.string(), result))
      fail("{}: cannot write image", job.target.string());
    if (on_image) {
      const std::scoped_lock lock(progress_mutex);
      on_image(++done, jobs.size());
    }
  });
}

}  // namespace

int perturbDataset(const fs::path& in, const fs::path& out, PerturbModel model, int level,
                   std::uint64_t seed, const PerturbProgress& on_image) {
  checkLevel(level);
  if (!fs::is_directory(in)) fail("{}: input dataset folder does not exist", in.string());
  std::error_code ec;
  if (fs::exists(out) && fs::equivalent(in, out, ec))
    fail("{}: output must differ from the input", out.string());
  const fs::path work = workFolderFor(out);
  const std::vector<ImageJob> jobs = imageJobs(in, work);

  fs::remove_all(work, ec);
  fs::create_directories(work, ec);
  if (ec) fail("{}: cannot create directory: {}", work.string(), ec.message());
  fs::copy(in, work, fs::copy_options::recursive | fs::copy_options::overwrite_existing, ec);
  if (ec) fail("{}: cannot copy the dataset to {}: {}", in.string(), work.string(), ec.message());

  try {
    perturbImages(jobs, model, level, seed, on_image);
    io::OutputFile note(work / "perturbation.txt");
    note.stream() << "# lumaslam perturb of " << in.string() << "\n"
                  << describePerturbation(model, level) << "\nseed " << seed << "\n";
    note.commit();
  } catch (...) {
    fs::remove_all(work, ec);
    throw;
  }
  replaceFolder(work, out);
  spdlog::info("perturb: {} images of {} -> {} ({})", jobs.size(), in.string(), out.string(),
               describePerturbation(model, level));
  return static_cast<int>(jobs.size());
}

}  // namespace lumaslam::synth
