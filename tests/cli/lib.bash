# Helpers for the shell tests: run illum, check exit codes and outputs.
# ctest sets ILLUM (the program), IL_SHARED_DIR, IL_TEST_TMP, IL_SOURCE_DIR.
set -u
: "${ILLUM:?}" "${IL_TEST_TMP:?}"
rm -rf "$IL_TEST_TMP"
mkdir -p "$IL_TEST_TMP"
cd "$IL_TEST_TMP" || exit 1
# Under -DIL_SANITIZE=ON a sanitizer report must not pass for a bad-input exit 1.
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}exitcode=86"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:+$UBSAN_OPTIONS:}exitcode=86:print_stacktrace=1"
failures=0
checks=0

fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }

# expect_exit CODE DESCRIPTION -- COMMAND...: runs the command, checks its
# exit status and that it printed an "illum:" line on stderr when it failed.
expect_exit() {
    want=$1; what=$2; shift 3
    checks=$((checks + 1))
    "$@" >out.txt 2>err.txt
    got=$?
    if [ "$got" != "$want" ]; then
        fail "$what: exit $got, expected $want ($*)"; cat err.txt >&2
    elif [ "$want" != 0 ] && ! grep -q '^illum: ' err.txt; then
        fail "$what: no 'illum:' error message"
    fi
}

# expect_stderr PATTERN DESCRIPTION: the last command's stderr matches.
expect_stderr() {
    checks=$((checks + 1))
    grep -q -- "$1" err.txt || { fail "$2: stderr lacks '$1'"; cat err.txt >&2; }
}
expect_stdout() {
    checks=$((checks + 1))
    grep -q -- "$1" out.txt || { fail "$2: stdout lacks '$1'"; cat out.txt >&2; }
}
expect_no_file() {
    checks=$((checks + 1))
    # neither the file nor a leftover temporary file
    if ls "$1"* >/dev/null 2>&1; then fail "$2: '$1' (or a temporary) exists"; fi
}
expect_file() {
    checks=$((checks + 1))
    [ -s "$1" ] || fail "$2: '$1' missing or empty"
}
finish() {
    echo "$((checks - failures)) passed, $failures failed"
    [ "$failures" = 0 ]
    exit $?
}

# wait_for_sigint PID: waits (at most 10 minutes) until the process catches
# SIGINT, so that a Ctrl-C sent next reaches illum's handler: a background
# job starts with SIGINT ignored, and a signal sent before illum installs its
# handler would be lost.  Reads SigCgt (bit 1: SIGINT) in /proc/PID/status.
wait_for_sigint() {
    for _ in $(seq 1 6000); do
        mask=$(sed -n 's/^SigCgt:[[:space:]]*//p' "/proc/$1/status" 2>/dev/null) || return 1
        [ -n "$mask" ] || return 1
        [ $(( 0x$mask & 2 )) != 0 ] && return 0
        sleep 0.1
    done
    return 1
}

# expect_interrupted TIMES WHAT -- COMMAND...: runs the command in the
# background with stderr in err.txt, sends it TIMES Ctrl-C (SIGINT) half a
# second apart once it catches them, and checks its exit status 130.
expect_interrupted() {
    times=$1; what=$2; shift 3
    "$@" 2>err.txt &
    pid=$!
    if wait_for_sigint "$pid"; then
        for _ in $(seq 1 "$times"); do
            sleep 0.5
            kill -INT "$pid" 2>/dev/null
        done
    fi
    wait "$pid"
    got=$?
    checks=$((checks + 1))
    [ "$got" = 130 ] || { fail "$what: exit $got, expected 130"; cat err.txt >&2; }
}

# expect_running_files WHAT FILE... -- COMMAND...: runs the command (a
# render with --write-every) in the background and checks that every FILE
# is on disk, non-empty, while it still runs (polled for 15 s); then stops
# it with Ctrl-C.
expect_running_files() {
    what=$1; shift
    files=()
    while [ "$1" != -- ]; do files+=("$1"); shift; done
    shift
    rm -f "${files[@]}"
    "$@" &
    pid=$!
    seen=0
    for _ in $(seq 1 150); do
        all=1
        for f in "${files[@]}"; do [ -s "$f" ] || all=0; done
        if [ "$all" = 1 ] && kill -0 "$pid" 2>/dev/null; then seen=1; break; fi
        sleep 0.1
    done
    kill -INT "$pid" 2>/dev/null
    wait "$pid"
    checks=$((checks + 1))
    [ "$seen" = 1 ] || fail "$what: no running image while rendering"
}
