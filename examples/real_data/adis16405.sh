#!/usr/bin/env bash
# Allan deviation and noise-term fit of the three ADIS16405 gyros in ../shared/data/imu-static
# (a real static record, 100 Hz, 10^6 samples, deg/s). The figures and plot in the README come
# from this script. Usage: examples/real_data/adis16405.sh [OUT_DIR]
#   STOCHNAV=path/to/stochnav chooses the binary; STOCHNAV_SHARED_DATA_DIR the data folder.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
stochnav="${STOCHNAV:-$root/build/release/framework/stochnav}"
data="${STOCHNAV_SHARED_DATA_DIR:-$root/../shared/data}/imu-static/adis16405_imu1_static_100hz.csv"
out="${1:-$root/out/adis16405}"
if [[ ! -f "$data" ]]; then
  echo "adis16405.sh: $data not found; set STOCHNAV_SHARED_DATA_DIR to the shared data folder" >&2
  exit 2
fi
mkdir -p "$out"

for axis in x y z; do
  input=(--input "$data" --column "gyro_${axis}_dps" --unit deg/s)
  echo "== gyro $axis: automatic term selection (BIC) =="
  # The power-law terms do not describe this MEMS record (its short-tau correlation; issue #30):
  # the fits are flagged failed (chi-square) and written with --keep-failed.
  "$stochnav" fit "${input[@]}" --format table --keep-failed
  "$stochnav" fit "${input[@]}" --format json --output "$out/fit_gyro_$axis.json" --keep-failed
done

# Gyro z carries a narrow-band line near 20 Hz: dense taus resolve its nulls at tau = k/f.
input=(--input "$data" --column gyro_z_dps --unit deg/s --taus dense)
terms=angle_random_walk,bias_instability,rate_random_walk,sinusoid
echo "== gyro z, dense taus, with a sinusoid term =="
"$stochnav" fit "${input[@]}" --terms "$terms" --format table --keep-failed
"$stochnav" fit "${input[@]}" --terms "$terms" --format json --output "$out/fit_gyro_z_line.json" \
  --keep-failed
"$stochnav" allan "${input[@]}" --fit "$out/fit_gyro_z_line.json" --plot "$out/gyro_z_allan.png" \
  --output "$out/gyro_z_allan.txt"
echo "Wrote $out/gyro_z_allan.png"
