#!/usr/bin/env bash
# The Python bridge's cost, side by side in one run (issue #16): an empty Python process() (it returns a
# stored pose) against the C++ null baseline constant_pose, on the same frames (the real TUM fr1/rpy
# sample, 640x480, when present; else a rendered Kinect v1 sequence), alternated N times; the mean
# per-frame time of process() for both, their difference, and the bridge's own part as the plugin
# records it (python_bridge_ms: GIL, wrapping, parsing the pose). Then two Python cells (orb_pnp.py) run
# with -j 1 and with -j 2: the rate ratio (one interpreter per cell process, nothing shared).
# A benchmark, not a test: not part of `make test`.
#   bench/python_bridge.sh [BUILD_DIR] [N] [DATA_DIR]
set -eu
build=$(cd "${1:-build}" && pwd)
n=${2:-5}
data=${3:-$(dirname "$0")/../../shared/data}
root=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
seq="$data/real/rgbd_dataset_freiburg1_rpy"
if [ ! -d "$seq" ]; then
  seq="$work/seq"
  "$build/bin/vobench" -q synth --sensor kinect1 --trajectory explore1 --frames 90 --layout tum --out "$seq"
fi
cat > "$work/empty.py" <<'PY'
import numpy as np


class Odometry:
    def __init__(self, camera, params, seed):
        self.pose = np.eye(4)

    def process(self, frame):
        return self.pose, "ok"
PY
/usr/bin/env python3 - "$build" "$n" "$seq" "$work" "$root" <<'PY'
import csv, os, statistics, subprocess, sys, time
build, n, seq, work, root = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4], sys.argv[5]
vobench = f"{build}/bin/vobench"
def track(name, algo, params):
    out = f"{work}/{name}"
    cmd = [vobench, "-q", "track", "--dataset", "tum", "--path", seq, "--algorithm", algo, "--out", out]
    for p in params:
        cmd += ["--param", p]
    subprocess.run(cmd, check=True, capture_output=True)
    rows = list(csv.DictReader(open(f"{out}/timing.csv")))[1:]  # frame 0 carries first-call costs
    bridge = [float(r["count_python_bridge_ms"]) for r in rows if r.get("count_python_bridge_ms")]
    return statistics.mean(float(r["process_ms"]) for r in rows), (statistics.mean(bridge) if bridge else 0.0), len(rows)
c_times, py_times, bridge = [], [], []
for _ in range(n):  # alternated: the machine's noise falls on both
    c_times.append(track("c", "constant_pose", [])[0])
    t, b, frames = track("py", "python", [f"module={work}/empty.py"])
    py_times.append(t)
    bridge.append(b)
c, p, b = min(c_times), min(py_times), min(bridge)
print(f"frames: {frames} of {seq} (frame 0 excluded), best of {n} alternated runs")
print(f"constant_pose (C++)        process() {c * 1000:8.2f} us/frame")
print(f"python, empty process()    process() {p * 1000:8.2f} us/frame   difference {(p - c) * 1000:.2f} us/frame")
print(f"  of which the bridge's own part (python_bridge_ms): {b * 1000:.2f} us/frame")

cfg = f"{work}/par.yaml"
open(cfg, "w").write(f"""name: python parallel
datasets:
  - {{name: tum, reader: tum, path: {os.path.dirname(seq)}, sequences: [{os.path.basename(seq)}]}}
algorithms:
  - {{name: a, plugin: python, params: {{module: {root}/plugins/odometry/python_examples/orb_pnp.py}}}}
  - {{name: b, plugin: python, params: {{module: {root}/plugins/odometry/python_examples/orb_pnp.py, features: 999}}}}
limits: {{timeout: 600, memory_mb: 4096, threads: 1}}
""")
walls = {}
for jobs in (1, 2, 1, 2):
    t0 = time.time()
    subprocess.run([vobench, "-q", "run", cfg, "-j", str(jobs), "--out", f"{work}/par{jobs}-{time.time()}"], check=True, capture_output=True)
    walls.setdefault(jobs, []).append(time.time() - t0)
w1, w2 = min(walls[1]), min(walls[2])
print(f"two orb_pnp.py cells: -j 1 {w1:.2f} s, -j 2 {w2:.2f} s: {w1 / w2:.2f}x the rate")
PY
