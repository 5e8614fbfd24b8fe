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
# --check: exit 1 unless Part I keeps the issue's limits: at most 2,600 lines and 1,800 code
# lines, no SIMD intrinsics or platform #if (OpenMP is reached through FOGRT__OMP, defined in
# the set-up), and at most 8 numbered seams.
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
bad=0
[ "$lines" -le 2600 ] || { echo "Part I: $lines lines, over 2,600"; bad=1; }
[ "$code" -le 1800 ] || { echo "Part I: $code code lines, over 1,800"; bad=1; }
simd=$(grep -nE '_mm(256)?_|intrin\.h|__SSE|__AVX|__x86_64__|_M_X64|__aarch64__|_MSC_VER|__GNUC__|__clang__' "$TMP/Part_I.c")
[ -z "$simd" ] || { echo "Part I has SIMD or platform code:"; echo "$simd"; bad=1; }
seams=$(grep -oE 'SEAM [0-9]+' "$TMP/Part_I.c" | sort -u | wc -l)
[ "$seams" -ge 1 ] && [ "$seams" -le 8 ] || { echo "Part I: $seams numbered seams (1 to 8 expected)"; bad=1; }
[ "$bad" = 0 ] && echo "Part I within its limits: $lines lines (<= 2,600), $code code lines (<= 1,800), $seams seams, no SIMD or platform #if"
exit "$bad"
