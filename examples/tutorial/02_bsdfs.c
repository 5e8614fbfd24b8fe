/* 02_bsdfs.c - tutorial step 2: the four BSDFs (docs/tutorial.md, section 2).

   The box gets an area light on the ceiling and four spheres, one per BSDF of the paper:
   diffuse (f = rho / pi), mirror, refraction and glass, where glass reflects with the Fresnel
   probability F (Schlick's approximation by default) and refracts otherwise. First the
   program asks each BSDF for one sample (fogrt_sample_bsdf) at 45 degrees and prints what it
   returned; then it path traces the scene (no fog yet) and prints its time and error.
   Usage: 02_bsdfs [out.png [samples_per_pixel]]                                            */
#define _POSIX_C_SOURCE 199309L
#include <math.h>
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#define TUT_W 200
#define TUT_H 150
#include "tutorial.h"

int main(int argc, char **argv)
{
    const char *png = argc > 1 ? argv[1] : "02_bsdfs.png";
    int spp = argc > 2 ? atoi(argv[2]) : 128;
    const char *name[4] = {"diffuse", "mirror", "refraction", "glass"};
    const fogrt_bsdf_type type[4] = {FOGRT_BSDF_DIFFUSE, FOGRT_BSDF_MIRROR, FOGRT_BSDF_REFRACTION, FOGRT_BSDF_GLASS};
    fogrt_vec3 wo;                       /* local frame: the normal is +z; 45 degrees off it */
    fogrt_scene *scene;
    fogrt_render_desc rd = fogrt_render_paper_defaults();   /* the paper's method (Part I) */
    tut_strip strip = tut_strip_make(1,
        "Step 2, the BSDFs: diffuse, mirror, refraction and glass spheres (left to "
        "right) in the Cornell box under its ceiling lamp; path traced, no fog");
    int k;
    if (spp < 1) { fprintf(stderr, "02_bsdfs: samples_per_pixel must be >= 1\n"); return 2; }
    wo.x = sinf(0.785398f); wo.y = 0.0f; wo.z = cosf(0.785398f);
    printf("one sample of each BSDF, wo at 45 degrees (Schlick F = %.4f at this angle, %.4f head-on)\n",
           fogrt_fresnel_schlick(1.5f, wo.z), fogrt_fresnel_schlick(1.5f, 1.0f));
    for (k = 0; k < 4; ++k) {
        fogrt_material_desc m;
        fogrt_bsdf_sample bs;
        int j, reflected = 0;
        memset(&m, 0, sizeof m);
        m.type = type[k];
        m.reflectance.x = m.reflectance.y = m.reflectance.z = 0.9f;
        m.transmittance = m.reflectance;
        m.ior = 1.5f;
        if (!fogrt_sample_bsdf(&m, FOGRT_FRESNEL_SCHLICK, wo, 0.5f, 0.3f, 0.7f, &bs)) continue;
        printf("  %-10s wi = (%+.3f %+.3f %+.3f)  weight f|cos|/pdf = %.3f  pdf = %.3f  %s%s\n", name[k],
               bs.wi.x, bs.wi.y, bs.wi.z, bs.weight.x, bs.pdf, bs.is_delta ? "delta" : "smooth",
               bs.is_transmission ? ", transmitted" : ", reflected");
        if (type[k] != FOGRT_BSDF_GLASS) continue;
        for (j = 0; j < 10000; ++j) {       /* u_lobe decides the lobe: reflect when u_lobe < F */
            if (fogrt_sample_bsdf(&m, FOGRT_FRESNEL_SCHLICK, wo, ((float)j + 0.5f) / 10000.0f, 0.3f, 0.7f, &bs) &&
                !bs.is_transmission) ++reflected;
        }
        printf("  %-10s reflects for %.2f%% of u_lobe in [0,1): the Fresnel F\n", "", reflected / 100.0);
    }

    scene = tut_scene_create();
    tut_cornell_box(scene, 0.3f, 12.0f);
    tut_four_spheres(scene);
    tut_check(fogrt_scene_build(scene, NULL), "fogrt_scene_build");
    tut_render(scene, &rd, spp, "path traced, no fog", &strip, 0, 1.0f);
    tut_strip_write(&strip, png);
    fogrt_scene_destroy(scene);
    return 0;
}
