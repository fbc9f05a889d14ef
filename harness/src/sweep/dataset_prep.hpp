// dataset_prep.hpp — a config's datasets made concrete: synthetic sequences rendered (once, cached
// under their parameters), `{sensor}` paths filled in, and each sequence's content fingerprinted.
#pragma once

#include "sweep/sweep_config.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace vobench {

struct SequenceRef {
    std::string name;    // e.g. "explore1", "rgbd_dataset_freiburg1_rpy"
    std::string sensor;  // "kinect1", "kinect2" or "" (the reader's)
    std::filesystem::path path;
    std::string reader;
    ParamMap options;  // the dataset's options, plus sensor= where the reader takes it
};

// Renders what is missing (unless `render` is false: then only the folders a render would make are
// named). Throws std::runtime_error naming the dataset on failure.
std::vector<SequenceRef> prepare_sequences(const DatasetSpec& dataset, const PluginRegistry& registry, bool render = true);

// A hash of every byte of the sequence folder. Whole-sequence hashing costs about as much as reading
// the sequence once, so results are remembered in `memo_file` (JSON) under a signature of file
// names, sizes and modification times, and recomputed only when that signature changes.
std::string dataset_checksum(const std::filesystem::path& sequence, const std::filesystem::path& memo_file);

}  // namespace vobench
