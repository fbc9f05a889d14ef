// vobench synth — render a synthetic Kinect v1 / v2 RGB-D sequence with ground truth.
#include "cli/commands.hpp"
#include "synth/sequence_writer.hpp"

#include <spdlog/spdlog.h>

#include <unistd.h>
#include <cstdio>
#include <iostream>

namespace vobench::cli {

void add_synth_command(CLI::App& app, int& exit_code) {
    auto* c = app.add_subcommand("synth", "Render a synthetic Kinect v1/v2 RGB-D sequence with ground truth");
    static synth::SynthOptions o;
    static std::string blur = "on", out;
    c->add_option("--sensor", o.sensor, "kinect1 or kinect2")->check(CLI::IsMember({"kinect1", "kinect2"}))->capture_default_str();
    c->add_option("--trajectory", o.trajectory, "explore1..4, speed1..4, or a trajectory file")->capture_default_str();
    c->add_option("--trajectory-format", o.trajectory_format, "For a file: putk2-raw (marker poses) or tum (camera poses)")
        ->check(CLI::IsMember({"putk2-raw", "tum"}))
        ->capture_default_str();
    c->add_option("--camera-in-marker", o.camera_in_marker, "Camera-in-marker pose file (default: PUT's for the sensor)");
    c->add_option("--frames", o.frames, "Render only the first N poses (0: all)");
    c->add_option("--seed", o.seed, "Seed of the scene and of all noise")->capture_default_str();
    c->add_option("--layout", o.layout, "Output layout: tum, putk2, putk2-tum, icl-tum, icl-povray")
        ->check(CLI::IsMember({"tum", "putk2", "putk2-tum", "icl-tum", "icl-povray"}))
        ->capture_default_str();
    c->add_option("--blur", blur, "Motion blur over the exposure: on or off")->check(CLI::IsMember({"on", "off"}))->capture_default_str();
    c->add_option("--out", out, "Output folder")->required();
    c->callback([&exit_code] {
        o.blur = blur == "on";
        o.out = out;
        const bool tty = isatty(fileno(stderr));
        const auto report = synth::synthesize(o, [tty](uint64_t done, uint64_t total) {
            if (tty)
                std::fprintf(stderr, "\rrendering %llu/%llu", static_cast<unsigned long long>(done),
                             static_cast<unsigned long long>(total));
            else if (done == total || done % 100 == 0)
                spdlog::info("rendered {}/{}", done, total);
        });
        if (tty) std::fprintf(stderr, "\n");
        std::cout << fmt::format("{}: {} frames of {} along {} in {:.2f} s ({:.2f} frames/s)\n", out, report.frames, o.sensor, o.trajectory,
                                 report.seconds, report.fps());
        exit_code = 0;
    });
}

}  // namespace vobench::cli
