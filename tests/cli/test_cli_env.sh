# Environment maps on the command line: --env on render (pt, radiosity, hr,
# photon, sppm) and bake, agreeing with each other on a plane under Grace
# Cathedral; a JSON scene's "environment" map; `illum envmap convert` round
# trips checked by `illum compare`; and bad input (missing or corrupt map,
# wrong shape for the mapping, bad option values) refused with a message and
# no output.
. "$(dirname "$0")/lib.bash"
: "${IL_SHARED_DIR:?}"
GRACE="$IL_SHARED_DIR/scenes/envmaps/probulator_grace_256x128.hdr"
UFFIZI="$IL_SHARED_DIR/scenes/envmaps/probulator_uffizi_256x128.hdr"

# The help of render and bake lists the options.
expect_exit 0 "render --help" -- "$ILLUM" render --help
for o in --env --env-mapping --env-intensity --env-rotate; do
    expect_stdout -- "$o" "render --help lists $o"
done
expect_exit 0 "bake --help" -- "$ILLUM" bake --help
expect_stdout -- "--env-rotate" "bake --help lists --env-rotate"
expect_exit 0 "envmap --help" -- "$ILLUM" envmap --help
expect_stdout -- "--to latlong|angular|cross" "envmap --help"
expect_exit 0 "help lists envmap" -- "$ILLUM" --help
expect_stdout "envmap convert" "illum --help lists envmap convert"

# A diffuse plane facing up with a box on it; the camera looks down at it.
cat > plane.json <<'JSON'
{
  "materials": {"ground": {"diffuse": 0.5}, "box": {"diffuse": [0.7, 0.5, 0.3]}},
  "meshes": [
    {"shape": "quad", "size": 4, "material": "ground"},
    {"shape": "box", "size": 0.6, "material": "box", "transform": {"translate": [0.3, 0.3, -0.2]}}
  ],
  "camera": {"position": [0, 3, 1.2], "target": [0, 0, 0], "fov": 45}
}
JSON
# Without a light the scene is refused; --env lights it.
expect_exit 1 "plane without a light" -- "$ILLUM" render plane.json -q -o none.exr
expect_no_file none.exr "plane without a light"
mean_lum() { sed -n 's/^mean_luminance *\([^ ]*\).*/\1/p' out.txt; }
# rel A B: |A/B - 1| in per cent, rounded.
rel() { awk -v a="$1" -v b="$2" 'BEGIN { d = (a / b - 1) * 100; if (d < 0) d = -d; printf "%.1f", d }'; }

expect_exit 0 "render --env pt" -- "$ILLUM" render plane.json --env "$GRACE" --env-rotate 30 \
    --width 48 --height 48 --spp 64 -q -o pt.exr
expect_file pt.exr "render --env pt"
expect_exit 0 "compare pt" -- "$ILLUM" compare pt.exr pt.exr
PT=$(mean_lum)
checks=$((checks + 1))
awk -v x="$PT" 'BEGIN { exit !(x > 0.05) }' || fail "pt under grace: mean luminance $PT"

# Every method lights the plane with the map; the image means agree with the
# path tracer's (radiosity and hr shade patches from the map by MIS, photon
# mapping emits photons by the map's importance tables).
for m in radiosity hr photon sppm; do
    extra=""
    [ "$m" = hr ] && extra="--vis-rays 4"
    [ "$m" = photon ] && extra="--photons 200000"
    [ "$m" = sppm ] && extra="--photons 50000 --spp 8"
    # shellcheck disable=SC2086
    expect_exit 0 "render --env $m" -- "$ILLUM" render plane.json --method "$m" --env "$GRACE" \
        --env-rotate 30 --width 48 --height 48 -q -o "$m.exr" $extra
    expect_file "$m.exr" "render --env $m"
    expect_exit 0 "compare $m" -- "$ILLUM" compare "$m.exr" pt.exr
    got=$(mean_lum)
    d=$(rel "$got" "$PT")
    echo "$m under grace: mean luminance $got, path tracer $PT ($d%)"
    checks=$((checks + 1))
    awk -v d="$d" 'BEGIN { exit !(d < 5) }' || fail "$m under grace: $got vs the path tracer's $PT ($d%)"
