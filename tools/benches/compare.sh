#!/usr/bin/env bash
# glint beside Embree 3 and POV-Ray, in one run: the tables of docs/performance-trace.md.
#
#   tools/benches/compare.sh [--threads N] [--quick] [--stadium-size WxH] [--rows LIST] [--repeat K]
#
# 1. Trace rows: `glint bench --trace` on each scene dumps its exact rays with its
#    answers; the Embree harness (tools/benches/embree/) traces the same rays; one row each:
#    primary and shadow Mrays/s, bytes per triangle, rays answered differently.
#    Scenes: cow.obj at 2048², 10³…10⁶ random triangles (generated here, not committed),
#    macho-cows, the stadium.
# 2. Render rows: `glint render` against POV-Ray 3.7 (tools/benches/povray/), whole-process wall
#    time, 1024×768, no anti-aliasing: the stadium and nonhier.
#
# --quick: small images and 10³–10⁴ triangles only (checks the machinery in a minute).
# --stadium-size: the stadium's image size in both of its rows (default 1024x768; it is
#   glint's slow case, minutes per pass with the uniform grid).
# --rows: a comma-separated subset of cow,random,macho-cows,stadium,renders (default all).
# --repeat: timed passes of each trace row, for glint and Embree alike (default 3; each
#   reports its fastest). On a shared machine whose load moves either side's rate 2–3×
#   between runs, more passes let both reach their unloaded rate within the same run.
# Needs: cargo, make, g++, libembree-dev, povray, python3. Scratch files go to
# target/bench-compare (GLINT_BENCH_DIR overrides); ray dumps are deleted after use.
set -euo pipefail
cd "$(dirname "$0")/../.."

threads=2
quick=0
stadium_size=1024x768
rows=cow,random,macho-cows,stadium,renders
repeat=3
usage="usage: tools/benches/compare.sh [--threads N] [--quick] [--stadium-size WxH] [--rows LIST] [--repeat K]"
while [ $# -gt 0 ]; do
    case "$1" in
        --threads) threads="$2"; shift 2 ;;
        --quick) quick=1; stadium_size=256x192; shift ;;
        --stadium-size) stadium_size="$2"; shift 2 ;;
        --rows) rows="$2"; shift 2 ;;
        --repeat) repeat="$2"; shift 2 ;;
        *) echo "$usage" >&2; exit 2 ;;
    esac
done
want() { [[ ",$rows," == *",$1,"* ]]; }
stadium_w="${stadium_size%x*}"
stadium_h="${stadium_size#*x}"

work="${GLINT_BENCH_DIR:-target/bench-compare}"
mkdir -p "$work"
cargo build --release --locked --quiet
make -C tools/benches/embree --quiet
glint=target/release/glint
# tools/benches/scenes/ read their meshes from the CS488 corpus, outside their own folder; the
# trace rows get --memory-limit 8192 as headroom (the 195 MiB 10⁶-triangle OBJ fits the default).
corpus=scenes/cs488/a4-2021plus
embree=target/embree/glint-embree-trace

if [ "$quick" = 1 ]; then
    cow_size=(--width 256 --height 256); max_n=10000; render_size=(256 192)
else
    cow_size=(); max_n=1000000; render_size=(1024 768)
fi

echo "# glint vs Embree and POV-Ray: $(date -u '+%Y-%m-%d %H:%M UTC'), $threads threads, fastest of $repeat, $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
echo "glint $(git rev-parse --short HEAD 2>/dev/null || echo '?'), $(g++ --version | head -1), $(povray --version 2>&1 | grep -o 'POV-Ray [0-9.a-z]*' | head -1)"

# value FILE PREFIX: the first number after PREFIX on the line that starts with it.
value() { grep -m1 "^$2" "$1" | sed "s/^$2//" | grep -o '^[0-9.]*'; }
# ratio A B: A / B to two decimals.
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a / b }'; }

echo
echo "## Trace: rays/s on the same rays (glint bench --trace, Embree 3 rtcIntersect1 / rtcOccluded1)"
echo
echo "| scene | triangles | glint primary Mrays/s | Embree primary | ratio | glint shadow Mrays/s | Embree shadow | ratio | glint B/triangle | Embree B/triangle | answers differing (primary; shadow) | hit checksum glint / Embree |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- | --- |"

