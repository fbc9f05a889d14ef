#!/usr/bin/env bash
# realtime.sh BUILD_DIR SOURCE_DIR WORK_DIR REAL_DIR — issue #20's real-time mode on the real TUM fr1/rpy
# sample (30 Hz): `timing: realtime` in a sweep with put_vo (well below 33 ms a frame: keeps up, dropping a
# frame only behind a call the machine stalled) and opencv_rgbd method=rgbd_icp (slower than 30 Hz here:
# drops frames, and says how many), both in the tables with their dropped-frame counts; every run.json
# carries its timing protocol (schema-valid); `vobench track --realtime` agrees.
set -euo pipefail
build=$1 src=$2 work=$3 real=$4
vobench="$build/bin/vobench"
rm -rf "$work"
mkdir -p "$work"
cd "$work"
cat > rt.yaml <<YAML
name: real time on fr1/rpy
datasets:
  - {name: tum, reader: tum, path: $real, sequences: [rgbd_dataset_freiburg1_rpy], options: {intrinsics: fr1}}
algorithms:
  - {plugin: put_vo}
  - {name: rgbd_icp, plugin: opencv_rgbd, params: {method: rgbd_icp}}
timing: {mode: realtime, speed: 1, warmup_frames: 1}
protocol: {name: tum-scripts, rpe_delta: 1, rpe_unit: s}
YAML
"$vobench" -q run rt.yaml -j 2 --out out | tee run.txt
grep -q "2 cells, 0 failed" run.txt
python3 - out <<'PY'
import glob, json, os, sys
runs = {json.load(open(f))["cell"]["algorithm"]: json.load(open(f)) for f in glob.glob(sys.argv[1] + "/runs/*/run.json")}
put, icp = runs["put_vo"], runs["rgbd_icp"]
for name, r in runs.items():
    p, t = r["timing_protocol"], r["timing"]
    assert r["status"] == "ok", (name, r["reason"])
    assert p["mode"] == "realtime" and p["speed"] == 1 and p["warmup_frames"] == 1, p
    assert t["processed_frames"] + t["dropped_frames"] == r["frames"] == 90, t
    assert t["frames_timed"] == t["processed_frames"] - 1, t  # the warm-up frame is not timed
    assert "latency_ms" in t and "cpu_per_wall" in t, t
    print(f"{name}: {t['dropped_frames']} of 90 frames dropped, latency {t['latency_ms']['mean']:.1f} ms mean, "
          f"CPU/wall {t['cpu_per_wall']:.2f}, pinned to core {p['pinned_core']}, RPE {r['metrics']['rpe.trans.rmse']:.4f} m")
# A frame is dropped exactly when it arrives (its stamp, speed 1) while the call before it still runs:
# frames.jsonl gives each processed frame's call time (ns), each dropped one "d".
def calls_past_period(frames_jsonl):
    busy_until, overran = None, 0
    for line in open(frames_jsonl):
        f = json.loads(line)
        if f.get("d"):
            assert busy_until is not None and f["t"] < busy_until, ("dropped while the plugin was idle", frames_jsonl, f)
        else:
            assert busy_until is None or f["t"] >= busy_until, ("processed while the plugin was busy", frames_jsonl, f)
            busy_until = f["t"] + f["ns"] / 1e9
            overran += f["ns"] > 1e9 / 30
    return overran
overran = {json.load(open(f))["cell"]["algorithm"]: calls_past_period(os.path.join(os.path.dirname(f), "frames.jsonl"))
           for f in glob.glob(sys.argv[1] + "/runs/*/run.json")}
# put_vo (3 ms a frame) keeps up: at most two calls past the 33-ms period, and only those cost frames.
# Not none: this shared machine sometimes stalls one call for ~100 ms (seen in 1 of 4 runs: 104 ms of
# CPU time in one call, every input, count and pose as in the other runs).
assert overran["put_vo"] <= 2, (overran, put["timing"])
assert icp["timing"]["dropped_frames"] > 20 and overran["rgbd_icp"] > 20, (overran, icp["timing"])
PY
grep -q "dropped frames |" out/summary.md
grep -q "Timing: real time at ×1" out/summary.md
grep -q 'id="timing-protocol"' out/report.html
/usr/bin/python3 "$src/tests/scripts/validate_json.py" "$src/schemas/run.schema.json" out/runs/*/run.json
# The same from the command line, one cell at a time.
"$vobench" -q track --dataset tum --path "$real/rgbd_dataset_freiburg1_rpy" --algorithm opencv_rgbd --param method=rgbd_icp --realtime \
  --json > icp.json
python3 -c "import json; j = json.load(open('icp.json')); d = j['metrics']['dropped_frames']; assert d > 0, d; print('track --realtime: rgbd_icp dropped', d)"
echo "real time: done"
