#!/usr/bin/env bash
# The report as a user gets it: leaderboard.json valid against schemas/leaderboard.schema.json (and a
# broken one refused), figures drawn by gnuplot, report.html opened in headless Chromium with its
# script run, its rows present, hostile names escaped, and a screenshot taken.
#   report_checks.sh VOBENCH SOURCE_DIR FAULT_PLUGIN_DIR WORKDIR
set -euo pipefail
vobench=$1 src=$2 faults=$3 work=$4
rm -rf "$work" && mkdir -p "$work" && cd "$work"
export VOBENCH_PLUGIN_PATH=
"$vobench" -q synth --sensor kinect1 --trajectory speed2 --frames 10 --out v1
"$vobench" -q synth --sensor kinect2 --trajectory speed2 --frames 10 --out v2
cat > sweep.yaml <<YAML
name: "report <checks> & 'quotes'"
datasets:
  - {name: sim, reader: tum, path: ., sequences: [v1, v2]}
algorithms:
  - {plugin: put_vo}
  - {name: "<script>alert('x')</script>", plugin: constant_pose}
  - {name: crasher, plugin: $faults/fault_segfault.so}
repeats: 2
criteria: ['rpe.trans.rmse <= 0.05', {criterion: 'failed_cells == 0', required: false}]
YAML
# A required criterion fails (the crasher has no RPE): vobench run says so and exits 1.
if "$vobench" -q run sweep.yaml --out out -j 2 > run.log 2>&1; then cat run.log; echo "FAIL: exit 0 with a failed required criterion"; exit 1; fi
grep -q "REQUIRED CRITERION NOT MET: crasher: rpe.trans.rmse <= 0.05" run.log || { cat run.log; exit 1; }

echo "== leaderboard.json against the schema"
/usr/bin/python3 "$src/tests/scripts/validate_json.py" "$src/schemas/leaderboard.schema.json" out/leaderboard.json
/usr/bin/python3 - <<'PY'
import json
lb = json.load(open("out/leaderboard.json"))
del lb["entries"][0]["aggregate"]
lb["failures"].append({"id": "x"})
json.dump(lb, open("broken.json", "w"))
PY
if /usr/bin/python3 "$src/tests/scripts/validate_json.py" "$src/schemas/leaderboard.schema.json" broken.json > broken.log; then
  echo "FAIL: a leaderboard without aggregate passed the schema"; exit 1
fi
grep -q "'aggregate' is a required property" broken.log

echo "== figures"
# Stems are a readable slug plus 8 hex digits of the full name (util/escape.hpp file_stem).
for f in 'rpe_put_vo_sim-v1-[0-9a-f]{8}\.' 'traj_put_vo_sim-v1-[0-9a-f]{8}\.' 'bars_put_vo-[0-9a-f]{8}\.'; do
  ls out/figures/ | grep -Eq "^$f" || { echo "FAIL: no figure $f"; ls out/figures; exit 1; }
done
bars=$(ls out/figures/ | grep -E '^bars_put_vo-[0-9a-f]{8}\.gp$' | sed 's/\.gp$//')
for ext in png svg pdf dat gp; do test -s "out/figures/$bars.$ext"; done
# The comparison figures: every entry on one scale, a mean and a 95 % interval per entry and sensor.
for m in ate.rmse rpe.trans.rmse rpe.rot.rmse ms_per_frame; do
  stem=$(ls out/figures/ | grep -E "^compare_$(echo $m | tr . _ )-[0-9a-f]{8}\.gp$|^compare_${m}-[0-9a-f]{8}\.gp$" | sed 's/\.gp$//' | head -1)
  [ -n "$stem" ] || { echo "FAIL: no comparison figure for $m"; ls out/figures; exit 1; }
  for ext in png svg pdf dat gp; do test -s "out/figures/$stem.$ext"; done
  # one data row per entry, each with mean <= ... the interval bounds around the mean
  /usr/bin/python3 - "out/figures/$stem.dat" <<'PY'
import sys, math
rows = [l.split('"')[2].split() for l in open(sys.argv[1]) if l.startswith('"')]
assert rows, "no entry rows"
for r in rows:
    for k in range(0, len(r), 4):
        mean, lo, hi = (float(x) for x in r[k:k + 3])
        if math.isnan(mean): continue
        assert lo <= mean + 1e-12 and mean <= hi + 1e-12, (mean, lo, hi)
PY
done

# RPE over time across entries: one figure per sequence and sensor that two or more entries ran.
entries=$(/usr/bin/python3 -c 'import json; print(len(json.load(open("out/leaderboard.json"))["entries"]))')
if [ "$entries" -ge 2 ]; then
  ls out/figures/ | grep -Eq '^rpe_over_time_.*-[0-9a-f]{8}\.png$' || { echo "FAIL: no RPE-over-time comparison"; ls out/figures; exit 1; }
fi

echo "== report.html in headless Chromium"
if ! command -v chromium > /dev/null; then echo "chromium is not installed (apt-get install chromium): skipped"; exit 77; fi
grep -q "https\?://" out/report.html && { echo "FAIL: report.html refers to the network"; grep -o "https\?://[^\"' ]*" out/report.html | head; exit 1; }
flags=(--headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking
       --disable-component-update --disable-sync --user-data-dir="$work/chromium-profile")
timeout 120 chromium "${flags[@]}" --virtual-time-budget=5000 --dump-dom "file://$work/out/report.html" > dom.html 2> chromium.log
grep -q 'data-ready="yes"' dom.html || { echo "FAIL: the page's script did not run"; exit 1; }
grep -q 'id="leaderboard" data-rows="3"' dom.html || { echo "FAIL: leaderboard rows"; grep -o '<table[^>]*>' dom.html; exit 1; }
grep -q '&lt;script&gt;alert' dom.html || { echo "FAIL: a hostile name was not escaped"; exit 1; }
if grep -q "<script>alert" dom.html; then echo "FAIL: raw script from a config name"; exit 1; fi
grep -q "SIGSEGV" dom.html
grep -q 'src="data:image/png;base64,' dom.html
timeout 120 chromium "${flags[@]}" --window-size=1280,2400 --screenshot="$work/report.png" "file://$work/out/report.html" 2>> chromium.log
test "$(stat -c %s report.png)" -gt 20000
echo "report.html: rows, escaping, figures and screenshot ($work/report.png) checked"
