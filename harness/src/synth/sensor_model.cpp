#include "synth/sensor_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vobench::synth {
namespace {

Eigen::Isometry3d pose(double x, double y, double z, double qw, double qx, double qy, double qz) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::Quaterniond(qw, qx, qy, qz).normalized().toRotationMatrix();
    T.translation() = Eigen::Vector3d(x, y, z);
    return T;
}

}  // namespace

SensorModel kinect1() {
    SensorModel s;
    s.name = "kinect1";
    s.principle = DepthPrinciple::StructuredLight;
    // PUT calibration of the Kinect v1 colour camera, camData.txt id 00022000 (640×480; ≈62°×48.6°).
    s.color = {640, 480, 532.77250, 531.85745, 312.23007, 260.11708, 4, {0.16054, -0.24682, 0.00136, 0.00149, 0, 0, 0, 0}};
    // Depth: 320×240 registered to the colour camera (half the colour resolution, same lens
    // distortion: pixel for pixel on the colour image), later upsampled to 640×480 as in the paper. Nominal depth FOV ≈58.5°×46.6° lies
    // inside the colour FOV.
    s.depth = {320, 240, 532.77250 / 2, 531.85745 / 2, 312.23007 / 2, 260.11708 / 2, s.color.distortion_count, s.color.distortion};
    s.depth_in_color = Eigen::Isometry3d::Identity();  // registered by the sensor
    // cameraZnacznikKin1.txt: x y z qw qx qy qz.
    s.camera_in_marker = pose(-0.11474, -0.18851, -0.078635, 0.5129, -0.48145, -0.49094, 0.51393);
    s.exposure_s = 0.015;
    // The auto-exposure follows the scene within about a frame: the renderer's model fitted to the
    // gains measured on the real fr1/rpy frames (`synth stats`, photometric_gain.hpp) gives τ 0.08 s,
    // and the same fit reads renderings back 1.5–2× slower than they were made (0.3 s: 0.19–0.91,
    // 0.1 s: 0.08–0.23); rendered with 0.04 s they read 0.04–0.11 (median of ten offices 0.074).
    s.exposure_time_constant_s = 0.04;
    s.color_noise_dn = 1.2;
    // +mosaic_noise (off by default): σ at the mosaic's sites whose demosaiced grey image reads 0.90 by
    // Immerkær's estimate (real fr1/rpy 0.93); docs/synthetic-sensors.md says why it is not the default.
    s.mosaic_noise_dn = 4.5;
    // smooth_noise: with it the ten rendered offices read Immerkær's σ 0.90–0.93,
    // flat-pixel noise power 2.17–2.40 and neighbour correlation 0.50–0.54 / 0.46–0.51, the real fr1/rpy
    // frames 0.93, 2.18, 0.59 / 0.49 (per-pixel noise alone: 0.90–0.93, 1.11–1.35, 0.30–0.41 / 0.25–0.36).
    s.smooth_noise_dn = 2.0;
    s.smooth_noise_px = 1.0;
    s.tone_contrast = 1.5;  // with +tone_curve: measured, saturated share 8.4 % rendered vs 8.7 % real (fr1/rpy)
    // Measured with the motion blur of generator 12 (sub-pixel streaks rendered): edge sharpness
    // (Laplacian variance / mean gradient²) 0.093 rendered (offices 1, 4, 5, 8) against 0.092 real
    // fr1/rpy; 0.6 px, calibrated while streaks under a pixel were dropped, now reads 0.071.
    s.optics_sigma_px = 0.5;
    s.lateral_sigma_px = 0.3;
    // The disparity noise is averaged over the matching window: on the real fr1/rpy and fr1/desk frames
    // the residuals of 32×32 plane fits at 1.5–3 m are correlated 0.77 / 0.87 with the next pixel,
    // 0.42 / 0.59 at 4 px and 0.10 / 0.25 at 8 px (`synth stats`, "depth noise correlation"), falling
    // about linearly as a box's autocorrelation does; independent draws read 0.59 / 0.37 / 0.15 on the
    // ten offices of the sim-to-real check, the window 0.74 / 0.44 / 0.13, and the 8×8 plane-fit noise
    // at 0–3 m then lies between the two real sequences' (docs/synthetic-sensors.md, "The matching
    // window").
    s.disparity_window_px = 7;
    // fixed_pattern_noise: real fr1/rpy's 32×32 plane-fit residuals at 0.8–3 m correlate 0.26 with the
    // same pixel one frame later and 0.13 four frames later (fr1/desk 0.40 / 0.21; `synth stats`,
    // "depth noise correlation with the same pixel …"); frames drawn anew read 0.05 / 0.02. Half the
    // per-pixel variance repeating, drifting over 8 px of disparity, reads 0.27 / 0.17 (ten offices of
    // the sim-to-real check: 0.25–0.28 / 0.14–0.22); a 2-px drift faded too fast (offices 1 and 2:
    // 0.08–0.09 at four frames). Only those two drifts were tried.
    s.disparity_fixed_share = 0.5;
    s.disparity_fixed_length_px = 8.0;
    // disparity_pattern: real fr1/rpy's fixed disparity pattern, less its best low-order field
    // (`synth stats --camera tum-fr1`, "fixed disparity pattern", disparity_pattern.hpp), reads 0.121 px
    // RMS over 16-px cells, 0.82 alike in the sequence's two halves, correlated 0.56 with itself 64 px
    // away; a field of 0.15 px on a 100-px lattice reads 0.077–0.154 px (median 0.099), 0.82–0.96 and
    // 0.41–0.65 over the ten offices of the sim-to-real check (at 64 px a 120-px lattice read 0.64–0.79 on
    // offices 1 and 2, an 80-px one 0.38–0.40 on office 1, along and across the rows; docs/synthetic-sensors.md, "The unit's disparity
    // pattern").
    s.disparity_pattern_sigma_px = 0.15;
    s.disparity_pattern_length_px = 100.0;
    // correlated_depth_noise: the σ that brings the one-frame depth residual of the rendered fr1/rpy
    // poses to the real one's in every range band (`synth stats --camera tum-fr1`), with the white σ
    // above kept: 0.06 px with independent draws (0–1 / 1–2 / 2–3 / 3+ m asked for 0.059 / 0.054 /
    // 0.068 / 0.058), 0.05 px with the matching window (ten offices: 1.00 / 1.02 / 0.95 / 1.03× the real).
    s.disparity_correlated_sigma_px = 0.05;
    s.disparity_correlation_px = 16;
    // Range: TUM's Kinect v1 depth reaches past 4.5 m and thins out there (fr1/rpy sample: 2.5 % of the
    // valid depth beyond 4 m, 32 % missing; `vobench synth stats`); Khoshelham & Elberink 2012 fit
    // their noise model to 5 m.
    s.max_range_m = 6.0;
    // Both Kinect v1 cameras are rolling-shutter CMOS sensors (Kerl et al. 2015 model their images so);
    // the readout time is not published: 25 ms of the 33 ms frame is assumed.
    s.color_readout_s = 0.025;
    s.depth_readout_s = 0.025;
    // How long TUM's recorded stamps (fr1, OpenNI driver) lag the exposures, measured from the images
    // and the motion-capture reference alone (`vobench synth stats --camera tum-fr1`, stamp_latency.hpp),
    // from each stream's regular clock (camera_clock.hpp; the stamps jitter about it): fr1/rpy colour
    // 4.5 ms, depth 20.8 ms; fr1/desk colour 6.8 ms, depth 17.0 ms. The means of the two.
    s.color_latency_s = 0.0056;
    s.depth_latency_s = 0.0189;
    s.far_dropout_start_m = 3.5;
    // Lost returns (dark, glossy, far, at depth steps) come in patches: the disparity is matched over a
    // correlation window, and a window whose pattern is mostly lost fails as a whole. Measured on the
    // real depth (`synth stats`): 0.75 % of fr1/rpy's missing pixels lie in holes under 50 px and 5.6 %
    // of its valid ones within 2 px of a hole (fr1/desk 0.73 %, 4.0 %); losing pixels one by one in
    // 2-cm blobs gave 4–5.6 % and 14–18.5 %, and the speckle cut dense methods off (RgbdOdometry lost
    // 0–4 frames an office, none on the real sample). An 11-px window over 10-cm blobs gives 0.45–1.1 %
    // and 7.1–9.0 % over ten renderings (docs/synthetic-sensors.md).
    s.dropout_window_px = 11;
    s.dropout_blob_m = 0.10;
    s.glancing_limit_deg = 75.0;
    // The projector's shadow is narrower in the real depth than its geometry (`synth stats --camera`,
    // depth_geometry.hpp): of the depth steps whose shadow would be 4–16 px wide, 34 % show no hole in
    // fr1/rpy (fr1/desk 11 %), and where it would be 8–40 px the hole is 3 px wide (median; fr1/desk
    // 5 px). The geometric shadow leaves 13 % and 11 px (office 1); the occluder's depth run 6 px into
    // it gives 28–48 % and 4–5 px over ten offices, between the two real sequences, and 5.4–7.8 % of
    // the valid depth within 2 px of a hole (real 5.6 %; 7.1–9.0 % before).
    s.shadow_fill_px = 6;
    // The registered depth border, measured on the missing-depth maps of TUM fr1 (rpy and desk agree):
    // 40 columns on the right and 34 rows at the top never measured, 3 rows at the bottom; on the left a
    // ramp whose width falls with range as the IR–colour parallax f·b/z (≈ 13 px at 1 m).
    s.border_left_px_m = 13.0;
    s.border_right_px = 40;
    s.border_top_px = 34;
    s.border_bottom_px = 3;
    return s;
}

