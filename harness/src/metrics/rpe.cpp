#include "metrics/rpe.hpp"

#include "metrics/ate.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vobench::metrics {

DeltaUnit parse_delta_unit(const std::string& name) {
    if (name == "f" || name == "frames") return DeltaUnit::Frames;
    if (name == "s") return DeltaUnit::Seconds;
    if (name == "m") return DeltaUnit::Metres;
    if (name == "rad") return DeltaUnit::Radians;
    if (name == "deg") return DeltaUnit::Degrees;
    throw std::invalid_argument("unknown delta unit '" + name + "' (f, s, m, rad or deg)");
}

const char* delta_unit_name(DeltaUnit unit) {
    switch (unit) {
        case DeltaUnit::Frames: return "f";
        case DeltaUnit::Seconds: return "s";
        case DeltaUnit::Metres: return "m";
        case DeltaUnit::Radians: return "rad";
        case DeltaUnit::Degrees: return "deg";
    }
    return "?";
}

double rotation_angle(const Eigen::Quaterniond& q) { return 2.0 * std::atan2(q.vec().norm(), std::abs(q.w())); }

namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

RpeResult summarise(std::vector<RpePair> pairs, std::size_t matched) {
    if (pairs.empty()) throw std::runtime_error("RPE: no pose pairs at this delta (sequence too short?)");
    RpeResult r;
    std::vector<double> trans, rot;
    for (const RpePair& p : pairs) {
        trans.push_back(p.trans_m);
        rot.push_back(p.rot_deg);
    }
    r.trans = compute_stats(trans);
    r.rot_deg = compute_stats(rot);
    r.pairs = std::move(pairs);
    r.matched = matched;
    return r;
}

}  // namespace

RpeResult compute_rpe_paper(const Trajectory& gt, const Trajectory& est, const RpeOptions& options) {
    return compute_rpe_paper(gt, est, associate(stamps_of(gt), stamps_of(est), options.association), options);
}

RpeResult compute_rpe_paper(const Trajectory& gt, const Trajectory& est, const Association& assoc, const RpeOptions& options) {
    if (!(options.delta > 0)) throw std::invalid_argument("RPE delta must be positive");
    const std::size_t n = assoc.matches.size();
    std::vector<Eigen::Isometry3d> Q(n), P(n);
    std::vector<double> index(n, 0.0);
    for (std::size_t k = 0; k < n; ++k) {
        Q[k] = gt[assoc.matches[k].first].isometry();
        P[k] = est[assoc.matches[k].second].isometry();
    }
    // The index along which Δ is measured (frames use i + Δ directly).
    for (std::size_t k = 0; k < n; ++k) {
        switch (options.unit) {
            case DeltaUnit::Frames: index[k] = static_cast<double>(k); break;
            case DeltaUnit::Seconds: index[k] = est[assoc.matches[k].second].t; break;
            case DeltaUnit::Metres: index[k] = k == 0 ? 0.0 : index[k - 1] + (Q[k].translation() - Q[k - 1].translation()).norm(); break;
            case DeltaUnit::Radians:
            case DeltaUnit::Degrees: {
                const double step = k == 0 ? 0.0 : rotation_angle(Eigen::Quaterniond(Q[k - 1].linear().transpose() * Q[k].linear()));
                index[k] = k == 0 ? 0.0 : index[k - 1] + (options.unit == DeltaUnit::Degrees ? step * kRadToDeg : step);
                break;
            }
        }
    }
    if (options.unit == DeltaUnit::Frames && options.delta != std::floor(options.delta))
        throw std::invalid_argument("RPE delta in frames must be a whole number");

    std::vector<RpePair> pairs;
    pairs.reserve(n);
    std::size_t j = 0;
    for (std::size_t i = 0; i < n; ++i) {
        // First j > i with index[j] − index[i] ≥ Δ; index is non-decreasing, so j only moves forward.
        j = std::max(j, i + 1);
        while (j < n && index[j] - index[i] < options.delta) ++j;
        if (j >= n) break;
        const Eigen::Isometry3d gt_motion = Q[i].inverse() * Q[j];
        const Eigen::Isometry3d est_motion = P[i].inverse() * P[j];
        const Eigen::Isometry3d E = gt_motion.inverse() * est_motion;  // Kraft et al. eq. 11
        pairs.push_back({est[assoc.matches[i].second].t, est[assoc.matches[j].second].t, E.translation().norm(),
                         rotation_angle(Eigen::Quaterniond(E.linear())) * kRadToDeg});
    }
    return summarise(std::move(pairs), n);
}

// ----- evaluate_rpe.py, line by line -------------------------------------------------------------

