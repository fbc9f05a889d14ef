#!/usr/bin/env bash
# The checksum logic of datasets/fetch.sh on local files (file:// URLs): a pinned checksum that
# matches, one that does not, an unpinned source refused, then pinned on first use and enforced.
set -euo pipefail
fetch=$1 work=$2
rm -rf "$work"; mkdir -p "$work/src"
echo "hello vobench" > "$work/src/good.txt"
tar -czf "$work/src/seq.tgz" -C "$work/src" good.txt
sum=$(sha256sum "$work/src/seq.tgz" | cut -d' ' -f1)
printf 'seq file://%s %s\n' "$work/src/seq.tgz" "$sum" > "$work/pinned.txt"
printf 'seq file://%s %s\n' "$work/src/seq.tgz" "0000000000000000000000000000000000000000000000000000000000000000" > "$work/wrong.txt"
printf 'seq file://%s -\n' "$work/src/seq.tgz" > "$work/unpinned.txt"

VOBENCH_SOURCES="$work/pinned.txt" "$fetch" tum --dest "$work/a"
test -f "$work/a/good.txt"
if VOBENCH_SOURCES="$work/wrong.txt" "$fetch" tum --dest "$work/b" 2> "$work/err"; then echo "mismatch accepted"; exit 1; fi
grep -q "SHA-256 mismatch" "$work/err"
if VOBENCH_SOURCES="$work/unpinned.txt" "$fetch" tum --dest "$work/c" 2> "$work/err"; then echo "unpinned accepted"; exit 1; fi
grep -q "no pinned SHA-256; refusing" "$work/err"
VOBENCH_SOURCES="$work/unpinned.txt" "$fetch" tum --dest "$work/c" --trust-on-first-use
grep -q "$sum seq" "$work/c/pinned.sha256"
echo "tampered" > "$work/src/good.txt"; tar -czf "$work/src/seq.tgz" -C "$work/src" good.txt
if VOBENCH_SOURCES="$work/unpinned.txt" "$fetch" tum --dest "$work/c" 2> "$work/err"; then echo "changed file accepted"; exit 1; fi
grep -q "SHA-256 mismatch" "$work/err"
echo "fetch.sh checksum logic: ok"
