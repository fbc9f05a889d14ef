// vobench data info — describe a sequence through its reader plugin.
#include "cli/commands.hpp"
#include "track/track.hpp"
#include "util/files.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <iostream>

namespace vobench::cli {

void add_data_command(CLI::App& app, int& exit_code) {
    auto* data = app.add_subcommand("data", "Data set tools");
    data->require_subcommand(1);
    auto* info = data->add_subcommand("info", "Describe a sequence as its reader sees it");
    static std::string dataset, path, sensor;
    static std::vector<std::string> options;
    static bool json = false;
    info->add_option("--dataset", dataset, "Dataset reader plugin (name or path)")->required();
    info->add_option("--path", path, "Sequence folder")->required();
    info->add_option("--sensor", sensor, "Sensor, passed to the reader as option sensor=S");
    info->add_option("--option", options, "Reader option key=value (repeatable)");
    info->add_flag("--json", json, "Print JSON");
    info->callback([&exit_code] {
        ParamMap opts = parse_key_values(options, "--option");
        if (!sensor.empty()) opts["sensor"] = sensor;
        DatasetInstance d(PluginRegistry().load(dataset, VOBENCH_KIND_DATASET));
        d.open(path, opts);
        const vobench_sequence_info& s = d.info();
        const metrics::Trajectory gt = ground_truth_of(s);
        double duration = 0;
        if (s.frame_count > 1) duration = d.read(s.frame_count - 1).timestamp - d.read(0).timestamp;
        nlohmann::json j{{"name", s.name ? s.name : ""},
                         {"sensor", s.sensor ? s.sensor : ""},
                         {"frames", s.frame_count},
                         {"width", s.camera->width},
                         {"height", s.camera->height},
                         {"depth_width", s.depth_width},
                         {"depth_height", s.depth_height},
                         {"fx", s.camera->fx},
                         {"fy", s.camera->fy},
                         {"cx", s.camera->cx},
                         {"cy", s.camera->cy},
                         {"distortion", std::vector<double>(s.camera->distortion, s.camera->distortion + s.camera->distortion_count)},
                         {"depth_scale", s.depth_scale},
                         {"gt_poses", gt.size()},
                         {"duration_s", duration}};
        if (json) {
            std::cout << json_text(j) << std::endl;
        } else {
            std::cout << fmt::format(
                "{} ({}): {} frames {}x{} (depth sensor {}x{}), fx {} fy {} cx {} cy {}, depth scale {}, "
                "{} ground-truth poses, {:.3f} s\n",
                j["name"].get<std::string>(), j["sensor"].get<std::string>(), s.frame_count, s.camera->width, s.camera->height,
                s.depth_width, s.depth_height, s.camera->fx, s.camera->fy, s.camera->cx, s.camera->cy, s.depth_scale, gt.size(), duration);
        }
        exit_code = 0;
    });
}

}  // namespace vobench::cli
