#include "putk2_files.hpp"

#include "text_lines.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace vobench::putk2 {
namespace {

std::vector<std::string> split(const std::string& line, const char* separators) {
    std::vector<std::string> fields;
    std::size_t pos = 0;
    while ((pos = line.find_first_not_of(separators, pos)) != std::string::npos) {
        const std::size_t end = line.find_first_of(separators, pos);
        fields.push_back(line.substr(pos, end == std::string::npos ? std::string::npos : end - pos));
        pos = end;
    }
    return fields;
}

double number(const std::string& field, const std::string& where) {
    char* end = nullptr;
    const double v = std::strtod(field.c_str(), &end);
    if (field.empty() || end != field.c_str() + field.size() || !std::isfinite(v))
        throw std::runtime_error(where + "'" + field + "' is not a number");
    return v;
}

}  // namespace

std::vector<CameraCalibration> parse_cam_data(const std::string& text, const std::string& name) {
    std::vector<CameraCalibration> cameras;
    for (const auto& [n, line] : vobench::text::data_lines(text)) {
        const std::string where = name + ":" + std::to_string(n) + ": ";
        const auto f = split(line, ", \t");
        if (f.size() != 13)
            throw std::runtime_error(where + "expected `id, fx, fy, cx, cy, k1, k2, p1, p2, k3, k4, k5, k6` (13 values), found " +
                                     std::to_string(f.size()));
        CameraCalibration c;
        c.id = f[0];
        c.fx = number(f[1], where);
        c.fy = number(f[2], where);
        c.cx = number(f[3], where);
        c.cy = number(f[4], where);
        for (int i = 0; i < 8; ++i) c.distortion[static_cast<std::size_t>(i)] = number(f[static_cast<std::size_t>(5 + i)], where);
        if (!(c.fx > 0) || !(c.fy > 0)) throw std::runtime_error(where + "focal lengths must be positive");
        cameras.push_back(c);
    }
    if (cameras.empty()) throw std::runtime_error(name + ": no camera lines");
    return cameras;
}

DepthCamera parse_depth_camera(const std::string& text, const std::string& name) {
    const auto lines = vobench::text::data_lines(text);
    if (lines.size() != 2) throw std::runtime_error(name + ": expected two lines, `fx fy cx cy` and `x y z qw qx qy qz`");
    DepthCamera d;
    const std::string w1 = name + ":" + std::to_string(lines[0].first) + ": ", w2 = name + ":" + std::to_string(lines[1].first) + ": ";
    const auto k = split(lines[0].second, " \t,");
    if (k.size() != 4) throw std::runtime_error(w1 + "expected `fx fy cx cy`");
    d.fx = number(k[0], w1);
    d.fy = number(k[1], w1);
    d.cx = number(k[2], w1);
    d.cy = number(k[3], w1);
    const auto p = split(lines[1].second, " \t,");
    if (p.size() != 7) throw std::runtime_error(w2 + "expected `x y z qw qx qy qz`");
    double v[7];
    for (int i = 0; i < 7; ++i) v[i] = number(p[static_cast<std::size_t>(i)], w2);
    const Eigen::Quaterniond q(v[3], v[4], v[5], v[6]);
    if (std::abs(q.norm() - 1.0) > 1e-3) throw std::runtime_error(w2 + "the quaternion is not of unit length");
    d.in_color.linear() = q.normalized().toRotationMatrix();
    d.in_color.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
    return d;
}

std::vector<MatchedFrame> parse_matched(const std::string& text, const std::string& name) {
    std::vector<MatchedFrame> frames;
    for (const auto& [n, line] : vobench::text::data_lines(text)) {
        const std::string where = name + ":" + std::to_string(n) + ": ";
        const auto f = split(line, " \t");
        if (f.size() != 3) throw std::runtime_error(where + "expected `frame rgb_file depth_file`");
        const double id = number(f[0], where);
        // Beyond 2^53 a double no longer holds every integer (and a long long may not hold it at all).
        if (id < 0 || id != std::floor(id) || id > 9007199254740992.0)
            throw std::runtime_error(where + "the frame number is not an integer in [0, 2^53]");
        if (!frames.empty() && id <= static_cast<double>(frames.back().id)) throw std::runtime_error(where + "frame numbers must increase");
        frames.push_back({static_cast<long long>(id), f[1], f[2]});
    }
    if (frames.empty()) throw std::runtime_error(name + ": no frames (empty sequence)");
    return frames;
}

}  // namespace vobench::putk2
