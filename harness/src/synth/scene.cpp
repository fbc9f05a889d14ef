#include "synth/scene.hpp"

#include "synth/desk_clutter.hpp"
#include "synth/random_field.hpp"
#include "synth/ray_index.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace vobench::synth {

namespace {

// Slab method (Kay & Kajiya 1986): entry = max of near planes, exit = min of far planes.
struct Slab {
    double t_enter = -std::numeric_limits<double>::infinity(), t_exit = std::numeric_limits<double>::infinity();
    int enter_axis = 0, exit_axis = 0;
};
Slab slab(const Eigen::Vector3d& mn, const Eigen::Vector3d& mx, const Eigen::Vector3d& o, const Eigen::Vector3d& inv) {
    Slab r;
    for (int a = 0; a < 3; ++a) {
        double t0 = (mn[a] - o[a]) * inv[a], t1 = (mx[a] - o[a]) * inv[a];
        if (t0 > t1) std::swap(t0, t1);
        if (t0 > r.t_enter) {
            r.t_enter = t0;
            r.enter_axis = a;
        }
        if (t1 < r.t_exit) {
            r.t_exit = t1;
            r.exit_axis = a;
        }
    }
    return r;
}

// x⁶⁰ by squaring (x⁴·x⁸·x¹⁶·x³²): within a few units in the last place of std::pow, at a tenth of
// its cost (pow was 8 % of a tum-fr1 frame's rendering).
double power60(double x) {
    const double x2 = x * x, x4 = x2 * x2, x8 = x4 * x4, x16 = x8 * x8, x32 = x16 * x16;
    return x32 * x16 * x8 * x4;
}

}  // namespace

void Scene::build_index() { index_ = boxes.empty() ? nullptr : std::make_shared<const RayIndex>(boxes); }

bool Scene::intersect(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t_min, double t_max, Hit& hit) const {
    double best = t_max;
    int best_box = -1, best_axis = 0;
    bool best_positive_side = false;
    const Eigen::Vector3d inv(1.0 / d.x(), 1.0 / d.y(), 1.0 / d.z());
    auto test = [&](int b) {
        const Box& box = boxes[static_cast<std::size_t>(b)];
        const Slab s = slab(box.min, box.max, o, inv);
        if (s.t_enter > s.t_exit) return;
        const double t = box.shell ? s.t_exit : s.t_enter;
        const int axis = box.shell ? s.exit_axis : s.enter_axis;
        if (t > t_min && t < best) {
            best = t;
            best_box = b;
            best_axis = axis;
            // Which face of the box: the ray travels towards +axis on the shell's far face (or from
            // the −axis side on a solid box's near face).
            best_positive_side = box.shell ? d[axis] > 0 : d[axis] < 0;
        }
    };
    if (index_) {
        IndexHit h;
        if (!index_->nearest(o, d, t_min, t_max, h)) return false;
        best = h.t;
        best_box = h.box;
        best_axis = h.axis;
        best_positive_side = h.max_side;  // for the shell: the far face the ray travels towards
    } else {
        for (std::size_t b = 0; b < boxes.size(); ++b) test(static_cast<int>(b));
    }
    if (best_box < 0) return false;
    hit = hit_on(best_box, best_axis, best_positive_side, o, d, best);
    return true;
}

Hit Scene::hit_on(int box_index, int axis, bool positive_side, const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t) const {
    const Box& box = boxes[static_cast<std::size_t>(box_index)];
    Hit hit;
    hit.t = t;
    hit.point = o + t * d;
    hit.normal = Eigen::Vector3d::Zero();
    hit.normal[axis] = d[axis] > 0 ? -1.0 : 1.0;
    hit.axis = axis;
    hit.material = box.shell ? box.material + 2 * axis + (positive_side ? 1 : 0) : box.material;
    const int ua = axis == 0 ? 1 : 0, va = axis == 2 ? 1 : 2;
    hit.u = hit.point[ua];
    hit.v = hit.point[va];
    return hit;
}

void Scene::intersect_packet(const Eigen::Vector3d& o, const Eigen::Vector3d* dirs, int count, double t_min, double t_max, Hit* hits,
                             bool* found) const {
    if (!index_) {
        for (int i = 0; i < count; ++i) found[i] = intersect(o, dirs[i], t_min, t_max, hits[i]);
        return;
    }
    for (int start = 0; start < count; start += RayIndex::kPacket) {
        const int n = std::min(RayIndex::kPacket, count - start);
        IndexHit h[RayIndex::kPacket];
        index_->nearest_packet(o, dirs + start, n, t_min, t_max, h);
        for (int i = 0; i < n; ++i) {
            found[start + i] = h[i].box >= 0;
            if (found[start + i]) hits[start + i] = hit_on(h[i].box, h[i].axis, h[i].max_side, o, dirs[start + i], h[i].t);
        }
    }
}

