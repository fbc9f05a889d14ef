#include "record/cell.hpp"

#include <algorithm>
#include <stdexcept>

namespace vobench {

namespace {
nlohmann::json cell_fields(const Cell& c);
}  // namespace

int64_t Cell::frames_required() const {
    if (frames_declared < 0) return -1;
    return max_frames > 0 ? std::min<int64_t>(frames_declared, static_cast<int64_t>(max_frames)) : frames_declared;
}

std::string Cell::base_entry_label() const { return params.empty() ? algorithm : algorithm + " [" + variant_label() + "]"; }

std::string Cell::filter_label() const {
    std::string label;
    for (const CellFilter& f : filters) {
        label += (label.empty() ? "" : " + ") + f.plugin;
        for (const auto& [k, v] : f.params) label += " " + k + "=" + v;
    }
    return label;
}

std::string Cell::entry_label() const { return filters.empty() ? base_entry_label() : base_entry_label() + " | " + filter_label(); }

nlohmann::json timing_spec_json(const TimingSpec& t) { return {{"mode", t.mode}, {"speed", t.speed}, {"warmup_frames", t.warmup_frames}}; }

TimingSpec timing_spec_from_json(const nlohmann::json& j) {
    TimingSpec t;
    t.mode = j.at("mode").get<std::string>();
    t.speed = j.at("speed").get<double>();
    t.warmup_frames = j.at("warmup_frames").get<uint64_t>();
    if ((t.mode != "offline" && t.mode != "realtime") || !(t.speed > 0 && t.speed < 1e6))
        throw std::invalid_argument("timing: mode must be offline or realtime and speed positive");
    return t;
}

nlohmann::json cell_to_json(const Cell& c) {
    nlohmann::json j = cell_fields(c);
    // Absent when default: the ids of cells recorded before timing existed stay what they were.
    if (!c.timing.is_default()) j["timing"] = timing_spec_json(c.timing);
    if (!c.filters.empty()) {
        j["filters"] = nlohmann::json::array();
        for (const CellFilter& f : c.filters)
            j["filters"].push_back(
                {{"plugin", f.plugin}, {"plugin_file", f.plugin_file}, {"plugin_hash", f.plugin_hash}, {"params", f.params}});
    }
    return j;
}

namespace {
nlohmann::json cell_fields(const Cell& c) {
    return {{"id", c.id},
            {"dataset", c.dataset},
            {"sequence", c.sequence},
            {"sensor", c.sensor},
            {"reader", c.reader},
            {"path", c.path},
            {"reader_options", c.reader_options},
            {"dataset_checksum", c.dataset_checksum},
            {"reader_hash", c.reader_hash},
            {"gt_accuracy", {{"position_m", c.gt_accuracy.position_m}, {"rotation_deg", c.gt_accuracy.rotation_deg}}},
            {"algorithm", c.algorithm},
            {"plugin", c.plugin},
            {"plugin_file", c.plugin_file},
            {"plugin_hash", c.plugin_hash},
            {"load_error", c.load_error},
            {"params", c.params},
            {"repeat", c.repeat},
            {"seed", c.seed},
            {"max_frames", c.max_frames},
            {"frames_declared", c.frames_declared},
            {"protocol", metrics::protocol_json(c.protocol)},
            {"limits", {{"timeout_s", c.limits.timeout_s}, {"memory_mb", c.limits.memory_mb}, {"threads", c.limits.threads}}}};
}
}  // namespace

Cell cell_from_json(const nlohmann::json& j) {
    Cell c;
    c.id = j.at("id");
    c.dataset = j.at("dataset");
    c.sequence = j.at("sequence");
    c.sensor = j.at("sensor");
    c.reader = j.at("reader");
    c.path = j.at("path");
    c.reader_options = j.at("reader_options").get<ParamMap>();
    c.dataset_checksum = j.at("dataset_checksum");
    c.reader_hash = j.at("reader_hash");
    c.gt_accuracy.position_m = j.at("gt_accuracy").at("position_m");
    c.gt_accuracy.rotation_deg = j.at("gt_accuracy").at("rotation_deg");
    c.algorithm = j.at("algorithm");
    c.plugin = j.at("plugin");
    c.plugin_file = j.at("plugin_file");
    c.plugin_hash = j.at("plugin_hash");
    c.load_error = j.at("load_error");
    c.params = j.at("params").get<ParamMap>();
    c.repeat = j.at("repeat");
    c.seed = j.at("seed");
    c.max_frames = j.at("max_frames");
    c.frames_declared = j.value("frames_declared", int64_t{-1});
    c.protocol = metrics::protocol_from_json(j.at("protocol"));
    c.limits.timeout_s = j.at("limits").at("timeout_s");
    c.limits.memory_mb = j.at("limits").at("memory_mb");
    c.limits.threads = j.at("limits").at("threads");
    if (j.contains("timing")) c.timing = timing_spec_from_json(j.at("timing"));
    if (j.contains("filters"))
        for (const auto& f : j.at("filters"))
            c.filters.push_back({f.at("plugin").get<std::string>(), f.at("plugin_file").get<std::string>(),
                                 f.at("plugin_hash").get<std::string>(), f.at("params").get<ParamMap>()});
    return c;
}

}  // namespace vobench
