#!/usr/bin/env bash
# The discrepancy workflow (`stochnav diagnose`) on the two real static records of
# ../shared/data/imu-static (CC BY-NC-SA: read from there, never copied here) and on a simulated
# FOG record with a hidden vibration episode.
#
# Each real record starts from an "old fit": the classic IEEE 952 terms fitted by `stochnav fit`
# over octave taus, as a datasheet or an earlier analysis would give them. diagnose then finds
# what that model misses:
#   1. ADIS16405 gyro z (deg/s): quantization, angle random walk, bias instability, rate random
#      walk. The record carries a narrow-band line near 20 Hz.
#      The same terms on gyro x: its short-tau Gauss-Markov term, named from the wavelet
#      variance.
#   2. XSens MTi-G gyro x (rad/s, with outliers): angle random walk, bias instability, rate
#      random walk; the classical/robust wavelet-variance split flags the outliers.
#   3. The Allan workflow's simulated FOG record (configs/noise/fog_vibration_example.json, a
#      vibration episode from 2400 s to 3600 s scaling the noise by 8), diagnosed against the
#      same model without its nonstationary term.
#   4. At the filter level (`diagnose --run`): the random-vibration table experiment simulated,
#      the filter run with a white gyro model tuned on the first (static) 10 minutes, and its
#      innovations asked where they disagree with that model.
# Outputs: OUT_DIR/<name>/report.json, report.md and plots (OUT_DIR defaults to out/diagnose,
# which git ignores).
# Usage: examples/diagnose/run.sh [OUT_DIR]   (STOCHNAV=path/to/stochnav to choose the binary,
#        STOCHNAV_SHARED_DATA_DIR to point at the shared data)
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
stochnav="${STOCHNAV:-$root/build/release/framework/stochnav}"
data="${STOCHNAV_SHARED_DATA_DIR:-$root/../shared/data}/imu-static"
out="${1:-$root/out/diagnose}"
mkdir -p "$out"

adis="$data/adis16405_imu1_static_100hz.csv"
mtig="$data/mtig_cont_imu1_gyrox_100hz.csv"

if [[ -f "$adis" ]]; then
  echo "== ADIS16405 gyro z =="
  # The usual power-law terms do not describe this record: the fit is flagged failed
  # (--keep-failed writes it), and diagnose names what it misses.
  "$stochnav" fit --input "$adis" --column gyro_z_dps --unit deg/s --taus octave \
    --terms quantization,angle_random_walk,bias_instability,rate_random_walk \
    --format json --output "$out/adis_gyro_z_old_fit.json" --keep-failed
  "$stochnav" diagnose --input "$adis" --column gyro_z_dps --unit deg/s \
    --model "$out/adis_gyro_z_old_fit.json" --out "$out/adis_gyro_z"
else
  echo "skipped: $adis not found"
fi

if [[ -f "$adis" ]]; then
  echo "== ADIS16405 gyro x =="
  # The same old fit on gyro x, whose samples have a lag-1 correlation of 0.17: the Allan loop
  # leaves a Gauss-Markov term on its tau_c bound (one sample); the wavelet variance names it
  # (report.json "short_tau_gauss_markov": tau_c about 2.6 ms, sigma about 2020 deg/h).
  "$stochnav" fit --input "$adis" --column gyro_x_dps --unit deg/s --taus octave \
    --terms quantization,angle_random_walk,bias_instability,rate_random_walk \
    --format json --output "$out/adis_gyro_x_old_fit.json" --keep-failed
  "$stochnav" diagnose --input "$adis" --column gyro_x_dps --unit deg/s \
    --model "$out/adis_gyro_x_old_fit.json" --out "$out/adis_gyro_x"
fi

if [[ -f "$mtig" ]]; then
  echo "== MTi-G gyro x (outliers) =="
  "$stochnav" fit --input "$mtig" --column gyro_x --unit rad/s --taus octave \
    --terms angle_random_walk,bias_instability,rate_random_walk \
    --format json --output "$out/mtig_gyro_x_old_fit.json" --keep-failed
  "$stochnav" diagnose --input "$mtig" --column gyro_x --unit rad/s \
    --model "$out/mtig_gyro_x_old_fit.json" --out "$out/mtig_gyro_x"
else
  echo "skipped: $mtig not found"
fi

echo "== Simulated FOG record with a hidden vibration episode =="
"$stochnav" simulate noise --model "$root/configs/noise/fog_vibration_example.json" \
  --duration 7200 --rate 100 --seed 1 --column gyro_x --out "$out/fog_gyro.csv"
python3 - "$root/configs/noise/fog_vibration_example.json" "$out/fog_without_episode.json" <<'PY'
import json, sys
model = json.load(open(sys.argv[1]))
model["terms"] = [t for t in model["terms"] if t["type"] != "nonstationary"]
json.dump(model, open(sys.argv[2], "w"), indent=2)
PY
"$stochnav" diagnose --input "$out/fog_gyro.csv" --column gyro_x \
  --model "$out/fog_without_episode.json" --out "$out/fog_episode"

echo "== Filter level: innovations of a run through the random-vibration experiment =="
"$stochnav" simulate scenario "$root/configs/scenarios/paper_random_vibration.json" \
  --out "$out/vibration_scenario" > /dev/null
cat > "$out/vibration_run.json" <<JSON
{"data": {"scenario": "vibration_scenario"},
 "noise": {"gyro": {"plugin": "white", "params": {}, "fit": {"end_s": 600}},
           "accel": {"plugin": "white", "params": {"N": 0.029}}},
 "aids": [{"plugin": "static_position",
           "params": {"sigma_position_m": 0.01, "sigma_velocity_mps": 0.3, "nis_gate": false}}]}
JSON
"$stochnav" run "$out/vibration_run.json" --out "$out/vibration_run" > /dev/null
"$stochnav" diagnose --run "$out/vibration_run" --out "$out/vibration_innovations"

echo
echo "Reports: $out/*/report.md"
