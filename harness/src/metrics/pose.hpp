// pose.hpp — the stamped pose every metric works on (TUM convention: camera-to-world, seconds).
#pragma once

#include <Eigen/Geometry>

#include <vector>

namespace vobench::metrics {

struct StampedPose {
    double t = 0.0;
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    Eigen::Quaterniond q = Eigen::Quaterniond::Identity();

    Eigen::Isometry3d isometry() const {
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.linear() = q.toRotationMatrix();
        T.translation() = p;
        return T;
    }
    static StampedPose from_isometry(double stamp, const Eigen::Isometry3d& T) {
        StampedPose s;
        s.t = stamp;
        s.p = T.translation();
        s.q = Eigen::Quaterniond(T.linear()).normalized();
        return s;
    }
};

// Sorted by stamp, stamps unique, unless a reader's warning says otherwise.
using Trajectory = std::vector<StampedPose>;

}  // namespace vobench::metrics
