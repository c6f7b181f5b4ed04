"""Writes path.csv: a 300 mm x 200 mm pocket contour (corner radius 20 mm, one point every 5 mm)
in a horizontal plane, the tool z axis pointing down (rx_deg = 180: URDF roll-pitch-yaw), and a
200 N cutting force against the feed direction, given in the tool frame.

    python3 make_path.py [cx_mm cy_mm cz_mm] > path.csv
"""
import math
import sys

CX, CY, CZ = (float(v) for v in sys.argv[1:4]) if len(sys.argv) == 4 else (1300.0, -700.0, 400.0)
W, H, R, STEP, FORCE = 300.0, 200.0, 20.0, 5.0, 200.0


def contour():
    """(x, y, feed direction) along the rounded rectangle, counter-clockwise from the middle of
    the lower edge."""
    a, b = W / 2 - R, H / 2 - R
    # Straight edges and quarter arcs as (start, end) pieces, walked by arc length.
    pieces = []
    corners = [(a, -b, -90), (a, b, 0), (-a, b, 90), (-a, -b, 180)]
    starts = [(0.0, -H / 2), (W / 2, -b), (a, H / 2), (-W / 2, b), (-a, -H / 2)]
    ends = [(a, -H / 2), (W / 2, b), (-a, H / 2), (-W / 2, -b), (0.0, -H / 2)]
    for k in range(5):
        pieces.append(("line", starts[k], ends[k]))
        if k < 4:
            pieces.append(("arc", corners[k]))
    pts = []
    for p in pieces:
        if p[0] == "line":
            (x0, y0), (x1, y1) = p[1], p[2]
            n = max(1, round(math.hypot(x1 - x0, y1 - y0) / STEP))
            d = ((x1 - x0) / math.hypot(x1 - x0, y1 - y0), (y1 - y0) / math.hypot(x1 - x0, y1 - y0))
            pts += [(x0 + (x1 - x0) * i / n, y0 + (y1 - y0) * i / n, d) for i in range(n)]
        else:
            cx, cy, start = p[1]
            n = max(1, round(R * math.pi / 2 / STEP))
            for i in range(n):
                t = math.radians(start + 90.0 * i / n)
                pts.append((cx + R * math.cos(t), cy + R * math.sin(t), (-math.sin(t), math.cos(t))))
    pts.append((0.0, -H / 2, (1.0, 0.0)))
    return pts


print("x_mm,y_mm,z_mm,rx_deg,ry_deg,rz_deg,fx_n,fy_n,fz_n,frame")
for x, y, (dx, dy) in contour():
    # Tool frame with rpy (180, 0, 0): tool x = base x, tool y = -base y, tool z = -base z.
    fx, fy = -FORCE * dx, FORCE * dy
    print(f"{CX + x:.3f},{CY + y:.3f},{CZ:.3f},180,0,0,{fx:.3f},{fy:.3f},0,tool")
