// text_lines.hpp — the data lines of a text file, as every dataset parser here reads them: numbered
// from 1, a trailing '\r' removed (files written on Windows), blank lines and '#' comments skipped.
#pragma once

#include <cstddef>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace vobench::text {

inline std::vector<std::pair<std::size_t, std::string>> data_lines(const std::string& text) {
    std::vector<std::pair<std::size_t, std::string>> out;
    std::istringstream in(text);
    std::string line;
    for (std::size_t number = 1; std::getline(in, line); ++number) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        const auto first = line.find_first_not_of(" \t");
        if (first == std::string::npos || line[first] == '#') continue;
        out.emplace_back(number, line);
    }
    return out;
}

}  // namespace vobench::text
