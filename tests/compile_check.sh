#!/bin/sh
# compile_check.sh - fogrt.h compiles warning-free (-Werror) in every supported configuration.
#
#   sh tests/compile_check.sh          (from the repository root; `make check-compile`)
#
# Checks, one line each ("ok", "FAIL" with the compiler output, or "skip"):
#   - C99 with gcc and with clang (clang only if installed), with and without -fopenmp:
#     the implementation in one file, the header alone in a second file, linked and run
#     (a tiny render of the default scene), and the header included twice after the define
#   - gcc with -Wdouble-promotion (STYLE.md section 8)
#   - C++ (g++ -std=c++11 -pedantic; clang++ too if installed): the implementation compiled
#     as C++ and linked with the C user file (checks extern "C")
#   - FOGRT_STATIC (every function static: must not warn about unused functions)
#   - all 16 combinations of FOGRT_NO_MEDIUM, FOGRT_NO_GLASS, FOGRT_NO_EXACT_FRESNEL and
#     FOGRT_NO_STDIO (compile only), with gcc, and the full strip as C++
#   - FOGRT_MINIMAL (Part I alone): gcc, linked and rendering the default scene; g++
#   - what each strip macro claims to remove is gone from the object file (nm): the public
#     functions of the feature are defined without the macro and absent with it
#   - FOGRT_MINIMAL: no function defined in Part II of fogrt.h is left in the object file
#     (nm, at -O0 with every static function kept), Part I's are
#   - Part I keeps its limits: at most 2,600 lines, none over 100 columns, one statement per
#     line, at most 8 seams, no SIMD or platform #if
#     (tools/part_sizes.sh --check)
# The C checks use -Wshadow -Wconversion -Wcast-qual on top of -Wall -Wextra -pedantic.
# Exit status 1 if any check failed.
#
# Compilers can be overridden: GCC=gcc-13 CLANG=clang-17 GXX=g++-13 sh tests/compile_check.sh

GCC=${GCC:-gcc}
CLANG=${CLANG:-clang}
GXX=${GXX:-g++}
CLANGXX=${CLANGXX:-clang++}

ROOT=$(pwd)
if [ ! -f "$ROOT/fogrt.h" ]; then
    echo "compile_check.sh: run from the repository root (fogrt.h not found)" >&2
    exit 2
fi

TMP=$(mktemp -d) || exit 2
trap 'rm -rf "$TMP"' EXIT
trap 'exit 130' INT TERM

CWARN="-std=c99 -Wall -Wextra -pedantic -Wshadow -Wconversion -Wcast-qual -Werror"
XXWARN="-std=c++11 -Wall -Wextra -pedantic -Werror"

passed=0
failed=0
skipped=0

# run DESCRIPTION COMMAND...: run a command, print one line, keep the count.
run() {
    desc=$1
    shift
    if "$@" >"$TMP/out.txt" 2>&1; then
        echo "ok    $desc"
        passed=$((passed + 1))
    else
        echo "FAIL  $desc"
        echo "      \$ $*"
        sed 's/^/      | /' "$TMP/out.txt" | head -40
        failed=$((failed + 1))
    fi
}

skip() {
    echo "skip  $1"
    skipped=$((skipped + 1))
}

have() { command -v "$1" >/dev/null 2>&1; }

# has_openmp COMPILER [LANGUAGE]: can the compiler build an OpenMP program (omp.h and the
# runtime present)? clang needs the libomp development package for this.
has_openmp() {
    printf '#include <omp.h>\nint main(void) { return omp_get_max_threads() > 0 ? 0 : 1; }\n' >"$TMP/omp_probe.c"
    $1 -x "${2:-c}" -fopenmp -o "$TMP/omp_probe" "$TMP/omp_probe.c" >/dev/null 2>&1
}

