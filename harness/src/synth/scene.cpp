#include "synth/scene.hpp"

#include "synth/random_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vobench::synth {

bool Scene::intersect(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t_min, double t_max, Hit& hit,
                      const std::vector<int>* candidates) const {
    double best = t_max;
    int best_box = -1, best_axis = 0;
    bool best_positive_side = false;
    const Eigen::Vector3d inv(1.0 / d.x(), 1.0 / d.y(), 1.0 / d.z());
    const std::size_t count = candidates ? candidates->size() : boxes.size();
    for (std::size_t k = 0; k < count; ++k) {
        const std::size_t b = candidates ? static_cast<std::size_t>((*candidates)[k]) : k;
        const Box& box = boxes[b];
        // Slab method (Kay & Kajiya 1986): entry = max of near planes, exit = min of far planes.
        double t_enter = -std::numeric_limits<double>::infinity(), t_exit = std::numeric_limits<double>::infinity();
        int enter_axis = 0, exit_axis = 0;
        for (int a = 0; a < 3; ++a) {
            double t0 = (box.min[a] - o[a]) * inv[a], t1 = (box.max[a] - o[a]) * inv[a];
            if (t0 > t1) std::swap(t0, t1);
            if (t0 > t_enter) {
                t_enter = t0;
                enter_axis = a;
            }
            if (t1 < t_exit) {
                t_exit = t1;
                exit_axis = a;
            }
        }
        if (t_enter > t_exit) continue;
        const double t = box.shell ? t_exit : t_enter;
        const int axis = box.shell ? exit_axis : enter_axis;
        if (t > t_min && t < best) {
            best = t;
            best_box = static_cast<int>(b);
            best_axis = axis;
            // Which face of the box: the ray travels towards +axis on the shell's far face (or from
            // the −axis side on a solid box's near face).
            best_positive_side = box.shell ? d[axis] > 0 : d[axis] < 0;
        }
    }
    if (best_box < 0) return false;
    const Box& box = boxes[static_cast<std::size_t>(best_box)];
    hit.t = best;
    hit.point = o + best * d;
    hit.normal = Eigen::Vector3d::Zero();
    hit.normal[best_axis] = d[best_axis] > 0 ? -1.0 : 1.0;
    hit.material = box.shell ? box.material + 2 * best_axis + (best_positive_side ? 1 : 0) : box.material;
    const int ua = best_axis == 0 ? 1 : 0, va = best_axis == 2 ? 1 : 2;
    hit.u = hit.point[ua];
    hit.v = hit.point[va];
    return true;
}

