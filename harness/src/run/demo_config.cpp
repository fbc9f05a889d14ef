#include "run/demo_config.hpp"

#include "synth/trajectory_families.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <set>

namespace vobench {
namespace {

class Reader {
public:
    explicit Reader(std::string file) : file_(std::move(file)) {}

    [[noreturn]] void fail(const YAML::Node& at, const std::string& message) const {
        const YAML::Mark m = at.Mark();
        throw ConfigError(fmt::format("{}:{}:{}: {}", file_, m.line + 1, m.column + 1, message));
    }
    void only_keys(const YAML::Node& map, const std::set<std::string>& allowed, const std::string& what) const {
        if (!map.IsMap()) fail(map, what + " must be a mapping");
        for (const auto& kv : map) {
            const std::string key = kv.first.as<std::string>();
            if (!allowed.count(key)) {
                std::string list;
                for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
                fail(kv.first, fmt::format("unknown key '{}' in {} (known: {})", key, what, list));
            }
        }
    }
    template <typename T>
    T scalar(const YAML::Node& node, const std::string& what) const {
        if (!node.IsScalar()) fail(node, what + " must be a single value");
        try {
            return node.as<T>();
        } catch (const YAML::Exception&) {
            fail(node, fmt::format("{}: '{}' is not of the expected type", what, node.Scalar()));
        }
    }

private:
    std::string file_;
};

}  // namespace

DemoConfig load_demo_config(const std::filesystem::path& path, const PluginRegistry& registry) {
    YAML::Node root;
    try {
        root = YAML::LoadFile(path.string());
    } catch (const YAML::BadFile&) {
        throw ConfigError(path.string() + ": cannot open file");
    } catch (const YAML::ParserException& e) {
        throw ConfigError(fmt::format("{}:{}:{}: {}", path.string(), e.mark.line + 1, e.mark.column + 1, e.msg));
    }
    const Reader r(path.string());
    DemoConfig c;
    r.only_keys(root, {"data", "output", "seed", "frames", "sequences", "algorithms"}, "the configuration");
    if (root["data"]) c.data = r.scalar<std::string>(root["data"], "data");
    if (root["output"]) c.output = r.scalar<std::string>(root["output"], "output");
    if (root["seed"]) c.seed = r.scalar<uint64_t>(root["seed"], "seed");
    if (root["frames"]) c.frames = r.scalar<uint64_t>(root["frames"], "frames");
    if (c.frames < 5) r.fail(root["frames"], "frames must be at least 5 (RPE needs Δ = 4)");

    const YAML::Node sequences = root["sequences"];
    if (!sequences || !sequences.IsSequence() || sequences.size() == 0) r.fail(sequences ? sequences : root, "sequences: a non-empty list is required");
    for (const YAML::Node& s : sequences) {
        r.only_keys(s, {"sensor", "trajectory"}, "a sequence");
        DemoSequence d{r.scalar<std::string>(s["sensor"], "sensor"), r.scalar<std::string>(s["trajectory"], "trajectory")};
        if (d.sensor != "kinect1" && d.sensor != "kinect2") r.fail(s["sensor"], "sensor '" + d.sensor + "' is not kinect1 or kinect2");
        if (!synth::is_trajectory_family(d.trajectory))
            r.fail(s["trajectory"], "trajectory '" + d.trajectory + "' is not one of explore1..4, speed1..4");
        c.sequences.push_back(d);
    }

    const YAML::Node algorithms = root["algorithms"];
    if (!algorithms || !algorithms.IsSequence() || algorithms.size() == 0)
        r.fail(algorithms ? algorithms : root, "algorithms: a non-empty list is required");
    for (const YAML::Node& a : algorithms) {
        r.only_keys(a, {"plugin", "params"}, "an algorithm");
        DemoAlgorithm d;
        d.plugin = r.scalar<std::string>(a["plugin"], "plugin");
        PluginPtr plugin;
        try {
            plugin = registry.find(d.plugin, VOBENCH_KIND_ODOMETRY);
        } catch (const PluginLoadError& e) {
            r.fail(a["plugin"], e.what());
        }
        if (const YAML::Node params = a["params"]) {
            if (!params.IsMap()) r.fail(params, "params must be a mapping");
            for (const auto& kv : params) {
                const std::string key = kv.first.as<std::string>();
                const std::string value = r.scalar<std::string>(kv.second, "parameter " + key);
                try {
                    validate_params(*plugin, {{key, value}});
                } catch (const std::invalid_argument& e) {
                    r.fail(kv.first, e.what());
                }
                d.params[key] = value;
            }
        }
        c.algorithms.push_back(d);
    }
    return c;
}

}  // namespace vobench
