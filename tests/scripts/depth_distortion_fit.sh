#!/usr/bin/env bash
# depth_distortion_fit.sh VOBENCH SOURCE_DIR REAL WORK — the `tum-fr1` camera's measured disparity
# distortion (disparity_distortion_fit_px, harness/src/synth/camera_catalog.cpp) is what `vobench synth
# fit-distortion` measures on the real fr1/rpy sample (within 0.05 px), and it lowers the residual there
# (fr1/desk, which the fit never sees, is printed beside it); and a rendering of the sample's poses
# through the camera reads back the same field (a within 0.15 px, b within 0.08, c within 0.6: over the
# ten offices of sim_to_real.sh, generator 15, a reads back −0.68…−0.13, b 0.988–1.129 and c
# −1.56…−0.39, mean (−0.390, 1.066, −0.960) against the real (−0.389, 1.065, −0.969); office 1 reads
# (−0.282, 1.129, −0.456). Each office's Kinect v1 has its own fixed disparity pattern (effect
# disparity_pattern), and the fit's weights see part of it as a field; before it, generator 14, the
# offices spread a −0.44…−0.36, b 1.050–1.085, c −1.47…−0.55). Then the joint fit (--fit-latency
# --fit-turn): the reference's turn about x that the rendering reads back is the real sample's within
# 0.15° (the camera's reference_turn_deg was chosen so; the ten offices read back +0.14…+1.12°, mean
# +0.60°, against the real +0.52°, office 1 +0.44°).
set -euo pipefail
vobench=$1 src=$2 real=$3 work=$4
seq=$real/rgbd_dataset_freiburg1_rpy
coefficients=$(sed -n 's/.*fr1.disparity_distortion_fit_px = {\(.*\)};.*/\1/p' "$src/harness/src/synth/camera_catalog.cpp" | tr -d ' ')
if [ -z "$coefficients" ]; then
  echo "camera_catalog.cpp: no fr1.disparity_distortion_fit_px = {a, b, c}; line found"
  exit 1
fi
"$vobench" synth fit-distortion "$seq" --camera tum-fr1 --validate "$real/rgbd_dataset_freiburg1_desk" \
  --expect="$coefficients" --tolerance 0.05
rm -rf "$work"
"$vobench" synth --sensor kinect1 --camera tum-fr1 --trajectory "$seq/groundtruth.txt" --trajectory-format tum --stamps "$seq" \
  --layout tum --seed 1 --out "$work/rgbd_dataset_freiburg1_rpy"
"$vobench" synth fit-distortion "$work/rgbd_dataset_freiburg1_rpy" --camera tum-fr1 --expect="$coefficients" \
  --tolerance 0.15,0.08,0.6
# The x component of the joint fit's reference turn, in degrees.
turn_x() {
  "$vobench" synth fit-distortion "$1" --camera tum-fr1 --fit-latency --fit-turn |
    sed -n 's/.*reference turn (\([-+0-9.]*\),.*/\1/p'
}
real_x=$(turn_x "$seq")
rendered_x=$(turn_x "$work/rgbd_dataset_freiburg1_rpy")
echo "reference turn about x, joint fit: real $real_x°, rendered $rendered_x°"
if [ -z "$real_x" ] || [ -z "$rendered_x" ]; then
  echo "FAIL: no reference turn in fit-distortion's output"
  exit 1
fi
if ! awk -v a="$real_x" -v b="$rendered_x" 'BEGIN { d = a - b; exit !(d < 0.15 && d > -0.15) }'; then
  echo "FAIL: the rendering reads back a turn about x more than 0.15° from the real sample's"
  exit 1
fi