SensorModel kinect2() {
    SensorModel s;
    s.name = "kinect2";
    s.principle = DepthPrinciple::TimeOfFlight;
    // PUT calibration of the Kinect v2 colour camera, camData.txt id 00033000 (1920×1080; ≈84°×54°).
    s.color = {
        1920,
        1080,
        1078.68499,
        1076.474256,
        952.6592286,
        530.7386644,
        8,
        {0.02712800285, -0.003876435388, -0.0003782667962, -0.002409935964, 0.05862808573, -0.02856023826, 0.05860957117, 0.03897302154}};
    // Depth: 512×424 with ≈70°×60° FOV (fx = fy ≈ 365.5 px); the depth camera sits ≈5.2 cm beside the
    // colour camera (Kinect v2 hardware; Fankhauser et al. 2015).
    s.depth = {512, 424, 365.5, 365.5, 255.5, 211.5, 0, {}};
    s.depth_in_color = Eigen::Isometry3d::Identity();
    s.depth_in_color.translation() = Eigen::Vector3d(0.052, 0.0, 0.0);
    // cameraZnacznikKin2.txt.
    s.camera_in_marker = pose(-0.10337, -0.11498, -0.21916, 0.55845, -0.44014, -0.44003, 0.54844);
    // The Kinect v2 colour camera lengthens its exposure indoors (it drops to 15 fps in dim light): the
    // blur that Kraft et al. blame for its RPE peaks at speed.
    s.exposure_s = 0.033;
    s.color_noise_dn = 2.5;
    s.lateral_sigma_px = 0.2;
    // Time of flight keeps more of dark surfaces than structured light, at a higher noise (Sarbolandi
    // et al. 2015, Fig. 14; Lachat et al. 2015: black and specular targets lose returns).
    s.color_readout_s = 0.025;  // its colour camera reads rows out one after another too (assumed 25 ms)
    s.depth_readout_s = 0.0;    // ToF: all pixels integrate together
    // Stamp latency: none (there is no real Kinect v2 recording with stamps here to measure it on).
    s.dark_albedo = 0.05;
    s.dark_dropout_max = 0.4;
    s.gloss_dropout = 0.5;
    return s;
}

