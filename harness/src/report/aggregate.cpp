#include "report/aggregate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace vobench {

std::size_t RunGroup::failed() const {
    return static_cast<std::size_t>(std::count_if(runs.begin(), runs.end(), [](const RunRecord* r) { return !r->ok; }));
}

std::vector<RunGroup> group_runs(const std::vector<RunRecord>& records) {
    std::vector<RunGroup> groups;
    for (const RunRecord& r : records) {
        auto it = std::find_if(groups.begin(), groups.end(), [&](const RunGroup& g) {
            return g.entry == r.entry() && g.dataset == r.cell.dataset && g.sequence == r.cell.sequence && g.sensor == r.cell.sensor;
        });
        if (it == groups.end()) {
            groups.push_back({r.entry(), r.cell.dataset, r.cell.sequence, r.cell.sensor, {}});
            it = groups.end() - 1;
        }
        it->runs.push_back(&r);
    }
    return groups;
}

namespace {
void add_unique(std::vector<std::string>& list, const std::string& s) {
    if (std::find(list.begin(), list.end(), s) == list.end()) list.push_back(s);
}
}  // namespace

std::vector<std::string> entries_of(const std::vector<RunGroup>& groups) {
    std::vector<std::string> out;
    for (const RunGroup& g : groups) add_unique(out, g.entry);
    return out;
}

std::vector<std::string> rows_of(const std::vector<RunGroup>& groups, const std::string& entry) {
    std::vector<std::string> out;
    for (const RunGroup& g : groups)
        if (g.entry == entry) add_unique(out, g.row_label());
    return out;
}

std::vector<std::string> sensors_of(const std::vector<RunGroup>& groups, const std::string& entry) {
    std::vector<std::string> out;
    for (const RunGroup& g : groups)
        if (g.entry == entry) add_unique(out, g.sensor);
    std::sort(out.begin(), out.end());
    return out;
}

const RunGroup* find_group(const std::vector<RunGroup>& groups, const std::string& entry, const std::string& row,
                           const std::string& sensor) {
    for (const RunGroup& g : groups)
        if (g.entry == entry && g.row_label() == row && g.sensor == sensor) return &g;
    return nullptr;
}

std::optional<MetricSummary> summarize(const RunGroup& group, const std::string& metric) {
    std::vector<double> v;
    for (const RunRecord* r : group.runs)
        if (r->ok)
            if (auto it = r->metrics.find(metric); it != r->metrics.end()) v.push_back(it->second);
    if (v.empty()) return std::nullopt;
    MetricSummary s;
    s.n = v.size();
    for (double x : v) s.mean += x;
    s.mean /= static_cast<double>(v.size());
    for (double x : v) s.std += (x - s.mean) * (x - s.mean);
    s.std = std::sqrt(s.std / static_cast<double>(v.size()));
    return s;
}

std::vector<std::string> stages_of(const std::vector<RunGroup>& groups, const std::string& entry) {
    std::vector<std::string> out;
    for (const RunGroup& g : groups)
        if (g.entry == entry)
            for (const RunRecord* r : g.runs)
                for (const auto& s : r->run.at("timing").value("stages", nlohmann::json::array())) add_unique(out, s.at("stage"));
    return out;
}

std::optional<double> stage_mean_ms(const RunGroup& group, const std::string& stage) {
    double sum = 0;
    std::size_t n = 0;
    for (const RunRecord* r : group.runs) {
        if (!r->ok) continue;
        for (const auto& s : r->run.at("timing").value("stages", nlohmann::json::array()))
            if (s.at("stage") == stage) {
                sum += s.at("mean_ms").get<double>();
                ++n;
            }
    }
    if (n == 0) return std::nullopt;
    return sum / static_cast<double>(n);
}

std::optional<double> timing_mean(const RunGroup& group, const std::string& field) {
    double sum = 0;
    std::size_t n = 0;
    for (const RunRecord* r : group.runs) {
        const nlohmann::json& t = r->run.at("timing");
        if (r->ok && t.contains(field)) {
            sum += t[field].get<double>();
            ++n;
        }
    }
    if (n == 0) return std::nullopt;
    return sum / static_cast<double>(n);
}

std::string accuracy_text(double sigma, const std::string& unit) {
    if (sigma > 0) return fmt::format("{:g} {}", sigma, unit);
    return sigma == 0 ? "exact" : "not known";
}

std::vector<std::pair<std::string, GroundTruthAccuracy>> dataset_accuracies(const std::vector<RunGroup>& groups) {
    std::vector<std::pair<std::string, GroundTruthAccuracy>> out;
    for (const RunGroup& g : groups)
        if (std::none_of(out.begin(), out.end(), [&](const auto& d) { return d.first == g.dataset; }))
            out.emplace_back(g.dataset, g.runs.front()->cell.gt_accuracy);
    return out;
}

std::string sensor_title(const std::string& sensor) {
    if (sensor == "kinect1") return "Kinect v1";
    if (sensor == "kinect2") return "Kinect v2";
    return sensor.empty() ? "–" : sensor;
}

}  // namespace vobench
