#include "metrics/trajectory_io.hpp"
#include "util/escape.hpp"
#include "util/files.hpp"

#include <fmt/format.h>

#include <unistd.h>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string_view>

namespace vobench::metrics {
namespace fs = std::filesystem;

TrajectoryFormat parse_trajectory_format(const std::string& name) {
    if (name == "tum") return TrajectoryFormat::Tum;
    if (name == "kitti") return TrajectoryFormat::Kitti;
    if (name == "euroc") return TrajectoryFormat::Euroc;
    if (name == "putk2-raw") return TrajectoryFormat::Putk2Raw;
    throw std::invalid_argument("unknown trajectory format '" + name + "' (tum, kitti, euroc or putk2-raw)");
}

const char* trajectory_format_name(TrajectoryFormat format) {
    switch (format) {
        case TrajectoryFormat::Tum: return "tum";
        case TrajectoryFormat::Kitti: return "kitti";
        case TrajectoryFormat::Euroc: return "euroc";
        case TrajectoryFormat::Putk2Raw: return "putk2-raw";
    }
    return "?";
}

namespace {

struct Line {
    std::size_t number;
    std::vector<std::string_view> fields;  // views into the text split_lines() was given: it must outlive them
};

// Splits text into non-comment lines of fields separated by any of `separators`. One pass over the
// text with a table of separator bytes (trajectory files reach 10^5–10^6 lines).
std::vector<Line> split_lines(const std::string& text, const char* separators) {
    bool is_separator[256] = {};
    for (const char* c = separators; *c; ++c) is_separator[static_cast<unsigned char>(*c)] = true;
    std::vector<Line> lines;
    std::size_t number = 0, begin = 0;
    while (begin < text.size()) {
        std::size_t end = text.find('\n', begin);
        if (end == std::string::npos) end = text.size();
        ++number;
        std::string_view line(text.data() + begin, end - begin);
        begin = end + 1;
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        const std::size_t first = line.find_first_not_of(" \t");
        if (first == std::string_view::npos || line[first] == '#') continue;
        Line out{number, {}};
        std::size_t pos = 0;
        while (pos < line.size()) {
            while (pos < line.size() && is_separator[static_cast<unsigned char>(line[pos])]) ++pos;
            if (pos == line.size()) break;
            std::size_t stop = pos;
            while (stop < line.size() && !is_separator[static_cast<unsigned char>(line[stop])]) ++stop;
            out.fields.emplace_back(line.substr(pos, stop - pos));
            pos = stop;
        }
        if (!out.fields.empty()) lines.push_back(std::move(out));
    }
    return lines;
}

// strtod's value and acceptance, faster: std::from_chars first (correctly rounded, as glibc's strtod,
// so the same double), strtod for what it does not take whole ("+1", hex, out of range).
double parse_double(std::string_view f, bool& whole) {
    double v = 0;
    const auto [ptr, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
    if (ec == std::errc() && ptr == f.data() + f.size()) {
        whole = true;
        return v;
    }
    const std::string text(f);
    char* end = nullptr;
    v = std::strtod(text.c_str(), &end);
    whole = end == text.c_str() + text.size();
    return v;
}

class Reader {
public:
    Reader(std::string name, const ReadOptions& options) : name_(std::move(name)), options_(options) {}

    [[noreturn]] void fail(std::size_t line, const std::string& message) const {
        throw TrajectoryError(fmt::format("{}:{}: {}", name_, line, message));
    }
    void warn(std::size_t line, const char* code, const std::string& message) {
        // One warning per code, with the count of further occurrences added at the end.
        for (auto& w : warned_)
            if (w.code == code) {
                ++w.more;
                return;
            }
        warned_.push_back({code, fmt::format("{}:{}: [{}] {}", name_, line, code, message), 0});
    }
    std::vector<std::string> warnings() const {
        std::vector<std::string> out;
        for (const auto& w : warned_) out.push_back(w.more ? fmt::format("{} (and {} more lines)", w.text, w.more) : w.text);
        return out;
    }

    // Parses fields[0..count) as numbers; non-numbers are errors, non-finite values are errors (or, in
    // tum-scripts mode, make the caller skip the line: returns false).
    bool numbers(const Line& line, std::size_t count, std::vector<double>& out) {
        if (line.fields.size() < count) fail(line.number, fmt::format("expected {} values, found {}", count, line.fields.size()));
        if (line.fields.size() > count)
            warn(line.number, "extra-columns", "values past the first " + std::to_string(count) + " are ignored");
        out.resize(count);
        for (std::size_t i = 0; i < count; ++i) {
            const std::string_view f = line.fields[i];
            bool whole = false;
            out[i] = parse_double(f, whole);
            if (!whole) fail(line.number, fmt::format("value {} ('{}') is not a number", i + 1, f));
            if (!std::isfinite(out[i])) {
                if (options_.tum_scripts) {
                    warn(line.number, "non-finite", "line has NaN or infinite values, skipped (as evaluate_rpe.py)");
                    return false;
                }
                fail(line.number, fmt::format("value {} is not finite ('{}')", i + 1, f));
            }
        }
        return true;
    }

    // Checks and normalises a quaternion; false when the line is to be skipped (tum-scripts mode).
    bool quaternion(std::size_t line, Eigen::Quaterniond& q) {
        const double norm = q.norm();
        if (norm < 1e-12) {
            if (options_.tum_scripts) {
                warn(line, "zero-quaternion", "zero quaternion, line skipped (as evaluate_rpe.py)");
                return false;
            }
            fail(line, "zero quaternion");
        }
        if (std::abs(norm - 1.0) > options_.quaternion_tolerance)
            warn(line, "non-unit-quaternion", fmt::format("quaternion norm {} is not 1; normalised", norm));
        // Leave unit quaternions bit for bit as written (a written trajectory reads back exactly).
        if (std::abs(norm - 1.0) > 1e-12) q.coeffs() /= norm;
        return true;
    }

    void add(std::size_t line, StampedPose pose) {
        poses_.push_back(std::move(pose));
        lines_.push_back(line);
    }

    ReadResult finish() {
        if (poses_.empty()) throw TrajectoryError(name_ + ": no poses");
        // Sort (stable) by stamp, remembering line numbers for messages.
        std::vector<std::size_t> order(poses_.size());
        for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
        bool sorted = true;
        for (std::size_t i = 1; i < poses_.size(); ++i)
            if (poses_[i].t < poses_[i - 1].t) {
                if (sorted) warn(lines_[i], "unsorted-stamps", "stamps are not in increasing order; sorted");
                sorted = false;
            }
        if (!sorted) std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return poses_[a].t < poses_[b].t; });
        ReadResult result;
        result.poses.reserve(poses_.size());
        for (std::size_t k = 0; k < order.size(); ++k) {
            const StampedPose& p = poses_[order[k]];
            if (!result.poses.empty() && result.poses.back().t == p.t) {
                // Real TUM ground truth has these (fr2/desk line 10863): keep the later line, as the
                // TUM scripts' dict does, and say so.
                warn(lines_[order[k]], "duplicate-stamp",
                     fmt::format("duplicate stamp {}; the later line wins (as the TUM scripts)", format_stamp(p.t)));
                result.poses.back() = p;
                continue;
            }
            result.poses.push_back(p);
        }
        result.warnings = warnings();
        return result;
    }

