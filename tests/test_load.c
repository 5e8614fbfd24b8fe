/* test_load.c - fogrt_load.h: CS184 .dae scenes, OBJ, PLY and camera files.

   - every shared CS184 scene (../shared/scenes/cs184/) against the fact sheet in
     ../shared/docs/cs184-dae.md: triangle and sphere counts, lights, materials, camera;
   - one small hand-written file per element or quirk in tests/data/;
   - malformed and truncated input: an error naming file and line, never a crash, and the
     scene untouched;
   - the fuzzers' regression inputs (tests/fuzz/regress/);
   - the names options.on_shape reports (.dae nodes, materials, geometries; OBJ objects,
     groups and materials, an OBJ split per group only when names are asked for), and that
     asking for them changes no primitive;
   - the Stanford bunny PLY, and the load time of CBbunny.dae. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <time.h>
#include <dirent.h>
#include <unistd.h>
#include <sys/stat.h>
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#define FOGRT_LOAD_IMPLEMENTATION
#include "fogrt_load.h"
#include "unity.h"

#ifndef FOGRT_SHARED_DIR
#define FOGRT_SHARED_DIR "../shared"
#endif
#define CS184_DIR FOGRT_SHARED_DIR "/scenes/cs184/"
#define DATA_DIR "tests/data/"

void setUp(void) {}
void tearDown(void) {}

/* ------------------------------------------------------------------------------------------
   Helpers
   ------------------------------------------------------------------------------------------ */
static fogrt_scene *new_scene(void)
{
    fogrt_scene *s = NULL;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_create(NULL, &s));
    return s;
}
/* The build that tells whether a scene is whole: the tree, the lights and the tables, without
   the roulette's pilot (thousands of camera paths through the default box, a quarter of a
   second each at -O2 and most of this program's time; the pilot cannot fail, and it runs on
   the same default scene in test_render.c and test_extremes.c). */
static fogrt_result build_without_pilot(fogrt_scene *s)
{
    fogrt_build_desc bd = fogrt_build_defaults();
    bd.roulette_pilot = false;
    return fogrt_scene_build(s, &bd);
}
static bool file_exists(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (f) fclose(f);
    return f != NULL;
}
static char *read_all(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    char *buf;
    long n;
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    n = ftell(f);
    fseek(f, 0, SEEK_SET);
    buf = (char *)malloc((size_t)n + 1);
    if (buf && fread(buf, 1, (size_t)n, f) != (size_t)n) { free(buf); buf = NULL; }
    fclose(f);
    *size = (size_t)n;
    return buf;
}
/* Loads tests/data/name (by extension) into a fresh scene and expects OK. */
static fogrt_scene *load_ok(const char *name, fogrt_load_report *rep, const fogrt_load_options *opt)
{
    char path[512], msg[700];
    fogrt_scene *s = new_scene();
    fogrt_result r;
    snprintf(path, sizeof path, DATA_DIR "%s", name);
    r = fogrt_load_file(s, path, opt, rep);
    snprintf(msg, sizeof msg, "%s:%d: %s", rep->file, rep->line, rep->message);
    TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_RESULT_OK, r, msg);
    return s;
}
static fogrt_load_options as_is(void)
{
    fogrt_load_options o;
    memset(&o, 0, sizeof o);
    o.place = FOGRT_LOAD_PLACE_AS_IS;
    return o;
}
static fogrt_vec3 tri_v(const fogrt_scene *s, uint32_t t, int k) { return s->tri_v[3 * t + (uint32_t)k]; }
static fogrt_vec3 tri_n(const fogrt_scene *s, uint32_t t, int k) { return s->tri_n[3 * t + (uint32_t)k]; }
static fogrt_vec3 winding_normal(const fogrt_scene *s, uint32_t t)
{
    fogrt_vec3 a = tri_v(s, t, 0), b = tri_v(s, t, 1), c = tri_v(s, t, 2), n;
    float e1x = b.x - a.x, e1y = b.y - a.y, e1z = b.z - a.z, e2x = c.x - a.x, e2y = c.y - a.y, e2z = c.z - a.z;
    n.x = e1y * e2z - e1z * e2y; n.y = e1z * e2x - e1x * e2z; n.z = e1x * e2y - e1y * e2x;
    return n;
}
static void assert_vec3(float tol, float x, float y, float z, fogrt_vec3 v, const char *what)
{
    TEST_ASSERT_FLOAT_WITHIN_MESSAGE(tol, x, v.x, what);
    TEST_ASSERT_FLOAT_WITHIN_MESSAGE(tol, y, v.y, what);
    TEST_ASSERT_FLOAT_WITHIN_MESSAGE(tol, z, v.z, what);
}
static fogrt_material_desc prim_material(const fogrt_scene *s, uint32_t prim)
{
    fogrt_material_desc m;
    /* through the scene's arrays, so this reads the same under either name of the getter */
    uint32_t id = prim < s->tri_count ? s->tri_material[prim] : s->sph_material[prim - s->tri_count];
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_get_material(s, id, &m));
    return m;
}
static bool same_colour(fogrt_vec3 a, float r, float g, float b)
{
    return fabsf(a.x - r) < 1e-5f && fabsf(a.y - g) < 1e-5f && fabsf(a.z - b) < 1e-5f;
}
/* Number of triangles whose material has this diffuse reflectance (and no emission). */
static uint32_t count_diffuse(const fogrt_scene *s, float r, float g, float b)
{
    uint32_t t, n = 0;
    for (t = 0; t < s->tri_count; ++t) {
        const fogrt_material_desc *m = &s->materials[s->tri_material[t]];
        if (m->type == FOGRT_BSDF_DIFFUSE && same_colour(m->reflectance, r, g, b) && same_colour(m->emission, 0, 0, 0)) n++;
    }
    return n;
}

/* ------------------------------------------------------------------------------------------
   1. The shared CS184 scenes against the fact sheet
   ------------------------------------------------------------------------------------------ */
typedef struct cs184_fact {
    const char *file;
    uint32_t triangles, spheres;
    uint32_t point_lights, spot_lights, merged_area;   /* merged: the <area> lamp is the emissive quad */
    uint32_t emissive_triangles;
    bool ambient;
    float cam[3], look[3];
} cs184_fact;

static const cs184_fact cs184_facts[] = {
    { "CBempty.dae",              12,    0, 1, 0, 0, 2, false, { 0, 0.75f, 4.8023f },  { 0, 0.75f, 0 } },
    { "CBspheres_lambertian.dae", 12,    2, 0, 0, 1, 2, false, { 0, 0.75f, 4.8023f },  { 0, 0.75f, 0 } },
    { "CBspheres.dae",            12,    2, 0, 0, 1, 2, false, { 0, 0.75f, 4.8023f },  { 0, 0.75f, 0 } },
    { "CBspheres_refract.dae",    12,    2, 0, 0, 1, 2, false, { 0, 0.75f, 4.8023f },  { 0, 0.75f, 0 } },
    { "CBbunny.dae",              28588, 0, 0, 0, 1, 2, false, { 0, 0.75f, -4.8023f }, { 0, 0.75f, 0 } },
    { "bunny.dae",                33696, 0, 0, 0, 0, 0, true,  { 0, 1.4877f, 3.3159f }, { 0, 0.3824f, 0 } },
    { "CBbunny_upSpot.dae",       28586, 0, 0, 1, 0, 0, false, { 0, 0.75f, -4.8023f }, { 0, 0.75f, 0 } },
};

/* Per-file extras from the fact sheet (materials and light placement). */
static void check_cs184_details(const char *file, fogrt_scene *s)
{
    fogrt_scene_info info;
    fogrt_light_desc l;
    uint32_t i;
    fogrt_scene_get_info(s, &info);
    if (strncmp(file, "CB", 2) == 0) {
        /* Cornell walls: red 0.6 0.2 0.2 on the image-left (x = -1), blue on the right */
        TEST_ASSERT_EQUAL_UINT32_MESSAGE(2, count_diffuse(s, 0.6f, 0.2f, 0.2f), file);
        TEST_ASSERT_EQUAL_UINT32_MESSAGE(2, count_diffuse(s, 0.2f, 0.2f, 0.6f), file);
        /* the red wall is on the image's left, the blue one on its right (CBbunny turns the
           whole box and puts the camera on the other side, so the layout is the same) */
        for (i = 0; i < s->tri_count; ++i) {
            fogrt_vec3 v = tri_v(s, i, 0), p = s->camera.position, d = s->camera.look_at, right;
            float side;
            d.x -= p.x; d.y -= p.y; d.z -= p.z;
            right.x = -d.z; right.y = 0; right.z = d.x;          /* cross(forward, +y) */
            side = (v.x - p.x) * right.x + (v.z - p.z) * right.z;
            if (same_colour(s->materials[s->tri_material[i]].reflectance, 0.6f, 0.2f, 0.2f))
                TEST_ASSERT_TRUE_MESSAGE(side < 0.0f, "red wall on the image's left");
            if (same_colour(s->materials[s->tri_material[i]].reflectance, 0.2f, 0.2f, 0.6f))
                TEST_ASSERT_TRUE_MESSAGE(side > 0.0f, "blue wall on the image's right");
            if (same_colour(s->materials[s->tri_material[i]].reflectance, 0.6f, 0.2f, 0.2f))
                TEST_ASSERT_FLOAT_WITHIN_MESSAGE(1e-3f, 1.0f, fabsf(v.x), "red wall at x = +-1");
        }
    }
    if (strcmp(file, "CBspheres.dae") == 0 || strcmp(file, "CBspheres_refract.dae") == 0 || strcmp(file, "CBspheres_lambertian.dae") == 0) {
        /* sphere 0 (node Sphere1): r 0.3 at (0.4, 0.3, 0.3); sphere 1: (-0.4, 0.3, -0.3) */
        fogrt_material_desc m0 = prim_material(s, info.triangle_count), m1 = prim_material(s, info.triangle_count + 1);
        assert_vec3(1e-4f, 0.4f, 0.3f, 0.3f, s->sph_c[0], "sphere 0 centre");
        assert_vec3(1e-4f, -0.4f, 0.3f, -0.3f, s->sph_c[1], "sphere 1 centre");
        TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.3f, s->sph_r[0]);
        TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.3f, s->sph_r[1]);
        if (strcmp(file, "CBspheres_lambertian.dae") == 0) {
            TEST_ASSERT_EQUAL_INT(FOGRT_BSDF_DIFFUSE, m0.type);
            TEST_ASSERT_TRUE(same_colour(m0.reflectance, 0.8f, 0.8f, 0.8f));
            TEST_ASSERT_EQUAL_INT(FOGRT_BSDF_DIFFUSE, m1.type);
        } else {
            TEST_ASSERT_EQUAL_INT(strcmp(file, "CBspheres.dae") == 0 ? FOGRT_BSDF_GLASS : FOGRT_BSDF_REFRACTION, m0.type);
            TEST_ASSERT_FLOAT_WITHIN(1e-6f, 1.45f, m0.ior);
            TEST_ASSERT_TRUE(same_colour(m0.transmittance, 1, 1, 1));
            TEST_ASSERT_EQUAL_INT(FOGRT_BSDF_MIRROR, m1.type);
            TEST_ASSERT_TRUE(same_colour(m1.reflectance, 1, 1, 1));
        }
    }
    if (strcmp(file, "CBbunny.dae") == 0 || strcmp(file, "CBbunny_upSpot.dae") == 0) {
        /* the bunny: 28576 triangles of diffuse 0.5 (phong in CBbunny, lambert in upSpot) */
        TEST_ASSERT_EQUAL_UINT32_MESSAGE(28576, count_diffuse(s, 0.5f, 0.5f, 0.5f), file);
    }
    if (strcmp(file, "CBbunny.dae") == 0) {
        /* bunny bounding box from the fact sheet: x [-0.386, 0.391], y [0.002, 0.774], z [-0.289, 0.306] */
        float lo[3] = { 1e9f, 1e9f, 1e9f }, hi[3] = { -1e9f, -1e9f, -1e9f };
        int k;
        for (i = 0; i < s->tri_count; ++i) {
            if (!same_colour(s->materials[s->tri_material[i]].reflectance, 0.5f, 0.5f, 0.5f)) continue;
            for (k = 0; k < 3; ++k) {
                fogrt_vec3 v = tri_v(s, i, k);
                lo[0] = fminf(lo[0], v.x); lo[1] = fminf(lo[1], v.y); lo[2] = fminf(lo[2], v.z);
                hi[0] = fmaxf(hi[0], v.x); hi[1] = fmaxf(hi[1], v.y); hi[2] = fmaxf(hi[2], v.z);
            }
        }
        TEST_ASSERT_FLOAT_WITHIN(2e-3f, -0.386f, lo[0]); TEST_ASSERT_FLOAT_WITHIN(2e-3f, 0.391f, hi[0]);
        TEST_ASSERT_FLOAT_WITHIN(2e-3f, 0.002f, lo[1]);  TEST_ASSERT_FLOAT_WITHIN(2e-3f, 0.774f, hi[1]);
        TEST_ASSERT_FLOAT_WITHIN(2e-3f, -0.289f, lo[2]); TEST_ASSERT_FLOAT_WITHIN(2e-3f, 0.306f, hi[2]);
    }
    if (strcmp(file, "CBempty.dae") == 0) {
        /* the "Area" node has no CGL extra: a point light of colour 5 at (0, 1.49, 0.0043) */
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_get_light(s, 0, &l));
        TEST_ASSERT_EQUAL_INT(FOGRT_LIGHT_POINT, l.type);
        assert_vec3(1e-4f, 0.0f, 1.49f, 0.0043f, l.position, "CBempty point light");
        TEST_ASSERT_TRUE(same_colour(l.intensity, 5, 5, 5));
    }
    if (strcmp(file, "CBbunny_upSpot.dae") == 0) {
        /* the paper's spot: (0, 1.432, 0) pointing down, full angle 60, blend 0.2916403 */
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_get_light(s, 0, &l));
        TEST_ASSERT_EQUAL_INT(FOGRT_LIGHT_SPOT, l.type);
        assert_vec3(1e-4f, 0.0f, 1.432015f, 0.0f, l.position, "spot position");
        assert_vec3(1e-5f, 0.0f, -1.0f, 0.0f, l.direction, "spot axis");
        TEST_ASSERT_TRUE(same_colour(l.intensity, 10, 10, 10));
        TEST_ASSERT_FLOAT_WITHIN(1e-4f, 30.0f, l.cutoff_deg);
        TEST_ASSERT_FLOAT_WITHIN(1e-3f, 30.0f * (1.0f - 0.2916403f), l.beam_deg);
        /* no emissive quad in this file: fogrt's lamp is the spot alone */
        TEST_ASSERT_EQUAL_UINT32(0, info.area_light_count);
    }
    if (strcmp(file, "bunny.dae") == 0) {
        TEST_ASSERT_EQUAL_UINT32(28576, count_diffuse(s, 0.48f, 0.48f, 0.48f));
        TEST_ASSERT_EQUAL_UINT32(5120, count_diffuse(s, 0.25f, 0.25f, 0.25f));
        TEST_ASSERT_TRUE(s->has_env && s->env_upper_only);
        TEST_ASSERT_TRUE(same_colour(s->env, 1, 1, 1));
    }
}

/* Every shared CS184 file loads with the fact sheet's counts, lights and camera; fails if the
   loader drops or duplicates geometry, misreads a transform or places the camera otherwise. */
