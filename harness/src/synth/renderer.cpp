#include "synth/renderer.hpp"

#include "synth/random_field.hpp"

#include "depth_registration.hpp"  // plugins/common

#include <tbb/parallel_for.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace vobench::synth {
namespace {

constexpr int kTile = 16;

// Salt values keep the random streams of different effects apart.
enum Salt : uint64_t { kColorNoise = 1, kDisparityNoise, kLateral, kDropout, kFlying, kFlyingMix, kExposure, kTofNoise };

// sRGB encoding (IEC 61966-2-1) as a 4096-entry table over [0, 1] linear: 8-bit output cannot tell.
double srgb(double linear) {
    static const std::vector<double> table = [] {
        std::vector<double> t(4097);
        for (std::size_t i = 0; i < t.size(); ++i) {
            const double l = static_cast<double>(i) / 4096.0;
            t[i] = l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055;
        }
        return t;
    }();
    return table[static_cast<std::size_t>(std::clamp(linear, 0.0, 1.0) * 4096.0 + 0.5)];
}

}  // namespace

Renderer::RayMap Renderer::make_ray_map(const PinholeCamera& c) {
    RayMap map;
    map.width = c.width;
    map.height = c.height;
    std::vector<cv::Point2f> pixels;
    pixels.reserve(static_cast<std::size_t>(c.width) * c.height);
    for (int v = 0; v < c.height; ++v)
        for (int u = 0; u < c.width; ++u) pixels.emplace_back(static_cast<float>(u), static_cast<float>(v));
    std::vector<cv::Point2f> normalised;
    const cv::Matx33d K(c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1);
    cv::undistortPoints(pixels, normalised, K, cv::Mat(1, 8, CV_64F, const_cast<double*>(c.distortion.data())), cv::noArray(),
                        cv::noArray(), cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 20, 1e-9));
    map.dirs.reserve(normalised.size());
    for (const auto& n : normalised) map.dirs.push_back(Eigen::Vector3d(n.x, n.y, 1.0).normalized());
    return map;
}

Renderer::Renderer(const Scene& scene, const SensorModel& sensor, uint64_t seed)
    : scene_(scene), sensor_(sensor), seed_(seed), color_rays_(make_ray_map(sensor.color)), depth_rays_(make_ray_map(sensor.depth)) {}

std::vector<std::vector<int>> Renderer::cull(const RayMap& rays, const Eigen::Isometry3d& pose) const {
    const int tiles_x = (rays.width + kTile - 1) / kTile, tiles_y = (rays.height + kTile - 1) / kTile;
    std::vector<std::vector<int>> lists(static_cast<std::size_t>(tiles_x * tiles_y));
    const Eigen::Vector3d origin = pose.translation();
    const Eigen::Matrix3d R = pose.linear();
    tbb::parallel_for(0, tiles_y, [&](int ty) {
        for (int tx = 0; tx < tiles_x; ++tx) {
            // The tile's corner rays, widened by one pixel, bound its pixels' rays (distortion is smooth).
            const int u0 = std::max(0, tx * kTile - 1), v0 = std::max(0, ty * kTile - 1);
            const int u1 = std::min(rays.width - 1, (tx + 1) * kTile), v1 = std::min(rays.height - 1, (ty + 1) * kTile);
            const Eigen::Vector3d c[4] = {R * rays.dirs[v0 * rays.width + u0], R * rays.dirs[v0 * rays.width + u1],
                                          R * rays.dirs[v1 * rays.width + u1], R * rays.dirs[v1 * rays.width + u0]};
            Eigen::Vector3d normals[4];
            for (int k = 0; k < 4; ++k) normals[k] = c[k].cross(c[(k + 1) % 4]);  // inward for clockwise image order
            const Eigen::Vector3d centre = (c[0] + c[1] + c[2] + c[3]).normalized();
            for (int k = 0; k < 4; ++k)
                if (normals[k].dot(centre) < 0) normals[k] = -normals[k];
            auto& list = lists[static_cast<std::size_t>(ty * tiles_x + tx)];
            for (std::size_t b = 0; b < scene_.boxes.size(); ++b) {
                const Box& box = scene_.boxes[b];
                bool outside = false;
                if (!box.shell) {
                    for (int k = 0; k < 4 && !outside; ++k) {
                        outside = true;
                        for (int corner = 0; corner < 8 && outside; ++corner) {
                            const Eigen::Vector3d p((corner & 1) ? box.max.x() : box.min.x(), (corner & 2) ? box.max.y() : box.min.y(),
                                                    (corner & 4) ? box.max.z() : box.min.z());
                            outside = normals[k].dot(p - origin) < 0;
                        }
                    }
                }
                if (!outside) list.push_back(static_cast<int>(b));
            }
        }
    });
    return lists;
}

RenderedFrame Renderer::render(uint64_t frame, const Eigen::Isometry3d& pose, const Eigen::Isometry3d& next_pose, double frame_interval_s,
                               bool blur) const {
    RenderedFrame out;
    render_color(frame, pose, next_pose, frame_interval_s, blur, out);
    if (sensor_.principle == DepthPrinciple::StructuredLight)
        render_depth_structured_light(frame, pose, out);
    else
        render_depth_time_of_flight(frame, pose, out);
    return out;
}

