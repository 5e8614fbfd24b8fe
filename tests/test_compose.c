/* test_compose.c - every feature composes with every other: one Algorithm 1 runs a scene
   that combines Part II's samplers with media inside shapes, and its image agrees with an
   independent estimate of the same image.

   Each comparison renders both sides several times with fixed, distinct seeds and compares
   the means of the runs, their standard errors taken from the spread of the runs (not from
   the renderer's own error estimate), |z| < 4.5 per channel (a false alarm about once in
   150000 comparisons; the seeds are fixed, so a run repeats exactly).
     - A spot lamp in fog bounded to a box, smoke inside a glass sphere, an environment map:
       the defaults (equiangular sampling, the glow and footprint, the light behind fog
       collisions, expected emission, environment-map sampling, the roulette's pilot) against
       the plain estimators of the same loop (free flight, light sampling with MIS, BSDF and
       phase sampling), which share none of B's samplers. The control: without the smoke the
       image is told apart.
     - Chromatic fog bounded to a part of a closed room, with a fog-filled interface sphere:
       each channel against the same scene in grey fog of that channel's sigma_t (no hero
       channel at all), an estimate that shares nothing of G's spectral weights.
     - An emitting medium inside an interface sphere, in world fog lit by a point lamp, with
       equiangular sampling on: the defaults against the plain estimators.
   And the render's list of samplers names what ran in each. */
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#include "unity.h"
#include "test_util.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

void setUp(void) {}
void tearDown(void) {}

#if defined(FOGRT_NO_SHAPES) || defined(FOGRT_NO_ESTIMATION) || defined(FOGRT_NO_LAMPS_IN_FOG)
#define COMPOSE_ONLY() TEST_IGNORE_MESSAGE("needs appendices B, C, G and H of fogrt.h: built without one of them")
#else
#define COMPOSE_ONLY() ((void)0)

#define RUNS 8

typedef struct spread { double mean[3], se[3]; } spread;

/* The mean colour of RUNS renders of w x h pixels, spp samples each, seeds seed0 + run, and
   the standard error of that mean from the runs' spread. */
static spread render_runs(const fogrt_scene *s, const fogrt_render_desc *d, int w, int h, int spp, uint64_t seed0)
{
    spread r;
    double sum[3] = { 0, 0, 0 }, sum2[3] = { 0, 0, 0 };
    for (int run = 0; run < RUNS; ++run) {
        fogrt_render_desc rd = *d;
        fogrt_image img;
        double m[3] = { 0, 0, 0 };
        rd.seed = seed0 + (uint64_t)run;
        CHECK_OK(fogrt_image_alloc(&img, w, h, NULL));
        CHECK_OK(fogrt_render(s, &rd, &img, SAN_REDUCED(spp, 4), NULL));
        for (int p = 0; p < w * h; ++p)
            for (int c = 0; c < 3; ++c) m[c] += img.sum[3 * p + c] / (double)img.count[p] / (w * h);
        fogrt_image_free(&img);
        for (int c = 0; c < 3; ++c) {
            sum[c] += m[c];
            sum2[c] += m[c] * m[c];
        }
    }
    for (int c = 0; c < 3; ++c) {
        r.mean[c] = sum[c] / RUNS;
        r.se[c] = std_error_of_mean(sum[c], sum2[c], RUNS);
    }
    return r;
}
/* |z| of channel c between two spreads. */
static double z_of(const spread *a, const spread *b, int c)
{
    double se = sqrt(a->se[c] * a->se[c] + b->se[c] * b->se[c]);
    return fabs(a->mean[c] - b->mean[c]) / fmax(se, 1e-12);
}
/* Every channel of a and b agrees (|z| < 4.5), each channel reported. */
static void check_agree(const char *what, const spread *a, const spread *b)
{
    for (int c = 0; c < 3; ++c) {
        char msg[240];
        snprintf(msg, sizeof msg, "%s, channel %d: %.5f +- %.5f against %.5f +- %.5f, z = %.2f", what, c, a->mean[c],
                 a->se[c], b->mean[c], b->se[c], z_of(a, b, c));
        TEST_MESSAGE(msg);
        TEST_ASSERT_TRUE_MESSAGE(a->mean[c] > 0.0 && b->mean[c] > 0.0, msg);
        TEST_ASSERT_TRUE_MESSAGE(z_of(a, b, c) < 4.5, msg);
    }
}
/* The defaults without B's samplers and C's choice of lights: the paper's estimators in the
   same loop. */
