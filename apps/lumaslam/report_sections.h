#pragma once
// The sections of `lumaslam report` (docs/report.md), each an HTML fragment for HtmlPage.
// Numbers shown come from summary.json and timing.csv as the run wrote them; cells carry
// data-key attributes named after the summary's keys (e.g. "tracked", "ate.rmse").
#include <string>

#include <nlohmann/json.hpp>

#include "report_evaluation.h"
#include "report_frames.h"
#include "run_folder.h"

namespace lumaslam::cli {

// Status, dataset, settings, frame counts, keyframes, loops, merges, detector, vocabulary,
// skipped frames, and the atlas' maps.
std::string runSection(const nlohmann::json& summary);

// ATE / RPE statistics of summary.json's "evaluation", with the trajectory's top and side
// views and the ATE along time from `again` (or why they are missing).
std::string evaluationSection(const nlohmann::json& summary, const Reevaluation& again);

// median / mean / p90 / max of every *_ms column and total ms per frame along the run.
std::string timingSection(const RunFolder& run);

// The state of every frame (ok / lost / not initialized) along the run.
std::string trackingSection(const RunFolder& run);

std::string framesSection(const SampleFrames& samples);

}  // namespace lumaslam::cli
