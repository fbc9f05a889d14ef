#!/usr/bin/env bash
# make demo: list the plugins, then run the main job on embedded synthetic data.
set -euo pipefail
build=${1:-build}
cd "$(dirname "$0")/.."
echo "== plugins"
"$build/bin/vobench" plugins list
echo
echo "== the main job: Kinect v1 vs Kinect v2, put_vo and the baselines (synthetic data rendered once, then cached)"
time "$build/bin/vobench" run configs/quickstart.yaml --resume -j "$(nproc)"
