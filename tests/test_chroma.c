/* test_chroma.c - appendix G of fogrt.h, chromatic media: sigma_t per colour channel
   (fogrt_medium_desc.sigma_t_rgb), sampled with one hero channel per path and weighed by the
   channels' mean density (one-sample spectral MIS; fogrt.h, G, "Chromatic media").

   - The desc: every bad component refused with one line naming the field; equal components
     are grey fog, bit for bit; under FOGRT_NO_MEDIA any use refused naming the macro.
   - A chromatic white furnace (a closed box whose walls emit 1, fog of albedo 1 and a
     different sigma_t per channel): with the free flight alone (no light sampling, no
     roulette) every sample's three channels add up to exactly 3, each channel being that
     channel's path density over the channels' mean; each channel's mean is 1 within 4
     standard errors, also with the defaults (light sampling, MIS, expected emission,
     roulette) and with a channel that has no fog at all.
   - Negative control: the same paths weighed by the hero channel's density alone (the
     integrator's hero_pdf switch, which fogrt itself never sets) break the sum of 3 on almost
     every sample, and with a channel of sigma_t 0 leave another channel's mean biased
     (the hero without fog never collides, so the paths that scatter are missing from its
     share): both checks above must fail for it.
   - Absorbing chromatic fog against Beer-Lambert per channel: an emitter seen through a slab,
     Le_c exp(-sigma_t,c d) (every sample with expected emission; the mean with the paper's
     estimator), and a floor in the fog lit by a point light above it through the same fog,
     rho I / (4 pi) exp(-2 sigma_t,c) (shadow rays per channel; with expected emission, the
     light behind a collision makes every sample exact).
   - Each channel of a chromatic render equals the same channel of a grey render with that
     channel's sigma_t (image means, within 4 standard errors of 8 independent batches), in a
     spot-lit box (equiangular sampling, the glow, the footprint, the light behind collisions)
     and a lamp-lit box with emitting fog, with the defaults and with the paper's settings.
   Fixed seeds throughout.                                                                  */
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#include "unity.h"
#include "test_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void setUp(void) {}
void tearDown(void) {}

#ifdef FOGRT_NO_MEDIA
#define MEDIA_ONLY() TEST_IGNORE_MESSAGE("needs appendix G of fogrt.h: built with FOGRT_NO_MEDIA (or FOGRT_MINIMAL)")
#endif
/* The scenes with fog in a box, and the checks of every sample with expected emission, need
   appendices B and C too. */
#if defined(FOGRT_NO_MEDIA) || defined(FOGRT_NO_LAMPS_IN_FOG) || defined(FOGRT_NO_ESTIMATION)
#define BOX_FOG_SKIP 1
#define BOX_FOG_ONLY() TEST_IGNORE_MESSAGE("needs appendices B, C and G of fogrt.h: built with FOGRT_NO_LAMPS_IN_FOG, FOGRT_NO_ESTIMATION, FOGRT_NO_MEDIA or FOGRT_MINIMAL")
#endif

typedef struct log_record { int errors, warnings; char last[512]; } log_record;
static void record(fogrt_log_level level, const char *msg, void *user)
{
    log_record *r = (log_record *)user;
    if (level == FOGRT_LOG_ERROR) r->errors++;
    if (level == FOGRT_LOG_WARNING) r->warnings++;
    snprintf(r->last, sizeof r->last, "%s", msg);
}

/* ==========================================================================================
   The desc
   ========================================================================================== */
/* Negative, infinite and NaN components are refused with INVALID_MEDIUM and one logged
   line naming medium.sigma_t_rgb, leaving the medium as it was; a chromatic desc reads back
   with sigma_t its largest component; equal components are stored as grey fog. Under
   FOGRT_NO_MEDIA a non-zero sigma_t_rgb is refused (UNSUPPORTED, naming the macro). */
