// files.hpp — the file helpers every layer uses: atomic writes (a reader sees the old file or the new
// one, never half of one) and JSON that never throws on what a plugin or a file put into it.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <string>

namespace vobench {

// Writes to <path>.tmp.<pid>.<n>, then renames it into place. Throws std::runtime_error naming the file.
void write_file_atomic(const std::filesystem::path& path, const std::string& text);

// JSON text in which invalid UTF-8 (a plugin's version string, a reader's sequence name) is replaced
// by U+FFFD instead of throwing. Non-finite numbers come out as null, as nlohmann writes them.
std::string json_text(const nlohmann::json& j, int indent = 2);

// json_text(j) + "\n", written atomically.
void write_json_atomic(const std::filesystem::path& path, const nlohmann::json& j);

// The parsed file, or null when it is missing, larger than `max_bytes`, or not JSON. Never throws.
nlohmann::json read_json_or_null(const std::filesystem::path& path, std::uintmax_t max_bytes = std::uintmax_t{256} << 20);

// The whole file as bytes; throws std::runtime_error naming it when it cannot be read.
std::string read_file(const std::filesystem::path& path);

}  // namespace vobench
