#!/bin/sh
# The Linespace benchmark of issue 7: the Cornell box with its tall block
# diffuse, glossy (Phong 50), mirror and glass, and the atrium; 2 threads,
# max depth 4, 128x128; the default Linespace (grid 8, N 4, 1M paths), N 2,
# N 4 with the coarse level (--coarse on), with empty entries tracing on
# too (--fallback on, the default until 2026-11-28), and the final gather
# (--trace-first-bounce on) at N 4 and N 2; one second of sampling each
# (and 0.2 s for the diffuse box) against the path tracer
# (bench_linespace.c explains the columns).  Prints figures, never judges.
# Usage: bench/linespace.sh [BUILD_DIR] (run from the repository root).
set -e
B=${1:-build}/bench/bench_linespace
first=1
run() {
  out=$($B --threads 2 --time 1 "$@")
  if [ $first = 1 ]; then
    echo "$out" | head -1
    first=0
  fi
  echo "$out" | tail -n +2
}
for v in diffuse glossy mirror glass; do
  run cornell --variant $v
  run cornell --variant $v --linespace-n 2
  run cornell --variant $v --coarse on
  run cornell --variant $v --fallback on
  run cornell --variant $v --trace-first-bounce on
  run cornell --variant $v --trace-first-bounce on --linespace-n 2
done
# Equal time at a fifth of a second, where the path tracer's noise is larger.
run cornell --time 0.2
run cornell --time 0.2 --linespace-n 2
run atrium --ref-spp 2048
run atrium --ref-spp 2048 --coarse on
run atrium --ref-spp 2048 --fallback on
run atrium --ref-spp 2048 --grid 16 --linespace-n 2
run atrium --ref-spp 2048 --trace-first-bounce on
