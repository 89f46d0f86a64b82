#!/usr/bin/env bash
# The first table to take on a machine with a hardware Vulkan GPU (issue 38, item 6), in
# under five minutes at the defaults on such a machine:
#
#   tools/benches/first_gpu.sh [--glint BIN] [--size N] [--adapter NAME] [--with-bench] [SCENE.lua...]
#
# Per scene (default: the scenes of `glint bench --gpu`), each in a process of its own:
#   - the GPU render (`glint render --backend gpu --stats`, N×N, the scene's own AA): the
#     GPU frame time from timestamp queries, Mrays/s over that time, the whole process'
#     wall time (start-up, script, packing, pipeline compilation and read-back included);
#   - the CPU tracer on the same machine and image (`--backend cpu --stats`): its rays
#     (the GPU traces the same samples), render time, Mrays/s and wall time.
# Then the register table of the kernels those renders compile (`glint kernels` on the
# hardware device), where the driver exposes VK_KHR_pipeline_executable_properties (AMD,
# NVIDIA); and with --with-bench, `glint bench --gpu --repeat 1` (512², AA none and the
# scene's AA, with image errors). A column the device cannot give says why ("no
# timestamps", "not exposed"). Runs on lavapipe too (slowly: use --size 32 and one scene;
# tests/cli/first_gpu.rs does).
set -euo pipefail
cd "$(dirname "$0")/../.."

glint=target/release/glint
size=512
adapter=()
with_bench=0
scenes=()
usage="usage: tools/benches/first_gpu.sh [--glint BIN] [--size N] [--adapter NAME] [--with-bench] [SCENE.lua...]"
while [ $# -gt 0 ]; do
    case "$1" in
        --glint) glint="$2"; shift 2 ;;
        --size) size="$2"; shift 2 ;;
        --adapter) adapter=(--adapter "$2"); shift 2 ;;
        --with-bench) with_bench=1; shift ;;
        -h|--help) echo "$usage"; exit 0 ;;
        -*) echo "$usage" >&2; exit 2 ;;
        *) scenes+=("$1"); shift ;;
    esac
done
if [ ${#scenes[@]} -eq 0 ]; then
    scenes=(scenes/cs488/a4-2021plus/simple.lua scenes/cs488/a4-2021plus/nonhier.lua
            scenes/cs488/a4-2021plus/hier.lua scenes/cs488/a4-2021plus/macho-cows.lua
            scenes/demo.lua)
fi
[ -x "$glint" ] || { echo "first_gpu.sh: no glint at $glint (cargo build --release, or --glint BIN)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

now() { date +%s.%N; }
# The first match of a sed expression in a file, or the fallback.
pick() { local v; v=$(sed -n "$2" "$1" | head -n 1); echo "${v:-$3}"; }

echo "# glint on the first GPU: $(date -u +%Y-%m-%dT%H:%MZ), ${size}×${size}, the scenes' own AA"
echo
"$glint" info | sed -n '1,3p'
echo
echo "| scene | GPU frame (timestamps) | GPU Mrays/s | GPU process wall | CPU render | CPU Mrays/s | CPU process wall | rays | GPU/CPU frame |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
for scene in "${scenes[@]}"; do
    name=$(basename "$scene" .lua)
    t0=$(now)
    if ! "$glint" render "$scene" --backend gpu "${adapter[@]}" --stats --width "$size" --height "$size" \
            -o "$work/$name-gpu.png" >"$work/gpu.out" 2>&1; then
        echo "| $name | GPU render failed: $(tail -n 1 "$work/gpu.out") ||||||||"
        continue
    fi
    t1=$(now)
    "$glint" render "$scene" --backend cpu --stats --width "$size" --height "$size" \
        -o "$work/$name-cpu.png" >"$work/cpu.out" 2>&1
    t2=$(now)
    gpu_ms=$(pick "$work/gpu.out" 's/.*GPU time \([0-9.]*\) ms (timestamp queries).*/\1/p' "")
    rays=$(pick "$work/cpu.out" 's/.*rays: \([0-9]*\) (camera.*/\1/p' 0)
    cpu_s=$(pick "$work/cpu.out" 's/.*time: \([0-9.]*\) s with counting.*/\1/p' 0)
    cpu_mrays=$(pick "$work/cpu.out" 's/.*counting, \([0-9.]*\) Mrays\/s.*/\1/p' 0)
    awk -v n="$name" -v g="$gpu_ms" -v r="$rays" -v c="$cpu_s" -v cm="$cpu_mrays" \
        -v t0="$t0" -v t1="$t1" -v t2="$t2" 'BEGIN {
        gw = t1 - t0; cw = t2 - t1
        if (g == "") { gf = "no timestamps"; gm = "no timestamps"; ratio = "—" }
        else { gf = sprintf("%.1f ms", g); gm = sprintf("%.2f", r / (g / 1000) / 1e6);
               ratio = (c > 0) ? sprintf("%.3f", (g / 1000) / c) : "—" }
        printf "| %s | %s | %s | %.2f s | %.3f s | %s | %.2f s | %d | %s |\n", n, gf, gm, gw, c, cm, cw, r, ratio
    }'
done
echo
echo "GPU Mrays/s: the CPU tracer's ray count (the same samples) over the GPU frame time."
echo
echo "## Kernel registers on this device"
echo
if "$glint" kernels "${scenes[@]}" --wave default >"$work/kernels.out" 2>"$work/kernels.err"; then
    cat "$work/kernels.out"
else
    echo "not exposed: $(tail -n 1 "$work/kernels.err")"
fi
if [ "$with_bench" = 1 ]; then
    echo
    "$glint" bench --gpu --repeat 1 "${adapter[@]}"
fi
