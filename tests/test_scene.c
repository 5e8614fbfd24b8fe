/* test_scene.c - the scene API and its error paths.
 *
 * What is checked: creating and destroying scenes (with a counting allocator that must see
 * every allocation freed), adding materials, meshes, spheres, lights, the camera and the
 * medium with good and bad data, the result codes and their strings, the features found by
 * fogrt_scene_build, and the messages given to the logger. The header's promise tested
 * throughout: "Bad data returns an error and leaves the scene as it was". */
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

/* ------------------------------------------------------------------------------------------
   Helpers: a counting allocator, a recording logger, small scenes and a scene snapshot
   ------------------------------------------------------------------------------------------ */

/* Every block gets a 16-byte header holding a magic number, so that freeing a pointer the
   allocator never handed out (or freeing one twice) is caught. */
#define COUNTING_MAGIC 0x466f6752u
typedef struct counting_allocator {
    long live;          /* blocks allocated and not yet freed */
    long allocs;        /* blocks allocated in total */
    long bad_frees;     /* frees of pointers that did not come from here */
    size_t bytes;       /* bytes requested in total */
} counting_allocator;

static void *counting_alloc(size_t size, void *user_data)
{
    counting_allocator *c = (counting_allocator *)user_data;
    unsigned char *block = (unsigned char *)malloc(size + 16);
    if (block == NULL) return NULL;
    *(uint32_t *)block = COUNTING_MAGIC;
    c->live++;
    c->allocs++;
    c->bytes += size;
    return block + 16;
}

static void counting_free(void *ptr, void *user_data)
{
    counting_allocator *c = (counting_allocator *)user_data;
    unsigned char *block;
    if (ptr == NULL) return;
    block = (unsigned char *)ptr - 16;
    if (*(uint32_t *)block != COUNTING_MAGIC) { c->bad_frees++; return; }
    *(uint32_t *)block = 0;
    c->live--;
    free(block);
}

/* The logger keeps the number of messages per level and the last error message. */
typedef struct log_record {
    int count[FOGRT_LOG_NUM];
    int total;
    int multi_line;               /* messages with a '\n' before their end */
    char last_error[512];
    char last_warning[512];
} log_record;

static void record_log(fogrt_log_level level, const char *message, void *user_data)
{
    log_record *r = (log_record *)user_data;
    size_t n = strlen(message);
    const char *nl = strchr(message, '\n');
    if (nl != NULL && nl != message + n - 1) r->multi_line++;
    if ((int)level >= 0 && level < FOGRT_LOG_NUM) r->count[level]++;
    r->total++;
    if (level == FOGRT_LOG_ERROR) {
        strncpy(r->last_error, message, sizeof r->last_error - 1);
        r->last_error[sizeof r->last_error - 1] = '\0';
    }
    if (level == FOGRT_LOG_WARNING) {
        strncpy(r->last_warning, message, sizeof r->last_warning - 1);
        r->last_warning[sizeof r->last_warning - 1] = '\0';
    }
}

static fogrt_scene *new_scene(log_record *log)
{
    fogrt_scene_desc sd;
    fogrt_scene *scene = NULL;
    memset(&sd, 0, sizeof sd);
    if (log != NULL) {
        memset(log, 0, sizeof *log);
        sd.logger.func = record_log;
        sd.logger.user_data = log;
    }
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_create(&sd, &scene));
    TEST_ASSERT_NOT_NULL(scene);
    return scene;
}

static uint32_t add_diffuse(fogrt_scene *scene, float r, float g, float b)
{
    fogrt_material_desc m;
    uint32_t id = 0xFFFFFFFFu;
    memset(&m, 0, sizeof m);
    m.type = FOGRT_BSDF_DIFFUSE;
    m.reflectance = v3(r, g, b);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_material(scene, &m, &id));
    return id;
}

static uint32_t add_material_of_type(fogrt_scene *scene, fogrt_bsdf_type type)
{
    fogrt_material_desc m;
    uint32_t id = 0xFFFFFFFFu;
    memset(&m, 0, sizeof m);
    m.type = type;
    m.reflectance = v3(0.9f, 0.9f, 0.9f);
    m.transmittance = v3(0.9f, 0.9f, 0.9f);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_material(scene, &m, &id));
    return id;
}

/* A unit quad in the plane z = 0, two triangles. */
static const float quad_positions[12] = { 0, 0, 0,  1, 0, 0,  1, 1, 0,  0, 1, 0 };
static const uint32_t quad_indices[6] = { 0, 1, 2,  0, 2, 3 };

static fogrt_mesh_desc quad_mesh(uint32_t material)
{
    fogrt_mesh_desc d;
    memset(&d, 0, sizeof d);
    d.positions = quad_positions;
    d.vertex_count = 4;
    d.indices = quad_indices;
    d.triangle_count = 2;
    d.material = material;
    return d;
}

static fogrt_camera_desc simple_camera(void)
{
    fogrt_camera_desc c;
    memset(&c, 0, sizeof c);
    c.position = v3(0.5f, 0.5f, 3.0f);
    c.look_at = v3(0.5f, 0.5f, 0.0f);
    c.up = v3(0, 1, 0);
    c.fov_deg = 40.0f;
    return c;
}

static fogrt_light_desc point_light(void)
{
    fogrt_light_desc l;
    memset(&l, 0, sizeof l);
    l.type = FOGRT_LIGHT_POINT;
    l.position = v3(0.5f, 0.5f, 1.0f);
    l.intensity = v3(1, 1, 1);
    return l;
}

static fogrt_light_desc spot_light(void)
{
    fogrt_light_desc l = point_light();
    l.type = FOGRT_LIGHT_SPOT;
    l.direction = v3(0, 0, -1);
    l.cutoff_deg = 30.0f;
    l.beam_deg = 20.0f;
    return l;
}

/* A scene with one of everything: two materials, a quad, a sphere, a point and a spot
   light, a camera and a medium. The error-path tests start from it. */
static fogrt_scene *full_scene(log_record *log)
{
    fogrt_scene *scene = new_scene(log);
    fogrt_mesh_desc mesh;
    fogrt_light_desc pl = point_light(), sl = spot_light();
    fogrt_camera_desc cam = simple_camera();
    fogrt_medium_desc med;
    uint32_t m0 = add_diffuse(scene, 0.5f, 0.5f, 0.5f);
    uint32_t m1 = add_diffuse(scene, 0.2f, 0.7f, 0.1f);
    mesh = quad_mesh(m0);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_mesh(scene, &mesh));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_sphere(scene, v3(0.5f, 0.5f, 0.5f), 0.2f, m1));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_light(scene, &pl));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_light(scene, &sl));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_set_camera(scene, &cam));
    memset(&med, 0, sizeof med);
    med.sigma_t = 0.25f;
    med.albedo = v3(0.8f, 0.8f, 0.8f);
    med.g = 0.3f;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_set_medium(scene, &med));
    if (log != NULL) memset(log, 0, sizeof *log);   /* only messages from the call under test */
    return scene;
}

/* Everything the public getters can see of a scene. */
#define SNAP_MAX 16
typedef struct scene_snapshot {
    fogrt_scene_info info;
    fogrt_material_desc materials[SNAP_MAX];
    fogrt_light_desc lights[SNAP_MAX];
    uint32_t prim_materials[SNAP_MAX];
    fogrt_camera_desc camera;
    fogrt_medium_desc medium;
} scene_snapshot;

