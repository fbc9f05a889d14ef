// camera_clock.hpp — the regular clock a camera exposes its frames on, fitted to recorded stamps.
//
// A Kinect exposes on its own free-running clock (30 Hz); a TUM list stamp is when the host received
// the image, so the stamps jitter about that clock (fr1/rpy: 2.4 ms rms colour, 1.9 ms depth; fr1/desk
// 1.2 ms, 1.3 ms). Measured on TUM fr1, the images follow the clock, not the stamps:
//   - image motion between consecutive frames (median LK flow) does not grow with the stamp interval
//     (correlation 0.01 over fr1/rpy's 89 pairs), while the reference's rotation over it does (0.35);
//   - the reference explains the images better at the clock's ticks than at the stamps: the colour
//     stream's photometric residual at the best latency (stamp_latency.hpp) falls from 32.4 to 25.4 grey
//     levels (fr1/rpy) and from 18.6 to 17.2 (fr1/desk); the depth residual by 5 % on both.
// So a rendering of real stamps exposes each image at its tick (effect `stamp_jitter`), and the error
// the jitter puts into every real RPE figure (the reference is read at the stamp) is in the rendered
// figures too. Fitting: frame numbers from the intervals rounded to the median interval (so dropped
// frames count), then a least-squares line through (frame number, stamp), refitted without the stamps
// more than a quarter period off it. See docs/synthetic-sensors.md.
#pragma once

#include <cstddef>
#include <vector>

namespace vobench::synth {

struct CameraClock {
    std::vector<double> ticks;  // one per stamp: the clock's time of that frame (the stamp itself where off the clock)
    double period_s = 0;        // the fitted frame period (0: not fitted)
    double jitter_rms_s = 0;    // rms of the stamps about their ticks, over those on the clock
    std::size_t off_clock = 0;  // stamps more than a quarter period from the line: kept as they are
    bool fitted = false;        // false: fewer than three stamps, or not strictly increasing; ticks = stamps
};

CameraClock fit_camera_clock(const std::vector<double>& stamps);

}  // namespace vobench::synth