static void test_chroma_desc_validation(void)
{
    log_record log;
    fogrt_scene_desc sd;
    fogrt_scene *s = NULL;
    fogrt_medium_desc m, got;
    memset(&log, 0, sizeof log);
    memset(&sd, 0, sizeof sd);
    sd.logger.func = record; sd.logger.user_data = &log;
    CHECK_OK(fogrt_scene_create(&sd, &s));
    memset(&m, 0, sizeof m);
    m.sigma_t = 0.5f; m.albedo = v3(0.9f, 0.9f, 0.9f); m.g = 0.3f;
    CHECK_OK(fogrt_scene_set_medium(s, &m));
#ifndef FOGRT_NO_MEDIA
    {
        static const float bad[4] = {-1.0f, -1e-30f, INFINITY, NAN};
        int i, c;
        for (i = 0; i < 4; ++i)
            for (c = 0; c < 3; ++c) {
                fogrt_medium_desc b = m;
                char msg[600];
                b.sigma_t_rgb = v3(0.2f, 0.4f, 0.8f);
                if (c == 0) b.sigma_t_rgb.x = bad[i];
                if (c == 1) b.sigma_t_rgb.y = bad[i];
                if (c == 2) b.sigma_t_rgb.z = bad[i];
                log.errors = 0;
                TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_INVALID_MEDIUM, fogrt_scene_set_medium(s, &b));
                snprintf(msg, sizeof msg, "component %d = %g: the message '%s' should name medium.sigma_t_rgb", c, (double)bad[i], log.last);
                TEST_ASSERT_EQUAL_INT_MESSAGE(1, log.errors, msg);
                TEST_ASSERT_NOT_NULL_MESSAGE(strstr(log.last, "medium.sigma_t_rgb"), msg);
                fogrt_scene_get_medium(s, &got);
                TEST_ASSERT_TRUE_MESSAGE(memcmp(&got, &m, sizeof m) == 0, "a refused desc changed the medium");
            }
    }
    m.sigma_t = 0.0f; m.sigma_t_rgb = v3(0.0f, 0.7f, 0.2f);            /* replaces sigma_t, a channel may be clear */
    CHECK_OK(fogrt_scene_set_medium(s, &m));
    fogrt_scene_get_medium(s, &got);
    TEST_ASSERT_EQUAL_FLOAT(0.7f, got.sigma_t);
    TEST_ASSERT_TRUE(got.sigma_t_rgb.x == 0.0f && got.sigma_t_rgb.y == 0.7f && got.sigma_t_rgb.z == 0.2f);
    m.sigma_t = 9.0f; m.sigma_t_rgb = v3(0.25f, 0.25f, 0.25f);          /* equal: grey fog of 0.25 */
    CHECK_OK(fogrt_scene_set_medium(s, &m));
    fogrt_scene_get_medium(s, &got);
    TEST_ASSERT_EQUAL_FLOAT(0.25f, got.sigma_t);
    TEST_ASSERT_TRUE(got.sigma_t_rgb.x == 0.0f && got.sigma_t_rgb.y == 0.0f && got.sigma_t_rgb.z == 0.0f);
    TEST_ASSERT_EQUAL_INT(0, log.warnings);
#else
    m.sigma_t_rgb = v3(0.1f, 0.2f, 0.3f);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_UNSUPPORTED, fogrt_scene_set_medium(s, &m));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(log.last, "FOGRT_NO_MEDIA"), log.last);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(log.last, "sigma_t_rgb"), log.last);
    fogrt_scene_get_medium(s, &got);
    TEST_ASSERT_EQUAL_FLOAT(0.5f, got.sigma_t);
#endif
    fogrt_scene_destroy(s);
}

#ifndef FOGRT_NO_MEDIA
/* ==========================================================================================
   Scenes
   ========================================================================================== */
