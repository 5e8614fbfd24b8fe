/* test_bvh.c - the BVH gives the same closest hit as testing every primitive.
 *
 * Random triangle soups (with spheres mixed in) are built with every heuristic and bin count,
 * then thousands of rays compare fogrt_scene_intersect (BVH) with fogrt_scene_intersect_brute.
 * The rays include the cases that break slab tests: axis-parallel directions with +0 and -0
 * components, origins exactly on triangles, vertices and box faces, rays inside triangle
 * planes, and rays aimed at shared edges (where two triangles tie). The tree itself is walked
 * to check its invariants, and the SAH is compared with the paper's volume heuristic. */
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

/* ------------------------------------------------------------------------------------------
   Test data from a generator of our own (SplitMix64, test_rng in test_util.h), so the soups
   do not depend on the library's RNG.
   ------------------------------------------------------------------------------------------ */
static float rng_range(test_rng *r, float lo, float hi) { return lo + (hi - lo) * rng_uniform(r); }
static uint32_t rng_below(test_rng *r, uint32_t n) { return (uint32_t)(rng_next(r) % n); }

static fogrt_vec3 vadd(fogrt_vec3 a, fogrt_vec3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static fogrt_vec3 vsub(fogrt_vec3 a, fogrt_vec3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static fogrt_vec3 vscale(fogrt_vec3 a, float s) { return v3(a.x * s, a.y * s, a.z * s); }
static fogrt_vec3 vnorm(fogrt_vec3 a)
{
    double len = sqrt((double)a.x * a.x + (double)a.y * a.y + (double)a.z * a.z);
    return v3((float)(a.x / len), (float)(a.y / len), (float)(a.z / len));
}
static float vcomp(fogrt_vec3 a, int axis) { return axis == 0 ? a.x : (axis == 1 ? a.y : a.z); }
static void vset(fogrt_vec3 *a, int axis, float value)
{
    if (axis == 0) a->x = value; else if (axis == 1) a->y = value; else a->z = value;
}
static fogrt_vec3 random_point(test_rng *r, float half)
{
    return v3(rng_range(r, -half, half), rng_range(r, -half, half), rng_range(r, -half, half));
}
static fogrt_vec3 random_direction(test_rng *r)
{
    for (;;) {
        fogrt_vec3 d = random_point(r, 1.0f);
        float l2 = vdot(d, d);
        if (l2 > 1e-4f && l2 <= 1.0f) return vnorm(d);
    }
}
/* A multiple of 1/4 in [-1, 1]: grid coordinates make shared edges, shared vertices, flat
   bounding boxes and origins exactly on box faces. */
static float grid_coord(test_rng *r) { return -1.0f + 0.25f * (float)rng_below(r, 9); }

/* ------------------------------------------------------------------------------------------
   A soup: triangles (3 vertices each, no indices) and spheres
   ------------------------------------------------------------------------------------------ */
typedef struct soup {
    fogrt_vec3 *v;                /* 3 per triangle */
    uint32_t tri_count;
    fogrt_vec3 *center;
    float *radius;
    uint32_t sphere_count;
    unsigned char *degenerate;    /* per triangle: zero area by construction */
} soup;

static void make_soup(soup *s, uint64_t seed, uint32_t tri_count, uint32_t sphere_count, float offset)
{
    test_rng r;
    uint32_t i;
    r.s = seed;
    s->tri_count = tri_count;
    s->sphere_count = sphere_count;
    s->v = (fogrt_vec3 *)calloc(3 * (size_t)tri_count + 3, sizeof(fogrt_vec3));
    s->degenerate = (unsigned char *)calloc((size_t)tri_count + 1, 1);
    s->center = (fogrt_vec3 *)calloc((size_t)sphere_count + 1, sizeof(fogrt_vec3));
    s->radius = (float *)calloc((size_t)sphere_count + 1, sizeof(float));
    TEST_ASSERT_NOT_NULL(s->v);
    for (i = 0; i < tri_count; i++) {
        fogrt_vec3 *t = &s->v[3 * i];
        uint32_t kind = rng_below(&r, 16);
        fogrt_vec3 c = random_point(&r, 1.0f);
        float size = 0.02f * powf(25.0f, rng_uniform(&r));   /* 0.02 .. 0.5, log-uniform */
        int k;
        if (kind < 7) {                                      /* random triangle */
            for (k = 0; k < 3; k++) t[k] = vadd(c, random_point(&r, size));
        } else if (kind < 9) {                               /* axis-aligned: flat bounds */
            int axis = (int)rng_below(&r, 3);
            float plane = rng_uniform(&r) < 0.5f ? grid_coord(&r) : vcomp(c, axis);
            for (k = 0; k < 3; k++) { t[k] = vadd(c, random_point(&r, size)); vset(&t[k], axis, plane); }
        } else if (kind < 11) {                              /* on the 1/4 grid */
            for (k = 0; k < 3; k++) t[k] = v3(grid_coord(&r), grid_coord(&r), grid_coord(&r));
        } else if (kind < 14 && i > 0) {                     /* shares an edge with the previous */
            const fogrt_vec3 *p = &s->v[3 * (i - 1)];
            t[0] = p[2]; t[1] = p[1];                        /* reversed: consistent winding */
            t[2] = vadd(vscale(vadd(p[1], p[2]), 0.5f), random_point(&r, size));
        } else if (kind < 15) {                              /* large, spanning the box */
            for (k = 0; k < 3; k++) t[k] = random_point(&r, 1.2f);
        } else {                                             /* degenerate: a line or a point */
            t[0] = c;
            t[1] = rng_uniform(&r) < 0.5f ? c : vadd(c, v3(size, 0, 0));
            t[2] = rng_uniform(&r) < 0.5f ? c : vadd(c, v3(2 * size, 0, 0));
            s->degenerate[i] = 1;
        }
        for (k = 0; k < 3; k++) t[k] = vadd(t[k], v3(offset, offset, offset));
    }
    for (i = 0; i < sphere_count; i++) {
        s->center[i] = rng_uniform(&r) < 0.3f ? v3(grid_coord(&r), grid_coord(&r), grid_coord(&r))
                                              : random_point(&r, 1.0f);
        s->center[i] = vadd(s->center[i], v3(offset, offset, offset));
        s->radius[i] = 0.02f * powf(15.0f, rng_uniform(&r));   /* 0.02 .. 0.3 */
    }
}

static void free_soup(soup *s)
{
    free(s->v); free(s->degenerate); free(s->center); free(s->radius);
    memset(s, 0, sizeof *s);
}

/* A scene holding the soup, built with the given build desc (NULL: defaults). */
static fogrt_scene *soup_scene(const soup *s, const fogrt_build_desc *bd)
{
    fogrt_scene *scene = NULL;
    fogrt_material_desc m;
    fogrt_mesh_desc mesh;
    uint32_t id, i;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_create(NULL, &scene));
    memset(&m, 0, sizeof m);
    m.reflectance = v3(0.5f, 0.5f, 0.5f);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_material(scene, &m, &id));
    if (s->tri_count > 0) {
        memset(&mesh, 0, sizeof mesh);
        mesh.positions = &s->v[0].x;              /* fogrt_vec3 is 3 packed floats */
        mesh.vertex_count = 3 * s->tri_count;
        mesh.triangle_count = s->tri_count;
        mesh.material = id;
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_mesh(scene, &mesh));
    }
    for (i = 0; i < s->sphere_count; i++)
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_sphere(scene, s->center[i], s->radius[i], id));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, bd));
    return scene;
}

/* ------------------------------------------------------------------------------------------
   Rays, in eight families
   ------------------------------------------------------------------------------------------ */
typedef struct test_ray { fogrt_vec3 o, d; float tmin, tmax; int family; } test_ray;

static const char *family_name[8] = {
    "random", "aimed at a triangle", "axis-parallel (+-0)", "origin on a vertex",
    "origin on a triangle", "inside a triangle's plane", "aimed at a vertex or edge",
    "one zero component (+-0)"
};

/* A signed zero: +0 or -0 at random. */
static float signed_zero(test_rng *r) { return rng_uniform(r) < 0.5f ? 0.0f : -0.0f; }

static fogrt_vec3 point_on_triangle(test_rng *r, const fogrt_vec3 *t)
{
    float b1 = rng_uniform(r), b2 = rng_uniform(r);
    if (b1 + b2 > 1.0f) { b1 = 1.0f - b1; b2 = 1.0f - b2; }
    return vadd(t[0], vadd(vscale(vsub(t[1], t[0]), b1), vscale(vsub(t[2], t[0]), b2)));
}

