/* test_furnace.c - white furnace tests: whole renders with a known answer.

   The scene is a closed box whose inner walls emit radiance 1 and (mostly) reflect nothing,
   filled with fog, with the camera inside. If the fog does not absorb (albedo 1), L = 1
   everywhere solves the transfer equation: what a ray loses to out-scattering, sigma_s L,
   it gains back by in-scattering, sigma_s L times the phase function's integral, 1. So every
   pixel must be 1 for every sigma_t and g, whatever the integrator does (NEE on or off, MIS
   on or off), as long as it is unbiased. Variants: absorbing fog is darker; walls of albedo
   rho that also emit 1 give 1 / (1 - rho); a non-absorbing glass sphere is invisible.
   See docs/sampling-notes.md (f). */
/* Public API only: make test links this program with one shared build of the
   implementation (compiled with FOGRT_TESTS_SHARED_IMPL) instead of compiling it again. */
#ifndef FOGRT_TESTS_SHARED_IMPL
#define FOGRT_IMPLEMENTATION
#endif
#include "fogrt.h"
#include "unity.h"
#include "test_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void setUp(void) {}
void tearDown(void) {}

/* ---- scene building ------------------------------------------------------------------- */

/* Adds the six faces of the box [-h,h]^3 as 12 triangles. inward = true winds every face
   counter-clockwise as seen from inside, so the front side (the emitting side) faces the
   centre. */
static void add_box(fogrt_scene *scene, float h, uint32_t material, bool inward)
{
    float pos[6 * 4 * 3];
    uint32_t idx[6 * 6];
    int axis, side, f = 0;
    for (axis = 0; axis < 3; ++axis) {
        for (side = -1; side <= 1; side += 2, ++f) {
            int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3, k;
            /* e1 x e2 = +axis, so (e1, e2) winds the face with its front toward +axis. The
               face at side -1 faces the centre when its front is +axis. */
            bool front_plus = (side < 0) == inward;
            int ea = front_plus ? a1 : a2, eb = front_plus ? a2 : a1;
            float corner[3], *p = pos + 12 * f;
            corner[axis] = (float)side * h; corner[a1] = -h; corner[a2] = -h;
            for (k = 0; k < 4; ++k) {   /* corner, +ea, +ea+eb, +eb */
                p[3 * k + 0] = corner[0]; p[3 * k + 1] = corner[1]; p[3 * k + 2] = corner[2];
                if (k == 1 || k == 2) p[3 * k + ea] += 2.0f * h;
                if (k == 2 || k == 3) p[3 * k + eb] += 2.0f * h;
            }
            idx[6 * f + 0] = 4 * f; idx[6 * f + 1] = 4 * f + 1; idx[6 * f + 2] = 4 * f + 2;
            idx[6 * f + 3] = 4 * f; idx[6 * f + 4] = 4 * f + 2; idx[6 * f + 5] = 4 * f + 3;
        }
    }
    {
        fogrt_mesh_desc md;
        memset(&md, 0, sizeof md);
        md.positions = pos; md.vertex_count = 24;
        md.indices = idx; md.triangle_count = 12;
        md.material = material;
        CHECK_OK(fogrt_scene_add_mesh(scene, &md));
    }
}

/* A furnace: the inward emitting box of half size 1 with diffuse walls of reflectance rho,
   the given fog, and a camera inside looking at a corner region (off-centre, so that the
   rays cross the box at many different lengths). */
static fogrt_scene *make_furnace(float rho, float sigma_t, fogrt_vec3 albedo, float g)
{
    fogrt_scene *scene = NULL;
    uint32_t wall_id;
    CHECK_OK(fogrt_scene_create(NULL, &scene));
    wall_id = add_basic_material(scene, FOGRT_BSDF_DIFFUSE, v3(rho, rho, rho), v3(1, 1, 1));
    add_box(scene, 1.0f, wall_id, true);
    set_medium(scene, sigma_t, albedo, g);
    set_camera(scene, v3(0.1f, -0.2f, 0.05f), v3(1.0f, 0.3f, -0.7f), 90.0f);
    return scene;
}

/* ---- image statistics ----------------------------------------------------------------- */

typedef struct image_stats {
    double mean[3];         /* mean over all pixels of the per-pixel mean, per channel */
    double std_error;       /* standard error of the image mean (luminance), from the
                               per-pixel variances of the mean (between streams) */
    double max_pixel_dev;   /* max over pixels and channels of |pixel mean - expected| */
    double max_pixel_z;     /* max over pixels of |lum mean - expected| / its standard error,
                               the error from the variance pooled over the whole image (a
                               pixel's own 16 or so samples estimate it poorly) */
    double max_sample_var;  /* max over pixels of the luminance sample variance */
    int bad_values;         /* non-finite or negative pixel means */
} image_stats;

/* Statistics of an accumulated image against an expected grey value. The luminance of a
   grey pixel (c, c, c) is c, so for grey scenes the sum_sq channel gives the variance. */
