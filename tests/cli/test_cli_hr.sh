# `illum render --method hr` and `illum bake --method hr` end to end: the
# office at a small size, the "hr" object of --stats, a bake to PLY, a JSON
# scene choosing hr, and bad options that stop before any output is written.
. "$(dirname "$0")/lib.bash"

expect_exit 0 "render --method hr --help" -- "$ILLUM" render --method hr --help
for o in --bf-eps --area-eps --energy-eps --vis-rays --max-iterations; do
    expect_stdout -- "$o" "hr help lists $o"
done
expect_exit 0 "bake --help" -- "$ILLUM" bake --help
expect_stdout -- "--bf-eps" "bake --help lists the hr options"
expect_exit 0 "info office" -- "$ILLUM" info office
expect_stdout "triangles:  1074" "info office"

# Render the office: an image, and stats with every il_hr_stats field.
expect_exit 0 "render office --method hr" -- "$ILLUM" render office --method hr --vis-rays 4 \
    --width 32 --height 24 --spp 1 -o office.exr --stats office.json
expect_file office.exr "render office --method hr"
expect_stderr "illum: hr: 537 patches" "render office: summary line"
for k in '"method":[[:space:]]*"hr"' '"hr":' '"patches":[[:space:]]*537' '"elements"' '"leaves"' \
         '"links"' '"iterations"' '"visibility_rays"' '"seconds_setup"' '"seconds_refine"' \
         '"seconds_gather"' '"seconds_average"' '"seconds_render"' '"peak_bytes"' \
         '"converged":[[:space:]]*true' '"energy_change"'; do
    checks=$((checks + 1))
    grep -q "$k" office.json || fail "office.json lacks $k"
done
checks=$((checks + 1))
grep -q '"radiosity":' office.json && fail "office.json has a radiosity object"
# Refinement happened: more elements than patches, and the image is not black.
checks=$((checks + 1))
grep -q '"elements":[[:space:]]*537,' office.json && fail "office: no element was refined"
expect_exit 0 "compare hr image" -- "$ILLUM" compare office.exr office.exr --max-rmse 0
checks=$((checks + 1))
grep -q "mean_luminance  0  0" out.txt && fail "hr image is black"

# Coarser epsilons give fewer elements (the options reach the solver).
expect_exit 0 "render coarse" -- "$ILLUM" render office --method hr --bf-eps 0.5 --area-eps 0.05 \
    --vis-rays 4 --max-iterations 3 --width 8 --height 8 --spp 1 -q -o coarse.exr --stats coarse.json
# One iteration (one refinement) is not enough to converge: the stats and a
# warning say so.
expect_exit 0 "render one iteration" -- "$ILLUM" render office --method hr --vis-rays 4 --max-iterations 1 \
    --width 8 --height 8 --spp 1 -o one.exr --stats one.json
expect_stderr "hr: not converged after 1 iteration" "render one iteration"
checks=$((checks + 1))
grep -q '"converged":[[:space:]]*false' one.json || fail "one.json: converged is not false"
checks=$((checks + 1))
grep -Eq '"sweeps":[[:space:]]*[1-9]' one.json || fail "one.json: no sweeps"
# A closed white room has no finite solution: the solve stops as stalled and
# says so, and the image is still written.
echo '{"materials": {"w": {"diffuse": 1}, "e": {"diffuse": 1, "emission": 5}},
       "meshes": [{"shape": "box", "size": 4, "flip": true, "material": "w"},
                  {"shape": "box", "size": 0.5, "material": "e"}],
       "camera": {"position": [0, 1, 1.9], "target": [0, 0, 0]}}' > white.json
expect_exit 0 "hr closed white room" -- "$ILLUM" render white.json --method hr --bf-eps 0.05 --area-eps 0.01 \
    --vis-rays 4 --width 8 --height 8 --spp 1 -o white.exr --stats white.json.stats
expect_stderr "hr: the solve stopped converging" "hr closed white room"
expect_file white.exr "hr closed white room"
checks=$((checks + 1))
grep -q '"stalled":[[:space:]]*true' white.json.stats || fail "white.json.stats: stalled is not true"
checks=$((checks + 1))
grep -q '"stalled":[[:space:]]*false' office.json || fail "office.json: stalled is not false"
elements() { sed -n 's/.*"elements":[[:space:]]*\([0-9]*\).*/\1/p' "$1" | head -1; }
checks=$((checks + 1))
[ "$(elements coarse.json)" -lt "$(elements office.json)" ] || \
    fail "coarse epsilons: $(elements coarse.json) elements, not fewer than $(elements office.json)"

