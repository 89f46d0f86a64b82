#!/usr/bin/env bash
# Big meshes through glint's front door: peak memory and time of a whole `glint render`
# (parse, flatten, pack, grids, trace, write) on two generated meshes, with Embree 3's
# load + build of the same file beside it. The table of docs/performance-trace.md
# ("Loading big meshes").
#
#   tools/benches/meshload.sh [--threads N] [--quick]
#
# Meshes (generated here, not committed; GLINT_BENCH_DIR, default target/bench-meshload):
#   bumpy torus, 2×10⁶ small triangles, shared vertices (tools/benches/bumpy_torus.py 1000 1000)
#   10⁶ random triangles, unshared vertices, 6 decimals (tools/benches/random_triangles.py, 107 MiB)
# Each renders at 640×480 with the default flags (the default --memory-limit included; a
# mesh it refuses is measured under --memory-limit 8192 and its row says so):
# peak RSS (/usr/bin/time's maximum resident set size, the process's VmHWM), bytes per triangle,
# and the phases: the script with its mesh parse, flatten + pack (grids included), the trace.
# --quick: 10⁵-triangle meshes (checks the machinery in seconds).
# Needs: cargo, python3, /usr/bin/time; for the Embree rows make, g++, libembree-dev.
set -euo pipefail
cd "$(dirname "$0")/../.."

threads=2
quick=0
while [ $# -gt 0 ]; do
    case "$1" in
        --threads) threads="$2"; shift 2 ;;
        --quick) quick=1; shift ;;
        *) echo "usage: tools/benches/meshload.sh [--threads N] [--quick]" >&2; exit 2 ;;
    esac
done
work="${GLINT_BENCH_DIR:-target/bench-meshload}"
mkdir -p "$work"
cargo build --release --locked --quiet
glint="$PWD/target/release/glint"
embree=""
if make -C tools/benches/embree all --quiet 2>/dev/null; then
    embree="$PWD/target/embree/glint-embree-objload"
fi
if [ "$quick" = 1 ]; then torus=(224 224); random_n=100000; else torus=(1000 1000); random_n=1000000; fi
torus_dir="$work/torus-${torus[0]}x${torus[1]}"
random_dir="$work/random-$random_n"
mkdir -p "$torus_dir" "$random_dir"
[ -s "$torus_dir/mesh.obj" ] || python3 tools/benches/bumpy_torus.py "${torus[@]}" > "$torus_dir/mesh.obj"
[ -s "$random_dir/mesh.obj" ] ||
    python3 tools/benches/random_triangles.py "$random_n" "$random_n" 6 > "$random_dir/mesh.obj"

echo "# glint mesh loading: $(date -u '+%Y-%m-%d %H:%M UTC'), glint $(git rev-parse --short HEAD 2>/dev/null || echo '?'), $threads threads, $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo "| mesh | triangles | OBJ MiB | glint peak RSS MiB | B/triangle | whole process s | script + parse s | flatten + pack s | trace s | Embree load s | Embree build s | Embree peak RSS MiB | B/triangle |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"

# row NAME SCENE DIR: renders SCENE in DIR (it reads DIR/mesh.obj) and prints one row.
row() {
    local name="$1" scene="$2" dir="$3" obj="$3/mesh.obj"
    cp "tools/benches/scenes/$scene" "$dir/scene.lua"
    local out="$dir/glint.txt"
    local flags=(render scene.lua -o image.png --backend cpu --threads "$threads" --stats --aa none)
    if ! (cd "$dir" && /usr/bin/time -v "$glint" "${flags[@]}") > "$out" 2>&1; then
        # Refused by the default memory limit: measured with a larger one, and said so.
        grep -q 'memory limit' "$out" || { cat "$out" >&2; return 1; }
        name="$name (refused by default; --memory-limit 8192)"
        (cd "$dir" && /usr/bin/time -v "$glint" "${flags[@]}" --memory-limit 8192) > "$out" 2>&1 ||
            { cat "$out" >&2; return 1; }
    fi
    local triangles peak wall build trace
    triangles=$(grep -o '[0-9]* stored triangles' "$out" | grep -o '^[0-9]*')
    peak=$(grep 'Maximum resident set size' "$out" | grep -o '[0-9]*$')
    wall=$(grep 'Elapsed (wall clock)' "$out" | awk -F': ' '{ n = split($2, t, ":"); s = 0; for (i = 1; i <= n; i++) s = s * 60 + t[i]; print s }')
    build=$(grep -o 'flatten and pack [0-9.]* s' "$out" | grep -o '[0-9.]*')
    trace=$(grep -o 'time: [0-9.]* s' "$out" | grep -o '[0-9.]*')
    local e_load=- e_build=- e_peak=- e_per=-
    if [ -n "$embree" ]; then
        local e
        e=$("$embree" "$obj" --threads "$threads")
        e_load=$(echo "$e" | grep -o 'load: [0-9.]*' | grep -o '[0-9.]*$')
        e_build=$(echo "$e" | grep -o 'build: [0-9.]*' | grep -o '[0-9.]*$')
        local kb
        kb=$(echo "$e" | grep -o 'peak RSS: [0-9]*' | grep -o '[0-9]*$')
        e_peak=$(awk -v k="$kb" 'BEGIN { printf "%.1f", k / 1024 }')
        e_per=$(awk -v k="$kb" -v n="$triangles" 'BEGIN { printf "%.0f", k * 1024 / n }')
    fi
    awk -v name="$name" -v n="$triangles" -v size="$(stat -L -c %s "$obj")" -v kb="$peak" \
        -v wall="$wall" -v build="$build" -v trace="$trace" \
        -v el="$e_load" -v eb="$e_build" -v ep="$e_peak" -v epb="$e_per" 'BEGIN {
        printf "| %s | %d | %.1f | %.1f | %.0f | %.2f | %.2f | %.2f | %.2f | %s | %s | %s | %s |\n",
            name, n, size / 1048576, kb / 1024, kb * 1024 / n, wall, wall - build - trace, build, trace,
            el, eb, ep, epb }'
}

row "bumpy torus" bumpy-torus.lua "$torus_dir"
row "random triangles" random-triangles-640.lua "$random_dir"