static void make_ray(test_rng *r, const soup *s, float offset, int family, test_ray *ray)
{
    const fogrt_vec3 *t = s->tri_count ? &s->v[3 * rng_below(r, s->tri_count)] : NULL;
    fogrt_vec3 shift = v3(offset, offset, offset);
    /* Aimed rays (families 1 and 6) go for a sphere in proportion to the sphere count. */
    if ((family == 1 || family == 6) && s->sphere_count > 0 &&
        rng_below(r, s->tri_count + s->sphere_count) >= s->tri_count) {
        uint32_t k = rng_below(r, s->sphere_count);
        fogrt_vec3 target = vadd(s->center[k], random_point(r, 0.5f * s->radius[k]));
        ray->family = family;
        ray->tmin = 0.0f;
        ray->tmax = INFINITY;
        ray->o = vadd(vscale(random_direction(r), 3.0f), shift);
        ray->d = vnorm(vsub(target, ray->o));
        return;
    }
    if (t == NULL && (family == 1 || (family >= 3 && family <= 6))) family = 0;
    ray->family = family;
    ray->tmin = 0.0f;
    ray->tmax = INFINITY;
    switch (family) {
    case 0:
        ray->o = vadd(random_point(r, 1.5f), shift);
        ray->d = random_direction(r);
        break;
    case 1:
        ray->o = vadd(vscale(random_direction(r), 3.0f), shift);
        ray->d = vnorm(vsub(point_on_triangle(r, t), ray->o));
        break;
    case 2: {
        int axis = (int)rng_below(r, 3);
        ray->o = rng_uniform(r) < 0.5f ? v3(grid_coord(r), grid_coord(r), grid_coord(r)) : random_point(r, 1.5f);
        ray->o = vadd(ray->o, shift);
        ray->d = v3(signed_zero(r), signed_zero(r), signed_zero(r));
        vset(&ray->d, axis, rng_uniform(r) < 0.5f ? 1.0f : -1.0f);
        if (rng_uniform(r) < 0.3f) vset(&ray->o, axis, vcomp(ray->o, axis) - 2.0f * vcomp(ray->d, axis));
        break;
    }
    case 3:
        ray->o = t[rng_below(r, 3)];
        ray->d = random_direction(r);
        break;
    case 4:
        ray->o = point_on_triangle(r, t);
        ray->d = random_direction(r);
        break;
    case 5: {   /* o and d both in the plane spanned by the triangle's edges */
        fogrt_vec3 e1 = vsub(t[1], t[0]), e2 = vsub(t[2], t[0]);
        fogrt_vec3 dir = vadd(vscale(e1, rng_range(r, -1, 1)), vscale(e2, rng_range(r, -1, 1)));
        ray->o = vadd(t[0], vadd(vscale(e1, rng_range(r, -1, 2)), vscale(e2, rng_range(r, -1, 2))));
        if (vdot(dir, dir) < 1e-12f) dir = e1;
        if (vdot(dir, dir) < 1e-12f) dir = v3(1, 0, 0);
        ray->d = vnorm(dir);
        break;
    }
    case 6: {
        int k = (int)rng_below(r, 3);
        fogrt_vec3 target = rng_uniform(r) < 0.5f ? t[k] : vscale(vadd(t[k], t[(k + 1) % 3]), 0.5f);
        ray->o = rng_uniform(r) < 0.5f ? vadd(random_point(r, 2.0f), shift)
                                       : vadd(v3(grid_coord(r), grid_coord(r), grid_coord(r)), shift);
        if (vdot(vsub(target, ray->o), vsub(target, ray->o)) < 1e-8f) ray->o = vadd(ray->o, v3(0.5f, 0, 0));
        ray->d = vnorm(vsub(target, ray->o));
        break;
    }
    default: {
        int axis = (int)rng_below(r, 3);
        ray->o = vadd(v3(grid_coord(r), grid_coord(r), grid_coord(r)), shift);
        ray->d = random_direction(r);
        vset(&ray->d, axis, signed_zero(r));
        if (vdot(ray->d, ray->d) < 1e-6f) vset(&ray->d, (axis + 1) % 3, 1.0f);
        ray->d = vnorm(ray->d);
        vset(&ray->d, axis, signed_zero(r));   /* normalising keeps the zero, but keep its sign random */
        break;
    }
    }
    /* Some rays get a finite segment, some a small positive tmin. */
    if (rng_below(r, 4) == 0) ray->tmax = rng_range(r, 0.0f, 3.0f);
    if (family != 3 && family != 4 && rng_below(r, 8) == 0) ray->tmin = 1e-4f;
}

/* ------------------------------------------------------------------------------------------
   Comparing answers
   ------------------------------------------------------------------------------------------ */
typedef struct answer { bool hit; fogrt_hit h; } answer;

/* Two closest-hit answers agree when both miss, or both hit the same primitive at the same
   t, or hit two different primitives at the same t (a tie, e.g. on a shared edge). */
static float tie_tolerance(float t) { return 2e-6f * (t > 1.0f ? t : 1.0f); }

static void describe_ray(char *buf, size_t n, const test_ray *ray, int index, const char *what)
{
    snprintf(buf, n, "%s: ray %d (%s) o=(%.9g, %.9g, %.9g) d=(%.9g, %.9g, %.9g) tmin=%g tmax=%g",
             what, index, family_name[ray->family], ray->o.x, ray->o.y, ray->o.z,
             ray->d.x, ray->d.y, ray->d.z, ray->tmin, ray->tmax);
}

static void assert_same_answer(const answer *want, const answer *got, const test_ray *ray, int index,
                               const char *what)
{
    char msg[512], details[700];
    describe_ray(msg, sizeof msg, ray, index, what);
    if (want->hit != got->hit) {
        snprintf(details, sizeof details, "%s: reference %s (prim %u t=%.9g), BVH %s (prim %u t=%.9g)", msg,
                 want->hit ? "hits" : "misses", want->hit ? want->h.prim : 0u, want->hit ? want->h.t : 0.0f,
                 got->hit ? "hits" : "misses", got->hit ? got->h.prim : 0u, got->hit ? got->h.t : 0.0f);
        TEST_FAIL_MESSAGE(details);
    }
    if (!want->hit) return;
    snprintf(details, sizeof details, "%s: reference prim %u t=%.9g, BVH prim %u t=%.9g", msg,
             want->h.prim, want->h.t, got->h.prim, got->h.t);
    TEST_ASSERT_FLOAT_WITHIN_MESSAGE(tie_tolerance(want->h.t), want->h.t, got->h.t, details);
    if (want->h.prim == got->h.prim) {
        TEST_ASSERT_FLOAT_WITHIN_MESSAGE(1e-5f, want->h.u, got->h.u, details);
        TEST_ASSERT_FLOAT_WITHIN_MESSAGE(1e-5f, want->h.v, got->h.v, details);
    }
}

/* Checks one BVH against precomputed reference answers: closest hit, the hit's own
   consistency (t in range, not a degenerate triangle), and that occlusion agrees. */
static void check_rays(const fogrt_scene *scene, const soup *s, const test_ray *rays,
                       const answer *reference, int ray_count, const char *what)
{
    int i;
    uint32_t prim_total = s->tri_count + s->sphere_count;
    for (i = 0; i < ray_count; i++) {
        const test_ray *ray = &rays[i];
        answer got;
        char msg[512];
        memset(&got, 0, sizeof got);
        got.hit = fogrt_scene_intersect(scene, ray->o, ray->d, ray->tmin, ray->tmax, &got.h);
        assert_same_answer(&reference[i], &got, ray, i, what);
        describe_ray(msg, sizeof msg, ray, i, what);
        if (got.hit) {
            TEST_ASSERT_TRUE_MESSAGE(got.h.t > ray->tmin && got.h.t < ray->tmax, msg);
            TEST_ASSERT_TRUE_MESSAGE(got.h.prim < prim_total, msg);
            TEST_ASSERT_FALSE_MESSAGE(got.h.prim < s->tri_count && s->degenerate[got.h.prim],
                                      "a degenerate triangle was hit");
            /* Nothing lies before the closest hit (beyond a tie's rounding: a box entered
               exactly at a vertex may round its entry distance past a tied hit); something
               lies just after it. "Just after" is 1e-4 t: Moller-Trumbore's t on a sliver
               triangle can be off by a few 1e-6 t (the box test is exact), so a tmax closer
               than that to the hit may legitimately cull the hit's box. */
            TEST_ASSERT_FALSE_MESSAGE(fogrt_scene_occluded(scene, ray->o, ray->d, ray->tmin,
                                                           got.h.t - tie_tolerance(got.h.t)), msg);
            TEST_ASSERT_TRUE_MESSAGE(fogrt_scene_occluded(scene, ray->o, ray->d, ray->tmin,
                                                          got.h.t * (1.0f + 1e-4f) + 1e-6f), msg);
        }
        TEST_ASSERT_EQUAL_INT_MESSAGE(got.hit, fogrt_scene_occluded(scene, ray->o, ray->d, ray->tmin, ray->tmax), msg);
    }
}

static void reference_answers(const fogrt_scene *scene, const soup *s, const test_ray *rays,
                              answer *reference, int ray_count, int *hits)
{
    int i;
    *hits = 0;
    for (i = 0; i < ray_count; i++) {
        memset(&reference[i], 0, sizeof reference[i]);
        reference[i].hit = fogrt_scene_intersect_brute(scene, rays[i].o, rays[i].d, rays[i].tmin,
                                                       rays[i].tmax, &reference[i].h);
        if (reference[i].hit) {
            (*hits)++;
            TEST_ASSERT_FALSE_MESSAGE(reference[i].h.prim < s->tri_count && s->degenerate[reference[i].h.prim],
                                      "brute force hit a degenerate triangle");
        }
    }
}

static test_ray *make_rays(const soup *s, uint64_t seed, int ray_count, float offset)
{
    test_rng r;
    int i;
    test_ray *rays = (test_ray *)malloc(sizeof(test_ray) * (size_t)ray_count);
    TEST_ASSERT_NOT_NULL(rays);
    r.s = seed * 7919u + 17u;
    for (i = 0; i < ray_count; i++) make_ray(&r, s, offset, i % 8, &rays[i]);
    return rays;
}

/* ------------------------------------------------------------------------------------------
   Tree invariants
   ------------------------------------------------------------------------------------------ */
typedef struct tree_stats { uint32_t reached, leaves, max_depth, max_leaf; } tree_stats;

static int box_contains_point(const fogrt_bvh_node *n, fogrt_vec3 p)
{
    return n->bmin[0] <= p.x && p.x <= n->bmax[0] && n->bmin[1] <= p.y && p.y <= n->bmax[1] &&
           n->bmin[2] <= p.z && p.z <= n->bmax[2];
}

