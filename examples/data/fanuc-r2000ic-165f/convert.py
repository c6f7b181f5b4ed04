#!/usr/bin/env python3
"""Converts the original FANUC R-2000iC/165F stiffness files (rad, N, m; one row per posture in
three files) into stiffid's measurement CSV (measurements.csv).

- Angles: rad -> deg with Python's math.degrees, written with repr (the shortest text that reads
  back as the same double), so no digit of the original is lost.
- Forces: copied as written (N, base frame, at the TCP). No moment columns: the cable pulls at the
  TCP, which is the loading point.
- Displacements: m -> mm by moving the decimal point (exact decimal arithmetic).
- posture = the row number 1..43, point = 1 (the TCP, the setup's only measuring point).

Usage: python3 convert.py [DIR] > measurements.csv
       (DIR defaults to original/ beside this script)
"""
import csv
import math
import sys
from decimal import Decimal
from pathlib import Path


def rows(path):
    with open(path, newline="") as f:
        return list(csv.reader(f))[1:]


def main():
    src = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent / "original"
    q, f, d = (rows(src / n) for n in ("joint_angles.csv", "forces.csv", "deltaX.csv"))
    assert len(q) == len(f) == len(d)
    out = csv.writer(sys.stdout, lineterminator="\n")
    out.writerow(["posture", "point"] + [f"q{i}_deg" for i in range(1, 7)]
                 + ["fx_n", "fy_n", "fz_n", "dx_mm", "dy_mm", "dz_mm"])
    for i, (qi, fi, di) in enumerate(zip(q, f, d), start=1):
        deg = [repr(math.degrees(float(v))) for v in qi]
        mm = [str(Decimal(v).scaleb(3).normalize()) for v in di]
        out.writerow([i, 1] + deg + [v.strip() for v in fi] + mm)


if __name__ == "__main__":
    main()
