# `illum render --method linespace` end to end: the help, small renders of
# the Cornell box with the variants, the "linespace" object of --stats and
# the summary line, and bad options that stop before any output is written.
. "$(dirname "$0")/lib.bash"

expect_exit 0 "render --method linespace --help" -- "$ILLUM" render --method linespace --help
for o in --grid --linespace-n --inject-rays --inject-depth --blur --occlusion-test --fallback \
         --solid-angle --coarse --coarse-below --trace-first-bounce --glossy-n1 --glossy-n2 --portal-light; do
    expect_stdout -- "$o" "linespace help lists $o"
done

expect_exit 0 "render linespace" -- "$ILLUM" render cornell --method linespace --inject-rays 20000 \
    --grid 4 --linespace-n 2 --width 24 --height 24 --spp 2 -o ls.exr --stats ls.json
expect_file ls.exr "render linespace"
expect_stderr "illum: linespace: grid 4x4x4, N 2" "render linespace: summary line"
for k in '"method":[[:space:]]*"linespace"' '"linespace":' '"inject_rays":[[:space:]]*20000' '"voxels"' \
         '"shafts"' '"candidates"' '"memory_bytes"' '"injected_segments"' '"lookups"' '"lookup_hits"' \
         '"lookup_empty"' '"lookup_occluded"' '"lookup_coarse"' '"seconds_build"' '"seconds_inject"' '"seconds_sample"' \
         '"n":[[:space:]]*2'; do
    checks=$((checks + 1))
    grep -q "$k" ls.json || fail "ls.json lacks $k"
done
expect_exit 0 "render linespace, variants" -- "$ILLUM" render cornell --method linespace --inject-rays 20000 \
    --grid 6 --blur 0.5 --occlusion-test off --fallback off --solid-angle off --inject-depth 3 \
    --glossy-n1 5 --glossy-n2 50 --width 16 --height 16 --spp 1 -q -o var.pfm
expect_file var.pfm "render linespace, variants"
expect_exit 0 "render linespace, glossy and glass" -- "$ILLUM" render cornell-spheres --method linespace \
    --inject-rays 20000 --width 16 --height 16 --spp 1 -q -o spheres.pfm
expect_file spheres.pfm "render linespace, cornell-spheres"
expect_exit 0 "render linespace, coarse level" -- "$ILLUM" render cornell --method linespace --inject-rays 20000 \
    --grid 4 --coarse on --coarse-below 4 --width 16 --height 16 --spp 2 -o coarse.pfm --stats coarse.json
expect_file coarse.pfm "render linespace, coarse level"
expect_stderr "from the coarse level" "render linespace, coarse level: summary line"
checks=$((checks + 1))
grep -q '"lookup_coarse":[[:space:]]*[1-9]' coarse.json || fail "coarse.json: no lookup read the coarse level"
for f in on occluded; do
    expect_exit 0 "render linespace, --fallback $f" -- "$ILLUM" render cornell --method linespace \
        --inject-rays 20000 --grid 4 --fallback $f --width 16 --height 16 --spp 2 -q -o fallback-$f.pfm
    expect_file fallback-$f.pfm "render linespace, --fallback $f"
done
checks=$((checks + 1))
cmp -s fallback-on.pfm fallback-occluded.pfm && fail "--fallback on and occluded gave the same image"
expect_exit 0 "render linespace, final gather" -- "$ILLUM" render cornell --method linespace \
    --inject-rays 20000 --grid 4 --trace-first-bounce on --width 16 --height 16 --spp 2 -q -o gather.pfm
expect_file gather.pfm "render linespace, final gather"

# The window room (portals, the sky outside): the grid over the room in
# view and the portals' light, or with --portal-light off the whole scene.
for pl in on off; do
    expect_exit 0 "window room, --portal-light $pl" -- "$ILLUM" render "$IL_SOURCE_DIR/scenes/window-room.json" \
        --method linespace --inject-rays 20000 --portal-light $pl --width 16 --height 12 --spp 1 \
        -o window-$pl.pfm --stats window-$pl.json
    expect_file window-$pl.pfm "window room, --portal-light $pl"
    [ $pl = on ] && expect_stderr "grid 7x5x8 over the interior in view" "window room: summary line"
done
checks=$((checks + 2))
grep -q '"interior":[[:space:]]*true' window-on.json || fail "window-on.json: the grid is not the interior's"
grep -q '"interior":[[:space:]]*false' window-off.json || fail "window-off.json: the grid is not the scene's"
expect_exit 2 "--portal-light with pt" -- "$ILLUM" render cornell --portal-light off -q -o bad.exr
expect_stderr "needs --method photon, sppm or linespace" "--portal-light with pt"
expect_exit 1 "--portal-light maybe" -- "$ILLUM" render cornell --method linespace --portal-light maybe -q -o bad.exr

# Ctrl-C during the injection (2e9 light paths would take minutes): it
# stops, the image with the paths injected so far is written, exit 130.
expect_interrupted 1 "interrupted injection" -- "$ILLUM" render cornell --method linespace \
    --inject-rays 2000000000 --width 16 --height 16 --spp 1 -o stopped.pfm --stats stopped.json
expect_file stopped.pfm "interrupted injection"
expect_stderr "injection stopped after" "interrupted injection"
checks=$((checks + 1))
grep -q '"stopped":[[:space:]]*true' stopped.json || fail "interrupted injection: stats lack stopped"

# Bad values and options of the wrong method: exit 1 or 2, no output.
expect_exit 1 "--grid 0" -- "$ILLUM" render cornell --method linespace --grid 0 -q -o bad.exr
expect_exit 1 "--grid 1000" -- "$ILLUM" render cornell --method linespace --grid 1000 -q -o bad.exr
expect_exit 1 "--linespace-n 9" -- "$ILLUM" render cornell --method linespace --linespace-n 9 -q -o bad.exr
expect_exit 1 "--inject-rays 0" -- "$ILLUM" render cornell --method linespace --inject-rays 0 -q -o bad.exr
expect_exit 1 "--blur -1" -- "$ILLUM" render cornell --method linespace --blur -1 -q -o bad.exr
expect_exit 1 "--fallback maybe" -- "$ILLUM" render cornell --method linespace --fallback maybe -q -o bad.exr
expect_stderr "none of occluded, on and off" "--fallback maybe"
expect_exit 1 "--coarse-below 0" -- "$ILLUM" render cornell --method linespace --coarse-below 0 -q -o bad.exr
expect_exit 1 "--coarse-below 256" -- "$ILLUM" render cornell --method linespace --coarse-below 256 -q -o bad.exr
expect_exit 1 "--coarse sometimes" -- "$ILLUM" render cornell --method linespace --coarse sometimes -q -o bad.exr
expect_exit 1 "--trace-first-bounce 2" -- "$ILLUM" render cornell --method linespace --trace-first-bounce 2 -q -o bad.exr
expect_exit 1 "--glossy-n2 below n1" -- "$ILLUM" render cornell --method linespace --glossy-n1 50 \
    --glossy-n2 20 -q -o bad.exr
expect_stderr "below --glossy-n1" "--glossy-n2 below n1"
expect_exit 2 "--grid without a value" -- "$ILLUM" render cornell --method linespace --grid
expect_exit 2 "linespace option with pt" -- "$ILLUM" render cornell --inject-rays 1000 -q -o bad.exr
expect_stderr "needs --method linespace" "linespace option with pt"
expect_no_file bad.exr "bad linespace options"
expect_exit 1 "bake linespace" -- "$ILLUM" bake cornell --method linespace -q -o bad.ply
expect_no_file bad.ply "bake linespace"
finish
