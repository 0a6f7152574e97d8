# `illum illuminance` end to end: the help, a plane's grid (given spacing
# and EN 12464-1's default cell), sensors from a file, readings against the
# inverse-square law, the CSV, thread independence, Ctrl-C, and bad input
# that stops before any output is written.
. "$(dirname "$0")/lib.bash"

# A 4 m square floor under a 10 W/sr point light 2 m up.  A sensor on the
# floor facing up sees no other surface, so it reads the direct light only:
# E = I cos / d^2, 683 lm/W.
cat > lamp.json <<'JSON'
{"meshes": [{"shape": "quad", "size": 4}],
 "lights": [{"type": "point", "position": [0, 2, 0], "intensity": 10}]}
JSON

expect_exit 0 "illuminance --help" -- "$ILLUM" illuminance --help
for o in --plane --area --margin --spacing --points --samples --max-depth -o; do
    expect_stdout -- "$o" "illuminance help lists $o"
done
expect_exit 0 "help illuminance" -- "$ILLUM" help illuminance
expect_stdout "--plane AXIS=VALUE" "help illuminance"
expect_exit 0 "illum --help" -- "$ILLUM" --help
expect_stdout "illuminance SCENE" "illum --help lists illuminance"

# One sensor below the lamp: 683 * 10 / 4 = 1707.5 lx.
expect_exit 0 "one sensor" -- "$ILLUM" illuminance lamp.json --plane y=0 --area -0.5,-0.5,0.5,0.5 \
    --spacing 1 --samples 16 -o one.csv
expect_stdout "1 sensors on y = 0 facing +y: 1 x 1 cells of 1 x 1 m" "one sensor: the grid"
expect_stdout "average     1708 lx" "one sensor: 1707.5 lx"
expect_file one.csv "one sensor"
checks=$((checks + 1))
head -1 one.csv | grep -q '^x,y,z,nx,ny,nz,lux,lux_error,irradiance_r,irradiance_g,irradiance_b$' ||
    fail "one.csv: header"
checks=$((checks + 1))
awk -F, 'NR == 2 { d = $7 - 1707.5; exit !(d < 0.01 && d > -0.01 && $9 == 2.5) }' one.csv ||
    fail "one.csv: $(sed -n 2p one.csv), expected 1707.5 lx and 2.5 W/m^2"

# The scene's bounds with 0.5 m cells: 8 x 8; EN 12464-1's cell for 4 m
# (0.2 * 5^log10 4 = 0.53 m) gives 8 x 8 too; a margin of 1 m leaves 2 m,
# whose cell is 0.2 * 5^log10 2 = 0.32 m: 6 x 6.
expect_exit 0 "grid 0.5 m" -- "$ILLUM" illuminance lamp.json --plane y=0 --spacing 0.5 --samples 8
expect_stdout "64 sensors on y = 0 facing +y: 8 x 8 cells of 0.5 x 0.5 m" "grid 0.5 m"
expect_stdout "uniformity" "grid 0.5 m"
expect_stdout "^lux, x across" "grid 0.5 m: the plan"
expect_exit 0 "default cell" -- "$ILLUM" illuminance lamp.json --plane y=0 --samples 8
expect_stdout "64 sensors on y = 0 facing +y: 8 x 8 cells of 0.5 x 0.5 m" "default cell"
expect_exit 0 "margin" -- "$ILLUM" illuminance lamp.json --plane y=0 --margin 1 --samples 8
expect_stdout "36 sensors on y = 0 facing +y: 6 x 6 cells of 0.333 x 0.333 m" "margin 1"
# Facing down below the floor: it has no back face to light, and nothing
# below emits.
expect_exit 0 "facing down" -- "$ILLUM" illuminance lamp.json --plane -y=-0.5 --samples 8
expect_stdout "facing -y" "facing down"
expect_stdout "average     0 lx" "facing down"
expect_stderr "warning: 64 of 64 sensors read 0 lx" "facing down"

