// End-to-end sweeps through the CLI: fault plugins become failed rows with the right reason, the
// sweep completes, finished cells are kept and skipped on --resume, and -j 2 computes what -j 1 does.
#include "test_support.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <fstream>
#include <map>
#include <sstream>

using namespace vobench;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

std::string slurp(const fs::path& file) {
    std::ifstream in(file);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

nlohmann::json json_of(const fs::path& file) { return nlohmann::json::parse(slurp(file)); }

// A small rendered sequence, shared by the tests of this file (rendered once per test process).
fs::path tiny_sequence(const std::string& sensor = "kinect1", const std::string& trajectory = "speed2") {
    static std::map<std::string, fs::path> made;
    static test::TempDir root;
    const std::string key = sensor + "-" + trajectory;
    if (made.count(key)) return made[key];
    const fs::path dir = root.path() / key;
    std::string out;
    const int rc = test::run_command(test::cli().string() + " -q synth --sensor " + sensor + " --trajectory " + trajectory +
                                         " --frames 8 --out " + dir.string() + " 2>&1",
                                     out);
    INFO(out);
    REQUIRE(rc == 0);
    return made[key] = dir;
}

int run_sweep(const fs::path& config, const std::string& args, std::string& out) {
    return test::run_command("VOBENCH_PLUGIN_PATH= " + test::cli().string() + " run " + config.string() + " " + args + " 2>&1", out);
}

std::string fault(const std::string& name) { return test::fault_plugin("fault_" + name).string(); }

}  // namespace