static int same_centroids(const soup *s, const uint32_t *prims, uint32_t count)
{
    fogrt_vec3 c0 = v3(0, 0, 0);
    uint32_t i;
    for (i = 0; i < count; i++) {
        uint32_t p = prims[i];
        fogrt_vec3 c;
        if (p < s->tri_count) {
            const fogrt_vec3 *t = &s->v[3 * p];
            fogrt_vec3 lo = t[0], hi = t[0];
            int k, a;
            for (k = 1; k < 3; k++)
                for (a = 0; a < 3; a++) {
                    if (vcomp(t[k], a) < vcomp(lo, a)) vset(&lo, a, vcomp(t[k], a));
                    if (vcomp(t[k], a) > vcomp(hi, a)) vset(&hi, a, vcomp(t[k], a));
                }
            c = vscale(vadd(lo, hi), 0.5f);
        } else {
            c = s->center[p - s->tri_count];
        }
        if (i == 0) c0 = c;
        else if (fabsf(c.x - c0.x) > 1e-6f || fabsf(c.y - c0.y) > 1e-6f || fabsf(c.z - c0.z) > 1e-6f) return 0;
    }
    return 1;
}

/* Whether the build may cut triangle p's box into pieces, several references to it (a long
   sliver, appendix A; the library's own rule). */
static bool sliver(const fogrt_scene *scene, uint32_t p)
{
#ifdef FOGRT_NO_WIDE_BVH
    (void)scene; (void)p;
    return false;
#else
    fogrt__aabb box;
    int axis;
    return p < scene->tri_count && fogrt__split_want(scene, p, &box, &axis) > 1;
#endif
}
/* The references of the tree: its leaves' primitive counts, summed. */
static uint32_t tree_refs(const fogrt_bvh_node *nodes, uint32_t node_count)
{
    uint32_t i, refs = 0;
    for (i = 0; i < node_count; i++) if (i != 1) refs += nodes[i].prim_count;
    return refs;
}
/* Walks the tree from the root: every reachable node once, node 1 never, children inside
   their parent, leaves holding their primitives' bounds, every primitive in exactly one
   leaf (a long sliver may be in several, each vertex then in one of their boxes), leaves no
   bigger than max_leaf_size (unless their primitives cannot be separated). */
static void check_tree(const fogrt_scene *scene, const soup *s, uint32_t max_leaf, tree_stats *st,
                       const char *what)
{
    const fogrt_bvh_node *nodes = NULL;
    const uint32_t *prim_index = NULL;
    uint32_t node_count = 0, prim_total = s->tri_count + s->sphere_count, i, k, refs;
    uint32_t *stack, *depth, sp = 0;
    unsigned char *visited, *seen, *corners;
    fogrt_scene_info info;
    char msg[256];
    fogrt_scene_get_bvh(scene, &nodes, &node_count, &prim_index);
    TEST_ASSERT_NOT_NULL_MESSAGE(nodes, what);
    TEST_ASSERT_NOT_NULL_MESSAGE(prim_index, what);
    TEST_ASSERT_GREATER_OR_EQUAL_MESSAGE(1, node_count, what);
    memset(st, 0, sizeof *st);
    refs = tree_refs(nodes, node_count);
    TEST_ASSERT_GREATER_OR_EQUAL_MESSAGE(prim_total, refs, what);
    visited = (unsigned char *)calloc(node_count + 1, 1);
    seen = (unsigned char *)calloc(prim_total + 1, 1);
    corners = (unsigned char *)calloc(prim_total + 1, 1);
    stack = (uint32_t *)malloc(sizeof(uint32_t) * (node_count + 2));
    depth = (uint32_t *)malloc(sizeof(uint32_t) * (node_count + 2));
    TEST_ASSERT_TRUE(visited && seen && corners && stack && depth);

    /* The root's bounds are the scene's bounds. */
    fogrt_scene_get_info(scene, &info);
    TEST_ASSERT_EQUAL_FLOAT_MESSAGE(info.bounds_min.x, nodes[0].bmin[0], what);
    TEST_ASSERT_EQUAL_FLOAT_MESSAGE(info.bounds_min.y, nodes[0].bmin[1], what);
    TEST_ASSERT_EQUAL_FLOAT_MESSAGE(info.bounds_min.z, nodes[0].bmin[2], what);
    TEST_ASSERT_EQUAL_FLOAT_MESSAGE(info.bounds_max.x, nodes[0].bmax[0], what);
    TEST_ASSERT_EQUAL_FLOAT_MESSAGE(info.bounds_max.y, nodes[0].bmax[1], what);
    TEST_ASSERT_EQUAL_FLOAT_MESSAGE(info.bounds_max.z, nodes[0].bmax[2], what);

    stack[sp] = 0; depth[sp++] = 0;
    while (sp > 0) {
        uint32_t ni = stack[--sp], level = depth[sp];
        const fogrt_bvh_node *n = &nodes[ni];
        snprintf(msg, sizeof msg, "%s: node %u", what, ni);
        TEST_ASSERT_LESS_THAN_MESSAGE(node_count, ni, msg);
        TEST_ASSERT_FALSE_MESSAGE(visited[ni], "a node is reached twice");
        TEST_ASSERT_TRUE_MESSAGE(ni != 1, "node 1 is in use");
        visited[ni] = 1;
        st->reached++;
        if (level > st->max_depth) st->max_depth = level;
        for (k = 0; k < 3; k++) TEST_ASSERT_TRUE_MESSAGE(n->bmin[k] <= n->bmax[k], msg);
        if (n->prim_count > 0) {                                 /* a leaf */
            st->leaves++;
            if (n->prim_count > st->max_leaf) st->max_leaf = n->prim_count;
            TEST_ASSERT_TRUE_MESSAGE((uint64_t)n->left_first + n->prim_count <= refs, msg);
            if (n->prim_count > max_leaf) {
                snprintf(msg, sizeof msg, "%s: leaf %u holds %u primitives, max_leaf_size %u",
                         what, ni, n->prim_count, max_leaf);
                TEST_ASSERT_TRUE_MESSAGE(same_centroids(s, &prim_index[n->left_first], n->prim_count), msg);
            }
            for (i = n->left_first; i < n->left_first + n->prim_count; i++) {
                uint32_t p = prim_index[i];
                TEST_ASSERT_LESS_THAN_MESSAGE(prim_total, p, msg);
                TEST_ASSERT_FALSE_MESSAGE(seen[p] && !sliver(scene, p), "a primitive is in two leaves");
                seen[p] = 1;
                if (p < s->tri_count) {
                    for (k = 0; k < 3; k++) if (box_contains_point(n, s->v[3 * p + k])) corners[p] |= (unsigned char)(1u << k);
                    TEST_ASSERT_TRUE_MESSAGE(corners[p] == 7 || sliver(scene, p), "leaf box misses a vertex");
                } else {
                    fogrt_vec3 c = s->center[p - s->tri_count];
                    float r = s->radius[p - s->tri_count];
                    TEST_ASSERT_TRUE_MESSAGE(box_contains_point(n, v3(c.x - r, c.y - r, c.z - r)) &&
                                             box_contains_point(n, v3(c.x + r, c.y + r, c.z + r)),
                                             "leaf box misses a sphere");
                }
            }
        } else {                                                 /* an inner node */
            uint32_t c = n->left_first;
            TEST_ASSERT_TRUE_MESSAGE(c >= 2 && c % 2 == 0, "children do not start on an even index >= 2");
            TEST_ASSERT_LESS_THAN_MESSAGE(node_count, c + 1, msg);
            for (k = 0; k < 2; k++) {
                const fogrt_bvh_node *child = &nodes[c + k];
                int a;
                for (a = 0; a < 3; a++)
                    TEST_ASSERT_TRUE_MESSAGE(child->bmin[a] >= n->bmin[a] && child->bmax[a] <= n->bmax[a],
                                             "child bounds outside the parent");
                stack[sp] = c + k; depth[sp++] = level + 1;
            }
        }
    }
    for (i = 0; i < prim_total; i++) {
        snprintf(msg, sizeof msg, "%s: primitive %u is in no leaf", what, i);
        TEST_ASSERT_TRUE_MESSAGE(seen[i], msg);
        snprintf(msg, sizeof msg, "%s: a vertex of sliver %u is in none of its leaves' boxes", what, i);
        TEST_ASSERT_TRUE_MESSAGE(i >= s->tri_count || corners[i] == 7, msg);
    }
    /* Every node but node 1 is used: no leaked nodes. */
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(node_count > 1 ? node_count - 1 : node_count, st->reached, what);
    free(visited); free(seen); free(corners); free(stack); free(depth);
}

/* ------------------------------------------------------------------------------------------
   The tests
   ------------------------------------------------------------------------------------------ */

/* Moller-Trumbore on its own: a known hit (t, u, v), both sides, misses beside the triangle,
   in its plane and on a degenerate triangle, and the open interval (tmin, tmax). */
