# `illum render --method radiosity` and `illum bake` end to end: images,
# stats, bakes in every format, and bad options that must stop before any
# output is written.  Small meshes and hemicubes keep it quick.
. "$(dirname "$0")/lib.bash"

R="--method radiosity --subdiv 2 --hemicube-res 32"

expect_exit 0 "render --method radiosity --help" -- "$ILLUM" render --method radiosity --help
for o in --patch-size --subdiv --form-factors --hemicube-res --ff-samples --solver --tolerance \
         --max-steps --ff-cache-mb --adaptive; do
    expect_stdout -- "$o" "radiosity help lists $o"
done
expect_exit 0 "bake --help" -- "$ILLUM" bake --help
expect_stdout "usage: illum bake" "bake --help"
expect_exit 0 "help bake" -- "$ILLUM" help bake
expect_exit 0 "info simple-room" -- "$ILLUM" info simple-room
expect_stdout "triangles:  12" "info simple-room"

# Render: an image, stats with the radiosity object, and compare runs on it.
expect_exit 0 "render simple-room" -- "$ILLUM" render simple-room $R --width 32 --height 32 --spp 2 \
    -q -o room.exr --stats room.json
expect_file room.exr "render simple-room"
for k in '"method":[[:space:]]*"radiosity"' '"radiosity":' '"patches":[[:space:]]*96' '"steps"' \
         '"unshot_fraction"' '"seconds_form_factors"' '"rows_computed"' '"peak_bytes"' \
         '"form_factors":[[:space:]]*"hemicube"'; do
    checks=$((checks + 1))
    grep -q "$k" room.json || fail "room.json lacks $k"
done
expect_exit 0 "compare radiosity image" -- "$ILLUM" compare room.exr room.exr --max-rmse 0
expect_stdout "rmse" "compare radiosity image"
# The ceiling light makes the image bright: the mean luminance is not zero.
checks=$((checks + 1))
grep -q "mean_luminance  0  0" out.txt && fail "radiosity image is black"

# Ray-cast form factors and a gathering solver run as well.
expect_exit 0 "raycast + jacobi" -- "$ILLUM" render shadow-room --method radiosity --subdiv 1 \
    --form-factors raycast --ff-samples 256 --solver jacobi --width 16 --height 16 --spp 1 -o shadow.pfm
expect_file shadow.pfm "raycast + jacobi"
# The summary gives no ray rate: the solve's rays are not counted, and the
# camera's over the whole time would read as a slow ray caster.
expect_stderr "illum: 1 spp in .* s (.* Msamples/s) -> shadow.pfm" "radiosity summary"
checks=$((checks + 1))
grep -q "Mrays/s" err.txt && fail "radiosity summary gives a ray rate"

# --form-factors auto (the default) takes ray-cast when the hemicube would
# have fewer than 4 pixels a patch (3*32^2 pixels, simple-room's 1,536
# patches at 4 levels) and says so in the summary and the stats.
for ff in "" "--form-factors auto"; do
    expect_exit 0 "auto form factors $ff" -- "$ILLUM" render simple-room --method radiosity --subdiv 4 \
        --hemicube-res 32 $ff --ff-samples 64 --max-steps 1 --width 8 --height 8 --spp 1 -o big.pfm \
        --stats big.json
    expect_stderr "1536 patches.*form factors (raycast)" "auto form factors $ff"
    checks=$((checks + 1))
    grep -q '"form_factors":[[:space:]]*"raycast"' big.json || fail "big.json: auto did not choose raycast"
done

# A JSON scene's "render" block can choose the method; then radiosity options
# need no --method on the command line.
cat > scene.json <<'EOF'
{
  "materials": {"light": {"emission": 1, "diffuse": 0.5}, "wall": {"diffuse": 0.6}},
  "meshes": [
    {"shape": "box", "size": 2, "flip": true, "material": "wall", "transform": {"translate": [0, 1, 0]}},
    {"shape": "quad", "size": 0.5, "flip": true, "material": "light", "transform": {"translate": [0, 1.99, 0]}}
  ],
  "camera": {"position": [0, 1, 0.9], "target": [0, 1, -1]},
  "render": {"method": "radiosity", "width": 8, "height": 8, "spp": 1}
}
EOF
expect_exit 0 "JSON render block selects radiosity" -- "$ILLUM" render scene.json --subdiv 1 --hemicube-res 32 \
    -q -o json.exr --stats json.json
expect_file json.exr "JSON render block selects radiosity"
checks=$((checks + 1))
grep -q '"method":[[:space:]]*"radiosity"' json.json || fail "json.json: method is not radiosity"
expect_exit 2 "JSON radiosity, --method pt with a radiosity option" -- "$ILLUM" render scene.json --method pt \
    --subdiv 1 -q -o json2.exr
expect_no_file json2.exr "JSON radiosity, --method pt with a radiosity option"

