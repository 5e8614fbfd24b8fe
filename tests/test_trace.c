/* test_trace.c - the path event trace (FOGRT_TRACE, fogrt_trace_path).

   A trace is only worth reading if it is the path the renderer really follows and if its
   numbers add up. These tests check both: fogrt_trace_path gives the very sample that
   fogrt_render adds to the pixel, the CONTRIBUTION events add up to the sample's radiance
   for a path that scatters in the fog, one that passes through glass and one that Russian
   roulette ends, and the events come in the order of the paper's Algorithm 1. */
#define FOGRT_TRACE
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#include "unity.h"
#include "test_util.h"

#include <stdio.h>
#include <string.h>

#define W 24
#define H 18
#define MAX_EVENTS 4096

#ifndef FOGRT_MINIMAL   /* the helpers of the tests below, all of Part II */
typedef struct recorder {
    fogrt_trace_event ev[MAX_EVENTS];
    int n;
    bool overflow;
} recorder;

static void record(const fogrt_trace_event *e, void *user)
{
    recorder *r = (recorder *)user;
    if (r->n < MAX_EVENTS) r->ev[r->n++] = *e;
    else r->overflow = true;
}

static recorder rec;

/* What a recorded path did. */
typedef struct path_facts {
    bool fog_collision, glass, roulette_end, refracted;
    fogrt_vec3 sum;            /* the counted contributions, added in the order they came */
    int contributions;
} path_facts;

static path_facts facts_of(const recorder *r)
{
    path_facts f;
    int i;
    memset(&f, 0, sizeof f);
    for (i = 0; i < r->n; ++i) {
        const fogrt_trace_event *e = &r->ev[i];
        if (e->kind == FOGRT_TRACE_FREE_FLIGHT && e->flag) f.fog_collision = true;
        if (e->kind == FOGRT_TRACE_BSDF_SAMPLE && e->bsdf == FOGRT_BSDF_GLASS) {
            f.glass = true;
            if (e->lobe == FOGRT_LOBE_REFRACT) f.refracted = true;
        }
        if (e->kind == FOGRT_TRACE_ROULETTE && !e->flag) f.roulette_end = true;
        if (e->kind == FOGRT_TRACE_CONTRIBUTION && e->flag) {
            f.sum.x += e->value.x; f.sum.y += e->value.y; f.sum.z += e->value.z;
            f.contributions++;
        }
    }
    return f;
}

static fogrt_scene *default_scene(void)
{
    fogrt_scene *scene = NULL;
    CHECK_OK(fogrt_scene_create(NULL, &scene));
    CHECK_OK(fogrt_scene_add_default(scene));
    CHECK_OK(fogrt_scene_build(scene, NULL));
    return scene;
}

#endif
/* The traced sample is the rendered one: a 1-spp image of the default scene holds, in every
   pixel, exactly what fogrt_trace_path returns for sample 0 of that pixel. */
static void test_trace_is_the_rendered_sample(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("D: the path trace");
#else
    fogrt_scene *scene = default_scene();
    fogrt_render_desc rd = fogrt_render_defaults();
    fogrt_image img;
    int x, y, differ = 0;
    rd.seed = 9;
    rd.threads = 1;
    CHECK_OK(fogrt_image_alloc(&img, W, H, NULL));
    CHECK_OK(fogrt_render(scene, &rd, &img, 1, NULL));
    for (y = 0; y < H; ++y)
        for (x = 0; x < W; ++x) {
            size_t p = (size_t)y * W + (size_t)x;
            fogrt_vec3 L = fogrt_trace_path(scene, &rd, W, H, x, y, 0, NULL, NULL);
            if ((double)L.x != img.sum[3 * p] || (double)L.y != img.sum[3 * p + 1] || (double)L.z != img.sum[3 * p + 2])
                differ++;
        }
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, differ, "pixels whose traced sample differs from the rendered one");
    fogrt_image_free(&img);
    fogrt_scene_destroy(scene);
#endif
}

/* The contributions add up to the sample, for every path of 4 samples per pixel of the
   default scene; among them, paths that scatter in the fog, refract through the glass sphere
   and end by Russian roulette (the first of each kind is printed). */