static image_stats get_stats(const fogrt_image *img, double expected)
{
    image_stats s;
    int p, c, n = img->width * img->height;
    double var_sum = 0.0, pooled = 0.0;
    memset(&s, 0, sizeof s);
    for (p = 0; p < n; ++p) {
        double cnt = (double)img->count[p], m[3], lum, var;
        TEST_ASSERT_TRUE_MESSAGE(img->count[p] > 1, "every pixel needs samples");
        for (c = 0; c < 3; ++c) {
            m[c] = img->sum[3 * p + c] / cnt;
            if (!isfinite(m[c]) || m[c] < 0.0) s.bad_values++;
            s.mean[c] += m[c] / n;
            if (fabs(m[c] - expected) > s.max_pixel_dev) s.max_pixel_dev = fabs(m[c] - expected);
        }
        lum = (m[0] + m[1] + m[2]) / 3.0;
        var = (img->sum_sq[p] / cnt - lum * lum) * cnt / (cnt - 1.0);
        if (var < 0.0) var = 0.0;   /* rounding of a zero-variance pixel */
        if (var > s.max_sample_var) s.max_sample_var = var;
        /* the variance of the pixel's mean: between its independent streams, as fogrt does
           (the pixel positions are stratified, so var / cnt would overestimate it) */
        var_sum += pixel_luminance_variance(img, p);
        pooled += var / n;
    }
    s.std_error = sqrt(var_sum) / n;
    for (p = 0; p < n; ++p) {
        double cnt = (double)img->count[p];
        double lum = (img->sum[3 * p] + img->sum[3 * p + 1] + img->sum[3 * p + 2]) / (3.0 * cnt);
        double z = fabs(lum - expected) / (sqrt(pooled / cnt) + 1e-6);
        if (z > s.max_pixel_z) s.max_pixel_z = z;
    }
    return s;
}

/* Renders spp samples per pixel of a w x h image of the scene (built here). */
static image_stats render_stats(fogrt_scene *scene, const fogrt_render_desc *rd_in, int w, int h,
                                int spp, double expected, fogrt_render_stats *rs_out)
{
    fogrt_image img;
    fogrt_render_desc rd = *rd_in;
    fogrt_render_stats rs;
    image_stats s;
    rd.width = w; rd.height = h;
    CHECK_OK(fogrt_scene_build(scene, NULL));
    CHECK_OK(fogrt_image_alloc(&img, w, h, NULL));
    CHECK_OK(fogrt_render(scene, &rd, &img, spp, &rs));
    TEST_ASSERT_EQUAL_UINT64_MESSAGE(0, img.rejected, "non-finite samples were dropped");
    TEST_ASSERT_EQUAL_UINT64(0, rs.rejected);
    TEST_ASSERT_EQUAL_UINT64((uint64_t)w * h * spp, rs.camera_rays);
    s = get_stats(&img, expected);
    {
        /* fogrt's own error estimate must agree with ours (grey images: luminance = value):
           relative_error = sqrt(sum_p Var[mean_p]) / sqrt(sum_p mean_p^2) */
        fogrt_error_estimate e;
        double sum_m2 = 0.0;
        int p;
        fogrt_image_error(&img, &e);
        for (p = 0; p < w * h; ++p) {
            double m = img.sum[3 * p + 1] / img.count[p];
            sum_m2 += m * m;
        }
        TEST_ASSERT_EQUAL_UINT64((uint64_t)w * h * spp, e.samples);
        TEST_ASSERT_EQUAL_UINT64(0, e.rejected);
        TEST_ASSERT_TRUE(fabs(e.mean_luminance - s.mean[1]) <= 1e-4 * (s.mean[1] + 1e-6));
        TEST_ASSERT_TRUE(fabs(e.relative_error * sqrt(sum_m2) / (w * h) - s.std_error) <= 1e-3 * s.std_error + 1e-7);
    }
    fogrt_image_free(&img);
    if (rs_out) *rs_out = rs;
    return s;
}

/* Asserts that an image averages to `expected` within a relative tolerance `rel_tol`:
   statistically (within 5 standard errors) and deterministically (within rel_tol, so that a
   large variance cannot hide a bias); the standard error must be below rel_tol / 3, so the
   test has the power to see a bias of rel_tol. No pixel may be off by more than 6
   (pooled) standard errors unless it is within `pixel_slack` (relative) of the answer. */
