/* 10_pixel_rates.c - tutorial step 10: where the samples go (docs/tutorial.md, section 10).

   The error a render reports is sum_p Var[mean_p] / sum_p mean_p^2: a sum over pixels, and
   some pixels are much noisier than others (here a spot light's cone in the fog, and the
   floor it lights, against the dim fog around them). With sigma_p the noise of one sample
   of pixel p, n_p samples there leave sigma_p^2 / n_p of variance, and for a fixed total
   that sum is least with n_p proportional to sigma_p. fogrt_image_sample_rates learns such
   rates from a short pilot (8 spp taken alike); render desc sample_rate then spends the
   rest of the samples by them. Each pixel's rate reads only its neighbours' noise (the
   other colour of a chessboard), never its own, and is made once: so no pixel's sample
   count follows its own samples, and the image stays unbiased (a pixel stopped because it
   "looks converged" before its rare bright path came would be dark for ever).
   Usage: 10_pixel_rates [out.png [samples_per_pixel]]                                      */
#define _POSIX_C_SOURCE 199309L
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#include "tutorial.h"

#define PILOT_SPP 8

/* spp samples per pixel, every pixel alike (rates NULL) or the pilot's then the rates'
   (rates: TUT_W x TUT_H floats, filled here). Prints one line and returns the image mean. */
static double render(const fogrt_scene *scene, fogrt_render_desc rd, int spp, float *rates, const char *label,
                     tut_strip *strip, int k)
{
    fogrt_image img;
    fogrt_error_estimate err;
    float *rgb = (float *)malloc(sizeof(float) * 3 * TUT_W * TUT_H);
    double t0, seconds, mean = 0.0;
    size_t i;
    if (!rgb) { fprintf(stderr, "10_pixel_rates: out of memory\n"); exit(1); }
    tut_check(fogrt_image_alloc(&img, TUT_W, TUT_H, NULL), "fogrt_image_alloc");
    t0 = tut_now();
    if (rates && spp > PILOT_SPP) {
        tut_check(fogrt_render(scene, &rd, &img, PILOT_SPP, NULL), "fogrt_render (pilot)");
        tut_check(fogrt_image_sample_rates(&img, rates), "fogrt_image_sample_rates");
        rd.sample_rate = rates;                       /* kept to the end: unbiased */
        tut_check(fogrt_render(scene, &rd, &img, spp - PILOT_SPP, NULL), "fogrt_render (rates)");
    } else {
        tut_check(fogrt_render(scene, &rd, &img, spp, NULL), "fogrt_render");
    }
    seconds = tut_now() - t0;
    fogrt_image_error(&img, &err);
    printf("%-34s %4d spp  %6.2f s  relative error %.4f  efficiency %7.1f  (%.1f samples per pixel on average)\n",
           label, spp, seconds, err.relative_error, 1.0 / (err.relative_error * err.relative_error * seconds),
           (double)err.samples / (TUT_W * TUT_H));
    fogrt_image_resolve(&img, rgb);
    for (i = 0; i < (size_t)TUT_W * TUT_H; ++i) mean += (rgb[3 * i] + rgb[3 * i + 1] + rgb[3 * i + 2]) / 3.0;
    tut_strip_put(strip, k, rgb, 1.5f);
    {
        char detail[96];
        snprintf(detail, sizeof detail, "%d spp on average, relative error %.4f", spp, err.relative_error);
        tut_strip_caption(strip, k, label, detail);
    }
    fogrt_image_free(&img);
    free(rgb);
    return mean / (TUT_W * TUT_H);
}

int main(int argc, char **argv)
{
    const char *png = argc > 1 ? argv[1] : "10_pixel_rates.png";
    int spp = argc > 2 ? atoi(argv[2]) : 64;
    tut_strip strip = tut_strip_make(3,
        "Step 10, where the samples go: a spot light in fog (sigma_t 0.5, albedo 0.9, g "
        "0.6, equiangular sampling as in step 8) over a diffuse sphere, every pixel alike against pixel rates");
    fogrt_render_desc rd = fogrt_render_paper_defaults();   /* the paper's method (Part I), */
    fogrt_light_desc spot;
    fogrt_scene *scene;
    float *rates = (float *)malloc(sizeof(float) * TUT_W * TUT_H), *map = (float *)malloc(sizeof(float) * 3 * TUT_W * TUT_H);
    float lo = 1e30f, hi = 0.0f;
    double even, adaptive;
    size_t i;
    rd.equiangular = true;                                  /* with step 8's lamp sampling (Part II, B) */
    if (spp <= PILOT_SPP) { fprintf(stderr, "10_pixel_rates: samples_per_pixel must be > %d\n", PILOT_SPP); return 2; }
    if (!rates || !map) { fprintf(stderr, "10_pixel_rates: out of memory\n"); return 1; }

    scene = tut_scene_create();
    tut_cornell_box(scene, 0.0f, 0.0f);             /* no lamp: the spot light only */
    {   /* one diffuse sphere under the spot (glass would add caustics, another story) */
        fogrt_vec3 c;
        c.x = -0.25f; c.y = 0.35f; c.z = -0.2f;
        tut_check(fogrt_scene_add_sphere(scene, c, 0.35f, tut_material(scene, FOGRT_BSDF_DIFFUSE, 0.8f, 0.8f, 0.8f)),
                  "fogrt_scene_add_sphere");
    }
    memset(&spot, 0, sizeof spot);
    spot.type = FOGRT_LIGHT_SPOT;
    spot.position.x = 0.0f; spot.position.y = 1.4f; spot.position.z = 0.0f;
    spot.direction.y = -1.0f;
    spot.intensity.x = 8.0f; spot.intensity.y = 7.2f; spot.intensity.z = 6.0f;
    spot.cutoff_deg = 25.0f; spot.beam_deg = 18.0f;
    tut_check(fogrt_scene_add_light(scene, &spot), "fogrt_scene_add_light");
    tut_fog(scene, 0.5f, 0.9f, 0.6f);
    tut_check(fogrt_scene_build(scene, NULL), "fogrt_scene_build");

    even = render(scene, rd, spp, NULL, "every pixel alike", &strip, 0);
    adaptive = render(scene, rd, spp, rates, "pixel rates after 8 spp", &strip, 2);
    /* the middle panel: the rates themselves, 0 black to the largest white */
    for (i = 0; i < (size_t)TUT_W * TUT_H; ++i) { lo = rates[i] < lo ? rates[i] : lo; hi = rates[i] > hi ? rates[i] : hi; }
    for (i = 0; i < (size_t)TUT_W * TUT_H; ++i) map[3 * i] = map[3 * i + 1] = map[3 * i + 2] = rates[i] / hi;
    tut_strip_put(&strip, 1, map, 0.0f);
    {
        char detail[96];
        snprintf(detail, sizeof detail, "black 0, white %.2f x the mean rate (here %.2f to %.2f)", (double)hi, (double)lo, (double)hi);
        tut_strip_caption(&strip, 1, "the rates fogrt_image_sample_rates made from the 8 spp pilot", detail);
    }
    printf("rates: %.2f to %.2f times the mean; image means %.5f (alike) and %.5f (rates): the same light\n",
           (double)lo, (double)hi, even, adaptive);
    tut_strip_write(&strip, png);
    free(rates); free(map);
    fogrt_scene_destroy(scene);
    return 0;
}
