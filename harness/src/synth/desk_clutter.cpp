#include "synth/desk_clutter.hpp"

#include <algorithm>

namespace vobench::synth {

Material desk_material(Random& r, uint64_t seed) {
    if (r.uniform(0, 1) < 0.6) {
        const float g = static_cast<float>(r.uniform(0.7, 0.88));
        return material(r, TextureStyle::Paint, Eigen::Vector3f(g, g, g * 0.97f), Eigen::Vector3f(0.5f, 0.5f, 0.5f), seed);
    }
    return material(r, TextureStyle::Wood, colour(r, 0.45f, 0.8f), colour(r, 0.2f, 0.4f), seed);
}

void build_desk(const Box& desk, double top, double floor, Random& r, uint64_t& next_seed, const AddBox& add) {
    constexpr double kTop = 0.03, kLeg = 0.04, kInset = 0.03;
    const double underside = top + kTop;  // z down
    add({desk.min.x(), desk.min.y(), top}, {desk.max.x(), desk.max.y(), underside}, desk_material(r, ++next_seed));
    const Material frame =
        r.uniform(0, 1) < 0.6
            ? material(r, TextureStyle::Paint, Eigen::Vector3f(0.12f, 0.12f, 0.13f), Eigen::Vector3f(0.05f, 0.05f, 0.05f), ++next_seed)
            : material(r, TextureStyle::Paint, Eigen::Vector3f(0.7f, 0.7f, 0.72f), Eigen::Vector3f(0.5f, 0.5f, 0.5f), ++next_seed);
    for (int corner = 0; corner < 4; ++corner) {
        const double x = corner % 2 == 0 ? desk.min.x() + kInset : desk.max.x() - kInset - kLeg;
        const double y = corner / 2 == 0 ? desk.min.y() + kInset : desk.max.y() - kInset - kLeg;
        add({x, y, underside}, {x + kLeg, y + kLeg, floor}, frame);
    }
    if (r.uniform(0, 1) < 0.5) {
        const bool long_x = desk.max.x() - desk.min.x() >= desk.max.y() - desk.min.y();
        const bool at_max = r.uniform(0, 1) < 0.5;
        const double panel_h = r.uniform(0.3, 0.45), t = 0.02;
        if (long_x) {
            const double y = at_max ? desk.max.y() - kInset - t : desk.min.y() + kInset;
            add({desk.min.x() + kInset + kLeg, y, underside}, {desk.max.x() - kInset - kLeg, y + t, underside + panel_h}, frame);
        } else {
            const double x = at_max ? desk.max.x() - kInset - t : desk.min.x() + kInset;
            add({x, desk.min.y() + kInset + kLeg, underside}, {x + t, desk.max.y() - kInset - kLeg, underside + panel_h}, frame);
        }
    }
}

// What stands on a real office desk (z down: `top` is the desk's upper surface): a monitor at the back,
// keyboard and mouse before it, papers, books, a mug, a box, cables. Sizes of common objects; each
// one a box.
void furnish_desk(const Box& desk, double top, Random& r, uint64_t& next_seed, const AddBox& add, const Eigen::Vector2d* user) {
    const bool long_x = desk.max.x() - desk.min.x() >= desk.max.y() - desk.min.y();
    // Desk coordinates: a along the long side, b across it from the front edge.
    const double len = long_x ? desk.max.x() - desk.min.x() : desk.max.y() - desk.min.y();
    const double depth = long_x ? desk.max.y() - desk.min.y() : desk.max.x() - desk.min.x();
    bool back_at_max = r.uniform(0, 1) < 0.5;
    if (user) {  // the back is the long side away from the user
        const double across = long_x ? user->y() : user->x(),
                     middle = long_x ? (desk.min.y() + desk.max.y()) / 2 : (desk.min.x() + desk.max.x()) / 2;
        back_at_max = across < middle;
    }
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

}  // namespace vobench::synth
