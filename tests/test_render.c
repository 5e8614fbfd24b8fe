/* test_render.c - whole renders: finite output, reproducibility, progress and cancelling, the
 * error estimate, unbiasedness of next-event estimation, the two integrators, the cameras,
 * tone mapping and the image writers.
 *
 * Statistical checks use fixed seeds, so they pass or fail the same way on every run; each
 * compares two estimates of one quantity with a tolerance of 4 standard errors, where the
 * standard error comes from independent batches (renders with different seeds). */
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

/* Where output files go: the directory of the test binary ($(BUILD)/tests), set by main. */
static char out_dir[512] = ".";

/* ------------------------------------------------------------------------------------------
   Helpers
   ------------------------------------------------------------------------------------------ */
static fogrt_scene *default_scene(void)
{
    fogrt_scene *scene = NULL;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_create(NULL, &scene));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_default(scene));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    return scene;
}

static uint32_t add_material(fogrt_scene *scene, fogrt_bsdf_type type, fogrt_vec3 refl, fogrt_vec3 emission)
{
    fogrt_material_desc m;
    uint32_t id = 0;
    memset(&m, 0, sizeof m);
    m.type = type;
    m.reflectance = refl;
    m.transmittance = v3(1, 1, 1);
    m.emission = emission;
    m.ior = 1.5f;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_material(scene, &m, &id));
    return id;
}

/* A closed Cornell-like box lit only by an area light on the ceiling, with a diffuse sphere
   and (if specular) a mirror and a glass sphere, and optionally fog: every light can be found
   both by next-event estimation and by BSDF sampling, so NEE on and off must agree. */
static fogrt_scene *area_light_box(float sigma_t, bool specular, float lamp_half)
{
    fogrt_scene *scene = NULL;
    uint32_t white;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_create(NULL, &scene));
    white = add_closed_box(scene, lamp_half, 6.0f);   /* walls face inward; the front wall is behind the camera */
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_sphere(scene, v3(-0.5f, 0.3f, -0.3f), 0.3f, white));
    if (specular) {
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_sphere(scene, v3(0.5f, 0.3f, -0.4f), 0.3f,
                                                                     add_material(scene, FOGRT_BSDF_MIRROR, v3(0.9f, 0.9f, 0.9f), v3(0, 0, 0))));
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_sphere(scene, v3(0.1f, 0.3f, 0.35f), 0.25f,
                                                                     add_material(scene, FOGRT_BSDF_GLASS, v3(1, 1, 1), v3(0, 0, 0))));
    }
    set_camera(scene, v3(0, 1, 0.95f), v3(0, 0.8f, 0), 75.0f);
    if (sigma_t > 0.0f) set_medium(scene, sigma_t, v3(0.8f, 0.8f, 0.8f), 0.5f);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    return scene;
}

static fogrt_render_desc render_desc(int width, int height, uint64_t seed)
{
    fogrt_render_desc rd;
    rd = fogrt_render_defaults();
    rd.width = width;
    rd.height = height;
    rd.seed = seed;
    rd.threads = 1;   /* the tests share 2 cores with other test programs */
    return rd;
}

/* Renders spp samples into a fresh image (the caller frees it). */
static void render_new(const fogrt_scene *scene, const fogrt_render_desc *rd, int spp, fogrt_image *img,
                       fogrt_render_stats *stats)
{
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_image_alloc(img, rd->width, rd->height, NULL));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_render(scene, rd, img, spp, stats));
}

/* Mean of (r + g + b) / 3 over the image (any linear functional would do). */
static double image_mean(const fogrt_image *img)
{
    size_t i, n = (size_t)img->width * (size_t)img->height;
    double sum = 0;
    for (i = 0; i < n; i++) {
        double c = img->count[i] ? (double)img->count[i] : 1.0;
        sum += ((double)img->sum[3 * i] + img->sum[3 * i + 1] + img->sum[3 * i + 2]) / (3.0 * c);
    }
    return sum / (double)n;
}

static size_t pixels(const fogrt_image *img) { return (size_t)img->width * (size_t)img->height; }

static void assert_same_image(const fogrt_image *a, const fogrt_image *b, const char *what)
{
    size_t n = pixels(a);
    TEST_ASSERT_EQUAL_INT(a->width, b->width);
    TEST_ASSERT_EQUAL_INT(a->height, b->height);
    TEST_ASSERT_TRUE_MESSAGE(memcmp(a->sum, b->sum, sizeof(double) * 3 * n) == 0, what);
    TEST_ASSERT_TRUE_MESSAGE(memcmp(a->sum_sq, b->sum_sq, sizeof(double) * n) == 0, what);
    TEST_ASSERT_TRUE_MESSAGE(memcmp(a->count, b->count, sizeof(uint32_t) * n) == 0, what);
    TEST_ASSERT_TRUE_MESSAGE(memcmp(a->stream_sum, b->stream_sum, sizeof(double) * FOGRT_IMAGE_STREAMS * n) == 0, what);
    TEST_ASSERT_TRUE_MESSAGE(memcmp(a->stream_count, b->stream_count, sizeof(uint32_t) * FOGRT_IMAGE_STREAMS * n) == 0, what);
    TEST_ASSERT_EQUAL_UINT64_MESSAGE(a->rejected, b->rejected, what);
}

/* Mean and standard error of the image mean over `batches` independent renders (seeds
   base_seed, base_seed + 1, ...). Under the sanitizers each render has a quarter of the spp
   (SAN_REDUCED): the same number of batches, so the same test with wider errors. */
typedef struct batch_estimate { double mean, std_error; } batch_estimate;

static batch_estimate batch_mean(const fogrt_scene *scene, const fogrt_render_desc *proto, int spp,
                                 int batches, uint64_t base_seed)
{
    batch_estimate e;
    double sum = 0, sum_sq = 0;
    int b;
    spp = SAN_REDUCED(spp, 4);
    for (b = 0; b < batches; b++) {
        fogrt_render_desc rd = *proto;
        fogrt_image img;
        double m;
        rd.seed = base_seed + (uint64_t)b;
        render_new(scene, &rd, spp, &img, NULL);
        TEST_ASSERT_EQUAL_UINT64(0, img.rejected);
        m = image_mean(&img);
        sum += m;
        sum_sq += m * m;
        fogrt_image_free(&img);
    }
    e.mean = sum / batches;
    e.std_error = sqrt(fmax(0.0, (sum_sq / batches - e.mean * e.mean) * batches / (batches - 1.0)) / batches);
    return e;
}

/* Two estimates of one mean agree within 4 standard errors (and the errors are not zero:
   a batch spread of 0 would make any tolerance meaningless). */
static void assert_means_agree(batch_estimate a, batch_estimate b, const char *what)
{
    char msg[256];
    double tol = 4.0 * sqrt(a.std_error * a.std_error + b.std_error * b.std_error);
    snprintf(msg, sizeof msg, "%s: %.5f +- %.5f vs %.5f +- %.5f (difference %.2f standard errors)", what,
             a.mean, a.std_error, b.mean, b.std_error, fabs(a.mean - b.mean) / (tol / 4.0));
    TEST_MESSAGE(msg);
    TEST_ASSERT_TRUE_MESSAGE(a.std_error > 0.0 && b.std_error > 0.0, msg);
    TEST_ASSERT_TRUE_MESSAGE(a.mean > 0.0 && b.mean > 0.0, msg);
    TEST_ASSERT_TRUE_MESSAGE(fabs(a.mean - b.mean) <= tol, msg);
}

/* The roulette's pilot (chapter 15) chooses k > 1 where the light found after the first
   roulette is a large share of the noise for its share of the time: an open box lit by a
   spot light and seen through fog from outside (the paper's kind of scene), a closed
   diffuse box (much of its light comes after several bounces) and the same box with a
   mirror and glass (caustics); it keeps k = 1 exactly where nothing is found after a
   roulette (a lit floor under an open sky), and where the build is told not to run it
   (roulette_pilot = false); the same scene built twice gets the same k;
   and the image mean with the pilot's k agrees with the mean with k = 1 (20 independent
   renders each, in two scenes): k changes the cost, not the answer. */
