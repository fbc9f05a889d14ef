// trajectory_io.hpp — reading and writing trajectories, with strict validation.
//
// Formats
//   tum        `t tx ty tz qx qy qz qw`; '#' comments; spaces, tabs or commas (as the TUM scripts).
//   kitti      12 numbers a line, the 3×4 matrix [R|t] row by row; no stamps: the line index is the stamp.
//   euroc      EuRoC ground-truth CSV: `t[ns], px, py, pz, qw, qx, qy, qz, ...`; stamps become seconds.
//   putk2-raw  PUTK² marker trajectory `id;rx;ry;rz;tx;ty;tz` (Rodrigues vector, rad, then metres); the
//              frame id is the stamp. With a camera-in-marker pose C, each pose is M·C (Kraft et al. 2016,
//              eq. 10): the camera's pose from the marker's.
//
// Validation (every message names file and line)
//   errors:   unreadable file; too few numbers; a non-number; a non-finite value; a zero quaternion;
//             an empty trajectory.
//   warnings (named, the pose kept): `non-unit-quaternion` (|‖q‖ − 1| > tolerance; normalised),
//             `unsorted-stamps` (sorted), `stamps-in-nanoseconds` (TUM stamps > 1e13 turned to seconds),
//             `extra-columns` (ignored), `duplicate-stamp` (the later line wins, as in the TUM scripts'
//             dict; real TUM ground truth has such lines).
//   In tum-scripts mode the reader behaves as evaluate_rpe.py's read_trajectory: a line with a NaN or a
//   zero quaternion is skipped with a warning, and nanosecond stamps are left as they are.
#pragma once

#include "metrics/pose.hpp"

#include <Eigen/Geometry>

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace vobench::metrics {

enum class TrajectoryFormat { Tum, Kitti, Euroc, Putk2Raw };
TrajectoryFormat parse_trajectory_format(const std::string& name);  // throws std::invalid_argument
const char* trajectory_format_name(TrajectoryFormat format);

class TrajectoryError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct ReadOptions {
    TrajectoryFormat format = TrajectoryFormat::Tum;
    std::optional<Eigen::Isometry3d> camera_in_marker;  // putk2-raw only
    double quaternion_tolerance = 1e-3;
    bool tum_scripts = false;
};

struct ReadResult {
    Trajectory poses;
    std::vector<std::string> warnings;  // "file:line: [code] message"
};

ReadResult read_trajectory(const std::filesystem::path& path, const ReadOptions& options = {});
// The same, from text already in memory (`name` is used in messages). Used by the fuzz targets.
ReadResult parse_trajectory(const std::string& text, const std::string& name, const ReadOptions& options = {});

// A camera-in-marker file: the first non-comment line `x y z qw qx qy qz` (w first, as PUT's files).
Eigen::Isometry3d read_camera_in_marker(const std::filesystem::path& path);

// One TUM line at full (round-trip) double precision, without newline.
std::string format_tum_line(const StampedPose& pose);
// Writes a TUM file atomically (temporary file, then rename). The header comment is cleaned of line
// breaks and control characters: a sequence name can never add a pose line.
void write_tum(const std::filesystem::path& path, const Trajectory& poses, const std::string& header_comment = "");

}  // namespace vobench::metrics
