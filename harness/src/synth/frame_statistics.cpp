#include "synth/frame_statistics.hpp"

#include "metrics/association.hpp"
#include "metrics/trajectory_io.hpp"
#include "synth/camera_clock.hpp"
#include "synth/depth_geometry.hpp"
#include "synth/depth_noise_persistence.hpp"
#include "synth/disparity_pattern.hpp"
#include "synth/image_spectrum.hpp"
#include "synth/photometric_gain.hpp"
#include "synth/sensor_model.hpp"
#include "synth/stamp_latency.hpp"
#include "synth/texture_edge_depth_noise.hpp"
#include "synth/track_precision.hpp"
#include "tum_lists.hpp"  // plugins/common
#include "util/files.hpp"

#include <fmt/format.h>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>

namespace vobench::synth {
namespace {

constexpr int kBorderPx = 16;
struct Band {
    double lo, hi;
    const char* name;
};
constexpr Band kRangeBands[] = {{0.0, 1.0, "0_1m"}, {1.0, 2.0, "1_2m"}, {2.0, 3.0, "2_3m"}, {3.0, 4.0, "3_4m"}, {4.0, 1e9, "4m_up"}};
constexpr Band kBrightnessBands[] = {{0, 40, "grey_0_40"}, {40, 80, "grey_40_80"}, {80, 160, "grey_80_160"}, {160, 256, "grey_160_255"}};

// Pooled ratios (numerator and denominator summed over frames) and per-frame means, in first-use order.
class Accumulator {
public:
    void ratio(const std::string& key, const std::string& label, double num, double den) {
        auto& e = entry(key, label);
        e.sum += num;
        e.count += den;
    }
    void mean(const std::string& key, const std::string& label, double value) {
        auto& e = entry(key, label);
        e.sum += value;
        e.count += 1;
    }
    void sample(const std::string& key, const std::string& label, double value) { entry(key, label).samples.push_back(value); }
    void maximum(const std::string& key, const std::string& label, double value) {
        auto& e = entry(key, label);
        e.is_max = true;
        e.sum = e.count == 0 ? value : std::max(e.sum, value);
        e.count = 1;
    }
    std::vector<Statistic> result() const {
        std::vector<Statistic> out;
        for (const auto& key : order_) {
            const Entry& e = entries_.at(key);
            double v = std::numeric_limits<double>::quiet_NaN();
            if (!e.samples.empty()) {
                auto s = e.samples;
                std::nth_element(s.begin(), s.begin() + static_cast<std::ptrdiff_t>(s.size() / 2), s.end());
                v = s[s.size() / 2];
            } else if (e.count > 0) {
                v = e.is_max ? e.sum : e.sum / e.count;
            }
            out.push_back({key, e.label, v});
        }
        return out;
    }

private:
    struct Entry {
        std::string label;
        double sum = 0, count = 0;
        bool is_max = false;
        std::vector<double> samples;  // medians
    };
    Entry& entry(const std::string& key, const std::string& label) {
        auto [it, inserted] = entries_.try_emplace(key);
        if (inserted) {
            it->second.label = label;
            order_.push_back(key);
        }
        return it->second;
    }
    std::map<std::string, Entry> entries_;
    std::vector<std::string> order_;
};

// Plane fits (fit_patch_plane) in complete patch×patch squares; the RMS residual of those that are
// planar (under 2 % of their range) by range band.
void plane_fit_noise(const cv::Mat& depth_m, int patch, const std::string& key, const std::string& label, Accumulator& acc) {
    for (int y = 0; y + patch <= depth_m.rows; y += patch)
        for (int x = 0; x + patch <= depth_m.cols; x += patch) {
            const std::optional<PatchPlane> plane = fit_patch_plane(depth_m, x, y, patch);
            if (!plane || plane->rms > 0.02 * plane->c) continue;  // incomplete, or not planar: an edge or clutter
            for (const Band& band : kRangeBands)
                if (plane->c >= band.lo && plane->c < band.hi)
                    acc.sample(key + band.name, fmt::format("{}, {}, mm", label, band.name), plane->rms * 1e3);
        }
}

// How the depth noise is shared between neighbours: the residuals of planar 32×32 plane fits at
// 1.5–3 m (divided by z², so near and far patches weigh as disparity errors do), their products with
// the residual 1, 4 and 8 px to the right and 4 px below, pooled over patches and frames and divided by
// the pooled squares. Independent noise gives 0 at every lag; a block matcher's window shares the error
// of its pixels, a smooth error field keeps it over its length.
void depth_noise_correlation(const cv::Mat& depth_m, Accumulator& acc) {
    constexpr int kPatch = 32;
    constexpr int kLags[] = {1, 4, 8};
    for (int y = 0; y + kPatch <= depth_m.rows; y += kPatch)
        for (int x = 0; x + kPatch <= depth_m.cols; x += kPatch) {
            const std::optional<cv::Mat> residuals = scaled_plane_residuals(depth_m, x, y, kPatch, 1.5, 3.0);
            if (!residuals) continue;
            const cv::Mat& r = *residuals;
            const double squares = r.dot(r);
            for (int lag : kLags) {
                const double right = r.colRange(0, kPatch - lag).dot(r.colRange(lag, kPatch));
                acc.ratio(fmt::format("depth_noise_corr.right_{}px", lag),
                          fmt::format("depth noise correlation with the pixel {} px to the right (32×32 plane fits, 1.5–3 m)", lag), right,
                          squares * (kPatch - lag) / kPatch);
            }
            const double below = r.rowRange(0, kPatch - 4).dot(r.rowRange(4, kPatch));
            acc.ratio("depth_noise_corr.below_4px", "depth noise correlation with the pixel 4 px below (32×32 plane fits, 1.5–3 m)", below,
                      squares * (kPatch - 4) / kPatch);
        }
}

void measure_depth(const cv::Mat& depth_m, const cv::Mat& grey, Accumulator& acc) {
    const int W = depth_m.cols, H = depth_m.rows;
    cv::Mat missing = depth_m <= 0;
    const double total = static_cast<double>(W) * H;
    acc.ratio("missing_depth.all", "missing depth, all pixels", cv::countNonZero(missing), total);
    cv::Mat interior = cv::Mat::zeros(H, W, CV_8U);
    interior(cv::Rect(kBorderPx, kBorderPx, W - 2 * kBorderPx, H - 2 * kBorderPx)).setTo(255);
    const double border_pixels = total - cv::countNonZero(interior);
    acc.ratio("missing_depth.border", "missing depth, 16-px border", cv::countNonZero(missing & ~interior), border_pixels);
    acc.ratio("missing_depth.interior", "missing depth, interior", cv::countNonZero(missing & interior), total - border_pixels);
    for (const Band& b : kBrightnessBands) {
        const cv::Mat in_band = (grey >= b.lo) & (grey < b.hi);
        acc.ratio(std::string("missing_depth.") + b.name, fmt::format("missing depth, grey {:.0f}–{:.0f}", b.lo, b.hi - 1),
                  cv::countNonZero(missing & in_band), cv::countNonZero(in_band));
    }
    // A hole's range: the smallest valid depth within 8 px (holes with none count as "far").
    cv::Mat filled = depth_m.clone();
    filled.setTo(1e6, missing);
    cv::erode(filled, filled, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(17, 17)));
    for (const Band& b : kRangeBands) {
        const cv::Mat in_band = (filled >= b.lo) & (filled < b.hi) & (filled < 1e5);
        acc.ratio(std::string("missing_depth.range_") + b.name, fmt::format("missing depth, range {}", b.name),
                  cv::countNonZero(missing & in_band), cv::countNonZero(in_band));
        const cv::Mat valid_in_band = (depth_m >= b.lo) & (depth_m < b.hi) & ~missing;
        acc.ratio(std::string("depth_histogram.") + b.name, fmt::format("share of valid depth, {}", b.name),
                  cv::countNonZero(valid_in_band), cv::countNonZero(~missing));
    }
    acc.ratio("missing_depth.no_valid_within_8px", "missing depth, no valid depth within 8 px", cv::countNonZero(missing & (filled >= 1e5)),
              total);
    // How the holes are cut up: a real Kinect v1 loses depth in whole patches (it matches its pattern
    // over a correlation window), a model that drops pixels one by one leaves speckle, and speckle
    // cuts dense methods off: a 5×5 filter or a pyramid level loses every pixel near a hole.
    cv::Mat near_hole;
    cv::dilate(missing, near_hole, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(5, 5)));
    acc.ratio("missing_depth.valid_near_hole", "valid depth with a hole within 2 px", cv::countNonZero(near_hole & ~missing),
              cv::countNonZero(~missing));
    cv::Mat labels, components, centroids;
    const int n = cv::connectedComponentsWithStats(missing, labels, components, centroids, 8, CV_32S);
    long small = 0;
    for (int c = 1; c < n; ++c)
        if (components.at<int>(c, cv::CC_STAT_AREA) < 50) small += components.at<int>(c, cv::CC_STAT_AREA);
    acc.ratio("missing_depth.small_holes", "missing depth in holes under 50 px", small, cv::countNonZero(missing));
    acc.mean("depth.max_m", "largest depth, m (mean over frames)", [&] {
        double mx = 0;
        cv::minMaxLoc(depth_m, nullptr, &mx);
        return mx;
    }());
    // Plane fits: 8×8 patches see the pixel noise; 32×32 patches also the part of it that is smooth
    // across the image (it bends a fitted plane within 8 px only a little, but not within 32).
    plane_fit_noise(depth_m, 8, "depth_noise_mm.", "depth noise (plane fit RMS)", acc);
    plane_fit_noise(depth_m, 32, "depth_noise_32px_mm.", "depth noise (plane fit RMS, 32×32 patches)", acc);
    depth_noise_correlation(depth_m, acc);
    if (const auto ratio = texture_edge_depth_noise_ratio(depth_m, grey))
        acc.sample("depth_noise.texture_edge_ratio", "depth noise on planes at grey-level edges ÷ away from them (median over frames)",
                   *ratio);
}