static void test_cs184_scenes_match_fact_sheet(void)
{
    size_t i;
    int found = 0;
    for (i = 0; i < sizeof cs184_facts / sizeof cs184_facts[0]; ++i) {
        const cs184_fact *f = &cs184_facts[i];
        char path[512], msg[700];
        fogrt_scene *s;
        fogrt_load_report rep;
        fogrt_load_options opt;
        fogrt_scene_info info;
        fogrt_camera_desc cam;
        fogrt_result r;
        uint32_t t;
        snprintf(path, sizeof path, CS184_DIR "%s", f->file);
        if (!file_exists(path)) continue;
        found++;
        memset(&opt, 0, sizeof opt);
        opt.image_width = 480; opt.image_height = 360;
        s = new_scene();
        r = fogrt_load_dae(s, path, &opt, &rep);
        snprintf(msg, sizeof msg, "%s:%d: %s", rep.file, rep.line, rep.message);
        TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_RESULT_OK, r, msg);
        TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_RESULT_OK, fogrt_scene_build(s, NULL), f->file);
        fogrt_scene_get_info(s, &info);
        TEST_ASSERT_EQUAL_UINT32_MESSAGE(f->triangles, info.triangle_count, f->file);
        TEST_ASSERT_EQUAL_UINT32_MESSAGE(f->spheres, info.sphere_count, f->file);
        TEST_ASSERT_EQUAL_UINT32_MESSAGE(f->point_lights, rep.point_lights, f->file);
        TEST_ASSERT_EQUAL_UINT32_MESSAGE(f->spot_lights, rep.spot_lights, f->file);
        TEST_ASSERT_EQUAL_UINT32_MESSAGE(f->point_lights + f->spot_lights, info.light_count, f->file);
        TEST_ASSERT_EQUAL_UINT32_MESSAGE(f->merged_area, rep.area_lights_merged, f->file);
        TEST_ASSERT_EQUAL_UINT32_MESSAGE(0, rep.area_rectangles, f->file);
        TEST_ASSERT_EQUAL_UINT32_MESSAGE(f->emissive_triangles, rep.emissive_triangles, f->file);
        TEST_ASSERT_EQUAL_INT_MESSAGE(f->ambient, rep.ambient, f->file);
        TEST_ASSERT_EQUAL_UINT32_MESSAGE(0, rep.warnings, f->file);
        /* CS184's camera: orbit position, looking at the box centre, +Y up */
        fogrt_scene_get_camera(s, &cam);
        TEST_ASSERT_TRUE_MESSAGE(rep.has_camera, f->file);
        assert_vec3(2e-3f, f->cam[0], f->cam[1], f->cam[2], cam.position, f->file);
        assert_vec3(2e-3f, f->look[0], f->look[1], f->look[2], cam.look_at, f->file);
        assert_vec3(0.0f, 0, 1, 0, cam.up, f->file);
        /* the fov CS184 uses for its 800x600 window (screenDist 875 px): tan(v/2) = 300/875 */
        TEST_ASSERT_FLOAT_WITHIN_MESSAGE(1e-4f, 300.0f / 875.0f, rep.frame_tan_half_y, f->file);
        /* the lamps (emissive quads) face down into the box */
        for (t = 0; t < info.triangle_count; ++t)
            if (!same_colour(s->materials[s->tri_material[t]].emission, 0, 0, 0))
                TEST_ASSERT_TRUE_MESSAGE((winding_normal(s, t).y) < (0.0f), f->file);
        check_cs184_details(f->file, s);
        fogrt_scene_destroy(s);
    }
    if (!found) TEST_IGNORE_MESSAGE("no CS184 scenes in " CS184_DIR " (../shared absent): skipped");
}

/* The Cornell walls' shading normals point into the box, as CS184 computes them for its open
   quads (negated winding normal); fails if the boundary rule is lost. */
static void test_cs184_wall_normals_point_into_box(void)
{
    fogrt_scene *s;
    fogrt_load_report rep;
    uint32_t t;
    int k, checked = 0;
    if (!file_exists(CS184_DIR "CBspheres.dae")) { TEST_IGNORE_MESSAGE("CBspheres.dae absent: skipped"); return; }
    s = new_scene();
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_load_dae(s, CS184_DIR "CBspheres.dae", NULL, &rep));
    for (t = 0; t < s->tri_count; ++t) {
        fogrt_vec3 c = tri_v(s, t, 0);
        if (!s->tri_has_n[t] || !same_colour(s->materials[s->tri_material[t]].emission, 0, 0, 0)) continue;
        for (k = 0; k < 3; ++k) {
            fogrt_vec3 n = tri_n(s, t, k);
            /* into the box: the normal points from the wall toward the box centre (0, 0.75, 0) */
            float to_centre = n.x * (0.0f - c.x) + n.y * (0.75f - c.y) + n.z * (0.0f - c.z);
            TEST_ASSERT_TRUE_MESSAGE((to_centre) > (0.0f), "to_centre > 0.0f");
            TEST_ASSERT_FLOAT_WITHIN(1e-5f, 1.0f, sqrtf(n.x * n.x + n.y * n.y + n.z * n.z));
            checked++;
        }
    }
    TEST_ASSERT_EQUAL_INT(30, checked);   /* 5 walls x 2 triangles x 3 corners */
    fogrt_scene_destroy(s);
}

/* Loading CBbunny.dae takes well under a second (printed); fails if parsing turns quadratic. */
static void test_cs184_bunny_load_time(void)
{
    struct timespec t0, t1;
    fogrt_scene *s;
    fogrt_load_report rep;
    double ms;
    char msg[128];
    if (!file_exists(CS184_DIR "CBbunny.dae")) { TEST_IGNORE_MESSAGE("CBbunny.dae absent: skipped"); return; }
    s = new_scene();
    clock_gettime(CLOCK_MONOTONIC, &t0);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_load_dae(s, CS184_DIR "CBbunny.dae", NULL, &rep));
    clock_gettime(CLOCK_MONOTONIC, &t1);
    ms = (double)(t1.tv_sec - t0.tv_sec) * 1e3 + (double)(t1.tv_nsec - t0.tv_nsec) * 1e-6;
    snprintf(msg, sizeof msg, "CBbunny.dae loaded in %.1f ms (%u triangles)", ms, rep.triangles);
    TEST_MESSAGE(msg);
#if defined(__SANITIZE_ADDRESS__)
    TEST_ASSERT_TRUE_MESSAGE((ms) < (5000.0), "ms < 5000.0");   /* sanitizers slow everything down */
#else
    TEST_ASSERT_TRUE_MESSAGE((ms) < (1000.0), "ms < 1000.0");
#endif
    fogrt_scene_destroy(s);
}

/* The CS184 framing is kept at every resolution: the same image fraction gives the same ray
   at 480x360 and 800x600, and a wider image only adds room at the sides; fails if the fov is
   recomputed from a fixed focal length in pixels as CS184 does. */
static void test_cs184_framing_at_every_resolution(void)
{
    fogrt_scene *s;
    fogrt_load_report rep;
    fogrt_load_options opt;
    fogrt_vec3 o1, d1, o2, d2;
    fogrt_camera_desc cam;
    if (!file_exists(CS184_DIR "CBspheres.dae")) { TEST_IGNORE_MESSAGE("CBspheres.dae absent: skipped"); return; }
    memset(&opt, 0, sizeof opt);
    opt.image_width = 480; opt.image_height = 360;
    s = new_scene();
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_load_dae(s, CS184_DIR "CBspheres.dae", &opt, &rep));
    fogrt_camera_ray(s, 480, 360, 0.0f, 0.0f, 0.5f, 0.5f, &o1, &d1);   /* top-left corner */
    fogrt_camera_ray(s, 800, 600, 0.0f, 0.0f, 0.5f, 0.5f, &o2, &d2);
    assert_vec3(1e-6f, d1.x, d1.y, d1.z, d2, "corner ray at 480x360 and 800x600");
    /* the 800x600 corner ray has CS184's half-angles: tan = 0.45714 (h) and 0.34286 (v) */
    TEST_ASSERT_FLOAT_WITHIN(1e-4f, -0.457143f, d1.x / -d1.z);
    TEST_ASSERT_FLOAT_WITHIN(1e-4f, 0.342857f, d1.y / -d1.z);
    fogrt_scene_destroy(s);
    /* 960x360 (wider): same vertical fov; 360x480 (taller): same horizontal fov */
    fogrt_load_fit_fov(rep.frame_tan_half_y, rep.frame_aspect, 960, 360, &cam);
    TEST_ASSERT_FALSE(cam.fov_is_horizontal);
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 37.8493f, cam.fov_deg);
    fogrt_load_fit_fov(rep.frame_tan_half_y, rep.frame_aspect, 360, 480, &cam);
    TEST_ASSERT_TRUE(cam.fov_is_horizontal);
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 49.1343f, cam.fov_deg);
}

/* ------------------------------------------------------------------------------------------
   2. One quirk per file (tests/data)
   ------------------------------------------------------------------------------------------ */
/* The minimal Y_UP scene: one triangle at its file position, grey 0.5 without a material,
   CS184's default camera (+z side, xfov 50 on 4:3); fails on any frame change. */
static void test_dae_minimal(void)
{
    fogrt_load_report rep;
    fogrt_scene *s = load_ok("dae_minimal_yup.dae", &rep, NULL);
    fogrt_material_desc m = prim_material(s, 0);
    TEST_ASSERT_EQUAL_UINT32(1, s->tri_count);
    assert_vec3(0, 1, 2, 3, tri_v(s, 0, 0), "v0");
    assert_vec3(0, 2, 2, 3, tri_v(s, 0, 1), "v1");
    TEST_ASSERT_EQUAL_INT(FOGRT_BSDF_DIFFUSE, m.type);
    TEST_ASSERT_TRUE(same_colour(m.reflectance, 0.5f, 0.5f, 0.5f));
    TEST_ASSERT_FALSE(rep.has_camera);
    /* bbox centre (1.5, 2.5, 3), diagonal sqrt(2): eye at centre + 1.5 sqrt(2) (0, 0, 1) */
    assert_vec3(1e-5f, 1.5f, 2.5f, 3.0f + 1.5f * sqrtf(2.0f), s->camera.position, "default camera");
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, tanf(25.0f * 3.14159265f / 180.0f) * 0.75f, rep.frame_tan_half_y);
    TEST_ASSERT_EQUAL_UINT32(0, rep.warnings);
    fogrt_scene_destroy(s);
}

/* up_axis: Z_UP maps (x,y,z) to (-x,z,y), X_UP to (y,x,-z), none = Y_UP with a warning;
   fails if the correction is missing, mirrored or applied after the node transform. */
static void test_dae_up_axis(void)
{
    fogrt_load_report rep;
    fogrt_scene *s = load_ok("dae_upaxis_zup.dae", &rep, NULL);
    assert_vec3(0, -1, 3, 2, tri_v(s, 0, 0), "Z_UP");
    assert_vec3(0, -2, 3, 2, tri_v(s, 0, 1), "Z_UP");
    /* a proper rotation: the winding normal (0,0,+) of the file becomes (0,+,0) */
    TEST_ASSERT_TRUE_MESSAGE((winding_normal(s, 0).y) > (0.0f), "winding_normal(s, 0).y > 0.0f");
    fogrt_scene_destroy(s);
    s = load_ok("dae_upaxis_xup.dae", &rep, NULL);
    assert_vec3(0, 2, 1, -3, tri_v(s, 0, 0), "X_UP");
    fogrt_scene_destroy(s);
    s = load_ok("dae_upaxis_none.dae", &rep, NULL);
    assert_vec3(0, 1, 2, 3, tri_v(s, 0, 0), "no up_axis");
    TEST_ASSERT_EQUAL_UINT32(1, rep.warnings);
    fogrt_scene_destroy(s);
}

/* translate / rotate / scale compose in document order, rotate in degrees, transforms after
   the first <matrix> are ignored, nested nodes compose parent x child. */
static void test_dae_transforms(void)
{
    fogrt_load_report rep;
    fogrt_scene *s = load_ok("dae_transforms.dae", &rep, NULL);
    TEST_ASSERT_EQUAL_UINT32(3, s->tri_count);
    assert_vec3(1e-5f, 1, 2, 0, tri_v(s, 0, 0), "A v0");
    assert_vec3(1e-5f, 0, 0, 0, tri_v(s, 0, 1), "A v1");
    assert_vec3(1e-5f, 1, 0, 0, tri_v(s, 0, 2), "A v2");
    assert_vec3(1e-5f, 2, 0, 5, tri_v(s, 1, 0), "B v0");
    assert_vec3(1e-5f, 1, 1, 5, tri_v(s, 1, 1), "B v1");
    assert_vec3(1e-5f, 3, 10, 0, tri_v(s, 2, 0), "C v0");
    assert_vec3(1e-5f, 0, 13, 0, tri_v(s, 2, 1), "C v1");
    fogrt_scene_destroy(s);
}

/* A 15-number camera matrix is zero-filled (not rejected), and only c = M (0,0,-1,1) places
   the camera; xfov 60 / aspect 2 is widened to 4:3 as CS184 does. */
static void test_dae_short_matrix_camera(void)
{
    fogrt_load_report rep;
    fogrt_load_options opt;
    fogrt_scene *s;
    float r = 1.5f * sqrtf(2.0f), cx = 1.0f / sqrtf(1.25f), cy = 0.5f / sqrtf(1.25f);
    memset(&opt, 0, sizeof opt);
    opt.image_width = 800; opt.image_height = 600;
    s = load_ok("dae_short_matrix.dae", &rep, &opt);
    TEST_ASSERT_TRUE(rep.has_camera);
    assert_vec3(1e-5f, 1.5f + r * cx, 2.5f + r * cy, 3.0f, s->camera.position, "camera position");
    assert_vec3(1e-5f, 1.5f, 2.5f, 3.0f, s->camera.look_at, "camera target");
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, tanf(30.0f * 3.14159265f / 180.0f) * 0.75f, rep.frame_tan_half_y);
    TEST_ASSERT_FALSE(s->camera.fov_is_horizontal);
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 2.0f * atanf(rep.frame_tan_half_y) * 180.0f / 3.14159265f, s->camera.fov_deg);
    fogrt_scene_destroy(s);
}

/* yfov given and narrower than 4:3 wide: the horizontal fov is widened, yfov kept; the first
   of two cameras wins (warning); Z_UP camera matrix of the Cornell files gives c = +z. */
static void test_dae_camera_yfov(void)
{
    fogrt_load_report rep;
    fogrt_scene *s = load_ok("dae_camera_yfov.dae", &rep, NULL);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, tanf(20.0f * 3.14159265f / 180.0f), rep.frame_tan_half_y);
    assert_vec3(1e-4f, 0, 0, 1.5f * sqrtf(8.0f), s->camera.position, "camera on +z");
    TEST_ASSERT_EQUAL_UINT32(1, rep.warnings);
    fogrt_scene_destroy(s);
}

/* One global id table: cross-library and forward references, a source taken from another
   mesh, and the first of two duplicate ids. */
static void test_dae_global_ids(void)
{
    fogrt_load_report rep;
    fogrt_scene *s = load_ok("dae_global_ids.dae", &rep, NULL);
    fogrt_material_desc m = prim_material(s, 0);
    TEST_ASSERT_EQUAL_UINT32(1, s->tri_count);
    assert_vec3(0, 0, 1, 0, tri_v(s, 0, 0), "mesh b reads mesh a's positions, reversed");
    TEST_ASSERT_TRUE(same_colour(m.reflectance, 0.7f, 0.1f, 0.1f));
    fogrt_scene_destroy(s);
}

/* polylist n-gons are fan-triangulated; the index stride is the largest offset + 1 (an extra
   COLOR input included); VERTEX is read at its own offset; 2-corner polygons are skipped. */
