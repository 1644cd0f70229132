#!/usr/bin/env bash
# Runs one example script end to end and checks what it wrote.
# Usage: run_example.sh [--needs FILE]... STOCHNAV SCRIPT EXPECTED...
#   STOCHNAV: the built binary (passed to the script as $STOCHNAV); SCRIPT: the example, given a
#   scratch output folder as its first argument (a .py script runs with $PYTHON, default python3); EXPECTED: files the script must write there,
#   each non-empty (relative to the output folder). --needs: reference data the example reads;
#   when one is absent the test is skipped (exit 77, CTest's SKIP_RETURN_CODE here).
set -euo pipefail
while [[ $1 == --needs ]]; do
  if [[ ! -f $2 ]]; then
    echo "skipped: $2 not found (the reference data in ../shared/data)"
    exit 77
  fi
  shift 2
done
stochnav=$1 script=$2
shift 2
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
case $script in
  *.py) STOCHNAV="$stochnav" "${PYTHON:-python3}" "$script" "$scratch/out" ;;
  *) STOCHNAV="$stochnav" bash "$script" "$scratch/out" ;;
esac
for file in "$@"; do
  if [[ ! -s $scratch/out/$file ]]; then
    echo "$script exited 0 but did not write $file" >&2
    exit 1
  fi
done