static void assert_mean(const image_stats *s, double expected, double rel_tol, double pixel_slack,
                        const char *what)
{
    char msg[320];
    int c;
    snprintf(msg, sizeof msg, "%s: mean (%.5f %.5f %.5f) expected %.5f, std error %.5f, "
             "max pixel z %.2f, max pixel dev %.4f", what, s->mean[0], s->mean[1], s->mean[2],
             expected, s->std_error, s->max_pixel_z, s->max_pixel_dev);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, s->bad_values, msg);
    for (c = 0; c < 3; ++c) {
        /* + 0.2%: Russian roulette kills are rare events (a path must first survive
           rr_depth bounces), so a finite sample can miss them and underestimate the
           variance of a mean that is otherwise almost noise-free */
        TEST_ASSERT_TRUE_MESSAGE(fabs(s->mean[c] - expected) <= 5.0 * s->std_error + 2e-3 * expected, msg);
        TEST_ASSERT_TRUE_MESSAGE(fabs(s->mean[c] - expected) <= rel_tol * expected, msg);
    }
    TEST_ASSERT_TRUE_MESSAGE(s->std_error <= rel_tol * expected / 3.0, msg);
    /* pixel_slack < 0: no pixel check (heavy-tailed estimators, where one sample can
       dominate a pixel) */
    if (pixel_slack >= 0.0)
        TEST_ASSERT_TRUE_MESSAGE(s->max_pixel_z <= 6.0 || s->max_pixel_dev <= pixel_slack * expected, msg);
}

static fogrt_render_desc base_desc(bool no_nee, bool no_mis)
{
    fogrt_render_desc rd;
    rd = fogrt_render_defaults();
    rd.max_depth = -1;      /* no depth cap: it would bias long fog walks */
    rd.nee = !(no_nee);
    rd.mis = !(no_mis);
    rd.seed = 1234;
    /* The paper's estimator: a ray counts the emitter it reaches only when its free flight
       gets there (then every no-NEE furnace path is exactly 1, as the zero-variance test
       checks). fogrt's default, expected_emission, has its own furnace test below. */
    rd.expected_emission = false;
    return rd;
}

/* The three ways of finding the light. */
enum { NO_NEE = 0, NEE_MIS = 1, NEE_NO_MIS = 2 };
static const char *mode_name(int mode)
{
    return mode == NO_NEE ? "no NEE" : mode == NEE_MIS ? "NEE+MIS" : "NEE without MIS";
}

/* ---- tests ---------------------------------------------------------------------------- */

/* Sanity of the set-up: without fog, every camera ray hits an inward emitting wall and sees
   exactly 1. Fails if the winding convention (front = CCW) or one-sided emission is wrong. */
static void test_empty_furnace_is_exactly_one(void)
{
    fogrt_scene *scene = make_furnace(0.0f, 0.0f, v3(1, 1, 1), 0.0f);
    fogrt_render_desc rd = base_desc(false, false);
    image_stats s = render_stats(scene, &rd, 8, 8, 4, 1.0, NULL);
    TEST_ASSERT_TRUE_MESSAGE(s.max_pixel_dev <= 1e-6, "an emitting wall seen directly must be 1");
    TEST_ASSERT_TRUE(s.max_sample_var <= 1e-10);
    fogrt_scene_destroy(scene);
}

/* The same box wound outward emits away from the camera: from inside it is black. Fails if
   area lights emit from their back side. */
static void test_backside_of_emitter_is_black(void)
{
    fogrt_scene *scene = NULL;
    fogrt_render_desc rd = base_desc(false, false);
    uint32_t id;
    image_stats s;
    CHECK_OK(fogrt_scene_create(NULL, &scene));
    id = add_basic_material(scene, FOGRT_BSDF_DEFAULT, v3(0, 0, 0), v3(1, 1, 1));
    add_box(scene, 1.0f, id, false);
    set_camera(scene, v3(0.1f, -0.2f, 0.05f), v3(1.0f, 0.3f, -0.7f), 90.0f);
    s = render_stats(scene, &rd, 8, 8, 4, 0.0, NULL);
    TEST_ASSERT_TRUE_MESSAGE(s.max_pixel_dev == 0.0, "the back of an emitter must be black");
    fogrt_scene_destroy(scene);
}

/* One furnace configuration: fog, light finding mode, image size and samples. */
typedef struct furnace_case { float sigma_t, g; int mode, w, h, spp; double rel_tol; } furnace_case;

/* The white furnace: albedo-1 fog of several densities and asymmetries, NEE off, NEE with
   MIS, NEE without MIS; every image must average to 1 (max_depth -1, default roulette).
   Fails on any transmittance, phase pdf, shadow-ray or MIS weight error. Sample counts are
   sized from the measured per-sample spread (about 0.3 with MIS or without NEE). NEE without
   MIS has a heavy tail (a light sample on a wall close to the fog point weighs A cos / d^2,
   unbounded: infinite variance as points approach the wall; measured unbiased to 0.2% with
   4 million samples), so it gets thin fog and a 10% tolerance, still far tighter than the
   error of a missing shadow-ray transmittance (+25%) or a double-counted emitter (+50%). */
/* Each case's furnace (black walls emitting 1, fog of albedo 1) must average to 1. */
static void run_furnace_cases(const furnace_case *cases, int n, bool expected_emission)
{
    int i;
    for (i = 0; i < n; ++i) {
        const furnace_case *fc = &cases[i];
        fogrt_scene *scene = make_furnace(0.0f, fc->sigma_t, v3(1, 1, 1), fc->g);
        fogrt_render_desc rd = base_desc(fc->mode == NO_NEE, fc->mode == NEE_NO_MIS);
        char what[160];
        image_stats s;
        rd.expected_emission = expected_emission;
        snprintf(what, sizeof what, "%ssigma_t %g g %g %s", expected_emission ? "expected emission, " : "",
                 fc->sigma_t, fc->g, mode_name(fc->mode));
        s = render_stats(scene, &rd, fc->w, fc->h, fc->spp, 1.0, NULL);
        assert_mean(&s, 1.0, fc->rel_tol, fc->mode == NEE_NO_MIS ? -1.0 : 0.3, what);
        fogrt_scene_destroy(scene);
    }
}

