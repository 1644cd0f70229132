#!/usr/bin/python3
"""stochnav.allan from Python against the CLI and the numpy reference, on one 1e7-sample array.

Usage: bench/python_allan_bench.py [BUILD_DIR] [--samples N] [--repeats R]
  BUILD_DIR   the build tree (default build/release): python/ (the module), framework/stochnav
              and bench/allan_bench_read_sum are taken from it.
Needs Debian's python3-numpy (run with /usr/bin/python3, the module's interpreter).

The record is the gyro-like one of allan_bench_whole_process.py (1e7 rate samples at 100 Hz).
Printed side by side, best of R runs each:

  python stochnav.allan   in-process: the array in memory -> OADEV at octave taus with n, edf,
                          alpha and the 68.3 % interval (the integration into phase included)
  python numpy reference  in-process: ../shared/tools/numpy_oadev.py's oadev (allantools'
                          estimator: cumsum, then one pass per tau), deviations only
  CLI whole process       `stochnav allan --input F.f64 --format json --output F.json`, the file
                          in the page cache: start-up, mapping, the same computation, output
  read+sum whole process  bench/allan_bench_read_sum on the same file: start-up, mapping and one
                          pass over the data, the part of the CLI's time that is not compute
  CLI compute (estimate)  CLI whole process - read+sum

The issue's goal: Python within 10 % of the CLI's compute time (no file I/O). No timing is
asserted anywhere; other processes on the machine make single runs noisy (the load average is
printed before and after).
"""
import argparse
import importlib.util
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def best_of(repeats, call):
    best = float("inf")
    result = None
    for _ in range(repeats):
        start = time.perf_counter()
        result = call()
        best = min(best, time.perf_counter() - start)
    return best, result


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("build", nargs="?", default=os.path.join(ROOT, "build", "release"))
    parser.add_argument("--samples", type=int, default=10_000_000)
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    sys.path.insert(0, os.path.join(args.build, "python"))
    import stochnav

    spec = importlib.util.spec_from_file_location(
        "numpy_oadev", os.path.join(ROOT, "..", "shared", "tools", "numpy_oadev.py"))
    numpy_oadev = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(numpy_oadev)

    rng = np.random.default_rng(42)
    walk = np.cumsum(1e-4 * rng.standard_normal(args.samples))
    y = 0.4 + walk + 0.04 * rng.standard_normal(args.samples)
    rate = 100.0

    work = tempfile.mkdtemp(prefix="stochnav_python_bench_")
    data = os.path.join(work, "record.f64")
    y.astype("<f8").tofile(data)
    output = os.path.join(work, "allan.json")
    cli = [os.path.join(args.build, "framework", "stochnav"), "allan", "--input", data, "--rate",
           "100", "--taus", "octave", "--format", "json", "--output", output]
    read_sum = [os.path.join(args.build, "bench", "allan_bench_read_sum"), data]

    load_before = os.getloadavg()
    python_s, ours = best_of(args.repeats, lambda: stochnav.allan(y, rate))
    numpy_s, theirs = best_of(args.repeats, lambda: numpy_oadev.oadev(y, rate))
    cli_s, _ = best_of(args.repeats, lambda: subprocess.run(cli, check=True))
    read_sum_s, _ = best_of(args.repeats,
                            lambda: subprocess.run(read_sum, check=True, capture_output=True))
    load_after = os.getloadavg()

    from_cli = json.load(open(output))
    same_as_cli = from_cli["adev"] == ours.dev.tolist()
    taus, adev, counts = theirs
    assert counts == ours.n.tolist(), "term counts differ from numpy's"
    numpy_difference = max(abs(a / b - 1.0) for a, b in zip(ours.dev, adev))
    cli_compute_s = cli_s - read_sum_s

    print(f"OADEV at {len(ours)} octave taus of {args.samples} samples; best of {args.repeats}; "
          f"{os.cpu_count()} CPUs, {stochnav.__name__} {stochnav.__version__}; load average "
          f"{load_before[0]:.1f} before, {load_after[0]:.1f} after\n")
    print(f"{'what':34} {'seconds':>8}")
    print(f"{'python stochnav.allan':34} {python_s:8.3f}")
    print(f"{'python numpy reference':34} {numpy_s:8.3f}")
    print(f"{'CLI whole process':34} {cli_s:8.3f}")
    print(f"{'read+sum whole process':34} {read_sum_s:8.3f}")
    print(f"{'CLI compute (estimate)':34} {cli_compute_s:8.3f}")
    print()
    print(f"python / CLI compute:        {python_s / cli_compute_s:6.2f}  (goal <= 1.10)")
    print(f"numpy / python stochnav:     {numpy_s / python_s:6.1f}x")
    print(f"deviations equal to the CLI's, bitwise: {same_as_cli}; largest relative difference "
          f"from numpy: {numpy_difference:.1e}")
    for path in os.listdir(work):
        os.remove(os.path.join(work, path))
    os.rmdir(work)


if __name__ == "__main__":
    main()
