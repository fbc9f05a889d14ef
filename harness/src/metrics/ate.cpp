#include "metrics/ate.hpp"

namespace vobench::metrics {

std::vector<double> stamps_of(const Trajectory& trajectory) {
    std::vector<double> stamps;
    stamps.reserve(trajectory.size());
    for (const StampedPose& p : trajectory) stamps.push_back(p.t);
    return stamps;
}

AteResult compute_ate(const Trajectory& gt, const Trajectory& est, const AteOptions& options) {
    return compute_ate(gt, est, associate(stamps_of(gt), stamps_of(est), options.association), options);
}

AteResult compute_ate(const Trajectory& gt, const Trajectory& est, const Association& association, const AteOptions& options) {
    AteResult r;
    r.association = association;
    const auto& matches = r.association.matches;
    Eigen::Matrix3Xd model(3, matches.size()), data(3, matches.size());
    for (std::size_t k = 0; k < matches.size(); ++k) {
        model.col(k) = est[matches[k].second].p;
        data.col(k) = gt[matches[k].first].p;
    }
    r.alignment = align(model, data, options.alignment, options.align_first);
    r.errors.reserve(matches.size());
    for (std::size_t k = 0; k < matches.size(); ++k) {
        const Eigen::Vector3d aligned = r.alignment.apply(model.col(k));
        r.errors.push_back((aligned - data.col(k)).norm());
        r.stamps.push_back(est[matches[k].second].t);
        r.aligned_estimate.push_back(aligned);
        r.ground_truth.push_back(data.col(k));
        r.aligned_orientation.push_back(Eigen::Quaterniond(r.alignment.R * est[matches[k].second].q.toRotationMatrix()).normalized());
        r.ground_truth_orientation.push_back(gt[matches[k].first].q);
    }
    r.stats = compute_stats(r.errors);
    return r;
}

}  // namespace vobench::metrics