/* The box x, z in [-1, 1], y in [0, 2], every wall of the material, wound to face inward. */
static void add_walls(fogrt_scene *s, uint32_t mat)
{
    add_quad_corners(s, v3(-1, 0, -1), v3(-1, 0, 1), v3(1, 0, 1), v3(1, 0, -1), mat);     /* floor */
    add_quad_corners(s, v3(-1, 2, -1), v3(1, 2, -1), v3(1, 2, 1), v3(-1, 2, 1), mat);     /* ceiling */
    add_quad_corners(s, v3(-1, 0, -1), v3(1, 0, -1), v3(1, 2, -1), v3(-1, 2, -1), mat);   /* back */
    add_quad_corners(s, v3(-1, 0, 1), v3(-1, 2, 1), v3(1, 2, 1), v3(1, 0, 1), mat);       /* front */
    add_quad_corners(s, v3(-1, 0, -1), v3(-1, 2, -1), v3(-1, 2, 1), v3(-1, 0, 1), mat);   /* left */
    add_quad_corners(s, v3(1, 0, -1), v3(1, 0, 1), v3(1, 2, 1), v3(1, 2, -1), mat);       /* right */
}
static fogrt_medium_desc chroma_desc(fogrt_vec3 sigma, fogrt_vec3 albedo, float g)
{
    fogrt_medium_desc m;
    memset(&m, 0, sizeof m);
    m.sigma_t_rgb = sigma; m.albedo = albedo; m.g = g;
    return m;
}
/* The furnace: the box's walls emit 1 and reflect nothing, fog of albedo 1 fills it. */
static fogrt_scene *furnace(fogrt_vec3 sigma, float g)
{
    fogrt_scene *s = NULL;
    fogrt_medium_desc m = chroma_desc(sigma, v3(1, 1, 1), g);
    CHECK_OK(fogrt_scene_create(NULL, &s));
    add_walls(s, add_basic_material(s, FOGRT_BSDF_DIFFUSE, v3(0, 0, 0), v3(1, 1, 1)));
    CHECK_OK(fogrt_scene_set_medium(s, &m));
    set_camera(s, v3(0.1f, 0.9f, 0.05f), v3(0.6f, 1.3f, -0.7f), 60.0f);
    CHECK_OK(fogrt_scene_build(s, NULL));
    return s;
}

/* One sample of the full integrator along (o, d), with the hero channel's density alone in
   the weights when hero_pdf (the negative control); the same stream gives the same paths
   either way when nothing else (roulette, light sampling) depends on the weights. */
static fogrt_vec3 sample(const fogrt_scene *s, const fogrt_render_desc *rd, fogrt_vec3 o, fogrt_vec3 d, fogrt_rng *rng,
                         bool hero_pdf)
{
    fogrt__settings st;
    fogrt__xs xs;
    uint64_t rays = 0;
    CHECK_OK(fogrt__resolve_render(s, rd, &st, NULL));
    fogrt__full_settings(s, &st, &xs);
    xs.hero_pdf = hero_pdf;
    fogrt__walk w;
    fogrt__walk_start(&w, s, o, fogrt__normalize(d), rng, &rays);
    return fogrt__full_radiance_xs(s, &st, &xs, &w);
}
/* A direction of the camera's view cone (rows of a 16 x 12 image), for sample i. */
static void camera_ray(const fogrt_scene *s, long i, fogrt_vec3 *o, fogrt_vec3 *d)
{
    fogrt_camera_ray(s, 16, 12, (float)(i % 16) + 0.5f, (float)((i / 16) % 12) + 0.5f, 0.5f, 0.5f, o, d);
}
typedef struct channel_stats { double mean[3], se[3]; long n; } channel_stats;
static void stats_add(double *sum, double *sum2, fogrt_vec3 L)
{
    double l[3] = {L.x, L.y, L.z};
    int c;
    for (c = 0; c < 3; ++c) { sum[c] += l[c]; sum2[c] += l[c] * l[c]; }
}
static channel_stats stats_end(const double *sum, const double *sum2, long n)
{
    channel_stats r;
    int c;
    r.n = n;
    for (c = 0; c < 3; ++c) { r.mean[c] = sum[c] / n; r.se[c] = std_error_of_mean(sum[c], sum2[c], n); }
    return r;
}
/* Whether every channel's mean is want[c] within 4 standard errors; the message says how far. */
static bool channels_within(const char *what, const channel_stats *r, const double *want, bool quiet)
{
    bool ok = true;
    int c;
    for (c = 0; c < 3; ++c) {
        double z = r->se[c] > 0.0 ? (r->mean[c] - want[c]) / r->se[c] : (r->mean[c] == want[c] ? 0.0 : INFINITY);
        char msg[300];
        snprintf(msg, sizeof msg, "%s, channel %d: %.5f +- %.5f (%ld samples), expected %.5f (z %+.2f)", what, c, r->mean[c],
                 r->se[c], r->n, want[c], z);
        if (!quiet) TEST_MESSAGE(msg);
        if (!(fabs(z) <= 4.0)) ok = false;
    }
    return ok;
}

