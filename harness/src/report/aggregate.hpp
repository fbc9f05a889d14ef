// aggregate.hpp — runs grouped the way the tables read them: one entry (algorithm + parameters) on one
// sequence from one sensor, over its repeats; mean ± std of each metric over the successful repeats.
#pragma once

#include "record/run_record.hpp"

#include <optional>
#include <string>
#include <vector>

namespace vobench {

struct RunGroup {
    std::string entry, dataset, sequence, sensor;
    std::vector<const RunRecord*> runs;  // the repeats
    std::size_t failed() const;
    std::string row_label() const { return dataset + "/" + sequence; }
};

struct MetricSummary {
    double mean = 0, std = 0;  // std: population (numpy's default, as the TUM scripts), 0 for one value
    std::size_t n = 0;         // repeats that have the metric
};

// In the records' order (load_runs sorts them).
std::vector<RunGroup> group_runs(const std::vector<RunRecord>& records);
// Entries, sequences ("dataset/sequence") and sensors in order of first appearance.
std::vector<std::string> entries_of(const std::vector<RunGroup>& groups);
std::vector<std::string> rows_of(const std::vector<RunGroup>& groups, const std::string& entry);
std::vector<std::string> sensors_of(const std::vector<RunGroup>& groups, const std::string& entry);
const RunGroup* find_group(const std::vector<RunGroup>& groups, const std::string& entry, const std::string& row,
                           const std::string& sensor);

// Over the successful runs of the group that have `metric`; nullopt when none has.
std::optional<MetricSummary> summarize(const RunGroup& group, const std::string& metric);

// Stage names (in first-seen order) and the mean ms per frame of one stage over the group's runs.
std::vector<std::string> stages_of(const std::vector<RunGroup>& groups, const std::string& entry);
std::optional<double> stage_mean_ms(const RunGroup& group, const std::string& stage);
// A timing field of run.json ("mean_ms", "fps", "peak_rss_mb", "harness_overhead_pct" …) averaged over successful runs.
std::optional<double> timing_mean(const RunGroup& group, const std::string& field);

// A declared ground-truth accuracy: "0.01 m", "exact" (0), "not known" (negative).
std::string accuracy_text(double sigma, const std::string& unit);
// Each dataset once, in order, with its runs' ground-truth accuracy.
std::vector<std::pair<std::string, GroundTruthAccuracy>> dataset_accuracies(const std::vector<RunGroup>& groups);

// "Kinect v1" for kinect1, "Kinect v2" for kinect2, the name otherwise ("–" when empty).
std::string sensor_title(const std::string& sensor);

}  // namespace vobench
