#!/usr/bin/env bash
# glint view's figures (docs/view.md#measured): for each scene and tracer, the time to
# the first image, the preview's frames per second while the camera moves, and samples
# per second while the image refines, at 640×400. Runs on the display in $DISPLAY (a
# hardware GPU's desktop: `tools/benches/view-measure.sh`), or, with none, on a private Xvfb
# (lavapipe presents there). Needs xdotool (and Xvfb without a display).
#   usage: [VIEW_SCENES="a.lua b.lua"] [VIEW_BACKENDS="gpu cpu"] tools/benches/view-measure.sh [GLINT_BINARY] [VIEW FLAGS…]
#   (view flags such as --adapter NAME, or --samples 2 to bound a slow adapter's run)
set -euo pipefail
cd "$(dirname "$0")/../.."
glint="${1:-target/release/glint}"
shift || true
extra=("$@")
for tool in xdotool "$glint"; do
  command -v "$tool" >/dev/null || { echo "needs $tool (apt-get install -y xvfb xdotool)" >&2; exit 1; }
done
if [ -z "${DISPLAY:-}" ]; then
  exec 3< <(Xvfb -displayfd 1 -screen 0 1024x768x24 -nolisten tcp 2>/dev/null)
  read -r number <&3
  export DISPLAY=":$number"
  trap 'kill %1 2>/dev/null || true' EXIT
fi
log="$(mktemp -d)"
echo "| scene | tracer | adapter | first image | moving (preview) | refining |"
echo "|---|---|---|---|---|---|"
scenes="${VIEW_SCENES:-scenes/demo.lua scenes/scrabble.lua scenes/cs488/a4-2021plus/macho-cows.lua}"
for scene in $scenes; do
  for backend in ${VIEW_BACKENDS:-gpu cpu}; do
    err="$log/$(basename "$scene" .lua)-$backend.txt"
    timeout 600 "$glint" view "$scene" --width 640 --height 400 --backend "$backend" "${extra[@]}" \
      >/dev/null 2>"$err" &
    pid=$!
    # The image complete, then a 2-second left drag: one 4-pixel step every 10 ms.
    until grep -q "image complete" "$err" 2>/dev/null; do
      kill -0 $pid 2>/dev/null || { cat "$err" >&2; exit 1; }
      sleep 0.2
    done
    window="$(xdotool search --name "glint view" | head -1)"
    steps=()
    for _ in $(seq 200); do steps+=(mousemove_relative -- 4 0 sleep 0.01); done
    xdotool mousemove --window "$window" 100 200 mousedown 1 "${steps[@]}" mouseup 1
    until grep -q "moving:" "$err"; do sleep 0.2; done
    # The refined image after the move, then quit.
    until [ "$(grep -c "image complete" "$err")" -ge 2 ]; do sleep 0.2; done
    xdotool windowfocus --sync "$window" key Escape
    wait $pid || true
    adapter="$(sed -n 's/^glint view: [A-Z]* tracer on \(.*\) (Vulkan.*/\1/p' "$err" | head -1)"
    first="$(sed -n 's/^glint view: first image after \(.*\)$/\1/p' "$err")"
    moving="$(sed -n 's/^glint view: moving: .*(\(.*\) frames\/s, stride up to \(.*\))$/\1 frames\/s at 1\/\2/p' "$err")"
    refine="$(sed -n 's/^glint view: image complete: \(.*\) samples a pixel in \(.*\) s (\(.*\) M samples\/s)$/\3 M samples\/s (\1 spp in \2 s)/p' "$err" | tail -1)"
    echo "| $(basename "$scene") | $backend | $adapter | $first | $moving | $refine |"
  done
done
rm -rf "$log"