// The noise where the image is flat (smoothed gradient under 4 grey levels, grey 15–240): the mean square of
// the image minus its Gaussian blur (σ 3 px), and that residual's correlation with its right and lower
// neighbour's — near 0 for noise independent from pixel to pixel (0.05 on a noisy ramp; smooth shading
// left in the residual adds to it); demosaicing and in-camera filtering
// correlate a real camera's noise, which Immerkær's estimate (finest scale only) cannot tell.
void measure_flat_noise(const cv::Mat& grey, Accumulator& acc) {
    cv::Mat smooth, residual, slight, gx, gy, magnitude;
    cv::GaussianBlur(grey, smooth, cv::Size(0, 0), 3.0);
    residual = grey - smooth;
    cv::GaussianBlur(grey, slight, cv::Size(0, 0), 1.5);
    cv::Sobel(slight, gx, CV_32F, 1, 0);
    cv::Sobel(slight, gy, CV_32F, 0, 1);
    cv::magnitude(gx, gy, magnitude);
    double rr = 0, right = 0, below = 0;
    std::size_t n = 0;
    for (int y = 8; y + 9 < grey.rows; ++y) {
        const float* g = grey.ptr<float>(y);
        const float* m = magnitude.ptr<float>(y);
        const float* m_below = magnitude.ptr<float>(y + 1);
        const float* r = residual.ptr<float>(y);
        const float* r_below = residual.ptr<float>(y + 1);
        for (int x = 8; x + 9 < grey.cols; ++x) {
            if (m[x] > 4 || m[x + 1] > 4 || m_below[x] > 4 || g[x] < 15 || g[x] > 240) continue;
            rr += static_cast<double>(r[x]) * r[x];
            right += static_cast<double>(r[x]) * r[x + 1];
            below += static_cast<double>(r[x]) * r_below[x];
            ++n;
        }
    }
    if (n == 0) return;
    acc.ratio("image.flat_noise_ms", "noise on flat pixels, mean square about a 3-px blur, grey levels²", rr, static_cast<double>(n));
    acc.ratio("image.flat_noise_corr_right", "noise on flat pixels, correlation with the right neighbour", right, rr);
    acc.ratio("image.flat_noise_corr_below", "noise on flat pixels, correlation with the neighbour below", below, rr);
}