# Bake: PLY and GLB (and .gltf with its .bin).
expect_exit 0 "bake ply" -- "$ILLUM" bake simple-room --subdiv 1 --hemicube-res 32 -q -o room.ply --stats bake.json
expect_file room.ply "bake ply"
checks=$((checks + 1))
head -c 400 room.ply | grep -q "property float radiance_r" || fail "room.ply lacks radiance_r"
checks=$((checks + 1))
grep -q '"radiosity":' bake.json || fail "bake.json lacks the radiosity object"
expect_exit 0 "bake glb" -- "$ILLUM" bake box-room --subdiv 1 --hemicube-res 32 --exposure -1 -q -o room.glb
expect_file room.glb "bake glb"
checks=$((checks + 1))
head -c 4 room.glb | grep -q "glTF" || fail "room.glb is not a GLB"
expect_exit 0 "bake gltf" -- "$ILLUM" bake simple-room --subdiv 1 --hemicube-res 32 -q -o room.gltf
expect_file room.gltf "bake gltf"
expect_file room.bin "bake gltf buffer"
# The baked PLY loads back as a scene mesh (assimp reads PLY).
expect_exit 1 "a bake has no light" -- "$ILLUM" info room.ply
expect_stderr "no light" "a bake has no light"
# ... and info still describes it: the triangles it has, then why it cannot render.
expect_stdout "^triangles:  [1-9]" "info describes a scene without light"
expect_stdout "^lights:     0 point/spot/directional, 0 emissive" "info describes a scene without light"

# Bad values: exit 1 with a message naming the option, no output.
for bad in "--patch-size -1" "--tolerance 0" "--solver foo" "--form-factors bar" "--subdiv 11" \
           "--hemicube-res 2" "--ff-samples 0" "--max-steps x" "--ff-cache-mb 0" "--adaptive -1"; do
    expect_exit 1 "render $bad" -- "$ILLUM" render simple-room --method radiosity $bad -q -o bad.exr
    expect_stderr "${bad%% *}" "render $bad"
    expect_no_file bad.exr "render $bad"
    expect_exit 1 "bake $bad" -- "$ILLUM" bake simple-room $bad -q -o bad.ply
    expect_no_file bad.ply "bake $bad"
done
expect_exit 2 "radiosity option without its value" -- "$ILLUM" render simple-room --method radiosity --subdiv
expect_exit 1 "unknown method" -- "$ILLUM" render simple-room --method foo -o bad.exr
expect_no_file bad.exr "unknown method"

# A radiosity option with the path tracer is a usage error, in either order.
expect_exit 2 "radiosity option with pt" -- "$ILLUM" render simple-room --method pt --subdiv 2 -q -o bad.exr
expect_stderr "needs --method radiosity" "radiosity option with pt"
expect_no_file bad.exr "radiosity option with pt"
expect_exit 2 "radiosity option, pt after" -- "$ILLUM" render simple-room --tolerance 0.1 --method pt -q -o bad.exr
expect_exit 2 "radiosity option, default method" -- "$ILLUM" render simple-room --subdiv 2 -q -o bad.exr
expect_no_file bad.exr "radiosity option, default method"

# bake: a bad extension is refused before the solve; -o is required.
expect_exit 1 "bake to .txt" -- "$ILLUM" bake simple-room -q -o baked.txt
expect_stderr "baked.txt" "bake to .txt"
expect_no_file baked.txt "bake to .txt"
expect_exit 2 "bake without -o" -- "$ILLUM" bake simple-room -q
expect_exit 1 "bake with pt" -- "$ILLUM" bake simple-room --method pt -q -o bad.ply
expect_no_file bad.ply "bake with pt"
# A closed white room has no finite solution: the solve stops as stalled,
# says so, and the image of the light it shot is still written.
echo '{"materials": {"w": {"diffuse": 1}, "e": {"diffuse": 1, "emission": 5}},
       "meshes": [{"shape": "box", "size": 4, "flip": true, "material": "w"},
                  {"shape": "box", "size": 0.5, "material": "e"}],
       "camera": {"position": [0, 1, 1.9], "target": [0, 0, 0]}}' > white.json
expect_exit 0 "closed white room" -- "$ILLUM" render white.json --method radiosity --form-factors raycast \
    --ff-samples 256 --patch-size 0.5 --width 16 --height 16 -o white.exr --stats white-stats.json
expect_stderr "the solve stopped converging" "closed white room"
grep -q '"stalled":[[:space:]]*true' white-stats.json || fail "white-stats.json: stalled is not true"
grep -q '"stalled":[[:space:]]*false' room.json || fail "room.json: stalled is not false"
expect_file white.exr "closed white room"

expect_exit 1 "bake into a missing folder" -- "$ILLUM" bake simple-room --subdiv 1 --hemicube-res 32 -q -o nodir/x.ply
expect_no_file nodir "bake into a missing folder"
expect_exit 1 "bake a missing scene" -- "$ILLUM" bake no-such-scene.obj -q -o bad.ply
expect_no_file bad.ply "bake a missing scene"
finish