    static std::string format_stamp(double t) { return fmt::format("{}", t); }
    const ReadOptions& options() const { return options_; }
    std::vector<StampedPose>& poses() { return poses_; }

private:
    struct Warned {
        std::string code, text;
        std::size_t more;
    };
    std::string name_;
    ReadOptions options_;
    std::vector<StampedPose> poses_;
    std::vector<std::size_t> lines_;
    std::vector<Warned> warned_;
};

void parse_tum(const std::string& text, Reader& r) {
    std::vector<double> v;
    bool nanoseconds_warned = false;
    for (const Line& line : split_lines(text, " \t,")) {
        if (!r.numbers(line, 8, v)) continue;
        StampedPose p;
        p.t = v[0];
        p.p = {v[1], v[2], v[3]};
        p.q = Eigen::Quaterniond(v[7], v[4], v[5], v[6]);
        if (!r.quaternion(line.number, p.q)) continue;
        if (p.t > 1e13 && !r.options().tum_scripts) {
            // Seconds since 1970 are ~1.7e9 now; 1e13 s is 300,000 years: these are nanoseconds.
            if (!nanoseconds_warned) r.warn(line.number, "stamps-in-nanoseconds", "stamps look like nanoseconds; divided by 1e9");
            nanoseconds_warned = true;
            p.t *= 1e-9;
        }
        r.add(line.number, p);
    }
}

void parse_kitti(const std::string& text, Reader& r) {
    std::vector<double> v;
    std::size_t index = 0;
    for (const Line& line : split_lines(text, " \t,")) {
        r.numbers(line, 12, v);
        Eigen::Matrix3d R;
        R << v[0], v[1], v[2], v[4], v[5], v[6], v[8], v[9], v[10];
        const double orthogonality = (R.transpose() * R - Eigen::Matrix3d::Identity()).norm();
        if (orthogonality > 1e-2 || R.determinant() < 0)
            r.fail(line.number, fmt::format("the 3×3 part is not a rotation (‖RᵀR − I‖ = {})", orthogonality));
        StampedPose p;
        p.t = static_cast<double>(index++);
        p.p = {v[3], v[7], v[11]};
        p.q = Eigen::Quaterniond(R);
        r.quaternion(line.number, p.q);
        r.add(line.number, p);
    }
}

void parse_euroc(const std::string& text, Reader& r) {
    std::vector<double> v;
    bool first = true;
    for (const Line& line : split_lines(text, ",")) {
        // A header without '#': skip it if its first field is not a number.
        if (first) {
            first = false;
            const std::string first_field(line.fields[0]);
            char* end = nullptr;
            std::strtod(first_field.c_str(), &end);
            if (end == first_field.c_str()) continue;
        }
        Line trimmed = line;
        for (std::string_view& f : trimmed.fields) {
            const auto b = f.find_first_not_of(" \t"), e = f.find_last_not_of(" \t");
            f = b == std::string_view::npos ? std::string_view() : f.substr(b, e - b + 1);
        }
        if (trimmed.fields.size() > 8) trimmed.fields.resize(8);  // velocities and biases follow
        r.numbers(trimmed, 8, v);
        StampedPose p;
        p.t = v[0] * 1e-9;  // EuRoC stamps are nanoseconds
        p.p = {v[1], v[2], v[3]};
        p.q = Eigen::Quaterniond(v[4], v[5], v[6], v[7]);
        r.quaternion(line.number, p.q);
        r.add(line.number, p);
    }
}

void parse_putk2_raw(const std::string& text, Reader& r) {
    std::vector<double> v;
    for (const Line& line : split_lines(text, "; \t")) {
        r.numbers(line, 7, v);
        if (v[0] != std::floor(v[0]) || v[0] < 0 || v[0] > 9007199254740992.0)
            r.fail(line.number, "the frame id is not an integer in [0, 2^53]");
        const Eigen::Vector3d rodrigues(v[1], v[2], v[3]);
        const double angle = rodrigues.norm();
        Eigen::Isometry3d M = Eigen::Isometry3d::Identity();
        if (angle > 0) M.linear() = Eigen::AngleAxisd(angle, rodrigues / angle).toRotationMatrix();
        M.translation() = Eigen::Vector3d(v[4], v[5], v[6]);
        // Kraft et al. 2016, eq. 10: camera pose = marker pose · camera-in-marker.
        const Eigen::Isometry3d T = r.options().camera_in_marker ? M * *r.options().camera_in_marker : M;
        r.add(line.number, StampedPose::from_isometry(v[0], T));
    }
}

std::string read_text(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw TrajectoryError(path.string() + ": cannot open file");
    std::ostringstream ss;
    ss << in.rdbuf();
    if (in.bad()) throw TrajectoryError(path.string() + ": read error");
    return ss.str();
}

}  // namespace

