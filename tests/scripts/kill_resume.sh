#!/usr/bin/env bash
# SIGKILL at any moment, then --resume: the same results as an uninterrupted run, no duplicate cell,
# no corrupt or temporary file, no orphaned cell process.
#   kill_resume.sh VOBENCH WORKDIR
set -euo pipefail
vobench=$1 work=$2
rm -rf "$work" && mkdir -p "$work" && cd "$work"
export VOBENCH_PLUGIN_PATH=
"$vobench" -q synth --sensor kinect1 --trajectory speed2 --frames 12 --out seq1
"$vobench" -q synth --sensor kinect1 --trajectory explore3 --frames 12 --out seq2
cat > sweep.yaml <<'YAML'
name: kill-and-resume
datasets:
  - {name: a, reader: tum, path: seq1}
  - {name: b, reader: tum, path: seq2}
algorithms:
  - {plugin: put_vo}
  - {plugin: orb_matching}
  - {plugin: constant_pose}
repeats: 2
YAML
"$vobench" -q run sweep.yaml --out straight -j 2 > /dev/null

# Ctrl-C (SIGINT): exit 130, finished cells kept, the running ones not recorded as failures.
"$vobench" -q run sweep.yaml --out killed -j 2 > interrupt.log 2>&1 &
pid=$!
for _ in $(seq 100); do [ "$(ls killed/runs 2> /dev/null | wc -l)" -ge 2 ] && break; sleep 0.05; done
kill -INT "$pid"
rc=0; wait "$pid" || rc=$?
[ "$rc" -eq 130 ] || { echo "FAIL: SIGINT gave exit $rc, expected 130"; cat interrupt.log; exit 1; }
grep -q "interrupted: .* continue with: .* --resume" interrupt.log || { cat interrupt.log; exit 1; }
if grep -l '"status": "failed"' killed/runs/*/run.json 2> /dev/null; then echo "FAIL: an interrupted cell was recorded as failed"; exit 1; fi
sleep 0.2
if pgrep -f "cell-exec $PWD/killed" > /dev/null; then echo "FAIL: a cell process outlived Ctrl-C"; exit 1; fi
echo "SIGINT: exit 130, $(ls killed/runs | wc -l) cells kept, none recorded as failed"

# Kill after growing delays until a run gets through on its own.
attempt=0
for delay in 0.15 0.4 0.7 1.1 1.6 2.2 3 5 8 12 20; do
  attempt=$((attempt + 1))
  "$vobench" -q run sweep.yaml --out killed --resume -j 2 > resume.log 2>&1 &
  pid=$!
  sleep "$delay"
  if kill -9 "$pid" 2> /dev/null; then
    wait "$pid" 2> /dev/null || true
    echo "attempt $attempt: killed after $delay s, $(ls killed/runs 2> /dev/null | grep -vc '^\.' || true) cells finished"
    sleep 0.2
    if pgrep -f "cell-exec $PWD/killed" > /dev/null; then echo "FAIL: a cell process outlived the killed vobench"; exit 1; fi
  else
    wait "$pid"
    echo "attempt $attempt: finished on its own"
    break
  fi
done
"$vobench" -q run sweep.yaml --out killed --resume -j 2 > /dev/null

python3 - <<'PY'
import json, os, sys, filecmp
a, b = "straight", "killed"
cells_a = json.load(open(f"{a}/cells.json")); cells_b = json.load(open(f"{b}/cells.json"))
ids = sorted(c["id"] for c in cells_a)
assert ids == sorted(c["id"] for c in cells_b), "different cell lists"
runs_b = sorted(d for d in os.listdir(f"{b}/runs") if not d.startswith("."))
assert runs_b == ids, f"cells in runs/: {runs_b} expected {ids}"
for i in ids:
    for f in ("trajectory.txt", "groundtruth.txt"):
        assert filecmp.cmp(f"{a}/runs/{i}/{f}", f"{b}/runs/{i}/{f}", shallow=False), f"{i}/{f} differs"
    ra = json.load(open(f"{a}/runs/{i}/run.json")); rb = json.load(open(f"{b}/runs/{i}/run.json"))
    assert ra["status"] == rb["status"] == "ok", i
    assert ra["evaluation"] == rb["evaluation"], f"{i}: metrics differ"
la = json.load(open(f"{a}/leaderboard.json")); lb = json.load(open(f"{b}/leaderboard.json"))
strip = lambda e: {k: v for k, v in e.items()}
for ea, eb in zip(la["entries"], lb["entries"]):
    for ca, cb in zip(ea["cells"], eb["cells"]):
        ma = {k: v for k, v in ca["metrics"].items() if k not in ("ms_per_frame", "fps")}
        mb = {k: v for k, v in cb["metrics"].items() if k not in ("ms_per_frame", "fps")}
        assert ma == mb, f"leaderboard metrics differ for {ca['id']}"
for root, dirs, files in os.walk(b):
    for f in files:
        assert ".tmp." not in f, f"temporary file left: {root}/{f}"
        if f.endswith(".json"):
            json.load(open(os.path.join(root, f)))
assert not os.path.exists(f"{b}/runs/.work"), "work folder left"
print(f"{len(ids)} cells: identical trajectories and metrics after kill -9 and --resume")
PY
