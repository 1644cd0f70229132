#!/usr/bin/env python3
"""A seeded family of drilling wells across the envelope, each simulated with truth, navigated
from a field start with the shipped recording config (configs/runs/drilling_recording.json) with
the truth kept aside, and scored station by station: the share of survey stations inside their
own 3 sigma per quantity and the worst error in sigmas, per case class.

The family (seed fixes every draw; stratified, see draw_well): latitude uniform in [-80, 80] deg
(both hemispheres), a
start at a drawn inclination (0-90 deg) and azimuth (0-360) that turns by a drawn rate, a mode
(rotary at 30-180 rpm, sliding, or a slide/rotate stand pattern at a drawn toolface), ROP 5-60
m/h, 28.5-m stands with 2-10 min connections, a vibration episode tied to the drilled depth, and
the sensor errors of configs/scenarios/drilling_build_hold.json
(a FOG MWD datasheet: 0.5 deg/h flicker and turn-on bias, 10-20 ppm scale factors).
Classes: mode x (east-west at high inclination: |sin azimuth| > 0.7 and inclination > 45 deg).

Each run sees the IMU and aid records only (OUT_DIR/well_K/recording); the truth is kept aside
and compared with survey.csv's survey stations afterwards. A well is flagged when its run says,
without truth, that something is wrong (a station flagged by the survey QC, a heading bank that
has not resolved, an optimistic innovation self-check); a well with a station outside 3 sigma
that is not flagged is silently wrong.

Usage: envelope.py STOCHNAV OUT_DIR [--wells N] [--hours H] [--seed S] [--require-inside SHARE]
Writes OUT_DIR/summary.json and OUT_DIR/summary.md; each well's scenario, run and files in
OUT_DIR/well_K/. With --require-inside it exits 1 unless every quantity has at least SHARE of
the family's stations inside 3 sigma and no well is silently wrong. Python 3 standard library only.
"""
import argparse
import bisect
import csv
import json
import math
import os
import random
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
QUANTITIES = [("inclination_deg", "inclination_sigma_deg"), ("azimuth_deg", "azimuth_sigma_deg"),
              ("north_m", "north_sigma_m"), ("east_m", "east_sigma_m"), ("tvd_m", "tvd_sigma_m")]


def draw_well(rng, k, hours):
    """Well k's scenario (JSON) and its class. Stratified so that every class is drawn: the
    mode cycles through rotate, slide and pattern, and every other well is east-west at high
    inclination (azimuth 90 or 270 +- 20 deg, inclination 50-90 deg)."""
    with open(os.path.join(ROOT, "configs/scenarios/drilling_build_hold.json")) as f:
        scenario = json.load(f)
    scenario.pop("comments", None)
    scenario["seed"] = rng.randrange(1, 1 << 30)
    latitude = rng.uniform(-80.0, 80.0)
    if k % 2 == 1:
        inclination = rng.uniform(50.0, 90.0)
        azimuth = rng.choice([90.0, 270.0]) + rng.uniform(-20.0, 20.0)
    else:
        inclination = rng.choice([rng.uniform(0.0, 30.0), rng.uniform(30.0, 90.0)])
        azimuth = rng.uniform(0.0, 360.0)
    turn = rng.choice([0.0, rng.uniform(-3.0, 3.0)])
    mode = ["rotate", "slide", "pattern"][k % 3]
    rop = rng.uniform(5.0, 60.0)
    scenario["site"]["latitude_deg"] = latitude
    d = scenario["drilling"]
    d.pop("well")
    d["well"] = {"start": {"inclination_deg": inclination, "azimuth_deg": azimuth},
                 "sections": [{"length_m": 20.0, "build_rate_deg_per_30m": 0.0,
                               "turn_rate_deg_per_30m": 0.0},
                              {"length_m": 2000.0, "build_rate_deg_per_30m": 0.0,
                               "turn_rate_deg_per_30m": turn}]}
    d["start_md_m"] = 10.0
    d["duration_s"] = hours * 3600.0
    d["rop_mph"] = rop
    d["connection_s"] = rng.uniform(120.0, 600.0)
    d["rotation_rpm"] = 0.0 if mode == "slide" else rng.uniform(30.0, 180.0)
    if mode == "pattern":
        slide = rng.uniform(5.0, 15.0)
        d["stand_pattern"] = [
            {"mode": "slide", "length_m": slide, "toolface_deg": rng.uniform(0.0, 360.0),
             "rop_mph": rop / 2.0},
            {"mode": "rotate", "length_m": d["stand_length_m"] - slide}]
    start_md = d["start_md_m"] + rop * 0.5  # half an hour into the drilling
    d["vibration_episodes"] = [{"start_md_m": start_md, "end_md_m": start_md + 5.0,
                                "axial_g": rng.uniform(1.0, 3.0),
                                "frequency_hz": rng.choice([8.0, 10.0, 12.0, 15.0])}]
    east_west = abs(math.sin(math.radians(azimuth))) > 0.7 and inclination > 45.0
    scenario["description"] = (f"envelope well: lat {latitude:.1f}, inc {inclination:.1f}, "
                               f"az {azimuth:.1f}, turn {turn:.2f} deg/30 m, {mode}, ROP {rop:.0f}")
    return scenario, f"{mode}{' east-west' if east_west else ''}"