// The grey image's variance by octave of wavelength and its spectral exponent (image_spectrum.hpp).
void measure_image_spectrum(const cv::Mat& grey, Accumulator& acc) {
    const auto spectrum = measure_spectrum(grey, kBorderPx);
    if (!spectrum) return;
    for (int k = 0; k < ImageSpectrum::kBands; ++k) {
        const int shortest = 2 << k, longest = 4 << k;
        acc.mean(fmt::format("image.spectrum_{}_{}px", shortest, longest),
                 fmt::format("image variance at wavelengths {}–{} px, grey levels²", shortest, longest),
                 spectrum->band_variance[static_cast<std::size_t>(k)]);
    }
    acc.mean("image.spectrum_exponent", "spectral exponent α (power ∝ 1/f^α, wavelengths 8–128 px)", spectrum->exponent);
}

void measure_image(const cv::Mat& bgr, Accumulator& acc) {
    cv::Mat grey8, grey;
    cv::cvtColor(bgr, grey8, cv::COLOR_BGR2GRAY);
    grey8.convertTo(grey, CV_32F);
    // Immerkær (1996): the noise kernel cancels image structure up to second order.
    const cv::Mat N = (cv::Mat_<float>(3, 3) << 1, -2, 1, -2, 4, -2, 1, -2, 1);
    cv::Mat response;
    cv::filter2D(grey, response, CV_32F, N);
    const cv::Rect inner(1, 1, grey.cols - 2, grey.rows - 2);
    const double sigma = std::sqrt(M_PI / 2.0) / (6.0 * inner.area()) * cv::sum(cv::abs(response(inner)))[0];
    acc.mean("image.noise_sigma", "image noise σ (Immerkær), grey levels", sigma);
    cv::Mat gx, gy, magnitude;
    cv::Sobel(grey, gx, CV_32F, 1, 0);
    cv::Sobel(grey, gy, CV_32F, 0, 1);
    cv::magnitude(gx, gy, magnitude);
    acc.ratio("image.gradient_density", "share of pixels with Sobel gradient > 40", cv::countNonZero(magnitude > 40), grey.total());
    acc.mean("image.mean_gradient", "mean Sobel gradient magnitude", cv::mean(magnitude)[0]);
    std::vector<cv::KeyPoint> corners;
    cv::FAST(grey8, corners, 20, true);
    acc.mean("image.fast_corners", "FAST corners per frame (threshold 20)", static_cast<double>(corners.size()));
    cv::Mat laplacian;
    cv::Laplacian(grey, laplacian, CV_32F);
    cv::Scalar mean, stddev;
    cv::meanStdDev(laplacian, mean, stddev);
    acc.mean("image.sharpness", "sharpness (variance of the Laplacian)", stddev[0] * stddev[0]);
    // The same per unit of texture: how sharp the edges are, whatever their number.
    const double g = cv::mean(magnitude)[0];
    if (g > 0) acc.mean("image.edge_sharpness", "edge sharpness (Laplacian variance / mean gradient²)", stddev[0] * stddev[0] / (g * g));
    measure_flat_noise(grey, acc);
    measure_image_spectrum(grey, acc);
    acc.mean("image.mean_grey", "mean grey level", cv::mean(grey8)[0]);
    acc.ratio("image.saturated", "share of saturated pixels (≥ 250)", cv::countNonZero(grey8 >= 250), grey.total());
}

