#include "icl_files.hpp"

#include "text_lines.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace vobench::icl {

std::vector<Association> parse_associations(const std::string& text, const std::string& name) {
    std::vector<Association> out;
    for (const auto& [n, line] : vobench::text::data_lines(text)) {
        std::istringstream fields(line);
        Association a;
        std::string extra;
        if (!(fields >> a.t_depth >> a.depth >> a.t_rgb >> a.rgb) || (fields >> extra) || !std::isfinite(a.t_rgb) ||
            !std::isfinite(a.t_depth))
            throw std::runtime_error(name + ":" + std::to_string(n) + ": expected `t_depth depth_file t_rgb rgb_file`");
        if (!out.empty() && !(a.t_rgb > out.back().t_rgb))
            throw std::runtime_error(name + ":" + std::to_string(n) + ": stamps must increase");
        out.push_back(a);
    }
    if (out.empty()) throw std::runtime_error(name + ": no frames (empty sequence)");
    return out;
}

std::vector<double> parse_camera(const std::string& text, const std::string& name) {
    for (const auto& [n, line] : vobench::text::data_lines(text)) {
        std::istringstream fields(line);
        std::vector<double> k;
        double v;
        while (k.size() < 12 && fields >> v) k.push_back(v);
        bool finite = true;
        for (double x : k) finite = finite && std::isfinite(x);
        if (k.size() < 4 || !finite || !(fields >> std::ws).eof())
            throw std::runtime_error(name + ":" + std::to_string(n) + ": expected `fx fy cx cy` and up to 8 distortion coefficients");
        return k;
    }
    throw std::runtime_error(name + ": no intrinsics line");
}

std::map<std::string, Eigen::Vector3d> parse_camera_vectors(const std::string& text, const std::string& name) {
    std::map<std::string, Eigen::Vector3d> vectors;
    std::istringstream in(text);
    std::string line;
    for (std::size_t n = 1; std::getline(in, line); ++n) {
        const auto eq = line.find('='), open = line.find('['), close = line.find(']');
        if (eq == std::string::npos) continue;
        std::string key = line.substr(0, eq);
        key.erase(key.find_last_not_of(" \t") + 1);
        key.erase(0, key.find_first_not_of(" \t"));
        if (open == std::string::npos || close == std::string::npos || close < open) continue;  // a scalar
        std::istringstream values(line.substr(open + 1, close - open - 1));
        Eigen::Vector3d v;
        char c1 = 0, c2 = 0;
        if (!(values >> v.x() >> c1 >> v.y() >> c2 >> v.z()) || c1 != ',' || c2 != ',' || !v.allFinite())
            throw std::runtime_error(name + ":" + std::to_string(n) + ": expected `" + key + " = [x, y, z]';`");
        vectors[key] = v;
    }
    return vectors;
}

std::vector<float> parse_ray_depth(const std::string& text, const std::string& name, std::size_t count) {
    std::vector<float> out;
    out.reserve(count);
    const char* p = text.c_str();
    for (std::size_t i = 0; i < count; ++i) {
        char* end = nullptr;
        const double d = std::strtod(p, &end);
        if (end == p)
            throw std::runtime_error(name + ": value " + std::to_string(i + 1) + " of " + std::to_string(count) +
                                     " is missing or not a number");
        if (!std::isfinite(d) || d < 0)
            throw std::runtime_error(name + ": value " + std::to_string(i + 1) + " of " + std::to_string(count) +
                                     " is not a non-negative finite number");
        out.push_back(static_cast<float>(d));
        p = end;
    }
    while (*p == ' ' || *p == '\n' || *p == '\r' || *p == '\t') ++p;
    if (*p) throw std::runtime_error(name + ": more than " + std::to_string(count) + " values");
    return out;
}

std::vector<Eigen::Isometry3d> parse_sim(const std::string& text, const std::string& name) {
    std::istringstream in(text);
    std::vector<double> v;
    std::string token;
    while (in >> token) {
        char* end = nullptr;
        v.push_back(std::strtod(token.c_str(), &end));
        if (*end != '\0' || !std::isfinite(v.back()))
            throw std::runtime_error(name + ": value " + std::to_string(v.size()) + " ('" + token + "') is not a number");
    }
    if (v.size() % 12 != 0) throw std::runtime_error(name + ": " + std::to_string(v.size()) + " values, not 12 per frame");
    std::vector<Eigen::Isometry3d> poses;
    for (std::size_t f = 0; f * 12 < v.size(); ++f) {
        Eigen::Matrix3d R;
        R << v[f * 12 + 0], v[f * 12 + 1], v[f * 12 + 2], v[f * 12 + 4], v[f * 12 + 5], v[f * 12 + 6], v[f * 12 + 8], v[f * 12 + 9],
            v[f * 12 + 10];
        if ((R.transpose() * R - Eigen::Matrix3d::Identity()).norm() > 1e-3 || R.determinant() < 0)
            throw std::runtime_error(name + ": frame " + std::to_string(f) + " is not a rotation");
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.linear() = Eigen::Quaterniond(R).normalized().toRotationMatrix();
        T.translation() = Eigen::Vector3d(v[f * 12 + 3], v[f * 12 + 7], v[f * 12 + 11]);
        poses.push_back(T);
    }
    return poses;
}

}  // namespace vobench::icl
