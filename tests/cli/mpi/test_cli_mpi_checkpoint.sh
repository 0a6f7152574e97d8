# Failures and checkpoints of a distributed render (docs/distributed.md,
# "Failures and checkpoints"), registered only with -DIL_MPI=ON: a rank that
# fails or dies ends the run non-zero with rank 0's message and no new
# output; the same command run again continues from the checkpoint and gives
# the uninterrupted film bit for bit; a checkpoint of another render is
# refused.  Also --time and --write-every under mpirun.
. "$(dirname "$0")/../lib.bash"
. "$(dirname "$0")/mpi.bash"

# 96x48: 18 tiles; 1 thread per rank: units of 2 tiles.
args=(cornell --width 96 --height 48 --spp 8 --seed 5 --threads 1)
expect_exit 0 "single process" -- "$ILLUM" render "${args[@]}" -q -o ref.pfm
fail_error=(env IL_TEST_MPI_FAIL_RANK=1 IL_TEST_MPI_FAIL_AFTER=1)
fail_crash=(env IL_TEST_MPI_FAIL_RANK=1 IL_TEST_MPI_FAIL_AFTER=1 IL_TEST_MPI_FAIL_MODE=crash)

for np in 2 3; do
    # Rank 1 fails after 1 unit (rank 0 answers each worker's first two
    # requests before anything else, so it surely gets a second): exit 3, rank 0 names it, the previous
    # output is untouched, the checkpoint holds what was done.
    cp "$IL_SOURCE_DIR/CMakeLists.txt" out$np.pfm
    expect_exit 3 "np $np: failing rank" -- "${MPI[@]}" -np "$np" "${fail_error[@]}" "$ILLUM" \
        render "${args[@]}" -q -o out$np.pfm --checkpoint-every 0.001 --checkpoint ck$np.bin
    expect_stderr "failed on rank 1: tile ([0-9]*, [0-9]*): failure injected" "np $np: failing rank"
    expect_stderr "checkpoint ck$np.bin holds [1-9][0-9]* of 18 tiles" "np $np: failing rank"
    checks=$((checks + 1))
    cmp -s "$IL_SOURCE_DIR/CMakeLists.txt" out$np.pfm || fail "np $np: the previous output was changed"
    rm -f out$np.pfm
    expect_file ck$np.bin "np $np: checkpoint after the failure"
    # The same command again continues from it: the uninterrupted film.
    expect_exit 0 "np $np: restart" -- "${MPI[@]}" -np "$np" "$ILLUM" render "${args[@]}" \
        -o out$np.pfm --checkpoint-every 0.001 --checkpoint ck$np.bin
    expect_stderr "resuming from checkpoint ck$np.bin: [1-9][0-9]* of 18 tiles" "np $np: restart"
    checks=$((checks + 1))
    cmp -s ref.pfm out$np.pfm || fail "np $np: the restarted film differs from the uninterrupted one"
    expect_no_file ck$np.bin "np $np: checkpoint removed after the image is written"
done

# Rank 0 itself failing: the same, its own message.
expect_exit 3 "rank 0 failing" -- "${MPI[@]}" -np 2 env IL_TEST_MPI_FAIL_RANK=0 \
    IL_TEST_MPI_FAIL_AFTER=1 "$ILLUM" render "${args[@]}" -q -o r0.pfm --checkpoint-every 0.001
expect_stderr "failed on rank 0: tile ([0-9]*, [0-9]*): failure injected" "rank 0 failing"
checks=$((checks + 1))
[ ! -e r0.pfm ] && [ ! -e r0.pfm.tmp ] || fail "rank 0 failing: r0.pfm was written"
expect_file r0.pfm.ckpt "rank 0 failing: checkpoint"
expect_exit 0 "restart after rank 0 failed" -- "${MPI[@]}" -np 2 "$ILLUM" render "${args[@]}" -q \
    -o r0.pfm --checkpoint-every 0.001
