#!/usr/bin/env python3
"""Measures a Kinect v1's fixed disparity distortion from a real TUM folder and its reference alone
(issue #15; the numbers behind the `tum-fr1` camera's `disparity_distortion_px`, harness/src/synth/camera_catalog.cpp).

Model: every measured disparity carries a fixed offset δ(x, y) = a·r² + b·x + c·y pixels (x, y the
pinhole-normalised pixel coordinates, r² = x² + y²), so a depth z_m was really z = f·b_IR / (f·b_IR / z_m − δ).
Its depth error grows as z²·δ / (f·b_IR): harmless at 1 m, centimetres at 3-4 m, and fixed to the
camera, so it does not move with the scene — consecutive views of the same surface disagree more the
further the camera turned. The fit minimises that disagreement: frame i's depth, corrected, moved by
the reference's relative motion (poses at each depth stamp less the depth latency, stamp_latency.hpp)
onto frame j's, for pairs 4 and 16 frames apart; residuals |Δz| / z, robust (IRLS, L1-like, over 5 %
ignored as occlusions). Gauss-Newton on (a, b, c) from zero.

A check on other data: `--validate DIR` applies the fitted field to a second folder of the same camera
and prints its residuals with and without it (gaps 1, 2, 4, 8).

Usage: fit_depth_distortion.py DIR [--validate DIR2] [--depth-latency 0.020] [--iterations 14]
       [--fx 517.3 --fy 516.5 --cx 318.6 --cy 255.3] [--focal-baseline 43.5] [--expect=A,B,C [--tolerance 0.1]]
With --expect it exits 1 when a fitted coefficient differs from the expected one by more than the
tolerance (px), or the field does not lower DIR's residual at 16 frames (the test that the catalogue's
numbers are reproducible).
Needs numpy and OpenCV's Python bindings (Debian: python3-opencv).
"""
import argparse

import cv2
import numpy as np


def read_list(path):
    return [line.split() for line in open(path) if line.strip() and not line.startswith("#")]


def rotation(q):
    x, y, z, w = q / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


class Folder:
    def __init__(self, path, a):
        self.a = a
        self.depth = [(float(t), p) for t, p in read_list(path + "/depth.txt")]
        self.images = [cv2.imread(path + "/" + p, cv2.IMREAD_UNCHANGED).astype(np.float64) / 5000.0 for _, p in self.depth]
        self.reference = np.array([[float(v) for v in row] for row in read_list(path + "/groundtruth.txt")])
        self.height, self.width = self.images[0].shape
        us, vs = np.meshgrid(np.arange(0, self.width, 8), np.arange(0, self.height, 8))
        self.us, self.vs = us.ravel(), vs.ravel()

    def pose(self, t):
        ref = self.reference
        k = np.searchsorted(ref[:, 0], t)
        if k == 0 or k >= len(ref):
            return None
        p, q = ref[k - 1], ref[k]
        s = (t - p[0]) / (q[0] - p[0])
        qa, qb = p[4:8], q[4:8]
        if np.dot(qa, qb) < 0:
            qb = -qb
        T = np.eye(4)
        T[:3, :3] = rotation((1 - s) * qa + s * qb)
        T[:3, 3] = (1 - s) * p[1:4] + s * q[1:4]
        return T

    def corrected(self, z, x, y, delta):
        d = self.a.focal_baseline / np.where(z > 0, z, np.nan) - (delta[0] * (x * x + y * y) + delta[1] * x + delta[2] * y)
        return np.where(d > 0, self.a.focal_baseline / d, np.nan)

    def residuals(self, i, j, delta):
        """Signed relative depth residuals of frame i moved onto frame j (NaN where not comparable)."""
        a = self.a
        pi, pj = self.pose(self.depth[i][0] - a.depth_latency), self.pose(self.depth[j][0] - a.depth_latency)
        if pi is None or pj is None:
            return np.array([])
        z = self.images[i][self.vs, self.us]
        m = z > 0
        x, y = (self.us[m] - a.cx) / a.fx, (self.vs[m] - a.cy) / a.fy
        zc = self.corrected(z[m], x, y, delta)
        P = np.stack([x * zc, y * zc, zc], 1)
        T = np.linalg.inv(pj) @ pi
        Q = P @ T[:3, :3].T + T[:3, 3]
        Q = Q[Q[:, 2] > 0.1]
        u, v = a.fx * Q[:, 0] / Q[:, 2] + a.cx, a.fy * Q[:, 1] / Q[:, 2] + a.cy
        u0, v0 = np.floor(u).astype(int), np.floor(v).astype(int)
        inside = (u0 >= 0) & (v0 >= 0) & (u0 < self.width - 1) & (v0 < self.height - 1)
        out = np.full(len(Q), np.nan)
        uu, vv, fu, fv = u0[inside], v0[inside], u[inside] - u0[inside], v[inside] - v0[inside]
        img = self.images[j]
        c = np.stack([img[vv, uu], img[vv, uu + 1], img[vv + 1, uu], img[vv + 1, uu + 1]], 1)
        smooth = (c > 0).all(1) & ((c.max(1) - c.min(1)) < 0.02 * c.mean(1) + 0.01)
        zj = (1 - fu) * (1 - fv) * c[:, 0] + fu * (1 - fv) * c[:, 1] + (1 - fu) * fv * c[:, 2] + fu * fv * c[:, 3]
        zj = self.corrected(zj, (u[inside] - a.cx) / a.fx, (v[inside] - a.cy) / a.fy, delta)
        zj[~smooth] = np.nan
        out[inside] = (zj - Q[inside, 2]) / Q[inside, 2]
        return out

    def median_residual(self, gap, delta):
        per_pair = []
        for i in range(len(self.images) - gap):
            r = self.residuals(i, i + gap, delta)
            r = r[np.isfinite(r)]
            if len(r) > 200:
                per_pair.append(np.median(np.abs(r)) * 100)
        return np.median(per_pair) if per_pair else float("nan"), len(per_pair)


