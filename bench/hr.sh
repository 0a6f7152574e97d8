#!/bin/sh
# The hierarchical-radiosity benchmark matrix of issue 4: office, the Cornell
# box and the radiosity rooms at the default epsilons, 1 and 2 threads, with
# the parallel speedup of the solve (setup + refinement + gather).
# Usage: bench/hr.sh [BUILD_DIR]
set -e
B=${1:-build}/bench/bench_hr
first=1
for scene in office cornell simple-room box-room; do
  for t in 1 2; do
    out=$($B $scene --threads $t)
    if [ $first = 1 ]; then
      echo "$out" | head -1
      first=0
    fi
    line=$(echo "$out" | tail -1)
    echo "$line"
    # column 14 is solve_s
    solve=$(echo "$line" | awk '{print $14}')
    if [ $t = 1 ]; then s1=$solve; else
      echo "$scene: speedup on 2 threads $(awk -v a="$s1" -v b="$solve" 'BEGIN { if (b > 0) printf "%.2f", a / b; else print "n/a" }')"
    fi
  done
done