trace_row() {
    local name="$1" scene="$2"; shift 2
    local g="$work/$name.glint.txt" e="$work/$name.embree.txt" rays="$work/$name.rays"
    "$glint" bench --trace "$scene" --threads "$threads" --dump-rays "$rays" --allow-read "$corpus" \
        --memory-limit 8192 --repeat "$repeat" "$@" > "$g"
    "$embree" "$rays" --threads "$threads" --repeat "$repeat" > "$e"
    rm -f "$rays"
    local gp ep gs es
    gp=$(value "$g" "primary: "); ep=$(value "$e" "primary: ")
    gs=$(value "$g" "shadow: "); es=$(value "$e" "shadow: ")
    local tris differ
    tris=$(grep -m1 '^image: ' "$g" | sed 's/.*, \([0-9]*\) triangles.*/\1/')
    differ=$(grep -m1 '^answers differing' "$e" | sed 's/.*: primary \([0-9]*\) of [0-9]*, shadow \([0-9]*\) of [0-9]*/\1; \2/')
    printf '| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s / %s |\n' \
        "$name" "$tris" "$gp" "$ep" "$(ratio "$gp" "$ep")" "$gs" "$es" "$(ratio "$gs" "$es")" \
        "$(value "$g" "memory: ")" "$(value "$e" "memory: ")" "$differ" \
        "$(value "$g" "hit checksum: ")" "$(value "$e" "hit checksum: ")"
}

want cow && trace_row cow tools/benches/scenes/cow.lua "${cow_size[@]}"
n=1000
while want random && [ "$n" -le "$max_n" ]; do
    dir="$work/random-$n"
    mkdir -p "$dir"
    [ -s "$dir/random-triangles.obj" ] || python3 tools/benches/random_triangles.py "$n" "$n" > "$dir/random-triangles.obj"
    cp tools/benches/scenes/random-triangles.lua "$dir/"
    if [ "$quick" = 1 ]; then
        trace_row "random-$n" "$dir/random-triangles.lua" --width 256 --height 256
    else
        trace_row "random-$n" "$dir/random-triangles.lua"
    fi
    n=$((n * 10))
done
want macho-cows && trace_row macho-cows scenes/cs488/a4-2021plus/macho-cows.lua
want stadium && trace_row stadium tools/benches/scenes/stadium.lua --width "$stadium_w" --height "$stadium_h"

if want random; then
echo
first=$(value "$work/random-1000.glint.txt" "primary: ")
last=$(value "$work/random-$max_n.glint.txt" "primary: ")
printf 'Per-ray cost (primary), %s vs 10³ random triangles: glint %s×' "$max_n" "$(ratio "$first" "$last")"
efirst=$(value "$work/random-1000.embree.txt" "primary: ")
elast=$(value "$work/random-$max_n.embree.txt" "primary: ")
printf ', Embree %s×\n' "$(ratio "$efirst" "$elast")"
fi
want renders || exit 0

echo
echo "## Render: glint against POV-Ray 3.7, no anti-aliasing, whole-process wall time"
echo
echo "| scene | size | glint (CPU) | POV-Ray | glint / POV-Ray |"
echo "| --- | --- | ---: | ---: | ---: |"
python3 tools/benches/povray/obj2mesh2.py scenes/cs488/a4-2021plus/cow.obj Cow > "$work/Cow.inc"
python3 tools/benches/povray/obj2mesh2.py scenes/cs488/a4-2021plus/smstdodeca.obj Dodec > "$work/Dodec.inc"

# seconds COMMAND...: its wall time (its output discarded; a failure stops the script).
seconds() {
    local start end
    start=$(date +%s.%N)
    "$@" > /dev/null 2>&1 || { echo "failed: $*" >&2; exit 1; }
    end=$(date +%s.%N)
    awk -v a="$start" -v b="$end" 'BEGIN { printf "%.2f", b - a }'
}

render_row() {
    local name="$1" scene="$2" pov="$3" w="$4" h="$5"
    local tg tp
    tg=$(seconds "$glint" render "$scene" -o "$work/$name-glint.png" --backend cpu --threads "$threads" \
        --width "$w" --height "$h" --aa none --allow-read "$corpus")
    tp=$(seconds povray +I"$pov" +O"$work/$name-povray.png" +W"$w" +H"$h" \
        -A +WT"$threads" File_Gamma=1.0 +L"$work" -D -V)
    printf '| %s | %s×%s | %s s | %s s | %s |\n' "$name" "$w" "$h" "$tg" "$tp" "$(ratio "$tg" "$tp")"
}

render_row stadium tools/benches/scenes/stadium.lua tools/benches/povray/stadium.pov "$stadium_w" "$stadium_h"
render_row nonhier scenes/cs488/a4-2021plus/nonhier.lua tools/benches/povray/nonhier.pov "${render_size[0]}" "${render_size[1]}"