/* The free flight alone (no light sampling, roulette or depth limit, the paper's emission
   when the flight reaches a wall): each sample is the path's density in each channel over
   the channels' mean, so its channels add up to 3. Returns how many of n samples break
   that by more than 1e-4 (float rounding over a few hundred collisions stays near 1e-6),
   and their statistics. */
static long furnace_walk(const fogrt_scene *s, bool hero_pdf, long n, uint64_t seed, channel_stats *out)
{
    fogrt_render_desc rd = fogrt_render_paper_defaults();
    double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
    long i, broken = 0;
    fogrt_rng rng;
    rd.nee = false; rd.max_depth = -1; rd.rr_depth = 1 << 30;
    fogrt_rng_seed(&rng, seed, 1);
    for (i = 0; i < n; ++i) {
        fogrt_vec3 o, d, L;
        camera_ray(s, i, &o, &d);
        L = sample(s, &rd, o, d, &rng, hero_pdf);
        if (!(fabs((double)L.x + L.y + L.z - 3.0) <= 3e-4)) broken++;
        stats_add(sum, sum2, L);
    }
    *out = stats_end(sum, sum2, n);
    return broken;
}
#endif

/* ==========================================================================================
   The chromatic white furnace and its negative control
   ========================================================================================== */
/* sigma_t (0.4, 1.5, 4), albedo 1, g 0.5: every sample's channels add up to 3 and each
   channel's mean is 1; the hero's density alone breaks the sum on nearly every sample (the
   same paths: the same stream, nothing depends on the weights). */
static void test_chroma_furnace_every_sample(void)
{
#ifdef FOGRT_NO_MEDIA
    MEDIA_ONLY();
#else
    const double one[3] = {1, 1, 1};
    const long n = SAN_REDUCED(40000, 10);
    fogrt_scene *s = furnace(v3(0.4f, 1.5f, 4.0f), 0.5f);
    channel_stats r;
    char msg[300];
    long broken = furnace_walk(s, false, n, 11, &r);
    snprintf(msg, sizeof msg, "spectral MIS: %ld of %ld samples whose channels do not add up to 3", broken, n);
    TEST_MESSAGE(msg);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, broken, msg);
    TEST_ASSERT_TRUE_MESSAGE(channels_within("spectral MIS, furnace (0.4, 1.5, 4)", &r, one, false), "a channel's mean is not 1");
    broken = furnace_walk(s, true, n, 11, &r);
    snprintf(msg, sizeof msg, "negative control (the hero's density alone): %ld of %ld samples whose channels do not add up to 3 "
             "(must be most of them)", broken, n);
    TEST_MESSAGE(msg);
    TEST_ASSERT_TRUE_MESSAGE(broken > n / 2, msg);
    fogrt_scene_destroy(s);
#endif
}

/* A channel without fog (sigma_t 0, 1, 3): spectral MIS keeps every mean at 1; the hero's
   density alone leaves channel 1 (and 2) short, since a hero without fog never collides and
   its paths cannot carry their share of the scattered light. */
static void test_chroma_furnace_clear_channel(void)
{
#ifdef FOGRT_NO_MEDIA
    MEDIA_ONLY();
#else
    const double one[3] = {1, 1, 1};
    const long n = SAN_REDUCED(40000, 10);
    fogrt_scene *s = furnace(v3(0.0f, 1.0f, 3.0f), -0.3f);
    channel_stats r;
    char msg[300];
    long broken = furnace_walk(s, false, n, 12, &r);
    snprintf(msg, sizeof msg, "spectral MIS, a clear channel: %ld of %ld samples whose channels do not add up to 3", broken, n);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, broken, msg);
    TEST_ASSERT_TRUE_MESSAGE(channels_within("spectral MIS, furnace (0, 1, 3)", &r, one, false), "a channel's mean is not 1");
    (void)furnace_walk(s, true, n, 12, &r);
    TEST_ASSERT_FALSE_MESSAGE(channels_within("negative control (the hero's density alone), furnace (0, 1, 3)", &r, one, false),
                              "negative control: the hero's density alone was not caught by the channels' means");
    fogrt_scene_destroy(s);
