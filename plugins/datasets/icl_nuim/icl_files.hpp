// icl_files.hpp — the text formats of ICL-NUIM (both layouts) and of camera.txt. Each parser throws
// std::runtime_error naming the file (`name`) and, where lines matter, the line.
#pragma once

#include <Eigen/Geometry>

#include <map>
#include <string>
#include <vector>

namespace vobench::icl {

struct Association {
    double t_depth, t_rgb;
    std::string depth, rgb;
};
// associations.txt: `t_depth depth_file t_rgb rgb_file` per line, stamps increasing.
std::vector<Association> parse_associations(const std::string& text, const std::string& name);

// camera.txt: `fx fy cx cy` and up to 8 distortion coefficients on the first non-comment line.
std::vector<double> parse_camera(const std::string& text, const std::string& name);

// POV-Ray camera file: `name = [x, y, z]';` lines (scalars such as cam_angle are skipped).
std::map<std::string, Eigen::Vector3d> parse_camera_vectors(const std::string& text, const std::string& name);

// .depth: exactly `count` non-negative numbers separated by white space.
std::vector<float> parse_ray_depth(const std::string& text, const std::string& name, std::size_t count);

// .gt.sim: 12 numbers per frame, the rows of [R|t]; R must be a rotation.
std::vector<Eigen::Isometry3d> parse_sim(const std::string& text, const std::string& name);

}  // namespace vobench::icl
