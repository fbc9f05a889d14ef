#!/usr/bin/env bash
# cmake/NpmAsset.cmake against a registry of its own (file:// URLs, laid out as npm's): the pinned
# tarball is extracted; a tampered one, a missing one and one without the file are refused with a
# message naming the package; a tampered tarball left in the build tree is fetched again.
#   npm_asset_check.sh SOURCE_DIR WORKDIR
set -euo pipefail
src=$1 work=$2
rm -rf "$work" && mkdir -p "$work/pkg/package" "$work/registry/demo/-" "$work/build"
echo "console.log('demo');" > "$work/pkg/package/demo.min.js"
tar -czf "$work/good.tgz" -C "$work/pkg" package
echo "console.log('tampered');" > "$work/pkg/package/demo.min.js"
tar -czf "$work/bad.tgz" -C "$work/pkg" package
rm "$work/pkg/package/demo.min.js" && echo x > "$work/pkg/package/other.js"
tar -czf "$work/empty.tgz" -C "$work/pkg" package
sum=$(sha512sum "$work/good.tgz" | cut -d' ' -f1)
cat > "$work/fetch.cmake" <<CMAKE
set(VOBENCH_NPM_REGISTRY "file://$work/registry")
include("$src/cmake/NpmAsset.cmake")
vobench_npm_asset(js PACKAGE demo VERSION 1.0.0 FILE package/demo.min.js SHA512 $sum)
file(READ "\${js}" text)
message(STATUS "extracted: \${text}")
CMAKE
fetch() { (cd "$work/build" && cmake -P "$work/fetch.cmake") > "$work/out.log" 2>&1; }
expect_refused() {  # expect_refused PATTERN WHAT
  if fetch; then cat "$work/out.log"; echo "FAIL: $2 accepted"; exit 1; fi
  # cmake wraps its messages: matched on the log as one line
  tr -s ' \n' ' ' < "$work/out.log" | grep -q "$1" || { cat "$work/out.log"; echo "FAIL: $2: no '$1'"; exit 1; }
  echo "ok: $2 refused ($1)"
}
expect_refused "Could not fetch demo@1.0.0 from file://" "a package the registry does not have"
cp "$work/bad.tgz" "$work/registry/demo/-/demo-1.0.0.tgz"
expect_refused "demo@1.0.0 from file://.*: SHA-512 mismatch" "a tampered tarball"
cp "$work/empty.tgz" "$work/registry/demo/-/demo-1.0.0.tgz"
sed -i "s/$sum/$(sha512sum "$work/empty.tgz" | cut -d' ' -f1)/" "$work/fetch.cmake"
expect_refused "package/demo.min.js: Not found in archive" "a tarball without the file"
sed -i "s/$(sha512sum "$work/empty.tgz" | cut -d' ' -f1)/$sum/" "$work/fetch.cmake"
rm -rf "$work/build"/* && cp "$work/good.tgz" "$work/registry/demo/-/demo-1.0.0.tgz"
fetch && grep -q "extracted: console.log('demo');" "$work/out.log" || { cat "$work/out.log"; echo "FAIL: the pinned tarball"; exit 1; }
echo "ok: the pinned tarball is fetched and its file extracted"
# The copy in the build tree is tampered with (the registry now serves the good one): fetched again.
cached=$(find "$work/build/_npm" -name '*.tgz')
cp "$work/bad.tgz" "$cached" && rm -f "$work/build/_npm/demo-1.0.0/package/demo.min.js"
fetch && grep -q "Fetching demo@1.0.0" "$work/out.log" && grep -q "extracted: console.log('demo');" "$work/out.log" ||
  { cat "$work/out.log"; echo "FAIL: a tampered cached tarball was used"; exit 1; }
echo "ok: a tampered tarball in the build tree is fetched again"
