#!/usr/bin/python3
"""Textbook numpy reference of the rest of the Allan family, the anchor of allan_family_bench.py.

Usage: bench/allan_family_numpy.py PHASE_FILE DEVIATION [--tau0 S] [--taus octave|LIST]
  PHASE_FILE  one phase point per line (s), '#' comment lines allowed
  DEVIATION   mtotdev, ttotdev, htotdev (uncorrected), theo1 (uncorrected), mtie, tierms

Prints one JSON line {"m": [...], "dev": [...], "n": [...]}. The definitions are NIST SP 1065
(W. Riley, Handbook of Frequency Stability Analysis, 2008) written out directly, vectorised
with numpy over the terms of one subsequence (MTOT, HTOT), over the start index (Theo1) or over
the windows (MTIE, TIE rms): the cost a careful numpy user pays, O(N m) per averaging factor.
Needs Debian's python3-numpy (/usr/bin/python3).
"""
import argparse
import json

import numpy as np


def reflected_modified_sum(seq, m):
    """sum over the N - 3m + 1 subsequences of 3m points of seq (half-mean trend removed, then
    extended to 9m points by even reflection at both ends) of the mean over its 6m terms of
    ((S1 - 2 S2 + S3) / m)^2, S the sums of three adjacent m-point blocks."""
    n = len(seq)
    half = (3 * m) // 2
    gap = 3 * m - half  # distance between the centres of the two half means
    ramp = np.arange(3 * m, dtype=float)
    total = 0.0
    for i in range(n - 3 * m + 1):
        sub = seq[i:i + 3 * m]
        slope = (sub[3 * m - half:].mean() - sub[:half].mean()) / gap
        z = sub - slope * ramp
        star = np.concatenate((z[::-1], z, z[::-1]))
        sums = np.concatenate(([0.0], np.cumsum(star)))
        block = sums[m:] - sums[:-m]  # block[j] = sum star[j : j + m]
        terms = (block[0:6 * m] - 2.0 * block[m:7 * m] + block[2 * m:8 * m]) / m
        total += np.mean(terms * terms)
    return total


def mtotdev(x, m, tau0):
    count = len(x) - 3 * m + 1
    tau = m * tau0
    return np.sqrt(reflected_modified_sum(x, m) / (2.0 * tau * tau * count)), count


def ttotdev(x, m, tau0):
    dev, count = mtotdev(x, m, tau0)
    return m * tau0 * dev / np.sqrt(3.0), count


def htotdev(x, m, tau0):
    if m == 1:  # Stable32: the overlapping Hadamard deviation at m = 1
        d = x[3:] - 3.0 * x[2:-1] + 3.0 * x[1:-2] - x[:-3]
        return np.sqrt(np.mean(d * d) / (6.0 * tau0 * tau0)), len(d)
    y = np.diff(x) / tau0
    count = len(y) - 3 * m + 1
    return np.sqrt(reflected_modified_sum(y, m) / (6.0 * count)), count


def theo1(x, m, tau0):
    n = len(x)
    k = m // 2
    total = 0.0
    for i in range(n - m):
        j = np.arange(1, k + 1)
        term = x[i] - x[i + j] + x[i + m] - x[i + m - j]
        total += np.sum(term * term / j)
    return np.sqrt(total / (0.75 * (n - m) * (m * tau0) ** 2)), (n - m) * k


def mtie(x, m, tau0):
    windows = np.lib.stride_tricks.sliding_window_view(x, m + 1)
    return float(np.max(windows.max(axis=1) - windows.min(axis=1))), len(x) - m


def tierms(x, m, tau0):
    d = x[m:] - x[:-m]
    return float(np.sqrt(np.mean(d * d))), len(d)


ESTIMATORS = {"mtotdev": mtotdev, "ttotdev": ttotdev, "htotdev": htotdev, "theo1": theo1,
              "mtie": mtie, "tierms": tierms}


def octave_factors(name, n):
    if name == "theo1":
        return [m for m in (2 ** p for p in range(1, 64)) if 10 <= m <= n - 3] or [10]
    if name == "mtie":
        return [w - 1 for w in (2 ** p for p in range(1, 64)) if w - 1 <= n - 1]
    limit = {"mtie": n - 1, "tierms": (n - 2) // 4}.get(name, (n - 1) // 3)
    factors = []
    m = 1
    while m <= limit:
        factors.append(m)
        m *= 2
    return factors


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("phase_file")
    parser.add_argument("deviation", choices=sorted(ESTIMATORS))
    parser.add_argument("--tau0", type=float, default=1.0)
    parser.add_argument("--taus", default="octave")
    args = parser.parse_args()
    x = np.loadtxt(args.phase_file, comments="#", ndmin=1)
    if args.taus == "octave":
        factors = octave_factors(args.deviation, len(x))
    else:
        factors = [int(v) for v in args.taus.split(",")]
    result = {"m": [], "dev": [], "n": []}
    for m in factors:
        dev, count = ESTIMATORS[args.deviation](x, m, args.tau0)
        result["m"].append(m)
        result["dev"].append(float(dev))
        result["n"].append(int(count))
    print(json.dumps(result))


if __name__ == "__main__":
    main()
