#!/usr/bin/env bash
# A million particles (bench/README.md, "A million particles"): times
#   particles run    scenarios/cloth_million.yaml                     (1 s: 6000 steps)
#   particles render scenarios/cloth_million.yaml -o cloth_million.mp4 --particle-radius 0.1px
#                                                                     (1 s: 60 frames, MP4)
# with /usr/bin/time, and prints for each its wall time, CPU time (user, system), peak memory
# (maximum resident set size) and the steps and frames it reports, after the machine's load
# (`uptime`) and the thread count. Peak memory must stay under 2 GB (the target).
# Usage: bench/million.sh [BUILD_DIR] [THREADS]     (default build, the default --threads)
#        OUT=dir bench/million.sh ...               keep the video in dir (default: a temporary one)
# Each command takes minutes on the 2-core machine; run it with `nice` if others share it.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
threads=()
if [ -n "${2:-}" ]; then threads=(--threads "$2"); fi
particles="$build/particles"
[ -x "$particles" ] || { echo "build $particles first (cmake --build $build --target particles)" >&2; exit 2; }
[ -x /usr/bin/time ] || { echo "needs /usr/bin/time (Debian: apt-get install time)" >&2; exit 2; }
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
out="${OUT:-$tmp}"
mkdir -p "$out"
scenario="$root/scenarios/cloth_million.yaml"

echo "machine: $(nproc) CPUs; $(uptime | sed 's/^ *//')"
echo "threads: ${2:-default (PARTICLES_THREADS, else one per CPU this process may use)}"
# Prints the command's summary lines that say what it did, then its time and memory.
timed() {
  local name=$1
  shift
  /usr/bin/time -f '%e %U %S %M' -o "$tmp/$name.time" "$@" >"$tmp/$name.log" 2>&1 || {
    cat "$tmp/$name.log" >&2
    echo "$name failed" >&2
    exit 1
  }
  read -r wall user sys kb <"$tmp/$name.time"
  grep -E '^(steps|simulated time|wall time) |frames \(' "$tmp/$name.log" | sed "s/^/$name: /"
  printf '%s: %.1f s wall, %.1f s user, %.1f s system, peak memory %d MiB (%s KB)\n' "$name" "$wall" "$user" "$sys" \
    $((kb / 1024)) "$kb"
}
timed run "$particles" run "$scenario" "${threads[@]}"
timed render "$particles" render "$scenario" -o "$out/cloth_million.mp4" --particle-radius 0.1px "${threads[@]}"
echo "after: $(uptime | sed 's/^ *//')"
