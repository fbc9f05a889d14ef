#!/usr/bin/env bash
# Start-up side by side, in one run (best of N, alternated): `vobench --version` (the light CLI),
# `vobench-worker --help` (a process that loads OpenCV, GDAL and TBB: what every command paid before
# the worker was split out), and `vobench eval` on TUM fr2/desk (ORB-SLAM vs ground truth, 20,960
# and 2,893 poses) including the process start; with TUM_EVALUATE_ATE=path/evaluate_ate.py (TUM's
# script, run by $TUM_PYTHON, default /usr/bin/python3 with numpy: not shipped here), that script on
# the same files, alternated with the rest. Not part of `make test`: a benchmark, not a test.
#   [TUM_EVALUATE_ATE=…] bench/startup.sh [BUILD_DIR] [N] [DATA_DIR]
set -eu
build=${1:-build}
n=${2:-30}
data=${3:-$(dirname "$0")/../../shared/data}
gt="$data/real/trajectories/freiburg2_desk-groundtruth.txt"
est="$data/real/trajectories/freiburg2_desk-ORB.txt"
python3 - "$build" "$n" "$gt" "$est" <<'PY'
import os, subprocess, sys, time
build, n, gt, est = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
cmds = {
    "vobench --version": [f"{build}/bin/vobench", "--version"],
    "vobench-worker --help (OpenCV, TBB loaded)": [f"{build}/bin/vobench-worker", "--help"],
}
if os.path.exists(gt) and os.path.exists(est):
    cmds["vobench eval fr2/desk (tum-scripts ATE)"] = [f"{build}/bin/vobench", "eval", "--gt", gt, "--est", est, "--protocol", "tum-scripts", "--metric", "ate"]
    script = os.environ.get("TUM_EVALUATE_ATE")
    if script:
        cmds["TUM evaluate_ate.py fr2/desk"] = [os.environ.get("TUM_PYTHON", "/usr/bin/python3"), script, gt, est]
else:
    print(f"(no {gt}: the eval row is skipped)")
best = {k: 1e9 for k in cmds}
for i in range(n):
    for k, c in cmds.items():
        if k.startswith("TUM") and i >= 3:  # seconds per run: three runs are enough for a best
            continue  # alternated, so machine noise hits all alike
        t0 = time.perf_counter()
        subprocess.run(c, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
        best[k] = min(best[k], time.perf_counter() - t0)
for k, v in best.items():
    print(f"{k:48s} {v * 1000:8.1f} ms  (best of {n})")
light, heavy = best["vobench --version"], best["vobench-worker --help (OpenCV, TBB loaded)"]
print(f"start-up ratio, heavy / light: {heavy / light:.1f}x")
if "TUM evaluate_ate.py fr2/desk" in best:
    ratio = best["TUM evaluate_ate.py fr2/desk"] / best["vobench eval fr2/desk (tum-scripts ATE)"]
    print(f"eval ratio, TUM script / vobench eval (both including process start): {ratio:.0f}x")
PY
