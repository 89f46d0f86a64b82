#!/usr/bin/env bash
# The instructions one GPU frame costs on lavapipe, counted by callgrind: a measure of a
# kernel change that this shared machine's load cannot blur (wall and GPU times of the
# same frame move by ±20% between runs; these counts repeat within 0.3%).
#
#   tools/benches/llvmpipe_instructions.sh [--glint BIN] [--size N] [--aa MODE]
#                                    [--kernel-variant software|hardware] SCENE.lua...
#
# For each scene it renders with the GPU tracer under `valgrind --tool=callgrind` at 8×8
# (twice: the first fills the shader cache) and at N×N (default 256), and prints the
# difference of the two runs' instruction counts: the frame's own work (llvmpipe runs the
# kernel on the CPU, so its JIT code counts like any other), without the start-up and
# the shader compilation, which both runs share. Compare two builds by running it for
# each; llvmpipe executes a SIMD group's instructions once for its 8 lanes, so a count is
# what the kernel costs that device, not a ray count. Needs valgrind and lavapipe
# (apt-get install -y valgrind mesa-vulkan-drivers); about a minute per scene.
# `--kernel-variant hardware` counts the kernels a hardware GPU gets (the wavefront
# kernels) on lavapipe instead of its own (the megakernels); default: lavapipe's own.
set -euo pipefail
cd "$(dirname "$0")/../.."

glint=target/release/glint
size=256
aa=none
variant=()
scenes=()
usage="usage: tools/benches/llvmpipe_instructions.sh [--glint BIN] [--size N] [--aa MODE] [--kernel-variant software|hardware] SCENE.lua..."
while [ $# -gt 0 ]; do
    case "$1" in
        --glint) glint="$2"; shift 2 ;;
        --size) size="$2"; shift 2 ;;
        --aa) aa="$2"; shift 2 ;;
        --kernel-variant) variant=(--kernel-variant "$2"); shift 2 ;;
        -h|--help) echo "$usage"; exit 0 ;;
        -*) echo "$usage" >&2; exit 2 ;;
        *) scenes+=("$1"); shift ;;
    esac
done
[ ${#scenes[@]} -gt 0 ] || { echo "$usage" >&2; exit 2; }
command -v valgrind > /dev/null || { echo "needs valgrind (apt-get install -y valgrind)" >&2; exit 2; }
[ -x "$glint" ] || { echo "no $glint: cargo build --release first" >&2; exit 2; }

scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

# Instructions of one whole `glint render` at side × side.
count() {
    local scene=$1 side=$2 out
    out=$(valgrind --tool=callgrind --callgrind-out-file=/dev/null "$glint" render "$scene" \
        --backend gpu --width "$side" --height "$side" --aa "$aa" "${variant[@]}" \
        -o "$scratch/frame.png" 2>&1)
    echo "$out" | sed -n 's/.*Collected : \([0-9]*\).*/\1/p'
}

for scene in "${scenes[@]}"; do
    count "$scene" 8 > /dev/null
    small=$(count "$scene" 8)
    large=$(count "$scene" "$size")
    [ -n "$small" ] && [ -n "$large" ] || { echo "$scene: no count (did the render fail?)" >&2; exit 1; }
    echo "$(basename "$scene") ${size}² aa $aa${variant[1]:+ (${variant[1]} kernels)}: $(( (large - small) / 1000000 ))M instructions a frame"
done