def run(stochnav, *args):
    result = subprocess.run([stochnav, *args], capture_output=True, text=True)
    if result.returncode != 0:
        raise RuntimeError(f"stochnav {' '.join(args)}: {result.stderr.strip()}")


# WGS-84 (the run's tie-on frame: experiment/survey.cpp, SurveyRecorder::tie_on_position_m).
WGS84_A = 6378137.0
WGS84_E2 = 6.69437999014e-3


def tie_on_frame(latitude_deg, height_m):
    """Metres per radian of latitude and of longitude at the tie-on (its local level frame)."""
    s = math.sin(math.radians(latitude_deg))
    w = 1.0 - WGS84_E2 * s * s
    meridian = WGS84_A * (1.0 - WGS84_E2) / w ** 1.5
    transverse = WGS84_A / math.sqrt(w)
    return meridian + height_m, (transverse + height_m) * math.cos(math.radians(latitude_deg))


def truth_at(truth, times, t):
    """The truth row at time t (linear between the 1-Hz rows; the azimuth through north)."""
    k = min(bisect.bisect_left(times, t), len(times) - 1)
    if k == 0 or times[k] <= t:
        return truth[k]
    a, b = truth[k - 1], truth[k]
    w = (t - a["t"]) / (b["t"] - a["t"])
    row = {key: a[key] + w * (b[key] - a[key]) for key in a}
    row["azimuth"] = a["azimuth"] + w * math.remainder(b["azimuth"] - a["azimuth"], 360.0)
    return row


def station_errors(survey_csv, truth_csv):
    """survey.csv's survey stations against the truth kept aside: (error, sigma) per quantity."""
    with open(truth_csv) as f:
        truth = [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]
    times = [row["t"] for row in truth]
    with open(survey_csv) as f:
        stations = [r for r in csv.DictReader(f) if r.get("station_type", "survey") == "survey"]
    first = truth[0]
    north_per_rad, east_per_rad = tie_on_frame(first["lat"], first["h"])
    pairs = {q: [] for q, _ in QUANTITIES}
    for r in stations:
        t = truth_at(truth, times, float(r["t_s"]))
        true = {"inclination_deg": t["inclination"], "azimuth_deg": t["azimuth"],
                "north_m": math.radians(t["lat"] - first["lat"]) * north_per_rad,
                "east_m": math.radians(math.remainder(t["lon"] - first["lon"], 360.0)) *
                east_per_rad,
                "tvd_m": first["h"] - t["h"]}
        for quantity, sigma in QUANTITIES:
            error = float(r[quantity]) - true[quantity]
            if quantity == "azimuth_deg":
                error = math.remainder(error, 360.0)
            pairs[quantity].append((error, float(r[sigma])))
    return pairs


def write_run_config(folder, truth_csv):
    """FOLDER/run.json: the shipped recording config with its tie-on at the well's surface
    location (the truth's first row: what a rig knows), its data given on the command line."""
    with open(truth_csv) as f:
        first = next(csv.DictReader(f))
    with open(os.path.join(ROOT, "configs/runs/drilling_recording.json")) as f:
        config = json.load(f)
    config.pop("data")
    config["initial_state"]["tie_on"] = {"latitude_deg": float(first["lat"]),
                                         "longitude_deg": float(first["lon"]),
                                         "height_m": float(first["h"])}
    with open(os.path.join(folder, "run.json"), "w") as f:
        json.dump(config, f, indent=1)


def score_well(stochnav, folder, scenario):
    """Simulates the well, runs it with the truth withheld (the run's folder holds the IMU and
    aid records only), then scores survey.csv against the truth."""
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, "scenario.json"), "w") as f:
        json.dump(scenario, f, indent=1)
    data = os.path.join(folder, "data")
    run(stochnav, "simulate", "scenario", os.path.join(folder, "scenario.json"), "--out", data)
    recording = os.path.join(folder, "recording")  # what a rig gives: no truth
    os.makedirs(recording, exist_ok=True)
    for name in ("imu.csv", "aids.csv"):
        target = os.path.join(recording, name)
        if not os.path.exists(target):
            os.symlink(os.path.join("..", "data", name), target)
    write_run_config(folder, os.path.join(data, "truth.csv"))
    out = os.path.join(folder, "run")
    run(stochnav, "run", os.path.join(folder, "run.json"), "--data", recording, "--out", out,
        "--no-plot")
    with open(os.path.join(out, "metrics.json")) as f:
        self_check = json.load(f)["self_check"]
    flags = {"survey_qc_flagged": self_check.get("survey_qc", {}).get("flagged", 0),
             "heading_unresolved": self_check.get("heading", {}).get("resolved") is False,
             "optimistic": bool(self_check.get("optimistic", False))}
    pairs = station_errors(os.path.join(out, "survey.csv"), os.path.join(data, "truth.csv"))
    score = {}
    for quantity, _ in QUANTITIES:
        finite = [(e, s) for e, s in pairs[quantity]
                  if math.isfinite(e) and math.isfinite(s) and s > 0]
        score[quantity] = {"stations": len(finite),
                           "inside": sum(abs(e) <= 3.0 * s for e, s in finite),
                           "worst_sigmas": max((abs(e) / s for e, s in finite), default=0.0)}
    return score, flags


