// The depth half of the renderer: Kinect v1 (structured light) and Kinect v2 (time of flight), with
// the ways their returns fail (sensor_model.hpp lists every parameter and its source).
#include "synth/renderer.hpp"

#include "synth/random_field.hpp"
#include "synth/ray_index.hpp"
#include "synth/smooth_field.hpp"

#include "depth_registration.hpp"  // plugins/common

#include <tbb/parallel_for.h>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace vobench::synth {

namespace {

// The matching window in pixels of this grid, odd (a centred box), 1 for none.
int matching_window_px(double width_px) { return width_px < 2 ? 1 : 2 * static_cast<int>(std::lround((width_px - 1) / 2)) + 1; }

// The part of a pixel's disparity draw that repeats from frame to frame: a block matcher's error at
// pixel (u, v) depends on the projector's speckle that its window sees there, which for a rigid
// projector and camera is the same whenever the pixel sees the same disparity d. Unit variance:
// independent draws on a lattice of d every `length` pixels, blended between the two nearest with
// weights √(1 − t), √t, so that the draw changes smoothly as d drifts. The cheap normal
// (gaussian_fast) is enough: the matching window averages 49 of them.
double sensor_fixed_draw(const HashStream& fixed, uint64_t pixel, double d, double length) {
    const double x = d / length, k = std::floor(x), t = x - k;
    const uint64_t bin = static_cast<uint64_t>(static_cast<int64_t>(k) + (int64_t{1} << 40));
    const uint64_t at_pixel = fixed(pixel);
    return std::sqrt(1.0 - t) * gaussian_fast(hash(at_pixel, bin)) + std::sqrt(t) * gaussian_fast(hash(at_pixel, bin + 1));
}

// Unit-variance noise averaged over a window×window box: each pixel's Gaussian draw (the stream
// `draws`, indexed as the per-pixel noise is) averaged with its neighbours', times the window so the
// average keeps unit variance. Its autocorrelation falls linearly to zero at a lag of one window.
// With a share ρ > 0, each draw is √(1 − ρ)·(this frame's) + √ρ·sensor_fixed_draw at the pixel's true
// disparity f·b / z (`truth`: z in metres, 0 where nothing was hit: there the frame's draw alone).
cv::Mat windowed_unit_noise(const HashStream& draws, const HashStream& fixed, const cv::Mat& truth, double fb, double share, double length,
                            int window) {
    const int W = truth.cols, H = truth.rows;
    cv::Mat noise(H, W, CV_64FC1);
    const double own = std::sqrt(1.0 - share), repeated = std::sqrt(share);
    tbb::parallel_for(0, H, [&](int v) {
        double* row = noise.ptr<double>(v);
        const float* z = truth.ptr<float>(v);
        for (int u = 0; u < W; ++u) {
            const uint64_t pixel = static_cast<uint64_t>(v) * W + u;
            row[u] = gaussian(draws(pixel));
            if (share > 0 && z[u] > 0) row[u] = own * row[u] + repeated * sensor_fixed_draw(fixed, pixel, fb / z[u], length);
        }
    });
    if (window > 1) {
        cv::blur(noise, noise, cv::Size(window, window), cv::Point(-1, -1), cv::BORDER_REFLECT_101);
        noise *= window;
    }
    return noise;
}

// Foreground fattening (sensor_model.hpp, shadow_fill_px): each run of shadowed pixels takes, over its
// first `fill` pixels, the depth of the measured pixel it starts beside. The shadow lies on the side of
// the occluder away from the projector, so runs are walked from the occluder: towards +u when the
// projector sits at −x of the colour camera.
void fill_shadow_edges(cv::Mat& depth, const cv::Mat& shadowed, int fill, bool towards_plus_u) {
    const int W = depth.cols, step = towards_plus_u ? 1 : -1;
    tbb::parallel_for(0, depth.rows, [&](int v) {
        float* row = depth.ptr<float>(v);
        const uint8_t* shade = shadowed.ptr<uint8_t>(v);
        for (int u = towards_plus_u ? 1 : W - 2; u >= 0 && u < W; u += step) {
            const float occluder = row[u - step];
            if (!shade[u] || shade[u - step] || occluder <= 0) continue;
            for (int k = 0; k < fill && u >= 0 && u < W && shade[u]; ++k, u += step) row[u] = occluder;
        }
    });
}

}  // namespace

