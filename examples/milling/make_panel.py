"""Writes panel.nc: a drilling pattern of 4 x 5 holes (8 mm, 10 mm deep) on a panel curved
about the part's x axis (radius 1000 mm, the holes 0.1 rad apart around it, 60 mm apart along
it), each drilled along the surface normal: the tool turned by A (deg, about the part's x axis,
`(stiffid: rotary = abc)`) from pointing down the part's -Z, fed 10 mm along its axis, rapid out.

    python3 make_panel.py > panel.nc
"""

import math

RADIUS, DEPTH, CLEAR = 1000.0, 10.0, 5.0
XS = [-90.0, -30.0, 30.0, 90.0]
ANGLES = [-0.2, -0.1, 0.0, 0.1, 0.2]


def point(x, phi, offset):
    """The point `offset` mm out along the normal from the surface at (x, phi)."""
    r = RADIUS + offset
    return x, r * math.sin(phi), r * math.cos(phi) - RADIUS


lines = [
    "(drilling pattern on a panel curved about X: radius 1000 mm, 4 x 5 holes)",
    "(stiffid: tool_rpy_deg = 180 0 0)",
    "(stiffid: rotary = abc)",
    "(operation: drill)",
    "G21 G90 G17",
    "T2 M06",
    "S3000 M03",
]
for x in XS:
    for phi in ANGLES:
        a = -math.degrees(phi)
        for offset, move in ((CLEAR, "G0"), (-DEPTH, "G1"), (CLEAR, "G0")):
            px, py, pz = point(x, phi, offset)
            feed = " F450" if move == "G1" else ""
            lines.append(f"{move} X{px:.3f} Y{py:.3f} Z{pz:.3f} A{a:.3f}{feed}")
lines += ["M05", "M30"]
print("\n".join(lines))
