#!/usr/bin/env python3
"""Formats a `stochnav compare` results.json as the README's result tables: one row per
variant, each metric's mean over the seeds of the maximum absolute error, and for every
variant but the baseline the per-seed improvement over the baseline (mean +/- std, %);
then the consistency of each variant (mean NEES against its bounds, worst share inside
3 sigma). Usage: readme_table.py DIR/results.json"""
import json
import sys

METRICS = [("lat_err_m", "lat (m)"), ("lon_err_m", "lon (m)"), ("height_err_m", "height (m)"),
           ("ve_err_mps", "vE (m/s)"), ("vn_err_mps", "vN (m/s)"), ("vu_err_mps", "vU (m/s)"),
           ("inclination_err_deg", "incl. (deg)"), ("toolface_err_deg", "toolface (deg)"),
           ("azimuth_err_deg", "azimuth (deg)")]


def cell(variant, metric, baseline):
    value = f"{variant['metrics'][metric]['mean']:.3g}"
    if variant["name"] == baseline:
        return value
    improvement = variant["improvement_pct"][metric]
    return f"{value} ({improvement['mean']:+.0f} ± {improvement['std']:.0f} %)"


def main(path):
    results = json.load(open(path))
    baseline = results["baseline"]
    print("| variant (gyro model) | " + " | ".join(name for _, name in METRICS) + " |")
    print("|---" * (len(METRICS) + 1) + "|")
    for variant in results["variants"]:
        cells = [cell(variant, metric, baseline) for metric, _ in METRICS]
        print(f"| {variant['name']} (`{variant['noise_model']}`) | " + " | ".join(cells) + " |")
    print()
    print("| variant | mean NEES (95 % bounds) | worst share inside 3 sigma | optimistic |")
    print("|---|---|---|---|")
    for variant in results["variants"]:
        consistency = variant.get("consistency")
        if not consistency:
            continue
        inside = consistency["inside_3sigma"]
        worst = min(inside, key=lambda metric: inside[metric])
        low, high = consistency["nees_bounds"]
        flag = "yes" if consistency.get("optimistic") else "no"
        print(f"| {variant['name']} | {consistency['nees_mean']:.3g} ({low:.2f}-{high:.2f}) | "
              f"{worst} {100 * inside[worst]:.1f} % | {flag} |")


if __name__ == "__main__":
    main(sys.argv[1])
