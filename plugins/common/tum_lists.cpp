#include "tum_lists.hpp"

#include "text_lines.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace vobench::tum {

std::vector<ListEntry> parse_list(const std::string& text, const std::string& name) {
    std::vector<ListEntry> entries;
    for (const auto& [number, line] : vobench::text::data_lines(text)) {
        std::istringstream fields(line);
        std::string stamp_text, path;
        fields >> stamp_text >> path;
        const std::string where = name + ":" + std::to_string(number) + ": ";
        char* end = nullptr;
        const double stamp = std::strtod(stamp_text.c_str(), &end);
        if (stamp_text.empty() || end != stamp_text.c_str() + stamp_text.size() || !std::isfinite(stamp))
            throw std::runtime_error(where + "expected `timestamp path`, the stamp '" + stamp_text + "' is not a number");
        if (path.empty()) throw std::runtime_error(where + "expected `timestamp path`, the path is missing");
        if (!entries.empty() && stamp <= entries.back().stamp)
            throw std::runtime_error(where + "stamp " + stamp_text + " is not after the previous line's");
        entries.push_back({stamp, path});
    }
    if (entries.empty()) throw std::runtime_error(name + ": no entries (empty sequence)");
    return entries;
}

}  // namespace vobench::tum
