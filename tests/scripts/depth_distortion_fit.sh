#!/usr/bin/env bash
# depth_distortion_fit.sh SOURCE_DIR REAL — the `tum-fr1` camera's disparity distortion
# (harness/src/synth/camera_catalog.cpp) is what scripts/fit_depth_distortion.py measures on the real
# fr1/rpy sample, and it lowers the residual there. Needs Debian's python3 with numpy and OpenCV
# (python3-opencv, installed by `make test`); skipped (77) without them.
set -euo pipefail
src=$1 real=$2
python=/usr/bin/python3
if ! "$python" -c 'import cv2, numpy' 2>/dev/null; then
  echo "SKIPPED: $python has no cv2/numpy (Debian: apt-get install python3-opencv)"
  exit 77
fi
coefficients=$(sed -n 's/.*fr1.disparity_distortion_px = {\(.*\)};.*/\1/p' "$src/harness/src/synth/camera_catalog.cpp" | tr -d ' ')
if [ -z "$coefficients" ]; then
  echo "camera_catalog.cpp: no fr1.disparity_distortion_px = {a, b, c}; line found"
  exit 1
fi
exec "$python" "$src/scripts/fit_depth_distortion.py" "$real/rgbd_dataset_freiburg1_rpy" \
  --validate "$real/rgbd_dataset_freiburg1_desk" --expect="$coefficients" --tolerance 0.05
