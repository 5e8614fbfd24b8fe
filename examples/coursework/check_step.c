/* check_step.c - judges one coursework step (docs/coursework.md).

   Built by `make check-step STEP=N [SRC=their.c] [SEED=K]` with -DCW_STEP=N and linked with
   the student's file, which defines that step's functions (coursework.h). Prints one line per
   check and writes the pictures into the directory given as the first argument (default
   build/coursework). A second argument N > 0 redraws every sampled check with another seed
   (a third, any word, turns the pictures off): the verdicts the kit gives use seed 0. The
   environment variable CW_SOURCE names the file judged (make check-step sets it), so that
   the verdict can say which file to edit.
   Exit status: 0 when every check passed, 1 otherwise.                                      */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#include "check.h"

#ifndef CW_STEP
#error "build with -DCW_STEP=N (make check-step STEP=N)"
#endif

int main(int argc, char **argv)
{
    static cw_run run;
    cw_fns f;
    const char *src;
    int failed;
    memset(&f, 0, sizeof f);
    memset(&run, 0, sizeof run);
    run.img_dir = argc > 1 ? argv[1] : "build/coursework";
    if (argc > 2) {                      /* another seed: a fresh draw of every sampler check */
        cw_seed_offset = strtoull(argv[2], NULL, 10);
        if (argc > 3) run.img_dir = NULL;   /* "-": no pictures */
    }
#if CW_STEP == 1
    f.sample_free_flight = cw_sample_free_flight;
    f.free_flight_pdf = cw_free_flight_pdf;
#elif CW_STEP == 2
    f.transmittance = cw_transmittance;
    f.transmittance_estimate = cw_transmittance_estimate;
#elif CW_STEP == 3
    f.hg_phase = cw_hg_phase;
    f.sample_hg_mu = cw_sample_hg_mu;
    f.sample_hg = cw_sample_hg;
#elif CW_STEP == 4
    f.split_cost = cw_split_cost;
    f.best_split = cw_best_split;
#elif CW_STEP == 5
    f.sample_diffuse = cw_sample_diffuse;
    f.diffuse_pdf = cw_diffuse_pdf;
    f.sample_mirror = cw_sample_mirror;
    f.fresnel_schlick = cw_fresnel_schlick;
    f.sample_glass = cw_sample_glass;
#elif CW_STEP == 6
    f.direct_surface = cw_direct_surface;
    f.direct_fog = cw_direct_fog;
#elif CW_STEP == 7
    f.path_radiance = cw_path_radiance;
#elif CW_STEP == 8
    f.mis_weight = cw_mis_weight;
    f.mis_radiance = cw_mis_radiance;
#elif CW_STEP == 9
    f.sample_equiangular = cw_sample_equiangular;
    f.equiangular_pdf = cw_equiangular_pdf;
#else
#error "steps 1-9 exist"
#endif
    src = getenv("CW_SOURCE");
    printf("step %d: %s\n", CW_STEP, cw_step_title(CW_STEP));
    if (src && *src) printf("judging %s\n", src);
    failed = cw_run_step(CW_STEP, &f, &run);
    if (failed && src && *src)
        printf("step %d: %d of %d checks passed in %.2f s -- %d failed: edit %s (the lines above say what each check "
               "saw)\n", CW_STEP, run.passed, run.count, run.seconds, failed, src);
    else
        printf("step %d: %d of %d checks passed in %.2f s%s\n", CW_STEP, run.passed, run.count, run.seconds,
               failed ? "" : " -- all passed");
    return failed ? 1 : 0;
}
