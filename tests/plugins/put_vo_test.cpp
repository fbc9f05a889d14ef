// put_vo against real data (TUM fr1/rpy) and the synthetic Kinect v1/v2 sequences.
#include "synth/sequence_writer.hpp"
#include "test_support.hpp"
#include "track/track.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <numeric>

using namespace vobench;

namespace {

TrackResult track(const std::string& path, const std::string& algorithm, const ParamMap& options = {}, const ParamMap& params = {},
                  uint64_t seed = 1) {
    TrackOptions o;
    o.dataset = "tum";
    o.path = path;
    o.dataset_options = options;
    o.params = params;
    o.algorithm = algorithm;
    o.seed = seed;
    return run_track(o, PluginRegistry({VOBENCH_PLUGIN_DIR}));
}

}  // namespace

// Issue #19: put_vo against RgbdOdometry on the real sample (seed 1, paper RPE over 4 frames), one
// RgbdOdometry run for all profiles. The default (key frames by image motion too, the pool refilled at
// each, FAST-Harris corners, 350 features): 0.0122 m / 0.69° against 0.0155 m / 0.82°, 0.0119-0.0130 m
// over seven nearby settings, each ahead (put_vo README, "The default since 2.0"); refresh (every frame
// a key frame): 0.0102 m. 0.85 leaves room for other builds. profile=keyframes (put_vo 1.0's default):
// 0.0147 m, level, and only just (one-step changes of the feature-pool parameters move it by up to
// 75 %; README, "How far the sample's figures move"); the 5 % allowance is for other machines' OpenCV builds.
TEST_CASE("put_vo on fr1/rpy: the default and refresh ahead of OpenCV RgbdOdometry's RPE, keyframes no worse", "[put_vo][reference]") {
    VOBENCH_REQUIRE_DATA(dir, "real/rgbd_dataset_freiburg1_rpy");
    const TrackResult cv = track(dir.string(), "opencv_rgbd", {{"intrinsics", "fr1"}});
    REQUIRE(cv.evaluation);
    const double cv_trans = cv.evaluation->rpe->trans.rmse;
    for (const std::string profile : {"default", "refresh", "keyframes"}) {
        const TrackResult put = track(dir.string(), "put_vo", {{"intrinsics", "fr1"}}, {{"profile", profile}});
        INFO("profile " << profile << ": RPE " << (put.evaluation ? put.evaluation->rpe->trans.rmse : -1) << " m / "
                        << (put.evaluation ? put.evaluation->rpe->rot_deg.rmse : -1) << " deg, RgbdOdometry " << cv_trans << " m / "
                        << cv.evaluation->rpe->rot_deg.rmse << " deg");
        REQUIRE(put.error.empty());
        REQUIRE(put.evaluation);
        CHECK(put.frames.size() == 90);
        CHECK(put.failed_frames == 0);
        if (profile == "keyframes") {
            CHECK(put.evaluation->rpe->trans.rmse <= 1.05 * cv_trans);
        } else {
            CHECK(put.evaluation->rpe->trans.rmse <= 0.85 * cv_trans);
            CHECK(put.evaluation->rpe->rot_deg.rmse <= cv.evaluation->rpe->rot_deg.rmse);
        }
    }
}

// Issue #19: over RANSAC seeds 1–5 the ATE on the sample varies by at most 10 % of its mean. Measured
// 0.0145 ± 0.0001 m; before gate_fallback 0.0096–0.0138 m (35 %: at frame 51 the gated refinement
// kept 74 pairs for some seeds and 25 for others).
TEST_CASE("put_vo on fr1/rpy: the ATE hardly moves with the RANSAC seed", "[put_vo][reference]") {
    VOBENCH_REQUIRE_DATA(dir, "real/rgbd_dataset_freiburg1_rpy");
    std::vector<double> ate;
    for (uint64_t seed = 1; seed <= 5; ++seed) {
        const TrackResult r = track(dir.string(), "put_vo", {{"intrinsics", "fr1"}}, {}, seed);
        REQUIRE(r.evaluation);
        CHECK(r.failed_frames == 0);
        REQUIRE(r.evaluation->ate);
        ate.push_back(r.evaluation->ate->stats.rmse);
    }
    const auto [low, high] = std::minmax_element(ate.begin(), ate.end());
    const double mean = std::accumulate(ate.begin(), ate.end(), 0.0) / static_cast<double>(ate.size());
    INFO("ATE " << *low << "–" << *high << " m, mean " << mean << " m");
    CHECK(*high - *low <= 0.10 * mean);
}

// detector=fast_harris keeps corners (LK window's reach on the coarsest level) from the image's
// edge; with a deep pyramid and a wide window that reach is larger than the image, so it is capped at
// a quarter of the image's shorter side — without the cap no corner is found and every frame is lost.
TEST_CASE("put_vo with fast_harris corners and a deep pyramid still tracks (the edge border is capped)", "[put_vo]") {
    VOBENCH_REQUIRE_DATA(dir, "real/rgbd_dataset_freiburg1_rpy");
    TrackOptions o;
    o.dataset = "tum";
    o.path = dir.string();
    o.dataset_options = {{"intrinsics", "fr1"}};
    o.params = {{"lk_levels", "8"}, {"lk_window", "61"}};  // the default detector: fast_harris
    o.algorithm = "put_vo";
    o.seed = 1;
    o.max_frames = 12;
    const TrackResult r = run_track(o, PluginRegistry({VOBENCH_PLUGIN_DIR}));
    REQUIRE(r.error.empty());
    CHECK(r.frames.size() == 12);
    CHECK(r.failed_frames == 0);
}

