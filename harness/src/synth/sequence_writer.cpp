#include "synth/sequence_writer.hpp"

#include "metrics/trajectory_io.hpp"
#include "synth/camera_catalog.hpp"
#include "synth/frame_plan.hpp"
#include "synth/measured_path.hpp"
#include "synth/office.hpp"
#include "synth/reference_frame_error.hpp"
#include "synth/renderer.hpp"
#include "synth/trajectory_families.hpp"
#include "util/files.hpp"

#include "png_encode.hpp"  // plugins/common: libdeflate, one row filter per image, 2.4-4x faster than cv::imwrite

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>

#include <chrono>
#include <future>
#include <optional>

#ifndef VOBENCH_VERSION
#define VOBENCH_VERSION "unknown"
#endif

namespace vobench::synth {
namespace fs = std::filesystem;

namespace {

struct Paths {
    metrics::Trajectory marker;  // empty when the input gave camera poses directly
    metrics::Trajectory camera;  // stamps: seconds
    Eigen::Isometry3d camera_in_marker = Eigen::Isometry3d::Identity();
};

Paths load_paths(const SynthOptions& o, const SensorModel& sensor) {
    Paths p;
    p.camera_in_marker = sensor.camera_in_marker;
    if (!o.camera_in_marker.empty()) p.camera_in_marker = metrics::read_camera_in_marker(o.camera_in_marker);
    if (is_trajectory_family(o.trajectory)) {
        p.marker = family_trajectory(o.trajectory, o.seed);
    } else {
        metrics::ReadOptions ro;
        ro.format = metrics::parse_trajectory_format(o.trajectory_format);
        if (!fs::exists(o.trajectory))
            throw std::invalid_argument("--trajectory: '" + o.trajectory + "' is neither a built-in trajectory (" +
                                        fmt::format("{}", fmt::join(trajectory_family_names(), ", ")) + ") nor a file");
        const auto read = metrics::read_trajectory(o.trajectory, ro);
        if (ro.format == metrics::TrajectoryFormat::Putk2Raw)
            p.marker = read.poses;
        else
            p.camera = read.poses;
    }
    if (!p.marker.empty()) {
        // Kraft et al. 2016, eq. 10: the camera's pose is the marker's pose times camera-in-marker.
        for (const auto& m : p.marker)
            p.camera.push_back(metrics::StampedPose::from_isometry(m.t / kFrameRateHz, m.isometry() * p.camera_in_marker));
    }
    return p;
}

std::string rodrigues_line(const metrics::StampedPose& m) {
    const Eigen::AngleAxisd aa(m.q);
    const Eigen::Vector3d r = aa.axis() * aa.angle();
    return fmt::format("{};{};{};{};{};{};{}", static_cast<long long>(m.t), r.x(), r.y(), r.z(), m.p.x(), m.p.y(), m.p.z());
}

// Where a layout puts a frame's images, and the depth it stores (16-bit).
struct FrameFiles {
    std::string color, depth;
    cv::Mat color8, depth16;
};

FrameFiles frame_files(const std::string& layout, uint64_t k, const std::string& stamp, const std::string& depth_stamp,
                       const RenderedFrame& frame) {
    FrameFiles f;
    f.color8 = frame.color;
    if (layout == "tum") {  // registered to colour, 5000 units per metre
        f.color = "rgb/" + stamp + ".png";
        f.depth = "depth/" + depth_stamp + ".png";
        frame.depth.convertTo(f.depth16, CV_16UC1, 5000.0);
        return f;
    }
    if (layout == "icl-tum") {  // as TUM, but frame-index names and ICL's upside-down images (fy < 0)
        f.color = fmt::format("rgb/{}.png", k);
        f.depth = fmt::format("depth/{}.png", k);
        cv::Mat depth16;
        frame.depth.convertTo(depth16, CV_16UC1, 5000.0);
        cv::flip(frame.color, f.color8, 0);
        cv::flip(depth16, f.depth16, 0);
        return f;
    }
    // PUTK²: the depth camera's own image in millimetres (Kinect v1: the 320×240 registered grid;
    // Kinect v2: 512×424, not registered — the reader registers it).
    f.color = layout == "putk2" ? fmt::format("rgb_{:05d}.png", k) : "rgb/" + stamp + ".png";
    f.depth = layout == "putk2" ? fmt::format("depth_{:05d}.png", k) : "depth/" + depth_stamp + ".png";
    frame.depth_native.convertTo(f.depth16, CV_16UC1, 1000.0);
    return f;
}

std::string pose_line(const Eigen::Isometry3d& T) {  // x y z qw qx qy qz (w first, as PUT's files)
    const Eigen::Quaterniond q(T.linear());
    const Eigen::Vector3d t = T.translation();
    return fmt::format("{} {} {} {} {} {} {}", t.x(), t.y(), t.z(), q.w(), q.x(), q.y(), q.z());
}

// The TUM layout's extras: camera.txt (colour intrinsics for the tum reader), and the marker
// trajectory with the camera-in-marker pose from which groundtruth.txt follows (eq. 10).
void write_tum_calibration(const SynthOptions& o, const SensorModel& sensor, const Paths& paths, uint64_t count) {
    const PinholeCamera& c = sensor.color;
    write_file_atomic(o.out / "camera.txt",
                      fmt::format("# fx fy cx cy k1 k2 p1 p2 k3 k4 k5 k6 (colour camera, OpenCV rational model)\n"
                                  "{} {} {} {} {}\n",
                                  c.fx, c.fy, c.cx, c.cy, fmt::join(c.distortion.begin(), c.distortion.begin() + c.distortion_count, " ")));
    if (paths.marker.empty()) return;
    std::string raw;
    for (uint64_t k = 0; k < count; ++k) raw += rodrigues_line(paths.marker[k]) + "\n";
    write_file_atomic(o.out / "marker_groundtruth.txt", raw);
    write_file_atomic(o.out / "camera_in_marker.txt",
                      "# camera pose in the marker frame: x y z qw qx qy qz\n" + pose_line(paths.camera_in_marker) + "\n");
}

// camera.txt in ICL-NUIM's sign convention (its images are stored upside down: fy < 0, cy from the
// bottom, p1 negated), so the icl_nuim reader's flip gives back the TUM layout's pixels.
void write_icl_calibration(const SynthOptions& o, const SensorModel& sensor) {
    const PinholeCamera& c = sensor.color;
    std::vector<double> d(c.distortion.begin(), c.distortion.begin() + c.distortion_count);
    if (d.size() > 2) d[2] = -d[2];
    write_file_atomic(o.out / "camera.txt",
                      fmt::format("# fx fy cx cy k1 k2 p1 p2 k3 k4 k5 k6, ICL-NUIM convention (fy < 0: images stored upside down)\n"
                                  "{} {} {} {} {}\n",
                                  c.fx, -c.fy, c.cx, (c.height - 1) - c.cy, fmt::join(d, " ")));
}

// ICL-NUIM's POV-Ray layout, frame k: scene_00_kkkk.png (colour as rendered), scene_00_kkkk.depth (text,
// row by row: the distance along each pixel's ray from the camera centre, metres — not z), and
// scene_00_kkkk.txt (POV-Ray camera vectors `name = [x, y, z]';`: cam_pos; cam_dir, the optical axis;
// cam_up, towards the top of the image). The ray of a pixel is its undistorted direction.
void write_povray_frame(const fs::path& out, uint64_t k, const Eigen::Isometry3d& pose, const RenderedFrame& frame,
                        const PinholeCamera& c) {
    const std::string base = fmt::format("scene_00_{:04d}", k);
    files::write_png(out / (base + ".png"), frame.color);
    std::vector<cv::Point2f> pixels, rays;
    for (int v = 0; v < frame.depth.rows; ++v)
        for (int u = 0; u < frame.depth.cols; ++u) pixels.emplace_back(static_cast<float>(u), static_cast<float>(v));
    const cv::Matx33d K(c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1);
    cv::undistortPoints(pixels, rays, K, cv::Mat(1, 8, CV_64F, const_cast<double*>(c.distortion.data())));
    std::string text;
    text.reserve(rays.size() * 10);
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const double z = frame.depth.at<float>(static_cast<int>(i) / frame.depth.cols, static_cast<int>(i) % frame.depth.cols);
        const double d = z * std::sqrt(1.0 + rays[i].x * rays[i].x + rays[i].y * rays[i].y);
        text += fmt::format("{:.6f}", d);
        text += (i + 1) % static_cast<std::size_t>(frame.depth.cols) == 0 ? '\n' : ' ';
    }
    write_file_atomic(out / (base + ".depth"), text);
    const Eigen::Vector3d p = pose.translation(), dir = pose.linear().col(2), up = -pose.linear().col(1);
    auto vec = [](const char* name, const Eigen::Vector3d& v) { return fmt::format("{} = [{}, {}, {}]';\n", name, v.x(), v.y(), v.z()); };
    write_file_atomic(out / (base + ".txt"), vec("cam_pos", p) + vec("cam_dir", dir) + vec("cam_up", up));
}

std::string sim_rows(const Eigen::Isometry3d& T) {
    std::string rows;
    for (int r = 0; r < 3; ++r) rows += fmt::format("{} {} {} {}\n", T(r, 0), T(r, 1), T(r, 2), T(r, 3));
    return rows;
}

// camera.txt for the POV-Ray layout: the images are stored as rendered (fy > 0).
void write_povray_calibration(const SynthOptions& o, const SensorModel& sensor) {
    const PinholeCamera& c = sensor.color;
    write_file_atomic(o.out / "camera.txt", fmt::format("# fx fy cx cy k1 k2 p1 p2 k3 k4 k5 k6\n{} {} {} {} {}\n", c.fx, c.fy, c.cx, c.cy,
                                                        fmt::join(c.distortion.begin(), c.distortion.begin() + c.distortion_count, " ")));
}

// PUTK²'s own files: camData.txt (colour intrinsics under PUT's camera id), cameraZnacznik.txt
// (camera in marker), trajectory.txt (raw marker poses) and, for Kinect v2, depth_camera.txt
// (depth intrinsics, then the depth camera's pose in the colour camera frame).
void write_putk2_calibration(const SynthOptions& o, const SensorModel& sensor, const Paths& paths, uint64_t count) {
    const PinholeCamera& c = sensor.color;
    const std::string id = sensor.name == "kinect1" ? "00022000" : "00033000";
    std::vector<double> d(c.distortion.begin(), c.distortion.end());
    write_file_atomic(o.out / "camData.txt", fmt::format("{}, {}, {}, {}, {}, {}\n", id, c.fx, c.fy, c.cx, c.cy, fmt::join(d, ", ")));
    write_file_atomic(o.out / "cameraZnacznik.txt",
                      "# camera pose in the marker frame\n# x y z qw qx qy qz\n" + pose_line(paths.camera_in_marker) + "\n");
    if (!paths.marker.empty()) {
        std::string raw;
        for (uint64_t k = 0; k < count; ++k) raw += rodrigues_line(paths.marker[k]) + "\n";
        write_file_atomic(o.out / "trajectory.txt", raw);
    }
    if (sensor.principle == DepthPrinciple::TimeOfFlight) {
        const PinholeCamera& dc = sensor.depth;
        write_file_atomic(o.out / "depth_camera.txt",
                          fmt::format("# depth camera: fx fy cx cy, then its pose in the colour camera frame: x y z qw qx qy qz\n"
                                      "{} {} {} {}\n{}\n",
                                      dc.fx, dc.fy, dc.cx, dc.cy, pose_line(sensor.depth_in_color)));
    }
}

// A per-axis figure for synth.json.
std::vector<double> as_list(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

// A stream's fitted clock for synth.json (not fitted: the images were taken at their stamps).
nlohmann::json clock_json(const CameraClock& c) {
    return {{"fitted", c.fitted}, {"period_s", c.period_s}, {"jitter_rms_s", c.jitter_rms_s}, {"off_clock", c.off_clock}};
}

}  // namespace

SynthReport synthesize(const SynthOptions& o, const std::function<void(uint64_t, uint64_t)>& progress) {
    if (o.layout != "tum" && o.layout != "putk2" && o.layout != "putk2-tum" && o.layout != "icl-tum" && o.layout != "icl-povray")
        throw std::invalid_argument("--layout: '" + o.layout + "' is not available (tum, putk2, putk2-tum, icl-tum, icl-povray)");
    if (o.out.empty()) throw std::invalid_argument("--out is required");
    SensorModel sensor = sensor_by_name(o.sensor);
    std::optional<CameraSpec> camera;
    if (!o.camera.empty()) camera = camera_by_name_or_file(o.camera);
    if (camera) sensor = with_color_camera(sensor, *camera);
    sensor.effects = parse_effects(o.effects);
    if (!o.blur) sensor.effects.motion_blur = false;
    const Paths paths = load_paths(o, sensor);
    if (paths.camera.size() < 2) throw std::invalid_argument("the trajectory has fewer than two poses");
    if (!o.stamps.empty() && (o.layout != "tum" || !paths.marker.empty()))
        throw std::invalid_argument("--stamps needs --layout tum and a trajectory file of camera poses (--trajectory-format tum)");
    std::size_t skipped = 0;
    // Only recorded stamps lag their exposures; a built-in trajectory's stamps are the exposures.
    const StampLatency latency =
        !o.stamps.empty() && sensor.effects.stamp_latency ? StampLatency{sensor.color_latency_s, sensor.depth_latency_s} : StampLatency{};
    StampClocks clocks;
    // A trajectory file is a measurement: the camera is rendered along its smoothed path, and the file
    // stays the reference (effect measured_reference). A built-in trajectory is the camera's own path.
    MeasuredPath measured;
    measured.smooth = paths.camera;
    if (sensor.effects.measured_reference && !is_trajectory_family(o.trajectory)) measured = smooth_measured_path(paths.camera);
    const metrics::Trajectory& rendered_path = measured.smooth;
    std::vector<PlannedFrame> plan =
        o.stamps.empty() ? plan_every_pose(rendered_path)
                         : plan_from_tum_stamps(rendered_path, o.stamps, skipped, latency, sensor.effects.stamp_jitter, &clocks);
    if (o.stamps.empty() && sensor.effects.stamp_offsets) offset_depth_stamps(plan, rendered_path, o.seed);
    const uint64_t count = o.frames > 0 ? std::min<uint64_t>(o.frames, plan.size()) : plan.size();
    plan.resize(count);

    // The room is fitted around the whole trajectory (not only the frames rendered), so that a
    // sequence's first N frames are the first N frames of the full sequence. It is built in the
    // office frame (z down); the poses written stay in the trajectory's own frame.
    std::vector<Eigen::Isometry3d> poses;
    for (const auto& c : paths.camera) poses.push_back(c.isometry());
    OfficeOptions office;
    office.seed = o.seed;
    if (camera && camera->min_room_m > 0) office.min_room = camera->min_room_m;
    const Eigen::Isometry3d to_office = office_from_world(poses, office.floor_z);
    for (auto& p : poses) p = to_office * p;
    const Scene scene = build_office(poses, office);
    const Renderer renderer(scene, sensor, o.seed);

    const bool putk2 = o.layout == "putk2" || o.layout == "putk2-tum";
    const bool icl = o.layout == "icl-tum";
    const bool povray = o.layout == "icl-povray";
    fs::create_directories(o.out);
    if (o.layout != "putk2" && !povray) {
        fs::create_directories(o.out / "rgb");
        fs::create_directories(o.out / "depth");
    }
    std::string gt_sim;  // icl-povray: 3×4 [R|t] per frame
    std::string rgb_list = "# color images\n# vobench synth\n# timestamp filename\n";
    std::string depth_list = "# depth maps\n# vobench synth\n# timestamp filename\n";
    std::string matched = "# frame rgb depth\n", associations;
    metrics::Trajectory gt;
    const auto start = std::chrono::steady_clock::now();
    double exposure_reference = 0;  // what the auto-exposure is adapted to (0: not yet)
    std::future<void> pending;      // PNG encoding of frame k overlaps rendering of frame k + 1
    for (uint64_t k = 0; k < count; ++k) {
        const PlannedFrame& planned = plan[k];
        PlannedFrame in_office = planned;
        in_office.color_pose = to_office * planned.color_pose;
        in_office.depth_pose = to_office * planned.depth_pose;
        in_office.next_pose = to_office * planned.next_pose;
        in_office.exposure_reference = exposure_reference;
        RenderedFrame frame = renderer.render(k, in_office, o.blur);
        // The auto-exposure follows the scene's brightness with time constant τ (first order).
        const double dt = k + 1 < count ? std::abs(plan[k + 1].color_stamp - planned.color_stamp) : 0.0;
        const double follow = 1.0 - std::exp(-dt / sensor.exposure_time_constant_s);
        exposure_reference =
            exposure_reference > 0 ? exposure_reference + follow * (frame.mean_luminance - exposure_reference) : frame.mean_luminance;
        const std::string stamp = fmt::format("{:.6f}", planned.color_stamp);
        const std::string depth_stamp = fmt::format("{:.6f}", planned.depth_stamp);
        // The reference: the file's own pose of this frame (one frame per pose here), not the path rendered.
        const auto pose = metrics::StampedPose::from_isometry(
            planned.color_stamp, o.stamps.empty() && k < paths.camera.size() ? paths.camera[k].isometry() : planned.color_pose);
        if (povray) {
            write_povray_frame(o.out, k, planned.color_pose, frame, sensor.color);
            gt_sim += sim_rows(pose.isometry());
            if (progress) progress(k + 1, count);
            continue;
        }
        const FrameFiles images = frame_files(o.layout, k, stamp, depth_stamp, frame);
        rgb_list += stamp + " " + images.color + "\n";
        depth_list += depth_stamp + " " + images.depth + "\n";
        matched += fmt::format("{} {} {}\n", k, images.color, images.depth);
        associations += fmt::format("{} {} {} {}\n", k, images.depth, k, images.color);
        metrics::StampedPose g = pose;
        // TUM: the stamp exactly as written in the lists; PUTK²: the frame index (it has no clock).
        g.t = putk2 || icl ? static_cast<double>(k) : std::stod(stamp);
        gt.push_back(g);
        if (pending.valid()) pending.get();
        pending = std::async(std::launch::async, [&o, images] {
            files::write_png(o.out / images.color, images.color8);
            files::write_png(o.out / images.depth, images.depth16);
        });
        if (progress) progress(k + 1, count);
    }
    if (pending.valid()) pending.get();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    if (povray) {
        write_file_atomic(o.out / "synth.gt.sim", gt_sim);
    } else if (o.layout == "putk2") {
        write_file_atomic(o.out / "matched.txt", matched);
    } else if (icl) {
        write_file_atomic(o.out / "associations.txt", associations);
    } else {
        write_file_atomic(o.out / "rgb.txt", rgb_list);
        write_file_atomic(o.out / "depth.txt", depth_list);
    }
    if (!o.stamps.empty() && count > 0) {
        // As TUM's own files: the motion-capture poses over the frames' span, at their own stamps.
        gt.clear();
        for (const auto& p : paths.camera)
            if (p.t >= plan.front().color_stamp - 0.05 && p.t <= plan.back().color_stamp + 0.05) gt.push_back(p);
    }
    // Effect reference_frame_error: a reference describing a frame a little turned from the optical one,
    // by the camera's measured turn (reference_frame_error.hpp), for camera-pose files as TUM's; PUT's
    // marker files carry their own camera-in-marker calibration, not looked at here. (icl-povray writes
    // its camera files as it renders.)
    const std::array<double, 3> no_turn{};
    const bool turn_reference = sensor.effects.reference_frame_error && sensor.reference_turn_deg != no_turn && paths.marker.empty() &&
                                !is_trajectory_family(o.trajectory) && !povray;
    const std::array<double, 3> turn_deg = turn_reference ? sensor.reference_turn_deg : no_turn;
    if (turn_reference) turn_reference_frame(gt, reference_turn(turn_deg));  // none: the poses as they were, to the last bit
    if (!povray) {
        metrics::write_tum(o.out / (icl ? "synth.gt.freiburg" : "groundtruth.txt"), gt,
                           putk2 || icl ? "vobench synth: camera poses (camera-to-world), stamps are frame indices (10 Hz)"
                                        : "vobench synth: camera poses (camera-to-world)");
    }
    if (putk2)
        write_putk2_calibration(o, sensor, paths, count);
    else if (icl)
        write_icl_calibration(o, sensor);
    else if (povray)
        write_povray_calibration(o, sensor);
    else
        write_tum_calibration(o, sensor, paths, count);
    const nlohmann::json meta{
        {"generator", "vobench synth"},
        {"generator_version", kGeneratorVersion},
        {"vobench_version", VOBENCH_VERSION},
        {"sensor", sensor.name},
        {"trajectory", o.trajectory},
        {"camera", o.camera.empty() ? "default" : o.camera},
        {"color_camera",
         {{"width", sensor.color.width},
          {"height", sensor.color.height},
          {"fx", sensor.color.fx},
          {"fy", sensor.color.fy},
          {"cx", sensor.color.cx},
          {"cy", sensor.color.cy},
          {"distortion",
           std::vector<double>(sensor.color.distortion.begin(), sensor.color.distortion.begin() + sensor.color.distortion_count)}}},
        {"stamps", o.stamps.string()},
        {"skipped_stamps", skipped},
        {"frames", count},
        {"seed", o.seed},
        {"blur", sensor.effects.motion_blur},
        {"auto_exposure", {{"target_linear_luminance", sensor.exposure_target}, {"time_constant_s", sensor.exposure_time_constant_s}}},
        {"effects",
         [&] {
             nlohmann::json e = nlohmann::json::object();
             for (const auto& [name, on] : effect_list(sensor.effects)) e[name] = on;
             return e;
         }()},
        {"layout", o.layout},
        {"frame_rate_hz", kFrameRateHz},
        {"depth_units_per_metre", putk2 ? 1000 : 5000},
        {"exposure_s", sensor.exposure_s},
        {"disparity_distortion_px", sensor.disparity_distortion_px},
        {"disparity_pattern_px",  // Kinect v1's fixed pattern beyond that field (effect disparity_pattern); none for ToF
         sensor.principle == DepthPrinciple::StructuredLight
             ? nlohmann::json{{"sigma", sensor.effects.disparity_pattern ? sensor.disparity_pattern_sigma_px : 0.0},
                              {"lattice", sensor.disparity_pattern_length_px}}
             : nlohmann::json(nullptr)},
        {"shadow_fill_px", sensor.shadow_fill_px},
        {"disparity_noise_px",  // Kinect v1's disparity error: per pixel (over its matching window, part of it repeating from frame to
                                // frame) and its smooth part; none for ToF
         sensor.principle == DepthPrinciple::StructuredLight ? nlohmann::json{{"sigma", sensor.disparity_sigma_px},
                                                                              {"window", sensor.disparity_window_px},
                                                                              {"repeated_share", sensor.disparity_fixed_share},
                                                                              {"repeated_drift", sensor.disparity_fixed_length_px},
                                                                              {"smooth_sigma", sensor.disparity_correlated_sigma_px},
                                                                              {"smooth_correlation", sensor.disparity_correlation_px}}
                                                             : nlohmann::json(nullptr)},
        {"min_room_m", office.min_room},
        {"stamp_latency_s", {{"color", latency.color_s}, {"depth", latency.depth_s}}},  // as rendered
        {"camera_clock", {{"color", clock_json(clocks.color)}, {"depth", clock_json(clocks.depth)}}},
        {"room_boxes", scene.boxes.size()},
        {"reference_turn_deg", turn_deg},  // as written to groundtruth.txt (rotation vector, camera axes)
        {"measured_reference",
         {{"bandwidth_s", measured.bandwidth_s},
          {"noise_rotation_deg", as_list(measured.noise.rotation_rad * (180.0 / M_PI))},
          {"noise_position_m", as_list(measured.noise.position_m)},
          {"residual_rotation_deg", measured.residual_rotation_rad * 180.0 / M_PI},
          {"residual_position_m", measured.residual_position_m}}}};
    write_json_atomic(o.out / "synth.json", meta);
    return {count, skipped, seconds};
}

}  // namespace vobench::synth
