"""Writes pocket.nc: the contour passes of a 300 mm x 200 mm pocket (corner radius 20 mm) at two
depths, 4 mm each, for a 20 mm three-flute end mill at 6000 rpm and 0.1 mm per tooth
(F1800 mm/min), down milling. Straight walls in 10 mm steps (G1), corners as arcs (G3), in the
part frame (millimetres, absolute), the tool z axis pointing down the part's -Z.

    python3 make_pocket.py > pocket.nc
"""

W, H, R, STEP = 300.0, 200.0, 20.0, 10.0
DEPTHS = (-4.0, -8.0)


def edge(x0, y0, x1, y1):
    """G1 blocks from (x0, y0) to (x1, y1) in steps of at most STEP."""
    n = max(1, round(max(abs(x1 - x0), abs(y1 - y0)) / STEP))
    return [f"G1 X{x0 + (x1 - x0) * k / n:.3f} Y{y0 + (y1 - y0) * k / n:.3f}" for k in range(1, n + 1)]


def contour():
    """The rounded rectangle counter-clockwise from the middle of the lower wall (down milling
    of the pocket's outer wall with the tool turning clockwise seen from the spindle: M03)."""
    a, b = W / 2, H / 2
    out = edge(0, -b, a - R, -b)
    out.append(f"G3 X{a:.3f} Y{-b + R:.3f} I0 J{R:.3f}")
    out += edge(a, -b + R, a, b - R)
    out.append(f"G3 X{a - R:.3f} Y{b:.3f} I{-R:.3f} J0")
    out += edge(a - R, b, -a + R, b)
    out.append(f"G3 X{-a:.3f} Y{b - R:.3f} I0 J{-R:.3f}")
    out += edge(-a, b - R, -a, -b + R)
    out.append(f"G3 X{-a + R:.3f} Y{-b:.3f} I{R:.3f} J0")
    out += edge(-a + R, -b, 0, -b)
    return out


lines = [
    "(pocket wall: 300 x 200 mm, corner radius 20 mm, two passes of 4 mm)",
    "(stiffid: tool_rpy_deg = 180 0 0)",
    "(operation: wall)",
    "G21 G90 G17",
    "T1 M06",
    "S6000 M03",
    "G0 X0 Y-100 Z5",
]
for z in DEPTHS:
    lines.append(f"G1 Z{z:.3f} F300")
    lines.append("F1800")
    lines += contour()
lines += ["G0 Z5", "M05", "M30"]
print("\n".join(lines))
