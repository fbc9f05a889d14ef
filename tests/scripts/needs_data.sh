#!/usr/bin/env bash
# needs_data.sh DIR command... — runs the command when DIR exists; otherwise says why and exits 77,
# which CTest reports as skipped (SKIP_RETURN_CODE).
dir=$1
shift
if [ ! -e "$dir" ]; then
  echo "SKIPPED: test data $dir is absent (set VOBENCH_TEST_DATA_DIR at configure time)"
  exit 77
fi
exec "$@"