static void test_dae_polylist_ngon(void)
{
    fogrt_load_report rep;
    fogrt_scene *s = load_ok("dae_polylist_ngon.dae", &rep, NULL);
    TEST_ASSERT_EQUAL_UINT32(6, s->tri_count);
    /* quad 0 1 2 3 -> (0,1,2) (0,2,3); pentagon 4 5 6 7 2 -> (4,5,6) (4,6,7) (4,7,2) */
    assert_vec3(0, 0, 0, 0, tri_v(s, 1, 0), "fan 0");
    assert_vec3(0, 1, 1, 0, tri_v(s, 1, 1), "fan 2");
    assert_vec3(0, 0, 1, 0, tri_v(s, 1, 2), "fan 3");
    assert_vec3(0, 2, 0, 0, tri_v(s, 4, 0), "pentagon fan 4");
    assert_vec3(0, 2.5f, 2, 0, tri_v(s, 4, 1), "pentagon fan 7");
    assert_vec3(0, 1, 1, 0, tri_v(s, 4, 2), "pentagon fan 2");
    TEST_ASSERT_EQUAL_UINT32(1, rep.warnings);   /* the 2-corner polygon */
    fogrt_scene_destroy(s);
}

/* Several primitive lists in one mesh (<triangles>, <polylist>, <polygons>), each bound to its
   material by symbol, an unknown symbol falling back to the first instance_material. */
static void test_dae_multi_lists(void)
{
    fogrt_load_report rep;
    fogrt_scene *s = load_ok("dae_multi_lists.dae", &rep, NULL);
    TEST_ASSERT_EQUAL_UINT32(7, s->tri_count);
    TEST_ASSERT_EQUAL_UINT32(2, count_diffuse(s, 0.1f, 0.1f, 0.8f));
    TEST_ASSERT_EQUAL_UINT32(5, count_diffuse(s, 0.1f, 0.8f, 0.1f));
    TEST_ASSERT_TRUE(same_colour(prim_material(s, 0).reflectance, 0.1f, 0.1f, 0.8f));
    fogrt_scene_destroy(s);
}

/* CGL spheres: radius ".25" x the node's X scale 2, centre the node origin through Z_UP, the
   geometry shared by two nodes, grey without a material. */
static void test_dae_sphere(void)
{
    fogrt_load_report rep;
    fogrt_scene *s = load_ok("dae_sphere.dae", &rep, NULL);
    TEST_ASSERT_EQUAL_UINT32(2, s->sph_count);
    assert_vec3(1e-6f, -1, 3, 2, s->sph_c[0], "sphere centre");
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.5f, s->sph_r[0]);
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.25f, s->sph_r[1]);
    TEST_ASSERT_EQUAL_INT(FOGRT_BSDF_MIRROR, prim_material(s, 0).type);
    TEST_ASSERT_TRUE(same_colour(prim_material(s, 0).reflectance, 0.9f, 0.9f, 0.9f));
    TEST_ASSERT_TRUE(same_colour(prim_material(s, 1).reflectance, 0.5f, 0.5f, 0.5f));
    fogrt_scene_destroy(s);
}

/* Material precedence and every CGL BSDF, in the order of dae_materials.dae's comment. */
static void test_dae_materials(void)
{
    fogrt_load_report rep;
    fogrt_scene *s = load_ok("dae_materials.dae", &rep, NULL);
    fogrt_material_desc m;
    float f0r = ((0.2f - 1) * (0.2f - 1) + 3.9f * 3.9f) / ((0.2f + 1) * (0.2f + 1) + 3.9f * 3.9f);
    TEST_ASSERT_EQUAL_UINT32(12, s->tri_count);
    m = prim_material(s, 0);
    TEST_ASSERT_EQUAL_INT(FOGRT_BSDF_GLASS, m.type);
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 1.45f, m.ior);
    TEST_ASSERT_TRUE(same_colour(m.transmittance, 0.9f, 0.9f, 0.9f));
    TEST_ASSERT_TRUE(same_colour(m.reflectance, 1, 1, 1));
    m = prim_material(s, 1);
    TEST_ASSERT_EQUAL_INT(FOGRT_BSDF_DIFFUSE, m.type);
    TEST_ASSERT_TRUE(same_colour(m.reflectance, 0.2f, 0.4f, 0.6f));
    TEST_ASSERT_TRUE(same_colour(prim_material(s, 2).reflectance, 0.3f, 0.3f, 0.3f));
    TEST_ASSERT_TRUE(same_colour(prim_material(s, 3).reflectance, 0.5f, 0.5f, 0.5f));
    TEST_ASSERT_TRUE(same_colour(prim_material(s, 4).reflectance, 0.5f, 0.5f, 0.5f));
    m = prim_material(s, 5);
    TEST_ASSERT_TRUE(same_colour(m.emission, 4, 5, 6));
    TEST_ASSERT_TRUE(same_colour(m.reflectance, 0, 0, 0));
    m = prim_material(s, 6);
    TEST_ASSERT_EQUAL_INT(FOGRT_BSDF_REFRACTION, m.type);
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 1.33f, m.ior);
    TEST_ASSERT_TRUE(same_colour(m.transmittance, 0.8f, 0.9f, 1.0f));
    m = prim_material(s, 7);
#ifndef FOGRT_NO_MICROFACET   /* the rough metal (Part II, I) as the file writes it */
    TEST_ASSERT_EQUAL_INT(FOGRT_BSDF_MICROFACET, m.type);
    TEST_ASSERT_EQUAL_FLOAT(0.05f, m.alpha);
    TEST_ASSERT_TRUE(same_colour(m.eta, 0.2f, 0.9f, 1.1f));
    TEST_ASSERT_TRUE(same_colour(m.k, 3.9f, 2.4f, 2.2f));
    TEST_ASSERT_EQUAL_INT(FOGRT_BSDF_MICROFACET, prim_material(s, 11).type);
    TEST_ASSERT_EQUAL_FLOAT(0.5f, prim_material(s, 11).alpha);
    (void)f0r;
#else                         /* built without it: the nearest BSDF, with a warning each */
    TEST_ASSERT_EQUAL_INT(FOGRT_BSDF_MIRROR, m.type);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, f0r, m.reflectance.x);
    m = prim_material(s, 11);
    TEST_ASSERT_EQUAL_INT(FOGRT_BSDF_DIFFUSE, m.type);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, f0r, m.reflectance.x);
#endif
    TEST_ASSERT_TRUE(same_colour(prim_material(s, 8).reflectance, 0.1f, 0.2f, 0.3f));
    TEST_ASSERT_TRUE(same_colour(prim_material(s, 9).reflectance, 0.5f, 0.5f, 0.5f));
    TEST_ASSERT_TRUE(same_colour(prim_material(s, 10).reflectance, 0.9f, 0.8f, 0.7f));
#ifndef FOGRT_NO_MICROFACET
    TEST_ASSERT_EQUAL_UINT32(1, rep.warnings);   /* one material without effect */
#else
    TEST_ASSERT_EQUAL_UINT32(3, rep.warnings);   /* two microfacets, one material without effect */
#endif
    fogrt_scene_destroy(s);
}

/* Smooth normals from connectivity: outward area-weighted at a closed part, negated on an
   open part, file normals ignored. */
static void test_dae_normals(void)
{
    fogrt_load_report rep;
    fogrt_scene *s = load_ok("dae_normals.dae", &rep, NULL);
    float k = 1.0f / sqrtf(3.0f);
    TEST_ASSERT_EQUAL_UINT32(6, s->tri_count);
    TEST_ASSERT_TRUE(s->tri_has_n[0]);
    assert_vec3(1e-6f, -k, -k, -k, tri_n(s, 0, 0), "tetrahedron vertex 0");
    /* vertex 3 = (0,0,1): faces -y, -x and (1,1,1): sum (-1,-1,0) + (1,1,1) = (0,0,1) */
    assert_vec3(1e-6f, 0, 0, 1, tri_n(s, 1, 2), "tetrahedron vertex 3");
    assert_vec3(0, 0, 0, -1, tri_n(s, 4, 0), "open quad: negated");
    assert_vec3(0, 0, 0, -1, tri_n(s, 5, 2), "open quad: negated");
    TEST_ASSERT_TRUE_MESSAGE((winding_normal(s, 4).z) > (0.0f), "winding_normal(s, 4).z > 0.0f");   /* winding untouched */
    fogrt_scene_destroy(s);
}

/* A CGL <area> light without an emissive mesh becomes an emissive rectangle from the node's
   X/Y scale, centred on the node, emitting along local -Z (down); CGL wins over <point>. */
static void test_dae_area_light_rectangle(void)
{
    fogrt_load_report rep;
    fogrt_scene *s = load_ok("dae_area_light.dae", &rep, NULL);
    fogrt_material_desc m;
    float lo[3] = { 9, 9, 9 }, hi[3] = { -9, -9, -9 };
    uint32_t t;
    int k;
    TEST_ASSERT_EQUAL_UINT32(1, rep.area_rectangles);
    TEST_ASSERT_EQUAL_UINT32(0, rep.point_lights);
    TEST_ASSERT_EQUAL_UINT32(4, s->tri_count);      /* floor quad + rectangle */
    for (t = 2; t < 4; ++t) {
        fogrt_vec3 n = winding_normal(s, t);
        m = prim_material(s, t);
        TEST_ASSERT_TRUE(same_colour(m.emission, 7, 8, 9));
        TEST_ASSERT_TRUE_MESSAGE((n.y) < (0.0f), "n.y < 0.0f");
        TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.0f, n.x);
        for (k = 0; k < 3; ++k) {
            fogrt_vec3 v = tri_v(s, t, k);
            lo[0] = fminf(lo[0], v.x); lo[1] = fminf(lo[1], v.y); lo[2] = fminf(lo[2], v.z);
            hi[0] = fmaxf(hi[0], v.x); hi[1] = fmaxf(hi[1], v.y); hi[2] = fmaxf(hi[2], v.z);
        }
    }
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, -0.25f, lo[0]); TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.25f, hi[0]);
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 2.0f, lo[1]);   TEST_ASSERT_FLOAT_WITHIN(1e-6f, 2.0f, hi[1]);
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, -0.125f, lo[2]); TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.125f, hi[2]);
    /* the camera's bounding box ignores lights: it frames the floor quad only */
    assert_vec3(1e-5f, 0, 0, 0, s->camera.look_at, "camera target");
    fogrt_scene_destroy(s);
}

/* With an emissive mesh the <area> element is the same lamp: nothing added twice. */
static void test_dae_area_light_merged(void)
{
    fogrt_load_report rep;
    fogrt_scene *s = load_ok("dae_area_with_emitter.dae", &rep, NULL);
    uint32_t t;
    TEST_ASSERT_EQUAL_UINT32(0, rep.area_rectangles);
    TEST_ASSERT_EQUAL_UINT32(1, rep.area_lights_merged);
    TEST_ASSERT_EQUAL_UINT32(2, rep.emissive_triangles);
    TEST_ASSERT_EQUAL_UINT32(4, s->tri_count);
    for (t = 0; t < s->tri_count; ++t)
        if (!same_colour(prim_material(s, t).emission, 0, 0, 0))
            TEST_ASSERT_TRUE_MESSAGE((winding_normal(s, t).y) < (0.0f), "winding_normal(s, t).y < 0.0f");   /* faces down */
    fogrt_scene_destroy(s);
}

/* point: intensity = colour at the node origin; spot: cutoff = falloff_angle / 2, beam =
   cutoff (1 - blend), axis = local -Z; COLLADA defaults; directional and unknown types
   skipped with warnings. The loaded spot follows I = clamp((cutoff - theta)/(cutoff - beam)). */
static void test_dae_point_and_spot(void)
{
    fogrt_load_report rep;
    fogrt_scene *s = load_ok("dae_point_spot.dae", &rep, NULL);
    fogrt_light_desc l;
    float mid;
    TEST_ASSERT_EQUAL_UINT32(1, rep.point_lights);
    TEST_ASSERT_EQUAL_UINT32(2, rep.spot_lights);
    TEST_ASSERT_EQUAL_UINT32(2, rep.warnings);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_get_light(s, 0, &l));
    TEST_ASSERT_EQUAL_INT(FOGRT_LIGHT_POINT, l.type);
    assert_vec3(0, 1, 2, 3, l.position, "point position");
    TEST_ASSERT_TRUE(same_colour(l.intensity, 1, 2, 3));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_get_light(s, 1, &l));
    TEST_ASSERT_EQUAL_INT(FOGRT_LIGHT_SPOT, l.type);
    assert_vec3(1e-6f, 0, 4, 0, l.position, "spot position");
    assert_vec3(1e-6f, 0, -1, 0, l.direction, "spot axis");
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 30.0f, l.cutoff_deg);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 22.5f, l.beam_deg);
    mid = 0.5f * (l.cutoff_deg + l.beam_deg) * 3.14159265f / 180.0f;
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 0.5f, fogrt_spot_falloff(l.cutoff_deg, l.beam_deg, cosf(mid)));
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 1.0f, fogrt_spot_falloff(l.cutoff_deg, l.beam_deg, cosf(0.3f)));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_get_light(s, 2, &l));
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 90.0f, l.cutoff_deg);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 90.0f, l.beam_deg);
    assert_vec3(1e-6f, 0, 0, -1, l.direction, "default spot axis");
    fogrt_scene_destroy(s);
}

/* <ambient>: constant radiance from the upper hemisphere only. */
static void test_dae_ambient(void)
{
    fogrt_load_report rep;
    fogrt_scene *s = load_ok("dae_ambient.dae", &rep, NULL);
    TEST_ASSERT_TRUE(rep.ambient);
    TEST_ASSERT_TRUE(s->has_env && s->env_upper_only);
    TEST_ASSERT_TRUE(same_colour(s->env, 0.5f, 0.6f, 0.7f));
    fogrt_scene_destroy(s);
}

/* BOM, CRLF, DOCTYPE, quotes, entities, CDATA, padded text, comments: all read. */
static void test_dae_xml_quirks(void)
{
    fogrt_load_report rep;
    fogrt_scene *s = load_ok("dae_xml_quirks.dae", &rep, NULL);
    TEST_ASSERT_EQUAL_UINT32(1, s->tri_count);
    TEST_ASSERT_EQUAL_UINT32(0, s->light_count);
    assert_vec3(0, 0, 1, 0, tri_v(s, 0, 2), "CDATA positions");
    TEST_ASSERT_EQUAL_UINT32(0, rep.warnings);
    fogrt_scene_destroy(s);
}

/* A mirroring node keeps the emitting side: the triangle is re-wound. */
static void test_dae_mirror_node(void)
{
    fogrt_load_report rep;
    fogrt_scene *s = load_ok("dae_mirror_node.dae", &rep, NULL);
    /* (0,0,0) (1,0,0) (0,1,0) mirrored to (0,0,0) (-1,0,0) (0,1,0), then re-wound */
    assert_vec3(0, 0, 1, 0, tri_v(s, 0, 1), "re-wound vertex 1");
    assert_vec3(0, -1, 0, 0, tri_v(s, 0, 2), "re-wound vertex 2");
    TEST_ASSERT_TRUE_MESSAGE((winding_normal(s, 0).z) > (0.0f), "winding_normal(s, 0).z > 0.0f");
    fogrt_scene_destroy(s);
}

/* ------------------------------------------------------------------------------------------
   3. OBJ, PLY and camera files
   ------------------------------------------------------------------------------------------ */
/* OBJ: quads and pentagons fan-triangulated, negative indices, v/t, ignored statements,
   CRLF; fails on a wrong fan or index base. */
