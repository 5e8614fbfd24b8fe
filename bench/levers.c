/* bench/levers.c - `make bench-levers`: the estimator levers of docs/benchmarks.md, measured
   in work (rays, CPU seconds of one thread) rather than wall time.
     1. light_by_power: relative error^2 x rays per sample at 64 spp (96 x 72), every light
        against one light chosen by power, on the default scene (2 lights) and on a closed
        box with 8 point lights of powers 1 to 128, without and with fog.
     2. the glow (14 d') on the paper's spot-lit scene (CBbunny_upSpot.dae at density 0.5,
        g 0.6, when ../shared/scenes is there): 160 x 120, 32 spp, one thread, glow off and
        on, 4 seeds: the relative MSE against a reference rendered first (glow on, 1024 spp
        in 2 seeds; --reference-spp N to change) times the CPU seconds, and the rays per
        sample. The error estimate of fogrt_image_error is printed too.
     3. expected emission (render desc expected_emission, 14 b) on the cross-check's
        lamp-lit box (tests/crosscheck/scenes.py: fog_iso, fog_forward, fog_back, glass_fog with exact
        Fresnel), 128 x 96, --lamp-spp samples (32), one thread, expected_emission off
        and on, 4 seeds: the relative MSE against a reference (on, --reference-spp samples
        in 2 seeds) times the CPU seconds, and the rays per sample.
   Usage: bench/levers [--no-spot] [--no-lamp] [--reference-spp N] [--lamp-spp N] */
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#ifdef HAVE_FOGRT_LOAD
#define FOGRT_LOAD_IMPLEMENTATION
#include "fogrt_load.h"
#endif
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <math.h>

#ifndef FOGRT_SHARED_DIR
#define FOGRT_SHARED_DIR "../shared"
#endif

static double cpu_seconds(void)
{
    return (double)clock() / (double)CLOCKS_PER_SEC;
}
static fogrt_vec3 v3(float x, float y, float z) { fogrt_vec3 r; r.x = x; r.y = y; r.z = z; return r; }

static uint32_t material(fogrt_scene *s, fogrt_vec3 refl)
{
    fogrt_material_desc m;
    uint32_t id = 0;
    memset(&m, 0, sizeof m);
    m.type = FOGRT_BSDF_DIFFUSE; m.reflectance = refl; m.transmittance = v3(1, 1, 1); m.ior = 1.5f;
    fogrt_scene_add_material(s, &m, &id);
    return id;
}
static void quad(fogrt_scene *s, fogrt_vec3 a, fogrt_vec3 b, fogrt_vec3 c, fogrt_vec3 d, uint32_t m)
{
    static const uint32_t idx[6] = { 0, 1, 2, 0, 2, 3 };
    float pos[12];
    fogrt_mesh_desc md;
    pos[0] = a.x; pos[1] = a.y; pos[2] = a.z; pos[3] = b.x; pos[4] = b.y; pos[5] = b.z;
    pos[6] = c.x; pos[7] = c.y; pos[8] = c.z; pos[9] = d.x; pos[10] = d.y; pos[11] = d.z;
    memset(&md, 0, sizeof md);
    md.positions = pos; md.vertex_count = 4; md.indices = idx; md.triangle_count = 2; md.material = m;
    fogrt_scene_add_mesh(s, &md);
}
/* A closed box [-1, 1] x [0, 2] x [-1, 1] with 8 point lights under its ceiling. */
static fogrt_scene *many_lights_box(bool fog)
{
    fogrt_scene *s = NULL;
    fogrt_camera_desc c;
    uint32_t w, r, g;
    int k;
    if (fogrt_scene_create(NULL, &s) != FOGRT_RESULT_OK) return NULL;
    w = material(s, v3(0.7f, 0.7f, 0.7f)); r = material(s, v3(0.7f, 0.1f, 0.1f)); g = material(s, v3(0.1f, 0.7f, 0.1f));
    quad(s, v3(-1, 0, -1), v3(-1, 0, 1), v3(1, 0, 1), v3(1, 0, -1), w);
    quad(s, v3(-1, 2, -1), v3(1, 2, -1), v3(1, 2, 1), v3(-1, 2, 1), w);
    quad(s, v3(-1, 0, -1), v3(1, 0, -1), v3(1, 2, -1), v3(-1, 2, -1), w);
    quad(s, v3(-1, 0, 1), v3(-1, 2, 1), v3(1, 2, 1), v3(1, 0, 1), w);
    quad(s, v3(-1, 0, -1), v3(-1, 2, -1), v3(-1, 2, 1), v3(-1, 0, 1), r);
    quad(s, v3(1, 0, -1), v3(1, 0, 1), v3(1, 2, 1), v3(1, 2, -1), g);
    for (k = 0; k < 8; k++) {                            /* powers 1, 2, 4, ..., 128 */
        fogrt_light_desc l;
        float I = 0.02f * (float)(1 << k) / 8.0f;
        memset(&l, 0, sizeof l);
        l.type = FOGRT_LIGHT_POINT;
        l.position = v3(-0.8f + 0.22f * (float)k, 1.5f + 0.05f * (float)(k % 3), -0.6f + 0.15f * (float)(k % 5));
        l.intensity = v3(I, I, I);
        fogrt_scene_add_light(s, &l);
    }
    memset(&c, 0, sizeof c);
    c.position = v3(0, 1, 0.95f); c.look_at = v3(0, 0.8f, 0); c.up = v3(0, 1, 0); c.fov_deg = 75.0f;
    fogrt_scene_set_camera(s, &c);
    if (fog) {
        fogrt_medium_desc m;
        memset(&m, 0, sizeof m);
        m.sigma_t = 0.5f; m.albedo = v3(0.9f, 0.9f, 0.9f); m.g = 0.3f;
        fogrt_scene_set_medium(s, &m);
    }
    if (fogrt_scene_build(s, NULL) != FOGRT_RESULT_OK) { fogrt_scene_destroy(s); return NULL; }
    return s;
}

