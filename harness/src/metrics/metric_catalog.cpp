#include "metrics/metric_catalog.hpp"

namespace vobench::metrics {

const std::vector<MetricInfo>& metric_catalog() {
    using B = Better;
    using C = Combine;
    using G = GtAccuracy;
    static const std::vector<MetricInfo> catalog = {
        {"ate.rmse", "m", B::lower, C::mean, G::position, "ATE RMSE"},
        {"ate.mean", "m", B::lower, C::mean, G::position, "ATE mean"},
        {"ate.median", "m", B::lower, C::mean, G::position, "ATE median"},
        {"ate.std", "m", B::lower, C::mean, G::position, "ATE std"},
        {"ate.max", "m", B::lower, C::mean, G::position, "ATE max"},
        {"rpe.trans.rmse", "m", B::lower, C::mean, G::position, "RPE RMSE"},
        {"rpe.trans.mean", "m", B::lower, C::mean, G::position, "RPE mean"},
        {"rpe.trans.median", "m", B::lower, C::mean, G::position, "RPE median"},
        {"rpe.rot.rmse", "deg", B::lower, C::mean, G::rotation, "RPE RMSE"},
        {"rpe.rot.mean", "deg", B::lower, C::mean, G::rotation, "RPE mean"},
        {"rpe.rot.median", "deg", B::lower, C::mean, G::rotation, "RPE median"},
        {"ms_per_frame", "ms", B::lower, C::mean, G::none, "ms per frame"},
        {"fps", "1/s", B::higher, C::mean, G::none, "frames per second"},
        {"lost_frames", "frames", B::lower, C::sum, G::none, "lost frames"},
        {"failed_frames", "frames", B::lower, C::sum, G::none, "failed frames"},
        {"dropped_frames", "frames", B::lower, C::sum, G::none, "dropped frames (real time)"},
        {"failed_cells", "cells", B::lower, C::sum, G::none, "failed cells"},
    };
    return catalog;
}

const MetricInfo* find_metric(const std::string& name) {
    for (const MetricInfo& m : metric_catalog())
        if (m.name == name) return &m;
    return nullptr;
}

std::vector<std::string> metric_names() {
    std::vector<std::string> names;
    for (const MetricInfo& m : metric_catalog()) names.push_back(m.name);
    return names;
}

MetricMap flatten(const Evaluation& e) {
    MetricMap m;
    if (e.ate) {
        const auto& s = e.ate->stats;
        m["ate.rmse"] = s.rmse;
        m["ate.mean"] = s.mean;
        m["ate.median"] = s.median;
        m["ate.std"] = s.std;
        m["ate.max"] = s.max;
    }
    if (e.rpe) {
        m["rpe.trans.rmse"] = e.rpe->trans.rmse;
        m["rpe.trans.mean"] = e.rpe->trans.mean;
        m["rpe.trans.median"] = e.rpe->trans.median;
        m["rpe.rot.rmse"] = e.rpe->rot_deg.rmse;
        m["rpe.rot.mean"] = e.rpe->rot_deg.mean;
        m["rpe.rot.median"] = e.rpe->rot_deg.median;
    }
    return m;
}

}  // namespace vobench::metrics