#endif
}

/* The same furnaces with the defaults (light sampling with MIS, expected emission, the
   roulette) and with the paper's settings: every channel's mean is 1. */
static void test_chroma_furnace_defaults(void)
{
#ifdef FOGRT_NO_MEDIA
    MEDIA_ONLY();
#else
    static const float sig[2][3] = {{0.4f, 1.5f, 4.0f}, {0.0f, 1.0f, 3.0f}};
    const double one[3] = {1, 1, 1};
    const long n = SAN_REDUCED(20000, 10);
    int k, paper;
    for (k = 0; k < 2; ++k)
        for (paper = 0; paper < 2; ++paper) {
            fogrt_scene *s = furnace(v3(sig[k][0], sig[k][1], sig[k][2]), 0.5f);
            fogrt_render_desc rd = paper ? fogrt_render_paper_defaults() : fogrt_render_defaults();
            double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
            channel_stats r;
            char what[120];
            fogrt_rng rng;
            long i;
            rd.max_depth = -1;
            fogrt_rng_seed(&rng, 20 + (uint64_t)(2 * k + paper), 1);
            for (i = 0; i < n; ++i) {
                fogrt_vec3 o, d;
                camera_ray(s, i, &o, &d);
                stats_add(sum, sum2, fogrt_trace(s, &rd, o, d, &rng, NULL));
            }
            r = stats_end(sum, sum2, n);
            snprintf(what, sizeof what, "%s, furnace (%g, %g, %g)", paper ? "paper" : "defaults", (double)sig[k][0],
                     (double)sig[k][1], (double)sig[k][2]);
            TEST_ASSERT_TRUE_MESSAGE(channels_within(what, &r, one, false), what);
            fogrt_scene_destroy(s);
        }
#endif
}

/* ==========================================================================================
   Absorbing chromatic fog: Beer-Lambert per channel
   ========================================================================================== */
#ifndef BOX_FOG_SKIP
#define ABS_SIGMA_R 0.3f
#define ABS_SIGMA_G 1.0f
#define ABS_SIGMA_B 2.5f
/* Fog of albedo 0 in the slab lo.y < y < hi.y (a box 100 wide), the camera at `eye`
   looking at `at` with a view 0.1 degrees wide, so that every ray crosses the slab within
   1e-6 of the same length. */
static fogrt_scene *absorbing(fogrt_vec3 lo, fogrt_vec3 hi, fogrt_vec3 eye, fogrt_vec3 at, fogrt_vec3 up)
{
    fogrt_scene *s = NULL;
    fogrt_medium_desc m = chroma_desc(v3(ABS_SIGMA_R, ABS_SIGMA_G, ABS_SIGMA_B), v3(0, 0, 0), 0.0f);
    fogrt_camera_desc cam;
    CHECK_OK(fogrt_scene_create(NULL, &s));
    m.bounded = true; m.bounds_min = lo; m.bounds_max = hi;
    CHECK_OK(fogrt_scene_set_medium(s, &m));
    memset(&cam, 0, sizeof cam);
    cam.position = eye; cam.look_at = at; cam.up = up; cam.fov_deg = 0.1f;
    CHECK_OK(fogrt_scene_set_camera(s, &cam));
    return s;
}
/* Every pixel of a render of spp samples within rel of want (per channel), or (paper) the
   image's channel means within 4 standard errors of 8 batches. */
