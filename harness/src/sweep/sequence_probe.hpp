// sequence_probe.hpp — how many frames a sequence holds, asked of its reader alone.
//
// A cell's child runs the reader and the odometry plugin in one process, so what it says about the
// sequence could have been written by the plugin. Before any cell runs, each sequence's reader is
// opened once in a child of its own (`vobench sequence-probe`), with no odometry plugin loaded; its
// frame count goes into every cell of that sequence (Cell::frames_declared), and the supervisor
// compares what each cell delivered against it. Remembered in <out>/.cache/sequences.json, keyed by
// the reader's hash, its options and the sequence's content checksum.
#pragma once

#include "abi/instances.hpp"

#include <cstdint>
#include <filesystem>
#include <string>

namespace vobench {

// The frame count the reader declares, or -1 when the probe failed (the cell will fail the same way,
// with its own message). Never throws.
int64_t probe_frame_count(const std::string& reader_file, const std::string& reader_hash, const std::filesystem::path& sequence,
                          const ParamMap& options, const std::string& checksum, const std::filesystem::path& out, int timeout_s);

// The child side: opens the sequence and writes {"frame_count": N} to `result`. Returns 0.
int sequence_probe_main(const std::string& reader_file, const std::filesystem::path& sequence, const std::string& options_json,
                        const std::filesystem::path& result);

}  // namespace vobench
