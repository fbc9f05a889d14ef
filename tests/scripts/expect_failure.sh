#!/usr/bin/env bash
# Runs a command that must fail (exit status 1, not a crash of vobench itself) and prints its output
# for CTest's PASS_REGULAR_EXPRESSION.
"$@"
status=$?
echo "exit status: $status"
[ "$status" -eq 1 ]
