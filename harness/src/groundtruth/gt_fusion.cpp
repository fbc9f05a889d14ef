#include "groundtruth/gt_fusion.hpp"

#include "metrics/trajectory_io.hpp"
#include "util/files.hpp"

#include <fmt/format.h>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vobench::gt {

namespace {

using Mat12 = Eigen::Matrix<double, 12, 12>;
using Vec12 = Eigen::Matrix<double, 12, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec6 = Eigen::Matrix<double, 6, 1>;

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
    Eigen::Matrix3d m;
    m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
    return m;
}

Eigen::Matrix3d exp_so3(const Eigen::Vector3d& w) {
    const double angle = w.norm();
    if (angle < 1e-12) return Eigen::Matrix3d::Identity() + skew(w);
    return Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
}

Eigen::Vector3d log_so3(const Eigen::Matrix3d& R) {
    const Eigen::AngleAxisd aa(R);
    return aa.angle() * aa.axis();
}

struct State {
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    Eigen::Vector3d v = Eigen::Vector3d::Zero(), w = Eigen::Vector3d::Zero();

    State plus(const Vec12& d) const {  // x ⊕ δ
        State s = *this;
        s.p += d.segment<3>(0);
        s.R = R * exp_so3(d.segment<3>(3));
        s.v += d.segment<3>(6);
        s.w += d.segment<3>(9);
        return s;
    }
    Vec12 minus(const State& o) const {  // x ⊖ o: the δ with o ⊕ δ = x
        Vec12 d;
        d << p - o.p, log_so3(o.R.transpose() * R), v - o.v, w - o.w;
        return d;
    }
};

struct Measurement {
    double t;
    const metrics::StampedPose* pose;
    double sigma_pos, sigma_rot;  // m, rad
};

// Pose of a trajectory at t by linear/slerp interpolation; nullopt outside it.
std::optional<Eigen::Isometry3d> interpolate(const metrics::Trajectory& traj, double t) {
    if (traj.empty() || t < traj.front().t || t > traj.back().t) return std::nullopt;
    const auto it = std::lower_bound(traj.begin(), traj.end(), t, [](const metrics::StampedPose& p, double s) { return p.t < s; });
    if (it == traj.begin()) return traj.front().isometry();
    const auto& b = *it;
    const auto& a = *(it - 1);
    const double u = b.t > a.t ? (t - a.t) / (b.t - a.t) : 0.0;
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = (1 - u) * a.p + u * b.p;
    T.linear() = a.q.slerp(u, b.q).toRotationMatrix();
    return T;
}

void update(State& x, Mat12& P, const Eigen::MatrixXd& H, const Eigen::VectorXd& r, const Eigen::MatrixXd& noise) {
    const Eigen::MatrixXd S = H * P * H.transpose() + noise;
    const Eigen::MatrixXd K = P * H.transpose() * S.inverse();
    x = x.plus(K * r);
    const Mat12 IKH = Mat12::Identity() - K * H;
    P = IKH * P * IKH.transpose() + K * noise * K.transpose();  // Joseph form: stays symmetric positive
}

}  // namespace

