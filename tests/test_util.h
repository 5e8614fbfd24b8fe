/* test_util.h - small helpers shared by the test programs: the CHECK_OK assertion, vector
   constructors, a test-side random number generator, scene building (materials, fog, camera,
   quads), and the luminance, variance and standard-error formulas the statistical checks use.

   Include it after "fogrt.h" (with FOGRT_IMPLEMENTATION) and "unity.h". Everything is static
   inline (or a macro), so a test program pays nothing for the helpers it does not use and
   gets no unused-function warnings. */
#ifndef FOGRT_TESTS_TEST_UTIL_H
#define FOGRT_TESTS_TEST_UTIL_H

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

/* ---- assertions ------------------------------------------------------------------------ */

/* Asserts that a fogrt call returns FOGRT_RESULT_OK, naming the result it got instead. */
#define CHECK_OK(call)                                                          \
    do {                                                                        \
        fogrt_result check_ok_r_ = (call);                                      \
        TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_RESULT_OK, check_ok_r_,             \
                                      fogrt_result_string(check_ok_r_));        \
    } while (0)

/* make test SANITIZE=1 builds the tests with FOGRT_TESTS_SANITIZE. The sanitizers look for
   memory errors and undefined behaviour, which a smaller run reaches through the same code,
   at 2 to 4 times the cost of the plain build; so there the heaviest statistical loops run
   a reduced variant, SAN_REDUCED(n, d) = n / d (at least 1), and the full size, whose
   statistics the test is about, runs in the plain make test. A reduced variant must still
   pass on its own (its tolerances follow its own standard errors). */
#ifdef FOGRT_TESTS_SANITIZE
#define SAN_REDUCED(n, d) ((n) / (d) > 0 ? (n) / (d) : 1)
#else
#define SAN_REDUCED(n, d) (n)
#endif

/* Under FOGRT_MINIMAL (fogrt.h's Part I alone) a test of Part II skips with one line naming
   the appendix it needs: put PART_II_ONLY("...") first in its body, inside #ifdef
   FOGRT_MINIMAL, and the Part II code under #else. */
#define PART_II_ONLY(what) TEST_IGNORE_MESSAGE("needs Part II of fogrt.h (" what "): built with FOGRT_MINIMAL")

/* fogrt.h's getters of the binary tree and its brute-force ray query are Part II's (they
   serve the benchmarks too), so under FOGRT_MINIMAL the tests that check Part I's BVH with
   them get the same three here, read from Part I's scene fields, under the same names. */
#if defined(FOGRT_MINIMAL) && defined(FOGRT_IMPLEMENTATION)
static inline void test_scene_get_bvh(const fogrt_scene *s, const fogrt_bvh_node **nodes, uint32_t *node_count,
                                      const uint32_t **prim_index)
{
    if (nodes) *nodes = s->nodes;
    if (node_count) *node_count = s->node_count;
    if (prim_index) *prim_index = s->prim_index;
}
/* As fogrt.h's: box areas relative to the root's, 1 per inner node, 1 per primitive in a leaf. */
static inline float test_bvh_sah_cost(const fogrt_scene *s)
{
    double cost = 0.0, root_area;
    uint32_t i;
    fogrt__aabb rb;
    if (!s->nodes || s->node_count == 0) return 0.0f;
    rb.lo = fogrt__v(s->nodes[0].bmin[0], s->nodes[0].bmin[1], s->nodes[0].bmin[2]);
    rb.hi = fogrt__v(s->nodes[0].bmax[0], s->nodes[0].bmax[1], s->nodes[0].bmax[2]);
    root_area = (double)FOGRT__MAX(fogrt__aabb_area(&rb), FLT_MIN);
    for (i = 0; i < s->node_count; ++i) {
        const fogrt_bvh_node *n = &s->nodes[i];
        fogrt__aabb nb;
        if (i == 1) continue;
        nb.lo = fogrt__v(n->bmin[0], n->bmin[1], n->bmin[2]);
        nb.hi = fogrt__v(n->bmax[0], n->bmax[1], n->bmax[2]);
        cost += (double)fogrt__aabb_area(&nb) / root_area * (n->prim_count > 0 ? 1.0 * n->prim_count : 1.0);
    }
    return (float)cost;
}
/* Every primitive tested, the closest hit kept: the reference the BVH must match. */
static inline bool test_scene_intersect_brute(const fogrt_scene *s, fogrt_vec3 o, fogrt_vec3 d, float tmin, float tmax,
                                              fogrt_hit *hit)
{
    uint32_t i;
    bool found = false;
    for (i = 0; i < s->tri_count + s->sph_count; ++i) {
        float t, u = 0.0f, v = 0.0f;
        bool h;
        if (i < s->tri_count) {
            const fogrt__v3 *tv = &s->tri_v[3 * i];
            h = fogrt__hit_triangle(o, d, tv[0], fogrt__sub(tv[1], tv[0]), fogrt__sub(tv[2], tv[0]), tmin, tmax, &t, &u, &v);
        } else {
            h = fogrt__hit_sphere(o, d, s->sph_c[i - s->tri_count], s->sph_r[i - s->tri_count], tmin, tmax, &t);
        }
        if (h) {
            found = true; tmax = t;
            if (hit) { hit->t = t; hit->prim = i; hit->u = u; hit->v = v; }
        }
    }
    return found;
}
#define fogrt_scene_get_bvh test_scene_get_bvh
#define fogrt_bvh_sah_cost test_bvh_sah_cost
#define fogrt_scene_intersect_brute test_scene_intersect_brute
#endif

