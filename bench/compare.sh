#!/usr/bin/env bash
# stiffid against the NumPy/SciPy baseline a user would write (bench/baseline), on identical inputs:
# the built-in paper setup, the start group bench/inputs/start-group.csv and the synthetic
# measurements bench/inputs/measurements.csv. Checks that both give the same numbers, then prints the
# medians and speed ratios. Not part of CI (it installs NumPy and SciPy from PyPI).
#
#   bash bench/compare.sh            # everything (about 10 minutes on 2 cores)
#   QUICK=1 bash bench/compare.sh    # shorter timing runs (noisier)
#
# Scratch output goes to target/compare; timings depend on the load of the machine (see `uptime`).
set -euo pipefail
cd "$(dirname "$0")/.."

setup_name=zhang2021-comau-nj165
setup=crates/stiffid-core/setups/$setup_name.toml
start=bench/inputs/start-group.csv
data=bench/inputs/measurements.csv
out=target/compare
venv=bench/.venv
mkdir -p "$out"
rm -f "$out"/*.json

echo "== load: $(uptime)" >&2
echo "== Python environment ($venv)" >&2
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
"$venv/bin/pip" install -q -r bench/baseline/requirements.txt
py=("$venv/bin/python" bench/baseline/baseline.py)

echo "== building stiffid (release)" >&2
cargo build --release -q -p stiffid-cli
stiffid=target/release/stiffid
has() { "$stiffid" help "$1" >/dev/null 2>&1; }

echo "== stiffid CLI on the inputs" >&2
if has evaluate; then
  "$stiffid" evaluate --setup "$setup_name" --postures "$start" --json >"$out/rs-evaluate.json"
fi
if has identify; then
  "$stiffid" identify --setup "$setup_name" --data "$data" --json >"$out/rs-identify.json"
fi
if has select; then
  "$stiffid" select --setup "$setup_name" --criterion zhang2021 --start "$start" \
    --out "$out/rs-selected.csv" --json >"$out/rs-select.json"
fi
if has reproduce; then
  t0=$(date +%s.%N)
  "$stiffid" reproduce --out "$out/report" --force >/dev/null
  t1=$(date +%s.%N)
  awk -v a="$t0" -v b="$t1" 'BEGIN { printf "{\"elapsed_s\": %.6f}\n", b - a }' >"$out/rs-reproduce-time.json"
fi

echo "== stiffid criterion benches" >&2
if [ -n "${QUICK:-}" ]; then times=(--warm-up-time 1 --measurement-time 2); else times=(); fi
for bench in compare design identify scaling; do
  cargo bench -q -p stiffid-bench --bench "$bench" -- --save-baseline compare "${times[@]}" >&2
done

echo "== NumPy/SciPy baseline (timeit)" >&2
repeat=$([ -n "${QUICK:-}" ] && echo 5 || echo 15)
"${py[@]}" evaluate --setup "$setup" --postures "$start" --time --repeat "$repeat" >"$out/py-evaluate.json"
"${py[@]}" identify --setup "$setup" --data "$data" --time --repeat "$repeat" >"$out/py-identify.json"
"${py[@]}" select --setup "$setup" --start "$start" --time --repeat 3 >"$out/py-select.json"

echo "== load: $(uptime)" >&2
echo
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
"$venv/bin/python" bench/report.py "$out" target/criterion
