// timing_csv.hpp — runs/<id>/timing.csv read back (track/track.cpp writes it): one row per frame,
//   index,stamp,process_ms,read_ms,status[,stage_<name>_ms …][,count_<name> …][,cpu_ms]
// The report's per-cell timing panel draws it. The file may come from a broken or hostile run: every
// number is checked (finite, not negative for times), and a bad one is refused naming file:line and
// the column; nothing here throws anything but TimingCsvError.
#pragma once

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace vobench {

struct TimingCsvError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct TimingStage {
    std::string name;        // without the stage_ prefix and _ms suffix
    std::vector<double> ms;  // per row; 0 where the frame did not report it, NaN for a dropped frame
};

struct TimingTable {
    std::vector<double> stamps;      // seconds
    std::vector<double> process_ms;  // NaN for a dropped frame (never given to the plugin)
    std::vector<double> read_ms;
    std::vector<std::string> status;  // ok, lost, failed, dropped
    std::vector<TimingStage> stages;  // in the file's column order
};

// At most `max_bytes` are read (a larger file is refused: it is not what a run writes).
TimingTable read_timing_csv(const std::filesystem::path& file, std::uintmax_t max_bytes = std::uintmax_t{512} << 20);

}  // namespace vobench
