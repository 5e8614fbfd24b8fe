#!/bin/sh
# part_sizes.sh [--check] [FILE]: the size of each region of fogrt.h's implementation
# (`make part-sizes`; `make check-compile` runs it with --check).
#
# Regions: Part I (from the comment that opens its banner "PART I: THE PAPER" to the line
# before Part II's), Part II's shared set-up, its appendices A to I (each from the comment
# that opens its heading "   X. Title"), and what stands after both parts (the API around the
# method, then the checks of what a build left out). Lines: every line of the region; code:
# the non-blank lines left once the preprocessor has dropped the comments
# (gcc -fpreprocessed -dD -E -P, which expands nothing).
# --check: exit 1 unless Part I keeps its formatting rules: at most 2,600 lines, no line over
# 100 columns, one statement per line (a line with two semicolons outside comments, strings
# and a for loop's header holds two; the one that closes a struct, "} name;", ends no
# statement), no SIMD intrinsics or platform #if (OpenMP is reached through FOGRT__OMP,
# defined in the set-up), and at most 8 numbered seams. Each broken rule prints the lines
# that break it (their numbers in FILE).
check=0
if [ "$1" = --check ]; then check=1; shift; fi
f=${1:-fogrt.h}
CC=${GCC:-gcc}
[ -f "$f" ] || { echo "part_sizes.sh: $f not found" >&2; exit 2; }
command -v "$CC" >/dev/null 2>&1 || { echo "part_sizes.sh: needs $CC (for the code lines)" >&2; exit 2; }
TMP=$(mktemp -d) || exit 2
trap 'rm -rf "$TMP"' EXIT

# first line matching an extended regular expression (0: none)
at() { grep -nE "$1" "$f" | head -1 | cut -d: -f1 | grep . || echo 0; }
# the line of the comment opener ("/*") at or above line $1
opener() { awk -v n="$1" 'NR <= n && /^\/\*/ { o = NR } END { print o + 0 }' "$f"; }

p1=$(at 'PART I: THE PAPER') p2=$(at 'PART II: BEYOND THE PAPER') after=$(at 'AFTER BOTH PARTS')
checks=$(at '^   Checks of what lies beyond Part I$') end=$(at '^#endif /\* FOGRT_IMPLEMENTATION_INCLUDED \*/')
for v in "$p1" "$p2" "$after" "$checks" "$end"; do
    [ "$v" -gt 0 ] || { echo "part_sizes.sh: a banner of $f was not found" >&2; exit 2; }
done
starts="$(opener "$p1") Part_I $(opener "$p2") Part_II_shared"
for x in A B C D E F G H I; do
    l=$(at "^   $x\. [A-Z]")
    [ "$l" -gt "$p2" ] && [ "$l" -lt "$after" ] || { echo "part_sizes.sh: appendix $x's heading not found" >&2; exit 2; }
    starts="$starts $(opener "$l") $x"
done
starts="$starts $(opener "$after") After_both:_the_API $(opener "$checks") After_both:_the_checks $end END"

printf '%-24s %7s %7s\n' region lines code
set -- $starts
while [ "$#" -ge 4 ]; do
    from=$1 name=$2 to=$(($3 - 1))
    sed -n "${from},${to}p" "$f" > "$TMP/$name.c"
    lines=$(wc -l < "$TMP/$name.c")
    code=$("$CC" -fpreprocessed -dD -E -P "$TMP/$name.c" 2>/dev/null | grep -cv '^[[:space:]]*$')
    printf '%-24s %7d %7d\n' "$(echo "$name" | tr _ ' ')" "$lines" "$code"
    echo "$lines $code" > "$TMP/$name.size"
    shift 2
done

[ "$check" = 1 ] || exit 0
read -r lines code < "$TMP/Part_I.size"
first=$(opener "$p1")
bad=0
# at most 10 of the lines that break a rule, as "fogrt.h:LINE: text"
show() { head -10 | awk -v f="$f" -v o="$first" -F '\t' '{ printf "  %s:%d: %s\n", f, $1 + o - 1, $2 }'; }
[ "$lines" -le 2600 ] || { echo "Part I: $lines lines, over 2,600"; bad=1; }
long=$(awk 'length($0) > 100 { printf "%d\t%s\n", NR, $0 }' "$TMP/Part_I.c")
[ -z "$long" ] || { echo "Part I: $(echo "$long" | wc -l) lines over 100 columns:"; echo "$long" | show; bad=1; }
# Two statements on a line: its semicolons, once comments (also those spanning lines),
# string and character literals, for loops' headers and the "} name;" closing a struct
# are taken out.
twice=$(awk '{
    s = $0; out = ""; i = 1; n = length(s)
    while (i <= n) {
        c = substr(s, i, 1); c2 = substr(s, i, 2)
        if (incomment) { if (c2 == "*/") { incomment = 0; i += 2 } else i++; continue }
        if (c2 == "/*") { incomment = 1; i += 2; continue }
        if (c2 == "//") break
        if (c == "\"" || c == "\047") {
            q = c; i++
            while (i <= n && substr(s, i, 1) != q) { if (substr(s, i, 1) == "\\") i++; i++ }
            i++; out = out "S"; continue
        }
        out = out c; i++
    }
    while (match(out, /(^|[^A-Za-z0-9_])for[ \t]*\(/)) {
        j = RSTART + RLENGTH; depth = 1
        while (j <= length(out) && depth > 0) {
            ch = substr(out, j, 1)
            if (ch == "(") depth++
            else if (ch == ")") depth--
            j++
        }
        out = substr(out, 1, RSTART) "F" substr(out, j)
    }
    gsub(/}[ \t]*[A-Za-z_][A-Za-z0-9_]*[ \t]*;/, "}", out)
    if (gsub(/;/, ";", out) >= 2) printf "%d\t%s\n", NR, $0
}' "$TMP/Part_I.c")
[ -z "$twice" ] || { echo "Part I: $(echo "$twice" | wc -l) lines with two statements or more:"; echo "$twice" | show; bad=1; }
simd=$(grep -nE '_mm(256)?_|intrin\.h|__SSE|__AVX|__x86_64__|_M_X64|__aarch64__|_MSC_VER|__GNUC__|__clang__' "$TMP/Part_I.c" |
       sed 's/:/	/')
[ -z "$simd" ] || { echo "Part I has SIMD or platform code:"; echo "$simd" | show; bad=1; }
seams=$(grep -oE 'SEAM [0-9]+' "$TMP/Part_I.c" | sort -u | wc -l)
[ "$seams" -ge 1 ] && [ "$seams" -le 8 ] || { echo "Part I: $seams numbered seams (1 to 8 expected)"; bad=1; }
longest=$(awk 'length($0) > m { m = length($0) } END { print m + 0 }' "$TMP/Part_I.c")
[ "$bad" = 0 ] && echo "Part I within its limits: $lines lines (<= 2,600), the longest $longest columns (<= 100), one statement per line, $seams seams, no SIMD or platform #if"
exit "$bad"
