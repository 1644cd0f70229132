#!/usr/bin/env python3
"""Independent reference values for gyro_tool_model_test.cpp (OwsgGyroReference.*) and
stationary_gyro_tool_model_test.cpp (OwsgStationaryGyroReference.*).

Evaluates the OWSG gyro tool models' weighting formulas *as the OWSG tool-model JSON writes
them* (welleng/errors/iscwsa_json/owsg_a/GYRO-NS-CT.json, GYRO-NS.json, GYRO-MWD.json, welleng
@ 6e673c7c, Apache-2.0: the formula strings, magnitudes, units and propagation modes, read from
the file given, not retyped), and propagates them with the ISCWSA balanced-tangential
derivatives written out here from the ISCWSA MWD document (not from stochnav's code), on the
test well of gyro_tool_model_test.cpp. Standard library only.

    python3 tests/survey_error/owsg_gyro_reference.py path/to/GYRO-NS-CT.json
    python3 tests/survey_error/owsg_gyro_reference.py path/to/GYRO-NS.json
    python3 tests/survey_error/owsg_gyro_reference.py path/to/GYRO-MWD.json

The tool model is recognised by the JSON's metadata/short_name.

GYRO-NS-CT: the gyrocompass terms (GXY-B1S, GXY-B2S, GXY-G4) are evaluated at the gyrocompass
stations and held at the initialising station's value through the continuous survey (as
welleng's withdrawn `_get_ref_init_error` did), the initialising station being the first at or
above the continuous start inclination (15 deg); every printed term is systematic.

GYRO-NS and GYRO-MWD: every station is a gyrocompass station (OWSG "XY Static Gyro" from 0 to
180 deg, no continuous survey); each term is propagated by the JSON's mode (Random: the
stations' covariances add; Systematic: the error vectors add). NoiseReductionFactor, which the
formula strings name but the JSON does not give, is 1: the OWSG tool tables of these two tools
(A020Gb, A019Gb) list no noise reduction factor (GYRO-NS-CT's, A021Gc, lists 0.4082).
"""

import json
import math
import re
import sys

TERMS = ["AXYZ-MIS", "AXYZ-SF", "AXYZ-ZB", "GXY-B1S", "GXY-B2S", "GXY-G4", "SAGE", "XYM1", "XYM2"]
GYROCOMPASS = {"GXY-B1S", "GXY-B2S", "GXY-G4"}
# GYRO-NS and GYRO-MWD: every term whose formulas need no previous station (XYM3E, XYM4E, XCLA,
# XCLH are the Rev5 rows validated against the ISCWSA workbook) and no TVD (DSTG, likewise).
STATIONARY_TERMS = ["DRFR", "DSFS", "SAGE", "XYM1", "XYM2", "AXYZ-MIS", "AXYZ-SF", "AXYZ-ZB",
                    "GXY-B1R", "GXY-B2R", "GXY-G1", "GXY-G4", "GXY-RN"]
NOISE_REDUCTION_FACTOR = {"GYRO-NS": 1.0, "GYRO-MWD": 1.0}
CHECKED = [12, 18, 40, 80]
START_INC = math.radians(15.0)
LATITUDE = math.radians(60.0)
EARTH_RATE_RAD_H = math.radians(15.041)
GRAVITY = 9.80665
UNIT_TO_SI = {"deg": math.pi / 180.0, "deg/hr": math.pi / 180.0, "m/s2": 1.0, "-": 1.0, "m": 1.0}


def test_well():
    """gyro_tool_model_test.cpp's well: 30 m stations, vertical to 300 m, a build of 2 deg / 30 m
    turning from azimuth 30 to 78 deg up to 50 deg, a hold to 2400 m."""
    stations = []
    for k in range(81):
        build = min(max(k - 10, 0), 25)
        stations.append((30.0 * k, math.radians(2.0 * build), math.radians(30.0 + 2.0 * build)))
    return stations


