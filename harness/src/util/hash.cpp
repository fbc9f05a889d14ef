#include "util/hash.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <stdexcept>
#include <vector>

namespace vobench {
namespace fs = std::filesystem;

std::string Hasher::hex() const { return fmt::format("{:016x}", h_); }

void hash_file(Hasher& h, const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw std::runtime_error(file.string() + ": cannot open for hashing");
    std::vector<char> buffer(1 << 20);
    while (in) {
        in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
        h.add(buffer.data(), static_cast<std::size_t>(in.gcount()));
    }
}

void hash_tree(Hasher& h, const fs::path& folder) {
    std::vector<fs::path> files;
    for (const auto& entry : fs::recursive_directory_iterator(folder))
        if (entry.is_regular_file()) files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    for (const fs::path& f : files) {
        h.add(fs::relative(f, folder).generic_string());
        hash_file(h, f);
    }
}

}  // namespace vobench
