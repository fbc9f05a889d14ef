#include "synth/office.hpp"

#include "synth/desk_clutter.hpp"
#include "synth/scene_random.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

namespace vobench::synth {
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

// Sizes of the furniture kinds add_furniture() places, metres: [min, max) of width, depth, height.
struct FurnitureSize {
    double width[2], depth[2], height[2];
};
constexpr int kPillar = 4;                                                              // square, floor to ceiling: only its width is drawn
constexpr FurnitureSize kFurnitureSizes[6] = {{{1.2, 1.6}, {0.6, 0.8}, {0.72, 0.78}},   // desk
                                              {{0.8, 1.2}, {0.3, 0.45}, {1.6, 2.2}},    // shelf
                                              {{0.4, 0.9}, {0.4, 0.6}, {0.6, 1.3}},     // cabinet
                                              {{0.4, 0.7}, {0.4, 0.7}, {0.5, 1.1}},     // box stack
                                              {{0.3, 0.5}, {0, 0}, {0, 0}},             // pillar
                                              {{0.25, 0.6}, {0.25, 0.6}, {0.2, 0.6}}};  // box

// The office, built in steps. Every step draws from the one stream `r_` and numbers materials from
// `next_seed_`, so the steps' order (that of build()) is part of what a seed means: changing it
// changes every office.
class OfficeBuilder {
public:
    OfficeBuilder(const std::vector<Eigen::Isometry3d>& poses, const OfficeOptions& o)
        : poses_(poses), o_(o), r_(o.seed * 7919 + 17), floor_(o.floor_z) {
        for (const auto& p : poses) path_.emplace_back(p.translation().x(), p.translation().y());
        s_.floor_z = o.floor_z;
        add_ = [this](const Eigen::Vector3d& mn, const Eigen::Vector3d& mx, const Material& m) { add(mn, mx, m); };
    }

    Scene build() {
        fit_room();
        add_shell();
        add_posters();
        add_windows();
        add_desks_in_view();
        add_furniture();
        add_structure_in_range();
        add_lights();
        s_.build_index();
        return std::move(s_);
    }

private:
    // The walls at x0_, x1_, y0_, y1_: the path's bounding box and a margin, widened to an office's size.
    void fit_room() {
        Eigen::Vector2d lo(1e9, 1e9), hi(-1e9, -1e9);
        for (const auto& p : path_) {
            lo = lo.cwiseMin(p);
            hi = hi.cwiseMax(p);
        }
        if (path_.empty()) lo = hi = Eigen::Vector2d::Zero();
        x0_ = lo.x() - o_.margin * r_.uniform(0.8, 1.2);
        x1_ = hi.x() + o_.margin * r_.uniform(0.8, 1.2);
        y0_ = lo.y() - o_.margin * r_.uniform(0.8, 1.2);
        y1_ = hi.y() + o_.margin * r_.uniform(0.8, 1.2);
        // A camera held in one spot (TUM's rpy, xyz) still stands in a room of an office's size.
        auto widen = [&](double& a, double& b) {
            const double deficit = o_.min_room * r_.uniform(1.0, 1.3) - (b - a);
            if (deficit <= 0) return;
            const double share = r_.uniform(0.25, 0.75);
            a -= deficit * share;
            b += deficit * (1 - share);
        };
        widen(x0_, x1_);
        widen(y0_, y1_);
    }

    // Room shell: materials 0..5 are its faces (−x, +x, −y, +y, ceiling (z min), floor (z max)).
    void add_shell() {
        next_seed_ = o_.seed * 1000003;
        for (int face = 0; face < 4; ++face)
            s_.materials.push_back(material(r_, TextureStyle::Paint, colour(r_, 0.55f, 0.85f), colour(r_, 0.3f, 0.5f), ++next_seed_));
        s_.materials.push_back(
            material(r_, TextureStyle::Tiles, Eigen::Vector3f(0.85f, 0.85f, 0.82f), Eigen::Vector3f(0.35f, 0.35f, 0.35f), ++next_seed_));
        const double floor_kind = r_.uniform(0, 1);  // tiles, carpet or a wooden parquet
        s_.materials.push_back(
            floor_kind < 0.35
                ? material(r_, TextureStyle::Tiles, colour(r_, 0.35f, 0.6f), Eigen::Vector3f(0.15f, 0.15f, 0.15f), ++next_seed_)
            : floor_kind < 0.65 ? material(r_, TextureStyle::Carpet, colour(r_, 0.2f, 0.45f), colour(r_, 0.4f, 0.6f), ++next_seed_)
                                : material(r_, TextureStyle::Wood, Eigen::Vector3f(0.45f, 0.28f, 0.15f),
                                           Eigen::Vector3f(0.15f, 0.08f, 0.04f), ++next_seed_));
        s_.boxes.push_back({Eigen::Vector3d(x0_, y0_, 0.0), Eigen::Vector3d(x1_, y1_, floor_), 0, true});
    }