static void take_snapshot(const fogrt_scene *scene, scene_snapshot *s)
{
    uint32_t i;
    memset(s, 0, sizeof *s);
    fogrt_scene_get_info(scene, &s->info);
    TEST_ASSERT_LESS_OR_EQUAL(SNAP_MAX, s->info.material_count);
    TEST_ASSERT_LESS_OR_EQUAL(SNAP_MAX, s->info.light_count);
    TEST_ASSERT_LESS_OR_EQUAL(SNAP_MAX, s->info.triangle_count + s->info.sphere_count);
    for (i = 0; i < s->info.material_count; i++)
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_get_material(scene, i, &s->materials[i]));
    for (i = 0; i < s->info.light_count; i++)
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_get_light(scene, i, &s->lights[i]));
    for (i = 0; i < s->info.triangle_count + s->info.sphere_count; i++)
        s->prim_materials[i] = fogrt_scene_get_prim_material(scene, i);
    fogrt_scene_get_camera(scene, &s->camera);
    fogrt_scene_get_medium(scene, &s->medium);
}

/* Bitwise float equality (NaN-safe: a NaN that slipped into the scene shows up as a change). */
static int same_float(float a, float b) { return memcmp(&a, &b, sizeof a) == 0; }
static int same_vec(fogrt_vec3 a, fogrt_vec3 b)
{
    return same_float(a.x, b.x) && same_float(a.y, b.y) && same_float(a.z, b.z);
}

static void assert_unchanged(const fogrt_scene *scene, const scene_snapshot *before, const char *what)
{
    scene_snapshot after;
    const fogrt_scene_info *a = &after.info, *b = &before->info;
    uint32_t i;
    take_snapshot(scene, &after);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(b->triangle_count, a->triangle_count, what);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(b->sphere_count, a->sphere_count, what);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(b->material_count, a->material_count, what);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(b->light_count, a->light_count, what);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(b->area_light_count, a->area_light_count, what);
    TEST_ASSERT_EQUAL_INT_MESSAGE(b->has_environment, a->has_environment, what);
    TEST_ASSERT_EQUAL_INT_MESSAGE(b->built, a->built, what);
    for (i = 0; i < b->material_count; i++) {
        const fogrt_material_desc *x = &before->materials[i], *y = &after.materials[i];
        TEST_ASSERT_TRUE_MESSAGE(x->type == y->type && same_vec(x->reflectance, y->reflectance) &&
                                 same_vec(x->transmittance, y->transmittance) &&
                                 same_vec(x->emission, y->emission) && same_float(x->ior, y->ior), what);
    }
    for (i = 0; i < b->light_count; i++) {
        const fogrt_light_desc *x = &before->lights[i], *y = &after.lights[i];
        TEST_ASSERT_TRUE_MESSAGE(x->type == y->type && same_vec(x->position, y->position) &&
                                 same_vec(x->direction, y->direction) &&
                                 same_vec(x->intensity, y->intensity) &&
                                 same_float(x->cutoff_deg, y->cutoff_deg) &&
                                 same_float(x->beam_deg, y->beam_deg) &&
                                 same_float(x->radius, y->radius), what);
    }
    for (i = 0; i < b->triangle_count + b->sphere_count; i++)
        TEST_ASSERT_EQUAL_UINT32_MESSAGE(before->prim_materials[i], after.prim_materials[i], what);
    TEST_ASSERT_TRUE_MESSAGE(same_vec(before->camera.position, after.camera.position) &&
                             same_vec(before->camera.look_at, after.camera.look_at) &&
                             same_vec(before->camera.up, after.camera.up) &&
                             same_float(before->camera.fov_deg, after.camera.fov_deg) &&
                             before->camera.fov_is_horizontal == after.camera.fov_is_horizontal &&
                             same_float(before->camera.lens_radius, after.camera.lens_radius) &&
                             same_float(before->camera.focal_distance, after.camera.focal_distance), what);
    TEST_ASSERT_TRUE_MESSAGE(same_float(before->medium.sigma_t, after.medium.sigma_t) &&
                             same_vec(before->medium.albedo, after.medium.albedo) &&
                             same_float(before->medium.g, after.medium.g), what);
}

/* After a rejected call: the expected result, the scene as it was, and exactly one error
   message on the logger that names the offending parameter. */
static void assert_rejected(fogrt_result expected, fogrt_result got, const fogrt_scene *scene,
                            const scene_snapshot *before, log_record *log,
                            const char *parameter, const char *what)
{
    char msg[768];
    snprintf(msg, sizeof msg, "%s: expected %s, got %s", what, fogrt_result_string(expected),
             fogrt_result_string(got));
    TEST_ASSERT_EQUAL_INT_MESSAGE(expected, got, msg);
    assert_unchanged(scene, before, what);
    snprintf(msg, sizeof msg, "%s: the logger got %d error message(s)", what, log->count[FOGRT_LOG_ERROR]);
    TEST_ASSERT_EQUAL_INT_MESSAGE(1, log->count[FOGRT_LOG_ERROR], msg);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, log->multi_line, what);
    snprintf(msg, sizeof msg, "%s: error message \"%s\" does not name \"%s\"", what, log->last_error, parameter);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(log->last_error, parameter), msg);
    memset(log, 0, sizeof *log);
}

static const float NaN_ = (float)NAN;
static const float INF_ = (float)INFINITY;

/* ------------------------------------------------------------------------------------------
   Creation, destruction and memory
   ------------------------------------------------------------------------------------------ */

/* A NULL desc must give a working scene with the default allocator; destroying NULL must be
   a no-op (a crash here is the failure). */
static void test_create_destroy_defaults(void)
{
    fogrt_scene *scene = NULL;
    fogrt_scene_info info;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_create(NULL, &scene));
    TEST_ASSERT_NOT_NULL(scene);
    fogrt_scene_get_info(scene, &info);
    TEST_ASSERT_EQUAL_UINT32(0, info.triangle_count);
    TEST_ASSERT_EQUAL_UINT32(0, info.sphere_count);
    TEST_ASSERT_EQUAL_UINT32(0, info.material_count);
    TEST_ASSERT_EQUAL_UINT32(0, info.light_count);
    TEST_ASSERT_FALSE(info.has_environment);
    TEST_ASSERT_FALSE(info.built);
    fogrt_scene_destroy(scene);
    fogrt_scene_destroy(NULL);
}

/* Every byte fogrt uses comes from the user's allocator and all of it is returned by
   fogrt_scene_destroy / fogrt_image_free; fails on a leak, a stray libc malloc that is freed
   through the user's free_fn, or a double free. */
static void test_counting_allocator(void)
{
    counting_allocator counter;
    fogrt_scene_desc sd;
    fogrt_scene *scene = NULL;
    fogrt_image img;
    fogrt_render_desc rd;
    long after_create;
    memset(&counter, 0, sizeof counter);
    memset(&sd, 0, sizeof sd);
    sd.allocator.alloc_fn = counting_alloc;
    sd.allocator.free_fn = counting_free;
    sd.allocator.user_data = &counter;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_create(&sd, &scene));
    after_create = counter.allocs;
    TEST_ASSERT_GREATER_THAN(0, after_create);   /* the scene object itself */
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_default(scene));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    TEST_ASSERT_GREATER_THAN(after_create, counter.allocs);   /* arrays and BVH */
    /* Building twice must free the first BVH. */
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));

    /* The image through the same allocator; render into it so per-thread scratch is used. */
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_image_alloc(&img, 8, 6, &sd.allocator));
    rd = fogrt_render_defaults();
    rd.width = 8;
    rd.height = 6;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_render(scene, &rd, &img, 1, NULL));
    fogrt_image_free(&img);
    fogrt_scene_destroy(scene);

    TEST_ASSERT_EQUAL_INT_MESSAGE(0, counter.bad_frees, "freed a pointer the allocator did not give");
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, counter.live, "blocks still allocated after destroy");
}