#ifndef FOGRT_MINIMAL   /* helpers of Part II's test below */
static fogrt_scene *spot_box(void)
{
    fogrt_scene *scene = NULL;
    fogrt_light_desc l;
    uint32_t white;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_create(NULL, &scene));
    white = add_material(scene, FOGRT_BSDF_DIFFUSE, v3(0.7f, 0.7f, 0.7f), v3(0, 0, 0));
    add_quad_corners(scene, v3(-1, 0, -1), v3(-1, 0, 1), v3(1, 0, 1), v3(1, 0, -1), white);     /* floor */
    add_quad_corners(scene, v3(-1, 2, -1), v3(1, 2, -1), v3(1, 2, 1), v3(-1, 2, 1), white);     /* ceiling */
    add_quad_corners(scene, v3(-1, 0, -1), v3(1, 0, -1), v3(1, 2, -1), v3(-1, 2, -1), white);   /* back */
    add_quad_corners(scene, v3(-1, 0, 1), v3(-1, 0, -1), v3(-1, 2, -1), v3(-1, 2, 1), white);   /* left */
    add_quad_corners(scene, v3(1, 0, -1), v3(1, 0, 1), v3(1, 2, 1), v3(1, 2, -1), white);       /* right */
    memset(&l, 0, sizeof l);
    l.type = FOGRT_LIGHT_SPOT; l.position = v3(0, 1.9f, 0); l.direction = v3(0, -1, 0);
    l.intensity = v3(5, 5, 5); l.cutoff_deg = 30.0f; l.beam_deg = 20.0f;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_light(scene, &l));
    set_camera(scene, v3(0, 1, 4.8f), v3(0, 1, 0), 40.0f);
    set_medium(scene, 0.5f, v3(0.9f, 0.9f, 0.9f), 0.6f);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    return scene;
}
static fogrt_scene *lit_floor(void)
{
    fogrt_scene *scene = NULL;
    fogrt_light_desc l;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_create(NULL, &scene));
    add_quad_corners(scene, v3(-1, 0, -1), v3(-1, 0, 1), v3(1, 0, 1), v3(1, 0, -1),
                     add_material(scene, FOGRT_BSDF_DIFFUSE, v3(0.7f, 0.7f, 0.7f), v3(0, 0, 0)));
    memset(&l, 0, sizeof l);
    l.type = FOGRT_LIGHT_POINT; l.position = v3(0, 1, 0); l.intensity = v3(2, 2, 2);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_light(scene, &l));
    set_camera(scene, v3(0, 1.5f, 2.5f), v3(0, 0, 0), 50.0f);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    return scene;
}
#endif
static void test_roulette_pilot(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("C: the roulette's pilot");
#else
    fogrt_scene *spot = spot_box(), *again = spot_box(), *box = area_light_box(0.0f, false, 0.3f);
    fogrt_scene *glass = area_light_box(0.0f, true, 0.15f), *open = lit_floor(), *def = default_scene();
    fogrt_render_desc rd = render_desc(32, 24, 0);
    batch_estimate with_k, with_1;
    float k = spot->x->rr_k;
    char msg[240];
    snprintf(msg, sizeof msg, "pilot k: spot-lit box seen through fog %.2f (built twice: %.2f), closed diffuse box %.2f, "
             "with glass and a mirror %.2f, lit floor %.2f, default scene %.2f",
             (double)k, (double)again->x->rr_k, (double)box->x->rr_k, (double)glass->x->rr_k, (double)open->x->rr_k, (double)def->x->rr_k);
    TEST_MESSAGE(msg);
    TEST_ASSERT_TRUE_MESSAGE(memcmp(&k, &again->x->rr_k, sizeof k) == 0, msg);
    TEST_ASSERT_TRUE_MESSAGE(k > 1.2f && k <= 4.0f, msg);
    TEST_ASSERT_TRUE_MESSAGE(box->x->rr_k > 1.2f && box->x->rr_k <= 4.0f, msg);
    TEST_ASSERT_TRUE_MESSAGE(glass->x->rr_k > 1.2f && glass->x->rr_k <= 4.0f, msg);
    TEST_ASSERT_TRUE_MESSAGE(open->x->rr_k == 1.0f, msg);
    TEST_ASSERT_TRUE_MESSAGE(def->x->rr_k >= 1.0f && def->x->rr_k <= 4.0f, msg);
    {   /* roulette_pilot = false: the same scene rebuilt keeps k = 1 */
        fogrt_build_desc bd = fogrt_build_defaults();
        bd.roulette_pilot = false;
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(again, &bd));
        TEST_ASSERT_EQUAL_FLOAT(1.0f, again->x->rr_k);
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(again, NULL));
        TEST_ASSERT_TRUE_MESSAGE(memcmp(&k, &again->x->rr_k, sizeof k) == 0, msg);
    }
    with_k = batch_mean(spot, &rd, 16, 20, 500);
    spot->x->rr_k = 1.0f;                                   /* the plain roulette, same scene */
    with_1 = batch_mean(spot, &rd, 16, 20, 600);
    assert_means_agree(with_k, with_1, "spot-lit fog, roulette with the pilot's k vs k = 1");
    with_k = batch_mean(glass, &rd, 16, 20, 700);
    glass->x->rr_k = 1.0f;
    with_1 = batch_mean(glass, &rd, 16, 20, 800);
    assert_means_agree(with_k, with_1, "fog-free box with glass, roulette with the pilot's k vs k = 1");
    fogrt_scene_destroy(spot); fogrt_scene_destroy(again); fogrt_scene_destroy(box); fogrt_scene_destroy(glass);
    fogrt_scene_destroy(open); fogrt_scene_destroy(def);
#endif
}

/* ------------------------------------------------------------------------------------------
   The default scene
   ------------------------------------------------------------------------------------------ */

/* 64x48 at 4 spp: every sample counted, every pixel finite and non-negative, no rejected
   (non-finite) samples, a lit image with structure (not one flat value). */
static void test_default_scene_renders(void)
{
    fogrt_scene *scene = default_scene();
    fogrt_render_desc rd = render_desc(64, 48, 1);
    fogrt_render_stats stats;
    fogrt_error_estimate err;
    fogrt_image img;
    float *rgb;
    size_t i, n;
    double mean, min_lum = 1e30, max_lum = 0;
    render_new(scene, &rd, 4, &img, &stats);
    n = pixels(&img);
    rgb = (float *)malloc(sizeof(float) * 3 * n);
    TEST_ASSERT_NOT_NULL(rgb);
    fogrt_image_resolve(&img, rgb);
    for (i = 0; i < n; i++) {
        double lum = (rgb[3 * i] + rgb[3 * i + 1] + rgb[3 * i + 2]) / 3.0;
        TEST_ASSERT_EQUAL_UINT32(4, img.count[i]);
        TEST_ASSERT_FLOAT_IS_DETERMINATE(rgb[3 * i]);
        TEST_ASSERT_FLOAT_IS_DETERMINATE(rgb[3 * i + 1]);
        TEST_ASSERT_FLOAT_IS_DETERMINATE(rgb[3 * i + 2]);
        TEST_ASSERT_FLOAT_IS_DETERMINATE(img.sum_sq[i]);
        TEST_ASSERT_TRUE(rgb[3 * i] >= 0.0f && rgb[3 * i + 1] >= 0.0f && rgb[3 * i + 2] >= 0.0f);
        if (lum < min_lum) min_lum = lum;
        if (lum > max_lum) max_lum = lum;
    }
    TEST_ASSERT_EQUAL_UINT64(0, img.rejected);
    TEST_ASSERT_EQUAL_UINT64(0, stats.rejected);
    TEST_ASSERT_EQUAL_UINT64(64 * 48 * 4, stats.camera_rays);
    TEST_ASSERT_TRUE(stats.rays > stats.camera_rays);     /* bounces and shadow rays too */
    mean = image_mean(&img);
    TEST_ASSERT_TRUE(mean > 0.0);
    TEST_ASSERT_TRUE(max_lum > 2.0 * min_lum);            /* walls, lamp and shadows differ */
    fogrt_image_error(&img, &err);
    TEST_ASSERT_EQUAL_UINT64(64 * 48 * 4, err.samples);
    TEST_ASSERT_EQUAL_UINT64(0, err.rejected);
    TEST_ASSERT_TRUE(err.mean_luminance > 0.0);
    TEST_ASSERT_TRUE(err.relative_error > 0.0 && err.relative_error < 10.0);
    free(rgb);
    fogrt_image_free(&img);
    fogrt_scene_destroy(scene);
}

/* The image does not depend on the thread count: threads = 1 and threads = 2 give the same
   bits (each sample's random stream depends only on seed, pixel and sample index). */
static void test_threads_bit_identical(void)
{
    fogrt_scene *scene = default_scene();
    fogrt_render_desc rd = render_desc(48, 36, 7);
    fogrt_image one, two;
    rd.threads = 1;
    render_new(scene, &rd, 4, &one, NULL);
    rd.threads = 2;
    render_new(scene, &rd, 4, &two, NULL);
    assert_same_image(&one, &two, "threads = 1 vs threads = 2");
#ifndef _OPENMP
    TEST_MESSAGE("built without OpenMP: both renders ran on one thread");
#endif
    fogrt_image_free(&one);
    fogrt_image_free(&two);
    fogrt_scene_destroy(scene);
}

