#pragma once
// Every parameter of the multi-level enhancement (paper section 3.1), its presets and the
// `Enhancement.*` settings keys that override them.
#include <string>
#include <vector>

#include "lumaslam/core/settings_file.h"

namespace lumaslam::enhance {

// Which weight goes with which exponent in Eq. 4.
enum class CompensationWeights {
  kPaper,    // L' = Lmean * L^alpha + (1 - Lmean) * L^beta (as printed)
  kSwapped,  // L' = (1 - Lmean) * L^alpha + Lmean * L^beta (dark images get the lift)
};

// The single channel that is compensated and equalised; colour is rebuilt from it.
enum class WorkChannel {
  kGray,   // luma (cv::COLOR_BGR2GRAY)
  kValue,  // HSV value V = max(R, G, B) (Eq. 5-8)
};

enum class ClipLimitMode {
  kFixed,   // one limit for every frame (classic CLAHE)
  kGlobal,  // Eq. 11 from whole-image sigma and d
  kLocal,   // Eq. 11 from each tile's own sigma and d
};

enum class SigmaSource {
  kIntensity,  // std of intensity (Eq. 12 as printed)
  kGradient,   // std of the Sobel gradient magnitude (what the text says)
};

enum class MaximaSource {
  kFixed,   // sigma_max / d_max as given (settings or `enhance --calibrate`)
  kOnline,  // running maxima over the frames seen, seeded with sigma_max / d_max
};

// How the two images of a stereo pair are enhanced.
enum class StereoMapping {
  kIndependent,  // each image its own plan (gate, table, limit): brightness may differ
  kDecisions,    // the left image's decisions (gate, Eq. 4 table, CLAHE limits) for both,
                 // CLAHE tables from each image's own histograms
  kShared,       // the left image's whole plan (tables too) applied to both
};

struct QualityGateParams {
  bool enabled = true;  // false: every frame counts as Q = 1 (needs compensation)
  double epsilon = 0.12;
  double theta = 0.22;
};

struct CompensationParams {
  bool enabled = true;
  double alpha = 0.2;
  double beta = 1.2;
  CompensationWeights weights = CompensationWeights::kPaper;
};

struct ClaheParams {
  bool enabled = true;
  int tiles_x = 8;
  int tiles_y = 8;
  ClipLimitMode limit_mode = ClipLimitMode::kGlobal;
  double fixed_limit = 2.0;  // OpenCV's normalised clip limit (used by kFixed)
  double base = 1.0;         // c in Eq. 11
  double gain = 1.0;         // multiplies the two adaptive terms of Eq. 11 (paper: 1)
  SigmaSource sigma = SigmaSource::kIntensity;
  MaximaSource maxima = MaximaSource::kFixed;
  double sigma_max = 0.0;  // 0: the prior for the chosen sigma source
  double d_max = 0.0;      // 0: the prior
};

struct EnhancerParams {
  std::string preset = "best";
  QualityGateParams gate;
  CompensationParams compensation;
  WorkChannel channel = WorkChannel::kValue;
  ClaheParams clahe;
  StereoMapping stereo = StereoMapping::kDecisions;  // measured (docs/enhancement.md, Stereo)

  // Names accepted by `Enhancement.preset`.
  static const std::vector<std::string>& presetNames();
  // Throws Error naming the preset when it is unknown.
  static EnhancerParams forPreset(const std::string& name);
  // `Enhancement.preset` (default "best") then every other `Enhancement.*` key on top of it.
  static EnhancerParams fromSettings(const core::SettingsFile& settings);
  // The settings text that fromSettings reads back to these parameters.
  std::string toSettingsText() const;
};

// Priors for sigma_max / d_max on 8-bit images (see docs/enhancement.md for how they were set).
double sigmaMaxPrior(SigmaSource source);
double laplacianVarianceMaxPrior();

}  // namespace lumaslam::enhance