/* An allocator that fails must give FOGRT_RESULT_OUT_OF_MEMORY, never a crash or a leak:
   allow the first n allocations, then fail, for growing n. */
typedef struct failing_allocator { counting_allocator c; long budget; } failing_allocator;
static void *failing_alloc(size_t size, void *user_data)
{
    failing_allocator *f = (failing_allocator *)user_data;
    if (f->c.allocs >= f->budget) return NULL;
    return counting_alloc(size, &f->c);
}
static void failing_free(void *ptr, void *user_data)
{
    counting_free(ptr, &((failing_allocator *)user_data)->c);
}

static void test_out_of_memory(void)
{
    long budget;
    int reached_ok = 0;
    for (budget = 0; budget < 200 && !reached_ok; budget++) {
        failing_allocator f;
        fogrt_scene_desc sd;
        fogrt_scene *scene = NULL;
        fogrt_result r;
        memset(&f, 0, sizeof f);
        f.budget = budget;
        memset(&sd, 0, sizeof sd);
        sd.allocator.alloc_fn = failing_alloc;
        sd.allocator.free_fn = failing_free;
        sd.allocator.user_data = &f;
        r = fogrt_scene_create(&sd, &scene);
        if (r == FOGRT_RESULT_OK) {
            r = fogrt_scene_add_default(scene);
            if (r == FOGRT_RESULT_OK) r = fogrt_scene_build(scene, NULL);
            reached_ok = r == FOGRT_RESULT_OK;
            fogrt_scene_destroy(scene);
        } else {
            TEST_ASSERT_NULL(scene);
        }
        if (!reached_ok) TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OUT_OF_MEMORY, r);
        TEST_ASSERT_EQUAL_INT(0, f.c.bad_frees);
        TEST_ASSERT_EQUAL_INT(0, f.c.live);
    }
    TEST_ASSERT_TRUE_MESSAGE(reached_ok, "the default scene never built within 200 allocations");
}

/* ------------------------------------------------------------------------------------------
   Result codes
   ------------------------------------------------------------------------------------------ */

/* Every code has its own sentence; an unknown code still gets a string (never NULL). */
static void test_result_strings(void)
{
    int i, j;
    for (i = 0; i < FOGRT_RESULT_NUM; i++) {
        const char *s = fogrt_result_string((fogrt_result)i);
        TEST_ASSERT_NOT_NULL(s);
        TEST_ASSERT_GREATER_THAN(0, (int)strlen(s));
        for (j = 0; j < i; j++)
            TEST_ASSERT_TRUE_MESSAGE(strcmp(s, fogrt_result_string((fogrt_result)j)) != 0,
                                     "two result codes share a message");
    }
    TEST_ASSERT_EQUAL_STRING("ok", fogrt_result_string(FOGRT_RESULT_OK));
    TEST_ASSERT_NOT_NULL(fogrt_result_string(FOGRT_RESULT_NUM));
    TEST_ASSERT_NOT_NULL(fogrt_result_string((fogrt_result)12345));
    TEST_ASSERT_NOT_NULL(fogrt_result_string((fogrt_result)-1));
}

/* ------------------------------------------------------------------------------------------
   Good data
   ------------------------------------------------------------------------------------------ */

/* Materials get ids 0, 1, 2, ... and read back as given; ior 0 reads back as the documented
   default 1.5. */
static void test_add_materials(void)
{
    fogrt_scene *scene = new_scene(NULL);
    fogrt_material_desc m, back;
    static const fogrt_bsdf_type types[3] = { FOGRT_BSDF_DIFFUSE, FOGRT_BSDF_MIRROR, FOGRT_BSDF_REFRACTION };
    uint32_t id = 99;
    int i;
    for (i = 0; i < 3; i++) {
        memset(&m, 0, sizeof m);
        m.type = types[i];
        m.reflectance = v3(0.1f * (float)i, 0.2f, 0.3f);
        m.transmittance = v3(0.4f, 0.5f, 0.6f);
        m.emission = v3(0, (float)i, 0);
        m.ior = 1.33f;
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_material(scene, &m, &id));
        TEST_ASSERT_EQUAL_UINT32((uint32_t)i, id);
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_get_material(scene, id, &back));
        TEST_ASSERT_EQUAL_INT(m.type, back.type);
        TEST_ASSERT_TRUE(same_vec(m.reflectance, back.reflectance));
        TEST_ASSERT_TRUE(same_vec(m.transmittance, back.transmittance));
        TEST_ASSERT_TRUE(same_vec(m.emission, back.emission));
        TEST_ASSERT_EQUAL_FLOAT(1.33f, back.ior);
    }
    /* Defaults: type 0 is diffuse, ior 0 is 1.5. */
    memset(&m, 0, sizeof m);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_material(scene, &m, &id));
    TEST_ASSERT_EQUAL_UINT32(3, id);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_get_material(scene, id, &back));
    TEST_ASSERT_TRUE(back.type == FOGRT_BSDF_DEFAULT || back.type == FOGRT_BSDF_DIFFUSE);
    TEST_ASSERT_EQUAL_FLOAT(1.5f, back.ior);
    /* Reading past the end is an error, not garbage. */
    TEST_ASSERT_NOT_EQUAL(FOGRT_RESULT_OK, fogrt_scene_get_material(scene, 4, &back));
    fogrt_scene_destroy(scene);
}

/* Meshes (indexed, non-indexed, per-triangle materials) and spheres add up in the counts,
   and prim_material maps triangles first, then spheres. The scene copies the arrays: the
   caller's buffers are overwritten after the call and the scene must not notice. */
