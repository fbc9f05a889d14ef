#!/usr/bin/env bash
# sim_to_real.sh VOBENCH SOURCE_DIR WORK REAL — issue #15's check: render the real TUM fr1/rpy sample's
# ground-truth poses at its own colour and depth stamps through TUM's fr1 camera, run the algorithms
# of configs/sim_to_real.yaml on the real and the rendered folder, and compare their RPE
# (sim_to_real_compare.py: every rendered/real ratio in [0.67, 1.5], the same order by rotation).
set -euo pipefail
vobench=$1 src=$2 work=$3 real=$4
seq=$real/rgbd_dataset_freiburg1_rpy
rm -rf "$work"
mkdir -p "$work/rendered"
"$vobench" synth --sensor kinect1 --camera tum-fr1 --trajectory "$seq/groundtruth.txt" --trajectory-format tum --stamps "$seq" \
  --layout tum --out "$work/rendered/rgbd_dataset_freiburg1_rpy"
"$vobench" synth stats "$seq" "$work/rendered/rgbd_dataset_freiburg1_rpy"
VOBENCH_REAL=$real VOBENCH_RENDERED=$work/rendered "$vobench" run "$src/configs/sim_to_real.yaml" -j 2 --out "$work/sweep" > "$work/sweep.log"
python3 "$src/tests/scripts/sim_to_real_compare.py" "$vobench" "$work/sweep"
