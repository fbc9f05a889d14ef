#!/usr/bin/env bash
# filter_guide.sh BUILD_DIR SOURCE_DIR WORK_DIR CMAKE — the "Writing a filter" part of
# docs/writing-a-plugin.md, step by step: the C filter taken from the page, built out of tree against the
# installed SDK header, checked, swept in a config beside a built-in filter, its degradation curve drawn.
set -euo pipefail
build=$1 src=$2 work=$3 cmake=$4
vobench="$build/bin/vobench"
rm -rf "$work"
mkdir -p "$work"
cd "$work"
"$cmake" --install "$build" --prefix "$work/sdk" --component sdk > /dev/null
python3 - "$src/docs/writing-a-plugin.md" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
code = re.search(r"<!-- filter.c -->\n```c\n(.*?)```", text, re.S).group(1)
open("darken.c", "w").write(code)
PY
cc -std=c99 -O2 -Wall -Wextra -Werror -fPIC -shared -fvisibility=hidden -I "$work/sdk/include" darken.c -o vobench_darken.so
"$vobench" plugins check ./vobench_darken.so | tee check.txt
tail -1 check.txt | grep -q "^PASS"
cat > darker.yaml <<'YAML'
datasets:
  - {name: sim, synthetic: {trajectories: [speed2], sensors: [kinect1], frames: 20, cache: datasets}}
algorithms:
  - {plugin: put_vo}
filters:
  - {plugin: ./vobench_darken.so, params: {factor: [1.0, 0.5, 0.2]}}
  - {plugin: depth_holes, params: {fraction: 0.1}}
YAML
"$vobench" -q run darker.yaml --out results/darker | tee run.txt
grep -q "3 cells, 0 failed" run.txt
grep -qF '### put_vo \| darken factor=0.5 + depth_holes fraction=0.1' results/darker/summary.md
ls results/darker/figures/ | grep -q "^degradation_darken_factor.*png$" || { echo "no degradation curve"; exit 1; }
/usr/bin/python3 "$src/tests/scripts/validate_json.py" "$src/schemas/run.schema.json" results/darker/runs/*/run.json
python3 - results/darker <<'PY'
import glob, json, sys
ids = set()
for f in glob.glob(sys.argv[1] + "/runs/*/run.json"):
    r = json.load(open(f))
    assert r["status"] == "ok", r["reason"]
    assert [x["plugin"] for x in r["cell"]["filters"]] == ["darken", "depth_holes"], r["cell"]["filters"]
    ids.add(r["cell"]["id"])
assert len(ids) == 3, ids
print("three cells, three ids, each with its chain of two filters")
PY
echo "filter guide: done"
