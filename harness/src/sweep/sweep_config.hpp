// sweep_config.hpp — a sweep's YAML file (configs/*.yaml), read and validated in full before anything
// runs. Every complaint (unknown key, wrong type, unknown plugin, parameter outside the plugin's table,
// missing path) is a ConfigError "file:line:column: message".
//
// The format, key by key, is documented in configs/README.md. Relative paths are taken from the
// current directory; `${VAR}` and `${VAR:-default}` in a path are replaced from the environment.
#pragma once

#include "abi/instances.hpp"
#include "abi/plugin_registry.hpp"
#include "metrics/evaluation.hpp"
#include "record/cell.hpp"
#include "record/criterion.hpp"
#include "sweep/filter_config.hpp"
#include "sweep/yaml_reader.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace vobench {

// Sequences the generator renders (once, cached) instead of a folder on disk.
struct SyntheticSpec {
    std::vector<std::string> trajectories;  // families (explore1 …) or PUTK² marker files
    std::vector<std::string> names;         // the sequence name of each (default: family or file stem)
    std::vector<std::string> sensors{"kinect1"};
    uint64_t frames = 50;
    uint64_t seed = 1;
    std::filesystem::path cache = "datasets/synthetic";
};

struct DatasetSpec {
    std::string name;
    std::string reader = "tum";
    std::optional<SyntheticSpec> synthetic;
    std::string path;                    // may hold {sensor}
    std::vector<std::string> sequences;  // sub-folders of path; empty: path is the sequence
    std::vector<std::string> sensors;    // empty: the sensor the reader reports
    ParamMap options;                    // reader options
    GroundTruthAccuracy gt_accuracy;
    std::string where;  // file:line:col of the entry

    // The folders on disk, one per (sequence, sensor), in that order: path with {sensor} filled in,
    // plus the sequence's sub-folder. Not for synthetic datasets.
    struct Folder {
        std::string sequence, sensor;
        std::filesystem::path path;
    };
    std::vector<Folder> folders() const;
};

struct AlgorithmSpec {
    std::string name;                // label in tables (default: the plugin name)
    std::string plugin;              // name or path
    std::vector<ParamMap> variants;  // one per point of the parameter sweep (at least one)
    std::string load_error;          // the plugin exists but refused to load: its cells fail
    // API 3 plugins (python module=FILE): per variant, why the plugin could not say which parameters it
    // takes for those values (an import error, a crash); "" where it could. Those cells fail.
    std::vector<std::string> variant_errors;
    std::string where;
};

struct SweepConfig {
    std::filesystem::path file;
    std::string name;
    std::filesystem::path output = "results/sweep";
    std::vector<uint64_t> seeds{1};  // one repeat per seed
    uint64_t max_frames = 0;         // 0: every frame
    std::vector<DatasetSpec> datasets;
    std::vector<AlgorithmSpec> algorithms;
    metrics::Protocol protocol;
    std::string rank_by = "ate.rmse";
    Limits limits;
    TimingSpec timing;
    // Each variant is one chain of filters applied to every cell (empty list: one variant, no filter).
    std::vector<std::vector<FilterChainItem>> filter_variants{{}};
    std::string backend = "local";
    std::vector<Criterion> criteria;
    nlohmann::json source;  // the whole file as JSON, for the record
};

// Metric names a config may rank by or set criteria on (the catalogue's, metrics/metric_catalog.hpp).
const std::vector<std::string>& known_metric_names();

// The part of a config the report needs, kept in <out>/sweep.json.
nlohmann::json sweep_record(const SweepConfig& config);

// Throws ConfigError. Plugins are looked up in `registry`; a path that does not exist is an error
// unless `check_paths` is false (for `--dry-run` on another machine's config).
SweepConfig load_sweep_config(const std::filesystem::path& file, const PluginRegistry& registry, bool check_paths = true);

// "${HOME}/data" → "/root/data"; "${X:-d}" → d when X is unset or empty.
std::string expand_env(const std::string& text);

}  // namespace vobench
