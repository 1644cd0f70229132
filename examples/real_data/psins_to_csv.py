#!/usr/bin/env python3
"""Converts the PSINS ring-laser-gyro record (../shared/data/psins/lasergyro.imu, BSD-2; see its
SOURCES.md) into a `stochnav run --data` recording folder: OUT/imu.csv with the columns
t, dtheta_x, dtheta_y, dtheta_z (rad), dv_x, dv_y, dv_z (m/s) over [t - dt, t], body axes as
PSINS writes them (x right, y forward, z up). No truth, no aids: the run configs
configs/runs/psins_*.json align on the static start and then detect ZUPTs from the IMU.

    python3 examples/real_data/psins_to_csv.py ../shared/data/psins/lasergyro.imu /tmp/psins
    stochnav run configs/runs/psins_zupt.json --data /tmp/psins --out /tmp/psins_zupt

Scales as framework/src/io/psins_imu.cpp: gyro counts x arcsec, accelerometer counts x ug*s with
PSINS' own g0 = 9.7803267714 m/s^2. Only the standard library is used.
"""
import math
import os
import sys

ARCSEC = math.pi / (180.0 * 3600.0)
MICRO_G = 9.7803267714e-6


def main(source, out_dir):
    rows = []
    with open(source) as f:
        for line in f:
            line = line.strip()
            if line and not line.startswith('%'):
                rows.append(line)
    if len(rows) < 4:
        sys.exit(f"{source}: fewer than three header rows and one epoch; not a PSINS .imu file")
    position = [float(x) for x in rows[1].split()]
    scale = [float(x) for x in rows[2].split()]
    interval_s = position[4] / 1000.0
    factors = [scale[i] * (ARCSEC if i < 3 else MICRO_G) for i in range(6)]
    os.makedirs(out_dir, exist_ok=True)
    target = os.path.join(out_dir, "imu.csv")
    with open(target + ".tmp", "w") as out:
        out.write("t,dtheta_x,dtheta_y,dtheta_z,dv_x,dv_y,dv_z\n")
        for k, row in enumerate(rows[3:], start=1):
            counts = row.split()
            if len(counts) != 6:
                sys.exit(f"{source}: epoch {k} has {len(counts)} values; expected 6")
            values = ",".join(repr(float(c) * f) for c, f in zip(counts, factors))
            out.write(f"{k * interval_s:.2f},{values}\n")
    os.replace(target + ".tmp", target)
    print(f"wrote {target}: {len(rows) - 3} epochs at {1.0 / interval_s:g} Hz; site latitude "
          f"{position[0]} deg, longitude {position[1]} deg, height {position[2]} m")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: psins_to_csv.py LASERGYRO.imu OUT_DIR")
    main(sys.argv[1], sys.argv[2])