static fogrt_render_desc plain_desc(void)
{
    fogrt_render_desc d = fogrt_render_defaults();
    d.equiangular = false;
    d.glow = false;
    d.footprint = false;
    d.expected_emission = false;
    d.light_by_power = false;
    return d;
}
static void check_samplers(const fogrt_scene *s, const fogrt_render_desc *d, const char *const *names)
{
    char buf[512];
    fogrt_render_samplers(s, d, buf, sizeof buf);
    TEST_MESSAGE(buf);
    for (; *names; ++names) TEST_ASSERT_NOT_NULL_MESSAGE(strstr(buf, *names), *names);
}
static fogrt_medium_desc medium(float sigma_t, float albedo, float g)
{
    fogrt_medium_desc m;
    memset(&m, 0, sizeof m);
    m.sigma_t = sigma_t;
    m.albedo = v3(albedo, albedo, albedo);
    m.g = g;
    return m;
}
static uint32_t add_clear_material(fogrt_scene *s, fogrt_bsdf_type type)
{
    fogrt_material_desc m;
    uint32_t id = 0;
    memset(&m, 0, sizeof m);
    m.type = type;
    m.ior = 1.5f;
    m.reflectance = v3(1, 1, 1);
    m.transmittance = v3(1, 1, 1);
    CHECK_OK(fogrt_scene_add_material(s, &m, &id));
    return id;
}

/* The open scene of the first check: a floor and a back wall under an environment map, a
   spot lamp above a glass sphere (smoke inside unless empty), fog in a box around them. */
static fogrt_scene *spot_scene(bool smoke)
{
    fogrt_scene *s = NULL;
    CHECK_OK(fogrt_scene_create(NULL, &s));
    uint32_t grey = add_basic_material(s, FOGRT_BSDF_DIFFUSE, v3(0.6f, 0.6f, 0.6f), v3(0, 0, 0));
    add_quad_corners(s, v3(-2, 0, -2), v3(-2, 0, 2), v3(2, 0, 2), v3(2, 0, -2), grey);
    add_quad_corners(s, v3(-2, 0, -2), v3(2, 0, -2), v3(2, 2.5f, -2), v3(-2, 2.5f, -2), grey);
    CHECK_OK(fogrt_scene_add_sphere(s, v3(0.0f, 0.6f, 0.0f), 0.45f, add_clear_material(s, FOGRT_BSDF_GLASS)));
    if (smoke) {
        fogrt_medium_desc m = medium(5.0f, 0.5f, 0.3f);
        CHECK_OK(fogrt_scene_set_interior(s, FOGRT_SHAPE_SPHERE, 0, &m));
    }
    fogrt_light_desc l;
    memset(&l, 0, sizeof l);
    l.type = FOGRT_LIGHT_SPOT;
    l.position = v3(0.3f, 2.0f, 0.2f);
    l.direction = v3(-0.15f, -1.0f, -0.1f);
    l.intensity = v3(6.0f, 6.0f, 6.0f);
    l.cutoff_deg = 30.0f;
    l.beam_deg = 20.0f;
    CHECK_OK(fogrt_scene_add_light(s, &l));
    float sky[8 * 4 * 3];
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x) {
            float *p = &sky[3 * (y * 8 + x)];
            p[0] = 0.2f + 0.1f * (float)x;
            p[1] = 0.3f + 0.2f * (float)(3 - y);
            p[2] = 0.8f - 0.05f * (float)x;
        }
    CHECK_OK(fogrt_scene_set_environment_map(s, 8, 4, sky, 1.0f));
    fogrt_medium_desc fog = medium(0.5f, 0.9f, 0.5f);
    fog.bounded = true;
    fog.bounds_min = v3(-1.5f, 0.0f, -1.5f);
    fog.bounds_max = v3(1.5f, 2.2f, 1.5f);
    CHECK_OK(fogrt_scene_set_medium(s, &fog));
    set_camera(s, v3(0.0f, 1.1f, 3.6f), v3(0.0f, 0.6f, 0.0f), 45.0f);
    CHECK_OK(fogrt_scene_build(s, NULL));
    return s;
}
#endif

