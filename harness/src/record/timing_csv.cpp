#include "record/timing_csv.hpp"

#include "util/files.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <string_view>

namespace vobench {
namespace fs = std::filesystem;

namespace {

std::vector<std::string_view> split_commas(std::string_view line) {
    std::vector<std::string_view> cells;
    std::size_t start = 0;
    for (std::size_t k = 0; k <= line.size(); ++k)
        if (k == line.size() || line[k] == ',') {
            cells.push_back(line.substr(start, k - start));
            start = k + 1;
        }
    return cells;
}

// A whole cell as a finite number; `empty_ok`: "" gives NaN (a dropped frame's process time).
double number(std::string_view cell, bool empty_ok, const std::string& where) {
    if (cell.empty() && empty_ok) return std::numeric_limits<double>::quiet_NaN();
    const std::string text(cell);
    char* end = nullptr;
    const double v = text.empty() ? 0.0 : std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v))
        throw TimingCsvError(fmt::format("{}: '{}' is not a finite number", where, text.substr(0, 40)));
    return v;
}

}  // namespace

TimingTable read_timing_csv(const fs::path& file, std::uintmax_t max_bytes) {
    std::error_code ec;
    const auto size = fs::file_size(file, ec);
    if (ec) throw TimingCsvError(file.string() + ": cannot read (" + ec.message() + ")");
    if (size > max_bytes)
        throw TimingCsvError(fmt::format("{}: {} bytes, more than the {} a timing file may have", file.string(), size, max_bytes));
    std::string text;
    try {
        text = read_file(file);
    } catch (const std::exception& e) {
        throw TimingCsvError(e.what());
    }
    TimingTable t;
    std::size_t pos = 0, line_no = 0, columns = 0;
    std::vector<std::size_t> stage_column;
    while (pos < text.size()) {
        std::size_t eol = text.find('\n', pos);
        if (eol == std::string::npos) eol = text.size();
        std::string_view line(text.data() + pos, eol - pos);
        pos = eol + 1;
        ++line_no;
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        const auto cells = split_commas(line);
        if (line_no == 1) {
            if (cells.size() < 5 || cells[0] != "index" || cells[1] != "stamp" || cells[2] != "process_ms" || cells[3] != "read_ms" ||
                cells[4] != "status")
                throw TimingCsvError(file.string() + ":1: not a timing.csv header (index,stamp,process_ms,read_ms,status,…)");
            columns = cells.size();
            for (std::size_t c = 5; c < cells.size(); ++c) {
                const std::string_view h = cells[c];
                if (h.size() > 9 && h.substr(0, 6) == "stage_" && h.substr(h.size() - 3) == "_ms") {
                    stage_column.push_back(c);
                    t.stages.push_back({std::string(h.substr(6, h.size() - 9)), {}});
                }
            }
            continue;
        }
        if (line.empty()) continue;
        const std::string where = fmt::format("{}:{}", file.string(), line_no);
        if (cells.size() != columns) throw TimingCsvError(fmt::format("{}: {} columns, the header has {}", where, cells.size(), columns));
        const std::string status(cells[4]);
        if (status != "ok" && status != "lost" && status != "failed" && status != "dropped" && status != "unknown")
            throw TimingCsvError(where + ": status '" + status.substr(0, 20) + "' is none of ok, lost, failed, dropped");
        const bool dropped = status == "dropped";
        t.stamps.push_back(number(cells[1], false, where + " stamp"));
        const double process = number(cells[2], dropped, where + " process_ms");
        const double read = number(cells[3], false, where + " read_ms");
        if (process < 0 || read < 0) throw TimingCsvError(where + ": a negative time");
        t.process_ms.push_back(process);
        t.read_ms.push_back(read);
        t.status.push_back(status);
        for (std::size_t s = 0; s < stage_column.size(); ++s) {
            const std::string_view cell = cells[stage_column[s]];
            const double ms = cell.empty() ? (dropped ? std::numeric_limits<double>::quiet_NaN() : 0.0)
                                           : number(cell, false, where + " stage " + t.stages[s].name);
            if (ms < 0) throw TimingCsvError(where + ": stage " + t.stages[s].name + " has a negative time");
            t.stages[s].ms.push_back(ms);
        }
    }
    if (line_no == 0) throw TimingCsvError(file.string() + ": empty");
    return t;
}

}  // namespace vobench
