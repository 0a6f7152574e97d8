# Bad input through the command line: a clear message, the documented exit
# status, and never an output file.
. "$(dirname "$0")/lib.bash"

expect_exit 2 "no command" -- "$ILLUM"
expect_exit 2 "unknown command" -- "$ILLUM" frobnicate
expect_exit 2 "render without scene" -- "$ILLUM" render
expect_exit 2 "unknown option" -- "$ILLUM" render cornell --bogus -o a.png
expect_no_file a.png "unknown option"
expect_exit 2 "option without value" -- "$ILLUM" render cornell --spp
expect_exit 1 "spp zero" -- "$ILLUM" render cornell --spp 0 -o a.png
expect_stderr "--spp" "spp zero"
expect_exit 1 "spp not a number" -- "$ILLUM" render cornell --spp many -o a.png
expect_exit 1 "negative width" -- "$ILLUM" render cornell --width -5 -o a.png
expect_exit 1 "huge width" -- "$ILLUM" render cornell --width 100000 -o a.png
expect_exit 1 "fov out of range" -- "$ILLUM" render cornell --fov 200 -o a.png
expect_exit 1 "bad vector" -- "$ILLUM" render cornell --camera-pos 1,2 -o a.png
expect_exit 1 "NaN vector" -- "$ILLUM" render cornell --camera-pos nan,0,0 -o a.png
expect_exit 1 "negative time" -- "$ILLUM" render cornell --time -1 -o a.png
expect_exit 1 "unknown method" -- "$ILLUM" render cornell --method magic -o a.png
expect_exit 1 "unknown output format" -- "$ILLUM" render cornell -o a.bmp
expect_exit 1 "camera looking at itself" -- "$ILLUM" render cornell --camera-pos 0,0,0 --camera-target 0,0,0 --spp 1 -o a.png
expect_no_file a.png "bad options"

# The options render, view and bake share take the same values in each.
for cmd in render view bake; do
    case $cmd in render) out="-o a.png" ;; bake) out="-o a.ply" ;; *) out="" ;; esac
    expect_exit 1 "$cmd threads zero" -- "$ILLUM" $cmd cornell --threads 0 $out
    expect_stderr "threads: expected a whole number from 1 to 4096" "$cmd threads zero"
    expect_exit 1 "$cmd threads beyond 4096" -- "$ILLUM" $cmd cornell --threads 4097 $out
    expect_stderr "from 1 to 4096" "$cmd threads beyond 4096"
    expect_exit 1 "$cmd seed negative" -- "$ILLUM" $cmd cornell --seed -1 $out
    expect_stderr "seed: expected a non-negative" "$cmd seed negative"
    expect_exit 1 "$cmd exposure beyond 50" -- "$ILLUM" $cmd cornell --exposure 51 $out
    expect_stderr "exposure: expected a number from -50 to 50" "$cmd exposure beyond 50"
done
for cmd in render view; do
    expect_exit 1 "$cmd max depth zero" -- "$ILLUM" $cmd cornell --max-depth 0
    expect_stderr "from 1 to 1024" "$cmd max depth zero"
    expect_exit 1 "$cmd spp beyond 2^24" -- "$ILLUM" $cmd cornell --spp 16777217
    expect_stderr "from 1 to 16777216" "$cmd spp beyond 2^24"
done
expect_exit 2 "bake takes no --spp" -- "$ILLUM" bake cornell --spp 4 -o a.ply
expect_stderr "unknown option" "bake takes no --spp"
expect_no_file a.ply "shared options"
expect_no_file a.png "shared options"

expect_exit 1 "missing scene file" -- "$ILLUM" render nonexistent.obj -o b.png
expect_stderr "nonexistent.obj" "missing scene file"
expect_no_file b.png "missing scene file"

printf '\x00\x01\x02garbage\xff\xfe' > garbage.obj
expect_exit 1 "garbage OBJ" -- "$ILLUM" render garbage.obj -o c.png
expect_stderr "garbage.obj" "garbage OBJ"
expect_no_file c.png "garbage OBJ"

: > empty.obj
expect_exit 1 "empty OBJ" -- "$ILLUM" render empty.obj -o d.png
expect_stderr "empty.obj" "empty OBJ"
expect_no_file d.png "empty OBJ"

# A PLY claiming two billion vertices in a few bytes: refused before assimp
# allocates for them.
printf 'ply\nformat ascii 1.0\nelement vertex 2000000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n' > huge.ply
expect_exit 1 "PLY count beyond the file" -- "$ILLUM" render huge.ply -o h.png
expect_stderr "huge.ply: element 'vertex': 2000000000 instances" "PLY count beyond the file"
expect_no_file h.png "PLY count beyond the file"

