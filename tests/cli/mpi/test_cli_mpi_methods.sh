# Every method but the path tracer under mpirun (docs/distributed.md: photon
# mapping, SPPM, radiosity, hierarchical radiosity, IBL, Linespace, RSM),
# registered only with -DIL_MPI=ON:
# -np 2 and -np 3 on localhost give the single-process film bit for bit.
. "$(dirname "$0")/../lib.bash"
. "$(dirname "$0")/mpi.bash"

# same_as_single NAME NPS -- RENDER ARGS...: the single-process film, then
# one mpirun per rank count, each compared byte for byte (PFM: the floats).
same_as_single() {
    name=$1; nps=$2; shift 3
    expect_exit 0 "$name: single process" -- "$ILLUM" render "$@" -q -o "$name-ref.pfm"
    for np in $nps; do
        expect_exit 0 "$name: mpirun -np $np" -- "${MPI[@]}" -np "$np" "$ILLUM" render "$@" -q \
            -o "$name-np$np.pfm" --stats "$name-np$np.json"
        expect_file "$name-np$np.pfm" "$name: mpirun -np $np"
        checks=$((checks + 1))
        cmp -s "$name-ref.pfm" "$name-np$np.pfm" ||
            fail "$name: mpirun -np $np: film differs from the single-process film"
    done
}

# Cornell box at a size that is not a multiple of the 16-pixel tile, 1
# thread per rank so that the ranks share the two cores.
base=(cornell --width 40 --height 28 --spp 2 --seed 7 --threads 1)
# Photon mapping with final gathering: photon ranges, the global map's
# kd-tree build (over 16384 photons), the precomputed irradiance and the
# camera tiles all split; the spheres' glass fills the caustic map too.
same_as_single photon "2 3" -- cornell-spheres "${base[@]:1}" --method photon --photons 20000 \
    --final-gather 4
# The grid lookup without precomputed irradiance.
same_as_single photon-grid "2" -- "${base[@]}" --method photon --photons 20000 --lookup grid \
    --precomputed-irradiance off
# SPPM: 3 passes, each pass's photons and kd-tree build split, pixel rows split.
same_as_single sppm "2 3" -- "${base[@]}" --spp 3 --method sppm --photons 20000
checks=$((checks + 1))
grep -q '"spp":[[:space:]]*3' sppm-np3.json || fail "sppm -np 3: stats lack 3 passes"
# The grid's cell size is the largest radius of all ranks' pixels.
same_as_single sppm-grid "2" -- "${base[@]}" --spp 3 --method sppm --photons 20000 --lookup grid
# Progressive radiosity (shooting, hemicube rows split) and Jacobi gathering
# over 1088 patches whose 1 MB row cache holds a fifth of the rows, so that
# every sweep recomputes rows and the ranks' caches differ.
same_as_single radiosity "2 3" -- "${base[@]}" --method radiosity --subdiv 2 --hemicube-res 32
same_as_single jacobi "3" -- "${base[@]}" --method radiosity --subdiv 3 --hemicube-res 32 \
    --solver jacobi --ff-cache-mb 1
# Ranks with different thread counts (as nodes of different sizes with
# --threads 0) still fetch the same row blocks: Gauss-Seidel gathering with
# ray-cast rows.
gs=(cornell --width 40 --height 28 --spp 2 --seed 7 --method radiosity --subdiv 2 --form-factors raycast
    --ff-samples 256 --solver gauss-seidel -q)
expect_exit 0 "gauss-seidel: single process" -- "$ILLUM" render "${gs[@]}" --threads 1 -o gs-ref.pfm
expect_exit 0 "gauss-seidel: ranks of 1 and 4 threads" -- timeout 120 "${MPI[@]}" -np 1 "$ILLUM" render "${gs[@]}" \
    --threads 1 -o gs.pfm : -np 1 "$ILLUM" render "${gs[@]}" --threads 4 -o gs.pfm
checks=$((checks + 1))
cmp -s gs-ref.pfm gs.pfm || fail "gauss-seidel, ranks of 1 and 4 threads: film differs"
# Hierarchical radiosity: each refinement's new links (form factors and
# visibility rays) split in sweeps; every rank builds the same hierarchy.
same_as_single hr "2 3" -- "${base[@]}" --method hr
# Spheres (triangles, more levels), a non-square ray count (no staged rays),
# 2 threads per rank.
same_as_single hr-spheres "2" -- cornell-spheres --width 40 --height 28 --spp 2 --seed 7 \
    --threads 2 --method hr --vis-rays 9
# The image methods with a precomputation every rank repeats (the same on
# each) and camera tiles split: Linespace, reflective shadow maps (with the
# shadow test), the environment as lights.
same_as_single linespace "2 3" -- "${base[@]}" --method linespace --linespace-n 2 --inject-rays 20000
same_as_single rsm "2" -- "${base[@]}" --method rsm --rsm-size 64 --rsm-samples 32 --rsm-shadow-test on
env_map="${IL_SHARED_DIR:-$IL_SOURCE_DIR/../shared}/scenes/envmaps/polyhaven_venice_sunset_1k.hdr"
same_as_single ibl "2 3" -- "${base[@]}" --method ibl --env "$env_map" --lights 32 --batch 8
# Their tiles go on demand: every rank claims some.
expect_exit 0 "rsm verbose" -- "${MPI[@]}" -np 2 "$ILLUM" render "${base[@]}" --method rsm --rsm-size 64 \
    --rsm-samples 32 -o rv.pfm
expect_stderr "camera tile claims per rank: [1-9][0-9]* [1-9]" "rsm verbose"
expect_exit 0 "hr verbose" -- "${MPI[@]}" -np 2 "$ILLUM" render "${base[@]}" --method hr -o hv.pfm
expect_stderr "mpi: 2 ranks, hr: .* exchanges, .* MB gathered" "hr verbose"

# The comparison can fail: another seed gives another SPPM film.
expect_exit 0 "sppm, other seed" -- "${MPI[@]}" -np 2 "$ILLUM" render cornell --width 40 \
    --height 28 --spp 3 --seed 8 --threads 1 --method sppm --photons 20000 -q -o seed8.pfm
expect_exit 4 "another seed differs" -- "$ILLUM" compare seed8.pfm sppm-ref.pfm --max-rmse 0

# Only rank 0 reports: one figures line with the exchanges, one summary.
expect_exit 0 "photon verbose" -- "${MPI[@]}" -np 2 "$ILLUM" render "${base[@]}" --method photon \
    --photons 5000 -o v.pfm
expect_stderr "mpi: 2 ranks, photon: .* 2 exchanges, .* MB gathered" "photon verbose"
checks=$((checks + 1))
[ "$(grep -c ' spp in ' err.txt)" = 1 ] || fail "photon verbose: expected exactly one summary line"

# What cannot run split says so, on rank 0, and writes nothing.
expect_exit 1 "sppm --time under mpirun" -- "${MPI[@]}" -np 2 "$ILLUM" render cornell --width 16 \
    --height 16 --method sppm --time 1 --threads 1 -q -o t.pfm
expect_stderr "renders a pass count, not for a time" "sppm --time under mpirun"
expect_no_file t.pfm "sppm --time under mpirun"

finish