/* Progressive rendering: 2 + 2 samples (and 1 + 3) in separate calls give the same bits as
   4 in one call; and 3 + 6 + 7 the same as 16, batches that split the pixel streams'
   stratified sequences (4 points each) in the middle. */
static void test_split_samples_identical(void)
{
    fogrt_scene *scene = default_scene();
    fogrt_render_desc rd = render_desc(48, 36, 3);
    fogrt_image once, split;
    render_new(scene, &rd, 16, &once, NULL);
    render_new(scene, &rd, 3, &split, NULL);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_render(scene, &rd, &split, 6, NULL));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_render(scene, &rd, &split, 7, NULL));
    assert_same_image(&once, &split, "16 spp vs 3 + 6 + 7 spp");
    fogrt_image_free(&once);
    fogrt_image_free(&split);
    render_new(scene, &rd, 4, &once, NULL);
    render_new(scene, &rd, 2, &split, NULL);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_render(scene, &rd, &split, 2, NULL));
    assert_same_image(&once, &split, "4 spp vs 2 + 2 spp");
    fogrt_image_clear(&split);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_render(scene, &rd, &split, 1, NULL));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_render(scene, &rd, &split, 3, NULL));
    assert_same_image(&once, &split, "4 spp vs 1 + 3 spp after fogrt_image_clear");
    fogrt_image_free(&once);
    fogrt_image_free(&split);
    fogrt_scene_destroy(scene);
}

/* The stratified pixel positions (chapter 15). In each stream of a pixel (sample indices
   r, r + 4, r + 8, ...) every aligned block of 2^m points is a (0,m,2)-net: for each split
   of the pixel into 2^a columns and 2^b rows, a + b = m, every cell holds exactly one
   point (checked for m = 4 over 200 pixel streams and m = 6 over 8, with later blocks too:
   points 16..31). Each point alone is uniform over the pixel (chi-square over 8 x 8 cells
   of point 0 and of point 5, over 4096 pixel streams, below 113.7, the p = 1e-4 bound for
   63 degrees of freedom), and the four streams of a pixel are uncorrelated (|r| of their
   x and y below 4.5 / sqrt(N)). Fails on a scramble that is not nested (cells hold 0 or 2
   points), on one that is not uniform, or on streams that share their scramble. */
#ifndef FOGRT_MINIMAL   /* helpers of Part II's test below */
static int count_net_failures(uint64_t base, uint64_t pix, int stream, int first, int m)
{
    int a, fails = 0, n = 1 << m;
    for (a = 0; a <= m; ++a) {
        int cells[64] = { 0 }, i, b = m - a;
        for (i = 0; i < n; ++i) {
            float jx, jy;
            int cx, cy;
            fogrt__stratified_position(base, pix, (uint32_t)(FOGRT_IMAGE_STREAMS * (first + i) + stream), &jx, &jy);
            TEST_ASSERT_TRUE(jx >= 0.0f && jx < 1.0f && jy >= 0.0f && jy < 1.0f);
            cx = (int)(jx * (float)(1 << a)); cy = (int)(jy * (float)(1 << b));
            cells[(cy << a) + cx]++;
        }
        for (i = 0; i < n; ++i) fails += cells[i] != 1;
    }
    return fails;
}
static double chi2_8x8(uint64_t base, int point)
{
    double cells[64] = { 0 }, chi2 = 0.0, expected = 4096.0 / 64.0;
    int i;
    for (i = 0; i < 4096; ++i) {
        float jx, jy;
        fogrt__stratified_position(base, (uint64_t)(i / 4), (uint32_t)(FOGRT_IMAGE_STREAMS * point + i % 4), &jx, &jy);
        cells[(int)(jy * 8.0f) * 8 + (int)(jx * 8.0f)] += 1.0;
    }
    for (i = 0; i < 64; ++i) chi2 += (cells[i] - expected) * (cells[i] - expected) / expected;
    return chi2;
}
#endif
static void test_pixel_positions_stratified(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("C: stratified pixel streams");
#else
    uint64_t base = fogrt__hash64(7);
    int p, r, fails = 0, pairs = 0;
    double c0, c5, sxy[FOGRT_IMAGE_STREAMS][2], cross[2] = { 0.0, 0.0 };
    char msg[200];
    for (p = 0; p < 50; ++p)
        for (r = 0; r < FOGRT_IMAGE_STREAMS; ++r) {
            fails += count_net_failures(base, (uint64_t)p * 7919u, r, 0, 4);
            fails += count_net_failures(base, (uint64_t)p * 7919u, r, 16, 4);
        }
    for (p = 0; p < 8; ++p) fails += count_net_failures(base, (uint64_t)p, p % 4, 0, 6);
    snprintf(msg, sizeof msg, "%d cells of the (0,m,2)-net checks do not hold exactly one point", fails);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, fails, msg);
    c0 = chi2_8x8(base, 0);
    c5 = chi2_8x8(base, 5);
    snprintf(msg, sizeof msg, "uniformity: chi-square %.1f (point 0), %.1f (point 5), 63 dof", c0, c5);
    TEST_MESSAGE(msg);
    TEST_ASSERT_TRUE_MESSAGE(c0 < 113.7 && c5 < 113.7, msg);
    /* correlation of the streams' first points, stream 0 against streams 1..3 */
    for (p = 0; p < 4096; ++p) {
        for (r = 0; r < FOGRT_IMAGE_STREAMS; ++r) {
            float jx, jy;
            fogrt__stratified_position(base, (uint64_t)p, (uint32_t)r, &jx, &jy);
            sxy[r][0] = jx - 0.5; sxy[r][1] = jy - 0.5;
        }
        for (r = 1; r < FOGRT_IMAGE_STREAMS; ++r) {
            cross[0] += sxy[0][0] * sxy[r][0] * 12.0;   /* 12 = 1 / Var[U(0,1)]: a correlation */
            cross[1] += sxy[0][1] * sxy[r][1] * 12.0;
        }
        pairs += FOGRT_IMAGE_STREAMS - 1;
    }
    snprintf(msg, sizeof msg, "streams: correlation %.4f (x), %.4f (y) over %d pairs", cross[0] / pairs, cross[1] / pairs, pairs);
    TEST_MESSAGE(msg);
    TEST_ASSERT_TRUE_MESSAGE(fabs(cross[0] / pairs) < 4.5 / sqrt((double)pairs) && fabs(cross[1] / pairs) < 4.5 / sqrt((double)pairs), msg);
#endif
}

/* The same seed gives the same image; another seed gives a different one (in most pixels,
   not just a few: the seed must reach every pixel's stream). */
static void test_seeds(void)
{
    fogrt_scene *scene = default_scene();
    fogrt_render_desc rd = render_desc(32, 24, 11);
    fogrt_image a, b, c;
    size_t i, n, differ = 0;
    render_new(scene, &rd, 2, &a, NULL);
    render_new(scene, &rd, 2, &b, NULL);
    rd.seed = 12;
    render_new(scene, &rd, 2, &c, NULL);
    assert_same_image(&a, &b, "same seed");
    n = pixels(&a);
    for (i = 0; i < n; i++) differ += memcmp(&a.sum[3 * i], &c.sum[3 * i], 3 * sizeof(double)) != 0;
    TEST_ASSERT_GREATER_THAN(n * 9 / 10, differ);
    fogrt_image_free(&a);
    fogrt_image_free(&b);
    fogrt_image_free(&c);
    fogrt_scene_destroy(scene);
}

/* The progress callback sees every row block in order, with the render's size and sample
   count; returning false stops the render with FOGRT_RESULT_CANCELLED at once (rows not yet
   started get no samples). */
typedef struct progress_log {
    int calls, last_rows_done, rows_total, spp, bad_order, cancel_after;
} progress_log;

static bool on_progress(const fogrt_progress *p, void *user_data)
{
    progress_log *log = (progress_log *)user_data;
    log->calls++;
    if (p->rows_done <= log->last_rows_done || p->rows_done > p->rows_total) log->bad_order++;
    log->last_rows_done = p->rows_done;
    log->rows_total = p->rows_total;
    log->spp = p->samples_per_pixel;
    return !(log->cancel_after > 0 && log->calls >= log->cancel_after);
}

