// ate.hpp — absolute trajectory error (Sturm et al. 2012; Kraft et al. 2016, eq. 12):
//   F_i = Q_i⁻¹ S P_i over the associated pairs, S the alignment of the estimate to the ground truth;
//   ATE = statistics of ‖trans(F_i)‖ — the translational residuals after alignment.
// This equals evaluate_ate.py exactly when the alignment is se3 (its Horn alignment) on all pairs.
#pragma once

#include "metrics/alignment.hpp"
#include "metrics/association.hpp"
#include "metrics/pose.hpp"
#include "metrics/statistics.hpp"

#include <vector>

namespace vobench::metrics {

struct AteOptions {
    AssociationOptions association;
    AlignmentMethod alignment = AlignmentMethod::Se3;
    std::size_t align_first = 0;  // 0: align on all pairs
};

struct AteResult {
    ErrorStats stats;
    Association association;
    Alignment alignment;
    std::vector<double> stamps;                                   // estimate stamps of the pairs
    std::vector<double> errors;                                   // metres, per pair (for plots)
    std::vector<Eigen::Vector3d> aligned_estimate, ground_truth;  // per pair (for plots)
    // Per pair (for the report's camera frusta): the estimate's orientation rotated by the alignment
    // (R · q_est; a scale does not rotate) and the ground truth's own.
    std::vector<Eigen::Quaterniond> aligned_orientation, ground_truth_orientation;
};

AteResult compute_ate(const Trajectory& gt, const Trajectory& est, const AteOptions& options);
// The same on an association already made (evaluate() shares one between ATE and RPE).
AteResult compute_ate(const Trajectory& gt, const Trajectory& est, const Association& association, const AteOptions& options);

std::vector<double> stamps_of(const Trajectory& trajectory);

}  // namespace vobench::metrics
