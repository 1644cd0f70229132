#!/usr/bin/env bash
# Runs every ```sh block of a Markdown page, in order, as one script, so that a page's commands
# cannot drift from the tool. The blocks run in a scratch folder holding links to the
# repository's examples/, a copy of its configs/, build/release (to the build folder under test)
# and, when the page needs it, ../shared/data (the reference data, STOCHNAV_SHARED_DATA_DIR);
# `stochnav` is on the PATH, and so is `python3` as $PYTHON when that is set. A failing command fails
# the test and names itself (set -x). ```text blocks are shown, not run (synopses with
# placeholders, install and CI commands). A page whose commands read ../shared/data is skipped
# (exit 77) when the data is absent.
# Usage: run_doc_commands.sh STOCHNAV SOURCE_DIR BUILD_DIR PAGE.md
set -euo pipefail
stochnav=$1 source_dir=$2 build_dir=$3 page=$4
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
mkdir -p "$scratch/bin" "$scratch/work/build"
printf '#!/bin/sh\nexec "%s" "$@"\n' "$stochnav" > "$scratch/bin/stochnav"
chmod +x "$scratch/bin/stochnav"
if [[ -n ${PYTHON:-} ]]; then  # the interpreter the build found, as python3
  printf '#!/bin/sh\nexec "%s" "$@"\n' "$PYTHON" > "$scratch/bin/python3"
  chmod +x "$scratch/bin/python3"
fi
cp -r "$source_dir/configs" "$scratch/work/configs"  # a copy: configs name data relative to themselves
ln -s "$source_dir/examples" "$scratch/work/examples"
ln -s "$build_dir" "$scratch/work/build/release"
awk '/^```sh$/ { inside = 1; next } /^```/ { inside = 0 } inside' "$page" > "$scratch/commands.sh"
if [[ ! -s $scratch/commands.sh ]]; then
  echo "$page has no \`\`\`sh block: nothing would be checked" >&2
  exit 1
fi
shared_data=${STOCHNAV_SHARED_DATA_DIR:-$source_dir/../shared/data}
if grep -q '\.\./shared/data' "$scratch/commands.sh"; then
  if [[ ! -d $shared_data ]]; then
    echo "skipped: $page reads ../shared/data, and $shared_data is not there" >&2
    exit 77
  fi
  mkdir "$scratch/shared"
  ln -s "$(cd "$shared_data" && pwd)" "$scratch/shared/data"
fi
cd "$scratch/work"
PATH="$scratch/bin:$PATH" bash -euxo pipefail "$scratch/commands.sh"
