#include "sweep/dataset_prep.hpp"

#include "metrics/trajectory_io.hpp"
#include "synth/sequence_writer.hpp"
#include "synth/trajectory_families.hpp"
#include "util/files.hpp"
#include "util/hash.hpp"
#include "util/subprocess.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include <fstream>

namespace vobench {
namespace fs = std::filesystem;

namespace {

// True when `dir` holds a complete sequence from this generator version.
bool rendered(const fs::path& dir) {
    if (!fs::exists(dir / "synth.json") || !fs::exists(dir / "groundtruth.txt")) return false;
    const nlohmann::json meta = read_json_or_null(dir / "synth.json");
    return meta.is_object() && meta.contains("generator_version") && meta["generator_version"] == synth::kGeneratorVersion;
}

// The folder name holds every parameter that defines the sequence, so a cached one is reused only
// when it is the same; a file trajectory is named by its stem and content hash.
fs::path ensure_rendered(const SyntheticSpec& spec, const std::string& trajectory, const std::string& sensor, bool render) {
    std::string label = trajectory;
    if (!synth::is_trajectory_family(trajectory)) {
        Hasher h;
        hash_file(h, trajectory);
        label = fs::path(trajectory).stem().string() + "-" + h.hex().substr(0, 8);
    }
    const fs::path dir = spec.cache / fmt::format("{}-{}-n{}-s{}", sensor, label, spec.frames, spec.seed);
    if (rendered(dir)) {
        spdlog::debug("using cached {}", dir.string());
        return dir;
    }
    if (!render) return dir;
    // Rendered by vobench-worker (OpenCV and TBB live there), with `vobench synth`'s defaults.
    const fs::path partial = dir.string() + ".partial";  // renamed into place only when complete
    fs::remove_all(partial);
    fs::create_directories(partial.parent_path());
    spdlog::info("rendering {} …", dir.string());
    ChildLimits limits;
    limits.timeout_s = 24 * 3600;
    limits.log = partial.string() + ".log";
    const ChildResult child =
        run_worker_limited({"synth", "--sensor", sensor, "--trajectory", trajectory, "--frames", std::to_string(spec.frames), "--seed",
                            std::to_string(spec.seed), "--out", partial.string()},
                           limits);
    if (!(child.exited && child.exit_code == 0) || !rendered(partial)) {
        std::string log;
        try {
            log = read_file(limits.log);
        } catch (const std::exception&) {}
        throw std::runtime_error(fmt::format("rendering {} failed ({}): {}", dir.string(), child.describe(),
                                             log.substr(log.size() > 2000 ? log.size() - 2000 : 0)));
    }
    std::error_code ec;
    fs::remove(limits.log, ec);
    fs::remove_all(dir);
    fs::rename(partial, dir);
    spdlog::info("rendered {} ({} frames, {:.1f} frames/s)", dir.string(), spec.frames,
                 static_cast<double>(spec.frames) / std::max(child.wall_s, 1e-9));
    return dir;
}

std::string signature_of(const fs::path& folder) {
    Hasher h;
    std::vector<std::string> lines;
    for (const auto& e : fs::recursive_directory_iterator(folder))
        if (e.is_regular_file())
            lines.push_back(fmt::format("{} {} {}", fs::relative(e.path(), folder).generic_string(), e.file_size(),
                                        e.last_write_time().time_since_epoch().count()));
    std::sort(lines.begin(), lines.end());
    for (const std::string& l : lines) h.add(l);
    return h.hex();
}

}  // namespace

std::vector<SequenceRef> prepare_sequences(const DatasetSpec& d, const PluginRegistry& registry, bool render) {
    std::vector<SequenceRef> out;
    if (d.synthetic) {
        for (std::size_t k = 0; k < d.synthetic->trajectories.size(); ++k)
            for (const std::string& sensor : d.synthetic->sensors) {
                const std::string& trajectory = d.synthetic->trajectories[k];
                const std::string& name = d.synthetic->names[k];
                try {
                    out.push_back({name, sensor, ensure_rendered(*d.synthetic, trajectory, sensor, render), "tum", d.options});
                } catch (const std::exception& e) {
                    throw std::runtime_error(
                        fmt::format("dataset '{}' ({}): rendering {} for {}: {}", d.name, d.where, trajectory, sensor, e.what()));
                }
            }
        return out;
    }
    bool reader_takes_sensor = false;
    for (const auto& p : registry.describe(d.reader, VOBENCH_KIND_DATASET).params) reader_takes_sensor |= p.name == "sensor";
    for (const DatasetSpec::Folder& f : d.folders()) {
        SequenceRef ref;
        ref.path = f.path;
        ref.name = f.sequence.empty() ? ref.path.lexically_normal().filename().string() : f.sequence;
        if (ref.name.empty()) ref.name = ref.path.lexically_normal().parent_path().filename().string();
        ref.sensor = f.sensor;
        ref.reader = d.reader;
        ref.options = d.options;
        if (!f.sensor.empty() && reader_takes_sensor) ref.options["sensor"] = f.sensor;
        if (!fs::is_directory(ref.path))
            throw std::runtime_error(fmt::format("dataset '{}' ({}): no such sequence folder: {}", d.name, d.where, ref.path.string()));
        out.push_back(ref);
    }
    return out;
}

std::string dataset_checksum(const fs::path& sequence, const fs::path& memo_file) {
    nlohmann::json memo = read_json_or_null(memo_file);
    if (!memo.is_object()) memo = nlohmann::json::object();
    const std::string key = fs::absolute(sequence).lexically_normal().string();
    const std::string signature = signature_of(sequence);
    // The memo is a file like any other: an entry of the wrong shape is recomputed.
    if (memo.contains(key) && memo[key].is_object() && memo[key].value("signature", nlohmann::json()) == signature &&
        memo[key].contains("checksum") && memo[key]["checksum"].is_string())
        return memo[key]["checksum"];
    Hasher h;
    hash_tree(h, sequence);
    const std::string checksum = h.hex();
    memo[key] = {{"signature", signature}, {"checksum", checksum}};
    fs::create_directories(memo_file.parent_path());
    write_file_atomic(memo_file, json_text(memo, 1) + "\n");
    return checksum;
}

}  // namespace vobench