TEST_CASE("every fault becomes a failed row with its reason, and the sweep completes", "[sweep]") {
    test::TempDir dir;
    const fs::path config = dir.path() / "faults.yaml";
    std::ofstream(config) << "name: faults\n"
                             "datasets:\n  - {name: tiny, reader: tum, path: "
                          << tiny_sequence().string()
                          << "}\n"
                             "algorithms:\n"
                             "  - {name: healthy, plugin: constant_pose}\n"
                             "  - {name: segfault, plugin: "
                          << fault("segfault")
                          << "}\n"
                             "  - {name: abort, plugin: "
                          << fault("abort")
                          << "}\n"
                             "  - {name: exception, plugin: "
                          << test::fault_plugin("vobench_counter").string()
                          << ", params: {throw_at: 3}}\n"
                             "  - {name: memory, plugin: "
                          << fault("memory")
                          << "}\n"
                             "  - {name: nan_pose, plugin: "
                          << fault("nan_pose")
                          << "}\n"
                             "  - {name: wrong_abi, plugin: "
                          << fault("wrong_abi")
                          << "}\n"
                             "  - {name: error_status, plugin: "
                          << fault("error_status")
                          << "}\n"
                             "  - {name: exit, plugin: "
                          << fault("exit")
                          << "}\n"
                             "  - {name: stdout_garbage, plugin: "
                          << fault("stdout_garbage")
                          << "}\n"
                             // A timeout no fault here should reach, even on a loaded machine: the
                             // memory eater must be stopped by the memory limit, not by the clock
                             // (the hang has a sweep of its own below).
                             "limits: {timeout: 120, memory_mb: 512}\n"
                             "criteria: ['failed_cells == 0']\n";
    const fs::path out = dir.path() / "out";
    std::string log;
    const int rc = run_sweep(config, "--out " + out.string() + " -j 2", log);
    INFO(log);
    CHECK(rc == 1);  // failed cells are results; the exit status comes from the required criterion below
    const nlohmann::json lb = json_of(out / "leaderboard.json");
    std::map<std::string, std::string> reasons;
    std::map<std::string, nlohmann::json> failed_at;
    for (const auto& f : lb["failures"]) {
        reasons[f["entry"]] = f["reason"];
        failed_at[f["entry"]] = f["failed_at_frame"];
    }
    CHECK(reasons.size() == 8);
    CHECK_THAT(reasons["segfault"], Contains("killed by signal 11 (SIGSEGV) at frame 0"));
    CHECK_THAT(reasons["abort"], Contains("killed by signal 6 (SIGABRT) at frame 3"));
    CHECK_THAT(reasons["exception [throw_at=3]"], Contains("failed at frame 3") && Contains("deliberate failure at frame 3"));
    CHECK_THAT(reasons["memory"], Contains("exceeded the memory limit of 512 MB (killed) at frame 3"));
    CHECK_THAT(reasons["nan_pose"], Contains("non-finite pose at frame 3"));
    CHECK_THAT(reasons["wrong_abi"], Contains("refused to load") && Contains("vobench_plugin_entry_v2"));
    CHECK_THAT(reasons["error_status"], Contains("failed at frame 3") && Contains("deliberate error status at frame 3"));
    CHECK_THAT(reasons["exit"], Contains("exited with code 3 at frame 0"));
    CHECK(reasons.count("healthy") == 0);
    CHECK(reasons.count("stdout_garbage") == 0);  // noise on stdout/stderr is the plugin's business, not a result
    CHECK(failed_at["abort"] == 3);
    // Undeclared in the config: the reader declares it (a rendered sequence: exact, 0).
    CHECK(lb["entries"][0]["cells"][0]["gt_accuracy"]["position_m"] == 0.0);

    // Partial trajectories are kept and marked: the three frames before the fault.
    for (const auto& e : lb["entries"]) {
        const std::string name = e["entry"];
        const std::string id = e["cells"][0]["id"];
        const nlohmann::json run = json_of(out / "runs" / id / "run.json");
        if (name == "abort" || name == "nan_pose" || name == "error_status" || name == "memory" || name == "exception [throw_at=3]") {
            CHECK(run["partial"] == true);
            CHECK(run["frames"] == 3);
            std::ifstream t(out / "runs" / id / "trajectory.txt");
            int lines = 0;
            for (std::string l; std::getline(t, l);) lines += !l.empty() && l[0] != '#';
            CHECK(lines == 3);
        }
        if (name == "healthy" || name == "stdout_garbage") {
            CHECK(run["status"] == "ok");
            CHECK(run["frames"] == 8);
            CHECK(e["rank"].is_number());
        } else {
            CHECK(e["rank"].is_null());
        }
        // The child's own peak resident set: the memory eater was stopped just above its 512 MB limit.
        if (name == "memory") CHECK(run["timing"]["peak_rss_mb"].get<double>() >= 512);
        if (name == "healthy") CHECK(run["timing"]["peak_rss_mb"].get<double>() < 256);
        if (name == "stdout_garbage") CHECK_THAT(slurp(out / "runs" / id / "child.log"), Contains("frame 3 FAILED"));
    }
    // The criterion failed_cells == 0 is reported per entry; it is required, so `run` says so.
    CHECK_THAT(log, Contains("REQUIRED CRITERION NOT MET: segfault: failed_cells == 0"));
    CHECK_THAT(slurp(out / "summary.md"), Contains("## Failures"));
    CHECK_THAT(slurp(out / "report.html"), Contains("SIGSEGV"));

    // The hang, alone under a short timeout: it never returns from frame 0, however slowly it started.
    const fs::path hang_config = dir.path() / "hang.yaml";
    std::ofstream(hang_config) << "name: hang\n"
                                  "datasets:\n  - {name: tiny, reader: tum, path: "
                               << tiny_sequence().string() << "}\nalgorithms:\n  - {name: hang, plugin: " << fault("hang")
                               << "}\nlimits: {timeout: 2}\n";
    std::string hang_log;
    const int hang_rc = run_sweep(hang_config, "--out " + (dir.path() / "hang").string(), hang_log);
    INFO(hang_log);
    CHECK(hang_rc == 0);  // a failed cell is a result; no criterion is required here
    const nlohmann::json hang = json_of(dir.path() / "hang" / "leaderboard.json");
    REQUIRE(hang["failures"].size() == 1);
    CHECK_THAT(hang["failures"][0]["reason"].get<std::string>(), Contains("timed out after 2 s (killed) at frame 0"));
}

