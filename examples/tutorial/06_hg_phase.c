/* 06_hg_phase.c - tutorial step 6: the Henyey-Greenstein phase function
   (docs/tutorial.md, section 6).

   Now the fog scatters (albedo 0.9): at a collision the path takes a new direction from the
   Henyey-Greenstein phase function, p(mu) = (1 - g^2) / (4 pi (1 + g^2 - 2 g mu)^(3/2))
   (eq. 9-10, fogrt_hg_phase), sampled by inverting its CDF (eq. 11-12, fogrt_sample_hg).
   g is the mean cosine of the scattering angle: g > 0 scatters forward, g < 0 back. A spot
   light high on the back wall shines toward the camera, so the sweep g = -0.5, 0, 0.5, 0.9
   shows the beam growing brighter as more light is scattered forward into the lens. The
   program first checks, with 10^6 samples each, that the mean cosine of the sampled
   directions is g.
   Usage: 06_hg_phase [out.png [samples_per_pixel]]                                         */
#define _POSIX_C_SOURCE 199309L
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#include "tutorial.h"

int main(int argc, char **argv)
{
    const char *png = argc > 1 ? argv[1] : "06_hg_phase.png";
    int spp = argc > 2 ? atoi(argv[2]) : 64;
    const float g[4] = {-0.5f, 0.0f, 0.5f, 0.9f};
    tut_strip strip = tut_strip_make(4,
        "Step 6, the Henyey-Greenstein phase: scattering fog (sigma_t 0.3, albedo 0.9), "
        "a spot light on the back wall aimed at the camera, g from -0.5 to 0.9");
    fogrt_render_desc rd = fogrt_render_paper_defaults();   /* the paper's method (Part I) */
    fogrt_light_desc spot;
    fogrt_vec3 wo;
    fogrt_rng rng;
    int k, i, n = 1000000;
    if (spp < 1) { fprintf(stderr, "06_hg_phase: samples_per_pixel must be >= 1\n"); return 2; }

    wo.x = 0.0f; wo.y = 0.0f; wo.z = 1.0f;        /* the ray travels along d = -wo = -z */
    for (k = 0; k < 4; ++k) {
        double mean_mu = 0.0;
        fogrt_rng_seed(&rng, 6, (uint64_t)k);
        for (i = 0; i < n; ++i) {
            float pdf, u1 = fogrt_rng_float(&rng), u2 = fogrt_rng_float(&rng);
            fogrt_vec3 wi = fogrt_sample_hg(g[k], wo, u1, u2, &pdf);
            mean_mu += -wi.z;                      /* cos(d, wi) */
        }
        printf("g %+.2f: mean cosine of %d HG samples %+.4f; p(forward) = %.3f, p(sideways) = %.3f, p(back) = %.3f per sr\n",
               g[k], n, mean_mu / n, fogrt_hg_phase(g[k], 1.0f), fogrt_hg_phase(g[k], 0.0f), fogrt_hg_phase(g[k], -1.0f));
    }

    memset(&spot, 0, sizeof spot);
    spot.type = FOGRT_LIGHT_SPOT;
    spot.position.x = 0.0f; spot.position.y = 1.3f; spot.position.z = -0.9f;
    spot.direction.x = 0.25f; spot.direction.y = -0.35f; spot.direction.z = 1.0f;  /* toward the camera */
    spot.intensity.x = spot.intensity.y = spot.intensity.z = 6.0f;
    spot.cutoff_deg = 14.0f; spot.beam_deg = 10.0f;
    for (k = 0; k < 4; ++k) {
        fogrt_scene *scene = tut_scene_create();
        char label[64];
        tut_cornell_box(scene, 0.3f, 3.0f);        /* a dim lamp, so the beam stands out */
        tut_four_spheres(scene);
        tut_check(fogrt_scene_add_light(scene, &spot), "fogrt_scene_add_light");
        tut_fog(scene, 0.3f, 0.9f, g[k]);
        tut_check(fogrt_scene_build(scene, NULL), "fogrt_scene_build");
        snprintf(label, sizeof label, "scattering fog, g %+.2f", g[k]);
        tut_render(scene, &rd, spp, label, &strip, k, 1.8f);   /* exposure 1.8 */
        fogrt_scene_destroy(scene);
    }
    tut_strip_write(&strip, png);
    return 0;
}
