"""Writes a large measurement CSV for the identification scaling measurement (docs/performance.md).

Each row is one posture of the FANUC R-2000iC/165F data set (examples/data/fanuc-r2000ic-165f),
cycled, with its axis angles shifted by a small deterministic amount so that every row is its own
posture with its own label (the worst case for posture bookkeeping). Standard library only.

    python3 bench/large_measurements.py ROWS OUT.csv
"""

import sys
from pathlib import Path

SOURCE = Path(__file__).resolve().parent.parent / "examples/data/fanuc-r2000ic-165f/measurements.csv"


def main() -> None:
    rows, out = int(sys.argv[1]), Path(sys.argv[2])
    lines = SOURCE.read_text().splitlines()
    header, data = lines[0], [l.split(",") for l in lines[1:] if l and not l.startswith("#")]
    with out.open("w") as f:
        f.write(header + "\n")
        for i in range(rows):
            src = data[i % len(data)]
            shift = 1e-4 * (i // len(data))
            q = [f"{float(v) + shift:.4f}" for v in src[2:8]]
            f.write(",".join([f"p{i}", src[1], *q, *src[8:]]) + "\n")


if __name__ == "__main__":
    main()