static void test_white_furnace_albedo_one(void)
{
    static const furnace_case cases[] = {
        { 0.3f, -0.7f, NO_NEE, 8, 8, 48, 0.03 },     /* thin fog, back scattering */
        { 1.0f,  0.0f, NO_NEE, 8, 8, 48, 0.03 },     /* isotropic */
        { 3.0f,  0.4f, NO_NEE, 8, 8, 64, 0.03 },     /* thick fog, forward; 64 spp: at 48 its
                                                        standard error is about 0.0095, at the
                                                        power bound 0.01 (assert_mean) */
        { 2.0f,  0.9f, NO_NEE, 8, 8, 48, 0.03 },     /* strongly forward */
        { 0.3f, -0.7f, NEE_MIS, 8, 8, 48, 0.03 },    /* the same four with NEE + MIS */
        { 1.0f,  0.0f, NEE_MIS, 8, 8, 48, 0.03 },
        { 3.0f,  0.4f, NEE_MIS, 16, 16, 48, 0.03 },
        { 2.0f,  0.9f, NEE_MIS, 8, 8, 48, 0.03 },
        { 3.0f, -0.3f, NEE_MIS, 16, 16, 48, 0.03 },  /* thick fog, back scattering */
        { 0.3f, -0.7f, NEE_NO_MIS, 16, 16, 64, 0.1 }, /* NEE alone: heavy tail, looser */
        { 0.3f,  0.5f, NEE_NO_MIS, 16, 16, 64, 0.1 },
    };
    run_furnace_cases(cases, (int)(sizeof cases / sizeof cases[0]), false);
}

/* Without NEE and without Russian roulette (rr_depth beyond any path; fogrt caps the
   survival probability at 0.95, which would change the weights), free-flight sampling and
   exact HG sampling give every path weight exactly 1: scattering weight = albedo = 1, the
   wall is reached with weight T/T = 1 and emits 1. So every sample is 1: any noise is a
   weight/pdf mismatch. Checked sample by sample with fogrt_trace, and on a rendered image. */
static void test_white_furnace_no_nee_zero_variance(void)
{
    static const float sigmas[] = { 0.5f, 2.0f, 6.0f };
    static const float gs[] = { -0.9f, 0.0f, 0.8f };
    int i, j, k;
    for (i = 0; i < 3; ++i) {
        for (j = 0; j < 3; ++j) {
            fogrt_scene *scene = make_furnace(0.0f, sigmas[i], v3(1, 1, 1), gs[j]);
            fogrt_render_desc rd = base_desc(true, false);
            fogrt_rng rng;
            uint64_t rays = 0;
            double max_dev = 0.0;
            char msg[320];
            image_stats s;
            rd.rr_depth = 1 << 30;
            CHECK_OK(fogrt_scene_build(scene, NULL));
            fogrt_rng_seed(&rng, 99, (uint64_t)(3 * i + j));
            for (k = 0; k < 400; ++k) {
                fogrt_vec3 d = fogrt_sample_uniform_sphere(fogrt_rng_float(&rng), fogrt_rng_float(&rng));
                fogrt_vec3 L = fogrt_trace(scene, &rd, v3(0.2f, 0.1f, -0.3f), d, &rng, &rays);
                double dev = fabs(L.x - 1.0);
                if (fabs(L.y - 1.0) > dev) dev = fabs(L.y - 1.0);
                if (fabs(L.z - 1.0) > dev) dev = fabs(L.z - 1.0);
                if (!(dev <= max_dev)) max_dev = dev;   /* NaN propagates */
            }
            snprintf(msg, sizeof msg, "sigma_t %g g %g: a sample differs from 1 by %g",
                     sigmas[i], gs[j], max_dev);
            TEST_ASSERT_TRUE_MESSAGE(max_dev <= 1e-5, msg);
            /* thick fog scatters many times per path: the walk really happened */
            TEST_ASSERT_TRUE_MESSAGE(rays >= (uint64_t)(400 * (i == 2 ? 10 : 1)), msg);
            /* the same through fogrt_render: zero variance in every pixel */
            s = render_stats(scene, &rd, 4, 4, 8, 1.0, NULL);
            TEST_ASSERT_TRUE_MESSAGE(s.max_pixel_dev <= 1e-5, msg);
            TEST_ASSERT_TRUE_MESSAGE(s.max_sample_var <= 1e-8, msg);
            fogrt_scene_destroy(scene);
        }
    }
}

