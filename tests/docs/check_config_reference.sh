#!/usr/bin/env bash
# docs/config-reference.md must be exactly what `stochnav plugins doc` prints for the bundled
# plugins: regenerate it with
#   STOCHNAV_PLUGIN_PATH= build/release/framework/stochnav plugins doc > docs/config-reference.md
# Usage: check_config_reference.sh STOCHNAV REFERENCE.md
set -euo pipefail
stochnav=$1 reference=$2
if ! diff -u "$reference" <("$stochnav" plugins doc); then
  echo "$reference differs from \`stochnav plugins doc\` (above); regenerate it:" \
       "STOCHNAV_PLUGIN_PATH= $stochnav plugins doc > $reference" >&2
  exit 1
fi
