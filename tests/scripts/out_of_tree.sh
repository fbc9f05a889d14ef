#!/usr/bin/env bash
# out_of_tree.sh BUILD_DIR TEMPLATE_DIR WORK_DIR CMAKE
# Does exactly what docs/writing-a-plugin.md says, step by step, out of tree: install the SDK, make a
# project with `vobench new-plugin`, build it with find_package(vobench), check it, run it on a
# synthetic sequence, and put it in a table beside put_vo.
set -euo pipefail
build=$1 template=$2 work=$3 cmake=$4
vobench="$build/bin/vobench"
rm -rf "$work"
mkdir -p "$work"
cd "$work"

# 1. install the SDK
"$cmake" --install "$build" --prefix "$work/sdk" --component sdk
# 2. make a project
"$vobench" new-plugin my_vo --dir my_vo
# 3. build
"$cmake" -S my_vo -B my_vo/build -DCMAKE_PREFIX_PATH="$work/sdk" -DCMAKE_BUILD_TYPE=Release
"$cmake" --build my_vo/build
plugin=my_vo/build/vobench_my_vo.so
exports=$(nm -D --defined-only "$plugin" | awk '{print $3}' | grep -v '^$' | sort -u)
echo "exports: $exports"
[ "$exports" = "vobench_plugin_entry_v1" ]
# 4. check
"$vobench" plugins check "$plugin"
# 5. run it
"$vobench" -q synth --sensor kinect1 --trajectory speed2 --frames 20 --out seq
VOBENCH_PLUGIN_PATH=my_vo/build "$vobench" -q track --dataset tum --path seq --algorithm my_vo --out run --json | tee track.json
grep -q '"frames": 20' track.json
test -s run/trajectory.txt
# 6. put it in the table
cat > mine.yaml <<'YAML'
datasets:
  - {name: sim, synthetic: {trajectories: [speed2], sensors: [kinect1], frames: 20, cache: datasets}}
algorithms:
  - {plugin: put_vo}
  - {plugin: my_vo}
YAML
VOBENCH_PLUGIN_PATH=my_vo/build "$vobench" -q run mine.yaml --out results/mine
grep -q "### my_vo" results/mine/summary.md
grep -q "### put_vo" results/mine/summary.md
grep -q '"entry": "my_vo"' results/mine/leaderboard.json
echo "from nothing to a row in the table: done"
