"""Writes table.csv: a 600 mm cut across the far side of the positioner's table of
track-cell.toml, for `compensate --path` with `--free positioner=-R..R/STEP`.

The line runs along the cell's x from 2700 to 3300 mm at y = 2200 mm (400 mm beyond the table's
centre, on the side away from the rail), z = 900 mm (the table's top), 25 mm between points, the
tool z axis down (rx = 180 deg); the side-milling force of the trim cut of trim.csv. Points and
force are the part's at e = 0 (cell coordinates): turning the table turns both with the part. The
path's own values: the robot at the table, e1 = 3000 mm, the table at rest (e2 = e3 = 0 deg).

    python3 make_table.py > table.csv
"""

START, LENGTH, STEP = 2700.0, 600.0, 25.0
Y, Z, STATION = 2200.0, 900.0, 3000.0
FORCE = (-150.0, 250.0, -80.0)

print("# a cut across the table's far side, the robot at 3000 mm, the table at rest")
print("x_mm,y_mm,z_mm,rx_deg,ry_deg,rz_deg,fx_n,fy_n,fz_n,frame,e1_mm,e2_deg,e3_deg")
n = round(LENGTH / STEP)
for k in range(n + 1):
    x = START + k * STEP
    print(f"{x:.3f},{Y:.3f},{Z:.3f},180,0,0,{FORCE[0]},{FORCE[1]},{FORCE[2]},base,{STATION:.3f},0,0")
