#!/usr/bin/env bash
# sim_to_real.sh VOBENCH SOURCE_DIR WORK REAL — issue #15's check: render the real TUM fr1/rpy sample's
# ground-truth poses at its own colour and depth stamps through TUM's fr1 camera in the offices of
# seeds 1-10, run the algorithms of configs/sim_to_real.yaml on the real and the rendered folders, and
# compare their RPE (sim_to_real_compare.py: every ratio of the median over the renderings to the real
# figure in [0.67, 1.5], the same order by rotation).
set -euo pipefail
vobench=$1 src=$2 work=$3 real=$4
seq=$real/rgbd_dataset_freiburg1_rpy
rm -rf "$work"
mkdir -p "$work/rendered"
for k in $(seq 1 10); do
  "$vobench" synth --sensor kinect1 --camera tum-fr1 --trajectory "$seq/groundtruth.txt" --trajectory-format tum --stamps "$seq" \
    --layout tum --seed "$k" --out "$work/rendered/seed$k/rgbd_dataset_freiburg1_rpy"
done
"$vobench" synth stats --camera tum-fr1 "$seq" "$work"/rendered/seed{1,2,3,4,5,6,7,8,9,10}/rgbd_dataset_freiburg1_rpy
VOBENCH_REAL=$real VOBENCH_RENDERED=$work/rendered "$vobench" run "$src/configs/sim_to_real.yaml" -j 2 --out "$work/sweep" > "$work/sweep.log"
python3 "$src/tests/scripts/sim_to_real_compare.py" "$vobench" "$work/sweep"
