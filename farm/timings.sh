#!/usr/bin/env bash
# Wall time of a scene rendered whole and as 1, 2, 4, 8 and 16 tiles, one process per
# tile one after another on this machine (as one farm node would run them), and of a
# 1-pixel crop (the fixed cost of a task: start-up, the script, the scene's build).
# Prints one TSV row per process: tiles, index, seconds. docs/farm.md quotes a run.
# Usage: farm/timings.sh GLINT SCENE WIDTH HEIGHT [TILE COUNTS...]
set -euo pipefail
glint=$1 scene=$2 width=$3 height=$4
shift 4
counts=("${@:-1 2 4 8 16}")
[ $# -eq 0 ] && counts=(1 2 4 8 16)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
run() { # label index args...
  local label=$1 index=$2 start end
  shift 2
  start=$(date +%s.%N)
  "$glint" render "$scene" --backend cpu --width "$width" --height "$height" "$@" 2>/dev/null
  end=$(date +%s.%N)
  printf '%s\t%s\t%.2f\n' "$label" "$index" "$(echo "$end - $start" | bc)"
}
printf 'tiles\tindex\tseconds\n'
for k in 1 2; do run crop-1px "$k" --crop 0,1,0,1 -o "$out/crop.png"; done
for n in "${counts[@]}"; do
  for ((i = 0; i < n; i++)); do run "$n" "$i" --tile "$i/$n" -o "$out/t.png"; done
done
