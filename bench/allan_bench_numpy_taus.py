#!/usr/bin/python3
"""The numpy anchor (../shared/tools/numpy_oadev.py, allantools' estimator) at any of stochnav's
tau sets, for like-for-like whole-process timings of `stochnav allan --taus SET`.

Usage: allan_bench_numpy_taus.py FILE.f64 RATE_HZ octave|dense
Prints one JSON line like numpy_oadev.py: {"seconds", "tau", "adev", "n"}.
octave: exactly numpy_oadev.py's set (and stochnav's on 1e7 samples). dense: stochnav's dense set,
round(10^(k/10)) without repeats, m <= (N - 1) / 4 for N rate samples (N + 1 phase points).
"""
import json, sys, time
import numpy as np


def factors(n, spacing):
    if spacing == "octave":
        ms = 2 ** np.arange(int(np.floor(np.log2(n / 3))) + 1)
        return [int(m) for m in ms if m <= (n - 1) // 2]
    max_m = (n - 1) // 4
    out = []
    k = 0
    while True:
        m = int(round(10 ** (k / 10)))
        if m > max_m:
            return out
        if not out or out[-1] != m:
            out.append(m)
        k += 1


def oadev(y, rate, ms):
    x = np.concatenate([[0.0], np.cumsum(y) / rate])
    taus, adev, cnt = [], [], []
    for m in ms:
        tau = m / rate
        d = x[2 * m:] - 2 * x[m:-m] + x[:-2 * m]
        taus.append(tau); adev.append(float(np.sqrt(np.sum(d * d) / (2.0 * tau * tau * d.size)))); cnt.append(int(d.size))
    return taus, adev, cnt


if __name__ == "__main__":
    t0 = time.perf_counter()
    y = np.fromfile(sys.argv[1], dtype="<f8")
    taus, adev, cnt = oadev(y, float(sys.argv[2]), factors(y.size, sys.argv[3]))
    print(json.dumps({"seconds": time.perf_counter() - t0, "tau": taus, "adev": adev, "n": cnt}))
