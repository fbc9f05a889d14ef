// protocol_options.hpp — the evaluation options shared by `eval` and `track`.
#pragma once

#include "metrics/evaluation.hpp"

#include <CLI/CLI.hpp>

#include <string>

namespace vobench::cli {

struct ProtocolArgs {
    std::string protocol = "paper";
    std::string metric = "both";
    double delta = 4.0;
    std::string delta_unit = "f";
    std::string align = "se3";
    std::size_t align_first = 0;
    double max_diff = 0.02;
    double offset = 0.0;

    void add_to(CLI::App* command);
    metrics::Protocol build() const;  // throws std::invalid_argument on a bad name
};

}  // namespace vobench::cli