static void check_image(const char *what, const fogrt_scene *s, bool paper, const double *want, double rel)
{
    fogrt_render_desc rd = paper ? fogrt_render_paper_defaults() : fogrt_render_defaults();
    double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
    fogrt_image img;
    float rgb[3 * 8 * 8];
    int b, p, c;
    CHECK_OK(fogrt_image_alloc(&img, 8, 8, NULL));
    for (b = 0; b < (paper ? 8 : 1); ++b) {
        double m[3] = {0, 0, 0};
        char msg[300];
        rd.seed = 300 + (uint64_t)b;
        fogrt_image_clear(&img);
        CHECK_OK(fogrt_render(s, &rd, &img, paper ? 64 : 4, NULL));
        fogrt_image_resolve(&img, rgb);
        for (p = 0; p < 64; ++p)
            for (c = 0; c < 3; ++c) {
                m[c] += rgb[3 * p + c] / 64.0;
                snprintf(msg, sizeof msg, "%s: pixel %d channel %d is %.7f, expected %.7f", what, p, c, (double)rgb[3 * p + c], want[c]);
                if (!paper) TEST_ASSERT_TRUE_MESSAGE(fabs(rgb[3 * p + c] - want[c]) <= rel * want[c], msg);
            }
        for (c = 0; c < 3; ++c) { sum[c] += m[c]; sum2[c] += m[c] * m[c]; }
    }
    fogrt_image_free(&img);
    if (paper) {
        channel_stats r = stats_end(sum, sum2, 8);
        TEST_ASSERT_TRUE_MESSAGE(channels_within(what, &r, want, false), what);
    } else {
        char msg[300];
        snprintf(msg, sizeof msg, "%s: every sample (%.6f, %.6f, %.6f) to %.0e", what, want[0], want[1], want[2], rel);
        TEST_MESSAGE(msg);
    }
}
#endif

/* An emitter (Le 1, 2, 3) seen through a slab of absorbing fog 0.7 thick: Le_c exp(-0.7
   sigma_t,c). Expected emission adds T_c Le to every sample; the paper's estimator adds Le
   when the flight gets through, weighed by T_c over the channels' mean T. */
static void test_chroma_absorbing_slab(void)
{
#ifdef BOX_FOG_SKIP
    BOX_FOG_ONLY();
#else
    const double d = 0.7, want[3] = {1.0 * exp(-d * ABS_SIGMA_R), 2.0 * exp(-d * ABS_SIGMA_G), 3.0 * exp(-d * ABS_SIGMA_B)};
    fogrt_scene *s = absorbing(v3(-50, -50, 2.0f), v3(50, 50, 2.7f), v3(0, 0, 0), v3(0, 0, 1), v3(0, 1, 0));
    add_quad_corners(s, v3(-10, -10, 5), v3(-10, 10, 5), v3(10, 10, 5), v3(10, -10, 5),
                     add_basic_material(s, FOGRT_BSDF_DIFFUSE, v3(0, 0, 0), v3(1, 2, 3)));   /* faces -z, the camera */
    CHECK_OK(fogrt_scene_build(s, NULL));
    check_image("emitter through absorbing fog, defaults", s, false, want, 2e-6);
    check_image("emitter through absorbing fog, paper", s, true, want, 0.0);
    fogrt_scene_destroy(s);
#endif
}

/* A white floor (rho 0.5) under a slab of absorbing fog 1 thick (0 < y < 1), a point light
   of intensity 1 at y = 2 above it and the camera at y = 3 looking straight down: the
   floor's radiance rho / pi I / 2^2 times T_c(1) on the shadow ray and T_c(1) on the camera
   ray, rho I / (4 pi) exp(-2 sigma_t,c). With the defaults every sample gives it: behind a
   collision the lamp's light at the floor counts T_c (b'), and where the flight reaches the
   floor its T_c / m over the lamp scale m; with the paper's settings the mean does. */
static void test_chroma_absorbing_shadow_ray(void)
{
#ifdef BOX_FOG_SKIP
    BOX_FOG_ONLY();
#else
    const double k = 0.5 / (4.0 * 3.14159265358979323846);
    const double want[3] = {k * exp(-2.0 * ABS_SIGMA_R), k * exp(-2.0 * ABS_SIGMA_G), k * exp(-2.0 * ABS_SIGMA_B)};
    fogrt_scene *s = absorbing(v3(-50, 0, -50), v3(50, 1, 50), v3(0, 3, 0), v3(0, 0, 0), v3(0, 0, 1));
    fogrt_light_desc l;
    add_quad_corners(s, v3(-10, 0, -10), v3(-10, 0, 10), v3(10, 0, 10), v3(10, 0, -10),
                     add_basic_material(s, FOGRT_BSDF_DIFFUSE, v3(0.5f, 0.5f, 0.5f), v3(0, 0, 0)));
    memset(&l, 0, sizeof l);
    l.type = FOGRT_LIGHT_POINT; l.position = v3(0, 2, 0); l.intensity = v3(1, 1, 1);
    CHECK_OK(fogrt_scene_add_light(s, &l));
    CHECK_OK(fogrt_scene_build(s, NULL));
    check_image("floor lit through absorbing fog, defaults", s, false, want, 2e-5);
    check_image("floor lit through absorbing fog, paper", s, true, want, 0.0);
    fogrt_scene_destroy(s);
#endif
}

