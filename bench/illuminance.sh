#!/bin/sh
# `illum illuminance` (docs/illuminance.md): seconds and ray rate of
#  1. work-plane grids: the office at y = 0.8 (0.5 m margin) and the
#     atrium at y = 0.85, 1024 samples a sensor, with their own lights and
#     (atrium) under the overcast sky alone;
#  2. the false-colour view of the Cornell box, 512x512 at 64 samples;
#  3. the noise of a grid against the sample count: the largest standard
#     error of the office's readings at 256, 1024 and 4096 samples;
#  4. scenes/window-room.json's work plane at 1024 samples, with its
#     window's portal and without it: seconds, noise.
# Usage: bench/illuminance.sh [BUILD_DIR] [THREADS] (from the repository root).
set -e
ILLUM=${1:-build}/illum
T=${2:-2}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
# The command's last stderr line: "illuminance: S s, R M rays/s".
timed() { "$@" --threads "$T" > "$OUT/out" 2> "$OUT/err"; tail -1 "$OUT/err" | sed 's/^illuminance: //'; }

echo "part 1: grids, 1024 samples, $T threads"
echo "office y=0.8:           $(timed "$ILLUM" illuminance office --plane y=0.8 --margin 0.5)"
echo "atrium y=0.85:          $(timed "$ILLUM" illuminance atrium --plane y=0.85)"
echo "atrium y=0.85, sky:     $(timed "$ILLUM" illuminance atrium --plane y=0.85 --sky overcast --sky-only)"
grep daylight "$OUT/out"
echo "part 2: view"
echo "cornell 512x512, 64:    $(timed "$ILLUM" illuminance cornell --view -o "$OUT/v.png")"
echo "part 3: the office's noise"
for n in 256 1024 4096; do
  timed "$ILLUM" illuminance office --plane y=0.8 --margin 0.5 --samples $n > /dev/null
  echo "$n samples: $(sed -n 's/^noise *//p' "$OUT/out")"
done
echo "part 4: window-room, 1024 samples, with and without its portal"
ROOM=scenes/window-room.json
sed -e '/"portals": \[/,/}\]},/d' -e 's/"environment": {"sky": "overcast",$/"environment": {"sky": "overcast"},/' \
    "$ROOM" > "$OUT/noportal.json"
for scene in "$ROOM" "$OUT/noportal.json"; do
  t=$(timed "$ILLUM" illuminance "$scene" --plane y=0.85 --area -2,-5,2,0 --margin 0.5)
  echo "$(basename "$scene"): $t; $(sed -n 's/^noise *//p' "$OUT/out")"
done