done

# The intensity scales the image; the mapping and rotation reach the renderer.
expect_exit 0 "render --env-intensity 2" -- "$ILLUM" render plane.json --env "$GRACE" --env-rotate 30 \
    --env-intensity 2 --width 48 --height 48 --spp 64 -q -o pt2.exr
expect_exit 0 "compare pt2" -- "$ILLUM" compare pt2.exr pt.exr
checks=$((checks + 1))
d=$(rel "$(mean_lum)" "$(awk -v p="$PT" 'BEGIN { print 2 * p }')")
awk -v d="$d" 'BEGIN { exit !(d < 1) }' || fail "--env-intensity 2: $(mean_lum) is not twice $PT"
expect_exit 0 "render unrotated" -- "$ILLUM" render plane.json --env "$GRACE" \
    --width 48 --height 48 --spp 64 -q -o pt0.exr
expect_exit 4 "--env-rotate 30 changes the image" -- "$ILLUM" compare pt0.exr pt.exr --max-rmse 0

# Bake with a map (radiosity and hr).
for m in radiosity hr; do
    expect_exit 0 "bake --env $m" -- "$ILLUM" bake plane.json --method "$m" --env "$GRACE" -q \
        -o "bake_$m.ply"
    expect_file "bake_$m.ply" "bake --env $m"
done

# envmap convert: lat-long -> angular -> lat-long and -> cross -> lat-long
# keep the image's mean (the light) to 1%; the probe is square, the cross 3:4.
expect_exit 0 "convert to angular" -- "$ILLUM" envmap convert "$GRACE" grace_probe.hdr --to angular
expect_stderr "angular 256x256" "convert to angular: size"
expect_exit 0 "convert back" -- "$ILLUM" envmap convert grace_probe.hdr grace_back.exr --to latlong --exr-float
expect_stderr "(angular 256x256) -> grace_back.exr (latlong 256x128)" "the probe's mapping is inferred"
expect_exit 0 "convert to cross" -- "$ILLUM" envmap convert "$UFFIZI" uffizi_cross.pfm --to cross
expect_stderr "cross 192x256" "convert to cross: size"
expect_exit 0 "cross back" -- "$ILLUM" envmap convert uffizi_cross.pfm uffizi_back.exr --to latlong \
    --width 256 --exr-float
for pair in "grace_back.exr $GRACE" "uffizi_back.exr $UFFIZI"; do
    # shellcheck disable=SC2086
    expect_exit 0 "compare round trip" -- "$ILLUM" compare $pair --json
    checks=$((checks + 1))
    awk '{ gsub(/[{},:"]/, " "); for (i = 1; i <= NF; i++) { if ($i == "mean_luminance_a") a = $(i+1);
           if ($i == "mean_luminance_b") b = $(i+1) } }
         END { d = a / b - 1; if (d < 0) d = -d; exit !(d < 0.01) }' out.txt ||
        fail "round trip $pair: mean luminance changed: $(cat out.txt)"
done
# The probe lights the scene like the lat-long map it came from.
expect_exit 0 "render with the probe" -- "$ILLUM" render plane.json --env grace_probe.hdr --env-rotate 30 \
    --width 48 --height 48 --spp 64 -q -o probe.exr
expect_exit 0 "compare probe" -- "$ILLUM" compare probe.exr pt.exr
d=$(rel "$(mean_lum)" "$PT")
echo "angular probe: mean luminance $(mean_lum), lat-long $PT ($d%)"
checks=$((checks + 1))
awk -v d="$d" 'BEGIN { exit !(d < 2) }' || fail "probe render: $(mean_lum) vs $PT"

