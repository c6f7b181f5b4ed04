#!/usr/bin/env python3
"""Independent plain least-squares fit of the FANUC R-2000iC/165F stiffness data, with NumPy only.

Reads the three original CSV files (rad, N, m; one row per posture) and fits the six joint
compliances of the Virtual Joint Method with springs on the *kinematic* joints, as the data's
authors did: tau = J_theta^T [F; 0], Psi[r, j] = J_theta[r, j] * tau_j (r = x, y, z of the TCP),
h = argmin |Psi h - delta| by numpy.linalg.lstsq (SVD), k = 1 / h.

The kinematics are written here from the data README (modified DH, axis map, TCP), not taken from
stiffid. The printed stiffness values are the reference in crates/stiffid-cli/tests/it/identify_cli.rs.

Usage: python3 numpy_reference.py [DIR]   (DIR defaults to original/ beside this script)
"""
import sys
from pathlib import Path

import numpy as np

# Modified DH rows: alpha_{i-1} [rad], a_{i-1} [m], theta offset [rad], d_i [m].
DH = [
    (0.0, 0.0, 0.0, 0.670),
    (-np.pi / 2, 0.312, -np.pi / 2, 0.0),
    (0.0, 1.075, 0.0, 0.0),
    (-np.pi / 2, 0.225, 0.0, 1.280),
    (np.pi / 2, 0.0, 0.0, 0.0),
    (-np.pi / 2, 0.0, 0.0, 0.215),
]
TCP = np.array([0.0069, 0.2453, 0.3193])  # flange frame, m


def rot_x(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1.0]])


def rot_z(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])


def trans(x, y, z):
    t = np.eye(4)
    t[:3, 3] = [x, y, z]
    return t


def tcp_jacobian(q):
    """Translational Jacobian (3x6, base frame) of the TCP in kinematic coordinates theta."""
    theta = np.array([q[0], q[1], -(q[1] + q[2]), -q[3], -q[4], -q[5]])
    t = np.eye(4)
    origins, axes = [], []
    for (alpha, a, offset, d), th in zip(DH, theta):
        t = t @ rot_x(alpha) @ trans(a, 0, 0) @ rot_z(th + offset) @ trans(0, 0, d)
        origins.append(t[:3, 3].copy())
        axes.append(t[:3, 2].copy())
    p = (t @ np.append(TCP, 1.0))[:3]
    return np.column_stack([np.cross(z, p - o) for z, o in zip(axes, origins)])


def main():
    data = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent / "original"
    q = np.loadtxt(data / "joint_angles.csv", delimiter=",", skiprows=1)
    f = np.loadtxt(data / "forces.csv", delimiter=",", skiprows=1)
    dx = np.loadtxt(data / "deltaX.csv", delimiter=",", skiprows=1)
    rows, rhs = [], []
    for qi, fi, di in zip(q, f, dx):
        j = tcp_jacobian(qi)
        tau = j.T @ fi  # no moment: the cable pulls at the TCP
        rows.append(j * tau)  # Psi[r, c] = J[r, c] * tau_c
        rhs.append(di)
    psi = np.vstack(rows)
    delta = np.concatenate(rhs)
    h, _, _, sv = np.linalg.lstsq(psi, delta, rcond=None)
    print(f"rows {psi.shape[0]}, postures {len(q)}, cond(Psi) {float(sv[0] / sv[-1])!r}")
    print("compliance_rad_per_nm", [float(v) for v in h])
    print("stiffness_nm_per_rad", [float(v) for v in 1.0 / h])


if __name__ == "__main__":
    main()
