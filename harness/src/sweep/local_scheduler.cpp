#include "sweep/local_scheduler.hpp"

#include "record/host_info.hpp"
#include "record/results_dir.hpp"
#include "sweep/cell_runner.hpp"
#include "util/subprocess.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <unistd.h>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <mutex>
#include <set>
#include <thread>

namespace vobench {
namespace fs = std::filesystem;

namespace {

// Finished cells with sound records; with `set_aside`, unsound ones go to corrupt/ (to be run again).
std::vector<std::string> finished_ids(const fs::path& out, bool set_aside) {
    const ResultsDir dir(out);
    std::vector<std::string> ids;
    for (const std::string& id : dir.run_ids()) {
        const std::string problem = record_problem(dir.run_dir(id), id);
        if (problem.empty()) {
            ids.push_back(id);
        } else if (set_aside) {
            const fs::path to = set_aside_corrupt(dir, id);
            spdlog::warn("{}: not a sound record ({}); moved to {}, the cell runs again", dir.run_dir(id).string(), problem, to.string());
        }
    }
    return ids;
}

// One line that rewrites itself on a terminal; plain log lines otherwise.
class Progress {
public:
    Progress(std::size_t total, int jobs) : total_(total), jobs_(jobs), tty_(::isatty(STDERR_FILENO) == 1) {}

