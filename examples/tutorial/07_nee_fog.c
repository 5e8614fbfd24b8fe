/* 07_nee_fog.c - tutorial step 7: light importance sampling in fog
   (docs/tutorial.md, section 7).

   The fog of step 6, lit only by the ceiling lamp. At every fog collision the path can
   sample the lamp directly (next-event estimation, rd.nee, the paper's "importance
   sampling"): a point on the lamp, a shadow ray that carries the transmittance T (eq. 8),
   times the phase function toward it (eq. 13), divided by the pdf of the light sample, and
   combined with phase sampling by MIS. Without it (rd.nee = false, the paper's "without
   importance sampling") light is found only when a sampled direction happens to hit the
   lamp. Both are unbiased; at the same sample count the printed errors show the difference.
   Usage: 07_nee_fog [out.png [samples_per_pixel]]                                          */
#define _POSIX_C_SOURCE 199309L
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#define TUT_W 200
#define TUT_H 150
#include "tutorial.h"

int main(int argc, char **argv)
{
    const char *png = argc > 1 ? argv[1] : "07_nee_fog.png";
    int spp = argc > 2 ? atoi(argv[2]) : 64;
    tut_strip strip = tut_strip_make(2,
        "Step 7, light sampling in fog: fog (sigma_t 0.3, albedo 0.9, g 0.5) lit only "
        "by the ceiling lamp, with and without next-event estimation at the fog "
        "collisions");
    fogrt_render_desc rd = fogrt_render_paper_defaults();   /* the paper's method (Part I) */
    fogrt_scene *scene;
    double t_on, t_off;
    if (spp < 1) { fprintf(stderr, "07_nee_fog: samples_per_pixel must be >= 1\n"); return 2; }
    scene = tut_scene_create();
    tut_cornell_box(scene, 0.3f, 12.0f);
    tut_four_spheres(scene);
    tut_fog(scene, 0.3f, 0.9f, 0.5f);
    tut_check(fogrt_scene_build(scene, NULL), "fogrt_scene_build");

    rd.nee = true;                                  /* light sampling at every vertex */
    t_on = tut_render(scene, &rd, spp, "fog, light sampling (nee)", &strip, 0, 1.0f);
    rd.nee = false;                                 /* light found only by hitting it */
    t_off = tut_render(scene, &rd, spp, "fog, phase/BSDF sampling only", &strip, 1, 1.0f);
    printf("light sampling costs %.2fx the time per sample\n", t_on / t_off);
    tut_strip_write(&strip, png);
    fogrt_scene_destroy(scene);
    return 0;
}
