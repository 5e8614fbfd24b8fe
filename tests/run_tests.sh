#!/bin/sh
# run_tests.sh - run test programs, keep each one's output in a log, and total up the results.
#
#   sh tests/run_tests.sh [-v] [-j N] PROG...     run the programs, N at a time (default 1),
#                                                 then report as below
#   sh tests/run_tests.sh --run LOG CMD [ARG...]  run one command into LOG (what `make test`
#                                                 does for each program, in parallel)
#   sh tests/run_tests.sh --report [-v] LOG...    report on logs written by --run
#
# A program is either a Unity test program, whose summary lines
#     N Tests M Failures K Ignored
# are added up, or a shell suite (tests/test_cli.sh) whose last line of the form
#     [NAME: ]N passed, M failed[, K skipped]
# gives its counts. A program that crashes, cannot be run, prints no summary, or exits
# non-zero although its summary reports no failures counts as one failed test.
#
# The report prints one line per program, in the order given (so the same on every run,
# whatever order the programs finished in), and the full output of every program that
# failed; with -v the full output of every program. The last line printed is always
#     T passed, F failed, I skipped
# with passed = tests - failures - ignored. Exit status: 1 if anything failed, else 0.

# ---- --run LOG CMD...: the output in LOG, "status wall_seconds cpu_seconds" in LOG.rc ----
if [ "$1" = --run ]; then
    log=$2
    shift 2
    case $1 in
        */*) ;;
        *) if [ -f "$1" ]; then first=./$1; shift; set -- "$first" "$@"; fi ;;   # a file here, not one in $PATH
    esac
    # nanoseconds when date has %N (GNU), else whole seconds
    now() { t=$(date +%s%N 2>/dev/null); case $t in *N*|'') echo "$(date +%s)000000000" ;; *) echo "$t" ;; esac; }
    t0=$(now)
    "$@" >"$log" 2>&1
    rc=$?
    t1=$(now)
    # `times` prints the shell's, then its children's user and system time: the command's CPU
    # (into a file: in a $(...) subshell it would see no children)
    times >"$log.rc"
    cpu=$(awk 'NR == 2 { n = split($0, f, " "); s = 0
                         for (i = 1; i <= n; i++) { split(f[i], ms, "m"); s += ms[1] * 60 + ms[2] }
                         printf "%.1f", s }' "$log.rc")
    echo "$rc $(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.1f", (b - a) / 1e9 }') ${cpu:-?}" >"$log.rc"
    exit 0
fi

# (from xargs below: PROG LOG)
[ "$1" = --run-pair ] && exec sh "$0" --run "$3" "$2"

verbose=0
jobs=1
report_only=0
while :; do
    case $1 in
        --report) report_only=1; shift ;;
        -v) verbose=1; shift ;;
        -j) jobs=$2; shift 2 ;;
        -j*) jobs=${1#-j}; shift ;;
        *) break ;;
    esac
done

tmpdir=""
trap '[ -n "$tmpdir" ] && rm -rf "$tmpdir"' EXIT
trap 'exit 130' INT TERM

# ---- run the programs themselves (not under make): into a temporary directory ----
if [ "$report_only" -eq 0 ]; then
    tmpdir=$(mktemp -d) || exit 1
    i=0
    for prog in "$@"; do
        i=$((i + 1))
        printf '%s\n%s\n' "$prog" "$tmpdir/$i.$(basename "$prog").log"
    done | xargs -n 2 -P "$jobs" sh "$0" --run-pair
    [ $? -eq 0 ] || exit 1
    i=0
    for prog in "$@"; do
        i=$((i + 1))
        set -- "$@" "$tmpdir/$i.$(basename "$prog").log"
    done
    shift "$i"
fi

tests=0
failures=0
ignored=0
broken=""
for log in "$@"; do
    name=$(basename "$log" .log)
    name=${name#[0-9]*.}
    if [ -r "$log.rc" ]; then read -r rc wall cpu <"$log.rc"; else rc=127 wall=? cpu=?; fi
    [ -r "$log" ] || log=/dev/null
    # "N Tests M Failures K Ignored" summed over all such lines, else the last "N passed, M failed"
    counts=$(awk '/^[0-9]+ Tests [0-9]+ Failures [0-9]+ Ignored/ { t += $1; f += $3; i += $5; n++ }
                  /^([^ ]+: )?[0-9]+ passed, [0-9]+ failed(, [0-9]+ skipped)? *$/ {
                      s = $0; sub(/^[^ ]+: /, "", s); split(s, w, /[ ,]+/)
                      sp = w[1]; sf = w[3]; si = (w[5] == "" ? 0 : w[5]); m = 1 }
                  END { if (n) print t, f, i; else if (m) print sp + sf + si, sf, si }' "$log")
    note=""
    if [ -z "$counts" ]; then
        t=1 f=1 i=0
        note="no summary (crashed or did not run, exit status $rc); counted as 1 failure"
    else
        t=${counts%% *}
        rest=${counts#* }
        f=${rest%% *}
        i=${rest#* }
        if [ "$f" -eq 0 ] && [ "$rc" -ne 0 ]; then
            t=$((t + 1)) f=1
            note="exit status $rc despite 0 failures; counted as 1 failure"
        fi
    fi
    tests=$((tests + t))
    failures=$((failures + f))
    ignored=$((ignored + i))
    if [ "$f" -ne 0 ] || [ "$rc" -ne 0 ]; then
        broken="$broken $name"
        status=FAIL
    else
        status=ok
    fi
    if [ "$verbose" -eq 1 ] || [ "$status" = FAIL ]; then
        echo "== $name"
        cat "$log"
    fi
    line=$(printf '%-4s %-22s %4d tests' "$status" "$name" "$t")
    [ "$f" -ne 0 ] && line="$line, $f failed"
    [ "$i" -ne 0 ] && line="$line, $i skipped"
    echo "$line  ($wall s, cpu $cpu s)${note:+  $note}"
done

[ -n "$broken" ] && echo "run_tests.sh: failing programs:$broken"
echo "$((tests - failures - ignored)) passed, $failures failed, $ignored skipped"
[ "$failures" -eq 0 ]