# Sensors from a file: a header, a comment, spaces and commas; 1 m aside
# the reading is 683 * 10 * 2 / 5^1.5 = 1221.79 lx.
printf 'x,y,z,nx,ny,nz\n# under the lamp\n0 0 0 # its centre\n1,0,0, 0,2,0\n\n' > points.csv
expect_exit 0 "points" -- "$ILLUM" illuminance lamp.json --points points.csv --samples 16 -o points.out.csv
expect_stdout "2 sensors from points.csv" "points"
checks=$((checks + 1))
awk -F, 'NR == 3 { d = $7 - 1221.79; exit !(d < 0.01 && d > -0.01 && $5 == 1) }' points.out.csv ||
    fail "points.out.csv: $(sed -n 3p points.out.csv), expected 1221.79 lx and a unit normal"

# A first line of bad numbers is not a header (it was skipped, and its
# sensor lost with exit 0); a coordinate beyond a float is refused with its
# line.
printf 'nan 0 0\n0 0 0\n' > nanfirst.csv
expect_exit 1 "points: nan on the first line" -- "$ILLUM" illuminance lamp.json --points nanfirst.csv -o bad.csv
expect_stderr "nanfirst.csv:1: expected" "points: nan on the first line"
printf '0 0 0\n1e39 0 0\n' > huge.csv
expect_exit 1 "points: 1e39" -- "$ILLUM" illuminance lamp.json --points huge.csv -o bad.csv
expect_stderr "huge.csv:2: expected" "points: 1e39"
expect_no_file bad.csv "points: bad numbers"
expect_exit 1 "an area of 2e308" -- "$ILLUM" illuminance lamp.json --plane y=0 --area -1e308,-1e308,1e308,1e308 -o bad.csv
expect_stderr "out of range (at most 1e15 a side" "an area of 2e308"
# A second --plane, --area, --points or --surface would replace the first.
expect_exit 1 "--plane twice" -- "$ILLUM" illuminance lamp.json --plane y=0 --plane y=1 -o bad.csv
expect_stderr "--plane: given twice" "--plane twice"
expect_exit 1 "--area twice" -- "$ILLUM" illuminance lamp.json --plane y=0 --area 0,0,1,1 --area 0,0,2,2 -o bad.csv
expect_exit 1 "--surface twice" -- "$ILLUM" illuminance lamp.json --surface a --surface b -o bad.csv
expect_stderr "--surface: given twice" "--surface twice"
expect_no_file bad.csv "options given twice"

# The same readings with one thread and two (the Cornell box: noisy paths).
expect_exit 0 "1 thread" -- "$ILLUM" illuminance cornell --plane y=0.1 --samples 64 --threads 1 -q -o t1.csv
expect_exit 0 "2 threads" -- "$ILLUM" illuminance cornell --plane y=0.1 --samples 64 --threads 2 -q -o t2.csv
checks=$((checks + 1))
cmp -s t1.csv t2.csv || fail "readings differ between 1 and 2 threads"
checks=$((checks + 1))
[ "$(wc -l < t1.csv)" = 17 ] || fail "t1.csv: $(wc -l < t1.csv) lines, expected a header and 16"

# Surfaces: the office's desk tops (six 1.4 x 0.7 m tops; their faces
# facing up), one sensor per 0.01 m^2; every face of them without --facing.
expect_exit 0 "surface" -- "$ILLUM" illuminance office --surface desk_tops --facing +y --samples 8 \
    -o desks.csv --stats desks.json
expect_stdout "588 sensors on 'desk_tops': 12 triangles, 5.88 m^2, one sensor per 0.01 m^2" "surface"
checks=$((checks + 1))
[ "$(wc -l < desks.csv)" = 589 ] || fail "desks.csv: $(wc -l < desks.csv) lines, expected 589"
checks=$((checks + 1))
awk -F, 'NR > 1 && ($2 != 0.75 || $5 != 1) { bad = 1 } END { exit bad }' desks.csv ||
    fail "desks.csv: a sensor off the tops (y 0.75, facing +y)"
checks=$((checks + 1))
grep -q '"mode":[[:space:]]*"surface"' desks.json || fail "desks.json: mode"
expect_exit 0 "surface, every face" -- "$ILLUM" illuminance office --surface DESK_TOPS --spacing 0.2 --samples 4
expect_stdout "on 'DESK_TOPS': 72 triangles" "surface, every face"

# Ctrl-C: stops at the next round and writes the readings so far.
expect_interrupted 1 "interrupted" -- "$ILLUM" illuminance cornell --plane y=0.1 --samples 16777216 \
    -o stopped.csv
