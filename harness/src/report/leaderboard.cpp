#include "report/leaderboard.hpp"

#include "metrics/metric_catalog.hpp"
#include "record/host_info.hpp"
#include "report/bootstrap.hpp"

#include <algorithm>
#include <cmath>

namespace vobench {

namespace {

bool is_count(const std::string& metric) {
    const metrics::MetricInfo* m = metrics::find_metric(metric);
    return m && m->combine == metrics::Combine::sum;
}

nlohmann::json metrics_json(const MetricMap& m) {
    nlohmann::json j = nlohmann::json::object();
    for (const auto& [k, v] : m)
        if (std::isfinite(v)) j[k] = v;  // JSON has no NaN or infinity (load_runs keeps none; this is the last guard)
    return j;
}

// Metrics of one cell that lie within the ground truth's own declared error (Ceriani et al. 2009).
nlohmann::json within_gt_error(const RunRecord& r) {
    nlohmann::json list = nlohmann::json::array();
    const auto& acc = r.cell.gt_accuracy;
    for (const auto& [k, v] : r.metrics) {
        const metrics::MetricInfo* m = metrics::find_metric(k);
        const metrics::GtAccuracy kind = m ? m->accuracy : metrics::GtAccuracy::none;
        const double sigma = kind == metrics::GtAccuracy::rotation   ? acc.rotation_deg
                             : kind == metrics::GtAccuracy::position ? acc.position_m
                                                                     : 0.0;
        if (sigma > 0 && v <= sigma) list.push_back(k);
    }
    return list;
}

}  // namespace

bool higher_is_better(const std::string& metric) {
    const metrics::MetricInfo* m = metrics::find_metric(metric);
    return m && m->better == metrics::Better::higher;
}

std::optional<double> criterion_value(const std::vector<const RunRecord*>& cells, const std::string& metric) {
    if (metric == "failed_cells")
        return static_cast<double>(std::count_if(cells.begin(), cells.end(), [](const RunRecord* r) { return !r->ok; }));
    double sum = 0;
    std::size_t n = 0;
    for (const RunRecord* r : cells) {
        if (!r->ok && !is_count(metric)) continue;
        if (auto it = r->metrics.find(metric); it != r->metrics.end()) {
            sum += it->second;
            ++n;
        }
    }
    if (n == 0) return std::nullopt;
    return is_count(metric) ? sum : sum / static_cast<double>(n);
}

bool criterion_holds(const Criterion& c, double v) {
    if (c.op == "<=") return v <= c.value;
    if (c.op == "<") return v < c.value;
    if (c.op == ">=") return v >= c.value;
    if (c.op == ">") return v > c.value;
    return v == c.value;
}

nlohmann::json build_leaderboard(const std::vector<RunRecord>& records, const LeaderboardContext& ctx) {
    const BootstrapOptions bootstrap;
    std::vector<std::string> entries;
    for (const RunRecord& r : records)
        if (std::find(entries.begin(), entries.end(), r.entry()) == entries.end()) entries.push_back(r.entry());

    nlohmann::json list = nlohmann::json::array();
    nlohmann::json failures = nlohmann::json::array();
    for (const std::string& entry : entries) {
        std::vector<const RunRecord*> cells;
        for (const RunRecord& r : records)
            if (r.entry() == entry) cells.push_back(&r);
        const Cell& first = cells.front()->cell;
        nlohmann::json e{{"entry", entry},
                         {"algorithm", first.algorithm},
                         {"plugin", first.plugin},
                         {"plugin_version", cells.front()->run.value("plugin", nlohmann::json::object()).value("version", "")},
                         {"plugin_hash", first.plugin_hash},
                         {"params", first.params},
                         {"rank", nullptr},
                         {"tied_with", nlohmann::json::array()}};
        nlohmann::json jcells = nlohmann::json::array();
        std::size_t failed = 0;
        for (const RunRecord* r : cells) {
            jcells.push_back(
                {{"id", r->cell.id},
                 {"dataset", r->cell.dataset},
                 {"sequence", r->cell.sequence},
                 {"sensor", r->cell.sensor},
                 {"repeat", r->cell.repeat},
                 {"seed", r->cell.seed},
                 {"status", r->ok ? "ok" : "failed"},
                 {"reason", r->reason},
                 {"metrics", metrics_json(r->metrics)},
                 {"gt_accuracy", {{"position_m", r->cell.gt_accuracy.position_m}, {"rotation_deg", r->cell.gt_accuracy.rotation_deg}}},
                 {"within_gt_error", within_gt_error(*r)}});
            if (!r->ok) {
                ++failed;
                failures.push_back({{"id", r->cell.id},
                                    {"entry", entry},
                                    {"dataset", r->cell.dataset},
                                    {"sequence", r->cell.sequence},
                                    {"sensor", r->cell.sensor},
                                    {"reason", r->reason},
                                    {"failed_at_frame", r->run.value("failed_at_frame", nlohmann::json(nullptr))},
                                    {"partial", r->partial}});
            }
        }
        nlohmann::json aggregate = nlohmann::json::object();
        for (const std::string& metric : metrics::metric_names()) {
            if (is_count(metric)) {
                if (auto v = criterion_value(cells, metric)) aggregate[metric] = {{"sum", *v}, {"n", cells.size()}};
                continue;
            }
            std::vector<double> values;
            for (const RunRecord* r : cells)
                if (r->ok)
                    if (auto it = r->metrics.find(metric); it != r->metrics.end()) values.push_back(it->second);
            if (values.empty()) continue;
            double mean = 0, var = 0;
            for (double v : values) mean += v;
            mean /= static_cast<double>(values.size());
            for (double v : values) var += (v - mean) * (v - mean);
            const auto [lo, hi] = bootstrap_mean_ci(values, bootstrap);
            aggregate[metric] = {
                {"mean", mean}, {"std", std::sqrt(var / static_cast<double>(values.size()))}, {"n", values.size()}, {"ci95", {lo, hi}}};
        }
        e["complete"] = failed == 0;
        e["failed_cells"] = failed;
        e["aggregate"] = aggregate;
        nlohmann::json crit = nlohmann::json::array();
        for (const Criterion& c : ctx.criteria) {
            const auto v = criterion_value(cells, c.metric);
            crit.push_back({{"criterion", c.text},
                            {"required", c.required},
                            {"value", v ? nlohmann::json(*v) : nlohmann::json(nullptr)},
                            {"passed", v.has_value() && criterion_holds(c, *v)}});
        }
        e["criteria"] = crit;
        e["cells"] = jcells;
        list.push_back(e);
    }

    // Rank complete entries that have the primary metric; mark overlapping intervals as ties.
    std::vector<std::size_t> ranked;
    for (std::size_t i = 0; i < list.size(); ++i)
        if (list[i]["complete"].get<bool>() && list[i]["aggregate"].contains(ctx.rank_by)) ranked.push_back(i);
    const bool higher = higher_is_better(ctx.rank_by);
    const auto mean_of = [&](std::size_t i) { return list[i]["aggregate"][ctx.rank_by]["mean"].get<double>(); };
    std::stable_sort(ranked.begin(), ranked.end(),
                     [&](std::size_t a, std::size_t b) { return higher ? mean_of(a) > mean_of(b) : mean_of(a) < mean_of(b); });
    for (std::size_t k = 0; k < ranked.size(); ++k) list[ranked[k]]["rank"] = k + 1;
    for (std::size_t a : ranked)
        for (std::size_t b : ranked) {
            if (a == b) continue;
            const auto& ca = list[a]["aggregate"][ctx.rank_by]["ci95"];
            const auto& cb = list[b]["aggregate"][ctx.rank_by]["ci95"];
            const bool overlap = ca[0].get<double>() <= cb[1].get<double>() && cb[0].get<double>() <= ca[1].get<double>();
            if (overlap) list[a]["tied_with"].push_back(list[b]["entry"]);
        }
    std::stable_sort(list.begin(), list.end(), [](const nlohmann::json& a, const nlohmann::json& b) {
        const bool ra = !a["rank"].is_null(), rb = !b["rank"].is_null();
        if (ra != rb) return ra;
        return ra && a["rank"].get<std::size_t>() < b["rank"].get<std::size_t>();
    });

    nlohmann::json problems = nlohmann::json::array();
    for (const Criterion& c : ctx.criteria) {
        nlohmann::json solutions = nlohmann::json::object();
        for (const auto& e : list)
            for (const auto& r : e["criteria"])
                if (r["criterion"] == c.text) solutions[e["entry"].get<std::string>()] = r["passed"];
        problems.push_back({{"criterion", c.text}, {"required", c.required}, {"passed_by", solutions}});
    }
    return {
        {"schema_version", kLeaderboardSchemaVersion},
        {"context",
         {{"name", ctx.name},
          {"generated", ctx.generated},
          {"vobench_version", vobench_version()},
          {"host", host_info()},
          {"protocol", ctx.protocol},
          {"primary_metric", ctx.rank_by},
          {"primary_order", higher ? "descending" : "ascending"},
          {"bootstrap",
           {{"method", "percentile"}, {"resamples", bootstrap.resamples}, {"confidence", bootstrap.confidence}, {"seed", bootstrap.seed}}},
          {"ties", "entries whose 95 % bootstrap intervals of the primary metric overlap"}}},
        {"entries", list},
        {"problems", problems},
        {"failures", failures}};
}

}  // namespace vobench