bool Scene::occluded(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const {
    const Eigen::Vector3d delta = to - from;
    const double length = delta.norm();
    if (index_) return index_->any(from, delta / length, 1e-4, length - 1e-3);
    Hit h;
    return intersect(from, delta / length, 1e-4, length - 1e-3, h);
}

Eigen::Vector3f Scene::shade(const Hit& hit, const Eigen::Vector3d& view_dir, double footprint, bool highlights) const {
    const Material& m = materials[static_cast<std::size_t>(hit.material)];
    const Eigen::Vector3f a = albedo(m, hit.u, hit.v, footprint);
    // Ambient plus diffuse point lights under the ceiling (no shadows: soft office lighting).
    double light = 0.12 + m.emission, specular = 0;
    const bool glossy = highlights && m.gloss > 0;
    // The normal is ±1 on one axis and 0 on the others, so n·x is exactly ±x[axis]: only that
    // component of a direction is divided out unless a highlight needs the whole direction (the
    // same numbers as the full dot products, at a third of the divisions).
    const int axis = hit.axis;
    const double side = hit.normal[axis];
    for (const PointLight& l : lights) {
        const Eigen::Vector3d to = l.position - hit.point;
        // A light behind the surface adds no diffuse light; without a highlight to compute, skip it.
        if (!glossy && side * to[axis] <= 0) continue;
        const double d2 = to.squaredNorm();
        const double distance = std::sqrt(d2);
        const double falloff = l.power / (1.0 + 0.3 * d2);
        light += falloff * std::max(0.0, side * (to[axis] / distance));
        if (glossy) {
            // Blinn–Phong (Blinn 1977): the half vector between light and eye, shininess 60.
            // Its axis component as Eigen's normalized() gives it (a zero vector stays as it is).
            const Eigen::Vector3d half = to / distance - view_dir;
            const double h2 = half.squaredNorm();
            const double half_on_axis = h2 > 0 ? half[axis] / std::sqrt(h2) : half[axis];
            specular += falloff * power60(std::max(0.0, side * half_on_axis));
        }
    }
    return a * static_cast<float>(light) + Eigen::Vector3f::Constant(static_cast<float>(3.0 * m.gloss * specular));
}

namespace {

// How far from the camera (horizontally) a desk it looks down at may stand: an arm's length plus a
// desk's depth.
constexpr double kDeskReach = 1.3;

// Where a camera's central ray meets the horizontal plane z = height (z down); none when the camera
// looks level or up (less than about 12° down) or stands below the plane.
std::optional<Eigen::Vector3d> gaze_at_height(const Eigen::Isometry3d& pose, double height) {
    const Eigen::Vector3d at = pose.translation(), dir = pose.linear().col(2);
    if (dir.z() < 0.2 || at.z() >= height) return std::nullopt;
    return at + dir * ((height - at.z()) / dir.z());
}

// Distance in the floor plane between two points.
double floor_distance(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return std::hypot(a.x() - b.x(), a.y() - b.y()); }

// Distance in the floor plane from (x, y) to the box's footprint.
double footprint_distance(const Box& b, double x, double y) {
    const double dx = std::max({b.min.x() - x, 0.0, x - b.max.x()});
    const double dy = std::max({b.min.y() - y, 0.0, y - b.max.y()});
    return std::hypot(dx, dy);
}

bool overlaps_any(const Scene& s, const Box& b) {
    for (const Box& o2 : s.boxes) {
        if (o2.shell) continue;
        if (b.min.x() < o2.max.x() && b.max.x() > o2.min.x() && b.min.y() < o2.max.y() && b.max.y() > o2.min.y() &&
            b.min.z() < o2.max.z() && b.max.z() > o2.min.z())
            return true;
    }
    return false;
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
    double x0 = lo.x() - o.margin * r.uniform(0.8, 1.2), x1 = hi.x() + o.margin * r.uniform(0.8, 1.2);
    double y0 = lo.y() - o.margin * r.uniform(0.8, 1.2), y1 = hi.y() + o.margin * r.uniform(0.8, 1.2);
    // A camera held in one spot (TUM's rpy, xyz) still stands in a room of an office's size.
    auto widen = [&](double& a, double& b) {
        const double deficit = o.min_room * r.uniform(1.0, 1.3) - (b - a);
        if (deficit <= 0) return;
        const double share = r.uniform(0.25, 0.75);
        a -= deficit * share;
        b += deficit * (1 - share);
    };
    widen(x0, x1);
    widen(y0, y1);
    const double floor = o.floor_z;

    // Room shell: materials 0..5 are its faces (−x, +x, −y, +y, ceiling (z min), floor (z max)).
    uint64_t next_seed = o.seed * 1000003;
    for (int face = 0; face < 4; ++face)
        s.materials.push_back(material(r, TextureStyle::Paint, colour(r, 0.55f, 0.85f), colour(r, 0.3f, 0.5f), ++next_seed));
    s.materials.push_back(
        material(r, TextureStyle::Tiles, Eigen::Vector3f(0.85f, 0.85f, 0.82f), Eigen::Vector3f(0.35f, 0.35f, 0.35f), ++next_seed));
    const double floor_kind = r.uniform(0, 1);  // tiles, carpet or a wooden parquet
    s.materials.push_back(
        floor_kind < 0.35 ? material(r, TextureStyle::Tiles, colour(r, 0.35f, 0.6f), Eigen::Vector3f(0.15f, 0.15f, 0.15f), ++next_seed)
        : floor_kind < 0.65
            ? material(r, TextureStyle::Carpet, colour(r, 0.2f, 0.45f), colour(r, 0.4f, 0.6f), ++next_seed)
            : material(r, TextureStyle::Wood, Eigen::Vector3f(0.45f, 0.28f, 0.15f), Eigen::Vector3f(0.15f, 0.08f, 0.04f), ++next_seed));
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

    // A flat panel on wall 0..3 (−x, +x, −y, +y): `centre` along the wall, `bottom` and `height` above
    // the floor, `thickness` into the room.
    auto wall_panel = [&](int wall, double centre, double width, double bottom, double height, double thickness) {
        const double wall_coord = wall == 0 ? x0 : wall == 1 ? x1 : wall == 2 ? y0 : y1;
        const double a = wall_coord, b = wall_coord + (wall % 2 == 0 ? 1.0 : -1.0) * thickness;
        Box panel;
        if (wall < 2) {
            panel.min = {std::min(a, b), centre - width / 2, floor - bottom - height};
            panel.max = {std::max(a, b), centre + width / 2, floor - bottom};
        } else {
            panel.min = {centre - width / 2, std::min(a, b), floor - bottom - height};
            panel.max = {centre + width / 2, std::max(a, b), floor - bottom};
        }
        return panel;
    };

    // Posters on every wall, 1.0–2.0 m above the floor (z down: floor − height).
    for (int wall = 0; wall < 4; ++wall) {
        const bool along_x = wall >= 2;
        const double length = along_x ? x1 - x0 : y1 - y0;
        const int count = std::max(3, static_cast<int>(length / 1.1));
        for (int k = 0; k < count; ++k) {
            const double centre = (along_x ? x0 : y0) + length * (k + r.uniform(0.3, 0.7)) / count;
            const double w = r.uniform(0.5, 1.1), h = r.uniform(0.4, 0.9), bottom = r.uniform(0.9, 1.4);
            const Box panel = wall_panel(wall, centre, w, bottom, h, 0.012);
            const TextureStyle style = r.uniform(0, 1) < 0.35 ? TextureStyle::Pages : TextureStyle::Poster;
            add(panel.min, panel.max, material(r, style, colour(r, 0.7f, 0.9f), colour(r, 0.5f, 0.7f), ++next_seed));
        }
    }

    // Windows: bright (emissive) panes with mullions; the IR sees through glass (no depth there).
    const int windows = r.pick(3);
    for (int k = 0; k < windows; ++k) {
        const int wall = r.pick(4);
        const bool along_x = wall >= 2;
        const double length = along_x ? x1 - x0 : y1 - y0, w = r.uniform(0.9, 1.6);
        if (length < w + 0.4) continue;
        const double centre = (along_x ? x0 : y0) + r.uniform(0.2 + w / 2, length - 0.2 - w / 2);
        const double bottom = r.uniform(0.8, 1.0), h = r.uniform(1.0, 1.4);
        const Box pane = wall_panel(wall, centre, w, bottom, h, 0.015);
        Material glass =
            material(r, TextureStyle::Tiles, Eigen::Vector3f(0.8f, 0.85f, 0.9f), Eigen::Vector3f(0.1f, 0.1f, 0.1f), ++next_seed);
        glass.scale = static_cast<float>(w);  // one mullion cross per pane
        glass.emission = static_cast<float>(r.uniform(1.5, 3.0));
        add(pane.min, pane.max, glass);
    }

    // Desks where the cameras look down: every 10th pose's central ray, met at desk height within
    // kDeskReach (horizontally), gets a desk under that point, clear of the path by 0.25 m — the desk
    // the camera's holder stands at. The nearest look-at points first: the desk a camera is held over
    // is the one under its steepest views; a view that meets desk height further away looks past it
    // (across the room, as fr1/rpy's fast turns do), and gets no desk in its way.
    std::vector<std::pair<double, std::size_t>> looked_at;  // (reach at a mid desk height, pose)
    for (std::size_t k = 0; k < poses.size(); k += 10) {
        const auto gaze = gaze_at_height(poses[k], floor - 0.74);
        looked_at.emplace_back(gaze ? floor_distance(*gaze, poses[k].translation()) : std::numeric_limits<double>::infinity(), k);
    }
    std::stable_sort(looked_at.begin(), looked_at.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& entry : looked_at) {
        const std::size_t k = entry.second;
        const Eigen::Vector3d at = poses[k].translation(), dir = poses[k].linear().col(2);
        const double desk_h = r.uniform(0.72, 0.76), top = floor - desk_h;
        const auto gaze = gaze_at_height(poses[k], top);
        if (!gaze) continue;
        const Eigen::Vector3d hit = *gaze;
        const double reach = floor_distance(hit, at);
        if (reach < 0.3 || reach > kDeskReach) continue;
        // The long side across the view, snapped to the room's axes.
        const bool long_x = std::abs(dir.y()) >= std::abs(dir.x());
        const double len = r.uniform(1.4, 1.8), depth = r.uniform(0.7, 0.85);
        const double w = long_x ? len : depth, d = long_x ? depth : len;
        const double cx = hit.x() + r.uniform(-0.15, 0.15), cy = hit.y() + r.uniform(-0.15, 0.15);
        Box desk{Eigen::Vector3d(cx - w / 2, cy - d / 2, top), Eigen::Vector3d(cx + w / 2, cy + d / 2, floor), 0, false};
        if (desk.min.x() < x0 || desk.max.x() > x1 || desk.min.y() < y0 || desk.max.y() > y1 || overlaps_any(s, desk)) continue;
        bool clear = true;
        for (const auto& p : path) clear = clear && footprint_distance(desk, p.x(), p.y()) >= 0.25;
        if (!clear) continue;
        build_desk(desk, top, floor, r, next_seed, add);
        const Eigen::Vector2d user(at.x(), at.y());
        furnish_desk(desk, top, r, next_seed, add, &user);
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
        // Shelves, cabinets and boxes against a wall, pillars free-standing, desks either (a coin): the
        // open floor of an office holds desks, so a view across the room meets desks and the far wall.
        double cx, cy;
        const bool swap = r.uniform(0, 1) < 0.5;
        if (swap) std::swap(w, d);
        const bool against_wall = kind != 4 && (r.uniform(0, 1) < 0.5 || kind != 0);
        if (against_wall) {
            const int wall = r.pick(4);
            cx = wall == 0 ? x0 + w / 2 : wall == 1 ? x1 - w / 2 : r.uniform(x0 + w / 2, x1 - w / 2);
            cy = wall == 2 ? y0 + d / 2 : wall == 3 ? y1 - d / 2 : r.uniform(y0 + d / 2, y1 - d / 2);
        } else {
            cx = r.uniform(x0 + w / 2, x1 - w / 2);
            cy = r.uniform(y0 + d / 2, y1 - d / 2);
        }
        Box b{Eigen::Vector3d(cx - w / 2, cy - d / 2, floor - h), Eigen::Vector3d(cx + w / 2, cy + d / 2, floor), 0, false};
        if (!clear_of_path(b)) continue;
        if (overlaps_any(s, b)) continue;
        TextureStyle style = kind == 1   ? TextureStyle::Wood
                             : kind == 4 ? TextureStyle::Tiles
                             : kind == 2 ? TextureStyle::Tiles
                                         : TextureStyle::Carpet;
        if (kind == 0) {
            build_desk(b, floor - h, floor, r, next_seed, add);
            furnish_desk(b, floor - h, r, next_seed, add);
        } else {
            add(b.min, b.max, material(r, style, colour(r, 0.4f, 0.75f), colour(r, 0.2f, 0.45f), ++next_seed));
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
        for (double y = y0 + 1.2; y < y1; y += 2.5) s.lights.push_back({Eigen::Vector3d(x, y, 0.2), 0.45});
    s.build_index();
    return s;
}

}  // namespace vobench::synth