static void test_obj_polygons(void)
{
    fogrt_load_report rep;
    fogrt_load_options opt = as_is();
    fogrt_scene *s = load_ok("obj_polygons.obj", &rep, &opt);
    TEST_ASSERT_EQUAL_UINT32(6, s->tri_count);
    TEST_ASSERT_EQUAL_UINT32(9, rep.vertices);
    TEST_ASSERT_EQUAL_UINT32(3, rep.faces);
    assert_vec3(0, 2, 0, 0, tri_v(s, 4, 0), "pentagon fan");
    assert_vec3(0, 2.5f, 2, 0, tri_v(s, 4, 1), "pentagon fan");
    assert_vec3(0, 2, 1, 0, tri_v(s, 4, 2), "pentagon fan");
    assert_vec3(0, 0, 0, 0, tri_v(s, 5, 0), "-9 is vertex 1");
    assert_vec3(0, 1, 0, 0, tri_v(s, 5, 1), "-8 is vertex 2");
    assert_vec3(0, 0, 1, 0, tri_v(s, 5, 2), "-6 is vertex 4");
    /* no normals in the file, and every face in the plane z = 0 facing +z: the computed
       smooth normals would be the face normals, so none are stored */
    TEST_ASSERT_FALSE(s->tri_has_n[0]);
    TEST_ASSERT_NULL(s->tri_n);
    fogrt_scene_destroy(s);
}

/* Counts the meshes a load with options.on_shape adds. */
static void count_meshes(void *user, fogrt_shape_kind kind, uint32_t index, const char *node, const char *material,
                         const char *geometry)
{
    (void)index; (void)node; (void)material; (void)geometry;
    if (kind == FOGRT_SHAPE_MESH) ++*(int *)user;
}
/* Loads the OBJ text obj (default placement unless as_is; with split, a mesh per group,
   counted in *meshes) into a fresh scene. */
static fogrt_scene *load_obj_text(const char *obj, bool place_as_is, bool split, int *meshes)
{
    fogrt_load_options opt = as_is();
    fogrt_load_report rep;
    fogrt_scene *s = new_scene();
    *meshes = 0;
    if (split) { opt.on_shape = count_meshes; opt.on_shape_user = meshes; }
    if (!place_as_is) opt.place = FOGRT_LOAD_PLACE_DEFAULT;
    TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_RESULT_OK, fogrt_load_obj_memory(s, obj, strlen(obj), "flat.obj", &opt, &rep), rep.message);
    return s;
}
/* A flat mesh (every face with an area facing one way in one plane) gets no computed
   normals, placed or not, in an axis plane or in a tilted one (z = x, exact in float), whole
   or split into a mesh per group (options.on_shape); a mesh lifted 1e-3 out of its plane, or
   with one face turned over, gets them (its groups too, each corner its vertex's normal). */
static void test_flat_mesh_without_normals(void)
{
    static const char *flat = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 0\ng a\nf 1 2 5\nf 2 3 5\ng b\nf 3 4 5\nf 4 1 5\nf 1 1 2\n";
    static const char *tilted = "v 0 0 0\nv 1 0 1\nv 1 1 1\nv 0 1 0\nf 1 2 3\nf 1 3 4\n";
    static const char *lifted = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 0.001\ng a\nf 1 2 5\nf 2 3 5\ng b\nf 3 4 5\nf 4 1 5\n";
    static const char *turned = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 0\nf 1 2 5\nf 2 3 5\nf 3 4 5\nf 1 4 5\n";
    static const struct { const char **obj; bool as_is, split, normals; int meshes; } cases[] = {
        { &flat, true, false, false, 0 }, { &flat, false, false, false, 0 }, { &flat, true, true, false, 2 },
        { &tilted, true, false, false, 0 }, { &lifted, true, false, true, 0 }, { &lifted, false, false, true, 0 },
        { &lifted, true, true, true, 2 }, { &turned, true, false, true, 0 } };
    size_t i;
    for (i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        int meshes;
        fogrt_scene *s = load_obj_text(*cases[i].obj, cases[i].as_is, cases[i].split, &meshes);
        char msg[64];
        snprintf(msg, sizeof msg, "case %u", (unsigned)i);
        TEST_ASSERT_EQUAL_INT_MESSAGE(cases[i].meshes, meshes, msg);
        TEST_ASSERT_EQUAL_INT_MESSAGE(cases[i].normals, s->tri_n != NULL, msg);
        TEST_ASSERT_EQUAL_INT_MESSAGE(cases[i].normals, s->tri_has_n[0], msg);
        TEST_ASSERT_EQUAL_INT_MESSAGE(cases[i].normals, s->tri_has_n[s->tri_count - 1], msg);
        if (cases[i].normals && cases[i].split)      /* the centre's normal, tilted toward none of the sides' */
            assert_vec3(1e-6f, 0, 0, 1, tri_n(s, s->tri_count - 1, 2), "the last group's centre vertex");
        fogrt_scene_destroy(s);
    }
}

/* OBJ normals (v//n, v/t/n) are used, normalised, one vertex per (position, normal) pair. */
static void test_obj_normals(void)
{
    fogrt_load_report rep;
    fogrt_load_options opt = as_is();
    fogrt_scene *s = load_ok("obj_normals.obj", &rep, &opt);
    TEST_ASSERT_EQUAL_UINT32(2, s->tri_count);
    assert_vec3(0, 0, 0, 1, tri_n(s, 0, 0), "vn 0 0 2 normalised");
    assert_vec3(0, 0, -1, 0, tri_n(s, 1, 0), "vn 0 -3 0 normalised");
    assert_vec3(0, 0, 0, 1, tri_v(s, 1, 1), "second face, vertex 4");
    fogrt_scene_destroy(s);
}

/* PLY ascii: extra vertex properties skipped, file normals, list faces fan-triangulated, an
   extra element parsed past. */
static void test_ply_ascii(void)
{
    fogrt_load_report rep;
    fogrt_load_options opt = as_is();
    fogrt_scene *s = load_ok("ply_ascii.ply", &rep, &opt);
    TEST_ASSERT_EQUAL_UINT32(3, s->tri_count);
    TEST_ASSERT_EQUAL_UINT32(5, rep.vertices);
    TEST_ASSERT_EQUAL_UINT32(2, rep.faces);
    assert_vec3(0, 2, 0, 0, tri_v(s, 0, 1), "x, y, z around the confidence property");
    assert_vec3(0, 1, 2, 0, tri_v(s, 2, 2), "triangle face");
    assert_vec3(0, 0, 0, 1, tri_n(s, 2, 2), "nz 2 normalised");
    fogrt_scene_destroy(s);
}

/* Writes a binary PLY (little or big endian) with a double and a uchar property besides
   x y z, a uchar/int list quad and a short list property on a second element. */
static size_t make_binary_ply(unsigned char *buf, bool little)
{
    static const float xyz[4][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 2, 0 }, { 0, 2, 0 } };
    const char *hdr_le = "ply\nformat binary_little_endian 1.0\n", *hdr_be = "ply\nformat binary_big_endian 1.0\n";
    const char *rest = "element vertex 4\nproperty float x\nproperty double extra\nproperty float y\nproperty float z\n"
                       "property uchar tag\nelement face 1\nproperty list uchar int vertex_indices\n"
                       "element misc 1\nproperty list uchar short values\nend_header\n";
    size_t n = 0;
    int v, k;
#define PUT(ptr, size) do { int b_; for (b_ = 0; b_ < (size); ++b_) buf[n++] = ((const unsigned char *)(ptr))[little ? b_ : (size) - 1 - b_]; } while (0)
    memcpy(buf, little ? hdr_le : hdr_be, strlen(little ? hdr_le : hdr_be)); n = strlen(little ? hdr_le : hdr_be);
    memcpy(buf + n, rest, strlen(rest)); n += strlen(rest);
    for (v = 0; v < 4; ++v) {
        double extra = 123.5;
        unsigned char tag = 7;
        PUT(&xyz[v][0], 4); PUT(&extra, 8); PUT(&xyz[v][1], 4); PUT(&xyz[v][2], 4); PUT(&tag, 1);
    }
    {
        unsigned char cnt = 4;
        int32_t idx;
        int16_t sh = -3;
        PUT(&cnt, 1);
        for (k = 0; k < 4; ++k) { idx = k; PUT(&idx, 4); }
        cnt = 2; PUT(&cnt, 1); PUT(&sh, 2); PUT(&sh, 2);
    }
#undef PUT
    return n;
}

/* PLY binary in both byte orders from memory (the host is little endian in practice; the
   test builds both layouts byte by byte), and truncated binary data as an error. */
static void test_ply_binary(void)
{
    unsigned char buf[1024];
    int little;
    for (little = 0; little < 2; ++little) {
        size_t n = make_binary_ply(buf, little != 0);
        fogrt_scene *s = new_scene();
        fogrt_load_report rep;
        fogrt_load_options opt = as_is();
        TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_RESULT_OK, fogrt_load_ply_memory(s, buf, n, "bin.ply", &opt, &rep), rep.message);
        TEST_ASSERT_EQUAL_UINT32(2, s->tri_count);
        assert_vec3(0, 1, 2, 0, tri_v(s, 0, 2), "binary vertex 2");
        assert_vec3(0, 0, 2, 0, tri_v(s, 1, 2), "binary vertex 3");
        fogrt_scene_destroy(s);
        s = new_scene();
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_PARSE_ERROR, fogrt_load_ply_memory(s, buf, n - 3, "bin.ply", &opt, &rep));
        TEST_ASSERT_NOT_NULL(strstr(rep.message, "truncated"));
        TEST_ASSERT_EQUAL_UINT32(0, s->tri_count);
        fogrt_scene_destroy(s);
    }
}

/* OBJ/PLY placement: scaled uniformly into the fit box, standing on its floor, centred in x
   and z; the default box is the free corner of the default Cornell box. */
static void test_mesh_placement(void)
{
    fogrt_load_report rep;
    fogrt_scene *s = new_scene();
    fogrt_scene_info info;
    float sx, sz;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_default(s));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_load_obj(s, DATA_DIR "obj_polygons.obj", NULL, &rep));
    fogrt_scene_destroy(s);
    s = new_scene();
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_load_obj(s, DATA_DIR "obj_normals.obj", NULL, &rep));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(s, NULL));
    fogrt_scene_get_info(s, &info);
    /* a unit tetrahedron-like mesh: limited by the 0.6 x 0.7 x 0.6 box, so scaled by 0.6 */
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, FOGRT_LOAD_FIT_MIN_Y, info.bounds_min.y);
    sx = info.bounds_max.x - info.bounds_min.x; sz = info.bounds_max.z - info.bounds_min.z;
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 0.6f, sx);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 0.6f, sz);
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 0.5f * (FOGRT_LOAD_FIT_MIN_X + FOGRT_LOAD_FIT_MAX_X), 0.5f * (info.bounds_min.x + info.bounds_max.x));
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 0.5f * (FOGRT_LOAD_FIT_MIN_Z + FOGRT_LOAD_FIT_MAX_Z), 0.5f * (info.bounds_min.z + info.bounds_max.z));
    fogrt_scene_destroy(s);
}

/* The Stanford bunny (res2) loads with its header counts and fits the box. */
static void test_stanford_bunny_ply(void)
{
    const char *path = FOGRT_SHARED_DIR "/scenes/stanford/bun_zipper_res2.ply";
    fogrt_scene *s;
    fogrt_load_report rep;
    fogrt_scene_info info;
    if (!file_exists(path)) { TEST_IGNORE_MESSAGE("bun_zipper_res2.ply absent (../shared): skipped"); return; }
    s = new_scene();
    TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_RESULT_OK, fogrt_load_ply(s, path, NULL, &rep), rep.message);
    TEST_ASSERT_EQUAL_UINT32(8171, rep.vertices);
    TEST_ASSERT_EQUAL_UINT32(16301, rep.faces);
    TEST_ASSERT_EQUAL_UINT32(16301, rep.triangles);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(s, NULL));
    fogrt_scene_get_info(s, &info);
    TEST_ASSERT_TRUE_MESSAGE((info.bounds_min.x) >= (FOGRT_LOAD_FIT_MIN_X - 1e-5f), "info.bounds_min.x >= FOGRT_LOAD_FIT_MIN_X - 1e-5f");
    TEST_ASSERT_TRUE_MESSAGE((info.bounds_max.x) <= (FOGRT_LOAD_FIT_MAX_X + 1e-5f), "info.bounds_max.x <= FOGRT_LOAD_FIT_MAX_X + 1e-5f");
    TEST_ASSERT_TRUE_MESSAGE((info.bounds_max.y) <= (FOGRT_LOAD_FIT_MAX_Y + 1e-5f), "info.bounds_max.y <= FOGRT_LOAD_FIT_MAX_Y + 1e-5f");
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 0.0f, info.bounds_min.y);
    fogrt_scene_destroy(s);
}

/* CS184 camera settings (-c): position, target, up from c2w's 2nd column, lens, and the
   framing from screenH / (2 screenDist); too few numbers is an error with a line. */
static void test_camera_file(void)
{
    fogrt_camera_desc cam;
    fogrt_load_report rep;
    const char *bad = "49 37 1.3 0.1 100\n0 0 1 0 0 0\n";
    TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_RESULT_OK, fogrt_load_camera_file(DATA_DIR "cam_settings.txt", 480, 360, &cam, &rep), rep.message);
    assert_vec3(0, 0.5f, 1, 4, cam.position, "position");
    assert_vec3(0, 0.5f, 0.75f, 0, cam.look_at, "target");
    assert_vec3(0, 0, 0.99f, -0.1f, cam.up, "up");
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 3.5f, cam.focal_distance);
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.05f, cam.lens_radius);
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 37.8493f, cam.fov_deg);
    TEST_ASSERT_FALSE(cam.fov_is_horizontal);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_PARSE_ERROR, fogrt_load_camera_memory(bad, strlen(bad), "bad.cam", 480, 360, &cam, &rep));
    TEST_ASSERT_EQUAL_INT(2, rep.line);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_IO_ERROR, fogrt_load_camera_file(DATA_DIR "no_such_camera.txt", 480, 360, &cam, &rep));
}

/* A message quoting bytes of a binary file holds no raw bytes: control bytes and broken
   UTF-8 become '?', well-formed UTF-8 (a material named in another script) is kept. */
static void test_messages_are_printable(void)
{
    fogrt_camera_desc cam;
    fogrt_load_report rep;
    fogrt_scene *s = NULL;
    fogrt_load_options opt;
    static const char cam_bytes[] = "\001\033[31m\377\300\xe2\x82 1 2\n";
    static const char obj_bytes[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 \033\377\n";
    static const char obj_utf8[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 \xc3\xa9\n";
    const unsigned char *p;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_PARSE_ERROR, fogrt_load_camera_memory(cam_bytes, sizeof cam_bytes - 1, "bytes.cam", 480, 360, &cam, &rep));
    for (p = (const unsigned char *)rep.message; *p; ++p)
        TEST_ASSERT_TRUE_MESSAGE(*p >= 0x20 && *p < 0x7F, rep.message);
    TEST_ASSERT_NOT_NULL(strchr(rep.message, '?'));
    memset(&opt, 0, sizeof opt);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_create(NULL, &s));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_PARSE_ERROR, fogrt_load_obj_memory(s, obj_bytes, sizeof obj_bytes - 1, "bytes.obj", &opt, &rep));
    for (p = (const unsigned char *)rep.message; *p; ++p)
        TEST_ASSERT_TRUE_MESSAGE(*p >= 0x20 && *p < 0x7F, rep.message);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_PARSE_ERROR, fogrt_load_obj_memory(s, obj_utf8, sizeof obj_utf8 - 1, "utf8.obj", &opt, &rep));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(rep.message, "\xc3\xa9"), rep.message);
    fogrt_scene_destroy(s);
}

/* ------------------------------------------------------------------------------------------
   4. Malformed and truncated input
   ------------------------------------------------------------------------------------------ */
