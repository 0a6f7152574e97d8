#!/bin/sh
# The CUDA backend against the CPU backend on the same machine (issue 10,
# docs/cuda.md): path tracer samples/s on the Cornell box, the Cornell box
# with the dragon and the atrium (512x512, max depth 8); photon tracing, grid
# and gather times on the Cornell box (1M photons, 16 passes); and the solve
# of a 10,230-patch Cornell box (ray-cast form factors, 4096 rays a patch,
# Jacobi sweeps).  The CPU uses all its cores.  Needs a build with
# -DIL_CUDA=ON and a GPU (`illum info --devices`).
# Usage: bench/cuda.sh [BUILD_DIR] [GPU_SPP] [CPU_SPP]  (from the repository root)
set -e
I=${1:-build}/illum
G=${2:-1024}
C=${3:-64}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
# The first number after "KEY": in a --stats file.
num() { sed -n "s/.*\"$1\":[[:space:]]*\([-0-9.e+]*\).*/\1/p" "$2" | head -1; }
run() { # DEVICE NAME ARGS...: one render into $T/DEVICE.json
  d=$1
  shift
  "$I" render "$@" --device "$d" -q -o "$T/$d.exr" --stats "$T/$d.json"
}

echo "path tracer, 512x512, max depth 8 (GPU $G spp, CPU $C spp): Msamples/s"
printf "%-16s %10s %10s %8s\n" scene gpu cpu gpu/cpu
for s in cornell bench/scenes/cornell-dragon.json atrium; do
  run cuda "$s" --spp "$G"
  run cpu "$s" --spp "$C"
  awk -v n="$(basename "$s" .json)" -v g="$(num samples_per_second "$T/cuda.json")" \
      -v c="$(num samples_per_second "$T/cpu.json")" \
      'BEGIN { printf "%-16s %10.1f %10.2f %7.1fx\n", n, g / 1e6, c / 1e6, g / c }'
done

echo
echo "photon mapping, cornell, 1M photons, 512x512 at 16 passes (the GPU: fixed-radius grid"
echo "read at the first hit; the CPU: kd-tree, docs/photon-mapping.md): seconds"
printf "%-6s %12s %10s %10s %12s %14s\n" device photons/s trace build gather "gather/frame"
for d in cuda cpu; do
  run $d cornell --method photon --spp 16
  f=$T/$d.json
  awk -v d=$d -v p="$(num photons_per_second "$f")" -v t="$(num seconds_trace "$f")" \
      -v b="$(num seconds_build "$f")" -v g="$(num seconds_render "$f")" \
      'BEGIN { printf "%-6s %11.1fM %10.4f %10.4f %12.4f %14.4f\n", d, p / 1e6, t, b, g, g / 16 }'
done

echo
echo "radiosity, cornell --patch-size 0.017, ray-cast form factors (4096 rays a patch), Jacobi: seconds"
printf "%-6s %8s %7s %14s %10s\n" device patches sweeps "form factors" solve
for d in cuda cpu; do
  run $d cornell --method radiosity --patch-size 0.017 --form-factors raycast --solver jacobi --spp 1
  f=$T/$d.json
  awk -v d=$d -v n="$(num patches "$f")" -v s="$(num steps "$f")" -v ff="$(num seconds_form_factors "$f")" \
      -v t="$(num seconds_solve "$f")" 'BEGIN { printf "%-6s %8d %7d %14.4f %10.4f\n", d, n, s, ff, t }'
done
