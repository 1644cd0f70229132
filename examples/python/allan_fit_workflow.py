#!/usr/bin/python3
"""The Allan-variance workflow from Python, notebook style: a gyro record -> Allan deviation and
wavelet variance with their intervals (plots) -> noise-term fits -> a comparison of the fitted
models with the record and with records simulated from them.

Usage: examples/python/allan_fit_workflow.py [OUT_DIR] [RECORD.csv COLUMN RATE_HZ UNIT]
  Default record: the ADIS16405 static gyro z in ../shared/data/imu-static (deg/s, 100 Hz,
  1e6 samples); without it, a simulated FOG-like record. Writes OUT_DIR (default
  out/python_workflow): allan.png, wv.png, comparison.png, fit.json, summary.txt.
  Needs the module (PYTHONPATH=build/release/python, or `cmake --install`) and Debian's
  python3-numpy and python3-matplotlib.
"""

# %% Set-up: the module, numpy, matplotlib without a display.
import os
import pathlib
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import stochnav

ROOT = pathlib.Path(__file__).resolve().parents[2]
out = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ROOT / "out" / "python_workflow")
out.mkdir(parents=True, exist_ok=True)
summary = []


def say(text=""):
    print(text)
    summary.append(text)


# %% 1. The record, in deg/h (the IEEE 952 reporting unit of gyros).
adis = pathlib.Path(os.environ.get("STOCHNAV_SHARED_DATA_DIR", ROOT.parent / "shared" / "data"))
adis = adis / "imu-static" / "adis16405_imu1_static_100hz.csv"
if len(sys.argv) > 2:
    path, column, rate, unit = sys.argv[2], sys.argv[3], float(sys.argv[4]), sys.argv[5]
    record = stochnav.read_record(path, column=column, rate=rate, unit=unit)
    x, rate, name = record.values, record.rate_hz, f"{path} [{column}]"
elif adis.exists():
    record = stochnav.read_record(adis, column="gyro_z_dps", unit="deg/s")
    x, rate, unit, name = record.values * 3600.0, record.rate_hz, "deg/h", "ADIS16405 gyro z"
else:
    truth = {"units": "deg/h", "rate_hz": 100,
             "terms": [{"type": "angle_random_walk", "N": 0.02},
                       {"type": "bias_instability", "B": 0.05},
                       {"type": "rate_random_walk", "K": 0.1}]}
    x, rate, unit, name = stochnav.simulate_noise(truth, 20000.0, 100.0, 1), 100.0, "deg/h", \
        "simulated FOG gyro"
say(f"record: {name}, {x.size} samples at {rate:g} Hz ({x.size / rate / 3600:.1f} h), {unit}")

# %% 2. Allan deviation (Stable32's intervals) and wavelet variance (the R package wv's).
allan = stochnav.allan(x, rate, taus="dense")
octave = stochnav.allan(x, rate)
wv = stochnav.wv(x, rate)
wv_robust = stochnav.wv(x, rate, robust=True)
say()
say(repr(octave))

# The same numbers as the textbook numpy estimator (allantools'), at the octave taus.
phase = np.concatenate([[0.0], np.cumsum(x)]) / rate
for m, dev in zip(octave.m[:3], octave.dev[:3]):
    d = phase[2 * m:] - 2 * phase[m:-m] + phase[:-2 * m]
    reference = np.sqrt(np.mean(d * d) / 2) / (m / rate)
    say(f"m = {m}: stochnav {dev:.10g}, numpy {reference:.10g}")

# %% 3. Fits: the terms chosen by BIC, and a model with a sinusoid term on dense taus (the
# ADIS gyro z carries a narrow-band line near 20 Hz: its nulls at tau = k / f). A fit whose
# terms cannot explain the record is flagged (.failed, with the reason) rather than returned as
# if it could: keep_failed=True keeps it for the comparison below.
chosen = stochnav.fit(x, rate, unit=unit, keep_failed=True)
with_line = stochnav.fit(x, rate, unit=unit, taus="dense", keep_failed=True,
                         terms=["angle_random_walk", "bias_instability", "rate_random_walk",
                                "sinusoid"])
(out / "fit.json").write_text(with_line.to_json())
models = (("chosen by BIC", chosen), ("with a sinusoid", with_line))
for label, model in models:
    d = model.diagnostics
    say()
    say(f"fit ({label}): chi-square {d['chi_square']:.1f} for {d['points']} points, "
        f"{d['parameters']} parameters{', FAILED: ' + d['failure'] if model.failed else ''}")
    say(repr(model))

# %% 4. Plots: deviation and wavelet variance with intervals, the fitted models over them.
figure, axes = plt.subplots(figsize=(7, 5))
axes.fill_between(allan.tau, allan.lo, allan.hi, alpha=0.3, label="68.3 % interval")
axes.loglog(allan.tau, allan.dev, "k.", markersize=3, label="OADEV")
for label, model in models:
    axes.loglog(allan.tau, model.allan_deviation(allan.tau),
                label=f"fit {label}: " + " + ".join(model.term_types))
axes.set(xlabel="tau (s)", ylabel=f"Allan deviation ({unit})", title=name)
axes.grid(True, which="both", alpha=0.3)
axes.legend(fontsize=8, loc="lower left")
figure.savefig(out / "allan.png", dpi=100)

figure, axes = plt.subplots(figsize=(7, 5))
axes.errorbar(wv.scale_s, wv.wv, yerr=[wv.wv - wv.lo, wv.hi - wv.wv], fmt="o", markersize=3,
              label="wavelet variance (95 %)")
axes.loglog(wv_robust.scale_s, wv_robust.wv, "x", label="robust")
for label, model in models:
    axes.loglog(wv.scale_s, model.wavelet_variance(wv.scale_s), label=f"implied by the fit {label}")
axes.set(xscale="log", yscale="log", xlabel="scale (s)", ylabel=f"wavelet variance ({unit})^2",
         title=name)
axes.grid(True, which="both", alpha=0.3)
axes.legend(fontsize=8, loc="lower left")
figure.savefig(out / "wv.png", dpi=100)

# %% 5. Comparison: records simulated from each fit against the record, tau by tau.
figure, axes = plt.subplots(figsize=(7, 5))
axes.fill_between(octave.tau, octave.lo / octave.dev, octave.hi / octave.dev, alpha=0.3,
                  label="record's 68.3 % interval")
say()
say(f"{'fit':<18} share of octave taus where the simulated record's OADEV lies inside the "
    "record's interval")
for label, model in models:
    simulated = stochnav.simulate_noise(model, x.size / rate, rate, 2, accept_failed=True)
    replica = stochnav.allan(simulated, rate)
    ratio = replica.dev / octave.dev
    inside = np.mean((octave.lo <= replica.dev) & (replica.dev <= octave.hi))
    axes.semilogx(octave.tau, ratio, "o-", label=f"simulated from {label}")
    say(f"{label:<18} {inside:.0%}")
axes.axhline(1.0, color="k", linewidth=0.8)
axes.set(xlabel="tau (s)", ylabel="OADEV / record's OADEV", title=f"{name}: fits simulated")
axes.grid(True, which="both", alpha=0.3)
axes.legend(fontsize=8, loc="lower left")
figure.savefig(out / "comparison.png", dpi=100)

(out / "summary.txt").write_text("\n".join(summary) + "\n")
print(f"\nwrote {out}/allan.png, wv.png, comparison.png, fit.json, summary.txt")
