#!/usr/bin/env python3
"""The cost of one `Setup.evaluate` call from Python against the Rust bench of the same work.

Times `setup.evaluate(group)` with `timeit` (the built-in paper setup, `group` its seeded random
group of 6 postures, seed 1: the group of the `design` bench) and runs the criterion bench
`design/evaluate/all/6x4` (`stiffid::design::evaluate` on that group), then prints both medians
and their ratio. The Python call also converts the postures, checks that the group identifies
every joint (a QR of Psi, as `stiffid evaluate` does) and builds the dict and arrays.

Usage (from the repository root, with the package installed, e.g. by .ci/test's venv):
    python crates/stiffid-py/bench/evaluate_overhead.py [--no-rust]
Timings depend on the load of the machine: the script prints `uptime` first.
"""

import argparse
import re
import statistics
import subprocess
import timeit
from pathlib import Path

import stiffid

REPO = Path(__file__).resolve().parents[3]
BENCH = "design/evaluate/all/6x4"


def python_median_us(repeats: int = 21) -> float:
    setup = stiffid.Setup.builtin("zhang2021-comau-nj165")
    group = setup.random_group(6, 1)
    timer = timeit.Timer(lambda: setup.evaluate(group))
    number, _ = timer.autorange()
    times = [t / number for t in timer.repeat(repeat=repeats, number=number)]
    return statistics.median(times) * 1e6


def rust_median_us() -> float:
    """The middle estimate of criterion's `time: [low mid high]` line."""
    out = subprocess.run(
        ["cargo", "bench", "-q", "-p", "stiffid", "--bench", "design", "--", BENCH, "--exact"],
        cwd=REPO, check=True, capture_output=True, text=True,
    ).stdout
    match = re.search(r"time:\s+\[\S+ \S+ (\S+) (\S+)", out)
    if not match:
        raise SystemExit(f"no criterion time in the bench output:\n{out}")
    value, unit = float(match.group(1)), match.group(2)
    return value * {"ns": 1e-3, "µs": 1.0, "us": 1.0, "ms": 1e3}[unit]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--no-rust", action="store_true", help="skip the criterion bench")
    args = parser.parse_args()
    print("load:", subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())
    py = python_median_us()
    print(f"Python setup.evaluate(group), 6 postures x 4 points: {py:.1f} us (timeit median)")
    if not args.no_rust:
        rust = rust_median_us()
        print(f"Rust bench {BENCH}: {rust:.1f} us (criterion median)")
        print(f"ratio Python / Rust: {py / rust:.2f}")


if __name__ == "__main__":
    main()
