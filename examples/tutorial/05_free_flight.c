/* 05_free_flight.c - tutorial step 5: exponential free flight and Beer-Lambert attenuation
   (docs/tutorial.md, section 5).

   The box of step 4 is filled with fog that only absorbs (albedo 0). Every ray samples the
   distance to its next collision from pdf(t) = sigma_t exp(-sigma_t t) (eq. 4-6,
   fogrt_sample_exponential); if that comes before the surface, the path is absorbed there,
   otherwise it reaches the surface with its weight unchanged. On average a surface at
   distance d is therefore seen through T = exp(-sigma_t d) (eq. 7-8, fogrt_transmittance),
   and shadow rays carry the same factor in closed form. That yes-or-no arrival is the
   paper's estimator (expected_emission = false here); fogrt's default instead adds the
   lamp's light times T whether or not the ray collides first, the same mean without the
   yes-or-no noise. The program checks the numbers, both ways, then renders four densities
   (fogrt's way in the image, the paper's printed beside it).
   Usage: 05_free_flight [out.png [samples_per_pixel]]                                      */
#define _POSIX_C_SOURCE 199309L
#include <math.h>
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#include "tutorial.h"

int main(int argc, char **argv)
{
    const char *png = argc > 1 ? argv[1] : "05_free_flight.png";
    int spp = argc > 2 ? atoi(argv[2]) : 64;
    const float sigma[4] = {0.0f, 0.1f, 0.2f, 0.4f};
    tut_strip strip = tut_strip_make(4,
        "Step 5, free flight: the Cornell box filled with absorbing fog (albedo 0) of "
        "rising density sigma_t [1 / scene unit]");
    fogrt_render_desc rd = fogrt_render_paper_defaults();   /* the paper's method (Part I) */
    fogrt_rng rng;
    int k, i, n = 1000000, reach = 0;
    double mean_t = 0.0;
    if (spp < 1) { fprintf(stderr, "05_free_flight: samples_per_pixel must be >= 1\n"); return 2; }

    /* Free flight: the mean of t is the mean free path 1/sigma_t, and the fraction of
       flights longer than d is T(d). */
    fogrt_rng_seed(&rng, 5, 0);
    for (i = 0; i < n; ++i) {
        float t = fogrt_sample_exponential(0.5f, fogrt_rng_float(&rng));
        mean_t += t;
        if (t > 3.0f) ++reach;
    }
    printf("sigma_t 0.5: mean free flight %.4f (1/sigma_t = 2), P(t > 3) = %.4f, T(3) = %.4f\n",
           mean_t / n, (double)reach / n, fogrt_transmittance(0.5f, 3.0f));

    for (k = 0; k < 4; ++k) {
        fogrt_scene *scene = tut_scene_create();
        fogrt_vec3 o, d, L;
        uint64_t rays = 0;
        char label[64];
        int way;
        tut_cornell_box(scene, 0.3f, 12.0f);
        tut_four_spheres(scene);
        tut_fog(scene, sigma[k], 0.0f, 0.0f);     /* albedo 0: the fog only absorbs */
        tut_check(fogrt_scene_build(scene, NULL), "fogrt_scene_build");
        /* One camera-style ray straight up into the lamp, 1.5 units through the fog: the
           mean of fogrt_trace must be Le T(1.5) (the lamp's radiance is 12). */
        o.x = 0.0f; o.y = 0.0f + 1e-3f; o.z = 0.0f;
        d.x = 0.0f; d.y = 1.0f; d.z = 0.0f;
        rd.max_depth = 0;                          /* emission only: just the attenuation */
        for (way = 0; way < 2; ++way) {            /* the paper's, then fogrt's default */
            double sum = 0.0, sum2 = 0.0, mean;
            rd.expected_emission = way == 1;
            fogrt_rng_seed(&rng, 7, (uint64_t)k);
            for (i = 0; i < 100000; ++i) { L = fogrt_trace(scene, &rd, o, d, &rng, &rays); sum += L.x; sum2 += (double)L.x * L.x; }
            mean = sum / 100000;
            printf("sigma_t %.2f: ray into the lamp, %-17s mean radiance %.4f +- %.4f, Le T(1.498) = %.4f\n", sigma[k],
                   way ? "fogrt's default:" : "paper's estimator:", mean, sqrt(fmax(sum2 / 100000 - mean * mean, 0.0) / 100000),
                   12.0 * fogrt_transmittance(sigma[k], 1.498f));
        }
        rd.max_depth = 64;
        rd.expected_emission = false;
        snprintf(label, sizeof label, "paper's, sigma_t %.2f", sigma[k]);
        tut_render(scene, &rd, spp, label, NULL, k, 1.0f);
        rd.expected_emission = true;
        snprintf(label, sizeof label, "absorbing fog, sigma_t %.2f", sigma[k]);
        tut_render(scene, &rd, spp, label, &strip, k, 1.0f);
        fogrt_scene_destroy(scene);
    }
    tut_strip_write(&strip, png);
    return 0;
}
