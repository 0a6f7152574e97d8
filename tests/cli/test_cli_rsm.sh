# `illum render --method rsm` end to end: the help, small renders with every
# texel and with the sampling pattern, the shadow test, the "rsm" object of
# --stats and the summary line, determinism, and bad options that stop
# before any output is written.
. "$(dirname "$0")/lib.bash"

# A floor and a wall lit by a spot, a ball in the way of part of the light.
cat > corner.json <<'JSON'
{"meshes": [{"shape": "quad", "size": 2},
            {"shape": "quad", "size": 2, "material": "wall",
             "transform": {"rotate": [90, 0, 0], "translate": [0, 1, -1]}},
            {"shape": "sphere", "radius": 0.25, "segments": 24,
             "transform": {"translate": [0, 0.25, -0.6]}}],
 "materials": {"wall": {"type": "diffuse", "diffuse": [0.7, 0.7, 0.7]}},
 "lights": [{"type": "spot", "position": [0, 1.2, 0.35], "direction": [0, -1, -0.3],
             "intensity": 10, "angle": 30, "exponent": 2}],
 "camera": {"position": [0, 1, 2.6], "target": [0, 0.55, -0.4], "fov": 48}}
JSON

expect_exit 0 "render --method rsm --help" -- "$ILLUM" render --method rsm --help
for o in --rsm-size --rsm-samples --rsm-radius --rsm-maps --rsm-shadow-test; do
    expect_stdout -- "$o" "rsm help lists $o"
done
expect_exit 0 "render --help" -- "$ILLUM" render --help
expect_stdout "rsm: reflective shadow maps" "render help lists rsm"

expect_exit 0 "render rsm" -- "$ILLUM" render corner.json --method rsm --rsm-size 64 --rsm-samples 100 \
    --width 24 --height 24 --spp 2 -o rsm.exr -o rsm.png --stats rsm.json
expect_file rsm.exr "render rsm"
expect_file rsm.png "render rsm"
expect_stderr "illum: rsm: 1 maps of 64^2" "render rsm: summary line"
expect_stderr "100 samples, r_max 1.5, shadow test off, 0 shadow rays" "render rsm: summary line"
checks=$((checks + 1))
grep -q "warning" err.txt && fail "render rsm: a warning with a spot light"
for k in '"method":[[:space:]]*"rsm"' '"rsm":' '"resolution":[[:space:]]*64' '"samples":[[:space:]]*100' \
         '"radius":[[:space:]]*1.5' '"shadow_test":[[:space:]]*false' '"maps":[[:space:]]*1' \
         '"texels"' '"map_bytes"' '"gathered"' '"shadow_rays":[[:space:]]*0' '"seconds_build"' \
         '"seconds_gather"'; do
    checks=$((checks + 1))
    grep -q "$k" rsm.json || fail "rsm.json lacks $k"
done

expect_exit 0 "rsm --rsm-shadow-test on" -- "$ILLUM" render corner.json --method rsm --rsm-size 64 \
    --rsm-samples 100 --rsm-radius 0.5 --rsm-shadow-test on --width 24 --height 24 --spp 2 \
    -o shadow.exr --stats shadow.json
expect_stderr "r_max 0.5, shadow test on" "--rsm-shadow-test on: summary line"
for k in '"shadow_test":[[:space:]]*true' '"radius":[[:space:]]*0.5'; do
    checks=$((checks + 1))
    grep -q "$k" shadow.json || fail "shadow.json lacks $k"
done
checks=$((checks + 1))
grep -q '"shadow_rays":[[:space:]]*0,' shadow.json && fail "shadow.json: no shadow rays cast"
checks=$((checks + 1))
cmp -s shadow.exr rsm.exr && fail "rsm: the shadow test did not change the image"

expect_exit 0 "rsm --rsm-samples all" -- "$ILLUM" render corner.json --method rsm --rsm-size 32 \
    --rsm-samples all --width 16 --height 16 -q -o all.pfm --stats all.json
checks=$((checks + 1))
grep -q '"samples":[[:space:]]*"all"' all.json || fail "all.json: samples is not \"all\""
# The same seed gives the same image, whatever the thread count.
expect_exit 0 "rsm again, 1 thread" -- "$ILLUM" render corner.json --method rsm --rsm-size 32 \
    --rsm-samples all --width 16 --height 16 -q -o again.pfm --threads 1
checks=$((checks + 1))
cmp -s again.pfm all.pfm || fail "rsm: the same seed gave another image"
# Two point lights inside a box, twelve maps: 8 a shading point by default,
# --rsm-maps N or all; the same image again from the same seed with another
# thread count.
cat > points.json <<'JSON'
{"meshes": [{"shape": "box", "size": 4}],
 "lights": [{"type": "point", "position": [0.5, 0.3, 0], "intensity": 2},
            {"type": "point", "position": [-0.5, -0.3, 0.2], "intensity": 1}],
 "camera": {"position": [0, 0, 1.5], "target": [0, 0, -1], "fov": 60}}
