// vobench synth — render a synthetic Kinect v1 / v2 RGB-D sequence with ground truth.
#include "cli/commands.hpp"
#include "synth/camera_catalog.hpp"
#include "synth/disparity_distortion_fit.hpp"
#include "synth/frame_statistics.hpp"
#include "synth/sequence_writer.hpp"
#include "util/escape.hpp"

#include <nlohmann/json.hpp>

#include <spdlog/spdlog.h>

#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <utility>

namespace vobench::cli {

namespace {

// `vobench synth stats DIR…`: one column per folder, one row per statistic (frame_statistics.hpp).
CLI::App* add_stats_command(CLI::App& synth, int& exit_code) {
    auto* c = synth.add_subcommand("stats", "Image and depth statistics of TUM-layout folders (real or rendered), side by side");
    static std::vector<std::string> folders;
    static std::size_t max_frames = 0;
    static bool json = false;
    static std::string camera;
    c->add_option("folders", folders, "TUM-layout folders (rgb.txt, depth.txt; depth 5000 units per metre)")->required();
    c->add_option("--max-frames", max_frames, "At most N colour-depth pairs per folder, evenly spaced (0: all)");
    c->add_option("--camera", camera,
                  "The colour camera the depth is registered to (a name, e.g. tum-fr1, or a camera file as for synth --camera): adds "
                  "the ICP conditioning and, with groundtruth.txt, the depth residual under the reference's motion and each stream's stamp "
                  "latency");
    c->add_flag("--json", json, "Print one JSON object");
    c->callback([&exit_code] {
        std::optional<synth::CameraSpec> spec;
        if (!camera.empty()) spec = synth::camera_by_name_or_file(camera);
        std::vector<synth::FolderStatistics> all;
        for (const auto& f : folders) all.push_back(synth::measure_folder(f, max_frames, 5000.0, spec ? &spec->color : nullptr));
        if (json) {
            nlohmann::json j = nlohmann::json::array();
            for (const auto& s : all) {
                nlohmann::json values = nlohmann::json::object();
                for (const auto& v : s.values) values[v.key] = std::isfinite(v.value) ? nlohmann::json(v.value) : nlohmann::json();
                j.push_back({{"folder", s.folder.string()}, {"frames", s.frames}, {"statistics", values}});
            }
            std::cout << j.dump(2) << "\n";
            exit_code = 0;
            return;
        }
        // Rows in the first folder's order, then any statistic only a later folder has.
        std::vector<std::pair<std::string, std::string>> rows;
        for (const auto& s : all)
            for (const auto& v : s.values)
                if (std::none_of(rows.begin(), rows.end(), [&](const auto& r) { return r.first == v.key; }))
                    rows.emplace_back(v.key, v.label);
        std::cout << "| statistic |";
        // Labels hold | (|Δt|) and folder names may hold anything: escaped, so each row keeps its cells.
        for (const auto& s : all) std::cout << " " << markdown_text(s.folder.filename().string()) << " (" << s.frames << " frames) |";
        std::cout << "\n|---|";
        for (std::size_t k = 0; k < all.size(); ++k) std::cout << "---:|";
        std::cout << "\n";
        for (const auto& [key, label] : rows) {
            std::cout << "| " << markdown_text(label) << " |";
            for (const auto& s : all) {
                const auto it = std::find_if(s.values.begin(), s.values.end(), [&](const auto& v) { return v.key == key; });
                std::cout << " "
                          << (it == s.values.end() || !std::isfinite(it->value) ? std::string("–") : fmt::format("{:.4g}", it->value))
                          << " |";
            }
            std::cout << "\n";
        }
        exit_code = 0;
    });
    return c;
}

// A disparity offset field given on the command line as "A,B,C" (px); an error naming the option otherwise.
synth::DisparityOffset parse_offset(const std::string& text, const std::string& option) {
    synth::DisparityOffset d{};
    char tail = 0;
    if (std::sscanf(text.c_str(), "%lf,%lf,%lf%c", &d[0], &d[1], &d[2], &tail) != 3 ||
        !std::all_of(d.begin(), d.end(), [](double v) { return std::isfinite(v); }))
        throw std::runtime_error(option + ": '" + text + "' is not three numbers A,B,C");
    return d;
}

// `vobench synth fit-distortion DIR`: a Kinect v1's fixed disparity distortion from a real folder and
// its reference (disparity_distortion_fit.hpp); with --expect, a check that it reproduces given numbers.
CLI::App* add_fit_distortion_command(CLI::App& synth, int& exit_code) {
    auto* c = synth.add_subcommand("fit-distortion",
                                   "Fit a Kinect v1's disparity distortion δ = a·r² + b·x + c·y px to a TUM folder's depth and reference");
    static std::string folder, validate, camera = "tum-fr1", expect;
    static double latency_ms = synth::kinect1().depth_latency_s * 1e3;
    static std::string tolerance = "0.05", turn_deg;
    static synth::DistortionFitOptions options;
    c->add_option("folder", folder, "TUM-layout folder with depth.txt and groundtruth.txt (depth 5000 units per metre)")->required();
    c->add_option("--camera", camera, "The colour camera the depth is registered to (a name or a camera file)")->capture_default_str();
    c->add_option("--validate", validate, "A second folder of the same camera: its residuals with and without the fitted field");
    c->add_option("--depth-latency-ms", latency_ms, "The depth stream's latency (synth stats --camera measures it)")->capture_default_str();
    c->add_option("--focal-baseline", options.focal_baseline_px_m, "IR focal length × baseline, px·m")->capture_default_str();
    c->add_option("--iterations", options.iterations, "Gauss–Newton iterations")->check(CLI::Range(1, 100))->capture_default_str();
    c->add_option("--reference-turn-deg", turn_deg,
                  "X,Y,Z: the frame the reference describes is turned by this rotation vector (camera axes, degrees)");
    c->add_flag("--fit-latency", options.fit_latency, "Fit the depth latency with the field (from --depth-latency-ms, within ±50 ms)");
    c->add_flag("--fit-turn", options.fit_reference_turn, "Fit the reference's turn with the field (from --reference-turn-deg)");
    c->add_option("--expect", expect, "A,B,C: exit 1 unless the fit reproduces these coefficients and lowers the residual at 16 frames");
    c->add_option("--tolerance", tolerance, "For --expect: largest difference per coefficient, px: T for all three, or TA,TB,TC")
        ->capture_default_str();
    c->callback([&exit_code] {
        options.depth_latency_s = latency_ms * 1e-3;
        if (!turn_deg.empty()) {
            const synth::DisparityOffset t = parse_offset(turn_deg, "--reference-turn-deg");  // three numbers, as a field's
            options.reference_turn_rad = Eigen::Vector3d(t[0], t[1], t[2]) * M_PI / 180.0;
        }
        const synth::CameraSpec spec = synth::camera_by_name_or_file(camera);
        const synth::DepthRays rays(spec.color);
        std::optional<synth::DisparityOffset> expected;
        if (!expect.empty()) expected = parse_offset(expect, "--expect");
        const synth::DisparityOffset allowed = tolerance.find(',') == std::string::npos
                                                   ? parse_offset(tolerance + "," + tolerance + "," + tolerance, "--tolerance")
                                                   : parse_offset(tolerance, "--tolerance");
        if (std::any_of(allowed.begin(), allowed.end(), [](double t) { return t < 0; }))
            throw std::runtime_error("--tolerance: '" + tolerance + "' has a negative number");
        const synth::DepthSequence sequence = synth::read_depth_sequence(folder, spec.color, 5000.0);
        const synth::DistortionFit fit = synth::fit_disparity_distortion(sequence, rays, options);
        const auto& d = fit.delta;
        std::cout << fmt::format("{}: δ = {:+.4f}·r² {:+.4f}·x {:+.4f}·y px ({} pairs, {} residuals)\n", folder, d[0], d[1], d[2],
                                 fit.pairs, fit.residuals);
        const Eigen::Vector3d turn = fit.reference_turn_rad * 180.0 / M_PI;
        std::cout << fmt::format("{}: depth latency {:.2f} ms{}, reference turn ({:+.3f}, {:+.3f}, {:+.3f})° ({:.3f}°){}\n", folder,
                                 fit.depth_latency_s * 1e3, options.fit_latency ? " (fitted)" : "", turn.x(), turn.y(), turn.z(),
                                 turn.norm(), options.fit_reference_turn ? " (fitted)" : "");
        // The residuals below: "without" at the given latency and turn with no field; "with" at the fitted values.
        synth::DistortionFitOptions fitted = options;
        fitted.depth_latency_s = fit.depth_latency_s;
        fitted.reference_turn_rad = fit.reference_turn_rad;
        // Each gap's residual without and with the field, printed; returns the last gap's pair.
        const auto report = [&](const std::string& name, const synth::DepthSequence& s, std::initializer_list<int> gaps) {
            std::pair<double, double> last{0, 0};
            for (const int gap : gaps) {
                std::size_t n = 0;
                last.first = synth::corrected_residual_pct(s, rays, gap, {0, 0, 0}, options, n);
                last.second = synth::corrected_residual_pct(s, rays, gap, d, fitted, n);
                std::cout << fmt::format("{}: gap {:2d} ({} pairs): residual {:.3f} % -> {:.3f} % with the fit\n", name, gap, n, last.first,
                                         last.second);
            }
            return last;
        };
        const auto [without16, with16] = report(folder, sequence, {1, 4, 16});
        if (!validate.empty()) report(validate, synth::read_depth_sequence(validate, spec.color, 5000.0), {1, 2, 4, 8});
        exit_code = 0;
        if (expected) {
            bool within = true;
            for (std::size_t k = 0; k < 3; ++k) within = within && std::abs(d[k] - (*expected)[k]) <= allowed[k];
            const bool lowered = with16 < without16;
            if (!within || !lowered) {
                std::cout << fmt::format("FAIL: fitted {:.3f}, {:.3f}, {:.3f}, expected {} ± {} px; residual at 16 frames lowered: {}\n",
                                         d[0], d[1], d[2], expect, tolerance, lowered);
                exit_code = 1;
            } else {
                std::cout << fmt::format("ok: the fit reproduces {} within {} px\n", expect, tolerance);
            }
        }
    });
    return c;
}

// `vobench synth undo-distortion DIR --out OUT`: a copy of a real folder with its depth corrected for the
// camera's measured disparity distortion (or a given one), to measure what the distortion costs an algorithm.
CLI::App* add_undo_distortion_command(CLI::App& synth, int& exit_code) {
    auto* c = synth.add_subcommand(
        "undo-distortion", "Copy a TUM folder with its depth corrected for a Kinect v1's disparity distortion δ = a·r² + b·x + c·y px");
    static std::string folder, out, camera = "tum-fr1", field;
    static double focal_baseline = synth::DistortionFitOptions{}.focal_baseline_px_m;
    c->add_option("folder", folder, "TUM-layout folder (depth.txt, depth 5000 units per metre)")->required();
    c->add_option("--out", out, "The corrected copy: a new or empty folder")->required();
    c->add_option("--camera", camera,
                  "The colour camera the depth is registered to; the field fit-distortion measured on its real frames is undone")
        ->capture_default_str();
    c->add_option("--field", field, "A,B,C: undo this field instead of the camera's (e.g. from synth fit-distortion)");
    c->add_option("--focal-baseline", focal_baseline, "IR focal length × baseline, px·m")->capture_default_str();
    c->callback([&exit_code] {
        const synth::CameraSpec spec = synth::camera_by_name_or_file(camera);
        synth::DisparityOffset delta = spec.disparity_distortion_fit_px;
        if (!field.empty()) {
            delta = parse_offset(field, "--field");
        } else if (delta == synth::DisparityOffset{0, 0, 0}) {
            throw std::runtime_error("--camera " + camera + " has no measured disparity distortion; give one with --field A,B,C");
        }
        const std::size_t n = synth::write_corrected_folder(folder, out, spec.color, delta, focal_baseline, 5000.0);
        std::cout << fmt::format("{}: {} depth images corrected for δ = {:+.4f}·r² {:+.4f}·x {:+.4f}·y px\n", out, n, delta[0], delta[1],
                                 delta[2]);
        exit_code = 0;
    });
    return c;
}

}  // namespace

void add_synth_command(CLI::App& app, int& exit_code) {
    auto* c = app.add_subcommand("synth", "Render a synthetic Kinect v1/v2 RGB-D sequence with ground truth");
    static synth::SynthOptions o;
    static std::string blur = "on", out;
    c->add_option("--sensor", o.sensor, "kinect1 or kinect2")->check(CLI::IsMember({"kinect1", "kinect2"}))->capture_default_str();
    c->add_option("--trajectory", o.trajectory, "explore1..4, speed1..4, or a trajectory file")->capture_default_str();
    c->add_option("--trajectory-format", o.trajectory_format, "For a file: putk2-raw (marker poses) or tum (camera poses)")
        ->check(CLI::IsMember({"putk2-raw", "tum"}))
        ->capture_default_str();
    c->add_option("--camera-in-marker", o.camera_in_marker, "Camera-in-marker pose file (default: PUT's for the sensor)");
    c->add_option(
        "--camera", o.camera,
        "Colour camera: putk2-kinect1, putk2-kinect2, tum-fr1, tum-fr2, tum-fr3, or a file `width height fx fy cx cy [k1 k2 p1 p2 "
        "k3 k4 k5 k6]` (default: the sensor's own)");
    static std::string stamps;
    c->add_option("--stamps", stamps,
                  "A TUM folder: render one frame per colour-depth pair of its rgb.txt/depth.txt, each image at its own stamp less "
                  "its stream's latency (effect stamp_latency; needs --trajectory-format tum)");
    c->add_option("--frames", o.frames, "Render only the first N poses (0: all)");
    c->add_option("--seed", o.seed, "Seed of the scene and of all noise")->capture_default_str();
    c->add_option("--layout", o.layout, "Output layout: tum, putk2, putk2-tum, icl-tum, icl-povray")
        ->check(CLI::IsMember({"tum", "putk2", "putk2-tum", "icl-tum", "icl-povray"}))
        ->capture_default_str();
    c->add_option("--effects", o.effects,
                  "Effects of the sensor models: all, none, or a comma list of [+|-]name applied to the defaults, e.g. "
                  "-motion_blur,-dark_dropout (names: vobench synth --effects help)");
    c->add_option("--blur", blur, "Motion blur over the exposure: on or off")->check(CLI::IsMember({"on", "off"}))->capture_default_str();
    c->add_option("--out", out, "Output folder (required to render)");
    auto* stats = add_stats_command(*c, exit_code);
    auto* fit = add_fit_distortion_command(*c, exit_code);
    auto* undo = add_undo_distortion_command(*c, exit_code);
    c->callback([&exit_code, c, stats, fit, undo] {
        if (c->got_subcommand(stats) || c->got_subcommand(fit) || c->got_subcommand(undo)) return;
        if (out.empty()) throw CLI::RequiredError("--out");
        o.blur = blur == "on";
        o.out = out;
        o.stamps = stamps;
        const bool tty = isatty(fileno(stderr));
        const auto report = synth::synthesize(o, [tty](uint64_t done, uint64_t total) {
            if (tty)
                std::fprintf(stderr, "\rrendering %llu/%llu", static_cast<unsigned long long>(done),
                             static_cast<unsigned long long>(total));
            else if (done == total || done % 100 == 0)
                spdlog::info("rendered {}/{}", done, total);
        });
        if (tty) std::fprintf(stderr, "\n");
        std::cout << fmt::format("{}: {} frames of {} along {} in {:.2f} s ({:.2f} frames/s)\n", out, report.frames, o.sensor, o.trajectory,
                                 report.seconds, report.fps());
        if (report.skipped_stamps > 0)
            spdlog::warn("--stamps: {} colour-depth pairs lie outside the trajectory's time span and were not rendered",
                         report.skipped_stamps);
        exit_code = 0;
    });
}

}  // namespace vobench::cli
