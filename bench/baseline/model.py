"""The stiffid science written the way a user would write it in NumPy/SciPy.

This is the baseline stiffid is compared against (`bench/compare.sh`): plain, idiomatic NumPy,
vectorised where natural (the Jacobians of all points of one posture at once), not heroically
optimised, and independent of the Rust code (it reads only the same robot and setup TOML files).

Conventions (as in stiffid): SI inside (m, rad, N, Nm), mm and degrees in files. Jacobians are
geometric, base frame, rows [v; omega]; in axis coordinates J_q = J_theta M. Observation-matrix
rows: posture-major, then measuring point, then x, y, z (Zhang et al., IEEE Access 2021, Eq. 11).
"""

import tomllib
from pathlib import Path

import numpy as np
from scipy.optimize import minimize

PRESETS = Path(__file__).resolve().parents[2] / "crates" / "stiffid-core" / "presets"


# ---------------------------------------------------------------- robot and setup files

def rpy_matrix(rpy):
    """R = Rz(yaw) Ry(pitch) Rx(roll) (URDF fixed-axis roll-pitch-yaw), rad."""
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = np.cos(r), np.sin(r), np.cos(p), np.sin(p), np.cos(y), np.sin(y)
    return np.array([
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ])


def transform(table):
    """4x4 homogeneous transform of a {xyz_mm, rpy_deg} table (identity if absent)."""
    t = np.eye(4)
    if table:
        t[:3, :3] = rpy_matrix(np.radians(table.get("rpy_deg", [0.0, 0.0, 0.0])))
        t[:3, 3] = np.array(table.get("xyz_mm", [0.0, 0.0, 0.0])) * 1e-3
    return t


def load_robot(path):
    """A robot TOML file (DH table, axis map, base and flange) as a dict in SI units."""
    with open(path, "rb") as f:
        doc = tomllib.load(f)
    joints = doc["joint"]
    amap = doc.get("axis_map", {})
    return {
        "convention": doc["convention"],
        "a": np.array([j["a_mm"] for j in joints]) * 1e-3,
        "alpha": np.radians([j["alpha_deg"] for j in joints]),
        "d": np.array([j["d_mm"] for j in joints]) * 1e-3,
        "theta_offset": np.radians([j.get("theta_offset_deg", 0.0) for j in joints]),
        "M": np.array(amap.get("matrix", np.eye(6)), dtype=float),
        "c": np.radians(amap.get("offset_deg", np.zeros(6))),
        "base": transform(doc.get("base")),
        "flange": transform(doc.get("flange")),
    }


def load_setup(path):
    """A setup TOML file as a dict in SI units; its robot is a preset name or a robot TOML path."""
    path = Path(path)
    with open(path, "rb") as f:
        doc = tomllib.load(f)
    robot_ref = doc["robot"]
    robot_path = (path.parent / robot_ref) if robot_ref.endswith(".toml") else PRESETS / f"{robot_ref}.toml"
    tool = doc["tool"]
    measuring = np.array(tool["measuring_points_mm"], dtype=float) * 1e-3
    return {
        "robot": load_robot(robot_path),
        "springs": doc.get("springs", "axis"),
        "L": doc["characteristic_length_mm"] * 1e-3,
        "k_nominal": np.array(doc["nominal_stiffness_nm_per_rad"], dtype=float),
        "loading_point": np.array(tool["loading_point_mm"], dtype=float) * 1e-3,
        "measuring_points": measuring,
        "tcp": np.array(tool["tcp_mm"], dtype=float) * 1e-3 if "tcp_mm" in tool else measuring[0],
        "load": doc["loading"]["load_n"],
        "anchor": np.array(doc["loading"]["anchor_mm"], dtype=float) * 1e-3,
        # The displacement's noise: a loaded minus an unloaded reading (the old variance_mm2).
        "sigma": np.sqrt(2.0) * doc["noise"]["reading_sd_mm"] * 1e-3
        if "reading_sd_mm" in doc["noise"]
        else np.sqrt(doc["noise"]["variance_mm2"] * 1e-6),
        "levels": np.array(doc["noise"]["level_multiples"], dtype=float),
        "lower": np.radians(doc["bounds"]["lower_deg"]),
        "upper": np.radians(doc["bounds"]["upper_deg"]),
        "test_postures": np.radians(doc.get("test", {}).get("postures_deg", np.zeros((0, 6)))),
    }


