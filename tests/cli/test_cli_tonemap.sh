# `illum tonemap` and the tone-mapping options of `illum render`
# (docs/tonemapping.md): every operator on a rendered EXR/HDR/PFM, the
# linear operator giving render's own PNG bytes, bloom, auto exposure, and
# bad input.
. "$(dirname "$0")/lib.bash"

expect_exit 0 "tonemap --help" -- "$ILLUM" tonemap --help
expect_stdout "usage: illum tonemap" "tonemap --help"
expect_stdout "--bloom-radius" "tonemap --help"
expect_exit 0 "help tonemap" -- "$ILLUM" help tonemap
expect_stdout "usage: illum tonemap" "help tonemap"
expect_exit 0 "render --help" -- "$ILLUM" render --help
expect_stdout "--tonemap linear|gamma|reinhard|filmic" "render --help"
expect_exit 0 "illum --help" -- "$ILLUM" --help
expect_stdout "tonemap IN OUT.png" "illum --help"

R="--width 40 --height 32 --spp 4 --seed 3 -q"
expect_exit 0 "render cornell" -- "$ILLUM" render cornell $R -o c.exr -o c.hdr -o c.pfm -o c.png
for f in c.exr c.hdr c.pfm c.png; do expect_file "$f" "render cornell"; done

# Every operator from every HDR format.
for op in linear gamma reinhard filmic; do
    for ext in exr hdr pfm; do
        expect_exit 0 "tonemap $op $ext" -- "$ILLUM" tonemap "c.$ext" "$op-$ext.png" --op "$op" -q
        expect_file "$op-$ext.png" "tonemap $op $ext"
    done
done
# --tonemap is the same as --op.
expect_exit 0 "tonemap --tonemap" -- "$ILLUM" tonemap c.pfm filmic2.png --tonemap filmic -q
checks=$((checks + 1))
cmp -s filmic2.png filmic-pfm.png || fail "--tonemap filmic and --op filmic differ"
# The operators differ from each other.
for op in gamma reinhard filmic; do
    checks=$((checks + 1))
    cmp -s "$op-pfm.png" linear-pfm.png && fail "$op gives the linear operator's bytes"
done

# Linear with EV 0 from the bit-exact PFM gives render's own PNG, byte for
# byte; with an exposure, both agree too.
checks=$((checks + 1))
cmp -s linear-pfm.png c.png || fail "tonemap --op linear differs from render's PNG"
expect_exit 0 "render --exposure" -- "$ILLUM" render cornell $R --exposure 1.5 -o e.png -o e.pfm
expect_exit 0 "tonemap --exposure" -- "$ILLUM" tonemap e.pfm te.png --exposure 1.5 -q
checks=$((checks + 1))
cmp -s e.png te.png || fail "--exposure 1.5: tonemap and render differ"
checks=$((checks + 1))
cmp -s e.png c.png && fail "--exposure 1.5 changed nothing"

# Options: gamma, white point, auto exposure (with and without a percentile),
# bloom; each changes the image.
expect_exit 0 "gamma 1.8" -- "$ILLUM" tonemap c.pfm g18.png --op gamma --gamma 1.8 -q
expect_exit 0 "white 0.5" -- "$ILLUM" tonemap c.pfm w.png --op reinhard --white 0.5 -q
expect_exit 0 "auto exposure" -- "$ILLUM" tonemap c.pfm auto.png --auto-exposure
expect_stderr "auto" "auto exposure"
expect_stderr "99% percentile" "auto exposure"
expect_exit 0 "auto exposure 50" -- "$ILLUM" tonemap c.pfm auto50.png --auto-exposure 50 --op filmic -q
expect_exit 0 "auto exposure last" -- "$ILLUM" tonemap --op filmic c.pfm auto99.png -q --auto-exposure
expect_exit 0 "bloom" -- "$ILLUM" tonemap c.exr bloom.png --op filmic --bloom 0.3 --bloom-threshold 0.5 --bloom-radius 0.05 -q
for pair in "g18.png gamma-pfm.png" "w.png reinhard-pfm.png" "auto.png linear-pfm.png" \
            "auto50.png auto99.png" "bloom.png filmic-exr.png"; do
    set -- $pair
    checks=$((checks + 1))
    cmp -s "$1" "$2" && fail "$1 and $2 are the same"
