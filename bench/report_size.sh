#!/usr/bin/env bash
# The report of a 100-cell sweep: how long `vobench report` takes and how large report.html is, with
# the figures and without gnuplot (PATH without it: data and scripts only), best of N runs each.
# Two sweeps of 100 cells on two rendered Kinect v1 sequences (FRAMES frames; the sweeps themselves are
# not timed): "repeats", five put_vo variants × ten repeats (10 explorer views), and "wide", 50 put_vo
# variants (a parameter grid) × one repeat (100 views, each with its trajectory, RPE and timing).
# Not part of `make test`: a benchmark, not a test.
#   bench/report_size.sh [BUILD_DIR] [WORKDIR] [FRAMES] [N]
set -eu
build=$(cd "${1:-build}" && pwd)
work=${2:-/tmp/vobench-report-size}
frames=${3:-300}
n=${4:-3}
mkdir -p "$work" && cd "$work"
for t in explore1 speed3; do
  [ -d "$t" ] || "$build/bin/vobench" -q synth --sensor kinect1 --trajectory "$t" --frames "$frames" --out "$t"
done
cat > repeats.yaml <<YAML
name: report size, 100 cells (5 entries x 2 sequences x 10 repeats)
datasets:
  - {name: sim, reader: tum, path: ., sequences: [explore1, speed3]}
algorithms:
  - {plugin: put_vo}
  - {name: paper, plugin: put_vo, params: {profile: paper}}
  - {name: umeyama, plugin: put_vo, params: {refinement: umeyama}}
  - {name: nearest, plugin: put_vo, params: {depth_interpolation: false}}
  - {name: keyframe6, plugin: put_vo, params: {keyframe_interval: 6}}
repeats: 10
YAML
cat > wide.yaml <<YAML
name: report size, 100 cells (50 entries x 2 sequences)
datasets:
  - {name: sim, reader: tum, path: ., sequences: [explore1, speed3]}
algorithms:
  - plugin: put_vo
    grid: {keyframe_interval: {from: 1, to: 10, step: 1}, redetect_below: [100, 150, 200, 250, 300]}
YAML
nognuplot=$(mktemp -d)
for tool in sh bash env; do ln -sf "$(command -v $tool)" "$nognuplot/$tool"; done
best() {  # best of n wall-clock seconds of "$@"
  local b=1e9
  for _ in $(seq "$n"); do
    local s e
    s=$(date +%s.%N); "$@" > /dev/null 2>&1 || true; e=$(date +%s.%N)
    b=$(echo "$e - $s" | bc -l | awk -v b="$b" '{print ($1 < b) ? $1 : b}')
  done
  echo "$b"
}
for layout in repeats wide; do
  out=out-$layout
  [ -f $out/leaderboard.json ] || "$build/bin/vobench" -q run $layout.yaml --out $out -j 2 > run-$layout.log 2>&1 || true
  cells=$(ls $out/runs | wc -l)
  with=$(best "$build/bin/vobench" -q report $out)
  size_with=$(stat -c %s $out/report.html)
  figures=$(ls $out/figures/*.png 2>/dev/null | wc -l)
  views=$(grep -o '"cell":"[0-9a-f]*"' $out/report.html | wc -l)
  without=$(best env PATH="$nognuplot" "$build/bin/vobench" -q report $out)
  size_without=$(stat -c %s $out/report.html)
  printf '%s: %s cells (%s frames a sequence), %s explorer views, %s figures\n' "$layout" "$cells" "$frames" "$views" "$figures"
  printf '  vobench report with gnuplot:    %6.2f s, report.html %5.2f MB\n' "$with" "$(echo "$size_with / 1048576" | bc -l)"
  printf '  vobench report without gnuplot: %6.2f s, report.html %5.2f MB (no figures embedded)\n' "$without" "$(echo "$size_without / 1048576" | bc -l)"
  "$build/bin/vobench" -q report $out > /dev/null 2>&1 || true
done