    // Posters on every wall, 1.0–2.0 m above the floor (z down: floor − height).
    void add_posters() {
        for (int wall = 0; wall < 4; ++wall) {
            const bool along_x = wall >= 2;
            const double length = along_x ? x1_ - x0_ : y1_ - y0_;
            const int count = std::max(3, static_cast<int>(length / 1.1));
            for (int k = 0; k < count; ++k) {
                const double centre = (along_x ? x0_ : y0_) + length * (k + r_.uniform(0.3, 0.7)) / count;
                const double w = r_.uniform(0.5, 1.1), h = r_.uniform(0.4, 0.9), bottom = r_.uniform(0.9, 1.4);
                const Box panel = wall_panel(wall, centre, w, bottom, h, 0.012);
                const TextureStyle style = r_.uniform(0, 1) < 0.35 ? TextureStyle::Pages : TextureStyle::Poster;
                add(panel.min, panel.max, material(r_, style, colour(r_, 0.7f, 0.9f), colour(r_, 0.5f, 0.7f), ++next_seed_));
            }
        }
    }

    // Windows: bright (emissive) panes with mullions; the IR sees through glass (no depth there).
    void add_windows() {
        const int windows = r_.pick(3);
        for (int k = 0; k < windows; ++k) {
            const int wall = r_.pick(4);
            const bool along_x = wall >= 2;
            const double length = along_x ? x1_ - x0_ : y1_ - y0_, w = r_.uniform(0.9, 1.6);
            if (length < w + 0.4) continue;
            const double centre = (along_x ? x0_ : y0_) + r_.uniform(0.2 + w / 2, length - 0.2 - w / 2);
            const double bottom = r_.uniform(0.8, 1.0), h = r_.uniform(1.0, 1.4);
            const Box pane = wall_panel(wall, centre, w, bottom, h, 0.015);
            Material glass =
                material(r_, TextureStyle::Tiles, Eigen::Vector3f(0.8f, 0.85f, 0.9f), Eigen::Vector3f(0.1f, 0.1f, 0.1f), ++next_seed_);
            glass.scale = static_cast<float>(w);  // one mullion cross per pane
            glass.emission = static_cast<float>(r_.uniform(1.5, 3.0));
            add(pane.min, pane.max, glass);
        }
    }

