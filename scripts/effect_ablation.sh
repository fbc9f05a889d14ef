#!/usr/bin/env bash
# effect_ablation.sh VOBENCH OUT [SENSORS] [TRAJECTORY] [FRAMES] [ALGORITHM] — what each effect of the
# sensor models (docs/synthetic-sensors.md) costs an algorithm: renders the path with all effects,
# then once with each effect off, runs the algorithm on each (vobench track, Kraft et al.'s RPE over 4
# frames) and prints "effect → RPE change" per sensor as a Markdown table. Same seed throughout, so
# the only difference between two rows is the effect.
#   scripts/effect_ablation.sh build/bin/vobench /tmp/ablation "kinect1 kinect2" explore1 60 put_vo
set -euo pipefail
vobench=$1 out=$2 sensors=${3:-"kinect1 kinect2"} trajectory=${4:-explore1} frames=${5:-60} algorithm=${6:-put_vo}
effects="motion_blur optics_blur image_noise vignetting auto_exposure highlights rolling_shutter depth_noise projector_shadow
depth_border registration_error dark_dropout glancing_dropout far_dropout edge_dropout flying_pixels"
mkdir -p "$out"
metric() {  # folder → "ATE RPE_t RPE_r"
  "$vobench" track --dataset tum --path "$1" --algorithm "$algorithm" --json 2>/dev/null |
    python3 -c 'import json,sys; m=json.load(sys.stdin)["metrics"]; print(m["ate.rmse"], m["rpe.trans.rmse"], m["rpe.rot.rmse"])'
}
echo "| sensor | effect off | ATE [m] | RPE t [m] | RPE r [°] | RPE t change |"
echo "|---|---|---:|---:|---:|---:|"
for sensor in $sensors; do
  base=""
  for effect in all $effects; do
    spec=$([ "$effect" = all ] && echo "" || echo "-$effect")
    dir=$out/$sensor-$trajectory-$effect
    [ -f "$dir/synth.json" ] || "$vobench" synth --sensor "$sensor" --trajectory "$trajectory" --frames "$frames" --effects "$spec" \
      --out "$dir" > /dev/null 2>&1
    read -r ate rpe rot <<< "$(metric "$dir")"
    [ -z "$base" ] && base=$rpe
    change=$(python3 -c "print(f'{100 * ($rpe - $base) / $base:+.0f} %')")
    printf '| %s | %s | %.4f | %.4f | %.3f | %s |\n' "$sensor" "$([ "$effect" = all ] && echo '(none: all on)' || echo "$effect")" \
      "$ate" "$rpe" "$rot" "$change"
  done
done