static void test_spot_lamp_smoke_in_glass_environment_map(void)
{
    COMPOSE_ONLY();
#ifndef FOGRT_NO_SHAPES
    fogrt_scene *s = spot_scene(true), *empty = spot_scene(false);
    fogrt_render_desc full = fogrt_render_defaults(), plain = plain_desc();
    const char *const names[] = { "fog in a box", "media in shapes", "equiangular", "environment-map sampling",
                                  "light behind collisions", "glow", NULL };
    check_samplers(s, &full, names);
    spread a = render_runs(s, &full, 24, 18, 32, 100);
    spread b = render_runs(s, &plain, 24, 18, 32, 200);
    check_agree("spot lamp, smoke in glass, environment map: defaults against plain estimators", &a, &b);
    spread e = render_runs(empty, &full, 24, 18, 32, 300);
    char msg[200];
    snprintf(msg, sizeof msg, "control: the empty glass sphere %.5f, with smoke %.5f, z = %.2f (must be told apart)",
             e.mean[1], a.mean[1], z_of(&a, &e, 1));
    TEST_MESSAGE(msg);
    TEST_ASSERT_TRUE_MESSAGE(z_of(&a, &e, 1) > 4.5, msg);
    fogrt_scene_destroy(s);
    fogrt_scene_destroy(empty);
#endif
}

#ifndef FOGRT_NO_SHAPES
/* A closed room with its ceiling lamp, fog in the lower part of it (sigma_t per channel, or
   grey), and an interface sphere of grey fog in it. */
static fogrt_scene *room_scene(fogrt_vec3 sigma_rgb, float grey_sigma)
{
    fogrt_scene *s = NULL;
    CHECK_OK(fogrt_scene_create(NULL, &s));
    (void)add_closed_box(s, 0.3f, 12.0f);
    CHECK_OK(fogrt_scene_add_sphere(s, v3(0.2f, 0.6f, -0.1f), 0.4f, add_clear_material(s, FOGRT_BSDF_DIFFUSE)));
    uint32_t iface = add_clear_material(s, FOGRT_BSDF_INTERFACE);
    CHECK_OK(fogrt_scene_set_shape_material(s, FOGRT_SHAPE_SPHERE, 0, iface));
    fogrt_medium_desc in = medium(2.5f, 0.8f, 0.4f);
    CHECK_OK(fogrt_scene_set_interior(s, FOGRT_SHAPE_SPHERE, 0, &in));
    fogrt_medium_desc fog = medium(grey_sigma, 0.9f, 0.3f);
    fog.sigma_t_rgb = sigma_rgb;
    fog.bounded = true;
    fog.bounds_min = v3(-1.0f, 0.0f, -1.0f);
    fog.bounds_max = v3(1.0f, 1.3f, 1.0f);
    CHECK_OK(fogrt_scene_set_medium(s, &fog));
    set_camera(s, v3(0.0f, 1.0f, 0.95f), v3(0.0f, 0.7f, -1.0f), 70.0f);
    CHECK_OK(fogrt_scene_build(s, NULL));
    return s;
}
#endif