typedef struct bad_case { const char *file; int line; const char *words; } bad_case;
static const bad_case bad_cases[] = {
    { "bad_unclosed.dae", 28, "not closed" },
    { "bad_mismatch.dae", 15, "does not match" },
    { "bad_number.dae", 11, "'x3'" },
    { "bad_index.dae", 18, "out of range" },
    { "bad_count.dae", 11, "count" },
    { "bad_upaxis.dae", 5, "up_axis" },
    { "bad_noscene.dae", 3, "instance_visual_scene" },
    { "bad_attr.dae", 17, "not quoted" },
    { "bad_root.dae", 3, "not a COLLADA" },
    { "bad_text.dae", 31, "outside the root" },
    { "bad_triangles_short.dae", 18, "too short" },
    { "bad_glass.dae", 9, "<ior>" },
    { "bad_vcount.dae", 12, "vcount" },
    { "obj_bad_index.obj", 6, "out of range" },
    { "obj_bad_number.obj", 4, "finite" },
    { "obj_bad_face.obj", 5, "fewer than 3" },
    { "ply_bad_index.ply", 14, "out of range" },
    { "ply_bad_header.ply", 6, "quaternion" },
    { "ply_truncated.ply", 11, "end of file" },
    { "ply_huge_count.ply", 11, "file too short" },      /* 4e9 vertices: refused before any allocation */
    { "bad_far_vertex.dae", 11, "beyond fogrt's limit of 1e30" },
    { "bad_far_node.dae", 25, "beyond fogrt's limit of 1e30" },
    { "obj_random.obj", 1, "not an OBJ mesh" },
};

/* Each malformed file gives PARSE_ERROR at the right line with a telling message, and adds
   nothing to the scene (the default scene stays as it was). */
static void test_malformed_files(void)
{
    size_t i;
    for (i = 0; i < sizeof bad_cases / sizeof bad_cases[0]; ++i) {
        char path[512], msg[800];
        fogrt_scene *s = new_scene();
        fogrt_load_report rep;
        fogrt_scene_info before, after;
        fogrt_result r;
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_default(s));
        fogrt_scene_get_info(s, &before);
        snprintf(path, sizeof path, DATA_DIR "%s", bad_cases[i].file);
        r = fogrt_load_file(s, path, NULL, &rep);
        snprintf(msg, sizeof msg, "%s: got %s:%d: %s", bad_cases[i].file, rep.file, rep.line, rep.message);
        TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_RESULT_PARSE_ERROR, r, msg);
        TEST_ASSERT_EQUAL_INT_MESSAGE(bad_cases[i].line, rep.line, msg);
        TEST_ASSERT_NOT_NULL_MESSAGE(strstr(rep.message, bad_cases[i].words), msg);
        TEST_ASSERT_EQUAL_STRING(path, rep.file);
        fogrt_scene_get_info(s, &after);
        TEST_ASSERT_EQUAL_UINT32_MESSAGE(before.triangle_count, after.triangle_count, msg);
        TEST_ASSERT_EQUAL_UINT32_MESSAGE(before.material_count, after.material_count, msg);
        TEST_ASSERT_EQUAL_UINT32_MESSAGE(before.light_count, after.light_count, msg);
        TEST_ASSERT_EQUAL_UINT32_MESSAGE(before.sphere_count, after.sphere_count, msg);
        TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_RESULT_OK, build_without_pilot(s), msg);
        fogrt_scene_destroy(s);
    }
    {   /* a missing file is an I/O error naming it */
        fogrt_scene *s = new_scene();
        fogrt_load_report rep;
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_IO_ERROR, fogrt_load_file(s, DATA_DIR "no_such_scene.dae", NULL, &rep));
        TEST_ASSERT_EQUAL_STRING(DATA_DIR "no_such_scene.dae", rep.file);
        TEST_ASSERT_NOT_NULL(strstr(rep.message, "cannot open"));
        fogrt_scene_destroy(s);
    }
}

typedef fogrt_result (*load_fn)(fogrt_scene *, const void *, size_t, const char *, const fogrt_load_options *, fogrt_load_report *);
static load_fn loader_for(const char *name)
{
    size_t n = strlen(name);
    if (n > 4 && strcmp(name + n - 4, ".dae") == 0) return fogrt_load_dae_memory;
    if (n > 4 && strcmp(name + n - 4, ".obj") == 0) return fogrt_load_obj_memory;
    if (n > 4 && strcmp(name + n - 4, ".ply") == 0) return fogrt_load_ply_memory;
    if (strncmp(name, "dae", 3) == 0) return fogrt_load_dae_memory;
    if (strncmp(name, "obj", 3) == 0) return fogrt_load_obj_memory;
    if (strncmp(name, "ply", 3) == 0) return fogrt_load_ply_memory;
    return NULL;
}

/* Loads every prefix of data: the result is OK or PARSE_ERROR with a message and a line
   inside the prefix, the scene is untouched on error, and for .dae every prefix that cuts
   the document's end tag fails. Returns the number of loads. */
static int truncation_sweep(const char *name, const char *data, size_t size, size_t step)
{
    load_fn fn = loader_for(name);
    size_t len, last_gt = size;
    int loads = 0;
    bool is_dae = fn == fogrt_load_dae_memory;
    while (last_gt > 0 && data[last_gt - 1] != '>') last_gt--;
    for (len = 0; len < size; len += step) {
        fogrt_scene *s = new_scene();
        fogrt_load_report rep;
        fogrt_result r = fn(s, data, len, name, NULL, &rep);
        char msg[800];
        int lines = 1;
        size_t i;
        for (i = 0; i < len; ++i) if (data[i] == '\n') lines++;
        snprintf(msg, sizeof msg, "%s cut at %u bytes: %s:%d: %s", name, (unsigned)len, rep.file, rep.line, rep.message);
        if (r == FOGRT_RESULT_PARSE_ERROR) {
            TEST_ASSERT_TRUE_MESSAGE(rep.message[0] != 0, msg);
            TEST_ASSERT_GREATER_OR_EQUAL_MESSAGE(1, rep.line, msg);
            TEST_ASSERT_LESS_OR_EQUAL_MESSAGE(lines, rep.line, msg);
            TEST_ASSERT_EQUAL_UINT32_MESSAGE(0, s->tri_count + s->sph_count + s->light_count + s->material_count, msg);
        } else {
            TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_RESULT_OK, r, msg);
            TEST_ASSERT_FALSE_MESSAGE(is_dae && len < last_gt, msg);
        }
        fogrt_scene_destroy(s);
        loads++;
    }
    return loads;
}

/* Every test file cut at every length (and the shared CBspheres.dae at many): never a crash
   (ASan/UBSan builds check memory too), always an error with a plausible line. */
static void test_truncated_files(void)
{
    static const char *names[] = {
        "dae_minimal_yup.dae", "dae_upaxis_zup.dae", "dae_transforms.dae", "dae_short_matrix.dae", "dae_camera_yfov.dae",
        "dae_global_ids.dae", "dae_polylist_ngon.dae", "dae_multi_lists.dae", "dae_sphere.dae", "dae_materials.dae",
        "dae_normals.dae", "dae_area_light.dae", "dae_area_with_emitter.dae", "dae_point_spot.dae", "dae_ambient.dae",
        "dae_xml_quirks.dae", "dae_mirror_node.dae", "bad_glass.dae", "bad_vcount.dae",
        "obj_polygons.obj", "obj_normals.obj", "obj_bad_index.obj", "ply_ascii.ply", "ply_bad_index.ply",
    };
    size_t i, size;
    int loads = 0;
    char msg[128];
    unsigned char bin[1024];
    for (i = 0; i < sizeof names / sizeof names[0]; ++i) {
        char path[512];
        char *data;
        snprintf(path, sizeof path, DATA_DIR "%s", names[i]);
        data = read_all(path, &size);
        TEST_ASSERT_NOT_NULL_MESSAGE(data, path);
        loads += truncation_sweep(names[i], data, size, 1);
        free(data);
    }
    size = make_binary_ply(bin, true);
    loads += truncation_sweep("bin_le.ply", (const char *)bin, size, 1);
    size = make_binary_ply(bin, false);
    loads += truncation_sweep("bin_be.ply", (const char *)bin, size, 1);
    if (file_exists(CS184_DIR "CBspheres.dae")) {
        char *data = read_all(CS184_DIR "CBspheres.dae", &size);
        TEST_ASSERT_NOT_NULL(data);
        loads += truncation_sweep("CBspheres.dae", data, size, 97);
        free(data);
    }
    snprintf(msg, sizeof msg, "%d truncated loads", loads);
    TEST_MESSAGE(msg);
}

/* The crashing inputs the fuzzers found (tests/fuzz/regress/, named dae_*, obj_*, ply_*)
   load or fail cleanly, and what loads also builds (two of them place a mesh with denormal
   or huge extents, which once made the BVH build's binning convert NaN to int). */
static void test_fuzz_regressions(void)
{
    DIR *dir = opendir("tests/fuzz/regress");
    struct dirent *e;
    int n = 0;
    char msg[128];
    TEST_ASSERT_NOT_NULL_MESSAGE(dir, "tests/fuzz/regress is missing");
    while ((e = readdir(dir)) != NULL) {
        char path[600];
        size_t size;
        char *data;
        load_fn fn = loader_for(e->d_name);
        fogrt_scene *s;
        fogrt_load_report rep;
        fogrt_result r;
        if (e->d_name[0] == '.' || !fn) continue;
        snprintf(path, sizeof path, "tests/fuzz/regress/%s", e->d_name);
        data = read_all(path, &size);
        TEST_ASSERT_NOT_NULL(data);
        s = new_scene();
        r = fn(s, data, size, e->d_name, NULL, &rep);
        TEST_ASSERT_TRUE_MESSAGE(r == FOGRT_RESULT_OK || r == FOGRT_RESULT_PARSE_ERROR || r == FOGRT_RESULT_TOO_LARGE ||
                                 r == FOGRT_RESULT_INVALID_GEOMETRY, e->d_name);
        if (r != FOGRT_RESULT_OK) TEST_ASSERT_TRUE_MESSAGE(rep.message[0] != 0, e->d_name);
        else {
            fogrt_result b = fogrt_scene_build(s, NULL);
            TEST_ASSERT_TRUE_MESSAGE(b == FOGRT_RESULT_OK || b == FOGRT_RESULT_EMPTY_SCENE, e->d_name);
        }
        fogrt_scene_destroy(s);
        free(data);
        n++;
    }
    closedir(dir);
    snprintf(msg, sizeof msg, "%d fuzz regression inputs replayed", n);
    TEST_MESSAGE(msg);
}

/* ------------------------------------------------------------------------------------------
   5. Memory, files and refusals
   ------------------------------------------------------------------------------------------ */
/* A counting allocator: live blocks and bytes, the peak, and an optional failure at the
   fail_at-th call (1-based; 0: never). */
typedef struct count_alloc { size_t cur, peak, calls, live, fail_at; } count_alloc;
static void *ca_alloc(size_t n, void *user)
{
    count_alloc *c = (count_alloc *)user;
    size_t *p;
    c->calls++;
    if (c->fail_at && c->calls == c->fail_at) return NULL;
    p = (size_t *)malloc(n + 2 * sizeof(size_t));
    if (!p) return NULL;
    p[0] = n;
    c->cur += n; c->live++;
    if (c->cur > c->peak) c->peak = c->cur;
    return p + 2;
}
static void ca_free(void *q, void *user)
{
    count_alloc *c = (count_alloc *)user;
    size_t *p;
    if (!q) return;
    p = (size_t *)q - 2;
    c->cur -= p[0]; c->live--;
    free(p);
}
static void ignore_log(fogrt_log_level level, const char *message, void *user) { (void)level; (void)message; (void)user; }
/* Options with the counting allocator (and a logger, so that warnings are kept too). */
static fogrt_load_options counted(count_alloc *c, fogrt_load_place place)
{
    fogrt_load_options o;
    memset(&o, 0, sizeof o);
    memset(c, 0, sizeof *c);
    o.allocator.alloc_fn = ca_alloc; o.allocator.free_fn = ca_free; o.allocator.user_data = c;
    o.logger.func = ignore_log;
    o.place = place;
    return o;
}

/* Everything a scene shows through its getters, to compare before and after a load. */
typedef struct scene_snap {
    fogrt_scene_info info;
    fogrt_material_desc mats[32];
    fogrt_light_desc lights[8];
    fogrt_camera_desc cam;
    fogrt_medium_desc med;
} scene_snap;
static void snap_scene(const fogrt_scene *s, scene_snap *o)
{
    uint32_t i;
    memset(o, 0, sizeof *o);
    fogrt_scene_get_info(s, &o->info);
    for (i = 0; i < o->info.material_count && i < 32; ++i) TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_get_material(s, i, &o->mats[i]));
    for (i = 0; i < o->info.light_count && i < 8; ++i) TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_get_light(s, i, &o->lights[i]));
    fogrt_scene_get_camera(s, &o->cam);
    fogrt_scene_get_medium(s, &o->med);
}
static void same_vec(fogrt_vec3 a, fogrt_vec3 b, const char *msg)
{
    TEST_ASSERT_EQUAL_FLOAT_MESSAGE(a.x, b.x, msg); TEST_ASSERT_EQUAL_FLOAT_MESSAGE(a.y, b.y, msg); TEST_ASSERT_EQUAL_FLOAT_MESSAGE(a.z, b.z, msg);
}
/* Field by field: counts, every material, every light, the camera and the medium. */
static void assert_same_scene(const scene_snap *a, const scene_snap *b, const char *msg)
{
    uint32_t i;
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(a->info.triangle_count, b->info.triangle_count, msg);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(a->info.sphere_count, b->info.sphere_count, msg);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(a->info.material_count, b->info.material_count, msg);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(a->info.light_count, b->info.light_count, msg);
    TEST_ASSERT_EQUAL_INT_MESSAGE(a->info.has_environment, b->info.has_environment, msg);
    for (i = 0; i < a->info.material_count && i < 32; ++i) {
        TEST_ASSERT_EQUAL_INT_MESSAGE(a->mats[i].type, b->mats[i].type, msg);
        same_vec(a->mats[i].reflectance, b->mats[i].reflectance, msg);
        same_vec(a->mats[i].transmittance, b->mats[i].transmittance, msg);
        same_vec(a->mats[i].emission, b->mats[i].emission, msg);
        TEST_ASSERT_EQUAL_FLOAT_MESSAGE(a->mats[i].ior, b->mats[i].ior, msg);
    }
    for (i = 0; i < a->info.light_count && i < 8; ++i) {
        TEST_ASSERT_EQUAL_INT_MESSAGE(a->lights[i].type, b->lights[i].type, msg);
        same_vec(a->lights[i].position, b->lights[i].position, msg);
        same_vec(a->lights[i].direction, b->lights[i].direction, msg);
        same_vec(a->lights[i].intensity, b->lights[i].intensity, msg);
        TEST_ASSERT_EQUAL_FLOAT_MESSAGE(a->lights[i].cutoff_deg, b->lights[i].cutoff_deg, msg);
        TEST_ASSERT_EQUAL_FLOAT_MESSAGE(a->lights[i].beam_deg, b->lights[i].beam_deg, msg);
        TEST_ASSERT_EQUAL_FLOAT_MESSAGE(a->lights[i].radius, b->lights[i].radius, msg);
    }
    same_vec(a->cam.position, b->cam.position, msg); same_vec(a->cam.look_at, b->cam.look_at, msg); same_vec(a->cam.up, b->cam.up, msg);
    TEST_ASSERT_EQUAL_FLOAT_MESSAGE(a->cam.fov_deg, b->cam.fov_deg, msg);
    TEST_ASSERT_EQUAL_INT_MESSAGE(a->cam.fov_is_horizontal, b->cam.fov_is_horizontal, msg);
    TEST_ASSERT_EQUAL_FLOAT_MESSAGE(a->cam.lens_radius, b->cam.lens_radius, msg);
    TEST_ASSERT_EQUAL_FLOAT_MESSAGE(a->cam.focal_distance, b->cam.focal_distance, msg);
    TEST_ASSERT_EQUAL_FLOAT_MESSAGE(a->med.sigma_t, b->med.sigma_t, msg);
    same_vec(a->med.albedo, b->med.albedo, msg);
    TEST_ASSERT_EQUAL_FLOAT_MESSAGE(a->med.g, b->med.g, msg);
}
/* A scene that already holds content: the default Cornell box (materials, triangles,
   spheres, a spot light, fog, a camera) and an environment. */
