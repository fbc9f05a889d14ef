#include "lk_tracker.hpp"

#include <opencv2/core/hal/intrin.hpp>
#include <opencv2/video/tracking.hpp>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <stdexcept>
#include <string>

namespace put_vo {
namespace {

constexpr int kLanes = 8;                     // int16 lanes of a 128-bit register: one group of window pixels
constexpr int kWeightBits = 14;               // bilinear weights in units of 2^-14 (OpenCV's W_BITS)
constexpr int kValueShift = kWeightBits - 5;  // image values kept ×32 (5 fractional bits), as OpenCV does
constexpr float kScale = 1.f / (1 << 20);     // undoes the ×32 of values and derivatives in A and b (FLT_SCALE)

struct Weights {
    cv::v_int16x8 top, bottom;  // (w00, w01) and (w10, w11) repeated: v_dotprod over zipped pixel pairs
};

// Fixed-point bilinear weights of the fractional offset (a, b), rounded as OpenCV rounds them.
Weights bilinear(float a, float b) {
    const int w00 = cvRound((1.f - a) * (1.f - b) * (1 << kWeightBits));
    const int w01 = cvRound(a * (1.f - b) * (1 << kWeightBits));
    const int w10 = cvRound((1.f - a) * b * (1 << kWeightBits));
    const int w11 = (1 << kWeightBits) - w00 - w01 - w10;
    return {cv::v_reinterpret_as_s16(cv::v_setall_s32(w00 | (w01 << 16))), cv::v_reinterpret_as_s16(cv::v_setall_s32(w10 | (w11 << 16)))};
}

// Σ weights × (a, b | c, d) per lane, rounded and shifted down: a, b the top row's pixel and its
// right neighbour, c, d the bottom row's.
cv::v_int16x8 blend(const cv::v_int16x8& a, const cv::v_int16x8& b, const cv::v_int16x8& c, const cv::v_int16x8& d, const Weights& w,
                    int shift) {
    cv::v_int16x8 ab_low, ab_high, cd_low, cd_high;
    cv::v_zip(a, b, ab_low, ab_high);
    cv::v_zip(c, d, cd_low, cd_high);
    const cv::v_int32x4 half = cv::v_setall_s32(1 << (shift - 1));
    const cv::v_int32x4 low = (cv::v_dotprod(ab_low, w.top) + cv::v_dotprod(cd_low, w.bottom) + half) >> shift;
    const cv::v_int32x4 high = (cv::v_dotprod(ab_high, w.top) + cv::v_dotprod(cd_high, w.bottom) + half) >> shift;
    return cv::v_pack(low, high);
}

// Eight image values (×32) from `p` on, bilinear between this row and the next.
cv::v_int16x8 image_values(const uchar* p, std::size_t step, const Weights& w) {
    auto load = [](const uchar* q) { return cv::v_reinterpret_as_s16(cv::v_load_expand(q)); };
    return blend(load(p), load(p + 1), load(p + step), load(p + step + 1), w, kValueShift);
}

// Eight Scharr derivatives (x and y) from `p` on (interleaved pairs), bilinear.
void derivatives(const short* p, std::size_t step, const Weights& w, cv::v_int16x8& dx, cv::v_int16x8& dy) {
    cv::v_int16x8 ax, ay, bx, by, cx, cy, ex, ey;
    cv::v_load_deinterleave(p, ax, ay);
    cv::v_load_deinterleave(p + 2, bx, by);
    cv::v_load_deinterleave(p + step, cx, cy);
    cv::v_load_deinterleave(p + step + 2, ex, ey);
    dx = blend(ax, bx, cx, ex, w, kWeightBits);
    dy = blend(ay, by, cy, ey, w, kWeightBits);
}

// The lane-wise products a·b, each converted to float (exact integer products, rounded once).
void products(const cv::v_int16x8& a, const cv::v_int16x8& b, float* out) {
    cv::v_int32x4 low, high;
    cv::v_mul_expand(a, b, low, high);
    cv::v_store(out, cv::v_cvt_f32(low));
    cv::v_store(out + 4, cv::v_cvt_f32(high));
}

bool outside(cv::Point corner, cv::Size window, const cv::Mat& image) {
    return corner.x < -window.width || corner.x >= image.cols || corner.y < -window.height || corner.y >= image.rows;
}

void check_level(const cv::Mat& m, int type, cv::Size size, int border, const char* what, int level) {
    cv::Size whole;
    cv::Point offset;
    const std::string where = std::string("track_lk: ") + what + " pyramid level " + std::to_string(level);
    if (m.type() != type || m.size() != size) throw std::invalid_argument(where + " has the wrong type or size");
    m.locateROI(whole, offset);
    if (offset.x < border || offset.y < border || offset.x + m.cols + border > whole.width || offset.y + m.rows + border > whole.height)
        throw std::invalid_argument(where + " has a border under " + std::to_string(border) + " px (build it with lk_pyramid_border)");
}

// One point's window, row by row: the template's values and derivatives (lanes past the window unused).
struct Template {
    std::vector<cv::v_int16x8> value, dx, dy;
};

// One point through the levels, coarse to fine; returns the position, clears `ok` where it fails.
cv::Point2f track_point(const std::vector<cv::Mat>& previous, const std::vector<cv::Mat>& next, cv::Point2f from, cv::Point2f start,
                        int levels, const LkOptions& o, Template& t, unsigned char& ok) {
    const cv::Size win = o.window;
    const cv::Point2f half_window((win.width - 1) * 0.5f, (win.height - 1) * 0.5f);
    const int iterations = std::clamp(o.max_iterations, 0, 100);
    const double epsilon = std::clamp(o.epsilon, 0.0, 10.0);
    const double epsilon2 = epsilon * epsilon;
    const float min_eigen_threshold = static_cast<float>(o.min_eigen);
    alignas(16) float p1[kLanes], p2[kLanes], p3[kLanes];
    // Integer sums: |value − value| ≤ 255·32 and |Scharr derivative| ≤ 16·255, so a window of at most
    // 64 products stays under 2^31 (64 · 8160 · 4080 ≈ 2.13e9).
    const bool integer = o.integer_sums && win.width * win.height <= 64;
    alignas(16) short lane_mask[kLanes];
    for (int k = 0; k < kLanes; ++k) lane_mask[k] = static_cast<short>(k < win.width ? -1 : 0);
    const cv::v_int16x8 in_window = cv::v_load(lane_mask);
    cv::Point2f result;  // this level's position; the next finer level starts at twice it
    for (int level = levels; level >= 0; --level) {
        const cv::Mat& I = previous[2 * level];
        const cv::Mat& dI = previous[2 * level + 1];
        const cv::Mat& J = next[2 * level];
        const float scale = 1.f / static_cast<float>(1 << level);
        result = level == levels ? start * scale : result * 2.f;
        const cv::Point2f corner = from * scale - half_window;
        const cv::Point icorner(cvFloor(corner.x), cvFloor(corner.y));
        if (outside(icorner, win, dI)) {
            if (level == 0) ok = 0;
            continue;
        }
        // The template and its structure tensor A = Σ [Ix² IxIy; IxIy Iy²].
        const Weights wi = bilinear(corner.x - static_cast<float>(icorner.x), corner.y - static_cast<float>(icorner.y));
        float a11 = 0, a12 = 0, a22 = 0;
        cv::v_int32x4 s11 = cv::v_setzero_s32(), s12 = s11, s22 = s11;
        for (int y = 0; y < win.height; ++y) {
            const uchar* src = I.data + static_cast<std::ptrdiff_t>(icorner.y + y) * static_cast<std::ptrdiff_t>(I.step) + icorner.x;
            const short* dsrc = reinterpret_cast<const short*>(dI.data + static_cast<std::ptrdiff_t>(icorner.y + y) *
                                                                             static_cast<std::ptrdiff_t>(dI.step)) +
                                2 * icorner.x;
            t.value[static_cast<std::size_t>(y)] = image_values(src, I.step, wi);
            cv::v_int16x8& dx = t.dx[static_cast<std::size_t>(y)];
            cv::v_int16x8& dy = t.dy[static_cast<std::size_t>(y)];
            derivatives(dsrc, dI.step1(), wi, dx, dy);
            if (integer) {  // lanes past the window zeroed, so that they add nothing here or below
                dx = dx & in_window;
                dy = dy & in_window;
                s11 += cv::v_dotprod(dx, dx);
                s12 += cv::v_dotprod(dx, dy);
                s22 += cv::v_dotprod(dy, dy);
                continue;
            }
            products(dx, dx, p1);
            products(dx, dy, p2);
            products(dy, dy, p3);
            for (int k = 0; k < win.width; ++k) {  // interleaved as OpenCV interleaves them
                a11 += p1[k];
                a12 += p2[k];
                a22 += p3[k];
            }
        }
        if (integer) {
            a11 = static_cast<float>(cv::v_reduce_sum(s11));
            a12 = static_cast<float>(cv::v_reduce_sum(s12));
            a22 = static_cast<float>(cv::v_reduce_sum(s22));
        }
        const float A11 = a11 * kScale, A12 = a12 * kScale, A22 = a22 * kScale;
        float D = A11 * A22 - A12 * A12;
        const float min_eigen =
            (A22 + A11 - std::sqrt((A11 - A22) * (A11 - A22) + 4.f * A12 * A12)) / static_cast<float>(2 * win.width * win.height);
        if (min_eigen < min_eigen_threshold || D < FLT_EPSILON) {  // too flat to track
            if (level == 0) ok = 0;
            continue;
        }
        D = 1.f / D;
        // Gauss–Newton steps: b = Σ (J − I)·∇I over the window, δ = −A⁻¹ b.
        cv::Point2f p = result - half_window, previous_step;
        for (int j = 0; j < iterations; ++j) {
            const cv::Point ip(cvFloor(p.x), cvFloor(p.y));
            if (outside(ip, win, J)) {
                if (level == 0) ok = 0;
                break;
            }
            const Weights wj = bilinear(p.x - static_cast<float>(ip.x), p.y - static_cast<float>(ip.y));
            float b1 = 0, b2 = 0;
            cv::v_int32x4 s1 = cv::v_setzero_s32(), s2 = s1;
            for (int y = 0; y < win.height; ++y) {
                const uchar* jp = J.data + static_cast<std::ptrdiff_t>(ip.y + y) * static_cast<std::ptrdiff_t>(J.step) + ip.x;
                const cv::v_int16x8 diff = image_values(jp, J.step, wj) - t.value[static_cast<std::size_t>(y)];
                if (integer) {
                    s1 += cv::v_dotprod(diff, t.dx[static_cast<std::size_t>(y)]);
                    s2 += cv::v_dotprod(diff, t.dy[static_cast<std::size_t>(y)]);
                    continue;
                }
                products(diff, t.dx[static_cast<std::size_t>(y)], p1);
                products(diff, t.dy[static_cast<std::size_t>(y)], p2);
                for (int k = 0; k < win.width; ++k) {
                    b1 += p1[k];
                    b2 += p2[k];
                }
            }
            if (integer) {
                b1 = static_cast<float>(cv::v_reduce_sum(s1));
                b2 = static_cast<float>(cv::v_reduce_sum(s2));
            }
            b1 *= kScale;
            b2 *= kScale;
            const cv::Point2f step((A12 * b2 - A22 * b1) * D, (A12 * b1 - A11 * b2) * D);
            p += step;
            result = p + half_window;
            if (step.ddot(step) <= epsilon2) break;
            // Oscillating between two positions: take the middle (OpenCV's rule, its double constant).
            if (j > 0 && std::abs(step.x + previous_step.x) < 0.01 && std::abs(step.y + previous_step.y) < 0.01) {
                result -= step * 0.5f;
                break;
            }
            previous_step = step;
        }
    }
    // OpenCV, asked for its error measure (put_vo always was), drops a track whose end lies out of reach.
    if (ok && outside(cv::Point(cvFloor(result.x - half_window.x), cvFloor(result.y - half_window.y)), win, next[0])) ok = 0;
    return result;
}

}  // namespace

int lk_pyramid_border(cv::Size window) { return std::max({kLanes, window.width, window.height}) + 1; }

void track_lk(const std::vector<cv::Mat>& previous, const std::vector<cv::Mat>& next, const std::vector<cv::Point2f>& from,
              std::vector<cv::Point2f>& to, std::vector<unsigned char>& status, const LkOptions& o) {
    const cv::Size win = o.window;
    if (win.width < 3 || win.height < 3) throw std::invalid_argument("track_lk: the window must be at least 3×3 px");
    if (o.use_initial_flow && to.size() != from.size())
        throw std::invalid_argument("track_lk: use_initial_flow needs a start for every point");
    if (previous.size() < 2 || next.size() < 2) throw std::invalid_argument("track_lk: empty pyramid");
    if (win.width >= kLanes) {  // OpenCV's own SIMD loop covers the rows: nothing to gain
        std::vector<float> error;
        const cv::TermCriteria criteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, o.max_iterations, o.epsilon);
        cv::calcOpticalFlowPyrLK(previous, next, from, to, status, error, win, o.levels, criteria,
                                 o.use_initial_flow ? cv::OPTFLOW_USE_INITIAL_FLOW : 0, o.min_eigen);
        return;
    }
    // As OpenCV: a pyramid with fewer levels (a small image) caps the levels used.
    const int levels = std::min({o.levels, static_cast<int>(previous.size() / 2) - 1, static_cast<int>(next.size() / 2) - 1});
    const int border = lk_pyramid_border(win);
    for (int l = 0; l <= levels; ++l) {
        const cv::Size size = previous[2 * l].size();
        check_level(previous[2 * l], CV_8UC1, size, border, "previous image", l);
        check_level(previous[2 * l + 1], CV_16SC2, size, border, "previous derivative", l);
        check_level(next[2 * l], CV_8UC1, size, border, "next image", l);
    }
    to.resize(from.size());
    status.assign(from.size(), 1);
    Template t;
    t.value.resize(static_cast<std::size_t>(win.height));
    t.dx.resize(t.value.size());
    t.dy.resize(t.value.size());
    for (std::size_t i = 0; i < from.size(); ++i)
        to[i] = track_point(previous, next, from[i], o.use_initial_flow ? to[i] : from[i], levels, o, t, status[i]);
}

}  // namespace put_vo
