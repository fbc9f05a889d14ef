#include "synth/scene.hpp"

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

}  // namespace vobench::synth
