#!/usr/bin/env bash
# The table of large-scene work on a many-core server (bench/README.md, "Large scenes on
# large servers"): each row's command timed (wall seconds, one run) on 1, 2, 4, 8 and 16 threads
# (those this machine has), on llvmpipe, and with --gpu where a row renders and a hardware EGL
# device answers. Prints one line per row and count as it goes, then the table in Markdown.
#
# Usage: bench/server_table.sh [BUILD_DIR]                 (default build; its `particles`)
#        PARTICLES=bundle/particles bench/server_table.sh    a program elsewhere (a server bundle,
#                                                           ../shared/device/README.md)
#        THREADS="1 16" ROWS="sympl rk4" bench/server_table.sh   some counts, some rows
# Rows: sympl rk4 beuler million stability render316 render316tiles render316tri render316res
# render1000 frames1000 demo (all by default). The render rows without --raster draw on `auto`'s
# path: cpu on llvmpipe, resident with --gpu. frames1000 is drawing-bound (12 frames of the 1000² cloth, 10 steps
# each): its GPU cell against its 16-thread cell is the target "GPU path ≥ 3× llvmpipe per frame".
# The scenarios are the checkout's: run it from there, or set SCENARIOS=dir.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
particles="${PARTICLES:-${1:-$root/build}/particles}"
scenarios="${SCENARIOS:-$root/scenarios}"
[ -x "$particles" ] || { echo "no program at $particles (cmake --build build --target particles)" >&2; exit 2; }
cores=$(nproc)
threads_wanted=(${THREADS:-1 2 4 8 16})
rows=(${ROWS:-sympl rk4 beuler million stability render316 render316tiles render316tri render316res render1000 frames1000 demo})
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

cloth=("$scenarios/cloth.yaml")
big=(--set "grids[0].size=[316, 316]")
# Each row: its label, and its command's arguments after the program (an array per row).
describe() {
  case "$1" in
    sympl) label="316² cloth, symplectic Euler, 500 steps at dt 2e-4 (run)"
      args=(run "${cloth[@]}" "${big[@]}" --integrator symplectic_euler --dt 2e-4 --duration 0.1) ;;
    rk4) label="316² cloth, RK4, 1 s (run)"
      args=(run "${cloth[@]}" "${big[@]}" --integrator rk4 --duration 1) ;;
    beuler) label="316² cloth, backward Euler, 0.5 s (run)"
      args=(run "${cloth[@]}" "${big[@]}" --integrator backward_euler --duration 0.5) ;;
    million) label="1000² cloth, 0.1 s = 600 steps (run)"
      args=(run "$scenarios/cloth_million.yaml" --duration 0.1) ;;
    stability) label="stability study of the cloth"
      args=(stability "${cloth[@]}" --csv "$tmp/stability.csv") ;;
    render316) label="316² cloth, 2 s to MP4 (render, auto)"
      args=(render "${cloth[@]}" "${big[@]}" --duration 2 -o "$tmp/out.mp4") ;;
    render316tiles) label="316² cloth, 2 s to MP4, --raster tiles"
      args=(render "${cloth[@]}" "${big[@]}" --duration 2 --raster tiles -o "$tmp/out.mp4") ;;
    render316tri) label="316² cloth, 2 s to MP4, --raster triangles"
      args=(render "${cloth[@]}" "${big[@]}" --duration 2 --raster triangles -o "$tmp/out.mp4") ;;
    render316res) label="316² cloth, 2 s to MP4, --raster resident"
      args=(render "${cloth[@]}" "${big[@]}" --duration 2 --raster resident -o "$tmp/out.mp4") ;;
    frames1000) label="1000² cloth, 12 frames at 600 fps to MP4 (drawing-bound)"
      args=(render "$scenarios/cloth_million.yaml" --duration 0.02 --fps 600 --particle-radius 0.1px -o "$tmp/out.mp4") ;;
    render1000) label="1000² cloth, 0.1 s to MP4 (6 frames)"
      args=(render "$scenarios/cloth_million.yaml" --duration 0.1 --particle-radius 0.1px -o "$tmp/out.mp4") ;;
    demo) label="cloth demo, 600 frames to MP4"
      args=(render "${cloth[@]}" -o "$tmp/out.mp4") ;;
    *) echo "unknown row '$1'" >&2; exit 2 ;;
  esac
}

# Wall seconds of one run, or "failed" (its stderr kept in $tmp/last.err).
wall() {
  local start end
  start=$(date +%s.%N)
  if "$particles" "$@" --quiet >/dev/null 2>"$tmp/last.err"; then
    end=$(date +%s.%N)
    printf '%.2f' "$(echo "$end - $start" | bc -l)"
  else
    echo failed
  fi
}

# Whether a hardware EGL device draws here (a one-frame render with --gpu).
gpu=no
if "$particles" render "${cloth[@]}" --at 0 --size 64x48 --gpu -o "$tmp/probe.png" --quiet >/dev/null 2>&1; then
  gpu=yes
fi
echo "machine: $cores CPUs, GPU: $gpu; $(uptime | sed 's/^ *//')"
echo "program: $particles ($("$particles" --version 2>/dev/null | head -n1))"

counts=()
for n in "${threads_wanted[@]}"; do
  if [ "$n" -le "$cores" ]; then counts+=("$n"); fi
done
# None of the counts asked for fits this machine (THREADS=16 on 2 cores): its own core count.
if [ "${#counts[@]}" -eq 0 ]; then counts=("$cores"); fi
declare -A result=()
for row in "${rows[@]}"; do
  describe "$row"
  for n in "${counts[@]}"; do
    result["$row,$n"]=$(wall "${args[@]}" --threads "$n")
    echo "$label, $n threads: ${result[$row,$n]} s"
  done
  if [ "$gpu" = yes ] && [ "${args[0]}" = render ]; then
    result["$row,gpu"]=$(wall "${args[@]}" --gpu --threads "${counts[-1]}")
    echo "$label, --gpu on ${counts[-1]} threads: ${result[$row,gpu]} s"
  fi
done

# The table: wall seconds, and each count's speed-up over the first.
echo
header="| work |"
rule="|---|"
for n in "${counts[@]}"; do header+=" $n thr. |"; rule+="---:|"; done
header+=" GPU (\`--gpu\`) |"
rule+="---:|"
echo "$header"
echo "$rule"
for row in "${rows[@]}"; do
  describe "$row"
  line="| $label |"
  first=${result[$row,${counts[0]}]}
  for n in "${counts[@]}"; do
    cell=${result[$row,$n]}
    if [ "$n" != "${counts[0]}" ] && [ "$cell" != failed ] && [ "$first" != failed ]; then
      cell+=" ($(printf '%.1f' "$(echo "$first / $cell" | bc -l)")×)"
    fi
    line+=" $cell |"
  done
  line+=" ${result[$row,gpu]:-} |"
  echo "$line"
done
