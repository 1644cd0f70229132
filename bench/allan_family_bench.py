#!/usr/bin/python3
"""Whole-process benchmark of the rest of the Allan family against its numpy anchor.

Usage: bench/allan_family_bench.py [BUILD_DIR] [--samples N] [--repeats R]
  BUILD_DIR   the build tree (default build/release): framework/stochnav is taken from it.
Needs Debian's python3-numpy (run with /usr/bin/python3).

One text file of N phase points (default 8192, a random walk: white FM, seed 1) is the input
of every process. For each of mtotdev, ttotdev, htotdev (uncorrected), theo1 (uncorrected),
mtie and tierms at octave factors, the best wall time of R runs of
  numpy      bench/allan_family_numpy.py FILE DEV: the textbook definitions, O(N m) per factor
  stochnav   stochnav allan --data phase --rate 1 --deviation DEV --taus octave --format json
             (plus noise identification, EDF and bounds where the estimator has them)
is printed with their ratio, and the largest relative difference of the deviations.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEVIATIONS = {"mtotdev": "mtotdev", "ttotdev": "ttotdev", "htotdev": "htotdev_nobias",
              "theo1": "theo1_nobias", "mtie": "mtie", "tierms": "tierms"}


def best_of(command, repeats):
    best = float("inf")
    out = b""
    for _ in range(repeats):
        start = time.perf_counter()
        out = subprocess.run(command, check=True, stdout=subprocess.PIPE).stdout
        best = min(best, time.perf_counter() - start)
    return best, json.loads(out)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("build", nargs="?", default=os.path.join(ROOT, "build", "release"))
    parser.add_argument("--samples", type=int, default=8192)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    cli = os.path.join(args.build, "framework", "stochnav")
    reference = os.path.join(ROOT, "bench", "allan_family_numpy.py")
    phase = np.cumsum(np.random.default_rng(1).standard_normal(args.samples))
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "phase.txt")
        np.savetxt(path, phase, fmt="%.17g")
        print(f"{args.samples} phase points, octave factors, best of {args.repeats} runs")
        print(f"{'deviation':<14} {'numpy s':>9} {'stochnav s':>11} {'ratio':>8} "
              f"{'max rel diff':>13}")
        for numpy_name, name in DEVIATIONS.items():
            numpy_s, expected = best_of(["/usr/bin/python3", reference, path, numpy_name],
                                        args.repeats)
            ours_s, ours = best_of([cli, "allan", "--input", path, "--data", "phase", "--rate",
                                    "1", "--deviation", name, "--taus", "octave", "--format",
                                    "json"], args.repeats)
            by_m = dict(zip(expected["m"], expected["dev"]))
            tau_scale = 0.75 if name.startswith("theo1") else 1.0
            differences = [abs(dev / by_m[round(tau / tau_scale)] - 1.0)
                           for tau, dev in zip(ours["tau"], ours[name])
                           if round(tau / tau_scale) in by_m]
            worst = max(differences) if differences else float("nan")
            print(f"{name:<14} {numpy_s:>9.3f} {ours_s:>11.3f} {numpy_s / ours_s:>7.0f}x "
                  f"{worst:>13.1e}")
    sys.stdout.flush()


if __name__ == "__main__":
    main()
