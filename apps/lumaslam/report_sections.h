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

// The run had a detector (summary "detector" name other than "none") or the motion test
// (summary "motion_evidence" on).
bool hadMovingThings(const nlohmann::json& summary);

// Detector, motion test, boxes / dropped / moving features per frame and the medians of
// motion_ms and detection_wait_ms from timing.csv, with a plot of the features removed per
// frame; moving map points from the summary.
std::string movingSection(const RunFolder& run);

// The run saved a map (summary "map_file" "saved"), failed to (`save_error`) or started from one.
bool hadMapFile(const nlohmann::json& summary);

// The saved map file read again as `lumaslam map info` reads it (keyframes, points, maps,
// settings fingerprint), or a note when it is gone or unreadable; the loaded map's counts.
std::string mapFileSection(const nlohmann::json& summary);

}  // namespace lumaslam::cli