done

# render: --tonemap and bloom write the PNG through the operator; the HDR
# outputs stay radiance, identical to a render without them.
expect_exit 0 "render --tonemap" -- "$ILLUM" render cornell $R --tonemap filmic --bloom 0.2 \
    --auto-exposure 95 -o rt.png -o rt.pfm
expect_file rt.png "render --tonemap"
expect_exit 0 "render --tonemap: radiance" -- "$ILLUM" compare rt.pfm c.pfm --max-rmse 0
expect_exit 0 "tonemap = render --tonemap" -- "$ILLUM" tonemap c.pfm rt2.png --op filmic --bloom 0.2 --auto-exposure 95 -q
checks=$((checks + 1))
cmp -s rt.png rt2.png || fail "render --tonemap and tonemap of its PFM differ"
expect_exit 0 "render --tonemap reinhard --white" -- "$ILLUM" render cornell $R --tonemap reinhard --white 2 -o rw.png
expect_file rw.png "render --tonemap reinhard"

# Bad input: values (exit 1), usage (exit 2); no output is left behind.
expect_exit 1 "missing input" -- "$ILLUM" tonemap nothere.exr out1.png
expect_stderr "nothere.exr" "missing input"
expect_no_file out1.png "missing input"
printf 'not an image' > junk.exr
expect_exit 1 "corrupt input" -- "$ILLUM" tonemap junk.exr out2.png
expect_no_file out2.png "corrupt input"
head -c 200 c.exr > cut.exr
expect_exit 1 "truncated input" -- "$ILLUM" tonemap cut.exr out3.png
expect_no_file out3.png "truncated input"
expect_exit 1 "output not png" -- "$ILLUM" tonemap c.pfm out4.exr
expect_stderr "png" "output not png"
expect_no_file out4.exr "output not png"
expect_exit 1 "unknown operator" -- "$ILLUM" tonemap c.pfm out5.png --op aces
expect_stderr "unknown operator" "unknown operator"
expect_exit 1 "bloom > 1" -- "$ILLUM" tonemap c.pfm out6.png --bloom 2
expect_exit 1 "bloom radius 0" -- "$ILLUM" tonemap c.pfm out6.png --bloom 0.5 --bloom-radius 0
expect_exit 1 "negative white" -- "$ILLUM" tonemap c.pfm out6.png --op reinhard --white -1
expect_exit 1 "gamma 0" -- "$ILLUM" tonemap c.pfm out6.png --op gamma --gamma 0
expect_exit 1 "percentile 0" -- "$ILLUM" tonemap c.pfm out6.png --auto-exposure 0
expect_exit 1 "percentile 101" -- "$ILLUM" tonemap c.pfm out6.png --auto-exposure 101
expect_exit 1 "exposure nan" -- "$ILLUM" tonemap c.pfm out6.png --exposure nan
expect_exit 1 "threshold text" -- "$ILLUM" tonemap c.pfm out6.png --bloom 0.2 --bloom-threshold bright
expect_no_file out6.png "bad values"
expect_exit 2 "--gamma without gamma" -- "$ILLUM" tonemap c.pfm out7.png --gamma 2
expect_stderr "needs --tonemap gamma" "--gamma without gamma"
expect_exit 2 "--white without reinhard" -- "$ILLUM" tonemap c.pfm out7.png --op filmic --white 2
expect_exit 2 "unknown option" -- "$ILLUM" tonemap c.pfm out7.png --glow 1
expect_exit 2 "missing value" -- "$ILLUM" tonemap c.pfm out7.png --bloom
expect_exit 2 "no output" -- "$ILLUM" tonemap c.pfm
expect_exit 2 "no arguments" -- "$ILLUM" tonemap
expect_exit 2 "three files" -- "$ILLUM" tonemap c.pfm out7.png extra.png
expect_no_file out7.png "usage errors"
expect_exit 1 "render: bad operator" -- "$ILLUM" render cornell $R --tonemap sepia -o bad.png
expect_exit 2 "render: --gamma without gamma" -- "$ILLUM" render cornell $R --gamma 2 -o bad.png
expect_exit 2 "render: --op is tonemap's" -- "$ILLUM" render cornell $R --op filmic -o bad.png
expect_no_file bad.png "render bad tone mapping"
finish
