#!/usr/bin/env bash
# The drilling envelope family (envelope.py): seeded wells across latitude, direction, mode and
# ROP, each from a field start with the shipped recording config, scored against truth kept
# aside. docs/drilling-envelope.md reports a run of 12 wells of 8 h.
# Usage: examples/drilling_envelope/run.sh [OUT_DIR] [WELLS] [HOURS]
#        (or STOCHNAV_ENVELOPE_WELLS / STOCHNAV_ENVELOPE_HOURS; default 12 wells of 8 h)
#        (STOCHNAV=path/to/stochnav to choose the binary; STOCHNAV_ENVELOPE_REQUIRE_INSIDE=0.95
#        to exit 1 unless 95 % of the family's stations are inside 3 sigma in every quantity
#        and no well is silently wrong)
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
stochnav="${STOCHNAV:-$root/build/release/framework/stochnav}"
out="${1:-$root/out/drilling_envelope}"
mkdir -p "$out"
python3 "$root/examples/drilling_envelope/envelope.py" "$stochnav" "$out" \
  --wells "${2:-${STOCHNAV_ENVELOPE_WELLS:-12}}" --hours "${3:-${STOCHNAV_ENVELOPE_HOURS:-8}}" \
  ${STOCHNAV_ENVELOPE_REQUIRE_INSIDE:+--require-inside "$STOCHNAV_ENVELOPE_REQUIRE_INSIDE"}
