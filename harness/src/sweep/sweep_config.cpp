#include "sweep/sweep_config.hpp"

#include "abi/plugin_probe.hpp"
#include "metrics/metric_catalog.hpp"
#include "sweep/filter_config.hpp"
#include "synth/trajectory_families.hpp"

#include <cmath>
#include <cstdlib>
#include <regex>
#include <set>

namespace vobench {
namespace fs = std::filesystem;

namespace {

// The YAML tree as JSON (scalars as strings), kept in run.json as the config the cells came from.
nlohmann::json to_json_tree(const YAML::Node& n) {
    if (n.IsMap()) {
        nlohmann::json j = nlohmann::json::object();
        for (const auto& kv : n) j[kv.first.as<std::string>()] = to_json_tree(kv.second);
        return j;
    }
    if (n.IsSequence()) {
        nlohmann::json j = nlohmann::json::array();
        for (const auto& item : n) j.push_back(to_json_tree(item));
        return j;
    }
    if (n.IsScalar()) return n.Scalar();
    return nullptr;
}

// One axis of a parameter sweep: a list of values or a range {from, to, step} (inclusive, as numbers
// are written: 1e-9 of a step tolerance so that 0.1 steps reach their end).
struct Axis {
    std::string key;
    std::vector<std::string> values;
    std::vector<YAML::Node> nodes;  // where each value was written, for messages
};

Axis read_axis(const YamlReader& r, const std::string& key, const YAML::Node& node) {
    Axis axis{key, {}, {}};
    if (node.IsMap()) {
        r.only_keys(node, {"from", "to", "step"}, "a range");
        const double from = r.scalar<double>(r.required(node, "from", "a range"), "from");
        const double to = r.scalar<double>(r.required(node, "to", "a range"), "to");
        const double step = r.scalar<double>(r.required(node, "step", "a range"), "step");
        if (!(step > 0) || !(to >= from)) r.fail(node, "a range needs from <= to and step > 0");
        const auto count = static_cast<uint64_t>(std::floor((to - from) / step + 1e-9)) + 1;
        if (count > 10000) r.fail(node, fmt::format("this range has {} values; at most 10000", count));
        for (uint64_t k = 0; k < count; ++k) {
            axis.values.push_back(fmt::format("{:.12g}", from + static_cast<double>(k) * step));
            axis.nodes.push_back(node);
        }
    } else if (node.IsSequence() && node.size() > 0) {
        for (const YAML::Node& v : node) {
            axis.values.push_back(r.scalar<std::string>(v, "parameter " + key));
            axis.nodes.push_back(v);
        }
    } else {
        r.fail(node, "a swept parameter takes a non-empty list or a range {from, to, step}");
    }
    return axis;
}

// For a plugin whose instances declare parameters by the values of others (API 3, e.g. python's
// module=FILE): each variant against the table a probe child gets for it (one probe per distinct set
// of the table's own values).
// A plugin that fails to answer (a module that does not import) is a result, as a plugin that refuses
// to load: its error is returned per variant, for failed rows. A value it then does not take is a
// mistake in the config.
std::vector<std::string> check_extra_params(const YamlReader& r, const YAML::Node& at, const PluginInfo& plugin,
                                            const std::vector<ParamMap>& variants) {
    std::vector<std::string> errors;
    for (const ParamMap& variant : variants) {
        errors.emplace_back();
        PluginInfo extended;
        try {
            extended = probe_extra_params(plugin, variant);
        } catch (const PluginLoadError& e) {
            errors.back() = e.what();
            continue;
        }
        try {
            validate_params(extended, variant);
        } catch (const std::invalid_argument& e) {
            r.fail(at, e.what());
        }
    }
    return errors;
}

// params × grid (cartesian product) × zip (lists walked together), each value checked against the
// plugin's parameter table where it was written.
std::vector<ParamMap> read_variants(const YamlReader& r, const YAML::Node& a, const PluginInfo* plugin, std::vector<std::string>& errors) {
    const auto in_table = [&](const std::string& key) {
        for (std::size_t i = 0; i < plugin->table_size && i < plugin->params.size(); ++i)
            if (plugin->params[i].name == key) return true;
        return false;
    };
    const auto check = [&](const std::string& key, const std::string& value, const YAML::Node& at) {
        if (!plugin) return;
        if (plugin->has_extra_params && !in_table(key)) return;  // one the plugin may declare: checked per variant below
        try {
            validate_params(*plugin, {{key, value}});
        } catch (const std::invalid_argument& e) {
            r.fail(at, e.what());
        }
    };
    ParamMap fixed;
    if (const YAML::Node params = a["params"]) {
        if (!params.IsMap()) r.fail(params, "params must be a mapping");
        for (const auto& kv : params) {
            const std::string key = kv.first.as<std::string>();
            fixed[key] = r.scalar<std::string>(kv.second, "parameter " + key);
            check(key, fixed[key], kv.first);
        }
    }
    std::vector<ParamMap> variants{fixed};
    if (const YAML::Node grid = a["grid"]) {
        if (!grid.IsMap()) r.fail(grid, "grid must be a mapping of parameter: values");
        for (const auto& kv : grid) {
            const Axis axis = read_axis(r, kv.first.as<std::string>(), kv.second);
            if (fixed.count(axis.key)) r.fail(kv.first, "parameter '" + axis.key + "' is both fixed in params and swept");
            std::vector<ParamMap> next;
            for (const ParamMap& v : variants)
                for (std::size_t i = 0; i < axis.values.size(); ++i) {
                    check(axis.key, axis.values[i], axis.nodes[i]);
                    ParamMap m = v;
                    m[axis.key] = axis.values[i];
                    next.push_back(m);
                }
            variants = std::move(next);
        }
    }
    if (const YAML::Node zip = a["zip"]) {
        if (!zip.IsMap() || zip.size() == 0) r.fail(zip, "zip must be a mapping of parameter: list of the same length");
        std::vector<Axis> axes;
        for (const auto& kv : zip) {
            axes.push_back(read_axis(r, kv.first.as<std::string>(), kv.second));
            if (axes.back().values.size() != axes.front().values.size())
                r.fail(kv.second, fmt::format("zip: '{}' has {} values, '{}' has {}", axes.back().key, axes.back().values.size(),
                                              axes.front().key, axes.front().values.size()));
            for (const ParamMap& v : variants)
                if (v.count(axes.back().key)) r.fail(kv.first, "parameter '" + axes.back().key + "' is swept twice");
        }
        std::vector<ParamMap> next;
        for (const ParamMap& v : variants)
            for (std::size_t i = 0; i < axes.front().values.size(); ++i) {
                ParamMap m = v;
                for (const Axis& axis : axes) {
                    check(axis.key, axis.values[i], axis.nodes[i]);
                    m[axis.key] = axis.values[i];
                }
                next.push_back(m);
            }
        variants = std::move(next);
    }
    if (plugin && plugin->has_extra_params) errors = check_extra_params(r, a, *plugin, variants);
    return variants;
}

metrics::Protocol read_protocol(const YamlReader& r, const YAML::Node& p) {
    metrics::Protocol protocol;
    r.only_keys(p, {"name", "metrics", "alignment", "align_first", "rpe_delta", "rpe_unit", "max_difference", "offset"}, "protocol");
    try {
        if (p["name"]) protocol.name = metrics::parse_protocol(r.scalar<std::string>(p["name"], "protocol name"));
        if (p["alignment"]) protocol.alignment = metrics::parse_alignment(r.scalar<std::string>(p["alignment"], "alignment"));
        if (p["rpe_unit"]) protocol.rpe_unit = metrics::parse_delta_unit(r.scalar<std::string>(p["rpe_unit"], "rpe_unit"));
    } catch (const std::invalid_argument& e) {
        r.fail(p, e.what());
    }
    if (p["metrics"]) {
        const std::string m = r.scalar<std::string>(p["metrics"], "metrics");
        if (m != "ate" && m != "rpe" && m != "both") r.fail(p["metrics"], "metrics must be ate, rpe or both");
        protocol.ate = m != "rpe";
        protocol.rpe = m != "ate";
    }
    if (p["align_first"]) protocol.align_first = r.scalar<std::size_t>(p["align_first"], "align_first");
    if (p["rpe_delta"]) protocol.rpe_delta = r.scalar<double>(p["rpe_delta"], "rpe_delta");
    if (p["max_difference"]) protocol.association.max_difference = r.scalar<double>(p["max_difference"], "max_difference");
    if (p["offset"]) protocol.association.offset = r.scalar<double>(p["offset"], "offset");
    if (!(protocol.rpe_delta > 0)) r.fail(p["rpe_delta"], "rpe_delta must be positive");
    if (!(protocol.association.max_difference > 0)) r.fail(p["max_difference"], "max_difference must be positive");
    return protocol;
}

DatasetSpec read_dataset(const YamlReader& r, const YAML::Node& d, const PluginRegistry& registry, bool check_paths) {
    r.only_keys(d, {"name", "reader", "path", "sequences", "sensors", "options", "synthetic", "ground_truth_accuracy"}, "a dataset");
    DatasetSpec s;
    s.where = r.where(d);
    s.name = r.scalar<std::string>(r.required(d, "name", "a dataset"), "name");
    if (const YAML::Node syn = d["synthetic"]) {
        if (d["path"] || d["sequences"] || d["sensors"] || d["reader"])
            r.fail(syn, "a synthetic dataset takes its trajectories and sensors inside synthetic:, not path/sequences/sensors/reader");
        r.only_keys(syn, {"trajectories", "sensors", "frames", "seed", "cache"}, "synthetic");
        SyntheticSpec spec;
        // Each item: a family or file, or {name: seq1, trajectory: FILE} to name the sequence.
        const YAML::Node trajectories = r.required(syn, "trajectories", "synthetic");
        if (!trajectories.IsSequence() || trajectories.size() == 0) r.fail(trajectories, "trajectories must be a non-empty list");
        for (const YAML::Node& item : trajectories) {
            std::string t, name;
            YAML::Node at = item;
            if (item.IsMap()) {
                r.only_keys(item, {"name", "trajectory"}, "a trajectory");
                at.reset(r.required(item, "trajectory", "a trajectory"));
                t = r.scalar<std::string>(at, "trajectory");
                if (item["name"]) name = r.scalar<std::string>(item["name"], "name");
            } else {
                t = r.scalar<std::string>(item, "trajectory");
            }
            if (!synth::is_trajectory_family(t)) {
                t = expand_env(t);
                if (check_paths && !fs::exists(t))
                    r.fail(at, "trajectory '" + t + "' is neither explore1..4, speed1..4 nor an existing PUTK² marker file");
            }
            if (name.empty()) name = synth::is_trajectory_family(t) ? t : fs::path(t).stem().string();
            spec.trajectories.push_back(t);
            spec.names.push_back(name);
        }
        if (syn["sensors"]) spec.sensors = r.scalars(syn["sensors"], "sensors");
        for (const std::string& sensor : spec.sensors)
            if (sensor != "kinect1" && sensor != "kinect2") r.fail(syn["sensors"], "sensor '" + sensor + "' is not kinect1 or kinect2");
        if (syn["frames"]) spec.frames = r.scalar<uint64_t>(syn["frames"], "frames");
        if (spec.frames < 5) r.fail(syn["frames"] ? syn["frames"] : syn, "frames must be at least 5 (RPE needs Δ = 4)");
        if (syn["seed"]) spec.seed = r.scalar<uint64_t>(syn["seed"], "seed");
        if (syn["cache"]) spec.cache = expand_env(r.scalar<std::string>(syn["cache"], "cache"));
        s.synthetic = spec;
        s.sensors = spec.sensors;
        // The generator's sensor model has a millimetre-exact ground truth by construction.
        s.gt_accuracy = {0.0, 0.0};
    } else {
        s.path = expand_env(r.scalar<std::string>(r.required(d, "path", "a dataset"), "path"));
        if (d["reader"]) s.reader = r.scalar<std::string>(d["reader"], "reader");
        if (d["sequences"]) s.sequences = r.scalars(d["sequences"], "sequences");
        if (d["sensors"]) s.sensors = r.scalars(d["sensors"], "sensors");
    }
    PluginInfo reader;
    try {
        reader = registry.describe(s.reader, VOBENCH_KIND_DATASET);
    } catch (const PluginLoadError& e) {
        r.fail(d["reader"] ? d["reader"] : d, e.what());
    }
    if (const YAML::Node options = d["options"]) {
        if (!options.IsMap()) r.fail(options, "options must be a mapping");
        for (const auto& kv : options) {
            const std::string key = kv.first.as<std::string>();
            s.options[key] = r.scalar<std::string>(kv.second, "option " + key);
            if (reader.has_extra_params && table_params(reader, {{key, ""}}).empty()) continue;  // checked below
            try {
                validate_params(reader, {{key, s.options[key]}});
            } catch (const std::invalid_argument& e) {
                r.fail(kv.first, e.what());
            }
        }
    }
    if (reader.has_extra_params)
        if (const auto errors = check_extra_params(r, d["options"] ? d["options"] : d, reader, {s.options}); !errors.front().empty())
            r.fail(d["reader"] ? d["reader"] : d, errors.front());
    if (!s.synthetic && !s.sensors.empty()) {
        bool has_sensor_option = false;
        for (const auto& p : reader.params) has_sensor_option |= p.name == "sensor";
        if (!has_sensor_option && s.path.find("{sensor}") == std::string::npos)
            r.fail(d["sensors"], "sensors: the reader '" + s.reader + "' has no 'sensor' option and the path has no {sensor}");
    }
    if (const YAML::Node acc = d["ground_truth_accuracy"]) {
        r.only_keys(acc, {"position_m", "rotation_deg"}, "ground_truth_accuracy");
        if (acc["position_m"]) s.gt_accuracy.position_m = r.scalar<double>(acc["position_m"], "position_m");
        if (acc["rotation_deg"]) s.gt_accuracy.rotation_deg = r.scalar<double>(acc["rotation_deg"], "rotation_deg");
        if ((acc["position_m"] && s.gt_accuracy.position_m < 0) || (acc["rotation_deg"] && s.gt_accuracy.rotation_deg < 0))
            r.fail(acc, "accuracies are non-negative (0: exact)");
    }
    if (check_paths && !s.synthetic)
        for (const auto& f : s.folders())
            if (!fs::is_directory(f.path))
                r.fail(d["sequences"] ? d["sequences"] : d["path"], "no such sequence folder: " + f.path.string());
    return s;
}

AlgorithmSpec read_algorithm(const YamlReader& r, const YAML::Node& a, const PluginRegistry& registry) {
    r.only_keys(a, {"name", "plugin", "params", "grid", "zip"}, "an algorithm");
    AlgorithmSpec s;
    s.where = r.where(a);
    s.plugin = r.scalar<std::string>(r.required(a, "plugin", "an algorithm"), "plugin");
    s.name = a["name"] ? r.scalar<std::string>(a["name"], "name") : s.plugin;
    std::optional<PluginInfo> plugin;
    try {
        plugin = registry.describe(s.plugin, VOBENCH_KIND_ODOMETRY);
    } catch (const PluginLoadError& e) {
        // A plugin that is not there at all is a mistake in the config; one that is there and refuses
        // to load (another ABI, a broken descriptor) is a result: its cells become failed rows.
        if (!registry.locate(s.plugin)) r.fail(a["plugin"], e.what());
        s.load_error = e.what();
    }
    s.variants = read_variants(r, a, plugin ? &*plugin : nullptr, s.variant_errors);
    return s;
}

}  // namespace

std::vector<DatasetSpec::Folder> DatasetSpec::folders() const {
    std::vector<Folder> out;
    const std::vector<std::string> all_sensors = sensors.empty() ? std::vector<std::string>{""} : sensors;
    const std::vector<std::string> all_sequences = sequences.empty() ? std::vector<std::string>{""} : sequences;
    for (const std::string& sequence : all_sequences)
        for (const std::string& sensor : all_sensors) {
            std::string base = path;
            if (const auto at = base.find("{sensor}"); at != std::string::npos) base.replace(at, 8, sensor);
            out.push_back({sequence, sensor, sequence.empty() ? fs::path(base) : fs::path(base) / sequence});
        }
    return out;
}

const std::vector<std::string>& known_metric_names() {
    static const std::vector<std::string> names = metrics::metric_names();
    return names;
}

std::string expand_env(const std::string& text) {
    static const std::regex var(R"(\$\{([A-Za-z_][A-Za-z0-9_]*)(:-([^}]*))?\})");
    std::string out;
    auto begin = text.cbegin();
    std::smatch m;
    while (std::regex_search(begin, text.cend(), m, var)) {
        out.append(begin, m[0].first);
        const char* value = std::getenv(m[1].str().c_str());
        out += value && *value ? std::string(value) : m[3].str();
        begin = m[0].second;
    }
    out.append(begin, text.cend());
    return out;
}

nlohmann::json sweep_record(const SweepConfig& c) {
    nlohmann::json criteria = nlohmann::json::array();
    for (const Criterion& k : c.criteria) criteria.push_back({{"criterion", k.text}, {"required", k.required}});
    return {{"name", c.name},
            {"config_file", c.file.string()},
            {"rank_by", c.rank_by},
            {"criteria", criteria},
            {"protocol", metrics::protocol_json(c.protocol)},
            {"config", c.source}};
}

SweepConfig load_sweep_config(const fs::path& file, const PluginRegistry& registry, bool check_paths) {
    const YamlReader r(file.string());
    const YAML::Node root = r.load();
    r.only_keys(root,
                {"name", "output", "seed", "repeats", "seeds", "frames", "datasets", "algorithms", "protocol", "rank_by", "limits",
                 "backend", "criteria", "timing", "filters"},
                "the configuration");
    SweepConfig c;
    c.file = file;
    c.source = to_json_tree(root);
    c.name = root["name"] ? r.scalar<std::string>(root["name"], "name") : file.stem().string();
    if (root["output"]) c.output = expand_env(r.scalar<std::string>(root["output"], "output"));
    const uint64_t seed = root["seed"] ? r.scalar<uint64_t>(root["seed"], "seed") : 1;
    if (root["seeds"] && root["repeats"]) r.fail(root["seeds"], "give either seeds: (a list) or repeats: (a count), not both");
    if (root["seeds"]) {
        c.seeds.clear();
        for (const std::string& s : r.scalars(root["seeds"], "seeds")) {
            try {
                c.seeds.push_back(std::stoull(s));
            } catch (const std::exception&) {
                r.fail(root["seeds"], "seed '" + s + "' is not a non-negative integer");
            }
        }
    } else {
        const uint64_t repeats = root["repeats"] ? r.scalar<uint64_t>(root["repeats"], "repeats") : 1;
        if (repeats < 1 || repeats > 1000) r.fail(root["repeats"], "repeats must be 1 … 1000");
        c.seeds.clear();
        for (uint64_t k = 0; k < repeats; ++k) c.seeds.push_back(seed + k);
    }
    if (root["frames"]) c.max_frames = r.scalar<uint64_t>(root["frames"], "frames");

    const YAML::Node datasets = root["datasets"];
    if (!datasets || !datasets.IsSequence() || datasets.size() == 0)
        r.fail(datasets ? datasets : root, "datasets: a non-empty list is required");
    std::set<std::string> names;
    for (const YAML::Node& d : datasets) {
        c.datasets.push_back(read_dataset(r, d, registry, check_paths));
        if (!names.insert(c.datasets.back().name).second) r.fail(d["name"], "dataset name '" + c.datasets.back().name + "' is used twice");
    }
    const YAML::Node algorithms = root["algorithms"];
    if (!algorithms || !algorithms.IsSequence() || algorithms.size() == 0)
        r.fail(algorithms ? algorithms : root, "algorithms: a non-empty list is required");
    names.clear();
    for (const YAML::Node& a : algorithms) {
        c.algorithms.push_back(read_algorithm(r, a, registry));
        if (!names.insert(c.algorithms.back().name).second)
            r.fail(a, "algorithm name '" + c.algorithms.back().name + "' is used twice (give one a name:)");
    }
    if (root["protocol"]) c.protocol = read_protocol(r, root["protocol"]);
    if (root["rank_by"]) {
        c.rank_by = r.scalar<std::string>(root["rank_by"], "rank_by");
        const auto& known = known_metric_names();
        if (std::find(known.begin(), known.end(), c.rank_by) == known.end())
            r.fail(root["rank_by"], "rank_by: unknown metric '" + c.rank_by + "'");
    }
    if (const YAML::Node l = root["limits"]) {
        r.only_keys(l, {"timeout", "memory_mb", "threads"}, "limits");
        if (l["timeout"]) c.limits.timeout_s = r.scalar<int>(l["timeout"], "timeout");
        if (l["memory_mb"]) c.limits.memory_mb = r.scalar<uint64_t>(l["memory_mb"], "memory_mb");
        if (l["threads"]) c.limits.threads = r.scalar<int>(l["threads"], "threads");
        if (c.limits.timeout_s < 1) r.fail(l["timeout"], "timeout must be at least 1 s");
        if (c.limits.memory_mb < 64) r.fail(l["memory_mb"], "memory_mb must be at least 64");
        if (c.limits.threads < 1) r.fail(l["threads"], "threads must be at least 1");
    }
    if (const YAML::Node t = root["timing"]) {  // `timing: realtime`, or {mode, speed, warmup_frames}
        const YAML::Node mode = t.IsMap() ? t["mode"] : t;
        if (t.IsMap()) r.only_keys(t, {"mode", "speed", "warmup_frames"}, "timing");
        if (mode) c.timing.mode = r.scalar<std::string>(mode, "timing mode");
        if (c.timing.mode != "offline" && c.timing.mode != "realtime") r.fail(mode ? mode : t, "timing mode must be offline or realtime");
        if (t.IsMap() && t["speed"]) c.timing.speed = r.scalar<double>(t["speed"], "speed");
        if (!(c.timing.speed > 0 && c.timing.speed <= 1000)) r.fail(t["speed"], "speed must be in (0, 1000]");
        if (t.IsMap() && t["warmup_frames"]) c.timing.warmup_frames = r.scalar<uint64_t>(t["warmup_frames"], "warmup_frames");
    }
    if (const YAML::Node filters = root["filters"]) c.filter_variants = read_filters(r, filters, registry);
    if (root["backend"]) {
        c.backend = r.scalar<std::string>(root["backend"], "backend");
        if (c.backend != "local" && c.backend != "slurm") r.fail(root["backend"], "backend must be local or slurm");
    }
    if (const YAML::Node criteria = root["criteria"]) {
        if (!criteria.IsSequence()) r.fail(criteria, "criteria must be a list");
        for (const YAML::Node& item : criteria) {
            std::string text;
            bool required = true;
            YAML::Node at = item;
            if (item.IsMap()) {
                r.only_keys(item, {"criterion", "required"}, "a criterion");
                at.reset(r.required(item, "criterion", "a criterion"));  // reset: `=` would overwrite the node itself
                text = r.scalar<std::string>(at, "criterion");
                if (item["required"]) required = r.scalar<bool>(item["required"], "required");
            } else {
                text = r.scalar<std::string>(item, "criterion");
            }
            try {
                Criterion crit = parse_criterion(text);
                crit.required = required;
                c.criteria.push_back(crit);
            } catch (const std::invalid_argument& e) {
                r.fail(at, e.what());
            }
        }
    }
    return c;
}

}  // namespace vobench
