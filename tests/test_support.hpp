// test_support.hpp — where the tests find data and plugins, and scratch folders.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace vobench::test {

// $VOBENCH_DATA_DIR, else the configured ../shared/data; nullopt (with a WARN) when absent.
std::optional<std::filesystem::path> data_dir(const std::string& sub = "");

std::filesystem::path fault_plugin(const std::string& name);  // build/tests/fault_plugins/<name>.so
std::filesystem::path plugin(const std::string& name);         // build/plugins/vobench_<name>.so
std::filesystem::path cli();                                    // build/bin/vobench

// A fresh, empty folder under the system temp dir, removed at destruction.
class TempDir {
public:
    TempDir();
    ~TempDir();
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

// Runs a shell command, returns its exit status and stdout.
int run_command(const std::string& command, std::string& out);

}  // namespace vobench::test

// Skips the rest of a test case, with a message in the output, when real data is absent.
#define VOBENCH_REQUIRE_DATA(var, sub)                                   \
    const auto var##_opt = ::vobench::test::data_dir(sub);               \
    if (!var##_opt) return;                                              \
    const std::filesystem::path var = *var##_opt
