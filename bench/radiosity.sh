#!/bin/sh
# The radiosity benchmark matrix of issue 3: simple room at 6,144 and 24,576
# patches, box room near 10,000 patches, converged to 0.01, 1 and 2 threads,
# both form-factor back-ends.  Usage: bench/radiosity.sh [BUILD_DIR]
set -e
B=${1:-build}/bench/bench_radiosity
for ff in hemicube raycast; do
  for t in 1 2; do
    $B simple-room --subdiv 5 --form-factors $ff --threads $t | tail -1
    $B simple-room --subdiv 6 --form-factors $ff --threads $t | tail -1
    $B box-room --patch-size 0.095 --form-factors $ff --threads $t | tail -1
  done
done