static void test_intersect_triangle(void)
{
    fogrt_vec3 v0 = v3(0, 0, 0), v1 = v3(1, 0, 0), v2 = v3(0, 1, 0);
    float t = -1, u = -1, v = -1;
    TEST_ASSERT_TRUE(fogrt_intersect_triangle(v0, v1, v2, v3(0.25f, 0.5f, 2), v3(0, 0, -1), 0, INFINITY, &t, &u, &v));
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 2.0f, t);
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.25f, u);
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.5f, v);
    /* From behind (surfaces are hit from both sides). */
    TEST_ASSERT_TRUE(fogrt_intersect_triangle(v0, v1, v2, v3(0.25f, 0.25f, -1), v3(0, 0, 1), 0, INFINITY, &t, &u, &v));
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 1.0f, t);
    /* Beside it; pointing away; in its plane; outside (tmin, tmax). */
    TEST_ASSERT_FALSE(fogrt_intersect_triangle(v0, v1, v2, v3(0.75f, 0.75f, 2), v3(0, 0, -1), 0, INFINITY, &t, &u, &v));
    TEST_ASSERT_FALSE(fogrt_intersect_triangle(v0, v1, v2, v3(0.25f, 0.25f, 2), v3(0, 0, 1), 0, INFINITY, &t, &u, &v));
    TEST_ASSERT_FALSE(fogrt_intersect_triangle(v0, v1, v2, v3(-1, 0.25f, 0), v3(1, 0, 0), 0, INFINITY, &t, &u, &v));
    TEST_ASSERT_FALSE(fogrt_intersect_triangle(v0, v1, v2, v3(0.25f, 0.25f, 2), v3(0, 0, -1), 0, 2.0f, &t, &u, &v));
    TEST_ASSERT_FALSE(fogrt_intersect_triangle(v0, v1, v2, v3(0.25f, 0.25f, 2), v3(0, 0, -1), 2.0f, INFINITY, &t, &u, &v));
    TEST_ASSERT_TRUE(fogrt_intersect_triangle(v0, v1, v2, v3(0.25f, 0.25f, 2), v3(0, 0, -1), 1.999f, 2.001f, &t, &u, &v));
    /* Degenerate: a line and a point are never hit, even dead on. */
    TEST_ASSERT_FALSE(fogrt_intersect_triangle(v0, v1, v3(2, 0, 0), v3(0.5f, 0, 2), v3(0, 0, -1), 0, INFINITY, &t, &u, &v));
    TEST_ASSERT_FALSE(fogrt_intersect_triangle(v0, v0, v0, v3(0, 0, 2), v3(0, 0, -1), 0, INFINITY, &t, &u, &v));
    /* A ray lying in the triangle's plane (up to rounding), passing 2.7 units from it: the
       determinant is rounding noise (-7.5e-9 for edges of length ~1) and dividing by it
       must not produce a hit far outside the triangle (a case from the soup test below). */
    {
        fogrt_vec3 a = v3(0.573809505f, 0.543248653f, -0.368106663f);
        fogrt_vec3 b = v3(-0.385244191f, 0.546278358f, -0.599250436f);
        fogrt_vec3 c = v3(-0.302871883f, 0.133899331f, -0.149217248f);
        fogrt_vec3 o = v3(-2.14673853f, 0.0619520247f, -0.512431264f);
        fogrt_vec3 d = v3(-0.97221595f, -0.233732015f, 0.01286548f);
        char msg[128];
        bool h = fogrt_intersect_triangle(a, b, c, o, d, 0, INFINITY, &t, &u, &v);
        snprintf(msg, sizeof msg, "in-plane ray reported a hit at t=%g, point (%g, %g, %g)", t,
                 o.x + t * d.x, o.y + t * d.y, o.z + t * d.z);
        TEST_ASSERT_FALSE_MESSAGE(h, msg);
    }
}

/* A ray with a +0 or -0 direction component whose origin lies exactly on a face of a box
   (here the flat box of one triangle in z = 0) runs inside that slab for all t: the BVH
   must not cull the box (brute force finds the hit on the triangle's edge). */
static void test_origin_on_box_face(void)
{
    soup s;
    fogrt_scene *scene;
    static const struct { fogrt_vec3 o, d; } rays[] = {
        { { 0.0f, 0.5f, 1.0f }, { -0.0f, 0.0f, -1.0f } },   /* o.x on bmin.x, d.x = -0 */
        { { 0.0f, 0.5f, 1.0f }, { 0.0f, 0.0f, -1.0f } },    /* o.x on bmin.x, d.x = +0 */
        { { 0.5f, 0.0f, 1.0f }, { 0.0f, -0.0f, -1.0f } },   /* o.y on bmin.y, d.y = -0 */
        { { 1.0f, 0.0f, 1.0f }, { 0.0f, 0.0f, -1.0f } },    /* o.x on bmax.x, d.x = +0 (a vertex) */
        { { 0.5f, 0.5f, 1.0f }, { 0.0f, 0.0f, -1.0f } },    /* inside the slabs: the control */
    };
    size_t k;
    memset(&s, 0, sizeof s);
    s.tri_count = 1;
    s.v = (fogrt_vec3 *)calloc(3, sizeof(fogrt_vec3));
    s.degenerate = (unsigned char *)calloc(1, 1);
    s.v[0] = v3(0, 0, 0); s.v[1] = v3(1, 0, 0); s.v[2] = v3(0, 1, 0);
    scene = soup_scene(&s, NULL);
    for (k = 0; k < sizeof rays / sizeof rays[0]; k++) {
        fogrt_hit h;
        char msg[160];
        snprintf(msg, sizeof msg, "o=(%g, %g, %g) d=(%g, %g, %g)", rays[k].o.x, rays[k].o.y, rays[k].o.z,
                 rays[k].d.x, rays[k].d.y, rays[k].d.z);
        TEST_ASSERT_TRUE_MESSAGE(fogrt_scene_intersect_brute(scene, rays[k].o, rays[k].d, 0, INFINITY, &h), msg);
        TEST_ASSERT_TRUE_MESSAGE(fogrt_scene_intersect(scene, rays[k].o, rays[k].d, 0, INFINITY, &h), msg);
        TEST_ASSERT_TRUE_MESSAGE(fogrt_scene_occluded(scene, rays[k].o, rays[k].d, 0, INFINITY), msg);
    }
    fogrt_scene_destroy(scene);
    free_soup(&s);
}

/* Ray-sphere: near root from outside, far root from inside, tangent-free misses, tmax. */
static void test_intersect_sphere(void)
{
    float t = -1;
    TEST_ASSERT_TRUE(fogrt_intersect_sphere(v3(0, 0, 0), 1.0f, v3(0, 0, 5), v3(0, 0, -1), 0, INFINITY, &t));
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 4.0f, t);
    TEST_ASSERT_TRUE(fogrt_intersect_sphere(v3(0, 0, 0), 1.0f, v3(0, 0, 0.5f), v3(0, 0, -1), 0, INFINITY, &t));
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 1.5f, t);
    TEST_ASSERT_TRUE(fogrt_intersect_sphere(v3(0, 0, 0), 1.0f, v3(0, 0, 5), v3(0, 0, -1), 4.5f, INFINITY, &t));
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 6.0f, t);
    TEST_ASSERT_FALSE(fogrt_intersect_sphere(v3(0, 0, 0), 1.0f, v3(0, 0, 5), v3(0, 0, 1), 0, INFINITY, &t));
    TEST_ASSERT_FALSE(fogrt_intersect_sphere(v3(0, 0, 0), 1.0f, v3(0, 1.01f, 5), v3(0, 0, -1), 0, INFINITY, &t));
    TEST_ASSERT_FALSE(fogrt_intersect_sphere(v3(0, 0, 0), 1.0f, v3(0, 0, 5), v3(0, 0, -1), 0, 3.9f, &t));
    /* A small sphere far away: the near root must not be lost to cancellation. */
    TEST_ASSERT_TRUE(fogrt_intersect_sphere(v3(0, 0, 0), 0.01f, v3(0, 0, 1000), v3(0, 0, -1), 0, INFINITY, &t));
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 999.99f, t);
}

/* The core check: on soups of several seeds and sizes (with spheres, and one far from the
   origin), the BVH answers every ray as brute force does. Fails on any slab test that drops
   a box it should enter (0 * inf = NaN on +-0 directions, origins on a face, flat boxes). */
static void test_bvh_matches_brute_force(void)
{
    static const struct { uint64_t seed; uint32_t tris, spheres; float offset; int rays; } cases[] = {
        { 1, 1, 0, 0.0f, 400 },     { 2, 7, 0, 0.0f, 1600 },    { 3, 0, 9, 0.0f, 1600 },
        { 4, 64, 8, 0.0f, 4000 },   { 5, 500, 0, 0.0f, 4000 },  { 6, 400, 100, 0.0f, 4000 },
        { 7, 2000, 50, 0.0f, 3000 }, { 8, 300, 30, 100.0f, 3000 },
    };
    size_t c;
    for (c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        soup s;
        fogrt_scene *scene;
        test_ray *rays;
        answer *reference;
        int hits, family_hits[8] = { 0 }, i;
        char what[256];
        make_soup(&s, cases[c].seed, cases[c].tris, cases[c].spheres, cases[c].offset);
        scene = soup_scene(&s, NULL);
        rays = make_rays(&s, cases[c].seed, cases[c].rays, cases[c].offset);
        reference = (answer *)malloc(sizeof(answer) * (size_t)cases[c].rays);
        TEST_ASSERT_NOT_NULL(reference);
        reference_answers(scene, &s, rays, reference, cases[c].rays, &hits);
        for (i = 0; i < cases[c].rays; i++) family_hits[rays[i].family] += reference[i].hit;
        snprintf(what, sizeof what, "soup seed %u (%u triangles, %u spheres, offset %g)",
                 (unsigned)cases[c].seed, cases[c].tris, cases[c].spheres, cases[c].offset);
        check_rays(scene, &s, rays, reference, cases[c].rays, what);
        /* A test where no ray hits checks nothing: each soup must see plenty of hits. */
        TEST_ASSERT_GREATER_THAN_MESSAGE(cases[c].rays / 10, hits, what);
        if (cases[c].tris >= 64) {
            snprintf(what, sizeof what, "seed %u: %d of %d rays hit; aimed %d, axis-parallel %d, "
                     "on a vertex %d, on a triangle %d, in-plane %d, at an edge %d, one zero %d",
                     (unsigned)cases[c].seed, hits, cases[c].rays, family_hits[1], family_hits[2],
                     family_hits[3], family_hits[4], family_hits[5], family_hits[6], family_hits[7]);
            TEST_MESSAGE(what);
        }
        free(reference); free(rays);
        fogrt_scene_destroy(scene);
        free_soup(&s);
    }
}

