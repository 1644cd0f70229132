#!/usr/bin/env bash
# The Allan-variance workflow on a simulated example record.
# 1. simulate a two-hour FOG gyro record from configs/noise/fog_vibration_example.json
#    (quantization, angle random walk, bias instability, rate random walk and a vibration
#    episode from 2400 s to 3600 s that scales the noise by 8);
# 2. its overlapping Allan deviation with Stable32 confidence intervals;
# 3. the noise-term fit (Ceres) with the IEEE 952 slope read-offs beside it;
# 4. plots: the deviation with the fitted terms, and the DAVAR heat map that shows the episode;
# 5. the windowed fit (the paper's Eq. 7): the white-noise coefficients rise in the episode.
# Usage: examples/allan_workflow/run.sh [OUT_DIR]   (STOCHNAV=path/to/stochnav to choose the binary)
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
stochnav="${STOCHNAV:-$root/build/release/framework/stochnav}"
out="${1:-$root/out/allan_workflow}"
mkdir -p "$out"

"$stochnav" simulate noise --model "$root/configs/noise/fog_vibration_example.json" \
  --duration 7200 --rate 100 --seed 1 --column gyro_x --out "$out/fog_gyro.csv"
input=(--input "$out/fog_gyro.csv" --column gyro_x --unit deg/h)

echo "== Overlapping Allan deviation (deg/h) =="
"$stochnav" allan "${input[@]}" --taus octave
echo
echo "== Noise-term fit =="
# The vibration episode makes the record non-stationary: no constant model describes it, so the
# whole-record fit is flagged failed (chi-square) and written with --keep-failed. The windowed
# fit below is the answer.
"$stochnav" fit "${input[@]}" --format table --keep-failed
"$stochnav" fit "${input[@]}" --format json --output "$out/fit.json" --keep-failed
"$stochnav" allan "${input[@]}" --taus dense --plot "$out/allan.png" --fit "$out/fit.json" \
  --output "$out/allan.txt"
"$stochnav" davar "${input[@]}" --window 60000 --step 3000 --plot "$out/davar.png" \
  --format csv --output "$out/davar.csv"
echo
echo "== Windowed fit (10-minute DAVAR windows): white-noise terms over time =="
"$stochnav" fit "${input[@]}" --window 60000 --step 30000 \
  --terms quantization,angle_random_walk --format table
echo
echo "Wrote $out/allan.png (deviation, 68.3 % intervals, fitted terms) and $out/davar.png (DAVAR)."
