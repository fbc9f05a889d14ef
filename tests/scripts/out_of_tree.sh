#!/usr/bin/env bash
# out_of_tree.sh BUILD_DIR TEMPLATE_DIR WORK_DIR CMAKE
# Installs the vobench SDK from BUILD_DIR into a fresh prefix, builds the plugin template out of tree
# against it with find_package(vobench), then loads and checks the result with the CLI.
set -euo pipefail
build=$1 template=$2 work=$3 cmake=$4
rm -rf "$work"
mkdir -p "$work"
"$cmake" --install "$build" --prefix "$work/prefix" --component sdk
"$cmake" -S "$template" -B "$work/build" -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_BUILD_TYPE=Release
"$cmake" --build "$work/build"
plugin="$work/build/vobench_template.so"
test -f "$plugin"
# Only the entry symbol is exported.
exports=$(nm -D --defined-only "$plugin" | awk '{print $3}' | grep -v '^$' | sort -u)
echo "exports: $exports"
[ "$exports" = "vobench_plugin_entry_v1" ]
"$build/bin/vobench" plugins check "$plugin"
VOBENCH_PLUGIN_PATH="$work/build" "$build/bin/vobench" plugins info template --json | grep -q "$work/build/vobench_template.so"
echo "out-of-tree plugin built, checked and found on VOBENCH_PLUGIN_PATH"