static void test_add_geometry(void)
{
    fogrt_scene *scene = new_scene(NULL);
    uint32_t m0 = add_diffuse(scene, 0.5f, 0.5f, 0.5f);
    uint32_t m1 = add_diffuse(scene, 0.1f, 0.2f, 0.3f);
    float soup[18] = { 0, 0, 2,  1, 0, 2,  0, 1, 2,   0, 0, 3,  1, 0, 3,  0, 1, 3 };
    uint32_t per_tri[2] = { 1, 0 };
    fogrt_mesh_desc mesh = quad_mesh(m0);
    fogrt_scene_info info;
    fogrt_hit hit;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_mesh(scene, &mesh));
    memset(&mesh, 0, sizeof mesh);
    mesh.positions = soup;              /* no indices: vertices 0,1,2 and 3,4,5 */
    mesh.vertex_count = 6;
    mesh.triangle_count = 2;
    mesh.triangle_materials = per_tri;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_mesh(scene, &mesh));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_sphere(scene, v3(5, 0, 0), 0.5f, m1));
    memset(soup, 0, sizeof soup);       /* the scene must hold its own copy */
    per_tri[0] = 77;
    fogrt_scene_get_info(scene, &info);
    TEST_ASSERT_EQUAL_UINT32(4, info.triangle_count);
    TEST_ASSERT_EQUAL_UINT32(1, info.sphere_count);
    TEST_ASSERT_EQUAL_UINT32(2, info.material_count);
    TEST_ASSERT_EQUAL_UINT32(m0, fogrt_scene_get_prim_material(scene, 0));
    TEST_ASSERT_EQUAL_UINT32(m0, fogrt_scene_get_prim_material(scene, 1));
    TEST_ASSERT_EQUAL_UINT32(m1, fogrt_scene_get_prim_material(scene, 2));
    TEST_ASSERT_EQUAL_UINT32(m0, fogrt_scene_get_prim_material(scene, 3));
    TEST_ASSERT_EQUAL_UINT32(m1, fogrt_scene_get_prim_material(scene, 4));

    /* After the build, the bounds cover the quad, the soup and the sphere, and a ray down
       the z axis at (0.25, 0.25) hits the soup's far triangle at z = 3 first. */
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    fogrt_scene_get_info(scene, &info);
    TEST_ASSERT_TRUE(info.built);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 0.0f, info.bounds_min.x);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, -0.5f, info.bounds_min.y);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, -0.5f, info.bounds_min.z);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 5.5f, info.bounds_max.x);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 1.0f, info.bounds_max.y);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 3.0f, info.bounds_max.z);
    TEST_ASSERT_TRUE(fogrt_scene_intersect(scene, v3(0.25f, 0.25f, 10), v3(0, 0, -1), 0, INF_, &hit));
    TEST_ASSERT_EQUAL_UINT32(3, hit.prim);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 7.0f, hit.t);
    fogrt_scene_destroy(scene);
}

/* Lights read back as given; camera and medium read back (camera fov 0 = the default 45). */
static void test_lights_camera_medium(void)
{
    fogrt_scene *scene = new_scene(NULL);
    fogrt_light_desc pl = point_light(), sl = spot_light(), back;
    fogrt_camera_desc cam = simple_camera(), cb;
    fogrt_medium_desc med, mb;
    fogrt_scene_info info;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_light(scene, &pl));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_light(scene, &sl));
    fogrt_scene_get_info(scene, &info);
    TEST_ASSERT_EQUAL_UINT32(2, info.light_count);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_get_light(scene, 1, &back));
    TEST_ASSERT_EQUAL_INT(FOGRT_LIGHT_SPOT, back.type);
    TEST_ASSERT_TRUE(same_vec(sl.position, back.position));
    TEST_ASSERT_TRUE(same_vec(sl.intensity, back.intensity));
    TEST_ASSERT_EQUAL_FLOAT(30.0f, back.cutoff_deg);
    TEST_ASSERT_EQUAL_FLOAT(20.0f, back.beam_deg);
    TEST_ASSERT_NOT_EQUAL(FOGRT_RESULT_OK, fogrt_scene_get_light(scene, 2, &back));

    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_set_camera(scene, &cam));
    fogrt_scene_get_camera(scene, &cb);
    TEST_ASSERT_TRUE(same_vec(cam.position, cb.position));
    TEST_ASSERT_TRUE(same_vec(cam.look_at, cb.look_at));
    TEST_ASSERT_EQUAL_FLOAT(40.0f, cb.fov_deg);
    cam.fov_deg = 0.0f;   /* documented: 0 = 45 */
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_set_camera(scene, &cam));
    fogrt_scene_get_camera(scene, &cb);
    TEST_ASSERT_EQUAL_FLOAT(45.0f, cb.fov_deg);
    cam.fov_deg = 179.0f;  /* just inside (0, 180) */
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_set_camera(scene, &cam));

    memset(&med, 0, sizeof med);
    med.sigma_t = 0.5f;
    med.albedo = v3(1.0f, 0.0f, 0.5f);   /* the ends of [0,1] are legal */
    med.g = -1.0f;                       /* |g| = 1 is legal; clamped with a warning */
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_set_medium(scene, &med));
    fogrt_scene_get_medium(scene, &mb);
    TEST_ASSERT_EQUAL_FLOAT(0.5f, mb.sigma_t);
    TEST_ASSERT_TRUE(same_vec(med.albedo, mb.albedo));
    fogrt_scene_destroy(scene);
}

/* |g| >= FOGRT_HG_G_MAX is clamped to +-FOGRT_HG_G_MAX and the logger gets a warning (not an
   error) naming g; g just below the limit is stored as given, without a warning. */
/* A scene that nothing can light (geometry only: what loading an OBJ or PLY into an empty
   scene gives) builds, and says once through the logger that every image will be black;
   with a light it says nothing. Fog with an environment and no bounds gets the box of the
   geometry, and says so once. */
static void test_unlit_and_unbounded_warnings(void)
{
    log_record log;
    fogrt_scene *scene = new_scene(&log);
    fogrt_material_desc m;
    fogrt_medium_desc med;
    fogrt_light_desc l;
    uint32_t id;
    memset(&m, 0, sizeof m);
    m.reflectance = v3(0.5f, 0.5f, 0.5f);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_material(scene, &m, &id));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_sphere(scene, v3(0, 0, 0), 1.0f, id));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    TEST_ASSERT_EQUAL_INT(1, log.count[FOGRT_LOG_WARNING]);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(log.last_warning, "nothing emits light"), log.last_warning);
    memset(&log, 0, sizeof log);
    memset(&l, 0, sizeof l);
    l.position = v3(0, 3, 0); l.intensity = v3(1, 1, 1);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_light(scene, &l));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    TEST_ASSERT_EQUAL_INT(0, log.count[FOGRT_LOG_WARNING]);
#ifdef FOGRT_MINIMAL   /* the fog's box, given or from the geometry, is Part II's (C) */
    (void)med;
#else
    memset(&med, 0, sizeof med);
    med.sigma_t = 0.3f; med.albedo = v3(0.9f, 0.9f, 0.9f);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_set_medium(scene, &med));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_set_environment(scene, v3(1, 1, 1), true));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    TEST_ASSERT_EQUAL_INT(1, log.count[FOGRT_LOG_WARNING]);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(log.last_warning, "box of the geometry"), log.last_warning);
    memset(&log, 0, sizeof log);
    med.bounded = true; med.bounds_min = v3(-2, -2, -2); med.bounds_max = v3(2, 2, 2);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_set_medium(scene, &med));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    TEST_ASSERT_EQUAL_INT(0, log.count[FOGRT_LOG_WARNING]);
    med.bounds_max.x = -3.0f;                                   /* min not below max */
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_INVALID_MEDIUM, fogrt_scene_set_medium(scene, &med));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(log.last_error, "bounds"), log.last_error);
#endif
    fogrt_scene_destroy(scene);
}

