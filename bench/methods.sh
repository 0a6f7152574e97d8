#!/bin/sh
# Every method on one scene against a long path-traced reference.  Each
# method runs at its defaults (unless its row says otherwise) and renders
# for BUDGET seconds after its own set-up (solve, photon maps, injection);
# the table gives its whole wall time, its mean luminance over the
# reference's, its relative MSE, and the relative MSE of the path tracer
# given that same wall time.  Prints figures, never judges; docs/methods.md
# shows the tables.
#
# Usage: bench/methods.sh [BUILD_DIR] [SCENE] [REF_SPP] [-- EXTRA RENDER OPTIONS]
#   (run from the repository root; default build, cornell, 4096 spp)
# Environment: BUDGET (seconds of rendering, default 2), W, H (image size,
# default 128), THREADS (default 2), METHODS (default "pt radiosity hr
# photon photon-fg sppm linespace linespace-fg rsm rsm-shadow ibl"; rsm
# needs a spot or point light, ibl an environment: e.g. `-- --env FILE`).
set -e
B=${1:-build}/illum
SCENE=${2:-cornell}
REF=${3:-4096}
[ $# -gt 3 ] && shift 3 || shift $#
[ "${1:-}" = "--" ] && shift
W=${W:-128}
H=${H:-128}
THREADS=${THREADS:-2}
BUDGET=${BUDGET:-2}
METHODS=${METHODS:-"pt radiosity hr photon photon-fg sppm linespace linespace-fg rsm rsm-shadow ibl"}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT

# The scene's render settings (max depth, camera) apply to every run; only
# the size, the seed and the thread count are set here.
common="--width $W --height $H --seed 1 --threads $THREADS -q"

seconds() { sed -n 's/.*"total_seconds":[[:space:]]*\([0-9.eE+-]*\).*/\1/p' "$1"; }
# The relative MSE and mean luminance ratio of $1 against the reference.
errors() {
  "$B" compare "$1" "$T/ref.exr" | awk '
    $1 == "rel_mse" { rel = $2 }
    $1 == "mean_luminance" { ratio = ($3 > 0) ? $2 / $3 : 0 }
    END { printf "%9.3f %9.5f", ratio, rel }'
}

"$B" render "$SCENE" $common "$@" --spp "$REF" --exr-float -o "$T/ref.exr" --stats "$T/ref.json"
echo "scene $SCENE, ${W}x$H, $THREADS threads, $BUDGET s of rendering each; reference: pt at $REF spp in $(seconds "$T/ref.json" | awk '{ printf "%.1f", $1 }') s"
printf '%-26s %8s %9s %9s %9s\n' "method" "seconds" "mean/ref" "rel_mse" "pt rel_mse"
printf '%-26s %8s %9s %9s %9s\n' "" "" "" "" "same time"

for m in $METHODS; do
  case $m in
    pt) args="--method pt"; label="pt" ;;
    radiosity) args="--method radiosity"; label="radiosity" ;;
    hr) args="--method hr"; label="hr" ;;
    photon) args="--method photon"; label="photon (map read directly)" ;;
    photon-fg) args="--method photon --final-gather 32"; label="photon, final gather 32" ;;
    sppm) args="--method sppm"; label="sppm" ;;
    linespace) args="--method linespace"; label="linespace" ;;
    linespace-fg) args="--method linespace --trace-first-bounce on"; label="linespace, final gather" ;;
    rsm) args="--method rsm"; label="rsm" ;;
    rsm-shadow) args="--method rsm --rsm-shadow-test on"; label="rsm, shadow test" ;;
    ibl) args="--method ibl --spp 4 --lights 1048576"; label="ibl (4 spp)" ;;
    *) echo "bench/methods.sh: unknown method '$m'" >&2; exit 2 ;;
  esac
  # A method the scene does not suit (ibl without an environment) says so
  # on stderr and is left out.
  if ! "$B" render "$SCENE" $common "$@" --time "$BUDGET" --spp 1000000 $args --exr-float -o "$T/m.exr" --stats "$T/m.json" 2>"$T/err"; then
    printf '%-26s %s\n' "$label" "not run: $(tail -n 1 "$T/err")"
    continue
  fi
  s=$(seconds "$T/m.json" | awk '{ printf "%.3f", ($1 < 0.001) ? 0.001 : $1 }')
  e=$(errors "$T/m.exr")
  # The path tracer given the method's whole wall time to render in.
  "$B" render "$SCENE" $common "$@" --method pt --spp 1000000 --time "$s" --exr-float -o "$T/pt.exr"
  pt=$(errors "$T/pt.exr" | awk '{ print $2 }')
  printf '%-26s %8.2f %s %9s\n' "$label" "$s" "$e" "$pt"
done
