# The command line end to end: every output format, stats, info, compare,
# determinism across thread counts, camera overrides.
. "$(dirname "$0")/lib.bash"

expect_exit 0 "help" -- "$ILLUM" --help
expect_stdout "render" "help"
for c in render info compare; do
    expect_exit 0 "$c --help" -- "$ILLUM" "$c" --help
    expect_stdout "usage: illum $c" "$c --help"
done
expect_exit 0 "version" -- "$ILLUM" --version
expect_exit 2 "version with an argument" -- "$ILLUM" --version extra
expect_exit 0 "help render" -- "$ILLUM" help render
expect_stdout "usage: illum render" "help render"
expect_exit 2 "help of an unknown command" -- "$ILLUM" help nosuch
expect_stderr "unknown command 'nosuch'" "help nosuch"

expect_exit 0 "info cornell" -- "$ILLUM" info cornell
expect_stdout "triangles:  32" "info cornell"

expect_exit 0 "render all formats" -- "$ILLUM" render cornell --width 32 --height 32 --spp 4 --quiet \
    -o c.png -o c.exr -o c.hdr -o c.pfm --stats stats.json
for f in c.png c.exr c.hdr c.pfm stats.json; do expect_file "$f" "render all formats"; done
checks=$((checks + 1))
grep -q '"spp":[[:space:]]*4' stats.json || fail "stats.json lacks spp 4"
checks=$((checks + 1))
grep -q '"rays_per_second"' stats.json || fail "stats.json lacks rays_per_second"

# The formats agree with each other within their precision.
expect_exit 0 "pfm vs exr(half)" -- "$ILLUM" compare c.exr c.pfm --max-rel-mse 1e-5
expect_exit 0 "pfm vs hdr" -- "$ILLUM" compare c.hdr c.pfm --max-rel-mse 1e-3
expect_exit 0 "compare identical" -- "$ILLUM" compare c.pfm c.pfm --max-rmse 0 --diff d.pfm
expect_stdout "rmse            0" "compare identical"
expect_file d.pfm "compare --diff"

# Same seed: bit-identical whatever the thread count; another seed differs.
expect_exit 0 "1 thread" -- "$ILLUM" render cornell --width 24 --height 24 --spp 3 --threads 1 --seed 7 -q -o t1.pfm
expect_exit 0 "2 threads" -- "$ILLUM" render cornell --width 24 --height 24 --spp 3 --threads 2 --seed 7 -q -o t2.pfm
checks=$((checks + 1))
cmp -s t1.pfm t2.pfm || fail "1 and 2 threads differ"
expect_exit 0 "other seed" -- "$ILLUM" render cornell --width 24 --height 24 --spp 3 --seed 8 -q -o t3.pfm
expect_exit 4 "another seed differs" -- "$ILLUM" compare t3.pfm t1.pfm --max-rmse 0

# Camera overrides and camera files: looking away from the box sees nothing.
expect_exit 0 "camera override" -- "$ILLUM" render cornell --width 8 --height 8 --spp 1 -q \
    --camera-pos 0.278,0.273,-0.8 --camera-target 0.278,0.273,-2 -o away.pfm
echo '{"position":[0.278,0.273,-0.8],"target":[0.278,0.273,-2],"fov":30}' > cam.json
expect_exit 0 "camera file" -- "$ILLUM" render cornell --width 8 --height 8 --spp 1 -q --camera-file cam.json -o away2.pfm
expect_exit 0 "black image" -- "$ILLUM" compare away.pfm away2.pfm --max-rmse 0
expect_stdout "mean_luminance  0  0" "black image"

# Time-limited rendering stops by itself.
expect_exit 0 "time limit" -- "$ILLUM" render cornell --width 16 --height 16 --time 0.5 -q -o timed.exr --stats timed.json
expect_file timed.exr "time limit"

# Ctrl-C: the render stops after the current pass, writes what it has and exits 130.
expect_interrupted 1 "interrupted render" -- "$ILLUM" render cornell --width 64 --height 64 \
    --time 60 -q -o interrupted.pfm --stats interrupted.json
expect_file interrupted.pfm "interrupted render"
expect_stderr "interrupted" "interrupted render"
checks=$((checks + 1))
grep -q '"interrupted":[[:space:]]*true' interrupted.json || fail "stats of the interrupted render"

# A second Ctrl-C quits at once, writing nothing: the way out of work that
# cannot stop part-way (here a first pass of 16.7 million samples, seconds
# long; a photon kd-tree build is another).
expect_interrupted 2 "second Ctrl-C" -- "$ILLUM" render cornell --width 4096 --height 4096 \
    --spp 2 -o never.pfm
expect_no_file never.pfm "second Ctrl-C"
expect_stderr "Ctrl-C again quits at once" "first Ctrl-C"

# --write-every: the running image is on disk while the render goes on.
expect_running_files "--write-every" running.pfm running.png -- \
    "$ILLUM" render cornell --width 64 --height 64 --time 20 --write-every 0.2 -q -o running.pfm -o running.png
expect_exit 1 "--write-every 0" -- "$ILLUM" render cornell --write-every 0 -o never.png
expect_no_file never.png "--write-every 0"

# A file without a camera gets the default one and renders.
if [ -n "${IL_SHARED_DIR:-}" ] && [ -f "$IL_SHARED_DIR/scenes/cornell-box-mcguire/CornellBox-Original.obj" ]; then
    expect_exit 0 "McGuire Cornell box" -- "$ILLUM" render "$IL_SHARED_DIR/scenes/cornell-box-mcguire/CornellBox-Original.obj" \
        --width 16 --height 16 --spp 2 -q -o mcguire.png
    expect_file mcguire.png "McGuire Cornell box"
fi
finish