TEST_CASE("finished cells are kept: --resume skips them, a plain rerun refuses", "[sweep]") {
    test::TempDir dir;
    const fs::path config = dir.path() / "s.yaml";
    std::ofstream(config) << "datasets:\n  - {name: tiny, reader: tum, path: " << tiny_sequence().string()
                          << ", ground_truth_accuracy: {position_m: 0.5, rotation_deg: 30}}\n"
                             "algorithms:\n  - {plugin: constant_pose}\n  - {plugin: orb_matching}\n";
    const fs::path out = dir.path() / "out";
    std::string log;
    // --only: a subset by wildcard on dataset/sequence/sensor/algorithm/id; --resume adds the rest.
    REQUIRE(run_sweep(config, "--out " + out.string() + " --only '*/constant_pose/*'", log) == 0);
    CHECK(json_of(out / "leaderboard.json")["entries"].size() == 1);
    REQUIRE(run_sweep(config, "--out " + out.string() + " --resume", log) == 0);
    CHECK_THAT(log, Contains("1 of 2 cells already finished or not selected; running 1"));
    fs::remove_all(out);
    REQUIRE(run_sweep(config, "--out " + out.string(), log) == 0);
    const auto before = fs::last_write_time(out / "runs" / json_of(out / "cells.json")[0]["id"].get<std::string>() / "run.json");
    CHECK(run_sweep(config, "--out " + out.string(), log) != 0);
    CHECK_THAT(log, Contains("already holds 2 finished cells: pass --resume"));
    REQUIRE(run_sweep(config, "--out " + out.string() + " --resume", log) == 0);
    CHECK_THAT(log, Contains("2 of 2 cells already finished or not selected; running 0"));
    CHECK(fs::last_write_time(out / "runs" / json_of(out / "cells.json")[0]["id"].get<std::string>() / "run.json") == before);
    CHECK(!fs::exists(out / "runs" / ".work"));

    // The report is rebuilt from runs/ alone.
    const nlohmann::json lb = json_of(out / "leaderboard.json");
    // The config's declared ground-truth accuracy flags metrics within it (here: everything).
    CHECK(lb["entries"][0]["cells"][0]["gt_accuracy"]["position_m"] == 0.5);
    CHECK_THAT(lb["entries"][0]["cells"][0]["within_gt_error"].dump(), Contains("ate.rmse"));
    CHECK_THAT(slurp(out / "summary.md"), Contains("‡"));
    for (const char* f : {"summary.md", "summary.csv", "summary.tex", "leaderboard.json", "report.html", "sweep.json"}) fs::remove(out / f);
    REQUIRE(test::run_command(test::cli().string() + " report " + out.string() + " 2>&1", log) == 0);
    const nlohmann::json again = json_of(out / "leaderboard.json");
    CHECK(again["entries"] == lb["entries"]);
    CHECK(fs::exists(out / "summary.tex"));
}

TEST_CASE("two cells at a time (-j 2) compute exactly what one at a time does", "[sweep]") {
    test::TempDir dir;
    const fs::path config = dir.path() / "s.yaml";
    std::ofstream(config) << "datasets:\n  - {name: a, reader: tum, path: " << tiny_sequence("kinect1", "speed2").string() << "}\n"
                          << "  - {name: b, reader: tum, path: " << tiny_sequence("kinect2", "speed3").string()
                          << "}\n"
                             "algorithms:\n  - {plugin: put_vo}\n  - {plugin: orb_matching}\nrepeats: 2\nframes: 6\n";
    std::string log;
    REQUIRE(run_sweep(config, "--out " + (dir.path() / "j1").string() + " -j 1", log) == 0);
    REQUIRE(run_sweep(config, "--out " + (dir.path() / "j2").string() + " -j 2", log) == 0);
    const nlohmann::json cells = json_of(dir.path() / "j1" / "cells.json");
    REQUIRE(cells.size() == 8);
    CHECK(cells == json_of(dir.path() / "j2" / "cells.json"));
    for (const auto& c : cells) {
        const std::string id = c["id"];
        CHECK(json_of(dir.path() / "j1" / "runs" / id / "run.json")["frames"] == 6);  // frames: 6 caps every sequence
        CHECK(slurp(dir.path() / "j1" / "runs" / id / "trajectory.txt") == slurp(dir.path() / "j2" / "runs" / id / "trajectory.txt"));
        CHECK(json_of(dir.path() / "j1" / "runs" / id / "run.json")["evaluation"] ==
              json_of(dir.path() / "j2" / "runs" / id / "run.json")["evaluation"]);
    }
}
