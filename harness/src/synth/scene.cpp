#include "synth/scene.hpp"

#include "synth/random_field.hpp"
#include "synth/ray_index.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

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
    if (index_) return index_->any(from, delta / length, 1e-4, length - 1e-3);
    Hit h;
    return intersect(from, delta / length, 1e-4, length - 1e-3, h);
}

Eigen::Vector3f Scene::shade(const Hit& hit, const Eigen::Vector3d& view_dir, double footprint, bool highlights) const {
    const Material& m = materials[static_cast<std::size_t>(hit.material)];
    const Eigen::Vector3f a = albedo(m, hit.u, hit.v, footprint);
    // Ambient plus diffuse point lights under the ceiling (no shadows: soft office lighting).
    double light = 0.12 + m.emission, specular = 0;
    for (const PointLight& l : lights) {
        const Eigen::Vector3d to = l.position - hit.point;
        const double d2 = to.squaredNorm();
        const Eigen::Vector3d l_dir = to / std::sqrt(d2);
        const double falloff = l.power / (1.0 + 0.3 * d2);
        light += falloff * std::max(0.0, hit.normal.dot(l_dir));
        if (highlights && m.gloss > 0) {
            // Blinn–Phong (Blinn 1977): the half vector between light and eye, shininess 60.
            const Eigen::Vector3d half = (l_dir - view_dir).normalized();
            specular += falloff * std::pow(std::max(0.0, hit.normal.dot(half)), 60.0);
        }
    }
    return a * static_cast<float>(light) + Eigen::Vector3f::Constant(static_cast<float>(3.0 * m.gloss * specular));
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

// The colour of a manufactured object: a hue times a luminance drawn log-uniformly over 0.03–0.9, so
// that black, mid and white things are equally common, as real surfaces' reflectances spread over
// decades (Attewell & Baddeley 2007) — not all mid-grey pastels.
Eigen::Vector3f object_colour(Random& r) {
    Eigen::Vector3f hue = colour(r, 0.15f, 1.0f);
    hue /= hue.maxCoeff();
    return hue * static_cast<float>(std::exp(r.uniform(std::log(0.03), std::log(0.9))));
}

// Distance in the floor plane from (x, y) to the box's footprint.
double footprint_distance(const Box& b, double x, double y) {
    const double dx = std::max({b.min.x() - x, 0.0, x - b.max.x()});
    const double dy = std::max({b.min.y() - y, 0.0, y - b.max.y()});
    return std::hypot(dx, dy);
}

// Office desks: white or grey laminate (most of TUM's) or wood.
Material desk_material(Random& r, uint64_t seed) {
    if (r.uniform(0, 1) < 0.6) {
        const float g = static_cast<float>(r.uniform(0.7, 0.88));
        return material(r, TextureStyle::Paint, Eigen::Vector3f(g, g, g * 0.97f), Eigen::Vector3f(0.5f, 0.5f, 0.5f), seed);
    }
    return material(r, TextureStyle::Wood, colour(r, 0.45f, 0.8f), colour(r, 0.2f, 0.4f), seed);
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

// What stands on a real office desk (z down: `top` is the desk's upper surface): a monitor at the back,
// keyboard and mouse before it, papers, books, a mug, a box, cables. Sizes of common objects; each
// one a box.
template <typename Add>
void furnish_desk(const Box& desk, double top, Random& r, uint64_t& next_seed, const Add& add) {
    const bool long_x = desk.max.x() - desk.min.x() >= desk.max.y() - desk.min.y();
    // Desk coordinates: a along the long side, b across it from the front edge.
    const double len = long_x ? desk.max.x() - desk.min.x() : desk.max.y() - desk.min.y();
    const double depth = long_x ? desk.max.y() - desk.min.y() : desk.max.x() - desk.min.x();
    const bool back_at_max = r.uniform(0, 1) < 0.5;
    auto place = [&](double a0, double a1, double b0, double b1, double h, const Material& m) {
        const double lo_b = back_at_max ? b0 : depth - b1, hi_b = back_at_max ? b1 : depth - b0;
        Eigen::Vector3d mn, mx;
        if (long_x) {
            mn = {desk.min.x() + a0, desk.min.y() + lo_b, top - h};
            mx = {desk.min.x() + a1, desk.min.y() + hi_b, top};
        } else {
            mn = {desk.min.x() + lo_b, desk.min.y() + a0, top - h};
            mx = {desk.min.x() + hi_b, desk.min.y() + a1, top};
        }
        add(mn, mx, m);
    };
    auto mat = [&](TextureStyle style, Eigen::Vector3f base, Eigen::Vector3f accent, float gloss = 0.0f) {
        Material m = material(r, style, base, accent, ++next_seed);
        m.gloss = gloss;
        return m;
    };
    auto spot = [&](double size, double room) { return r.uniform(0.0, std::max(0.01, room - size)); };
    const Eigen::Vector3f black(0.03f, 0.03f, 0.035f), white(0.85f, 0.85f, 0.83f);
    // Monitor: foot, neck and a screen standing on them, near the back edge.
    const double mon_w = r.uniform(0.45, 0.6), mon_h = r.uniform(0.3, 0.38);
    const double mon_a = r.uniform(0.1, std::max(0.11, len - mon_w - 0.1)), mon_b = depth - r.uniform(0.12, 0.2);
    const double mid = mon_a + mon_w / 2;
    place(mid - 0.1, mid + 0.1, mon_b - 0.1, mon_b + 0.08, 0.015, mat(TextureStyle::Paint, black * 3, black));
    place(mid - 0.03, mid + 0.03, mon_b + 0.03, mon_b + 0.06, 0.06, mat(TextureStyle::Paint, black * 3, black));
    place(mon_a, mon_a + mon_w, mon_b - 0.01, mon_b + 0.02, 0.06 + mon_h, mat(TextureStyle::Screen, black, black, 0.6f));
    // Keyboard and mouse in front of it.
    const double kb_a = std::clamp(mid - 0.23 + r.uniform(-0.1, 0.1), 0.02, std::max(0.02, len - 0.48));
    const double kb_b = r.uniform(0.08, std::max(0.09, mon_b - 0.35));
    const bool white_keys = r.uniform(0, 1) < 0.4;
    place(kb_a, kb_a + 0.46, kb_b, kb_b + 0.16, 0.025,
          mat(TextureStyle::Keys, white_keys ? white : Eigen::Vector3f(0.08f, 0.08f, 0.09f),
              white_keys ? Eigen::Vector3f(0.2f, 0.2f, 0.2f) : Eigen::Vector3f(0.7f, 0.7f, 0.7f)));
    if (kb_a + 0.6 < len)
        place(kb_a + 0.52, kb_a + 0.58, kb_b + 0.02, kb_b + 0.12, 0.03, mat(TextureStyle::Paint, colour(r, 0.05f, 0.8f), black, 0.3f));
    // Papers: a few sheets in a spread, each a millimetre above the last.
    const int sheets = 2 + r.pick(6);
    for (int k = 0; k < sheets; ++k) {
        const bool portrait = r.uniform(0, 1) < 0.5;
        const double w = portrait ? 0.21 : 0.297, d = portrait ? 0.297 : 0.21;
        const double a = spot(w, len), b = spot(d, depth * 0.7);
        place(a, a + w, b, b + d, 0.001 * (k + 1),
              mat(TextureStyle::Pages, Eigen::Vector3f(0.92f, 0.92f, 0.9f), Eigen::Vector3f(0.85f, 0.85f, 0.83f)));
    }
    // A stack of books or binders, a mug, a small box, cables to the monitor.
    const int books = r.pick(4);
    double stack = 0;
    const double book_a = spot(0.3, len), book_b = spot(0.3, depth);
    for (int k = 0; k < books; ++k) {
        const double t = r.uniform(0.02, 0.05);
        place(book_a + r.uniform(0, 0.03), book_a + r.uniform(0.17, 0.26), book_b, book_b + r.uniform(0.22, 0.3), stack + t,
              mat(TextureStyle::Photo, object_colour(r), object_colour(r)));
        stack += t;
    }
    const double mug_a = spot(0.085, len), mug_b = spot(0.085, depth);
    place(mug_a, mug_a + 0.085, mug_b, mug_b + 0.085, 0.1, mat(TextureStyle::Paint, object_colour(r), object_colour(r), 0.4f));
    if (r.uniform(0, 1) < 0.6) {
        const double w = r.uniform(0.12, 0.3), d = r.uniform(0.1, 0.25);
        const double a = spot(w, len), b = spot(d, depth);
        place(a, a + w, b, b + d, r.uniform(0.05, 0.2), mat(TextureStyle::Photo, object_colour(r), object_colour(r)));
    }
    // The small things that cover a used desk (pens, phones, staplers, cases, tins, bottles, notes):
    // boxes of 2–15 cm in strong colours and prints, a dozen or more; they may touch and stack.
    const int small = 15 + r.pick(20);
    for (int k = 0; k < small; ++k) {
        const double w = r.uniform(0.02, 0.15), d = r.uniform(0.02, 0.15), h = r.uniform(0.01, 0.15);
        const double a = spot(w, len), b = spot(d, depth);
        const double pick = r.uniform(0, 1);
        const TextureStyle style = pick < 0.45 ? TextureStyle::Photo : pick < 0.7 ? TextureStyle::Poster : TextureStyle::Paint;
        place(a, a + w, b, b + d, h, mat(style, object_colour(r), object_colour(r), r.uniform(0, 1) < 0.3 ? 0.4f : 0.0f));
    }
    for (int k = 0; k < 2; ++k) {
        const double ca = r.uniform(0.05, std::max(0.06, len - 0.05));
        place(ca, ca + 0.008, r.uniform(0.05, 0.3), mon_b, 0.008, mat(TextureStyle::Paint, black * 2, black));
    }
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

    // Windows: bright (emissive) panes with mullions; the IR sees through glass (no depth there).
    const int windows = r.pick(3);
    for (int k = 0; k < windows; ++k) {
        const int wall = r.pick(4);
        const bool along_x = wall >= 2;
        const double length = along_x ? x1 - x0 : y1 - y0, w = r.uniform(0.9, 1.6);
        if (length < w + 0.4) continue;
        const double centre = (along_x ? x0 : y0) + r.uniform(0.2 + w / 2, length - 0.2 - w / 2);
        const double wall_coord = wall == 0 ? x0 : wall == 1 ? x1 : wall == 2 ? y0 : y1;
        const double inward = (wall % 2 == 0) ? 1.0 : -1.0, a = wall_coord, b = wall_coord + inward * 0.015;
        const double bottom = r.uniform(0.8, 1.0), h = r.uniform(1.0, 1.4);
        Eigen::Vector3d mn, mx;
        if (!along_x) {
            mn = {std::min(a, b), centre - w / 2, floor - bottom - h};
            mx = {std::max(a, b), centre + w / 2, floor - bottom};
        } else {
            mn = {centre - w / 2, std::min(a, b), floor - bottom - h};
            mx = {centre + w / 2, std::max(a, b), floor - bottom};
        }
        Material glass =
            material(r, TextureStyle::Tiles, Eigen::Vector3f(0.8f, 0.85f, 0.9f), Eigen::Vector3f(0.1f, 0.1f, 0.1f), ++next_seed);
        glass.scale = static_cast<float>(w);  // one mullion cross per pane
        glass.emission = static_cast<float>(r.uniform(1.5, 3.0));
        add(mn, mx, glass);
    }

    // Desks where the cameras look down: every 10th pose's central ray, met at desk height 0.3–2.2 m
    // away (horizontally), gets a desk under that point, clear of the path by 0.25 m.
    for (std::size_t k = 0; k < poses.size(); k += 10) {
        const Eigen::Vector3d at = poses[k].translation(), dir = poses[k].linear().col(2);
        const double desk_h = r.uniform(0.72, 0.76), top = floor - desk_h;
        if (dir.z() < 0.2 || at.z() >= top) continue;  // looking level or up, or below desk height
        const Eigen::Vector3d hit = at + dir * ((top - at.z()) / dir.z());
        const double reach = std::hypot(hit.x() - at.x(), hit.y() - at.y());
        if (reach < 0.3 || reach > 2.2) continue;
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
        add(desk.min, desk.max, desk_material(r, ++next_seed));
        furnish_desk(desk, top, r, next_seed, add);
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
        if (overlaps_any(s, b)) continue;
        TextureStyle style = kind == 0 || kind == 1 ? TextureStyle::Wood
                             : kind == 4            ? TextureStyle::Tiles
                             : kind == 2            ? TextureStyle::Tiles
                                                    : TextureStyle::Carpet;
        add(b.min, b.max, material(r, style, colour(r, 0.4f, 0.75f), colour(r, 0.2f, 0.45f), ++next_seed));
        if (kind == 0) furnish_desk(b, floor - h, r, next_seed, add);
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
