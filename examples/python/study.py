#!/usr/bin/env python3
"""The paper's study and the FANUC data from Python, with the `stiffid` package.

1. Runs the simulation study of Zhang et al. (IEEE Access 2021) on the built-in paper setup
   (the same numbers as `stiffid reproduce`): five groups of postures, 200 Monte Carlo runs per
   group and noise level, and prints each group's average deviation rate and the findings.
2. Plots the paper's Fig. 8 (mean deviation rate against noise level, one panel per joint, one
   line per group) into fig8.png, if matplotlib is installed.
3. Identifies the joint stiffness of the FANUC R-2000iC/165F from its real measurements
   (examples/data/fanuc-r2000ic-165f/measurements.csv) with 95% confidence intervals.

Install the package first (from the repository root): pip install ./crates/stiffid-py
Usage: python examples/python/study.py [--runs N] [--out fig8.png]
"""

import argparse
from pathlib import Path

import numpy as np

import stiffid

DATA = Path(__file__).resolve().parents[1] / "data" / "fanuc-r2000ic-165f" / "measurements.csv"


def study(runs: int) -> dict:
    s = stiffid.reproduce(runs=runs, seed=1)  # the document of summary.json, arrays as NumPy arrays
    print(f"The paper's study: {runs} runs per group and noise level, seed 1, {s['elapsed_s']:.1f} s")
    for group in s["groups"]:
        print(f"  {group['title']:<30} relative-a {group['relative_a']:.5f}  "
              f"average deviation rate {group['average_deviation_pct']:.3f}%")
    f = s["findings"]
    print(
        f"  Group 3 (the paper's procedure) beats Groups 1 and 2: {f['group3_beats_groups_1_and_2']} "
        f"({f['group3_factor_vs_group1']:.2f}x and {f['group3_factor_vs_group2']:.2f}x lower); "
        f"the global relative-a group is {f['relative_a_factor_vs_group3']:.2f}x lower still"
    )
    return s


def plot_fig8(s: dict, out: Path) -> None:
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed: no figure (pip install matplotlib)")
        return
    rates = np.array([g["mean_deviation_pct"] for g in s["groups"]])  # (groups, levels, 6), percent
    predicted = np.array([g["predicted_deviation_pct"] for g in s["groups"]])
    levels = np.arange(1, len(s["levels"]) + 1)
    fig, axes = plt.subplots(2, 3, figsize=(12, 7), sharex=True)
    for joint, ax in enumerate(axes.flat):
        for g, title in enumerate(group["title"] for group in s["groups"]):
            line = ax.plot(levels, rates[g, :, joint], marker="o", label=title)[0]
            ax.plot(levels, predicted[g, :, joint], ls=":", color=line.get_color())
        ax.set_title(f"joint {joint + 1}")
        ax.set_xlabel("noise level")
        ax.set_ylabel("mean deviation rate, %")
    axes.flat[0].legend(fontsize=7)
    fig.suptitle("Fig. 8: mean deviation rate (dotted: first-order prediction)")
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    print(f"Fig. 8 written to {out}")


def fanuc() -> None:
    setup = stiffid.Setup.builtin("fanuc-r2000ic-165f")
    result = stiffid.identify(setup, DATA)  # the identify document, its numbers as NumPy arrays
    ci = result["ci95_nm_per_rad"]  # None only for exactly six rows (no degrees of freedom)
    assert ci is not None
    print(f"FANUC R-2000iC/165F, {result['postures']} postures ({result['rows']} rows), least squares by QR:")
    for j in range(6):
        k = result["stiffness_nm_per_rad"][j]
        lo, hi = ci[j]
        print(f"  k{j + 1} = {k:12.0f} Nm/rad   95% CI [{lo:.0f}, {hi:.0f}]")
    print(f"  residual RMS {result['residual_rms_mm']:.4f} mm, cond(Psi) {result['cond_psi']:.1f}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=200, help="Monte Carlo runs (the paper: 200)")
    parser.add_argument("--out", type=Path, default=Path("fig8.png"), help="where to write Fig. 8")
    args = parser.parse_args()
    plot_fig8(study(args.runs), args.out)
    fanuc()


if __name__ == "__main__":
    main()
