#include "util/files.hpp"

#include <unistd.h>
#include <atomic>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace vobench {
namespace fs = std::filesystem;

void write_file_atomic(const fs::path& path, const std::string& text) {
    // pid and a per-process counter: two threads writing one name never share a temporary file.
    static std::atomic<uint64_t> counter{0};
    const fs::path tmp = path.string() + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out) throw std::runtime_error(tmp.string() + ": cannot create file");
        out << text;
        out.flush();
        if (!out) throw std::runtime_error(tmp.string() + ": write error");
    }
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw std::runtime_error(path.string() + ": cannot rename the temporary file into place");
    }
}

std::string json_text(const nlohmann::json& j, int indent) { return j.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace); }

void write_json_atomic(const fs::path& path, const nlohmann::json& j) { write_file_atomic(path, json_text(j) + "\n"); }

nlohmann::json read_json_or_null(const fs::path& path, std::uintmax_t max_bytes) {
    std::error_code ec;
    const auto size = fs::file_size(path, ec);
    if (ec || size > max_bytes || !fs::is_regular_file(path, ec)) return nullptr;
    std::ifstream in(path, std::ios::binary);
    if (!in) return nullptr;
    nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
    return j.is_discarded() ? nlohmann::json(nullptr) : j;
}

std::string read_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path.string() + ": cannot read file");
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

}  // namespace vobench
