#!/bin/sh
# The many-light benchmark of issue 6 (--method ibl), on the Stanford bunny
# and dragon on a ground plane under Grace Cathedral (256x128) and Poly
# Haven's Pedestrian Overpass (1k, a sun 69,000 times the mean):
#  1. a 512x512 frame with 1480 lights and ray-cast shadows on 1 and 2
#     threads (and shadow maps on 2 threads), wall and CPU seconds;
#  2. the error of the four light sets at equal time (2 s each on 1
#     thread, which a shared machine disturbs least) against a 32768-light
#     importance + Sobol reference with the same camera samples.
# Usage: bench/ibl.sh [BUILD_DIR] [1|2] (run from the repository root;
# the second argument runs only that part).
set -e
B=${1:-build}/bench/bench_ibl
PART=${2:-all}
E=../shared/scenes/envmaps
SCENES="bench/scenes/bunny-ground.json bench/scenes/dragon-ground.json"
MAPS="$E/probulator_grace_256x128.hdr $E/polyhaven_pedestrian_overpass_1k.hdr"
if [ "$PART" != 2 ]; then
  first=1
  for scene in $SCENES; do
    for env in $MAPS; do
      for run in "--threads 1" "--threads 2" "--threads 2 --shadows maps"; do
        out=$($B $scene --env $env --lights 1480 $run)
        if [ $first = 1 ]; then
          echo "$out" | head -1
          first=0
        fi
        echo "$out" | tail -1
      done
    done
  done
fi
if [ "$PART" != 1 ]; then
  first=1
  for scene in $SCENES; do
    for env in $MAPS; do
      out=$($B $scene --env $env --equal-time 2 --reference-lights 32768 --threads 1)
      if [ $first = 1 ]; then
        echo "$out" | head -1
        first=0
      fi
      echo "$out" | tail -n +2
    done
  done
fi