static fogrt_scene *content_scene(void)
{
    fogrt_scene *s = new_scene();
    fogrt_vec3 env = { 0.05f, 0.1f, 0.2f };
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_default(s));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_set_environment(s, env, true));
    return s;
}
static char *data_file(const char *name, size_t *size)
{
    char path[512];
    char *d;
    snprintf(path, sizeof path, DATA_DIR "%s", name);
    d = read_all(path, size);
    TEST_ASSERT_NOT_NULL_MESSAGE(d, path);
    return d;
}

/* A file of tests/data that a loader reads: .dae, .obj or .ply. */
static int is_scene_file(const char *name)
{
    size_t n = strlen(name);
    return n >= 5 && (strcmp(name + n - 4, ".dae") == 0 || strcmp(name + n - 4, ".obj") == 0 || strcmp(name + n - 4, ".ply") == 0);
}
/* Every file of tests/data that fails to load (with the default placement, or as is) leaves
   a scene that already holds content exactly as it was, and says why in one message that
   names the file. */
static void test_failed_load_changes_nothing(void)
{
    DIR *dir = opendir("tests/data");
    struct dirent *e;
    int refused = 0, p;
    char msg[900];
    TEST_ASSERT_NOT_NULL(dir);
    while ((e = readdir(dir)) != NULL) {
        char path[600];
        if (!is_scene_file(e->d_name)) continue;
        snprintf(path, sizeof path, DATA_DIR "%s", e->d_name);
        for (p = 0; p < 2; ++p) {
            fogrt_load_options o = as_is();
            fogrt_scene *s = content_scene();
            fogrt_load_report rep;
            scene_snap before, after;
            fogrt_result r;
            snap_scene(s, &before);
            r = fogrt_load_file(s, path, p ? &o : NULL, &rep);
            snprintf(msg, sizeof msg, "%s (%s): %s:%d: %s", e->d_name, p ? "as is" : "placed", rep.file, rep.line, rep.message);
            if (r != FOGRT_RESULT_OK) {
                refused++;
                TEST_ASSERT_EQUAL_STRING_MESSAGE(path, rep.file, msg);
                TEST_ASSERT_TRUE_MESSAGE(rep.message[0] != 0 && strchr(rep.message, '\n') == NULL, msg);
                snap_scene(s, &after);
                assert_same_scene(&before, &after, msg);
                TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_RESULT_OK, build_without_pilot(s), msg);
            }
            fogrt_scene_destroy(s);
        }
    }
    closedir(dir);
    snprintf(msg, sizeof msg, "%d refused loads left the scene as it was", refused);
    TEST_MESSAGE(msg);
    TEST_ASSERT_GREATER_OR_EQUAL(2 * 19 + 4, refused);
}

/* All loader memory goes through options.allocator, all of it is freed, and an allocator
   that fails at the N-th call, for every N, gives OUT_OF_MEMORY and an unchanged scene. */
static void test_counting_allocator(void)
{
    static const char *names[] = { "dae_materials.dae", "dae_instances.dae", "dae_area_light.dae", "dae_sphere.dae",
                                   "dae_multi_lists.dae", "obj_normals.obj", "obj_polygons.obj", "ply_ascii.ply" };
    size_t i, n, runs = 0;
    char msg[700];
    for (i = 0; i < sizeof names / sizeof names[0]; ++i) {
        count_alloc c;
        fogrt_load_options o = counted(&c, FOGRT_LOAD_PLACE_DEFAULT);
        fogrt_load_report rep;
        fogrt_scene *s = content_scene();
        size_t size, total;
        char *data = data_file(names[i], &size);
        load_fn fn = loader_for(names[i]);
        TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_RESULT_OK, fn(s, data, size, names[i], &o, &rep), names[i]);
        TEST_ASSERT_EQUAL_UINT_MESSAGE(0, c.live, names[i]);
        TEST_ASSERT_TRUE_MESSAGE(c.calls > 0, names[i]);
        fogrt_scene_destroy(s);
        total = c.calls;
        for (n = 1; n <= total; ++n) {
            scene_snap before, after;
            fogrt_result r;
            s = content_scene();
            snap_scene(s, &before);
            o = counted(&c, FOGRT_LOAD_PLACE_DEFAULT);
            c.fail_at = n;
            r = fn(s, data, size, names[i], &o, &rep);
            snprintf(msg, sizeof msg, "%s failing at allocation %u of %u: %s:%d: %s", names[i], (unsigned)n, (unsigned)total, rep.file, rep.line, rep.message);
            TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_RESULT_OUT_OF_MEMORY, r, msg);
            TEST_ASSERT_EQUAL_STRING_MESSAGE("out of memory", rep.message, msg);
            TEST_ASSERT_EQUAL_UINT_MESSAGE(0, c.live, msg);
            snap_scene(s, &after);
            assert_same_scene(&before, &after, msg);
            fogrt_scene_destroy(s);
            runs++;
        }
        free(data);
    }
    {   /* half an allocator is a caller's mistake */
        count_alloc c;
        fogrt_load_options o = counted(&c, FOGRT_LOAD_PLACE_DEFAULT);
        fogrt_load_report rep;
        fogrt_scene *s = new_scene();
        o.allocator.free_fn = NULL;
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_INVALID_ARGUMENT, fogrt_load_file(s, DATA_DIR "obj_polygons.obj", &o, &rep));
        TEST_ASSERT_EQUAL_UINT(0, c.calls);
        fogrt_scene_destroy(s);
    }
    snprintf(msg, sizeof msg, "%u loads with a failing allocator", (unsigned)runs);
    TEST_MESSAGE(msg);
}

/* A scratch file name in $TMPDIR (or /tmp), unique to this process. */
static void tmp_path(char *out, size_t size, const char *name)
{
    const char *dir = getenv("TMPDIR");
    snprintf(out, size, "%s/fogrt_test_%ld_%s", dir && dir[0] ? dir : "/tmp", (long)getpid(), name);
}
/* A FIFO, a device or a directory is refused at once, without a single read (a FIFO would
   block forever in open or read: the alarm turns such a hang into a failure). */
static void test_non_regular_files(void)
{
    char fifo[512], msg[900];
    fogrt_load_report rep;
    fogrt_camera_desc cam;
    fogrt_scene *s = new_scene();
    scene_snap before, after;
    tmp_path(fifo, sizeof fifo, "fifo.ply");
    remove(fifo);
    TEST_ASSERT_EQUAL_INT(0, mkfifo(fifo, 0600));
    snap_scene(s, &before);
    alarm(10);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_IO_ERROR, fogrt_load_file(s, fifo, NULL, &rep));
    snprintf(msg, sizeof msg, "%s:%d: %s", rep.file, rep.line, rep.message);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(rep.message, "a FIFO, not a regular file"), msg);
    TEST_ASSERT_EQUAL_STRING(fifo, rep.file);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_IO_ERROR, fogrt_load_camera_file(fifo, 64, 48, &cam, &rep));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(rep.message, "FIFO"), rep.message);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_IO_ERROR, fogrt_load_ply(s, "/dev/zero", NULL, &rep));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(rep.message, "character device"), rep.message);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_IO_ERROR, fogrt_load_camera_file("/dev/zero", 64, 48, &cam, &rep));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_IO_ERROR, fogrt_load_obj(s, "tests/data", NULL, &rep));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(rep.message, "directory"), rep.message);
    alarm(0);
    remove(fifo);
    snap_scene(s, &after);
    assert_same_scene(&before, &after, "non-regular files");
    fogrt_scene_destroy(s);
}

/* The size is checked before reading: a file over the limit is refused with the real limit
   in the message, and a 1.5 GiB sparse file costs no memory. */
static void test_file_size_limit(void)
{
    char sparse[512], msg[900];
    count_alloc c;
    fogrt_load_options o = counted(&c, FOGRT_LOAD_PLACE_DEFAULT);
    fogrt_load_report rep;
    fogrt_scene *s = new_scene();
    FILE *f;
    o.max_file_bytes = 100;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_TOO_LARGE, fogrt_load_file(s, DATA_DIR "dae_materials.dae", &o, &rep));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(rep.message, "7298 bytes, more than the limit of 100 bytes"), rep.message);
    TEST_ASSERT_EQUAL_UINT(0, c.calls);
    tmp_path(sparse, sizeof sparse, "sparse.obj");
    f = fopen(sparse, "wb");
    TEST_ASSERT_NOT_NULL(f);
    TEST_ASSERT_EQUAL_INT(0, fseek(f, 1610612735L, SEEK_SET));   /* 1.5 GiB - 1 */
    TEST_ASSERT_EQUAL_INT('v', fputc('v', f));
    TEST_ASSERT_EQUAL_INT(0, fclose(f));
    o = counted(&c, FOGRT_LOAD_PLACE_DEFAULT);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_TOO_LARGE, fogrt_load_file(s, sparse, &o, &rep));
    snprintf(msg, sizeof msg, "%s: %s", rep.file, rep.message);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(rep.message, "1610612736 bytes, more than the limit of 1073741824 bytes (1 GiB"), msg);
    TEST_ASSERT_NULL_MESSAGE(strstr(rep.message, "2 GB"), msg);
    TEST_ASSERT_EQUAL_UINT_MESSAGE(0, c.calls, msg);
    remove(sparse);
    fogrt_scene_destroy(s);
}

/* Declared counts are checked against the file's size before anything is allocated. */
static void test_ply_declared_counts(void)
{
    count_alloc c;
    fogrt_load_options o = counted(&c, FOGRT_LOAD_PLACE_DEFAULT);
    fogrt_load_report rep;
    fogrt_scene *s = new_scene();
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_PARSE_ERROR, fogrt_load_file(s, DATA_DIR "ply_huge_count.ply", &o, &rep));
    TEST_ASSERT_EQUAL_INT(11, rep.line);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(rep.message, "file too short"), rep.message);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(rep.message, "4000000000 vertices"), rep.message);
    TEST_ASSERT_TRUE_MESSAGE(c.peak < 8192, "more than the file's copy and the header were allocated");
    fogrt_scene_destroy(s);
}

/* A binary PLY with one vertex property of each double value given (x, y, z, then w). */
static size_t make_ply_doubles(unsigned char *buf, const double *w, const char *wname)
{
    size_t n;
    int v;
    n = (size_t)sprintf((char *)buf, "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty double x\nproperty float y\n"
                                     "property float z\nproperty double %s\nelement face 1\nproperty list uchar uint vertex_indices\nend_header\n", wname);
    for (v = 0; v < 3; ++v) {
        double x = v == 1 ? 1.0 : 0.0;
        float y = v == 2 ? 1.0f : 0.0f, z = 0.0f;
        memcpy(buf + n, &x, 8); memcpy(buf + n + 8, &y, 4); memcpy(buf + n + 12, &z, 4); memcpy(buf + n + 16, &w[v], 8);
        n += 24;
    }
    buf[n++] = 3;
    for (v = 0; v < 3; ++v) { uint32_t i = (uint32_t)v; memcpy(buf + n, &i, 4); n += 4; }
    return n;
}
/* Values in properties the loader skips may be anything (1e300, NaN); used ones are checked
   with the true reason. (Little-endian hosts only for the binary part, like make_binary_ply.) */
static void test_ply_skipped_values(void)
{
    unsigned char buf[1024];
    double w[3] = { 1e300, -1e300, 0.0 }, x_far[3];
    size_t n;
    fogrt_load_report rep;
    fogrt_load_options o = as_is();
    fogrt_scene *s = load_ok("ply_skipped_huge.ply", &rep, NULL);
    TEST_ASSERT_EQUAL_UINT32(1, rep.triangles);
    fogrt_scene_destroy(s);
    w[2] = nan("");
    n = make_ply_doubles(buf, w, "quality");
    s = new_scene();
    TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_RESULT_OK, fogrt_load_ply_memory(s, buf, n, "skipped.ply", NULL, &rep), rep.message);
    TEST_ASSERT_EQUAL_UINT32(1, rep.triangles);
    fogrt_scene_destroy(s);
    /* the same doubles where they are used: x */
    x_far[0] = 0.0; x_far[1] = 1e300; x_far[2] = 0.0;
    n = make_ply_doubles(buf, x_far, "x");   /* a second x overrides the first */
    s = new_scene();
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_PARSE_ERROR, fogrt_load_ply_memory(s, buf, n, "used.ply", NULL, &rep));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(rep.message, "vertex 1: x = 1e+300 is not a finite float"), rep.message);
    x_far[1] = 1e31;
    n = make_ply_doubles(buf, x_far, "x");
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_PARSE_ERROR, fogrt_load_ply_memory(s, buf, n, "used.ply", &o, &rep));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(rep.message, "vertex 1: x = 1e+31 is beyond fogrt's limit of 1e30"), rep.message);
    TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_RESULT_OK, fogrt_load_ply_memory(s, buf, n, "placed.ply", NULL, &rep), rep.message);
    fogrt_scene_destroy(s);
}

/* Coordinates beyond the scene's 1e30 are refused by the loader, with file and line, before
   the scene sees them; placed into the box they are fine. */
static void test_far_coordinates(void)
{
    static const struct { const char *file; int line; } far[] = { { "obj_far.obj", 3 }, { "ply_far.ply", 12 } };
    size_t i;
    for (i = 0; i < 2; ++i) {
        char path[512], msg[700];
        fogrt_load_options o = as_is();
        fogrt_load_report rep;
        fogrt_scene *s = load_ok(far[i].file, &rep, NULL);
        TEST_ASSERT_EQUAL_UINT32(1, rep.triangles);
        fogrt_scene_destroy(s);
        s = new_scene();
        snprintf(path, sizeof path, DATA_DIR "%s", far[i].file);
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_PARSE_ERROR, fogrt_load_file(s, path, &o, &rep));
        snprintf(msg, sizeof msg, "%s:%d: %s", rep.file, rep.line, rep.message);
        TEST_ASSERT_EQUAL_INT_MESSAGE(far[i].line, rep.line, msg);
        TEST_ASSERT_NOT_NULL_MESSAGE(strstr(rep.message, "beyond fogrt's limit of 1e30"), msg);
        TEST_ASSERT_EQUAL_UINT32(0, s->tri_count + s->material_count);
        fogrt_scene_destroy(s);
    }
}

/* OBJ: a UTF-8 byte-order mark is skipped; LF, CRLF and CR line endings read alike (and
   count lines alike); a file without a 'v' statement (random bytes, only comments, empty)
   is malformed, not an empty mesh. */
