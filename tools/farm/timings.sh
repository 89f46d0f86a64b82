#!/usr/bin/env bash
# Wall and CPU time of a scene rendered as 1, 2, 4, 8 and 16 tiles, one process per tile
# one after another on this machine (as one farm node would run them), and of a 1-pixel
# crop (a task's fixed cost: start-up, the script, the scene's build). One TSV row per
# process: tiles, index, wall seconds, CPU seconds (user + system), exit code; glint's
# messages go to stderr. docs/farm.md quotes a run.
# Usage: tools/farm/timings.sh GLINT SCENE WIDTH HEIGHT [TILE COUNTS...]  (default 1 2 4 8 16)
set -uo pipefail
glint=$1 scene=$2 width=$3 height=$4
shift 4
counts=("$@")
[ ${#counts[@]} -eq 0 ] && counts=(1 2 4 8 16)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
run() { # label index args...
  local label=$1 index=$2 times code
  shift 2
  times=$(mktemp)
  /usr/bin/time -f '%e %U %S' -o "$times" \
    "$glint" render "$scene" --backend cpu --width "$width" --height "$height" "$@"
  code=$?
  read -r wall user sys <"$times"
  rm -f "$times"
  printf '%s\t%s\t%s\t%.2f\t%s\n' "$label" "$index" "$wall" "$(echo "$user + $sys" | bc)" "$code"
}
printf 'tiles\tindex\twall_s\tcpu_s\texit\n'
for k in 1 2; do run crop-1px "$k" --crop 0,1,0,1 -o "$out/crop.png"; done
for n in "${counts[@]}"; do
  for ((i = 0; i < n; i++)); do run "$n" "$i" --tile "$i/$n" -o "$out/t.png"; done
done