/* ==========================================================================================
   Each channel is its own grey fog
   ========================================================================================== */
#ifndef BOX_FOG_SKIP
/* A closed box in fog (below y = 1.5, as tests/test_media.c's phase_box, so that no fog point
   comes near a lamp), lit by a spot light (lamp = 0) or by its ceiling lamp, with the fog's
   sigma_t per channel or grey, and its emission. */
static fogrt_scene *lit_box(float lamp, fogrt_vec3 sigma, float grey, fogrt_vec3 emission)
{
    fogrt_scene *s = NULL;
    fogrt_medium_desc m = chroma_desc(sigma, v3(0.8f, 0.85f, 0.9f), 0.6f);
    CHECK_OK(fogrt_scene_create(NULL, &s));
    add_closed_box(s, 0.4f, lamp);
    if (!(lamp > 0.0f)) {
        fogrt_light_desc l;
        memset(&l, 0, sizeof l);
        l.type = FOGRT_LIGHT_SPOT; l.position = v3(-0.6f, 1.8f, -0.3f); l.direction = v3(0.7f, -1.6f, 0.2f);
        l.intensity = v3(3, 3, 3); l.cutoff_deg = 25; l.beam_deg = 18;
        CHECK_OK(fogrt_scene_add_light(s, &l));
    }
    m.sigma_t = grey; m.emission = emission;
    m.bounded = true; m.bounds_min = v3(-1, 0, -1); m.bounds_max = v3(1, 1.5f, 1);
    CHECK_OK(fogrt_scene_set_medium(s, &m));
    set_camera(s, v3(0, 1.0f, 0.95f), v3(0, 0.9f, -1), 60.0f);
    CHECK_OK(fogrt_scene_build(s, NULL));
    return s;
}
/* The image's channel means over 8 batches of spp (different seeds), and their standard
   errors from the batches' spread. */
static channel_stats batch_means(const fogrt_scene *s, const fogrt_render_desc *rd_in, int spp, uint64_t seed)
{
    fogrt_render_desc rd = *rd_in;
    double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
    fogrt_image img;
    float rgb[3 * 16 * 12];
    int b, p;
    CHECK_OK(fogrt_image_alloc(&img, 16, 12, NULL));
    for (b = 0; b < 8; ++b) {
        double m[3] = {0, 0, 0};
        rd.seed = seed + (uint64_t)b;
        fogrt_image_clear(&img);
        CHECK_OK(fogrt_render(s, &rd, &img, spp, NULL));
        TEST_ASSERT_EQUAL_UINT64(0, img.rejected);
        fogrt_image_resolve(&img, rgb);
        for (p = 0; p < 16 * 12; ++p) { m[0] += rgb[3 * p] / 192.0; m[1] += rgb[3 * p + 1] / 192.0; m[2] += rgb[3 * p + 2] / 192.0; }
        stats_add(sum, sum2, v3((float)m[0], (float)m[1], (float)m[2]));
    }
    fogrt_image_free(&img);
    return stats_end(sum, sum2, 8);
}
/* Channel c of the chromatic render against channel c of the grey render of sigma_t[c],
   within 4 combined standard errors, each below 5% of the chromatic mean (the test's power;
   in the sanitizers' reduced variant, with a quarter of the samples, 10%). */