/* An axis-aligned box (like the Cornell box walls) seen by rays that run exactly along the
   walls, start exactly on them and on their edges and corners: the flat leaf boxes of a
   scene made of axis-aligned quads are the classic place for a slab test to fail. */
static void test_axis_aligned_box_rays(void)
{
    /* Six faces of the cube [-1,1]^3, two triangles each, plus a grid of small quads on z = 0. */
    soup s;
    fogrt_scene *scene;
    test_ray *rays;
    answer *reference;
    test_rng r;
    int i, hits, ray_count = 6000;
    uint32_t f, q = 0;
    memset(&s, 0, sizeof s);
    s.tri_count = 12 + 2 * 16;
    s.v = (fogrt_vec3 *)calloc(3 * (size_t)s.tri_count, sizeof(fogrt_vec3));
    s.degenerate = (unsigned char *)calloc(s.tri_count, 1);
    for (f = 0; f < 6; f++) {
        int axis = (int)(f / 2), a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
        float side = (f % 2) ? 1.0f : -1.0f;
        fogrt_vec3 corner[4];
        int k;
        for (k = 0; k < 4; k++) {
            corner[k] = v3(0, 0, 0);
            vset(&corner[k], axis, side);
            vset(&corner[k], a1, (k == 1 || k == 2) ? 1.0f : -1.0f);
            vset(&corner[k], a2, (k >= 2) ? 1.0f : -1.0f);
        }
        s.v[3 * q + 0] = corner[0]; s.v[3 * q + 1] = corner[1]; s.v[3 * q + 2] = corner[2]; q++;
        s.v[3 * q + 0] = corner[0]; s.v[3 * q + 1] = corner[2]; s.v[3 * q + 2] = corner[3]; q++;
    }
    for (f = 0; f < 16; f++) {
        float x0 = -1.0f + 0.5f * (float)(f % 4), y0 = -1.0f + 0.5f * (float)(f / 4);
        s.v[3 * q + 0] = v3(x0, y0, 0); s.v[3 * q + 1] = v3(x0 + 0.5f, y0, 0); s.v[3 * q + 2] = v3(x0 + 0.5f, y0 + 0.5f, 0); q++;
        s.v[3 * q + 0] = v3(x0, y0, 0); s.v[3 * q + 1] = v3(x0 + 0.5f, y0 + 0.5f, 0); s.v[3 * q + 2] = v3(x0, y0 + 0.5f, 0); q++;
    }
    scene = soup_scene(&s, NULL);
    rays = (test_ray *)malloc(sizeof(test_ray) * (size_t)ray_count);
    reference = (answer *)malloc(sizeof(answer) * (size_t)ray_count);
    TEST_ASSERT_TRUE(rays && reference);
    r.s = 99;
    for (i = 0; i < ray_count; i++) {
        test_ray *ray = &rays[i];
        int axis = (int)rng_below(&r, 3);
        ray->family = 2;
        ray->tmin = 0.0f;
        ray->tmax = INFINITY;
        /* Origins on the 1/4 grid (on walls, edges, corners and the z = 0 grid lines), some
           just outside the cube; directions axis-parallel or with one or two zero parts. */
        ray->o = v3(grid_coord(&r), grid_coord(&r), grid_coord(&r));
        if (rng_below(&r, 4) == 0) vset(&ray->o, axis, rng_uniform(&r) < 0.5f ? -1.5f : 1.5f);
        if (rng_below(&r, 2) == 0) {
            ray->d = v3(signed_zero(&r), signed_zero(&r), signed_zero(&r));
            vset(&ray->d, axis, rng_uniform(&r) < 0.5f ? 1.0f : -1.0f);
        } else {
            ray->family = 7;
            ray->d = random_direction(&r);
            vset(&ray->d, axis, 0.0f);
            if (vdot(ray->d, ray->d) < 1e-6f) vset(&ray->d, (axis + 1) % 3, 1.0f);
            ray->d = vnorm(ray->d);
            vset(&ray->d, axis, signed_zero(&r));
        }
    }
    reference_answers(scene, &s, rays, reference, ray_count, &hits);
    check_rays(scene, &s, rays, reference, ray_count, "axis-aligned box");
    TEST_ASSERT_GREATER_THAN(ray_count / 4, hits);
    free(rays); free(reference);
    fogrt_scene_destroy(scene);
    free_soup(&s);
}

/* The tree's invariants hold for the default build and for leaf sizes 1, 2, 8 and 16, with
   either heuristic, on soups with and without spheres. */
static void test_tree_structure(void)
{
    static const int leaf_sizes[] = { 4, 1, 2, 8, 16 };
    static const fogrt_bvh_heuristic heuristics[] = { FOGRT_BVH_SAH, FOGRT_BVH_VOLUME };
    soup soups[3];
    size_t a, b, k;
    make_soup(&soups[0], 11, 300, 0, 0.0f);
    make_soup(&soups[1], 12, 200, 60, 0.0f);
    make_soup(&soups[2], 13, 1, 0, 0.0f);
    for (k = 0; k < 3; k++)
        for (a = 0; a < sizeof leaf_sizes / sizeof leaf_sizes[0]; a++)
            for (b = 0; b < 2; b++) {
                fogrt_build_desc bd;
                fogrt_scene *scene;
                tree_stats st;
                char what[128];
                bd = fogrt_build_defaults();
                bd.max_leaf_size = leaf_sizes[a];
                bd.heuristic = heuristics[b];
                scene = soup_scene(&soups[k], &bd);
                snprintf(what, sizeof what, "soup %u, %s, max_leaf_size %d", (unsigned)k,
                         b == 0 ? "SAH" : "volume", leaf_sizes[a]);
                check_tree(scene, &soups[k], leaf_sizes[a] ? (uint32_t)leaf_sizes[a] : 4u, &st, what);
                if (soups[k].tri_count + soups[k].sphere_count > 16)
                    TEST_ASSERT_GREATER_THAN_MESSAGE(1, st.leaves, what);
                fogrt_scene_destroy(scene);
            }
    for (k = 0; k < 3; k++) free_soup(&soups[k]);
}

/* Primitives that cannot be separated (all with the same centroid) and scenes with a single
   primitive, only spheres, or no geometry at all (a light only): the build must still give
   a valid tree, and queries must answer (and not loop) on the empty one. */
static void test_degenerate_scenes(void)
{
    soup s;
    fogrt_scene *scene;
    fogrt_hit hit;
    tree_stats st;
    uint32_t i;
    fogrt_light_desc light;

    /* 40 copies of one triangle, then 40 concentric spheres. */
    memset(&s, 0, sizeof s);
    s.tri_count = 40;
    s.v = (fogrt_vec3 *)calloc(3 * 40, sizeof(fogrt_vec3));
    s.degenerate = (unsigned char *)calloc(40, 1);
    for (i = 0; i < 40; i++) { s.v[3 * i] = v3(0, 0, 0); s.v[3 * i + 1] = v3(1, 0, 0); s.v[3 * i + 2] = v3(0, 1, 0); }
    scene = soup_scene(&s, NULL);
    check_tree(scene, &s, 4, &st, "40 identical triangles");
    TEST_ASSERT_TRUE(fogrt_scene_intersect(scene, v3(0.2f, 0.2f, 1), v3(0, 0, -1), 0, INFINITY, &hit));
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 1.0f, hit.t);
    fogrt_scene_destroy(scene);
    free_soup(&s);

    memset(&s, 0, sizeof s);
    s.sphere_count = 40;
    s.center = (fogrt_vec3 *)calloc(40, sizeof(fogrt_vec3));
    s.radius = (float *)calloc(40, sizeof(float));
    for (i = 0; i < 40; i++) { s.center[i] = v3(1, 2, 3); s.radius[i] = 0.1f + 0.01f * (float)i; }
    scene = soup_scene(&s, NULL);
    check_tree(scene, &s, 4, &st, "40 concentric spheres");
    TEST_ASSERT_TRUE(fogrt_scene_intersect(scene, v3(1, 2, 10), v3(0, 0, -1), 0, INFINITY, &hit));
    TEST_ASSERT_EQUAL_UINT32(39, hit.prim);                 /* the largest sphere is hit first */
    TEST_ASSERT_FLOAT_WITHIN(1e-5f, 7.0f - 0.49f, hit.t);
    fogrt_scene_destroy(scene);
    free_soup(&s);

    /* No geometry: a point light only. */
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_create(NULL, &scene));
    memset(&light, 0, sizeof light);
    light.intensity = v3(1, 1, 1);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_light(scene, &light));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    TEST_ASSERT_FALSE(fogrt_scene_intersect(scene, v3(0, 0, 0), v3(0, 0, 1), 0, INFINITY, &hit));
    TEST_ASSERT_FALSE(fogrt_scene_intersect_brute(scene, v3(0, 0, 0), v3(0, 0, 1), 0, INFINITY, &hit));
    TEST_ASSERT_FALSE(fogrt_scene_occluded(scene, v3(0, 0, 0), v3(0, 0, 1), 0, INFINITY));
    fogrt_scene_destroy(scene);
}