# ---- the test sources ------------------------------------------------------------------
# impl.c: the implementation, included twice (the second include must be a no-op).
cat >"$TMP/impl.c" <<'EOF'
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#include "fogrt.h"
EOF
cp "$TMP/impl.c" "$TMP/impl.cc"

# user.c: the header alone, as a user sees it; renders a few pixels of the default scene.
cat >"$TMP/user.c" <<'EOF'
#include "fogrt.h"
#include <stdio.h>
#include <string.h>

int main(void)
{
    fogrt_scene *scene = NULL;
    fogrt_image img;
    fogrt_render_desc rd = fogrt_render_defaults();
    fogrt_result r;
    rd.width = 8;
    rd.height = 6;
    if (fogrt_scene_create(NULL, &scene) != FOGRT_RESULT_OK) return 1;
    r = fogrt_scene_add_default(scene);
    if (r == FOGRT_RESULT_OK) r = fogrt_scene_build(scene, NULL);
    if (r == FOGRT_RESULT_OK) r = fogrt_image_alloc(&img, 8, 6, NULL);
    if (r == FOGRT_RESULT_OK) {
        r = fogrt_render(scene, &rd, &img, 1, NULL);
        fogrt_image_free(&img);
    }
    fogrt_scene_destroy(scene);
    if (r != FOGRT_RESULT_OK) {
        printf("render failed: %s\n", fogrt_result_string(r));
        return 1;
    }
    return 0;
}
EOF

# static.c: everything static in one translation unit, most functions never called.
cat >"$TMP/static.c" <<'EOF'
#define FOGRT_STATIC
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
int main(void)
{
    fogrt_scene *scene = NULL;
    if (fogrt_scene_create(NULL, &scene) != FOGRT_RESULT_OK) return 1;
    fogrt_scene_destroy(scene);
    return 0;
}
EOF

# c_build COMPILER OMPFLAG LABEL: compile impl + user, link, run.
c_build() {
    cc=$1 omp=$2 label=$3
    out="$TMP/prog_$(echo "$label" | tr -c 'A-Za-z0-9' '_')"
    run "$label: implementation file" $cc $CWARN $omp -I"$ROOT" -c "$TMP/impl.c" -o "$out.impl.o"
    run "$label: header-only user file" $cc $CWARN $omp -I"$ROOT" -c "$TMP/user.c" -o "$out.user.o"
    if [ -f "$out.impl.o" ] && [ -f "$out.user.o" ]; then
        run "$label: link and render the default scene" \
            sh -c "$cc $omp -o '$out' '$out.impl.o' '$out.user.o' -lm && '$out'"
    fi
}

# ---- C: gcc and clang, with and without OpenMP ------------------------------------------
if have "$GCC"; then
    c_build "$GCC" -fopenmp "$GCC -std=c99 -fopenmp"
    c_build "$GCC" "" "$GCC -std=c99 (no OpenMP)"
    run "$GCC -Wdouble-promotion (STYLE.md section 8)" \
        $GCC $CWARN -Wdouble-promotion -fopenmp -I"$ROOT" -c "$TMP/impl.c" -o "$TMP/dp.o"
    run "$GCC FOGRT_STATIC: all functions static, no unused-function warnings" \
        sh -c "$GCC $CWARN -I'$ROOT' -o '$TMP/static' '$TMP/static.c' -lm && '$TMP/static'"
else
    skip "$GCC not installed"
fi

if have "$CLANG"; then
    if has_openmp "$CLANG"; then
        c_build "$CLANG" -fopenmp "$CLANG -std=c99 -fopenmp"
    else
        skip "$CLANG -fopenmp: no OpenMP support (omp.h or libomp missing; Debian: libomp-dev)"
    fi
    c_build "$CLANG" "" "$CLANG -std=c99 (no OpenMP)"
else
    skip "clang: not installed (install the clang package to run the clang checks)"
fi

