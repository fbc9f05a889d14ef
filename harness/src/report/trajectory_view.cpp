#include "report/trajectory_view.hpp"

#include "record/timing_csv.hpp"
#include "report/aggregate.hpp"
#include "util/escape.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>

namespace vobench {
namespace {

using nlohmann::json;

// Display numbers, shortened: positions and quaternions to 1e-5 (10 µm on a path of metres), times
// to 0.1 ms, errors and milliseconds to four significant digits. The value is the double nearest the
// printed decimal, so that the JSON writer's shortest round-trip form is that decimal (x/step·step
// would print 17 digits). A non-finite value becomes null.
json as_json(const std::string& printed) { return std::strtod(printed.c_str(), nullptr); }
json rounded(double x, int decimals) { return std::isfinite(x) ? as_json(fmt::format("{:.{}f}", x, decimals)) : json(nullptr); }
json significant(double x) { return std::isfinite(x) ? as_json(fmt::format("{:.4g}", x)) : json(nullptr); }

json track(const std::string& label, const std::string& role, const std::vector<double>& stamps, double t0,
           const std::vector<Eigen::Vector3d>& positions, const std::vector<Eigen::Quaterniond>& orientations,
           const std::vector<std::size_t>& shown) {
    json t = json::array(), p = json::array(), q = json::array();
    for (std::size_t i : shown) {
        t.push_back(rounded(stamps[i] - t0, 4));
        for (int a = 0; a < 3; ++a) p.push_back(rounded(positions[i][a], 5));
        const Eigen::Quaterniond& o = orientations[i];
        for (double c : {o.w(), o.x(), o.y(), o.z()}) q.push_back(rounded(c, 5));
    }
    return {{"label", clean_text(label)}, {"role", role}, {"t", t}, {"p", p}, {"q", q}};
}

json timing_view(const std::filesystem::path& file, double t0, std::size_t max_rows) {
    const TimingTable table = read_timing_csv(file);
    const std::size_t n = table.stamps.size();
    const std::size_t bucket = n <= max_rows ? 1 : (n + max_rows - 1) / max_rows;
    // Bucket means (a dropped frame's NaN left out), so that stacked stages still add up to the mean
    // process time of the frames they stand for.
    const auto mean = [&](const std::vector<double>& v, std::size_t from) {
        double s = 0;
        std::size_t k = 0;
        for (std::size_t i = from; i < std::min(n, from + bucket); ++i)
            if (std::isfinite(v[i])) {
                s += v[i];
                ++k;
            }
        return k ? significant(s / static_cast<double>(k)) : json(nullptr);
    };
    json t = json::array(), process = json::array(), read = json::array(), stages = json::array();
    for (std::size_t i = 0; i < n; i += bucket) {
        t.push_back(rounded(table.stamps[i] - t0, 4));
        process.push_back(mean(table.process_ms, i));
        read.push_back(mean(table.read_ms, i));
    }
    for (const TimingStage& s : table.stages) {
        json ms = json::array();
        for (std::size_t i = 0; i < n; i += bucket) ms.push_back(mean(s.ms, i));
        stages.push_back({{"name", clean_text(s.name)}, {"ms", ms}});
    }
    std::size_t lost = 0, dropped = 0;
    for (const std::string& s : table.status) {
        lost += s == "lost";
        dropped += s == "dropped";
    }
    return {{"t", t},    {"process", process}, {"read", read}, {"stages", stages},
            {"rows", n}, {"bucket", bucket},   {"lost", lost}, {"dropped", dropped}};
}

}  // namespace

std::vector<std::size_t> display_indices(std::size_t n, std::size_t max) {
    std::vector<std::size_t> shown;
    if (n == 0) return shown;
    const std::size_t step = n <= max || max < 2 ? 1 : (n + max - 2) / (max - 1);
    for (std::size_t i = 0; i < n; i += step) shown.push_back(i);
    if (shown.back() != n - 1) shown.push_back(n - 1);
    return shown;
}

std::optional<json> cell_view(const RunRecord& run, const ViewLimits& limits) {
    if (!run.evaluation || !run.evaluation->ate || run.evaluation->ate->stamps.empty()) return std::nullopt;
    const metrics::AteResult& ate = *run.evaluation->ate;
    const double t0 = ate.stamps.front();
    const std::vector<std::size_t> shown = display_indices(ate.stamps.size(), limits.max_poses);
    json est =
        track("estimate (aligned as ATE aligns it)", "estimate", ate.stamps, t0, ate.aligned_estimate, ate.aligned_orientation, shown);
    json err = json::array();
    for (std::size_t i : shown) err.push_back(significant(ate.errors[i]));
    est["err"] = err;
    json v = {
        {"cell", run.cell.id},
        {"entry", clean_text(run.entry())},
        {"row", clean_text(run.cell.dataset + "/" + run.cell.sequence)},
        {"sensor", clean_text(sensor_title(run.cell.sensor))},
        {"t0", t0},
        {"poses", ate.stamps.size()},
        {"shown", shown.size()},
        {"ate_rmse", ate.stats.rmse},
        {"tracks",
         json::array({track("ground truth", "reference", ate.stamps, t0, ate.ground_truth, ate.ground_truth_orientation, shown), est})}};
    if (const auto& rpe = run.evaluation->rpe; rpe && !rpe->pairs.empty()) {
        const std::vector<std::size_t> pairs = display_indices(rpe->pairs.size(), limits.max_rpe_pairs);
        json t = json::array(), trans = json::array(), rot = json::array();
        for (std::size_t i : pairs) {
            t.push_back(rounded(rpe->pairs[i].t_first - t0, 4));
            trans.push_back(significant(rpe->pairs[i].trans_m));
            rot.push_back(significant(rpe->pairs[i].rot_deg));
        }
        v["rpe"] = {{"t", t}, {"trans", trans}, {"rot", rot}, {"pairs", rpe->pairs.size()}, {"shown", pairs.size()}};
    }
    try {
        v["timing"] = timing_view(run.dir / "timing.csv", t0, limits.max_timing_rows);
    } catch (const TimingCsvError& e) {
        v["timing_error"] = clean_text(e.what());
    }
    return v;
}

json trajectories_view(const std::optional<PlotInput>& reference, const std::vector<PlotInput>& estimates,
                       const std::vector<PlottedTrajectory>& lines, const ViewLimits& limits) {
    json tracks = json::array();
    const double t0 = reference && !reference->poses.empty()                   ? reference->poses.front().t
                      : !estimates.empty() && !estimates.front().poses.empty() ? estimates.front().poses.front().t
                                                                               : 0.0;
    std::size_t poses = 0, shown_total = 0;
    const auto add = [&](const PlotInput& in, const metrics::Alignment& a, const std::string& role) {
        std::vector<double> stamps;
        std::vector<Eigen::Vector3d> p;
        std::vector<Eigen::Quaterniond> q;
        for (const metrics::StampedPose& s : in.poses) {
            stamps.push_back(s.t);
            p.push_back(a.apply(s.p));
            q.push_back(Eigen::Quaterniond(a.R * s.q.toRotationMatrix()).normalized());
        }
        const std::vector<std::size_t> shown = display_indices(stamps.size(), limits.max_poses);
        poses += stamps.size();
        shown_total += shown.size();
        tracks.push_back(track(in.label, role, stamps, t0, p, q, shown));
    };
    std::size_t line = 0;
    if (reference) add(*reference, lines.at(line++).alignment, "reference");
    for (const PlotInput& e : estimates) add(e, lines.at(line++).alignment, "estimate");
    return {{"t0", t0}, {"poses", poses}, {"shown", shown_total}, {"tracks", tracks}};
}

}  // namespace vobench
