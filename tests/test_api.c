/* test_api.c - promises of the library's calls: a failure's reason can be read back, a
   failed call leaves the scene as it was (fogrt_scene_add_default and rebuilds included),
   a black image says so, and an absurd thread count is cut to what the machine can run. */
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#include "unity.h"
#include "test_util.h"
#include <stdlib.h>
#include <string.h>
#include <math.h>

void setUp(void) {}
void tearDown(void) {}

/* An allocator that fails from its n-th call on (n < 0: never). */
typedef struct failing { long calls, fail_at; } failing;
static void *failing_alloc(size_t size, void *user)
{
    failing *f = (failing *)user;
    if (f->fail_at >= 0 && f->calls++ >= f->fail_at) return NULL;
    return malloc(size);
}
static void failing_free(void *p, void *user) { (void)user; free(p); }
static fogrt_scene *failing_scene(failing *f)
{
    fogrt_scene_desc sd;
    fogrt_scene *s = NULL;
    memset(&sd, 0, sizeof sd);
    sd.allocator.alloc_fn = failing_alloc; sd.allocator.free_fn = failing_free; sd.allocator.user_data = f;
    f->fail_at = -1; f->calls = 0;
    CHECK_OK(fogrt_scene_create(&sd, &s));
    return s;
}

static void test_last_error_reads_back_the_reason(void)
{
    fogrt_scene *s = NULL;
    fogrt_material_desc m;
    uint32_t id;
    CHECK_OK(fogrt_scene_create(NULL, &s));
    TEST_ASSERT_EQUAL_STRING("", fogrt_scene_last_error(s));
    memset(&m, 0, sizeof m);
    m.type = FOGRT_BSDF_DIFFUSE; m.reflectance = v3(-1.0f, 0.5f, 0.5f);
    TEST_ASSERT_NOT_EQUAL(FOGRT_RESULT_OK, fogrt_scene_add_material(s, &m, &id));
    TEST_ASSERT_NOT_NULL(strstr(fogrt_scene_last_error(s), "reflectance"));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_EMPTY_SCENE, fogrt_scene_build(s, NULL));
    TEST_ASSERT_NOT_NULL(strstr(fogrt_scene_last_error(s), "no geometry"));
    fogrt_scene_destroy(s);
}

static void render_tiny(const fogrt_scene *s, fogrt_render_stats *stats, double *sum)
{
    fogrt_image img;
    fogrt_render_desc rd = fogrt_render_defaults();
    int i;
    rd.threads = 1;
    CHECK_OK(fogrt_image_alloc(&img, 8, 6, NULL));
    CHECK_OK(fogrt_render(s, &rd, &img, 2, stats));
    *sum = 0.0;
    for (i = 0; i < 3 * 8 * 6; ++i) *sum += img.sum[i];
    fogrt_image_free(&img);
}

static void test_black_image_says_so(void)
{
    fogrt_scene *s = NULL;
    fogrt_render_stats st;
    double sum;
    CHECK_OK(fogrt_scene_create(NULL, &s));
    add_quad(s, v3(-1, 0, -1), v3(2, 0, 0), v3(0, 0, 2),
             add_basic_material(s, FOGRT_BSDF_DIFFUSE, v3(0.5f, 0.5f, 0.5f), v3(0, 0, 0)));
    CHECK_OK(fogrt_scene_build(s, NULL));                /* nothing emits */
    render_tiny(s, &st, &sum);
    TEST_ASSERT_TRUE(st.black);
    fogrt_scene_destroy(s);
    CHECK_OK(fogrt_scene_create(NULL, &s));
    CHECK_OK(fogrt_scene_add_default(s));
    CHECK_OK(fogrt_scene_build(s, NULL));
    render_tiny(s, &st, &sum);
    TEST_ASSERT_FALSE(st.black);
    TEST_ASSERT_TRUE(sum > 0.0);
    fogrt_scene_destroy(s);
}

/* Every allocation of fogrt_scene_add_default failing in turn: the scene keeps nothing of
   the half-added box. */
