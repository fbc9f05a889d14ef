// wall_rig.hpp — a test scene for the sensor models: a camera at the origin and a flat wall ahead.
#pragma once

#include "synth/scene.hpp"

#include <Eigen/Geometry>

namespace vobench::synth {

// A camera at the origin looking along world +x (camera z → world x, camera x → world −y, camera y →
// world z, i.e. down: the PUTK² world has z down), a wall at distance `wall`, and optionally a box
// covering the left half of the view at distance `near`.
struct TestRig {
    Scene scene;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    TestRig(double wall, double near = 0) {
        Material m;
        m.style = TextureStyle::Paint;
        m.base = Eigen::Vector3f(0.6f, 0.6f, 0.6f);
        scene.materials = {m, m, m, m, m, m, m};
        scene.boxes.push_back({Eigen::Vector3d(-20, -20, -20), Eigen::Vector3d(wall, 20, 20), 0, true});
        if (near > 0)
            scene.boxes.push_back(
                {Eigen::Vector3d(near, 0.0, -20), Eigen::Vector3d(near + 0.02, 20, 20), 6, false});  // thin: no side face in view
        Eigen::Matrix3d R;
        R.col(0) = Eigen::Vector3d(0, -1, 0);  // camera x
        R.col(1) = Eigen::Vector3d(0, 0, 1);   // camera y
        R.col(2) = Eigen::Vector3d(1, 0, 0);   // camera z
        pose.linear() = R;
    }
};

}  // namespace vobench::synth
