#!/bin/sh
# Linespace against the path tracer at equal total time, as a user of
# `illum render` meets them: the CLI's settings (max depth 8, grid 8, N 4,
# 1M injected paths) at 256x256 on the Cornell box and the atrium, with
# Linespace at 4, 16 (the default), 64 and 256 spp; its whole time (build,
# injection and sampling, --stats total_seconds) is given to the path
# tracer (--time).  Each line: the relative MSE of both against the path
# tracer at 2048 spp with another seed (whose own noise is in both).
# Prints figures, never judges.
# Usage: bench/linespace_total.sh [BUILD_DIR] [THREADS] (from the repository root).
set -e
I=${1:-build}/illum
T=${2:-2}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
S="--width 256 --height 256 --threads $T -q --exr-float"
json() { python3 -c "import json; print($1 % json.load(open('$2'))$3)"; }
err() { "$I" compare "$1" "$OUT/ref.exr" | awk '/rel_mse/ {print $2}'; }
for scene in cornell atrium; do
  "$I" render $scene $S --spp 2048 --seed 1001 -o "$OUT/ref.exr"
  for spp in 4 16 64 256; do
    "$I" render $scene $S --method linespace --spp $spp -o "$OUT/ls.exr" --stats "$OUT/ls.json"
    t=$(json "'%.3f'" "$OUT/ls.json" "['total_seconds']")
    "$I" render $scene $S --time "$t" --spp 1000000 -o "$OUT/pt.exr" --stats "$OUT/pt.json"
    p=$(json "'%d'" "$OUT/pt.json" "['spp']")
    echo "$scene: linespace $spp spp in $t s, rel_mse $(err "$OUT/ls.exr"); pt $p spp in that time, rel_mse $(err "$OUT/pt.exr")"
  done
done