    void started() {
        std::lock_guard<std::mutex> lock(mutex_);
        ++running_;
        draw_locked(false);
    }
    void finished(const Cell& cell, const CellOutcome& o) {
        std::lock_guard<std::mutex> lock(mutex_);
        --running_;
        ++done_;
        if (!o.ok) ++failed_;
        frames_ += o.frames;
        if (tty_) std::fputs("\r\033[K", stderr);
        const std::string what = fmt::format("{}/{}/{} {} [{}]", cell.dataset, cell.sequence, cell.sensor.empty() ? "-" : cell.sensor,
                                             cell.entry_label(), cell.id.substr(0, 8));
        if (o.ok)
            spdlog::info("done {} — {} frames in {:.1f} s", what, o.frames, o.wall_s);
        else
            spdlog::warn("FAILED {} — {}", what, o.reason);
        draw_locked(true);
    }
    void stopped() {
        std::lock_guard<std::mutex> lock(mutex_);
        --running_;
    }
    void end() {
        if (tty_) std::fputs("\n", stderr);
    }
    uint64_t frames() const { return frames_; }

private:
    void draw_locked(bool force) {
        const auto now = std::chrono::steady_clock::now();
        const double elapsed = std::chrono::duration<double>(now - start_).count();
        if (!tty_ || (!force && now - last_ < std::chrono::milliseconds(500))) return;
        last_ = now;
        std::string eta = "–";
        if (done_ > 0) {
            const double per_cell = elapsed / static_cast<double>(done_);
            const double left = per_cell * static_cast<double>(total_ - done_);
            eta = fmt::format("{}:{:02d}", static_cast<int>(left) / 60, static_cast<int>(left) % 60);
        }
        std::fprintf(stderr, "\r\033[K[%zu/%zu done, %zu failed, %zu running, -j %d] %.0f frames/s, ETA %s", done_, total_, failed_,
                     running_, jobs_, elapsed > 0 ? static_cast<double>(frames_) / elapsed : 0.0, eta.c_str());
        std::fflush(stderr);
    }
    std::mutex mutex_;
    std::size_t total_, done_ = 0, failed_ = 0, running_ = 0;
    uint64_t frames_ = 0;
    int jobs_;
    bool tty_;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now(), last_{};
};

std::atomic<bool> g_interrupted{false};

// A signal sent by a process of a running cell (a plugin calling kill(getppid(), SIGTERM), or
// kill(-1, …)) fails that cell and the sweep goes on; from anyone else (Ctrl-C, `kill`) it stops
// the sweep.
extern "C" void on_interrupt(int signal, siginfo_t* info, void*) {
    // si_code <= 0: sent by a process (kill, sigqueue, tgkill); a terminal's Ctrl-C comes from the kernel.
    if (info != nullptr && info->si_code <= 0 && blame_signal_sender(signal, info->si_pid)) return;
    g_interrupted = true;
}

// SIGINT and SIGTERM go to on_interrupt while it lives; the former handlers come back after.
class InterruptGuard {
public:
    InterruptGuard() {
        g_interrupted = false;
        struct sigaction sa {};
        sa.sa_sigaction = on_interrupt;
        sa.sa_flags = SA_SIGINFO;
        sigemptyset(&sa.sa_mask);
        ::sigaction(SIGINT, &sa, &old_int_);
        ::sigaction(SIGTERM, &sa, &old_term_);
    }
    ~InterruptGuard() {
        ::sigaction(SIGINT, &old_int_, nullptr);
        ::sigaction(SIGTERM, &old_term_, nullptr);
    }
    InterruptGuard(const InterruptGuard&) = delete;
    InterruptGuard& operator=(const InterruptGuard&) = delete;

private:
    struct sigaction old_int_ {
    }, old_term_{};
};

}  // namespace

void prepare_output(const std::vector<Cell>& cells, const SweepOptions& options) {
    // Temporary files of writes that a killed vobench never renamed into place: never results.
    for (const fs::path& folder : {options.out, options.out / "figures"}) {
        if (!fs::is_directory(folder)) continue;
        for (const auto& e : fs::directory_iterator(folder))
            if (e.is_regular_file() && e.path().filename().string().find(".tmp.") != std::string::npos) fs::remove(e.path());
    }
    const std::vector<std::string> done = finished_ids(options.out, options.resume);
    if (options.fresh && fs::exists(options.out / "runs")) {
        const fs::path aside = options.out / ("discarded-" + utc_now_iso());
        fs::create_directories(aside);
        fs::rename(options.out / "runs", aside / "runs");
        spdlog::warn("--fresh: earlier results moved to {}", aside.string());
        return;
    }
    if (done.empty()) return;
    if (!options.resume)
        throw std::runtime_error(
            fmt::format("{} already holds {} finished cells: pass --resume to continue that sweep, or --fresh to set them "
                        "aside and start again",
                        options.out.string(), done.size()));
    std::set<std::string> current;
    for (const Cell& c : cells) current.insert(c.id);
    std::size_t moved = 0;
    for (const std::string& id : done)
        if (!current.count(id)) {
            fs::create_directories(options.out / "stale");
            fs::remove_all(options.out / "stale" / id);
            fs::rename(options.out / "runs" / id, options.out / "stale" / id);
            ++moved;
        }
    if (moved > 0)
        spdlog::info("{} finished cells belong to another configuration or plugin build; moved to {}", moved,
                     (options.out / "stale").string());
}

std::vector<Cell> pending_cells(const std::vector<Cell>& cells, const SweepOptions& options) {
    std::vector<Cell> out;
    for (const Cell& c : cells) {
        if (!options.only.empty() && !cell_matches(c, options.only)) continue;
        if (options.resume && cell_finished(options.out, c.id)) continue;
        out.push_back(c);
    }
    return out;
}

SweepTally run_local(const std::vector<Cell>& cells, const SweepOptions& options) {
    SweepTally tally;
    tally.cells = cells.size();
    const std::vector<Cell> todo = pending_cells(cells, options);
    tally.skipped = cells.size() - todo.size();
    if (tally.skipped > 0)
        spdlog::info("{} of {} cells already finished or not selected; running {}", tally.skipped, cells.size(), todo.size());
    // Work left behind by a killed run: never trusted, always redone.
    fs::remove_all(options.out / "runs" / ".work");
    const auto start = std::chrono::steady_clock::now();
    Progress progress(todo.size(), options.jobs);
    const InterruptGuard interrupt_guard;
    std::atomic<std::size_t> next{0}, failed{0}, ran{0};
    std::mutex error_mutex;
    std::string fatal;
    // -j N with N cells of one thread each on at least N cores: worker j's cells run on the j-th CPU
    // this process may use, so two cells never share a core (recorded as each cell's pinned_core).
    const std::vector<int> cpus = allowed_cpus();
    const bool pin = options.jobs >= 2 && static_cast<std::size_t>(options.jobs) <= cpus.size();
    auto worker = [&](int slot) {
        for (std::size_t k; (k = next++) < todo.size();) {
            {
                std::lock_guard<std::mutex> lock(error_mutex);
                if (!fatal.empty() || g_interrupted) return;
            }
            progress.started();
            try {
                const int core = pin && todo[k].limits.threads == 1 ? cpus[static_cast<std::size_t>(slot)] : -1;
                const CellOutcome o = run_cell(todo[k], options.out, &g_interrupted, core);
                if (o.interrupted) {
                    progress.stopped();
                    continue;
                }
                if (!o.ok) ++failed;
                ++ran;
                progress.finished(todo[k], o);
            } catch (const std::exception& e) {  // the output folder cannot be written: stop cleanly
                std::lock_guard<std::mutex> lock(error_mutex);
                fatal = e.what();
            }
        }
    };
    std::vector<std::thread> pool;
    for (int j = 0; j < std::max(1, options.jobs); ++j) pool.emplace_back(worker, j);
    for (std::thread& t : pool) t.join();
    progress.end();
    if (!fatal.empty()) throw std::runtime_error("the sweep stopped: " + fatal);
    tally.ran = ran;
    tally.interrupted = g_interrupted;
    tally.failed = failed;
    tally.frames = progress.frames();
    tally.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return tally;
}

}  // namespace vobench
