#!/bin/bash
# Regenerates docs/viewer.md's screenshots, docs/images/viewer-<method>.png:
# `illum view` of every method in scripted mode (--frames, --screenshot)
# under a virtual display (xvfb-run, Mesa's llvmpipe).
#   scripts/viewer-screenshots.sh [ILLUM] [SHARED]
# ILLUM: the program (default build/illum); SHARED: the folder with
# scenes/envmaps (default /tmp/shared).  About 3 minutes on 2 cores.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
illum=${1:-$root/build/illum}
shared=${2:-/tmp/shared}
probe=$shared/scenes/envmaps/probulator_pisa_256x128.hdr
out=$root/docs/images
[ -x "$illum" ] || { echo "no illum program at $illum" >&2; exit 1; }
[ -f "$probe" ] || { echo "no HDR probe at $probe" >&2; exit 1; }
command -v xvfb-run >/dev/null || { echo "xvfb-run not found (apt-get install xvfb xauth)" >&2; exit 1; }
mkdir -p "$out"
export LIBGL_ALWAYS_SOFTWARE=1

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# From outside the open front of the Cornell box, so that the environment
# shows around it (ibl).
cat > "$tmp/outside.json" <<'JSON'
{"position": [0.9, 0.6, -1.6], "target": [0.28, 0.27, 0.28], "up": [0, 1, 0], "fov": 45}
JSON

# shot METHOD [view options...]: 384 x 288, the info line printed.  The
# sample counts keep the noise (and so each PNG) small: under 150 KB.
shot() {
    local method=$1
    shift
    xvfb-run -a -s "-screen 0 1024x768x24" "$illum" view cornell --method "$method" \
        --width 384 --height 288 --seed 1 -q --frames 2 \
        --screenshot "$out/viewer-$method.png" "$@"
}
shot pt --spp 256
shot sppm --spp 128 --photons 50000
shot photon --spp 64
shot radiosity --spp 1 --subdiv 2 --keys B              # the mesh view with the patch boundaries
shot hr --spp 1                                         # the Gouraud-shaded mesh view
shot linespace --spp 128
shot rsm --spp 32
shot ibl --spp 4 --lights 256 --env "$probe" --camera-file "$tmp/outside.json"
ls -l "$out"/viewer-*.png
