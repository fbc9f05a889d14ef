// hash.hpp — a fast 64-bit content hash (multiply–xorshift, as in MurmurHash's finaliser), used for
// cache keys, cell ids and file fingerprints. Not cryptographic: it names things, it does not sign them.
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>

namespace vobench {

class Hasher {
public:
    void add(const void* data, std::size_t size) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (; size >= 8; p += 8, size -= 8) {
            uint64_t w;
            std::memcpy(&w, p, 8);
            mix(w);
        }
        uint64_t tail = 0;
        std::memcpy(&tail, p, size);
        mix(tail ^ (static_cast<uint64_t>(size) << 56));
    }
    void add(const std::string& s) { add(s.data(), s.size()); }
    uint64_t value() const { return h_; }
    std::string hex() const;  // 16 lower-case hex digits

private:
    void mix(uint64_t w) {
        w *= 0x87c37b91114253d5ull;
        w ^= w >> 31;
        h_ = (h_ ^ w) * 0x9e3779b97f4a7c15ull;
        h_ ^= h_ >> 29;
    }
    uint64_t h_ = 0x6a09e667f3bcc908ull;
};

// Every byte of one file; throws std::runtime_error naming the file when it cannot be read.
void hash_file(Hasher& h, const std::filesystem::path& file);

// Every regular file under `folder` (relative names and contents, in sorted order).
void hash_tree(Hasher& h, const std::filesystem::path& folder);

}  // namespace vobench
