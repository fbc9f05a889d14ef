// slurm_backend.hpp — the same cells on a Slurm cluster.
//
// `vobench run CONFIG --backend slurm` writes the cell list into the output folder (which the nodes
// must share), submits one `sbatch --array` job whose task k runs
// `vobench run-cell OUT --batch FILE --task k --chunk C` — cells k·C … k·C+C−1 of the batch, each in
// its own child process exactly as locally — and follows the job with squeue until it ends. Tasks that
// ended without finishing their cells (cancelled, timed out, node failure, out of memory) become
// failed rows with Slurm's state and reason, read from `scontrol show job` (or sacct). With --detach
// it returns after submitting and `vobench collect OUT` finishes later. Results are the files of a
// local run; `vobench report` works the same.
#pragma once

#include "sweep/cell.hpp"
#include "sweep/local_scheduler.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace vobench {

struct SlurmOptions {
    std::string partition, account, time, mem;  // passed to sbatch when given
    int array_limit = 0;                        // at most this many tasks at once (%K); 0: Slurm's default
    int chunk = 1;                              // cells per array task
    int poll_s = 5;                             // squeue interval while following
};

// Submits the pending cells (all of `cells` not finished in `out`); returns the job id ("" when
// nothing is pending). Throws std::runtime_error with sbatch's message when submission fails.
std::string submit_slurm(const std::vector<Cell>& pending, const std::filesystem::path& out, const SlurmOptions& options, int threads);

// Follows every job submitted into `out` that is not collected yet, until none of its tasks is
// queued or running; records failed rows for cells their tasks left unfinished. Returns the tally.
SweepTally follow_slurm(const std::filesystem::path& out, int poll_s);

// The array-task side: cells [task·chunk, task·chunk + chunk) of the batch file. Returns an exit code.
int run_cell_batch(const std::filesystem::path& out, const std::filesystem::path& batch, int task, int chunk);

// Per array task: {"JobState": "TIMEOUT", "Reason": "…", "ExitCode": "0:9"}, parsed from
// `scontrol -o show job` output (one line per task).
std::map<int, std::map<std::string, std::string>> parse_scontrol_tasks(const std::string& text);

}  // namespace vobench