static void test_add_default_all_or_nothing(void)
{
    failing f;
    long n;
    for (n = 0; n < 64; ++n) {
        fogrt_scene *s = failing_scene(&f);
        fogrt_scene_info info;
        fogrt_result r;
        f.fail_at = n; f.calls = 0;
        r = fogrt_scene_add_default(s);
        fogrt_scene_get_info(s, &info);
        if (r == FOGRT_RESULT_OK) {
            TEST_ASSERT_TRUE(info.material_count > 0);
            fogrt_scene_destroy(s);
            break;
        }
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OUT_OF_MEMORY, r);
        TEST_ASSERT_EQUAL_UINT32(0, info.material_count);
        TEST_ASSERT_EQUAL_UINT32(0, info.triangle_count);
        TEST_ASSERT_EQUAL_UINT32(0, info.sphere_count);
        TEST_ASSERT_EQUAL_UINT32(0, info.light_count);
        fogrt_scene_destroy(s);
    }
    TEST_ASSERT_TRUE_MESSAGE(n > 0 && n < 64, "add_default needs between 1 and 63 allocations");
}

/* A rebuild of a built scene failing at every allocation in turn: the scene stays built and
   renders exactly the image it rendered before. */
static void test_rebuild_all_or_nothing(void)
{
    failing f;
    fogrt_scene *s = failing_scene(&f);
    fogrt_render_stats st;
    fogrt_build_desc bd = fogrt_build_defaults();
    double before, after;
    long n, failures = 0;
    bd.roulette_pilot = false;                          /* the pilot's renders would only add time */
    CHECK_OK(fogrt_scene_add_default(s));
    CHECK_OK(fogrt_scene_build(s, &bd));
    render_tiny(s, &st, &before);
    for (n = 0; n < 200; ++n) {
        fogrt_scene_info info;
        fogrt_result r;
        f.fail_at = n; f.calls = 0;
        r = fogrt_scene_build(s, &bd);
        f.fail_at = -1;
        if (r == FOGRT_RESULT_OK) break;
        ++failures;
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OUT_OF_MEMORY, r);
        fogrt_scene_get_info(s, &info);
        TEST_ASSERT_TRUE(info.built);
        render_tiny(s, &st, &after);
        TEST_ASSERT_EQUAL_DOUBLE(before, after);
    }
    TEST_ASSERT_TRUE(failures > 0 && n < 200);
    render_tiny(s, &st, &after);
    TEST_ASSERT_EQUAL_DOUBLE(before, after);
    fogrt_scene_destroy(s);
}

/* threads = 100000 renders (cut to FOGRT_MAX_THREADS and 4 per processor), the same image. */
static void test_absurd_thread_count_is_cut(void)
{
    fogrt_scene *s = NULL;
    fogrt_image a, b;
    fogrt_render_desc rd = fogrt_render_defaults();
    CHECK_OK(fogrt_scene_create(NULL, &s));
    CHECK_OK(fogrt_scene_add_default(s));
    CHECK_OK(fogrt_scene_build(s, NULL));
    CHECK_OK(fogrt_image_alloc(&a, 16, 12, NULL));
    CHECK_OK(fogrt_image_alloc(&b, 16, 12, NULL));
    rd.threads = 100000;
    CHECK_OK(fogrt_render(s, &rd, &a, 2, NULL));
    rd.threads = 1;
    CHECK_OK(fogrt_render(s, &rd, &b, 2, NULL));
    TEST_ASSERT_EQUAL_MEMORY(b.sum, a.sum, sizeof(double) * 3 * 16 * 12);
    fogrt_image_free(&a);
    fogrt_image_free(&b);
    fogrt_scene_destroy(s);
}

/* With per-pixel rates the image is a function of the inputs alone: 24 spp asked for in
   one call, in 4 + 20, or in 24 calls of 1 give the same image bit for bit (the counts no
   longer depend on how the samples were split, so neither on a caller's timing). */