# A lit-less scene: one grey triangle.
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' > dark.obj
expect_exit 1 "scene without lights" -- "$ILLUM" render dark.obj -o e.png
expect_stderr "light" "scene without lights"
expect_stderr "no light: .* --env MAP.hdr" "scene without lights: the hint names --env"
expect_no_file e.png "scene without lights"

# Only NaN triangles: all dropped, so the scene is empty.
printf 'v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' > nan.obj
expect_exit 1 "only NaN triangles" -- "$ILLUM" render nan.obj -o f.png
expect_no_file f.png "only NaN triangles"

# An emitter plus one NaN triangle: the NaN one is dropped with a warning.
cat > nan2.mtl <<'MTL'
newmtl light
Kd 0 0 0
Ke 1 1 1
MTL
cat > nan2.obj <<'OBJ'
mtllib nan2.mtl
v 0 0 0
v 1 0 0
v 0 1 0
v nan 1 1
usemtl light
f 1 2 3
f 1 2 4
OBJ
expect_exit 0 "one NaN triangle among good ones" -- "$ILLUM" render nan2.obj --width 8 --height 8 --spp 1 -o g.png
expect_stderr "warning" "one NaN triangle among good ones"
expect_file g.png "one NaN triangle among good ones"

expect_exit 1 "missing camera file" -- "$ILLUM" render cornell --camera-file nope.json -o h.png
echo '{"position": [1, 2]}' > badcam.json
expect_exit 1 "bad camera file" -- "$ILLUM" render cornell --camera-file badcam.json -o h.png
# Found by fuzzing: a key given twice (the first was read), text after the
# object, and an empty object were taken without a word.
echo '{"fov": 40, "fov": 0}' > twicecam.json
expect_exit 1 "camera file: a key twice" -- "$ILLUM" render cornell --camera-file twicecam.json -o h.png
expect_stderr 'the key "fov" appears twice' "camera file: a key twice"
echo '{"fov": 40} junk' > junkcam.json
expect_exit 1 "camera file: text after it" -- "$ILLUM" render cornell --camera-file junkcam.json -o h.png
echo '{}' > emptycam.json
expect_exit 1 "camera file: no key" -- "$ILLUM" render cornell --camera-file emptycam.json -o h.png
expect_no_file h.png "camera files"
echo '{"fov": 30, "zoom": 2}' > zoomcam.json
expect_exit 0 "camera file: an unknown key" -- "$ILLUM" render cornell --camera-file zoomcam.json --width 8 \
    --height 8 --spp 1 -o zoom.png
expect_stderr 'unknown key "zoom" ignored' "camera file: an unknown key"

# Coordinates beyond +-1e15: Embree aborts the program on a ray from there
# (the photon mapper's emission rays did), so the scene is refused first.
echo '{"meshes": [{"positions": [0,0,0, 1,0,0, 0,1,0]}],
       "lights": [{"type": "point", "position": [1e20, 0, 1], "intensity": [1, 1, 1]}]}' > farlight.json
expect_exit 1 "light beyond 1e15" -- "$ILLUM" render farlight.json --method photon --spp 1 -o far.png
expect_stderr "out of range" "light beyond 1e15"
expect_exit 1 "camera beyond 1e15" -- "$ILLUM" render cornell --camera-pos 0,0,1e30 --spp 1 -o far.png
expect_no_file far.png "coordinates beyond 1e15"

expect_exit 1 "output into a missing folder" -- "$ILLUM" render cornell --width 8 --height 8 --spp 1 -o no/such/dir/i.png
expect_no_file no/such/dir/i.png "missing folder"

# Every output is checked before the work starts: a render of 10^6 seconds
# ends at once, and no image is written when only the stats file cannot be.
expect_exit 1 "output checked before the render" -- "$ILLUM" render cornell --time 1000000 -o no/such/dir/i.exr
expect_stderr "no/such/dir/i.exr: cannot create file" "output checked before the render"
expect_exit 1 "stats into a missing folder" -- "$ILLUM" render cornell --width 8 --height 8 --spp 1 -o j.png --stats no/such/dir/s.json
expect_stderr "no/such/dir/s.json" "stats into a missing folder"
expect_no_file j.png "stats into a missing folder"
mkdir -p folder.exr
expect_exit 1 "output is a folder" -- "$ILLUM" render cornell --width 8 --height 8 --spp 1 -o folder.exr
expect_stderr "folder.exr: is a folder" "output is a folder"
expect_exit 1 "empty output name" -- "$ILLUM" render cornell --width 8 --height 8 --spp 1 -o j.png --stats ''
expect_stderr "empty" "empty output name"
expect_no_file j.png "empty output name"
expect_exit 1 "bake stats into a missing folder" -- "$ILLUM" bake cornell -o k.ply --stats no/such/dir/s.json
expect_no_file k.ply "bake stats into a missing folder"
# A name of 250 characters is written (its temporary name would be too
# long beside it, so it gets a short one in the folder); one of 300 is
# refused before the work.
long=$(printf 'l%.0s' $(seq 1 246)).png
expect_exit 0 "250-character output name" -- "$ILLUM" render cornell --width 8 --height 8 --spp 1 -q -o "$long"
expect_file "$long" "250-character output name"
rm -f "$long"
expect_exit 1 "300-character output name" -- "$ILLUM" render cornell --time 1000000 -q \
    -o "$(printf 'm%.0s' $(seq 1 296)).png"