/* ---- vectors --------------------------------------------------------------------------- */

static inline fogrt_vec3 v3(float x, float y, float z) { fogrt_vec3 v; v.x = x; v.y = y; v.z = z; return v; }
static inline float vdot(fogrt_vec3 a, fogrt_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

/* ---- random numbers of our own (SplitMix64) ---------------------------------------------
   Test data that does not depend on the library's RNG, so a change there cannot change the
   cases a test checks. */
typedef struct test_rng { uint64_t s; } test_rng;
static inline uint64_t rng_next(test_rng *r)
{
    uint64_t z = (r->s += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}
static inline float rng_uniform(test_rng *r) { return (float)(rng_next(r) >> 40) * 0x1p-24f; }   /* [0,1) */

/* ---- scene building: materials, fog, camera --------------------------------------------- */

/* Adds a material of the given type, reflectance and emission (no transmittance, ior 0 = the
   default) and returns its id. FOGRT_BSDF_DEFAULT is what a zeroed desc holds. */
static inline uint32_t add_basic_material(fogrt_scene *scene, fogrt_bsdf_type type, fogrt_vec3 reflectance,
                                          fogrt_vec3 emission)
{
    fogrt_material_desc m;
    uint32_t id = 0;
    memset(&m, 0, sizeof m);
    m.type = type;
    m.reflectance = reflectance;
    m.emission = emission;
    CHECK_OK(fogrt_scene_add_material(scene, &m, &id));
    return id;
}

/* Fills the scene with homogeneous fog. */
static inline void set_medium(fogrt_scene *scene, float sigma_t, fogrt_vec3 albedo, float g)
{
    fogrt_medium_desc med;
    memset(&med, 0, sizeof med);
    med.sigma_t = sigma_t; med.albedo = albedo; med.g = g;
    CHECK_OK(fogrt_scene_set_medium(scene, &med));
}

/* A pinhole camera at `position` looking at `look_at`, with vertical field of view fov_deg
   (0: fogrt's default, 45); the other fields zero (default up, no lens). */
static inline void set_camera(fogrt_scene *scene, fogrt_vec3 position, fogrt_vec3 look_at, float fov_deg)
{
    fogrt_camera_desc cam;
    memset(&cam, 0, sizeof cam);
    cam.position = position; cam.look_at = look_at; cam.fov_deg = fov_deg;
    CHECK_OK(fogrt_scene_set_camera(scene, &cam));
}

/* ---- scene building: quads ------------------------------------------------------------- */

/* Adds the quad a, b, c, d (two triangles a b c and a c d, one mesh); its front side is the
   one from which a, b, c, d run counter-clockwise. */
static inline void add_quad_corners(fogrt_scene *scene, fogrt_vec3 a, fogrt_vec3 b, fogrt_vec3 c, fogrt_vec3 d,
                                    uint32_t material)
{
    float pos[12];
    static const uint32_t idx[6] = { 0, 1, 2, 0, 2, 3 };
    fogrt_mesh_desc md;
    pos[0] = a.x; pos[1] = a.y; pos[2] = a.z; pos[3] = b.x; pos[4] = b.y; pos[5] = b.z;
    pos[6] = c.x; pos[7] = c.y; pos[8] = c.z; pos[9] = d.x; pos[10] = d.y; pos[11] = d.z;
    memset(&md, 0, sizeof md);
    md.positions = pos; md.vertex_count = 4;
    md.indices = idx; md.triangle_count = 2;
    md.material = material;
    CHECK_OK(fogrt_scene_add_mesh(scene, &md));
}

/* Adds the parallelogram p, p+e1, p+e1+e2, p+e2; its front side is along e1 x e2. */
static inline void add_quad(fogrt_scene *scene, fogrt_vec3 p, fogrt_vec3 e1, fogrt_vec3 e2, uint32_t material)
{
    fogrt_vec3 corner[4];
    int k;
    for (k = 0; k < 4; ++k) {
        float a = (k == 1 || k == 2) ? 1.0f : 0.0f, b = (k == 2 || k == 3) ? 1.0f : 0.0f;
        corner[k] = v3(p.x + a * e1.x + b * e2.x, p.y + a * e1.y + b * e2.y, p.z + a * e1.z + b * e2.z);
    }
    add_quad_corners(scene, corner[0], corner[1], corner[2], corner[3], material);
}

/* A closed 2 x 2 x 2 Cornell-like box (x, z in [-1, 1], y in [0, 2]): white floor, ceiling,
   back and front walls, red left and green right walls, all wound to face inward, and a
   square ceiling lamp of half-width lamp_half and radiance lamp_radiance facing down.
   Returns the white material's id (the first material added). */
static inline uint32_t add_closed_box(fogrt_scene *scene, float lamp_half, float lamp_radiance)
{
    uint32_t white, red, green, lamp;
    white = add_basic_material(scene, FOGRT_BSDF_DIFFUSE, v3(0.7f, 0.7f, 0.7f), v3(0, 0, 0));
    red = add_basic_material(scene, FOGRT_BSDF_DIFFUSE, v3(0.7f, 0.1f, 0.1f), v3(0, 0, 0));
    green = add_basic_material(scene, FOGRT_BSDF_DIFFUSE, v3(0.1f, 0.7f, 0.1f), v3(0, 0, 0));
    lamp = add_basic_material(scene, FOGRT_BSDF_DIFFUSE, v3(0, 0, 0), v3(lamp_radiance, lamp_radiance, lamp_radiance));
    add_quad_corners(scene, v3(-1, 0, -1), v3(-1, 0, 1), v3(1, 0, 1), v3(1, 0, -1), white);     /* floor */
    add_quad_corners(scene, v3(-1, 2, -1), v3(1, 2, -1), v3(1, 2, 1), v3(-1, 2, 1), white);     /* ceiling */
    add_quad_corners(scene, v3(-1, 0, -1), v3(1, 0, -1), v3(1, 2, -1), v3(-1, 2, -1), white);   /* back */
    add_quad_corners(scene, v3(-1, 0, 1), v3(-1, 2, 1), v3(1, 2, 1), v3(1, 0, 1), white);       /* front */
    add_quad_corners(scene, v3(-1, 0, -1), v3(-1, 2, -1), v3(-1, 2, 1), v3(-1, 0, 1), red);     /* left */
    add_quad_corners(scene, v3(1, 0, -1), v3(1, 0, 1), v3(1, 2, 1), v3(1, 2, -1), green);       /* right */
    add_quad_corners(scene, v3(-lamp_half, 1.99f, -lamp_half), v3(lamp_half, 1.99f, -lamp_half),
                     v3(lamp_half, 1.99f, lamp_half), v3(-lamp_half, 1.99f, lamp_half), lamp);  /* lamp */
    return white;
}

/* ---- statistics of samples and images -------------------------------------------------- */

/* Rec. 709 luminance, the weights fogrt uses for fogrt_image.sum_sq. */
static inline double luminance(double r, double g, double b) { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }

/* The luminance of pixel p's mean. */
static inline double pixel_luminance(const fogrt_image *img, int p)
{
    return luminance(img->sum[3 * p], img->sum[3 * p + 1], img->sum[3 * p + 2]) / img->count[p];
}

/* The sample variance s^2 of pixel p's luminance samples: (E[L^2] - mean^2) n / (n - 1),
   clamped at 0 (rounding can make it slightly negative for a noise-free pixel). */
static inline double pixel_sample_variance(const fogrt_image *img, int p)
{
    double n = img->count[p], mean = pixel_luminance(img, p);
    return fmax(img->sum_sq[p] / n - mean * mean, 0.0) * n / (n - 1.0);
}

/* The variance of pixel p's mean luminance: fogrt's estimate from the spread of the pixel's
   independent sample streams. Not s^2 / n: the pixel positions are stratified, so the
   samples of a pixel are not independent and s^2 / n would overestimate. */
static inline double pixel_luminance_variance(const fogrt_image *img, int p)
{
    return fogrt_image_pixel_variance(img, (size_t)p);
}

/* The standard error of the mean of n samples, from their sum and sum of squares. */
static inline double std_error_of_mean(double sum, double sum_sq, long n)
{
    double mean = sum / n;
    return sqrt(fmax(sum_sq / n - mean * mean, 0.0) / (n - 1));
}

#endif /* FOGRT_TESTS_TEST_UTIL_H */