expect_file stopped.csv "interrupted: the readings so far"

# The view: a sensor on the surface each pixel sees.  Looking straight down
# from 1.5 m, the centre pixel of a 33x33 view sees the floor below the
# lamp: 1707.5 lx in the PFM.  The PNG is the view and the legend beside it
# (62 pixels wide below 200 rows).
view=(--view --camera-pos 0,1.5,0 --camera-target 0,0,0 --camera-up 0,0,-1 --fov 60)
expect_exit 0 "view" -- "$ILLUM" illuminance lamp.json "${view[@]}" --width 33 --height 33 \
    --samples 8 -o view.pfm -o view.png -o view.exr
expect_stdout "view 33x33: 1089 pixels see a surface, 8 samples each" "view"
expect_stdout "palette     0 .. 2000 lx" "view: the palette's round top"
for f in view.pfm view.png view.exr; do expect_file "$f" "view"; done
checks=$((checks + 1))
centre=$(od -A n -t f4 -j $(( $(head -c 64 view.pfm | head -3 | wc -c) + (16 * 33 + 16) * 12 )) -N 4 view.pfm)
awk -v v="$centre" 'BEGIN { d = v - 1707.5; exit !(d < 0.01 && d > -0.01) }' ||
    fail "view.pfm: the centre pixel reads $centre lx, expected 1707.5"
checks=$((checks + 1))
[ "$(od -A n -t u1 -j 16 -N 8 view.png | tr -s ' ')" = " 0 0 0 95 0 0 0 33" ] ||
    fail "view.png: not 95x33 (the view and its legend)"
expect_exit 0 "view, --stats" -- "$ILLUM" illuminance lamp.json "${view[@]}" --width 9 --height 9 \
    --samples 4 -q --stats view.json -o v9.png
for k in '"mode":[[:space:]]*"view"' '"sensors":[[:space:]]*81' '"median":' '"palette_max":[[:space:]]*2000'; do
    checks=$((checks + 1))
    grep -q "$k" view.json || fail "view.json lacks $k"
done
checks=$((checks + 1))
grep -q '"daylight_factor"' view.json && fail "view.json: a daylight factor without the sky"
expect_exit 0 "view, --scale-max" -- "$ILLUM" illuminance lamp.json "${view[@]}" --width 16 --height 16 \
    --samples 4 --scale-max 500 -q -o scaled.png
expect_stdout "palette     0 .. 500 lx" "--scale-max"
expect_exit 0 "view, default size" -- "$ILLUM" illuminance cornell --view --samples 1 -q -o big.png
checks=$((checks + 1))
[ "$(od -A n -t u1 -j 16 -N 8 big.png | tr -s ' ')" = " 0 0 2 124 0 0 2 0" ] ||
    fail "big.png: not 636x512 (512 and a 124-pixel legend)"

# Daylight: the overcast sky alone (the lamp switched off) gives the open
# floor its 10,000 lx, a daylight factor of 100%; with the lamp on, the
# summary says the factor needs --sky-only.
expect_exit 0 "overcast, sky only" -- "$ILLUM" illuminance lamp.json --sky overcast --sky-only \
    --plane y=0 --area -1,-1,1,1 --spacing 1 --samples 1024
expect_stdout "daylight    factor 99.[5-9]% average\|daylight    factor 100% average" "sky only: DF 100%"
expect_exit 0 "overcast, --stats" -- "$ILLUM" illuminance lamp.json --sky overcast --sky-only \
    --plane y=0 --area -1,-1,1,1 --spacing 1 --samples 64 -q --stats sky.json
for k in '"mode":[[:space:]]*"plane"' '"sensors":[[:space:]]*4' '"samples":[[:space:]]*64' \
         '"average":' '"uniformity_min_average":' '"daylight_factor":' '"outdoor_lux":[[:space:]]*10000' \
         '"type":[[:space:]]*"overcast"'; do
    checks=$((checks + 1))
    grep -q "$k" sky.json || fail "sky.json lacks $k"
done
expect_exit 0 "overcast, lamp on" -- "$ILLUM" illuminance lamp.json --sky overcast --sky-lux 20000 \
    --plane y=0 --area -1,-1,1,1 --spacing 1 --samples 64
