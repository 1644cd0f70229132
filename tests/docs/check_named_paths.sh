#!/usr/bin/env bash
# Every examples/ and configs/ path that README.md, docs/ and plugins/README.md name exists, so a
# page cannot send a reader to a script or config that was renamed or removed.
# Usage: check_named_paths.sh SOURCE_DIR
set -euo pipefail
cd "$1"
missing=0
while IFS=: read -r page path; do
  if [[ ! -e $path ]]; then
    echo "$page names $path, which does not exist; fix the page or restore the file" >&2
    missing=1
  fi
done < <(grep -o -E '(examples|configs)/[A-Za-z0-9_./-]*[A-Za-z0-9_]' \
           README.md docs/*.md plugins/README.md | sort -u)
exit $missing
