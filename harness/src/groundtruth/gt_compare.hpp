// gt_compare.hpp — how good is a ground truth? Its error at sparse, independent validation poses
// (Ceriani et al. 2009, "Rawseeds ground truth collection systems for indoor self-localization and
// mapping", Auton. Robots 27: the ground truth is checked against poses measured by other means, and
// Table 1 reports "poses localised" with the mean, standard deviation and maximum of the error).
//
// Each validation pose is matched to a ground-truth pose — the nearest in time within `max_dt`, or the
// one with the same stamp when stamps are ids — and compared in the common frame (no alignment: both
// are meant to be in the same world frame; `align` applies an se3 fit first when they are not).
#pragma once

#include "metrics/pose.hpp"
#include "metrics/statistics.hpp"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <string>

namespace vobench::gt {

enum class MatchBy { Time, Id };

struct CompareOptions {
    MatchBy by = MatchBy::Time;
    double max_dt = 0.02;  // s (MatchBy::Time)
    bool align = false;    // se3 fit of the ground truth onto the validation poses first
};

struct CompareResult {
    std::size_t validation_poses = 0, localised = 0;
    metrics::ErrorStats position_m;    // ‖p_gt − p_val‖
    metrics::ErrorStats rotation_deg;  // angle of q_gt⁻¹ q_val
    std::vector<double> unmatched_stamps;
};

// Throws std::invalid_argument when no validation pose can be localised.
CompareResult compare_ground_truth(const metrics::Trajectory& gt, const metrics::Trajectory& validation, const CompareOptions& options);

nlohmann::json compare_json(const CompareResult& r, const CompareOptions& options);

// The layout of Rawseeds Table 1: "25/26 poses localised; position error mean … std … max …".
std::string compare_table(const CompareResult& r);

}  // namespace vobench::gt