// profile=paper turns off what the plugin adds to §5.1 (flow prior, forward-backward check, depth
// weighting, noise-model refinement, depth interpolation, parallax key frames, refill, FAST-Harris
// corners). Measured on the sample (configs/real_sample.yaml, seeds 1-5): it loses one frame per seed
// and its RPE per second is 0.083 m against the default's 0.039 m (4 frames: 0.023 against 0.012 m).
TEST_CASE("put_vo profile=paper runs the paper's pipeline: a different trajectory, near the default's error", "[put_vo][reference]") {
    VOBENCH_REQUIRE_DATA(dir, "real/rgbd_dataset_freiburg1_rpy");
    const TrackResult def = track(dir.string(), "put_vo", {{"intrinsics", "fr1"}});
    const TrackResult paper = track(dir.string(), "put_vo", {{"intrinsics", "fr1"}}, {{"profile", "paper"}});
    REQUIRE(paper.error.empty());
    REQUIRE(paper.evaluation);
    REQUIRE(def.evaluation);
    CHECK(paper.frames.size() == 90);
    CHECK(paper.failed_frames <= 2);
    CHECK(paper.evaluation->rpe->trans.rmse != def.evaluation->rpe->trans.rmse);
    INFO("RPE paper " << paper.evaluation->rpe->trans.rmse << " m, default " << def.evaluation->rpe->trans.rmse << " m");
    CHECK(paper.evaluation->rpe->trans.rmse < 2 * def.evaluation->rpe->trans.rmse);
}

TEST_CASE("put_vo is deterministic: same input and seed, bit-identical trajectory", "[put_vo][determinism]") {
    VOBENCH_REQUIRE_DATA(dir, "real/rgbd_dataset_freiburg1_rpy");
    const TrackResult a = track(dir.string(), "put_vo", {{"intrinsics", "fr1"}});
    const TrackResult b = track(dir.string(), "put_vo", {{"intrinsics", "fr1"}});
    REQUIRE(a.estimate.size() == b.estimate.size());
    for (std::size_t k = 0; k < a.estimate.size(); ++k) {
        CHECK(a.estimate[k].p == b.estimate[k].p);
        CHECK(a.estimate[k].q.coeffs() == b.estimate[k].q.coeffs());
    }
}

// Since issue #15 the rendering is meant to be as hard as real data: put_vo's RPE stays within 1.5× of
// the paper's real Table 5 values, and Kinect v2 beats Kinect v1 as in the paper.
TEST_CASE("put_vo on sim-PUTK² explore1: within 1.5x the paper's Table 5 RPE, Kinect v2 better than v1", "[put_vo][synth]") {
    test::TempDir tmp;
    double ate[2], rpe[2];
    const char* sensors[2] = {"kinect1", "kinect2"};
    for (int s = 0; s < 2; ++s) {
        synth::SynthOptions o;
        o.sensor = sensors[s];
        o.trajectory = "explore1";
        o.frames = 40;
        o.out = tmp.path() / sensors[s];
        synth::synthesize(o);
        const TrackResult r = track(o.out.string(), "put_vo");
        REQUIRE(r.evaluation);
        CHECK(r.failed_frames == 0);
        ate[s] = r.evaluation->ate->stats.rmse;
        rpe[s] = r.evaluation->rpe->trans.rmse;
    }
    INFO("Kinect v1: ATE " << ate[0] << " RPE " << rpe[0] << "; Kinect v2: ATE " << ate[1] << " RPE " << rpe[1]);
    CHECK(rpe[0] <= 1.5 * 0.017);  // Kraft et al. Table 5, Kinect v1
    CHECK(rpe[1] <= 1.5 * 0.011);  // Kinect v2
    CHECK(ate[1] < ate[0]);
}

// Long (label `long`, `make test-long`): the four exploration paths, 150 frames each, both sensors.
TEST_CASE("put_vo on the four sim-PUTK² exploration paths (Table 5 targets)", "[.long][put_vo][synth]") {
    test::TempDir tmp;
    int v2_better = 0;
    for (const char* path : {"explore1", "explore2", "explore3", "explore4"}) {
        double ate[2], rpe[2];
        const char* sensors[2] = {"kinect1", "kinect2"};
        for (int s = 0; s < 2; ++s) {
            synth::SynthOptions o;
            o.sensor = sensors[s];
            o.trajectory = path;
            o.frames = 150;
            o.out = tmp.path() / (std::string(path) + sensors[s]);
            synth::synthesize(o);
            const TrackResult r = track(o.out.string(), "put_vo");
            REQUIRE(r.evaluation);
            ate[s] = r.evaluation->ate->stats.rmse;
            rpe[s] = r.evaluation->rpe->trans.rmse;
            WARN(path << " " << sensors[s] << ": ATE " << ate[s] << " m, RPE " << rpe[s] << " m, lost " << r.failed_frames << ", "
                      << r.mean_ms() << " ms/frame");
        }
        CHECK(rpe[0] <= 1.5 * 0.017);
        CHECK(rpe[1] <= 1.5 * 0.011);
        v2_better += ate[1] < ate[0];
    }
    CHECK(v2_better >= 3);
}