# ---- C++ -----------------------------------------------------------------------------------
# cxx_build COMPILER OMPFLAG LABEL: the implementation as C++, linked with the C user file.
cxx_build() {
    cxx=$1 omp=$2 label=$3
    rm -f "$TMP/impl_cxx.o"
    run "$label: implementation as C++" $cxx $XXWARN $omp -I"$ROOT" -c "$TMP/impl.cc" -o "$TMP/impl_cxx.o"
    run "$label: header-only user file as C++" $cxx $XXWARN -I"$ROOT" -x c++ -c "$TMP/user.c" -o "$TMP/user_cxx.o"
    if have "$GCC" && [ -f "$TMP/impl_cxx.o" ]; then
        run "$label: C++ implementation linked with a C user (extern \"C\")" \
            sh -c "$GCC $CWARN -I'$ROOT' -c '$TMP/user.c' -o '$TMP/user_c.o' && $cxx $omp -o '$TMP/mixed' '$TMP/impl_cxx.o' '$TMP/user_c.o' -lm && '$TMP/mixed'"
    fi
}

if have "$GXX"; then
    cxx_build "$GXX" -fopenmp "$GXX -std=c++11 -fopenmp"
else
    skip "$GXX not installed"
fi
if have "$CLANGXX"; then
    if has_openmp "$CLANGXX" c++; then
        cxx_build "$CLANGXX" -fopenmp "$CLANGXX -std=c++11 -fopenmp"
    else
        cxx_build "$CLANGXX" "" "$CLANGXX -std=c++11 (no OpenMP)"
    fi
else
    skip "clang++: not installed"
fi

# ---- the strip macros: all 16 combinations --------------------------------------------------
if have "$GCC"; then
    for medium in 0 1; do
        for glass in 0 1; do
            for exact in 0 1; do
                for stdio in 0 1; do
                    defs=""
                    [ $medium = 1 ] && defs="$defs -DFOGRT_NO_MEDIUM"
                    [ $glass = 1 ] && defs="$defs -DFOGRT_NO_GLASS"
                    [ $exact = 1 ] && defs="$defs -DFOGRT_NO_EXACT_FRESNEL"
                    [ $stdio = 1 ] && defs="$defs -DFOGRT_NO_STDIO"
                    run "$GCC strip:${defs:- (none)}" \
                        $GCC $CWARN -fopenmp $defs -I"$ROOT" -c "$TMP/impl.c" -o "$TMP/strip.o"
                done
            done
        done
    done
fi
if have "$GCC"; then
    run "$GCC FOGRT_MINIMAL: Part I alone, linked and rendering the default scene" \
        sh -c "$GCC $CWARN -fopenmp -DFOGRT_MINIMAL -I'$ROOT' -c '$TMP/impl.c' -o '$TMP/min_impl.o' && $GCC $CWARN -DFOGRT_MINIMAL -I'$ROOT' -c '$TMP/user.c' -o '$TMP/min_user.o' && $GCC -fopenmp -o '$TMP/min_prog' '$TMP/min_impl.o' '$TMP/min_user.o' -lm && '$TMP/min_prog'"
fi
if have "$GXX"; then
    run "$GXX FOGRT_MINIMAL" $GXX $XXWARN -DFOGRT_MINIMAL -I"$ROOT" -c "$TMP/impl.cc" -o "$TMP/min_cxx.o"
    run "$GXX FOGRT_NO_MEDIA" $GXX $XXWARN -DFOGRT_NO_MEDIA -I"$ROOT" -c "$TMP/impl.cc" -o "$TMP/nomedia_cxx.o"
