"""Agreement checks and the speed table of bench/compare.sh.

    python bench/report.py OUT_DIR CRITERION_DIR

OUT_DIR holds the JSON written by the baseline (py-*.json) and by the stiffid CLI (rs-*.json);
CRITERION_DIR is cargo's target/criterion. Exits 1 if the two implementations disagree.
"""

import json
import sys
from pathlib import Path

REL = 1e-9  # agreement tolerance, relative
CRITERIA = ["classical", "zhang2021", "scaled_cond", "d_optimal", "relative_a", "test_pose_mm", "cond_psi"]

# (label, Rust criterion bench id, Python timing (file, key) or None, target median s, target ratio)
NAMES = ["classical", "zhang2021", "scaled-cond", "d-optimal", "relative-a", "test-pose"]
ROWS = [
    (f"criterion evaluation, {name}, 6 postures x 4 points", f"design_evaluate_{name}_6x4", ("evaluate", name), 4e-6, 1000)
    for name in NAMES
] + [
    (f"criterion and its exact gradient, {name}", f"design_gradient_{name}_6x4", None, 25e-6, None)
    for name in NAMES
] + [
    ("every criterion + predicted rates (stiffid evaluate)", "design_evaluate_all_6x4", ("evaluate", "evaluate"), None, None),
    ("least squares alone, 72 x 6 (QR factor and solve; numpy.linalg.lstsq)", "compare/lstsq", ("identify", "lstsq"), None, None),
    ("identification 72 x 6 with statistics (bench identify)", "identify_72x6 least squares and statistics", None, 5e-6, None),
    ("identification from the 24 measurement rows", "compare/identify", ("identify", "identify"), None, None),
    ("local search, zhang2021, SLSQP from the start group, exact gradient", "compare/local-search", ("select", "local_search"), 10e-3, 2000),
    ("local search, zhang2021, our SQP (--solver active-set) from the start group, exact gradient", "compare/local-search-active-set", ("select", "local_search"), 10e-3, 2000),
    ("local search, zhang2021, from the start group, finite differences", "compare/local-search-fd", ("select", "local_search"), None, None),
    ("default global search, relative-a (bench design)", "design_search/global_relative-a_default", None, 0.3, None),
    ("default global search, relative-a, finite differences", "design_search/global-fd_relative-a_default", None, None, None),
    ("Monte Carlo of reproduce (5 groups x 6 levels x 200 runs)", "monte-carlo/reproduce-5x6x200", None, 50e-3, None),
]


def load(out, name):
    path = out / f"{name}.json"
    return json.loads(path.read_text()) if path.exists() else None


def median_s(criterion_dir, bench_id):
    path = criterion_dir / bench_id / "new" / "estimates.json"
    if not path.exists():
        return None
    return json.loads(path.read_text())["median"]["point_estimate"] * 1e-9


def rel(a, b):
    return abs(a - b) / max(abs(a), abs(b), 1e-300)


def check(out):
    """Print the agreement checks; return True if all pass."""
    ok = True

    def line(what, passed, detail):
        nonlocal ok
        ok &= passed
        print(f"  {'ok  ' if passed else 'FAIL'} {what}: {detail}")

    print("Agreement (stiffid CLI vs NumPy/SciPy baseline, same inputs)")
    py, rs = load(out, "py-evaluate"), load(out, "rs-evaluate")
    if py and rs:
        for k in CRITERIA:
            r = rel(py[k], rs[k])
            line(k, r <= REL, f"stiffid {rs[k]:.12g}, numpy {py[k]:.12g}, rel diff {r:.1e}")
        r = max(rel(a, b) for pa, ra in zip(py["predicted_deviation_pct"], rs["predicted_deviation_pct"])
                for a, b in zip(pa, ra))
        line("predicted_deviation_pct", r <= REL, f"max rel diff {r:.1e}")
    else:
        print("  (skipped: stiffid evaluate output missing)")
    py, rs = load(out, "py-identify"), load(out, "rs-identify")
    if py and rs:
        r = max(rel(a, b) for a, b in zip(py["stiffness_nm_per_rad"], rs["stiffness_nm_per_rad"]))
        line("identified stiffness", r <= REL, f"max rel diff {r:.1e} over 6 joints")
    else:
        print("  (skipped: stiffid identify output missing)")
    py, rs = load(out, "py-select"), load(out, "rs-select")
    if py and rs:
        after = rs["value"]
        line("local search result", after <= py["after"] * (1 + REL),
             f"zhang2021 from {py['before']:.6g}: stiffid {after:.6g}, SciPy SLSQP {py['after']:.6g} "
             f"({py['evaluations']} evaluations, {py['message']})")
    else:
        print("  (skipped: stiffid select output missing)")
    return ok