expect_stderr "the file name is too long (300 characters; at most 255)" "300-character output name"
if ls -a | grep -q -e '\.tmp-' -e '\.illum-tmp-'; then fail "an output check left a temporary file"; fi

# Zero where the library would take a default is a mistake when written
# (found by fuzzing): a scene's camera fov 0 or up [0,0,0], a spot's angle
# 0 or direction [0,0,0], --camera-up 0,0,0, a camera file's fov 0.
base='"materials": {"e": {"emission": 1}}, "meshes": [{"shape": "quad", "size": 1, "material": "e"}]'
cam='"position": [0, 0, 3], "target": [0, 0, 0]'
printf '{%s, "camera": {%s, "fov": 0}}' "$base" "$cam" > fov0.json
printf '{%s, "camera": {%s, "up": [0, 0, 0]}}' "$base" "$cam" > up0.json
printf '{%s, "lights": [{"type": "spot", "position": [0, 1, 0], "angle": 0}]}' "$base" > angle0.json
printf '{%s, "lights": [{"type": "spot", "position": [0, 1, 0], "direction": [0, 0, 0]}]}' "$base" > dir0.json
printf '{%s, "lights": [{"type": "point", "position": [0, 1, 0], "intensity": 3e38}]}' "$base" > huge.json
for f in fov0:camera.fov up0:camera.up angle0:angle dir0:direction huge:"intensity 3e+38 is out of range"; do
    expect_exit 1 "zero where a default would be: ${f%%:*}" -- "$ILLUM" render "${f%%:*}.json" --spp 1 -o z.png
    expect_stderr "${f#*:}" "${f%%:*}: the message"
done
printf '{%s, "camera": {%s}}' "$base" "$cam" > cam.json
expect_exit 1 "--camera-up 0,0,0" -- "$ILLUM" render cam.json --camera-up 0,0,0 --spp 1 -o z.png
expect_stderr "up (--camera-up" "--camera-up 0,0,0: the message"
printf '{"fov": 0}' > fov0cam.json
expect_exit 1 "camera file with fov 0" -- "$ILLUM" render cam.json --camera-file fov0cam.json --spp 1 -o z.png
expect_stderr "must be in (0, 180)" "camera file with fov 0: the message"
expect_no_file z.png "zero where a default would be"
expect_exit 1 "illuminance on an empty surface name" -- "$ILLUM" illuminance cornell --surface '' -o z.csv
expect_no_file z.csv "illuminance on an empty surface name"
# A map whose texel is finite but so large that the sampling sums overflow:
# refused naming the file (it was "distribution: weight 3 is inf").
printf 'PF\n1 1\n-1.0\n\x0c\x13\x9a\x79\x0c\x13\x9a\x79\x0c\x13\x9a\x79' > huge.pfm
expect_exit 1 "a map of 1e35" -- "$ILLUM" render cornell --env huge.pfm --spp 1 --width 8 --height 8 -o z.png
expect_stderr "huge.pfm: environment map: texel (0, 0) is 1e+35" "a map of 1e35: the message"

# Two outputs in one file, and a device as an output (found by fuzzing: the
# later output replaced the earlier with exit 0, and the temporary file
# was renamed over /dev/null, which root may do).
expect_exit 1 "image and stats in one file" -- "$ILLUM" render cornell --width 8 --height 8 --spp 1 -o same.png --stats same.png
expect_stderr "same.png and same.png name the same file" "image and stats in one file"
expect_no_file same.png "image and stats in one file"
expect_exit 1 "one output named twice" -- "$ILLUM" render cornell --width 8 --height 8 --spp 1 -o twice.png -o ./twice.png
expect_stderr "name the same file" "one output named twice"
if [ -c /dev/null ]; then
    expect_exit 1 "stats into /dev/null" -- "$ILLUM" render cornell --width 8 --height 8 --spp 1 -o dn.png --stats /dev/null
    expect_stderr "/dev/null: is a device or a pipe" "stats into /dev/null"
    checks=$((checks + 1))
    [ -c /dev/null ] || fail "/dev/null is no longer a device"