static void test_medium_g_clamp_warns(void)
{
    log_record log;
    fogrt_scene *scene = new_scene(&log);
    fogrt_medium_desc med, back;
    memset(&med, 0, sizeof med);
    med.sigma_t = 1.0f;
    med.albedo = v3(0.5f, 0.5f, 0.5f);
    med.g = 1.0f;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_set_medium(scene, &med));
    fogrt_scene_get_medium(scene, &back);
    TEST_ASSERT_EQUAL_FLOAT(FOGRT_HG_G_MAX, back.g);
    TEST_ASSERT_EQUAL_INT(1, log.count[FOGRT_LOG_WARNING]);
    TEST_ASSERT_EQUAL_INT(0, log.count[FOGRT_LOG_ERROR]);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(log.last_warning, "g"), log.last_warning);
    memset(&log, 0, sizeof log);
    med.g = -1.0f;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_set_medium(scene, &med));
    fogrt_scene_get_medium(scene, &back);
    TEST_ASSERT_EQUAL_FLOAT(-FOGRT_HG_G_MAX, back.g);
    TEST_ASSERT_EQUAL_INT(1, log.count[FOGRT_LOG_WARNING]);
    memset(&log, 0, sizeof log);
    med.g = 0.999f;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_set_medium(scene, &med));
    fogrt_scene_get_medium(scene, &back);
    TEST_ASSERT_EQUAL_FLOAT(0.999f, back.g);
    TEST_ASSERT_EQUAL_INT(0, log.total);
    fogrt_scene_destroy(scene);
}

/* ------------------------------------------------------------------------------------------
   Bad data: each returns its documented code, leaves the scene as it was (even its "built"
   state), and logs one error naming the parameter.
   ------------------------------------------------------------------------------------------ */

static void test_bad_materials(void)
{
    log_record log;
    fogrt_scene *scene = full_scene(&log);
    scene_snapshot before;
    fogrt_material_desc good, m;
    uint32_t id = 1234;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    take_snapshot(scene, &before);
    memset(&good, 0, sizeof good);
    good.type = FOGRT_BSDF_GLASS;
    good.reflectance = good.transmittance = v3(1, 1, 1);
    good.ior = 1.5f;

    m = good; m.reflectance.y = NaN_;
    assert_rejected(FOGRT_RESULT_INVALID_MATERIAL, fogrt_scene_add_material(scene, &m, &id), scene, &before, &log, "reflectance", "NaN reflectance");
    m = good; m.reflectance.x = -0.1f;
    assert_rejected(FOGRT_RESULT_INVALID_MATERIAL, fogrt_scene_add_material(scene, &m, &id), scene, &before, &log, "reflectance", "negative reflectance");
    m = good; m.transmittance.z = INF_;
    assert_rejected(FOGRT_RESULT_INVALID_MATERIAL, fogrt_scene_add_material(scene, &m, &id), scene, &before, &log, "transmittance", "infinite transmittance");
    m = good; m.emission.x = -1.0f;
    assert_rejected(FOGRT_RESULT_INVALID_MATERIAL, fogrt_scene_add_material(scene, &m, &id), scene, &before, &log, "emission", "negative emission");
    m = good; m.emission.z = NaN_;
    assert_rejected(FOGRT_RESULT_INVALID_MATERIAL, fogrt_scene_add_material(scene, &m, &id), scene, &before, &log, "emission", "NaN emission");
    m = good; m.ior = -1.5f;
    assert_rejected(FOGRT_RESULT_INVALID_MATERIAL, fogrt_scene_add_material(scene, &m, &id), scene, &before, &log, "ior", "negative ior");
    m = good; m.ior = NaN_;
    assert_rejected(FOGRT_RESULT_INVALID_MATERIAL, fogrt_scene_add_material(scene, &m, &id), scene, &before, &log, "ior", "NaN ior");
    m = good; m.type = FOGRT_BSDF_NUM;
    assert_rejected(FOGRT_RESULT_INVALID_MATERIAL, fogrt_scene_add_material(scene, &m, &id), scene, &before, &log, "type", "BSDF type out of range");
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(1234, id, "a rejected material wrote an id");
    fogrt_scene_destroy(scene);
}

static void test_bad_meshes(void)
{
    log_record log;
    fogrt_scene *scene = full_scene(&log);
    scene_snapshot before;
    fogrt_mesh_desc mesh;
    float nan_pos[12], inf_pos[12];
    uint32_t bad_idx[6] = { 0, 1, 2,  0, 2, 4 };      /* vertex 4 of 4 */
    uint32_t bad_tri_mat[2] = { 0, 2 };                /* material 2 of 2 */
    memcpy(nan_pos, quad_positions, sizeof nan_pos);
    nan_pos[7] = NaN_;
    memcpy(inf_pos, quad_positions, sizeof inf_pos);
    inf_pos[3] = -INF_;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    take_snapshot(scene, &before);

    mesh = quad_mesh(0); mesh.positions = nan_pos;
    assert_rejected(FOGRT_RESULT_INVALID_GEOMETRY, fogrt_scene_add_mesh(scene, &mesh), scene, &before, &log, "position", "NaN vertex position");
    mesh = quad_mesh(0); mesh.positions = inf_pos;
    assert_rejected(FOGRT_RESULT_INVALID_GEOMETRY, fogrt_scene_add_mesh(scene, &mesh), scene, &before, &log, "position", "infinite vertex position");
    mesh = quad_mesh(0); mesh.indices = bad_idx;
    assert_rejected(FOGRT_RESULT_INVALID_GEOMETRY, fogrt_scene_add_mesh(scene, &mesh), scene, &before, &log, "ind", "vertex index out of range");
    mesh = quad_mesh(0); mesh.indices = NULL;   /* implicit 0,1,2 / 3,4,5 needs 6 vertices */
    assert_rejected(FOGRT_RESULT_INVALID_GEOMETRY, fogrt_scene_add_mesh(scene, &mesh), scene, &before, &log, "vertex_count", "too few vertices for implicit indices");
    mesh = quad_mesh(2);
    assert_rejected(FOGRT_RESULT_INVALID_MATERIAL, fogrt_scene_add_mesh(scene, &mesh), scene, &before, &log, "material", "mesh material out of range");
    mesh = quad_mesh(0); mesh.triangle_materials = bad_tri_mat;
    assert_rejected(FOGRT_RESULT_INVALID_MATERIAL, fogrt_scene_add_mesh(scene, &mesh), scene, &before, &log, "material", "per-triangle material out of range");
    fogrt_scene_destroy(scene);
}

static void test_bad_spheres(void)
{
    log_record log;
    fogrt_scene *scene = full_scene(&log);
    scene_snapshot before;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    take_snapshot(scene, &before);
    assert_rejected(FOGRT_RESULT_INVALID_GEOMETRY, fogrt_scene_add_sphere(scene, v3(0, 0, 0), 0.0f, 0), scene, &before, &log, "radius", "radius 0");
    assert_rejected(FOGRT_RESULT_INVALID_GEOMETRY, fogrt_scene_add_sphere(scene, v3(0, 0, 0), -1.0f, 0), scene, &before, &log, "radius", "negative radius");
    assert_rejected(FOGRT_RESULT_INVALID_GEOMETRY, fogrt_scene_add_sphere(scene, v3(0, 0, 0), NaN_, 0), scene, &before, &log, "radius", "NaN radius");
    assert_rejected(FOGRT_RESULT_INVALID_GEOMETRY, fogrt_scene_add_sphere(scene, v3(0, 0, 0), INF_, 0), scene, &before, &log, "radius", "infinite radius");
    assert_rejected(FOGRT_RESULT_INVALID_GEOMETRY, fogrt_scene_add_sphere(scene, v3(0, NaN_, 0), 1.0f, 0), scene, &before, &log, "center", "NaN center");
    assert_rejected(FOGRT_RESULT_INVALID_GEOMETRY, fogrt_scene_add_sphere(scene, v3(INF_, 0, 0), 1.0f, 0), scene, &before, &log, "center", "infinite center");
    assert_rejected(FOGRT_RESULT_INVALID_MATERIAL, fogrt_scene_add_sphere(scene, v3(0, 0, 0), 1.0f, 2), scene, &before, &log, "material", "sphere material out of range");
    assert_rejected(FOGRT_RESULT_INVALID_MATERIAL, fogrt_scene_add_sphere(scene, v3(0, 0, 0), 1.0f, 0xFFFFFFFFu), scene, &before, &log, "material", "sphere material 0xFFFFFFFF");
    fogrt_scene_destroy(scene);
}