    // Desks where the cameras look down: every 10th pose's central ray, met at desk height within
    // kDeskReach (horizontally), gets a desk under that point, clear of the path by 0.25 m — the desk
    // the camera's holder stands at. The nearest look-at points first: the desk a camera is held over
    // is the one under its steepest views; a view that meets desk height further away looks past it
    // (across the room, as fr1/rpy's fast turns do), and gets no desk in its way.
    void add_desks_in_view() {
        std::vector<std::pair<double, std::size_t>> looked_at;  // (reach at a mid desk height, pose)
        for (std::size_t k = 0; k < poses_.size(); k += 10) {
            const auto gaze = gaze_at_height(poses_[k], floor_ - 0.74);
            looked_at.emplace_back(gaze ? floor_distance(*gaze, poses_[k].translation()) : std::numeric_limits<double>::infinity(), k);
        }
        std::stable_sort(looked_at.begin(), looked_at.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
        for (const auto& entry : looked_at) {
            const std::size_t k = entry.second;
            const Eigen::Vector3d at = poses_[k].translation(), dir = poses_[k].linear().col(2);
            const double desk_h = r_.uniform(0.72, 0.76), top = floor_ - desk_h;
            const auto gaze = gaze_at_height(poses_[k], top);
            if (!gaze) continue;
            const Eigen::Vector3d hit = *gaze;
            const double reach = floor_distance(hit, at);
            if (reach < 0.3 || reach > kDeskReach) continue;
            // The long side across the view, snapped to the room's axes.
            const bool long_x = std::abs(dir.y()) >= std::abs(dir.x());
            const double len = r_.uniform(1.4, 1.8), depth = r_.uniform(0.7, 0.85);
            const double w = long_x ? len : depth, d = long_x ? depth : len;
            const double cx = hit.x() + r_.uniform(-0.15, 0.15), cy = hit.y() + r_.uniform(-0.15, 0.15);
            Box desk{Eigen::Vector3d(cx - w / 2, cy - d / 2, top), Eigen::Vector3d(cx + w / 2, cy + d / 2, floor_), 0, false};
            if (!inside_room(desk) || overlaps_any(s_, desk)) continue;
            bool clear = true;
            for (const auto& p : path_) clear = clear && footprint_distance(desk, p.x(), p.y()) >= 0.25;
            if (!clear) continue;
            build_desk(desk, top, floor_, r_, next_seed_, add_);
            const Eigen::Vector2d user(at.x(), at.y());
            furnish_desk(desk, top, r_, next_seed_, add_, &user);
        }
    }

    // Furniture along the walls and in the open, rejected where it would block the path.
    void add_furniture() {
        const int attempts = 400;
        for (int k = 0; k < attempts; ++k) {
            const int kind = r_.pick(6);  // desk, shelf, cabinet, box stack, pillar, box
            // Width, depth and height drawn in that order from the kind's ranges; a pillar is square
            // and reaches the ceiling.
            const FurnitureSize& size = kFurnitureSizes[kind];
            double w = r_.uniform(size.width[0], size.width[1]);
            double d = kind == kPillar ? w : r_.uniform(size.depth[0], size.depth[1]);
            const double h = kind == kPillar ? floor_ : r_.uniform(size.height[0], size.height[1]);
            // Shelves, cabinets and boxes against a wall, pillars free-standing, desks either (a coin): the
            // open floor of an office holds desks, so a view across the room meets desks and the far wall.
            double cx, cy;
            const bool swap = r_.uniform(0, 1) < 0.5;
            if (swap) std::swap(w, d);
            const bool against_wall = kind != kPillar && (r_.uniform(0, 1) < 0.5 || kind != 0);
            if (against_wall) {
                const int wall = r_.pick(4);
                cx = wall == 0 ? x0_ + w / 2 : wall == 1 ? x1_ - w / 2 : r_.uniform(x0_ + w / 2, x1_ - w / 2);
                cy = wall == 2 ? y0_ + d / 2 : wall == 3 ? y1_ - d / 2 : r_.uniform(y0_ + d / 2, y1_ - d / 2);
            } else {
                cx = r_.uniform(x0_ + w / 2, x1_ - w / 2);
                cy = r_.uniform(y0_ + d / 2, y1_ - d / 2);
            }
            Box b{Eigen::Vector3d(cx - w / 2, cy - d / 2, floor_ - h), Eigen::Vector3d(cx + w / 2, cy + d / 2, floor_), 0, false};
            if (!clear_of_path(b)) continue;
            if (overlaps_any(s_, b)) continue;
            TextureStyle style = kind == 1         ? TextureStyle::Wood
                                 : kind == kPillar ? TextureStyle::Tiles
                                 : kind == 2       ? TextureStyle::Tiles
                                                   : TextureStyle::Carpet;
            if (kind == 0) {
                build_desk(b, floor_ - h, floor_, r_, next_seed_, add_);
                furnish_desk(b, floor_ - h, r_, next_seed_, add_);
            } else {
                add(b.min, b.max, material(r_, style, colour(r_, 0.4f, 0.75f), colour(r_, 0.2f, 0.45f), ++next_seed_));
            }
            if (kind == 1) {  // book rows on the shelf's faces
                for (double z = floor_ - 0.3; z > floor_ - h + 0.2; z -= 0.4)
                    add({cx - w / 2 - 0.01, cy - d / 2 - 0.01, z - 0.25}, {cx + w / 2 + 0.01, cy + d / 2 + 0.01, z - 0.02},
                        material(r_, TextureStyle::Poster, colour(r_, 0.3f, 0.8f), colour(r_, 0.2f, 0.9f), ++next_seed_));
            }
        }
    }

    // Structure in range everywhere along the path: where less than half of a coarse fan of rays
    // from every 5th pose meets something within 0.5–4.3 m, a cabinet ahead, beside the path.
    void add_structure_in_range() {
        for (std::size_t k = 0; k < poses_.size(); k += 5) {
            if (in_range_fraction(poses_[k]) >= 0.5) continue;
            Eigen::Vector3d forward = poses_[k].linear() * Eigen::Vector3d::UnitZ();
            forward.z() = 0;
            if (forward.norm() < 1e-6) continue;
            forward.normalize();
            const Eigen::Vector3d side(-forward.y(), forward.x(), 0);
            const Eigen::Vector3d at = poses_[k].translation();
            bool placed = false;
            for (double distance : {2.5, 3.2, 1.9}) {
                for (double lateral : {0.0, 0.8, -0.8, 1.4, -1.4}) {
                    const Eigen::Vector3d c = at + forward * distance + side * lateral;
                    const double w = r_.uniform(0.6, 1.0), d = r_.uniform(0.4, 0.6), h = r_.uniform(1.0, 1.9);
                    Box b{Eigen::Vector3d(c.x() - w / 2, c.y() - d / 2, floor_ - h), Eigen::Vector3d(c.x() + w / 2, c.y() + d / 2, floor_),
                          0, false};
                    if (!inside_room(b) || !clear_of_path(b)) continue;
                    const TextureStyle style = r_.uniform(0, 1) < 0.5 ? TextureStyle::Poster : TextureStyle::Tiles;
                    add(b.min, b.max, material(r_, style, colour(r_, 0.45f, 0.8f), colour(r_, 0.15f, 0.4f), ++next_seed_));
                    placed = true;
                    break;
                }
                if (placed) break;
            }
        }
    }

    // Ceiling lights on a 2.5 m grid.
    void add_lights() {
        for (double x = x0_ + 1.2; x < x1_; x += 2.5)
            for (double y = y0_ + 1.2; y < y1_; y += 2.5) s_.lights.push_back({Eigen::Vector3d(x, y, 0.2), 0.45});
    }

    void add(const Eigen::Vector3d& mn, const Eigen::Vector3d& mx, const Material& m) {
        s_.materials.push_back(m);
        s_.boxes.push_back({mn, mx, static_cast<int>(s_.materials.size() - 1), false});
    }

    bool clear_of_path(const Box& b) const {
        for (const auto& p : path_)
            if (footprint_distance(b, p.x(), p.y()) < o_.clearance) return false;
        return true;
    }

    bool inside_room(const Box& b) const { return b.min.x() >= x0_ && b.max.x() <= x1_ && b.min.y() >= y0_ && b.max.y() <= y1_; }

    // A flat panel on wall 0..3 (−x, +x, −y, +y): `centre` along the wall, `bottom` and `height` above
    // the floor, `thickness` into the room.
    Box wall_panel(int wall, double centre, double width, double bottom, double height, double thickness) const {
        const double wall_coord = wall == 0 ? x0_ : wall == 1 ? x1_ : wall == 2 ? y0_ : y1_;
        const double a = wall_coord, b = wall_coord + (wall % 2 == 0 ? 1.0 : -1.0) * thickness;
        Box panel;
        if (wall < 2) {
            panel.min = {std::min(a, b), centre - width / 2, floor_ - bottom - height};
            panel.max = {std::max(a, b), centre + width / 2, floor_ - bottom};
        } else {
            panel.min = {centre - width / 2, std::min(a, b), floor_ - bottom - height};
            panel.max = {centre + width / 2, std::max(a, b), floor_ - bottom};
        }
        return panel;
    }

    // The share of a 9×7 fan of rays over the central field of view that meets something within 0.5–4.3 m.
    double in_range_fraction(const Eigen::Isometry3d& pose) const {
        int in = 0, total = 0;
        for (int i = -4; i <= 4; ++i)
            for (int j = -3; j <= 3; ++j) {
                const Eigen::Vector3d dir = pose.linear() * Eigen::Vector3d(0.12 * i, 0.1 * j, 1.0).normalized();
                Hit h;
                ++total;
                if (s_.intersect(pose.translation(), dir, 1e-6, 1e3, h) && h.t > 0.5 && h.t < 4.3) ++in;
            }
        return static_cast<double>(in) / total;
    }

    const std::vector<Eigen::Isometry3d>& poses_;
    const OfficeOptions& o_;
    std::vector<Eigen::Vector2d> path_;  // the poses' floor positions
    Scene s_;
    Random r_;
    uint64_t next_seed_ = 0;
    double x0_ = 0, x1_ = 0, y0_ = 0, y1_ = 0;  // the walls
    double floor_;
    AddBox add_;  // add(), for desk_clutter
};

}  // namespace

Scene build_office(const std::vector<Eigen::Isometry3d>& poses, const OfficeOptions& options) {
    return OfficeBuilder(poses, options).build();
}

}  // namespace vobench::synth