static void channels_agree(const char *what, float lamp, fogrt_vec3 emission, bool paper, int full_spp)
{
    const int spp = SAN_REDUCED(full_spp, 4);
    const double power = 0.05 * sqrt((double)full_spp / spp);
    const float sig[3] = {0.3f, 0.9f, 2.0f};
    fogrt_render_desc rd = paper ? fogrt_render_paper_defaults() : fogrt_render_defaults();
    fogrt_scene *s = lit_box(lamp, v3(sig[0], sig[1], sig[2]), 0.0f, emission);
    channel_stats chroma = batch_means(s, &rd, spp, 1000), grey;
    int c;
    fogrt_scene_destroy(s);
    for (c = 0; c < 3; ++c) {
        double z;
        char msg[300];
        s = lit_box(lamp, v3(0, 0, 0), sig[c], emission);
        grey = batch_means(s, &rd, spp, 2000 + 100 * (uint64_t)c);
        fogrt_scene_destroy(s);
        z = (chroma.mean[c] - grey.mean[c]) / sqrt(chroma.se[c] * chroma.se[c] + grey.se[c] * grey.se[c]);
        snprintf(msg, sizeof msg, "%s, %s, channel %d: chromatic %.5f +- %.5f, grey sigma_t %g %.5f +- %.5f (z %+.2f)", what,
                 paper ? "paper" : "defaults", c, chroma.mean[c], chroma.se[c], (double)sig[c], grey.mean[c], grey.se[c], z);
        TEST_MESSAGE(msg);
        TEST_ASSERT_TRUE_MESSAGE(fabs(z) <= 4.0 && chroma.se[c] < power * chroma.mean[c], msg);
    }
}
#endif

/* sigma_t (0.3, 0.9, 2) against grey 0.3, 0.9 and 2, channel by channel: a spot-lit box
   (equiangular sampling with the phase function, the glow and footprint, the light behind
   collisions, all reading the per-channel T) and a lamp-lit box with emitting fog (light
   sampling, MIS, expected emission, the fog's emission per channel). */
static void test_chroma_channels_are_grey_fogs(void)
{
#ifdef BOX_FOG_SKIP
    BOX_FOG_ONLY();
#else
    int paper;
    for (paper = 0; paper < 2; ++paper) {
        channels_agree("spot-lit box", 0.0f, v3(0, 0, 0), paper != 0, paper ? 32 : 16);
        channels_agree("lamp-lit box, emitting fog", 6.0f, v3(0.4f, 0.3f, 0.2f), paper != 0, paper ? 32 : 16);
    }
#endif
}

/* sigma_t_rgb with three equal components renders the grey fog of that sigma_t bit for bit. */
static void test_chroma_equal_channels_are_grey(void)
{
#ifdef BOX_FOG_SKIP
    BOX_FOG_ONLY();
#else
    fogrt_scene *a = lit_box(0.0f, v3(0.7f, 0.7f, 0.7f), 0.0f, v3(0, 0, 0)), *b = lit_box(0.0f, v3(0, 0, 0), 0.7f, v3(0, 0, 0));
    fogrt_render_desc rd = fogrt_render_defaults();
    fogrt_image ia, ib;
    CHECK_OK(fogrt_image_alloc(&ia, 16, 12, NULL));
    CHECK_OK(fogrt_image_alloc(&ib, 16, 12, NULL));
    rd.seed = 9;
    CHECK_OK(fogrt_render(a, &rd, &ia, 8, NULL));
    CHECK_OK(fogrt_render(b, &rd, &ib, 8, NULL));
    TEST_ASSERT_TRUE_MESSAGE(memcmp(ia.sum, ib.sum, sizeof(double) * 3 * 16 * 12) == 0, "equal channels do not render grey fog bit for bit");
    TEST_ASSERT_FALSE(a->x->world.chroma);
    fogrt_image_free(&ia); fogrt_image_free(&ib);
    fogrt_scene_destroy(a); fogrt_scene_destroy(b);
#endif
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_chroma_desc_validation);
    RUN_TEST(test_chroma_furnace_every_sample);
    RUN_TEST(test_chroma_furnace_clear_channel);
    RUN_TEST(test_chroma_furnace_defaults);
    RUN_TEST(test_chroma_absorbing_slab);
    RUN_TEST(test_chroma_absorbing_shadow_ray);
    RUN_TEST(test_chroma_channels_are_grey_fogs);
    RUN_TEST(test_chroma_equal_channels_are_grey);
    return UNITY_END();
}
