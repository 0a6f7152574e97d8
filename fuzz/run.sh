#!/usr/bin/env bash
# Builds the .hdr reader's libFuzzer target with clang, AddressSanitizer and
# UndefinedBehaviorSanitizer, and fuzzes it (fuzz/README.md).
#
#   fuzz/run.sh [SECONDS] [extra libFuzzer options...]     (default 60 s)
#
# Build output and the growing working corpus go to build-fuzz/ (or
# $FUZZ_BUILD); the seed corpus fuzz/corpus/hdr is only read.  Crashing
# inputs are written to build-fuzz/artifacts/.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-60}
shift || true
build=${FUZZ_BUILD:-$root/build-fuzz}
mkdir -p "$build/corpus" "$build/artifacts"

# The reader needs rgbe*.c, error.c (il_fail), color.c (XYZ -> Rec.709) and
# image.c (il_image_alloc).  image.c also holds the file dispatch, which calls
# the EXR/PNG/PFM codecs (and their libraries); the target never goes through
# it, so those are replaced by stubs that abort.  The stubs are made from the
# link's own list of missing symbols, and the build fails if anything but
# image.c is missing one.
srcs=(fuzz/fuzz_hdr.c src/image/rgbe.c src/image/rgbe_read.c src/image/image.c
      src/core/error.c src/core/color.c src/core/atomic_file.c)
flags=(-std=c17 -g -O1 -fno-omit-frame-pointer -D_POSIX_C_SOURCE=200809L
       -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined
       -I"$root/src" -I"$root/include")
cd "$root"
clang "${flags[@]}" "${srcs[@]}" -lm -o "$build/fuzz_hdr.nolink" \
    -Wl,--warn-unresolved-symbols > "$build/link.log" 2>&1 || { cat "$build/link.log"; exit 1; }
rm -f "$build/fuzz_hdr.nolink"
if grep "undefined reference" "$build/link.log" | grep -v "image\.c:" | grep -q .; then
    echo "fuzz/run.sh: unresolved symbols outside image.c:" >&2
    grep "undefined reference" "$build/link.log" | grep -v "image\.c:" >&2
    exit 1
fi
{
    echo '#include <stdlib.h>'
    sed -n "s/.*undefined reference to \`\([A-Za-z_0-9]*\)'.*/\1/p" "$build/link.log" | sort -u |
        while read -r sym; do echo "void $sym(void); void $sym(void) { abort(); }"; done
} > "$build/stubs.c"
clang "${flags[@]}" "${srcs[@]}" "$build/stubs.c" -lm -o "$build/fuzz_hdr"

export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
exec "$build/fuzz_hdr" "$build/corpus" "$root/fuzz/corpus/hdr" \
    -dict="$root/fuzz/hdr.dict" -max_total_time="$seconds" -max_len=4096 \
    -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$build/artifacts/" "$@"