static void test_obj_bom_and_line_endings(void)
{
    static const char *same[] = { "obj_cr.obj", "obj_crlf.obj" };
    fogrt_load_report rep;
    fogrt_load_options o = as_is();
    fogrt_scene *s = load_ok("obj_bom.obj", &rep, &o), *ref;
    size_t i, size, k;
    char *d;
    uint32_t t;
    TEST_ASSERT_EQUAL_UINT32(2, rep.triangles);
    TEST_ASSERT_EQUAL_UINT32(4, rep.vertices);
    assert_vec3(0.0f, 0, 0, 0, tri_v(s, 0, 0), "BOM: the first vertex is kept");
    assert_vec3(0.0f, 0, 0, 1, tri_v(s, 1, 2), "BOM: the fourth vertex");
    fogrt_scene_destroy(s);
    d = data_file("obj_crlf.obj", &size);
    for (i = 0, k = 0; i < size; ++i) if (d[i] != '\r') d[k++] = d[i];   /* the LF version */
    ref = new_scene();
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_load_obj_memory(ref, d, k, "lf.obj", &o, &rep));
    TEST_ASSERT_EQUAL_UINT32(3, rep.triangles);
    for (i = 0; i < 2; ++i) {
        s = load_ok(same[i], &rep, &o);
        TEST_ASSERT_EQUAL_UINT32_MESSAGE(ref->tri_count, s->tri_count, same[i]);
        for (t = 0; t < s->tri_count; ++t) {
            assert_vec3(0.0f, tri_v(ref, t, 0).x, tri_v(ref, t, 0).y, tri_v(ref, t, 0).z, tri_v(s, t, 0), same[i]);
            assert_vec3(0.0f, tri_v(ref, t, 2).x, tri_v(ref, t, 2).y, tri_v(ref, t, 2).z, tri_v(s, t, 2), same[i]);
        }
        fogrt_scene_destroy(s);
    }
    fogrt_scene_destroy(ref);
    s = new_scene();
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_PARSE_ERROR, fogrt_load_obj_memory(s, "v 0 0 0\rv 1 0 0\rf 1 2 x\r", 24, "cr.obj", NULL, &rep));
    TEST_ASSERT_EQUAL_INT(3, rep.line);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_PARSE_ERROR, fogrt_load_obj_memory(s, "v 0 0 0\r\nv 1 0 0\r\n\r\nf 1 2 3\r\n", 29, "crlf.obj", NULL, &rep));
    TEST_ASSERT_EQUAL_INT(4, rep.line);     /* vertex 3 out of range, on line 4 */
    free(d);
    {   /* random bytes, comments only, nothing: parse errors */
        static char noise[65536];
        uint32_t seed, x;
        for (seed = 1; seed <= 8; ++seed) {
            for (i = 0, x = seed * 2654435761u; i < sizeof noise; ++i) { x = x * 1664525u + 1013904223u; noise[i] = (char)(x >> 24); }
            TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_RESULT_PARSE_ERROR, fogrt_load_obj_memory(s, noise, sizeof noise, "noise.obj", NULL, &rep), rep.message);
        }
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_PARSE_ERROR, fogrt_load_obj_memory(s, "# only a comment\n", 17, "c.obj", NULL, &rep));
        TEST_ASSERT_NOT_NULL(strstr(rep.message, "not an OBJ mesh"));
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_PARSE_ERROR, fogrt_load_obj_memory(s, "", 0, "empty.obj", NULL, &rep));
        TEST_ASSERT_EQUAL_UINT32(0, s->tri_count + s->material_count);
    }
    fogrt_scene_destroy(s);
}

/* Writes a .dae with one geometry of 2 * gw * gh triangles instanced by `nodes` nodes. */
static char *make_instanced_dae(int gw, int gh, int nodes, size_t *size)
{
    size_t cap = (size_t)(gw + 1) * (size_t)(gh + 1) * 40 + (size_t)gw * (size_t)gh * 80 + (size_t)nodes * 120 + 2048, n = 0;
    char *s = (char *)malloc(cap);
    int i, j, k;
    TEST_ASSERT_NOT_NULL(s);
    n += (size_t)sprintf(s + n, "<?xml version=\"1.0\"?>\n<COLLADA version=\"1.4.1\"><asset><up_axis>Y_UP</up_axis></asset>\n"
                                "<library_geometries><geometry id=\"g\"><mesh><source id=\"pos\"><float_array id=\"pa\" count=\"%d\">",
                         3 * (gw + 1) * (gh + 1));
    for (j = 0; j <= gh; ++j) for (i = 0; i <= gw; ++i) n += (size_t)sprintf(s + n, "%g %g 0 ", 0.01 * i, 0.01 * j);
    n += (size_t)sprintf(s + n, "</float_array></source><vertices id=\"v\"><input semantic=\"POSITION\" source=\"#pos\"/></vertices>\n"
                                "<triangles count=\"%d\"><input semantic=\"VERTEX\" source=\"#v\" offset=\"0\"/><p>", 2 * gw * gh);
    for (j = 0; j < gh; ++j)
        for (i = 0; i < gw; ++i) {
            int a = j * (gw + 1) + i, b = a + 1, c = a + gw + 1, d = c + 1;
            n += (size_t)sprintf(s + n, "%d %d %d %d %d %d ", a, b, d, a, d, c);
        }
    n += (size_t)sprintf(s + n, "</p></triangles></mesh></geometry></library_geometries>\n<library_visual_scenes><visual_scene id=\"S\">\n");
    for (k = 0; k < nodes; ++k)
        n += (size_t)sprintf(s + n, "<node><translate>%d %d 0</translate><instance_geometry url=\"#g\"/></node>\n", k % 100, k / 100);
    n += (size_t)sprintf(s + n, "</visual_scene></library_visual_scenes><scene><instance_visual_scene url=\"#S\"/></scene></COLLADA>\n");
    TEST_ASSERT_TRUE(n < cap);
    *size = n;
    return s;
}

/* Nodes instancing one geometry share its parsed form: the right triangles and materials
   per instance, loader memory independent of the instance count, and a file that asks for
   more than max_triangles (all instances counted) refused early with the count. */
static void test_dae_instances_share_geometry(void)
{
    fogrt_load_report rep;
    fogrt_scene *s = load_ok("dae_instances.dae", &rep, NULL), *big;
    count_alloc c;
    fogrt_load_options o;
    size_t size;
    char *d, msg[700];
    uint32_t t;
    scene_snap before, after;
    TEST_ASSERT_EQUAL_UINT32(6, rep.triangles);
    TEST_ASSERT_EQUAL_UINT32(2, rep.materials);
    for (t = 0; t < 6; ++t) {
        fogrt_material_desc m = prim_material(s, t);
        TEST_ASSERT_TRUE_MESSAGE(winding_normal(s, t).z > 0.0f, "every instance keeps the front side (+z), the mirrored one too");
        TEST_ASSERT_TRUE(same_colour(m.reflectance, t / 2 == 1 ? 0.1f : 0.8f, t / 2 == 1 ? 0.8f : 0.1f, 0.1f));
        assert_vec3(1e-6f, 0, 0, -1, tri_n(s, t, 0), "smooth normal of the open quad: negated, as CS184's (see fogrt__ld_open_parts)");
    }
    assert_vec3(0.0f, 0, 0, -1, tri_v(s, 0, 0), "instance a");
    assert_vec3(0.0f, 2, 0, -1, tri_v(s, 2, 0), "instance b, moved by 2 in x");
    assert_vec3(0.0f, 0, 3, -1, tri_v(s, 4, 0), "instance c, mirrored in x and moved by 3 in y");
    assert_vec3(0.0f, -1, 4, -1, tri_v(s, 4, 1), "instance c: its (1,1) corner mirrored, re-wound");
    fogrt_scene_destroy(s);

    /* 2000 instances of a 1000-triangle geometry: 2 million triangles, loader memory of the
       order of the file and one instance */
    d = make_instanced_dae(25, 20, 2000, &size);
    o = counted(&c, FOGRT_LOAD_PLACE_DEFAULT);
    big = new_scene();
    TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_RESULT_OK, fogrt_load_dae_memory(big, d, size, "inst.dae", &o, &rep), rep.message);
    TEST_ASSERT_EQUAL_UINT32(2000000, rep.triangles);
    snprintf(msg, sizeof msg, "loader peak %u bytes for a %u-byte file and 2e6 triangles", (unsigned)c.peak, (unsigned)size);
    TEST_MESSAGE(msg);
    TEST_ASSERT_TRUE_MESSAGE(c.peak < 8 * size, msg);
    TEST_ASSERT_EQUAL_UINT(0, c.live);
    fogrt_scene_destroy(big);
    /* the limit: 1999 nodes fit under 1999000 triangles, the 2000th does not */
    o = counted(&c, FOGRT_LOAD_PLACE_DEFAULT);
    o.max_triangles = 1999000;
    big = content_scene();
    snap_scene(big, &before);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_TOO_LARGE, fogrt_load_dae_memory(big, d, size, "inst.dae", &o, &rep));
    snprintf(msg, sizeof msg, "%s:%d: %s", rep.file, rep.line, rep.message);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(rep.message, "asks for 2000000 triangles, more than the limit of 1999000"), msg);
    TEST_ASSERT_EQUAL_INT_MESSAGE(2005, rep.line, msg);   /* the 2000th node (nodes start on line 6) */
    snap_scene(big, &after);
    assert_same_scene(&before, &after, msg);
    fogrt_scene_destroy(big);
    free(d);
    {   /* OBJ and PLY count their triangles the same way */
        fogrt_load_options lim = as_is();
        s = new_scene();
        lim.max_triangles = 2;
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_TOO_LARGE, fogrt_load_file(s, DATA_DIR "obj_polygons.obj", &lim, &rep));
        TEST_ASSERT_NOT_NULL_MESSAGE(strstr(rep.message, "more than the limit of 2"), rep.message);
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_TOO_LARGE, fogrt_load_file(s, DATA_DIR "ply_ascii.ply", &lim, &rep));
        TEST_ASSERT_NOT_NULL_MESSAGE(strstr(rep.message, "more than the limit of 2"), rep.message);
        TEST_ASSERT_EQUAL_UINT32(0, s->tri_count + s->material_count);
        fogrt_scene_destroy(s);
    }
}

/* Peak loader memory per triangle, for a PLY fan (one face of 200k corners) and an OBJ grid:
   bounded by the input (the file's copy) plus a fixed number of bytes per triangle. */
static void test_bytes_per_triangle(void)
{
    int nv = 1000, corners = 200000, i, j, g = 150;
    size_t cap = 4096 + (size_t)nv * 12 + (size_t)corners * 4, n, on = 0;
    unsigned char *ply = (unsigned char *)malloc(cap);
    char *obj = (char *)malloc((size_t)(g + 1) * (g + 1) * 40 + (size_t)g * g * 60), msg[300];
    count_alloc c;
    fogrt_load_options o;
    fogrt_load_report rep;
    fogrt_scene *s;
    TEST_ASSERT_NOT_NULL(ply); TEST_ASSERT_NOT_NULL(obj);
    n = (size_t)sprintf((char *)ply, "ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\n"
                                     "property float z\nelement face 1\nproperty list uint int vertex_indices\nend_header\n", nv);
    for (i = 0; i < nv; ++i) {
        float p[3];
        p[0] = cosf(6.2831853f * (float)i / (float)nv); p[1] = sinf(6.2831853f * (float)i / (float)nv); p[2] = 0.001f * (float)i;
        memcpy(ply + n, p, 12); n += 12;
    }
    memcpy(ply + n, &corners, 4); n += 4;
    for (i = 0; i < corners; ++i) { int32_t k = i ? 1 + i % (nv - 1) : 0; memcpy(ply + n, &k, 4); n += 4; }
    o = counted(&c, FOGRT_LOAD_PLACE_DEFAULT);
    s = new_scene();
    TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_RESULT_OK, fogrt_load_ply_memory(s, ply, n, "fan.ply", &o, &rep), rep.message);
    snprintf(msg, sizeof msg, "PLY fan: %u triangles, %u-byte file, loader peak %u bytes = %.1f bytes/triangle",
             rep.triangles, (unsigned)n, (unsigned)c.peak, (double)c.peak / rep.triangles);
    TEST_MESSAGE(msg);
    TEST_ASSERT_TRUE_MESSAGE(c.peak <= n + 12u * rep.triangles + 64u * (unsigned)nv + 65536u, msg);
    fogrt_scene_destroy(s);
    for (j = 0; j <= g; ++j) for (i = 0; i <= g; ++i) on += (size_t)sprintf(obj + on, "v %d %d %d\n", i, j, (i * j) % 7);
    for (j = 0; j < g; ++j)
        for (i = 0; i < g; ++i) {
            int a = j * (g + 1) + i + 1, b = a + 1, cc = a + g + 1, d = cc + 1;
            on += (size_t)sprintf(obj + on, "f %d %d %d\nf %d %d %d\n", a, b, d, a, d, cc);
        }
    o = counted(&c, FOGRT_LOAD_PLACE_DEFAULT);
    s = new_scene();
    TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_RESULT_OK, fogrt_load_obj_memory(s, obj, on, "grid.obj", &o, &rep), rep.message);
    snprintf(msg, sizeof msg, "OBJ grid: %u triangles, %u-byte file, loader peak %u bytes = %.1f bytes/triangle",
             rep.triangles, (unsigned)on, (unsigned)c.peak, (double)c.peak / rep.triangles);
    TEST_MESSAGE(msg);
    TEST_ASSERT_TRUE_MESSAGE(c.peak <= on + 12u * rep.triangles + 36u * rep.vertices + 65536u, msg);
    fogrt_scene_destroy(s);
    free(ply); free(obj);
}

/* A camera file the scene would refuse is refused by the loader, with its line and the true
   reason (not "up is parallel" for an overflow; one message, not the core's and the CLI's). */
static void test_camera_file_refusals(void)
{
    static const struct { const char *text; int line; const char *words; } cases[] = {
        { "49 37 1.3 0.1 100\n3e38 0 0 -3e38 0 0\n1 0 4 2 20\n1 0 0 0 1 0 0 0 1\n800 600 875\n", 2, "overflows a float" },
        { "49 37 1.3 0.1 100\n0 0 0 0 1 0\n1 0 4 2 20\n1 0 0 0 1 0 0 0 1\n800 600 875\n", 4, "parallel" },
        { "49 37 1.3 0.1 100\n0 0 1 0 0 0\n1 0 4 2 20\n1 0 0 0 1 0 0 0 1\n800 1e9 1\n", 5, "less than 180" },
    };
    size_t i;
    for (i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        fogrt_camera_desc cam;
        fogrt_load_report rep;
        char msg[600];
        fogrt_result r = fogrt_load_camera_memory(cases[i].text, strlen(cases[i].text), "c.cam", 480, 360, &cam, &rep);
        snprintf(msg, sizeof msg, "case %u: %s:%d: %s", (unsigned)i, rep.file, rep.line, rep.message);
        TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_RESULT_PARSE_ERROR, r, msg);
        TEST_ASSERT_EQUAL_INT_MESSAGE(cases[i].line, rep.line, msg);
        TEST_ASSERT_NOT_NULL_MESSAGE(strstr(rep.message, cases[i].words), msg);
    }
}

