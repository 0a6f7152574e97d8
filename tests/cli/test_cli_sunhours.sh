# `illum sunhours` end to end: the help, a courtyard's plane and a file's
# points on the March equinox at the equator, where the sun is up about
# 12.08 h (12 h and the refraction at each end), climbing 15 degrees an
# hour, and a wall to the east hides the morning sun below the wall's top;
# the CSV and --stats; a scene without lights; Ctrl-C; bad input.
. "$(dirname "$0")/lib.bash"

# A 20 m square ground and a wall 10 m high and 20 km long just east of
# the origin (x = 0.5), lit by nothing: sun hours need no light.
cat > court.json <<'JSON'
{"meshes": [{"shape": "quad", "size": 20, "transform": {"translate": [0, -0.01, 0]}},
            {"shape": "quad", "size": [20, 20000], "transform": {"rotate": [0, 0, 90], "translate": [0.5, 0, 0]}}]}
JSON
printf '# x y z nx ny nz\n0 0 0 0 1 0\n-5 0 0 0 1 0\n0 0 0 0 -1 0\n' > points.txt
day=(--from 2026-03-20T00:00Z --latitude 0 --longitude 0)

expect_exit 0 "sunhours --help" -- "$ILLUM" sunhours --help
for o in --plane --points --from --latitude --longitude --hours --step --min-altitude --north --at-least -o --stats; do
    expect_stdout -- "$o" "sunhours help lists $o"
done
expect_exit 0 "help sunhours" -- "$ILLUM" help sunhours
expect_exit 0 "illum --help" -- "$ILLUM" --help
expect_stdout "sunhours SCENE" "illum --help lists sunhours"

# At the origin, beside the wall, the morning sun is hidden below
# atan(10 / 0.5) = 87 degrees: about the afternoon's 6.2 h are left; 5 m
# west of it, below atan(10 / 5.5) = 61 degrees: about 8 h are left.
expect_exit 0 "points" -- "$ILLUM" sunhours court.json --points points.txt "${day[@]}" -o points.csv \
    --stats points.json
expect_stdout "3 sensors from points.txt" "points: the count"
expect_stdout "the sun above 0 degrees for 12.08 h" "points: the day's length"
expect_stdout "minimum     0.00 h" "points: facing down"
expect_stdout "maximum     [78].[0-9]* h at (-5, 0, 0)" "points: away from the wall"
checks=$((checks + 1))
[ "$(head -1 points.csv)" = "x,y,z,nx,ny,nz,sun_hours" ] || fail "points.csv: header $(head -1 points.csv)"
checks=$((checks + 1))
awk -F, 'NR == 2 { exit !($7 > 6.1 && $7 < 6.4) } NR == 3 { exit !($7 > 7.8 && $7 < 8.2) }' points.csv ||
    fail "points.csv: $(sed -n 2,3p points.csv | tr '\n' ' '), expected about 6.2 h and 8 h"
for k in '"mode":[[:space:]]*"points"' '"sensors":[[:space:]]*3' '"sun_up_hours":' '"latitude":[[:space:]]*0' \
         '"step_minutes":[[:space:]]*1' '"average":' '"rays":'; do
    checks=$((checks + 1))
    grep -q "$k" points.json || fail "points.json lacks $k"
done
# The plane: 100 cells of 2 m; the sensors beyond the wall's line (x > 0.5)
# lose the afternoon sun, those before it the morning's: each keeps more
# than half the day.
expect_exit 0 "plane" -- "$ILLUM" sunhours court.json --plane y=0 --area -10,-10,10,10 --spacing 2 "${day[@]}" \
    --at-least 6 --stats plane.json -q
expect_stdout "100 sensors on y = 0 facing +y: 10 x 10 cells of 2 x 2 m" "plane: the grid"
expect_stdout "at least    6 h on 100.0% of the sensors (100 of 100)" "plane: every sensor half a day"
checks=$((checks + 1))
grep -q '"share_at_least":[[:space:]]*1' plane.json || fail "plane.json lacks the share"
# A minimum altitude of 30 degrees: the sun climbs 15 degrees an hour there.
expect_exit 0 "min altitude" -- "$ILLUM" sunhours court.json --points points.txt "${day[@]}" --min-altitude 30
expect_stdout "the sun above 30 degrees for 8.0[0-4] h" "min altitude: about 8 h"

# Ctrl-C: a year over 160,000 sensors stops at the next round and writes
# the hours of the part of the year counted.
expect_interrupted 1 "interrupted" -- "$ILLUM" sunhours court.json --plane y=0 --area -10,-10,10,10 --spacing 0.05 \
    --from 2026-01-01T00:00Z --hours 8760 --latitude 0 --longitude 0 -o stopped.csv --stats stopped.json
expect_file stopped.csv "interrupted: the hours so far"
for k in '"stopped":[[:space:]]*true' '"hours_done":'; do
    checks=$((checks + 1))
    grep -q "$k" stopped.json || fail "stopped.json lacks $k"
done
checks=$((checks + 1))
awk '/"hours_done"/ { gsub(/[^0-9.]/, "", $2); exit !($2 > 0 && $2 < 8760) }' stopped.json ||
    fail "stopped.json: hours_done not within the year"

expect_exit 2 "no period" -- "$ILLUM" sunhours court.json --plane y=0 --latitude 0 --longitude 0
expect_exit 2 "no place" -- "$ILLUM" sunhours court.json --plane y=0 --from 2026-03-20T00:00Z
expect_exit 2 "plane and points" -- "$ILLUM" sunhours court.json --plane y=0 --points points.txt "${day[@]}"
expect_exit 2 "area without a plane" -- "$ILLUM" sunhours court.json --points points.txt --area 0,0,1,1 "${day[@]}"
expect_exit 2 "unknown option" -- "$ILLUM" sunhours court.json --plane y=0 --samples 4 "${day[@]}"
expect_exit 1 "no offset" -- "$ILLUM" sunhours court.json --plane y=0 --from 2026-03-20T00:00 --latitude 0 --longitude 0
expect_stderr "UTC offset" "no offset"
expect_exit 1 "step 0" -- "$ILLUM" sunhours court.json --plane y=0 "${day[@]}" --step 0
expect_exit 1 "--plane twice" -- "$ILLUM" sunhours court.json --plane y=0 --plane y=1 "${day[@]}"
expect_stderr "--plane: given twice" "--plane twice"
expect_exit 1 "latitude 95" -- "$ILLUM" sunhours court.json --plane y=0 --from 2026-03-20T00:00Z --latitude 95 --longitude 0
expect_exit 1 "not csv" -- "$ILLUM" sunhours court.json --plane y=0 "${day[@]}" -o hours.png
# A period running past 2100 (found by fuzzing: it failed mid-count without
# naming the option).
expect_exit 1 "a period past 2100" -- "$ILLUM" sunhours court.json --plane y=0 --from 2100-12-31T23:59Z \
    --latitude 0 --longitude 0 -o late.csv
expect_stderr "the period must lie within the years 1900 to 2100" "a period past 2100"
expect_no_file late.csv "a period past 2100"
expect_exit 1 "missing scene" -- "$ILLUM" sunhours nothing.json --plane y=0 "${day[@]}" -o none.csv
expect_no_file none.csv "missing scene"
finish
