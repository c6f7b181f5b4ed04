"""Command line of the NumPy/SciPy baseline: the same work as stiffid, as JSON, with timeit medians.

    python baseline.py evaluate --setup S.toml --postures P.csv [--time]
    python baseline.py identify --setup S.toml --data D.csv [--time]
    python baseline.py select   --setup S.toml --start P.csv [--time]
    python baseline.py synth    --setup S.toml --postures P.csv --seed N [--level M]   (CSV to stdout)

Postures CSV: posture,q1_deg..q6_deg. Measurement CSV (stiffid's format): posture,point (1-based),
q1_deg..q6_deg,fx_n,fy_n,fz_n[,mx_nm,my_nm,mz_nm],dx_mm,dy_mm,dz_mm (loaded minus unloaded).
Timings are medians over repeats of `timeit` (each repeat long enough to be measurable), in seconds
per call.
"""

import argparse
import csv
import json
import sys
import time
import timeit

import numpy as np

import model

Q = [f"q{i}_deg" for i in range(1, 7)]


def read_postures(path):
    with open(path, newline="") as f:
        return np.radians([[float(r[c]) for c in Q] for r in csv.DictReader(f)])


def read_measurements(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    moment = [c for c in ("mx_nm", "my_nm", "mz_nm")]
    return {
        "q": np.radians([[float(r[c]) for c in Q] for r in rows]),
        "point": np.array([int(r["point"]) - 1 for r in rows]),
        "wrench": np.array([[float(r[c]) for c in ("fx_n", "fy_n", "fz_n")]
                            + [float(r.get(c) or 0.0) for c in moment] for r in rows]),
        "delta": np.array([[float(r[c]) for c in ("dx_mm", "dy_mm", "dz_mm")] for r in rows]) * 1e-3,
    }


def median_time(fn, repeat):
    """Median seconds per call over `repeat` repeats of a timeit loop of at least 0.2 s."""
    timer = timeit.Timer(fn)
    number, _ = timer.autorange()
    return float(np.median(timer.repeat(repeat=repeat, number=number))) / number


def cmd_evaluate(a, setup):
    P = read_postures(a.postures)
    e = model.evaluate(setup, P)
    out = {k: v for k, v in e.items() if k not in ("test_pose_m", "predicted_deviation_pct")}
    out["test_pose_mm"] = e["test_pose_m"] * 1e3
    out["predicted_deviation_pct"] = e["predicted_deviation_pct"].tolist()
    if a.time:
        out["time_s"] = {name: median_time(lambda f=f: f(setup, P), a.repeat) for name, f in model.CRITERIA.items()}
        out["time_s"]["evaluate"] = median_time(lambda: model.evaluate(setup, P), a.repeat)
    return out


def cmd_identify(a, setup):
    rows = read_measurements(a.data)
    k, h, cond = model.identify(setup, rows)
    out = {"stiffness_nm_per_rad": k.tolist(), "compliance_rad_per_nm": h.tolist(), "cond_psi": cond,
           "rows": 3 * len(rows["q"])}
    if a.time:
        Psi = np.vstack([model.posture_block(setup, q, wrench=w, points=[p])
                         for q, p, w in zip(rows["q"], rows["point"], rows["wrench"])])
        delta = rows["delta"].reshape(-1)
        out["time_s"] = {
            "lstsq": median_time(lambda: model.solve(Psi, delta), a.repeat),
            "identify": median_time(lambda: model.identify(setup, rows), a.repeat),
        }
    return out


def cmd_select(a, setup):
    start = read_postures(a.start)
    t0 = time.perf_counter()
    best, res = model.local_search(setup, start)
    elapsed = time.perf_counter() - t0
    out = {
        "criterion": "zhang2021",
        "before": model.zhang2021(setup, start),
        "after": float(res.fun),
        "evaluations": int(res.nfev),
        "iterations": int(res.nit),
        "message": res.message,
        "postures_deg": np.degrees(best).tolist(),
        "within_bounds": bool(np.all(best >= setup["lower"]) and np.all(best <= setup["upper"])),
    }
    if a.time:
        runs = [elapsed] + [timeit.timeit(lambda: model.local_search(setup, start), number=1)
                            for _ in range(a.repeat - 1)]
        out["time_s"] = {"local_search": float(np.median(runs))}
    return out


def cmd_synth(a, setup):
    """Rope-mass measurements of the postures with the setup's nominal stiffness plus seeded noise."""
    P = read_postures(a.postures)
    rng = np.random.default_rng(a.seed)
    w = csv.writer(sys.stdout, lineterminator="\n")
    w.writerow(["posture", "point"] + Q + ["fx_n", "fy_n", "fz_n", "dx_mm", "dy_mm", "dz_mm"])
    h = 1.0 / setup["k_nominal"]
    for i, q in enumerate(P):
        Z, O, flange = model.forward(setup["robot"], q)
        wrench = model.rope_wrench(setup, model.point_position(flange, setup["loading_point"]))
        delta = (model.posture_block(setup, q, wrench=wrench) @ h).reshape(-1, 3)
        delta += rng.normal(0.0, setup["sigma"] * np.sqrt(a.level), delta.shape)
        for k, d in enumerate(delta):
            w.writerow([i + 1, k + 1] + [repr(float(v)) for v in np.degrees(q)]
                       + [repr(float(v)) for v in wrench[:3]] + [repr(float(v)) for v in d * 1e3])
    return None


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", required=True)
    for name, files in [("evaluate", ["--postures"]), ("identify", ["--data"]), ("select", ["--start"]),
                        ("synth", ["--postures"])]:
        s = sub.add_parser(name)
        s.add_argument("--setup", required=True)
        for f in files:
            s.add_argument(f, required=True)
        s.add_argument("--time", action="store_true", help="add timeit medians (s) under time_s")
        s.add_argument("--repeat", type=int, default=15 if name != "select" else 3)
        if name == "synth":
            s.add_argument("--seed", type=int, required=True)
            s.add_argument("--level", type=float, default=1.0, help="noise level multiple")
    a = p.parse_args()
    setup = model.load_setup(a.setup)
    out = {"evaluate": cmd_evaluate, "identify": cmd_identify, "select": cmd_select, "synth": cmd_synth}[a.command](a, setup)
    if out is not None:
        json.dump(out, sys.stdout, indent=1, default=float)
        print()


if __name__ == "__main__":
    main()
