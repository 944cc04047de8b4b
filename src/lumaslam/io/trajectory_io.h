#pragma once
// Trajectory files: TUM (`t tx ty tz qx qy qz qw`), EuRoC ground-truth csv
// (`timestamp_ns,px,py,pz,qw,qx,qy,qz[,...]`, also ORB-SLAM3's `1403715274312143104.0000000000`
// stamps) and KITTI poses (12 numbers per line, row-major [R|t], times from a times.txt).
// All poses are T_w_c, timestamps in seconds, strictly increasing.
#include <filesystem>
#include <string_view>

#include "lumaslam/core/pose.h"

namespace lumaslam::io {

enum class TrajectoryFormat { Auto, Tum, EurocCsv, Kitti };

// "auto", "tum", "euroc" (or "euroc-csv"), "kitti"; throws Error naming the value otherwise.
TrajectoryFormat parseTrajectoryFormat(std::string_view name);
std::string_view trajectoryFormatName(TrajectoryFormat format);

// By the first data line: commas → EuRoC, 12 fields → KITTI, 8 fields → TUM.
TrajectoryFormat detectTrajectoryFormat(const std::filesystem::path& file);

// Throws Error (naming file and line) for a missing/empty file, a malformed line, a quaternion
// whose norm is off by more than 1e-3 (smaller errors are normalised), a KITTI rotation that is
// not a rotation (|R^T R - I| > 1e-3; smaller errors are projected onto SO(3)), or timestamps
// that do not strictly increase. KITTI without `kitti_times`: timestamp = frame index.
Trajectory readTrajectory(const std::filesystem::path& file,
                          TrajectoryFormat format = TrajectoryFormat::Auto,
                          const std::filesystem::path& kitti_times = {});

// Writes with full precision (TUM: t as %.9f; EuRoC: integer nanoseconds; poses with the
// shortest digits that read back to the same double). KITTI stores no timestamps: pass
// `kitti_times` to also write them, one per line. Auto means TUM.
void writeTrajectory(const std::filesystem::path& file, const Trajectory& trajectory,
                     TrajectoryFormat format = TrajectoryFormat::Tum,
                     const std::filesystem::path& kitti_times = {});

// KITTI times.txt: one timestamp (seconds) per line.
std::vector<double> readTimestamps(const std::filesystem::path& file);

}  // namespace lumaslam::io
