#!/usr/bin/env bash
# Renders tests/golden/povray-torus.png, POV-Ray's rendition of the smooth torus that
# tests/oracle/shading.rs compares glint's smooth shading with (POV-Ray is not assumed in CI, so
# the image is checked in). Needs povray (3.7) and python3; run from the repository root:
#   bash tools/benches/povray/torus-reference.sh
set -euo pipefail
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python3 scenes/meshes/make_torus.py
python3 tools/benches/povray/obj2mesh2.py scenes/meshes/torus.obj Torus > "$work/Torus.inc"
povray +Ibenches/povray/torus.pov +O"$work/torus.png" +W200 +H150 -A +WT2 \
  File_Gamma=1.0 +L"$work" -D -GA 2> "$work/povray.log" || { cat "$work/povray.log"; exit 1; }
cp "$work/torus.png" tests/golden/povray-torus.png
echo "wrote tests/golden/povray-torus.png ($(povray --version 2>&1 | grep -o 'POV-Ray [0-9.a-z]*' | head -1))"
