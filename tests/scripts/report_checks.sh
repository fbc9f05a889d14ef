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
  - {name: put_vo_paper, plugin: put_vo, params: {profile: paper}}
  - {name: opencv_rgbd, plugin: opencv_rgbd, params: {method: rgbd}}
  - {plugin: orb_matching}
  - {name: "<script>alert('x')</script>", plugin: constant_pose}
  - {name: crasher, plugin: $faults/fault_segfault.so}
repeats: 3
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
  ls out/figures/ | grep -E "^$f" > /dev/null || { echo "FAIL: no figure $f"; ls out/figures; exit 1; }
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

# Box plots over repeats and sequences: one per accuracy metric, a box per entry with cells (five here).
for m in ate.rmse rpe.trans.rmse rpe.rot.rmse; do
  stem=$(ls out/figures/ | grep -E "^boxes_${m}-[0-9a-f]{8}\.png$" | sed 's/\.png$//' || true)
  [ -n "$stem" ] || { echo "FAIL: no box plot for $m"; ls out/figures | grep boxes; cat out/figures/boxes_*.log 2>/dev/null; exit 1; }
  test "$(grep -c '^#.* cells$' "out/figures/$stem.dat")" -eq 5 || { echo "FAIL: $stem.dat: not five boxes"; exit 1; }
done

# RPE over time across entries: one figure per sequence and sensor that two or more entries ran.
entries=$(/usr/bin/python3 -c 'import json; print(len(json.load(open("out/leaderboard.json"))["entries"]))')
if [ "$entries" -ge 2 ]; then
  ls out/figures/ | grep -E '^rpe_over_time_.*-[0-9a-f]{8}\.png$' > /dev/null || { echo "FAIL: no RPE-over-time comparison"; ls out/figures; exit 1; }
fi

echo "== report.html in headless Chromium (WebGL through SwiftShader), offline"
if ! command -v chromium > /dev/null; then echo "chromium is not installed (apt-get install chromium): skipped"; exit 77; fi
# Every request the browser makes goes to a proxy that forwards nothing and logs it: the page must make none.
/usr/bin/python3 "$src/tests/scripts/logging_proxy.py" "$work/requests.log" > proxy.port & proxy=$!
trap 'kill $proxy 2> /dev/null || true' EXIT
for _ in $(seq 50); do [ -s proxy.port ] && break; sleep 0.1; done
touch "$work/requests.log"
flags=(--headless --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader --disable-quic --no-first-run
       --disable-background-networking --disable-component-update --disable-sync --disable-default-apps
       --proxy-server="http://127.0.0.1:$(cat proxy.port)" --proxy-bypass-list="<-loopback>"
       --user-data-dir="$work/chromium-profile" --window-size=1280,2400 --hide-scrollbars)
