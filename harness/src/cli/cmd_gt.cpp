// vobench gt compare / gt fuse — the quality of a ground truth, and two ground truths made one
// (Ceriani et al. 2009). See groundtruth/gt_compare.hpp and groundtruth/gt_fusion.hpp.
#include "cli/commands.hpp"
#include "groundtruth/gt_compare.hpp"
#include "groundtruth/gt_fusion.hpp"
#include "metrics/trajectory_io.hpp"
#include "util/files.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <iostream>

namespace vobench::cli {

namespace {

metrics::Trajectory load(const std::string& path, const std::string& format) {
    metrics::ReadOptions options;
    options.format = metrics::parse_trajectory_format(format);
    metrics::ReadResult r = metrics::read_trajectory(path, options);
    for (const std::string& w : r.warnings) spdlog::warn("{}", w);
    return std::move(r.poses);
}

// "0.02" or "0.02,1.5": position σ (m) and optionally rotation σ (°).
void parse_sigma(const std::string& text, gt::PoseStream& s, const std::string& option) {
    const auto comma = text.find(',');
    try {
        std::size_t used = 0;
        s.sigma_pos_m = std::stod(text.substr(0, comma), &used);
        if (comma != std::string::npos) s.sigma_rot_deg = std::stod(text.substr(comma + 1));
    } catch (const std::exception&) {
        throw CLI::ValidationError(option, "'" + text + "' is not POS or POS,ROT_DEG");
    }
}

}  // namespace

void add_gt_commands(CLI::App& app, int& exit_code) {
    auto* gt = app.add_subcommand("gt", "Ground-truth quality: compare against validation poses, fuse two streams");
    gt->require_subcommand(1);

    auto* cmp = gt->add_subcommand("compare", "Error of a ground truth at sparse validation poses (Rawseeds Table 1)");
    static std::string gt_file, validation, gt_format = "tum", val_format = "tum", by = "time";
    static double max_dt = 0.02;
    static bool align = false, json = false;
    cmp->add_option("--gt", gt_file, "The ground truth to judge")->required()->check(CLI::ExistingFile);
    cmp->add_option("--validation", validation, "Independent validation poses")->required()->check(CLI::ExistingFile);
    cmp->add_option("--gt-format", gt_format, "tum, kitti, euroc or putk2-raw")->capture_default_str();
    cmp->add_option("--validation-format", val_format, "tum, kitti, euroc or putk2-raw")->capture_default_str();
    cmp->add_option("--by", by, "Match validation poses by time (nearest within --max-dt) or id (equal stamps)")
        ->check(CLI::IsMember({"time", "id"}))
        ->capture_default_str();
    cmp->add_option("--max-dt", max_dt, "Largest stamp difference for --by time, s")->capture_default_str();
    cmp->add_flag("--align", align, "Fit the ground truth onto the validation poses (se3) first");
    cmp->add_flag("--json", json, "JSON on stdout");
    cmp->callback([&exit_code] {
        gt::CompareOptions o;
        o.by = by == "id" ? gt::MatchBy::Id : gt::MatchBy::Time;
        o.max_dt = max_dt;
        o.align = align;
        const gt::CompareResult r = gt::compare_ground_truth(load(gt_file, gt_format), load(validation, val_format), o);
        if (json)
            std::cout << json_text(gt::compare_json(r, o)) << "\n";
        else
            std::cout << gt::compare_table(r);
        exit_code = 0;
    });

    auto* fuse = gt->add_subcommand("fuse", "Fuse two independent ground-truth streams (EKF forward, RTS smoother backward, SE(3))");
    static std::string a_file, b_file, odo_file, a_format = "tum", b_format = "tum", out, sigma_a, sigma_b, sigma_odo = "0.05,2";
    static double accel = 0.5, gyro = 0.5;
    fuse->add_option("a", a_file, "First ground-truth stream")->required()->check(CLI::ExistingFile);
    fuse->add_option("b", b_file, "Second ground-truth stream (same world frame)")->required()->check(CLI::ExistingFile);
    fuse->add_option("--sigma-a", sigma_a, "1σ of stream A: POS_M[,ROT_DEG]")->required();
    fuse->add_option("--sigma-b", sigma_b, "1σ of stream B: POS_M[,ROT_DEG]")->required();
    fuse->add_option("--format-a", a_format, "tum, kitti, euroc or putk2-raw")->capture_default_str();
    fuse->add_option("--format-b", b_format, "tum, kitti, euroc or putk2-raw")->capture_default_str();
    fuse->add_option("--odometry", odo_file, "Optional odometry (TUM): its relative motion is the motion input")->check(CLI::ExistingFile);
    fuse->add_option("--sigma-odometry", sigma_odo, "1σ of the odometry's velocity: M_PER_S[,DEG_PER_S]")->capture_default_str();
    fuse->add_option("--accel-noise", accel, "Motion model: random walk of the velocity, m/s²/√Hz")->capture_default_str();
    fuse->add_option("--gyro-noise", gyro, "Motion model: random walk of the angular velocity, rad/s²/√Hz")->capture_default_str();
    fuse->add_option("--out", out, "Fused trajectory (TUM); covariances in OUT.cov")->required();
    fuse->callback([&exit_code] {
        gt::PoseStream a, b;
        a.poses = load(a_file, a_format);
        b.poses = load(b_file, b_format);
        parse_sigma(sigma_a, a, "--sigma-a");
        parse_sigma(sigma_b, b, "--sigma-b");
        gt::FusionOptions o;
        o.accel_noise = accel;
        o.gyro_noise = gyro;
        if (!odo_file.empty()) {
            gt::PoseStream odo;
            odo.poses = load(odo_file, "tum");
            parse_sigma(sigma_odo, odo, "--sigma-odometry");
            o.odometry = odo;
        }
        const auto fused = gt::fuse_ground_truth(a, b, o);
        gt::write_fused(out, fused);
        double mean_sigma = 0;
        for (const auto& f : fused) mean_sigma += std::sqrt(f.covariance.block<3, 3>(0, 0).trace() / 3.0);
        std::cout << fmt::format("{} poses fused from {} (σ {} m) and {} (σ {} m){}; mean position σ {:.4f} m → {} (+ .cov)\n",
                                 fused.size(), a.poses.size(), a.sigma_pos_m, b.poses.size(), b.sigma_pos_m,
                                 odo_file.empty() ? "" : " with odometry", mean_sigma / static_cast<double>(fused.size()), out);
        exit_code = 0;
    });
}

}  // namespace vobench::cli