namespace {

// The switches in one table: name, member.
using EffectMember = bool Effects::*;
const std::vector<std::pair<std::string, EffectMember>>& effect_table() {
    static const std::vector<std::pair<std::string, EffectMember>> table = {{"motion_blur", &Effects::motion_blur},
                                                                            {"optics_blur", &Effects::optics_blur},
                                                                            {"image_noise", &Effects::image_noise},
                                                                            {"mosaic_noise", &Effects::mosaic_noise},
                                                                            {"smooth_noise", &Effects::smooth_noise},
                                                                            {"vignetting", &Effects::vignetting},
                                                                            {"auto_exposure", &Effects::auto_exposure},
                                                                            {"tone_curve", &Effects::tone_curve},
                                                                            {"highlights", &Effects::highlights},
                                                                            {"rolling_shutter", &Effects::rolling_shutter},
                                                                            {"depth_noise", &Effects::depth_noise},
                                                                            {"correlated_depth_noise", &Effects::correlated_depth_noise},
                                                                            {"fixed_pattern_noise", &Effects::fixed_pattern_noise},
                                                                            {"disparity_pattern", &Effects::disparity_pattern},
                                                                            {"projector_shadow", &Effects::projector_shadow},
                                                                            {"depth_border", &Effects::depth_border},
                                                                            {"dark_dropout", &Effects::dark_dropout},
                                                                            {"glancing_dropout", &Effects::glancing_dropout},
                                                                            {"far_dropout", &Effects::far_dropout},
                                                                            {"edge_dropout", &Effects::edge_dropout},
                                                                            {"registration_error", &Effects::registration_error},
                                                                            {"flying_pixels", &Effects::flying_pixels},
                                                                            {"stamp_offsets", &Effects::stamp_offsets},
                                                                            {"stamp_latency", &Effects::stamp_latency},
                                                                            {"stamp_jitter", &Effects::stamp_jitter},
                                                                            {"depth_distortion", &Effects::depth_distortion},
                                                                            {"measured_reference", &Effects::measured_reference},
                                                                            {"reference_frame_error", &Effects::reference_frame_error}};
    return table;
}

}  // namespace