static void test_bad_lights(void)
{
    log_record log;
    fogrt_scene *scene = full_scene(&log);
    scene_snapshot before;
    fogrt_light_desc l;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    take_snapshot(scene, &before);
    l = point_light(); l.intensity.y = -1.0f;
    assert_rejected(FOGRT_RESULT_INVALID_LIGHT, fogrt_scene_add_light(scene, &l), scene, &before, &log, "intensity", "negative intensity");
    l = point_light(); l.intensity.x = NaN_;
    assert_rejected(FOGRT_RESULT_INVALID_LIGHT, fogrt_scene_add_light(scene, &l), scene, &before, &log, "intensity", "NaN intensity");
    l = point_light(); l.intensity.z = INF_;
    assert_rejected(FOGRT_RESULT_INVALID_LIGHT, fogrt_scene_add_light(scene, &l), scene, &before, &log, "intensity", "infinite intensity");
    l = point_light(); l.position.x = NaN_;
    assert_rejected(FOGRT_RESULT_INVALID_LIGHT, fogrt_scene_add_light(scene, &l), scene, &before, &log, "position", "NaN light position");
    l = point_light(); l.radius = -0.5f;
    assert_rejected(FOGRT_RESULT_INVALID_LIGHT, fogrt_scene_add_light(scene, &l), scene, &before, &log, "radius", "negative light radius");
    l = point_light(); l.type = FOGRT_LIGHT_NUM;
    assert_rejected(FOGRT_RESULT_INVALID_LIGHT, fogrt_scene_add_light(scene, &l), scene, &before, &log, "type", "light type out of range");
    l = spot_light(); l.cutoff_deg = 181.0f;
    assert_rejected(FOGRT_RESULT_INVALID_LIGHT, fogrt_scene_add_light(scene, &l), scene, &before, &log, "cutoff", "spot cutoff above 180");
    l = spot_light(); l.cutoff_deg = -10.0f;
    assert_rejected(FOGRT_RESULT_INVALID_LIGHT, fogrt_scene_add_light(scene, &l), scene, &before, &log, "cutoff", "negative spot cutoff");
    l = spot_light(); l.beam_deg = 40.0f;    /* beam must be within 0..cutoff (30) */
    assert_rejected(FOGRT_RESULT_INVALID_LIGHT, fogrt_scene_add_light(scene, &l), scene, &before, &log, "beam", "spot beam above cutoff");
    l = spot_light(); l.beam_deg = -1.0f;
    assert_rejected(FOGRT_RESULT_INVALID_LIGHT, fogrt_scene_add_light(scene, &l), scene, &before, &log, "beam", "negative spot beam");
    l = spot_light(); l.direction = v3(0, 0, 0);
    assert_rejected(FOGRT_RESULT_INVALID_LIGHT, fogrt_scene_add_light(scene, &l), scene, &before, &log, "direction", "zero spot direction");
    l = spot_light(); l.direction.y = NaN_;
    assert_rejected(FOGRT_RESULT_INVALID_LIGHT, fogrt_scene_add_light(scene, &l), scene, &before, &log, "direction", "NaN spot direction");
    fogrt_scene_destroy(scene);
}

static void test_bad_cameras(void)
{
    log_record log;
    fogrt_scene *scene = full_scene(&log);
    scene_snapshot before;
    fogrt_camera_desc c;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    take_snapshot(scene, &before);
    c = simple_camera(); c.fov_deg = 180.0f;
    assert_rejected(FOGRT_RESULT_INVALID_CAMERA, fogrt_scene_set_camera(scene, &c), scene, &before, &log, "fov", "fov 180");
    c = simple_camera(); c.fov_deg = 270.0f;
    assert_rejected(FOGRT_RESULT_INVALID_CAMERA, fogrt_scene_set_camera(scene, &c), scene, &before, &log, "fov", "fov 270");
    c = simple_camera(); c.fov_deg = -30.0f;
    assert_rejected(FOGRT_RESULT_INVALID_CAMERA, fogrt_scene_set_camera(scene, &c), scene, &before, &log, "fov", "negative fov");
    c = simple_camera(); c.fov_deg = NaN_;
    assert_rejected(FOGRT_RESULT_INVALID_CAMERA, fogrt_scene_set_camera(scene, &c), scene, &before, &log, "fov", "NaN fov");
    c = simple_camera(); c.look_at = c.position;
    assert_rejected(FOGRT_RESULT_INVALID_CAMERA, fogrt_scene_set_camera(scene, &c), scene, &before, &log, "look_at", "eye == target");
    c = simple_camera(); c.position.z = NaN_;
    assert_rejected(FOGRT_RESULT_INVALID_CAMERA, fogrt_scene_set_camera(scene, &c), scene, &before, &log, "position", "NaN eye");
    c = simple_camera(); c.look_at.x = INF_;
    assert_rejected(FOGRT_RESULT_INVALID_CAMERA, fogrt_scene_set_camera(scene, &c), scene, &before, &log, "look_at", "infinite target");
    c = simple_camera(); c.up = v3(0, 0, -2);   /* parallel to the view direction */
    assert_rejected(FOGRT_RESULT_INVALID_CAMERA, fogrt_scene_set_camera(scene, &c), scene, &before, &log, "up", "up parallel to the view direction");
    c = simple_camera(); c.focal_distance = -1.0f;
    assert_rejected(FOGRT_RESULT_INVALID_CAMERA, fogrt_scene_set_camera(scene, &c), scene, &before, &log, "focal_distance", "negative focal distance");
    c = simple_camera(); c.lens_radius = -0.1f;
    assert_rejected(FOGRT_RESULT_INVALID_CAMERA, fogrt_scene_set_camera(scene, &c), scene, &before, &log, "lens_radius", "negative lens radius");
    fogrt_scene_destroy(scene);
}

