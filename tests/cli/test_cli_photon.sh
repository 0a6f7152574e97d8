# `illum render --method photon|sppm` end to end: the help, small renders of
# the caustics scene with each search structure, the "photon" object of
# --stats, and bad options that stop before any output is written.
. "$(dirname "$0")/lib.bash"

expect_exit 0 "render --method photon --help" -- "$ILLUM" render --method photon --help
for o in --photons --lookup --radius --photon-depth --k --photon-filter --final-gather --alpha \
         --initial-radius --precomputed-irradiance --portal-light; do
    expect_stdout -- "$o" "photon help lists $o"
done
expect_exit 0 "info cornell-spheres" -- "$ILLUM" info cornell-spheres

expect_exit 0 "render photon" -- "$ILLUM" render cornell-spheres --method photon --photons 20000 \
    --final-gather 2 --width 24 --height 24 --spp 1 -o pm.exr --stats pm.json
expect_file pm.exr "render photon"
expect_stderr "illum: photon: 20000 photons emitted" "render photon: summary line"
for k in '"method":[[:space:]]*"photon"' '"photon":' '"emitted":[[:space:]]*20000' '"stored_global"' \
         '"stored_caustic"' '"photon_rays"' '"seconds_trace"' '"seconds_build"' '"seconds_render"' \
         '"photons_per_second"' '"map_bytes"' '"bytes_per_photon":[[:space:]]*20'; do
    checks=$((checks + 1))
    grep -q "$k" pm.json || fail "pm.json lacks $k"
done
# The glass and the mirror make caustic photons.
checks=$((checks + 1))
grep -q '"stored_caustic":[[:space:]]*0,' pm.json && fail "cornell-spheres: no caustic photons"

expect_exit 0 "render photon, grid" -- "$ILLUM" render cornell-spheres --method photon --photons 20000 \
    --lookup grid --radius 0.03 --photon-filter epanechnikov --width 24 --height 24 --spp 1 -q -o grid.pfm
expect_file grid.pfm "render photon, grid"
expect_exit 0 "render photon, full estimates" -- "$ILLUM" render cornell --method photon --photons 20000 \
    --precomputed-irradiance off --width 16 --height 16 --spp 1 -q -o full.pfm
expect_file full.pfm "render photon, full estimates"
expect_exit 1 "--precomputed-irradiance maybe" -- "$ILLUM" render cornell --method photon \
    --precomputed-irradiance maybe -q -o bad.exr
expect_exit 0 "render sppm" -- "$ILLUM" render cornell --method sppm --photons 10000 --alpha 0.6 \
    --initial-radius 0.02 --width 24 --height 24 --spp 3 -o sppm.exr --stats sppm.json
expect_file sppm.exr "render sppm"
expect_stderr "illum: sppm: 3 passes, 30000 photons emitted" "render sppm: summary line"
checks=$((checks + 1))
grep -q '"passes":[[:space:]]*3' sppm.json || fail "sppm.json: passes is not 3"

# Photons through a window: with the portals' light most of them reach the
# room and are stored; without it, as without portals, almost none do.
stored() { sed -n 's/.*"stored_global":[[:space:]]*\([0-9]*\).*/\1/p' "$1"; }
for pl in on off; do
    expect_exit 0 "window room, --portal-light $pl" -- "$ILLUM" render "$IL_SOURCE_DIR/scenes/window-room.json" \
        --method photon --photons 20000 --portal-light $pl --width 16 --height 12 --spp 1 -q \
        -o window-$pl.pfm --stats window-$pl.json
done
checks=$((checks + 1))
[ "$(stored window-on.json)" -gt 10000 ] && [ "$(stored window-off.json)" -lt 1000 ] ||
    fail "window room: $(stored window-on.json) photons stored with the portals' light, $(stored window-off.json) without"
expect_exit 1 "--portal-light maybe" -- "$ILLUM" render cornell --method sppm --portal-light maybe -q -o bad.exr

# Ctrl-C while photons are traced (2e8 would take minutes): the tracing
# stops, the image with the photons traced so far is written, exit 130.
expect_interrupted 1 "interrupted photon tracing" -- "$ILLUM" render cornell --method photon \
    --photons 200000000 --width 16 --height 16 --spp 1 -o stopped.pfm --stats stopped.json
expect_file stopped.pfm "interrupted photon tracing"
expect_stderr "set-up stopped after" "interrupted photon tracing"
checks=$((checks + 1))
grep -q '"stopped":[[:space:]]*true' stopped.json || fail "interrupted photon tracing: stats lack stopped"

# Bad values and options of the wrong method: exit 1 or 2, no output.
expect_exit 1 "--photons 0" -- "$ILLUM" render cornell --method photon --photons 0 -q -o bad.exr
expect_no_file bad.exr "--photons 0"
expect_exit 1 "--lookup octree" -- "$ILLUM" render cornell --method photon --lookup octree -q -o bad.exr
expect_stderr "available: kdtree, grid" "--lookup octree"
expect_exit 1 "--radius 2" -- "$ILLUM" render cornell --method photon --radius 2 -q -o bad.exr
expect_exit 1 "--alpha 1" -- "$ILLUM" render cornell --method sppm --alpha 1 -q -o bad.exr
expect_exit 1 "--final-gather x" -- "$ILLUM" render cornell --method photon --final-gather x -q -o bad.exr
expect_exit 2 "--photons without a value" -- "$ILLUM" render cornell --method photon --photons
expect_exit 2 "photon option with pt" -- "$ILLUM" render cornell --photons 1000 -q -o bad.exr
expect_stderr "needs --method photon or --method sppm" "photon option with pt"
expect_exit 2 "final gather with sppm" -- "$ILLUM" render cornell --method sppm --final-gather 4 -q -o bad.exr
expect_stderr "needs --method photon" "final gather with sppm"
expect_exit 2 "alpha with photon" -- "$ILLUM" render cornell --method photon --alpha 0.5 -q -o bad.exr
expect_stderr "needs --method sppm" "alpha with photon"
expect_no_file bad.exr "options of the wrong method"
expect_exit 1 "bake photon" -- "$ILLUM" bake cornell --method photon -q -o bad.ply
expect_stderr "cannot bake" "bake photon"
expect_no_file bad.ply "bake photon"
finish