/* Warnings reach options.logger only when the load succeeds: a refusal is its one message. */
typedef struct warn_log { int calls; bool named; } warn_log;
static void log_warning(fogrt_log_level level, const char *message, void *user)
{
    warn_log *w = (warn_log *)user;
    w->calls++;
    w->named = w->named || (level == FOGRT_LOG_WARNING && strstr(message, "up.dae:") && strstr(message, ": warning: "));
}
static void test_warnings_only_on_success(void)
{
    fogrt_load_options o;
    fogrt_load_report rep;
    warn_log w;
    fogrt_scene *s = new_scene();
    size_t size;
    char *d = data_file("dae_upaxis_none.dae", &size), *num;
    memset(&o, 0, sizeof o);
    memset(&w, 0, sizeof w);
    o.logger.func = log_warning; o.logger.user_data = &w;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_load_dae_memory(s, d, size, "up.dae", &o, &rep));
    TEST_ASSERT_EQUAL_UINT32(1, rep.warnings);
    TEST_ASSERT_EQUAL_INT(1, w.calls);
    TEST_ASSERT_TRUE(w.named);
    fogrt_scene_destroy(s);
    num = strstr(d, "1 2 3  2 2 3");
    TEST_ASSERT_NOT_NULL(num);
    num[0] = 'x';                                  /* a bad number after the up_axis warning */
    s = new_scene();
    memset(&w, 0, sizeof w);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_PARSE_ERROR, fogrt_load_dae_memory(s, d, size, "up.dae", &o, &rep));
    TEST_ASSERT_EQUAL_UINT32(1, rep.warnings);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, w.calls, "a refused load logged its warnings");
    fogrt_scene_destroy(s);
    free(d);
}

/* ------------------------------------------------------------------------------------------
   Names: options.on_shape
   ------------------------------------------------------------------------------------------ */
/* What on_shape was told, one "mesh 7 node|material|geometry" line per call. */
typedef struct shape_log { int n; char line[16][200]; } shape_log;
static void log_shape(void *user, fogrt_shape_kind kind, uint32_t index, const char *node, const char *material,
                      const char *geometry)
{
    shape_log *log = (shape_log *)user;
    if (log->n < 16)
        snprintf(log->line[log->n], sizeof log->line[0], "%s %u %s|%s|%s", kind == FOGRT_SHAPE_MESH ? "mesh" : "sphere",
                 (unsigned)index, node, material, geometry);
    log->n++;
}
static fogrt_load_options naming(shape_log *log)
{
    fogrt_load_options o = as_is();
    memset(log, 0, sizeof *log);
    o.on_shape = log_shape; o.on_shape_user = log;
    return o;
}
/* Loads tests/data/name into s with on_shape and expects the lines want (NULL-terminated;
   "%m" and "%s" in them stand for the scene's mesh and sphere counts before the load). */
static void expect_names(fogrt_scene *s, const char *name, const char *const *want)
{
    char path[512], msg[900];
    shape_log log;
    fogrt_load_options o = naming(&log);
    fogrt_load_report rep;
    fogrt_scene_info before;
    int k;
    fogrt_scene_get_info(s, &before);
    snprintf(path, sizeof path, DATA_DIR "%s", name);
    snprintf(msg, sizeof msg, "%s", name);
    TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_RESULT_OK, fogrt_load_file(s, path, &o, &rep), msg);
    for (k = 0; want[k]; ++k) {
        char line[200];
        const char *w = want[k];
        int m = w[0] == 'm', base = (int)(m ? before.mesh_count : before.sphere_count);
        snprintf(line, sizeof line, "%s %d %s", m ? "mesh" : "sphere", base + atoi(strchr(w, ' ') + 1), strchr(strchr(w, ' ') + 1, ' ') + 1);
        snprintf(msg, sizeof msg, "%s: call %d: got '%s'", name, k, k < log.n ? log.line[k] : "(none)");
        TEST_ASSERT_EQUAL_STRING_MESSAGE(line, k < log.n ? log.line[k] : "", msg);
    }
    snprintf(msg, sizeof msg, "%s: %d calls, expected %d", name, log.n, k);
    TEST_ASSERT_EQUAL_INT_MESSAGE(k, log.n, msg);
}

/* .dae: the node, the bound material and the geometry, by name attribute or else id; the
   numbers continue the scene's own; a shared geometry is named by every instance. */
static void test_dae_shape_names(void)
{
    static const char *const instances[] = { "m 0 a|red|quad", "m 1 b|green|quad", "m 2 c|red|quad", NULL };
    static const char *const spheres[] = { "s 0 s1|chrome|ball", "s 1 s2||ball", NULL };
    static const char *const area[] = { "m 0 floor||floor", "m 1 Area||", NULL };
    static const char *const cb[] = { "m 0 ceiling|ceiling|ceiling", "m 1 light|light|light", "m 2 floor|floor|floor",
                                      "m 3 leftWall|leftWall|leftWall", "m 4 rightWall|rightWall|rightWall",
                                      "m 5 backWall|backWall|backWall", "s 0 Sphere1|refract|Sphere1", "s 1 Sphere2|chrome|Sphere1", NULL };
    fogrt_scene *s = content_scene();
    shape_log log;
    fogrt_load_options o = naming(&log);
    fogrt_load_report rep;
    expect_names(s, "dae_instances.dae", instances);
    expect_names(s, "dae_sphere.dae", spheres);        /* after the box's spheres and a.dae's meshes */
    fogrt_scene_destroy(s);
    s = new_scene();
    expect_names(s, "dae_area_light.dae", area);       /* the CGL <area> rectangle: its node */
    fogrt_scene_destroy(s);
    s = new_scene();                                    /* a refused load names nothing */
    TEST_ASSERT_NOT_EQUAL(FOGRT_RESULT_OK, fogrt_load_file(s, DATA_DIR "bad_index.dae", &o, &rep));
    TEST_ASSERT_EQUAL_INT(0, log.n);
    fogrt_scene_destroy(s);
    if (!file_exists(CS184_DIR "CBspheres.dae")) TEST_IGNORE_MESSAGE("../shared absent: CBspheres.dae's names not checked");
    s = new_scene();
    o = naming(&log);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_load_file(s, CS184_DIR "CBspheres.dae", &o, &rep));
    {
        int k;
        for (k = 0; cb[k]; ++k) {
            char line[200];
            snprintf(line, sizeof line, "%s %s", cb[k][0] == 'm' ? "mesh" : "sphere", cb[k] + 2);
            TEST_ASSERT_EQUAL_STRING(line, log.line[k]);
        }
        TEST_ASSERT_EQUAL_INT(k, log.n);
    }
    fogrt_scene_destroy(s);
}

/* OBJ: a mesh per o or g followed by faces (o, usemtl at its first face, g; an empty group
   is no mesh, a group name used twice two meshes); without on_shape one mesh; PLY: one mesh
   without names. */
static void test_obj_group_names(void)
{
    static const char *const groups[] = { "m 0 boxes|red|", "m 1 boxes|red|left tet", "m 2 boxes|blue|right",
                                          "m 3 floor|blue|", "m 4 floor|blue|right", NULL };
    static const char *const ply[] = { "m 0 ||", NULL };
    static const uint32_t tris[5] = { 1, 3, 4, 2, 1 };
    fogrt_scene *s = content_scene();
    fogrt_scene_info before, after;
    fogrt_load_report rep;
    fogrt_load_options o = as_is();
    uint32_t t, k;
    fogrt_scene_get_info(s, &before);
    expect_names(s, "obj_groups.obj", groups);
    fogrt_scene_get_info(s, &after);
    TEST_ASSERT_EQUAL_UINT32(before.mesh_count + 5, after.mesh_count);
    for (k = 0; k < 5; ++k) {                           /* each mesh holds its group's triangles */
        uint32_t n = 0;
        for (t = before.triangle_count; t < after.triangle_count; ++t) n += s->tri_mesh[t] == before.mesh_count + k;
        TEST_ASSERT_EQUAL_UINT32(tris[k], n);
    }
    fogrt_scene_destroy(s);
    s = new_scene();
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_load_file(s, DATA_DIR "obj_groups.obj", &o, &rep));
    fogrt_scene_get_info(s, &after);
    TEST_ASSERT_EQUAL_UINT32(1, after.mesh_count);      /* without names: one mesh, as ever */
    TEST_ASSERT_EQUAL_UINT32(11, after.triangle_count);
    fogrt_scene_destroy(s);
    s = content_scene();
    expect_names(s, "ply_ascii.ply", ply);
    fogrt_scene_destroy(s);
}

/* Asking for names changes no triangle, normal, material or sphere, nor their order: every
   file of tests/data that loads gives the same primitives with and without on_shape, placed
   and as is (only an OBJ's meshes are numbered differently). */
static void test_names_change_no_primitive(void)
{
    DIR *dir = opendir("tests/data");
    struct dirent *e;
    int compared = 0, p;
    char msg[700];
    TEST_ASSERT_NOT_NULL(dir);
    while ((e = readdir(dir)) != NULL) {
        char path[600];
        if (!is_scene_file(e->d_name)) continue;
        snprintf(path, sizeof path, DATA_DIR "%s", e->d_name);
        for (p = 0; p < 2; ++p) {
            shape_log log;
            fogrt_load_options plain = as_is(), named = naming(&log);
            fogrt_scene *a = new_scene(), *b = new_scene();
            fogrt_load_report rep;
            if (!p) plain.place = named.place = FOGRT_LOAD_PLACE_DEFAULT;
            snprintf(msg, sizeof msg, "%s (%s)", e->d_name, p ? "as is" : "placed");
            if (fogrt_load_file(a, path, &plain, &rep) == FOGRT_RESULT_OK) {
                TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_RESULT_OK, fogrt_load_file(b, path, &named, &rep), msg);
                TEST_ASSERT_EQUAL_UINT32_MESSAGE(a->tri_count, b->tri_count, msg);
                TEST_ASSERT_EQUAL_UINT32_MESSAGE(a->sph_count, b->sph_count, msg);
                TEST_ASSERT_EQUAL_UINT32_MESSAGE(a->material_count, b->material_count, msg);
                TEST_ASSERT_TRUE_MESSAGE(a->tri_count == 0 || memcmp(a->tri_v, b->tri_v, sizeof *a->tri_v * 3 * a->tri_count) == 0, msg);
                TEST_ASSERT_TRUE_MESSAGE((a->tri_n == NULL) == (b->tri_n == NULL), msg);
                TEST_ASSERT_TRUE_MESSAGE(!a->tri_n || memcmp(a->tri_n, b->tri_n, sizeof *a->tri_n * 3 * a->tri_count) == 0, msg);
                TEST_ASSERT_TRUE_MESSAGE(a->tri_count == 0 || memcmp(a->tri_material, b->tri_material, sizeof(uint32_t) * a->tri_count) == 0, msg);
                TEST_ASSERT_TRUE_MESSAGE(a->sph_count == 0 || (memcmp(a->sph_c, b->sph_c, sizeof *a->sph_c * a->sph_count) == 0 &&
                                                              memcmp(a->sph_r, b->sph_r, sizeof(float) * a->sph_count) == 0), msg);
                TEST_ASSERT_EQUAL_INT_MESSAGE((int)(a->mesh_count + a->sph_count), log.n + (strstr(e->d_name, "groups") ? -4 : 0), msg);
                if (!strstr(e->d_name, "groups")) TEST_ASSERT_EQUAL_UINT32_MESSAGE(a->mesh_count, b->mesh_count, msg);
                compared++;
            }
            fogrt_scene_destroy(a); fogrt_scene_destroy(b);
        }
    }
    closedir(dir);
    snprintf(msg, sizeof msg, "%d loads compared with and without names", compared);
    TEST_MESSAGE(msg);
    TEST_ASSERT_GREATER_OR_EQUAL(2 * 20, compared);
}

/* With names asked for, every allocation still goes through options.allocator and is freed,
   and an allocator failing at the N-th call, for every N, leaves the scene as it was and
   names nothing. */
static void test_names_counting_allocator(void)
{
    static const char *files[] = { "dae_instances.dae", "dae_area_light.dae", "dae_sphere.dae", "obj_groups.obj", "ply_ascii.ply" };
    size_t i, n;
    char msg[700];
    for (i = 0; i < sizeof files / sizeof files[0]; ++i) {
        count_alloc c;
        shape_log log;
        fogrt_load_options o = counted(&c, FOGRT_LOAD_PLACE_DEFAULT);
        fogrt_load_report rep;
        fogrt_scene *s = content_scene();
        size_t size, total;
        char *data = data_file(files[i], &size);
        load_fn fn = loader_for(files[i]);
        memset(&log, 0, sizeof log);
        o.on_shape = log_shape; o.on_shape_user = &log;
        TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_RESULT_OK, fn(s, data, size, files[i], &o, &rep), files[i]);
        TEST_ASSERT_EQUAL_UINT_MESSAGE(0, c.live, files[i]);
        TEST_ASSERT_TRUE_MESSAGE(log.n > 0, files[i]);
        fogrt_scene_destroy(s);
        total = c.calls;
        for (n = 1; n <= total; ++n) {
            scene_snap before, after;
            s = content_scene();
            snap_scene(s, &before);
            o = counted(&c, FOGRT_LOAD_PLACE_DEFAULT);
            memset(&log, 0, sizeof log);
            o.on_shape = log_shape; o.on_shape_user = &log;
            c.fail_at = n;
            snprintf(msg, sizeof msg, "%s with names, failing at allocation %u of %u", files[i], (unsigned)n, (unsigned)total);
            TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_RESULT_OUT_OF_MEMORY, fn(s, data, size, files[i], &o, &rep), msg);
            TEST_ASSERT_EQUAL_UINT_MESSAGE(0, c.live, msg);
            TEST_ASSERT_EQUAL_INT_MESSAGE(0, log.n, msg);
            snap_scene(s, &after);
            assert_same_scene(&before, &after, msg);
            fogrt_scene_destroy(s);
        }
        free(data);
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_cs184_scenes_match_fact_sheet);
    RUN_TEST(test_cs184_wall_normals_point_into_box);
    RUN_TEST(test_cs184_bunny_load_time);
    RUN_TEST(test_cs184_framing_at_every_resolution);
    RUN_TEST(test_dae_minimal);
    RUN_TEST(test_dae_up_axis);
    RUN_TEST(test_dae_transforms);
    RUN_TEST(test_dae_short_matrix_camera);
    RUN_TEST(test_dae_camera_yfov);
    RUN_TEST(test_dae_global_ids);
    RUN_TEST(test_dae_polylist_ngon);
    RUN_TEST(test_dae_multi_lists);
    RUN_TEST(test_dae_sphere);
    RUN_TEST(test_dae_materials);
    RUN_TEST(test_dae_normals);
    RUN_TEST(test_dae_area_light_rectangle);
    RUN_TEST(test_dae_area_light_merged);
    RUN_TEST(test_dae_point_and_spot);
    RUN_TEST(test_dae_ambient);
    RUN_TEST(test_dae_xml_quirks);
    RUN_TEST(test_dae_mirror_node);
    RUN_TEST(test_obj_polygons);
    RUN_TEST(test_flat_mesh_without_normals);
    RUN_TEST(test_obj_normals);
    RUN_TEST(test_ply_ascii);
    RUN_TEST(test_ply_binary);
    RUN_TEST(test_mesh_placement);
    RUN_TEST(test_stanford_bunny_ply);
    RUN_TEST(test_camera_file);
    RUN_TEST(test_messages_are_printable);
    RUN_TEST(test_malformed_files);
    RUN_TEST(test_truncated_files);
    RUN_TEST(test_fuzz_regressions);
    RUN_TEST(test_failed_load_changes_nothing);
    RUN_TEST(test_counting_allocator);
    RUN_TEST(test_non_regular_files);
    RUN_TEST(test_file_size_limit);
    RUN_TEST(test_ply_declared_counts);
    RUN_TEST(test_ply_skipped_values);
    RUN_TEST(test_far_coordinates);
    RUN_TEST(test_obj_bom_and_line_endings);
    RUN_TEST(test_dae_instances_share_geometry);
    RUN_TEST(test_bytes_per_triangle);
    RUN_TEST(test_camera_file_refusals);
    RUN_TEST(test_warnings_only_on_success);
    RUN_TEST(test_dae_shape_names);
    RUN_TEST(test_obj_group_names);
    RUN_TEST(test_names_change_no_primitive);
    RUN_TEST(test_names_counting_allocator);
    return UNITY_END();
}
