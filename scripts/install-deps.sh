#!/usr/bin/env bash
# Installs the Debian 12 packages vobench needs, only those missing, non-interactively.
# Used by `make demo` and (with --test: what the tests also need) `make test`; safe to run again (it
# does nothing when all are present).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  libopencv-dev libopencv-contrib-dev   # OpenCV 4.6 with rgbd and optflow
  libeigen3-dev libyaml-cpp-dev nlohmann-json3-dev
  libboost-dev libboost-filesystem-dev  # Boost.DLL, Boost.Process (1.74)
  libcli11-dev libspdlog-dev libfmt-dev libtbb-dev libzstd-dev
  catch2 libbenchmark-dev
  binutils                              # nm, for the exported-symbol test
  curl                                  # datasets/fetch.sh
  clang libclang-rt-14-dev              # libFuzzer targets of the text parsers (found when configuring)
  gnuplot-nox                           # the report's figures
  pybind11-dev python3-dev python3-numpy  # the Python bridge plugins (python, python_dataset)
  libopen3d-dev                         # the open3d_rgbd plugin (Open3D's RGB-D odometry)
  libembree-dev                         # the renderer's ray casting (Embree 3)
  libdeflate-dev                        # the dataset readers' PNG inflating (plugins/common/png_raster.cpp)
)
if [ "${1:-}" = "--test" ]; then
  packages+=(
    python3 python3-jsonschema          # leaderboard.json against its JSON Schema
    chromium                            # report.html opened headless
    procps                              # pgrep/pkill in the sweep and Slurm tests
    clang-format                        # the format check (CTest style.format)
    python3-opencv                      # the Python example plugin (orb_pnp.py) and its tests
  )
fi

missing=()
for p in "${packages[@]}"; do
  [[ "$p" == \#* ]] && continue
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "vobench: installing missing Debian packages: ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then SUDO="sudo"; else
    echo "vobench: these packages are missing and I am not root (and there is no sudo): ${missing[*]}" >&2
    exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
