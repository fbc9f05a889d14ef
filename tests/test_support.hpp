// test_support.hpp — where the tests find data and plugins, and scratch folders.
#pragma once

#include <vobench/vobench_plugin.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>

namespace vobench::test {

// $VOBENCH_DATA_DIR, else the configured ../shared/data; nullopt (with a WARN) when absent.
std::optional<std::filesystem::path> data_dir(const std::string& sub = "");

std::filesystem::path fault_plugin(const std::string& name);  // build/tests/fault_plugins/<name>.so
std::filesystem::path plugin(const std::string& name);        // build/plugins/vobench_<name>.so
std::filesystem::path cli();                                  // build/bin/vobench

// The bytes of a file ("" when it cannot be read), to compare files whole.
std::string file_bytes(const std::filesystem::path& file);

// A fresh, empty folder under the system temp dir, removed at destruction.
class TempDir {
public:
    TempDir();
    ~TempDir();
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

// A 1×1 RGB-D frame that owns its pixels, for plugins that do not look at them (test plugins).
struct TinyFrame {
    uint16_t depth = 0;
    uint8_t rgb[3] = {0, 0, 0};
    vobench_image color{sizeof(vobench_image), 1, 1, 3, VOBENCH_PIXEL_RGB8, rgb};
    vobench_image depth_image{sizeof(vobench_image), 1, 1, 2, VOBENCH_PIXEL_DEPTH_U16, &depth};
    vobench_frame frame{sizeof(vobench_frame), 0, 0.0, 0.0, &color, &depth_image, 0.001};
    TinyFrame(const TinyFrame&) = delete;  // the frame points into this object
    TinyFrame() = default;
};

// A 1×1 pinhole camera to go with it.
inline const vobench_camera kTinyCamera{sizeof(vobench_camera), 1, 1, 1.0, 1.0, 0.0, 0.0, VOBENCH_DISTORTION_NONE, 0, {0}};

// Opens `sequence` with the reader at `plugin` and reads every frame; the error message, or "".
std::string read_all_error(const std::filesystem::path& plugin, const std::filesystem::path& sequence,
                           const std::map<std::string, std::string>& options = {});

// Runs a shell command, returns its exit status and stdout.
int run_command(const std::string& command, std::string& out);

}  // namespace vobench::test

// Skips the rest of a test case, with a message in the output, when real data is absent.
#define VOBENCH_REQUIRE_DATA(var, sub)                     \
    const auto var##_opt = ::vobench::test::data_dir(sub); \
    if (!var##_opt) return;                                \
    const std::filesystem::path var = *var##_opt