static void test_progress_and_cancel(void)
{
    fogrt_scene *scene = default_scene();
    fogrt_render_desc rd = render_desc(16, 40, 5);
    progress_log log;
    fogrt_image img;
    int x, y, rows_with_samples = 0;
    memset(&log, 0, sizeof log);
    rd.progress = on_progress;
    rd.user_data = &log;
    render_new(scene, &rd, 2, &img, NULL);
    TEST_ASSERT_GREATER_OR_EQUAL(1, log.calls);
    TEST_ASSERT_EQUAL_INT(0, log.bad_order);
    TEST_ASSERT_EQUAL_INT(40, log.last_rows_done);
    TEST_ASSERT_EQUAL_INT(40, log.rows_total);
    TEST_ASSERT_EQUAL_INT(2, log.spp);

    /* Cancel at the first callback. */
    memset(&log, 0, sizeof log);
    log.cancel_after = 1;
    fogrt_image_clear(&img);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_CANCELLED, fogrt_render(scene, &rd, &img, 2, NULL));
    TEST_ASSERT_EQUAL_INT(1, log.calls);
    TEST_ASSERT_LESS_THAN(40, log.last_rows_done);
    for (y = 0; y < 40; y++) {
        int counted = 0;
        for (x = 0; x < 16; x++) counted += img.count[y * 16 + x] != 0;
        TEST_ASSERT_TRUE(counted == 0 || counted == 16);   /* rows are done whole */
        rows_with_samples += counted == 16;
    }
    TEST_ASSERT_EQUAL_INT(log.last_rows_done, rows_with_samples);
    fogrt_image_free(&img);
    fogrt_scene_destroy(scene);
}

/* ------------------------------------------------------------------------------------------
   The error estimate
   ------------------------------------------------------------------------------------------ */

/* Monte Carlo error falls as 1/sqrt(spp): fogrt_image_error at 16 spp is about half of that
   at 4 spp (accepted: 0.35 .. 0.65). And the estimate is calibrated: the RMS difference of two
   independent 16 spp renders is sqrt(2) times the error of one, so measured / predicted must
   be near 1 (accepted: 0.7 .. 1.4). */
/* The relative error of one image measured against an independent render of the same
   spp, in luminance (Rec. 709 weights): their difference has twice each one's variance. */
static double measured_relative_error(const fogrt_image *x, const fogrt_image *y)
{
    size_t i, n = pixels(x);
    float *a = (float *)malloc(sizeof(float) * 3 * n), *b = (float *)malloc(sizeof(float) * 3 * n);
    double diff_sq = 0, mean_sq = 0;
    TEST_ASSERT_TRUE(a && b);
    fogrt_image_resolve(x, a);
    fogrt_image_resolve(y, b);
    for (i = 0; i < n; i++) {
        double la = luminance(a[3 * i], a[3 * i + 1], a[3 * i + 2]);
        double lb = luminance(b[3 * i], b[3 * i + 1], b[3 * i + 2]);
        diff_sq += (la - lb) * (la - lb);
        mean_sq += 0.5 * (la * la + lb * lb);
    }
    free(a); free(b);
    return sqrt(diff_sq / mean_sq) / sqrt(2.0);
}
/* x's own error estimate against the error measured between x and y: within 0.7 to 1.4. */
static void assert_estimate_calibrated(const fogrt_image *x, const fogrt_image *y, const char *what)
{
    fogrt_error_estimate e;
    double measured = measured_relative_error(x, y), ratio;
    char msg[200];
    fogrt_image_error(x, &e);
    ratio = measured / e.relative_error;
    snprintf(msg, sizeof msg, "%s: measured relative error %.4f, estimated %.4f, ratio %.3f (ideal 1)",
             what, measured, e.relative_error, ratio);
    TEST_MESSAGE(msg);
    TEST_ASSERT_TRUE_MESSAGE(ratio >= 0.7 && ratio <= 1.4, msg);
}

static void test_error_estimate(void)
{
    fogrt_scene *scene = default_scene();
    fogrt_render_desc rd = render_desc(64, 48, 21);
    fogrt_image i4, i16, j16;
    fogrt_error_estimate e4, e16;
    double ratio;
    char msg[200];
#ifdef FOGRT_MINIMAL   /* Part I's samples of the lamp in fog have a heavier tail: four times the spp */
    const int lo = 16, hi = 64;
#else
    const int lo = 4, hi = 16;
#endif
    render_new(scene, &rd, lo, &i4, NULL);
    rd.seed = 22;
    render_new(scene, &rd, hi, &i16, NULL);
    rd.seed = 23;
    render_new(scene, &rd, hi, &j16, NULL);
    fogrt_image_error(&i4, &e4);
    fogrt_image_error(&i16, &e16);
    ratio = e16.relative_error / e4.relative_error;
    snprintf(msg, sizeof msg, "relative error: %.4f at %d spp, %.4f at %d spp, ratio %.3f (ideal 0.5)",
             e4.relative_error, lo, e16.relative_error, hi, ratio);
    TEST_MESSAGE(msg);
    TEST_ASSERT_TRUE_MESSAGE(ratio >= 0.35 && ratio <= 0.65, msg);
    TEST_ASSERT_EQUAL_UINT64(64 * 48 * (uint64_t)hi, e16.samples);

    assert_estimate_calibrated(&i16, &j16, hi == 16 ? "16 spp" : "64 spp");   /* against an independent render */
    fogrt_image_free(&i4);
    fogrt_image_free(&i16);
    fogrt_image_free(&j16);
    fogrt_scene_destroy(scene);
}

/* ------------------------------------------------------------------------------------------
   Unbiasedness: different estimators of the same image agree
   ------------------------------------------------------------------------------------------ */

/* Without fog, next-event estimation with MIS, NEE without MIS and no NEE at all are three
   unbiased estimators of one image: their means agree within noise. Fails on a double-counted
   or dropped emitter (a wrong MIS weight, emission after a specular bounce lost, a wrong
   light pdf). */
static void test_nee_unbiased_without_fog(void)
{
    fogrt_scene *scene = area_light_box(0.0f, true, 0.7f);
    fogrt_render_desc rd = render_desc(24, 18, 0);
    batch_estimate with_mis, without_mis, no_nee;
    TEST_ASSERT_EQUAL_UINT32(0, fogrt_scene_get_features(scene) & FOGRT_FEATURE_MEDIUM);
    /* 20 batches each: no NEE finds the small lamp only by hitting it, its batch means are
       heavy-tailed, and 10 batches (9 degrees of freedom) estimate its standard error so
       poorly that an unbiased pair can land 4.1 errors apart (seen at one seed; 6 x 40
       further batches agreed within 2.2 errors) */
    with_mis = batch_mean(scene, &rd, 8, 20, 100);
    rd.mis = false;
    without_mis = batch_mean(scene, &rd, 8, 20, 200);
    rd.mis = true;
    rd.nee = false;
    no_nee = batch_mean(scene, &rd, 8, 20, 300);
    assert_means_agree(with_mis, no_nee, "NEE + MIS vs no NEE");
    assert_means_agree(without_mis, no_nee, "NEE without MIS vs no NEE");
    fogrt_scene_destroy(scene);
}

/* The same in fog: NEE through the phase function (with transmittance on the shadow ray) must
   agree with finding the lamp by phase sampling alone. */
static void test_nee_unbiased_in_fog(void)
{
    fogrt_scene *scene = area_light_box(0.6f, true, 0.7f);
    fogrt_render_desc rd = render_desc(24, 18, 0);
    batch_estimate with_nee, no_nee;
    TEST_ASSERT_TRUE(fogrt_scene_get_features(scene) & FOGRT_FEATURE_MEDIUM);
    with_nee = batch_mean(scene, &rd, 8, 10, 400);
    rd.nee = false;
    no_nee = batch_mean(scene, &rd, 8, 10, 500);
    assert_means_agree(with_nee, no_nee, "in fog: NEE + MIS vs no NEE");
    fogrt_scene_destroy(scene);
}

/* Aiming at the glow of the lamps (render desc glow, chapter 14 d') changes how directions
   are drawn in fog, not what is estimated: in a fog-filled box lit by a spot, a point light
   and a small area lamp (so the MIS weights at the same vertices use the mixture's pdf), the
   image mean with the glow agrees with the mean without it, and with the estimator that
   finds point and spot lights only at fog collisions (equiangular off, which turns the glow
   off too), and with the glow that leaves out the spot's footprint on the floor. Fails on a
   mixture pdf that does not match the directions drawn, on a light
   sample whose MIS weight uses the phase pdf alone, or on roulette that forgets the
   mixture's weight. */
