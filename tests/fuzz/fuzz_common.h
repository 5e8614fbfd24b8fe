/* fuzz_common.h - the body shared by the libFuzzer targets fuzz_dae.c, fuzz_obj.c and
   fuzz_ply.c: each passes its parser's fogrt_load_*_memory to fuzz_load_one.

   Any input must load or fail with one message line, without crashing, leaking (the loader's
   allocator counts its blocks) or changing the scene; max_triangles is 2^20 so that a small
   input cannot ask for gigabytes. Unless -DFUZZ_NO_BUILD, a successful load is also built
   (fogrt_scene_build), so the BVH build is fuzzed with whatever the parser accepts (this
   found the NaN binning of coordinates near FLT_MAX, now refused by fogrt.h). */
#ifndef FOGRT_FUZZ_COMMON_H
#define FOGRT_FUZZ_COMMON_H

#include <stdint.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#define FOGRT_LOAD_IMPLEMENTATION
#include "fogrt_load.h"

/* The signature shared by fogrt_load_dae_memory, fogrt_load_obj_memory and
   fogrt_load_ply_memory. */
typedef fogrt_result (*fuzz_loader)(fogrt_scene *scene, const void *data, size_t size, const char *name,
                                    const fogrt_load_options *options, fogrt_load_report *report);

/* The loader's allocations, counted: every block must be freed by the time a load returns. */
static long fuzz_live_blocks;
static void *fuzz_alloc(size_t n, void *user) { (void)user; fuzz_live_blocks++; return malloc(n); }
static void fuzz_free(void *p, void *user) { (void)user; if (p) fuzz_live_blocks--; free(p); }
/* A logger that hears nothing, so that the loader keeps (and frees) its warnings too. */
static void fuzz_log(fogrt_log_level level, const char *message, void *user) { (void)level; (void)message; (void)user; }

/* One fuzz input through `load` (name: the file name its messages use). Traps on a broken
   promise; returns 0, as libFuzzer wants. */
static int fuzz_load_one(const uint8_t *data, size_t size, fuzz_loader load, const char *name)
{
    fogrt_scene *scene = NULL;
    fogrt_load_report rep;
    fogrt_load_options opt;
    fogrt_scene_info before, after;
    fogrt_result r;
    if (fogrt_scene_create(NULL, &scene) != FOGRT_RESULT_OK) return 0;
    memset(&opt, 0, sizeof opt);
    opt.allocator.alloc_fn = fuzz_alloc; opt.allocator.free_fn = fuzz_free;
    opt.logger.func = fuzz_log;
    opt.max_triangles = 1u << 20;          /* a 64 KB input may instance a mesh many times */
    fogrt_scene_get_info(scene, &before);
    r = load(scene, data, size, name, &opt, &rep);
    fogrt_scene_get_info(scene, &after);
    if (fuzz_live_blocks != 0) __builtin_trap();
    if (r != FOGRT_RESULT_OK) {
        /* a refusal says why in one line, and adds nothing */
        if (rep.message[0] == 0 || rep.line < 0 || strchr(rep.message, '\n')) __builtin_trap();
        if (after.triangle_count != before.triangle_count || after.material_count != before.material_count ||
            after.sphere_count != before.sphere_count || after.light_count != before.light_count) __builtin_trap();
    }
#ifndef FUZZ_NO_BUILD
    if (r == FOGRT_RESULT_OK) {
        /* a loaded scene must build (or be empty) */
        r = fogrt_scene_build(scene, NULL);
        if (r != FOGRT_RESULT_OK && r != FOGRT_RESULT_EMPTY_SCENE && r != FOGRT_RESULT_TOO_LARGE) __builtin_trap();
    }
#endif
    fogrt_scene_destroy(scene);
    return 0;
}

#endif /* FOGRT_FUZZ_COMMON_H */
