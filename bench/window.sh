#!/bin/sh
# Photon mapping, SPPM and Linespace through a window (docs/photon-mapping.md,
# "Windows"): scenes/window-room.json, 160x120, under the overcast sky and
# under the clear sky with the sun at 30 degrees, and scenes/lamp-room.json
# (the overcast sky and a lamp in the room), and scenes/l-room.json (an
# L-shaped room: l-overcast, l-clear), against the path tracer
# at 1024 spp (another seed); photon at 64 spp (seconds, photons stored), SPPM and the
# path tracer for 10 s each (passes); Linespace at 64 spp with the portals'
# light and without (docs/linespace.md, "Windows"), and the path tracer for
# the time Linespace took.  Each line: the relative MSE and the
# mean luminance against the reference's, from `illum compare`.
# Usage: bench/window.sh [BUILD_DIR] [THREADS] (from the repository root).
set -e
ILLUM=${1:-build}/illum
T=${2:-2}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
SIZE="--width 160 --height 120 --threads $T -q --exr-float"
error() { "$ILLUM" compare "$1" "$OUT/ref.exr" | awk '/rel_mse/ {m = $2} /mean_luminance/ {a = $2; b = $3} END {printf "rel_mse %s, mean %s against %s", m, a, b}'; }
stat() { python3 -c "import json, sys; d = json.load(open('$OUT/s.json')); print($1)"; }
for sky in overcast clear lamp l-overcast l-clear; do
  SKY=""
  SCENE=scenes/window-room.json
  case $sky in *clear) SKY="--sky clear --sun 30,180" ;; esac
  [ $sky = lamp ] && SCENE=scenes/lamp-room.json
  case $sky in l-*) SCENE=scenes/l-room.json ;; esac
  "$ILLUM" render $SCENE $SIZE $SKY --spp 1024 --seed 1001 -o "$OUT/ref.exr"
  "$ILLUM" render $SCENE $SIZE $SKY --method photon --spp 64 -o "$OUT/a.exr" --stats "$OUT/s.json"
  echo "$sky, photon 64 spp: $(stat "'%.1f s, %d + %d photons stored' % (d['total_seconds'], d['photon']['stored_global'], d['photon']['stored_caustic'])"); $(error "$OUT/a.exr")"
  for m in sppm pt; do
    "$ILLUM" render $SCENE $SIZE $SKY --method $m --time 10 --spp 1000000 -o "$OUT/a.exr" --stats "$OUT/s.json"
    echo "$sky, $m 10 s: $(stat "'%d passes' % d['spp']"); $(error "$OUT/a.exr")"
  done
  for pl in off on; do
    "$ILLUM" render $SCENE $SIZE $SKY --method linespace --portal-light $pl --spp 64 -o "$OUT/a.exr" --stats "$OUT/s.json"
    echo "$sky, linespace 64 spp, --portal-light $pl: $(stat "'%.2f s, grid %s' % (d['total_seconds'], 'x'.join(str(g) for g in d['linespace']['grid']))"); $(error "$OUT/a.exr")"
  done
  T_LS=$(stat "'%.2f' % d['total_seconds']")
  "$ILLUM" render $SCENE $SIZE $SKY --method pt --time "$T_LS" --spp 1000000 -o "$OUT/a.exr" --stats "$OUT/s.json"
  echo "$sky, pt for linespace's $T_LS s: $(stat "'%d passes' % d['spp']"); $(error "$OUT/a.exr")"
done