/* The cross-check's box (tests/crosscheck/scenes.py, box_scene): x in [-1, 1], y in [0, 2],
   z in [-1, 1], open toward the camera, a square lamp of radiance 20 under the ceiling, fog
   everywhere outside the glass; a grey diffuse sphere, or (glass) a glass sphere. */
static fogrt_scene *lamp_box(float sigma_t, float albedo, float g, bool glass)
{
    fogrt_scene *s = NULL;
    fogrt_camera_desc c;
    fogrt_medium_desc md;
    fogrt_material_desc lm;
    uint32_t w, r, gr, lamp, ball;
    const float h = 0.3f, y = 1.98f;
    if (fogrt_scene_create(NULL, &s) != FOGRT_RESULT_OK) return NULL;
    w = material(s, v3(0.725f, 0.71f, 0.68f)); r = material(s, v3(0.63f, 0.065f, 0.05f));
    gr = material(s, v3(0.14f, 0.45f, 0.09f));
    memset(&lm, 0, sizeof lm);
    lm.type = glass ? FOGRT_BSDF_GLASS : FOGRT_BSDF_DIFFUSE;
    lm.reflectance = glass ? v3(1, 1, 1) : v3(0.6f, 0.6f, 0.6f); lm.transmittance = v3(1, 1, 1); lm.ior = 1.5f;
    fogrt_scene_add_material(s, &lm, &ball);
    lm.type = FOGRT_BSDF_DIFFUSE; lm.reflectance = v3(0, 0, 0); lm.emission = v3(20, 20, 20);
    fogrt_scene_add_material(s, &lm, &lamp);
    quad(s, v3(-1, 0, -1), v3(-1, 0, 1), v3(1, 0, 1), v3(1, 0, -1), w);
    quad(s, v3(-1, 2, -1), v3(1, 2, -1), v3(1, 2, 1), v3(-1, 2, 1), w);
    quad(s, v3(-1, 0, -1), v3(1, 0, -1), v3(1, 2, -1), v3(-1, 2, -1), w);
    quad(s, v3(-1, 0, -1), v3(-1, 2, -1), v3(-1, 2, 1), v3(-1, 0, 1), r);
    quad(s, v3(1, 0, -1), v3(1, 0, 1), v3(1, 2, 1), v3(1, 2, -1), gr);
    quad(s, v3(-h, y, -h), v3(h, y, -h), v3(h, y, h), v3(-h, y, h), lamp);   /* faces down */
    if (glass) fogrt_scene_add_sphere(s, v3(0.0f, 0.6f, 0.2f), 0.6f, ball);
    else fogrt_scene_add_sphere(s, v3(-0.4f, 0.45f, -0.3f), 0.45f, ball);
    memset(&c, 0, sizeof c);
    c.position = v3(0, 1, 3.2f); c.look_at = v3(0, 1, 0); c.up = v3(0, 1, 0); c.fov_deg = 40.0f;
    fogrt_scene_set_camera(s, &c);
    memset(&md, 0, sizeof md);
    md.sigma_t = sigma_t; md.albedo = v3(albedo, albedo, albedo); md.g = g;
    fogrt_scene_set_medium(s, &md);
    if (fogrt_scene_build(s, NULL) != FOGRT_RESULT_OK) { fogrt_scene_destroy(s); return NULL; }
    return s;
}