def fit(folder, iterations):
    pairs = [(i, i + g) for g in (4, 16) for i in range(0, len(folder.images) - g, 2)]

    def all_residuals(delta):
        return np.concatenate([folder.residuals(i, j, delta) for i, j in pairs])

    delta = np.zeros(3)
    for it in range(iterations):
        r0 = all_residuals(delta)
        J = np.stack([(all_residuals(delta + step) - r0) / 1e-3 for step in np.eye(3) * 1e-3], 1)
        ok = np.isfinite(r0) & np.isfinite(J).all(1)
        r, J = r0[ok], J[ok]
        w = 1.0 / np.maximum(np.abs(r), 0.005)
        w[np.abs(r) > 0.05] = 0
        delta -= np.linalg.solve((J * w[:, None]).T @ J, (J * w[:, None]).T @ r)
        print(f"iteration {it + 1}: δ = {delta[0]:+.3f}·r² {delta[1]:+.3f}·x {delta[2]:+.3f}·y px")
    return delta


def report(name, folder, delta, gaps):
    for g in gaps:
        without, n = folder.median_residual(g, np.zeros(3))
        with_field, _ = folder.median_residual(g, delta)
        print(f"{name}: gap {g:2d} ({n} pairs): residual {without:.3f} % → {with_field:.3f} % with the field")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("folder")
    ap.add_argument("--validate")
    ap.add_argument("--depth-latency", type=float, default=0.020)
    ap.add_argument("--iterations", type=int, default=14)
    ap.add_argument("--fx", type=float, default=517.3)
    ap.add_argument("--fy", type=float, default=516.5)
    ap.add_argument("--cx", type=float, default=318.6)
    ap.add_argument("--cy", type=float, default=255.3)
    ap.add_argument("--focal-baseline", type=float, default=580.0 * 0.075, help="IR focal length × baseline, px·m")
    ap.add_argument("--expect", help="A,B,C: the coefficients the fit must reproduce")
    ap.add_argument("--tolerance", type=float, default=0.1)
    a = ap.parse_args()
    folder = Folder(a.folder, a)
    delta = fit(folder, a.iterations)
    report(a.folder, folder, delta, (1, 4, 16))
    if a.validate:
        report(a.validate, Folder(a.validate, a), delta, (1, 2, 4, 8))
    if a.expect:
        expected = np.array([float(v) for v in a.expect.split(",")])
        lowered = folder.median_residual(16, delta)[0] < folder.median_residual(16, np.zeros(3))[0]
        if np.abs(delta - expected).max() > a.tolerance or not lowered:
            print(f"FAIL: fitted {np.round(delta, 3)}, expected {expected} ± {a.tolerance} px; residual lowered: {lowered}")
            return 1
        print(f"ok: the fit reproduces {expected} within {a.tolerance} px")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
