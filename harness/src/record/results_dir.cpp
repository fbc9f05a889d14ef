#include "record/results_dir.hpp"

#include "metrics/trajectory_io.hpp"
#include "util/files.hpp"

#include <algorithm>
#include <chrono>

namespace vobench {
namespace fs = std::filesystem;

std::vector<std::string> ResultsDir::run_ids() const {
    std::vector<std::string> ids;
    std::error_code ec;
    for (fs::directory_iterator it(runs(), ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (!name.empty() && name.front() != '.' && it->is_directory(ec)) ids.push_back(name);
    }
    std::sort(ids.begin(), ids.end());
    return ids;
}

std::vector<std::string> ResultsDir::expected_ids() const {
    std::vector<std::string> ids;
    const nlohmann::json cells = read_json_or_null(cells_json());
    if (!cells.is_array()) return ids;
    for (const auto& c : cells)
        if (c.is_object() && c.contains("id") && c["id"].is_string()) ids.push_back(c["id"]);
    return ids;
}

std::string record_problem(const fs::path& dir, const std::string& id) {
    const fs::path file = dir / "run.json";
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) return "no run.json";
    const nlohmann::json run = read_json_or_null(file, std::uintmax_t{64} << 20);
    if (!run.is_object()) return "run.json is not a JSON object (truncated or corrupt)";
    if (!run.contains("schema_version") || run["schema_version"] != 1) return "run.json has no schema_version 1";
    if (!run.contains("cell") || !run["cell"].is_object() || run["cell"].value("id", std::string()) != id)
        return "run.json does not describe cell " + id;
    if (!run.contains("status") || (run["status"] != "ok" && run["status"] != "failed")) return "run.json has no status ok or failed";
    if (!run.contains("frames") || !run["frames"].is_number_unsigned()) return "run.json has no frame count";
    if (!run.contains("timing") || !run["timing"].is_object()) return "run.json has no timing";
    // Real-time mode: dropped frames were handled but have no pose.
    const uint64_t dropped =
        run.contains("dropped_frames") && run["dropped_frames"].is_number_unsigned() ? run["dropped_frames"].get<uint64_t>() : 0;
    if (dropped > run["frames"].get<uint64_t>()) return "run.json says more frames were dropped than handled";
    const uint64_t frames = run["frames"].get<uint64_t>() - dropped;
    if (frames == 0) return "";
    try {
        const std::size_t poses = metrics::read_trajectory(dir / "trajectory.txt").poses.size();
        if (poses != frames)
            return "trajectory.txt holds " + std::to_string(poses) + " poses, run.json says " + std::to_string(frames) +
                   (dropped > 0 ? " (" + std::to_string(dropped) + " more dropped)" : "");
    } catch (const std::exception& e) {
        return std::string("trajectory.txt: ") + e.what();
    }
    return "";
}

fs::path set_aside_corrupt(const ResultsDir& dir, const std::string& id) {
    const auto now = std::chrono::system_clock::now().time_since_epoch();
    const fs::path target = dir.corrupt() / (id + "." + std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(now).count()));
    fs::create_directories(dir.corrupt());
    fs::rename(dir.run_dir(id), target);
    return target;
}

}  // namespace vobench
