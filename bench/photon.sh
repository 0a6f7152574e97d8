#!/bin/sh
# The photon-mapping benchmark matrix of issue 5: 250k, 1M and 6M photons on
# the Cornell box with its boxes, the caustics box, the Cornell box with the
# bunny and with the dragon, and the atrium; 1 and 2 threads; a 512x512
# frame with the global map read directly.
# Usage: bench/photon.sh [BUILD_DIR] (run from the repository root).
set -e
B=${1:-build}/bench/bench_photon
first=1
for scene in cornell cornell-spheres bench/scenes/cornell-bunny.json bench/scenes/cornell-dragon.json atrium; do
  for n in 250000 1000000 6000000; do
    for t in 1 2; do
      out=$($B $scene --photons $n --threads $t)
      if [ $first = 1 ]; then
        echo "$out" | head -1
        first=0
      fi
      echo "$out" | tail -1
    done
  done
done
