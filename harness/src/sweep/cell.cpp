#include "sweep/cell.hpp"

#include "sweep/dataset_prep.hpp"
#include "sweep/sequence_probe.hpp"
#include "util/files.hpp"
#include "util/hash.hpp"

#include <fnmatch.h>

#include <map>
#include <optional>

namespace vobench {
namespace fs = std::filesystem;

std::string Cell::variant_label() const {
    std::string label;
    for (const auto& [k, v] : params) label += (label.empty() ? "" : " ") + k + "=" + v;
    return label.empty() ? "defaults" : label;
}

namespace {

std::string file_hash(const fs::path& file) {
    Hasher h;
    hash_file(h, file);
    return h.hex();
}

// The id: every field that defines the result, not the limits (a longer timeout does not change what
// a finished cell computed) and not the id itself.
std::string cell_id(const Cell& c) {
    nlohmann::json j = cell_to_json(c);
    j.erase("id");
    j.erase("limits");
    j.erase("path");             // the content checksum stands for it: a moved data set keeps its results
    j.erase("plugin_file");      // the binary hash stands for it
    j.erase("frames_declared");  // derived from the reader and the checksum
    Hasher h;
    h.add(json_text(j, -1));
    // A parameter naming a file (a Python module, a vocabulary, a model) stands for its content too:
    // an edited module must not be taken for the finished cell of the old one.
    for (const auto& [key, value] : c.params) {
        std::error_code ec;
        if (value.empty() || value.size() > 4096 || !fs::is_regular_file(value, ec)) continue;
        try {
            h.add("file parameter " + key + " " + file_hash(value));
        } catch (const std::exception&) {
            h.add("file parameter " + key + " unreadable");
        }
    }
    return h.hex();
}

}  // namespace

std::vector<Cell> expand_cells(const SweepConfig& config, const PluginRegistry& registry, const fs::path& out, bool render) {
    std::map<fs::path, std::string> filter_hashes;  // each filter binary hashed once
    const auto filter_hash = [&](const fs::path& file) {
        auto it = filter_hashes.find(file);
        return it != filter_hashes.end() ? it->second : filter_hashes[file] = file_hash(file);
    };
    const fs::path memo = out / ".cache" / "checksums.json";
    // Each algorithm's binary, found and hashed once (not once per sequence).
    std::vector<std::pair<std::string, std::string>> binaries;  // (file, hash) per algorithm
    for (const AlgorithmSpec& a : config.algorithms) {
        std::optional<fs::path> file;
        if (a.load_error.empty())
            file = registry.describe(a.plugin, VOBENCH_KIND_ODOMETRY).path;
        else
            file = registry.locate(a.plugin);
        binaries.emplace_back(file ? fs::absolute(*file).lexically_normal().string() : "", file ? file_hash(*file) : "");
    }
    std::vector<Cell> cells;
    for (const DatasetSpec& d : config.datasets) {
        const PluginInfo reader = registry.describe(d.reader, VOBENCH_KIND_DATASET);
        const std::string reader_hash = file_hash(reader.path);
        for (const SequenceRef& s : prepare_sequences(d, registry, render)) {
            const std::string checksum = fs::is_directory(s.path) ? dataset_checksum(s.path, memo) : "to-render";
            const PluginInfo sequence_reader = s.reader == d.reader ? reader : registry.describe(s.reader, VOBENCH_KIND_DATASET);
            const int64_t declared = render && checksum != "to-render"
                                         ? probe_frame_count(fs::absolute(sequence_reader.path).string(), file_hash(sequence_reader.path),
                                                             s.path, s.options, checksum, out, config.limits.timeout_s)
                                         : -1;
            for (std::size_t ai = 0; ai < config.algorithms.size(); ++ai) {
                const AlgorithmSpec& a = config.algorithms[ai];
                const auto& [plugin_file, plugin_hash] = binaries[ai];
                for (const auto& chain : config.filter_variants)
                    for (std::size_t vi = 0; vi < a.variants.size(); ++vi)
                        for (std::size_t r = 0; r < config.seeds.size(); ++r) {
                            const ParamMap& params = a.variants[vi];
                            Cell c;
                            c.dataset = d.name;
                            c.sequence = s.name;
                            c.sensor = s.sensor;
                            c.reader = s.reader;
                            c.path = fs::absolute(s.path).lexically_normal().string();
                            c.reader_options = s.options;
                            c.dataset_checksum = checksum;
                            c.reader_hash = reader_hash;
                            c.gt_accuracy = d.gt_accuracy;
                            c.algorithm = a.name;
                            c.plugin = a.plugin;
                            c.plugin_file = plugin_file;
                            c.plugin_hash = plugin_hash;
                            c.load_error = a.load_error;
                            if (c.load_error.empty() && vi < a.variant_errors.size()) c.load_error = a.variant_errors[vi];
                            c.params = params;
                            c.repeat = r;
                            c.seed = config.seeds[r];
                            c.max_frames = config.max_frames;
                            c.frames_declared = declared;
                            c.protocol = config.protocol;
                            c.limits = config.limits;
                            c.timing = config.timing;
                            for (const FilterChainItem& f : chain)
                                c.filters.push_back(
                                    {f.name, fs::absolute(f.file).lexically_normal().string(), filter_hash(f.file), f.params});
                            c.id = cell_id(c);
                            cells.push_back(std::move(c));
                        }
            }
        }
    }
    return cells;
}

bool cell_matches(const Cell& c, const std::string& pattern) {
    const std::string key = c.dataset + "/" + c.sequence + "/" + c.sensor + "/" + c.algorithm + "/" + c.id;
    return fnmatch(pattern.c_str(), key.c_str(), 0) == 0 || fnmatch(("*" + pattern + "*").c_str(), key.c_str(), 0) == 0;
}

}  // namespace vobench
