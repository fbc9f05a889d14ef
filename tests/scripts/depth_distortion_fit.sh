#!/usr/bin/env bash
# depth_distortion_fit.sh VOBENCH SOURCE_DIR REAL — the `tum-fr1` camera's disparity distortion
# (harness/src/synth/camera_catalog.cpp) is what `vobench synth fit-distortion` measures on the real
# fr1/rpy sample (within 0.05 px), and it lowers the residual there; fr1/desk, which the fit never
# sees, is printed beside it.
set -euo pipefail
vobench=$1 src=$2 real=$3
coefficients=$(sed -n 's/.*fr1.disparity_distortion_px = {\(.*\)};.*/\1/p' "$src/harness/src/synth/camera_catalog.cpp" | tr -d ' ')
if [ -z "$coefficients" ]; then
  echo "camera_catalog.cpp: no fr1.disparity_distortion_px = {a, b, c}; line found"
  exit 1
fi
exec "$vobench" synth fit-distortion "$real/rgbd_dataset_freiburg1_rpy" --camera tum-fr1 \
  --validate "$real/rgbd_dataset_freiburg1_desk" --expect="$coefficients" --tolerance 0.05
