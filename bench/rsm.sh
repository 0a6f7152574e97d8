#!/bin/sh
# The reflective-shadow-map benchmark of issue 7 (--method rsm) on the
# Cornell box lit by a spot (bench/scenes/cornell-spot-rsm.json, max depth 2:
# direct light and one bounce):
#  1. one 512x512 frame at 1 spp with a 512x512 map and 400 samples, without
#     and with the shadow test: seconds building the map and gathering
#     (wall; CPU seconds of the whole command from /usr/bin/time when present);
#  2. the error against a path-traced reference (--max-depth 2, REF_SPP spp)
#     of rsm at 4 spp, without and with the shadow test, and of the path
#     tracer given the same wall time as the shadow-tested rsm.
# Usage: bench/rsm.sh [BUILD_DIR] [THREADS] [REF_SPP] (from the repository root).
set -e
ILLUM=${1:-build}/illum
T=${2:-2}
REF_SPP=${3:-1024}
SCENE=bench/scenes/cornell-spot-rsm.json
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
field() { sed -n "s/.*\"$2\":[[:space:]]*\([^,]*\),*$/\1/p" "$1" | head -1; }
cpu() { if [ -x /usr/bin/time ]; then /usr/bin/time -f %U+%S -o "$OUT/cpu" "$@"; \
        echo "$(cat "$OUT/cpu" | bc 2>/dev/null || cat "$OUT/cpu")"; else "$@"; echo -; fi; }

echo "part 1: 512x512, 1 spp, map 512^2, 400 samples, $T threads"
echo "shadow_test build_s gather_s shadow_rays cpu_s"
for st in off on; do
  c=$(cpu "$ILLUM" render $SCENE --method rsm --rsm-shadow-test $st --spp 1 --threads $T -q \
      -o "$OUT/a.exr" --stats "$OUT/a.json")
  echo "$st $(field "$OUT/a.json" seconds_build) $(field "$OUT/a.json" seconds_gather)" \
       "$(field "$OUT/a.json" shadow_rays) $c"
done

echo "part 2: 256x256 against a path-traced reference (max depth 2, $REF_SPP spp)"
"$ILLUM" render $SCENE --method pt --max-depth 2 --spp $REF_SPP --width 256 --height 256 \
    --threads $T -q -o "$OUT/ref.exr" --seed 99
echo "method seconds rmse mean_lum mean_lum_ref"
for st in off on; do
  "$ILLUM" render $SCENE --method rsm --rsm-shadow-test $st --spp 4 --width 256 --height 256 \
      --threads $T -q -o "$OUT/rsm-$st.exr" --stats "$OUT/rsm-$st.json"
  secs=$(field "$OUT/rsm-$st.json" render_seconds)
  cmp=$("$ILLUM" compare "$OUT/rsm-$st.exr" "$OUT/ref.exr" | tr '\n' ' ')
  echo "rsm-shadow-$st $secs $(echo "$cmp" | awk '{print $2, $6, $7}')"
done
"$ILLUM" render $SCENE --method pt --max-depth 2 --time "$secs" --spp 1000000 --width 256 \
    --height 256 --threads $T -q -o "$OUT/pt.exr" --stats "$OUT/pt.json"
cmp=$("$ILLUM" compare "$OUT/pt.exr" "$OUT/ref.exr" | tr '\n' ' ')
echo "pt-equal-time($(field "$OUT/pt.json" spp)spp) $(field "$OUT/pt.json" render_seconds)" \
     "$(echo "$cmp" | awk '{print $2, $6, $7}')"