void Renderer::render_color(uint64_t frame, const Eigen::Isometry3d& pose, const Eigen::Isometry3d& next_pose, double frame_interval_s,
                            bool blur, RenderedFrame& out) const {
    const int W = color_rays_.width, H = color_rays_.height;
    const auto tiles = cull(color_rays_, pose);
    const int tiles_x = (W + kTile - 1) / kTile;
    cv::Mat linear(H, W, CV_32FC3);
    cv::Mat range(H, W, CV_64FC1);  // camera-frame z of each colour pixel, for the blur
    const Eigen::Matrix3d R = pose.linear();
    const Eigen::Vector3d o = pose.translation();
    const double pixel_angle = 1.0 / sensor_.color.fx;
    // Auto-exposure settles within ±3% from frame to frame.
    const double gain = sensor_.gain * (1.0 + 0.03 * (2.0 * uniform(hash(seed_, kExposure, frame)) - 1.0));
    tbb::parallel_for(0, H, [&](int v) {
        for (int u = 0; u < W; ++u) {
            const Eigen::Vector3d dir_cam = color_rays_.dirs[static_cast<std::size_t>(v) * W + u];
            const Eigen::Vector3d dir = R * dir_cam;
            Hit hit;
            Eigen::Vector3f c(0, 0, 0);
            double z = 1e3;
            if (scene_.intersect(o, dir, 1e-6, 1e3, hit, &tiles[static_cast<std::size_t>((v / kTile) * tiles_x + u / kTile)])) {
                const double cos_in = std::max(0.05, std::abs(hit.normal.dot(dir)));
                c = scene_.shade(hit, hit.t * pixel_angle / cos_in);
                z = hit.t * dir_cam.z();
            }
            linear.at<cv::Vec3f>(v, u) = cv::Vec3f(c.z(), c.y(), c.x()) * static_cast<float>(gain);  // BGR
            range.at<double>(v, u) = z;
        }
    });

    cv::Mat blurred = linear;
    if (blur && frame_interval_s > 0) {
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
                const Eigen::Vector3d X = color_rays_.dirs[static_cast<std::size_t>(v) * W + u] /
                                          color_rays_.dirs[static_cast<std::size_t>(v) * W + u].z() * range.at<double>(v, u);
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
                const int samples = std::clamp(static_cast<int>(std::ceil((pb - pa).norm())) + 1, 1, 24);
                cv::Vec3f sum(0, 0, 0);
                for (int k = 0; k < samples; ++k) {
                    const Eigen::Vector2d p =
                        samples == 1 ? Eigen::Vector2d(u, v) : pa + (pb - pa) * (static_cast<double>(k) / (samples - 1));
                    const int x = std::clamp(static_cast<int>(p.x() + 0.5), 0, W - 1);
                    const int y = std::clamp(static_cast<int>(p.y() + 0.5), 0, H - 1);
                    sum += linear.at<cv::Vec3f>(y, x);
                }
                blurred.at<cv::Vec3f>(v, u) = sum / static_cast<float>(samples);
            }
        });
    }

    out.color.create(H, W, CV_8UC3);
    tbb::parallel_for(0, H, [&](int v) {
        for (int u = 0; u < W; ++u) {
            const cv::Vec3f c = blurred.at<cv::Vec3f>(v, u);
            cv::Vec3b& px = out.color.at<cv::Vec3b>(v, u);
            for (int ch = 0; ch < 3; ++ch) {
                const double noise =
                    sensor_.color_noise_dn * gaussian_fast(hash(seed_, kColorNoise, frame, (static_cast<uint64_t>(v) * W + u) * 3 + ch));
                px[ch] = cv::saturate_cast<uint8_t>(255.0 * srgb(c[ch]) + noise);
            }
        }
    });
}

bool Renderer::cast_depth_ray(uint64_t frame, const Eigen::Isometry3d& depth_pose, const std::vector<std::vector<int>>& tiles, int u, int v,
                              DepthRay& out) const {
    // Lateral noise: the sampling position jitters by a fraction of a pixel.
    const uint64_t pixel = static_cast<uint64_t>(v) * depth_rays_.width + u;
    const double lateral = sensor_.lateral_sigma_px / sensor_.depth.fx;
    Eigen::Vector3d dir_cam = depth_rays_.dirs[pixel];
    dir_cam.x() += lateral * gaussian(hash(seed_, kLateral, frame, 2 * pixel));
    dir_cam.y() += lateral * gaussian(hash(seed_, kLateral, frame, 2 * pixel + 1));
    dir_cam.normalize();
    const Eigen::Vector3d dir = depth_pose.linear() * dir_cam;
    const int tiles_x = (depth_rays_.width + kTile - 1) / kTile;
    if (!scene_.intersect(depth_pose.translation(), dir, 1e-6, 1e3, out.hit,
                          &tiles[static_cast<std::size_t>((v / kTile) * tiles_x + u / kTile)]))
        return false;
    out.z = out.hit.t * dir_cam.z();
    out.incidence = std::acos(std::min(1.0, std::abs(out.hit.normal.dot(dir))));
    return true;
}