Renderer::DepthStreams::DepthStreams(uint64_t seed, uint64_t frame)
    : lateral(seed, kLateral, frame),
      lost_return(seed, kLostReturn, frame),
      disparity(seed, kDisparityNoise, frame),
      edge_dropout(seed, kEdgeDropout, frame),
      dropout(seed, kDropout, frame),
      tof(seed, kTofNoise, frame),
      flying(seed, kFlying, frame),
      flying_mix(seed, kFlyingMix, frame) {}

void Renderer::cast_depth_rays(const DepthStreams& random, const Eigen::Isometry3d& depth_pose, int u0, int n, int v, DepthRay* out,
                               bool* found) const {
    Eigen::Vector3d dirs_cam[RayIndex::kPacket], dirs[RayIndex::kPacket];
    for (Eigen::Vector3d& d : dirs) d.setZero();  // lanes past n stay unused
    Hit hits[RayIndex::kPacket];
    for (int i = 0; i < n; ++i) {
        const uint64_t pixel = static_cast<uint64_t>(v) * depth_rays_.width + u0 + i;
        Eigen::Vector3d& dir_cam = dirs_cam[i];
        dir_cam = depth_rays_.dirs[pixel];
        if (sensor_.effects.registration_error && sensor_.principle == DepthPrinciple::StructuredLight) {
            // The registered depth pixel (u, v) holds what the colour pixel (u − dx, v − dy) sees.
            const double px = depth_rays_.width / 640.0;
            dir_cam.x() -= sensor_.registration_shift_px.x() * px / sensor_.depth.fx * dir_cam.z();
            dir_cam.y() -= sensor_.registration_shift_px.y() * px / sensor_.depth.fy * dir_cam.z();
        }
        if (sensor_.effects.depth_noise) {
            // Lateral noise: the sampling position jitters by a fraction of a pixel.
            const double lateral = sensor_.lateral_sigma_px / sensor_.depth.fx;
            dir_cam.x() += lateral * gaussian(random.lateral(2 * pixel));
            dir_cam.y() += lateral * gaussian(random.lateral(2 * pixel + 1));
        }
        dir_cam.normalize();
        dirs[i] = depth_pose.linear() * dir_cam;
    }
    scene_.intersect_packet(depth_pose.translation(), dirs, n, 1e-6, 1e3, hits, found);
    for (int i = 0; i < n; ++i) {
        if (!found[i]) continue;
        out[i].hit = hits[i];
        out[i].z = hits[i].t * dirs_cam[i].z();
        out[i].incidence = std::acos(std::min(1.0, std::abs(hits[i].normal.dot(dirs[i]))));
    }
}

bool Renderer::return_lost(const DepthStreams& random, uint64_t pixel, const DepthRay& ray) const {
    const Effects& fx = sensor_.effects;
    const Material& m = scene_.materials[static_cast<std::size_t>(ray.hit.material)];
    double p = 0;
    if (fx.dark_dropout) {
        if (m.emission > 0) return true;  // glass: the IR passes through to what lies beyond range
        const Eigen::Vector3f a = albedo(m, ray.hit.u, ray.hit.v, 0.005);
        const double luminance = 0.2126 * a.x() + 0.7152 * a.y() + 0.0722 * a.z();
        if (luminance < sensor_.dark_albedo) p = sensor_.dark_dropout_max * (1.0 - luminance / sensor_.dark_albedo);
        p = 1.0 - (1.0 - p) * (1.0 - sensor_.gloss_dropout * m.gloss);
    }
    if (fx.far_dropout && sensor_.principle == DepthPrinciple::StructuredLight && ray.z > sensor_.far_dropout_start_m)
        p = 1.0 -
            (1.0 - p) * (1.0 - std::min(1.0, (ray.z - sensor_.far_dropout_start_m) / (sensor_.max_range_m - sensor_.far_dropout_start_m)));
    if (p <= 0) return false;
    // Blobs fixed on the surface (value noise mapped to about uniform in [0, 1]), their edges
    // flickering a little from frame to frame.
    const double field =
        0.5 + 0.8 * lattice_noise(ray.hit.u / sensor_.dropout_blob_m, ray.hit.v / sensor_.dropout_blob_m, m.seed ^ 0xd1b54a32d192ed03ull);
    const double flicker = 0.15 * (uniform(random.lost_return(pixel)) - 0.5);
    return std::clamp(field, 0.0, 1.0) + flicker < p;
}

