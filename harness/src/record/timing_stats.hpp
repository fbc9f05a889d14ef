// timing_stats.hpp — the numbers a run's speed is quoted by, and how they were taken (issue #20).
//
// One function for `vobench track` and the cell's supervisor, so a figure means the same wherever it
// is printed. Statistics are over the frames given to the plugin, after the warm-up frames
// (TimingSpec::warmup_frames, recorded); dropped frames (real-time mode) are counted, not timed.
#pragma once

#include "record/cell.hpp"
#include "record/frame_stream.hpp"

#include <nlohmann/json.hpp>

#include <vector>

namespace vobench {

// {"frames_timed", "mean_ms", "median_ms", "p95_ms", "max_ms", "fps", "cpu_ms", "cpu_per_wall",
//  "processed_frames", "dropped_frames", "stages": [{"stage", "mean_ms"}], and in real-time mode
//  "latency_ms": {"mean", "p95", "max"}} — process() wall time on the steady clock; cpu_ms the process's
// CPU time during the call (all threads but the frame-reading one), so cpu_per_wall above 1 shows a
// plugin running threads of its own.
nlohmann::json timing_statistics(const std::vector<FrameRecord>& frames, const TimingSpec& timing);

// How the times were taken, for the record: mode, speed, warm-up frames, clocks, what is inside the
// window, threads allowed, the CPU (model, frequency, governor) and, when known, the cell's CPU
// affinity and whether it was pinned.
nlohmann::json timing_protocol(const TimingSpec& timing, int threads_allowed, const nlohmann::json& affinity, int pinned_core);

}  // namespace vobench