static void test_rates_do_not_depend_on_batches(void)
{
#ifdef FOGRT_NO_ESTIMATION
    TEST_IGNORE_MESSAGE("needs Part II of fogrt.h (C: per-pixel rates): built with FOGRT_MINIMAL or FOGRT_NO_ESTIMATION");
#else
    fogrt_scene *s = NULL;
    fogrt_image img[3];
    fogrt_render_desc rd = fogrt_render_defaults();
    float rates[16 * 12];
    int i, k;
    CHECK_OK(fogrt_scene_create(NULL, &s));
    CHECK_OK(fogrt_scene_add_default(s));
    CHECK_OK(fogrt_scene_build(s, NULL));
    for (i = 0; i < 3; ++i) CHECK_OK(fogrt_image_alloc(&img[i], 16, 12, NULL));
    CHECK_OK(fogrt_render(s, &rd, &img[0], 2, NULL));      /* every pixel alike, then the rates */
    CHECK_OK(fogrt_image_sample_rates(&img[0], rates));
    for (i = 1; i < 3; ++i) CHECK_OK(fogrt_render(s, &rd, &img[i], 2, NULL));
    rd.sample_rate = rates;
    CHECK_OK(fogrt_render(s, &rd, &img[0], 24, NULL));
    CHECK_OK(fogrt_render(s, &rd, &img[1], 4, NULL));
    rd.threads = 2;
    CHECK_OK(fogrt_render(s, &rd, &img[1], 20, NULL));
    for (k = 0; k < 24; ++k) CHECK_OK(fogrt_render(s, &rd, &img[2], 1, NULL));
    for (i = 1; i < 3; ++i) {
        TEST_ASSERT_EQUAL_MEMORY(img[0].count, img[i].count, sizeof(uint32_t) * 16 * 12);
        TEST_ASSERT_EQUAL_MEMORY(img[0].sum, img[i].sum, sizeof(double) * 3 * 16 * 12);
    }
    for (i = 0; i < 3; ++i) fogrt_image_free(&img[i]);
    fogrt_scene_destroy(s);
#endif
}

/* A render whose cancel flag is set stops at once: cancelled, no sample taken, nothing
   counted; cleared, the same image renders as before. */
static void test_cancel_flag_stops_a_render(void)
{
    fogrt_scene *s = NULL;
    fogrt_image img;
    fogrt_render_stats st;
    fogrt_render_desc rd = fogrt_render_defaults();
    volatile int flag = 1;
    uint32_t i;
    CHECK_OK(fogrt_scene_create(NULL, &s));
    CHECK_OK(fogrt_scene_add_default(s));
    CHECK_OK(fogrt_scene_build(s, NULL));
    CHECK_OK(fogrt_image_alloc(&img, 16, 12, NULL));
    rd.cancel = &flag;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_CANCELLED, fogrt_render(s, &rd, &img, 4, &st));
    TEST_ASSERT_EQUAL_UINT64(0, st.camera_rays);
    for (i = 0; i < 16 * 12; ++i) TEST_ASSERT_EQUAL_UINT32(0, img.count[i]);
    flag = 0;
    CHECK_OK(fogrt_render(s, &rd, &img, 4, &st));
    TEST_ASSERT_EQUAL_UINT64(16 * 12 * 4, st.camera_rays);
    fogrt_image_free(&img);
    fogrt_scene_destroy(s);
}

/* A pixel counts its samples in 32 bits: a render that would take a count past 2^32 - 1 is
   refused (TOO_LARGE, the image untouched), one that reaches it exactly is not. */
static void test_sample_count_never_wraps(void)
{
    fogrt_scene *s = NULL;
    fogrt_image img;
    fogrt_render_stats st;
    fogrt_render_desc rd = fogrt_render_defaults();
    CHECK_OK(fogrt_scene_create(NULL, &s));
    CHECK_OK(fogrt_scene_add_default(s));
    CHECK_OK(fogrt_scene_build(s, NULL));
    CHECK_OK(fogrt_image_alloc(&img, 4, 3, NULL));
    img.count[5] = 0xFFFFFFFFu - 3u;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_TOO_LARGE, fogrt_render(s, &rd, &img, 4, &st));
    TEST_ASSERT_EQUAL_UINT32(0xFFFFFFFFu - 3u, img.count[5]);
    TEST_ASSERT_EQUAL_UINT32(0, img.count[0]);
    CHECK_OK(fogrt_render(s, &rd, &img, 3, &st));
    TEST_ASSERT_EQUAL_UINT32(0xFFFFFFFFu, img.count[5]);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_TOO_LARGE, fogrt_render(s, &rd, &img, 1, &st));
    TEST_ASSERT_EQUAL_UINT32(0xFFFFFFFFu, img.count[5]);
    fogrt_image_free(&img);
    fogrt_scene_destroy(s);
}