cv::Mat Renderer::make_disparity_pattern(const SensorModel& sensor, int W, int H, uint64_t seed) {
    // A smooth field of the unit (another for each seed) less its own best a·r² + b·x + c·y + constant —
    // that part is the camera's low-order field (disparity_distortion_px), which it brings measured and
    // a rendering reads back (tests/scripts/depth_distortion_fit.sh).
    const SmoothField field(W, H, std::max(1.0, sensor.disparity_pattern_length_px * (W / 640.0)), hash(seed, kDisparityPattern, 0));
    Eigen::Matrix4d normal = Eigen::Matrix4d::Zero();
    Eigen::Vector4d rhs = Eigen::Vector4d::Zero();
    for (int v = 0; v < H; v += 4)
        for (int u = 0; u < W; u += 4) {
            const Eigen::Vector4d b = disparity_field_terms(sensor.depth, u, v);
            normal += b * b.transpose();
            rhs += b * field.at(u, v);
        }
    const Eigen::Vector4d low_order = normal.ldlt().solve(rhs);
    cv::Mat out(H, W, CV_64FC1);
    std::vector<double> row(static_cast<std::size_t>(W));
    for (int v = 0; v < H; ++v) {
        field.row(v, row.data());
        for (int u = 0; u < W; ++u)
            out.at<double>(v, u) = sensor.disparity_pattern_sigma_px *
                                   (row[static_cast<std::size_t>(u)] - disparity_field_terms(sensor.depth, u, v).dot(low_order));
    }
    return out;
}

