#!/usr/bin/env bash
# -j scaling of a CPU-bound sweep: the same config with -j 1 and -j N, alternated (noise hits both),
# wall times, their ratio, and a check that both computed identical trajectories and metrics.
#   bench/sweep_scaling.sh [BUILD_DIR] [N] [ROUNDS]
set -euo pipefail
build=$(realpath "${1:-build}") jobs=${2:-2} rounds=${3:-2}
work=$(mktemp -d) && trap 'rm -rf "$work"' EXIT
cd "$work"
cat > sweep.yaml <<YAML
name: scaling
datasets:
  - {name: sim, synthetic: {trajectories: [explore1, explore2, speed2, speed3], sensors: [kinect1], frames: 60, cache: $work/seq}}
algorithms:
  - {plugin: put_vo}
  - {plugin: orb_matching}
  - {name: rgbd, plugin: opencv_rgbd, params: {method: rgbd}}
limits: {threads: 1}
YAML
"$build/bin/vobench" -q run sweep.yaml --out warm --dry-run > /dev/null
"$build/bin/vobench" -q run sweep.yaml --out warm > /dev/null   # renders the sequences, warms the page cache
for r in $(seq "$rounds"); do
  for j in 1 "$jobs"; do
    s=$(date +%s.%N)
    "$build/bin/vobench" -q run sweep.yaml --out "j$j-$r" -j "$j" > /dev/null
    e=$(date +%s.%N)
    echo "round $r -j $j: $(echo "$e - $s" | bc) s"
    echo "$j $(echo "$e - $s" | bc)" >> times
  done
done
python3 - "$jobs" <<'PY'
import json, sys, glob, os, filecmp
jobs = sys.argv[1]
t = {}
for line in open("times"):
    j, s = line.split(); t.setdefault(j, []).append(float(s))
one, many = min(t["1"]), min(t[jobs])
print(f"-j 1: {one:.2f} s, -j {jobs}: {many:.2f} s (best of {len(t['1'])}); speed-up {one / many:.2f}x")
cells = json.load(open("j1-1/cells.json"))
for c in cells:
    for d in glob.glob(f"j{jobs}-*"):
        assert filecmp.cmp(f"j1-1/runs/{c['id']}/trajectory.txt", f"{d}/runs/{c['id']}/trajectory.txt", shallow=False)
        assert json.load(open(f"j1-1/runs/{c['id']}/run.json"))["evaluation"] == json.load(open(f"{d}/runs/{c['id']}/run.json"))["evaluation"]
print(f"{len(cells)} cells: identical trajectories and metrics")
PY