checks=$((checks + 1))
cmp -s ref.pfm r0.pfm || fail "restart after rank 0 failed: film differs"

# A rank that dies (SIGKILL): mpirun ends the job, non-zero; rank 0 says so;
# no output; the checkpoint (default name: output + .ckpt) survives.
expect_exit_nonzero() {
    checks=$((checks + 1))
    "$@" >out.txt 2>err.txt && fail "a dying rank: exit 0 ($*)"
}
expect_exit_nonzero "${MPI[@]}" -np 2 "${fail_crash[@]}" "$ILLUM" render "${args[@]}" -q \
    -o crash.pfm --checkpoint-every 0.001
expect_stderr "rank 0 was ended by mpirun (a rank died" "a dying rank"
checks=$((checks + 1))
[ ! -e crash.pfm ] || fail "a dying rank: crash.pfm was written"
expect_file crash.pfm.ckpt "a dying rank: checkpoint"
expect_exit 0 "restart after a dying rank" -- "${MPI[@]}" -np 3 "$ILLUM" render "${args[@]}" -q \
    -o crash.pfm --checkpoint-every 0.001
checks=$((checks + 1))
cmp -s ref.pfm crash.pfm || fail "restart after a dying rank: film differs"
expect_no_file crash.pfm.ckpt "restart after a dying rank: checkpoint removed"

# A checkpoint of another render (another seed), a file that is not one, a
# damaged one: refused, kept, nothing written.
expect_exit 3 "checkpoint for the mismatch" -- "${MPI[@]}" -np 2 "${fail_error[@]}" "$ILLUM" \
    render "${args[@]}" -q -o mm.pfm --checkpoint-every 0.001 --checkpoint mm.bin
expect_file mm.bin "checkpoint for the mismatch"
expect_exit 1 "another seed" -- "${MPI[@]}" -np 2 "$ILLUM" render "${args[@]}" --seed 6 -q \
    -o mm.pfm --checkpoint-every 0.001 --checkpoint mm.bin
expect_stderr "mm.bin: written by another render" "another seed"
expect_no_file mm.pfm "another seed"
expect_file mm.bin "another seed: the checkpoint is kept"
head -c 1000 mm.bin >cut.bin
expect_exit 1 "a cut checkpoint" -- "${MPI[@]}" -np 2 "$ILLUM" render "${args[@]}" -q \
    -o mm.pfm --checkpoint-every 0.001 --checkpoint cut.bin
expect_stderr "cut.bin: damaged" "a cut checkpoint"
expect_exit 1 "not a checkpoint" -- "${MPI[@]}" -np 2 "$ILLUM" render "${args[@]}" -q \
    -o mm.pfm --checkpoint-every 0.001 --checkpoint ref.pfm
expect_stderr "ref.pfm: not an illum checkpoint" "not a checkpoint"
# The matching command still continues from mm.bin.
expect_exit 0 "the matching command" -- "${MPI[@]}" -np 2 "$ILLUM" render "${args[@]}" -q \
    -o mm.pfm --checkpoint-every 0.001 --checkpoint mm.bin
checks=$((checks + 1))
cmp -s ref.pfm mm.pfm || fail "the matching command: film differs"

# What checkpoints do not cover says so.
expect_exit 1 "checkpoint with photon" -- "${MPI[@]}" -np 2 "$ILLUM" render cornell --method photon \
    --width 32 --height 32 -q -o p.pfm --checkpoint-every 1
expect_stderr "checkpoints (--checkpoint-every) cover --method pt" "checkpoint with photon"
expect_exit 1 "checkpoint with --time" -- "${MPI[@]}" -np 2 "$ILLUM" render cornell --time 1 \
    --width 32 --height 32 -q -o p.pfm --checkpoint-every 1
expect_stderr "use --spp, not --time, with --checkpoint-every" "checkpoint with --time"
expect_exit 2 "checkpoint without mpirun" -- "$ILLUM" render "${args[@]}" -q -o p.pfm \
    --checkpoint-every 1
