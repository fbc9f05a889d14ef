#include "groundtruth/gt_compare.hpp"

#include "metrics/alignment.hpp"
#include "metrics/rpe.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vobench::gt {

namespace {

// Index of the ground-truth pose matched to stamp t, or npos.
std::size_t match(const metrics::Trajectory& gt, double t, const CompareOptions& o) {
    const auto it = std::lower_bound(gt.begin(), gt.end(), t, [](const metrics::StampedPose& p, double s) { return p.t < s; });
    std::size_t best = std::string::npos;
    double best_dt = o.by == MatchBy::Id ? 1e-9 : o.max_dt;
    for (auto c : {it, it == gt.begin() ? it : it - 1}) {
        if (c == gt.end()) continue;
        const double dt = std::abs(c->t - t);
        if (dt <= best_dt) {
            best_dt = dt;
            best = static_cast<std::size_t>(c - gt.begin());
        }
    }
    return best;
}

}  // namespace

CompareResult compare_ground_truth(const metrics::Trajectory& gt_in, const metrics::Trajectory& validation, const CompareOptions& o) {
    metrics::Trajectory gt = gt_in;
    std::sort(gt.begin(), gt.end(), [](const auto& a, const auto& b) { return a.t < b.t; });
    CompareResult r;
    r.validation_poses = validation.size();
    std::vector<std::pair<std::size_t, std::size_t>> pairs;  // (gt, validation)
    for (std::size_t k = 0; k < validation.size(); ++k) {
        const std::size_t g = match(gt, validation[k].t, o);
        if (g == std::string::npos)
            r.unmatched_stamps.push_back(validation[k].t);
        else
            pairs.emplace_back(g, k);
    }
    r.localised = pairs.size();
    if (pairs.empty()) throw std::invalid_argument("no validation pose could be matched to a ground-truth pose");
    Eigen::Isometry3d fit = Eigen::Isometry3d::Identity();
    if (o.align) {
        if (pairs.size() < 3) throw std::invalid_argument("--align needs at least 3 localised poses");
        Eigen::Matrix3Xd from(3, pairs.size()), to(3, pairs.size());
        for (std::size_t k = 0; k < pairs.size(); ++k) {
            from.col(k) = gt[pairs[k].first].p;
            to.col(k) = validation[pairs[k].second].p;
        }
        const metrics::Alignment a = metrics::align(from, to, metrics::AlignmentMethod::Se3);
        fit.linear() = a.R;
        fit.translation() = a.t;
    }
    std::vector<double> pos, rot;
    for (const auto& [g, v] : pairs) {
        const Eigen::Isometry3d G = fit * gt[g].isometry();
        pos.push_back((G.translation() - validation[v].p).norm());
        const Eigen::Quaterniond d = Eigen::Quaterniond(G.linear()).conjugate() * validation[v].q;
        rot.push_back(metrics::rotation_angle(d.normalized()) * 180.0 / M_PI);
    }
    r.position_m = metrics::compute_stats(pos);
    r.rotation_deg = metrics::compute_stats(rot);
    return r;
}

nlohmann::json compare_json(const CompareResult& r, const CompareOptions& o) {
    return {{"validation_poses", r.validation_poses},
            {"localised", r.localised},
            {"match", o.by == MatchBy::Time ? "time" : "id"},
            {"max_dt_s", o.max_dt},
            {"aligned", o.align},
            {"position_m", r.position_m},
            {"rotation_deg", r.rotation_deg},
            {"unmatched_stamps", r.unmatched_stamps}};
}

std::string compare_table(const CompareResult& r) {
    return fmt::format(
        "| poses localised | position error mean [m] | std [m] | max [m] | angular error mean [°] | std [°] | max [°] |\n"
        "|---|---:|---:|---:|---:|---:|---:|\n"
        "| {}/{} | {:.4f} | {:.4f} | {:.4f} | {:.3f} | {:.3f} | {:.3f} |\n",
        r.localised, r.validation_poses, r.position_m.mean, r.position_m.std, r.position_m.max, r.rotation_deg.mean, r.rotation_deg.std,
        r.rotation_deg.max);
}

}  // namespace vobench::gt
