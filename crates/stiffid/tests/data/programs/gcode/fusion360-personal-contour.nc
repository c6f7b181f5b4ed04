(1024_block_14bit)
(T1  D=1.4 CR=0 - ZMIN=-3 - flat end mill)
G90 G94
G17
G21
(When using Fusion 360 for Personal Use, the feedrate of)
(rapid moves is reduced to match the feedrate of cutting)
(moves, which can increase machining time. Unrestricted rapid)
(moves are available with a Fusion 360 Subscription.)

(2D Contour5)
T1
S5000 M3
G54
G0 X-0.7 Y-0.7
Z10
G1 Z5 F1000
Z2 F333.3
Z-1
Y20 F1000
Y20.7
X20
X20.7
Y-0.7
X-0.7
Z-2 F333.3
Y20 F1000
Y20.7
X20
X20.7
Y-0.7
X-0.7
Z-3 F333.3
Y20 F1000
Y20.7
X20
X20.7
Y-0.7
X-0.7
Z10
M5
M30
