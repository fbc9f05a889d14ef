// evaluation.hpp — one named protocol, applied: ATE and/or RPE of an estimate against ground truth,
// with every parameter used written beside the numbers.
#pragma once

#include "metrics/ate.hpp"
#include "metrics/rpe.hpp"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>

namespace vobench::metrics {

enum class ProtocolName { Paper, TumScripts };
ProtocolName parse_protocol(const std::string& name);  // "paper" | "tum-scripts"
const char* protocol_name(ProtocolName protocol);

struct Protocol {
    ProtocolName name = ProtocolName::Paper;
    bool ate = true;
    bool rpe = true;
    AssociationOptions association;
    AlignmentMethod alignment = AlignmentMethod::Se3;  // tum-scripts: always se3 (Horn)
    std::size_t align_first = 0;
    double rpe_delta = 4.0;  // Kraft et al. 2016: n = 4 frames
    DeltaUnit rpe_unit = DeltaUnit::Frames;
};

struct Evaluation {
    Protocol protocol;
    std::optional<AteResult> ate;
    std::optional<RpeResult> rpe;
};

// Throws std::invalid_argument for a protocol that cannot be applied (e.g. tum-scripts with sim3) and
// std::runtime_error when the trajectories do not overlap.
Evaluation evaluate(const Trajectory& gt, const Trajectory& est, const Protocol& protocol);

nlohmann::json protocol_json(const Protocol& protocol);
// The inverse of protocol_json (a run record read back); throws on a malformed record.
Protocol protocol_from_json(const nlohmann::json& j);
// {"ate": {...}, "rpe": {"trans": {...}, "rot_deg": {...}}, "protocol": {...}}
nlohmann::json evaluation_json(const Evaluation& evaluation);

}  // namespace vobench::metrics
