#include "track/track.hpp"

#include "metrics/trajectory_io.hpp"
#include "track/frame_cache.hpp"
#include "track/frame_prefetcher.hpp"
#include "util/escape.hpp"
#include "util/files.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>
#include <unordered_map>
#include <unordered_set>

namespace vobench {

double TrackResult::mean_ms() const {
    if (frames.empty()) return 0.0;
    double total = 0;
    for (const FrameRecord& f : frames) total += static_cast<double>(f.process_ns);
    return total / static_cast<double>(frames.size()) * 1e-6;
}

metrics::Trajectory ground_truth_of(const vobench_sequence_info& info) {
    metrics::Trajectory gt;
    if (info.ground_truth == nullptr) return gt;
    for (uint64_t k = 0; k < info.gt_count; ++k) {
        const double* v = info.ground_truth + 8 * k;
        metrics::StampedPose p;
        p.t = v[0];
        p.p = {v[1], v[2], v[3]};
        p.q = Eigen::Quaterniond(v[7], v[4], v[5], v[6]).normalized();
        gt.push_back(p);
    }
    return gt;
}

std::string check_ground_truth(const vobench_sequence_info& info) {
    if (info.ground_truth == nullptr) return "";
    for (uint64_t k = 0; k < info.gt_count; ++k) {
        const double* v = info.ground_truth + 8 * k;
        for (int c = 0; c < 8; ++c)
            if (!std::isfinite(v[c])) return fmt::format("ground-truth pose {} (stamp {}) is not finite", k, v[0]);
        if (std::sqrt(v[4] * v[4] + v[5] * v[5] + v[6] * v[6] + v[7] * v[7]) < 1e-9)
            return fmt::format("ground-truth pose {} (stamp {}) has a zero quaternion", k, v[0]);
    }
    return "";
}

namespace {

// Why the names a plugin emitted in one call break the limits, or "".
std::string check_names(const FrameRecord& rec, std::unordered_set<std::string>& seen) {
    if (rec.stages.size() > kMaxNamesPerFrame || rec.counters.size() > kMaxNamesPerFrame)
        return fmt::format("emitted {} stage and {} counter names in one call (at most {} each)", rec.stages.size(), rec.counters.size(),
                           kMaxNamesPerFrame);
    for (const auto& [name, ns] : rec.stages) {
        if (name.size() > kMaxNameBytes) return fmt::format("named a stage with {} bytes (at most {})", name.size(), kMaxNameBytes);
        seen.insert("s:" + name);
    }
    for (const auto& [name, v] : rec.counters) {
        if (name.size() > kMaxNameBytes) return fmt::format("named a counter with {} bytes (at most {})", name.size(), kMaxNameBytes);
        if (!std::isfinite(v)) return fmt::format("reported the non-finite value {} for counter '{}'", v, clean_text(name));
        seen.insert("c:" + name);
    }
    if (seen.size() > kMaxNamesPerRun)
        return fmt::format("emitted more than {} distinct stage and counter names in one run", kMaxNamesPerRun);
    return "";
}

// CPU time of this process, all threads (CLOCK_PROCESS_CPUTIME_ID), ns.
int64_t process_cpu_ns() {
    timespec t{};
    ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return int64_t{t.tv_sec} * 1000000000 + t.tv_nsec;
}

}  // namespace

TrackResult run_track(const TrackOptions& options, const PluginRegistry& registry) {
    DatasetInstance dataset(registry.load(options.dataset, VOBENCH_KIND_DATASET));
    dataset.open(options.path, options.dataset_options);
    const vobench_sequence_info& info = dataset.info();
    std::vector<std::unique_ptr<FilterInstance>> filters;
    vobench_camera camera = *info.camera;  // each filter may change the geometry for those after it
    for (std::size_t k = 0; k < options.filters.size(); ++k) {
        filters.push_back(std::make_unique<FilterInstance>(registry.load(options.filters[k].plugin, VOBENCH_KIND_FILTER)));
        filters.back()->start(camera, options.filters[k].params, options.seed + 1000003 * (k + 1));
        camera = filters.back()->output_camera();
    }
    OdometryInstance odometry(registry.load(options.algorithm, VOBENCH_KIND_ODOMETRY));
    odometry.start(camera, options.params, options.seed);

    TrackResult result;
    result.sequence = info.name ? info.name : "";
    result.sensor = info.sensor ? info.sensor : "";
    const uint64_t count = options.max_frames > 0 ? std::min(options.max_frames, info.frame_count) : info.frame_count;
    spdlog::info("tracking {} frames of {} ({}) with {}", count, result.sequence, result.sensor, odometry.plugin().name());
    std::unique_ptr<FrameCache> cache;
    if (!options.frame_cache.empty())
        cache = std::make_unique<FrameCache>(options.frame_cache / sequence_key(dataset.plugin(), options.dataset_options, options.path));
    if (options.on_start) options.on_start(info, odometry.plugin());
    if (const std::string why = check_ground_truth(info); !why.empty()) {
        result.error = fmt::format("reader '{}': {}", dataset.plugin().name(), why);
        return result;
    }
    if (count == 0) {
        result.error = fmt::format("reader '{}' declared no frames in {}", dataset.plugin().name(), options.path);
        return result;
    }
    std::unordered_set<std::string> names_seen;
    double last_stamp = -std::numeric_limits<double>::infinity();
    // Real time: frame i arrives at (stamp_i - stamp_0) / speed on a clock that the plugin's measured
    // process() times advance; the plugin is free again at its frame's arrival plus that time. A
    // clock of measured durations, not of sleeps: reading (decoding PNGs) cannot slow the stream down.
    const bool realtime = options.timing.mode == "realtime";
    double first_stamp = 0, free_at = -std::numeric_limits<double>::infinity();
    FramePrefetcher frames(dataset, count, options.prefetch_depth, cache.get());  // decoding overlaps the plugin, on another thread
    const auto loop_start = std::chrono::steady_clock::now();
    for (uint64_t i = 0; i < count; ++i) {
        std::unique_ptr<OwnedFrame> owned;
        const auto r0 = std::chrono::steady_clock::now();
        try {
            owned = frames.next();
        } catch (const std::exception& e) {  // a bad frame ends the run; what was tracked is kept
            result.error = fmt::format("reading frame {}: {}", i, e.what());
            break;
        }
        const vobench_frame* delivered = &owned->frame;
        try {
            for (auto& f : filters)
                if (delivered) delivered = f->apply(*delivered);
        } catch (const std::exception& e) {
            result.error = e.what();
            break;
        }
        const vobench_frame& read = owned->frame;  // the reader's stamps define the stream
        if (!std::isfinite(read.timestamp) || !(read.timestamp > last_stamp)) {
            result.error = fmt::format(
                "reader '{}' gave frame {} the stamp {}, {}", dataset.plugin().name(), i, read.timestamp,
                std::isfinite(read.timestamp) ? fmt::format("not after the previous frame's {}", last_stamp) : "not a finite number");
            break;
        }
        last_stamp = read.timestamp;
        if (i == 0) first_stamp = read.timestamp;
        const double arrival = (read.timestamp - first_stamp) / options.timing.speed;
        if (delivered == nullptr || (realtime && arrival < free_at)) {
            FrameRecord rec;
            rec.index = i;
            rec.stamp = read.timestamp;
            rec.read_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - r0).count();
            rec.dropped = true;
            ++result.dropped_frames;
            if (options.on_frame) options.on_frame(rec, metrics::StampedPose{});
            result.frames.push_back(std::move(rec));
            continue;
        }
        const vobench_frame& frame = *delivered;
        vobench_pose pose{};
        pose.struct_size = sizeof(pose);
        vobench_tracking_status tracking = VOBENCH_TRACKING_OK;
        odometry.host().begin_call();
        const int64_t cpu0 = process_cpu_ns() - frames.reader_cpu_ns();
        const auto t0 = std::chrono::steady_clock::now();
        const vobench_status status = odometry.process(frame, pose, tracking);
        const auto t1 = std::chrono::steady_clock::now();
        const int64_t cpu1 = process_cpu_ns() - frames.reader_cpu_ns();
        if (status != VOBENCH_OK) {
            result.error = fmt::format("plugin '{}' failed at frame {} ({}): {}", odometry.plugin().name(), i, status_name(status),
                                       odometry.last_error());
            break;
        }
        FrameRecord rec;
        rec.read_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(t0 - r0).count();
        rec.index = i;
        rec.stamp = read.timestamp;
        rec.process_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(t1 - t0).count();
        rec.cpu_ns = std::max<int64_t>(0, cpu1 - cpu0);
        free_at = arrival + static_cast<double>(rec.process_ns) * 1e-9;
        rec.tracking = tracking;
        rec.stages = odometry.host().stage_ns();
        rec.counters = odometry.host().counters();
        const Eigen::Quaterniond q(pose.qw, pose.qx, pose.qy, pose.qz);
        if (!std::isfinite(pose.tx) || !std::isfinite(pose.ty) || !std::isfinite(pose.tz) || !std::isfinite(q.norm())) {
            result.error = fmt::format("plugin '{}' returned a non-finite pose at frame {}", odometry.plugin().name(), i);
            break;
        }
        // The ABI asks for a unit quaternion; normalising a wrong one silently would hide a plugin bug.
        if (std::abs(q.norm() - 1.0) > 1e-6) {
            result.error = fmt::format("plugin '{}' returned a quaternion of norm {:.9g} (not unit) at frame {}", odometry.plugin().name(),
                                       q.norm(), i);
            break;
        }
        if (tracking < VOBENCH_TRACKING_OK || tracking > VOBENCH_TRACKING_FAILED) {
            result.error =
                fmt::format("plugin '{}' returned the unknown tracking status {} at frame {}", odometry.plugin().name(), tracking, i);
            break;
        }
        if (const std::string why = check_names(rec, names_seen); !why.empty()) {
            result.error = fmt::format("plugin '{}' {} at frame {}", odometry.plugin().name(), why, i);
            break;
        }
        if (tracking != VOBENCH_TRACKING_OK) ++result.failed_frames;
        metrics::StampedPose sp;
        sp.t = read.timestamp;
        sp.p = {pose.tx, pose.ty, pose.tz};
        sp.q = q.normalized();
        result.estimate.push_back(sp);
        if (options.on_frame) options.on_frame(rec, sp);
        result.frames.push_back(std::move(rec));
    }
    result.loop_wall_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - loop_start).count();

    const metrics::Trajectory gt = ground_truth_of(info);
    if (!options.evaluate) {
        result.evaluation_error = "not evaluated here";
    } else if (gt.empty()) {
        result.evaluation_error = "the sequence has no ground truth";
    } else if (result.estimate.size() < 2) {
        result.evaluation_error = "fewer than two estimated poses";
    } else {
        try {
            result.evaluation = metrics::evaluate(gt, result.estimate, options.protocol);
        } catch (const std::exception& e) {
            result.evaluation_error = e.what();
        }
    }
    return result;
}

