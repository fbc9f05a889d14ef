#include "cli/protocol_options.hpp"

#include <stdexcept>

namespace vobench::cli {

void ProtocolArgs::add_to(CLI::App* c) {
    c->add_option("--protocol", protocol, "paper (Kraft et al. eqs. 11-12) or tum-scripts (evaluate_ate/rpe.py exactly)")
        ->check(CLI::IsMember({"paper", "tum-scripts"}))
        ->capture_default_str();
    c->add_option("--metric", metric, "ate, rpe or both")->check(CLI::IsMember({"ate", "rpe", "both"}))->capture_default_str();
    c->add_option("--delta", delta, "RPE step")->capture_default_str();
    c->add_option("--delta-unit", delta_unit, "RPE step unit: f (frames), s, m, rad or deg")
        ->check(CLI::IsMember({"f", "s", "m", "rad", "deg"}))
        ->capture_default_str();
    c->add_option("--align", align, "ATE alignment: se3, sim3, posyaw or none")
        ->check(CLI::IsMember({"se3", "sim3", "posyaw", "none"}))
        ->capture_default_str();
    c->add_option("--align-first", align_first, "Align on the first N matched poses only (0: all)")->capture_default_str();
    c->add_option("--max-diff", max_diff, "Association: largest stamp difference, seconds")->capture_default_str();
    c->add_option("--offset", offset, "Association: seconds added to the estimate's stamps")->capture_default_str();
}

metrics::Protocol ProtocolArgs::build() const {
    metrics::Protocol p;
    p.name = metrics::parse_protocol(protocol);
    p.ate = metric != "rpe";
    p.rpe = metric != "ate";
    p.rpe_delta = delta;
    p.rpe_unit = metrics::parse_delta_unit(delta_unit);
    p.alignment = metrics::parse_alignment(align);
    p.align_first = align_first;
    p.association.max_difference = max_diff;
    p.association.offset = offset;
    if (!(max_diff > 0)) throw std::invalid_argument("--max-diff must be positive");
    return p;
}

}  // namespace vobench::cli