static void test_bad_media(void)
{
    log_record log;
    fogrt_scene *scene = full_scene(&log);
    scene_snapshot before;
    fogrt_medium_desc good, m;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    take_snapshot(scene, &before);
    memset(&good, 0, sizeof good);
    good.sigma_t = 1.0f;
    good.albedo = v3(0.5f, 0.5f, 0.5f);
    good.g = 0.5f;
    m = good; m.sigma_t = -0.01f;
    assert_rejected(FOGRT_RESULT_INVALID_MEDIUM, fogrt_scene_set_medium(scene, &m), scene, &before, &log, "sigma_t", "negative sigma_t");
    m = good; m.sigma_t = NaN_;
    assert_rejected(FOGRT_RESULT_INVALID_MEDIUM, fogrt_scene_set_medium(scene, &m), scene, &before, &log, "sigma_t", "NaN sigma_t");
    m = good; m.sigma_t = INF_;
    assert_rejected(FOGRT_RESULT_INVALID_MEDIUM, fogrt_scene_set_medium(scene, &m), scene, &before, &log, "sigma_t", "infinite sigma_t");
    m = good; m.g = 1.01f;
    assert_rejected(FOGRT_RESULT_INVALID_MEDIUM, fogrt_scene_set_medium(scene, &m), scene, &before, &log, "g", "g > 1");
    m = good; m.g = -1.5f;
    assert_rejected(FOGRT_RESULT_INVALID_MEDIUM, fogrt_scene_set_medium(scene, &m), scene, &before, &log, "g", "g < -1");
    m = good; m.g = NaN_;
    assert_rejected(FOGRT_RESULT_INVALID_MEDIUM, fogrt_scene_set_medium(scene, &m), scene, &before, &log, "g", "NaN g");
    m = good; m.albedo.y = 1.001f;
    assert_rejected(FOGRT_RESULT_INVALID_MEDIUM, fogrt_scene_set_medium(scene, &m), scene, &before, &log, "albedo", "albedo > 1");
    m = good; m.albedo.x = -0.001f;
    assert_rejected(FOGRT_RESULT_INVALID_MEDIUM, fogrt_scene_set_medium(scene, &m), scene, &before, &log, "albedo", "albedo < 0");
    m = good; m.albedo.z = NaN_;
    assert_rejected(FOGRT_RESULT_INVALID_MEDIUM, fogrt_scene_set_medium(scene, &m), scene, &before, &log, "albedo", "NaN albedo");
    fogrt_scene_destroy(scene);
}

/* A non-finite or negative environment radiance is bad data too. The header names no code
   for it; fogrt answers INVALID_ARGUMENT (the environment is set, not added as a light). */
static void test_bad_environment(void)
{
    log_record log;
    fogrt_scene *scene = full_scene(&log);
    scene_snapshot before;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    take_snapshot(scene, &before);
    assert_rejected(FOGRT_RESULT_INVALID_ARGUMENT, fogrt_scene_set_environment(scene, v3(1, NaN_, 1), false), scene, &before, &log, "radiance", "NaN environment");
    assert_rejected(FOGRT_RESULT_INVALID_ARGUMENT, fogrt_scene_set_environment(scene, v3(1, 1, -1), true), scene, &before, &log, "radiance", "negative environment");
    fogrt_scene_destroy(scene);
}

/* Good changes after a build do mark the scene unbuilt; a silent logger stays silent. */
static void test_changes_unbuild(void)
{
    fogrt_scene *scene = full_scene(NULL);
    fogrt_scene_info info;
    fogrt_light_desc l = point_light();
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    fogrt_scene_get_info(scene, &info);
    TEST_ASSERT_TRUE(info.built);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_light(scene, &l));
    fogrt_scene_get_info(scene, &info);
    TEST_ASSERT_FALSE(info.built);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_sphere(scene, v3(0, 0, 0), 0.1f, 0));
    fogrt_scene_get_info(scene, &info);
    TEST_ASSERT_FALSE(info.built);
    fogrt_scene_destroy(scene);
}

/* Bad build parameters are rejected too (bins at most 64). */
static void test_bad_build_desc(void)
{
    log_record log;
    fogrt_scene *scene = full_scene(&log);
    fogrt_build_desc bd;
    fogrt_scene_info info;
    bd = fogrt_build_defaults();
    bd.bins = 65;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_INVALID_ARGUMENT, fogrt_scene_build(scene, &bd));
    TEST_ASSERT_EQUAL_INT(1, log.count[FOGRT_LOG_ERROR]);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(log.last_error, "bins"), log.last_error);
    fogrt_scene_get_info(scene, &info);
    TEST_ASSERT_FALSE(info.built);
    bd.bins = 64;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, &bd));
    fogrt_scene_destroy(scene);
}

/* ------------------------------------------------------------------------------------------
   Rendering needs a build
   ------------------------------------------------------------------------------------------ */

/* fogrt_render on a scene never built, or changed since the build, returns NOT_BUILT and
   leaves the image untouched; a mismatched image size is an invalid argument. */
static void test_render_not_built(void)
{
    fogrt_scene *scene = new_scene(NULL);
    fogrt_image img;
    fogrt_render_desc rd;
    fogrt_light_desc l = point_light();
    int i;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_default(scene));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_image_alloc(&img, 4, 3, NULL));
    fogrt_image_clear(&img);
    rd = fogrt_render_defaults();
    rd.width = 4;
    rd.height = 3;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_NOT_BUILT, fogrt_render(scene, &rd, &img, 1, NULL));
    for (i = 0; i < 4 * 3; i++) TEST_ASSERT_EQUAL_UINT32(0, img.count[i]);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_render(scene, &rd, &img, 1, NULL));
    for (i = 0; i < 4 * 3; i++) TEST_ASSERT_EQUAL_UINT32(1, img.count[i]);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_light(scene, &l));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_NOT_BUILT, fogrt_render(scene, &rd, &img, 1, NULL));
    for (i = 0; i < 4 * 3; i++) TEST_ASSERT_EQUAL_UINT32(1, img.count[i]);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    rd.width = 5;   /* does not match the 4x3 image */
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_INVALID_ARGUMENT, fogrt_render(scene, &rd, &img, 1, NULL));
    for (i = 0; i < 4 * 3; i++) TEST_ASSERT_EQUAL_UINT32(1, img.count[i]);
    fogrt_image_free(&img);
    fogrt_scene_destroy(scene);
}

/* A scene with neither geometry nor lights cannot be built. */
static void test_empty_scene(void)
{
    fogrt_scene *scene = new_scene(NULL);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_EMPTY_SCENE, fogrt_scene_build(scene, NULL));
    fogrt_scene_destroy(scene);
}

/* ------------------------------------------------------------------------------------------
   Features found by the build
   ------------------------------------------------------------------------------------------ */

static uint32_t features_of(fogrt_scene *scene)
{
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    return fogrt_scene_get_features(scene);
}

static void assert_features(uint32_t expected, uint32_t got, const char *what)
{
    char msg[256];
    snprintf(msg, sizeof msg, "%s: expected features 0x%x, got 0x%x", what, (unsigned)expected, (unsigned)got);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(expected, got, msg);
}

/* The integrator skips what a scene does not use, so the features must be exact: a flag
   set too often costs time, a flag missing drops a part of the image. */
