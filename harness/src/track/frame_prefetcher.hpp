// frame_prefetcher.hpp — decoding runs ahead of the odometry plugin on another thread.
//
// A reader's frame is valid only until its next read (ABI rule 7), so the prefetch thread copies each
// frame into a buffer it owns and hands it over through a bounded queue: I/O and decoding overlap the
// plugin's compute, and memory stays flat in the sequence length (at most `depth` + 1 frames exist,
// whatever the sequence's length). The reader is used by the prefetch thread alone (ABI thread rule).
// A read error is delivered in order, as an exception at the frame where it happened.
#pragma once

#include "abi/instances.hpp"

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace vobench {

// A decoded frame that owns its pixels.
struct OwnedFrame {
    std::vector<uint8_t> color, depth;
    vobench_image color_image{}, depth_image{};
    vobench_frame frame{};

    explicit OwnedFrame(const vobench_frame& f);
    OwnedFrame(const OwnedFrame&) = delete;
    OwnedFrame& operator=(const OwnedFrame&) = delete;
};

class FrameCache;

class FramePrefetcher {
public:
    // Reads frames [0, count) of `dataset`, at most `depth` ahead of the consumer; `depth` 0 reads
    // each frame in next(), on the caller's thread (one core per run: a sweep cell with threads: 1,
    // so that -j N on N cores scales). With a cache: from
    // it when complete, else from the reader, storing each frame (and marking the cache complete when
    // the whole sequence went through).
    FramePrefetcher(DatasetInstance& dataset, uint64_t count, std::size_t depth = 4, const FrameCache* cache = nullptr);
    ~FramePrefetcher();
    FramePrefetcher(const FramePrefetcher&) = delete;
    FramePrefetcher& operator=(const FramePrefetcher&) = delete;

    // The next frame in order; nullptr after the last. Rethrows the reader's error at its frame.
    std::unique_ptr<OwnedFrame> next();
    // CPU time the reading thread has used, as of its last finished frame (0 without a thread): what
    // the process's CPU clock counts besides the plugin.
    int64_t reader_cpu_ns() const { return reader_cpu_ns_.load(); }

private:
    void run();
    std::unique_ptr<OwnedFrame> read(uint64_t index, bool from_cache);
    uint64_t next_index_ = 0;  // depth 0 only

    DatasetInstance& dataset_;
    const FrameCache* cache_;
    const uint64_t count_;
    const std::size_t depth_;
    std::mutex mutex_;
    std::condition_variable changed_;
    std::deque<std::unique_ptr<OwnedFrame>> queue_;
    std::exception_ptr error_;
    bool done_ = false, stop_ = false;
    std::atomic<int64_t> reader_cpu_ns_{0};
    std::thread thread_;
};

}  // namespace vobench