/* The SAH tree and the paper's volume-heuristic tree answer every ray identically, and the
   SAH tree is no more expensive by the SAH cost measure (it minimises that measure; on a
   soup of mixed sizes the volume heuristic, blind to flat boxes, does worse). The binary
   layout: the trees as Part I builds them, without appendix A's pieces of long slivers
   (both trees would cut the same slivers, and the measure would weigh the pieces). */
static void test_sah_vs_volume(void)
{
    static const uint64_t seeds[] = { 21, 22 };
    size_t c;
    for (c = 0; c < 2; c++) {
        soup s;
        fogrt_build_desc bd;
        fogrt_scene *sah, *vol;
        test_ray *rays;
        answer *ref;
        float cost_sah, cost_vol;
        int i, hits = 0, ray_count = 3000;
        char msg[200];
        tree_stats st_sah, st_vol;
        make_soup(&s, seeds[c], 1500, c == 0 ? 0u : 100u, 0.0f);
        bd = fogrt_build_defaults();
        bd.layout = FOGRT_BVH_LAYOUT_BINARY;
        bd.heuristic = FOGRT_BVH_SAH;
        sah = soup_scene(&s, &bd);
        bd.heuristic = FOGRT_BVH_VOLUME;
        vol = soup_scene(&s, &bd);
        check_tree(sah, &s, 4, &st_sah, "SAH");
        check_tree(vol, &s, 4, &st_vol, "volume");
        rays = make_rays(&s, seeds[c], ray_count, 0.0f);
        ref = (answer *)malloc(sizeof(answer) * (size_t)ray_count);
        TEST_ASSERT_NOT_NULL(ref);
        /* The SAH tree's answers are the reference for the volume tree (both were already
           compared with brute force above, this checks them against each other). */
        for (i = 0; i < ray_count; i++) {
            memset(&ref[i], 0, sizeof ref[i]);
            ref[i].hit = fogrt_scene_intersect(sah, rays[i].o, rays[i].d, rays[i].tmin, rays[i].tmax, &ref[i].h);
            hits += ref[i].hit;
        }
        check_rays(vol, &s, rays, ref, ray_count, "volume heuristic vs SAH");
        TEST_ASSERT_GREATER_THAN(ray_count / 10, hits);
        cost_sah = fogrt_bvh_sah_cost(sah);
        cost_vol = fogrt_bvh_sah_cost(vol);
        snprintf(msg, sizeof msg, "seed %u, 1500 triangles%s: SAH cost %.3f (%u leaves, depth %u), "
                 "volume heuristic %.3f (%u leaves, depth %u)", (unsigned)seeds[c],
                 c == 0 ? "" : " + 100 spheres", cost_sah, st_sah.leaves, st_sah.max_depth,
                 cost_vol, st_vol.leaves, st_vol.max_depth);
        TEST_MESSAGE(msg);
        TEST_ASSERT_TRUE_MESSAGE(cost_sah > 0.0f && cost_vol > 0.0f, msg);
        TEST_ASSERT_TRUE_MESSAGE(cost_sah <= cost_vol, msg);
        free(rays); free(ref);
        fogrt_scene_destroy(sah);
        fogrt_scene_destroy(vol);
        free_soup(&s);
    }
}


/* The two layouts answer alike: the binary tree traced as built and the wide tree of chapter
   10b (the default from 16 primitives) give the closest hit that testing every primitive
   gives, on soups with and without spheres, for every ray family, and the default picks the
   binary tree for tiny scenes. Fails if the wide collapse loses a child, a leaf packet drops
   a primitive, or a lane test differs from the binary slab test. */
static void test_layouts_agree(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("A: the wide BVH");
#else
    static const uint32_t tris[3] = { 5, 900, 3000 }, spheres[3] = { 2, 0, 120 };
    static const fogrt_bvh_layout layouts[3] = { FOGRT_BVH_LAYOUT_BINARY, FOGRT_BVH_LAYOUT_WIDE, FOGRT_BVH_LAYOUT_DEFAULT };
    int k, l, hits, ray_count = 2000;
    for (k = 0; k < 3; k++) {
        soup s;
        test_ray *rays;
        answer *ref;
        fogrt_scene *scene;
        make_soup(&s, 200 + (uint64_t)k, tris[k], spheres[k], 0.0f);
        scene = soup_scene(&s, NULL);
        rays = make_rays(&s, 200 + (uint64_t)k, ray_count, 0.0f);
        ref = (answer *)malloc(sizeof(answer) * (size_t)ray_count);
        TEST_ASSERT_NOT_NULL(ref);
        reference_answers(scene, &s, rays, ref, ray_count, &hits);
        TEST_ASSERT_EQUAL_INT((tris[k] + spheres[k]) >= FOGRT_WBVH_MIN_PRIMS, scene->x->wide != NULL);
        fogrt_scene_destroy(scene);
        for (l = 0; l < 3; l++) {
            fogrt_build_desc bd = fogrt_build_defaults();
            char what[96];
            bd.layout = layouts[l];
            scene = soup_scene(&s, &bd);
            snprintf(what, sizeof what, "soup of %u triangles and %u spheres, layout %d", tris[k], spheres[k], (int)layouts[l]);
            TEST_ASSERT_EQUAL_INT_MESSAGE(layouts[l] == FOGRT_BVH_LAYOUT_BINARY ? 0 : (layouts[l] == FOGRT_BVH_LAYOUT_WIDE ? 1 : (tris[k] + spheres[k] >= FOGRT_WBVH_MIN_PRIMS)),
                                          scene->x->wide != NULL, what);
            check_rays(scene, &s, rays, ref, ray_count, what);
            fogrt_scene_destroy(scene);
        }
        free(rays); free(ref);
        free_soup(&s);
    }
#endif
}

/* Every bin count from 2 to 64 (and 0 = the default 8) builds a valid tree that answers as
   brute force does; 65 bins is refused. The SAH cost by bin count is printed. */
static void test_bins_variants(void)
{
    static const int bins[] = { 1, 2, 3, 4, 7, 8, 16, 32, 64 };
    soup s;
    test_ray *rays;
    answer *ref;
    fogrt_scene *scene;
    fogrt_build_desc bd;
    int hits, ray_count = 1500;
    size_t b;
    float cost_2 = 0.0f, cost_64 = 0.0f;
    char line[512];
    size_t len = 0;
    make_soup(&s, 31, 600, 40, 0.0f);
    scene = soup_scene(&s, NULL);
    rays = make_rays(&s, 31, ray_count, 0.0f);
    ref = (answer *)malloc(sizeof(answer) * (size_t)ray_count);
    TEST_ASSERT_NOT_NULL(ref);
    reference_answers(scene, &s, rays, ref, ray_count, &hits);
    TEST_ASSERT_GREATER_THAN(ray_count / 10, hits);
    fogrt_scene_destroy(scene);
    len += (size_t)snprintf(line + len, sizeof line - len, "SAH cost by bins:");
    for (b = 0; b < sizeof bins / sizeof bins[0]; b++) {
        float cost;
        tree_stats st;
        char what[64];
        bd = fogrt_build_defaults();
        bd.bins = bins[b];
        scene = soup_scene(&s, &bd);
        snprintf(what, sizeof what, "bins %d", bins[b]);
        check_tree(scene, &s, 4, &st, what);
        check_rays(scene, &s, rays, ref, ray_count, what);
        cost = fogrt_bvh_sah_cost(scene);
        if (bins[b] == 2) cost_2 = cost;
        if (bins[b] == 64) cost_64 = cost;
        if (len < sizeof line)
            len += (size_t)snprintf(line + len, sizeof line - len, " %d: %.3f", bins[b], cost);
        fogrt_scene_destroy(scene);
    }
    TEST_MESSAGE(line);
    /* A finer sweep sees every plane the 2-bin sweep sees (the middle one) and more, so on a
       soup it must not build a worse tree; a much worse one means bins are mishandled (for
       example an empty bin's box spoiling its neighbours' bounds). */
    TEST_ASSERT_TRUE_MESSAGE(cost_64 <= cost_2, line);
    /* Too many bins is an invalid argument. */
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_create(NULL, &scene));
    {
        fogrt_light_desc light;
        memset(&light, 0, sizeof light);
        light.intensity = v3(1, 1, 1);
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_light(scene, &light));
    }
    bd = fogrt_build_defaults();
    bd.bins = 65;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_INVALID_ARGUMENT, fogrt_scene_build(scene, &bd));
    fogrt_scene_destroy(scene);
    free(rays); free(ref);
    free_soup(&s);
}

#ifndef FOGRT_MINIMAL   /* (with Part I alone there is one split to compare) */
/* Part I's scalar binned split, from tests/bvh_paths.c compiled twice (mk/test_bvh.mk). */
uint32_t bvh_paths_nosimd(const float *tri, uint32_t tri_count, const float *sph, uint32_t sph_count,
                          const fogrt_build_desc *desc, fogrt_bvh_node **nodes, uint32_t **prim_index);
uint32_t bvh_paths_nowide(const float *tri, uint32_t tri_count, const float *sph, uint32_t sph_count,
                          const fogrt_build_desc *desc, fogrt_bvh_node **nodes, uint32_t **prim_index);

/* The spheres of a soup as x, y, z, radius. */
static float *soup_spheres(const soup *s)
{
    float *sph = (float *)malloc(sizeof(float) * 4 * ((size_t)s->sphere_count + 1));
    uint32_t i;
    TEST_ASSERT_NOT_NULL(sph);
    for (i = 0; i < s->sphere_count; i++) {
        sph[4 * i] = s->center[i].x; sph[4 * i + 1] = s->center[i].y; sph[4 * i + 2] = s->center[i].z;
        sph[4 * i + 3] = s->radius[i];
    }
    return sph;
}
/* This program's tree of the soup (the split in SSE lanes) against the other build's,
   node for node (every byte: boxes, with the signs of zeros, links and counts) and in
   primitive order. */