expect_stderr "work under mpirun" "checkpoint without mpirun"
expect_exit 1 "--checkpoint alone" -- "${MPI[@]}" -np 2 "$ILLUM" render "${args[@]}" -q -o p.pfm \
    --checkpoint c.bin
expect_stderr "--checkpoint needs --checkpoint-every" "--checkpoint alone"
expect_no_file p.pfm "refused checkpoints"

# --write-every writes rank 0's film so far: after a failure the last
# running image is there (whole, its unfinished tiles black).
expect_exit 3 "--write-every, failing rank" -- "${MPI[@]}" -np 2 "${fail_error[@]}" "$ILLUM" \
    render "${args[@]}" -q -o run.pfm --write-every 0.001
expect_file run.pfm "--write-every, failing rank"
expect_exit 4 "the running image is not the final one" -- "$ILLUM" compare run.pfm ref.pfm \
    --max-rmse 0
expect_exit 1 "--write-every with photon" -- "${MPI[@]}" -np 2 "$ILLUM" render cornell \
    --method photon --width 32 --height 32 -q -o p.pfm --write-every 1
expect_stderr "--write-every under mpirun: --method pt only" "--write-every with photon"

# A checkpoint made to pass the checksum but holding what no render writes
# (found by fuzzing: a NaN film was trusted, and its image came out as
# 65504s): a NaN in the first pixel, the FNV-1a sum written anew (bash's
# 64-bit arithmetic wraps as the C code's does).
expect_exit 3 "checkpoint for the NaN test" -- "${MPI[@]}" -np 2 "${fail_error[@]}" "$ILLUM" \
    render "${args[@]}" -q -o nan.pfm --checkpoint-every 0.001 --checkpoint cknan.bin
if [ -s cknan.bin ]; then
    size=$(stat -c %s cknan.bin)
    # The header (40 bytes), 18 done bytes, then the film: its first double NaN.
    printf '\x00\x00\x00\x00\x00\x00\xf8\x7f' | dd of=cknan.bin bs=1 seek=58 conv=notrunc 2>/dev/null
    h=$((0xcbf29ce484222325))
    for b in $(head -c $((size - 8)) cknan.bin | od -An -v -tu1); do
        h=$(( (h ^ b) * 0x100000001b3 ))
    done
    sum=""
    for k in 0 1 2 3 4 5 6 7; do sum="$sum\\x$(printf '%02x' $(( (h >> (8 * k)) & 255 )))"; done
    printf "$sum" | dd of=cknan.bin bs=1 seek=$((size - 8)) conv=notrunc 2>/dev/null
    expect_exit 1 "a checkpoint holding NaN" -- "${MPI[@]}" -np 2 "$ILLUM" render "${args[@]}" \
        -q -o nan.pfm --checkpoint-every 0.001 --checkpoint cknan.bin
    expect_stderr "checkpoint cknan.bin: pixel 0 holds nan, which no render writes" "a checkpoint holding NaN"
    expect_no_file nan.pfm "a checkpoint holding NaN"
else
    fail "checkpoint for the NaN test: no checkpoint"
fi

# --time: rounds of samples until the deadline; --spp caps them.
expect_exit 0 "--time with --spp" -- "${MPI[@]}" -np 2 "$ILLUM" render cornell --width 48 \
    --height 32 --time 100 --spp 6 --threads 1 -q -o time.pfm --stats time.json
checks=$((checks + 1))
grep -q '"spp":[[:space:]]*6' time.json || fail "--time with --spp 6: stats lack spp 6"
expect_exit 0 "--time alone" -- "${MPI[@]}" -np 3 "$ILLUM" render cornell --width 48 \
    --height 32 --time 0.3 --threads 1 -q -o time2.pfm
expect_file time2.pfm "--time alone"

finish
