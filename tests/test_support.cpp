#include "test_support.hpp"

#include "abi/instances.hpp"

#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <random>

namespace vobench::test {
namespace fs = std::filesystem;

std::optional<fs::path> data_dir(const std::string& sub) {
    const char* env = std::getenv("VOBENCH_DATA_DIR");
    fs::path root = env && *env ? fs::path(env) : fs::path(VOBENCH_TEST_DATA_DIR);
    fs::path p = sub.empty() ? root : root / sub;
    if (!fs::exists(p)) {
        WARN("SKIPPED: real test data " << p << " is absent (set VOBENCH_DATA_DIR)");
        return std::nullopt;
    }
    return p;
}

fs::path fault_plugin(const std::string& name) { return fs::path(VOBENCH_FAULT_PLUGIN_DIR) / (name + ".so"); }
fs::path plugin(const std::string& name) { return fs::path(VOBENCH_PLUGIN_DIR) / ("vobench_" + name + ".so"); }
fs::path cli() { return fs::path(VOBENCH_CLI); }

std::string file_bytes(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

TempDir::TempDir() {
    std::random_device rd;
    path_ = fs::temp_directory_path() / ("vobench-test-" + std::to_string(rd()) + std::to_string(rd()));
    fs::create_directories(path_);
}

TempDir::~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
}

std::string read_all_error(const fs::path& plugin, const fs::path& sequence, const std::map<std::string, std::string>& options) {
    try {
        DatasetInstance d(PluginLibrary::load(plugin));
        d.open(sequence.string(), options);
        for (uint64_t i = 0; i < d.info().frame_count; ++i) d.read(i);
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

int run_command(const std::string& command, std::string& out) {
    out.clear();
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) return -1;
    std::array<char, 4096> buffer;
    std::size_t n;
    while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) out.append(buffer.data(), n);
    const int status = pclose(pipe);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace vobench::test