/* Several light samples per NEE (CS184 -l) must not change the mean. Fails if the light
   samples are not averaged (divided by light_samples) or the MIS weights ignore their
   number. */
static void test_white_furnace_light_samples(void)
{
    fogrt_scene *scene = make_furnace(0.0f, 1.5f, v3(1, 1, 1), 0.5f);
    fogrt_render_desc rd = base_desc(false, false);
    image_stats s;
    rd.light_samples = 4;
    s = render_stats(scene, &rd, 8, 8, 48, 1.0, NULL);
    assert_mean(&s, 1.0, 0.03, 0.3, "light_samples 4, MIS");
    fogrt_scene_destroy(scene);
    /* without MIS: thin fog and many samples (heavy tail, see above). 128 spp: NEE alone
       near a wall has a variance close to infinite, so one render's standard error is
       itself a heavy-tailed draw; at 32 spp 2 of 10 seeds exceeded assert_mean's bound
       rel_tol / 3 (one of them this test's seed once the pixel positions were stratified),
       at 128 spp the largest of 16 seeds was 0.033, this seed's 0.016 */
    scene = make_furnace(0.0f, 0.3f, v3(1, 1, 1), 0.5f);
    rd.mis = false;
    s = render_stats(scene, &rd, 16, 16, 128, 1.0, NULL);
    assert_mean(&s, 1.0, 0.1, -1.0, "light_samples 4, no MIS");
    fogrt_scene_destroy(scene);
}

/* The default estimator, expected_emission: every ray adds T Le of the wall it reaches,
   whether or not it collides first. Still exactly 1 on average in the furnace (but no longer
   per path: a path that scatters k times adds k + 1 partial terms), in fog of every
   thickness and with each way of finding the light. Fails if T is not the probability of
   reaching the wall (e.g. the fog's span is measured to the wrong end), if the collision
   branch adds the emission again, or if the emission uses the throughput after the
   collision's albedo. */
static void test_white_furnace_expected_emission(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("E: expected emission");
#else
    static const furnace_case cases[] = {
        { 0.3f, -0.7f, NO_NEE, 8, 8, 96, 0.03 },
        { 1.0f,  0.0f, NO_NEE, 8, 8, 128, 0.03 },    /* 128 spp: see below */
        { 3.0f,  0.4f, NO_NEE, 16, 16, 96, 0.03 },   /* thick: many partial terms per path */
        /* 128 spp, not 96 (this one and sigma_t 1 without NEE): assert_mean wants a standard
           error below rel_tol / 3 = 0.01, and at 96 spp this case's true one is 0.0099 (the
           per-sample variance's s^2 / n over 12 seeds: 0.0097 to 0.0102), so whether it
           passed was the seed's luck; the estimate from 4 streams (3 degrees of freedom a
           pixel) scatters more still. At 128 spp 16 seeds gave at most 0.0093 */
        { 1.0f,  0.0f, NEE_MIS, 8, 8, 128, 0.03 },
        { 2.0f,  0.9f, NEE_MIS, 8, 8, 96, 0.03 },
        { 0.3f,  0.5f, NEE_NO_MIS, 16, 16, 64, 0.1 },
    };
    run_furnace_cases(cases, (int)(sizeof cases / sizeof cases[0]), true);
#endif
}

/* Absorbing fog (albedo < 1) must be darker than 1, never brighter, and darker for lower
   albedo. Fails if the scattering weight is not the albedo. */
static void test_absorbing_fog_is_darker(void)
{
    static const float albedos[] = { 0.95f, 0.7f, 0.3f };
    int i, mode;
    for (mode = NO_NEE; mode <= NEE_MIS; ++mode) {
        double prev = 1.0, prev_se = 0.0;
        for (i = 0; i < 3; ++i) {
            float a = albedos[i];
            fogrt_scene *scene = make_furnace(0.0f, 2.0f, v3(a, a, a), 0.3f);
            fogrt_render_desc rd = base_desc(mode == NO_NEE, false);
            image_stats s = render_stats(scene, &rd, 8, 8, 16, 0.0, NULL);
            char msg[320];
            snprintf(msg, sizeof msg, "albedo %g %s: mean %g (previous %g), std error %g",
                     a, mode_name(mode), s.mean[1], prev, s.std_error);
            TEST_ASSERT_EQUAL_INT_MESSAGE(0, s.bad_values, msg);
            TEST_ASSERT_TRUE_MESSAGE(s.mean[1] + 5.0 * sqrt(s.std_error * s.std_error + prev_se * prev_se) < prev, msg);
            TEST_ASSERT_TRUE_MESSAGE(s.mean[1] > 0.0, msg);
            /* each pixel too: without NEE every sample is at most 1; with NEE allow noise */
            TEST_ASSERT_TRUE_MESSAGE(s.max_pixel_dev <= (mode == NO_NEE ? 1.0 + 1e-6 : 1.1), msg);
            prev = s.mean[1];
            prev_se = s.std_error;
            fogrt_scene_destroy(scene);
        }
    }
}