void Renderer::render_depth_structured_light(uint64_t frame, const PlannedFrame& f, RenderedFrame& out) const {
    // Kinect v1: depth on a grid registered to the colour camera, from disparity against the
    // projector pattern (Khoshelham & Elberink 2012): z = f·b/d, d quantised to 1/8 px with noise.
    const Effects& fx = sensor_.effects;
    const int W = depth_rays_.width, H = depth_rays_.height;
    const DepthStreams random(seed_, frame);
    // Registered: the depth grid is the colour camera's. The IR camera's rolling shutter moves it
    // while the rows are read (the colour camera's motion at the depth stamp: they are ~10 ms apart).
    const Eigen::Isometry3d next = f.depth_pose * (f.color_pose.inverse() * f.next_pose);
    const auto rows = row_poses(f.depth_pose, next, f.blur_interval_s, fx.rolling_shutter ? sensor_.depth_readout_s : 0.0, H);
    const double fb = sensor_.ir_focal_px * sensor_.baseline_m;
    // The registered image's unmeasured border, in this grid's pixels.
    const double px = W / 640.0;
    const int right = W - static_cast<int>(std::lround(sensor_.border_right_px * px));
    const int top = static_cast<int>(std::lround(sensor_.border_top_px * px));
    const int bottom = H - static_cast<int>(std::lround(sensor_.border_bottom_px * px));
    // The smooth part of the disparity error, a new field each frame (built only when it is on).
    const double correlated_sigma = fx.depth_noise && fx.correlated_depth_noise ? sensor_.disparity_correlated_sigma_px : 0.0;
    std::optional<SmoothField> correlated;
    if (correlated_sigma > 0)
        correlated.emplace(W, H, std::max(1.0, sensor_.disparity_correlation_px * px), hash(seed_, kCorrelatedDisparity, frame));
    // The unit's fixed disparity offset field (zero unless the camera brings a measured one).
    const auto& a = sensor_.disparity_distortion_px;
    const bool distortion = fx.depth_distortion && (a[0] != 0 || a[1] != 0 || a[2] != 0);
    const auto disparity_offset = [&](int u, int v) {
        const Eigen::Vector4d t = disparity_field_terms(sensor_.depth, u, v);
        return a[0] * t[0] + a[1] * t[1] + a[2] * t[2];
    };
    cv::Mat truth = cv::Mat::zeros(H, W, CV_32FC1);
    cv::Mat clean = cv::Mat::zeros(H, W, CV_64FC1);  // the disparity before noise, where a pixel is measured
    out.depth_native = cv::Mat::zeros(H, W, CV_32FC1);
    cv::Mat lost = cv::Mat::zeros(H, W, CV_8UC1);      // 255 where the return is lost (dark, glossy, far, depth step)
    cv::Mat shadowed = cv::Mat::zeros(H, W, CV_8UC1);  // 255 where the projector's pattern does not reach
    tbb::parallel_for(0, H, [&](int v) {
        const Eigen::Isometry3d& depth_pose = rows[static_cast<std::size_t>(v)];
        DepthRay rays[RayIndex::kPacket];
        bool found[RayIndex::kPacket];
        for (int u = 0; u < W; ++u) {
            const int lane = u % RayIndex::kPacket;
            if (lane == 0) cast_depth_rays(random, depth_pose, u, std::min(RayIndex::kPacket, W - u), v, rays, found);
            if (!found[lane]) continue;
            const DepthRay& ray = rays[lane];
            const uint64_t pixel = static_cast<uint64_t>(v) * W + u;
            const double z = ray.z;
            truth.at<float>(v, u) = static_cast<float>(z);
            if (z < sensor_.min_range_m || z > sensor_.max_range_m) continue;
            if (fx.depth_border && (u >= right || v < top || v >= bottom || u < sensor_.border_left_px_m * px / z)) continue;
            if (fx.glancing_dropout && ray.incidence > sensor_.glancing_limit_deg * M_PI / 180.0) continue;
            if (return_lost(random, pixel, ray)) lost.at<uint8_t>(v, u) = 255;
            const Hit& hit = ray.hit;
            // The projector's shadow: a point the pattern cannot reach has no disparity.
            if (fx.projector_shadow && scene_.occluded(hit.point + hit.normal * 1e-4, depth_pose * sensor_.projector_in_color)) {
                shadowed.at<uint8_t>(v, u) = 255;
                continue;
            }
            const double offset =
                (distortion ? disparity_offset(u, v) : 0.0) + (disparity_pattern_.empty() ? 0.0 : disparity_pattern_.at<double>(v, u));
            if (!fx.depth_noise && offset == 0) {
                out.depth_native.at<float>(v, u) = static_cast<float>(z);
                continue;
            }
            clean.at<double>(v, u) = fb / z + offset;
        }
    });
    // The disparity noise, per pixel or averaged over the matching window, part of it repeating at a
    // pixel from frame to frame (sensor_fixed_draw), then the quantisation.
    const int noise_window = fx.depth_noise ? matching_window_px(sensor_.disparity_window_px * px) : 1;
    const double fixed_share = fx.depth_noise && fx.fixed_pattern_noise ? sensor_.disparity_fixed_share : 0.0;
    cv::Mat unit_noise;
    if (fx.depth_noise)
        unit_noise = windowed_unit_noise(random.disparity, HashStream(seed_, kFixedDisparity, 0), truth, fb, fixed_share,
                                         std::max(1e-3, sensor_.disparity_fixed_length_px), noise_window);
    tbb::parallel_for(0, H, [&](int v) {
        std::vector<double> correlated_row;
        if (correlated) {
            correlated_row.resize(static_cast<std::size_t>(W));
            correlated->row(v, correlated_row.data());
        }
        for (int u = 0; u < W; ++u) {
            double d = clean.at<double>(v, u);
            if (d == 0) continue;  // not measured, or measured without noise above
            if (fx.depth_noise) {
                d += sensor_.disparity_sigma_px * unit_noise.at<double>(v, u);
                if (correlated) d += correlated_sigma * correlated_row[static_cast<std::size_t>(u)];
                d = std::round(d / sensor_.disparity_step_px) * sensor_.disparity_step_px;
            }
            if (d <= 0) continue;
            out.depth_native.at<float>(v, u) = static_cast<float>(fb / d);
        }
    });
    if (fx.projector_shadow && sensor_.shadow_fill_px > 0)
        fill_shadow_edges(out.depth_native, shadowed, static_cast<int>(std::lround(sensor_.shadow_fill_px * px)),
                          sensor_.projector_in_color.x() < 0);
    if (fx.edge_dropout) {
        // The correlation window straddling a depth step matches neither side.
        const cv::Mat measured = out.depth_native.clone();
        tbb::parallel_for(1, H - 1, [&](int v) {
            for (int u = 1; u < W - 1; ++u) {
                const float z = truth.at<float>(v, u);
                if (measured.at<float>(v, u) <= 0) continue;
                bool step = false;
                for (int k = 0; k < 4 && !step; ++k) {
                    const float n = truth.at<float>(v + (k == 2) - (k == 3), u + (k == 0) - (k == 1));
                    step = n <= 0 || std::abs(n - z) > 0.05f * z;
                }
                if (step && uniform(random.edge_dropout(static_cast<uint64_t>(v) * W + u)) < sensor_.edge_dropout_probability)
                    lost.at<uint8_t>(v, u) = 255;
            }
        });
    }
    // The returns lost by matching: a majority vote over the correlation window (a median of the mask),
    // so that holes come in patches and the speckle of pixel-by-pixel losses is gone.
    const int window = static_cast<int>(std::lround(sensor_.dropout_window_px * px)) | 1;  // odd
    if (window > 1) cv::medianBlur(lost, lost, window);
    out.depth_native.setTo(0, lost);
    // PUTK²'s 320×240 depth is rescaled to the 640×480 colour image as in the paper (nearest: no
    // invented depths); a full-resolution grid is the colour image already.
    if (out.depth_native.size() == cv::Size(sensor_.color.width, sensor_.color.height))
        out.depth = out.depth_native.clone();
    else
        cv::resize(out.depth_native, out.depth, cv::Size(sensor_.color.width, sensor_.color.height), 0, 0, cv::INTER_NEAREST);
}