void Renderer::render_depth_structured_light(uint64_t frame, const Eigen::Isometry3d& pose, RenderedFrame& out) const {
    // Kinect v1: depth on a 320×240 grid registered to the colour camera, from disparity against the
    // projector pattern (Khoshelham & Elberink 2012): z = f·b/d, d quantised to 1/8 px with noise.
    const int W = depth_rays_.width, H = depth_rays_.height;
    const Eigen::Isometry3d& depth_pose = pose;  // registered: the depth grid is the colour camera's
    const auto tiles = cull(depth_rays_, depth_pose);
    const Eigen::Vector3d projector = pose * sensor_.projector_in_color;
    const double fb = sensor_.ir_focal_px * sensor_.baseline_m;
    out.depth_native = cv::Mat::zeros(H, W, CV_32FC1);
    tbb::parallel_for(0, H, [&](int v) {
        for (int u = 0; u < W; ++u) {
            const uint64_t pixel = static_cast<uint64_t>(v) * W + u;
            DepthRay ray;
            if (!cast_depth_ray(frame, depth_pose, tiles, u, v, ray)) continue;
            const double z = ray.z;
            if (z < sensor_.min_range_m || z > sensor_.max_range_m) continue;
            if (ray.incidence > sensor_.glancing_limit_deg * M_PI / 180.0) continue;
            const Hit& hit = ray.hit;
            // The projector's shadow: a point the pattern cannot reach has no disparity.
            if (scene_.occluded(hit.point + hit.normal * 1e-4, projector)) continue;
            const double d = fb / z + sensor_.disparity_sigma_px * gaussian(hash(seed_, kDisparityNoise, frame, pixel));
            const double dq = std::round(d / sensor_.disparity_step_px) * sensor_.disparity_step_px;
            if (dq <= 0) continue;
            out.depth_native.at<float>(v, u) = static_cast<float>(fb / dq);
        }
    });
    // The paper rescales 320×240 depth to the 640×480 colour image (nearest: no invented depths).
    cv::resize(out.depth_native, out.depth, cv::Size(sensor_.color.width, sensor_.color.height), 0, 0, cv::INTER_NEAREST);
}

rgbd::Intrinsics intrinsics_of(const PinholeCamera& c) { return {c.fx, c.fy, c.cx, c.cy, c.distortion_count, c.distortion}; }

void Renderer::render_depth_time_of_flight(uint64_t frame, const Eigen::Isometry3d& pose, RenderedFrame& out) const {
    // Kinect v2: its own 512×424 camera beside the colour camera; axial noise after Fankhauser et al.
    // (2015); flying pixels mixing fore- and background at discontinuities; isolated dropouts.
    const int W = depth_rays_.width, H = depth_rays_.height;
    const Eigen::Isometry3d depth_pose = pose * sensor_.depth_in_color;
    const auto tiles = cull(depth_rays_, depth_pose);
    cv::Mat truth = cv::Mat::zeros(H, W, CV_32FC1), noisy = cv::Mat::zeros(H, W, CV_32FC1);
    tbb::parallel_for(0, H, [&](int v) {
        for (int u = 0; u < W; ++u) {
            const uint64_t pixel = static_cast<uint64_t>(v) * W + u;
            DepthRay ray;
            if (!cast_depth_ray(frame, depth_pose, tiles, u, v, ray)) continue;
            const double z = ray.z, incidence = ray.incidence;
            truth.at<float>(v, u) = static_cast<float>(z);
            if (z < sensor_.min_range_m || z > sensor_.max_range_m) continue;
            if (incidence > sensor_.glancing_limit_deg * M_PI / 180.0) continue;
            if (uniform(hash(seed_, kDropout, frame, pixel)) < sensor_.dropout_probability) continue;
            noisy.at<float>(v, u) = static_cast<float>(z + kinect2_sigma_z(z, incidence) * gaussian(hash(seed_, kTofNoise, frame, pixel)));
        }
    });
    // Flying pixels: a pixel whose footprint straddles a depth step returns a mixture of both depths.
    out.depth_native = noisy.clone();
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
            if (uniform(hash(seed_, kFlying, frame, pixel)) >= sensor_.flying_pixel_probability) continue;
            const double alpha = 0.15 + 0.7 * uniform(hash(seed_, kFlyingMix, frame, pixel));
            out.depth_native.at<float>(v, u) = static_cast<float>(noisy.at<float>(v, u) + alpha * (other - z));
        }
    });
    // To the 1920×1080 colour camera, z-buffered splats (see plugins/common/depth_registration.hpp).
    out.depth = rgbd::register_depth(out.depth_native, intrinsics_of(sensor_.depth), intrinsics_of(sensor_.color), sensor_.depth_in_color,
                                     cv::Size(sensor_.color.width, sensor_.color.height));
}

}  // namespace vobench::synth