# Chromium's own services (network time, component updates, sign-in) ask Google's hosts whatever the
# page does; every other request can only have come from the page.
page_requests() {
  if grep -Ev '^[A-Z]+ (https?://)?(clients[0-9]*\.google\.com|(update|optimizationguide-pa)\.googleapis\.com|accounts\.google\.com|[a-z0-9-]+\.gvt1\.com)[:/]' "$work/requests.log"; then
    echo "FAIL: the page asked the network for the above"; exit 1
  fi
}
page() {  # page FILE OUTPUT: the DOM after the scripts ran, and a screenshot
  timeout 180 chromium "${flags[@]}" --virtual-time-budget=15000 --dump-dom "file://$1" > "$2.html" 2>> chromium.log
  timeout 180 chromium "${flags[@]}" --virtual-time-budget=15000 --screenshot="$2.png" "file://$1" 2>> chromium.log
}
page "$work/out/report.html" dom-report
grep -q 'data-ready="yes"' dom-report.html || { echo "FAIL: the page's script did not run"; exit 1; }
grep -q 'id="leaderboard" data-rows="6"' dom-report.html || { echo "FAIL: leaderboard rows"; grep -o '<table[^>]*>' dom-report.html; exit 1; }
grep -q '&lt;script&gt;alert' dom-report.html || { echo "FAIL: a hostile name was not escaped"; exit 1; }
if grep -q "<script>alert" dom-report.html; then echo "FAIL: raw script from a config name"; exit 1; fi
grep -q "SIGSEGV" dom-report.html
grep -q 'src="data:image/png;base64,' dom-report.html
/usr/bin/python3 - "$work" <<'PY'
import re, sys, cv2, numpy as np
work = sys.argv[1]
dom = open(f"{work}/dom-report.html", encoding="utf-8").read()
body = re.search(r"<body([^>]*)>", dom).group(1)
attr = dict(re.findall(r'data-([a-z-]+)="([^"]*)"', body))
assert attr.get("viewer") == "drawn", f"the 3-D viewer was not drawn: {attr}"
assert "csp-violations" not in attr, f"the page tried to fetch something: {attr}"
# Five working entries on two sequences: ten views; the crasher has none.
assert attr.get("views") == "10", attr
assert attr.get("resources") == "0", f"resources fetched: {attr}"
cells = re.search(r'<table[^>]*id="cells"[^>]*>', dom).group(0)
assert 'data-rows="12"' in cells and 'data-visible="12"' in cells, cells  # 6 entries x 2 sequences
assert len(re.findall(r"<tr[^>]* data-view=", dom)) == 10
assert re.search(r'id="frame-info"[^>]*>t = ', dom), "no frame information under the slider"
assert 'class="main-svg"' in dom, "plotly drew no chart"
x, y, w, h = (int(v) for v in attr["viewer-rect"].split(","))
shot = cv2.imread(f"{work}/dom-report.png")
crop = shot[y:y + h, x:x + w]
assert crop.size and h > 300 and w > 300, (x, y, w, h, shot.shape)
ink = float(np.mean(np.any(crop < 235, axis=2)))
colours = len(np.unique(crop.reshape(-1, 3) // 16, axis=0))
assert ink > 0.02 and colours >= 12, f"the viewer's canvas looks blank: {ink:.4f} of its pixels inked, {colours} colours"
print(f"viewer canvas {w}x{h} at ({x},{y}): {ink:.3f} of its pixels inked, {colours} colour bins")
PY
page_requests
# The filters, set from the address: one algorithm, one sequence leaves one row of the cells table.
timeout 180 chromium "${flags[@]}" --virtual-time-budget=15000 --dump-dom "file://$work/out/report.html#entry=put_vo&row=sim%2Fv2" \
  > dom-filtered.html 2>> chromium.log
grep -Eq '<table[^>]*id="cells"[^>]*data-visible="1"' dom-filtered.html || { echo "FAIL: the filter from the address"; grep -o '<table[^>]*>' dom-filtered.html; exit 1; }
grep -Eq '<table[^>]*id="leaderboard"[^>]*data-visible="1"' dom-filtered.html || { echo "FAIL: the leaderboard filter"; exit 1; }
page_requests

echo "== vobench plot --out FILE.html"
run_dir=out/runs/$(/usr/bin/python3 -c 'import json; print([e for e in json.load(open("out/leaderboard.json"))["entries"] if e["entry"] == "put_vo"][0]["cells"][0]["id"])')/
"$vobench" -q plot --ref "${run_dir}groundtruth.txt" "${run_dir}trajectory.txt" --label "<b>estimate</b>" --out "$work/plot.html" > plot.log
page "$work/plot.html" dom-plot
/usr/bin/python3 - "$work" <<'PY'
import re, sys
dom = open(f"{sys.argv[1]}/dom-plot.html", encoding="utf-8").read()
attr = dict(re.findall(r'data-([a-z-]+)="([^"]*)"', re.search(r"<body([^>]*)>", dom).group(1)))
assert attr.get("viewer") == "drawn" and attr.get("views") == "1" and "csp-violations" not in attr, attr
assert "<b>estimate</b>" not in dom.split('id="vobench-data"')[0], "a label reached the page as markup"
print("plot.html: drawn, one view, offline")
PY
page_requests
echo "report.html and plot.html: rows, escaping, figures, the 3-D viewer's canvas and no network request checked ($work/dom-report.png, $work/dom-plot.png)"
