#!/usr/bin/env python3
"""Writes the hand-made seed corpus fuzz/corpus/hdr/ (fuzz/README.md).

An encoder independent of src/image: every ok-pattern-* file holds the same
9x8 picture of RGBE bytes in one of the eight orientations and one of the three
scanline encodings (flat, old-style runs, new-style per-channel runs), so the
replay test (fuzz/replay.c) can check that they all decode to one image.  The
other files cover header variants (ok-*) and corrupt files (bad-*).
Run from the repository root: python3 fuzz/make_corpus.py
"""
import os

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus", "hdr")
W, H = 9, 8


def pattern():
    """RGBE bytes p[y][x], y from the top.  Mantissas >= 128 (never a run
    marker, never a 2,2 RLE start); a constant row stretch and a constant
    column stretch make old-style runs in either scanline direction; blue is
    constant, a run in every new-style scanline."""
    p = [[(128 + (13 * x + 7 * y) % 128, 128 + (5 * x + 11 * y) % 128, 200,
           128 + (x + y) % 4) for x in range(W)] for y in range(H)]
    for x in range(2, 8):
        p[2][x] = (130, 140, 200, 129)
    for y in range(1, 7):
        p[y][8] = (160, 170, 200, 131)
    return p


# Resolution line -> (x_first, x_decreasing, y_increasing); see rgbe_read.c.
ORIENT = {
    "mYpX": "-Y {h} +X {w}", "mYmX": "-Y {h} -X {w}",
    "pYpX": "+Y {h} +X {w}", "pYmX": "+Y {h} -X {w}",
    "pXpY": "+X {w} +Y {h}", "pXmY": "+X {w} -Y {h}",
    "mXpY": "-X {w} +Y {h}", "mXmY": "-X {w} -Y {h}",
}


def scanlines(p, res):
    """The picture's pixels in file order, as a list of scanlines."""
    a, b = res.split()[0], res.split()[2]
    w, h = len(p[0]), len(p)
    if a[1] == "Y":
        ys = range(h) if a[0] == "-" else range(h - 1, -1, -1)
        xs = range(w) if b[0] == "+" else range(w - 1, -1, -1)
        return [[p[y][x] for x in xs] for y in ys]
    xs = range(w) if a[0] == "+" else range(w - 1, -1, -1)
    ys = range(h) if b[0] == "-" else range(h - 1, -1, -1)
    return [[p[y][x] for y in ys] for x in xs]


def flat(line):
    return b"".join(bytes(px) for px in line)


def old_rle(line):
    """Pixels, each repeat of the previous pixel as (1,1,1,n) markers, low
    byte first (n << 0, n << 8, ...)."""
    out, i = bytearray(), 0
    while i < len(line):
        out += bytes(line[i])
        j = i + 1
        while j < len(line) and line[j] == line[i]:
            j += 1
        c = j - i - 1
        while c > 0:
            out += bytes((1, 1, 1, c & 255))
            c >>= 8
        i = j
    return bytes(out)


def new_rle(line):
    n = len(line)
    out = bytearray((2, 2, n >> 8, n & 255))
    for k in range(4):
        b = [px[k] for px in line]
        i = 0
        while i < n:
            j = i
            while j < n and j - i < 127 and b[j] == b[i]:
                j += 1
            if j - i >= 3:
                out += bytes((128 + j - i, b[i]))
                i = j
                continue
            j = i  # literal up to the next run of 3 or 128 bytes
            while j < n and j - i < 128 and not (j + 2 < n and b[j] == b[j + 1] == b[j + 2]):
                j += 1
            out += bytes((j - i,)) + bytes(b[i:j])
            i = j
    return bytes(out)


def header(res, extra=""):
    return ("#?RADIANCE\n# fuzz seed\n" + extra + "FORMAT=32-bit_rle_rgbe\n\n" + res + "\n").encode()


def save(name, data):
    with open(os.path.join(OUT, name), "wb") as f:
        f.write(data)


