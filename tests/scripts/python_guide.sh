#!/usr/bin/env bash
# python_guide.sh BUILD_DIR SOURCE_DIR WORK_DIR
# Does exactly what the Python part of docs/writing-a-plugin.md says, step by step (paths made absolute):
# new-plugin --python, plugins info/check with --param module=, track on a rendered sequence, a table
# beside put_vo, and the PNG-folder reader under `vobench track`.
set -euo pipefail
build=$1 src=$2 work=$3
vobench="$build/bin/vobench"
rm -rf "$work"
mkdir -p "$work"
cd "$work"

# 1. make a plugin
"$vobench" new-plugin my_py_vo --python --dir my_py_vo
test -s my_py_vo/my_py_vo.py
# 2. look at it and check it
"$vobench" plugins info python --param module=my_py_vo/my_py_vo.py | tee info.txt
grep -q "declared for the values given" info.txt
grep -q "scale .*double" info.txt
"$vobench" plugins check python --param module=my_py_vo/my_py_vo.py | tee check.txt
tail -1 check.txt | grep -q "^PASS"
# 3. run it, and put it in the table
"$vobench" -q synth --sensor kinect1 --trajectory speed2 --frames 20 --out seq
"$vobench" -q track --dataset tum --path seq --algorithm python --param module=my_py_vo/my_py_vo.py --out run --json | tee track.json
grep -q '"frames": 20' track.json
grep -q "count_python_bridge_ms" run/timing.csv
cat > mine_py.yaml <<'YAML'
datasets:
  - {name: sim, synthetic: {trajectories: [speed2], sensors: [kinect1], frames: 20, cache: datasets}}
algorithms:
  - {plugin: put_vo}
  - {name: my_py_vo, plugin: python, params: {module: my_py_vo/my_py_vo.py}, grid: {scale: [1.0, 2.0]}}
YAML
"$vobench" -q run mine_py.yaml --out results/mine_py
grep -qF '### my_py_vo \[module=my_py_vo/my_py_vo.py scale=1.0\]' results/mine_py/summary.md
grep -qF '### my_py_vo \[module=my_py_vo/my_py_vo.py scale=2.0\]' results/mine_py/summary.md
grep -q '"entry": "my_py_vo' results/mine_py/leaderboard.json
# 4. a dataset reader in Python
mkdir -p folder && cp -r seq/rgb seq/depth folder/ && grep -v '^#' seq/groundtruth.txt > folder/poses.txt
sed -n 2p seq/camera.txt | cut -d' ' -f1-4 > folder/camera.txt
"$vobench" -q track --dataset python_dataset --option module="$src/plugins/datasets/python_examples/png_folder.py" --path folder \
  --algorithm put_vo --out run_png --json | tee png.json
grep -q '"frames": 20' png.json
python3 - <<'PY'
import json
j = json.load(open("png.json"))
ate = j["metrics"]["ate.rmse"]
assert 0 < ate < 0.05, f"put_vo through the Python reader: ATE {ate} m"
print(f"put_vo through the Python PNG reader: ATE {ate:.4f} m")
PY
cat > png.yaml <<YAML
datasets:
  - {name: pngs, reader: python_dataset, path: folder, options: {module: $src/plugins/datasets/python_examples/png_folder.py}}
algorithms:
  - {plugin: put_vo}
  - {name: my_py_vo, plugin: python, params: {module: my_py_vo/my_py_vo.py}}
YAML
"$vobench" -q run png.yaml --out results/png | tee png_run.txt
grep -q "2 cells, 0 failed" png_run.txt
grep -q '"entry": "put_vo"' results/png/leaderboard.json
echo "python guide: done"