expect_stdout "--sky-only gives the daylight factor" "sky and lamp"
expect_exit 0 "render under the sky" -- "$ILLUM" render lamp.json --sky overcast --sky-only --width 8 \
    --height 8 --spp 2 -q -o sky.pfm
expect_file sky.pfm "render under the sky"
expect_exit 1 "unknown sky" -- "$ILLUM" illuminance lamp.json --sky cloudy --plane y=0 -o bad.csv
expect_exit 1 "ground albedo 2" -- "$ILLUM" illuminance lamp.json --sky overcast --ground-albedo 2 --plane y=0 -o bad.csv
expect_exit 2 "sky lux without the sky" -- "$ILLUM" illuminance lamp.json --sky-lux 5000 --plane y=0 -o bad.csv
expect_exit 2 "sky and env" -- "$ILLUM" illuminance lamp.json --sky overcast --env x.hdr --plane y=0 -o bad.csv
expect_exit 1 "sky only without a sky" -- "$ILLUM" render lamp.json --sky-only -o bad.png
expect_stderr "the scene has no sky of its own" "sky only without a sky"

# The clear sky and its sun (--sky clear, CIE type 12): the open floor gets
# the sky's horizontal illuminance plus the sun's E sin(altitude), 10,000 +
# 20,000 sin 30 = 20,000 lx, and no daylight factor (that needs the overcast
# sky).  From a moment and a place the sun stands where NREL's SPA example
# puts it (2003-10-17 12:30:30 at UTC-7, Golden, Colorado: altitude 39.89,
# azimuth 194.34), the direct light after the IES model.
expect_exit 0 "clear sky, --sun" -- "$ILLUM" illuminance lamp.json --sky clear --sun 30,180 --sun-lux 20000 \
    --sky-only --plane y=0 --area -0.5,-0.5,0.5,0.5 --spacing 1 --samples 4096 -o clear.csv
expect_stderr "CIE sky type 12, sun at 30.00 degrees altitude, 180.00 azimuth; sky 10000 lx horizontal, sun 20000 lx normal" \
    "clear sky: the sun"
checks=$((checks + 1))
awk -F, 'NR == 2 { d = $7 - 20000; exit !(d < 200 && d > -200) }' clear.csv ||
    fail "clear.csv: $(sed -n 2p clear.csv), expected 20000 lx within 1%"
checks=$((checks + 1))
grep -q "daylight" out.txt && fail "clear sky: a daylight factor"
expect_exit 0 "clear sky, --sun-time" -- "$ILLUM" illuminance lamp.json --sky cie:12 \
    --sun-time 2003-10-17T12:30:30-07:00 --latitude 39.742476 --longitude -105.1786 --north 30 \
    --plane y=0 --area -0.5,-0.5,0.5,0.5 --spacing 1 --samples 16 --stats sun.json
expect_stderr "sun at 39.89 degrees altitude, 194.34 azimuth" "SPA's example"
for k in '"type":[[:space:]]*"cie:12"' '"sun_altitude":[[:space:]]*39.89' '"sun_azimuth":[[:space:]]*194.33' \
         '"north":[[:space:]]*30' '"sun_normal_lux":' '"sky_lux":[[:space:]]*10000' \
         '"sun_diameter":[[:space:]]*0.533'; do
    checks=$((checks + 1))
    grep -q "$k" sun.json || fail "sun.json lacks $k"
done
# A JSON scene's own clear sky and sun: --sky-only switches the lamp off and
# keeps the sky's sun (10,000 + 40,000 sin 30 = 30,000 lx); --sky overcast on
# the command line replaces the sky and its sun (10,000 lx).
cat > sunny.json <<'JSON'
{"meshes": [{"shape": "quad", "size": 4}],
 "lights": [{"type": "point", "position": [0, 2, 0], "intensity": 10}],
 "environment": {"sky": "clear", "sun": [30, 180], "sun_lux": 40000, "ground_albedo": 0}}
JSON
expect_exit 0 "info, JSON sky" -- "$ILLUM" info sunny.json
expect_stdout "^sky:        CIE type 12, 10000 lx horizontal; sun at 30.00 altitude, 180.00 azimuth (north 0), 40000 lx normal, 0.533 degrees across" \
    "info shows the sky and its sun"