ReadResult parse_trajectory(const std::string& text, const std::string& name, const ReadOptions& options) {
    Reader reader(name, options);
    switch (options.format) {
        case TrajectoryFormat::Tum: parse_tum(text, reader); break;
        case TrajectoryFormat::Kitti: parse_kitti(text, reader); break;
        case TrajectoryFormat::Euroc: parse_euroc(text, reader); break;
        case TrajectoryFormat::Putk2Raw: parse_putk2_raw(text, reader); break;
    }
    return reader.finish();
}

ReadResult read_trajectory(const fs::path& path, const ReadOptions& options) {
    return parse_trajectory(read_text(path), path.string(), options);
}

Eigen::Isometry3d read_camera_in_marker(const fs::path& path) {
    ReadOptions options;
    Reader r(path.string(), options);
    const std::string text = read_text(path);  // named: the lines view into it
    const std::vector<Line> lines = split_lines(text, " \t,");
    if (lines.empty()) throw TrajectoryError(path.string() + ": no pose (expected `x y z qw qx qy qz`)");
    std::vector<double> v;
    r.numbers(lines.front(), 7, v);
    Eigen::Quaterniond q(v[3], v[4], v[5], v[6]);
    r.quaternion(lines.front().number, q);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = q.toRotationMatrix();
    T.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
    return T;
}

std::string format_tum_line(const StampedPose& p) {
    // fmt's "{}" prints the shortest text that reads back to the same double: full precision.
    return fmt::format("{} {} {} {} {} {} {} {}", p.t, p.p.x(), p.p.y(), p.p.z(), p.q.x(), p.q.y(), p.q.z(), p.q.w());
}

void write_tum(const fs::path& path, const Trajectory& poses, const std::string& header_comment) {
    std::string text;
    if (!header_comment.empty()) text += "# " + clean_text(header_comment) + "\n";
    text += "# timestamp tx ty tz qx qy qz qw\n";
    for (const StampedPose& p : poses) {
        text += format_tum_line(p);
        text += '\n';
    }
    write_file_atomic(path, text);
}

}  // namespace vobench::metrics
