#include "synth/trajectory_families.hpp"

#include "synth/random_field.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace vobench::synth {
namespace {

constexpr double kDeg = M_PI / 180.0;

struct Step {
    enum Kind { Straight, Turn, Arc } kind;
    double amount;  // metres (negative: backwards) or radians
    double speed;   // m/s, or rad/s for turns
    double radius;  // arcs only
};

// Integrates motion primitives at 10 Hz with short acceleration ramps.
class PathBuilder {
public:
    explicit PathBuilder(double start_heading = 0.0) : heading_(start_heading) { emit(); }

    void run(const std::vector<Step>& steps) {
        for (const Step& s : steps) {
            switch (s.kind) {
                case Step::Straight: straight(s.amount, s.speed); break;
                case Step::Turn: turn(s.amount, s.speed); break;
                case Step::Arc: arc(s.amount, s.speed, s.radius); break;
            }
        }
    }
    const std::vector<std::array<double, 3>>& states() const { return states_; }

private:
    static double ramped(double travelled, double total, double peak) {
        const double ramp = std::min(0.25 * total, 0.5 * peak);  // reach full speed within ~0.5 s
        const double edge = std::min(travelled, total - travelled);
        return ramp <= 0 ? peak : peak * std::clamp(0.2 + 0.8 * edge / ramp, 0.2, 1.0);
    }
    void straight(double distance, double speed) {
        const double total = std::abs(distance), dir = distance < 0 ? -1.0 : 1.0;
        for (double done = 0; done < total;) {
            const double step = std::min(ramped(done, total, speed) / kFrameRateHz, total - done);
            x_ += dir * step * std::cos(heading_);
            y_ += dir * step * std::sin(heading_);
            done += step;
            emit();
        }
    }
    void turn(double angle, double rate) {
        const double total = std::abs(angle), dir = angle < 0 ? -1.0 : 1.0;
        for (double done = 0; done < total;) {
            const double step = std::min(ramped(done, total, rate) / kFrameRateHz, total - done);
            heading_ += dir * step;
            done += step;
            emit();
        }
    }
    void arc(double angle, double speed, double radius) {
        const double total = std::abs(angle) * radius, dir = angle < 0 ? -1.0 : 1.0;
        for (double done = 0; done < total;) {
            const double step = std::min(ramped(done, total, speed) / kFrameRateHz, total - done);
            heading_ += dir * step / (2 * radius);
            x_ += step * std::cos(heading_);
            y_ += step * std::sin(heading_);
            heading_ += dir * step / (2 * radius);
            done += step;
            emit();
        }
    }
    void emit() { states_.push_back({x_, y_, heading_}); }

