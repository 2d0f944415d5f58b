#!/usr/bin/env bash
# What a style costs a render (bench/README.md, "Styles"): each render against the same render
# without the style, best of REPEATS wall-clock runs each, and their ratio.
#   1. the 316² cloth (99,856 particles), 1 s to MP4, particles coloured by speed over a given
#      range, with a colour bar;
#   2. the same with `range: auto`, which adds one simulation pass before the first frame;
#   3. the 25² cloth for 2 s to MP4 with 2 s trails on 100 of its particles (its bottom four rows, which the mouse swings).
# Usage: bench/style_costs.sh [PARTICLES_BINARY] [REPEATS]   (defaults: build/particles, 3)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
particles="${1:-$root/build/particles}"
repeats="${2:-3}"
scratch="$(mktemp -d)"
trap 'rm -rf -- "$scratch"' EXIT

# best_seconds ARGS…: the shortest wall time of `particles ARGS…` over $repeats runs.
best_seconds() {
  local best="" start end took
  for _ in $(seq "$repeats"); do
    start=$(date +%s.%N)
    "$particles" "$@" -q > /dev/null
    end=$(date +%s.%N)
    took=$(awk -v a="$start" -v b="$end" 'BEGIN { print b - a }')
    if [[ -z "$best" ]] || awk -v t="$took" -v b="$best" 'BEGIN { exit !(t < b) }'; then best=$took; fi
  done
  printf '%.2f' "$best"
}

# compare NAME PLAIN_ARGS… -- STYLE_ARGS…: the plain render, the styled one, and the ratio.
compare() {
  local name=$1
  shift
  local plain=() styled=()
  while [[ $1 != -- ]]; do plain+=("$1"); shift; done
  shift
  styled=("$@")
  local a b
  a=$(best_seconds "${plain[@]}")
  b=$(best_seconds "${plain[@]}" "${styled[@]}")
  printf '%-44s plain %6s s  styled %6s s  ratio %.2f\n' "$name" "$a" "$b" "$(awk -v a="$a" -v b="$b" 'BEGIN { print b / a }')"
}

cloth316=(render "$root/scenarios/cloth.yaml" --set "grids.0.size=[316, 316]"
  --set "grids.0.spacing=[0.0060952380952380956, 0.0060952380952380956]"
  --set "mouse.0.grab=cloth[315][158]" --duration 1 -o "$scratch/cloth316.mp4")
compare "316² cloth, speed over [0, 2], colour bar" "${cloth316[@]}" -- \
  --set "style.particles={color_by: speed, range: [0, 2]}" --set "style.colorbar={for: particles}"
compare "316² cloth, speed over range: auto, colour bar" "${cloth316[@]}" -- \
  --set "style.particles.color_by=speed" --set "style.colorbar={for: particles}"
cloth25=(render "$root/scenarios/cloth.yaml" --duration 2 -o "$scratch/cloth25.mp4")
compare "25² cloth, 2 s trails on 100 particles" "${cloth25[@]}" -- \
  --set 'style.select=[{particles: ["cloth[21][*]", "cloth[22][*]", "cloth[23][*]", "cloth[24][*]"], trail: {seconds: 2}}]'