bool Scene::occluded(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const {
    const Eigen::Vector3d delta = to - from;
    const double length = delta.norm();
    Hit h;
    return intersect(from, delta / length, 1e-4, length - 1e-3, h);
}

Eigen::Vector3f Scene::shade(const Hit& hit, double footprint) const {
    const Eigen::Vector3f a = albedo(materials[static_cast<std::size_t>(hit.material)], hit.u, hit.v, footprint);
    // Ambient plus diffuse point lights under the ceiling (no shadows: soft office lighting).
    double light = 0.22;
    for (const PointLight& l : lights) {
        const Eigen::Vector3d to = l.position - hit.point;
        const double d2 = to.squaredNorm();
        light += l.power * std::max(0.0, hit.normal.dot(to) / std::sqrt(d2)) / (1.0 + 0.3 * d2);
    }
    return a * static_cast<float>(light);
}

namespace {

class Random {
public:
    explicit Random(uint64_t seed) : state_(seed) {}
    double uniform(double lo, double hi) { return lo + (hi - lo) * synth::uniform(mix64(++state_ * 0x2545f4914f6cdd1dull)); }
    int pick(int n) { return std::min(n - 1, static_cast<int>(uniform(0, n))); }

private:
    uint64_t state_;
};

Material material(Random& r, TextureStyle style, Eigen::Vector3f base, Eigen::Vector3f accent, uint64_t seed) {
    Material m;
    m.style = style;
    m.base = base;
    m.accent = accent;
    m.scale = static_cast<float>(r.uniform(0.8, 1.25));
    m.seed = seed;
    return m;
}

Eigen::Vector3f colour(Random& r, float lo, float hi) {
    return {static_cast<float>(r.uniform(lo, hi)), static_cast<float>(r.uniform(lo, hi)), static_cast<float>(r.uniform(lo, hi))};
}

// Distance in the floor plane from (x, y) to the box's footprint.
double footprint_distance(const Box& b, double x, double y) {
    const double dx = std::max({b.min.x() - x, 0.0, x - b.max.x()});
    const double dy = std::max({b.min.y() - y, 0.0, y - b.max.y()});
    return std::hypot(dx, dy);
}

}  // namespace

Scene build_office(const std::vector<Eigen::Isometry3d>& poses, const OfficeOptions& o) {
    std::vector<Eigen::Vector2d> path;
    for (const auto& p : poses) path.emplace_back(p.translation().x(), p.translation().y());
    Scene s;
    s.floor_z = o.floor_z;
    Random r(o.seed * 7919 + 17);
    Eigen::Vector2d lo(1e9, 1e9), hi(-1e9, -1e9);
    for (const auto& p : path) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    if (path.empty()) lo = hi = Eigen::Vector2d::Zero();
    const double x0 = lo.x() - o.margin * r.uniform(0.8, 1.2), x1 = hi.x() + o.margin * r.uniform(0.8, 1.2);
    const double y0 = lo.y() - o.margin * r.uniform(0.8, 1.2), y1 = hi.y() + o.margin * r.uniform(0.8, 1.2);
    const double floor = o.floor_z;

    // Room shell: materials 0..5 are its faces (−x, +x, −y, +y, ceiling (z min), floor (z max)).
    uint64_t next_seed = o.seed * 1000003;
    for (int face = 0; face < 4; ++face)
        s.materials.push_back(material(r, TextureStyle::Paint, colour(r, 0.55f, 0.85f), colour(r, 0.3f, 0.5f), ++next_seed));
    s.materials.push_back(
        material(r, TextureStyle::Tiles, Eigen::Vector3f(0.85f, 0.85f, 0.82f), Eigen::Vector3f(0.35f, 0.35f, 0.35f), ++next_seed));
    s.materials.push_back(r.uniform(0, 1) < 0.5
                              ? material(r, TextureStyle::Tiles, colour(r, 0.35f, 0.6f), Eigen::Vector3f(0.15f, 0.15f, 0.15f), ++next_seed)
                              : material(r, TextureStyle::Carpet, colour(r, 0.2f, 0.45f), colour(r, 0.4f, 0.6f), ++next_seed));
    s.boxes.push_back({Eigen::Vector3d(x0, y0, 0.0), Eigen::Vector3d(x1, y1, floor), 0, true});

    auto add = [&](Eigen::Vector3d mn, Eigen::Vector3d mx, Material m) {
        s.materials.push_back(m);
        s.boxes.push_back({mn, mx, static_cast<int>(s.materials.size() - 1), false});
    };
    auto clear_of_path = [&](const Box& b) {
        for (const auto& p : path)
            if (footprint_distance(b, p.x(), p.y()) < o.clearance) return false;
        return true;
    };

    // Posters on every wall, 1.0–2.0 m above the floor (z down: floor − height).
    for (int wall = 0; wall < 4; ++wall) {
        const bool along_x = wall >= 2;
        const double length = along_x ? x1 - x0 : y1 - y0;
        const int count = std::max(3, static_cast<int>(length / 1.1));
        for (int k = 0; k < count; ++k) {
            const double centre = (along_x ? x0 : y0) + length * (k + r.uniform(0.3, 0.7)) / count;
            const double w = r.uniform(0.5, 1.1), h = r.uniform(0.4, 0.9), bottom = r.uniform(0.9, 1.4);
            const double wall_coord = wall == 0 ? x0 : wall == 1 ? x1 : wall == 2 ? y0 : y1;
            const double inward = (wall % 2 == 0) ? 1.0 : -1.0;
            Eigen::Vector3d mn, mx;
            const double a = wall_coord, b = wall_coord + inward * 0.012;
            if (!along_x) {
                mn = {std::min(a, b), centre - w / 2, floor - bottom - h};
                mx = {std::max(a, b), centre + w / 2, floor - bottom};
            } else {
                mn = {centre - w / 2, std::min(a, b), floor - bottom - h};
                mx = {centre + w / 2, std::max(a, b), floor - bottom};
            }
            const TextureStyle style = r.uniform(0, 1) < 0.35 ? TextureStyle::Pages : TextureStyle::Poster;
            add(mn, mx, material(r, style, colour(r, 0.7f, 0.9f), colour(r, 0.5f, 0.7f), ++next_seed));
        }
    }

    // Furniture along the walls and in the open, rejected where it would block the path.
    const int attempts = 400;
    for (int k = 0; k < attempts; ++k) {
        const int kind = r.pick(6);  // desk, shelf, cabinet, box stack, pillar, box
        double w, d, h;
        switch (kind) {
            case 0:
                w = r.uniform(1.2, 1.6);
                d = r.uniform(0.6, 0.8);
                h = r.uniform(0.72, 0.78);
                break;
            case 1:
                w = r.uniform(0.8, 1.2);
                d = r.uniform(0.3, 0.45);
                h = r.uniform(1.6, 2.2);
                break;
            case 2:
                w = r.uniform(0.4, 0.9);
                d = r.uniform(0.4, 0.6);
                h = r.uniform(0.6, 1.3);
                break;
            case 3:
                w = r.uniform(0.4, 0.7);
                d = r.uniform(0.4, 0.7);
                h = r.uniform(0.5, 1.1);
                break;
            case 4:
                w = r.uniform(0.3, 0.5);
                d = w;
                h = floor;
                break;
            default:
                w = r.uniform(0.25, 0.6);
                d = r.uniform(0.25, 0.6);
                h = r.uniform(0.2, 0.6);
                break;
        }
        // Against a wall (most furniture) or free-standing.
        double cx, cy;
        const bool swap = r.uniform(0, 1) < 0.5;
        if (swap) std::swap(w, d);
        if (kind != 4 && r.uniform(0, 1) < 0.5) {
            const int wall = r.pick(4);
            cx = wall == 0 ? x0 + w / 2 : wall == 1 ? x1 - w / 2 : r.uniform(x0 + w / 2, x1 - w / 2);
            cy = wall == 2 ? y0 + d / 2 : wall == 3 ? y1 - d / 2 : r.uniform(y0 + d / 2, y1 - d / 2);
        } else {
            cx = r.uniform(x0 + w / 2, x1 - w / 2);
            cy = r.uniform(y0 + d / 2, y1 - d / 2);
        }
        Box b{Eigen::Vector3d(cx - w / 2, cy - d / 2, floor - h), Eigen::Vector3d(cx + w / 2, cy + d / 2, floor), 0, false};
        if (!clear_of_path(b)) continue;
        bool overlaps = false;
        for (std::size_t i = 1; i < s.boxes.size() && !overlaps; ++i) {
            const Box& o2 = s.boxes[i];
            overlaps = b.min.x() < o2.max.x() && b.max.x() > o2.min.x() && b.min.y() < o2.max.y() && b.max.y() > o2.min.y() &&
                       b.min.z() < o2.max.z() && b.max.z() > o2.min.z();
        }
        if (overlaps) continue;
        TextureStyle style = kind == 0 || kind == 1 ? TextureStyle::Wood
                             : kind == 4            ? TextureStyle::Tiles
                             : kind == 2            ? TextureStyle::Tiles
                                                    : TextureStyle::Carpet;
        add(b.min, b.max, material(r, style, colour(r, 0.4f, 0.75f), colour(r, 0.2f, 0.45f), ++next_seed));
        if (kind == 0) {  // papers and a monitor on the desk
            const double top = floor - h;
            add({cx - 0.25, cy - 0.17, top - 0.004}, {cx + 0.05, cy + 0.17, top},
                material(r, TextureStyle::Pages, Eigen::Vector3f(0.92f, 0.92f, 0.9f), Eigen::Vector3f(0.8f, 0.8f, 0.78f), ++next_seed));
            add({cx + 0.1, cy - 0.03, top - 0.38}, {cx + 0.6, cy + 0.03, top},
                material(r, TextureStyle::Poster, Eigen::Vector3f(0.15f, 0.15f, 0.18f), colour(r, 0.3f, 0.9f), ++next_seed));
        }
        if (kind == 1) {  // book rows on the shelf's faces
            for (double z = floor - 0.3; z > floor - h + 0.2; z -= 0.4)
                add({cx - w / 2 - 0.01, cy - d / 2 - 0.01, z - 0.25}, {cx + w / 2 + 0.01, cy + d / 2 + 0.01, z - 0.02},
                    material(r, TextureStyle::Poster, colour(r, 0.3f, 0.8f), colour(r, 0.2f, 0.9f), ++next_seed));
        }
    }

    // Structure in range everywhere along the path.
    auto in_range_fraction = [&](const Eigen::Isometry3d& pose) {
        int in = 0, total = 0;
        for (int i = -4; i <= 4; ++i)
            for (int j = -3; j <= 3; ++j) {
                const Eigen::Vector3d dir = pose.linear() * Eigen::Vector3d(0.12 * i, 0.1 * j, 1.0).normalized();
                Hit h;
                ++total;
                if (s.intersect(pose.translation(), dir, 1e-6, 1e3, h) && h.t > 0.5 && h.t < 4.3) ++in;
            }
        return static_cast<double>(in) / total;
    };
    for (std::size_t k = 0; k < poses.size(); k += 5) {
        if (in_range_fraction(poses[k]) >= 0.5) continue;
        Eigen::Vector3d forward = poses[k].linear() * Eigen::Vector3d::UnitZ();
        forward.z() = 0;
        if (forward.norm() < 1e-6) continue;
        forward.normalize();
        const Eigen::Vector3d side(-forward.y(), forward.x(), 0);
        const Eigen::Vector3d at = poses[k].translation();
        bool placed = false;
        for (double distance : {2.5, 3.2, 1.9}) {
            for (double lateral : {0.0, 0.8, -0.8, 1.4, -1.4}) {
                const Eigen::Vector3d c = at + forward * distance + side * lateral;
                const double w = r.uniform(0.6, 1.0), d = r.uniform(0.4, 0.6), h = r.uniform(1.0, 1.9);
                Box b{Eigen::Vector3d(c.x() - w / 2, c.y() - d / 2, floor - h), Eigen::Vector3d(c.x() + w / 2, c.y() + d / 2, floor), 0,
                      false};
                if (b.min.x() < x0 || b.max.x() > x1 || b.min.y() < y0 || b.max.y() > y1 || !clear_of_path(b)) continue;
                const TextureStyle style = r.uniform(0, 1) < 0.5 ? TextureStyle::Poster : TextureStyle::Tiles;
                add(b.min, b.max, material(r, style, colour(r, 0.45f, 0.8f), colour(r, 0.15f, 0.4f), ++next_seed));
                placed = true;
                break;
            }
            if (placed) break;
        }
    }

    // Ceiling lights on a 2.5 m grid.
    for (double x = x0 + 1.2; x < x1; x += 2.5)
        for (double y = y0 + 1.2; y < y1; y += 2.5) s.lights.push_back({Eigen::Vector3d(x, y, 0.2), 0.32});
    return s;
}

}  // namespace vobench::synth
