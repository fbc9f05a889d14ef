#include "sweep/sequence_probe.hpp"

#include "abi/plugin_registry.hpp"
#include "util/files.hpp"
#include "util/hash.hpp"
#include "util/subprocess.hpp"

#include <unistd.h>
#include <cstdio>
#include <mutex>

namespace vobench {
namespace fs = std::filesystem;

int sequence_probe_main(const std::string& reader_file, const fs::path& sequence, const std::string& options_json, const fs::path& result) {
    nlohmann::json answer;
    try {
        DatasetInstance d(PluginRegistry().load(reader_file, VOBENCH_KIND_DATASET));
        d.open(sequence.string(), nlohmann::json::parse(options_json).get<ParamMap>());
        answer = {{"frame_count", d.info().frame_count}};
    } catch (const std::exception& e) {
        answer = {{"error", e.what()}};
    }
    write_json_atomic(result, answer);
    std::fflush(nullptr);
    ::_exit(0);  // plugin code's static destructors are not part of the answer
}

int64_t probe_frame_count(const std::string& reader_file, const std::string& reader_hash, const fs::path& sequence, const ParamMap& options,
                          const std::string& checksum, const fs::path& out, int timeout_s) {
    static std::mutex mutex;
    const std::lock_guard<std::mutex> lock(mutex);
    Hasher h;
    h.add(reader_hash + "\n" + nlohmann::json(options).dump() + "\n" + checksum);
    const std::string key = h.hex();
    const fs::path memo_file = out / ".cache" / "sequences.json";
    nlohmann::json memo = read_json_or_null(memo_file, 16 << 20);
    if (!memo.is_object()) memo = nlohmann::json::object();
    if (memo.contains(key) && memo[key].is_number_integer()) return memo[key].get<int64_t>();

    const fs::path result = fs::temp_directory_path() / ("vobench-sequence-" + std::to_string(::getpid()) + "-" + key + ".json");
    std::error_code ec;
    fs::remove(result, ec);
    ChildLimits limits;
    limits.timeout_s = timeout_s;
    limits.contain = true;
    const ChildResult child = run_self_limited(
        {"sequence-probe", reader_file, fs::absolute(sequence).string(), nlohmann::json(options).dump(), result.string()}, limits);
    const nlohmann::json answer = read_json_or_null(result, 1 << 20);
    fs::remove(result, ec);
    if (!(child.exited && child.exit_code == 0) || !answer.is_object() || !answer.contains("frame_count") ||
        !answer["frame_count"].is_number_unsigned())
        return -1;
    const int64_t count = static_cast<int64_t>(answer["frame_count"].get<uint64_t>());
    memo[key] = count;
    try {
        fs::create_directories(memo_file.parent_path());
        write_json_atomic(memo_file, memo);
    } catch (const std::exception&) {
        // only costs a probe next time
    }
    return count;
}

}  // namespace vobench
