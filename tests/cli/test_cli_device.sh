# The compute device options (docs/cuda.md): `illum info --devices` lists the
# CPU and says what there is of CUDA; `illum render --device cuda` stops with
# exit 3 and a reason, before writing anything, on a machine (or a build)
# without a usable GPU, and renders on one; unknown devices are bad input.
. "$(dirname "$0")/lib.bash"

expect_exit 0 "info --devices" -- "$ILLUM" info --devices
expect_stdout "^cpu: " "info --devices lists the CPU"
expect_stdout "^cuda" "info --devices says something about CUDA"
if grep -q "built without CUDA" out.txt; then cuda=off; else cuda=on; fi
if grep -q "^cuda:[0-9]" out.txt; then gpu=yes; else gpu=no; fi
echo "CUDA in the build: $cuda, a GPU: $gpu"

expect_exit 0 "render --help" -- "$ILLUM" render --help
expect_stdout "--device cpu|cuda" "render --help lists --device"
expect_exit 1 "unknown device" -- "$ILLUM" render cornell --device gpu -o bad.exr
expect_stderr "unknown device 'gpu'" "unknown device"
expect_no_file bad.exr "unknown device"
expect_exit 2 "--device without a value" -- "$ILLUM" render cornell --device

if [ "$cuda" = on ] && [ "$gpu" = yes ]; then
    # A GPU: path tracing, photon mapping and radiosity render; the other
    # methods are refused (bad input).
    expect_exit 0 "render --device cuda" -- "$ILLUM" render cornell --device cuda --spp 4 --width 32 --height 32 -q -o cuda.pfm
    expect_file cuda.pfm "render --device cuda"
    expect_exit 0 "render --device cuda --method photon" -- "$ILLUM" render cornell --device cuda --method photon --spp 4 --width 32 --height 32 -q -o photon.pfm
    expect_file photon.pfm "render --device cuda --method photon"
    expect_exit 0 "render --device cuda --method radiosity" -- "$ILLUM" render cornell --device cuda --method radiosity --spp 1 --width 32 --height 32 -q -o rad.pfm
    expect_file rad.pfm "render --device cuda --method radiosity"
    # --time, the ray count and Ctrl-C on the GPU (il_cuda_run).
    expect_exit 0 "render --device cuda --time" -- "$ILLUM" render cornell --device cuda --time 0.5 --width 32 --height 32 -q -o timed.pfm --stats timed.json
    expect_file timed.pfm "render --device cuda --time"
    checks=$((checks + 1))
    grep -Eq '"spp":[[:space:]]*[1-9]' timed.json && grep -Eq '"rays":[[:space:]]*[1-9]' timed.json ||
        { fail "render --device cuda --time: no samples or rays in the stats"; cat timed.json >&2; }
    expect_exit 0 "render --device cuda --method photon --time" -- "$ILLUM" render cornell --device cuda --method photon --time 0.5 --photons 10000 --width 32 --height 32 -q -o ptimed.pfm
    expect_file ptimed.pfm "render --device cuda --method photon --time"
    expect_exit 1 "render --device cuda --method radiosity --time" -- "$ILLUM" render cornell --device cuda --method radiosity --time 1 -o bad.exr
    expect_stderr "not --time" "render --device cuda --method radiosity --time"
    expect_no_file bad.exr "render --device cuda --method radiosity --time"
    # A closed white room has no finite solution: the GPU's sweeps stop as
    # stalled, say so, and write the image (the same test as on the CPU).
    echo '{"materials": {"w": {"diffuse": 1}, "e": {"diffuse": 1, "emission": 5}},
           "meshes": [{"shape": "box", "size": 4, "flip": true, "material": "w"},
                      {"shape": "box", "size": 0.5, "material": "e"}],
           "camera": {"position": [0, 1, 1.9], "target": [0, 0, 0]}}' > white.json
    expect_exit 0 "closed white room on the GPU" -- "$ILLUM" render white.json --device cuda --method radiosity \
        --patch-size 0.5 --width 16 --height 16 -o white.exr --stats white-stats.json
    expect_stderr "the solve stopped converging" "closed white room on the GPU"
    expect_file white.exr "closed white room on the GPU"
    checks=$((checks + 1))
    grep -q '"stalled":[[:space:]]*true' white-stats.json || { fail "white-stats.json: stalled is not true"; cat white-stats.json >&2; }
    expect_interrupted 1 "interrupted GPU render" -- "$ILLUM" render cornell --device cuda --spp 16000000 --width 64 --height 64 -q -o stopped.pfm --stats stopped.json
    expect_file stopped.pfm "interrupted GPU render"
    checks=$((checks + 1))
    grep -Eq '"interrupted":[[:space:]]*true' stopped.json || { fail "interrupted GPU render: stats"; cat stopped.json >&2; }
    # --write-every: the GPU's running image is on disk while the render
    # goes on (path tracing and the photon gather).
    for m in pt photon; do
        expect_running_files "render --device cuda --method $m --write-every" running_$m.pfm running_$m.png -- \
            "$ILLUM" render cornell --device cuda --method $m --width 64 --height 64 --time 20 --write-every 0.2 -q \
            -o running_$m.pfm -o running_$m.png
    done
    expect_exit 1 "render --device cuda --method sppm" -- "$ILLUM" render cornell --device cuda --method sppm -o bad.exr
    expect_stderr "method pt, photon or radiosity" "render --device cuda --method sppm"
    expect_no_file bad.exr "render --device cuda --method sppm"
else
    # No GPU, or no CUDA in the build: exit 3, a reason, no output file.
    expect_exit 3 "render --device cuda" -- "$ILLUM" render cornell --device cuda --spp 1 -o cuda.exr
    expect_no_file cuda.exr "render --device cuda"
    expect_exit 3 "render --device cuda --write-every" -- "$ILLUM" render cornell --device cuda --write-every 1 -o every.exr
    expect_no_file every.exr "render --device cuda --write-every"
    for m in photon radiosity; do
        expect_exit 3 "render --device cuda --method $m" -- "$ILLUM" render cornell --device cuda --method $m -o cuda.exr
        expect_no_file cuda.exr "render --device cuda --method $m"
    done
    if [ "$cuda" = off ]; then
        expect_stderr "built without CUDA" "render --device cuda, no CUDA build"
    else
        expect_stderr "use --device cpu" "render --device cuda, no GPU"
    fi
fi

# --device cpu is the default and renders as before.
expect_exit 0 "render --device cpu" -- "$ILLUM" render cornell --device cpu --spp 1 --width 32 --height 32 -q -o cpu.pfm
expect_file cpu.pfm "render --device cpu"
finish