// How far depth edges sit from colour edges: the shift (dx, dy) of the depth-step map that best
// overlaps the colour-edge map, pooled over frames (registration error shows as a shift ≠ 0).
constexpr int kMaxShift = 4;
using ShiftScores = std::array<std::array<double, 2 * kMaxShift + 1>, 2 * kMaxShift + 1>;

void score_edge_shifts(const cv::Mat& depth_m, const cv::Mat& grey, ShiftScores& scores) {
    const int W = depth_m.cols, H = depth_m.rows;
    cv::Mat gx, gy, magnitude;
    cv::Sobel(grey, gx, CV_32F, 1, 0);
    cv::Sobel(grey, gy, CV_32F, 0, 1);
    cv::magnitude(gx, gy, magnitude);
    // Depth steps, centred: |z(u+1) − z(u−1)| or the same vertically over 10 % of z, both sides valid.
    // Collected once (inside the margin every shift can reach), then scored for each shift.
    const int m = kMaxShift + 16;
    std::vector<cv::Point> steps;
    for (int v = m; v < H - m; ++v)
        for (int u = m; u < W - m; ++u) {
            const float z = depth_m.at<float>(v, u), l = depth_m.at<float>(v, u - 1), r = depth_m.at<float>(v, u + 1),
                        t = depth_m.at<float>(v - 1, u), b = depth_m.at<float>(v + 1, u);
            if (z <= 0 || l <= 0 || r <= 0 || t <= 0 || b <= 0) continue;
            if (std::abs(r - l) > 0.1f * z || std::abs(b - t) > 0.1f * z) steps.emplace_back(u, v);
        }
    if (steps.empty()) return;
    for (int dy = -kMaxShift; dy <= kMaxShift; ++dy)
        for (int dx = -kMaxShift; dx <= kMaxShift; ++dx) {
            double hits = 0;
            for (const cv::Point& p : steps) hits += magnitude.at<float>(p.y - dy, p.x - dx) > 60;
            scores[static_cast<std::size_t>(dy + kMaxShift)][static_cast<std::size_t>(dx + kMaxShift)] +=
                hits / static_cast<double>(steps.size());
        }
}

