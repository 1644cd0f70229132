#!/usr/bin/python3
"""Whole-process benchmark of the Allan engine against the numpy anchor, measured in one run.

Usage: bench/allan_bench_whole_process.py [BUILD_DIR] [--samples N] [--repeats R]
  BUILD_DIR   the build tree (default build/release): framework/stochnav and
              bench/allan_bench_read_sum are taken from it.
Needs Debian's python3-numpy (run with /usr/bin/python3).

One raw little-endian float64 file of N gyro-like rate samples at 100 Hz (default 1e7, 80 MB,
in the page cache) is the input of every process. Each process is timed from start to exit (best
of R runs, the programs interleaved) with its CPU time (user + system, least of the R runs) and
its peak resident memory (GNU time's %M, ru_maxrss):

  read+sum        bench/allan_bench_read_sum: map the file, add every sample, print the sum.
                  The physical limit of anything that reads the data once.
  stochnav start  stochnav --version: process start (loading libstochnav and the libraries it
                  needs, Ceres's among them), setting up the command line, exit. Every stochnav
                  process pays it before it reads a byte.
  numpy octave    ../shared/tools/numpy_oadev.py: load, cumsum, OADEV at octave taus (allantools'
                  estimator); prints tau, adev, n as one JSON line.
  numpy dense     bench/allan_bench_numpy_taus.py: the same estimator at stochnav's dense set.
  stochnav allan  --taus octave|dense --format json --output F: OADEV plus n, edf, identified
                  noise type alpha and the Stable32 68.3 % interval at every tau, written to F.
  stochnav davar  --window 50000 --step 5000 --format json --output F: the OADEV of every window
                  at the window's octave taus (1991 windows x 14 taus on 1e7 samples), to F.

stochnav computes more than the anchor (noise identification, edf, bounds), so the ratios are
conservative. Other processes on the machine make single runs noisy: take the best of several.
The load average before and after is printed: with other work on the CPUs stochnav's threads
no longer run side by side and its wall-time ratios fall towards the CPU-time ratios (printed
last).
"""
import argparse, json, os, subprocess, sys, tempfile, time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run(command, stdout_path):
    """Wall seconds, CPU seconds (user + system, all threads) and peak RSS (bytes) of one
    process, which must exit with 0. The peak comes from GNU time (%M), whose child is a fresh,
    small process (a child forked from this script would inherit its resident pages into
    ru_maxrss); the CPU time from wait4 on GNU time, which includes its waited-for child's, in
    microseconds (GNU time's own %U %S count in 10 ms ticks)."""
    rss_path = stdout_path + ".rss"
    err_path = stdout_path + ".err"
    with open(stdout_path, "wb") as out, open(err_path, "wb") as err:
        start = time.perf_counter()
        process = subprocess.Popen(["/usr/bin/time", "-f", "%M", "-o", rss_path] + command,
                                   stdout=out, stderr=err)
        _, status, usage = os.wait4(process.pid, 0)
        seconds = time.perf_counter() - start
        process.returncode = os.waitstatus_to_exitcode(status)
    if process.returncode != 0:
        sys.exit(f"failed ({process.returncode}): {' '.join(command)}\n"
                 f"{open(err_path).read()}")
    with open(rss_path) as rss:
        peak = int(rss.read().split()[-1]) * 1024
    return seconds, usage.ru_utime + usage.ru_stime, peak


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("build", nargs="?", default=os.path.join(ROOT, "build", "release"))
    parser.add_argument("--samples", type=int, default=10_000_000)
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()

    stochnav = os.path.join(args.build, "framework", "stochnav")
    read_sum = os.path.join(args.build, "bench", "allan_bench_read_sum")
    anchor = os.path.join(ROOT, "..", "shared", "tools", "numpy_oadev.py")
    anchor_taus = os.path.join(ROOT, "bench", "allan_bench_numpy_taus.py")
    work = tempfile.mkdtemp(prefix="stochnav_allan_whole_")
    data = os.path.join(work, "record.f64")
    # Generated in a child, so this process stays small (numpy never loaded here).
    subprocess.run(["/usr/bin/python3", "-c", f"""
import numpy as np
rng = np.random.default_rng(42)
walk = np.cumsum(1e-4 * rng.standard_normal({args.samples}))
(0.4 + walk + 0.04 * rng.standard_normal({args.samples})).astype("<f8").tofile({data!r})
"""], check=True)
    data_bytes = os.path.getsize(data)
    out = lambda name: os.path.join(work, name)

    programs = {
        "read+sum": [read_sum, data],
        "stochnav start": [stochnav, "--version"],
        "numpy octave": ["/usr/bin/python3", anchor, data, "100"],
        "stochnav allan octave": [stochnav, "allan", "--input", data, "--rate", "100", "--taus",
                                  "octave", "--format", "json", "--output", out("octave.json")],
        "numpy dense": ["/usr/bin/python3", anchor_taus, data, "100", "dense"],
        "stochnav allan dense": [stochnav, "allan", "--input", data, "--rate", "100", "--taus",
                                 "dense", "--format", "json", "--output", out("dense.json")],
        "stochnav davar": [stochnav, "davar", "--input", data, "--rate", "100", "--window",
                           "50000", "--step", "5000", "--format", "json", "--output",
                           out("davar.json")],
    }
    load_before = os.getloadavg()
    best = {name: (float("inf"), 0) for name in programs}
    cpu = {name: float("inf") for name in programs}
    for _ in range(args.repeats):
        for name, command in programs.items():
            seconds, cpu_seconds, rss = run(command, out(name.replace(" ", "_") + ".stdout"))
            best[name] = (min(best[name][0], seconds), max(best[name][1], rss))
            cpu[name] = min(cpu[name], cpu_seconds)

    def agreement(ours, theirs):
        a = json.load(open(out(ours)))
        b = json.loads(open(out(theirs)).read())
        assert a["n"] == b["n"], "n differs"
        assert all(abs(x / y - 1.0) < 1e-12 for x, y in zip(a["tau"], b["tau"])), "tau differs"
        return max(abs(x / y - 1.0) for x, y in zip(a["adev"], b["adev"]))

    load_after = os.getloadavg()
    limit = best["read+sum"][0]
    print(f"{args.samples} samples, {data_bytes / 1e6:.0f} MB raw float64; best of {args.repeats} "
          f"whole-process runs; {os.cpu_count()} CPUs; load average (1 min) {load_before[0]:.1f} "
          f"before, {load_after[0]:.1f} after (above 0.5 other processes shared the CPUs)\n")
    print(f"{'program':24} {'seconds':>8} {'x read+sum':>10} {'peak MB':>8} {'/ data':>7} "
          f"{'CPU s':>7}")
    for name, (seconds, rss) in best.items():
        print(f"{name:24} {seconds:8.3f} {seconds / limit:10.1f} {rss / 1e6:8.1f} "
              f"{rss / data_bytes:7.2f} {cpu[name]:7.3f}")
    octave = best["numpy octave"][0] / best["stochnav allan octave"][0]
    dense = best["numpy dense"][0] / best["stochnav allan dense"][0]
    davar = best["stochnav davar"][0] / best["stochnav allan octave"][0]
    memory = max(best[n][1] for n in programs if n.startswith("stochnav")) / data_bytes
    over_limit = lambda name: best[name][0] / limit
    verdict = lambda met: "met" if met else "NOT met"
    print()
    print(f"OADEV octave, speed-up over numpy:  {octave:6.1f}x  "
          f"(goal >= 25x: {verdict(octave >= 25)}); "
          f"{over_limit('stochnav allan octave'):.1f}x a read+sum; largest relative adev "
          f"difference {agreement('octave.json', 'numpy_octave.stdout'):.1e}")
    print(f"OADEV dense,  speed-up over numpy:  {dense:6.1f}x  "
          f"(goal >= 25x: {verdict(dense >= 25)}); "
          f"{over_limit('stochnav allan dense'):.1f}x a read+sum; largest relative adev "
          f"difference {agreement('dense.json', 'numpy_dense.stdout'):.1e}")
    start = best["stochnav start"][0]
    octave_seconds = best["stochnav allan octave"][0]
    print(f"stochnav allan octave, {octave_seconds * 1e3:.1f} ms: process start "
          f"{start * 1e3:.1f} ms ({start / octave_seconds:.0%}), the rest (map, integrate, sums, "
          f"noise identification, output, exit) {(octave_seconds - start) * 1e3:.1f} ms = "
          f"{(octave_seconds - start) / limit:.1f}x a read+sum (whose own start is in it)")
    print(f"DAVAR 50000/5000 over one OADEV run: {davar:6.2f}x  (goal <= 1.5x: "
          f"{verdict(davar <= 1.5)}); {over_limit('stochnav davar'):.1f}x a read+sum")
    print(f"peak memory of stochnav / data size: {memory:6.2f}   (goal <= 1.2: "
          f"{verdict(memory <= 1.2)})")
    # CPU seconds: what the speed-ups tend to when every CPU is
    # busy with other work; on idle CPUs stochnav's threads run side by side and the wall-time
    # ratios above are higher.
    cpu_ratio = lambda theirs, ours: cpu[theirs] / cpu[ours]
    octave_cpu = cpu_ratio("numpy octave", "stochnav allan octave")
    dense_cpu = cpu_ratio("numpy dense", "stochnav allan dense")
    print(f"CPU-time ratios, numpy / stochnav:   octave {octave_cpu:.1f}x, dense {dense_cpu:.1f}x")
    for path in os.listdir(work):
        os.remove(os.path.join(work, path))
    os.rmdir(work)


if __name__ == "__main__":
    main()
