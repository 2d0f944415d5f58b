#!/usr/bin/env bash
# Everything the large-scene targets ask of a GPU server, in one run, most important first, within a time budget
# (a lent machine is held for minutes): the core's benchmarks on 1–16 threads, the server table's
# target rows, the GPU path against the golden references (golden check --gpu), the same bytes on
# every thread count, golden check through OSMesa, then the table's remaining cells while time is
# left. Prints as it goes; bench/README.md ("Large scenes on large servers") says how to read it.
#
# Usage (from the checkout, whose scenarios and golden/ it uses):
#   PARTICLES=bundle/particles PARTICLES_BENCH=bundle/particles_bench bench/server_session.sh [BUDGET_S]
# with the programs and their libraries carried as ../shared/device/README.md says (bundle both
# programs, and libOSMesa.so.8 and libavfilter.so.8 too: the program opens OSMesa and FFmpeg only
# when used, so ldd does not list them; libavfilter's own libraries are FFmpeg's others; unpack the
# two .xz into the libraries' folder). BUDGET_S (default 450): sections that would start later than their share of it are
# skipped and say so. Writes only beneath its own temporary folder.
set -uo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
particles="${PARTICLES:-$root/build/particles}"
bench="${PARTICLES_BENCH:-$root/build/particles_bench}"
budget="${1:-450}"
[ -x "$particles" ] || { echo "no program at $particles" >&2; exit 2; }
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
start=$(date +%s)
elapsed() { echo $(( $(date +%s) - start )); }
# section NAME SHARE: whether to run a section that may start until SHARE % of the budget is spent.
section() {
  echo "== [$(elapsed) s] $1"
  if [ "$(elapsed)" -ge $(( budget * $2 / 100 )) ]; then echo "   skipped: past ${2} % of the ${budget} s budget"; return 1; fi
}
export PARTICLES="$particles" SCENARIOS="$root/scenarios"

echo "machine: $(nproc) CPUs; $(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //')"
"$particles" --version | head -n 3
"$particles" render scenarios/cloth.yaml --at 1 --size 64x48 --gpu --verbose -o "$tmp/probe.png" 2>&1 | head -n 3

if section "the core on 1-16 threads (bench/README.md, \"The core past two threads\")" 20 && [ -x "$bench" ]; then
  "$bench" --benchmark_filter='PoolHandOut|PoolCopy|IntegratorStepThreads/cloth/316|DerivEval_ClothThreads/316' \
    --benchmark_min_time=0.2 2>&1 | grep -E '^BM_|^Run on|CPU Caches' | sed -e 's|/process_time/real_time||'
fi
if section "server table: the targets' rows on 1, 2, 4, 8 and 16 threads" 30; then
  THREADS="1 2 4 8 16" ROWS="sympl render316" bench/server_table.sh
  THREADS="16" ROWS="frames1000 render1000 demo" bench/server_table.sh
fi
if section "the GPU path against the golden references (golden check --gpu)" 60; then
  "$particles" golden check golden/golden.yaml --gpu -o "$tmp/golden-gpu" -j 4
  echo "golden check --gpu: exit $?"
fi
if section "the same bytes on 1, 3, 8 and 16 threads" 65; then
  big=(--set "grids[0].size=[316, 316]")
  for n in 1 3 8 16; do
    "$particles" run scenarios/cloth.yaml "${big[@]}" --integrator symplectic_euler --dt 2e-4 --duration 0.05 \
      --threads "$n" --quiet --trace "$tmp/trace_$n.csv"
    "$particles" render scenarios/cloth.yaml "${big[@]}" --at 0.5 --threads "$n" --quiet -o "$tmp/tiles_$n.png"
    "$particles" render scenarios/cloth.yaml "${big[@]}" --at 0.5 --threads "$n" --gpu --quiet -o "$tmp/gpu_$n.png"
  done
  kinds=(trace_ tiles_)
  if [ -f "$tmp/gpu_1.png" ]; then kinds+=(gpu_); else echo "gpu: no frame drawn (no GPU here), not compared"; fi
  for n in 3 8 16; do
    for kind in "${kinds[@]}"; do
      ext=png; [ "$kind" = trace_ ] && ext=csv
      if cmp -s "$tmp/${kind}1.$ext" "$tmp/${kind}$n.$ext"; then echo "${kind%_} on $n threads: the bytes of 1"; else echo "${kind%_} on $n threads: DIFFERS from 1"; fi
    done
  done
  if [ -f "$tmp/gpu_1.png" ]; then
    "$particles" compare "$tmp/tiles_1.png" "$tmp/gpu_1.png"
    echo "the 316² cloth at 1280x720, the GPU's frame against llvmpipe's: exit $?"
  fi
fi
if section "golden check through OSMesa (llvmpipe, this CPU and glibc)" 70; then
  "$particles" golden check golden/golden.yaml --gl osmesa -o "$tmp/golden-osmesa" -j 8 -q
  echo "golden check --gl osmesa: exit $?"
fi
if section "server table: the other rows on 16 threads" 75; then
  THREADS="16" ROWS="rk4 beuler million stability render316tri render316res" bench/server_table.sh
fi
if section "server table: one thread, for the ratios" 80; then
  THREADS="1" ROWS="rk4 beuler demo million stability" bench/server_table.sh
fi
echo "== [$(elapsed) s] done"
