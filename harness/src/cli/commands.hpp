// commands.hpp — each subcommand registers itself on the CLI11 app. A command's callback does the
// work and stores its exit status in `exit_code` (0 success, 1 failure; usage errors are CLI11's).
#pragma once

#include "metrics/pose.hpp"

#include <CLI/CLI.hpp>

#include <map>
#include <string>
#include <vector>

namespace vobench::cli {

void add_plugins_commands(CLI::App& app, int& exit_code);
void add_track_command(CLI::App& app, int& exit_code);
void add_eval_command(CLI::App& app, int& exit_code);
void add_traj_command(CLI::App& app, int& exit_code);
void add_data_command(CLI::App& app, int& exit_code);
void add_synth_command(CLI::App& app, int& exit_code);
void add_run_commands(CLI::App& app, int& exit_code);  // run, report, collect, run-cell, sequence-probe
void add_gt_commands(CLI::App& app, int& exit_code);   // gt compare, gt fuse
void add_new_plugin_command(CLI::App& app, int& exit_code);
void add_plot_command(CLI::App& app, int& exit_code);

// A trajectory file in any format `eval` reads (tum, kitti, euroc, putk2-raw), its warnings logged.
metrics::Trajectory load_trajectory_file(const std::string& path, const std::string& format, const std::string& camera_in_marker = "",
                                         bool tum_scripts = false);

// "k=v" items into a map; throws CLI::ValidationError naming the bad item.
std::map<std::string, std::string> parse_key_values(const std::vector<std::string>& items, const std::string& option);

}  // namespace vobench::cli
