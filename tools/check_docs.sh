#!/bin/sh
# check_docs.sh - what README.md and docs/ say is checked against the tree (make check-docs,
# part of make test). Prints one line per claim that no longer holds and "check-docs: N passed,
# M failed"; exit status 1 if any failed.
#
#   1. every C code block of README.md, copied as a user copies it (into an empty directory
#      with fogrt.h beside it, stb from the system), compiles warning-free with the README's
#      command plus -std=c99 -Wall -Wextra -pedantic -Werror; a block with main() is linked and
#      run, and the files it says it writes exist. A block without main() is compiled alone.
#   2. README's complete program is examples/minimal.c (after the file's opening comment).
#   3. every field of the descriptions a user fills (fogrt_*_desc, fogrt_allocator,
#      fogrt_logger) is named in README.md's section on that struct ("#### `fogrt_X_desc`").
#   4. every fogrt_ function, type and FOGRT_ macro that README.md and docs/*.md name in
#      backquotes exists in the headers or the programs around them; every repository file
#      they name exists.
#   5. no prose quotes line numbers ("fogrt.h:123", "test_x.c:45", "line 123 of fogrt.h"), which
#      move with every edit, nor spells out how many cross-check scenes, tutorial programs or test
#      programs there are (counts that change as they are added; say "every" instead).
#   6. docs/validation.md's table of scenes lists exactly the cross-check's scenes.
#
#   sh tools/check_docs.sh [CC] [BUILD_DIR]
cc=${1:-cc}
out=${2:-build}/check-docs
cd "$(dirname "$0")/.." || exit 2
rm -rf "$out" && mkdir -p "$out" || exit 2
checks=0
failed=0
# ok starts a check (a code block, a struct, a document's names...); fail prints one line per
# claim that does not hold and counts the check it belongs to as failed once.
last_failed=-1
fail() { echo "check-docs: $*"; [ "$last_failed" = "$checks" ] || { failed=$((failed + 1)); last_failed=$checks; }; }
ok() { checks=$((checks + 1)); }
# OpenMP as the README's command has it, when this compiler has it
omp=-fopenmp
echo 'int main(void){return 0;}' >"$out/omp.c"
$cc -fopenmp -o "$out/omp" "$out/omp.c" 2>/dev/null || omp=

# ---- 1, 2: README's C blocks ----
awk -v dir="$out" '
    /^```c[ ]*$/ { n++; f = sprintf("%s/block%d.c", dir, n); inside = 1; printf "" >f; next }
    /^```/ && inside { inside = 0; close(f); next }
    inside { print >f }
' README.md
blocks=$(ls "$out"/block*.c 2>/dev/null)
[ -n "$blocks" ] || fail "README.md has no C code block"
ok
for b in $blocks; do
    name=$(basename "$b" .c)
    d="$out/$name"
    mkdir -p "$d" && cp fogrt.h "$d/" && cp "$b" "$d/prog.c"
    ok
    if grep -q '^int main' "$b"; then
        if ! (cd "$d" && $cc -std=c99 -Wall -Wextra -pedantic -Werror -O2 $omp prog.c -o prog -lm) >"$d/cc.log" 2>&1; then
            fail "README.md's C block $name (saved as $b) does not compile as copied: $(head -3 "$d/cc.log")"
            continue
        fi
        ok
        if ! (cd "$d" && OMP_WAIT_POLICY=passive ./prog) >"$d/run.log" 2>&1; then
            fail "README.md's C block $name exits non-zero: $(tail -2 "$d/run.log")"
            continue
        fi
        # the files the program says it writes ("out.png" in a string) are there, non-empty
        for f in $(grep -o '"[A-Za-z0-9_]*\.\(png\|pfm\|ppm\)"' "$b" | tr -d '"' | sort -u); do
            [ -s "$d/$f" ] || fail "README.md's C block $name writes no $f"
        done
    else
        (cd "$d" && $cc -std=c99 -Wall -Wextra -pedantic -Werror -O0 -c prog.c -o prog.o) >"$d/cc.log" 2>&1 ||
            fail "README.md's C block $name (saved as $b) does not compile as copied: $(head -3 "$d/cc.log")"
    fi