    double x_ = 0, y_ = 0, heading_;
    std::vector<std::array<double, 3>> states_;
};

std::vector<Step> family_steps(const std::string& name) {
    using S = Step;
    const double v = 0.13, w = 30 * kDeg;  // PUTK² exploration: ≈0.12–0.16 m/s; sudden turns
    if (name == "explore1")                // a loop around a rectangle and back: 18.6 m
        return {{S::Straight, 4.0, v, 0}, {S::Turn, 90 * kDeg, w, 0}, {S::Straight, 2.2, v, 0},     {S::Turn, 90 * kDeg, w, 0},
                {S::Straight, 4.0, v, 0}, {S::Turn, 90 * kDeg, w, 0}, {S::Straight, 2.2, v, 0},     {S::Turn, 90 * kDeg, w, 0},
                {S::Straight, 3.0, v, 0}, {S::Straight, -1.5, v, 0},  {S::Turn, -120 * kDeg, w, 0}, {S::Straight, 1.7, v, 0}};
    if (name == "explore2")  // a figure of eight with long straights: 27 m
        return {{S::Straight, 3.5, v, 0},      {S::Arc, 180 * kDeg, v, 1.0}, {S::Straight, 3.5, v, 0},
                {S::Arc, -180 * kDeg, v, 1.0}, {S::Straight, 3.5, v, 0},     {S::Arc, 180 * kDeg, v, 1.0},
                {S::Straight, 2.0, v, 0},      {S::Turn, 90 * kDeg, w, 0},   {S::Straight, 1.5, v, 0}};
    if (name == "explore3")  // back and forth with reversing and sudden turns: 31 m
        return {{S::Straight, 5.0, 0.15, 0},         {S::Straight, -2.0, 0.12, 0},        {S::Turn, 90 * kDeg, 40 * kDeg, 0},
                {S::Straight, 2.0, 0.15, 0},         {S::Turn, 90 * kDeg, 40 * kDeg, 0},  {S::Straight, 5.0, 0.15, 0},
                {S::Straight, -1.5, 0.12, 0},        {S::Turn, -90 * kDeg, 40 * kDeg, 0}, {S::Straight, 2.5, 0.15, 0},
                {S::Turn, -90 * kDeg, 40 * kDeg, 0}, {S::Straight, 5.0, 0.15, 0},         {S::Turn, 180 * kDeg, 40 * kDeg, 0},
                {S::Straight, 6.0, 0.15, 0}};
    if (name == "explore4")  // zig-zag and two loops, the longest: 38 m
        return {{S::Straight, 3.0, v, 0},  {S::Turn, 45 * kDeg, w, 0},  {S::Straight, 2.5, v, 0}, {S::Turn, -90 * kDeg, w, 0},
                {S::Straight, 2.5, v, 0},  {S::Turn, 45 * kDeg, w, 0},  {S::Straight, 3.0, v, 0}, {S::Arc, 360 * kDeg, v, 1.2},
                {S::Straight, -2.0, v, 0}, {S::Turn, 180 * kDeg, w, 0}, {S::Straight, 6.0, v, 0}, {S::Arc, -360 * kDeg, v, 1.0},
                {S::Straight, 4.0, v, 0},  {S::Turn, -90 * kDeg, w, 0}, {S::Straight, 2.0, v, 0}};
    // One path, four speeds (PUTK² sequences 5–8): straight, a quarter arc, straight; 6.3 m.
    const double speeds[4] = {0.16, 0.38, 0.75, 1.04};
    for (int k = 0; k < 4; ++k)
        if (name == "speed" + std::to_string(k + 1)) {
            const double s = speeds[k];
            return {{S::Straight, 3.0, s, 0}, {S::Arc, 90 * kDeg, s, 1.0}, {S::Straight, 1.73, s, 0}};
        }
    throw std::invalid_argument("unknown trajectory '" + name + "' (explore1..4, speed1..4, or a trajectory file)");
}

// Smooth noise in time, for vibrations: value noise over frames, amplitude 1.
double wobble(uint64_t seed, uint64_t channel, double t) {
    const double f = std::floor(t);
    const double a = 2 * uniform(hash(seed, channel, static_cast<uint64_t>(f))) - 1;
    const double b = 2 * uniform(hash(seed, channel, static_cast<uint64_t>(f) + 1)) - 1;
    const double s = t - f;
    return a + (b - a) * s * s * (3 - 2 * s);
}

}  // namespace

std::vector<std::string> trajectory_family_names() {
    return {"explore1", "explore2", "explore3", "explore4", "speed1", "speed2", "speed3", "speed4"};
}

bool is_trajectory_family(const std::string& name) {
    for (const auto& n : trajectory_family_names())
        if (n == name) return true;
    return false;
}

metrics::Trajectory family_trajectory(const std::string& name, uint64_t seed) {
    PathBuilder builder;
    builder.run(family_steps(name));
    metrics::Trajectory out;
    std::size_t k = 0;
    for (const auto& [x, y, heading] : builder.states()) {
        const double t = static_cast<double>(k) / kFrameRateHz;
        // Marker orientation as in the real data: flipped about x (its z points up, the world's down),
        // then turned about the world's z; the cameras look along the marker's −x, hence ψ = heading + π.
        const double roll = 0.15 * kDeg * wobble(seed, 1, t * 3), pitch = 0.15 * kDeg * wobble(seed, 2, t * 3);
        const Eigen::Matrix3d R = Eigen::AngleAxisd(heading + M_PI, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
                                  Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix() *
                                  Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()).toRotationMatrix() *
                                  Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()).toRotationMatrix();
        Eigen::Isometry3d M = Eigen::Isometry3d::Identity();
        M.linear() = R;
        M.translation() = Eigen::Vector3d(x, y, kMarkerZ + 0.001 * wobble(seed, 3, t * 2));
        out.push_back(metrics::StampedPose::from_isometry(static_cast<double>(k), M));
        ++k;
    }
    return out;
}

}  // namespace vobench::synth
