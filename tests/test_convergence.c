/* test_convergence.c - the render's live error estimate tracks the truth.
 *
 * fogrt_image_error estimates the relative MSE of an image from its own samples:
 *     est(n) = sum_p s_p^2 / n_p  /  sum_p mean_p^2        (luminance; s_p^2 = sample variance)
 * The measured relative MSE of the same image against a long reference render R (another
 * seed, 16x the largest sample count) is, with the same denominator,
 *     meas(n) = (sum_p (mean_p - R_p)^2 - sum_p Var[R_p])  /  sum_p mean_p^2,
 * where sum_p Var[R_p] (the reference's own noise, which adds to the squared difference) is
 * subtracted using the reference's own variance estimate. The denominators are the same,
 * so est / meas = sum_p s_p^2 / n_p  /  (sum_p (mean_p - R_p)^2 - sum_p Var[R_p]).
 *
 * On a small fog box lit by an area light (32x24 pixels), for the path and the one-bounce
 * integrator, est / meas must lie in [1/2, 2] at every point of the progressive ladder
 * 4, 8, ..., 256 samples per pixel. Seeds are fixed, so the outcome is deterministic.
 *
 * Two negative controls show that the check can fail:
 *   - an estimate that forgets the 1/n (the per-sample variance instead of the variance of
 *     the mean) is off by the factor n and fails at every point;
 *   - a biased image (the path integrator cut at BIASED_DEPTH bounces, against the full
 *     reference) has an error that stops falling at its bias, while its estimate keeps
 *     falling: the ratio leaves [1/2, 2] as the samples grow. */
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

#define W 32
#define H 24
#define LADDER_MIN 4
#define LADDER_MAX 256
#define REF_SPP (8 * LADDER_MAX)
#define N_LADDER 7   /* 4, 8, ..., 256 */
#define BIASED_DEPTH 4   /* the negative control's cut: bounces after the camera ray */

/* A closed box (2 x 2 x 2) with a ceiling lamp, a diffuse sphere and scattering fog; the
   camera inside looks at the back wall. */
static fogrt_scene *fog_box(void)
{
    fogrt_scene *scene = NULL;
    uint32_t white;
    CHECK_OK(fogrt_scene_create(NULL, &scene));
    white = add_closed_box(scene, 0.3f, 8.0f);
    CHECK_OK(fogrt_scene_add_sphere(scene, v3(-0.3f, 0.4f, -0.3f), 0.4f, white));
    set_camera(scene, v3(0, 1, 0.95f), v3(0, 0.9f, -1), 70.0f);
    set_medium(scene, 0.6f, v3(0.85f, 0.85f, 0.85f), 0.3f);
    CHECK_OK(fogrt_scene_build(scene, NULL));
    return scene;
}

/* Sums over the pixels of one image against the reference. */
typedef struct ladder_point {
    int spp;
    double est;          /* fogrt_image_error's relative_error squared */
    double est_no_1_n;   /* negative control: the per-sample variance, no division by n */
    double meas;         /* measured relative MSE, reference noise subtracted */
    double mse;          /* its numerator per pixel: the measured MSE, reference noise subtracted */
} ladder_point;

static double luminance_mean(const fogrt_image *img, int p) { return pixel_luminance(img, p); }

static ladder_point measure(const fogrt_image *img, const fogrt_image *ref)
{
    ladder_point lp;
    fogrt_error_estimate e;
    double sq_err = 0.0, ref_var = 0.0, mean_sq = 0.0, var_sample = 0.0;
    int p;
    fogrt_image_error(img, &e);
    for (p = 0; p < W * H; ++p) {
        double m = luminance_mean(img, p), d = m - luminance_mean(ref, p);
        sq_err += d * d;
        ref_var += pixel_luminance_variance(ref, p);
        mean_sq += m * m;
        var_sample += pixel_sample_variance(img, p);   /* s_p^2: the variance of one sample */
    }
    lp.spp = (int)img->count[0];
    lp.est = e.relative_error * e.relative_error;
    lp.est_no_1_n = var_sample / mean_sq;
    lp.meas = (sq_err - ref_var) / mean_sq;
    lp.mse = (sq_err - ref_var) / (W * H);
    return lp;
}

/* Renders the ladder progressively (4 spp, then 4 more, then 8 more, ...), measuring each
   point against ref. */
static void run_ladder(const fogrt_scene *scene, const fogrt_render_desc *rd, const fogrt_image *ref,
                       ladder_point out[N_LADDER])
{
    fogrt_image img;
    int k, done = 0;
    CHECK_OK(fogrt_image_alloc(&img, W, H, NULL));
    for (k = 0; k < N_LADDER; ++k) {
        int target = LADDER_MIN << k;
        CHECK_OK(fogrt_render(scene, rd, &img, target - done, NULL));
        done = target;
        out[k] = measure(&img, ref);
    }
    fogrt_image_free(&img);
}

/* The reference of one integrator, rendered once (the path one serves two tests). */
static fogrt_image references[FOGRT_INTEGRATOR_NUM];
static const fogrt_image *reference(const fogrt_scene *scene, fogrt_render_desc rd)
{
    fogrt_image *ref = &references[rd.integrator];
    if (ref->count) return ref;
    rd.seed = 0x5EEDBA5Eu;   /* independent of the ladder's samples */
    CHECK_OK(fogrt_image_alloc(ref, W, H, NULL));
    CHECK_OK(fogrt_render(scene, &rd, ref, REF_SPP, NULL));
    return ref;
}

