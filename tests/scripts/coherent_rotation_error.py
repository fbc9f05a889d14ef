#!/usr/bin/env python3
"""coherent_rotation_error.py SWEEP_DIR [--delta-frames N] — how much of each run's rotational RPE one
constant rotation of the camera frame explains (docs/synthetic-sensors.md, "Where the contrast is
missing, and what the remaining gap is not").

For every run of a `vobench run` output folder it pairs the estimate with the run's own
groundtruth.txt (interpolated at the estimate's stamps), takes the relative rotations over N frames,
E = E_a⁻¹E_b and G = G_a⁻¹G_b, and finds by a grid search (2° down to 0.25°) the rotation X that
minimises the RMS angle of G⁻¹ · X⁻¹ E X. A reference or calibration that is off by a fixed rotation
shows as a large share removed; on renderings, whose reference is exact, only the fit's own gain
from three free parameters remains. Standard library only.
"""
import argparse
import itertools
import json
import math
import pathlib
import sys


def read_tum(path):
    rows = []
    for line in path.read_text().splitlines():
        if line.strip() and not line.startswith("#"):
            rows.append([float(x) for x in line.split()[:8]])
    return rows


def quat_to_matrix(q):
    x, y, z, w = q
    n = math.sqrt(x * x + y * y + z * z + w * w)
    x, y, z, w = x / n, y / n, z / n, w / n
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]


def mul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def transpose(a):
    return [[a[j][i] for j in range(3)] for i in range(3)]


def angle_deg(m):
    return math.degrees(math.acos(max(-1.0, min(1.0, (m[0][0] + m[1][1] + m[2][2] - 1) / 2))))


def rotation(w):
    """exp of the rotation vector w (radians), Rodrigues' formula."""
    a = math.sqrt(sum(c * c for c in w))
    if a < 1e-12:
        return [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    k = [c / a for c in w]
    K = [[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]]
    K2 = mul(K, K)
    return [[(1.0 if i == j else 0.0) + math.sin(a) * K[i][j] + (1 - math.cos(a)) * K2[i][j] for j in range(3)] for i in range(3)]


def reference_at(gt, t):
    """The reference's orientation at stamp t: its quaternions interpolated linearly and normalised."""
    lo, hi = 0, len(gt) - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if gt[mid][0] <= t:
            lo = mid
        else:
            hi = mid
    a, b = gt[lo], gt[hi]
    s = 0.0 if b[0] == a[0] else min(1.0, max(0.0, (t - a[0]) / (b[0] - a[0])))
    qa, qb = a[4:8], b[4:8]
    if sum(x * y for x, y in zip(qa, qb)) < 0:
        qb = [-x for x in qb]
    return quat_to_matrix([(1 - s) * x + s * y for x, y in zip(qa, qb)])


def relative_pairs(run, delta):
    est = read_tum(run / "trajectory.txt")
    gt = read_tum(run / "groundtruth.txt")
    g = [reference_at(gt, row[0]) for row in est]
    e = [quat_to_matrix(row[4:8]) for row in est]
    return [(mul(transpose(g[i]), g[i + delta]), mul(transpose(e[i]), e[i + delta])) for i in range(len(est) - delta)]


def rms_angle(pairs, x):
    xt = transpose(x)
    return math.sqrt(sum(angle_deg(mul(transpose(g), mul(xt, mul(e, x)))) ** 2 for g, e in pairs) / len(pairs))


def fit(pairs):
    best = (rms_angle(pairs, rotation([0, 0, 0])), [0.0, 0.0, 0.0])
    for step in (2.0, 1.0, 0.5, 0.25):
        centre = best[1]
        for d in itertools.product((-2, -1, 0, 1, 2), repeat=3):
            w = [c + math.radians(step) * k for c, k in zip(centre, d)]
            s = rms_angle(pairs, rotation(w))
            if s < best[0]:
                best = (s, w)
    return best


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("sweep", type=pathlib.Path)
    parser.add_argument("--delta-frames", type=int, default=30)
    args = parser.parse_args()
    print("| dataset | algorithm | rotational RMSE [°] | with the fitted X [°] | removed | X (rotation vector, °) |")
    print("|---|---|---:|---:|---:|---|")
    for cell in sorted(args.sweep.glob("runs/*/cell.json")):
        meta = json.loads(cell.read_text())
        run = cell.parent
        if not (run / "trajectory.txt").exists() or not (run / "groundtruth.txt").exists():
            continue
        try:
            pairs = relative_pairs(run, args.delta_frames)
        except (ValueError, IndexError, ZeroDivisionError) as e:  # a broken or empty trajectory file
            print(f"{run}: skipped, its trajectory or reference cannot be read: {e}", file=sys.stderr)
            continue
        if not pairs:
            continue
        before = rms_angle(pairs, rotation([0, 0, 0]))
        after, w = fit(pairs)
        name = meta["algorithm"] + (" " + json.dumps(meta["params"], sort_keys=True) if meta.get("params") else "")
        removed = 100 * (1 - after / before) if before > 0 else 0.0
        print(f"| {meta['dataset']} | {name} | {before:.3f} | {after:.3f} | {removed:.0f} % | "
              f"{', '.join(f'{math.degrees(c):.2f}' for c in w)} |")


if __name__ == "__main__":
    main()
