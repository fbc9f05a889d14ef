#include "synth/renderer.hpp"

#include "synth/random_field.hpp"
#include "synth/ray_index.hpp"

#include "depth_registration.hpp"  // plugins/common

#include <tbb/parallel_for.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace vobench::synth {
namespace {

// sRGB encoding (IEC 61966-2-1) as a 4096-entry table over [0, 1] linear: 8-bit output cannot tell.
// The tone curve's fixed point: the real fr1 frames' mean grey level (136 of 255, vobench synth stats),
// which auto-exposure already brings the rendered frames to, so the stretch leaves the mean in place.
constexpr double kTonePivot = 136.0 / 255.0;

// Built once, before main: the tone pass reads it for every channel of every pixel.
const std::vector<double> srgb_table = [] {
    std::vector<double> t(4097);
    for (std::size_t i = 0; i < t.size(); ++i) {
        const double l = static_cast<double>(i) / 4096.0;
        t[i] = l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055;
    }
    return t;
}();

double srgb(double linear) { return srgb_table[static_cast<std::size_t>(std::clamp(linear, 0.0, 1.0) * 4096.0 + 0.5)]; }

// The motion blur's samples along a streak: at most this many, at the midpoints (k + ½) / n of n
// equal parts of its length — the midpoint rule for the exposure's average, which with the samples
// interpolated between pixels is exact for a streak under a pixel — tabulated once (each entry is
// the quotient the division gives; a division per sample was a fifth of the blur's time).
constexpr int kMaxBlurSamples = 24;
struct BlurFractions {
    double table[kMaxBlurSamples + 1][kMaxBlurSamples] = {};
    BlurFractions() {
        for (int n = 2; n <= kMaxBlurSamples; ++n)
            for (int k = 0; k < n; ++k) table[n][k] = (k + 0.5) / n;
    }
    const double* operator[](int n) const { return table[n]; }
};
const BlurFractions blur_fractions;

// cv::GaussianBlur over the whole image, on every core: OpenCV's filter runs on one thread, but a
// filter on a band of rows (a view into the image) reads the rows above and below the band from the
// image itself and extrapolates (BORDER_REFLECT) only at the image's own edges, so the bands together
// are the very image one call gives (1920×1080: 17.5 → 11.8 ms on 2 cores).
cv::Mat gaussian_blur_in_bands(const cv::Mat& image, double sigma) {
    constexpr int kBands = 16;
    cv::Mat out(image.size(), image.type());
    cv::parallel_for_(cv::Range(0, kBands), [&](const cv::Range& bands) {
        for (int b = bands.start; b < bands.end; ++b) {
            const int top = b * image.rows / kBands, bottom = (b + 1) * image.rows / kBands;
            if (bottom <= top) continue;
            const cv::Rect band(0, top, image.cols, bottom - top);
            cv::Mat target = out(band);
            cv::GaussianBlur(image(band), target, cv::Size(0, 0), sigma, sigma, cv::BORDER_REFLECT);
        }
    });
    return out;
}

}  // namespace

Renderer::RayMap Renderer::make_ray_map(const PinholeCamera& c) {
    RayMap map;
    map.width = c.width;
    map.height = c.height;
    const std::size_t W = static_cast<std::size_t>(std::max(c.width, 0));
    map.dirs.resize(W * static_cast<std::size_t>(std::max(c.height, 0)));
    map.on_plane.resize(map.dirs.size());
    const cv::Matx33d K(c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1);
    const cv::Mat distortion(1, 8, CV_64F, const_cast<double*>(c.distortion.data()));
    // undistortPoints iterates on each point alone, so undistorting row by row on every core gives
    // exactly the numbers one call over the whole image gives (2 M points for a Kinect v2 colour
    // camera: the serial call was 7 % of a 10-frame rendering).
    tbb::parallel_for(0, c.height, [&](int v) {
        std::vector<cv::Point2f> pixels(W), normalised;
        for (std::size_t u = 0; u < W; ++u) pixels[u] = cv::Point2f(static_cast<float>(u), static_cast<float>(v));
        cv::undistortPoints(pixels, normalised, K, distortion, cv::noArray(), cv::noArray(),
                            cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 20, 1e-9));
        for (std::size_t u = 0; u < W; ++u) {
            const std::size_t i = static_cast<std::size_t>(v) * W + u;
            map.dirs[i] = Eigen::Vector3d(normalised[u].x, normalised[u].y, 1.0).normalized();
            map.on_plane[i] = map.dirs[i] / map.dirs[i].z();
        }
    });
    return map;
}

