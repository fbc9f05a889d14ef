// tum_lists.hpp — the TUM RGB-D list files (rgb.txt, depth.txt): `timestamp path` lines, '#' comments.
#pragma once

#include <string>
#include <vector>

namespace vobench::tum {

struct ListEntry {
    double stamp;
    std::string path;  // relative to the sequence folder
};

// Parses a list file's text; `name` is used in messages ("rgb.txt:12: ..."). Throws std::runtime_error
// on a malformed line, an unsorted or duplicate stamp, or an empty list.
std::vector<ListEntry> parse_list(const std::string& text, const std::string& name);

}  // namespace vobench::tum
