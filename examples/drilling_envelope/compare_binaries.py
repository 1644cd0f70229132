#!/usr/bin/env python3
"""The same simulated wells navigated by several stochnav binaries (an ablation: builds that
differ in one change), scored station by station against the truth.

The wells are envelope.py's draw (draw_well) with the latitude redrawn within +-LAT deg (60 by
default, where the runs are one filter rather than the bank over the heading). Each well is
simulated once, by the first binary, and every binary runs the shipped recording config on the
same records. With --scenario FILE the wells are that one scenario instead, simulated with the
seeds SEED, SEED + 1, ... (a seeded study of one well; HOURS and --lat are then unused).
Prints one JSON line per well and binary, then a table per binary: stations inside 3 sigma and
the RMS of error / sigma per quantity. docs/drilling-envelope.md, section 7, gives the ablations
made with it.

Usage: compare_binaries.py OUT_DIR WELLS HOURS SEED STOCHNAV_A [STOCHNAV_B ...] [--lat LAT]
                           [--scenario FILE]
Runs already in OUT_DIR are reused. Python 3 standard library only.
"""
import argparse
import json
import math
import os
import random
import string

import envelope


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out")
    parser.add_argument("wells", type=int)
    parser.add_argument("hours", type=float)
    parser.add_argument("seed", type=int)
    parser.add_argument("binaries", nargs="+")
    parser.add_argument("--lat", type=float, default=60.0)
    parser.add_argument("--scenario")
    args = parser.parse_args()
    binaries = dict(zip(string.ascii_uppercase, args.binaries))
    rng = random.Random(args.seed)
    rows = []
    for k in range(args.wells):
        if args.scenario:
            with open(args.scenario) as f:
                scenario = json.load(f)
            scenario["seed"] = args.seed + k
            case = "seed %d" % scenario["seed"]
        else:
            scenario, case = envelope.draw_well(rng, k, args.hours)
            scenario["site"]["latitude_deg"] = rng.uniform(-args.lat, args.lat)
        folder = os.path.join(args.out, f"well_{k}")
        os.makedirs(folder, exist_ok=True)
        with open(os.path.join(folder, "scenario.json"), "w") as f:
            json.dump(scenario, f, indent=1)
        data = os.path.join(folder, "data")
        if not os.path.exists(os.path.join(data, "truth.csv")):
            envelope.run(binaries["A"], "simulate", "scenario",
                         os.path.join(folder, "scenario.json"), "--out", data)
        envelope.write_run_config(folder, os.path.join(data, "truth.csv"))
        for name, binary in binaries.items():
            out = os.path.join(folder, "run_" + name)
            if not os.path.exists(os.path.join(out, "survey.csv")):
                envelope.run(binary, "run", os.path.join(folder, "run.json"), "--data", data,
                             "--out", out, "--no-plot")
            pairs = envelope.station_errors(os.path.join(out, "survey.csv"),
                                            os.path.join(data, "truth.csv"))
            row = {"well": k, "class": case, "latitude_deg": scenario["site"]["latitude_deg"],
                   "binary": name}
            for quantity, _ in envelope.QUANTITIES:
                finite = [(e, s) for e, s in pairs[quantity]
                          if math.isfinite(e) and math.isfinite(s) and s > 0]
                row[quantity] = {"stations": len(finite),
                                 "inside": sum(abs(e) <= 3.0 * s for e, s in finite),
                                 "sum_z2": sum((e / s) ** 2 for e, s in finite)}
            rows.append(row)
            print(json.dumps(row), flush=True)
    print("| binary | " + " | ".join(q.split("_")[0] for q, _ in envelope.QUANTITIES) + " |")
    print("|---" * (len(envelope.QUANTITIES) + 1) + "|")
    for name in binaries:
        cells = []
        for quantity, _ in envelope.QUANTITIES:
            mine = [r[quantity] for r in rows if r["binary"] == name]
            n = sum(m["stations"] for m in mine)
            inside = sum(m["inside"] for m in mine)
            rms_z = math.sqrt(sum(m["sum_z2"] for m in mine) / n) if n else float("nan")
            cells.append(f"{inside}/{n} ({rms_z:.2f})")
        print(f"| {name} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
