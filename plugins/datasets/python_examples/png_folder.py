"""png_folder — a vobench dataset reader in Python for the simplest layout there is:

    FOLDER/rgb/*.png     colour images, sorted by name
    FOLDER/depth/*.png   16-bit depth images, the same count, paired with the colour images in order
    FOLDER/poses.txt     one line per frame: timestamp tx ty tz qx qy qz qw (camera-to-world, TUM)
    FOLDER/camera.txt    optional: a line "fx fy cx cy" (else the fx, fy, cx, cy options)

    vobench track --dataset python_dataset --option module=png_folder.py --path FOLDER --algorithm put_vo
"""
import glob
import os

import cv2
import numpy as np


class Dataset:
    PARAMS = {
        "depth_scale": (float, 1.0 / 5000.0, "metres per depth unit of the PNGs", 1e-9, 1.0),
        "fx": (float, 525.0, "focal length x, pixels (when there is no camera.txt)", 1.0, 1e5),
        "fy": (float, 525.0, "focal length y, pixels", 1.0, 1e5),
        "cx": (float, 319.5, "principal point x, pixels", -1e5, 1e5),
        "cy": (float, 239.5, "principal point y, pixels", -1e5, 1e5),
    }

    def open(self, path, options):
        self.rgb = sorted(glob.glob(os.path.join(path, "rgb", "*.png")))
        self.depth = sorted(glob.glob(os.path.join(path, "depth", "*.png")))
        if not self.rgb or len(self.rgb) != len(self.depth):
            raise ValueError(f"{path}: {len(self.rgb)} colour and {len(self.depth)} depth PNGs (need as many, at least one)")
        self.poses = np.loadtxt(os.path.join(path, "poses.txt"), comments="#", ndmin=2)
        if self.poses.shape != (len(self.rgb), 8):
            raise ValueError(f"{path}/poses.txt: {self.poses.shape[0]} lines of {self.poses.shape[1]} numbers, "
                             f"need {len(self.rgb)} of 8 (t tx ty tz qx qy qz qw)")
        self.scale = options["depth_scale"]
        self.k = [options[key] for key in ("fx", "fy", "cx", "cy")]
        camera_file = os.path.join(path, "camera.txt")
        if os.path.exists(camera_file):
            self.k = [float(v) for v in np.loadtxt(camera_file, comments="#", ndmin=1)[:4]]
        height, width = cv2.imread(self.rgb[0], cv2.IMREAD_COLOR).shape[:2]
        self.size = (width, height)
        self.name = os.path.basename(os.path.normpath(path))

    def describe(self):
        fx, fy, cx, cy = self.k
        return {"name": self.name, "sensor": "unknown", "frame_count": len(self.rgb), "depth_scale": self.scale,
                "camera": {"width": self.size[0], "height": self.size[1], "fx": fx, "fy": fy, "cx": cx, "cy": cy},
                "ground_truth": self.poses}

    def read_frame(self, i):
        bgr = cv2.imread(self.rgb[i], cv2.IMREAD_COLOR)
        depth = cv2.imread(self.depth[i], cv2.IMREAD_ANYDEPTH)
        if bgr is None or depth is None or depth.dtype != np.uint16:
            raise IOError(f"frame {i}: {self.rgb[i]} or {self.depth[i]} is not a readable PNG (depth: 16-bit)")
        return {"rgb": cv2.cvtColor(bgr, cv2.COLOR_BGR2RGB), "depth": depth, "timestamp": float(self.poses[i, 0])}
