# `illum render --method ibl` end to end: the help, small renders with each
# light selection and shadow method, the "ibl" object of --stats, a time
# limit, and bad options that stop before any output is written.
. "$(dirname "$0")/lib.bash"

cat > ball.json <<'JSON'
{"meshes": [{"shape": "quad", "size": 4},
            {"shape": "sphere", "radius": 0.5, "segments": 24, "material": "ball",
             "transform": {"translate": [0, 0.5, 0]}}],
 "materials": {"ball": {"type": "phong", "diffuse": [0.5, 0.3, 0.2], "specular": 0.2}},
 "camera": {"position": [0, 1.4, 3], "target": [0, 0.4, 0]},
 "environment": {"radiance": [0.8, 0.9, 1.0]}}
JSON

expect_exit 0 "render --method ibl --help" -- "$ILLUM" render --method ibl --help
for o in --lights --light-selection --shadows --batch --shadow-map-size --shadow-bias --pcf; do
    expect_stdout -- "$o" "ibl help lists $o"
done
expect_exit 0 "render --help" -- "$ILLUM" render --help
expect_stdout "pt|radiosity|hr|photon|sppm|ibl" "render help lists ibl"

expect_exit 0 "render ibl" -- "$ILLUM" render ball.json --method ibl --lights 200 --batch 50 \
    --width 24 --height 24 -o ibl.exr -o ibl.png --stats ibl.json
expect_file ibl.exr "render ibl"
expect_file ibl.png "render ibl"
expect_stderr "illum: ibl: 200 lights (importance-sobol), shadows rays" "render ibl: summary line"
for k in '"method":[[:space:]]*"ibl"' '"ibl":' '"lights":[[:space:]]*200' \
         '"selection":[[:space:]]*"importance-sobol"' '"shadows":[[:space:]]*"rays"' \
         '"batch":[[:space:]]*50' '"shadow_rays"' '"seconds_lights"' '"seconds_shade"' \
         '"spp":[[:space:]]*1,'; do
    checks=$((checks + 1))
    grep -q "$k" ibl.json || fail "ibl.json lacks $k"
done
checks=$((checks + 1))
grep -q '"shadow_rays":[[:space:]]*0,' ibl.json && fail "ibl.json: no shadow rays cast"

for sel in importance importance-sobol sobol random; do
    expect_exit 0 "--light-selection $sel" -- "$ILLUM" render ball.json --method ibl --lights 64 \
        --light-selection $sel --width 16 --height 16 -q -o sel-$sel.pfm
    expect_file sel-$sel.pfm "--light-selection $sel"
done
expect_exit 0 "--shadows maps" -- "$ILLUM" render ball.json --method ibl --lights 64 --shadows maps \
    --shadow-map-size 128 --shadow-bias 0.002 --pcf 5 --width 16 --height 16 -o maps.pfm --stats maps.json
expect_file maps.pfm "--shadows maps"
expect_stderr "shadows maps" "--shadows maps: summary line"
checks=$((checks + 1))
grep -q '"shadow_rays":[[:space:]]*0,' maps.json || fail "maps.json: shadow maps cast shadow rays"
expect_exit 0 "--shadows none" -- "$ILLUM" render ball.json --method ibl --lights 64 --shadows none \
    --width 16 --height 16 -q -o none.pfm
expect_file none.pfm "--shadows none"
# The same seed gives the same image; shadows change it.
expect_exit 0 "compare rays with themselves" -- "$ILLUM" compare sel-importance-sobol.pfm sel-importance-sobol.pfm
expect_exit 0 "render ibl again" -- "$ILLUM" render ball.json --method ibl --lights 64 --width 16 \
    --height 16 -q -o again.pfm --threads 1
checks=$((checks + 1))
cmp -s again.pfm sel-importance-sobol.pfm || fail "ibl: the same seed gave another image"
checks=$((checks + 1))
cmp -s none.pfm sel-importance-sobol.pfm && fail "ibl: --shadows none gave the shadowed image"

# A map through --env replaces the scene's sky; the benchmark scenes have
# no light of their own and need one.
MAP="$IL_SHARED_DIR/scenes/envmaps/probulator_grace_256x128.hdr"
BUNNY="$IL_SOURCE_DIR/bench/scenes/bunny-ground.json"
expect_exit 0 "ibl --env" -- "$ILLUM" render ball.json --env "$MAP" --method ibl --lights 64 \
    --width 16 --height 16 -q -o env.pfm