fi
if have "$GCC"; then
    for defs in -DFOGRT_NO_WIDE_BVH -DFOGRT_NO_LAMPS_IN_FOG -DFOGRT_NO_ESTIMATION \
                "-DFOGRT_NO_WIDE_BVH -DFOGRT_NO_LAMPS_IN_FOG -DFOGRT_NO_ESTIMATION" \
                "-DFOGRT_NO_LAMPS_IN_FOG -DFOGRT_NO_MEDIUM" "-DFOGRT_NO_ESTIMATION -DFOGRT_TRACE" \
                -DFOGRT_NO_MEDIA "-DFOGRT_NO_MEDIA -DFOGRT_NO_LAMPS_IN_FOG -DFOGRT_TRACE" -DFOGRT_NO_SHAPES \
                -DFOGRT_NO_MICROFACET "-DFOGRT_NO_MICROFACET -DFOGRT_TRACE" \
                -DFOGRT_WBVH_NO_AVX2 -DFOGRT_WBVH_NO_SIMD; do
        run "$GCC appendix removed: $defs" $GCC $CWARN -fopenmp $defs -I"$ROOT" -c "$TMP/impl.c" -o "$TMP/app.o"
    done
fi
if have "$GXX"; then
    run "$GXX strip: all four" $GXX $XXWARN -DFOGRT_NO_MEDIUM -DFOGRT_NO_GLASS -DFOGRT_NO_EXACT_FRESNEL \
        -DFOGRT_NO_STDIO -I"$ROOT" -c "$TMP/impl.cc" -o "$TMP/strip_cxx.o"
fi


# ---- fogrt_load.h: the same warnings, as C, as C++ and under FOGRT_STATIC -------------------
cat >"$TMP/load.c" <<'EOF2'
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#define FOGRT_LOAD_IMPLEMENTATION
#include "fogrt_load.h"
int main(void) { return 0; }
EOF2
cat >"$TMP/load_static.c" <<'EOF2'
#define FOGRT_STATIC
#include "load.c"
EOF2
cp "$TMP/load.c" "$TMP/load.cc"
if have "$GCC"; then
    run "$GCC fogrt_load.h (-Wconversion -Wcast-qual)" $GCC $CWARN -I"$ROOT" -c "$TMP/load.c" -o "$TMP/load.o"
    run "$GCC fogrt_load.h FOGRT_STATIC" $GCC $CWARN -I"$ROOT" -I"$TMP" -c "$TMP/load_static.c" -o "$TMP/load_s.o"
    run "$GCC fogrt_load.h with FOGRT_NO_GLASS" $GCC $CWARN -DFOGRT_NO_GLASS -I"$ROOT" -c "$TMP/load.c" -o "$TMP/load_ng.o"
fi
if have "$CLANG"; then
    run "$CLANG fogrt_load.h (-Wconversion -Wcast-qual)" $CLANG $CWARN -I"$ROOT" -c "$TMP/load.c" -o "$TMP/load_c.o"
fi
if have "$GXX"; then
    run "$GXX fogrt_load.h as C++" $GXX $XXWARN -I"$ROOT" -c "$TMP/load.cc" -o "$TMP/load_cxx.o"
fi