// Throws naming `depth_path` when the depth image is not the colour image's size (not registered to it).
void require_registered(const std::filesystem::path& depth_path, const cv::Mat& depth_m, const cv::Mat& color) {
    if (depth_m.size() != color.size())
        throw std::runtime_error(depth_path.string() + ": depth is " + std::to_string(depth_m.cols) + "×" + std::to_string(depth_m.rows) +
                                 ", colour " + std::to_string(color.cols) + "×" + std::to_string(color.rows) + " (not registered)");
}

// The streams' clocks (camera_clock.hpp), stamp latencies and readouts (stamp_latency.hpp) over the
// first kLatencyFrames associated pairs. The latencies are measured from the clock's ticks, as the renderer
// exposes (effect stamp_jitter); the colour scan is also run on the stamps as they are, and the ratio
// of the two residuals says which the images follow (> 1: the clock).
void measure_timing(const std::filesystem::path& folder, const std::vector<tum::ListEntry>& rgb, const std::vector<tum::ListEntry>& depth,
                    const std::vector<metrics::Match>& pairs, const metrics::Trajectory& reference, const DepthRays& rays,
                    double depth_scale, Accumulator& acc) {
    constexpr std::size_t kLatencyFrames = 120;
    std::vector<double> rgb_stamps, depth_stamps;
    for (const auto& e : rgb) rgb_stamps.push_back(e.stamp);
    for (const auto& e : depth) depth_stamps.push_back(e.stamp);
    const CameraClock rgb_clock = fit_camera_clock(rgb_stamps), depth_clock = fit_camera_clock(depth_stamps);
    if (rgb_clock.fitted)
        acc.mean("stamps.color_jitter_ms", "colour stamps' jitter about the camera's clock, rms ms", rgb_clock.jitter_rms_s * 1e3);
    if (depth_clock.fitted)
        acc.mean("stamps.depth_jitter_ms", "depth stamps' jitter about the camera's clock, rms ms", depth_clock.jitter_rms_s * 1e3);
    LatencyFrames color, depth_stream;
    std::vector<double> color_stamps;  // as recorded, for the comparison
    for (std::size_t k = 0; k < std::min(kLatencyFrames, pairs.size()); ++k) {
        const auto color_path = folder / rgb[pairs[k].first].path, depth_path = folder / depth[pairs[k].second].path;
        const cv::Mat grey = cv::imread(color_path.string(), cv::IMREAD_GRAYSCALE);
        if (grey.empty()) throw std::runtime_error(color_path.string() + ": cannot be decoded as an image");
        const cv::Mat depth_m = read_depth_metres(depth_path, depth_scale);
        require_registered(depth_path, depth_m, grey);
        require_camera_size(depth_path, depth_m, rays.camera());
        color.stamps.push_back(rgb_clock.ticks[pairs[k].first]);
        color_stamps.push_back(rgb_stamps[pairs[k].first]);
        color.grey.push_back(grey);
        color.depth_m.push_back(depth_m);
        depth_stream.stamps.push_back(depth_clock.ticks[pairs[k].second]);
        depth_stream.depth_m.push_back(depth_m);
    }
    const LatencyEstimate c = color_latency(color, reference, rays), d = depth_latency(depth_stream, reference, rays);
    if (c.pairs > 0)
        acc.mean("stamps.color_latency_ms", "colour exposed before its clock tick, ms (best agreement with the reference)", c.latency_ms);
    if (d.pairs > 0)
        acc.mean("stamps.depth_latency_ms", "depth exposed before its clock tick, ms (best agreement with the reference)", d.latency_ms);
    if (c.pairs > 0) {
        const ReadoutEstimate r = color_readout(color, reference, rays, c.latency_ms);
        if (r.pairs > 0)
            acc.mean("stamps.color_readout_ms", "colour rows read out over, ms (rolling shutter; best agreement with the reference)",
                     r.readout_ms);
    }
    if (d.pairs > 0) {
        const ReadoutEstimate r = depth_readout(depth_stream, reference, rays, d.latency_ms);
        if (r.pairs > 0)
            acc.mean("stamps.depth_readout_ms", "depth rows read out over, ms (rolling shutter; best agreement with the reference)",
                     r.readout_ms);
    }
    if (c.pairs > 0 && rgb_clock.fitted) {
        color.stamps = color_stamps;
        const LatencyEstimate at_stamps = color_latency(color, reference, rays);
        if (at_stamps.pairs > 0 && c.cost_at_best > 0)
            acc.mean("stamps.clock_evidence",
                     "colour residual under the reference at the stamps ÷ at the clock's ticks (> 1: exposed on the clock)",
                     at_stamps.cost_at_best / c.cost_at_best);
    }
}

