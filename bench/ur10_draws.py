"""The real UR10's held-out figures of docs/performance.md: `stiffid calibrate` on seeded draws of
series C of the Fraunhofer IPA UR10 tracker data (C. Landgraf, K. Ernst, G. Schleth, M. Fabritius,
M. F. Huber, IEEE CASE 2021; repository christianlandgraf/ipa-robot-accuracy, MIT License; not
shipped here: point the script at your copy).

    python3 bench/ur10_draws.py DATA_DIR WORK_DIR [--poses 100] [--draws 10] [--stiffid PATH]
        [-- calibrate options...]

DATA_DIR holds Series_C/measurements_random_poses.csv. WORK_DIR gets the UR10's robot file
(Universal Robots' standard DH table, joints within +-360 deg), a setup from `stiffid setups new`
with one measuring point 109 mm along the flange axis (the T-Mac) and a tracker noise of
0.03 mm, and per draw `drawK/fit.csv` (the poses fitted: the first `--poses` of series C's 2773
shuffled by Python's `random.Random(K)`, so a larger draw holds the smaller one of the same K)
and `drawK/held.csv` (the others). Each draw is calibrated with `--validate` on its held-out
poses and the options after `--`; the script prints each draw's held-out RMS, the model fitted,
the intervals' coverage (held-out coordinates inside their intervals), the widest interval's
farthest end against the largest held-out error, and the CPU time (user + system) of the run,
then the mean and worst and the coverage pooled over the draws' coordinates.

With `--explicit N` it also calibrates each draw with the model fitted given explicitly
(`--gravity` and `--maps` of the rung chosen, the same `--validate`), prints the largest
difference of the two fits' parameters (SI) and of their held-out RMS, and then times both
without `--validate`, alternated N times: the least CPU time of each and their ratio.
"""
import argparse
import csv
import json
import math
import os
import random
import resource
import subprocess
import sys

ROBOT = """name = "UR10"
source = "Universal Robots UR10 (CB series) standard DH table"
convention = "standard-dh"
""" + "".join(
    f"""
[[joint]]
a_mm = {a}
alpha_deg = {alpha}
d_mm = {d}
lower_deg = -360.0
upper_deg = 360.0
"""
    for a, alpha, d in [
        (0.0, 90.0, 127.3),
        (-612.0, 0.0, 0.0),
        (-572.3, 0.0, 0.0),
        (0.0, 90.0, 163.941),
        (0.0, -90.0, 115.7),
        (0.0, 0.0, 92.2),
    ]
)

HEADER = "posture,point,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,x_tracker_mm,y_tracker_mm,z_tracker_mm\n"
JOINTS = ["shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint", "wrist_1_joint", "wrist_2_joint", "wrist_3_joint"]


def rows(data_dir):
    """Series C's poses: joint angles (deg) and the T-Mac's tracker position (mm)."""
    path = os.path.join(data_dir, "Series_C", "measurements_random_poses.csv")
    with open(path) as f:
        r = csv.reader(f, delimiter=";")
        ix = {h: i for i, h in enumerate(next(r))}
        for row in r:
            v = lambda h: float(row[ix[h]].replace(",", "."))
            yield [math.degrees(v(j)) for j in JOINTS], [v("measurement_" + c) for c in "xyz"]


def setup(work, stiffid):
    """The robot file and the setup in `work`."""
    with open(os.path.join(work, "ur10.toml"), "w") as f:
        f.write(ROBOT)
    text = subprocess.run(
        [stiffid, "setups", "new", "--robot", "ur10.toml", "--payload-kg", "10"],
        capture_output=True, text=True, check=True, cwd=work,
    ).stdout
    lines, skip = [], False
    for line in text.splitlines():
        if line.startswith("measuring_points_mm"):
            lines.append("measuring_points_mm = [[0.0, 0.0, 109.0]]")
            skip = not line.rstrip().endswith("]")
            continue
        if skip:
            skip = line.strip() != "]"
            continue
        if line.startswith("reading_sd_mm"):
            line = "reading_sd_mm = 0.03"
        lines.append(line)
    with open(os.path.join(work, "setup.toml"), "w") as f:
        f.write("\n".join(lines) + "\n")


def draw(poses, work, k, n):
    """Draw `k`'s fitted and held-out readings files."""
    order = list(range(len(poses)))
    random.Random(k).shuffle(order)
    d = os.path.join(work, f"draw{k}")
    os.makedirs(d, exist_ok=True)
    for name, chosen in (("fit.csv", sorted(order[:n])), ("held.csv", sorted(order[n:]))):
        with open(os.path.join(d, name), "w") as f:
            f.write(HEADER)
            for i in chosen:
                q, m = poses[i]
                f.write(f"P{i + 1},1," + ",".join(repr(x) for x in q + m) + "\n")
    return d


