"""Writes trim.csv: a 3000 mm trim line along the rail of track-cell.toml, for `compensate --path`.

The line runs along the cell's x from 1500 to 4500 mm at y = 1500 mm (beside the rail), z = 900 mm
(the table's top), 50 mm between points, the tool z axis down (rx = 180 deg); the side-milling
force of a trim cut (feed force against x, the radial force into the part along +y, a little
down), fixed in the cell frame. The path's own station: the robot parked in the middle of the
line, e1 = 3000 mm (the positioner at rest, e2 = e3 = 0 deg), as a program that does not move the
track would leave it.

    python3 make_trim.py > trim.csv
"""

START, LENGTH, STEP = 1500.0, 3000.0, 50.0
Y, Z, STATION = 1500.0, 900.0, 3000.0
FORCE = (-150.0, 250.0, -80.0)

print("# trim line: 3000 mm along the rail, the robot parked at 3000 mm")
print("x_mm,y_mm,z_mm,rx_deg,ry_deg,rz_deg,fx_n,fy_n,fz_n,frame,e1_mm,e2_deg,e3_deg")
n = round(LENGTH / STEP)
for k in range(n + 1):
    x = START + k * STEP
    print(f"{x:.3f},{Y:.3f},{Z:.3f},180,0,0,{FORCE[0]},{FORCE[1]},{FORCE[2]},base,{STATION:.3f},0,0")