/* Ray-box exit distance from a point inside [-1,1]^3. */
static double box_exit(fogrt_vec3 o, fogrt_vec3 d)
{
    double t = 1e30, oc[3], dc[3];
    int a;
    oc[0] = o.x; oc[1] = o.y; oc[2] = o.z; dc[0] = d.x; dc[1] = d.y; dc[2] = d.z;
    for (a = 0; a < 3; ++a) {
        if (dc[a] > 0.0 && (1.0 - oc[a]) / dc[a] < t) t = (1.0 - oc[a]) / dc[a];
        if (dc[a] < 0.0 && (-1.0 - oc[a]) / dc[a] < t) t = (-1.0 - oc[a]) / dc[a];
    }
    return t;
}

/* Per-channel albedo (1, 0.5, 0): red is a white furnace (1), blue sees only the unscattered
   light, exp(-sigma_t * distance to the wall) averaged over the pixel, and green lies in
   between. Fails if channels are mixed up or the camera ray's transmittance is wrong. */
static void test_chromatic_albedo(void)
{
    const float sigma_t = 1.2f;
    const int w = 6, h = 6, spp = 64, sub = 8;
    fogrt_scene *scene = make_furnace(0.0f, sigma_t, v3(1.0f, 0.5f, 0.0f), 0.2f);
    fogrt_render_desc rd = base_desc(false, false);
    fogrt_image img;
    int x, y, i, j;
    rd.width = w; rd.height = h;
    CHECK_OK(fogrt_scene_build(scene, NULL));
    CHECK_OK(fogrt_image_alloc(&img, w, h, NULL));
    CHECK_OK(fogrt_render(scene, &rd, &img, spp, NULL));
    TEST_ASSERT_EQUAL_UINT64(0, img.rejected);
    for (y = 0; y < h; ++y) {
        for (x = 0; x < w; ++x) {
            int p = y * w + x;
            double n = img.count[p], r = img.sum[3 * p] / n, gch = img.sum[3 * p + 1] / n;
            double b = img.sum[3 * p + 2] / n, expect_b = 0.0, se_b;
            char msg[320];
            /* expected blue: average of exp(-sigma_t t_exit) over the pixel footprint */
            for (j = 0; j < sub; ++j) {
                for (i = 0; i < sub; ++i) {
                    fogrt_vec3 o, d;
                    fogrt_camera_ray(scene, w, h, x + (i + 0.5f) / sub, y + (j + 0.5f) / sub,
                                     0.5f, 0.5f, &o, &d);
                    expect_b += exp(-sigma_t * box_exit(o, d)) / (sub * sub);
                }
            }
            /* blue is a Bernoulli estimate of expect_b (or better) */
            se_b = sqrt(expect_b * (1.0 - expect_b) / n);
            snprintf(msg, sizeof msg, "pixel %d,%d: rgb %g %g %g, expected blue %g (se %g)",
                     x, y, r, gch, b, expect_b, se_b);
            TEST_ASSERT_TRUE_MESSAGE(fabs(b - expect_b) <= 5.0 * se_b + 2e-3, msg);
            TEST_ASSERT_TRUE_MESSAGE(gch >= b - 1e-6 && gch <= 1.0 + 1e-6, msg);
            TEST_ASSERT_TRUE_MESSAGE(r >= gch, msg);
        }
    }
    {
        image_stats s = get_stats(&img, 1.0);
        char msg[320];
        snprintf(msg, sizeof msg, "red channel mean %g", s.mean[0]);
        /* the red channel is an albedo-1 furnace; its noise is below the luminance noise */
        TEST_ASSERT_TRUE_MESSAGE(fabs(s.mean[0] - 1.0) <= 0.01, msg);
        TEST_ASSERT_TRUE_MESSAGE(s.mean[2] < s.mean[1] && s.mean[1] < s.mean[0], msg);
    }
    fogrt_image_free(&img);
    fogrt_scene_destroy(scene);
}

/* A depth cap cuts long fog walks, so it darkens the furnace: documents the bias that
   max_depth = -1 avoids. Fails if max_depth is ignored. */
static void test_depth_cap_darkens(void)
{
    fogrt_scene *scene = make_furnace(0.0f, 4.0f, v3(1, 1, 1), 0.0f);
    fogrt_render_desc rd = base_desc(true, false);
    fogrt_render_stats rs;
    image_stats s;
    char msg[320];
    rd.max_depth = 1;
    s = render_stats(scene, &rd, 8, 8, 16, 1.0, &rs);
    snprintf(msg, sizeof msg, "max_depth 1: mean %g", s.mean[1]);
    TEST_ASSERT_TRUE_MESSAGE(s.mean[1] < 0.9 && s.mean[1] > 0.0, msg);
    /* a path has at most 2 segments (camera ray + 1 bounce) and no shadow rays */
    TEST_ASSERT_TRUE_MESSAGE(rs.rays <= 2 * rs.camera_rays, "max_depth 1: too many rays");
    fogrt_scene_destroy(scene);
}

