// demo_config.hpp — the YAML file `vobench demo` reads (configs/quickstart.yaml), validated in full
// before anything runs: unknown keys, wrong types, unknown sensors, trajectories or plugins, and
// parameters outside a plugin's table are reported with file, line and column.
#pragma once

#include "abi/instances.hpp"
#include "abi/plugin_registry.hpp"

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace vobench {

struct DemoSequence {
    std::string sensor, trajectory;
};

struct DemoAlgorithm {
    std::string plugin;
    ParamMap params;
};

struct DemoConfig {
    std::filesystem::path data = "datasets/synthetic", output = "results/demo";
    uint64_t seed = 1, frames = 50;
    std::vector<DemoSequence> sequences;
    std::vector<DemoAlgorithm> algorithms;
};

class ConfigError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Throws ConfigError("file:line:column: message").
DemoConfig load_demo_config(const std::filesystem::path& path, const PluginRegistry& registry);

}  // namespace vobench
