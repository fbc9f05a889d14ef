#!/usr/bin/env bash
# effect_ablation.sh VOBENCH OUT [SENSORS] [TRAJECTORY] [FRAMES] [ALGORITHM] [SEEDS] — what each effect
# of the sensor models (docs/synthetic-sensors.md) costs an algorithm: renders the path with all
# effects, then once with each effect off, runs the algorithm on each (vobench track, Kraft et al.'s
# RPE over 4 frames) and prints "effect → RPE change" per sensor as a Markdown table. For each render
# seed the only difference between two rows is the effect; over 60 frames one seed's RPE moves by tens
# of per cent with any change to the frames, so give several seeds (e.g. "1 2 3"): the table then
# shows the median over seeds, and the change is the median of each seed's own change [their range].
#   scripts/effect_ablation.sh build/bin/vobench /tmp/ablation "kinect1 kinect2" explore1 60 put_vo "1 2 3"
set -euo pipefail
vobench=$1 out=$2 sensors=${3:-"kinect1 kinect2"} trajectory=${4:-explore1} frames=${5:-60} algorithm=${6:-put_vo}
seeds=${7:-1}
effects="motion_blur optics_blur image_noise smooth_noise vignetting auto_exposure highlights rolling_shutter depth_noise
correlated_depth_noise fixed_pattern_noise disparity_pattern projector_shadow depth_border registration_error dark_dropout glancing_dropout far_dropout edge_dropout flying_pixels"
mkdir -p "$out"
metric() {  # folder → "ATE RPE_t RPE_r"
  "$vobench" track --dataset tum --path "$1" --algorithm "$algorithm" --json 2>/dev/null |
    python3 -c 'import json,sys; m=json.load(sys.stdin)["metrics"]; print(m["ate.rmse"], m["rpe.trans.rmse"], m["rpe.rot.rmse"])'
}
echo "| sensor | effect off | ATE [m] | RPE t [m] | RPE r [°] | RPE t change |"
echo "|---|---|---:|---:|---:|---:|"
for sensor in $sensors; do
  declare -A base=()  # seed → the all-on folder's RPE t, tracked once (the "all" pass comes first)
  for effect in all $effects; do
    spec=$([ "$effect" = all ] && echo "" || echo "-$effect")
    rows=""
    for seed in $seeds; do
      dir=$out/$sensor-$trajectory-s$seed-$effect
      [ -f "$dir/synth.json" ] || "$vobench" synth --sensor "$sensor" --trajectory "$trajectory" --frames "$frames" --seed "$seed" \
        --effects "$spec" --out "$dir" > /dev/null 2>&1
      read -r ate rpe rot <<< "$(metric "$dir")"
      [ "$effect" = all ] && base[$seed]=$rpe
      rows="$rows $ate,$rpe,$rot,${base[$seed]}"
    done
    python3 - "$sensor" "$([ "$effect" = all ] && echo '(none: all on)' || echo "$effect")" $rows <<'PY'
import statistics, sys
sensor, name, rows = sys.argv[1], sys.argv[2], [[float(x) for x in r.split(",")] for r in sys.argv[3:]]
med = lambda k: statistics.median(r[k] for r in rows)
changes = [100 * (r[1] - r[3]) / r[3] for r in rows]
spread = f" [{min(changes):+.0f} … {max(changes):+.0f}]" if len(changes) > 1 else ""
print(f"| {sensor} | {name} | {med(0):.4f} | {med(1):.4f} | {med(2):.3f} | {statistics.median(changes):+.0f} %{spread} |")
PY
  done
done