expect_file env.pfm "ibl --env"
checks=$((checks + 1))
cmp -s env.pfm sel-importance-sobol.pfm && fail "ibl --env: the map did not change the image"
expect_exit 0 "ibl bunny-ground --env" -- "$ILLUM" render "$BUNNY" --env "$MAP" --method ibl --lights 16 \
    --width 16 --height 16 -q -o bunny.pfm
expect_file bunny.pfm "ibl bunny-ground --env"
expect_exit 1 "bunny-ground without --env" -- "$ILLUM" render "$BUNNY" --method ibl --lights 16 -q -o nolight.pfm
expect_stderr "no light" "bunny-ground without --env"
expect_no_file nolight.pfm "bunny-ground without --env"

# A time limit stops after a batch (one batch of 256 lights over 64x64
# pixels takes well over the shortest limit, 1 ms); spp is antialiasing.
expect_exit 0 "ibl --time" -- "$ILLUM" render ball.json --method ibl --lights 100000 --batch 256 \
    --time 0.001 --width 64 --height 64 -q -o timed.exr --stats timed.json
checks=$((checks + 1))
grep -q '"lights":[[:space:]]*256,' timed.json || fail "ibl --time: not stopped after the first batch"
expect_exit 0 "ibl --spp 2" -- "$ILLUM" render ball.json --method ibl --lights 16 --spp 2 --width 8 \
    --height 8 -q -o spp.exr --stats spp.json
checks=$((checks + 1))
grep -q '"spp":[[:space:]]*2,' spp.json || fail "ibl --spp 2: stats spp"

# Bad values and options of the wrong method: exit 1 or 2, no output.
expect_exit 1 "--lights 0" -- "$ILLUM" render ball.json --method ibl --lights 0 -q -o bad.exr
expect_stderr "--lights" "--lights 0"
expect_exit 1 "--lights x" -- "$ILLUM" render ball.json --method ibl --lights x -q -o bad.exr
expect_exit 1 "--light-selection median-cut" -- "$ILLUM" render ball.json --method ibl \
    --light-selection median-cut -q -o bad.exr
expect_stderr "available: importance-sobol, importance, sobol, random" "--light-selection median-cut"
expect_exit 1 "--shadows soft" -- "$ILLUM" render ball.json --method ibl --shadows soft -q -o bad.exr
expect_stderr "available: rays, maps, none" "--shadows soft"
expect_exit 1 "--pcf 4" -- "$ILLUM" render ball.json --method ibl --pcf 4 -q -o bad.exr
expect_stderr "even" "--pcf 4"
expect_exit 1 "--pcf 17" -- "$ILLUM" render ball.json --method ibl --pcf 17 -q -o bad.exr
expect_exit 1 "--shadow-bias 0" -- "$ILLUM" render ball.json --method ibl --shadow-bias 0 -q -o bad.exr
expect_exit 1 "--shadow-bias nan" -- "$ILLUM" render ball.json --method ibl --shadow-bias nan -q -o bad.exr
expect_exit 1 "--shadow-map-size 0" -- "$ILLUM" render ball.json --method ibl --shadow-map-size 0 -q -o bad.exr
expect_exit 1 "--shadow-map-size 9000" -- "$ILLUM" render ball.json --method ibl --shadow-map-size 9000 -q -o bad.exr
expect_exit 1 "--batch 0" -- "$ILLUM" render ball.json --method ibl --batch 0 -q -o bad.exr
expect_exit 1 "ibl --spp 5000" -- "$ILLUM" render ball.json --method ibl --spp 5000 -q -o bad.exr
expect_stderr "spp 5000" "ibl --spp 5000"
expect_exit 2 "--lights without a value" -- "$ILLUM" render ball.json --method ibl --lights
expect_exit 2 "ibl option with pt" -- "$ILLUM" render ball.json --lights 100 -q -o bad.exr
expect_stderr "needs --method ibl" "ibl option with pt"
expect_exit 2 "ibl option with photon" -- "$ILLUM" render ball.json --method photon --shadows maps -q -o bad.exr
expect_stderr "needs --method ibl" "ibl option with photon"
expect_no_file bad.exr "bad ibl options"
# A scene lit only by a lamp has no environment to convert.
expect_exit 1 "ibl without environment" -- "$ILLUM" render cornell --method ibl -q -o noenv.exr
expect_stderr "no environment" "ibl without environment"
expect_no_file noenv.exr "ibl without environment"
expect_exit 1 "bake ibl" -- "$ILLUM" bake ball.json --method ibl -q -o bad.ply
expect_no_file bad.ply "bake ibl"
finish
