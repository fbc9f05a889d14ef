// frames.jsonl: what the child writes comes back exactly; anything plugin code could have done to the
// file (cut it, forge a line, write garbage or non-numbers) ends the stream at that line, named.
#include "record/frame_stream.hpp"
#include "util/files.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

using namespace vobench;
namespace fs = std::filesystem;

namespace {

fs::path stream_file(const std::string& text) {
    const fs::path f = fs::temp_directory_path() / ("vobench-frames-" + std::to_string(std::hash<std::string>{}(text)) + ".jsonl");
    std::ofstream(f, std::ios::binary) << text;
    return f;
}

std::string frames(int n) {
    std::string text;
    for (int i = 0; i < n; ++i) {
        FrameRecord f;
        f.index = static_cast<uint64_t>(i);
        f.stamp = 1.0 + 0.1 * i;
        f.process_ns = 1000 + i;
        f.stages = {{"tracking", 500}};
        f.counters = {{"inliers", 42.5}};
        metrics::StampedPose p;
        p.t = f.stamp;
        p.p = {0.01 * i, 0, 0};
        text += encode_frame(f, p);
    }
    return text;
}

}  // namespace

TEST_CASE("frames come back as written", "[record][frames]") {
    const FrameStream s = decode_frames(stream_file(frames(5)));
    CHECK(s.error.empty());
    CHECK_FALSE(s.truncated_tail);
    REQUIRE(s.frames.size() == 5);
    CHECK(s.poses[4].p.x() == 0.04);
    CHECK(s.frames[3].stamp == 1.0 + 0.1 * 3);
    CHECK(s.frames[2].counters.at(0).second == 42.5);
    CHECK(s.frames[2].stages.at(0).second == 500);
}

TEST_CASE("a last line cut short by a crash is dropped, not an error", "[record][frames]") {
    const std::string text = frames(4);
    const FrameStream s = decode_frames(stream_file(text.substr(0, text.size() - 20)));
    CHECK(s.frames.size() == 3);
    CHECK(s.truncated_tail);
    CHECK(s.error.empty());
}

TEST_CASE("a forged, garbled or non-numeric line ends the stream with its line number", "[record][frames]") {
    const std::string good = frames(3);
    const std::vector<std::pair<std::string, std::string>> cases = {
        {R"({"i":0,"t":0,"ns":1,"r":0,"s":0,"p":[0,0,0,0,0,0,1]})", "frame index is not 3"},
        {"garbage", "not JSON"},
        {R"({"i":3,"t":null,"ns":1,"r":0,"s":0,"p":[0,0,0,0,0,0,1]})", "the stamp is not a finite number"},
        {R"({"i":3,"t":1,"ns":1,"r":0,"s":0,"p":[0,0,0,0,0,1]})", "the pose is not 7 numbers"},
        {R"({"i":3,"t":1,"ns":1,"r":0,"s":0,"p":[0,0,"x",0,0,0,1]})", "the pose is not finite"},
        {R"({"i":3,"t":1,"ns":1,"r":0,"s":9,"p":[0,0,0,0,0,0,1]})", "unknown tracking status"},
        {R"({"i":3,"t":1,"ns":1,"r":0,"s":0,"p":[0,0,0,0,0,0,1],"c":{"x":null}})", "counter 'x' is not a finite number"},
        {R"({"i":3,"t":1,"ns":"1","r":0,"s":0,"p":[0,0,0,0,0,0,1]})", "times are not integers"},
        {R"([1,2,3])", "not a JSON object"},
    };
    for (const auto& [line, why] : cases) {
        const FrameStream s = decode_frames(stream_file(good + line + "\n" + frames(5).substr(good.size())));
        INFO(line);
        CHECK(s.frames.size() == 3);
        CHECK(s.error == "frames.jsonl line 4: " + why);
    }
}

TEST_CASE("a missing or empty stream has no frames and no error", "[record][frames]") {
    CHECK(decode_frames("/nonexistent/frames.jsonl").frames.empty());
    CHECK(decode_frames(stream_file("")).error.empty());
}

TEST_CASE("dropped frames (real time, filters) come back as dropped, without a pose, and a forged one ends the stream",
          "[record][frames]") {
    FrameRecord kept, dropped;
    kept.index = 0;
    kept.stamp = 1.0;
    kept.process_ns = 5000;
    kept.cpu_ns = 4000;
    dropped.index = 1;
    dropped.stamp = 1.033;
    dropped.read_ns = 7;
    dropped.dropped = true;
    metrics::StampedPose p;
    p.t = 1.0;
    const std::string text = encode_frame(kept, p) + encode_frame(dropped, p) +
                             encode_frame(
                                 [&] {
                                     FrameRecord f = kept;
                                     f.index = 2;
                                     f.stamp = 1.066;
                                     return f;
                                 }(),
                                 p);
    const FrameStream s = decode_frames(stream_file(text));
    REQUIRE(s.error.empty());
    REQUIRE(s.frames.size() == 3);
    CHECK(s.dropped_frames == 1);
    CHECK(s.poses.size() == 2);  // one per frame the plugin saw
    CHECK(s.frames[1].dropped);
    CHECK(s.frames[1].read_ns == 7);
    CHECK(s.frames[0].cpu_ns == 4000);
    // A dropped line with a pose or anything else added is not one the harness writes.
    const FrameStream forged =
        decode_frames(stream_file(encode_frame(kept, p) + "{\"i\":1,\"t\":1.0,\"r\":0,\"d\":1,\"p\":[0,0,0,0,0,0,1]}\n"));
    CHECK(forged.frames.size() == 1);
    CHECK(forged.error == "frames.jsonl line 2: a malformed dropped frame");
}