fi
expect_exit 1 "bake stats onto the glTF's buffer" -- "$ILLUM" bake cornell -o bk.gltf --stats bk.bin
expect_stderr "bk.gltf writes its buffer there" "bake stats onto the glTF's buffer"
mkdir -p bkdir.bin
expect_exit 1 "the glTF's buffer is a folder" -- "$ILLUM" bake cornell -o bkdir.gltf
expect_stderr "bkdir.bin: is a folder" "the glTF's buffer is a folder"
expect_no_file bkdir.gltf "the glTF's buffer is a folder"

# compare --json of an image holding NaN: null, not the invalid "nan".
printf 'PF\n1 1\n-1.0\n\x00\x00\xc0\x7f\x00\x00\xc0\x7f\x00\x00\xc0\x7f' > nan.pfm
printf 'PF\n1 1\n-1.0\n\x00\x00\x00\x3f\x00\x00\x00\x3f\x00\x00\x00\x3f' > half.pfm
expect_exit 0 "compare --json with NaN" -- "$ILLUM" compare nan.pfm half.pfm --json
expect_stdout '"rmse": null' "compare --json with NaN"
checks=$((checks + 1))
grep -qiw -e nan -e inf out.txt && fail "compare --json printed nan or inf"
# A scene's render size beyond --width's 16384 was silently ignored (the
# image came out 512 x 512): refused, naming the key.
printf '{%s, "render": {"width": 20000}}' "$base" > wide.json
expect_exit 1 "render.width 20000" -- "$ILLUM" render wide.json --spp 1 -o z.png
expect_stderr "render.width" "render.width 20000: the message"

# A header asking for 20000 x 20000 pixels (4.8 GB) in a tiny file, and a
# device that never ends: refused before anything is allocated or read.
printf 'PF\n20000 20000\n-1.0\n\x00\x00\x00\x00' > vast.pfm
expect_exit 1 "a 20000 x 20000 image" -- "$ILLUM" compare vast.pfm vast.pfm
expect_stderr "exceeds 268435456 pixels" "a 20000 x 20000 image: the message"
if [ -c /dev/zero ]; then
    expect_exit 1 "a map read from /dev/zero" -- "$ILLUM" render cornell --env /dev/zero --spp 1 -o z.png
    expect_stderr "/dev/zero: not a file" "a map read from /dev/zero: the message"
    printf '{"materials": {"t": {"diffuse": 0.5, "texture": "/dev/zero"}}, "meshes": [{"shape": "quad", "size": 1, "material": "t"}], "lights": [{"type": "point", "position": [0, 1, 0]}]}' > devzero.json
    # A texture that cannot be read is a warning, and the material's colour
    # (scene-format.md); it used to read /dev/zero for ever.
    expect_exit 0 "a texture read from /dev/zero" -- "$ILLUM" render devzero.json --spp 1 --width 8 \
        --height 8 -o devzero.png
    expect_stderr "/dev/zero not loaded (/dev/zero: not a file)" "a texture read from /dev/zero: the warning"
fi

# Corrupt images given to compare.
printf 'not an image' > bad.png
printf '#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 100 +X 100\n\x02\x02' > bad.hdr
printf 'v/1\x01\x00\x00' > bad.exr
expect_exit 1 "corrupt PNG" -- "$ILLUM" compare bad.png bad.png
expect_stderr "bad.png" "corrupt PNG"
expect_exit 1 "truncated HDR" -- "$ILLUM" compare bad.hdr bad.hdr
expect_exit 1 "corrupt EXR" -- "$ILLUM" compare bad.exr bad.exr
expect_exit 1 "missing image" -- "$ILLUM" compare none.exr none.exr
expect_exit 2 "compare with one image" -- "$ILLUM" compare only.exr
"$ILLUM" render cornell --width 8 --height 8 --spp 1 --quiet -o small.exr
expect_exit 1 "diff into a missing folder" -- "$ILLUM" compare small.exr small.exr --diff no/such/dir/d.exr
expect_stderr "no/such/dir/d.exr" "diff into a missing folder"
expect_exit 1 "tonemap into a missing folder" -- "$ILLUM" tonemap small.exr no/such/dir/t.png
expect_exit 1 "envmap convert into a folder" -- "$ILLUM" envmap convert small.exr folder.exr --to angular
expect_stderr "is a folder" "envmap convert into a folder"

finish