static void test_features(void)
{
    fogrt_scene *scene;
    fogrt_mesh_desc mesh;
    fogrt_medium_desc med;
    fogrt_light_desc pl = point_light(), sl = spot_light();
    fogrt_material_desc emissive;
    uint32_t id, glass, refr;

    /* Triangles and a point light; a medium with sigma_t = 0 is no medium; an unused glass
       material does not bring in Fresnel. */
    scene = new_scene(NULL);
    mesh = quad_mesh(add_diffuse(scene, 0.5f, 0.5f, 0.5f));
    glass = add_material_of_type(scene, FOGRT_BSDF_GLASS);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_mesh(scene, &mesh));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_light(scene, &pl));
    memset(&med, 0, sizeof med);
    med.sigma_t = 0.0f;
    med.albedo = v3(1, 1, 1);
    med.g = 0.5f;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_set_medium(scene, &med));
    assert_features(FOGRT_FEATURE_TRIANGLES | FOGRT_FEATURE_POINT_LIGHTS, features_of(scene), "quad + point light");

    /* A glass sphere: spheres, refraction and Fresnel. */
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_sphere(scene, v3(0, 0, 1), 0.3f, glass));
    assert_features(FOGRT_FEATURE_TRIANGLES | FOGRT_FEATURE_POINT_LIGHTS | FOGRT_FEATURE_SPHERES |
                    FOGRT_FEATURE_REFRACTION | FOGRT_FEATURE_FRESNEL, features_of(scene), "+ glass sphere");

    /* Fog on: the medium flag. */
    med.sigma_t = 0.1f;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_set_medium(scene, &med));
    assert_features(FOGRT_FEATURE_TRIANGLES | FOGRT_FEATURE_POINT_LIGHTS | FOGRT_FEATURE_SPHERES |
                    FOGRT_FEATURE_REFRACTION | FOGRT_FEATURE_FRESNEL | FOGRT_FEATURE_MEDIUM,
                    features_of(scene), "+ fog");
    fogrt_scene_destroy(scene);

    /* Refraction without glass: no Fresnel. A spot light is a point light too. An emissive
       sphere is an area light. The environment has its own flag. */
    scene = new_scene(NULL);
    refr = add_material_of_type(scene, FOGRT_BSDF_REFRACTION);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_sphere(scene, v3(0, 0, 0), 1.0f, refr));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_light(scene, &sl));
    assert_features(FOGRT_FEATURE_SPHERES | FOGRT_FEATURE_REFRACTION | FOGRT_FEATURE_POINT_LIGHTS |
                    FOGRT_FEATURE_SPOT_LIGHTS, features_of(scene), "refraction sphere + spot");
    memset(&emissive, 0, sizeof emissive);
    emissive.emission = v3(2, 2, 2);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_material(scene, &emissive, &id));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_sphere(scene, v3(3, 0, 0), 0.5f, id));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_set_environment(scene, v3(0.1f, 0.1f, 0.1f), false));
    assert_features(FOGRT_FEATURE_SPHERES | FOGRT_FEATURE_REFRACTION | FOGRT_FEATURE_POINT_LIGHTS |
                    FOGRT_FEATURE_SPOT_LIGHTS | FOGRT_FEATURE_AREA_LIGHTS | FOGRT_FEATURE_ENVIRONMENT,
                    features_of(scene), "+ emissive sphere + environment");
    fogrt_scene_destroy(scene);

    /* An emissive triangle mesh alone, and mirror + diffuse (no refraction, no Fresnel). */
    scene = new_scene(NULL);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_material(scene, &emissive, &id));
    mesh = quad_mesh(id);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_mesh(scene, &mesh));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_sphere(scene, v3(0, 0, 1), 0.2f,
                                                                 add_material_of_type(scene, FOGRT_BSDF_MIRROR)));
    assert_features(FOGRT_FEATURE_TRIANGLES | FOGRT_FEATURE_AREA_LIGHTS | FOGRT_FEATURE_SPHERES,
                    features_of(scene), "emissive quad + mirror sphere");
    fogrt_scene_destroy(scene);

    /* The default scene uses everything but the environment. */
    scene = new_scene(NULL);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_default(scene));
    assert_features(FOGRT_FEATURE_MEDIUM | FOGRT_FEATURE_FRESNEL | FOGRT_FEATURE_REFRACTION |
                    FOGRT_FEATURE_AREA_LIGHTS | FOGRT_FEATURE_POINT_LIGHTS | FOGRT_FEATURE_SPOT_LIGHTS |
                    FOGRT_FEATURE_SPHERES | FOGRT_FEATURE_TRIANGLES, features_of(scene), "default scene");
    fogrt_scene_destroy(scene);
}

/* The default scene matches its description: the Cornell box bounds (walls x, z = +-1,
   floor 0, ceiling 1.5), two spheres, a spot light, an area light and fog sigma_t 0.3,
   albedo 0.9, g 0.6. */
static void test_default_scene_contents(void)
{
    fogrt_scene *scene = new_scene(NULL);
    fogrt_scene_info info;
    fogrt_medium_desc med;
    fogrt_light_desc light;
    uint32_t node_count = 0;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_default(scene));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    fogrt_scene_get_info(scene, &info);
    TEST_ASSERT_EQUAL_UINT32(2, info.sphere_count);
    TEST_ASSERT_EQUAL_UINT32(1, info.light_count);
    TEST_ASSERT_GREATER_OR_EQUAL(1, info.area_light_count);
    TEST_ASSERT_GREATER_OR_EQUAL(10, info.triangle_count);
    TEST_ASSERT_FLOAT_WITHIN(1e-4f, -1.0f, info.bounds_min.x);
    TEST_ASSERT_FLOAT_WITHIN(1e-4f, 0.0f, info.bounds_min.y);
    TEST_ASSERT_FLOAT_WITHIN(1e-4f, 1.0f, info.bounds_max.x);
    TEST_ASSERT_FLOAT_WITHIN(1e-4f, 1.5f, info.bounds_max.y);
    TEST_ASSERT_FLOAT_WITHIN(1e-4f, -1.0f, info.bounds_min.z);
    TEST_ASSERT_TRUE(info.bounds_max.z >= 1.0f - 1e-4f);
    /* The memory getter holds at least the triangles' vertices and the binary tree's nodes. */
#ifndef FOGRT_MINIMAL   /* the tree and memory getters are Part II's */
    fogrt_scene_get_bvh(scene, NULL, &node_count, NULL);
    TEST_ASSERT_TRUE(fogrt_scene_get_memory(scene) >= 3 * sizeof(fogrt_vec3) * info.triangle_count + sizeof(fogrt_bvh_node) * node_count);
#else
    (void)node_count;
#endif
    fogrt_scene_get_medium(scene, &med);
    TEST_ASSERT_EQUAL_FLOAT(0.3f, med.sigma_t);
    TEST_ASSERT_EQUAL_FLOAT(0.9f, med.albedo.x);
    TEST_ASSERT_EQUAL_FLOAT(0.6f, med.g);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_get_light(scene, 0, &light));
    TEST_ASSERT_EQUAL_INT(FOGRT_LIGHT_SPOT, light.type);
    fogrt_scene_destroy(scene);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_create_destroy_defaults);
    RUN_TEST(test_counting_allocator);
    RUN_TEST(test_out_of_memory);
    RUN_TEST(test_result_strings);
    RUN_TEST(test_add_materials);
    RUN_TEST(test_add_geometry);
    RUN_TEST(test_lights_camera_medium);
    RUN_TEST(test_medium_g_clamp_warns);
    RUN_TEST(test_unlit_and_unbounded_warnings);
    RUN_TEST(test_bad_materials);
    RUN_TEST(test_bad_meshes);
    RUN_TEST(test_bad_spheres);
    RUN_TEST(test_bad_lights);
    RUN_TEST(test_bad_cameras);
    RUN_TEST(test_bad_media);
    RUN_TEST(test_bad_environment);
    RUN_TEST(test_changes_unbuild);
    RUN_TEST(test_bad_build_desc);
    RUN_TEST(test_render_not_built);
    RUN_TEST(test_empty_scene);
    RUN_TEST(test_features);
    RUN_TEST(test_default_scene_contents);
    return UNITY_END();
}
