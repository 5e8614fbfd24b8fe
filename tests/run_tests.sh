#!/bin/sh
# run_tests.sh - run Unity test executables and total up their results.
#
#   sh tests/run_tests.sh build/test_vec build/test_bvh ...
#
# Every program is run (a failing one does not stop the others) and its
# output is shown.  Each program's Unity summary line
#     N Tests M Failures K Ignored
# is added up.  A program that crashes, cannot be run, prints no summary, or
# exits non-zero although its summary reports no failures counts as one
# failed test.  The last line printed is always
#     T passed, F failed, I skipped
# with passed = tests - failures - ignored.  Exit status: 1 if anything
# failed, else 0.

tests=0
failures=0
ignored=0
broken=""
log=$(mktemp) || exit 1
trap 'rm -f "$log"' EXIT
trap 'exit 130' INT TERM

for prog in "$@"; do
    case $prog in
        */*) cmd=$prog ;;
        *)   cmd=./$prog ;;   # do not look bare names up in $PATH
    esac
    echo "== $prog"
    "$cmd" >"$log" 2>&1
    rc=$?
    cat "$log"

    # "N Tests M Failures K Ignored" -> "N M K", summed over all such lines.
    counts=$(awk '/^[0-9]+ Tests [0-9]+ Failures [0-9]+ Ignored/ {
                      t += $1; f += $3; i += $5; n++ }
                  END { if (n) print t, f, i }' "$log")
    if [ -z "$counts" ]; then
        echo "run_tests.sh: $prog: no Unity summary (crashed or did not run, exit status $rc); counted as 1 failure"
        tests=$((tests + 1))
        failures=$((failures + 1))
        broken="$broken $prog"
        continue
    fi
    t=${counts%% *}
    rest=${counts#* }
    f=${rest%% *}
    i=${rest#* }
    tests=$((tests + t))
    failures=$((failures + f))
    ignored=$((ignored + i))
    if [ "$f" -eq 0 ] && [ "$rc" -ne 0 ]; then
        echo "run_tests.sh: $prog: exit status $rc despite 0 failures; counted as 1 failure"
        tests=$((tests + 1))
        failures=$((failures + 1))
    fi
    if [ "$f" -ne 0 ] || [ "$rc" -ne 0 ]; then
        broken="$broken $prog"
    fi
done

[ -n "$broken" ] && echo "run_tests.sh: failing programs:$broken"
echo "$((tests - failures - ignored)) passed, $failures failed, $ignored skipped"
[ "$failures" -eq 0 ]