rgbd::Intrinsics intrinsics_of(const PinholeCamera& c) { return {c.fx, c.fy, c.cx, c.cy, c.distortion_count, c.distortion}; }

void Renderer::render_depth_time_of_flight(uint64_t frame, const PlannedFrame& f, RenderedFrame& out) const {
    // Kinect v2: its own 512×424 camera beside the colour camera; axial noise after Fankhauser et al.
    // (2015); flying pixels mixing fore- and background at discontinuities; isolated dropouts.
    const Effects& fx = sensor_.effects;
    const int W = depth_rays_.width, H = depth_rays_.height;
    const DepthStreams random(seed_, frame);
    // A global shutter: one pose for the whole image.
    const Eigen::Isometry3d depth_pose = f.depth_pose * sensor_.depth_in_color;
    cv::Mat truth = cv::Mat::zeros(H, W, CV_32FC1), noisy = cv::Mat::zeros(H, W, CV_32FC1);
    tbb::parallel_for(0, H, [&](int v) {
        DepthRay rays[RayIndex::kPacket];
        bool found[RayIndex::kPacket];
        for (int u = 0; u < W; ++u) {
            const int lane = u % RayIndex::kPacket;
            if (lane == 0) cast_depth_rays(random, depth_pose, u, std::min(RayIndex::kPacket, W - u), v, rays, found);
            if (!found[lane]) continue;
            const DepthRay& ray = rays[lane];
            const uint64_t pixel = static_cast<uint64_t>(v) * W + u;
            const double z = ray.z, incidence = ray.incidence;
            truth.at<float>(v, u) = static_cast<float>(z);
            if (z < sensor_.min_range_m || z > sensor_.max_range_m) continue;
            if (fx.glancing_dropout && incidence > sensor_.glancing_limit_deg * M_PI / 180.0) continue;
            if (fx.dark_dropout && uniform(random.dropout(pixel)) < sensor_.dropout_probability) continue;
            if (return_lost(random, pixel, ray)) continue;
            const double noise = fx.depth_noise ? kinect2_sigma_z(z, incidence) * gaussian(random.tof(pixel)) : 0.0;
            noisy.at<float>(v, u) = static_cast<float>(z + noise);
        }
    });
    // Flying pixels: a pixel whose footprint straddles a depth step returns a mixture of both depths.
    out.depth_native = noisy.clone();
    if (fx.flying_pixels) {
        tbb::parallel_for(0, H, [&](int v) {
            for (int u = 0; u < W; ++u) {
                const float z = truth.at<float>(v, u);
                if (noisy.at<float>(v, u) <= 0) continue;
                float other = z;
                const int du[4] = {1, -1, 0, 0}, dv[4] = {0, 0, 1, -1};
                for (int k = 0; k < 4; ++k) {
                    const int x = u + du[k], y = v + dv[k];
                    if (x < 0 || y < 0 || x >= W || y >= H) continue;
                    const float n = truth.at<float>(y, x);
                    if (n > 0 && std::abs(n - z) > 0.05f && std::abs(n - z) > std::abs(other - z)) other = n;
                }
                if (other == z) continue;
                const uint64_t pixel = static_cast<uint64_t>(v) * W + u;
                if (uniform(random.flying(pixel)) >= sensor_.flying_pixel_probability) continue;
                const double alpha = 0.15 + 0.7 * uniform(random.flying_mix(pixel));
                out.depth_native.at<float>(v, u) = static_cast<float>(noisy.at<float>(v, u) + alpha * (other - z));
            }
        });
    }
    // To the 1920×1080 colour camera, z-buffered splats (see plugins/common/depth_registration.hpp).
    out.depth = (*registration_)(out.depth_native);
}

}  // namespace vobench::synth
