#!/bin/sh
# check.sh - self-check of the Unity-compatible runner in tests/runner.
#
# Builds selftest.c and selftest_fail.c against tests/runner (warning-free,
# plain, with ASan/UBSan, and selftest.c also as C++), runs them and checks
# the per-test results and the summary lines.  If UNITY_DIR points at the
# real Unity's src/ directory, the same checks run against it too
# (compiled with -DUNITY_INCLUDE_DOUBLE).  Exits non-zero on any mismatch.
#
#   sh tests/runner/check.sh
#   UNITY_DIR=/path/to/Unity/src sh tests/runner/check.sh
set -u

HERE=$(cd "$(dirname "$0")" && pwd)
CC=${CC:-gcc}
CXX=${CXX:-g++}
WARN="-std=c99 -Wall -Wextra -pedantic -Wshadow"
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
errors=0

# Build from a copy of the test sources: a quoted #include "unity.h" looks in
# the source file's own directory first, which would always pick up
# tests/runner/unity.h, even when testing against the real Unity.
SRC="$OUT/src"
mkdir "$SRC"
cp "$HERE/selftest.c" "$HERE/selftest_fail.c" "$SRC/"

bad() { echo "check.sh: MISMATCH: $*"; errors=$((errors + 1)); }

# compile NAME OUTPUT-EXE COMPILER-AND-FLAGS...
# (sh has no local variables, hence the prefixed names in each function)
compile() {
    c_name=$1; c_exe=$2; shift 2
    if ! "$@" -o "$c_exe" >"$OUT/cc.log" 2>&1 || [ -s "$OUT/cc.log" ]; then
        cat "$OUT/cc.log"
        bad "$c_name: build failed or produced warnings"
        return 1
    fi
}

# expect LABEL EXE EXPECTED-SUMMARY EXPECTED-EXIT
# Runs EXE, checks that every test named fail_*/ignore_*/pass_*/test_* got
# the status its name promises, the summary line and the exit status.
expect() {
    x_label=$1; x_summary=$3; x_want_rc=$4
    "$2" >"$OUT/run.log" 2>&1
    x_rc=$?
    sed -nE 's/^[^:]*:[0-9]+:([A-Za-z0-9_]+):(PASS|FAIL|IGNORE).*$/\1 \2/p' \
        "$OUT/run.log" >"$OUT/status.log"
    while read -r test status; do
        case $test:$status in
            fail_*:FAIL | ignore_*:IGNORE | pass_*:PASS | test_*:PASS) ;;
            *) bad "$x_label: $test reported $status" ;;
        esac
    done <"$OUT/status.log"
    x_tests=$(wc -l <"$OUT/status.log" | tr -d ' ')
    x_got=$(grep -E '^[0-9]+ Tests [0-9]+ Failures [0-9]+ Ignored' "$OUT/run.log" | sed 's/ *$//')
    [ "$x_got" = "$x_summary" ] || bad "$x_label: summary '$x_got', expected '$x_summary'"
    case $x_summary in
        "$x_tests "*) ;;
        *) bad "$x_label: $x_tests result lines for '$x_summary'" ;;
    esac
    [ "$x_rc" -eq "$x_want_rc" ] || bad "$x_label: exit status $x_rc, expected $x_want_rc"
}

# exact_line LABEL MARKER SUFFIX: the output line for the assertion on the
# source line tagged MARKER must end in ":<line>:SUFFIX".
exact_line() {
    l_line=$(grep -n "$2" "$HERE/selftest_fail.c" | cut -d: -f1)
    grep -qF ":$l_line:$3" "$OUT/run.log" || bad "$1: no line ending in ':$l_line:$3'"
}

# check_runner LABEL INCLUDE-DIR UNITY-C EXTRA-FLAGS
check_runner() {
    label=$1; inc=$2; src=$3; flags=$4
    # shellcheck disable=SC2086
    compile "$label selftest" "$OUT/selftest" $CC $flags -I"$inc" "$SRC/selftest.c" "$src" -lm &&
        expect "$label selftest" "$OUT/selftest" "9 Tests 0 Failures 0 Ignored" 0
    # shellcheck disable=SC2086
    compile "$label selftest_fail" "$OUT/selftest_fail" $CC $flags -I"$inc" "$SRC/selftest_fail.c" "$src" -lm &&
        {
            expect "$label selftest_fail" "$OUT/selftest_fail" "29 Tests 24 Failures 2 Ignored" 24
            exact_line "$label" CHECK-LINE-INT "fail_equal_int:FAIL: Expected 1 Was 2"
            exact_line "$label" CHECK-LINE-STRING \
                "fail_string:FAIL: Expected 'fog' Was 'fig' Character 1 Expected 'o' Was 'i':strings"
            grep -q '^OK$' "$OUT/run.log" && bad "$label: failing run printed OK"
            grep -q '^FAIL$' "$OUT/run.log" || bad "$label: failing run did not end in FAIL"
        }
    echo "check.sh: $label done"
}

check_runner "tests/runner" "$HERE" "$HERE/unity.c" "$WARN -O2"
check_runner "tests/runner+asan" "$HERE" "$HERE/unity.c" \
    "$WARN -g -fsanitize=address,undefined -fno-sanitize-recover=undefined"

# selftest.c compiled as C++ against the runner (itself compiled as C).
if command -v "$CXX" >/dev/null 2>&1; then
    $CC $WARN -c "$HERE/unity.c" -o "$OUT/unity.o" &&
        compile "c++ selftest" "$OUT/selftest_cxx" $CXX -Wall -Wextra -Wshadow -x c++ \
            -I"$HERE" "$SRC/selftest.c" -x none "$OUT/unity.o" &&
        expect "c++ selftest" "$OUT/selftest_cxx" "9 Tests 0 Failures 0 Ignored" 0
    echo "check.sh: c++ done"
fi

if [ -n "${UNITY_DIR:-}" ]; then
    check_runner "real Unity" "$UNITY_DIR" "$UNITY_DIR/unity.c" "-std=c99 -DUNITY_INCLUDE_DOUBLE"
fi

if [ "$errors" -ne 0 ]; then
    echo "check.sh: $errors mismatch(es)"
    exit 1
fi
echo "check.sh: all checks passed"