static void by_power(const fogrt_scene *s, const char *name)
{
    int p;
    for (p = 0; p < 2; p++) {
        fogrt_render_desc rd = fogrt_render_defaults();
        fogrt_image img;
        fogrt_render_stats st;
        fogrt_error_estimate e;
        double rays;
        rd.light_by_power = p != 0; rd.threads = 1; rd.seed = 7;
        if (fogrt_image_alloc(&img, 96, 72, NULL) != FOGRT_RESULT_OK) return;
        fogrt_render(s, &rd, &img, 64, &st);
        fogrt_image_error(&img, &e);
        rays = (double)st.rays / (double)st.camera_rays;
        printf("%-26s %-6s rel. error %.4f  rays/sample %6.2f  rel. error^2 x rays %.4g\n", name, p ? "power" : "all",
               e.relative_error, rays, e.relative_error * e.relative_error * rays);
        fogrt_image_free(&img);
    }
}

typedef struct spot_run { double rel_mse, cpu, rays, estimate; } spot_run;

static double luminance(const float *c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

/* One render of W x H on one thread, timed in CPU seconds, with its relative MSE against
   ref (when given); the image goes to out (when given). */
static spot_run render_run(const fogrt_scene *s, const fogrt_render_desc *rd0, int W, int H, int spp,
                           const float *ref, float *out)
{
    spot_run r;
    fogrt_render_desc rd;
    fogrt_image img;
    fogrt_render_stats st;
    fogrt_error_estimate e;
    double t0, num = 0.0, den = 0.0;
    float *rgb = out ? out : (float *)malloc(sizeof(float) * 3 * (size_t)W * (size_t)H);
    int i;
    memset(&r, 0, sizeof r);
    if (!rgb || fogrt_image_alloc(&img, W, H, NULL) != FOGRT_RESULT_OK) { if (!out) free(rgb); return r; }
    rd = *rd0; rd.threads = 1;
    t0 = cpu_seconds();
    fogrt_render(s, &rd, &img, spp, &st);
    r.cpu = cpu_seconds() - t0;
    fogrt_image_error(&img, &e);
    fogrt_image_resolve(&img, rgb);
    for (i = 0; ref && i < W * H; i++) {
        double a = luminance(rgb + 3 * i), b = luminance(ref + 3 * i);
        num += (a - b) * (a - b); den += b * b;
    }
    r.rel_mse = den > 0.0 ? num / den : 0.0;
    r.rays = (double)st.rays / (double)st.camera_rays;
    r.estimate = e.relative_error;
    fogrt_image_free(&img);
    if (!out) free(rgb);
    return r;
}

/* 3. The lamp-lit box, expected_emission off and on; the reference with it on. */
static void lamp_scenes(int ref_spp, int spp)
{
    enum { W = 128, H = 96 };
    static const struct { const char *name; float sigma_t, albedo, g; bool glass; } sc[4] = {
        { "fog_iso", 0.5f, 0.8f, 0.0f, false }, { "fog_forward", 0.5f, 0.8f, 0.7f, false },
        { "fog_back", 0.5f, 0.8f, -0.7f, false }, { "glass_fog", 0.2f, 0.9f, 0.5f, true } };
    float *ref = (float *)malloc(sizeof(float) * 3 * W * H), *half = (float *)malloc(sizeof(float) * 3 * W * H);
    int i, k, q, seed;
    printf("lamp-lit box (the cross-check's), 128x96, %d spp, 1 thread, max depth 64, exact Fresnel; reference %d spp\n",
           spp, ref_spp);
    for (q = 0; q < 4 && ref && half; q++) {
        fogrt_scene *s = lamp_box(sc[q].sigma_t, sc[q].albedo, sc[q].g, sc[q].glass);
        fogrt_render_desc rd = fogrt_render_defaults();
        double sum[2] = { 0.0, 0.0 };
        if (!s) continue;
        rd.max_depth = 64; rd.fresnel = FOGRT_FRESNEL_EXACT;
        memset(ref, 0, sizeof(float) * 3 * W * H);
        for (k = 0; k < 2; k++) {
            rd.seed = 100 + (uint64_t)k;
            render_run(s, &rd, W, H, ref_spp / 2, NULL, half);
            for (i = 0; i < 3 * W * H; i++) ref[i] += 0.5f * half[i];
        }
        for (seed = 1; seed <= 4; seed++)
            for (k = 0; k < 2; k++) {
                spot_run r;
                rd.seed = (uint64_t)seed; rd.expected_emission = k != 0;
                r = render_run(s, &rd, W, H, spp, ref, NULL);
                sum[k] += r.rel_mse * r.cpu;
                printf("  %-11s seed %d expected_emission %-3s  CPU %.2f s  rays/sample %5.2f  rel. MSE %.5f  x CPU s %.4f\n",
                       sc[q].name, seed, k ? "on" : "off", r.cpu, r.rays, r.rel_mse, r.rel_mse * r.cpu);
            }
        printf("  %-11s mean rel. MSE x CPU s: off %.4f  on %.4f  (off / on %.1f)\n", sc[q].name, sum[0] / 4.0,
               sum[1] / 4.0, sum[1] > 0.0 ? sum[0] / sum[1] : 0.0);
        fogrt_scene_destroy(s);
    }
    free(ref); free(half);
}

#ifdef HAVE_FOGRT_LOAD
static spot_run spot_render(const fogrt_scene *s, bool glow, uint64_t seed, int spp, const float *ref, float *out)
{
    fogrt_render_desc rd = fogrt_render_defaults();
    rd.glow = glow; rd.seed = seed; rd.max_depth = 64;
    return render_run(s, &rd, 160, 120, spp, ref, out);
}

static void spot_scene(int ref_spp)
{
    const char *path = FOGRT_SHARED_DIR "/scenes/cs184/CBbunny_upSpot.dae";
    fogrt_scene *s = NULL;
    fogrt_load_options lo;
    fogrt_load_report rep;
    fogrt_medium_desc md;
    float *ref = (float *)calloc(3 * 160 * 120, sizeof(float)), *half = (float *)malloc(sizeof(float) * 3 * 160 * 120);
    int i, k, seed;
    if (!ref || !half || fogrt_scene_create(NULL, &s) != FOGRT_RESULT_OK) { free(ref); free(half); return; }
    memset(&lo, 0, sizeof lo);
    lo.image_width = 800; lo.image_height = 600;
    if (fogrt_load_file(s, path, &lo, &rep) != FOGRT_RESULT_OK) {
        printf("spot-lit fog: skipped (%s not readable)\n", path);
        fogrt_scene_destroy(s); free(ref); free(half);
        return;
    }
    fogrt_scene_get_medium(s, &md);
    md.sigma_t = 0.5f; md.albedo = v3(0.9f, 0.9f, 0.9f); md.g = 0.6f;
    fogrt_scene_set_medium(s, &md);
    fogrt_scene_build(s, NULL);
    for (k = 0; k < 2; k++) {                            /* the reference: two halves, glow on */
        spot_render(s, true, 100 + (uint64_t)k, ref_spp / 2, NULL, half);
        for (i = 0; i < 3 * 160 * 120; i++) ref[i] += 0.5f * half[i];
    }
    printf("spot-lit fog (CBbunny_upSpot.dae, density 0.5, g 0.6), 160x120, 32 spp, 1 thread; reference %d spp\n", ref_spp);
    for (seed = 1; seed <= 4; seed++)
        for (k = 0; k < 2; k++) {
            spot_run r = spot_render(s, k != 0, (uint64_t)seed, 32, ref, NULL);
            printf("  seed %d glow %-3s  CPU %.2f s  rays/sample %5.2f  estimate %.4f  rel. MSE vs reference %.4f  x CPU s %.3f\n",
                   seed, k ? "on" : "off", r.cpu, r.rays, r.estimate, r.rel_mse, r.rel_mse * r.cpu);
        }
    fogrt_scene_destroy(s);
    free(ref); free(half);
}
#endif

int main(int argc, char **argv)
{
    fogrt_scene *s = NULL;
    int i, ref_spp = 2048, lamp_spp = 32;
    bool spot = true, lamp = true;
    for (i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--no-spot") == 0) spot = false;
        else if (strcmp(argv[i], "--no-lamp") == 0) lamp = false;
        else if (strcmp(argv[i], "--reference-spp") == 0 && i + 1 < argc) ref_spp = atoi(argv[++i]);
        else if (strcmp(argv[i], "--lamp-spp") == 0 && i + 1 < argc) lamp_spp = atoi(argv[++i]);
        else { fprintf(stderr, "usage: %s [--no-spot] [--no-lamp] [--reference-spp N] [--lamp-spp N]\n", argv[0]); return 2; }
    }
    if (lamp_spp < 1) lamp_spp = 1;
    if (ref_spp < 2) ref_spp = 2;
    if (fogrt_scene_create(NULL, &s) == FOGRT_RESULT_OK && fogrt_scene_add_default(s) == FOGRT_RESULT_OK &&
        fogrt_scene_build(s, NULL) == FOGRT_RESULT_OK)
        by_power(s, "default scene (2 lights)");
    fogrt_scene_destroy(s);
    for (i = 0; i < 2; i++) {
        s = many_lights_box(i != 0);
        if (s) by_power(s, i ? "8 point lights, fog" : "8 point lights, no fog");
        fogrt_scene_destroy(s);
    }
#ifdef HAVE_FOGRT_LOAD
    if (spot) spot_scene(ref_spp);
#else
    (void)spot;
#endif
    if (lamp) lamp_scenes(ref_spp, lamp_spp);
    return 0;
}