expect_exit 0 "JSON sky, sky only" -- "$ILLUM" illuminance sunny.json --sky-only --plane y=0 \
    --area -0.5,-0.5,0.5,0.5 --spacing 1 --samples 4096 -o sunny.csv
checks=$((checks + 1))
awk -F, 'NR == 2 { d = $7 - 30000; exit !(d < 300 && d > -300) }' sunny.csv ||
    fail "sunny.csv: $(sed -n 2p sunny.csv), expected 30000 lx within 1%"
expect_exit 0 "JSON sky, --stats" -- "$ILLUM" illuminance sunny.json --sky-only --plane y=0 \
    --area -0.5,-0.5,0.5,0.5 --spacing 1 --samples 4 -q --stats sunny.json.stats
for k in '"type":[[:space:]]*"cie:12"' '"sun_altitude":[[:space:]]*30' '"sun_azimuth":[[:space:]]*180' \
         '"sun_normal_lux":[[:space:]]*40000' '"ground_albedo":[[:space:]]*0'; do
    checks=$((checks + 1))
    grep -q "$k" sunny.json.stats || fail "sunny.json.stats lacks $k"
done
# A JSON scene's own overcast sky gives the daylight factor where it is the
# only light: with --sky-only, or in a scene without lamps.
cat > cloudy.json <<'JSON'
{"meshes": [{"shape": "quad", "size": 4}],
 "lights": [{"type": "point", "position": [0, 2, 0], "intensity": 10}],
 "environment": {"sky": "overcast", "sky_lux": 20000}}
JSON
sed '/"lights"/d' cloudy.json > unlit.json
expect_exit 0 "info, JSON overcast" -- "$ILLUM" info cloudy.json
expect_stdout "^sky:        CIE overcast, 20000 lx horizontal" "info shows the overcast sky"
expect_exit 0 "JSON overcast, sky only" -- "$ILLUM" illuminance cloudy.json --sky-only --plane y=0 \
    --area -1,-1,1,1 --spacing 1 --samples 1024 --stats cloudy.stats
expect_stdout "daylight    factor 99.[5-9]% average\|daylight    factor 100% average" "JSON overcast: DF 100%"
expect_stdout "(20000 lx outdoors)" "JSON overcast: its own sky's lux"
for k in '"type":[[:space:]]*"overcast"' '"sky_lux":[[:space:]]*20000' '"outdoor_lux":[[:space:]]*20000'; do
    checks=$((checks + 1))
    grep -q "$k" cloudy.stats || fail "cloudy.stats lacks $k"
done
expect_exit 0 "JSON overcast, lamp on" -- "$ILLUM" illuminance cloudy.json --plane y=0 \
    --area -1,-1,1,1 --spacing 1 --samples 64
expect_stdout "--sky-only gives the daylight factor" "JSON overcast and lamp"
expect_exit 0 "JSON overcast, no lamp" -- "$ILLUM" illuminance unlit.json --plane y=0 \
    --area -1,-1,1,1 --spacing 1 --samples 1024
expect_stdout "daylight    factor 99.[5-9]% average\|daylight    factor 100% average" "JSON overcast alone: DF 100%"
expect_exit 0 "JSON sky replaced" -- "$ILLUM" illuminance sunny.json --sky overcast --sky-only --plane y=0 \
    --area -0.5,-0.5,0.5,0.5 --spacing 1 --samples 1024 -o overcast.csv
checks=$((checks + 1))
awk -F, 'NR == 2 { d = $7 - 10000; exit !(d < 100 && d > -100) }' overcast.csv ||
    fail "overcast.csv: $(sed -n 2p overcast.csv), expected 10000 lx within 1%"
expect_exit 0 "render under a clear sky" -- "$ILLUM" render lamp.json --sky cie:7 --sun 45,90 --width 8 \
    --height 8 --spp 2 -q -o clear.pfm
expect_file clear.pfm "render under a clear sky"
# The sun's disc: --sun-diameter 0 is a point, beyond 90 is refused, and it
# needs a CIE sky.
expect_exit 0 "sharp sun" -- "$ILLUM" illuminance lamp.json --sky clear --sun 30,180 --sun-diameter 0 \
    --plane y=0 --area -0.5,-0.5,0.5,0.5 --spacing 1 --samples 4 -q --stats sharp.json
