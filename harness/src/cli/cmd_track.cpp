// vobench track — one odometry plugin on one sequence.
#include "cli/commands.hpp"
#include "cli/protocol_options.hpp"
#include "metrics/metric_catalog.hpp"
#include "record/timing_stats.hpp"
#include "track/track.hpp"
#include "util/files.hpp"
#include "util/subprocess.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include <iostream>

namespace vobench::cli {

void add_track_command(CLI::App& app, int& exit_code) {
    auto* c = app.add_subcommand("track", "Run one odometry plugin on one sequence; write trajectory.txt and timing.csv");
    static TrackOptions options;
    static std::string sensor, out;
    static std::vector<std::string> dataset_options, params;
    static bool json = false;
    static ProtocolArgs protocol;
    c->add_option("--dataset", options.dataset, "Dataset reader plugin (name or path)")->required();
    c->add_option("--path", options.path, "Sequence folder")->required();
    c->add_option("--sensor", sensor, "Sensor, passed to the reader as option sensor=S");
    c->add_option("--option", dataset_options, "Reader option key=value (repeatable)");
    c->add_option("--algorithm", options.algorithm, "Odometry plugin (name or path)")->required();
    c->add_option("--param", params, "Odometry parameter key=value (repeatable)");
    c->add_option("--frames", options.max_frames, "Use only the first N frames (0: all)");
    c->add_option("--seed", options.seed, "Seed handed to the plugin")->capture_default_str();
    c->add_option("--out", out, "Output folder for trajectory.txt and timing.csv");
    static std::string cache;
    c->add_option("--frame-cache", cache, "Decoded-frame cache folder (zstd, keyed by reader, options and content)");
    c->add_flag("--json", json, "Print a JSON summary on stdout");
    static std::vector<std::string> filters;
    c->add_option("--filter", filters, "A filter between reader and plugin, NAME or NAME:key=value,key=value (repeatable, in order)");
    static bool realtime = false;
    c->add_flag("--realtime", realtime,
                "Offer frames at their recorded stamps; a frame that arrives while the plugin is busy is dropped (as on a robot)");
    c->add_option("--speed", options.timing.speed, "With --realtime: the stream's speed factor")
        ->capture_default_str()
        ->check(CLI::Range(1e-3, 1e3));
    c->add_option("--warmup", options.timing.warmup_frames, "Frames left out of the timing statistics (not of the trajectory)");
    protocol.add_to(c);
    c->callback([&exit_code] {
        options.dataset_options = parse_key_values(dataset_options, "--option");
        if (!sensor.empty()) options.dataset_options["sensor"] = sensor;
        options.params = parse_key_values(params, "--param");
        options.protocol = protocol.build();
        options.frame_cache = cache;
        options.timing.mode = realtime ? "realtime" : "offline";
        options.filters.clear();
        for (const std::string& f : filters) {
            const auto colon = f.find(':');
            FilterSpec spec{f.substr(0, colon), {}};
            if (colon != std::string::npos) {
                std::vector<std::string> items;
                for (std::size_t b = colon + 1, e; b <= f.size(); b = e + 1) {
                    e = std::min(f.find(',', b), f.size());
                    if (e > b) items.push_back(f.substr(b, e - b));
                }
                spec.params = parse_key_values(items, "--filter");
            }
            options.filters.push_back(spec);
        }
        const TrackResult r = run_track(options, PluginRegistry());
        if (!out.empty()) {
            write_track_outputs(r, out);
            spdlog::info("wrote {}/trajectory.txt and timing.csv", out);
        }
        const nlohmann::json timing = timing_statistics(r.frames, options.timing);
        const double ms = timing["mean_ms"].get<double>();
        // The metrics under the catalogue's names, as in run.json and the leaderboard.
        nlohmann::json metric_values{{"lost_frames", r.failed_frames},
                                     {"failed_frames", r.failed_frames},
                                     {"dropped_frames", r.dropped_frames},
                                     {"ms_per_frame", ms},
                                     {"fps", ms > 0 ? 1000.0 / ms : 0.0}};
        nlohmann::json j{{"frames", r.frames.size()},
                         {"metrics", nullptr},
                         {"timing", timing},
                         {"timing_protocol", timing_protocol(options.timing, -1, allowed_cpus(), -1)}};
        if (r.evaluation) {
            for (const auto& [name, value] : metrics::flatten(*r.evaluation)) metric_values[name] = value;
            j["protocol"] = metrics::protocol_json(r.evaluation->protocol);
        } else {
            spdlog::warn("no evaluation: {}", r.evaluation_error);
        }
        j["metrics"] = metric_values;
        if (!r.error.empty()) j["error"] = r.error;
        if (json) {
            std::cout << json_text(j) << std::endl;
        } else {
            std::cout << fmt::format("{} ({}): {} frames, {} not tracked, {:.3f} ms/frame ({:.1f} fps) in the plugin\n", r.sequence,
                                     r.sensor, r.frames.size(), r.failed_frames, ms, ms > 0 ? 1000.0 / ms : 0.0);
            if (options.timing.mode == "realtime")
                std::cout << fmt::format("real time (x{}): {} frames dropped (arrived while the plugin was busy), {} processed\n",
                                         options.timing.speed, r.dropped_frames, r.frames.size() - r.dropped_frames);
            if (r.evaluation && r.evaluation->ate) std::cout << fmt::format("ATE rmse {:.6f} m\n", r.evaluation->ate->stats.rmse);
            if (r.evaluation && r.evaluation->rpe)
                std::cout << fmt::format("RPE (delta {} {}) rmse {:.6f} m, {:.6f} deg\n", r.evaluation->protocol.rpe_delta,
                                         metrics::delta_unit_name(r.evaluation->protocol.rpe_unit), r.evaluation->rpe->trans.rmse,
                                         r.evaluation->rpe->rot_deg.rmse);
        }
        if (!r.error.empty()) spdlog::error("{}", r.error);
        exit_code = r.error.empty() ? 0 : 1;
    });
}

}  // namespace vobench::cli
