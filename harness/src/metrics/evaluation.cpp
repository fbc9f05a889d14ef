#include "metrics/evaluation.hpp"

#include <stdexcept>

namespace vobench::metrics {

ProtocolName parse_protocol(const std::string& name) {
    if (name == "paper") return ProtocolName::Paper;
    if (name == "tum-scripts") return ProtocolName::TumScripts;
    throw std::invalid_argument("unknown protocol '" + name + "' (paper or tum-scripts)");
}

const char* protocol_name(ProtocolName protocol) { return protocol == ProtocolName::Paper ? "paper" : "tum-scripts"; }

Evaluation evaluate(const Trajectory& gt, const Trajectory& est, const Protocol& protocol) {
    if (protocol.name == ProtocolName::TumScripts && (protocol.alignment != AlignmentMethod::Se3 || protocol.align_first != 0))
        throw std::invalid_argument(
            "the tum-scripts protocol aligns with Horn's method on all pairs (se3); "
            "use --protocol paper for other alignments");
    Evaluation e;
    e.protocol = protocol;
    // One association serves ATE and the paper's RPE.
    const bool needs_association = protocol.ate || (protocol.rpe && protocol.name == ProtocolName::Paper);
    const Association association = needs_association ? associate(stamps_of(gt), stamps_of(est), protocol.association) : Association{};
    if (protocol.ate) e.ate = compute_ate(gt, est, association, {protocol.association, protocol.alignment, protocol.align_first});
    if (protocol.rpe) {
        const RpeOptions options{protocol.rpe_delta, protocol.rpe_unit, protocol.association};
        e.rpe = protocol.name == ProtocolName::Paper ? compute_rpe_paper(gt, est, association, options)
                                                     : compute_rpe_tum_scripts(gt, est, options);
    }
    return e;
}

nlohmann::json protocol_json(const Protocol& p) {
    nlohmann::json j{
        {"name", protocol_name(p.name)}, {"max_difference_s", p.association.max_difference}, {"offset_s", p.association.offset}};
    if (p.ate) j["ate"] = {{"alignment", alignment_name(p.alignment)}, {"align_first", p.align_first}};
    if (p.rpe) {
        j["rpe"] = {{"delta", p.rpe_delta}, {"delta_unit", delta_unit_name(p.rpe_unit)}};
        if (p.name == ProtocolName::TumScripts)
            j["rpe"]["mode"] = "evaluate_rpe.py --fixed_delta --max_pairs 0; gt rejected beyond 2x median interval";
        else
            j["rpe"]["mode"] = "associated pairs, E_i = (Q_i^-1 Q_i+d)^-1 (P_i^-1 P_i+d)";
    }
    return j;
}

Protocol protocol_from_json(const nlohmann::json& j) {
    Protocol p;
    p.name = parse_protocol(j.at("name").get<std::string>());
    p.association.max_difference = j.at("max_difference_s").get<double>();
    p.association.offset = j.at("offset_s").get<double>();
    p.ate = j.contains("ate");
    p.rpe = j.contains("rpe");
    if (p.ate) {
        p.alignment = parse_alignment(j["ate"].at("alignment").get<std::string>());
        p.align_first = j["ate"].at("align_first").get<std::size_t>();
    }
    if (p.rpe) {
        p.rpe_delta = j["rpe"].at("delta").get<double>();
        p.rpe_unit = parse_delta_unit(j["rpe"].at("delta_unit").get<std::string>());
    }
    return p;
}

nlohmann::json evaluation_json(const Evaluation& e) {
    nlohmann::json j = nlohmann::json::object();
    if (e.ate) {
        j["ate"] = e.ate->stats;
        j["ate"]["unmatched_gt"] = e.ate->association.unmatched_first;
        j["ate"]["unmatched_est"] = e.ate->association.unmatched_second;
        j["ate"]["max_dt_s"] = e.ate->association.max_dt;
        j["ate"]["scale"] = e.ate->alignment.scale;
    }
    if (e.rpe) j["rpe"] = {{"trans", e.rpe->trans}, {"rot_deg", e.rpe->rot_deg}};
    j["protocol"] = protocol_json(e.protocol);
    return j;
}

}  // namespace vobench::metrics
