#!/usr/bin/env bash
# End-to-end `particles render` against the encoder alone (the target: render + encode should
# approach the encoder's own throughput). Renders scenarios/cloth.yaml (1280×720, 60 fps, 10 s = 600 frames)
# once to raw RGBA frames (not timed), then times, REPS times each:
#   encoder alone:  ffmpeg encoding those raw frames with the same settings as ours
#                   (libx264, preset medium, crf 18, keyframes every 2 s = 120 frames, yuv420p,
#                   +faststart)
#   end to end:     particles render scenarios/cloth.yaml -o cloth.mp4 (simulate, draw, encode)
# and prints median wall times, frames per second and their ratio.
# Usage: bench/render_vs_ffmpeg.sh [BUILD_DIR] [REPS]     (default build-bench, 3)
#        RENDER_ARGS='--msaa 1' bench/render_vs_ffmpeg.sh   extra options for particles render
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build-bench}"
reps="${2:-3}"
particles="$build/particles"
[ -x "$particles" ] || { echo "build $particles first (cmake --build $build --target particles)" >&2; exit 2; }
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
scenario="$root/scenarios/cloth.yaml"
frames=600

"$particles" render "$scenario" -o "$tmp/frames/" --png-level 1 --quiet
ffmpeg -v error -i "$tmp/frames/frame_%06d.png" -f rawvideo -pix_fmt rgba "$tmp/frames.raw"
rm -rf "$tmp/frames"

seconds() { local s e; s=$(date +%s.%N); "$@" >/dev/null 2>&1; e=$(date +%s.%N); echo "$e - $s" | bc -l; }
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }

enc=(); e2e=()
for _ in $(seq "$reps"); do
  enc+=("$(seconds ffmpeg -y -v error -f rawvideo -pix_fmt rgba -s 1280x720 -r 60 -i "$tmp/frames.raw" \
           -c:v libx264 -preset medium -crf 18 -g 120 -pix_fmt yuv420p -movflags +faststart "$tmp/ffmpeg.mp4")")
  # shellcheck disable=SC2086  # RENDER_ARGS is a list of words
  e2e+=("$(seconds "$particles" render "$scenario" -o "$tmp/particles.mp4" --quiet ${RENDER_ARGS:-})")
done
encMed=$(printf '%s\n' "${enc[@]}" | median)
e2eMed=$(printf '%s\n' "${e2e[@]}" | median)
printf 'encoder alone (ffmpeg, raw RGBA in):  %6.2f s  %6.1f frames/s   runs: %s\n' "$encMed" \
  "$(echo "$frames / $encMed" | bc -l)" "${enc[*]}"
printf 'particles render end to end:          %6.2f s  %6.1f frames/s   runs: %s\n' "$e2eMed" \
  "$(echo "$frames / $e2eMed" | bc -l)" "${e2e[*]}"
printf 'end-to-end throughput / encoder alone: %.2f\n' "$(echo "$encMed / $e2eMed" | bc -l)"