static void compare_split_paths(const soup *s, const fogrt_build_desc *bd, bool nowide, const char *what)
{
    fogrt_scene *scene = soup_scene(s, bd);
    fogrt_bvh_node *nodes = NULL;
    uint32_t *prim_index = NULL, count, i;
    float *sph = soup_spheres(s);
    char msg[256];
    count = (nowide ? bvh_paths_nowide : bvh_paths_nosimd)(&s->v[0].x, s->tri_count, sph, s->sphere_count, bd,
                                                           &nodes, &prim_index);
    snprintf(msg, sizeof msg, "%s against %s: %u nodes, Part I's %u", what,
             nowide ? "FOGRT_NO_WIDE_BVH" : "FOGRT_WBVH_NO_SIMD", scene->node_count, count);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(scene->node_count, count, msg);
    for (i = 0; i < count; i++)
        if (memcmp(&nodes[i], &scene->nodes[i], sizeof nodes[i]) != 0) {
            snprintf(msg + strlen(msg), sizeof msg - strlen(msg), "; node %u differs", i);
            TEST_FAIL_MESSAGE(msg);
        }
    TEST_ASSERT_EQUAL_MEMORY_MESSAGE(prim_index, scene->prim_index,
                                     sizeof(uint32_t) * (s->tri_count + s->sphere_count), msg);
    free(nodes); free(prim_index); free(sph);
    fogrt_scene_destroy(scene);
}
/* Soups of every kind for test_split_paths_agree: make_soup's (flat boxes, the 1/4 grid,
   shared edges, degenerate triangles, spheres); its zeros given random signs (min and max of
   +0 and -0 keep the later one, so the order of the binning shows in a box); every
   centroid at one point; every centroid on a line (two flat axes); and a soup 1e29 times
   as big, whose box areas overflow to infinity. */
static void split_paths_soup(soup *s, int kind)
{
    static const uint32_t tris[6] = { 3000, 2001, 300, 500, 1500, 2 }, spheres[6] = { 120, 0, 7, 0, 40, 1 };
    test_rng r;
    uint32_t i, k;
    make_soup(s, 700 + (uint64_t)kind, tris[kind], spheres[kind], 0.0f);
    r.s = 900 + (uint64_t)kind;
    for (i = 0; i < 3 * s->tri_count; i++) {
        fogrt_vec3 *v = &s->v[i];
        float size = 0.001f * (float)(1 + i / 3 % 13);
        if (kind == 1) for (k = 0; k < 3; k++) if (vcomp(*v, (int)k) == 0.0f) vset(v, (int)k, signed_zero(&r));
        if (kind == 2) *v = v3(0.25f + (i % 3 == 0 ? size : (i % 3 == 1 ? -size : 0.0f)), 0.5f, -0.0f);
        if (kind == 3) *v = v3(vcomp(*v, 0), 0.5f, signed_zero(&r));
        if (kind == 4) *v = vscale(*v, 1e29f);
    }
    for (i = 0; i < s->sphere_count; i++) {
        if (kind == 2) { s->center[i] = v3(0.25f, 0.5f, 0.0f); s->radius[i] = 0.01f * (float)(i + 1); }
        if (kind == 4) { s->center[i] = vscale(s->center[i], 1e29f); s->radius[i] *= 1e29f; }
    }
}
#endif

/* The tree does not depend on the path of the binned split: appendix A's, in SSE lanes
   (this program), and Part I's scalar code (FOGRT_WBVH_NO_SIMD: the same build otherwise;
   FOGRT_NO_WIDE_BVH: no appendix A), give the same nodes, byte for byte, with both
   heuristics, 1 to 64 bins, leaf sizes from 1 to 16, large costs, both layouts (the wide
   one keeps small binary nodes unsplit, seam 2), on every soup of split_paths_soup. */
static void test_split_paths_agree(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("A: the split in SIMD lanes");
#else
    static const struct { fogrt_bvh_heuristic h; int bins, leaf; float c_trav; } v[] = {
        { FOGRT_BVH_SAH, 0, 4, 1.0f }, { FOGRT_BVH_VOLUME, 0, 4, 1.0f }, { FOGRT_BVH_SAH, 1, 4, 1.0f },
        { FOGRT_BVH_VOLUME, 1, 1, 1.0f }, { FOGRT_BVH_SAH, 2, 1, 1.0f }, { FOGRT_BVH_SAH, 3, 2, 1.0f },
        { FOGRT_BVH_SAH, 64, 16, 1.0f }, { FOGRT_BVH_VOLUME, 64, 2, 1.0f }, { FOGRT_BVH_SAH, 16, 8, 40.0f } };
    int kind, j, layout;
    for (kind = 0; kind < 6; kind++) {
        soup s;
        split_paths_soup(&s, kind);
        for (j = 0; j < (int)(sizeof v / sizeof v[0]); j++)
            for (layout = 0; layout < 2; layout++) {
                fogrt_build_desc bd = fogrt_build_defaults();
                char what[128];
                bd.heuristic = v[j].h; bd.max_leaf_size = v[j].leaf; bd.c_trav = v[j].c_trav;
                if (v[j].bins) bd.bins = v[j].bins;
                bd.layout = layout ? FOGRT_BVH_LAYOUT_DEFAULT : FOGRT_BVH_LAYOUT_BINARY;
                bd.roulette_pilot = false;
                snprintf(what, sizeof what, "soup %d (%u triangles, %u spheres), heuristic %d, %d bins, leaves %d, c_trav %g, layout %s",
                         kind, s.tri_count, s.sphere_count, (int)v[j].h, bd.bins, v[j].leaf, (double)v[j].c_trav,
                         layout ? "default" : "binary");
                compare_split_paths(&s, &bd, false, what);
                if (!layout) compare_split_paths(&s, &bd, true, what);
            }
        free_soup(&s);
    }
#endif
}

/* A fan of n slivers around the origin, from the arc of radius 1 between angles 0 and
   span, tilted into the plane z = x: near the shared vertex every box overlaps every other.
   (z = x holds in float exactly, so every sliver lies in the one plane: in a plane the
   rounded vertices leave, a ray at the shared vertex gets a t from each sliver's own tilt,
   up to 1e-3 apart, and the closest of them may sit in a box that starts beyond another.) */
static void make_fan(soup *s, uint32_t n, double span)
{
    uint32_t i;
    memset(s, 0, sizeof *s);
    s->tri_count = n;
    s->v = (fogrt_vec3 *)calloc(3 * (size_t)n + 3, sizeof(fogrt_vec3));
    s->degenerate = (unsigned char *)calloc((size_t)n + 1, 1);
    s->center = (fogrt_vec3 *)calloc(1, sizeof(fogrt_vec3));
    s->radius = (float *)calloc(1, sizeof(float));
    TEST_ASSERT_TRUE(s->v && s->degenerate && s->center && s->radius);
    for (i = 0; i < n; i++) {
        double a0 = span * i / n, a1 = span * (i + 1) / n;
        s->v[3 * i + 1] = v3((float)cos(a0), (float)sin(a0), (float)cos(a0));
        s->v[3 * i + 2] = v3((float)cos(a1), (float)sin(a1), (float)cos(a1));
    }
}
/* The references of a built scene's tree (its binary tree kept). */
static uint32_t scene_refs(const fogrt_scene *scene)
{
    const fogrt_bvh_node *nodes = NULL;
    uint32_t node_count = 0;
    fogrt_scene_get_bvh(scene, &nodes, &node_count, NULL);
    TEST_ASSERT_NOT_NULL(nodes);
    return tree_refs(nodes, node_count);
}
/* Rays at points inside the soup's triangles (2% of the way in from every edge) from
   random origins, and random rays through its box: the scene's answers must be brute
   force's, the same primitive at the same t (a sliver's t is poorly conditioned, up to
   1e-4 off, but computed alike by both), and occlusion must agree. (make_rays aims at
   vertices and edges too: at the shared vertex of a fan every sliver hits, each at its own
   rounded t, and which is closest is decided by rounding.) */
static void check_inside_rays(const fogrt_scene *scene, const soup *s, uint64_t seed, int ray_count, const char *what)
{
    test_rng r;
    int i, hits = 0;
    r.s = seed;
    for (i = 0; i < ray_count; i++) {
        fogrt_vec3 o = random_point(&r, 2.0f), d;
        fogrt_hit a, b;
        bool ha, hb;
        char msg[256];
        if (i % 4 != 3) {
            const fogrt_vec3 *t = &s->v[3 * rng_below(&r, s->tri_count)];
            float b1 = rng_range(&r, 0.02f, 0.96f), b2 = rng_range(&r, 0.02f, 0.98f - b1);
            fogrt_vec3 p = vadd(t[0], vadd(vscale(vsub(t[1], t[0]), b1), vscale(vsub(t[2], t[0]), b2)));
            d = vnorm(vsub(p, o));
        } else {
            d = random_direction(&r);
        }
        memset(&a, 0, sizeof a); memset(&b, 0, sizeof b);
        ha = fogrt_scene_intersect(scene, o, d, 0.0f, INFINITY, &a);
        hb = fogrt_scene_intersect_brute(scene, o, d, 0.0f, INFINITY, &b);
        snprintf(msg, sizeof msg, "%s: ray %d o=(%.9g, %.9g, %.9g) d=(%.9g, %.9g, %.9g): BVH %d prim %u t=%.9g, brute %d prim %u t=%.9g",
                 what, i, o.x, o.y, o.z, d.x, d.y, d.z, ha, a.prim, a.t, hb, b.prim, b.t);
        TEST_ASSERT_TRUE_MESSAGE(ha == hb && (!ha || (a.prim == b.prim && a.t == b.t)), msg);
        TEST_ASSERT_EQUAL_INT_MESSAGE(hb, fogrt_scene_occluded(scene, o, d, 0.0f, INFINITY), msg);
        hits += hb;
    }
    TEST_ASSERT_GREATER_THAN_MESSAGE(ray_count / 2, hits, what);
}