def main():
    os.makedirs(OUT, exist_ok=True)
    p = pattern()
    for key, res in ORIENT.items():
        res = res.format(w=W, h=H)
        lines = scanlines(p, res)
        for enc, fn in (("flat", flat), ("oldrle", old_rle), ("rle", new_rle)):
            save("ok-pattern-%s-%s" % (key, enc), header(res) + b"".join(fn(l) for l in lines))

    px = [(128, 64, 32, 129), (200, 200, 200, 130), (255, 0, 128, 120)]
    save("ok-rgbe-magic-crlf",
         b"#?RGBE\r\n# comment\r\nFORMAT=32-bit_rle_rgbe\r\n\r\n-Y 1 +X 3\r\n" + flat(px))
    save("ok-no-format", b"#?RADIANCE\n\n-Y 1 +X 3\n" + flat(px))
    save("ok-exposure-colorcorr",
         b"#?RADIANCE\nEXPOSURE=2\nEXPOSURE= 0.5e1\n  COLORCORR=1 2 0.5\nCOLORCORR=1\t1 4\n"
         b"PIXASPECT=2\nVIEW= -vtv -vp 0 0 0\nPRIMARIES=0 0 0 0 0 0 0 0\nGAMMA=1\n"
         b"FORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 3\n" + flat(px))
    save("ok-xyze", b"#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 3\n" + flat(
        [(243, 255, 255, 128), (211, 109, 9, 128), (0, 255, 0, 128)]))
    wide = [(130, 131, 132, 129)] * 300
    # Row 1: 299 repeats as (1,1,1,43) (1,1,1,1).  Row 2 starts with a run
    # (repeating row 1's last pixel), then a zero-count marker shifts the
    # next one: 43 + 1 + (0 + (1 << 8)) = 300 pixels.
    save("ok-wide-oldrle", header("-Y 2 +X 300") + old_rle(wide)
         + bytes((1, 1, 1, 43, 200, 150, 140, 128, 1, 1, 1, 0, 1, 1, 1, 1)))
    row = p[0]
    save("ok-mixed", header("-Y 3 +X 9") + new_rle(row)
         + flat([(2, 200, 5, 128)] + row[1:]) + flat([(2, 2, 130, 128)] + row[1:]))

    good = header("-Y 8 +X 9") + b"".join(new_rle(l) for l in scanlines(p, "-Y 8 +X 9"))
    save("bad-truncated-rle", good[:-5])
    save("bad-truncated-flat", header("-Y 2 +X 3") + flat(px) + flat(px)[:-1])
    save("bad-run-overrun", header("-Y 1 +X 9") + bytes((2, 2, 0, 9, 128 + 10, 7)) + bytes(40))
    save("bad-literal-overrun", header("-Y 1 +X 9") + bytes((2, 2, 0, 9, 10)) + bytes(60))
    save("bad-length-mismatch", header("-Y 1 +X 9") + bytes((2, 2, 0, 10)) + bytes(60))
    save("bad-first-repeat", header("-Y 1 +X 3") + bytes((1, 1, 1, 2)) + flat(px))
    save("bad-old-run-overrun", header("-Y 1 +X 3") + flat(px[:1]) + bytes((1, 1, 1, 3)))
    save("bad-format", b"#?RADIANCE\nFORMAT=32-bit_rle_rgba\n\n-Y 1 +X 3\n" + flat(px))
    save("bad-conflicting-format",
         b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 3\n" + flat(px))
    save("bad-exposure-zero", b"#?RADIANCE\nEXPOSURE=0\n\n-Y 1 +X 3\n" + flat(px))
    save("bad-colorcorr", b"#?RADIANCE\nCOLORCORR=1 2\n\n-Y 1 +X 3\n" + flat(px))
    save("bad-resolution", b"#?RADIANCE\n\n-Y 1 +Y 3\n" + flat(px))
    save("bad-huge", b"#?RADIANCE\n\n-Y 65537 +X 3\n" + flat(px))
    save("bad-zero-size", b"#?RADIANCE\n\n-Y 0 +X 3\n" + flat(px))
    save("bad-no-empty-line", b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n-Y 1 +X 3\n")


if __name__ == "__main__":
    main()
