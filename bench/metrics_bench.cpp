// Metrics speed: ATE + RPE on 10^6-pose trajectories, and TUM association on fr2/desk (20,957
// ground-truth poses), beside the literal O(N·M) association of associate.py for the ratio.
#include "metrics/evaluation.hpp"
#include "metrics/trajectory_io.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>

using namespace vobench::metrics;

namespace {

Trajectory make(std::size_t n, double noise, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> g(0.0, 1.0);
    Trajectory t(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double s = 0.01 * static_cast<double>(i);
        t[i].t = s;
        t[i].p = {std::sin(0.01 * s) * 10 + noise * g(rng), std::cos(0.013 * s) * 10 + noise * g(rng), 0.001 * s};
        t[i].q = Eigen::Quaterniond(Eigen::AngleAxisd(0.02 * s + noise * g(rng), Eigen::Vector3d::UnitZ()));
    }
    return t;
}

void BM_AteAndRpe(benchmark::State& state) {
    const std::size_t n = static_cast<std::size_t>(state.range(0));
    const Trajectory gt = make(n, 0.0, 1), est = make(n, 0.01, 2);
    Protocol p;  // paper: association, se3 alignment, RPE Δ = 4 frames
    for (auto _ : state) {
        const Evaluation e = evaluate(gt, est, p);
        benchmark::DoNotOptimize(e.rpe->trans.rmse);
    }
    state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(n));
}
BENCHMARK(BM_AteAndRpe)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();

struct Fr2Desk {
    std::vector<double> gt, est;
    Fr2Desk() {
        const char* env = std::getenv("VOBENCH_DATA_DIR");
        const std::filesystem::path dir = std::filesystem::path(env ? env : VOBENCH_TEST_DATA_DIR) / "real" / "trajectories";
        ReadOptions o;
        o.tum_scripts = true;
        if (std::filesystem::exists(dir / "freiburg2_desk-groundtruth.txt")) {
            gt = stamps_of(read_trajectory(dir / "freiburg2_desk-groundtruth.txt", o).poses);
            est = stamps_of(read_trajectory(dir / "freiburg2_desk-ORB.txt", o).poses);
        } else {  // same sizes and rates, made up
            for (int i = 0; i < 20957; ++i) gt.push_back(0.01 * i);
            for (int i = 0; i < 2893; ++i) est.push_back(0.0333 * i + 0.003);
        }
    }
};
const Fr2Desk& fr2() {
    static const Fr2Desk data;
    return data;
}

void BM_AssociateFr2Desk(benchmark::State& state) {
    for (auto _ : state) benchmark::DoNotOptimize(associate(fr2().gt, fr2().est, {}).matches.size());
    state.counters["matches"] = static_cast<double>(associate(fr2().gt, fr2().est, {}).matches.size());
}
BENCHMARK(BM_AssociateFr2Desk)->Unit(benchmark::kMillisecond)->UseRealTime();

// associate.py as written: every one of the N·M pairs is tested. The reference for the ratio.
void BM_AssociateFr2DeskLiteral(benchmark::State& state) {
    const auto& a = fr2().gt;
    const auto& b = fr2().est;
    for (auto _ : state) {
        std::vector<std::tuple<double, std::size_t, std::size_t>> potential;
        for (std::size_t i = 0; i < a.size(); ++i)
            for (std::size_t j = 0; j < b.size(); ++j)
                if (std::abs(a[i] - b[j]) < 0.02) potential.emplace_back(std::abs(a[i] - b[j]), i, j);
        std::sort(potential.begin(), potential.end());
        benchmark::DoNotOptimize(potential.size());
    }
}
BENCHMARK(BM_AssociateFr2DeskLiteral)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