/* One reflective-wall configuration. */
typedef struct wall_case { float rho, sigma_t; int mode, rr_depth, w, h, spp; double rel_tol; } wall_case;

/* Lambertian walls of reflectance rho that also emit 1, in albedo-1 fog: each wall bounce
   keeps a fraction rho, so the pixel is 1 + rho + rho^2 + ... = 1 / (1 - rho). Russian
   roulette must keep this unbiased (max_depth = -1). Fails on a biased roulette, a wrong
   Lambertian weight (e.g. rho / 2pi), or next-event estimation from a surface that loses
   (or double counts) light. Sample counts follow the measured spread (about 0.6 at rho 0.5,
   4.6 at rho 0.8; NEE without MIS has a heavy tail near the box edges). */
static void test_reflective_walls(void)
{
    static const wall_case cases[] = {
        { 0.5f, 0.0f, NO_NEE, 3, 16, 16, 16, 0.03 },        /* no fog: 2 */
        { 0.5f, 0.0f, NEE_MIS, 3, 16, 16, 16, 0.03 },
        { 0.5f, 0.0f, NEE_NO_MIS, 3, 16, 16, 64, 0.1 },  /* heavy tail: looser */
        { 0.5f, 1.0f, NO_NEE, 3, 16, 16, 32, 0.03 },        /* fog and walls: still 2 */
        { 0.5f, 1.0f, NEE_MIS, 3, 16, 16, 32, 0.03 },
        { 0.8f, 0.0f, NO_NEE, 3, 16, 16, 64, 0.03 },      /* 5: long paths, roulette does the work */
        { 0.8f, 0.0f, NEE_MIS, 3, 16, 16, 64, 0.03 },
        { 0.8f, 1.0f, NO_NEE, 3, 16, 16, 64, 0.03 },
        { 0.8f, 1.0f, NEE_MIS, 3, 16, 16, 64, 0.03 },
        { 0.6f, 0.5f, NO_NEE, 1, 16, 16, 32, 0.03 },      /* roulette from the first bounce: 2.5 */
        { 0.6f, 0.5f, NEE_MIS, 1, 16, 16, 32, 0.03 },
    };
    int i;
    for (i = 0; i < (int)(sizeof cases / sizeof cases[0]); ++i) {
        const wall_case *wc = &cases[i];
        double expected = 1.0 / (1.0 - wc->rho);
        fogrt_scene *scene = make_furnace(wc->rho, wc->sigma_t, v3(1, 1, 1), 0.3f);
        fogrt_render_desc rd = base_desc(wc->mode == NO_NEE, wc->mode == NEE_NO_MIS);
        char what[160];
        image_stats s;
        rd.rr_depth = wc->rr_depth;
        snprintf(what, sizeof what, "rho %g sigma_t %g %s rr_depth %d", wc->rho, wc->sigma_t,
                 mode_name(wc->mode), wc->rr_depth);
        s = render_stats(scene, &rd, wc->w, wc->h, wc->spp, expected, NULL);
        assert_mean(&s, expected, wc->rel_tol, -1.0, what);   /* skewed: no pixel check */
        fogrt_scene_destroy(scene);
    }
}

/* A single bounce (max_depth 1, no roulette) at the middle of a wall of reflectance 0.5
   that sees only emitters of radiance 1: exactly 1 + 0.5. Traced from the box centre at
   points away from the wall edges, so the NEE weights stay bounded (near an edge a light
   sample on the adjacent wall can be arbitrarily close). This isolates the first next-event
   estimate at a surface. Fails if NEE from a surface loses light, e.g. when a shadow ray
   toward a light facing the surface is stopped by the light itself, or double counts it. */
static void test_one_bounce_off_emitting_walls(void)
{
    static const fogrt_vec3 targets[] = {
        { 0.0f, 0.0f, -1.0f }, { 0.3f, -0.2f, -1.0f }, { 1.0f, 0.25f, 0.1f }, { -0.2f, 1.0f, 0.4f }
    };
    int mode, t, k;
    fogrt_scene *scene = make_furnace(0.5f, 0.0f, v3(1, 1, 1), 0.0f);
    CHECK_OK(fogrt_scene_build(scene, NULL));
    for (mode = NO_NEE; mode <= NEE_NO_MIS; ++mode) {
        for (t = 0; t < 4; ++t) {
            fogrt_render_desc rd = base_desc(mode == NO_NEE, mode == NEE_NO_MIS);
            fogrt_rng rng;
            double sum = 0.0, sum_sq = 0.0, mean, se;
            int n = mode == NEE_NO_MIS ? 32000 : 4000;   /* NEE alone is noisier */
            char msg[320];
            rd.max_depth = 1;
            rd.rr_depth = 1 << 30;
            fogrt_rng_seed(&rng, 21, (uint64_t)(4 * mode + t));
            for (k = 0; k < n; ++k) {
                fogrt_vec3 L = fogrt_trace(scene, &rd, v3(0, 0, 0), targets[t], &rng, NULL);
                TEST_ASSERT_TRUE(isfinite(L.y) && L.y >= 0.0f);
                sum += L.y;
                sum_sq += (double)L.y * L.y;
            }
            mean = sum / n;
            se = std_error_of_mean(sum, sum_sq, n);
            snprintf(msg, sizeof msg, "%s, wall point %d: mean %.5f expected 1.5 (se %.5f)",
                     mode_name(mode), t, mean, se);
            TEST_ASSERT_TRUE_MESSAGE(fabs(mean - 1.5) <= 5.0 * se + 1e-5, msg);
            TEST_ASSERT_TRUE_MESSAGE(fabs(mean - 1.5) <= 0.01, msg);
            TEST_ASSERT_TRUE_MESSAGE(se <= 0.003, msg);
            if (mode == NO_NEE) TEST_ASSERT_TRUE_MESSAGE(se <= 1e-6, msg);   /* every sample is 1.5 */
        }
    }
    fogrt_scene_destroy(scene);
}

