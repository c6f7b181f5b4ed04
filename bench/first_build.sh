#!/usr/bin/env bash
# The first build of the command from a fresh clone, measured so that the load of the machine
# hardly matters: `cargo build --release --timings -p stiffid-cli` into an empty target directory,
# every rustc run wrapped to record its CPU time (user + system), then bench/first_build.py:
# the CPU sum, the critical path weighted by CPU time, and the wall time this work would take on
# two idle cores.
#
#   bash bench/first_build.sh [DIR]   # clones this checkout's HEAD into DIR (default /tmp/stiffid-first-build)
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
dir="${1:-/tmp/stiffid-first-build}"
if [ -e "$dir" ]; then echo "error: $dir exists: give a new directory" >&2; exit 2; fi
git clone -q "$here" "$dir"
git -C "$dir" checkout -q "$(git -C "$here" rev-parse HEAD)"
wrapper="$dir/rustc-cpu.sh"
cat > "$wrapper" <<'WRAP'
#!/bin/sh
# RUSTC_WRAPPER: appends "crate user_s system_s wall_s" of each compilation to $CPU_LOG.
rustc="$1"; shift
name=unknown; prev=
for a in "$@"; do
  [ "$prev" = "--crate-name" ] && name="$a"
  prev="$a"
done
case " $* " in *" - "*|*"--print"*) exec "$rustc" "$@";; esac
exec /usr/bin/time -a -o "$CPU_LOG" -f "$name %U %S %e" "$rustc" "$@"
WRAP
chmod +x "$wrapper"
uptime
(cd "$dir" && CARGO_TARGET_DIR="$dir/target" RUSTC_WRAPPER="$wrapper" CPU_LOG="$dir/cpu.log" \
  /usr/bin/time -f "wall %e s" cargo build --release --timings -p stiffid-cli)
uptime
python3 "$here/bench/first_build.py" "$dir" "$dir/target/cargo-timings/cargo-timing.html" "$dir/cpu.log"