static void print_ladder(const char *name, const ladder_point lp[N_LADDER])
{
    int k;
    for (k = 0; k < N_LADDER; ++k)
        printf("convergence %-7s spp %3d  estimated relMSE %.4e  measured %.4e  ratio %.3f  (no-1/n control %.3f)\n",
               name, lp[k].spp, lp[k].est, lp[k].meas, lp[k].est / lp[k].meas, lp[k].est_no_1_n / lp[k].meas);
}

static void check_tracks(fogrt_integrator integrator, const char *name)
{
    fogrt_scene *scene = fog_box();
    fogrt_render_desc rd = fogrt_render_defaults();
    ladder_point lp[N_LADDER];
    char msg[160];
    int k;
    rd.integrator = integrator;
    rd.seed = 11;
    run_ladder(scene, &rd, reference(scene, rd), lp);
    print_ladder(name, lp);
    for (k = 0; k < N_LADDER; ++k) {
        double ratio = lp[k].est / lp[k].meas;
        snprintf(msg, sizeof msg, "%s at %d spp: estimated relMSE %.4g, measured %.4g (ratio %.3f)",
                 name, lp[k].spp, lp[k].est, lp[k].meas, ratio);
        TEST_ASSERT_TRUE_MESSAGE(lp[k].meas > 0.0, msg);
        TEST_ASSERT_TRUE_MESSAGE(ratio >= 0.5 && ratio <= 2.0, msg);
        /* negative control: forgetting the 1/n is caught at every point */
        snprintf(msg, sizeof msg, "%s at %d spp: the no-1/n control (ratio %.3f) should fail the factor-2 check",
                 name, lp[k].spp, lp[k].est_no_1_n / lp[k].meas);
        TEST_ASSERT_TRUE_MESSAGE(lp[k].est_no_1_n / lp[k].meas > 2.0, msg);
    }
    /* The error falls as 1/n: over the ladder (64x the samples) by a factor near 64. This is
       checked on the MSE, the numerator: the relative MSE's denominator, sum_p mean_p^2 of
       the image itself, also holds the image's noise (sum_p Var[mean_p] on top of the
       true sum_p mean_p^2: a third more at 4 spp here), so the relative MSE at 4 spp comes
       out low and its fall over the ladder short of the MSE's. */
    snprintf(msg, sizeof msg, "%s: measured MSE fell by %.1fx from %d to %d spp (relative MSE by %.1fx), expected about %dx",
             name, lp[0].mse / lp[N_LADDER - 1].mse, LADDER_MIN, LADDER_MAX, lp[0].meas / lp[N_LADDER - 1].meas,
             LADDER_MAX / LADDER_MIN);
    TEST_MESSAGE(msg);
    TEST_ASSERT_TRUE_MESSAGE(lp[0].mse / lp[N_LADDER - 1].mse > 0.5 * LADDER_MAX / LADDER_MIN &&
                             lp[0].mse / lp[N_LADDER - 1].mse < 2.0 * LADDER_MAX / LADDER_MIN, msg);
    fogrt_scene_destroy(scene);
}

static void test_estimate_tracks_truth_path(void) { check_tracks(FOGRT_INTEGRATOR_PATH, "path"); }
static void test_estimate_tracks_truth_direct(void) { check_tracks(FOGRT_INTEGRATOR_DIRECT, "direct"); }

/* Negative control: a biased image. The path integrator cut after BIASED_DEPTH bounces misses the
   multiply scattered light; against the full reference its measured error levels off at
   the bias, which the estimate (variance only) cannot see, so the factor-2 check fails at
   the top of the ladder. */
static void test_bias_is_not_seen_by_the_estimate(void)
{
    fogrt_scene *scene = fog_box();
    fogrt_render_desc rd = fogrt_render_defaults(), cut;
    ladder_point lp[N_LADDER];
    char msg[160];
    rd.seed = 11;
    cut = rd;
    cut.max_depth = BIASED_DEPTH;
    run_ladder(scene, &cut, reference(scene, rd), lp);
    print_ladder("biased", lp);
    snprintf(msg, sizeof msg, "path cut at %d bounces, %d spp: ratio %.3f should be below 1/2 (bias)", BIASED_DEPTH,
             lp[N_LADDER - 1].spp, lp[N_LADDER - 1].est / lp[N_LADDER - 1].meas);
    TEST_ASSERT_TRUE_MESSAGE(lp[N_LADDER - 1].est / lp[N_LADDER - 1].meas < 0.5, msg);
    /* and its measured error stops falling like 1/n */
    snprintf(msg, sizeof msg, "biased: measured relMSE fell only %.1fx over the ladder",
             lp[0].meas / lp[N_LADDER - 1].meas);
    TEST_ASSERT_TRUE_MESSAGE(lp[0].meas / lp[N_LADDER - 1].meas < 0.25 * LADDER_MAX / LADDER_MIN, msg);
    fogrt_scene_destroy(scene);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_estimate_tracks_truth_path);
    RUN_TEST(test_estimate_tracks_truth_direct);
    RUN_TEST(test_bias_is_not_seen_by_the_estimate);
    fogrt_image_free(&references[FOGRT_INTEGRATOR_PATH]);
    fogrt_image_free(&references[FOGRT_INTEGRATOR_DIRECT]);
    return UNITY_END();
}
