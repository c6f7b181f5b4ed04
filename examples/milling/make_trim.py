"""Writes trim.nc: a 1200 mm trim line along the part's x axis (an edge trimmed by side
milling, 10 mm steps), gently curved in the part's y (a 20 mm sine over its length), the tool
z axis down the part's -Z, for a 12 mm two-flute end mill at 0.05 mm per tooth (F1200 mm/min at
S12000).

    python3 make_trim.py > trim.nc
"""

import math

LENGTH, STEP, WAVE = 1200.0, 10.0, 20.0

lines = [
    "(trim line: 1200 mm along X, a 20 mm sine in Y)",
    "(stiffid: tool_rpy_deg = 180 0 0)",
    "(operation: trim)",
    "G21 G90 G17",
    "T3 M06",
    "S12000 M03",
    f"G0 X{-LENGTH / 2:.3f} Y0 Z5",
    "G1 Z-6.000 F300",
    "F1200",
]
n = round(LENGTH / STEP)
for k in range(1, n + 1):
    x = -LENGTH / 2 + k * STEP
    y = WAVE * math.sin(2 * math.pi * k / n)
    lines.append(f"G1 X{x:.3f} Y{y:.3f}")
lines += ["G0 Z5", "M05", "M30"]
print("\n".join(lines))
