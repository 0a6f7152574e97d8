# Distributed rendering (docs/distributed.md), registered only with -DIL_MPI=ON:
# mpirun -np 2 and -np 3 on localhost give the single-process film bit for bit,
# and a failing rank ends the run with rank 0's message and no output.
. "$(dirname "$0")/../lib.bash"
. "$(dirname "$0")/mpi.bash"

# Cornell box, sizes that are not multiples of the 16-pixel tile, both
# samplers and filters; 1 thread per rank so the ranks share the cores.
render_args=(cornell --width 40 --height 28 --spp 6 --seed 11 --threads 1 -q)
expect_exit 0 "single process" -- "$ILLUM" render "${render_args[@]}" -o ref.pfm
for np in 1 2 3; do
    expect_exit 0 "mpirun -np $np" -- "${MPI[@]}" -np "$np" "$ILLUM" render "${render_args[@]}" \
        -o np$np.pfm -o np$np.exr --stats np$np.json
    expect_file np$np.pfm "mpirun -np $np"
    checks=$((checks + 1))
    cmp -s ref.pfm np$np.pfm || fail "mpirun -np $np: film differs from the single-process film"
    checks=$((checks + 1))
    grep -q '"spp":[[:space:]]*6' np$np.json || fail "mpirun -np $np: stats lack spp 6"
done
# A Gaussian filter and the PCG sampler go through the same tiles.
other=(cornell --width 33 --height 17 --spp 5 --seed 4 --filter gaussian --sampler pcg --threads 1 -q)
expect_exit 0 "single process (gaussian, pcg)" -- "$ILLUM" render "${other[@]}" -o ref2.pfm
expect_exit 0 "mpirun -np 3 (gaussian, pcg)" -- "${MPI[@]}" -np 3 "$ILLUM" render "${other[@]}" -o m2.pfm
checks=$((checks + 1))
cmp -s ref2.pfm m2.pfm || fail "mpirun -np 3 (gaussian, pcg): film differs"
# Ranks with 2 threads each get units of 4 tiles, split among their threads.
expect_exit 0 "mpirun -np 2, 2 threads each" -- "${MPI[@]}" -np 2 "$ILLUM" render cornell --width 40 \
    --height 28 --spp 6 --seed 11 --threads 2 -q -o t2.pfm
checks=$((checks + 1))
cmp -s ref.pfm t2.pfm || fail "mpirun -np 2, 2 threads each: film differs"
# The comparison can fail: another seed gives another film.
expect_exit 0 "mpirun -np 2, other seed" -- "${MPI[@]}" -np 2 "$ILLUM" render cornell --width 40 \
    --height 28 --spp 6 --seed 12 --threads 1 -q -o seed12.pfm
expect_exit 4 "another seed differs" -- "$ILLUM" compare seed12.pfm ref.pfm --max-rmse 0

# Only rank 0 writes and reports: one summary line, one mpi line.
expect_exit 0 "mpirun -np 2 verbose" -- "${MPI[@]}" -np 2 "$ILLUM" render cornell --width 32 \
    --height 32 --spp 2 --threads 1 -o v.pfm
expect_stderr "mpi: 2 ranks, 4 tiles" "mpirun -np 2 verbose"
checks=$((checks + 1))
[ "$(grep -c ' spp in ' err.txt)" = 1 ] || fail "mpirun -np 2: expected exactly one summary line"

# A rank whose tiles fail: rank 0 names it, exit 3, nothing written.  All
# ranks start rendering together (after a collective); 20 units of about
# 10 ms each make sure rank 2 gets one.
fail_args=(cornell --width 160 --height 64 --spp 32 --threads 1 -q -o bad.pfm)
expect_exit 3 "failing rank" -- "${MPI[@]}" -np 2 "$ILLUM" render "${fail_args[@]}" \
    : -np 1 env IL_MPI_TEST_FAIL=1 "$ILLUM" render "${fail_args[@]}"
expect_stderr "failed on rank 2: tile ([0-9]*, [0-9]*): failure injected" "failing rank"
expect_no_file bad.pfm "failing rank"
# A rank that fails before the render (its scene is missing).
expect_exit 1 "rank without its scene" -- "${MPI[@]}" -np 1 "$ILLUM" render "${render_args[@]}" \
    -o bad2.pfm : -np 1 "$ILLUM" render no-such-scene.obj --spp 6 -q -o bad2.pfm
expect_stderr "rank 1 failed before the render began" "rank without its scene"
expect_no_file bad2.pfm "rank without its scene"
# (--time under mpirun: test_cli_mpi_checkpoint.sh)
# (the other methods run split: test_cli_mpi_methods.sh)

finish