checks=$((checks + 1))
grep -q '"sun_diameter":[[:space:]]*0$' sharp.json || fail "sharp.json: the sun is not a point"
expect_exit 1 "sun diameter 100" -- "$ILLUM" illuminance lamp.json --sky clear --sun 30,180 \
    --sun-diameter 100 --plane y=0 -o bad.csv
expect_exit 2 "sun diameter, overcast" -- "$ILLUM" illuminance lamp.json --sky overcast --sun-diameter 1 \
    --plane y=0 -o bad.csv
expect_exit 1 "CIE type 16" -- "$ILLUM" illuminance lamp.json --sky cie:16 --sun 30,180 --plane y=0 -o bad.csv
expect_exit 1 "CIE type x" -- "$ILLUM" illuminance lamp.json --sky cie:x --sun 30,180 --plane y=0 -o bad.csv
expect_exit 1 "sun below the horizon" -- "$ILLUM" illuminance lamp.json --sky clear --plane y=0 -o bad.csv \
    --sun-time 2026-12-21T20:00+01:00 --latitude 52.52 --longitude 13.40
expect_stderr "below the horizon" "night"
expect_exit 1 "sun altitude -5" -- "$ILLUM" illuminance lamp.json --sky clear --sun -5,180 --plane y=0 -o bad.csv
expect_exit 1 "no UTC offset" -- "$ILLUM" illuminance lamp.json --sky clear --sun-time 2026-06-21T13:00 \
    --latitude 52 --longitude 13 --plane y=0 -o bad.csv
expect_stderr "UTC offset" "no UTC offset"
expect_exit 1 "30 February" -- "$ILLUM" illuminance lamp.json --sky clear --sun-time 2026-02-30T13:00Z \
    --latitude 52 --longitude 13 --plane y=0 -o bad.csv
expect_exit 1 "latitude 91" -- "$ILLUM" illuminance lamp.json --sky clear --sun-time 2026-06-21T13:00Z \
    --latitude 91 --longitude 13 --plane y=0 -o bad.csv
expect_exit 1 "negative sun lux" -- "$ILLUM" illuminance lamp.json --sky clear --sun 30,180 --sun-lux -1 \
    --plane y=0 -o bad.csv
expect_exit 2 "clear sky without its sun" -- "$ILLUM" illuminance lamp.json --sky clear --plane y=0 -o bad.csv
expect_exit 2 "time without the place" -- "$ILLUM" illuminance lamp.json --sky clear \
    --sun-time 2026-06-21T13:00Z --latitude 52 --plane y=0 -o bad.csv
expect_exit 2 "--sun and --sun-time" -- "$ILLUM" illuminance lamp.json --sky clear --sun 30,180 \
    --sun-time 2026-06-21T13:00Z --latitude 52 --longitude 13 --plane y=0 -o bad.csv
expect_exit 2 "a sun for the overcast sky" -- "$ILLUM" illuminance lamp.json --sky overcast --sun 30,180 \
    --plane y=0 -o bad.csv
expect_exit 2 "north without a sky" -- "$ILLUM" render lamp.json --north 20 -o bad.png