# A JSON scene with an environment map beside it.
cp "$GRACE" grace.hdr
sed 's/"camera"/"environment": {"map": "grace.hdr", "rotation": 30, "intensity": 2},\n  "camera"/' \
    plane.json > json_env.json
expect_exit 0 "info with a map" -- "$ILLUM" info json_env.json
expect_stdout "environment" "info shows the environment"
expect_exit 0 "render a JSON map" -- "$ILLUM" render json_env.json --width 48 --height 48 --spp 64 -q \
    -o json.exr
expect_exit 0 "compare JSON map" -- "$ILLUM" compare json.exr pt2.exr --max-rmse 0
sed 's/grace.hdr/missing.hdr/' json_env.json > json_missing.json
expect_exit 1 "JSON map missing" -- "$ILLUM" render json_missing.json -q -o jm.exr
expect_stderr "environment.map" "JSON map missing names the key"
expect_no_file jm.exr "JSON map missing"
sed 's/"rotation": 30/"mapping": "cross"/' json_env.json > json_cross.json
expect_exit 1 "JSON map of the wrong shape" -- "$ILLUM" render json_cross.json -q -o jc.exr
expect_stderr "3:4" "JSON map of the wrong shape"

# Bad input.
expect_exit 1 "missing map" -- "$ILLUM" render plane.json --env nothere.hdr -q -o bad.exr
expect_stderr "nothere.hdr" "missing map: names the file"
expect_no_file bad.exr "missing map"
printf '#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8 +X 16\nxx' > corrupt.hdr
expect_exit 1 "corrupt map" -- "$ILLUM" render plane.json --env corrupt.hdr -q -o bad.exr
expect_stderr "corrupt.hdr" "corrupt map: names the file"
expect_no_file bad.exr "corrupt map"
expect_exit 1 "2:1 map as angular" -- "$ILLUM" render plane.json --env "$GRACE" --env-mapping angular \
    -q -o bad.exr
expect_stderr "square" "2:1 map as angular"
expect_exit 1 "2:1 map as cross" -- "$ILLUM" render plane.json --method radiosity --env "$GRACE" \
    --env-mapping cross -q -o bad.exr
expect_stderr "3:4" "2:1 map as cross"
expect_no_file bad.exr "wrong shape"
expect_exit 1 "bad mapping name" -- "$ILLUM" render plane.json --env "$GRACE" --env-mapping cube -q
expect_exit 1 "intensity 0" -- "$ILLUM" render plane.json --env "$GRACE" --env-intensity 0 -q
expect_exit 1 "rotation not a number" -- "$ILLUM" render plane.json --env "$GRACE" --env-rotate west -q
expect_exit 2 "--env-rotate without --env" -- "$ILLUM" render plane.json --env-rotate 30 -q
expect_stderr "needs --env" "--env-rotate without --env"
expect_exit 2 "--env without a file" -- "$ILLUM" render plane.json --env
expect_exit 2 "bake --env-intensity without --env" -- "$ILLUM" bake plane.json -o b.ply --env-intensity 2
expect_exit 2 "convert without --to" -- "$ILLUM" envmap convert "$GRACE" x.exr
expect_exit 2 "convert without OUT" -- "$ILLUM" envmap convert "$GRACE" --to cross
expect_exit 2 "envmap without an action" -- "$ILLUM" envmap
expect_exit 2 "envmap unknown action" -- "$ILLUM" envmap shrink "$GRACE" x.exr
expect_exit 1 "convert a 2:1 map as angular" -- "$ILLUM" envmap convert "$GRACE" x.exr --from angular --to cross
expect_stderr "square" "convert a 2:1 map as angular"
expect_exit 1 "convert to a cross of width 100" -- "$ILLUM" envmap convert "$GRACE" x.exr --to cross --width 100
expect_exit 1 "convert a missing file" -- "$ILLUM" envmap convert nothere.hdr x.exr --to angular
expect_no_file x.exr "failed conversions"

finish