void write_track_outputs(const TrackResult& result, const std::filesystem::path& dir) {
    std::filesystem::create_directories(dir);
    metrics::write_tum(dir / "trajectory.txt", result.estimate, "vobench estimate: " + result.sequence);
    // Columns: the union of stage and counter names, in first-seen order; a hash map from name to
    // column keeps this linear in what the plugin emitted.
    std::vector<std::string> stages, counters;
    std::unordered_map<std::string, std::size_t> stage_column, counter_column;
    bool any_cpu = false;
    for (const FrameRecord& f : result.frames) {
        any_cpu |= f.cpu_ns >= 0;
        for (const auto& [name, ns] : f.stages)
            if (stage_column.emplace(name, stages.size()).second) stages.push_back(name);
        for (const auto& [name, v] : f.counters)
            if (counter_column.emplace(name, counters.size()).second) counters.push_back(name);
    }
    // Names are the plugin's: kept to [A-Za-z0-9_.-] in the header, so the CSV stays one header line.
    const auto column_name = [](const std::string& name) {
        std::string out;
        for (char c : clean_text(name)) out += std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '-' ? c : '_';
        return out;
    };
    std::string csv = "index,stamp,process_ms,read_ms,status";
    for (const auto& s : stages) csv += ",stage_" + column_name(s) + "_ms";
    for (const auto& c : counters) csv += ",count_" + column_name(c);
    if (any_cpu) csv += ",cpu_ms";
    csv += '\n';
    static const char* kStatus[] = {"ok", "lost", "failed"};
    std::vector<std::string> row_stages, row_counters;
    for (const FrameRecord& f : result.frames) {
        if (f.dropped) {  // not given to the plugin: no time, no stages
            csv += fmt::format("{},{},,{},dropped{}{}\n", f.index, f.stamp, static_cast<double>(f.read_ns) * 1e-6,
                               std::string(stages.size() + counters.size(), ','), any_cpu ? "," : "");
            continue;
        }
        csv += fmt::format("{},{},{},{},{}", f.index, f.stamp, static_cast<double>(f.process_ns) * 1e-6,
                           static_cast<double>(f.read_ns) * 1e-6, f.tracking >= 0 && f.tracking <= 2 ? kStatus[f.tracking] : "unknown");
        row_stages.assign(stages.size(), "0");
        row_counters.assign(counters.size(), "");
        for (const auto& [name, ns] : f.stages) row_stages[stage_column[name]] = fmt::format("{}", static_cast<double>(ns) * 1e-6);
        for (const auto& [name, v] : f.counters) row_counters[counter_column[name]] = fmt::format("{}", v);
        for (const auto& v : row_stages) csv += "," + v;
        for (const auto& v : row_counters) csv += "," + v;
        if (any_cpu) csv += f.cpu_ns >= 0 ? fmt::format(",{}", static_cast<double>(f.cpu_ns) * 1e-6) : ",";
        csv += '\n';
    }
    write_file_atomic(dir / "timing.csv", csv);
}

}  // namespace vobench
