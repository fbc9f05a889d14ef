"""orb_pnp — frame-to-frame RGB-D visual odometry in Python: ORB features, descriptor matching with
Lowe's ratio test, and PnP-RANSAC on the previous frame's depth (3-D points) against the current
frame's keypoints (2-D), refined by Levenberg-Marquardt on the inliers. The classic sparse pipeline
(e.g. Endres et al. 2012, without the graph), in OpenCV's Python bindings (Debian python3-opencv).

    plugin: python
    params: {module: plugins/odometry/python_examples/orb_pnp.py, features: 1000}
"""
import cv2
import numpy as np

import vobench


class Odometry:
    PARAMS = {
        "features": (int, 1000, "ORB features detected per frame", 50, 20000),
        "ratio": (float, 0.8, "Lowe's ratio test: best match distance below ratio x the second best", 0.1, 1.0),
        "reprojection_px": (float, 3.0, "RANSAC inlier threshold, pixels", 0.1, 50.0),
        "iterations": (int, 200, "RANSAC iterations", 10, 100000),
        "min_inliers": (int, 12, "fewer inliers than this: the frame is lost (the pose is kept)", 4, 10000),
        "max_depth_m": (float, 6.0, "ignore depth readings beyond this range, metres", 0.1, 100.0),
    }

    def __init__(self, camera, params, seed):
        self.p = params
        self.K = camera.K
        self.dist = np.array(camera.distortion, dtype=np.float64) if camera.distortion_model == "opencv" else None
        self.orb = cv2.ORB_create(nfeatures=params["features"])
        self.matcher = cv2.BFMatcher(cv2.NORM_HAMMING)
        cv2.setRNGSeed(int(seed) & 0x7FFFFFFF)  # RANSAC draws from OpenCV's generator: same seed, same run
        self.reset()

    def reset(self):
        self.pose = np.eye(4)  # camera-to-world of the last frame
        self.prev_points = None  # previous frame's keypoints with depth, in its camera frame (N x 3)
        self.prev_desc = None

    def _features(self, frame):
        """All keypoints (undistorted pixels) and descriptors, and those with a depth reading as 3-D
        points in the camera frame with their descriptors."""
        gray = cv2.cvtColor(frame.rgb, cv2.COLOR_RGB2GRAY)
        keypoints, desc = self.orb.detectAndCompute(gray, None)
        if desc is None:
            return np.zeros((0, 2)), None, np.zeros((0, 3)), None
        uv = np.array([k.pt for k in keypoints], dtype=np.float64)
        depth = frame.depth  # float32 metres, NaN where there is no reading
        rows = np.clip(np.rint(uv[:, 1]).astype(int), 0, depth.shape[0] - 1)
        cols = np.clip(np.rint(uv[:, 0]).astype(int), 0, depth.shape[1] - 1)
        z = depth[rows, cols].astype(np.float64)
        ok = np.isfinite(z) & (z > 0.1) & (z < self.p["max_depth_m"])
        if self.dist is not None:  # depth is looked up where the pixel is; geometry uses the ideal pinhole
            uv = cv2.undistortPoints(uv.reshape(-1, 1, 2), self.K, self.dist, P=self.K).reshape(-1, 2)
        fx, fy, cx, cy = self.K[0, 0], self.K[1, 1], self.K[0, 2], self.K[1, 2]
        xyz = np.stack([(uv[:, 0] - cx) * z / fx, (uv[:, 1] - cy) * z / fy, z], axis=1)
        return uv, desc, xyz[ok], desc[ok]

    def process(self, frame):
        with vobench.stage("detection"):
            uv_all, desc_all, xyz, desc_with_depth = self._features(frame)
        status = "ok"
        if self.prev_desc is not None and desc_all is not None and len(desc_all) >= 2:
            with vobench.stage("matching"):
                pairs = self.matcher.knnMatch(desc_all, self.prev_desc, k=2)
                good = [m[0] for m in pairs if len(m) == 2 and m[0].distance < self.p["ratio"] * m[1].distance]
            vobench.counter("matches", len(good))
            if len(good) >= self.p["min_inliers"]:
                with vobench.stage("pnp"):
                    obj = self.prev_points[[m.trainIdx for m in good]]
                    img = uv_all[[m.queryIdx for m in good]]
                    found, rvec, tvec, inliers = cv2.solvePnPRansac(
                        obj, img, self.K, None, iterationsCount=self.p["iterations"],
                        reprojectionError=self.p["reprojection_px"], confidence=0.999, flags=cv2.SOLVEPNP_EPNP)
                    n = 0 if inliers is None else len(inliers)
                    if found and n >= self.p["min_inliers"]:
                        idx = inliers[:, 0]
                        _, rvec, tvec = cv2.solvePnP(obj[idx], img[idx], self.K, None, rvec, tvec,
                                                     useExtrinsicGuess=True, flags=cv2.SOLVEPNP_ITERATIVE)
                vobench.counter("inliers", n)
                if found and n >= self.p["min_inliers"]:
                    # x_current = R x_previous + t: the previous camera seen from the current one.
                    current_from_previous = np.eye(4)
                    current_from_previous[:3, :3] = cv2.Rodrigues(rvec)[0]
                    current_from_previous[:3, 3] = tvec[:, 0]
                    self.pose = self.pose @ np.linalg.inv(current_from_previous)
                else:
                    status = "lost"
            else:
                status = "lost"
        self.prev_points, self.prev_desc = xyz, desc_with_depth
        return self.pose, status