static void test_chromatic_fog_in_a_box_with_a_fog_filled_interface(void)
{
    COMPOSE_ONLY();
#if !defined(FOGRT_NO_SHAPES) && !defined(FOGRT_NO_MEDIA)
    const float sigma[3] = { 0.4f, 1.0f, 2.2f };
    fogrt_scene *s = room_scene(v3(sigma[0], sigma[1], sigma[2]), 0.0f);
    fogrt_render_desc full = fogrt_render_defaults();
    const char *const names[] = { "fog in a box", "media in shapes", "hero channel", NULL };
    check_samplers(s, &full, names);
    spread a = render_runs(s, &full, 20, 15, 24, 400);
    for (int c = 0; c < 3; ++c) {
        fogrt_scene *g = room_scene(v3(0, 0, 0), sigma[c]);
        spread b = render_runs(g, &full, 20, 15, 24, 500 + 10 * (uint64_t)c);
        char msg[240];
        snprintf(msg, sizeof msg, "chromatic fog, channel %d: %.5f +- %.5f; grey fog of its sigma_t %.3f: %.5f +- %.5f, z = %.2f",
                 c, a.mean[c], a.se[c], (double)sigma[c], b.mean[c], b.se[c], z_of(&a, &b, c));
        TEST_MESSAGE(msg);
        TEST_ASSERT_TRUE_MESSAGE(z_of(&a, &b, c) < 4.5, msg);
        fogrt_scene_destroy(g);
    }
    fogrt_scene_destroy(s);
#endif
}

static void test_emitting_medium_in_a_shape_with_equiangular_sampling(void)
{
    COMPOSE_ONLY();
#if !defined(FOGRT_NO_SHAPES) && !defined(FOGRT_NO_MEDIA)
    fogrt_scene *s = NULL;
    CHECK_OK(fogrt_scene_create(NULL, &s));
    (void)add_closed_box(s, 0.0f, 0.0f);
    CHECK_OK(fogrt_scene_add_sphere(s, v3(-0.2f, 0.7f, -0.2f), 0.35f, add_clear_material(s, FOGRT_BSDF_DIFFUSE)));
    CHECK_OK(fogrt_scene_set_shape_material(s, FOGRT_SHAPE_SPHERE, 0, add_clear_material(s, FOGRT_BSDF_INTERFACE)));
    fogrt_medium_desc glow = medium(3.0f, 0.5f, 0.0f);
    glow.emission = v3(2.0f, 1.0f, 0.4f);
    CHECK_OK(fogrt_scene_set_interior(s, FOGRT_SHAPE_SPHERE, 0, &glow));
    fogrt_light_desc l;
    memset(&l, 0, sizeof l);
    l.type = FOGRT_LIGHT_POINT;
    l.position = v3(0.4f, 1.5f, 0.1f);
    l.intensity = v3(2.0f, 2.0f, 2.0f);
    CHECK_OK(fogrt_scene_add_light(s, &l));
    fogrt_medium_desc fog = medium(0.6f, 0.85f, 0.4f);
    CHECK_OK(fogrt_scene_set_medium(s, &fog));
    set_camera(s, v3(0.0f, 1.0f, 0.95f), v3(0.0f, 0.8f, -1.0f), 70.0f);
    CHECK_OK(fogrt_scene_build(s, NULL));
    fogrt_render_desc full = fogrt_render_defaults(), plain = plain_desc();
    const char *const names[] = { "media in shapes", "equiangular", "glow", NULL };
    check_samplers(s, &full, names);
    spread a = render_runs(s, &full, 20, 15, 32, 600);
    spread b = render_runs(s, &plain, 20, 15, 32, 700);
    check_agree("emitting medium in a sphere, lamp in fog: defaults against plain estimators", &a, &b);
    fogrt_scene_destroy(s);
#endif
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_spot_lamp_smoke_in_glass_environment_map);
    RUN_TEST(test_chromatic_fog_in_a_box_with_a_fog_filled_interface);
    RUN_TEST(test_emitting_medium_in_a_shape_with_equiangular_sampling);
    return UNITY_END();
}