std::vector<FusedPose> fuse_ground_truth(const PoseStream& a, const PoseStream& b, const FusionOptions& o) {
    if (a.poses.empty() || b.poses.empty()) throw std::invalid_argument("gt fuse: both streams need poses");
    for (const PoseStream* s : {&a, &b})
        if (!(s->sigma_pos_m > 0) || !(s->sigma_rot_deg > 0)) throw std::invalid_argument("gt fuse: sigmas must be positive");
    constexpr double kDeg = M_PI / 180.0;
    std::vector<Measurement> events;
    for (const auto& p : a.poses) events.push_back({p.t, &p, a.sigma_pos_m, a.sigma_rot_deg * kDeg});
    for (const auto& p : b.poses) events.push_back({p.t, &p, b.sigma_pos_m, b.sigma_rot_deg * kDeg});
    std::stable_sort(events.begin(), events.end(), [](const Measurement& x, const Measurement& y) { return x.t < y.t; });

    // Steps: distinct stamps, each with the measurements that fall on it.
    std::vector<double> stamps;
    std::vector<std::vector<const Measurement*>> at;
    for (const Measurement& m : events) {
        if (stamps.empty() || m.t - stamps.back() > o.merge_dt) {
            stamps.push_back(m.t);
            at.emplace_back();
        }
        at.back().push_back(&m);
    }
    const std::size_t n = stamps.size();
    std::vector<State> x_pred(n), x_filt(n);
    std::vector<Mat12> P_pred(n), P_filt(n), F(n, Mat12::Identity());

    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(6, 12);
    H.block<3, 3>(0, 0).setIdentity();
    H.block<3, 3>(3, 3).setIdentity();
    Eigen::MatrixXd Hv = Eigen::MatrixXd::Zero(6, 12);
    Hv.block<3, 3>(0, 6).setIdentity();
    Hv.block<3, 3>(3, 9).setIdentity();

    State x;
    x.p = at[0][0]->pose->p;
    x.R = at[0][0]->pose->q.toRotationMatrix();
    Mat12 P = Mat12::Zero();
    P.diagonal() << Eigen::Vector3d::Constant(at[0][0]->sigma_pos * at[0][0]->sigma_pos),
        Eigen::Vector3d::Constant(at[0][0]->sigma_rot * at[0][0]->sigma_rot), Eigen::Vector3d::Constant(1.0),
        Eigen::Vector3d::Constant(1.0);
    for (std::size_t k = 0; k < n; ++k) {
        if (k > 0) {
            const double dt = stamps[k] - stamps[k - 1];
            Mat12& Fk = F[k];
            Fk.setIdentity();
            Fk.block<3, 3>(0, 3) = -x.R * skew(x.v) * dt;
            Fk.block<3, 3>(0, 6) = x.R * dt;
            Fk.block<3, 3>(3, 3) = exp_so3(x.w * dt).transpose();
            Fk.block<3, 3>(3, 9) = Eigen::Matrix3d::Identity() * dt;
            x.p += x.R * x.v * dt;
            x.R = x.R * exp_so3(x.w * dt);
            Mat12 Q = Mat12::Zero();
            Q.diagonal() << Eigen::Vector3d::Constant(1e-10 * dt), Eigen::Vector3d::Constant(1e-10 * dt),
                Eigen::Vector3d::Constant(o.accel_noise * o.accel_noise * dt), Eigen::Vector3d::Constant(o.gyro_noise * o.gyro_noise * dt);
            P = Fk * P * Fk.transpose() + Q;
        }
        x_pred[k] = x;
        P_pred[k] = P;
        for (const Measurement* m : at[k]) {
            Eigen::VectorXd r(6);
            r << m->pose->p - x.p, log_so3(x.R.transpose() * m->pose->q.toRotationMatrix());
            Eigen::MatrixXd noise = Eigen::MatrixXd::Zero(6, 6);
            noise.diagonal() << Eigen::Vector3d::Constant(m->sigma_pos * m->sigma_pos),
                Eigen::Vector3d::Constant(m->sigma_rot * m->sigma_rot);
            update(x, P, H, r, noise);
        }
        if (o.odometry && k > 0) {
            const auto T0 = interpolate(o.odometry->poses, stamps[k - 1]), T1 = interpolate(o.odometry->poses, stamps[k]);
            const double dt = stamps[k] - stamps[k - 1];
            if (T0 && T1 && dt > 0) {
                const Eigen::Isometry3d d = T0->inverse() * *T1;  // body motion over the step
                Eigen::VectorXd r(6);
                r << d.translation() / dt - x.v, log_so3(d.linear()) / dt - x.w;
                Eigen::MatrixXd noise = Eigen::MatrixXd::Zero(6, 6);
                const double sp = o.odometry->sigma_pos_m, sr = o.odometry->sigma_rot_deg * kDeg;
                noise.diagonal() << Eigen::Vector3d::Constant(sp * sp), Eigen::Vector3d::Constant(sr * sr);
                update(x, P, Hv, r, noise);
            }
        }
        x_filt[k] = x;
        P_filt[k] = P;
    }

    // Rauch–Tung–Striebel, backward, in error-state form.
    std::vector<State> x_s(n);
    std::vector<Mat12> P_s(n);
    x_s[n - 1] = x_filt[n - 1];
    P_s[n - 1] = P_filt[n - 1];
    for (std::size_t k = n - 1; k-- > 0;) {
        const Mat12 C = P_filt[k] * F[k + 1].transpose() * P_pred[k + 1].inverse();
        x_s[k] = x_filt[k].plus(C * x_s[k + 1].minus(x_pred[k + 1]));
        P_s[k] = P_filt[k] + C * (P_s[k + 1] - P_pred[k + 1]) * C.transpose();
    }
    std::vector<FusedPose> out(n);
    for (std::size_t k = 0; k < n; ++k) {
        out[k].pose.t = stamps[k];
        out[k].pose.p = x_s[k].p;
        out[k].pose.q = Eigen::Quaterniond(x_s[k].R).normalized();
        out[k].covariance = P_s[k].block<6, 6>(0, 0);
    }
    return out;
}

void write_fused(const std::filesystem::path& file, const std::vector<FusedPose>& fused) {
    metrics::Trajectory t;
    std::string cov = "# stamp, then the 6x6 covariance of [position (m), rotation about the body axes (rad)], row-major\n";
    for (const FusedPose& f : fused) {
        t.push_back(f.pose);
        cov += fmt::format("{:.9f}", f.pose.t);
        for (int r = 0; r < 6; ++r)
            for (int c = 0; c < 6; ++c) cov += fmt::format(" {:.9e}", f.covariance(r, c));
        cov += "\n";
    }
    metrics::write_tum(file, t, "vobench gt fuse: EKF forward, RTS smoother backward");
    write_file_atomic(file.string() + ".cov", cov);
}

}  // namespace vobench::gt