Effects parse_effects(const std::string& spec) {
    Effects e;
    std::size_t start = 0;
    while (start <= spec.size()) {
        const std::size_t comma = std::min(spec.find(',', start), spec.size());
        std::string item = spec.substr(start, comma - start);
        start = comma + 1;
        item.erase(0, item.find_first_not_of(" \t"));
        item.erase(item.find_last_not_of(" \t") + 1);
        if (item.empty()) continue;
        if (item == "all" || item == "none") {
            for (const auto& [name, member] : effect_table()) e.*member = item == "all" && name != "stamp_offsets";
            continue;
        }
        const bool on = item[0] != '-';
        if (item[0] == '+' || item[0] == '-') item.erase(0, 1);
        bool found = false;
        for (const auto& [name, member] : effect_table())
            if (name == item) {
                e.*member = on;
                found = true;
            }
        if (!found) {
            std::string names;
            for (const auto& [name, member] : effect_table()) names += (names.empty() ? "" : ", ") + name;
            throw std::invalid_argument("--effects: unknown effect '" + item + "' (all, none, or [+|-] one of: " + names + ")");
        }
    }
    return e;
}

std::vector<std::pair<std::string, bool>> effect_list(const Effects& e) {
    std::vector<std::pair<std::string, bool>> list;
    for (const auto& [name, member] : effect_table()) list.emplace_back(name, e.*member);
    return list;
}

SensorModel sensor_by_name(const std::string& name) {
    if (name == "kinect1") return kinect1();
    if (name == "kinect2") return kinect2();
    throw std::invalid_argument("unknown sensor '" + name + "' (kinect1 or kinect2)");
}

double kinect2_sigma_z(double z, double theta) {
    const double t = std::min(theta, 1.45);  // the fit diverges at grazing incidence
    const double mm = 1.5 - 0.5 * z + 0.3 * z * z + 0.1 * std::pow(z, 1.5) * t * t / ((M_PI / 2 - t) * (M_PI / 2 - t));
    return mm * 1e-3;
}

}  // namespace vobench::synth