def flagged(flags):
    """Whether the run said, without truth, that something is wrong."""
    return flags["survey_qc_flagged"] > 0 or flags["heading_unresolved"] or flags["optimistic"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("stochnav")
    parser.add_argument("out")
    parser.add_argument("--wells", type=int, default=12)
    parser.add_argument("--hours", type=float, default=8.0)
    parser.add_argument("--seed", type=int, default=25)
    parser.add_argument("--require-inside", type=float, default=None, metavar="SHARE",
                        help="exit 1 unless, over the family, every quantity has at least SHARE "
                             "of its stations inside 3 sigma and no well is silently wrong")
    args = parser.parse_args()
    rng = random.Random(args.seed)
    classes = {}
    wells = []
    for k in range(args.wells):
        scenario, case_class = draw_well(rng, k, args.hours)
        score, flags = score_well(args.stochnav, os.path.join(args.out, f"well_{k}"), scenario)
        outside = any(score[q]["inside"] < score[q]["stations"] for q, _ in QUANTITIES)
        silently_wrong = outside and not flagged(flags)
        wells.append({"well": k, "class": case_class, "description": scenario["description"],
                      "score": score, "flags": flags, "silently_wrong": silently_wrong})
        total = classes.setdefault(case_class, {q: {"stations": 0, "inside": 0, "worst_sigmas": 0.0}
                                                for q, _ in QUANTITIES} |
                                   {"wells": 0, "flagged_wells": 0, "silently_wrong_wells": 0})
        total["wells"] += 1
        total["flagged_wells"] += flagged(flags)
        total["silently_wrong_wells"] += silently_wrong
        for q, _ in QUANTITIES:
            for key in ("stations", "inside"):
                total[q][key] += score[q][key]
            total[q]["worst_sigmas"] = max(total[q]["worst_sigmas"], score[q]["worst_sigmas"])
        print(f"well {k} ({case_class}): " + ", ".join(
            f"{q.split('_')[0]} {score[q]['inside']}/{score[q]['stations']}" for q, _ in QUANTITIES) +
            (" [flagged]" if flagged(flags) else "") +
            (" SILENTLY WRONG" if silently_wrong else ""), flush=True)
    family = {q: {key: sum(c[q][key] for c in classes.values()) for key in ("stations", "inside")}
              for q, _ in QUANTITIES}
    with open(os.path.join(args.out, "summary.json"), "w") as f:
        json.dump({"seed": args.seed, "hours": args.hours, "classes": classes, "family": family,
                   "wells": wells}, f, indent=1)
    lines = ["| class | wells | " + " | ".join(q.split("_")[0] for q, _ in QUANTITIES) +
             " | wells flagged (no truth) | silently wrong |",
             "|---|---|" + "---|" * len(QUANTITIES) + "---|---|"]
    rows = sorted(classes.items()) + [("**family**", dict(family, wells=len(wells),
                                                       flagged_wells=sum(c["flagged_wells"] for c in classes.values()),
                                                       silently_wrong_wells=sum(c["silently_wrong_wells"] for c in classes.values())))]
    for name, total in rows:
        cells = []
        for q, _ in QUANTITIES:
            t = total[q]
            share = 100.0 * t["inside"] / t["stations"] if t["stations"] else float("nan")
            worst = f" (worst {t['worst_sigmas']:.1f})" if "worst_sigmas" in t else ""
            cells.append(f"{share:.0f} % of {t['stations']}{worst}")
        lines.append(f"| {name} | {total['wells']} | " + " | ".join(cells) +
                     f" | {total['flagged_wells']} | {total['silently_wrong_wells']} |")
    with open(os.path.join(args.out, "summary.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))
    if args.require_inside is None:
        return 0
    failures = [f"{q}: {t['inside']} of {t['stations']} stations inside 3 sigma, under "
                f"{args.require_inside:.0%}" for q, t in family.items()
                if t["stations"] and t["inside"] < args.require_inside * t["stations"]]
    failures += [f"well {w['well']} ({w['class']}) is outside 3 sigma and not flagged"
                 for w in wells if w["silently_wrong"]]
    for failure in failures:
        print(f"envelope: {failure}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