# ---------------------------------------------------------------- kinematics

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


def forward(robot, q):
    """Joint axes (3x6 directions Z, 3x6 points O) and the flange transform at axis angles q (rad)."""
    theta = robot["M"] @ q + robot["c"] + robot["theta_offset"]
    t = robot["base"].copy()
    Z = np.empty((3, 6))
    O = np.empty((3, 6))
    for i in range(6):
        if robot["convention"] == "modified-dh":
            t = t @ rot_x(robot["alpha"][i]) @ trans(robot["a"][i], 0, 0)
            Z[:, i], O[:, i] = t[:3, 2], t[:3, 3]
            t = t @ rot_z(theta[i]) @ trans(0, 0, robot["d"][i])
        else:  # standard DH
            Z[:, i], O[:, i] = t[:3, 2], t[:3, 3]
            t = t @ rot_z(theta[i]) @ trans(0, 0, robot["d"][i]) @ trans(robot["a"][i], 0, 0) @ rot_x(robot["alpha"][i])
    return Z, O, t @ robot["flange"]


def point_position(flange, point):
    """Base-frame position (m) of a point given in the flange frame (m); point may be (n, 3)."""
    return point @ flange[:3, :3].T + flange[:3, 3]


def jacobians(setup, Z, O, flange, points):
    """Geometric Jacobians (n, 6, 6), rows [v; omega], of n flange-frame points, springs' coordinates."""
    P = point_position(flange, points)                                  # (n, 3)
    v = np.cross(Z.T[None, :, :], P[:, None, :] - O.T[None, :, :])      # (n, 6 joints, 3)
    J = np.concatenate([v, np.broadcast_to(Z.T, v.shape)], axis=2).transpose(0, 2, 1)
    return J @ setup["robot"]["M"] if setup["springs"] == "axis" else J


def dexterity(J, L):
    """k(J_N) = (1/6) sqrt(tr(A) tr(A^-1)), A = J_N J_N^T, J_N = diag(I/L, I) J (Eq. 20-21)."""
    JN = J.copy()
    JN[:3] /= L
    A = JN @ JN.T
    return np.sqrt(np.trace(A) * np.trace(np.linalg.inv(A))) / 6.0


def rope_wrench(setup, p1):
    """F = G (P2 - P1) / |P2 - P1| at the loading point, no moment."""
    d = setup["anchor"] - p1
    return np.concatenate([setup["load"] * d / np.linalg.norm(d), np.zeros(3)])


# ---------------------------------------------------------------- observation matrix

def posture_block(setup, q, wrench=None, points=None):
    """The 3p x 6 observation rows of one posture: Psi[r, j] = J_m[r, j] tau_j, tau = J_f^T W (Eq. 11).

    The wrench defaults to the rope-mass load; points (indices) default to every measuring point.
    """
    Z, O, flange = forward(setup["robot"], q)
    pts = setup["measuring_points"] if points is None else setup["measuring_points"][points]
    J = jacobians(setup, Z, O, flange, np.vstack([setup["loading_point"], pts]))
    if wrench is None:
        wrench = rope_wrench(setup, point_position(flange, setup["loading_point"]))
    tau = J[0].T @ wrench
    return (J[1:, :3, :] * tau).reshape(-1, 6)


def observation_matrix(setup, postures):
    """The 3pn x 6 observation matrix of postures (n, 6) (rad) under the rope-mass load."""
    return np.vstack([posture_block(setup, q) for q in postures])


# ---------------------------------------------------------------- design criteria

def classical(setup, postures):
    """max_i k(J_N)_i over the postures, J the TCP Jacobian in the springs' coordinates."""
    ks = []
    for q in postures:
        Z, O, flange = forward(setup["robot"], q)
        ks.append(dexterity(jacobians(setup, Z, O, flange, setup["tcp"][None])[0], setup["L"]))
    return max(ks)


def zhang2021(setup, postures):
    """The paper's index: classical * cond_2(Psi) (Section III-B)."""
    return classical(setup, postures) * np.linalg.cond(observation_matrix(setup, postures))


