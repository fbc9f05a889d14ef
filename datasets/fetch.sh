#!/usr/bin/env bash
# fetch.sh DATASET [NAME ...] [--dest DIR] [--trust-on-first-use]
#
# Downloads sequences listed in datasets/DATASET/sources.txt (`name url sha256`, '#' comments) into
# DIR (default datasets/DATASET), verifies each archive's SHA-256 and unpacks it. A source whose
# checksum is not pinned yet (sha256 `-`) is refused unless --trust-on-first-use is given; the checksum
# then computed is recorded in DIR/pinned.sha256 and enforced on every later fetch. This machine has
# no internet, so no upstream checksum could be pinned here: see each data set's README.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
dataset=${1:?usage: fetch.sh DATASET [NAME ...] [--dest DIR] [--trust-on-first-use]}
shift
dest="$here/$dataset" tofu=0 names=()
while [ $# -gt 0 ]; do
  case $1 in
    --dest) dest=$2; shift 2 ;;
    --trust-on-first-use) tofu=1; shift ;;
    *) names+=("$1"); shift ;;
  esac
done
sources=${VOBENCH_SOURCES:-$here/$dataset/sources.txt}
[ -f "$sources" ] || { echo "fetch.sh: no $sources" >&2; exit 2; }
mkdir -p "$dest"
pinned="$dest/pinned.sha256"
touch "$pinned"
status=0
while read -r name url sha; do
  [ -z "${name:-}" ] && continue
  case $name in \#*) continue ;; esac
  if [ ${#names[@]} -gt 0 ] && ! printf '%s\n' "${names[@]}" | grep -qx "$name"; then continue; fi
  archive="$dest/$(basename "$url")"
  expected=$sha
  [ "$expected" = "-" ] && expected=$(awk -v n="$name" '$2 == n {print $1}' "$pinned")
  if [ -z "$expected" ] && [ $tofu -eq 0 ]; then
    echo "fetch.sh: $name: no pinned SHA-256; refusing (use --trust-on-first-use to pin the first download)" >&2
    status=1; continue
  fi
  echo "fetch.sh: $name <- $url"
  curl -fL --retry 3 -o "$archive.part" "$url"
  actual=$(sha256sum "$archive.part" | cut -d' ' -f1)
  if [ -n "$expected" ] && [ "$actual" != "$expected" ]; then
    echo "fetch.sh: $name: SHA-256 mismatch: expected $expected, got $actual ($archive.part kept for inspection)" >&2
    status=1; continue
  fi
  [ -z "$expected" ] && { echo "$actual $name" >> "$pinned"; echo "fetch.sh: $name: pinned $actual (trust on first use)"; }
  mv "$archive.part" "$archive"
  case $archive in
    *.tgz|*.tar.gz) tar -xzf "$archive" -C "$dest" ;;
    *.zip) unzip -oq "$archive" -d "$dest" ;;
  esac
  echo "fetch.sh: $name: ok"
done < "$sources"
exit $status
