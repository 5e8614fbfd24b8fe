/* nomedium_cost.c - a fixed, fog-free render for bench/callgrind.sh.

   fogrt promises that a scene without fog (sigma_t = 0) pays nothing for the fog machinery.
   callgrind.sh builds this program twice, normally and with -DFOGRT_NO_MEDIUM (the fog code
   stripped at compile time), runs both under callgrind counting only the instructions executed
   inside fogrt_render, and compares the two totals.

   The scene is the default scene with its medium switched off; the render is small, with a
   fixed seed and sample count, on one thread (build without -fopenmp), so the instruction count
   is the same on every run. It prints the mean radiance and a checksum of the image so that the
   two builds can be seen to render the same picture.                                          */
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define WIDTH 64
#define HEIGHT 48
#define SPP 8

static void check(fogrt_result r, const char *what)
{
    if (r != FOGRT_RESULT_OK) {
        fprintf(stderr, "nomedium_cost: %s failed: %s\n", what, fogrt_result_string(r));
        exit(1);
    }
}

static fogrt_result (*volatile render_fn)(const fogrt_scene *, const fogrt_render_desc *, fogrt_image *,
                                          int, fogrt_render_stats *);

int main(void)
{
    fogrt_scene *scene = NULL;
    fogrt_medium_desc medium;
    fogrt_render_desc rd;
    fogrt_render_stats stats;
    fogrt_image img;
    float *rgb;
    double mean = 0.0;
    uint32_t checksum = 2166136261u;   /* FNV-1a over the bytes of the resolved image */
    size_t i;

    check(fogrt_scene_create(NULL, &scene), "fogrt_scene_create");
    check(fogrt_scene_add_default(scene), "fogrt_scene_add_default");
    medium.sigma_t = 0.0f;                                      /* no fog */
    medium.albedo.x = medium.albedo.y = medium.albedo.z = 0.9f;
    medium.g = 0.0f;
    check(fogrt_scene_set_medium(scene, &medium), "fogrt_scene_set_medium");
    check(fogrt_scene_build(scene, NULL), "fogrt_scene_build");
    check(fogrt_image_alloc(&img, WIDTH, HEIGHT, NULL), "fogrt_image_alloc");

    rd = fogrt_render_defaults();
    rd.width = WIDTH; rd.height = HEIGHT;
    rd.seed = 2024; rd.threads = 1;
    /* Called through a volatile pointer so that the compiler cannot inline fogrt_render into
       main: callgrind.sh counts the instructions executed inside the function of that name. */
    render_fn = fogrt_render;
    check(render_fn(scene, &rd, &img, SPP, &stats), "fogrt_render");

    rgb = (float *)malloc(sizeof(float) * 3 * WIDTH * HEIGHT);
    if (!rgb) { fprintf(stderr, "nomedium_cost: out of memory\n"); return 1; }
    fogrt_image_resolve(&img, rgb);
    for (i = 0; i < (size_t)3 * WIDTH * HEIGHT; i++) {
        const unsigned char *b = (const unsigned char *)&rgb[i];
        size_t k;
        mean += rgb[i];
        for (k = 0; k < sizeof(float); k++) checksum = (checksum ^ b[k]) * 16777619u;
    }
    mean /= 3.0 * WIDTH * HEIGHT;
    printf("%s: %dx%d, %d spp, features 0x%x, %llu rays, mean radiance %.6f, image checksum %08x\n",
#ifdef FOGRT_NO_MEDIUM
           "FOGRT_NO_MEDIUM build",
#else
           "normal build (sigma_t = 0)",
#endif
           WIDTH, HEIGHT, SPP, (unsigned)fogrt_scene_get_features(scene),
           (unsigned long long)stats.rays, mean, (unsigned)checksum);

    free(rgb);
    fogrt_image_free(&img);
    fogrt_scene_destroy(scene);
    return 0;
}