Renderer::Renderer(const Scene& scene, const SensorModel& sensor, uint64_t seed)
    : scene_(scene), sensor_(sensor), seed_(seed), color_rays_(make_ray_map(sensor.color)), depth_rays_(make_ray_map(sensor.depth)) {
    if (sensor.principle == DepthPrinciple::TimeOfFlight)
        registration_.emplace(intrinsics_of(sensor.depth), intrinsics_of(sensor.color), sensor.depth_in_color,
                              cv::Size(sensor.depth.width, sensor.depth.height), cv::Size(sensor.color.width, sensor.color.height));
    else if (sensor.effects.disparity_pattern && sensor.disparity_pattern_sigma_px > 0)
        disparity_pattern_ = make_disparity_pattern(sensor, depth_rays_.width, depth_rays_.height, seed);
}

std::vector<Eigen::Isometry3d> Renderer::row_poses(const Eigen::Isometry3d& pose, const Eigen::Isometry3d& next_pose, double interval_s,
                                                   double readout_s, int rows) {
    std::vector<Eigen::Isometry3d> poses(static_cast<std::size_t>(rows), pose);
    if (readout_s <= 0 || interval_s == 0) return poses;
    const Eigen::Isometry3d motion = pose.inverse() * next_pose;
    const Eigen::AngleAxisd aa(motion.linear());
    for (int v = 0; v < rows; ++v) {
        const double s = (static_cast<double>(v) / rows - 0.5) * readout_s / interval_s;
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.linear() = Eigen::AngleAxisd(aa.angle() * s, aa.axis()).toRotationMatrix();
        T.translation() = motion.translation() * s;
        poses[static_cast<std::size_t>(v)] = pose * T;
    }
    return poses;
}

RenderedFrame Renderer::render(uint64_t frame, const Eigen::Isometry3d& pose, const Eigen::Isometry3d& next_pose, double frame_interval_s,
                               bool blur) const {
    PlannedFrame f;
    f.color_pose = f.depth_pose = pose;
    f.next_pose = next_pose;
    f.blur_interval_s = frame_interval_s;
    return render(frame, f, blur);
}

RenderedFrame Renderer::render(uint64_t frame, const PlannedFrame& f, bool blur) const {
    RenderedFrame out;
    render_color(frame, f, blur, out);
    if (sensor_.principle == DepthPrinciple::StructuredLight)
        render_depth_structured_light(frame, f, out);
    else
        render_depth_time_of_flight(frame, f, out);
    return out;
}

