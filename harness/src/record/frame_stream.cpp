#include "record/frame_stream.hpp"

#include "util/files.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>

namespace vobench {

std::string encode_frame(const FrameRecord& f, const metrics::StampedPose& p) {
    if (f.dropped) return json_text(nlohmann::json{{"i", f.index}, {"t", f.stamp}, {"r", f.read_ns}, {"d", 1}}, -1) + "\n";
    nlohmann::json j{{"i", f.index},   {"t", f.stamp},    {"ns", f.process_ns},
                     {"r", f.read_ns}, {"s", f.tracking}, {"p", {p.p.x(), p.p.y(), p.p.z(), p.q.x(), p.q.y(), p.q.z(), p.q.w()}}};
    if (f.cpu_ns >= 0) j["cpu"] = f.cpu_ns;
    for (const auto& [name, ns] : f.stages) j["st"][name] = ns;
    for (const auto& [name, v] : f.counters) j["c"][name] = v;
    return json_text(j, -1) + "\n";
}

namespace {

bool finite_number(const nlohmann::json& v) { return v.is_number() && std::isfinite(v.get<double>()); }

// Why `j` is not frame `expected`, or "".
std::string check_line(const nlohmann::json& j, uint64_t expected) {
    if (!j.is_object()) return "not a JSON object";
    if (j.contains("d")) {  // a dropped frame: index, stamp, read time, nothing else
        if (j.size() != 4 || j["d"] != 1 || !j.contains("i") || !j.contains("t") || !j.contains("r")) return "a malformed dropped frame";
        if (!j["i"].is_number_unsigned() || j["i"].get<uint64_t>() != expected) return "frame index is not " + std::to_string(expected);
        if (!finite_number(j["t"]) || !j["r"].is_number_integer()) return "a dropped frame's stamp or time is not a number";
        return "";
    }
    if (j.contains("cpu") && !j["cpu"].is_number_integer()) return "the CPU time is not an integer";
    for (const char* key : {"i", "t", "ns", "r", "s", "p"})
        if (!j.contains(key)) return std::string("no field '") + key + "'";
    if (!j["i"].is_number_unsigned() || j["i"].get<uint64_t>() != expected) return "frame index is not " + std::to_string(expected);
    if (!finite_number(j["t"])) return "the stamp is not a finite number";
    if (!j["ns"].is_number_integer() || !j["r"].is_number_integer()) return "times are not integers";
    if (!j["s"].is_number_integer() || j["s"].get<int64_t>() < VOBENCH_TRACKING_OK || j["s"].get<int64_t>() > VOBENCH_TRACKING_FAILED)
        return "unknown tracking status";
    const auto& p = j["p"];
    if (!p.is_array() || p.size() != 7) return "the pose is not 7 numbers";
    for (const auto& v : p)
        if (!finite_number(v)) return "the pose is not finite";
    if (j.contains("st")) {
        if (!j["st"].is_object()) return "stages are not an object";
        for (const auto& [name, ns] : j["st"].items())
            if (!ns.is_number_integer()) return "stage '" + name + "' is not an integer";
    }
    if (j.contains("c")) {
        if (!j["c"].is_object()) return "counters are not an object";
        for (const auto& [name, v] : j["c"].items())
            if (!finite_number(v)) return "counter '" + name + "' is not a finite number";
    }
    return "";
}

}  // namespace

FrameStream decode_frames(const std::filesystem::path& file) {
    FrameStream s;
    std::ifstream in(file, std::ios::binary);
    std::string line;
    for (uint64_t n = 1; std::getline(in, line); ++n) {
        if (in.eof()) {  // no newline after it: the child died while writing this line
            s.truncated_tail = true;
            break;
        }
        const nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
        const std::string why = j.is_discarded() ? "not JSON" : check_line(j, s.frames.size());
        if (!why.empty()) {
            s.error = "frames.jsonl line " + std::to_string(n) + ": " + why;
            break;
        }
        FrameRecord f;
        f.index = j["i"];
        f.stamp = j["t"];
        if (j.contains("d")) {
            f.dropped = true;
            f.read_ns = j["r"];
            ++s.dropped_frames;
            s.frames.push_back(std::move(f));
            continue;
        }
        if (j.contains("cpu")) f.cpu_ns = j["cpu"];
        f.process_ns = j["ns"];
        f.read_ns = j["r"];
        f.tracking = j["s"];
        if (j.contains("st"))
            for (const auto& [name, ns] : j["st"].items()) f.stages.emplace_back(name, ns.get<int64_t>());
        if (j.contains("c"))
            for (const auto& [name, v] : j["c"].items()) f.counters.emplace_back(name, v.get<double>());
        const auto& p = j["p"];
        metrics::StampedPose sp;
        sp.t = f.stamp;
        sp.p = Eigen::Vector3d(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
        sp.q = Eigen::Quaterniond(p[6].get<double>(), p[3].get<double>(), p[4].get<double>(), p[5].get<double>());
        if (f.tracking != VOBENCH_TRACKING_OK) ++s.lost_frames;
        s.poses.push_back(sp);
        s.frames.push_back(std::move(f));
    }
    return s;
}

}  // namespace vobench