def scaled(setup, Psi):
    """S = Psi diag(h_nominal) / sigma: unitless; inv(S^T S) is the covariance of relative errors."""
    return Psi * (1.0 / setup["k_nominal"]) / setup["sigma"]


def scaled_cond(setup, postures):
    """cond_2(S)."""
    return np.linalg.cond(scaled(setup, observation_matrix(setup, postures)))


def d_optimal(setup, postures):
    """det((S^T S)^-1)^(1/12): the geometric mean of the relative standard deviations."""
    S = scaled(setup, observation_matrix(setup, postures))
    return np.linalg.det(np.linalg.inv(S.T @ S)) ** (1.0 / 12.0)


def relative_a(setup, postures):
    """sqrt(mean_j [(S^T S)^-1]_jj): the RMS predicted relative standard deviation."""
    S = scaled(setup, observation_matrix(setup, postures))
    return np.sqrt(np.mean(np.diag(np.linalg.inv(S.T @ S))))


def test_pose_with(setup, cov):
    """sigma sqrt(mean_t tr(A_t cov A_t^T)) over the test postures under the rope load, m."""
    if not len(setup["test_postures"]):
        return 0.0
    A = [posture_block(setup, q) for q in setup["test_postures"]]
    return setup["sigma"] * np.sqrt(np.mean([np.trace(a @ cov @ a.T) for a in A]))


def test_pose(setup, postures):
    """The RMS error (m) of the deflection predicted at the test postures (Klimchik & Pashkevich)."""
    Psi = observation_matrix(setup, postures)
    return test_pose_with(setup, np.linalg.inv(Psi.T @ Psi))


CRITERIA = {"classical": classical, "zhang2021": zhang2021, "scaled-cond": scaled_cond,
            "d-optimal": d_optimal, "relative-a": relative_a, "test-pose": test_pose}


def evaluate(setup, postures):
    """Every design criterion of stiffid's `evaluate` (issue 4 definitions), SI (test pose in m)."""
    Psi = observation_matrix(setup, postures)
    S = scaled(setup, Psi)
    C = np.linalg.inv(S.T @ S)
    kc = classical(setup, postures)
    cond_psi = np.linalg.cond(Psi)
    rel_std = np.sqrt(np.diag(C))
    return {
        "classical": kc,
        "zhang2021": kc * cond_psi,
        "scaled_cond": np.linalg.cond(S),
        "d_optimal": np.linalg.det(C) ** (1.0 / 12.0),
        "relative_a": np.sqrt(np.mean(np.diag(C))),
        "test_pose_m": test_pose_with(setup, np.linalg.inv(Psi.T @ Psi)),
        "cond_psi": cond_psi,
        "predicted_deviation_pct": 100 * np.sqrt(2 / np.pi) * np.sqrt(setup["levels"])[:, None] * rel_std,
    }


# ---------------------------------------------------------------- identification

def identify(setup, rows):
    """Least-squares joint stiffness (Eq. 13-14) from measurement rows.

    rows: dict of arrays q (m, 6) rad, point (m,) 0-based, wrench (m, 6) N/Nm, delta (m, 3) metres.
    Returns (stiffness Nm/rad, compliance rad/Nm, cond(Psi)).
    """
    Psi = np.vstack([
        posture_block(setup, q, wrench=w, points=[k]) for q, k, w in zip(rows["q"], rows["point"], rows["wrench"])
    ])
    h, *_ = np.linalg.lstsq(Psi, rows["delta"].reshape(-1), rcond=None)
    return 1.0 / h, h, np.linalg.cond(Psi)


def solve(Psi, delta):
    """The least-squares step alone: h = argmin |Psi h - delta| (numpy.linalg.lstsq, SVD)."""
    return np.linalg.lstsq(Psi, delta, rcond=None)[0]


# ---------------------------------------------------------------- local search

def local_search(setup, start, criterion=zhang2021, maxiter=100):
    """SciPy SLSQP from a start group (n, 6) rad within the setup bounds, finite-difference gradient."""
    n = len(start)
    bounds = list(zip(np.tile(setup["lower"], n), np.tile(setup["upper"], n)))

    def objective(x):
        return criterion(setup, x.reshape(n, 6))

    res = minimize(objective, start.reshape(-1), method="SLSQP", bounds=bounds, options={"maxiter": maxiter})
    return res.x.reshape(n, 6), res