// How much of the projector's geometric shadow the depth shows as a hole (depth_geometry.hpp): of the
// steps whose shadow would be 4–16 px, the share that show none, and the hole's median width where it
// would be 8–40 px. The depth is registered to the colour camera, so the shadow's width is the
// parallax between the projector and the colour camera (Kinect v1: 5 cm; the projector–IR baseline,
// 7.5 cm, less the colour camera's 2.5 cm from the IR one), not the projector–IR baseline.
void measure_shadow_steps(const cv::Mat& depth_m, double fx, Accumulator& acc) {
    static const double projector_to_color_m = std::abs(kinect1().projector_in_color.x());
    for (const ShadowStep& s : projector_shadow_steps(depth_m, fx, projector_to_color_m)) {
        if (s.predicted_px >= 4 && s.predicted_px < 16)
            acc.ratio("shadow.no_hole_4_16px", "depth steps with a 4–16 px projector shadow that show no hole", s.hole_px == 0 ? 1 : 0, 1);
        if (s.predicted_px >= 8 && s.predicted_px < 40)
            acc.sample("shadow.hole_8_40px", "hole beside a depth step with an 8–40 px projector shadow, px (median)", s.hole_px);
    }
}

// Each measured frame against the one before it in rgb.txt: the tracker's precision
// (track_precision.hpp) and the colour camera's brightness change
// (photometric_gain.hpp): the median and the 90th percentile of its absolute log ratio over the
// frames, in per cent; and, when the measured frames are consecutive, the auto-exposure time constant
// that best explains them.
class FrameToFrame {
public:
    void add(const std::filesystem::path& folder, const std::vector<tum::ListEntry>& rgb, std::size_t index, const cv::Mat& grey,
             const cv::Mat& depth_m) {
        const bool follows = index == last_index_ + 1;
        GainFrame current = prepare_gain_frame(grey);
        std::optional<GainChange> change;
        if (index > 0) {
            if (!follows) {  // the frame before was not measured: read it
                const auto path = folder / rgb[index - 1].path;
                const cv::Mat before = cv::imread(path.string(), cv::IMREAD_GRAYSCALE);
                if (before.empty()) throw std::runtime_error(path.string() + ": cannot be decoded as an image");
                last_ = prepare_gain_frame(before);
            }
            if (last_.grey.size() != grey.size())
                throw std::runtime_error((folder / rgb[index].path).string() + ": not the size of the colour image before it");
            change = measure_gain_change(last_, current);
            if (change) changes_.push_back(100.0 * std::abs(change->log_ratio));
            // The same pair gives the tracker's precision (track_precision.hpp).
            if (const auto fb = forward_backward_median_px(last_.grey, grey)) precision_.push_back(*fb);
        }
        // The exposure fit needs an unbroken run: every frame's change from the one before.
        if (!exposure_.empty() && !(follows && change)) run_broken_ = true;
        if (!run_broken_)
            exposure_.push_back(
                {rgb[index].stamp, current.mean_linear_light, change ? change->log_ratio : 0.0, median_valid_depth(depth_m)});
        last_index_ = index;
        last_ = std::move(current);
    }
    void report(Accumulator& acc) const {
        if (!precision_.empty()) {
            auto sorted = precision_;
            const auto middle = sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2);
            std::nth_element(sorted.begin(), middle, sorted.end());
            acc.mean("image.track_fb_median_px",
                     "Lucas–Kanade forward–backward distance from the frame before (7×7 window, 3 levels), px (median over frames)",
                     *middle);
        }
        if (!changes_.empty()) {
            auto sorted = changes_;
            std::sort(sorted.begin(), sorted.end());
            auto at = [&](double q) { return sorted[static_cast<std::size_t>(std::round(q * static_cast<double>(sorted.size() - 1)))]; };
            acc.mean("image.gain_change_median_pct", "brightness change from the frame before, median of the absolute log ratio, %",
                     at(0.5));
            acc.mean("image.gain_change_p90_pct", "brightness change from the frame before, 90th percentile of the absolute log ratio, %",
                     at(0.9));
        }
        if (run_broken_) return;
        if (const auto fit = fit_exposure_time_constant(exposure_)) {
            acc.mean("image.exposure_time_constant_s", "auto-exposure time constant, s (best fit of the renderer's model to the gains)",
                     fit->time_constant_s);
            if (fit->rms_of_gain > 0)
                acc.mean("image.exposure_explained", "share of the gains' variance the fitted auto-exposure explains",
                         1.0 - (fit->rms * fit->rms) / (fit->rms_of_gain * fit->rms_of_gain));
            acc.mean("image.scene_luminance_log_sd", "scene brightness over the views (observed mean ÷ gain), sd of its log",
                     fit->scene_log_sd);
            if (std::isfinite(fit->scene_depth_correlation))
                acc.mean("image.scene_luminance_depth_correlation",
                         "scene brightness against the frame's median depth, correlation (< 0: far views darker)",
                         fit->scene_depth_correlation);
        }
    }

