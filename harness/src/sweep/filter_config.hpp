// filter_config.hpp — a config's `filters:` chain (issue #20): perturbation plugins between reader and
// algorithm, their parameters swept like an algorithm's.
#pragma once

#include "abi/params.hpp"
#include "abi/plugin_registry.hpp"
#include "sweep/yaml_reader.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace vobench {

// One filter of a chain with one value per parameter.
struct FilterChainItem {
    std::string plugin;  // name or path, as the config gives it
    std::string name;    // the descriptor's name
    std::filesystem::path file;
    ParamMap params;
};

// filters: [{plugin: depth_holes, params: {fraction: [0, 0.1, 0.2], radius: 6}}, …] — a list value is
// swept; the chains are the cartesian product of every list, each value checked where it was written.
std::vector<std::vector<FilterChainItem>> read_filters(const YamlReader& r, const YAML::Node& list, const PluginRegistry& registry);

}  // namespace vobench