JSON
for m in "" "--rsm-maps 3" "--rsm-maps all"; do
    expect_exit 0 "rsm points $m" -- "$ILLUM" render points.json --method rsm --rsm-size 16 \
        --rsm-samples 20 $m --width 12 --height 12 --spp 2 -o "points$m.pfm" --stats points.json.out
    case "$m" in
        "") want=8 ;; *3) want=3 ;; *) want=12 ;;
    esac
    expect_stderr "rsm: 12 maps of 16^2 ($want a shading point)" "rsm points $m: summary line"
    checks=$((checks + 1))
    grep -q "\"maps_per_point\":[[:space:]]*$want" points.json.out || fail "rsm points $m: maps_per_point"
done
expect_exit 0 "rsm points, 1 thread" -- "$ILLUM" render points.json --method rsm --rsm-size 16 \
    --rsm-samples 20 --rsm-maps 3 --width 12 --height 12 --spp 2 -q -o again3.pfm --threads 1
checks=$((checks + 1))
cmp -s again3.pfm "points--rsm-maps 3.pfm" || fail "rsm --rsm-maps 3: the same seed gave another image"
expect_exit 1 "--rsm-maps 0" -- "$ILLUM" render corner.json --method rsm --rsm-maps 0 -q -o bad.exr
expect_stderr "--rsm-maps" "--rsm-maps 0"
expect_exit 1 "--rsm-maps 5000" -- "$ILLUM" render corner.json --method rsm --rsm-maps 5000 -q -o bad.exr

# A scene without spot, point or directional light: direct light only, no map.
expect_exit 0 "rsm cornell (area light only)" -- "$ILLUM" render cornell --method rsm --width 16 \
    --height 16 --spp 1 -q -o cornell.pfm --stats cornell.json
checks=$((checks + 1))
grep -q '"maps":[[:space:]]*0' cornell.json || fail "cornell.json: an area light got a map"
expect_exit 0 "rsm cornell, not quiet" -- "$ILLUM" render cornell --method rsm --width 16 \
    --height 16 --spp 1 -o cornell.pfm
expect_stderr "warning: rsm: the scene has no point, spot or directional light" "rsm cornell: the warning"

# Bad values and options of the wrong method: exit 1 or 2, no output.
expect_exit 1 "--rsm-size 0" -- "$ILLUM" render corner.json --method rsm --rsm-size 0 -q -o bad.exr
expect_stderr "--rsm-size" "--rsm-size 0"
expect_exit 1 "--rsm-size 5000" -- "$ILLUM" render corner.json --method rsm --rsm-size 5000 -q -o bad.exr
expect_exit 1 "--rsm-samples 0" -- "$ILLUM" render corner.json --method rsm --rsm-samples 0 -q -o bad.exr
expect_exit 1 "--rsm-samples some" -- "$ILLUM" render corner.json --method rsm --rsm-samples some -q -o bad.exr
expect_exit 1 "--rsm-samples 70000" -- "$ILLUM" render corner.json --method rsm --rsm-samples 70000 -q -o bad.exr
expect_exit 1 "--rsm-radius 0" -- "$ILLUM" render corner.json --method rsm --rsm-radius 0 -q -o bad.exr
expect_exit 1 "--rsm-radius 3" -- "$ILLUM" render corner.json --method rsm --rsm-radius 3 -q -o bad.exr
expect_exit 1 "--rsm-radius nan" -- "$ILLUM" render corner.json --method rsm --rsm-radius nan -q -o bad.exr
expect_exit 1 "--rsm-shadow-test yes" -- "$ILLUM" render corner.json --method rsm --rsm-shadow-test yes -q -o bad.exr
expect_stderr "neither on nor off" "--rsm-shadow-test yes"
expect_exit 2 "--rsm-size without a value" -- "$ILLUM" render corner.json --method rsm --rsm-size
expect_exit 2 "rsm option with pt" -- "$ILLUM" render corner.json --rsm-size 64 -q -o bad.exr
expect_stderr "needs --method rsm" "rsm option with pt"
expect_exit 2 "rsm option with photon" -- "$ILLUM" render corner.json --method photon --rsm-shadow-test on -q -o bad.exr
expect_stderr "needs --method rsm" "rsm option with photon"
expect_no_file bad.exr "bad rsm options"
expect_exit 1 "bake rsm" -- "$ILLUM" bake corner.json --method rsm -q -o bad.ply
expect_no_file bad.ply "bake rsm"
finish