private:
    static double median_valid_depth(const cv::Mat& depth_m) {
        std::vector<float> valid;
        for (int v = 0; v < depth_m.rows; ++v)
            for (int u = 0; u < depth_m.cols; ++u)
                if (depth_m.at<float>(v, u) > 0) valid.push_back(depth_m.at<float>(v, u));
        if (valid.empty()) return std::numeric_limits<double>::quiet_NaN();
        const auto middle = valid.begin() + static_cast<std::ptrdiff_t>(valid.size() / 2);
        std::nth_element(valid.begin(), middle, valid.end());
        return *middle;
    }

    std::size_t last_index_ = static_cast<std::size_t>(-1);
    GainFrame last_;  // the frame measured last
    std::vector<double> changes_;
    std::vector<double> precision_;  // forward–backward distance, px, per measured pair
    std::vector<ExposureFrame> exposure_;
    bool run_broken_ = false;
};

}  // namespace

FolderStatistics measure_folder(const std::filesystem::path& folder, std::size_t max_frames, double depth_scale,
                                const PinholeCamera* camera) {
    const auto rgb = tum::parse_list(read_file(folder / "rgb.txt"), (folder / "rgb.txt").string());
    const auto depth = tum::parse_list(read_file(folder / "depth.txt"), (folder / "depth.txt").string());
    std::vector<double> rgb_stamps, depth_stamps;
    for (const auto& e : rgb) rgb_stamps.push_back(e.stamp);
    for (const auto& e : depth) depth_stamps.push_back(e.stamp);
    const auto pairs = metrics::associate(rgb_stamps, depth_stamps, metrics::AssociationOptions{}).matches;
    std::vector<std::size_t> chosen;
    const std::size_t n = max_frames > 0 ? std::min(max_frames, pairs.size()) : pairs.size();
    for (std::size_t k = 0; k < n; ++k) chosen.push_back(n == pairs.size() ? k : k * pairs.size() / n);
    Accumulator acc;
    ShiftScores shifts{};
    FrameToFrame frame_to_frame;
    std::optional<DepthRays> rays;
    if (camera) rays.emplace(*camera);
    for (std::size_t k : chosen) {
        const auto& m = pairs[k];
        const auto color_path = folder / rgb[m.first].path, depth_path = folder / depth[m.second].path;
        const cv::Mat bgr = cv::imread(color_path.string(), cv::IMREAD_COLOR);
        if (bgr.empty()) throw std::runtime_error(color_path.string() + ": cannot be decoded as an image");
        const cv::Mat depth_m = read_depth_metres(depth_path, depth_scale);
        require_registered(depth_path, depth_m, bgr);
        cv::Mat grey;
        cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
        measure_depth(depth_m, grey, acc);
        score_edge_shifts(depth_m, grey, shifts);
        measure_image(bgr, acc);
        frame_to_frame.add(folder, rgb, m.first, grey, depth_m);
        if (rays) {
            require_camera_size(depth_path, depth_m, *camera);
            const IcpConditioning c = icp_conditioning(depth_m, *rays);
            acc.sample("geometry.icp_condition", "ICP conditioning λmax/λmin (Gelfand 2003; median)", c.condition);
            acc.sample("geometry.icp_weakest", "ICP weakest constraint λmin, m² (median)", c.weakest);
            measure_shadow_steps(depth_m, camera->fx, acc);
        }
        const double offset_ms = std::abs(rgb_stamps[m.first] - depth_stamps[m.second]) * 1e3;
        acc.mean("stamps.offset_mean_ms", "colour–depth stamp offset, mean |Δt|, ms", offset_ms);
        acc.maximum("stamps.offset_max_ms", "colour–depth stamp offset, largest |Δt|, ms", offset_ms);
    }
    frame_to_frame.report(acc);
    // The depth image's content sits (dx, dy) px from the colour image's: colour edge at depth edge − shift.
    int best_x = 0, best_y = 0;
    for (int dy = -kMaxShift; dy <= kMaxShift; ++dy)
        for (int dx = -kMaxShift; dx <= kMaxShift; ++dx)
            if (shifts[static_cast<std::size_t>(dy + kMaxShift)][static_cast<std::size_t>(dx + kMaxShift)] >
                shifts[static_cast<std::size_t>(best_y + kMaxShift)][static_cast<std::size_t>(best_x + kMaxShift)]) {
                best_x = dx;
                best_y = dy;
            }
    if (!chosen.empty()) {
        acc.mean("registration.edge_shift_x_px", "depth edges right of colour edges, px (best overlap)", best_x);
        acc.mean("registration.edge_shift_y_px", "depth edges below colour edges, px (best overlap)", best_y);
    }
    // Every depth image in the list's order (consecutive frames), not only the associated pairs.
    std::vector<std::filesystem::path> depth_paths;
    for (const auto& e : depth) depth_paths.push_back(folder / e.path);
    for (const NoisePersistence& p : same_pixel_noise_correlation(depth_paths, {1, 4}, max_frames, depth_scale))
        if (p.patches > 0)
            acc.mean(fmt::format("depth_noise_persistence.gap_{}", p.gap),
                     fmt::format("depth noise correlation with the same pixel {} frame{} later (32×32 plane fits, 0.8–3 m)", p.gap,
                                 p.gap == 1 ? "" : "s"),
                     p.correlation);
    if (rays && std::filesystem::exists(folder / "groundtruth.txt")) {
        const auto reference = metrics::read_trajectory(folder / "groundtruth.txt").poses;
        measure_timing(folder, rgb, depth, pairs, reference, *rays, depth_scale, acc);
        // The unit's fixed disparity pattern, from the first frames (all of them are held at once).
        constexpr std::size_t kPatternFrames = 200;
        const DisparityPattern pattern = estimate_disparity_pattern(
            read_depth_sequence(folder, *camera, depth_scale, max_frames > 0 ? std::min(max_frames, kPatternFrames) : kPatternFrames),
            *rays, kinect1().depth_latency_s, DistortionFitOptions{}.focal_baseline_px_m);
        if (std::isfinite(pattern.rms_px)) {
            acc.mean("reference.disparity_pattern_px", "fixed disparity pattern beyond the low-order field, RMS over 16-px cells, px",
                     pattern.rms_px);
            acc.mean("reference.disparity_pattern_halves", "fixed disparity pattern alike in the frames' two halves (correlation)",
                     pattern.halves_correlation);
            acc.mean("reference.disparity_pattern_64px", "fixed disparity pattern's correlation with itself 64 px away",
                     pattern.correlation_64px);
        }
        for (const auto& g : reference_consistency(depth_stamps, depth_paths, reference, *rays, {1, 4, 16}, max_frames, depth_scale)) {
            if (g.pairs == 0) continue;
            acc.mean(
                fmt::format("reference.depth_residual_pct.gap_{}", g.gap),
                fmt::format("depth residual under the reference's motion, gap {} frame{}, % of z (median)", g.gap, g.gap == 1 ? "" : "s"),
                g.median_pct);
            if (g.gap != 1) continue;
            // From one frame to the next the reference's error is least: what is left is how the depth of a
            // surface point changes from frame to frame, by range.
            static constexpr const char* kBands[] = {"0_1m", "1_2m", "2_3m", "3m_up"};
            for (std::size_t b = 0; b < g.by_range_pct.size(); ++b)
                if (std::isfinite(g.by_range_pct[b]))
                    acc.mean(
                        fmt::format("reference.depth_residual_pct.gap_1.{}", kBands[b]),
                        fmt::format("depth residual under the reference's motion, gap 1 frame, {}, % of z (median of points)", kBands[b]),
                        g.by_range_pct[b]);
        }
    }
    return {folder, chosen.size(), acc.result()};
}

}  // namespace vobench::synth