static void test_glow_unbiased(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("B: the glow and footprint of a lamp");
#else
    fogrt_scene *scene = NULL;
    fogrt_light_desc spot, point;
    fogrt_render_desc rd = render_desc(24, 18, 0);
    batch_estimate glow, no_glow, no_footprint, collisions;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_create(NULL, &scene));
    add_closed_box(scene, 0.15f, 6.0f);
    memset(&spot, 0, sizeof spot);
    spot.type = FOGRT_LIGHT_SPOT;
    spot.position = v3(0.2f, 1.6f, -0.2f); spot.direction = v3(0.0f, -1.0f, 0.1f);
    spot.intensity = v3(2.0f, 1.8f, 1.5f); spot.cutoff_deg = 30.0f; spot.beam_deg = 20.0f;
    point = spot;
    point.type = FOGRT_LIGHT_POINT; point.position = v3(-0.5f, 0.6f, 0.1f); point.intensity = v3(0.4f, 0.5f, 0.6f);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_light(scene, &spot));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_light(scene, &point));
    set_camera(scene, v3(0, 1, 0.95f), v3(0, 0.8f, 0), 75.0f);
    set_medium(scene, 0.8f, v3(0.9f, 0.9f, 0.9f), 0.6f);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    /* the spot lights the floor: its footprint is aimed at too; the point light has none */
    TEST_ASSERT_TRUE_MESSAGE(scene->x->footprints && scene->x->footprints[0].on && !scene->x->footprints[1].on,
                             "the build found no footprint for the spot over the floor (or one for the point light)");
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 1.0f, scene->x->footprints[0].n.y);
    TEST_ASSERT_TRUE_MESSAGE(scene->x->footprints[0].radius > 0.0f, "no sphere around the spot's lit patch on the floor");
    glow = batch_mean(scene, &rd, 8, 12, 600);
    rd.footprint = false;
    no_footprint = batch_mean(scene, &rd, 8, 12, 900);
    rd.footprint = true;
    rd.glow = false;
    no_glow = batch_mean(scene, &rd, 8, 12, 700);
    rd.glow = true;
    rd.equiangular = false;
    collisions = batch_mean(scene, &rd, 32, 12, 800);
    assert_means_agree(glow, no_glow, "glow on vs off");
    assert_means_agree(glow, no_footprint, "glow with the spot's footprint vs without it");
    assert_means_agree(glow, collisions, "glow on vs lights found at fog collisions only");
    fogrt_scene_destroy(scene);
#endif
}

/* expected_emission (the default) is another estimator of the same image: in the closed box
   filled with fog, looking up at its lamp, the means agree with the paper's way (the lamp's
   light only when a free flight reaches it), with and without next-event estimation, and
   the image's error at equal samples is well below it (the lamp's pixels no longer flicker
   between Le and 0). Fails on an emission counted with the wrong transmittance, counted twice
   on the surface branch, or with the throughput after a collision's albedo. */
static void test_expected_emission_unbiased(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("E: expected emission");
#else
    int nee;
    for (nee = 0; nee < 2; ++nee) {
        fogrt_scene *scene = NULL;
        fogrt_render_desc rd = render_desc(24, 18, 0);
        fogrt_image img;
        fogrt_error_estimate e_on, e_off;
        batch_estimate on, off;
        char msg[160];
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_create(NULL, &scene));
        add_closed_box(scene, 0.3f, 6.0f);
        set_camera(scene, v3(0, 0.7f, 0.9f), v3(0, 1.99f, 0), 70.0f);
        set_medium(scene, 0.8f, v3(0.85f, 0.85f, 0.85f), 0.3f);
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
        rd.nee = nee == 1;
        on = batch_mean(scene, &rd, 8, 12, 900);
        render_new(scene, &rd, 32, &img, NULL);
        fogrt_image_error(&img, &e_on);
        fogrt_image_free(&img);
        rd.expected_emission = false;
        off = batch_mean(scene, &rd, 8, 12, 1000);
        render_new(scene, &rd, 32, &img, NULL);
        fogrt_image_error(&img, &e_off);
        fogrt_image_free(&img);
        snprintf(msg, sizeof msg, "NEE %s: expected emission on vs off", nee ? "on" : "off");
        assert_means_agree(on, off, msg);
        snprintf(msg, sizeof msg, "NEE %s: relative error at 32 spp %.4f (on) vs %.4f (off)", nee ? "on" : "off",
                 e_on.relative_error, e_off.relative_error);
        TEST_MESSAGE(msg);
        TEST_ASSERT_TRUE_MESSAGE(e_on.relative_error < 0.8 * e_off.relative_error, msg);
        fogrt_scene_destroy(scene);
    }
#endif
}

/* Choosing one light per vertex by power (render desc light_by_power) is another estimator
   of the same image: in the closed box with its area lamp, an emissive sphere, a spot and a
   point light of very different powers, without fog and with it, the means with one light
   picked by power agree with sampling every light, and it traces fewer rays. Fails on a
   pick probability left out of the sample's weight or of the MIS weights (at the light
   sample, or where a BSDF sample hits the lamp or the emissive sphere). */
static void test_lights_by_power_unbiased(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("C: lights chosen by power");
#else
    for (int fog = 0; fog < 2; fog++) {
        fogrt_scene *scene = NULL;
        fogrt_light_desc spot, point;
        fogrt_render_desc rd = render_desc(24, 18, 0);
        fogrt_render_stats st_all, st_power;
        fogrt_image img;
        batch_estimate all, power;
        char what[64];
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_create(NULL, &scene));
        add_closed_box(scene, 0.2f, 6.0f);
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_sphere(scene, v3(0.5f, 0.3f, -0.3f), 0.15f,
                                                                     add_material(scene, FOGRT_BSDF_DIFFUSE, v3(0, 0, 0), v3(3.0f, 2.0f, 1.0f))));
        memset(&spot, 0, sizeof spot);
        spot.type = FOGRT_LIGHT_SPOT;
        spot.position = v3(-0.3f, 1.7f, 0.0f); spot.direction = v3(0.1f, -1.0f, 0.0f);
        spot.intensity = v3(3.0f, 3.0f, 3.0f); spot.cutoff_deg = 35.0f; spot.beam_deg = 25.0f;
        point = spot;
        point.type = FOGRT_LIGHT_POINT; point.position = v3(0.4f, 1.2f, 0.3f); point.intensity = v3(0.05f, 0.05f, 0.08f);
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_light(scene, &spot));
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_light(scene, &point));
        set_camera(scene, v3(0, 1, 0.95f), v3(0, 0.8f, 0), 75.0f);
        if (fog) set_medium(scene, 0.5f, v3(0.9f, 0.9f, 0.9f), 0.3f);
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
        all = batch_mean(scene, &rd, 8, 12, 900 + 100 * (uint64_t)fog);
        render_new(scene, &rd, 4, &img, &st_all);
        fogrt_image_free(&img);
        rd.light_by_power = true;
        power = batch_mean(scene, &rd, 16, 12, 950 + 100 * (uint64_t)fog);
        render_new(scene, &rd, 4, &img, &st_power);
        fogrt_image_free(&img);
        snprintf(what, sizeof what, "%s: every light vs one light by power", fog ? "in fog" : "without fog");
        assert_means_agree(all, power, what);
        TEST_ASSERT_TRUE_MESSAGE(st_power.rays < st_all.rays, what);
        fogrt_scene_destroy(scene);
    }
#endif
}

/* The DIRECT integrator (one bounce, the paper's baseline) estimates the same quantity as
   path tracing cut after one bounce (max_depth = 1): emitted plus direct light. With MIS on
   (the default) and off, without fog and with it, in a box with a large lamp (where BSDF
   sampling finds the lamp often, so MIS weights matter) and without mirror or glass (through
   those DIRECT follows the specular chain to the first diffuse surface, while max_depth
   counts the bounce). Fails if MIS-weighted light samples are not completed by the BSDF
   samples that hit the lamp. */
static void test_direct_integrator(void)
{
    static const float sigmas[2] = { 0.0f, 0.6f };
    int k;
    for (k = 0; k < 2; k++) {
        fogrt_scene *scene = area_light_box(sigmas[k], false, 0.95f);
        fogrt_render_desc rd = render_desc(24, 18, 0);
        batch_estimate direct, direct_no_mis, path1, full;
        char what[96];
        rd.integrator = FOGRT_INTEGRATOR_PATH;
        rd.max_depth = 1;
        path1 = batch_mean(scene, &rd, 8, 10, 700);
        rd.max_depth = 64;
        full = batch_mean(scene, &rd, 8, 4, 800);
        rd.integrator = FOGRT_INTEGRATOR_DIRECT;
        direct = batch_mean(scene, &rd, 8, 10, 600);
        rd.mis = false;
        direct_no_mis = batch_mean(scene, &rd, 8, 10, 900);
        snprintf(what, sizeof what, "sigma_t %g: DIRECT (no MIS) vs PATH with max_depth 1", sigmas[k]);
        assert_means_agree(direct_no_mis, path1, what);
        snprintf(what, sizeof what, "sigma_t %g: DIRECT (MIS) vs PATH with max_depth 1", sigmas[k]);
        assert_means_agree(direct, path1, what);
        /* Indirect light only adds: full path tracing is clearly brighter. */
        TEST_ASSERT_TRUE(full.mean > path1.mean + 4.0 * (full.std_error + path1.std_error));
        fogrt_scene_destroy(scene);
    }
}