# ---- the strip macros really strip (nm) -----------------------------------------------------
# gone_nm FLAGS KINDS MACRO SYMBOL...: each SYMBOL is in the object built with FLAGS (as one
# of the nm KINDS: T defined, t static, U called) and absent from the one built with MACRO too.
# The object without the macro is built once per FLAGS, for all the checks that use them.
gone_nm() {
    flags=$1 kinds=$2 macro=$3
    shift 3
    normal="$TMP/nm_normal_$(printf '%s' "$flags" | tr -c 'A-Za-z0-9' '_').o"
    [ -f "$normal" ] || $GCC $flags -I"$ROOT" -c "$TMP/impl.c" -o "$normal" || return 1
    $GCC $flags -D"$macro" -I"$ROOT" -c "$TMP/impl.c" -o "$TMP/nm_stripped.o" || return 1
    for sym in "$@"; do
        nm "$normal" | grep -q " [$kinds] $sym\$" || { echo "$sym missing from the normal build"; return 1; }
        if nm "$TMP/nm_stripped.o" | grep -q " $sym\$"; then echo "$sym still in the $macro build"; return 1; fi
    done
}
# strip_nm MACRO SYMBOL...: the public functions (and fopen) at -O2.
strip_nm() { gone_nm "-std=c99 -O2" TU "$@"; }
if have "$GCC" && have nm; then
    run "nm: FOGRT_NO_MEDIUM removes free flight, transmittance, HG and equiangular" strip_nm FOGRT_NO_MEDIUM \
        fogrt_sample_exponential fogrt_exponential_pdf fogrt_exponential_cdf fogrt_invert_exponential fogrt_transmittance \
        fogrt_hg_phase fogrt_sample_hg_mu fogrt_sample_hg fogrt_hg_pdf fogrt_sample_equiangular fogrt_equiangular_pdf
    run "nm: FOGRT_NO_GLASS removes Fresnel and refraction" strip_nm FOGRT_NO_GLASS \
        fogrt_fresnel_schlick fogrt_fresnel_dielectric fogrt_refract
    run "nm: FOGRT_NO_EXACT_FRESNEL removes the exact Fresnel" strip_nm FOGRT_NO_EXACT_FRESNEL fogrt_fresnel_dielectric
    run "nm: FOGRT_NO_STDIO removes the file writers" strip_nm FOGRT_NO_STDIO fogrt_write_pfm fogrt_write_ppm fopen
else
    skip "nm checks: gcc or nm not installed"
fi

# ---- each FOGRT_NO_<appendix> leaves its appendix out (nm, every function visible) ----------
# appendix_nm MACRO SYMBOL...: private functions too (nothing inlined, every static kept).
appendix_nm() { gone_nm "-std=c99 -O0 -fno-inline -fkeep-static-functions" tT "$@"; }
if have "$GCC" && have nm; then
    run "nm: FOGRT_NO_WIDE_BVH removes appendix A" appendix_nm FOGRT_NO_WIDE_BVH \
        fogrt__wbvh_build fogrt__wbvh_pack_leaf fogrt__wide_leaf_keep fogrt__alloc_big
    run "nm: FOGRT_NO_LAMPS_IN_FOG removes appendix B" appendix_nm FOGRT_NO_LAMPS_IN_FOG \
        fogrt_sample_equiangular fogrt_sample_glow fogrt__hg_table_build fogrt__find_footprints fogrt__scatter_glow
    run "nm: FOGRT_NO_ESTIMATION removes appendix C" appendix_nm FOGRT_NO_ESTIMATION \
        fogrt_image_sample_rates fogrt_scene_set_environment_map fogrt_fresnel_dielectric fogrt__roulette_pilot \
        fogrt__stratified_position fogrt__build_light_pick
    run "nm: FOGRT_NO_MEDIA removes appendix G" appendix_nm FOGRT_NO_MEDIA \
        fogrt_sample_hg2 fogrt_sample_rayleigh fogrt_sample_phase fogrt__media_check fogrt__media_emission \
        fogrt__media_next_event fogrt__chroma_next_event fogrt__chroma_mix fogrt__chroma_shadow
    run "nm: FOGRT_NO_SHAPES removes appendix H" appendix_nm FOGRT_NO_SHAPES \
        fogrt_scene_set_interior fogrt_scene_set_shape_material fogrt__h_next_event fogrt__shapes_build fogrt__find_boundaries fogrt__h_shadow
    run "nm: FOGRT_NO_MICROFACET removes appendix I" appendix_nm FOGRT_NO_MICROFACET \
        fogrt__mf_sample fogrt__mf_eval fogrt__mf_pdf fogrt__mf_check fogrt__mf_fresnel1 fogrt__mf_lambda
else
    skip "appendix nm checks: gcc or nm not installed"
fi

