"""The smallest vobench odometry plugin in Python: it reports the first frame's pose (identity) for
every frame, so it scores what constant_pose scores. Copy it and fill in process().

    vobench track --dataset tum --sequence DIR --plugin python --param module=template.py
"""
import numpy as np

import vobench  # the host: vobench.stage("name"), vobench.counter("name", value), vobench.log("text")


class Odometry:
    # Parameters: name -> (type, default, help[, min, max]); type bool, int, float, str or a tuple of
    # words. They appear in `vobench plugins info python --param module=template.py`, are validated
    # like any plugin's, and can be swept in a config's grid.
    PARAMS = {
        "scale": (float, 1.0, "an example parameter (unused)", 0.0, 10.0),
    }

    def __init__(self, camera, params, seed):
        # camera: width, height, fx, fy, cx, cy, K (3x3), distortion_model, distortion
        # params: {"scale": 1.0, ...} typed; seed: int, for any randomness
        self.camera = camera
        self.params = params
        self.pose = np.eye(4)

    def process(self, frame):
        # frame.rgb (H x W x 3 uint8), frame.bgr, frame.depth (H x W float32 metres, NaN = none),
        # frame.depth_raw, frame.depth_scale, frame.timestamp, frame.depth_timestamp, frame.index.
        # The arrays are valid during this call only: keep copies, not the arrays.
        with vobench.stage("tracking"):
            pass
        return self.pose, "ok"  # 4x4 camera-to-world (or (t, q) with q = x y z w); "ok" | "lost" | "failed"

    def reset(self):  # optional
        self.pose = np.eye(4)
