# Window panes (thin_glass) end to end, with scenes/window-room.json: a room
# lit by the overcast sky through one glazed window.  The pane passes light
# on a straight line, so the daylight factor with the pane is the open
# window's times the pane's transmittance over the angles the sky comes in
# at (0.923 at normal incidence, less at a slant): between 0.80 and 0.93 of
# it.  A render, an OBJ sheet of glass taken as a pane, bad panes; the
# room's portal in `info`, the hint without it, a bad portal.
. "$(dirname "$0")/lib.bash"

ROOM="$IL_SOURCE_DIR/scenes/window-room.json"
area=(--plane y=0.85 --area -2,-5,2,0 --margin 0.5 --samples 4096 --threads 2)
# The same room with the pane moved 500 m away (the line after its name;
# the portal stays on the window): an open window.
sed '/"name": "window",/{n;s/"translate": \[0, 1.5, 0\]/"translate": [0, 1.5, 500]/}' "$ROOM" > open.json
checks=$((checks + 1))
grep -q '"translate": \[0, 1.5, 500\]' open.json && [ "$(grep -c '"translate": \[0, 1.5, 0\]' open.json)" = 1 ] ||
    fail "open.json: expected the pane moved and the portal left"
checks=$((checks + 1))
cmp -s "$ROOM" open.json && fail "open.json: the window pane was not moved"

df_average() { sed -n 's/^daylight *factor \([0-9.]*\)% average.*/\1/p' out.txt; }
expect_exit 0 "the glazed window" -- "$ILLUM" illuminance "$ROOM" "${area[@]}"
expect_stdout "48 sensors on y = 0.85" "glazed: the grid"
glazed=$(df_average)
expect_exit 0 "the open window" -- "$ILLUM" illuminance open.json "${area[@]}"
open=$(df_average)
echo "daylight factor: glazed $glazed%, open $open%"
checks=$((checks + 1))
awk -v g="$glazed" -v o="$open" 'BEGIN { r = g / o; exit !(o > 2 && r > 0.80 && r < 0.93) }' ||
    fail "daylight factor glazed $glazed% against open $open%: expected 0.80-0.93 of it"

expect_exit 0 "info" -- "$ILLUM" info "$ROOM"
expect_stdout "panes:      1 mesh of thin_glass" "info: the pane"
expect_stdout "portals:    2 triangles, 2.4 m^2" "info: the portal"
# Without its portal, info suggests one.
sed -e '/"portals": \[/,/}\]},/d' -e 's/"environment": {"sky": "overcast",$/"environment": {"sky": "overcast"},/' "$ROOM" > noportal.json
expect_exit 0 "info without the portal" -- "$ILLUM" info noportal.json
expect_stdout "portals:    none (a portal on each window" "info: the hint"
# A bad portal: exit 1, the message names it, no image.
sed 's/"portals": \[{"shape": "quad"/"portals": [{"shape": "box"/' "$ROOM" > badportal.json
expect_exit 1 "a box portal" -- "$ILLUM" render badportal.json --spp 1 -o badportal.png
expect_stderr "shape: a portal is a \"quad\"" "bad portal: the message"
expect_no_file badportal.png "bad portal: no image"
expect_exit 0 "render" -- "$ILLUM" render "$ROOM" --spp 4 --width 64 --height 48 -o room.exr
expect_file room.exr "render: the image"

# The sun seen through the window (5 degrees up, due south): its disc is
# brighter than a half EXR holds, so the half file keeps 65504 there and
# says so; --exr-float keeps it and says nothing (--fov 20: the disc
# covers a few pixels).
expect_exit 0 "the sun in view" -- "$ILLUM" render "$ROOM" --sky clear --sun 5,180 --spp 16 --fov 20 \
    --width 160 --height 120 -o sun.exr
expect_stderr "brighter than 65504, the most a half EXR holds" "the sun in view: the warning"
expect_exit 0 "the sun in view, float" -- "$ILLUM" render "$ROOM" --sky clear --sun 5,180 --spp 16 --fov 20 \
    --width 160 --height 120 --exr-float -o sunf.exr
checks=$((checks + 1))
grep -q "half EXR" err.txt && fail "the sun in view, float: a warning about half floats"
expect_exit 0 "compare the two" -- "$ILLUM" compare sun.exr sunf.exr
checks=$((checks + 1))
awk '/^max_abs_error/ { exit !($2 > 1e5) }' out.txt || fail "the sun in view: the float file keeps the disc's radiance"

# An OBJ window: one transparent sheet (d 0.4) becomes a pane, with a warning.
printf 'newmtl pane\nKd 0 0 0\nd 0.4\nNi 1.5\nnewmtl wall\nKd 0.5 0.5 0.5\nKe 1 1 1\n' > sheet.mtl
printf 'mtllib sheet.mtl\no glass\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl pane\nf 1 2 3 4\no lamp\nv 0 0 -1\nv 1 0 -1\nv 1 1 -1\nv 0 1 -1\nusemtl wall\nf 5 6 7 8\n' > sheet.obj
expect_exit 0 "info on an OBJ sheet of glass" -- "$ILLUM" info sheet.obj
expect_stdout "material 'pane' is transparent on an open mesh ('glass'" "OBJ sheet: taken as a pane"

# Bad panes: exit 1 and a message that names the material.
sed 's/"glass":   {"type": "thin_glass", "ior": 1.52}/"glass": {"type": "thin_glass", "transmittance": 0.97}/' \
    "$ROOM" > bad.json
expect_exit 1 "a pane clearer than glass" -- "$ILLUM" render bad.json --spp 1 -o bad.png
expect_stderr "material 'glass': transmittance 0.97 is outside 0 to 0.9231" "bad pane: the message"
expect_no_file bad.png "bad pane: no image"
sed 's/"glass":   {"type": "thin_glass", "ior": 1.52}/"glass": {"type": "thin_glass", "specular": [1, 0.8, 0.8]}/' \
    "$ROOM" > tinted.json
expect_exit 1 "a tinted pane" -- "$ILLUM" render tinted.json --spp 1 -o tinted.png
expect_stderr "a thin_glass pane is neutral" "tinted pane: the message"
finish