# A JSON scene's "render" block can choose hr; hr options then need no --method.
cat > scene.json <<'JSON'
{
  "materials": {"light": {"emission": 1, "diffuse": 0.5}, "wall": {"diffuse": 0.6}},
  "meshes": [
    {"shape": "box", "size": 2, "flip": true, "material": "wall", "transform": {"translate": [0, 1, 0]}},
    {"shape": "quad", "size": 0.5, "flip": true, "material": "light", "transform": {"translate": [0, 1.99, 0]}}
  ],
  "camera": {"position": [0, 1, 0.9], "target": [0, 1, -1]},
  "render": {"method": "hr", "width": 8, "height": 8, "spp": 1}
}
JSON
expect_exit 0 "JSON render block selects hr" -- "$ILLUM" render scene.json --vis-rays 4 -q -o json.exr \
    --stats json.json
expect_file json.exr "JSON render block selects hr"
checks=$((checks + 1))
grep -q '"method":[[:space:]]*"hr"' json.json || fail "json.json: method is not hr"
expect_exit 2 "JSON hr, --method pt with an hr option" -- "$ILLUM" render scene.json --method pt \
    --vis-rays 4 -q -o json2.exr
expect_no_file json2.exr "JSON hr, --method pt with an hr option"

# Bake to PLY with the hr object in the stats.
expect_exit 0 "bake office --method hr" -- "$ILLUM" bake office --method hr --vis-rays 4 -q \
    -o office.ply --stats bake.json
expect_file office.ply "bake office --method hr"
checks=$((checks + 1))
head -c 400 office.ply | grep -q "property float radiance_r" || fail "office.ply lacks radiance_r"
checks=$((checks + 1))
grep -q '"hr":' bake.json || fail "bake.json lacks the hr object"
checks=$((checks + 1))
grep -q '"method":[[:space:]]*"hr"' bake.json || fail "bake.json: method is not hr"

# Bad values: exit 1 naming the option, no output.
for bad in "--bf-eps 0" "--bf-eps 2" "--area-eps -1" "--energy-eps x" "--vis-rays 0" \
           "--vis-rays 5000" "--max-iterations 0" "--max-iterations 1.5"; do
    expect_exit 1 "render $bad" -- "$ILLUM" render office --method hr $bad -q -o bad.exr
    expect_stderr "${bad%% *}" "render $bad"
    expect_no_file bad.exr "render $bad"
    expect_exit 1 "bake $bad" -- "$ILLUM" bake office --method hr $bad -q -o bad.ply
    expect_no_file bad.ply "bake $bad"
done
expect_exit 2 "hr option without its value" -- "$ILLUM" render office --method hr --bf-eps

# An hr option with another method is a usage error, in either order; so is a
# radiosity option with hr.
expect_exit 2 "hr option with pt" -- "$ILLUM" render office --method pt --bf-eps 0.1 -q -o bad.exr
expect_stderr "needs --method hr" "hr option with pt"
expect_no_file bad.exr "hr option with pt"
expect_exit 2 "hr option, pt after" -- "$ILLUM" render office --vis-rays 4 --method pt -q -o bad.exr
expect_exit 2 "hr option, default method" -- "$ILLUM" render office --vis-rays 4 -q -o bad.exr
expect_exit 2 "hr option with radiosity" -- "$ILLUM" render office --method radiosity --vis-rays 4 -q -o bad.exr
expect_exit 2 "radiosity option with hr" -- "$ILLUM" render office --method hr --subdiv 2 -q -o bad.exr
expect_stderr "needs --method radiosity" "radiosity option with hr"
expect_no_file bad.exr "radiosity option with hr"
expect_exit 2 "bake: hr option with radiosity" -- "$ILLUM" bake office --vis-rays 4 -q -o bad.ply
expect_no_file bad.ply "bake: hr option with radiosity"
expect_exit 2 "bake: radiosity option with hr" -- "$ILLUM" bake office --method hr --subdiv 1 -q -o bad.ply
expect_no_file bad.ply "bake: radiosity option with hr"
# On a terminal the solve draws its progress line (script(1) gives it one).
if command -v script >/dev/null 2>&1; then
    script -qec "'$ILLUM' render office --method hr --vis-rays 4 --width 8 --height 8 --spp 1 -o tty.exr" \
        /dev/null >tty.txt 2>&1
    checks=$((checks + 1))
    grep -q "hr: linking patches" tty.txt || { fail "no hr progress line on a terminal"; cat tty.txt >&2; }
fi

# Ctrl-C during the solve (here a first refinement that would run for
# minutes): the solve stops, the image of its solution is written and the
# exit status is 130; a bake likewise.
long="--method hr --vis-rays 4096 --bf-eps 1e-4"
expect_interrupted 1 "interrupted hr render" -- "$ILLUM" render cornell $long --width 16 \
    --height 16 --spp 1 -o stopped.pfm --stats stopped.json
expect_file stopped.pfm "interrupted hr render"
expect_stderr "the hr solve stopped after 0 iterations" "interrupted hr render"
checks=$((checks + 1))
grep -q '"stopped":[[:space:]]*true' stopped.json || fail "interrupted hr render: stats lack stopped"
expect_interrupted 1 "interrupted hr bake" -- "$ILLUM" bake cornell $long -o stopped.ply
expect_file stopped.ply "interrupted hr bake"
expect_stderr "interrupted" "interrupted hr bake"

finish
