#include "synth/camera_clock.hpp"

#include <algorithm>
#include <cmath>

namespace vobench::synth {
namespace {

struct Line {
    double offset = 0, slope = 0;  // t − t0 = offset + slope · frame
    bool ok = false;
};

// Least squares through (frame[i], t[i]) for the points `use` selects.
Line fit_line(const std::vector<double>& frame, const std::vector<double>& t, const std::vector<bool>& use) {
    double n = 0, mf = 0, mt = 0;
    for (std::size_t i = 0; i < t.size(); ++i)
        if (use[i]) {
            n += 1;
            mf += frame[i];
            mt += t[i];
        }
    if (n < 2) return {};
    mf /= n;
    mt /= n;
    double sff = 0, sft = 0;
    for (std::size_t i = 0; i < t.size(); ++i)
        if (use[i]) {
            sff += (frame[i] - mf) * (frame[i] - mf);
            sft += (frame[i] - mf) * (t[i] - mt);
        }
    if (!(sff > 0)) return {};
    Line l;
    l.slope = sft / sff;
    l.offset = mt - l.slope * mf;
    l.ok = l.slope > 0 && std::isfinite(l.slope) && std::isfinite(l.offset);
    return l;
}

}  // namespace

CameraClock fit_camera_clock(const std::vector<double>& stamps) {
    CameraClock clock;
    clock.ticks = stamps;
    const std::size_t n = stamps.size();
    if (n < 3) return clock;
    for (std::size_t i = 0; i < n; ++i)
        if (!std::isfinite(stamps[i]) || (i > 0 && !(stamps[i] > stamps[i - 1]))) return clock;
    std::vector<double> intervals(n - 1);
    for (std::size_t i = 1; i < n; ++i) intervals[i - 1] = stamps[i] - stamps[i - 1];
    std::nth_element(intervals.begin(), intervals.begin() + static_cast<long>(intervals.size() / 2), intervals.end());
    const double nominal = intervals[intervals.size() / 2];
    // Frame numbers: each interval counts the frame periods it spans, at least one.
    std::vector<double> frame(n, 0.0), t(n);
    for (std::size_t i = 0; i < n; ++i) t[i] = stamps[i] - stamps[0];  // relative: full precision in the fit
    for (std::size_t i = 1; i < n; ++i) frame[i] = frame[i - 1] + std::max(1.0, std::round((stamps[i] - stamps[i - 1]) / nominal));
    std::vector<bool> use(n, true);
    Line line = fit_line(frame, t, use);
    if (!line.ok) return clock;
    // Once more without the stamps a quarter period or more off the line (a stalled transfer, a pause).
    const double tolerance = 0.25 * line.slope;
    for (std::size_t i = 0; i < n; ++i) use[i] = std::abs(t[i] - (line.offset + line.slope * frame[i])) < tolerance;
    line = fit_line(frame, t, use);
    if (!line.ok) return clock;
    double squares = 0, on = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const double tick = line.offset + line.slope * frame[i];
        if (std::abs(t[i] - tick) >= tolerance) {
            ++clock.off_clock;
            continue;
        }
        clock.ticks[i] = stamps[0] + tick;
        squares += (t[i] - tick) * (t[i] - tick);
        on += 1;
    }
    clock.period_s = line.slope;
    clock.jitter_rms_s = on > 0 ? std::sqrt(squares / on) : 0.0;
    clock.fitted = true;
    return clock;
}

}  // namespace vobench::synth
