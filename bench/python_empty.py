"""The empty Python odometry plugin of the bridge benchmarks: process() returns a stored pose, so what
is timed is the bridge (bench/odometry_bench.cpp, bench/python_bridge.sh)."""
import numpy as np


class Odometry:
    def __init__(self, camera, params, seed):
        self.pose = np.eye(4)

    def process(self, frame):
        return self.pose, "ok"

    def reset(self):
        pass