def fmt_s(s):
    if s is None:
        return "-"
    for unit, f in (("s", 1), ("ms", 1e-3), ("us", 1e-6)):
        if s >= f:
            return f"{s / f:.3g} {unit}"
    return f"{s / 1e-9:.3g} ns"


def table(out, criterion_dir, extra):
    print("\nMedians (stiffid: criterion; NumPy/SciPy: timeit)")
    head = ["work", "stiffid", "NumPy/SciPy", "ratio", "target"]
    rows = []
    for label, bench_id, py_key, target_s, target_ratio in ROWS:
        rs = median_s(criterion_dir, bench_id)
        py = None
        if py_key:
            data = load(out, f"py-{py_key[0]}")
            py = data and data.get("time_s", {}).get(py_key[1])
        ratio = f"{py / rs:.0f}x" if (py and rs) else "-"
        goal = " and ".join(x for x in [target_s and f"<= {fmt_s(target_s)}",
                                        target_ratio and f">= {target_ratio}x"] if x) or "-"
        miss = (target_s and rs and rs > target_s) or (target_ratio and py and rs and py / rs < target_ratio)
        rows.append([label, fmt_s(rs), fmt_s(py), ratio, goal + (" (missed)" if miss else "")])
    for label, s, target_s in extra:
        rows.append([label, fmt_s(s), "-", "-", f"<= {fmt_s(target_s)}" + (" (missed)" if s > target_s else "")])
    widths = [max(len(r[i]) for r in rows + [head]) for i in range(5)]
    for r in [head, ["-" * w for w in widths]] + rows:
        print("| " + " | ".join(c.ljust(w) for c, w in zip(r, widths)) + " |")


SCALING = [
    ("criterion evaluation (every criterion)", "scaling-evaluate", [6, 24, 96, 384], "posture", 1),
    ("identification (QR factor and solve)", "scaling-identify", [6, 24, 96, 384], "posture", 1),
    ("Monte Carlo, 1 group x 6 levels", "monte-carlo", [200, 2000, 20000], "identification (run x level)", 6),
]


def scaling(criterion_dir):
    """How the cost grows: median and cost per unit, relative to the smallest size."""
    print("\nScaling (stiffid, criterion medians)")
    for label, prefix, sizes, unit, per_size in SCALING:
        medians = [median_s(criterion_dir, f"{prefix}/{n}") for n in sizes]
        if None in medians:
            print(f"  {label}: (not measured)")
            continue
        per = [m / (n * per_size) for m, n in zip(medians, sizes)]
        cells = ", ".join(f"{n}: {fmt_s(m)} ({fmt_s(p)} per {unit}, x{p / per[0]:.2f})"
                          for n, m, p in zip(sizes, medians, per))
        print(f"  {label}: {cells}")


def main():
    out, criterion_dir = Path(sys.argv[1]), Path(sys.argv[2])
    ok = check(out)
    extra = []
    e2e = load(out, "rs-reproduce-time")
    if e2e:
        extra.append(("stiffid reproduce, end to end (wall clock)", e2e["elapsed_s"], 0.5))
    table(out, criterion_dir, extra)
    scaling(criterion_dir)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