def calibrate(stiffid, work, d, options, validate=True):
    """The document of one run and its CPU time, s."""
    held = ["--validate", os.path.join(d, "held.csv")] if validate else []
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    out = subprocess.run(
        [stiffid, "calibrate", "--setup", os.path.join(work, "setup.toml"), "--data", os.path.join(d, "fit.csv"),
         "--json"] + held + options,
        capture_output=True, text=True, check=True,
    ).stdout
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return json.loads(out), (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def farthest_end(validation):
    """The farthest finite end of the held-out coordinates' intervals from zero, mm; None without."""
    ends = [abs(e) for p in validation["errors"] for c in (p["interval_mm"] or []) for e in c if e is not None]
    return max(ends, default=None)


def without(options, names):
    """`options` without the options `names` and their values."""
    at = [j for j, o in enumerate(options) if o in names]
    return [o for j, o in enumerate(options) if j not in at and j - 1 not in at]


def explicit(stiffid, work, d, doc, options, repeats):
    """The model `doc` fitted, given explicitly: its fit against `doc`'s, and both runs' least CPU
    time without `--validate` over `repeats` alternated runs."""
    given = without(options, ("--gravity", "--maps"))
    model = ["--gravity", doc["gravity"], "--maps", doc["maps"]["chosen"]]
    other, _ = calibrate(stiffid, work, d, given + model)
    mine = {p["name"]: p["value"] for p in doc["parameters"]}
    theirs = {p["name"]: p["value"] for p in other["parameters"]}
    apart = max((abs(v - theirs[n]) for n, v in mine.items()), default=0.0) if mine.keys() == theirs.keys() else math.inf
    cpu = [[], []]
    for _ in range(repeats):
        cpu[0].append(calibrate(stiffid, work, d, without(options, ("--level",)), validate=False)[1])
        cpu[1].append(calibrate(stiffid, work, d, without(given, ("--level",)) + model, validate=False)[1])
    held = abs(other["validation"]["rms_mm"] - doc["validation"]["rms_mm"])
    return (f"; given explicitly ({' '.join(model)}): parameters apart by {apart:.3g} (SI), held-out RMS by {held:.2g} mm; "
            f"CPU without --validate {min(cpu[0]):.2f} s against {min(cpu[1]):.2f} s, {min(cpu[0]) / min(cpu[1]):.2f} times")


def main():
    argv = sys.argv[1:]
    options = argv[argv.index("--") + 1:] if "--" in argv else []
    argv = argv[: argv.index("--")] if "--" in argv else argv
    p = argparse.ArgumentParser()
    p.add_argument("data_dir")
    p.add_argument("work_dir")
    p.add_argument("--poses", type=int, default=100)
    p.add_argument("--draws", type=int, default=10)
    p.add_argument("--stiffid", default="stiffid")
    p.add_argument("--explicit", type=int, default=0)
    a = p.parse_args(argv)
    a.stiffid = os.path.abspath(a.stiffid) if os.sep in a.stiffid else a.stiffid
    os.makedirs(a.work_dir, exist_ok=True)
    setup(a.work_dir, a.stiffid)
    poses = list(rows(a.data_dir))
    figures, pooled = [], [0, 0]
    for k in range(1, a.draws + 1):
        d = draw(poses, a.work_dir, k, a.poses)
        doc, cpu = calibrate(a.stiffid, a.work_dir, d, options)
        v = doc["validation"]
        i = v.get("intervals") or {}
        ladder = doc.get("ladder")
        model = doc["gravity"]
        if ladder:
            r = ladder["rungs"][ladder["chosen"]]
            model = r["gravity"] + (" + maps" if r["maps"] else "")
        figures.append(v["rms_mm"])
        pooled[0] += i.get("covered") or 0
        pooled[1] += i.get("coordinates") or 0
        end = farthest_end(v)
        bound = f"farthest end {end:.3f} mm, {end / v['max_mm']:.2f} times the largest error" if end else "no finite end"
        more = explicit(a.stiffid, a.work_dir, d, doc, options, a.explicit) if a.explicit else ""
        print(
            f"draw {k}: held out RMS {v['rms_mm']:.4f} mm (max {v['max_mm']:.3f}); {model}, maps {doc['maps'].get('chosen')}; "
            f"{i.get('level')} intervals cover {i.get('covered')} of {i.get('coordinates')} coordinates ({bound}); CPU {cpu:.2f} s{more}",
            flush=True,
        )
    print(f"mean {sum(figures) / len(figures):.4f} mm, worst {max(figures):.4f} mm over {len(figures)} draws", end="")
    print(f"; intervals cover {pooled[0]} of {pooled[1]} held-out coordinates pooled ({100 * pooled[0] / pooled[1]:.2f} %)" if pooled[1] else "")


if __name__ == "__main__":
    main()