# ---- FOGRT_MINIMAL leaves Part II out whole (nm) --------------------------------------------
# The names: every function defined between Part II's banner and its closing #endif. Both
# objects are built at -O0 -fno-inline with -fkeep-static-functions (and FOGRT_TRACE, for
# appendix D), so that every private function that exists shows up, called or not. The full
# object must hold each name (the extraction and the flags work; the always-inline
# FOGRT__HOT helpers excepted: they never stand alone, and their callers are checked), the
# minimal one none of them and no symbol of Part II's families, and still Part I's.
part2_names() {
    awk '/PART II: BEYOND THE PAPER/ { p = 1 } /^#endif \/\* FOGRT_MINIMAL \*\// { p = 0 }
         p && /^FOGRT__(PRIVATE|PUBLIC|HOT)/ { print }' "$ROOT/fogrt.h" | grep -v "^FOGRT__$1" |
        sed -E 's/\(.*//; s/.*[ *]([A-Za-z_0-9]+)$/\1/' | sort -u
}
minimal_nm() {
    flags="-std=c99 -O0 -fno-inline -fkeep-static-functions -DFOGRT_TRACE -I$ROOT"
    $GCC $flags -c "$TMP/impl.c" -o "$TMP/nm_full.o" || return 1
    $GCC $flags -DFOGRT_MINIMAL -c "$TMP/impl.c" -o "$TMP/nm_minimal.o" || return 1
    nm "$TMP/nm_full.o" | awk '{ print $NF }' | sort -u >"$TMP/full.syms"
    nm "$TMP/nm_minimal.o" | awk '{ print $NF }' | sort -u >"$TMP/minimal.syms"
    part2_names NONE >"$TMP/part2.names"
    part2_names HOT >"$TMP/part2_standalone.names"
    n=$(wc -l <"$TMP/part2.names")
    [ "$n" -ge 50 ] || { echo "only $n Part II functions found after the banner in fogrt.h"; return 1; }
    missing=$(comm -23 "$TMP/part2_standalone.names" "$TMP/full.syms")
    [ -z "$missing" ] || { echo "not in the full object (the check cannot see them):" $missing; return 1; }
    left=$(comm -12 "$TMP/part2.names" "$TMP/minimal.syms")
    [ -z "$left" ] || { echo "Part II functions left under FOGRT_MINIMAL:" $left; return 1; }
    left=$(grep -E '^fogrt__(wbvh|wide|hg_table|hgt_|x_|glow|footprint|equiangular|pilot|sobol|env_pdf|sample_env|rate_|sat_|trace_)|^fogrt_(image_sample_rates|trace_path|trace_describe|sample_equiangular|equiangular_pdf|sample_glow|glow_pdf|fresnel_dielectric|scene_get_memory|scene_get_bvh|bvh_sah_cost|scene_intersect_brute)$' "$TMP/minimal.syms")
    [ -z "$left" ] || { echo "Part II symbols left under FOGRT_MINIMAL:" $left; return 1; }
    for sym in fogrt__algorithm1 fogrt__radiance fogrt__build_tree fogrt_render fogrt_scene_build fogrt_render_paper_defaults; do
        grep -qx "$sym" "$TMP/minimal.syms" || { echo "$sym (Part I) missing from the FOGRT_MINIMAL object"; return 1; }
    done
    echo "$n Part II functions, none left under FOGRT_MINIMAL"
}
if have "$GCC" && have nm; then
    run "nm: FOGRT_MINIMAL leaves out every function of Part II and keeps Part I" minimal_nm
else
    skip "nm FOGRT_MINIMAL check: gcc or nm not installed"
fi

# ---- Part I's limits (tools/part_sizes.sh, `make part-sizes`) -----------------------------
if have "$GCC"; then
    run "Part I within its limits (lines, 100 columns, one statement a line, seams, no SIMD or platform #if)" \
        env GCC="$GCC" sh "$ROOT/tools/part_sizes.sh" --check "$ROOT/fogrt.h"
else
    skip "Part I's limits: gcc not installed"
fi

echo "compile: $passed passed, $failed failed, $skipped skipped"
[ "$failed" -eq 0 ]