done
ok
full=$(grep -l '^int main' $blocks 2>/dev/null | head -n 1)
if [ -z "$full" ]; then
    fail "README.md has no complete program (a C block with main)"
else
    awk 'started || /^#/ { started = 1; print }' examples/minimal.c >"$out/minimal_body.c"
    cmp -s "$full" "$out/minimal_body.c" ||
        fail "README.md's complete program differs from examples/minimal.c: $(diff "$full" "$out/minimal_body.c" | head -4 | tr '\n' ' ')"
fi

# ---- 3: the fields of every description a user fills ----
fields() {   # the member names of struct $1 in fogrt.h
    awk -v s="$1" '
        $0 ~ "^typedef struct " s " [{]" { inside = 1; next }
        inside && $0 ~ "^} " s ";" { exit }
        inside {
            if (incomment) { if ($0 !~ /\*\//) next; sub(/.*\*\//, ""); incomment = 0 }
            if ($0 ~ /\/\*/ && $0 !~ /\*\//) incomment = 1
            sub(/\/\*.*/, ""); line = line $0
            if (line !~ /;/) next
            decl = line; line = ""
            if (decl ~ /\(\*[a-z_0-9]+\)/) { match(decl, /\(\*[a-z_0-9]+\)/); print substr(decl, RSTART + 2, RLENGTH - 3); next }
            sub(/;.*/, "", decl)
            n = split(decl, part, ",")
            for (i = 1; i <= n; i++) {
                p = part[i]; sub(/\[.*/, "", p); gsub(/[*]/, " ", p)
                m = split(p, w, " "); if (m > 0) print w[m]
            }
        }' fogrt.h
}
section() {  # README.md's section under the heading "#### `$1`", to the next heading
    awk -v h="#### \`$1\`" 'index($0, h) == 1 { f = 1; next } f && /^#/ { exit } f' README.md
}
# struct:the README section that documents it (the allocator and logger are the scene desc's)
for pair in fogrt_scene_desc:fogrt_scene_desc fogrt_allocator:fogrt_scene_desc fogrt_logger:fogrt_scene_desc \
            fogrt_material_desc:fogrt_material_desc fogrt_mesh_desc:fogrt_mesh_desc fogrt_light_desc:fogrt_light_desc \
            fogrt_camera_desc:fogrt_camera_desc fogrt_medium_desc:fogrt_medium_desc fogrt_build_desc:fogrt_build_desc \
            fogrt_render_desc:fogrt_render_desc; do
    s=${pair%%:*} sec=${pair#*:}
    list=$(fields "$s")
    ok
    [ -n "$list" ] || { fail "fogrt.h has no struct $s (tools/check_docs.sh lists it)"; continue; }
    section "$sec" >"$out/section.md"
    ok
    [ -s "$out/section.md" ] || { fail "README.md has no section \"#### \`$sec\`\" documenting $s's fields"; continue; }
    for f in $list; do
        grep -q "\`$f\`\|\`$f(" "$out/section.md" || fail "README.md's section on $sec does not name $s's field \`$f\`"
    done
done

# ---- 4: names and files the docs cite ----
docs="README.md $(ls docs/*.md)"
known="$out/known.txt"
# the headers' names, and those of the programs around them (a test macro, `fogrt_cli`)
{ find examples tests bench tools -type f \( -name '*.c' -o -name '*.h' -o -name '*.sh' -o -name '*.py' \) -exec cat {} +
  cat fogrt.h fogrt_load.h Makefile mk/*.mk
  find examples tests bench tools -type f | sed 's|.*/||; s/\.[a-z]*$//'; } | grep -o '\<\(fogrt\|FOGRT\)_[A-Za-z0-9_]*' | sort -u >"$known"
for doc in $docs; do
    ok
    for name in $(grep -o '`[^`]*`' "$doc" | grep -o '\<\(fogrt\|FOGRT\)_[A-Za-z0-9_]*' | sort -u); do
        case $name in *_|*_X) continue ;; esac     # a prefix or a pattern (`fogrt_scene_get_X`), not a name
        grep -qx "$name" "$known" || fail "$doc names \`$name\`, which neither the headers nor the programs in the tree have"
    done
    # repository paths in backquotes or links: examples/..., tests/..., docs/..., tools/..., bench/..., mk/...
    ok
    for path in $(grep -o '[`(]\(examples\|tests\|docs\|tools\|bench\|mk\|\.ci\)/[A-Za-z0-9_./-]*[`)]' "$doc" | tr -d '`()' | sort -u); do
        case $path in *'*'*|*/) continue ;; esac
        [ -e "$path" ] || [ -e "${path%/}" ] || fail "$doc names $path, which is not in the tree"
    done
done

# ---- 5: numbers that move ----
for doc in $docs; do
    ok
    hit=$(grep -n '\(fogrt\(_load\)\?\.h\|\.c\|\.sh\):[0-9]\|\<lines\? [0-9][0-9]*\(-[0-9]*\)\? of `\?fogrt' "$doc" | head -3)
    [ -z "$hit" ] || fail "$doc quotes line numbers: $hit"
    ok
    hit=$(grep -in '\(^\|[ (]\)\(ten\|eleven\|twelve\|thirteen\|fourteen\|fifteen\|sixteen\|seventeen\|eighteen\|nineteen\|twenty\|[0-9][0-9]\) \(cross-check \)\?\(scenes\|numbered programs\|tutorial programs\|test programs\)\>' "$doc" | head -3)
    [ -z "$hit" ] || fail "$doc counts scenes or programs in prose (say \"every\"): $hit"
done

# ---- 5b: Part I's limits as README.md quotes them are those tools/part_sizes.sh enforces ----
ok
quoted=$(tr '\n' ' ' <README.md | grep -o 'holds Part I to [0-9,]* lines, [0-9,]* code lines' | tr -d ',' | sed 's/[^0-9 ]//g' | tr -s ' ')
enforced=$(sed -n 's/.*"\$lines" -le \([0-9]*\).*/\1/p; s/.*"\$code" -le \([0-9]*\).*/\1/p' tools/part_sizes.sh | tr '\n' ' ')
[ -z "$quoted" ] || [ "$(echo $quoted)" = "$(echo $enforced)" ] ||
    fail "README.md quotes Part I's limits as$quoted; tools/part_sizes.sh enforces $enforced"

# ---- 6: docs/validation.md's table of scenes is the cross-check's list (tests/crosscheck/scenes.py) ----
ok
{ grep -o 'box_scene("[^"]*"' tests/crosscheck/scenes.py | sed 's/.*("//; s/"$//'
  grep -o '^        ("[^"]*",' tests/crosscheck/scenes.py | sed 's/^ *("//; s/",$//'; } | sort >"$out/scenes.txt"
awk '/^## The scenes/ { f = 1; next } f && /^## / { exit } f' docs/validation.md |
  sed -n 's/^| \([a-z][a-z_0-9+.-]*\) |.*/\1/p' | grep -vx scene | sort >"$out/scenes_doc.txt"
[ -s "$out/scenes.txt" ] || fail "no scene names found in tests/crosscheck/scenes.py (tools/check_docs.sh reads box_scene(\"name\", ...))"
cmp -s "$out/scenes.txt" "$out/scenes_doc.txt" ||
    fail "docs/validation.md's table of scenes is not the cross-check's list: $(diff "$out/scenes.txt" "$out/scenes_doc.txt" | grep '^[<>]' | tr '\n' ' ')"

echo "check-docs: $((checks - failed)) passed, $failed failed"
[ "$failed" -eq 0 ]
