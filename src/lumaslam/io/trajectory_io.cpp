#include "lumaslam/io/trajectory_io.h"

#include "lumaslam/io/output_file.h"

#include <cmath>
#include <fstream>

#include "lumaslam/core/error.h"
#include "lumaslam/io/rotation_projection.h"
#include "lumaslam/io/text_lines.h"

namespace lumaslam::io {

namespace {
constexpr double kUnitTolerance = 1e-3;

[[noreturn]] void badLine(const std::filesystem::path& file, const TextLine& line,
                          std::string_view expected) {
  fail("{}:{}: expected {}, got '{}'", file.string(), line.number, expected, line.text);
}

Eigen::Quaterniond unitQuaternion(const Eigen::Quaterniond& q, const std::filesystem::path& file,
                                  const TextLine& line) {
  const double norm = q.norm();
  if (std::abs(norm - 1.0) > kUnitTolerance)
    fail("{}:{}: quaternion norm is {:.6f}, not 1 (off by more than {}): '{}'", file.string(),
         line.number, norm, kUnitTolerance, line.text);
  return q.normalized();
}

Eigen::Matrix3d nearestRotation(const Eigen::Matrix3d& R, const std::filesystem::path& file,
                                const TextLine& line) {
  const auto rotation = projectToRotation(R, kUnitTolerance);
  if (!rotation)
    fail("{}:{}: the 3x3 part is not a rotation (|R^T R - I| = {:.2e}, det = {:.4f}): '{}'",
         file.string(), line.number, (R.transpose() * R - Eigen::Matrix3d::Identity()).norm(),
         R.determinant(), line.text);
  return *rotation;
}

SE3 makePose(const Eigen::Vector3d& t, const Eigen::Quaterniond& q) {
  SE3 T = SE3::Identity();
  T.linear() = q.toRotationMatrix();
  T.translation() = t;
  return T;
}

void checkIncreasing(const Trajectory& trajectory, const std::filesystem::path& file,
                     const std::vector<TextLine>& lines) {
  for (std::size_t i = 1; i < trajectory.size(); ++i) {
    if (!(trajectory[i].timestamp > trajectory[i - 1].timestamp))
      fail("{}:{}: timestamp {:.9f} does not increase (previous line {}: {:.9f})", file.string(),
           lines[i].number, trajectory[i].timestamp, lines[i - 1].number,
           trajectory[i - 1].timestamp);
  }
}

StampedPose parseTumLine(const std::filesystem::path& file, const TextLine& line) {
  const auto fields = splitFields(line.text, " \t");
  if (fields.size() != 8) badLine(file, line, "8 numbers 't tx ty tz qx qy qz qw'");
  double v[8];
  for (int i = 0; i < 8; ++i) v[i] = parseNumber(fields[i], file, line);
  const Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);
  return {v[0], makePose({v[1], v[2], v[3]}, unitQuaternion(q, file, line))};
}

StampedPose parseEurocLine(const std::filesystem::path& file, const TextLine& line) {
  const auto fields = splitFields(line.text, ",");
  if (fields.size() < 8)
    badLine(file, line, "at least 8 fields 'timestamp_ns,px,py,pz,qw,qx,qy,qz'");
  const double t = parseNanosecondsAsSeconds(fields[0], file, line);
  double v[7];
  for (int i = 0; i < 7; ++i) v[i] = parseNumber(fields[i + 1], file, line);
  const Eigen::Quaterniond q(v[3], v[4], v[5], v[6]);
  return {t, makePose({v[0], v[1], v[2]}, unitQuaternion(q, file, line))};
}

SE3 parseKittiLine(const std::filesystem::path& file, const TextLine& line) {
  const auto fields = splitFields(line.text, " \t");
  if (fields.size() != 12) badLine(file, line, "12 numbers (row-major 3x4 [R|t])");
  Eigen::Matrix<double, 3, 4> P;
  for (int i = 0; i < 12; ++i) P(i / 4, i % 4) = parseNumber(fields[i], file, line);
  SE3 T = SE3::Identity();
  T.linear() = nearestRotation(P.leftCols<3>(), file, line);
  T.translation() = P.col(3);
  return T;
}

Eigen::Quaterniond rotationOf(const SE3& T) {
  return Eigen::Quaterniond(T.rotation());
}

TrajectoryFormat detectFormat(const std::filesystem::path& file, const TextLine& first);
}  // namespace

TrajectoryFormat parseTrajectoryFormat(std::string_view name) {
  if (name == "auto") return TrajectoryFormat::Auto;
  if (name == "tum") return TrajectoryFormat::Tum;
  if (name == "euroc" || name == "euroc-csv") return TrajectoryFormat::EurocCsv;
  if (name == "kitti") return TrajectoryFormat::Kitti;
  fail("unknown trajectory format '{}' (expected auto, tum, euroc or kitti)", name);
}

std::string_view trajectoryFormatName(TrajectoryFormat format) {
  switch (format) {
    case TrajectoryFormat::Auto:
      return "auto";
    case TrajectoryFormat::Tum:
      return "tum";
    case TrajectoryFormat::EurocCsv:
      return "euroc";
    case TrajectoryFormat::Kitti:
      return "kitti";
  }
  return "?";
}

