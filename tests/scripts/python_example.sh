#!/usr/bin/env bash
# python_example.sh BUILD_DIR SOURCE_DIR WORK_DIR REAL_DIR
# configs/python_example.yaml as shipped (orb_pnp.py through the python bridge beside put_vo, on
# sim-PUTK² Kinect v1 and v2 and on the real fr1/rpy sample), with 20 rendered frames instead of 50 and
# its cache and output in WORK_DIR: every cell a success, orb_pnp in the tables and the leaderboard.
set -euo pipefail
build=$1 src=$2 work=$3 real=$4
rm -rf "$work"
mkdir -p "$work"
sed -e 's/frames: 50/frames: 20/' -e "s#cache: datasets/synthetic#cache: $work/cache#" -e "s#module: plugins/#module: $src/plugins/#" \
  "$src/configs/python_example.yaml" > "$work/python_example.yaml"
VOBENCH_REAL="$real" "$build/bin/vobench" -q run "$work/python_example.yaml" -j 2 --out "$work/out" | tee "$work/run.txt"
grep -q "9 cells, 0 failed" "$work/run.txt"
python3 - "$work/out" <<'PY'
import json, os, sys
out = sys.argv[1]
rows = {}
for cell in os.listdir(os.path.join(out, "runs")):
    if not os.path.isfile(os.path.join(out, "runs", cell, "run.json")):
        continue
    r = json.load(open(os.path.join(out, "runs", cell, "run.json")))
    c = r["cell"]
    rows[(c["algorithm"].split(" ")[0], c["sequence"], c["sensor"])] = r
want = [("orb_pnp", "explore1", "kinect1"), ("orb_pnp", "explore1", "kinect2"), ("orb_pnp", "rgbd_dataset_freiburg1_rpy", "")]
for key in want:
    r = rows[key]
    assert r["status"] == "ok", (key, r["reason"])
    print(key, "ATE %.4f m, RPE %.4f m" % (r["metrics"]["ate.rmse"], r["metrics"]["rpe.trans.rmse"]))
board = json.load(open(os.path.join(out, "leaderboard.json")))
ranked = [e["entry"] for e in board["entries"] if e.get("rank") is not None]
assert any(e.startswith("orb_pnp") for e in ranked) and "put_vo" in ranked, ranked
md = open(os.path.join(out, "summary.md")).read()
assert "### orb_pnp" in md and "### put_vo" in md
print("ranked:", ranked)
PY