/* The DIRECT integrator on the default scene (fog, spot light, glass): finite and lit. */
static void test_direct_default_scene(void)
{
    fogrt_scene *scene = default_scene();
    fogrt_render_desc rd = render_desc(32, 24, 31);
    fogrt_image img;
    size_t i;
    rd.integrator = FOGRT_INTEGRATOR_DIRECT;
    render_new(scene, &rd, 4, &img, NULL);
    TEST_ASSERT_EQUAL_UINT64(0, img.rejected);
    for (i = 0; i < 3 * pixels(&img); i++) TEST_ASSERT_FLOAT_IS_DETERMINATE(img.sum[i]);
    TEST_ASSERT_TRUE(image_mean(&img) > 0.0);
    fogrt_image_free(&img);
    fogrt_scene_destroy(scene);
}

/* ------------------------------------------------------------------------------------------
   Cameras
   ------------------------------------------------------------------------------------------ */

/* A thin-lens camera: ray origins lie on the lens disk (radius lens_radius, perpendicular to
   the view), and all rays through one pixel meet again on the plane in focus. The image
   renders finite and differs from the pinhole image. */
static void test_thin_lens(void)
{
    fogrt_scene *scene = NULL;
    fogrt_camera_desc cam;
    fogrt_render_desc rd = render_desc(32, 24, 41);
    fogrt_image pin, lens;
    fogrt_vec3 fwd, focus0 = v3(0, 0, 0);
    float len;
    size_t i;
    int k;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_create(NULL, &scene));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_default(scene));
    fogrt_scene_get_camera(scene, &cam);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    render_new(scene, &rd, 4, &pin, NULL);

    cam.lens_radius = 0.1f;
    cam.focal_distance = 3.0f;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_set_camera(scene, &cam));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    fwd = v3(cam.look_at.x - cam.position.x, cam.look_at.y - cam.position.y, cam.look_at.z - cam.position.z);
    len = sqrtf(fwd.x * fwd.x + fwd.y * fwd.y + fwd.z * fwd.z);
    fwd = v3(fwd.x / len, fwd.y / len, fwd.z / len);
    for (k = 0; k < 9; k++) {
        fogrt_vec3 o, d, rel, focus;
        float lu1 = 0.05f + 0.1f * (float)k, lu2 = 0.9f - 0.1f * (float)k, along, t;
        fogrt_camera_ray(scene, 32, 24, 7.5f, 20.25f, lu1, lu2, &o, &d);
        TEST_ASSERT_FLOAT_WITHIN(1e-5f, 1.0f, sqrtf(d.x * d.x + d.y * d.y + d.z * d.z));
        rel = v3(o.x - cam.position.x, o.y - cam.position.y, o.z - cam.position.z);
        along = rel.x * fwd.x + rel.y * fwd.y + rel.z * fwd.z;
        TEST_ASSERT_FLOAT_WITHIN(1e-5f, 0.0f, along);                                   /* on the lens plane */
        TEST_ASSERT_TRUE(sqrtf(rel.x * rel.x + rel.y * rel.y + rel.z * rel.z) <= 0.1f + 1e-5f);   /* inside the lens */
        t = (3.0f - along) / (d.x * fwd.x + d.y * fwd.y + d.z * fwd.z);                   /* to the focal plane */
        focus = v3(o.x + t * d.x, o.y + t * d.y, o.z + t * d.z);
        if (k == 0) focus0 = focus;
        TEST_ASSERT_FLOAT_WITHIN(1e-4f, focus0.x, focus.x);
        TEST_ASSERT_FLOAT_WITHIN(1e-4f, focus0.y, focus.y);
        TEST_ASSERT_FLOAT_WITHIN(1e-4f, focus0.z, focus.z);
    }
    render_new(scene, &rd, 4, &lens, NULL);
    TEST_ASSERT_EQUAL_UINT64(0, lens.rejected);
    for (i = 0; i < 3 * pixels(&lens); i++) TEST_ASSERT_FLOAT_IS_DETERMINATE(lens.sum[i]);
    TEST_ASSERT_TRUE(image_mean(&lens) > 0.0);
    TEST_ASSERT_FALSE(memcmp(pin.sum, lens.sum, sizeof(double) * 3 * pixels(&pin)) == 0);
    fogrt_image_free(&pin);
    fogrt_image_free(&lens);
    fogrt_scene_destroy(scene);
}

/* A pinhole camera: every ray starts at the eye; the centre of the image looks at look_at. */
static void test_pinhole_rays(void)
{
    fogrt_scene *scene = default_scene();
    fogrt_camera_desc cam;
    fogrt_vec3 o, d, to;
    float len;
    fogrt_scene_get_camera(scene, &cam);
    fogrt_camera_ray(scene, 64, 48, 32.0f, 24.0f, 0.3f, 0.8f, &o, &d);
    TEST_ASSERT_EQUAL_FLOAT(cam.position.x, o.x);
    TEST_ASSERT_EQUAL_FLOAT(cam.position.y, o.y);
    TEST_ASSERT_EQUAL_FLOAT(cam.position.z, o.z);
    to = v3(cam.look_at.x - o.x, cam.look_at.y - o.y, cam.look_at.z - o.z);
    len = sqrtf(to.x * to.x + to.y * to.y + to.z * to.z);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, to.x / len, d.x);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, to.y / len, d.y);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, to.z / len, d.z);
    /* The top row looks up (+y), the left column looks left (-x, camera looks down -z). */
    fogrt_camera_ray(scene, 64, 48, 32.0f, 0.0f, 0.5f, 0.5f, &o, &d);
    TEST_ASSERT_TRUE(d.y > to.y / len);
    fogrt_camera_ray(scene, 64, 48, 0.0f, 24.0f, 0.5f, 0.5f, &o, &d);
    TEST_ASSERT_TRUE(d.x < 0.0f);
    fogrt_scene_destroy(scene);
}

/* An empty scene lit only by a uniform environment, without fog: every camera ray escapes
   and sees exactly the environment radiance (zero variance); with upper_hemisphere_only, a
   downward ray sees nothing. */
static void test_environment_only(void)
{
    fogrt_scene *scene = NULL;
    fogrt_render_desc rd = render_desc(8, 6, 1);
    fogrt_image img;
    fogrt_rng rng;
    fogrt_vec3 L;
    float *rgb;
    size_t i;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_create(NULL, &scene));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_set_environment(scene, v3(0.25f, 0.5f, 1.0f), false));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    render_new(scene, &rd, 3, &img, NULL);
    rgb = (float *)malloc(sizeof(float) * 3 * pixels(&img));
    TEST_ASSERT_NOT_NULL(rgb);
    fogrt_image_resolve(&img, rgb);
    for (i = 0; i < pixels(&img); i++) {
        TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.25f, rgb[3 * i]);
        TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.5f, rgb[3 * i + 1]);
        TEST_ASSERT_FLOAT_WITHIN(1e-6f, 1.0f, rgb[3 * i + 2]);
    }
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_set_environment(scene, v3(1, 1, 1), true));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    fogrt_rng_seed(&rng, 1, 2);
    L = fogrt_trace(scene, NULL, v3(0, 0, 0), v3(0, -1, 0), &rng, NULL);
    TEST_ASSERT_EQUAL_FLOAT(0.0f, L.x + L.y + L.z);
    L = fogrt_trace(scene, NULL, v3(0, 0, 0), v3(0.6f, 0.8f, 0), &rng, NULL);
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 1.0f, L.y);
    free(rgb);
    fogrt_image_free(&img);
    fogrt_scene_destroy(scene);
}

/* ------------------------------------------------------------------------------------------
   Output
   ------------------------------------------------------------------------------------------ */

/* 0 -> 0 and 1 -> 255 in every mode; NaN, negatives and -inf -> 0; above 1 and +inf -> 255;
   exposure 0 means 1, exposure 2 doubles; the sRGB curve at 0.5 (0.7354 -> 188) and its
   linear toe (0.001 -> 12.92 * 0.001 -> 3); gamma 2.2 at 0.5 (0.7297 -> 186); monotonic. */