static void test_contributions_add_up(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("D: the path trace");
#else
    fogrt_scene *scene = default_scene();
    fogrt_render_desc rd = fogrt_render_defaults();
    bool seen_fog = false, seen_glass = false, seen_rr = false;
    int x, y, k, checked = 0;
    rd.seed = 3;
    for (k = 0; k < 4; ++k)
        for (y = 0; y < H; ++y)
            for (x = 0; x < W; ++x) {
                path_facts f;
                fogrt_vec3 L;
                char msg[256];
                rec.n = 0; rec.overflow = false;
                L = fogrt_trace_path(scene, &rd, W, H, x, y, (uint32_t)k, record, &rec);
                TEST_ASSERT_FALSE(rec.overflow);
                f = facts_of(&rec);
                bool first = (f.fog_collision && !seen_fog) || (f.refracted && !seen_glass) || (f.roulette_end && !seen_rr);
                if (f.fog_collision) seen_fog = true;
                if (f.refracted) seen_glass = true;
                if (f.roulette_end) seen_rr = true;
                snprintf(msg, sizeof msg, "pixel (%d, %d) sample %d (fog %d glass %d roulette %d): %d contributions sum to "
                         "(%.9g %.9g %.9g), the sample is (%.9g %.9g %.9g)", x, y, k, f.fog_collision, f.refracted,
                         f.roulette_end, f.contributions, (double)f.sum.x, (double)f.sum.y, (double)f.sum.z,
                         (double)L.x, (double)L.y, (double)L.z);
                if (first) TEST_MESSAGE(msg);
                TEST_ASSERT_TRUE_MESSAGE(f.sum.x == L.x && f.sum.y == L.y && f.sum.z == L.z, msg);
                TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_TRACE_END, rec.ev[rec.n - 1].kind, msg);
                TEST_ASSERT_TRUE_MESSAGE(rec.ev[rec.n - 1].value.x == L.x, msg);
                checked++;
            }
    TEST_ASSERT_TRUE_MESSAGE(seen_fog && seen_glass && seen_rr, "no fog, glass or roulette-ended path found in 4 spp");
    TEST_ASSERT_EQUAL_INT(4 * W * H, checked);
    fogrt_scene_destroy(scene);
#endif
}

/* The order of Algorithm 1: a camera ray first and END last; every segment starts with its
   free flight (in fog), is followed by a surface, a fog collision or an escape; a light
   sample or a new direction happens only at a scattering vertex; bounce numbers never go
   down. And every event has a readable description naming what it is. */
static void test_event_order_and_text(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("D: the path trace");
#else
    fogrt_scene *scene = default_scene();
    fogrt_render_desc rd = fogrt_render_defaults();
    int i, x, y, last_bounce = 0, descriptions = 0;
    bool after_vertex = false;
    char line[512];
    for (y = 4; y < H; y += 5)
        for (x = 3; x < W; x += 6) {
            rec.n = 0;
            fogrt_trace_path(scene, &rd, W, H, x, y, 1, record, &rec);
            TEST_ASSERT_EQUAL_INT(FOGRT_TRACE_CAMERA, rec.ev[0].kind);
            TEST_ASSERT_EQUAL_INT(FOGRT_TRACE_END, rec.ev[rec.n - 1].kind);
            last_bounce = 0;
            after_vertex = false;
            for (i = 0; i < rec.n; ++i) {
                const fogrt_trace_event *e = &rec.ev[i];
                TEST_ASSERT_TRUE(e->kind == FOGRT_TRACE_END || e->bounce >= last_bounce);
                if (e->kind != FOGRT_TRACE_END) last_bounce = e->bounce;
                if (e->kind == FOGRT_TRACE_SURFACE || (e->kind == FOGRT_TRACE_FREE_FLIGHT && e->flag)) after_vertex = true;
                if (e->kind == FOGRT_TRACE_PHASE_SAMPLE || e->kind == FOGRT_TRACE_BSDF_SAMPLE) {
                    TEST_ASSERT_TRUE_MESSAGE(after_vertex, "a new direction before any vertex");
                    after_vertex = false;
                }
                fogrt_trace_describe(e, line, sizeof line);
                TEST_ASSERT_TRUE(strlen(line) > 10);
                if (e->kind == FOGRT_TRACE_FREE_FLIGHT) TEST_ASSERT_NOT_NULL(strstr(line, "eq. 6"));
                if (e->kind == FOGRT_TRACE_PHASE_SAMPLE) TEST_ASSERT_NOT_NULL(strstr(line, "eq. 11"));
                descriptions++;
            }
        }
    TEST_ASSERT_GREATER_THAN(20, descriptions);
    fogrt_scene_destroy(scene);
#endif
}

/* min_depth: the contributions it drops are marked as not counted, and the sample is the sum
   of the counted ones only (so the trace explains CS184's -o 0 too). */
static void test_min_depth_marks_dropped_light(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("D: the path trace");
#else
    fogrt_scene *scene = default_scene();
    fogrt_render_desc rd = fogrt_render_defaults();
    int x, dropped = 0;
    rd.min_depth = 2; rd.max_depth = 2;
    for (x = 0; x < W; ++x) {
        path_facts f;
        fogrt_vec3 L;
        int i;
        rec.n = 0;
        L = fogrt_trace_path(scene, &rd, W, H, x, H / 2, 0, record, &rec);
        f = facts_of(&rec);
        for (i = 0; i < rec.n; ++i) dropped += rec.ev[i].kind == FOGRT_TRACE_CONTRIBUTION && !rec.ev[i].flag;
        TEST_ASSERT_TRUE(f.sum.x == L.x && f.sum.y == L.y && f.sum.z == L.z);
    }
    TEST_ASSERT_GREATER_THAN_MESSAGE(0, dropped, "min_depth 2 dropped no contribution on a whole row");
    fogrt_scene_destroy(scene);
#endif
}

void setUp(void) {}
void tearDown(void) {}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_trace_is_the_rendered_sample);
    RUN_TEST(test_contributions_add_up);
    RUN_TEST(test_event_order_and_text);
    RUN_TEST(test_min_depth_marks_dropped_light);
    return UNITY_END();
}
