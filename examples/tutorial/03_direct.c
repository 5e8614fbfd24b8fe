/* 03_direct.c - tutorial step 3: one-bounce direct lighting (docs/tutorial.md, section 3).

   The scene of step 2, rendered by the paper's baseline integrator, FOGRT_INTEGRATOR_DIRECT:
   the camera ray is followed through mirrors and glass to the first diffuse point, and only
   the light that reaches that point straight from the lamp is counted (eq. 3 with one
   bounce). Two estimators of the same integral, at the same sample count:
     left:  light sampling (rd.nee): pick a point on the lamp, cast a shadow ray, combined
            with BSDF sampling by multiple importance sampling (rd.mis);
     right: BSDF sampling only (rd.nee = false): the light counts only when a cosine-
            distributed direction happens to hit the lamp.
   Both converge to the same image; the printed errors show how much sooner the first does.
   Usage: 03_direct [out.png [samples_per_pixel]]                                           */
#define _POSIX_C_SOURCE 199309L
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#define TUT_W 200
#define TUT_H 150
#include "tutorial.h"

int main(int argc, char **argv)
{
    const char *png = argc > 1 ? argv[1] : "03_direct.png";
    int spp = argc > 2 ? atoi(argv[2]) : 32;
    fogrt_scene *scene;
    fogrt_render_desc rd = fogrt_render_paper_defaults();   /* the paper's method (Part I) */
    tut_strip strip = tut_strip_make(2,
        "Step 3, direct light (one bounce): the four spheres lit by the ceiling lamp, "
        "sampled two ways at the same samples per pixel");
    if (spp < 1) { fprintf(stderr, "03_direct: samples_per_pixel must be >= 1\n"); return 2; }
    scene = tut_scene_create();
    tut_cornell_box(scene, 0.3f, 12.0f);
    tut_four_spheres(scene);
    tut_check(fogrt_scene_build(scene, NULL), "fogrt_scene_build");

    rd.integrator = FOGRT_INTEGRATOR_DIRECT;       /* one bounce: the paper's baseline */
    rd.nee = true;                                 /* sample the light (and MIS) */
    tut_render(scene, &rd, spp, "direct, light sampling + MIS", &strip, 0, 1.0f);
    rd.nee = false;                                /* only BSDF sampling finds the lamp */
    tut_render(scene, &rd, spp, "direct, BSDF sampling only", &strip, 1, 1.0f);
    tut_strip_write(&strip, png);
    fogrt_scene_destroy(scene);
    return 0;
}
