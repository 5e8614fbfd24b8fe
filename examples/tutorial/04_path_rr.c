/* 04_path_rr.c - tutorial step 4: global illumination with Russian roulette
   (docs/tutorial.md, section 4).

   The same scene, now with FOGRT_INTEGRATOR_PATH, the paper's Algorithm 1 without fog: at
   every diffuse point the path samples the light (step c) and then a new direction from the
   BSDF (step d), so light that bounced any number of times is counted. Paths are ended by
   Russian roulette (step e): after rr_depth bounces a path goes on with probability
   q = min(0.95, max component of its weight) and its weight is divided by q, which keeps the
   estimate unbiased. Three panels:
     left:   max_depth 1, direct light only (as step 3, but through the path integrator);
     middle: full global illumination, roulette after 3 bounces (the default);
     right:  full global illumination, roulette from the first bounce (rr_depth 0).
   Usage: 04_path_rr [out.png [samples_per_pixel]]                                          */
#define _POSIX_C_SOURCE 199309L
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#define TUT_W 200
#define TUT_H 150
#include "tutorial.h"

int main(int argc, char **argv)
{
    const char *png = argc > 1 ? argv[1] : "04_path_rr.png";
    int spp = argc > 2 ? atoi(argv[2]) : 64;
    fogrt_scene *scene;
    fogrt_render_desc rd = fogrt_render_paper_defaults();   /* the paper's method (Part I) */
    tut_strip strip = tut_strip_make(3,
        "Step 4, path tracing and Russian roulette: the four spheres, direct light only "
        "against every bounce with roulette from bounce 3 or 1");
    if (spp < 1) { fprintf(stderr, "04_path_rr: samples_per_pixel must be >= 1\n"); return 2; }
    scene = tut_scene_create();
    tut_cornell_box(scene, 0.3f, 12.0f);
    tut_four_spheres(scene);
    tut_check(fogrt_scene_build(scene, NULL), "fogrt_scene_build");

    rd.integrator = FOGRT_INTEGRATOR_PATH;        /* Algorithm 1 (the default) */
    rd.max_depth = 1;
    tut_render(scene, &rd, spp, "path, max_depth 1 (direct only)", &strip, 0, 1.0f);
    rd.max_depth = -1;                            /* unlimited: roulette ends every path */
    rd.rr_depth = 3;
    tut_render(scene, &rd, spp, "path, roulette after 3 bounces", &strip, 1, 1.0f);
    rd.rr_depth = 0;
    tut_render(scene, &rd, spp, "path, roulette from bounce 1", &strip, 2, 1.0f);
    tut_strip_write(&strip, png);
    fogrt_scene_destroy(scene);
    return 0;
}