/* Long slivers enter the wide layout's tree as several references with the boxes of their
   parts (appendix A): a fan of 3000 gets one extra reference per sliver (the budget: as many
   as the primitives), the tree keeps its invariants (every vertex of a sliver in one of its
   leaves' boxes), rays at points all along the slivers find what brute force finds (the
   pieces' boxes leave no gap), and the SAH cost falls below
   two thirds of the uncut binary layout's. A lone sliver among well-shaped triangles gets
   all 16 pieces; the well-shaped triangles (a grid) alone are not cut at all. */
static void test_sliver_pieces(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("A: the pieces of long slivers");
#else
    soup s;
    fogrt_scene *scene;
    fogrt_build_desc bd = fogrt_build_defaults();
    tree_stats st;
    float cost_cut, cost_whole;
    uint32_t i, j;
    char msg[160];
    bd.roulette_pilot = false;
    make_fan(&s, 3000, 1.5707963267948966);
    scene = soup_scene(&s, &bd);
    TEST_ASSERT_EQUAL_UINT32(2 * 3000, scene_refs(scene));
    check_tree(scene, &s, 4, &st, "fan of 3000");
    check_inside_rays(scene, &s, 61, 4000, "fan of 3000, cut");
    cost_cut = fogrt_bvh_sah_cost(scene);
    fogrt_scene_destroy(scene);
    bd.layout = FOGRT_BVH_LAYOUT_BINARY;
    scene = soup_scene(&s, &bd);
    TEST_ASSERT_EQUAL_UINT32(3000, scene_refs(scene));
    cost_whole = fogrt_bvh_sah_cost(scene);
    snprintf(msg, sizeof msg, "fan of 3000: SAH cost %.1f cut, %.1f whole", (double)cost_cut, (double)cost_whole);
    TEST_MESSAGE(msg);
    TEST_ASSERT_TRUE_MESSAGE(cost_cut < 0.67f * cost_whole, msg);
    fogrt_scene_destroy(scene);
    free_soup(&s);

    bd.layout = FOGRT_BVH_LAYOUT_DEFAULT;
    make_fan(&s, 2 * 20 * 20 + 1, 1.0);           /* room for a grid of 800 and one sliver */
    for (i = 0; i < 20; i++)
        for (j = 0; j < 20; j++) {
            fogrt_vec3 *t = &s.v[3 * (2 * (20 * i + j))];
            float x = 0.1f * (float)i, y = 0.1f * (float)j;
            t[0] = v3(x, y, x); t[1] = v3(x + 0.1f, y, x + 0.1f); t[2] = v3(x, y + 0.1f, x);
            t[3] = v3(x + 0.1f, y, x + 0.1f); t[4] = v3(x + 0.1f, y + 0.1f, x + 0.1f); t[5] = v3(x, y + 0.1f, x);
        }
    s.tri_count = 800;                             /* the grid: a box is at most 8 times its triangle */
    scene = soup_scene(&s, &bd);
    TEST_ASSERT_EQUAL_UINT32(800, scene_refs(scene));
    fogrt_scene_destroy(scene);
    s.tri_count = 801;                             /* and one sliver above it: 3.5 long, 1e-3 across */
    s.v[3 * 800] = v3(0.0f, 0.0f, 1.0f); s.v[3 * 800 + 1] = v3(2.0f, 2.0f, 3.0f); s.v[3 * 800 + 2] = v3(2.0f, 2.001f, 3.0f);
    scene = soup_scene(&s, &bd);
    TEST_ASSERT_EQUAL_UINT32(800 + 16, scene_refs(scene));
    check_tree(scene, &s, 4, &st, "grid and a sliver");
    check_inside_rays(scene, &s, 62, 2000, "grid and a sliver");
    fogrt_scene_destroy(scene);
    free_soup(&s);
#endif
}

/* fogrt_build_desc.release_binary frees the binary tree once the wide tree is made of it:
   the getters then give no tree, the memory getter at least its nodes and indices less,
   every ray the same answer bit for bit, a rebuild the same again; the binary layout, which
   traces the binary tree, keeps it. */
static void test_release_binary(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("A: the wide tree");
#else
    soup s;
    fogrt_scene *kept, *freed;
    fogrt_build_desc bd = fogrt_build_defaults();
    const fogrt_bvh_node *nodes = NULL;
    const uint32_t *prim_index = NULL;
    uint32_t node_count = 1;
    test_ray *rays;
    int i, rebuild, ray_count = 2000;
    make_soup(&s, 71, 1200, 30, 0.0f);
    bd.roulette_pilot = false;
    kept = soup_scene(&s, &bd);
    bd.release_binary = true;
    freed = soup_scene(&s, &bd);
    rays = make_rays(&s, 71, ray_count, 0.0f);
    for (rebuild = 0; rebuild < 2; rebuild++) {
        fogrt_scene_get_bvh(freed, &nodes, &node_count, &prim_index);
        TEST_ASSERT_NULL(nodes);
        TEST_ASSERT_NULL(prim_index);
        TEST_ASSERT_EQUAL_UINT32(0, node_count);
        TEST_ASSERT_EQUAL_FLOAT(0.0f, fogrt_bvh_sah_cost(freed));
        TEST_ASSERT_TRUE(fogrt_scene_get_memory(kept) - fogrt_scene_get_memory(freed) >=
                         kept->node_count * sizeof(fogrt_bvh_node) + 1230 * sizeof(uint32_t));
        for (i = 0; i < ray_count; i++) {
            fogrt_hit a, b;
            bool ha, hb;
            memset(&a, 0, sizeof a); memset(&b, 0, sizeof b);
            ha = fogrt_scene_intersect(kept, rays[i].o, rays[i].d, rays[i].tmin, rays[i].tmax, &a);
            hb = fogrt_scene_intersect(freed, rays[i].o, rays[i].d, rays[i].tmin, rays[i].tmax, &b);
            TEST_ASSERT_EQUAL_INT(ha, hb);
            TEST_ASSERT_EQUAL_MEMORY(&a, &b, sizeof a);
            TEST_ASSERT_EQUAL_INT(fogrt_scene_occluded(kept, rays[i].o, rays[i].d, rays[i].tmin, rays[i].tmax),
                                  fogrt_scene_occluded(freed, rays[i].o, rays[i].d, rays[i].tmin, rays[i].tmax));
        }
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(freed, &bd));
    }
    fogrt_scene_destroy(freed);
    bd.layout = FOGRT_BVH_LAYOUT_BINARY;
    freed = soup_scene(&s, &bd);
    fogrt_scene_get_bvh(freed, &nodes, &node_count, &prim_index);
    TEST_ASSERT_NOT_NULL(nodes);
    TEST_ASSERT_NOT_NULL(prim_index);
    fogrt_scene_destroy(freed);
    fogrt_scene_destroy(kept);
    free(rays);
    free_soup(&s);
#endif
}

/* Expensive intersections (c_int large) or traversal (c_trav large) change the tree's shape
   but never its answers. */
static void test_cost_parameters(void)
{
    static const float costs[][2] = { { 1.0f, 1.0f }, { 0.1f, 10.0f }, { 10.0f, 0.1f } };
    soup s;
    test_ray *rays;
    answer *ref;
    fogrt_scene *scene;
    int hits, ray_count = 1000;
    size_t c;
    make_soup(&s, 41, 400, 20, 0.0f);
    scene = soup_scene(&s, NULL);
    rays = make_rays(&s, 41, ray_count, 0.0f);
    ref = (answer *)malloc(sizeof(answer) * (size_t)ray_count);
    TEST_ASSERT_NOT_NULL(ref);
    reference_answers(scene, &s, rays, ref, ray_count, &hits);
    fogrt_scene_destroy(scene);
    for (c = 0; c < 3; c++) {
        fogrt_build_desc bd;
        tree_stats st;
        char what[96];
        bd = fogrt_build_defaults();
        bd.c_trav = costs[c][0];
        bd.c_int = costs[c][1];
        bd.max_leaf_size = 16;
        scene = soup_scene(&s, &bd);
        snprintf(what, sizeof what, "c_trav %g c_int %g", costs[c][0], costs[c][1]);
        check_tree(scene, &s, 16, &st, what);
        check_rays(scene, &s, rays, ref, ray_count, what);
        fogrt_scene_destroy(scene);
    }
    free(rays); free(ref);
    free_soup(&s);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_intersect_triangle);
    RUN_TEST(test_intersect_sphere);
    RUN_TEST(test_origin_on_box_face);
    RUN_TEST(test_bvh_matches_brute_force);
    RUN_TEST(test_axis_aligned_box_rays);
    RUN_TEST(test_tree_structure);
    RUN_TEST(test_degenerate_scenes);
    RUN_TEST(test_sah_vs_volume);
    RUN_TEST(test_bins_variants);
    RUN_TEST(test_layouts_agree);
    RUN_TEST(test_cost_parameters);
    RUN_TEST(test_split_paths_agree);
    RUN_TEST(test_sliver_pieces);
    RUN_TEST(test_release_binary);
    return UNITY_END();
}
