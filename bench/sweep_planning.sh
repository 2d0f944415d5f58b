#!/usr/bin/env bash
# Planning a sweep of many values (bench/README.md, "Planning a sweep"): times
#   particles sweep SWEEP.yaml -o OUT --emit parallel --quiet
# for sweeps of one parameter over N values on two scenes of 3,025 particles, each written here:
#   grid      scenarios/cloth.yaml at 55 × 55 (the grid section makes the particles and springs)
#   explicit  the same cloth written out: 3,025 particles and 5,940 springs, one entry each
# and the parameters
#   grid-kd         forces[1].kd      (the drag's coefficient: a kind entry's number)
#   grid-scale      grids[0].springs.structural.ks, scale: true (the example sweep's parameter)
#   grid-dt         dt                (the simulation section)
#   explicit-ks     forces[2].ks      (one spring's stiffness)
# Planning checks every value against the scenario and writes jobs.csv, a folder per job and
# jobs.txt; nothing runs. Prints for each its wall time, CPU time and peak memory (/usr/bin/time).
# Usage: bench/sweep_planning.sh [BUILD_DIR]              (default build)
#        COUNTS="1000 100000" CASES="grid-kd explicit-ks" bench/sweep_planning.sh ...
#        (defaults: COUNTS="1000 100000", every case)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
particles="$build/particles"
[ -x "$particles" ] || { echo "build $particles first (cmake --build $build --target particles)" >&2; exit 2; }
[ -x /usr/bin/time ] || { echo "needs /usr/bin/time (Debian: apt-get install time)" >&2; exit 2; }
counts="${COUNTS:-1000 100000}"
cases="${CASES:-grid-kd grid-scale grid-dt explicit-ks}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

# The report's cloth at 55 × 55, the mouse grabbing the new bottom middle.
sed -e 's/size: \[25, 25\]/size: [55, 55]/' -e 's/cloth\[24\]\[12\]/cloth[54][27]/' \
  "$root/scenarios/cloth.yaml" >"$tmp/grid.yaml"
# The same particles and structural springs written out one entry each (0.5 MB of YAML).
awk -v n=55 'BEGIN {
  print "name: explicit_cloth"
  print "simulation: {integrator: rk4, dt: 0.01, duration: 1}"
  print "particles:"
  for (r = 0; r < n; r++) for (c = 0; c < n; c++)
    printf "  - {name: p%d_%d, pos: [%.2f, %.2f], mass: 0.002%s}\n", r, c, c * 0.08, -r * 0.08, r == 0 ? ", fixed: true" : ""
  print "forces:"
  print "  - {type: gravity}"
  print "  - {type: drag, kd: 0.002}"
  for (r = 0; r < n; r++) for (c = 0; c < n; c++) {
    if (c + 1 < n) printf "  - {type: spring, a: p%d_%d, b: p%d_%d, ks: 25, kd: 0.01}\n", r, c, r, c + 1
    if (r + 1 < n) printf "  - {type: spring, a: p%d_%d, b: p%d_%d, ks: 25, kd: 0.01}\n", r, c, r + 1, c
  }
}' >"$tmp/explicit.yaml"

# sweep FILE SCENARIO PARAMETER COUNT: one parameter over COUNT values.
sweep() {
  printf 'scenarios: [%s]\ncommand: run\noptions: {duration: 0.1}\nparameters:\n  - %s\n' "$2" "$3" >"$1"
}

echo "machine: $(nproc) CPUs; $(uptime | sed 's/^ *//')"
for count in $counts; do
  for name in $cases; do
    case $name in
      grid-kd) sweep "$tmp/$name.yaml" grid.yaml "{key: 'forces[1].kd', range: {from: 0.001, to: 0.01, count: $count}}" ;;
      grid-scale)
        sweep "$tmp/$name.yaml" grid.yaml \
          "{key: 'grids[0].springs.structural.ks', scale: true, range: {from: 0.25, to: 16, count: $count, spacing: log}}"
        ;;
      grid-dt) sweep "$tmp/$name.yaml" grid.yaml "{key: dt, range: {from: 0.001, to: 0.01, count: $count}}" ;;
      explicit-ks) sweep "$tmp/$name.yaml" explicit.yaml "{key: 'forces[2].ks', range: {from: 1, to: 100, count: $count}}" ;;
      *) echo "unknown case $name" >&2; exit 2 ;;
    esac
    rm -rf "$tmp/out"
    /usr/bin/time -f '%e %U %S %M' -o "$tmp/time" "$particles" sweep "$tmp/$name.yaml" -o "$tmp/out" --emit parallel \
      --quiet >"$tmp/log" 2>&1 || { cat "$tmp/log" >&2; echo "$name ($count values) failed" >&2; exit 1; }
    read -r wall user sys kb <"$tmp/time"
    printf '%-12s %7d values: %8.2f s wall, %8.2f s user, %6.2f s system, peak memory %4d MiB, jobs.csv %d bytes\n' \
      "$name" "$count" "$wall" "$user" "$sys" $((kb / 1024)) "$(stat -c %s "$tmp/out/jobs.csv")"
  done
done
echo "after: $(uptime | sed 's/^ *//')"
