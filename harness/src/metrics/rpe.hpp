// rpe.hpp — relative pose error, in two named protocols.
//
// paper (default; Sturm et al. 2012, Kraft et al. 2016 eq. 11)
//   Estimate and ground truth are first associated (association.hpp). Over the n matched pairs, for a
//   step Δ: E_i = (Q_i⁻¹ Q_{i+Δ})⁻¹ (P_i⁻¹ P_{i+Δ}), Q ground truth, P estimate, for every i that has a
//   partner (m = n − Δ pairs for Δ in frames). For Δ in seconds, metres, radians or degrees the partner
//   of i is the first j whose stamp (s) or ground-truth path length / rotation travelled (m, rad, deg)
//   since i reaches Δ. Errors: ‖trans(E_i)‖ in metres and the rotation angle of E_i in degrees
//   (2·atan2(‖v‖, |w|) of its quaternion, accurate near zero).
//
// tum-scripts (evaluate_rpe.py --fixed_delta --max_pairs 0, as published with the benchmark)
//   Differences from paper, all reproduced on purpose:
//   1. No association: each estimate stamp takes the nearest ground-truth stamp (its own binary search,
//      find_closest_index), rejected when farther than 2 × the median ground-truth interval.
//   2. Pairs are chosen on the estimate: the partner of i is the index closest to index_i + Δ, where
//      the index is the position (f), the stamp (s), or the estimate's own path length (m) or rotation
//      (rad, deg); a pair is dropped when its partner is the last pose — even for Δ = 1 frame.
//   3. Composition order: E = (P_i⁻¹ P_j)(Q_i⁻¹ Q_j)⁻¹ — the estimate's motion first.
//   4. The angle is arccos(clip((tr R − 1)/2)), from 4×4 matrices built as transform44 builds them.
//   5. Poses with a NaN or a zero quaternion are skipped; of duplicate stamps the last wins.
#pragma once

#include "metrics/association.hpp"
#include "metrics/pose.hpp"
#include "metrics/statistics.hpp"

#include <string>
#include <vector>

namespace vobench::metrics {

enum class DeltaUnit { Frames, Seconds, Metres, Radians, Degrees };
DeltaUnit parse_delta_unit(const std::string& name);  // f, s, m, rad, deg
const char* delta_unit_name(DeltaUnit unit);

struct RpeOptions {
    double delta = 4.0;  // the paper's n = 4 frames
    DeltaUnit unit = DeltaUnit::Frames;
    AssociationOptions association;  // paper: association; tum-scripts: only the offset is used
};

struct RpePair {
    double t_first, t_second;  // estimate stamps
    double trans_m, rot_deg;
};

struct RpeResult {
    ErrorStats trans;    // metres
    ErrorStats rot_deg;  // degrees
    std::vector<RpePair> pairs;
    std::size_t matched = 0;  // associated poses (paper) or estimate poses (tum-scripts)
};

RpeResult compute_rpe_paper(const Trajectory& gt, const Trajectory& est, const RpeOptions& options);
RpeResult compute_rpe_paper(const Trajectory& gt, const Trajectory& est, const Association& association, const RpeOptions& options);
RpeResult compute_rpe_tum_scripts(const Trajectory& gt, const Trajectory& est, const RpeOptions& options);

// Rotation angle of a unit quaternion in radians, in [0, π].
double rotation_angle(const Eigen::Quaterniond& q);

}  // namespace vobench::metrics
