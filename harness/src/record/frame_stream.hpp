// frame_stream.hpp — frames.jsonl, both ends: the cell's child writes one line per frame as it goes
// (so a crash keeps every frame before it), the supervisor reads them back.
//
// The reading end trusts nothing: the child runs plugin code, which may have scribbled on the file,
// cut it short or written values that are not numbers. A line is accepted only when every field has
// its type, every number is finite and the frame index is the next one; the first line that is not
// ends the stream, and `error` says which line and why. A last line cut short by a crash is not an
// error (the child died while writing it): `truncated_tail` says so.
#pragma once

#include "metrics/trajectory_io.hpp"

#include <vobench/vobench_plugin.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace vobench {

// What the host measured around one process() call.
struct FrameRecord {
    uint64_t index = 0;
    double stamp = 0;
    int64_t process_ns = 0;
    int64_t read_ns = 0;  // waiting for this frame (decoding it, when there is no prefetch thread)
    // CPU time of the process during the call, all its threads but the frame-reading one (-1: not
    // measured): above process_ns when the plugin runs threads of its own.
    int64_t cpu_ns = -1;
    // Real-time mode: the frame arrived while the plugin was busy and was not given to it (no pose).
    bool dropped = false;
    vobench_tracking_status tracking = VOBENCH_TRACKING_OK;
    std::vector<std::pair<std::string, int64_t>> stages;
    std::vector<std::pair<std::string, double>> counters;
};

// One line, newline included; a dropped frame's line has no pose (`pose` is not read).
std::string encode_frame(const FrameRecord& frame, const metrics::StampedPose& pose);

struct FrameStream {
    std::vector<FrameRecord> frames;
    metrics::Trajectory poses;       // one per frame that was not dropped
    std::size_t lost_frames = 0;     // tracking status not OK
    std::size_t dropped_frames = 0;  // real-time mode: not given to the plugin
    std::string error;               // "" or "frames.jsonl line 7: …"
    bool truncated_tail = false;     // the last line had no newline (the child died while writing it)
};

FrameStream decode_frames(const std::filesystem::path& file);

}  // namespace vobench
