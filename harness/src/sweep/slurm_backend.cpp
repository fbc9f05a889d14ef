#include "sweep/slurm_backend.hpp"

#include "metrics/trajectory_io.hpp"
#include "record/host_info.hpp"
#include "sweep/cell_runner.hpp"
#include "util/files.hpp"
#include "util/subprocess.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <boost/dll/runtime_symbol_info.hpp>

#include <unistd.h>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <thread>

namespace vobench {
namespace fs = std::filesystem;

namespace {

std::vector<std::string> read_lines(const fs::path& file) {
    std::vector<std::string> lines;
    std::ifstream in(file);
    for (std::string l; std::getline(in, l);)
        if (!l.empty()) lines.push_back(l);
    return lines;
}

nlohmann::json read_jobs(const fs::path& out) {
    const nlohmann::json j = read_json_or_null(out / "slurm" / "jobs.json");
    return j.is_array() ? j : nlohmann::json::array();
}

void write_jobs(const fs::path& out, const nlohmann::json& jobs) { write_json_atomic(out / "slurm" / "jobs.json", jobs); }

std::map<std::string, Cell> cells_by_id(const fs::path& out) {
    std::ifstream in(out / "cells.json");
    if (!in) throw std::runtime_error((out / "cells.json").string() + ": missing (was this folder made by vobench run?)");
    std::map<std::string, Cell> cells;
    for (const auto& j : nlohmann::json::parse(in)) {
        Cell c = cell_from_json(j);
        cells.emplace(c.id, c);
    }
    return cells;
}

// A single-quoted shell word.
std::string sh(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

ChildResult slurm_command(const std::vector<std::string>& argv) {
    try {
        return run_program(argv, 120);
    } catch (const std::exception& e) {
        throw std::runtime_error(argv.front() + " could not be started (is Slurm installed and on PATH?): " + e.what());
    }
}

// The task's state, from the controller while it remembers the job, else from accounting.
std::map<int, std::map<std::string, std::string>> task_states(const std::string& job) {
    const ChildResult s = slurm_command({"scontrol", "-o", "show", "job", job});
    auto tasks = s.exited && s.exit_code == 0 ? parse_scontrol_tasks(s.output) : std::map<int, std::map<std::string, std::string>>{};
    if (!tasks.empty()) return tasks;
    const ChildResult a = slurm_command({"sacct", "-n", "-P", "-X", "-j", job, "-o", "JobID,State,ExitCode"});
    if (a.exited && a.exit_code == 0) {
        std::istringstream in(a.output);
        for (std::string line; std::getline(in, line);) {
            const auto us = line.find('_'), bar = line.find('|');
            if (us == std::string::npos || bar == std::string::npos || us > bar) continue;
            const auto bar2 = line.find('|', bar + 1);
            try {
                const int task = std::stoi(line.substr(us + 1, bar - us - 1));
                tasks[task] = {{"JobState", line.substr(bar + 1, bar2 - bar - 1)},
                               {"ExitCode", bar2 == std::string::npos ? "" : line.substr(bar2 + 1)}};
            } catch (const std::exception&) {}
        }
    }
    return tasks;
}

}  // namespace

std::map<int, std::map<std::string, std::string>> parse_scontrol_tasks(const std::string& text) {
    std::map<int, std::map<std::string, std::string>> tasks;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        std::map<std::string, std::string> fields;
        std::istringstream words(line);
        for (std::string w; words >> w;)
            if (const auto eq = w.find('='); eq != std::string::npos) fields[w.substr(0, eq)] = w.substr(eq + 1);
        if (!fields.count("ArrayTaskId")) continue;
        // One task ("3"), or the record of tasks that never started: "2-4%1", "1,3-5" (the %K throttle dropped).
        std::string ids = fields["ArrayTaskId"];
        ids = ids.substr(0, ids.find('%'));
        std::istringstream parts(ids);
        for (std::string part; std::getline(parts, part, ',');) {
            try {
                const auto dash = part.find('-');
                const int first = std::stoi(part.substr(0, dash));
                const int last = dash == std::string::npos ? first : std::stoi(part.substr(dash + 1));
                for (int t = first; t <= last && t - first < 1000000; ++t) tasks[t] = fields;
            } catch (const std::exception&) {}
        }
    }
    return tasks;
}

std::string submit_slurm(const std::vector<Cell>& pending, const fs::path& out_in, const SlurmOptions& o, int threads) {
    if (pending.empty()) return "";
    const fs::path out = fs::absolute(out_in).lexically_normal();
    for (const auto& j : read_jobs(out))
        if (!j.value("collected", false))
            throw std::runtime_error(fmt::format("job {} of this folder is not collected yet: run `vobench collect {}` first",
                                                 j.value("job", ""), out.string()));
    fs::create_directories(out / "slurm" / "logs");
    const std::string stamp = std::to_string(std::chrono::system_clock::now().time_since_epoch().count());
    const fs::path batch = out / "slurm" / ("batch-" + stamp + ".txt");
    std::string ids;
    for (const Cell& c : pending) ids += c.id + "\n";
    write_file_atomic(batch, ids);
    const int chunk = std::max(1, o.chunk);
    const std::size_t tasks = (pending.size() + static_cast<std::size_t>(chunk) - 1) / static_cast<std::size_t>(chunk);

    std::string script = "#!/bin/bash\n# written by vobench run --backend slurm; one array task runs `chunk` cells, each isolated\n";
    script += fmt::format("#SBATCH --job-name=vobench\n#SBATCH --array=0-{}{}\n", tasks - 1,
                          o.array_limit > 0 ? fmt::format("%{}", o.array_limit) : "");
    script +=
        fmt::format("#SBATCH --output={}\n#SBATCH --cpus-per-task={}\n", sh((out / "slurm" / "logs" / "%A_%a.log").string()), threads);
    if (!o.partition.empty()) script += "#SBATCH --partition=" + o.partition + "\n";
    if (!o.account.empty()) script += "#SBATCH --account=" + o.account + "\n";
    if (!o.time.empty()) script += "#SBATCH --time=" + o.time + "\n";
    if (!o.mem.empty()) script += "#SBATCH --mem=" + o.mem + "\n";
    if (const char* path = std::getenv("VOBENCH_PLUGIN_PATH")) script += "export VOBENCH_PLUGIN_PATH=" + sh(path) + "\n";
    script += fmt::format("exec {} -q run-cell {} --batch {} --task \"$SLURM_ARRAY_TASK_ID\" --chunk {}\n",
                          sh(boost::dll::program_location().string()), sh(out.string()), sh(batch.string()), chunk);
    const fs::path job_script = out / "slurm" / ("job-" + stamp + ".sh");
    write_file_atomic(job_script, script);
    fs::permissions(job_script, fs::perms::owner_exec, fs::perm_options::add);

    const ChildResult r = slurm_command({"sbatch", "--parsable", job_script.string()});
    std::string job = r.output.substr(0, r.output.find_first_of(";\n"));
    if (!r.exited || r.exit_code != 0 || job.empty() || job.find_first_not_of("0123456789") != std::string::npos)
        throw std::runtime_error("sbatch refused the job (" + r.describe() + "): " + r.output);
    nlohmann::json jobs = read_jobs(out);
    jobs.push_back({{"job", job},
                    {"batch", batch.string()},
                    {"script", job_script.string()},
                    {"cells", pending.size()},
                    {"tasks", tasks},
                    {"chunk", chunk},
                    {"submitted", utc_now_iso()},
                    {"collected", false}});
    write_jobs(out, jobs);
    spdlog::info("submitted Slurm job {}: {} cells in {} array tasks ({} per task)", job, pending.size(), tasks, chunk);
    return job;
}

SweepTally follow_slurm(const fs::path& out_in, int poll_s) {
    const fs::path out = fs::absolute(out_in).lexically_normal();
    const std::map<std::string, Cell> cells = cells_by_id(out);
    nlohmann::json jobs = read_jobs(out);
    SweepTally tally;
    const auto start = std::chrono::steady_clock::now();
    const bool tty = ::isatty(STDERR_FILENO) == 1;
    for (auto& j : jobs) {
        if (j.value("collected", false)) continue;
        const std::string job = j["job"];
        const std::vector<std::string> ids = read_lines(j["batch"].get<std::string>());
        const int chunk = j["chunk"];
        std::size_t last_done = static_cast<std::size_t>(-1);
        for (;;) {
            const ChildResult q = slurm_command({"squeue", "-h", "-j", job, "-o", "%i|%T"});
            std::size_t queued = 0, running = 0;
            std::istringstream in(q.output);
            for (std::string line; std::getline(in, line);) {
                if (line.find("|RUNNING") != std::string::npos)
                    ++running;
                else if (!line.empty() && line.find("Invalid job id") == std::string::npos)
                    ++queued;
            }
            std::size_t done = 0;
            for (const std::string& id : ids) done += cell_finished(out, id);
            if (tty)
                std::fprintf(stderr, "\r\033[K[slurm job %s] %zu/%zu cells done, %zu tasks running, %zu queued", job.c_str(), done,
                             ids.size(), running, queued);
            else if (done != last_done)
                spdlog::info("slurm job {}: {}/{} cells done, {} tasks running, {} queued", job, done, ids.size(), running, queued);
            last_done = done;
            if (running + queued == 0) break;
            std::this_thread::sleep_for(std::chrono::seconds(poll_s));
        }
        if (tty) std::fputs("\n", stderr);
        // Cells that no task finished: failed rows with Slurm's account of their task.
        const auto states = task_states(job);
        for (std::size_t k = 0; k < ids.size(); ++k) {
            ++tally.cells;
            if (cell_finished(out, ids[k])) {
                // cell_finished() validated the record: status and frames are there and typed.
                const nlohmann::json run = read_json_or_null(out / "runs" / ids[k] / "run.json");
                if (run["status"] != "ok") ++tally.failed;
                tally.frames += run["frames"].get<uint64_t>();
                ++tally.ran;
                continue;
            }
            const int task = static_cast<int>(k) / chunk;
            std::string reason = fmt::format("slurm array task {}_{} ended without finishing this cell", job, task);
            if (const auto it = states.find(task); it != states.end()) {
                const auto& f = it->second;
                reason += fmt::format(": state {}", f.count("JobState") ? f.at("JobState") : "?");
                if (f.count("Reason") && f.at("Reason") != "None") reason += ", reason " + f.at("Reason");
                if (f.count("ExitCode")) reason += ", exit code " + f.at("ExitCode");
            } else {
                reason += " (Slurm keeps no record of it: cancelled before it started, or purged)";
            }
            reason += fmt::format("; log: slurm/logs/{}_{}.log", job, task);
            const auto cell = cells.find(ids[k]);
            if (cell == cells.end()) continue;
            record_unrun_cell(cell->second, out, reason);
            ++tally.failed;
            ++tally.ran;
            spdlog::warn("FAILED {}/{}/{} {} — {}", cell->second.dataset, cell->second.sequence, cell->second.sensor,
                         cell->second.entry_label(), reason);
        }
        j["collected"] = true;
        j["collected_at"] = utc_now_iso();
        write_jobs(out, jobs);
    }
    tally.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return tally;
}

int run_cell_batch(const fs::path& out, const fs::path& batch, int task, int chunk) {
    const std::map<std::string, Cell> cells = cells_by_id(out);
    const std::vector<std::string> ids = read_lines(batch);
    int failures = 0;
    for (std::size_t k = static_cast<std::size_t>(task) * static_cast<std::size_t>(chunk);
         k < ids.size() && k < static_cast<std::size_t>(task + 1) * static_cast<std::size_t>(chunk); ++k) {
        if (cell_finished(out, ids[k])) continue;  // a requeued task does not redo finished cells
        const auto it = cells.find(ids[k]);
        if (it == cells.end()) {
            spdlog::error("{}: cell {} is not in cells.json", batch.string(), ids[k]);
            ++failures;
            continue;
        }
        const CellOutcome o = run_cell(it->second, out);
        spdlog::info("{} {} — {}", o.ok ? "done" : "FAILED", ids[k], o.ok ? fmt::format("{} frames", o.frames) : o.reason);
    }
    return failures == 0 ? 0 : 1;
}

}  // namespace vobench
