#include "track/frame_cache.hpp"
#include "synth/sequence_writer.hpp"
#include "test_support.hpp"
#include "track/track.hpp"

#include <catch2/catch.hpp>

#include <fstream>

using namespace vobench;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

TEST_CASE("the decoded-frame cache serves identical frames and follows the content", "[run][cache]") {
    test::TempDir tmp;
    synth::SynthOptions s;
    s.sensor = "kinect1";
    s.trajectory = "speed2";
    s.frames = 8;
    s.out = tmp.path() / "seq";
    synth::synthesize(s);
    TrackOptions o;
    o.dataset = "tum";
    o.path = s.out.string();
    o.algorithm = "put_vo";
    const PluginRegistry registry({VOBENCH_PLUGIN_DIR});
    const TrackResult plain = run_track(o, registry);
    o.frame_cache = tmp.path() / "cache";
    const TrackResult filling = run_track(o, registry);  // decodes and fills the cache
    const TrackResult cached = run_track(o, registry);   // reads the cache only
    REQUIRE(plain.estimate.size() == 8);
    for (const TrackResult* r : {&filling, &cached}) {
        REQUIRE(r->estimate.size() == plain.estimate.size());
        for (std::size_t k = 0; k < plain.estimate.size(); ++k) {
            CHECK(r->estimate[k].p == plain.estimate[k].p);  // bit-identical input, bit-identical output
            CHECK(r->estimate[k].t == plain.estimate[k].t);
        }
    }
    const std::string key = sequence_key(*PluginLibrary::load(test::plugin("tum")), {}, s.out);
    const FrameCache cache(o.frame_cache / key);
    CHECK(cache.complete());

    // Another option or another byte of data is another key.
    CHECK(sequence_key(*PluginLibrary::load(test::plugin("tum")), {{"undistort", "true"}}, s.out) != key);
    std::ofstream(s.out / "rgb.txt", std::ios::app) << "# touched\n";
    CHECK(sequence_key(*PluginLibrary::load(test::plugin("tum")), {}, s.out) != key);

    // A damaged cache file is an error naming it, not silently wrong pixels.
    fs::resize_file(cache.folder() / "frame_000003.vbf", 100);
    CHECK_THROWS_WITH(cache.load(3), Contains("frame_000003.vbf: truncated"));
}