static void test_tonemap(void)
{
    /* 4 pixels = 12 values. */
    const float in[12] = { 0.0f, 1.0f, (float)NAN, -0.5f, 2.0f, (float)INFINITY,
                           -(float)INFINITY, 0.5f, 0.001f, 0.25f, 0.0f, 0.0f };
    unsigned char out[12], ramp_out[3 * 256];
    float ramp[3 * 256];
    int mode, i;
    for (mode = 0; mode < FOGRT_TONEMAP_NUM; mode++) {
        fogrt_tonemap tm = (fogrt_tonemap)mode;
        unsigned mid = mode == FOGRT_TONEMAP_GAMMA22 ? 186u : 188u;
        fogrt_tonemap_rgb8(in, 2, 2, 0.0f, tm, out);
        TEST_ASSERT_EQUAL_UINT(0, out[0]);
        TEST_ASSERT_EQUAL_UINT(255, out[1]);
        TEST_ASSERT_EQUAL_UINT(0, out[2]);      /* NaN */
        TEST_ASSERT_EQUAL_UINT(0, out[3]);
        TEST_ASSERT_EQUAL_UINT(255, out[4]);
        TEST_ASSERT_EQUAL_UINT(255, out[5]);
        TEST_ASSERT_EQUAL_UINT(0, out[6]);
        TEST_ASSERT_EQUAL_UINT(mid, out[7]);
        if (mode != FOGRT_TONEMAP_GAMMA22) TEST_ASSERT_EQUAL_UINT(3, out[8]);
        /* Exposure 1 stop (x2): 0.5 maps like 1, 0.25 like 0.5. */
        fogrt_tonemap_rgb8(in, 2, 2, 1.0f, tm, out);
        TEST_ASSERT_EQUAL_UINT(255, out[7]);
        TEST_ASSERT_EQUAL_UINT(mid, out[9]);
        TEST_ASSERT_EQUAL_UINT(0, out[2]);      /* NaN stays 0 */
        /* A ramp maps monotonically and covers 0..255. */
        for (i = 0; i < 3 * 256; i++) ramp[i] = (float)i / (3 * 256 - 1.0f);
        fogrt_tonemap_rgb8(ramp, 256, 1, 0.0f, tm, ramp_out);
        for (i = 1; i < 3 * 256; i++) TEST_ASSERT_TRUE(ramp_out[i] >= ramp_out[i - 1]);
        TEST_ASSERT_EQUAL_UINT(0, ramp_out[0]);
        TEST_ASSERT_EQUAL_UINT(255, ramp_out[3 * 256 - 1]);
    }
}

static long file_size(const char *path)
{
    FILE *f = fopen(path, "rb");
    long size;
    if (f == NULL) return -1;
    fseek(f, 0, SEEK_END);
    size = ftell(f);
    fclose(f);
    return size;
}

/* PFM: header "PF", "w h", a negative scale (little endian), then 12 bytes per pixel with the
   bottom row first. PPM: "P6", "w h", "255", then 3 bytes per pixel, top row first. An
   unwritable path gives FOGRT_RESULT_IO_ERROR. */
static void test_write_files(void)
{
    enum { W = 5, H = 3 };
    float rgb[3 * W * H], back[3 * W];
    unsigned char rgb8[3 * W * H], back8[3];
    char path[600], magic[3] = { 0 };
    int w = 0, h = 0, i;
    float scale = 0;
    long size, header;
    FILE *f;
    for (i = 0; i < 3 * W * H; i++) { rgb[i] = 0.01f * (float)i; rgb8[i] = (unsigned char)(i * 5); }

    snprintf(path, sizeof path, "%s/test_render_out.pfm", out_dir);
    TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_RESULT_OK, fogrt_write_pfm(path, W, H, rgb), path);
    f = fopen(path, "rb");
    TEST_ASSERT_NOT_NULL_MESSAGE(f, path);
    TEST_ASSERT_EQUAL_INT(3, fscanf(f, "%2s %d %d", magic, &w, &h));
    TEST_ASSERT_EQUAL_INT(1, fscanf(f, "%f", &scale));
    TEST_ASSERT_EQUAL_INT('\n', fgetc(f));          /* one whitespace byte, then the data */
    header = ftell(f);
    TEST_ASSERT_EQUAL_STRING("PF", magic);
    TEST_ASSERT_EQUAL_INT(W, w);
    TEST_ASSERT_EQUAL_INT(H, h);
    TEST_ASSERT_TRUE(scale < 0.0f);
    TEST_ASSERT_EQUAL_INT(W, (int)fread(back, 3 * sizeof(float), W, f));
    fclose(f);
    TEST_ASSERT_EQUAL_MEMORY(&rgb[3 * W * (H - 1)], back, sizeof back);   /* bottom row first */
    size = file_size(path);
    TEST_ASSERT_EQUAL_INT64(header + 12L * W * H, size);
    remove(path);

    snprintf(path, sizeof path, "%s/test_render_out.ppm", out_dir);
    TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_RESULT_OK, fogrt_write_ppm(path, W, H, rgb8), path);
    f = fopen(path, "rb");
    TEST_ASSERT_NOT_NULL(f);
    TEST_ASSERT_EQUAL_INT(4, fscanf(f, "%2s %d %d %f", magic, &w, &h, &scale));
    TEST_ASSERT_EQUAL_INT('\n', fgetc(f));
    header = ftell(f);
    TEST_ASSERT_EQUAL_STRING("P6", magic);
    TEST_ASSERT_EQUAL_INT(W, w);
    TEST_ASSERT_EQUAL_INT(H, h);
    TEST_ASSERT_EQUAL_FLOAT(255.0f, scale);
    TEST_ASSERT_EQUAL_INT(1, (int)fread(back8, 3, 1, f));
    fclose(f);
    TEST_ASSERT_EQUAL_MEMORY(rgb8, back8, 3);                              /* top row first */
    TEST_ASSERT_EQUAL_INT64(header + 3L * W * H, file_size(path));
    remove(path);

    /* A directory that does not exist, and a directory itself. */
    snprintf(path, sizeof path, "%s/no-such-dir/x.pfm", out_dir);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_IO_ERROR, fogrt_write_pfm(path, W, H, rgb));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_IO_ERROR, fogrt_write_ppm(path, W, H, rgb8));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_IO_ERROR, fogrt_write_pfm(out_dir, W, H, rgb));
}

/* ------------------------------------------------------------------------------------------
   Adaptive sampling: fogrt_image_sample_rates and render desc sample_rate (chapter 15)
   ------------------------------------------------------------------------------------------ */

/* The rates' shape: finite, mean 1 over each colour of the chessboard, none below the floor
   (0.3 of the mean before normalising) nor above FOGRT_MAX_SAMPLE_RATE, uneven where the
   noise is; 1 everywhere in an image without noise; an image without samples is refused.
   And the property that keeps the image unbiased: a pixel's rate does not move when its own
   samples, or any pixel's of its colour, change; it does move when a neighbour of the other
   colour changes (so the first check is not vacuous). */
static void test_sample_rates_shape(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("C: per-pixel rates");
#else
    fogrt_scene *scene = spot_box();
    fogrt_render_desc rd = render_desc(40, 30, 5);
    fogrt_image img, empty;
    size_t i, n, p, q;
    float *r0, *r1;
    double mean[2] = {0, 0}, lo = 1e9, hi = 0;
    char msg[200];
    render_new(scene, &rd, 8, &img, NULL);
    n = pixels(&img);
    r0 = (float *)malloc(sizeof(float) * n);
    r1 = (float *)malloc(sizeof(float) * n);
    TEST_ASSERT_TRUE(r0 && r1);
    CHECK_OK(fogrt_image_sample_rates(&img, r0));
    for (i = 0; i < n; ++i) {
        TEST_ASSERT_TRUE(r0[i] > 0.0f && r0[i] <= FOGRT_MAX_SAMPLE_RATE);
        mean[((i % 40) + i / 40) & 1] += r0[i];
        lo = fmin(lo, r0[i]); hi = fmax(hi, r0[i]);
    }
    snprintf(msg, sizeof msg, "rates: mean %.6f / %.6f, min %.3f, max %.3f", mean[0] / (n / 2), mean[1] / (n / 2), lo, hi);
    TEST_MESSAGE(msg);
    TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-4, 1.0, mean[0] / (double)(n / 2), msg);
    TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-4, 1.0, mean[1] / (double)(n / 2), msg);
    TEST_ASSERT_TRUE_MESSAGE(hi > 1.5 * lo, msg);          /* the spot's cone is noisier than the dark */

    /* pixel p = (20, 15): its own samples and a same-coloured pixel's made wildly noisy */
    p = 15 * 40 + 20; q = 15 * 40 + 22;
    img.stream_sum[FOGRT_IMAGE_STREAMS * p] += 1000.0;
    img.stream_sum[FOGRT_IMAGE_STREAMS * q + 1] += 1000.0;
    CHECK_OK(fogrt_image_sample_rates(&img, r1));
    TEST_ASSERT_TRUE_MESSAGE(r1[p] == r0[p], "a pixel's rate read its own samples");
    TEST_ASSERT_TRUE_MESSAGE(r1[q] == r0[q], "a pixel's rate read its own samples");
    for (i = 0; i < n; ++i)
        if ((((i % 40) + i / 40) & 1) == 1) TEST_ASSERT_TRUE_MESSAGE(r1[i] == r0[i], "a rate read a pixel of its own colour");
    TEST_ASSERT_TRUE_MESSAGE(r1[p + 1] != r0[p + 1], "the other colour's rate next to it did not move");

    /* no noise: every rate 1 */
    for (i = 0; i < FOGRT_IMAGE_STREAMS * n; ++i) img.stream_sum[i] = (double)img.stream_count[i] * 0.25;
    CHECK_OK(fogrt_image_sample_rates(&img, r1));
    for (i = 0; i < n; ++i) TEST_ASSERT_EQUAL_FLOAT(1.0f, r1[i]);
    /* no samples: refused */
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_image_alloc(&empty, 40, 30, NULL));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_INVALID_ARGUMENT, fogrt_image_sample_rates(&empty, r1));
    fogrt_image_free(&empty);
    free(r0); free(r1);
    fogrt_image_free(&img);
    fogrt_scene_destroy(scene);
