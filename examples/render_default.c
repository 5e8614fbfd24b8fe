/* render_default.c - render fogrt's embedded default scene (the fog-filled Cornell box).

   Usage: render_default [out.png [out.pfm [samples_per_pixel [width height [seconds]]]]]
   Renders progressively, a batch of samples at a time, and after each batch prints how
   noisy the image still is (fogrt's own relative error estimate) against the seconds spent.
   Stops at samples_per_pixel (default 256) or when the next batch would pass the time budget
   (default 45 seconds), whichever comes first.
   Uses only fogrt's public API; the PNG goes through stb_image_write (Debian libstb-dev). */
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#include "stb_write.h"           /* stb_image_write, its warnings silenced */

static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void log_stderr(fogrt_log_level level, const char *msg, void *user)
{
    (void)user;
    fprintf(stderr, "fogrt: %s: %s\n", level == FOGRT_LOG_ERROR ? "error" : "warning", msg);
}

int main(int argc, char **argv)
{
    const char *png = argc > 1 ? argv[1] : "fog.png";
    const char *pfm = argc > 2 ? argv[2] : "fog.pfm";
    int spp = argc > 3 ? atoi(argv[3]) : 256;
    int width = argc > 5 ? atoi(argv[4]) : 480, height = argc > 5 ? atoi(argv[5]) : 360;
    double budget = argc > 6 ? atof(argv[6]) : 45.0;
    int batch = 4, done = 0;
    fogrt_scene_desc sd = {0};
    fogrt_scene *scene = NULL;
    fogrt_image img;
    fogrt_render_desc rd = fogrt_render_defaults();
    fogrt_render_stats st;
    fogrt_error_estimate err;
    fogrt_result r;
    uint64_t rays = 0;
    double t0, seconds;
    float *rgb;
    unsigned char *rgb8;

    if (spp <= 0 || width <= 0 || height <= 0) {
        fprintf(stderr, "render_default: samples and resolution must be positive\n");
        return 2;
    }
    sd.logger.func = log_stderr;
    if ((r = fogrt_scene_create(&sd, &scene)) != FOGRT_RESULT_OK ||
        (r = fogrt_scene_add_default(scene)) != FOGRT_RESULT_OK ||
        (r = fogrt_scene_build(scene, NULL)) != FOGRT_RESULT_OK ||
        (r = fogrt_image_alloc(&img, width, height, NULL)) != FOGRT_RESULT_OK) {
        fprintf(stderr, "render_default: %s\n", fogrt_result_string(r));
        fogrt_scene_destroy(scene);
        return 1;
    }
    rd.width = width; rd.height = height;
    t0 = now_seconds();
    /* Progressive rendering: add a batch, report error against time, repeat. */
    printf("# seconds  spp  relative_error\n");
    while (done < spp) {
        int n = done + batch > spp ? spp - done : batch;
        double elapsed = now_seconds() - t0;
        /* the time per sample so far sizes the next batch to what the budget still allows */
        if (done > 0) {
            int fits = (int)((budget - elapsed) / (elapsed / done));
            if (fits < 1) break;
            if (n > fits) n = fits;
        }
        if ((r = fogrt_render(scene, &rd, &img, n, &st)) != FOGRT_RESULT_OK) {
            fprintf(stderr, "render_default: %s\n", fogrt_result_string(r));
            break;
        }
        rays += st.rays;
        done += n;
        fogrt_image_error(&img, &err);
        printf("%9.3f %4d %.5f\n", now_seconds() - t0, done, err.relative_error);
        fflush(stdout);
        if (batch < 32) batch *= 2;
    }
    seconds = now_seconds() - t0;

    rgb = (float *)malloc(sizeof(float) * 3 * (size_t)width * (size_t)height);
    rgb8 = (unsigned char *)malloc(3 * (size_t)width * (size_t)height);
    if (!rgb || !rgb8) { fprintf(stderr, "render_default: out of memory\n"); return 1; }
    fogrt_image_resolve(&img, rgb);
    fogrt_tonemap_rgb8(rgb, width, height, 0.0f, FOGRT_TONEMAP_SRGB, rgb8);   /* 0 EV: as rendered */
    if (!stbi_write_png(png, width, height, 3, rgb8, width * 3))
        fprintf(stderr, "render_default: could not write %s\n", png);
    if (fogrt_write_pfm(pfm, width, height, rgb) != FOGRT_RESULT_OK)
        fprintf(stderr, "render_default: could not write %s\n", pfm);
    printf("%dx%d, %d spp, %.2f s, %.2f Mrays/s, %.3g samples/s, relative error %.4f, %llu non-finite samples dropped -> %s, %s\n",
           width, height, done, seconds, (double)rays / seconds * 1e-6,
           (double)width * height * done / seconds, err.relative_error,
           (unsigned long long)err.rejected, png, pfm);
    free(rgb); free(rgb8);
    fogrt_image_free(&img);
    fogrt_scene_destroy(scene);
    return 0;
}