/* A fan of slivers around one vertex (every box overlaps every other there: a ray visits
   thousands of nodes) builds without the roulette's pilot, whose fixed number of paths would
   take minutes in it; an ordinary scene keeps it. */
static void test_pilot_skipped_in_sliver_fans(void)
{
#ifdef FOGRT_NO_ESTIMATION
    TEST_IGNORE_MESSAGE("needs Part II of fogrt.h (C: the roulette's pilot): built with FOGRT_MINIMAL or FOGRT_NO_ESTIMATION");
#else
    enum { N = 20000 };
    static float v[3 * (N + 2)];
    static uint32_t idx[3 * N];
    fogrt_scene *s = NULL;
    fogrt_mesh_desc md;
    fogrt_light_desc l;
    fogrt_build_desc bd = fogrt_build_defaults();
    int i;
    v[0] = v[1] = v[2] = 0.0f;
    for (i = 0; i <= N; ++i) {
        double a = 3.14159 * i / N;
        v[3 * (i + 1)] = (float)(10.0 * cos(a)); v[3 * (i + 1) + 1] = (float)(10.0 * sin(a)); v[3 * (i + 1) + 2] = -5.0f;
    }
    for (i = 0; i < N; ++i) { idx[3 * i] = 0; idx[3 * i + 1] = (uint32_t)i + 1; idx[3 * i + 2] = (uint32_t)i + 2; }
    CHECK_OK(fogrt_scene_create(NULL, &s));
    memset(&md, 0, sizeof md);
    md.positions = v; md.vertex_count = N + 2; md.indices = idx; md.triangle_count = N;
    md.material = add_basic_material(s, FOGRT_BSDF_DIFFUSE, v3(0.5f, 0.5f, 0.5f), v3(0, 0, 0));
    CHECK_OK(fogrt_scene_add_mesh(s, &md));
    memset(&l, 0, sizeof l);
    l.type = FOGRT_LIGHT_POINT; l.position = v3(0, 0, 5); l.intensity = v3(10, 10, 10);
    CHECK_OK(fogrt_scene_add_light(s, &l));
    CHECK_OK(fogrt_scene_build(s, NULL));
    TEST_ASSERT_TRUE(fogrt_bvh_sah_cost(s) > FOGRT__PILOT_MAX_SAH);
    TEST_ASSERT_EQUAL_FLOAT(1.0f, s->x->rr_k);
    bd.release_binary = true;                            /* the tree is priced before it goes */
    CHECK_OK(fogrt_scene_build(s, &bd));
    TEST_ASSERT_EQUAL_FLOAT(0.0f, fogrt_bvh_sah_cost(s));
    TEST_ASSERT_EQUAL_FLOAT(1.0f, s->x->rr_k);
    fogrt_scene_destroy(s);
    CHECK_OK(fogrt_scene_create(NULL, &s));
    CHECK_OK(fogrt_scene_add_default(s));
    CHECK_OK(fogrt_scene_build(s, NULL));
    TEST_ASSERT_TRUE(fogrt_bvh_sah_cost(s) < FOGRT__PILOT_MAX_SAH);
    TEST_ASSERT_TRUE(s->x->rr_k > 1.0f);                 /* the default scene's pilot finds k > 1 */
    fogrt_scene_destroy(s);
#endif
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_last_error_reads_back_the_reason);
    RUN_TEST(test_black_image_says_so);
    RUN_TEST(test_add_default_all_or_nothing);
    RUN_TEST(test_rebuild_all_or_nothing);
    RUN_TEST(test_absurd_thread_count_is_cut);
    RUN_TEST(test_rates_do_not_depend_on_batches);
    RUN_TEST(test_cancel_flag_stops_a_render);
    RUN_TEST(test_sample_count_never_wraps);
    RUN_TEST(test_pilot_skipped_in_sliver_fans);
    return UNITY_END();
}
