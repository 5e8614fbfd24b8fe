/* 08_equiangular.c - tutorial step 8: equiangular sampling (docs/tutorial.md, section 8).

   A point light hangs in the fog and is the only light. Its light scattered once by the fog
   toward the camera is an integral along every ray of sigma_s T(t) p I / r(t)^2, and
   r(t)^2 = h^2 + (t - delta)^2 has a sharp peak where the ray passes the light (h is the
   distance of the light from the ray, delta the closest approach). Next-event estimation
   at free-flight collisions (rd.equiangular = false, as the paper does) places the
   collisions by T(t), blind to the peak: rays that pass close to the light are noisy.
   Equiangular sampling (Kulla and Fajardo 2012, rd.equiangular = true, the default;
   fogrt_sample_equiangular) draws t with pdf proportional to 1 / r(t)^2, so the 1/r^2
   cancels and the glow around the light is smooth at a few samples per pixel.
   Usage: 08_equiangular [out.png [samples_per_pixel]]                                      */
#define _POSIX_C_SOURCE 199309L
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#define TUT_W 200
#define TUT_H 150
#include "tutorial.h"

int main(int argc, char **argv)
{
    const char *png = argc > 1 ? argv[1] : "08_equiangular.png";
    int spp = argc > 2 ? atoi(argv[2]) : 32;
    tut_strip strip = tut_strip_make(2,
        "Step 8, equiangular sampling: a point light in fog (sigma_t 0.3, albedo 0.9, g "
        "0.3), its light gathered along every fog segment or only at collisions");
    fogrt_render_desc rd = fogrt_render_paper_defaults();   /* the paper's method (Part I) */
    fogrt_light_desc point;
    fogrt_scene *scene;
    float pdf;
    if (spp < 1) { fprintf(stderr, "08_equiangular: samples_per_pixel must be >= 1\n"); return 2; }
    /* The sampler on its own: a light 0.05 from the ray, closest at t = 3, segment [0, 10]:
       half the samples fall within 0.05 of t = 3 (the angle is uniform). */
    printf("equiangular, h 0.05, delta 3 on [0, 10]: u = 0.25 -> t = %.4f, u = 0.5 -> t = %.4f, u = 0.75 -> t = %.4f\n",
           fogrt_sample_equiangular(3.0f, 0.05f, 0.0f, 10.0f, 0.25f, &pdf),
           fogrt_sample_equiangular(3.0f, 0.05f, 0.0f, 10.0f, 0.5f, &pdf),
           fogrt_sample_equiangular(3.0f, 0.05f, 0.0f, 10.0f, 0.75f, &pdf));

    scene = tut_scene_create();
    tut_cornell_box(scene, 0.0f, 0.0f);             /* no lamp: the point light only */
    tut_four_spheres(scene);
    memset(&point, 0, sizeof point);
    point.type = FOGRT_LIGHT_POINT;
    point.position.x = 0.1f; point.position.y = 0.9f; point.position.z = 0.0f;
    point.intensity.x = 1.0f; point.intensity.y = 0.85f; point.intensity.z = 0.6f;
    tut_check(fogrt_scene_add_light(scene, &point), "fogrt_scene_add_light");
    tut_fog(scene, 0.3f, 0.9f, 0.3f);
    tut_check(fogrt_scene_build(scene, NULL), "fogrt_scene_build");

    rd.equiangular = true;                          /* Part II, B, switched on (the full defaults have it) */
    tut_render(scene, &rd, spp, "point light, equiangular", &strip, 0, 1.5f);
    rd.equiangular = false;                         /* NEE at fog collisions only */
    tut_render(scene, &rd, spp, "point light, collisions only", &strip, 1, 1.5f);
    tut_strip_write(&strip, png);
    fogrt_scene_destroy(scene);
    return 0;
}
