// criterion.hpp — a benchmark problem's criterion (Rawseeds: "well-defined problems with explicit
// criteria"), e.g. `rpe.trans.rmse <= 0.02`, checked per algorithm entry. Written into sweep.json by
// `vobench run`, read back by the report.
#pragma once

#include <string>

namespace vobench {

struct Criterion {
    std::string metric;  // ate.rmse, rpe.trans.rmse, failed_frames, ...
    std::string op;      // <=, <, >=, >, ==
    double value = 0;
    bool required = true;  // a failed required criterion makes `vobench run` exit non-zero
    std::string text;      // as written
};

// "metric op number" with a catalogue metric; throws std::invalid_argument naming what is wrong.
Criterion parse_criterion(const std::string& text);

}  // namespace vobench
