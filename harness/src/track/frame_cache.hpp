// frame_cache.hpp — an optional decoded-frame cache, for sweeps that replay one sequence many times.
//
// A sequence's frames, as a reader delivered them, are stored one file per frame: a small header
// (stamps, depth scale, image geometry and formats) and the pixels compressed with zstd (level 1: fast
// to write, ~1 GB/s to read). The cache folder is named by a content key — the reader's name and
// version, its options, and a hash of every file of the sequence (names and bytes) — so any change to
// the data, the reader or its options makes a new cache instead of serving stale frames. A cache
// counts only once a `complete` marker is written after the last frame; every file is written to a
// temporary name and renamed, so an interrupted run never leaves a half file behind.
#pragma once

#include "abi/instances.hpp"
#include "track/frame_prefetcher.hpp"

#include <filesystem>
#include <memory>
#include <string>

namespace vobench {

// 16 hex digits identifying (reader, options, sequence content).
std::string sequence_key(const PluginLibrary& reader, const ParamMap& options, const std::filesystem::path& sequence);

class FrameCache {
public:
    explicit FrameCache(std::filesystem::path folder);
    const std::filesystem::path& folder() const { return folder_; }

    bool complete() const;
    // Throws std::runtime_error naming the file when it is missing or corrupt.
    std::unique_ptr<OwnedFrame> load(uint64_t index) const;
    void store(uint64_t index, const vobench_frame& frame) const;
    void mark_complete(uint64_t frames) const;

private:
    std::filesystem::path file_of(uint64_t index) const;
    std::filesystem::path folder_;
};

}  // namespace vobench
