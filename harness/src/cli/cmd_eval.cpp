// vobench eval --gt FILE --est FILE ...
#include "cli/commands.hpp"
#include "cli/protocol_options.hpp"
#include "metrics/trajectory_io.hpp"
#include "metrics/trajectory_stats.hpp"
#include "util/files.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <iostream>

namespace vobench::cli {

metrics::Trajectory load_trajectory_file(const std::string& path, const std::string& format, const std::string& camera_in_marker,
                                         bool tum_scripts) {
    metrics::ReadOptions options;
    options.format = metrics::parse_trajectory_format(format);
    options.tum_scripts = tum_scripts;
    if (!camera_in_marker.empty()) options.camera_in_marker = metrics::read_camera_in_marker(camera_in_marker);
    metrics::ReadResult r = metrics::read_trajectory(path, options);
    for (const std::string& w : r.warnings) spdlog::warn("{}", w);
    return std::move(r.poses);
}

namespace {

void print_stats(const char* title, const metrics::ErrorStats& s, const char* unit) {
    std::cout << fmt::format("{:<24} rmse {:.6f} {u}  mean {:.6f}  median {:.6f}  std {:.6f}  min {:.6f}  max {:.6f}  ({} pairs)\n", title,
                             s.rmse, s.mean, s.median, s.std, s.min, s.max, s.count, fmt::arg("u", unit));
}

}  // namespace

void add_eval_command(CLI::App& app, int& exit_code) {
    auto* c = app.add_subcommand("eval", "ATE and RPE of an estimated trajectory against ground truth");
    static std::string gt, est, gt_format = "tum", est_format = "tum", gt_cim, est_cim;
    static bool json = false;
    static ProtocolArgs protocol;
    c->add_option("--gt", gt, "Ground-truth trajectory")->required()->check(CLI::ExistingFile);
    c->add_option("--est", est, "Estimated trajectory")->required()->check(CLI::ExistingFile);
    c->add_option("--gt-format", gt_format, "tum, kitti, euroc or putk2-raw")->capture_default_str();
    c->add_option("--est-format", est_format, "tum, kitti, euroc or putk2-raw")->capture_default_str();
    c->add_option("--gt-camera-in-marker", gt_cim, "putk2-raw ground truth: camera-in-marker pose file (eq. 10)");
    c->add_option("--est-camera-in-marker", est_cim, "putk2-raw estimate: camera-in-marker pose file");
    c->add_flag("--json", json, "Print one JSON object");
    protocol.add_to(c);
    c->callback([&exit_code] {
        const metrics::Protocol p = protocol.build();
        const bool tum = p.name == metrics::ProtocolName::TumScripts;
        const metrics::Trajectory g = load_trajectory_file(gt, gt_format, gt_cim, tum);
        const metrics::Trajectory e = load_trajectory_file(est, est_format, est_cim, tum);
        const metrics::Evaluation ev = metrics::evaluate(g, e, p);
        if (json) {
            std::cout << json_text(metrics::evaluation_json(ev)) << std::endl;
        } else {
            std::cout << "protocol: " << json_text(metrics::protocol_json(p), -1) << "\n";
            if (ev.ate) print_stats("ATE (m)", ev.ate->stats, "m");
            if (ev.rpe) {
                print_stats("RPE translation (m)", ev.rpe->trans, "m");
                print_stats("RPE rotation (deg)", ev.rpe->rot_deg, "deg");
            }
        }
        exit_code = 0;
    });
}

void add_traj_command(CLI::App& app, int& exit_code) {
    auto* traj = app.add_subcommand("traj", "Trajectory tools");
    traj->require_subcommand(1);
    auto* stats = traj->add_subcommand("stats", "Poses, duration, length, mean velocity (Kraft et al. Table 4)");
    static std::string file, format = "tum", cim;
    static double rate = 0;
    static bool json = false;
    stats->add_option("FILE", file, "Trajectory file")->required()->check(CLI::ExistingFile);
    stats->add_option("--format", format, "tum, kitti, euroc or putk2-raw")->capture_default_str();
    stats->add_option("--camera-in-marker", cim, "putk2-raw: camera-in-marker pose file (eq. 10)");
    stats->add_option("--rate", rate, "Frame rate: duration = (poses - 1) / rate");
    stats->add_flag("--json", json, "Print JSON");
    stats->callback([&exit_code] {
        const metrics::Trajectory t = load_trajectory_file(file, format, cim, false);
        const metrics::TrajectoryStats s = metrics::compute_trajectory_stats(t, rate > 0 ? std::optional<double>(rate) : std::nullopt);
        if (json) {
            nlohmann::json j = s;
            std::cout << json_text(j) << std::endl;
        } else {
            std::cout << fmt::format("poses {}  duration {:.4f} s  length {:.4f} m  mean velocity {:.4f} m/s  rotation {:.2f} deg\n",
                                     s.poses, s.duration_s, s.length_m, s.mean_velocity_mps, s.rotation_deg);
        }
        exit_code = 0;
    });
}

}  // namespace vobench::cli
