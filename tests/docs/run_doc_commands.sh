#!/usr/bin/env bash
# Runs every ```sh block of a Markdown page, in order, as one script, so that a page's commands
# cannot drift from the tool. The blocks run in a scratch folder holding a link to the
# repository's configs/, with `stochnav` on the PATH; a failing command fails the test and
# names itself (set -x). ```text blocks are shown, not run (install paths, placeholders).
# Usage: run_doc_commands.sh STOCHNAV SOURCE_DIR PAGE.md
set -euo pipefail
stochnav=$1 source_dir=$2 page=$3
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
mkdir "$scratch/bin" "$scratch/work"
printf '#!/bin/sh\nexec "%s" "$@"\n' "$stochnav" > "$scratch/bin/stochnav"
chmod +x "$scratch/bin/stochnav"
ln -s "$source_dir/configs" "$scratch/work/configs"
awk '/^```sh$/ { inside = 1; next } /^```/ { inside = 0 } inside' "$page" > "$scratch/commands.sh"
if [[ ! -s $scratch/commands.sh ]]; then
  echo "$page has no \`\`\`sh block: nothing would be checked" >&2
  exit 1
fi
cd "$scratch/work"
PATH="$scratch/bin:$PATH" bash -euxo pipefail "$scratch/commands.sh"