/* A non-absorbing specular object inside the furnace is invisible: it only redirects rays,
   and every direction sees 1. Glass (Schlick and exact Fresnel), refraction-only and mirror,
   without fog and in albedo-1 fog (fogrt has no fog inside refractive objects; both give 1).
   Fails on a lost or doubled 1/eta^2 factor, wrong Fresnel lobe weights, or lost TIR paths. */
static void test_specular_sphere_invisible(void)
{
    static const fogrt_bsdf_type types[] = { FOGRT_BSDF_GLASS, FOGRT_BSDF_REFRACTION, FOGRT_BSDF_MIRROR };
    int t, j, fr, mode;
    for (t = 0; t < 3; ++t) {
        for (j = 0; j < 2; ++j) {
#ifdef FOGRT_MINIMAL
            for (fr = 0; fr < 1; ++fr) {         /* Schlick only: the exact Fresnel is Part II's (C) */
#else
            for (fr = 0; fr < 2; ++fr) {
#endif
                for (mode = 0; mode < 2; ++mode) {
                    fogrt_scene *scene = make_furnace(0.0f, j ? 1.0f : 0.0f, v3(1, 1, 1), 0.3f);
                    fogrt_material_desc m;
                    fogrt_render_desc rd = base_desc(mode == 0, false);
                    uint32_t id = 0;
                    char what[160];
                    image_stats s;
                    memset(&m, 0, sizeof m);
                    m.type = types[t];
                    m.reflectance = v3(1, 1, 1);
                    m.transmittance = v3(1, 1, 1);
                    m.ior = 1.6f;
                    CHECK_OK(fogrt_scene_add_material(scene, &m, &id));
                    CHECK_OK(fogrt_scene_add_sphere(scene, v3(0.1f, 0.0f, 0.0f), 0.45f, id));
                    /* look straight at the sphere, so it fills most of the image */
                    set_camera(scene, v3(-0.3f, 0.1f, -0.8f), v3(0.1f, 0.0f, 0.0f), 60.0f);
                    rd.fresnel = fr ? FOGRT_FRESNEL_EXACT : FOGRT_FRESNEL_SCHLICK;
                    snprintf(what, sizeof what, "bsdf %d sigma_t %d fresnel %d nee %d", (int)types[t],
                             j, fr, mode);
                    s = render_stats(scene, &rd, 8, 8, 16, 1.0, NULL);
                    assert_mean(&s, 1.0, 0.03, 0.3, what);
                    fogrt_scene_destroy(scene);
                }
            }
        }
    }
}

/* The furnace holds for the direct-lighting integrator only without scattering: with no fog
   the camera sees the walls directly, 1 everywhere (one-bounce baseline agrees). */
static void test_direct_integrator_empty_furnace(void)
{
    fogrt_scene *scene = make_furnace(0.0f, 0.0f, v3(1, 1, 1), 0.0f);
    fogrt_render_desc rd = base_desc(false, false);
    image_stats s;
    rd.integrator = FOGRT_INTEGRATOR_DIRECT;
    s = render_stats(scene, &rd, 8, 8, 4, 1.0, NULL);
    TEST_ASSERT_TRUE_MESSAGE(s.max_pixel_dev <= 1e-6, "direct integrator: walls seen directly must be 1");
    fogrt_scene_destroy(scene);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_empty_furnace_is_exactly_one);
    RUN_TEST(test_backside_of_emitter_is_black);
    RUN_TEST(test_white_furnace_albedo_one);
    RUN_TEST(test_white_furnace_no_nee_zero_variance);
    RUN_TEST(test_white_furnace_light_samples);
    RUN_TEST(test_white_furnace_expected_emission);
    RUN_TEST(test_absorbing_fog_is_darker);
    RUN_TEST(test_chromatic_albedo);
    RUN_TEST(test_depth_cap_darkens);
    RUN_TEST(test_reflective_walls);
    RUN_TEST(test_one_bounce_off_emitting_walls);
    RUN_TEST(test_specular_sphere_invisible);
    RUN_TEST(test_direct_integrator_empty_furnace);
    return UNITY_END();
}