#endif
}

/* fogrt_render with sample_rate: a pixel of rate 0 gets no sample, one of rate 2.5 gets 2 or
   3 per sample asked (5 after two calls of 1 each on average: the coin must not stick), the
   stats count the samples taken, the image is the same on 1 and 2 threads; rates that are
   NaN, negative or above FOGRT_MAX_SAMPLE_RATE are refused with the image untouched. */
static void test_sample_rates_render(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("C: per-pixel rates");
#else
    fogrt_scene *scene = default_scene();
    fogrt_render_desc rd = render_desc(16, 12, 3);
    fogrt_image a, b;
    fogrt_render_stats st;
    float rates[16 * 12];
    size_t i;
    uint64_t total = 0, twice = 0;
    int k;
    for (i = 0; i < 16 * 12; ++i) rates[i] = i % 3 == 0 ? 0.0f : i % 3 == 1 ? 1.0f : 2.5f;
    rd.sample_rate = rates;
    render_new(scene, &rd, 4, &a, &st);
    for (i = 0; i < 16 * 12; ++i) {
        total += a.count[i];
        if (i % 3 == 0) TEST_ASSERT_EQUAL_UINT32(0, a.count[i]);
        if (i % 3 == 1) TEST_ASSERT_EQUAL_UINT32(4, a.count[i]);
        if (i % 3 == 2) TEST_ASSERT_TRUE(a.count[i] == 10);
    }
    TEST_ASSERT_EQUAL_UINT64(total, st.camera_rays);
    rd.threads = 2;
    render_new(scene, &rd, 4, &b, NULL);
    assert_same_image(&a, &b, "sample rates: 1 and 2 threads");
    fogrt_image_free(&b);
    /* fractional rates over many calls of 1 spp: rate 0.5 gives half a sample a call */
    for (i = 0; i < 16 * 12; ++i) rates[i] = 0.5f;
    rd.threads = 1;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_image_alloc(&b, 16, 12, NULL));
    for (k = 0; k < 40; ++k) CHECK_OK(fogrt_render(scene, &rd, &b, 1, NULL));
    for (i = 0; i < 16 * 12; ++i) { twice += b.count[i]; TEST_ASSERT_TRUE(b.count[i] >= 6 && b.count[i] <= 34); }
    TEST_ASSERT_TRUE(twice > 16 * 12 * 18 && twice < 16 * 12 * 22);   /* 20 per pixel on average */
    fogrt_image_free(&b);
    /* bad rates */
    rates[7] = -1.0f;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_INVALID_ARGUMENT, fogrt_render(scene, &rd, &a, 1, NULL));
    rates[7] = NAN;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_INVALID_ARGUMENT, fogrt_render(scene, &rd, &a, 1, NULL));
    rates[7] = FOGRT_MAX_SAMPLE_RATE * 2.0f;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_INVALID_ARGUMENT, fogrt_render(scene, &rd, &a, 1, NULL));
    TEST_ASSERT_EQUAL_UINT64(total, st.camera_rays);
    for (i = 0, twice = 0; i < 16 * 12; ++i) twice += a.count[i];
    TEST_ASSERT_EQUAL_UINT64(total, twice);
    fogrt_image_free(&a);
    fogrt_scene_destroy(scene);
#endif
}

/* Rendered the way the CLI does (8 spp alike, the rates, then 24 more spp at those rates),
   the spot-lit box seen through fog has the same image mean as with every pixel alike,
   over 16 renders each; and the image's own error estimate still matches the error
   measured between two such renders. Fails on rates that read a pixel's own samples in a
   way that shifts its mean, on a coin that sticks, or on counts that miss the streams. */
#ifndef FOGRT_MINIMAL   /* helper of Part II's test below */
static void render_adaptive_like_cli(const fogrt_scene *scene, fogrt_render_desc rd, fogrt_image *img, float *rates)
{
    render_new(scene, &rd, 8, img, NULL);
    CHECK_OK(fogrt_image_sample_rates(img, rates));
    rd.sample_rate = rates;
    CHECK_OK(fogrt_render(scene, &rd, img, 24, NULL));
}
#endif
static void test_sample_rates_unbiased(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("C: per-pixel rates");
#else
    fogrt_scene *scene = spot_box();
    fogrt_render_desc rd = render_desc(32, 24, 0);
    float *rates = (float *)malloc(sizeof(float) * 32 * 24);
    double sum = 0, sum_sq = 0;
    batch_estimate adaptive, even;
    fogrt_image img, other;
    int k;
    TEST_ASSERT_TRUE(rates != NULL);
    for (k = 0; k < 16; ++k) {
        double m;
        rd.seed = 900 + (uint64_t)k;
        render_adaptive_like_cli(scene, rd, &img, rates);
        m = image_mean(&img);
        sum += m; sum_sq += m * m;
        fogrt_image_free(&img);
    }
    adaptive.mean = sum / 16;
    adaptive.std_error = sqrt(fmax(0.0, (sum_sq / 16 - adaptive.mean * adaptive.mean) * 16 / 15.0) / 16);
    even = batch_mean(scene, &rd, 32, 16, 950);
    assert_means_agree(adaptive, even, "sample rates after 8 spp vs every pixel alike");

    rd.seed = 990;
    render_adaptive_like_cli(scene, rd, &img, rates);
    rd.seed = 991;
    render_adaptive_like_cli(scene, rd, &other, rates);
    assert_estimate_calibrated(&img, &other, "with sample rates");
    free(rates);
    fogrt_image_free(&img);
    fogrt_image_free(&other);
    fogrt_scene_destroy(scene);
#endif
}

int main(int argc, char **argv)
{
    /* Output files go next to the test binary, i.e. into the build directory. */
    if (argc > 0 && argv[0] != NULL && strrchr(argv[0], '/') != NULL) {
        size_t len = (size_t)(strrchr(argv[0], '/') - argv[0]);
        if (len > 0 && len < sizeof out_dir) { memcpy(out_dir, argv[0], len); out_dir[len] = '\0'; }
    }
    UNITY_BEGIN();
    RUN_TEST(test_default_scene_renders);
    RUN_TEST(test_threads_bit_identical);
    RUN_TEST(test_split_samples_identical);
    RUN_TEST(test_pixel_positions_stratified);
    RUN_TEST(test_seeds);
    RUN_TEST(test_progress_and_cancel);
    RUN_TEST(test_error_estimate);
    RUN_TEST(test_nee_unbiased_without_fog);
    RUN_TEST(test_nee_unbiased_in_fog);
    RUN_TEST(test_glow_unbiased);
    RUN_TEST(test_expected_emission_unbiased);
    RUN_TEST(test_lights_by_power_unbiased);
    RUN_TEST(test_direct_integrator);
    RUN_TEST(test_direct_default_scene);
    RUN_TEST(test_thin_lens);
    RUN_TEST(test_pinhole_rays);
    RUN_TEST(test_environment_only);
    RUN_TEST(test_tonemap);
    RUN_TEST(test_write_files);
    RUN_TEST(test_roulette_pilot);
    RUN_TEST(test_sample_rates_shape);
    RUN_TEST(test_sample_rates_render);
    RUN_TEST(test_sample_rates_unbiased);
    return UNITY_END();
}