TrajectoryFormat detectTrajectoryFormat(const std::filesystem::path& file) {
  const auto lines = readDataLines(file);
  if (lines.empty()) fail("{}: no trajectory data (empty file)", file.string());
  return detectFormat(file, lines.front());
}

namespace {
TrajectoryFormat detectFormat(const std::filesystem::path& file, const TextLine& first) {
  if (first.text.find(',') != std::string::npos) return TrajectoryFormat::EurocCsv;
  const auto fields = splitFields(first.text, " \t");
  if (fields.size() == 12) return TrajectoryFormat::Kitti;
  if (fields.size() == 8) return TrajectoryFormat::Tum;
  fail(
      "{}:{}: cannot tell the trajectory format: {} fields (TUM has 8, KITTI 12, EuRoC csv "
      "uses commas): '{}'",
      file.string(), first.number, fields.size(), first.text);
}
}  // namespace

std::vector<double> readTimestamps(const std::filesystem::path& file) {
  const auto lines = readDataLines(file);
  std::vector<double> times;
  times.reserve(lines.size());
  for (const auto& line : lines) {
    const auto fields = splitFields(line.text, " \t");
    if (fields.size() != 1) badLine(file, line, "one timestamp per line");
    times.push_back(parseNumber(fields[0], file, line));
    if (times.size() > 1 && !(times.back() > times[times.size() - 2]))
      fail("{}:{}: timestamp {} does not increase", file.string(), line.number, times.back());
  }
  return times;
}

Trajectory readTrajectory(const std::filesystem::path& file, TrajectoryFormat format,
                          const std::filesystem::path& kitti_times) {
  const auto lines = readDataLines(file);
  if (lines.empty()) fail("{}: no trajectory data (empty file)", file.string());
  if (format == TrajectoryFormat::Auto) format = detectFormat(file, lines.front());

  Trajectory trajectory;
  trajectory.reserve(lines.size());
  switch (format) {
    case TrajectoryFormat::Tum:
      for (const auto& line : lines) trajectory.push_back(parseTumLine(file, line));
      break;
    case TrajectoryFormat::EurocCsv:
      for (const auto& line : lines) trajectory.push_back(parseEurocLine(file, line));
      break;
    case TrajectoryFormat::Kitti: {
      std::vector<double> times;
      if (!kitti_times.empty()) {
        times = readTimestamps(kitti_times);
        if (times.size() < lines.size())
          fail("{}: {} timestamps for {} poses in {}", kitti_times.string(), times.size(),
               lines.size(), file.string());
      }
      for (std::size_t i = 0; i < lines.size(); ++i) {
        const double t = times.empty() ? static_cast<double>(i) : times[i];
        trajectory.push_back({t, parseKittiLine(file, lines[i])});
      }
      break;
    }
    case TrajectoryFormat::Auto:
      break;
  }
  checkIncreasing(trajectory, file, lines);
  return trajectory;
}

void writeTrajectory(const std::filesystem::path& file, const Trajectory& trajectory,
                     TrajectoryFormat format, const std::filesystem::path& kitti_times) {
  if (format == TrajectoryFormat::Auto) format = TrajectoryFormat::Tum;
  OutputFile out(file);
  auto& stream = out.stream();
  // "{}" prints the shortest decimal that reads back to the same double.
  switch (format) {
    case TrajectoryFormat::Tum:
    case TrajectoryFormat::Auto:
      stream << "# timestamp tx ty tz qx qy qz qw\n";
      for (const auto& [t, T] : trajectory) {
        const Eigen::Vector3d p = T.translation();
        const Eigen::Quaterniond q = rotationOf(T);
        stream << fmt::format("{:.9f} {} {} {} {} {} {} {}\n", t, p.x(), p.y(), p.z(), q.x(), q.y(),
                              q.z(), q.w());
      }
      break;
    case TrajectoryFormat::EurocCsv:
      stream << "#timestamp [ns],p_RS_R_x [m],p_RS_R_y [m],p_RS_R_z [m],q_RS_w [],q_RS_x [],"
                "q_RS_y [],q_RS_z []\n";
      for (const auto& [t, T] : trajectory) {
        const Eigen::Vector3d p = T.translation();
        const Eigen::Quaterniond q = rotationOf(T);
        stream << fmt::format("{},{},{},{},{},{},{},{}\n", secondsToNanoseconds(t), p.x(), p.y(),
                              p.z(), q.w(), q.x(), q.y(), q.z());
      }
      break;
    case TrajectoryFormat::Kitti:
      for (const auto& pose : trajectory) {
        const Eigen::Matrix<double, 3, 4> P = pose.T_w_c.matrix().topRows<3>();
        for (int i = 0; i < 12; ++i)
          stream << (i == 0 ? "" : " ") << fmt::format("{}", P(i / 4, i % 4));
        stream << '\n';
      }
      break;
  }
  out.commit();

  if (format == TrajectoryFormat::Kitti && !kitti_times.empty()) {
    OutputFile times(kitti_times);
    for (const auto& pose : trajectory) times.stream() << fmt::format("{:.9f}\n", pose.timestamp);
    times.commit();
  }
}

}  // namespace lumaslam::io