def formula(text):
    text = re.sub(r"\bSqr\(", "sqrt(", text)
    for excel, py in (("Sin", "sin"), ("Cos", "cos"), ("Tan", "tan"), ("Abs", "abs"),
                      ("Max", "max")):
        text = re.sub(r"\b%s\(" % excel, py + "(", text)
    code = compile(text.replace("^", "**"), "<formula>", "eval")
    return lambda env: eval(code, {"__builtins__": {}, "sin": math.sin, "cos": math.cos,
                                   "tan": math.tan, "abs": abs, "max": max,
                                   "sqrt": math.sqrt}, env)


def direction(inc, azi):
    return (math.sin(inc) * math.cos(azi), math.sin(inc) * math.sin(azi), math.cos(inc))


def d_direction(inc, azi):
    """dt/dI and dt/dA."""
    return ((math.cos(inc) * math.cos(azi), math.cos(inc) * math.sin(azi), -math.sin(inc)),
            (-math.sin(inc) * math.sin(azi), math.sin(inc) * math.cos(azi), 0.0))


def outer_sum(vectors, r, c):
    """Element (r, c) of the sum of e e^T over `vectors`."""
    total = vectors[0][r] * vectors[0][c]
    for e in vectors[1:]:
        total += e[r] * e[c]
    return total


def main(path):
    model = json.load(open(path))
    short_name = model["metadata"]["short_name"]
    terms = {t["name"]: t for t in model["terms"]}
    well = test_well()
    n = len(well)
    if short_name == "GYRO-NS-CT":
        init = next(k for k in range(1, n) if well[k][1] >= START_INC)
        names, carried, nrf = TERMS, GYROCOMPASS, None
    else:
        init = n  # no continuous survey: every station keeps its own weights
        names, carried, nrf = STATIONARY_TERMS, set(), NOISE_REDUCTION_FACTOR[short_name]
    for name in names:
        term = terms[name]
        magnitude = term["value"] * UNIT_TO_SI[term["units"]]
        random = term["propagation_mode"] == "Random" and short_name != "GYRO-NS-CT"
        weights = [formula(term[axis + "_formula"])
                   for axis in ("depth", "inclination", "azimuth")]
        dpde = [(0.0, 0.0, 0.0)]
        for k in range(1, n):
            at = min(k, init) if name in carried else k
            md, inc, azi = well[at]
            env = {"MD": md, "Inc": inc, "AzT": azi, "Gfield": GRAVITY,
                   "EarthRate": EARTH_RATE_RAD_H, "Latitude": LATITUDE}
            if nrf is not None:
                env["NoiseReductionFactor"] = nrf
            dpde.append(tuple(w(env) for w in weights))
        # e_k: the station's error moving the legs before and after it (ISCWSA document).
        before, both = [(0.0, 0.0, 0.0)] * n, [(0.0, 0.0, 0.0)] * n
        for k in range(1, n):
            t_prev, t = direction(*well[k - 1][1:]), direction(*well[k][1:])
            dt_di, dt_da = d_direction(*well[k][1:])
            d_md, d_i, d_a = dpde[k]
            step = well[k][0] - well[k - 1][0]
            b = [magnitude * (d_md * (t_prev[i] + t[i]) / 2 +
                              step / 2 * (d_i * dt_di[i] + d_a * dt_da[i])) for i in range(3)]
            a = [0.0, 0.0, 0.0]
            if k + 1 < n:
                t_next = direction(*well[k + 1][1:])
                step_after = well[k + 1][0] - well[k][0]
                a = [magnitude * (-d_md * (t[i] + t_next[i]) / 2 +
                                  step_after / 2 * (d_i * dt_di[i] + d_a * dt_da[i]))
                     for i in range(3)]
            before[k] = b
            both[k] = [b[i] + a[i] for i in range(3)]
        for station in CHECKED:
            if random:  # sum_(k<K) e_k e_k^T + e*_K e*_K^T
                vectors = [both[k] for k in range(1, station)] + [before[station]]
            else:  # systematic: E_K = sum_(k<K) e_k + e*_K
                vectors = [[sum(both[k][i] for k in range(1, station)) + before[station][i]
                            for i in range(3)]]
            nev = [outer_sum(vectors, r, c)
                   for r, c in ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2))]
            print('{"%s", %d, {%s}},' % (name, station, ", ".join("%.17g" % v for v in nev)))


if __name__ == "__main__":
    main(sys.argv[1])
