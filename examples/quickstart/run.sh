#!/usr/bin/env bash
# The README's first command: the paper's random-vibration experiment (Zhang et al., Sensors
# 2017, Table 3) reproduced in simulation and compared across every noise-model plugin.
#   configs/experiments/paper_random_vibration.json: 10 min static, 10 min random vibration
#   (13.12 g RMS), 10 min static on a vibration table; static-position updates at 1 Hz; the
#   variants differ only in the gyro noise model (classic datasheet white noise, white tuned on
#   the static part, Gauss-Markov, AR, ARMA, augmented shaping states, DAVAR offline and causal,
#   adaptive Sage-Husa, and the oracle that knows the simulated truth).
# Writes OUT_DIR/table.md (the paper's Table 3 shape: max errors, mean +/- std over seeds, and
# the improvement over the classic model), results.json, metrics.png and errors_<variant>.png.
# Usage: examples/quickstart/run.sh [OUT_DIR] [SEEDS]   (defaults: out/quickstart, the config's
#        seeds; STOCHNAV=path/to/stochnav to choose the binary)
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
stochnav="${STOCHNAV:-$root/build/release/framework/stochnav}"
out="${1:-$root/out/quickstart}"
seeds=()
if [[ $# -ge 2 ]]; then seeds=(--seeds "$2"); fi

"$stochnav" compare "$root/configs/experiments/paper_random_vibration.json" --out "$out" \
  "${seeds[@]}"
echo
echo "Table: $out/table.md; plots: $out/metrics.png and $out/errors_<variant>.png"
