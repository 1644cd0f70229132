#!/usr/bin/env python3
"""Independent reference values for gyro_tool_model_test.cpp (OwsgGyroReference.*).

Evaluates the OWSG GYRO-NS-CT weighting formulas *as the OWSG tool-model JSON writes them*
(welleng/errors/iscwsa_json/owsg_a/GYRO-NS-CT.json, welleng @ 6e673c7c, Apache-2.0: the
formula strings, read from the file given, not retyped), and propagates them with the ISCWSA
balanced-tangential derivatives written out here from the ISCWSA MWD document (not from
stochnav's code), on the test well of gyro_tool_model_test.cpp. Standard library only.

    python3 tests/survey_error/owsg_gyro_reference.py path/to/GYRO-NS-CT.json

The gyrocompass terms (GXY-B1S, GXY-B2S, GXY-G4) are evaluated at the gyrocompass stations and
held at the initialising station's value through the continuous survey (as welleng's withdrawn
`_get_ref_init_error` did), the initialising station being the first at or above the continuous
start inclination (15 deg).
"""

import json
import math
import re
import sys

TERMS = ["AXYZ-MIS", "AXYZ-SF", "AXYZ-ZB", "GXY-B1S", "GXY-B2S", "GXY-G4", "SAGE", "XYM1", "XYM2"]
GYROCOMPASS = {"GXY-B1S", "GXY-B2S", "GXY-G4"}
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


def main(path):
    terms = {t["name"]: t for t in json.load(open(path))["terms"]}
    well = test_well()
    n = len(well)
    init = next(k for k in range(1, n) if well[k][1] >= START_INC)
    for name in TERMS:
        term = terms[name]
        magnitude = term["value"] * UNIT_TO_SI[term["units"]]
        weights = [formula(term[axis + "_formula"])
                   for axis in ("depth", "inclination", "azimuth")]
        dpde = [(0.0, 0.0, 0.0)]
        for k in range(1, n):
            at = min(k, init) if name in GYROCOMPASS else k
            md, inc, azi = well[at]
            env = {"MD": md, "Inc": inc, "AzT": azi, "Gfield": GRAVITY,
                   "EarthRate": EARTH_RATE_RAD_H, "Latitude": LATITUDE}
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
        for station in CHECKED:  # systematic: E_K = sum_(k<K) e_k + e*_K
            e = [sum(both[k][i] for k in range(1, station)) + before[station][i]
                 for i in range(3)]
            nev = [e[0] * e[0], e[1] * e[1], e[2] * e[2], e[0] * e[1], e[0] * e[2], e[1] * e[2]]
            print('{"%s", %d, {%s}},' % (name, station, ", ".join("%.17g" % v for v in nev)))


if __name__ == "__main__":
    main(sys.argv[1])