# Bad input: a clear message, the exit status, no output file.
expect_exit 1 "view to CSV" -- "$ILLUM" illuminance lamp.json --view -o bad.csv
expect_exit 1 "plane to PNG" -- "$ILLUM" illuminance lamp.json --plane y=0 -o bad.png
expect_exit 2 "view and plane" -- "$ILLUM" illuminance lamp.json --view --plane y=0 -o bad.png
expect_exit 2 "width without view" -- "$ILLUM" illuminance lamp.json --plane y=0 --width 8 -o bad.csv
expect_exit 2 "camera without view" -- "$ILLUM" illuminance lamp.json --plane y=0 --fov 30 -o bad.csv
expect_exit 1 "view, width 0" -- "$ILLUM" illuminance lamp.json --view --width 0 -o bad.png
expect_no_file bad.png "bad view input"
expect_exit 1 "surface nothing matches" -- "$ILLUM" illuminance office --surface walnut -o bad.csv
expect_stderr "the scene's meshes: 'floor'" "surface nothing matches: the names"
expect_exit 1 "surface facing no face" -- "$ILLUM" illuminance office --surface desk_tops --facing 1,1,1 -o bad.csv
expect_exit 1 "facing zero" -- "$ILLUM" illuminance office --surface desk_tops --facing 0,0,0 -o bad.csv
expect_exit 2 "facing without surface" -- "$ILLUM" illuminance office --plane y=0.8 --facing +y -o bad.csv
expect_exit 2 "margin with surface" -- "$ILLUM" illuminance office --surface desk --margin 1 -o bad.csv
expect_exit 1 "surface smaller than a cell" -- "$ILLUM" illuminance office --surface desk_tops --spacing 1000 -o bad.csv
expect_no_file bad.csv "bad surface input"
expect_exit 1 "stats in a missing folder" -- "$ILLUM" illuminance lamp.json --plane y=0 --stats no/such/s.json
expect_exit 2 "no --plane, --points, --surface or --view" -- "$ILLUM" illuminance lamp.json -o bad.csv
expect_exit 2 "both --plane and --points" -- "$ILLUM" illuminance lamp.json --plane y=0 --points points.csv -o bad.csv
expect_exit 2 "--spacing with --points" -- "$ILLUM" illuminance lamp.json --points points.csv --spacing 1 -o bad.csv
expect_exit 2 "unknown option" -- "$ILLUM" illuminance lamp.json --plane y=0 --bogus -o bad.csv
expect_exit 2 "no scene" -- "$ILLUM" illuminance --plane y=0 -o bad.csv
expect_exit 1 "bad plane" -- "$ILLUM" illuminance lamp.json --plane q=1 -o bad.csv
expect_stderr "expected AXIS=VALUE" "bad plane"
expect_exit 1 "plane without a number" -- "$ILLUM" illuminance lamp.json --plane y= -o bad.csv
expect_exit 1 "area of three numbers" -- "$ILLUM" illuminance lamp.json --plane y=0 --area 0,0,1 -o bad.csv
expect_exit 1 "area inside out" -- "$ILLUM" illuminance lamp.json --plane y=0 --area 1,1,0,0 -o bad.csv
expect_exit 1 "margin too wide" -- "$ILLUM" illuminance lamp.json --plane y=0 --margin 2 -o bad.csv
expect_stderr "the measuring area is empty" "margin too wide"
expect_exit 1 "spacing 0" -- "$ILLUM" illuminance lamp.json --plane y=0 --spacing 0 -o bad.csv
expect_exit 1 "too many sensors" -- "$ILLUM" illuminance lamp.json --plane y=0 --spacing 0.0001 -o bad.csv
expect_exit 1 "samples 0" -- "$ILLUM" illuminance lamp.json --plane y=0 --samples 0 -o bad.csv
expect_exit 1 "max depth 0" -- "$ILLUM" illuminance lamp.json --plane y=0 --max-depth 0 -o bad.csv
expect_exit 1 "missing scene" -- "$ILLUM" illuminance missing.obj --plane y=0 -o bad.csv
expect_exit 1 "missing points file" -- "$ILLUM" illuminance lamp.json --points missing.txt -o bad.csv
expect_stderr "missing.txt: cannot open" "missing points file"
printf '0 0 0\n1 2 3 4\n' > four.txt
expect_exit 1 "four numbers" -- "$ILLUM" illuminance lamp.json --points four.txt -o bad.csv
expect_stderr "four.txt:2: expected" "four numbers: the line"
printf '0 nan 0\n' > nan.txt
expect_exit 1 "NaN" -- "$ILLUM" illuminance lamp.json --points nan.txt -o bad.csv
printf '0 0 0 0 0 0\n' > zero.txt
expect_exit 1 "zero normal" -- "$ILLUM" illuminance lamp.json --points zero.txt -o bad.csv
expect_stderr "zero.txt:1: the normal is zero" "zero normal"
printf '# nothing\n' > empty.txt
expect_exit 1 "no sensor" -- "$ILLUM" illuminance lamp.json --points empty.txt -o bad.csv
printf '0 0 0 x\n' > junk.txt
expect_exit 1 "junk" -- "$ILLUM" illuminance lamp.json --points junk.txt -o bad.csv
expect_no_file bad.csv "bad input"
expect_exit 1 "output in a missing folder" -- "$ILLUM" illuminance lamp.json --plane y=0 -o no/such/dir.csv

finish