void Renderer::render_color(uint64_t frame, const PlannedFrame& f, bool blur, RenderedFrame& out) const {
    const Eigen::Isometry3d& pose = f.color_pose;
    const Eigen::Isometry3d& next_pose = f.next_pose;
    const double frame_interval_s = f.blur_interval_s;
    const Effects& fx = sensor_.effects;
    const int W = color_rays_.width, H = color_rays_.height;
    const auto rows = row_poses(pose, next_pose, frame_interval_s, fx.rolling_shutter ? sensor_.color_readout_s : 0.0, H);
    cv::Mat linear(H, W, CV_32FC3);
    cv::Mat range(H, W, CV_64FC1);  // camera-frame z of each colour pixel, for the blur
    const double pixel_angle = 1.0 / sensor_.color.fx;
    tbb::parallel_for(0, H, [&](int v) {
        const Eigen::Matrix3d R = rows[static_cast<std::size_t>(v)].linear();
        const Eigen::Vector3d o = rows[static_cast<std::size_t>(v)].translation();
        // A row's rays share the origin: traced in packets (RayIndex::kPacket), shaded one by one.
        constexpr int kRun = RayIndex::kPacket;
        for (int u0 = 0; u0 < W; u0 += kRun) {
            const int n = std::min(kRun, W - u0);
            Eigen::Vector3d dirs[kRun];
            for (int i = 0; i < n; ++i) dirs[i] = R * color_rays_.dirs[static_cast<std::size_t>(v) * W + u0 + i];
            Hit hits[kRun];
            bool found[kRun];
            scene_.intersect_packet(o, dirs, n, 1e-6, 1e3, hits, found);
            for (int i = 0; i < n; ++i) {
                const int u = u0 + i;
                Eigen::Vector3f c(0, 0, 0);
                double z = 1e3;
                if (found[i]) {
                    const Hit& hit = hits[i];
                    const double cos_in = std::max(0.05, std::abs(hit.normal.dot(dirs[i])));
                    c = scene_.shade(hit, dirs[i], hit.t * pixel_angle / cos_in, fx.highlights);
                    z = hit.t * color_rays_.dirs[static_cast<std::size_t>(v) * W + u].z();
                }
                linear.at<cv::Vec3f>(v, u) = cv::Vec3f(c.z(), c.y(), c.x());  // BGR
                range.at<double>(v, u) = z;
            }
        }
    });

    // Auto-exposure: the gain that brings the mean luminance the camera is adapted to (a lagging
    // average of earlier frames, PlannedFrame::exposure_reference; this frame's own for the first) to
    // the target, so bright surfaces clip where the view also holds dark ones, as real images do.
    const cv::Scalar mean_bgr = cv::mean(linear);
    out.mean_luminance = 0.0722 * mean_bgr[0] + 0.7152 * mean_bgr[1] + 0.2126 * mean_bgr[2];
    double gain = sensor_.gain;
    if (fx.auto_exposure) {
        const double reference = f.exposure_reference > 0 ? f.exposure_reference : out.mean_luminance;
        gain *= std::clamp(sensor_.exposure_target / std::max(reference, 1e-4), 0.25, 8.0);
    }
    linear *= gain;
    cv::Mat blurred = linear;
    if (blur && fx.motion_blur && frame_interval_s != 0) {  // negative: the pose given is an earlier one
        // Motion blur as a post-process: each pixel averages the sharp image along the path its
        // scene point travels in the image during the exposure (centred on the frame's stamp).
        const Eigen::Isometry3d motion = pose.inverse() * next_pose;  // camera motion over one interval
        const double fraction = sensor_.exposure_s / frame_interval_s;
        const Eigen::AngleAxisd aa(motion.linear());
        auto partial = [&](double s) {  // motion scaled to a fraction s of the interval
            Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
            T.linear() = Eigen::AngleAxisd(aa.angle() * s, aa.axis()).toRotationMatrix();
            T.translation() = motion.translation() * s;
            return T;
        };
        const Eigen::Isometry3d start = partial(-0.5 * fraction).inverse(), end = partial(0.5 * fraction).inverse();
        blurred = cv::Mat(H, W, CV_32FC3);
        tbb::parallel_for(0, H, [&](int v) {
            for (int u = 0; u < W; ++u) {
                const Eigen::Vector3d X = color_rays_.on_plane[static_cast<std::size_t>(v) * W + u] * range.at<double>(v, u);
                const Eigen::Vector3d a = start * X, b = end * X;
                if (a.z() <= 0.05 || b.z() <= 0.05) {
                    blurred.at<cv::Vec3f>(v, u) = linear.at<cv::Vec3f>(v, u);
                    continue;
                }
                // The image-space path, from the pinhole projection (distortion changes the length of
                // a few-pixel streak by a fraction of a pixel), centred on the pixel itself.
                const Eigen::Vector2d fa(sensor_.color.fx * a.x() / a.z(), sensor_.color.fy * a.y() / a.z());
                const Eigen::Vector2d fb(sensor_.color.fx * b.x() / b.z(), sensor_.color.fy * b.y() / b.z());
                const Eigen::Vector2d half = 0.5 * (fb - fa);
                const Eigen::Vector2d pa = Eigen::Vector2d(u, v) - half, pb = Eigen::Vector2d(u, v) + half;
                const int samples = std::clamp(static_cast<int>(std::ceil((pb - pa).norm())) + 1, 1, kMaxBlurSamples);
                if (samples == 1) {
                    blurred.at<cv::Vec3f>(v, u) = linear.at<cv::Vec3f>(v, u);
                    continue;
                }
                const Eigen::Vector2d path = pb - pa;
                const double* fractions = blur_fractions[samples];
                cv::Vec3f sum(0, 0, 0);
                // Each sample interpolated between its four pixels: read at the nearest pixel, a streak
                // under a pixel (slow motion, far surfaces) would leave the image exactly sharp.
                for (int k = 0; k < samples; ++k) {
                    const Eigen::Vector2d p = pa + path * fractions[k];
                    const double x = std::clamp(p.x(), 0.0, W - 1.0), y = std::clamp(p.y(), 0.0, H - 1.0);
                    const int x0 = std::min(static_cast<int>(x), W - 2), y0 = std::min(static_cast<int>(y), H - 2);
                    const float ax = static_cast<float>(x - x0), ay = static_cast<float>(y - y0);
                    const cv::Vec3f* r0 = linear.ptr<cv::Vec3f>(y0);
                    const cv::Vec3f* r1 = linear.ptr<cv::Vec3f>(y0 + 1);
                    sum += (r0[x0] * (1 - ax) + r0[x0 + 1] * ax) * (1 - ay) + (r1[x0] * (1 - ax) + r1[x0 + 1] * ax) * ay;
                }
                blurred.at<cv::Vec3f>(v, u) = sum / static_cast<float>(samples);
            }
        });
    }

    // Lens and demosaicing point spread (scaled with the image: σ is given for 640 columns).
    if (fx.optics_blur && sensor_.optics_sigma_px > 0) {
        const double sigma = sensor_.optics_sigma_px * W / 640.0;
        blurred = gaussian_blur_in_bands(blurred, sigma);
    }
    // Vignetting: brightness falls as r² towards the corners (r = 1 at a corner).
    const double half_diagonal2 = 0.25 * (static_cast<double>(W) * W + static_cast<double>(H) * H);
    const double vignetting = fx.vignetting ? sensor_.vignetting : 0.0;
    const double noise_dn = fx.image_noise ? sensor_.color_noise_dn : 0.0;
    const double contrast = fx.tone_curve ? sensor_.tone_contrast : 1.0;
    out.color.create(H, W, CV_8UC3);
    const HashStream color_noise(seed_, kColorNoise, frame);
    const bool stretch = contrast != 1.0;
    // +mosaic_noise: the sensor's noise lands on its RGGB Bayer mosaic (one value a pixel) and the
    // demosaicing interpolates it bilinearly into the two missing channels, as it does the signal, so
    // the noise is correlated across neighbouring pixels and channels.
    cv::Mat mosaic;
    const bool on_mosaic = noise_dn > 0 && fx.mosaic_noise && sensor_.mosaic_noise_dn > 0;
    if (on_mosaic) {
        mosaic.create(H, W, CV_32F);
        tbb::parallel_for(0, H, [&](int v) {
            float* m = mosaic.ptr<float>(v);
            for (int u = 0; u < W; ++u)
                m[u] = static_cast<float>(sensor_.mosaic_noise_dn *
                                          gaussian_fast(color_noise(static_cast<uint64_t>(v) * W + static_cast<uint64_t>(u))));
        });
    }
    auto mosaic_at = [&](int u, int v) { return mosaic.at<float>(std::clamp(v, 0, H - 1), std::clamp(u, 0, W - 1)); };
    // The noise of BGR channel ch at (u, v): the site's own value where the mosaic holds that colour,
    // else the mean of the nearest sites that do (2 or 4 of them).
    auto demosaiced_noise = [&](int u, int v, int ch) -> double {
        const bool even_row = v % 2 == 0, even_col = u % 2 == 0;
        const int site = even_row ? (even_col ? 2 : 1) : (even_col ? 1 : 0);  // R G / G B, as BGR indices
        if (site == ch) return mosaic_at(u, v);
        if (ch == 1)  // green at a red or blue site: its four edge neighbours
            return 0.25 * (mosaic_at(u - 1, v) + mosaic_at(u + 1, v) + mosaic_at(u, v - 1) + mosaic_at(u, v + 1));
        if (site != 1)  // red at blue or blue at red: the four diagonal neighbours
            return 0.25 * (mosaic_at(u - 1, v - 1) + mosaic_at(u + 1, v - 1) + mosaic_at(u - 1, v + 1) + mosaic_at(u + 1, v + 1));
        // red or blue at a green site: the two neighbours along the row that holds that colour
        const bool along_row = (ch == 2) == even_row;
        return along_row ? 0.5 * (mosaic_at(u - 1, v) + mosaic_at(u + 1, v)) : 0.5 * (mosaic_at(u, v - 1) + mosaic_at(u, v + 1));
    };
    // smooth_noise: a second part of the noise, white noise blurred to a correlation length of
    // smooth_noise_px — the real frames' flat-pixel noise has twice the power of white noise that
    // matches their finest scale, and more correlation between neighbours (docs/synthetic-sensors.md).
    cv::Mat smooth;
    if (noise_dn > 0 && fx.smooth_noise && sensor_.smooth_noise_dn > 0) {
        const double sigma = sensor_.smooth_noise_px * W / 640.0;
        const int ksize = 2 * static_cast<int>(std::ceil(4 * sigma)) + 1;
        const cv::Mat k = cv::getGaussianKernel(ksize, sigma, CV_64F);
        const double gain = k.dot(k);  // the blur's 2-D kernel is k kᵀ: its squares sum to (Σ k²)²
        const HashStream smooth_noise(seed_, kSmoothColorNoise, frame);
        smooth.create(H, W, CV_32FC3);
        tbb::parallel_for(0, H, [&](int v) {
            float* m = smooth.ptr<float>(v);
            const uint64_t row = static_cast<uint64_t>(v) * W * 3;
            for (int i = 0; i < W * 3; ++i) m[i] = static_cast<float>(gaussian_fast(smooth_noise(row + static_cast<uint64_t>(i))));
        });
        cv::GaussianBlur(smooth, smooth, cv::Size(ksize, ksize), sigma, sigma, cv::BORDER_REFLECT_101);
        smooth *= sensor_.smooth_noise_dn / gain;  // unit variance, then σ
    }
    std::vector<double> du2(static_cast<std::size_t>(W));  // (u − cx)², per column
    for (int u = 0; u < W; ++u) du2[static_cast<std::size_t>(u)] = (u - sensor_.color.cx) * (u - sensor_.color.cx);
    tbb::parallel_for(0, H, [&](int v) {
        const double dv = v - sensor_.color.cy, dv2 = dv * dv;
        const cv::Vec3f* in = blurred.ptr<cv::Vec3f>(v);
        uint8_t* px = out.color.ptr<uint8_t>(v);
        const uint64_t row_index = static_cast<uint64_t>(v) * W * 3;
        for (int u = 0; u < W; ++u, px += 3) {
            const float fall_off =
                static_cast<float>(1.0 - vignetting * std::min(1.0, (du2[static_cast<std::size_t>(u)] + dv2) / half_diagonal2));
            const cv::Vec3f c = in[u] * fall_off;
            for (int ch = 0; ch < 3; ++ch) {
                const double noise = (on_mosaic      ? demosaiced_noise(u, v, ch)
                                      : noise_dn > 0 ? noise_dn * gaussian_fast(color_noise(row_index + static_cast<uint64_t>(u) * 3 + ch))
                                                     : 0.0) +
                                     (smooth.empty() ? 0.0 : smooth.ptr<cv::Vec3f>(v)[u][ch]);
                // The tone curve acts on the signal; the sensor's noise is added after it (its σ was
                // measured on the real images, tone curve and all).
                const double y = srgb(c[ch]);
                const double display = stretch ? std::clamp(kTonePivot + contrast * (y - kTonePivot), 0.0, 1.0) : y;
                // saturate_cast<uint8_t> without its branches: the same rounding, then the same clamp.
                px[ch] = static_cast<uint8_t>(std::clamp(cvRound(255.0 * display + noise), 0, 255));
            }
        }
    });
}

}  // namespace vobench::synth