namespace {

// transform44(): the script's quaternion-to-matrix, including its scaling by sqrt(2 / ‖q‖²).
Eigen::Matrix4d transform44(const StampedPose& p) {
    Eigen::Vector4d q(p.q.x(), p.q.y(), p.q.z(), p.q.w());
    const double nq = q.dot(q);
    Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
    T.block<3, 1>(0, 3) = p.p;
    if (nq < 4.0 * std::numeric_limits<double>::epsilon()) return T;
    q *= std::sqrt(2.0 / nq);
    const Eigen::Matrix4d o = q * q.transpose();
    T(0, 0) = 1.0 - o(1, 1) - o(2, 2);
    T(0, 1) = o(0, 1) - o(2, 3);
    T(0, 2) = o(0, 2) + o(1, 3);
    T(1, 0) = o(0, 1) + o(2, 3);
    T(1, 1) = 1.0 - o(0, 0) - o(2, 2);
    T(1, 2) = o(1, 2) - o(0, 3);
    T(2, 0) = o(0, 2) - o(1, 3);
    T(2, 1) = o(1, 2) + o(0, 3);
    T(2, 2) = 1.0 - o(0, 0) - o(1, 1);
    return T;
}

// find_closest_index(L, t): the script's binary search, which keeps the best index seen on its path.
std::size_t find_closest_index(const std::vector<double>& L, double t) {
    std::size_t beginning = 0, end = L.size(), best = 0;
    double difference = std::abs(L[0] - t);
    while (beginning < end) {
        const std::size_t middle = (end + beginning) / 2;
        if (std::abs(L[middle] - t) < difference) {
            difference = std::abs(L[middle] - t);
            best = middle;
        }
        if (t == L[middle]) return middle;
        if (L[middle] > t)
            end = middle;
        else
            beginning = middle + 1;
    }
    return best;
}

Eigen::Matrix4d ominus(const Eigen::Matrix4d& a, const Eigen::Matrix4d& b) { return a.inverse() * b; }

double compute_angle(const Eigen::Matrix4d& T) {
    return std::acos(std::min(1.0, std::max(-1.0, (T.block<3, 3>(0, 0).trace() - 1.0) / 2.0)));
}

double median_of(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

RpeResult compute_rpe_tum_scripts(const Trajectory& gt, const Trajectory& est, const RpeOptions& options) {
    if (gt.size() < 2 || est.size() < 2) throw std::runtime_error("RPE: need at least two poses in each trajectory");
    const double offset = options.association.offset;
    const std::vector<double> stamps_gt = stamps_of(gt), stamps_est = stamps_of(est);
    std::vector<Eigen::Matrix4d> T_gt(gt.size()), T_est(est.size());
    for (std::size_t k = 0; k < gt.size(); ++k) T_gt[k] = transform44(gt[k]);
    for (std::size_t k = 0; k < est.size(); ++k) T_est[k] = transform44(est[k]);

    // The script's overlap check: at least two distinct estimate stamps map back and forth.
    {
        std::vector<double> returned;
        for (double t_est : stamps_est) {
            const double t_gt = stamps_gt[find_closest_index(stamps_gt, t_est + offset)];
            const double t_back = stamps_est[find_closest_index(stamps_est, t_gt - offset)];
            if (std::find(returned.begin(), returned.end(), t_back) == returned.end()) returned.push_back(t_back);
            if (returned.size() >= 2) break;
        }
        if (returned.size() < 2)
            throw std::runtime_error("Number of overlap in the timestamps is too small. Did you run the evaluation on the right files?");
    }

    std::vector<double> index_est(est.size());
    double sum = 0;
    for (std::size_t k = 0; k < est.size(); ++k) {
        switch (options.unit) {
            case DeltaUnit::Frames: index_est[k] = static_cast<double>(k); break;
            case DeltaUnit::Seconds: index_est[k] = stamps_est[k]; break;
            case DeltaUnit::Metres:
                if (k > 0) sum += ominus(T_est[k], T_est[k - 1]).block<3, 1>(0, 3).norm();
                index_est[k] = sum;
                break;
            case DeltaUnit::Radians:
            case DeltaUnit::Degrees:
                if (k > 0) sum += compute_angle(ominus(T_est[k], T_est[k - 1])) * (options.unit == DeltaUnit::Degrees ? kRadToDeg : 1.0);
                index_est[k] = sum;
                break;
        }
    }

    std::vector<double> intervals;
    for (std::size_t k = 1; k < stamps_gt.size(); ++k) intervals.push_back(stamps_gt[k] - stamps_gt[k - 1]);
    const double gt_max_time_difference = 2.0 * median_of(intervals);

    std::vector<RpePair> pairs;
    for (std::size_t i = 0; i < est.size(); ++i) {
        const std::size_t j = find_closest_index(index_est, index_est[i] + options.delta);
        if (j == est.size() - 1) continue;
        const std::size_t g0 = find_closest_index(stamps_gt, stamps_est[i] + offset);
        const std::size_t g1 = find_closest_index(stamps_gt, stamps_est[j] + offset);
        if (std::abs(stamps_gt[g0] - (stamps_est[i] + offset)) > gt_max_time_difference ||
            std::abs(stamps_gt[g1] - (stamps_est[j] + offset)) > gt_max_time_difference)
            continue;
        const Eigen::Matrix4d error44 = ominus(ominus(T_est[j], T_est[i]), ominus(T_gt[g1], T_gt[g0]));
        pairs.push_back({stamps_est[i], stamps_est[j], error44.block<3, 1>(0, 3).norm(), compute_angle(error44) * kRadToDeg});
    }
    if (pairs.size() < 2) throw std::runtime_error("Couldn't find matching timestamp pairs between groundtruth and estimated trajectory!");
    return summarise(std::move(pairs), est.size());
}

}  // namespace vobench::metrics
