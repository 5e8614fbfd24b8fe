/* bench.c - how fast fogrt builds its BVH, traces rays and renders. Run it with `make bench`.

   It prints, all measured in one run so that the ratios compare like with like:
     1. BVH build seconds (median of several builds) of three meshes: (a) the CS184 bunny
        (CBbunny.dae, when fogrt_load.h and ../shared are there, else a displaced sphere of the
        same size, ~28.6k triangles), (b) a displaced sphere of 1M triangles and (c) a fan of
        100,000 slivers around one vertex (bench/fan.h; its primary rays on 128 x 128 pixels);
     2. bytes per triangle of the built scene: fogrt_scene_get_memory with its split
        (geometry, binary BVH, wide BVH, the rest), what fogrt's allocator handed out (after
        the build and at its peak), and Embree's allocations through its memory monitor;
     3. throughput in million rays per second (median of several passes over the same rays),
        on 1 and 2 OpenMP threads, of four ray sets per mesh:
          primary  one camera ray through the centre of every pixel (coherent);
          random   origins uniform in the scene bounds, directions uniform on the sphere
                   (incoherent, the hard case);
          bounce   one cosine-weighted diffuse bounce from every primary hit (incoherent,
                   what a path tracer traces after the first hit);
          shadow   any-hit rays from every primary and every bounce hit toward a point
                   uniform in the scene bounds, tmax = the distance to it (next-event
                   estimation's visibility test);
        closest-hit rays go through fogrt_scene_intersect, shadow rays through
        fogrt_scene_occluded, and, when bench_embree.c is linked (HAVE_EMBREE), through
        Embree 3's rtcIntersect1 / rtcOccluded1 too, with the fogrt/Embree ratio;
     4. samples per second of a full render of the default scene (fogrt_scene_add_default)
        on 1 and 2 threads, and their ratio.
   Before timing, a sample of every ray set is checked against fogrt_scene_intersect_brute
   (and the Embree answers against fogrt's), so a fast but wrong BVH cannot pass unnoticed.

   Usage: bench [--quick] [--fan]   --quick: fewer rays and repetitions (a smoke test, noisy);
                                    --fan: the fan alone                                     */
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#ifdef HAVE_FOGRT_LOAD
#define FOGRT_LOAD_IMPLEMENTATION
#include "fogrt_load.h"
#endif

#include "fan.h"
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#ifndef FOGRT_SHARED_DIR
#define FOGRT_SHARED_DIR "../shared"
#endif
#ifndef BENCH_CFLAGS
#define BENCH_CFLAGS "(unknown flags)"
#endif

#ifdef HAVE_EMBREE
/* bench_embree.c (the same prototypes are defined there). */
typedef struct bench_embree bench_embree;
const char *bench_embree_version(void);
bench_embree *bench_embree_create(const float *positions, uint32_t vertex_count,
                                  const uint32_t *indices, uint32_t triangle_count,
                                  const float *spheres, uint32_t sphere_count,
                                  int build_threads, double *build_seconds);
void bench_embree_trace(const bench_embree *e, const float *rays, size_t ray_count, int threads, bool any_hit,
                        float *t_out, uint32_t *prim_out);
void bench_embree_memory(const bench_embree *e, double *buffers, double *commit_peak, double *commit_final);
void bench_embree_destroy(bench_embree *e);
#endif

/* ------------------------------------------------------------------------------------------
   Small helpers: clock, median, allocation that cannot fail silently
   ------------------------------------------------------------------------------------------ */
static double now_seconds(void)
{
#ifdef _OPENMP
    return omp_get_wtime();
#else
    return (double)clock() / CLOCKS_PER_SEC;   /* one thread: CPU time is wall time */
#endif
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median of n values (sorts them in place). */
static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, compare_doubles);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static void *xmalloc(size_t size)
{
    void *p = malloc(size ? size : 1);
    if (!p) { fprintf(stderr, "bench: out of memory (%zu bytes)\n", size); exit(1); }
    return p;
}

static void check(fogrt_result r, const char *what)
{
    if (r != FOGRT_RESULT_OK) {
        fprintf(stderr, "bench: %s failed: %s\n", what, fogrt_result_string(r));
        exit(1);
    }
}

/* fogrt's scenes allocate through this allocator, which counts the bytes handed out (live
   now, and the most at once since `peak` was last reset). Each block carries its size in a
   header of 16 bytes, which keeps malloc's alignment. */
typedef struct byte_counter { size_t live, peak; } byte_counter;
static byte_counter g_fogrt_bytes;

static void *counted_alloc(size_t size, void *user_data)
{
    byte_counter *c = (byte_counter *)user_data;
    unsigned char *block = (unsigned char *)malloc(size + 16);
    if (!block) return NULL;
    memcpy(block, &size, sizeof size);
    c->live += size;
    if (c->live > c->peak) c->peak = c->live;
    return block + 16;
}

static void counted_free(void *ptr, void *user_data)
{
    byte_counter *c = (byte_counter *)user_data;
    size_t size;
    if (!ptr) return;
    memcpy(&size, (unsigned char *)ptr - 16, sizeof size);
    c->live -= size;
    free((unsigned char *)ptr - 16);
}

/* Is the machine quiet? Other processes running during the benchmark lower every figure.
   The one-thread timings also add up their process CPU time: on a quiet machine it equals
   the wall time; a smaller share means the benchmark waited for a CPU. */
static double g_wall_1t, g_cpu_1t;

static double cpu_seconds(void) { return (double)clock() / CLOCKS_PER_SEC; }

static void print_load_average(const char *when)
{
    FILE *f = fopen("/proc/loadavg", "r");
    double l1 = 0.0;
    if (!f) return;
    if (fscanf(f, "%lf", &l1) == 1) printf("load average (1 min) %s: %.2f\n", when, l1);
    fclose(f);
}

static int max_threads(void)
{
#ifdef _OPENMP
    return omp_get_max_threads();
#else
    return 1;
#endif
}

/* ------------------------------------------------------------------------------------------
   Benchmark geometry: plain arrays (so Embree can get the very same triangles) plus a camera
   ------------------------------------------------------------------------------------------ */
typedef struct bench_geometry {
    char name[64];
    float *positions;          /* 3 per vertex */
    uint32_t vertex_count;
    uint32_t *indices;         /* 3 per triangle */
    uint32_t triangle_count;
    float *spheres;            /* x, y, z, radius per sphere */
    uint32_t sphere_count;
    fogrt_camera_desc camera;
} bench_geometry;

static void geometry_free(bench_geometry *g)
{
    free(g->positions); free(g->indices); free(g->spheres);
    memset(g, 0, sizeof *g);
}

/* A unit sphere with bumps, as a latitude-longitude grid closed by a fan at each pole:
   2 * segments * (rings - 1) triangles. Its triangles are all of similar size, like a scanned
   model's; the bumps make the surface non-convex so that bounce rays hit it again. */
static void make_displaced_sphere(uint32_t rings, uint32_t segments, const char *name, bench_geometry *g)
{
    const float pi = 3.14159265358979f;
    uint32_t j, i, v = 0, t = 0;
    memset(g, 0, sizeof *g);
    snprintf(g->name, sizeof g->name, "%s", name);
    g->vertex_count = 2 + (rings - 1) * segments;
    g->triangle_count = 2 * segments * (rings - 1);
    g->positions = (float *)xmalloc(sizeof(float) * 3 * g->vertex_count);
    g->indices = (uint32_t *)xmalloc(sizeof(uint32_t) * 3 * g->triangle_count);

    /* Vertices: north pole, the rings from north to south, south pole. */
    g->positions[v++] = 0.0f; g->positions[v++] = 1.0f; g->positions[v++] = 0.0f;
    for (j = 1; j < rings; j++) {
        float theta = pi * (float)j / (float)rings;
        for (i = 0; i < segments; i++) {
            float phi = 2.0f * pi * (float)i / (float)segments;
            float r = 1.0f + 0.08f * sinf(9.0f * theta) * cosf(7.0f * phi)
                           + 0.03f * sinf(31.0f * theta + 5.0f * phi);
            g->positions[v++] = r * sinf(theta) * cosf(phi);
            g->positions[v++] = r * cosf(theta);
            g->positions[v++] = r * sinf(theta) * sinf(phi);
        }
    }
    g->positions[v++] = 0.0f; g->positions[v++] = -1.0f; g->positions[v++] = 0.0f;

#define RING_VERTEX(ring, seg) (1u + ((ring) - 1u) * segments + ((seg) % segments))
    /* Triangles: the north fan, quads between neighbouring rings, the south fan. */
    for (i = 0; i < segments; i++) {
        g->indices[t++] = 0; g->indices[t++] = RING_VERTEX(1, i + 1); g->indices[t++] = RING_VERTEX(1, i);
    }
    for (j = 1; j + 1 < rings; j++) {
        for (i = 0; i < segments; i++) {
            uint32_t a = RING_VERTEX(j, i), b = RING_VERTEX(j, i + 1);
            uint32_t c = RING_VERTEX(j + 1, i), d = RING_VERTEX(j + 1, i + 1);
            g->indices[t++] = a; g->indices[t++] = b; g->indices[t++] = d;
            g->indices[t++] = a; g->indices[t++] = d; g->indices[t++] = c;
        }
    }
    for (i = 0; i < segments; i++) {
        g->indices[t++] = g->vertex_count - 1;
        g->indices[t++] = RING_VERTEX(rings - 1, i); g->indices[t++] = RING_VERTEX(rings - 1, i + 1);
    }
#undef RING_VERTEX

    /* A camera 3.2 units away: the sphere fills most of the frame. */
    g->camera.position.x = 0.6f; g->camera.position.y = 0.8f; g->camera.position.z = 3.0f;
    g->camera.fov_deg = 45.0f;
}

/* A fan of n long thin triangles around one vertex (bench/fan.h, tilted against every axis),
   the case that defeats boxes: near the shared vertex every sliver's box overlaps every
   other's. The camera looks at it from 1.8 units along its normal. */
static void make_fan(uint32_t n, const char *name, bench_geometry *g)
{
    uint32_t i;
    memset(g, 0, sizeof *g);
    snprintf(g->name, sizeof g->name, "%s", name);
    g->vertex_count = n + 2;
    g->triangle_count = n;
    g->positions = (float *)xmalloc(sizeof(float) * 3 * g->vertex_count);
    g->indices = (uint32_t *)xmalloc(sizeof(uint32_t) * 3 * g->triangle_count);
    for (i = 0; i < g->vertex_count; i++) fan_vertex(i, n, 0.5 * 3.14159265358979323846, 1, g->positions + 3 * i);
    for (i = 0; i < n; i++) { g->indices[3 * i] = 0; g->indices[3 * i + 1] = i + 1; g->indices[3 * i + 2] = i + 2; }
    g->camera.position.x = -0.28f; g->camera.position.y = -0.28f; g->camera.position.z = 1.9f;
    g->camera.look_at.x = g->camera.look_at.y = g->camera.look_at.z = 0.45f;
    g->camera.up.y = 1.0f;
    g->camera.fov_deg = 60.0f;
}

/* A fresh scene holding the geometry (one diffuse material) and its camera, not yet built. */
static fogrt_scene *geometry_scene(const bench_geometry *g)
{
    fogrt_scene *scene = NULL;
    fogrt_scene_desc sd;
    fogrt_material_desc m;
    uint32_t material = 0, s;
    memset(&sd, 0, sizeof sd);
    sd.allocator.alloc_fn = counted_alloc;
    sd.allocator.free_fn = counted_free;
    sd.allocator.user_data = &g_fogrt_bytes;
    check(fogrt_scene_create(&sd, &scene), "fogrt_scene_create");
    memset(&m, 0, sizeof m);
    m.type = FOGRT_BSDF_DIFFUSE;
    m.reflectance.x = m.reflectance.y = m.reflectance.z = 0.5f;
    check(fogrt_scene_add_material(scene, &m, &material), "fogrt_scene_add_material");
    if (g->triangle_count) {
        fogrt_mesh_desc mesh;
        memset(&mesh, 0, sizeof mesh);
        mesh.positions = g->positions;
        mesh.vertex_count = g->vertex_count;
        mesh.indices = g->indices;
        mesh.triangle_count = g->triangle_count;
        mesh.material = material;
        check(fogrt_scene_add_mesh(scene, &mesh), "fogrt_scene_add_mesh");
    }
    for (s = 0; s < g->sphere_count; s++) {
        const float *sp = g->spheres + 4 * s;
        fogrt_vec3 c;
        c.x = sp[0]; c.y = sp[1]; c.z = sp[2];
        check(fogrt_scene_add_sphere(scene, c, sp[3], material), "fogrt_scene_add_sphere");
    }
    check(fogrt_scene_set_camera(scene, &g->camera), "fogrt_scene_set_camera");
    return scene;
}

#ifdef HAVE_FOGRT_LOAD
/* Copies the triangles (as 3 unshared vertices each, in the scene's order) and spheres of a
   scene. The public API has no triangle read-back, so this reads the scene's private arrays
   (bench.c compiles the implementation, as the tests do). */
static void copy_scene_geometry(const fogrt_scene *scene, bench_geometry *g)
{
    uint32_t i;
    g->triangle_count = scene->tri_count;
    g->vertex_count = 3 * scene->tri_count;
    g->positions = (float *)xmalloc(sizeof(float) * 3 * g->vertex_count);
    g->indices = (uint32_t *)xmalloc(sizeof(uint32_t) * 3 * g->triangle_count);
    for (i = 0; i < g->vertex_count; i++) {
        g->positions[3 * i + 0] = scene->tri_v[i].x;
        g->positions[3 * i + 1] = scene->tri_v[i].y;
        g->positions[3 * i + 2] = scene->tri_v[i].z;
        g->indices[i] = i;
    }
    g->sphere_count = scene->sph_count;
    g->spheres = (float *)xmalloc(sizeof(float) * 4 * g->sphere_count);
    for (i = 0; i < g->sphere_count; i++) {
        g->spheres[4 * i + 0] = scene->sph_c[i].x;
        g->spheres[4 * i + 1] = scene->sph_c[i].y;
        g->spheres[4 * i + 2] = scene->sph_c[i].z;
        g->spheres[4 * i + 3] = scene->sph_r[i];
    }
}

/* The CS184 bunny: load CBbunny.dae and copy out its triangles, spheres and camera (the
   benchmark then rebuilds scenes from these arrays, so fogrt and Embree get the same input).
   Returns false if the file cannot be read. */
static bool load_cs184_bunny(bench_geometry *g, int image_side)
{
    const char *path = FOGRT_SHARED_DIR "/scenes/cs184/CBbunny.dae";
    fogrt_scene *scene = NULL;
    fogrt_load_options options;
    fogrt_load_report report;
    fogrt_result r;
    memset(g, 0, sizeof *g);
    memset(&options, 0, sizeof options);
    options.image_width = options.image_height = image_side;   /* frame the camera for it */
    check(fogrt_scene_create(NULL, &scene), "fogrt_scene_create");
    r = fogrt_load_dae(scene, path, &options, &report);
    if (r != FOGRT_RESULT_OK) {
        fprintf(stderr, "bench: cannot load %s (%s:%d: %s); using a synthetic mesh instead\n",
                path, report.file, report.line, report.message);
        fogrt_scene_destroy(scene);
        return false;
    }
    snprintf(g->name, sizeof g->name, "CS184 CBbunny.dae");
    copy_scene_geometry(scene, g);
    fogrt_scene_get_camera(scene, &g->camera);
    fogrt_scene_destroy(scene);
    return true;
}
#endif

/* ------------------------------------------------------------------------------------------
   Ray sets: 8 floats per ray, ox oy oz tmin dx dy dz tmax (bench_embree.c reads the same)
   ------------------------------------------------------------------------------------------ */
typedef struct ray_set {
    const char *name;
    float *rays;
    size_t count;
    bool any_hit;        /* shadow rays: traced with fogrt_scene_occluded / rtcOccluded1 */
} ray_set;

static void put_ray(float *r, fogrt_vec3 o, fogrt_vec3 d, float tmin, float tmax)
{
    r[0] = o.x; r[1] = o.y; r[2] = o.z; r[3] = tmin;
    r[4] = d.x; r[5] = d.y; r[6] = d.z; r[7] = tmax;
}

/* One pinhole camera ray through the centre of every pixel of a side x side image. */
static ray_set make_primary_rays(const fogrt_scene *scene, int side)
{
    ray_set s;
    int x, y;
    s.name = "primary";
    s.any_hit = false;
    s.count = (size_t)side * (size_t)side;
    s.rays = (float *)xmalloc(sizeof(float) * 8 * s.count);
    for (y = 0; y < side; y++)
        for (x = 0; x < side; x++) {
            fogrt_vec3 o, d;
            fogrt_camera_ray(scene, side, side, (float)x + 0.5f, (float)y + 0.5f, 0.5f, 0.5f, &o, &d);
            put_ray(s.rays + 8 * ((size_t)y * (size_t)side + (size_t)x), o, d, 0.0f, INFINITY);
        }
    return s;
}

/* Origins uniform in the scene's bounding box, directions uniform on the sphere. */
static ray_set make_random_rays(const fogrt_scene *scene, size_t count, uint64_t seed)
{
    ray_set s;
    fogrt_scene_info info;
    fogrt_rng rng;
    size_t i;
    fogrt_scene_get_info(scene, &info);
    fogrt_rng_seed(&rng, seed, 1);
    s.name = "random";
    s.any_hit = false;
    s.count = count;
    s.rays = (float *)xmalloc(sizeof(float) * 8 * count);
    for (i = 0; i < count; i++) {
        fogrt_vec3 o, d;
        o.x = info.bounds_min.x + (info.bounds_max.x - info.bounds_min.x) * fogrt_rng_float(&rng);
        o.y = info.bounds_min.y + (info.bounds_max.y - info.bounds_min.y) * fogrt_rng_float(&rng);
        o.z = info.bounds_min.z + (info.bounds_max.z - info.bounds_min.z) * fogrt_rng_float(&rng);
        d = fogrt_sample_uniform_sphere(fogrt_rng_float(&rng), fogrt_rng_float(&rng));
        put_ray(s.rays + 8 * i, o, d, 0.0f, INFINITY);
    }
    return s;
}

/* Geometric unit normal of primitive prim (triangles first, then spheres) at point p. */
static fogrt_vec3 geometric_normal(const bench_geometry *g, uint32_t prim, fogrt_vec3 p)
{
    fogrt_vec3 n;
    float len;
    if (prim < g->triangle_count) {
        const uint32_t *tri = g->indices + 3 * (size_t)prim;
        const float *a = g->positions + 3 * (size_t)tri[0];
        const float *b = g->positions + 3 * (size_t)tri[1];
        const float *c = g->positions + 3 * (size_t)tri[2];
        float e1[3], e2[3];
        int k;
        for (k = 0; k < 3; k++) { e1[k] = b[k] - a[k]; e2[k] = c[k] - a[k]; }
        n.x = e1[1] * e2[2] - e1[2] * e2[1];
        n.y = e1[2] * e2[0] - e1[0] * e2[2];
        n.z = e1[0] * e2[1] - e1[1] * e2[0];
    } else {
        const float *sp = g->spheres + 4 * (size_t)(prim - g->triangle_count);
        n.x = p.x - sp[0]; n.y = p.y - sp[1]; n.z = p.z - sp[2];
    }
    len = sqrtf(n.x * n.x + n.y * n.y + n.z * n.z);
    if (len > 0.0f) { n.x /= len; n.y /= len; n.z /= len; }
    return n;
}

/* The hit point of closest-hit ray r at distance t on primitive prim, pushed off the surface
   by eps along the normal on the side the ray came from (*o), and that normal (*nrm). */
static void surface_point(const bench_geometry *g, const float *r, float t, uint32_t prim, float eps,
                          fogrt_vec3 *o, fogrt_vec3 *nrm)
{
    fogrt_vec3 p, n;
    float sign;
    p.x = r[0] + t * r[4]; p.y = r[1] + t * r[5]; p.z = r[2] + t * r[6];
    n = geometric_normal(g, prim, p);
    sign = (n.x * r[4] + n.y * r[5] + n.z * r[6]) > 0.0f ? -1.0f : 1.0f;  /* face the ray */
    n.x *= sign; n.y *= sign; n.z *= sign;
    o->x = p.x + eps * n.x; o->y = p.y + eps * n.y; o->z = p.z + eps * n.z;
    *nrm = n;
}

/* One cosine-weighted diffuse bounce from every hit of the primary rays (t_hit, prim_hit are
   fogrt's answers for them). The origin is pushed off the surface by eps along the normal on
   the side the primary ray came from. */
static ray_set make_bounce_rays(const bench_geometry *g, const ray_set *primary, const float *t_hit,
                                const uint32_t *prim_hit, float eps, uint64_t seed)
{
    ray_set s;
    fogrt_rng rng;
    size_t i, n = 0;
    fogrt_rng_seed(&rng, seed, 2);
    s.name = "bounce";
    s.any_hit = false;
    s.rays = (float *)xmalloc(sizeof(float) * 8 * (primary->count ? primary->count : 1));
    for (i = 0; i < primary->count; i++) {
        fogrt_vec3 nrm, local, t1, t2, d, o;
        float len;
        if (t_hit[i] < 0.0f) continue;
        surface_point(g, primary->rays + 8 * i, t_hit[i], prim_hit[i], eps, &o, &nrm);
        /* Orthonormal frame (t1, t2, nrm): t1 from the axis least aligned with the normal. */
        if (fabsf(nrm.x) < 0.9f) { t1.x = 0.0f; t1.y = nrm.z; t1.z = -nrm.y; }
        else                     { t1.x = -nrm.z; t1.y = 0.0f; t1.z = nrm.x; }
        len = sqrtf(t1.x * t1.x + t1.y * t1.y + t1.z * t1.z);
        t1.x /= len; t1.y /= len; t1.z /= len;
        t2.x = nrm.y * t1.z - nrm.z * t1.y;
        t2.y = nrm.z * t1.x - nrm.x * t1.z;
        t2.z = nrm.x * t1.y - nrm.y * t1.x;
        local = fogrt_sample_cosine_hemisphere(fogrt_rng_float(&rng), fogrt_rng_float(&rng));
        d.x = local.x * t1.x + local.y * t2.x + local.z * nrm.x;
        d.y = local.x * t1.y + local.y * t2.y + local.z * nrm.y;
        d.z = local.x * t1.z + local.y * t2.z + local.z * nrm.z;
        len = sqrtf(d.x * d.x + d.y * d.y + d.z * d.z);
        d.x /= len; d.y /= len; d.z /= len;
        put_ray(s.rays + 8 * n, o, d, 0.0f, INFINITY);
        n++;
    }
    s.count = n;
    return s;
}

/* Shadow rays, as next-event estimation traces them: from every hit of `from` (t_hit,
   prim_hit: fogrt's closest-hit answers), the origin pushed off the surface as for the bounce
   rays, toward a point q uniform in the scene's bounding box; a q behind the surface is
   mirrored through the tangent plane, so that every ray leaves on the side the light would
   be seen from. tmin 0, tmax = the distance to q: the ray is occluded only by geometry
   between the surface and q. Appends to *s (room for from->count more rays). */
static void add_shadow_rays(const bench_geometry *g, const fogrt_scene_info *box, const ray_set *from,
                            const float *t_hit, const uint32_t *prim_hit, float eps, fogrt_rng *rng,
                            ray_set *s)
{
    size_t i;
    for (i = 0; i < from->count; i++) {
        fogrt_vec3 o, nrm, q, d;
        float side, len;
        if (t_hit[i] < 0.0f) continue;
        surface_point(g, from->rays + 8 * i, t_hit[i], prim_hit[i], eps, &o, &nrm);
        q.x = box->bounds_min.x + (box->bounds_max.x - box->bounds_min.x) * fogrt_rng_float(rng);
        q.y = box->bounds_min.y + (box->bounds_max.y - box->bounds_min.y) * fogrt_rng_float(rng);
        q.z = box->bounds_min.z + (box->bounds_max.z - box->bounds_min.z) * fogrt_rng_float(rng);
        d.x = q.x - o.x; d.y = q.y - o.y; d.z = q.z - o.z;
        side = d.x * nrm.x + d.y * nrm.y + d.z * nrm.z;
        if (side < 0.0f) { d.x -= 2.0f * side * nrm.x; d.y -= 2.0f * side * nrm.y; d.z -= 2.0f * side * nrm.z; }
        len = sqrtf(d.x * d.x + d.y * d.y + d.z * d.z);
        if (!(len > eps)) continue;        /* q on the surface point itself: no ray */
        d.x /= len; d.y /= len; d.z /= len;
        put_ray(s->rays + 8 * s->count, o, d, 0.0f, len);
        s->count++;
    }
}

/* ------------------------------------------------------------------------------------------
   Tracing: the loop that is timed
   ------------------------------------------------------------------------------------------ */
/* Closest hit (or, for a shadow set, any hit) of every ray: t and the primitive, or t = -1
   and UINT32_MAX on a miss (any hit: t = 0 when occluded). */
static void trace_fogrt(const fogrt_scene *scene, const ray_set *s, int threads, float *t_out, uint32_t *prim_out)
{
    long i, n = (long)s->count;
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1024) num_threads(threads)
#else
    (void)threads;
#endif
    for (i = 0; i < n; i++) {
        const float *r = s->rays + 8 * (size_t)i;
        fogrt_vec3 o, d;
        fogrt_hit hit;
        o.x = r[0]; o.y = r[1]; o.z = r[2];
        d.x = r[4]; d.y = r[5]; d.z = r[6];
        t_out[i] = -1.0f;
        prim_out[i] = UINT32_MAX;
        if (s->any_hit) {
            if (fogrt_scene_occluded(scene, o, d, r[3], r[7])) t_out[i] = 0.0f;
        } else if (fogrt_scene_intersect(scene, o, d, r[3], r[7], &hit)) {
            t_out[i] = hit.t;
            prim_out[i] = hit.prim;
        }
    }
}

#ifdef HAVE_EMBREE
static void trace_embree(const bench_embree *e, const ray_set *s, int threads, float *t_out, uint32_t *prim_out)
{
    bench_embree_trace(e, s->rays, s->count, threads, s->any_hit, t_out, prim_out);
}
#endif

/* Do two closest-hit answers agree? Both miss, or both hit at the same distance up to float
   round-off (the primitive may differ on a shared edge, so it is not compared). Any-hit
   answers (t 0 or -1) agree when they are equal. */
static bool same_answer(float ta, float tb)
{
    if (ta < 0.0f || tb < 0.0f) return ta < 0.0f && tb < 0.0f;
    return fabsf(ta - tb) <= 1e-4f * (1.0f + fmaxf(ta, tb));
}

/* Checks up to `samples` rays of the set, spread evenly, against the brute-force reference;
   returns how many disagree (*checked: how many were compared). For a shadow set the reference any-hit answer is "brute force
   finds a hit with tmin < t < tmax". */
static size_t check_against_brute(const fogrt_scene *scene, const ray_set *s, size_t samples,
                                  const float *t_bvh, size_t *checked)
{
    size_t k, bad = 0, step = s->count / (samples ? samples : 1);
    if (step == 0) step = 1;
    for (k = 0; k < s->count; k += step) {
        const float *r = s->rays + 8 * k;
        fogrt_vec3 o, d;
        fogrt_hit hit;
        float t;
        o.x = r[0]; o.y = r[1]; o.z = r[2];
        d.x = r[4]; d.y = r[5]; d.z = r[6];
        t = fogrt_scene_intersect_brute(scene, o, d, r[3], r[7], &hit) ? hit.t : -1.0f;
        if (s->any_hit && t >= 0.0f) t = 0.0f;
        if (!same_answer(t, t_bvh[k])) bad++;
        ++*checked;
    }
    return bad;
}

/* ------------------------------------------------------------------------------------------
   The benchmark of one geometry: build times, then every ray set on 1 and 2 threads
   ------------------------------------------------------------------------------------------ */
typedef struct bench_options {
    int image_side;       /* primary rays: side x side */
    int trace_reps;       /* passes over each ray set per configuration (median taken) */
    int build_reps;
    int render_reps;      /* renders per thread count (median taken) */
    double render_seconds;  /* the samples per pixel are chosen for about this long a render */
} bench_options;

#define MAX_REPS 15
#define SET_COUNT 4

/* Bytes per triangle of the built scene. fogrt: fogrt_scene_get_memory split into the
   geometry (the same getter before the build: what was added), the binary tree (nodes,
   prim_index, and the packed primitives when the binary tree is traced), the wide tree, and
   the rest (light and environment
   tables); then what the counting allocator saw: held after the build (spare capacity
   included) and the most held at once during it. Embree: the geometry buffers set before
   rtcCommitScene, and the bytes rtcCommitScene added (kept after it, and at its peak). */
static void print_memory(const fogrt_scene *scene, size_t geometry_bytes, size_t held, size_t peak,
                         const void *embree_scene)
{
    double tris = (double)(scene->tri_count + scene->sph_count), total = (double)fogrt_scene_get_memory(scene);
    double binary = (double)scene->node_count * sizeof(fogrt_bvh_node) + (double)fogrt__tree_refs(scene) * sizeof(uint32_t)
                  + (scene->prims ? tris * (double)sizeof(fogrt__prim) : 0.0);   /* the binary layout only */
    double wide = scene->x->wide ? (double)fogrt__wbvh_bytes(scene->x->wide) : 0.0;
    double geometry = (double)geometry_bytes;
    if (tris < 1.0) tris = 1.0;
    printf("memory    fogrt  %8.1f B/tri  (fogrt_scene_get_memory: geometry %.1f + binary BVH %.1f + wide BVH %.1f"
           " + other %.1f; allocated %.1f after the build, %.1f at its peak)\n",
           total / tris, geometry / tris, binary / tris, wide / tris, (total - geometry - binary - wide) / tris,
           (double)held / tris, (double)peak / tris);
#ifdef HAVE_EMBREE
    {
        double buffers, commit_peak, commit_final;
        bench_embree_memory((const bench_embree *)embree_scene, &buffers, &commit_peak, &commit_final);
        printf("memory    embree %8.1f B/tri  (geometry buffers %.1f + rtcCommitScene %.1f kept, %.1f at its peak)"
               "   fogrt/embree %.2f, BVH alone %.2f\n",
               (buffers + commit_final) / tris, buffers / tris, commit_final / tris, commit_peak / tris,
               total / (buffers + commit_final), (total - geometry) / commit_final);
    }
#else
    (void)embree_scene;
#endif
}

/* The four ray sets of a built scene (rays[3] has room for 2 x the primary count; t_f, p_f
   as many answers). */
static void make_ray_sets(const bench_geometry *g, const fogrt_scene *scene, int image_side, ray_set *sets,
                          float *t_f, uint32_t *p_f)
{
    fogrt_scene_info info;
    fogrt_rng rng;
    float extent, eps;
    fogrt_scene_get_info(scene, &info);
    extent = fmaxf(info.bounds_max.x - info.bounds_min.x,
                   fmaxf(info.bounds_max.y - info.bounds_min.y, info.bounds_max.z - info.bounds_min.z));
    eps = 1e-4f * extent;
    sets[0] = make_primary_rays(scene, image_side);
    sets[1] = make_random_rays(scene, sets[0].count, 12345u);
    trace_fogrt(scene, &sets[0], max_threads(), t_f, p_f);
    sets[2] = make_bounce_rays(g, &sets[0], t_f, p_f, eps, 777u);
    sets[3].name = "shadow";
    sets[3].any_hit = true;
    sets[3].count = 0;
    sets[3].rays = (float *)xmalloc(sizeof(float) * 8 * (sets[0].count + sets[2].count + 1));
    fogrt_rng_seed(&rng, 4242u, 3);
    add_shadow_rays(g, &info, &sets[0], t_f, p_f, eps, &rng, &sets[3]);
    trace_fogrt(scene, &sets[2], max_threads(), t_f, p_f);
    add_shadow_rays(g, &info, &sets[2], t_f, p_f, eps, &rng, &sets[3]);
}

/* Decimals for a rate in Mrays/s: 2, and 4 below 0.1 (a fan's rays run at thousands a second). */
static int rate_digits(double mrays) { return mrays < 0.1 ? 4 : 2; }

/* One ray set: checks, then 1 and 2 threads, fogrt and Embree alternating; prints its line. */
static void bench_ray_set(const bench_geometry *g, const fogrt_scene *scene, const void *embree_scene,
                          const ray_set *s, const bench_options *opt, float *t_f, uint32_t *p_f,
                          float *t_e, uint32_t *p_e)
{
    double mrays_f[2] = {0, 0};
    size_t hits = 0, i, bad_brute, samples, checked = 0;
    int ti, rep, threads_list[2] = {1, 2};
#ifdef HAVE_EMBREE
    const bench_embree *embree = (const bench_embree *)embree_scene;
    size_t bad_embree = 0;
    double mrays_e[2] = {0, 0};
#else
    (void)embree_scene; (void)t_e; (void)p_e;
#endif
    /* Correctness first: a sample against brute force (at most ~5e7 triangle tests). */
    trace_fogrt(scene, s, max_threads(), t_f, p_f);
    for (i = 0; i < s->count; i++) hits += t_f[i] >= 0.0f;
    samples = (size_t)(5e7 / (double)(g->triangle_count + g->sphere_count + 1));
    if (samples > 2000) samples = 2000;
    bad_brute = check_against_brute(scene, s, samples, t_f, &checked);
#ifdef HAVE_EMBREE
    trace_embree(embree, s, max_threads(), t_e, p_e);
    for (i = 0; i < s->count; i++) bad_embree += !same_answer(t_f[i], t_e[i]);
#endif
    /* Timing: fogrt and Embree alternate, so drifts of the machine hit both alike. */
    for (ti = 0; ti < 2; ti++) {
        int threads = threads_list[ti];
        double tf[MAX_REPS];
#ifdef HAVE_EMBREE
        double te[MAX_REPS];
#endif
        if (threads > max_threads()) continue;
        for (rep = 0; rep < opt->trace_reps; rep++) {
            double t0 = now_seconds(), c0 = cpu_seconds();
            trace_fogrt(scene, s, threads, t_f, p_f);
            tf[rep] = now_seconds() - t0;
            if (threads == 1) { g_wall_1t += tf[rep]; g_cpu_1t += cpu_seconds() - c0; }
#ifdef HAVE_EMBREE
            t0 = now_seconds(); c0 = cpu_seconds();
            trace_embree(embree, s, threads, t_e, p_e);
            te[rep] = now_seconds() - t0;
            if (threads == 1) { g_wall_1t += te[rep]; g_cpu_1t += cpu_seconds() - c0; }
#endif
        }
        mrays_f[ti] = (double)s->count / median(tf, opt->trace_reps) / 1e6;
#ifdef HAVE_EMBREE
        mrays_e[ti] = (double)s->count / median(te, opt->trace_reps) / 1e6;
#endif
    }
    printf("%-8s %9zu %5.1f | %9.*f %9.*f", s->name, s->count,
           100.0 * (double)hits / (double)(s->count ? s->count : 1), rate_digits(mrays_f[0]), mrays_f[0],
           rate_digits(mrays_f[1]), mrays_f[1]);
#ifdef HAVE_EMBREE
    printf(" | %9.*f %9.*f | %8.2f %8.2f", rate_digits(mrays_e[0]), mrays_e[0], rate_digits(mrays_e[1]), mrays_e[1],
           mrays_f[0] / mrays_e[0], mrays_e[1] > 0 ? mrays_f[1] / mrays_e[1] : 0.0);
#endif
    printf(" | %6.2f | brute %zu/%zu bad", mrays_f[0] > 0 ? mrays_f[1] / mrays_f[0] : 0.0, bad_brute, checked);
#ifdef HAVE_EMBREE
    printf(", embree %zu/%zu differ", bad_embree, s->count);
#endif
    printf("\n");
}

static void bench_geometry_run(const bench_geometry *g, const bench_options *opt)
{
    fogrt_scene *scene = NULL;
    double times[MAX_REPS], build_median, sah;
    uint32_t node_count = 0;
    const fogrt_bvh_node *nodes;
    const uint32_t *prim_index;
    ray_set sets[SET_COUNT];
    float *t_f, *t_e;
    uint32_t *p_f, *p_e;
    size_t max_rays, geometry_bytes = 0, held = 0, peak = 0;
    int rep, k;
    void *embree_scene = NULL;
#ifdef HAVE_EMBREE
    bench_embree *embree = NULL;
    double embree_build[MAX_REPS], embree_build_median = 0.0;
#endif

    printf("\n== %s: %u triangles, %u spheres ==\n", g->name, g->triangle_count, g->sphere_count);

    /* BVH build: a fresh scene each time; only fogrt_scene_build is timed. */
    for (rep = 0; rep < opt->build_reps; rep++) {
        double t0;
        if (scene) fogrt_scene_destroy(scene);
        scene = geometry_scene(g);
        geometry_bytes = fogrt_scene_get_memory(scene);
        g_fogrt_bytes.peak = g_fogrt_bytes.live;
        t0 = now_seconds();
        check(fogrt_scene_build(scene, NULL), "fogrt_scene_build");
        times[rep] = now_seconds() - t0;
        held = g_fogrt_bytes.live;
        peak = g_fogrt_bytes.peak;
    }
    build_median = median(times, opt->build_reps);
    fogrt_scene_get_bvh(scene, &nodes, &node_count, &prim_index);
    sah = fogrt_bvh_sah_cost(scene);
    printf("build     fogrt  %8.4f s  (median of %d; %u nodes, SAH cost %.2f)\n",
           build_median, opt->build_reps, node_count, sah);
#ifdef HAVE_EMBREE
    for (rep = 0; rep < opt->build_reps; rep++) {
        if (embree) bench_embree_destroy(embree);
        embree = bench_embree_create(g->positions, g->vertex_count, g->indices, g->triangle_count,
                                     g->spheres, g->sphere_count, 1, &embree_build[rep]);
        if (!embree) { fprintf(stderr, "bench: Embree scene creation failed\n"); exit(1); }
    }
    embree_scene = embree;
    embree_build_median = median(embree_build, opt->build_reps);
    printf("build     embree %8.4f s  (median of %d, 1 build thread)   fogrt/embree time %.2f\n",
           embree_build_median, opt->build_reps, build_median / embree_build_median);
#endif
    print_memory(scene, geometry_bytes, held, peak, embree_scene);

    /* Ray sets. */
    max_rays = 2 * (size_t)opt->image_side * (size_t)opt->image_side + 1;
    t_f = (float *)xmalloc(sizeof(float) * max_rays);
    t_e = (float *)xmalloc(sizeof(float) * max_rays);
    p_f = (uint32_t *)xmalloc(sizeof(uint32_t) * max_rays);
    p_e = (uint32_t *)xmalloc(sizeof(uint32_t) * max_rays);
    make_ray_sets(g, scene, opt->image_side, sets, t_f, p_f);

    printf("%-8s %9s %5s | %9s %9s", "rays", "count", "hit%", "fogrt 1T", "fogrt 2T");
#ifdef HAVE_EMBREE
    printf(" | %9s %9s | %8s %8s", "embree 1T", "embree 2T", "f/e 1T", "f/e 2T");
#endif
    printf(" | %6s | %s\n", "2T/1T", "checks");
    for (k = 0; k < SET_COUNT; k++) bench_ray_set(g, scene, embree_scene, &sets[k], opt, t_f, p_f, t_e, p_e);
    printf("(Mrays/s = million rays per second, median of %d passes; primary, random, bounce: closest hit,"
           " shadow: any hit, hit%% = occluded; f/e = fogrt/Embree)\n", opt->trace_reps);

    for (k = 0; k < SET_COUNT; k++) free(sets[k].rays);
    free(t_f); free(t_e); free(p_f); free(p_e);
#ifdef HAVE_EMBREE
    bench_embree_destroy(embree);
#endif
    fogrt_scene_destroy(scene);
}

/* ------------------------------------------------------------------------------------------
   Render: samples per second of the default scene
   ------------------------------------------------------------------------------------------ */
static void bench_render(const bench_options *opt)
{
    fogrt_scene *scene = NULL;
    fogrt_image img;
    fogrt_render_desc rd;
    fogrt_render_stats stats;
    const int width = 320, height = 240;
    int spp, ti, rep, reps = opt->render_reps;
    double t0, t1, rate[3] = {0, 0, 0};
    check(fogrt_scene_create(NULL, &scene), "fogrt_scene_create");
    check(fogrt_scene_add_default(scene), "fogrt_scene_add_default");
    check(fogrt_scene_build(scene, NULL), "fogrt_scene_build");
    check(fogrt_image_alloc(&img, width, height, NULL), "fogrt_image_alloc");
    rd = fogrt_render_defaults();
    rd.width = width; rd.height = height; rd.seed = 1;

    /* Choose the samples per pixel so that one render on 2 threads takes about render_seconds. */
    rd.threads = max_threads() >= 2 ? 2 : 1;
    t0 = now_seconds();
    check(fogrt_render(scene, &rd, &img, 1, &stats), "fogrt_render");
    t1 = now_seconds() - t0;
    spp = (int)(opt->render_seconds / (t1 > 1e-6 ? t1 : 1e-6));
    if (spp < 1) spp = 1;
    if (spp > 1024) spp = 1024;

    printf("\n== render: default scene (fogrt_scene_add_default), %dx%d, %d spp, path integrator ==\n",
           width, height, spp);
    printf("%-8s | %14s | %14s | %s\n", "threads", "samples/s", "Mrays/s", "rays per sample");
    for (ti = 1; ti <= 2; ti++) {
        double times[MAX_REPS];
        uint64_t rays = 0, samples = 0;
        if (ti > max_threads()) continue;
        rd.threads = ti;
        for (rep = 0; rep < reps; rep++) {
            fogrt_image_clear(&img);
            t0 = now_seconds();
            check(fogrt_render(scene, &rd, &img, spp, &stats), "fogrt_render");
            times[rep] = now_seconds() - t0;
            rays = stats.rays; samples = stats.camera_rays;
        }
        t1 = median(times, reps);
        rate[ti] = (double)samples / t1;
        printf("%-8d | %14.0f | %14.2f | %.2f\n", ti, (double)samples / t1, (double)rays / t1 / 1e6,
               (double)rays / (double)(samples ? samples : 1));
    }
    if (rate[1] > 0.0 && rate[2] > 0.0)
        printf("2T/1T    | %14.2f | (samples/s on 2 threads over 1 thread; the goal: >= 1.9 on a quiet machine)\n",
               rate[2] / rate[1]);
    printf("(median of %d renders; Mrays/s counts camera, bounce and shadow rays)\n", reps);
    fogrt_image_free(&img);
    fogrt_scene_destroy(scene);
}

int main(int argc, char **argv)
{
    bench_options opt, fan_opt;
    bench_geometry bunny, big, fan;
    bool quick = false, fan_only = false, have_bunny = false;
    int a;

    for (a = 1; a < argc; a++) {
        if (strcmp(argv[a], "--quick") == 0) quick = true;
        else if (strcmp(argv[a], "--fan") == 0) fan_only = true;
        else {
            fprintf(stderr, "usage: %s [--quick] [--fan]\n", argv[0]);
            return 2;
        }
    }
    opt.image_side = quick ? 512 : 1024;
    opt.trace_reps = quick ? 3 : 5;
    opt.build_reps = quick ? 3 : 5;
    opt.render_reps = quick ? 3 : 5;
    opt.render_seconds = quick ? 0.3 : 1.0;

    printf("fogrt benchmark: compiled with %s (%s), %d OpenMP thread(s) available",
#ifdef __VERSION__
           "cc " __VERSION__,
#else
           "cc",
#endif
           BENCH_CFLAGS, max_threads());
#ifdef HAVE_EMBREE
    printf(", Embree %s", bench_embree_version());
#else
    printf(", without Embree (make bench BENCH_EMBREE=0: no ratios)");
#endif
    printf("\n");
    print_load_average("at the start");

    if (!fan_only) {
#ifdef HAVE_FOGRT_LOAD
        have_bunny = load_cs184_bunny(&bunny, opt.image_side);
#endif
        if (!have_bunny) make_displaced_sphere(124, 116, "synthetic bunny-sized mesh (displaced sphere)", &bunny);
        bench_geometry_run(&bunny, &opt);
        geometry_free(&bunny);

        make_displaced_sphere(501, 1000, "synthetic 1M-triangle mesh (displaced sphere)", &big);
        bench_geometry_run(&big, &opt);
        geometry_free(&big);
    }

    /* A ray costs a fan about as many box tests as it has slivers near the ray: fewer rays. */
    fan_opt = opt;
    fan_opt.image_side = quick ? 64 : 128;
    make_fan(100000, "fan of 100,000 slivers around one vertex (bench/fan.h)", &fan);
    bench_geometry_run(&fan, &fan_opt);
    geometry_free(&fan);

    if (!fan_only) bench_render(&opt);

    printf("\n");
    print_load_average("at the end");
    if (g_wall_1t > 0.0) {
        double share = g_cpu_1t / g_wall_1t;
        printf("one-thread ray timings got %.0f%% of a CPU%s\n", 100.0 * share,
               share < 0.9 ? ": the machine was busy, the figures are too low and noisy" : "");
    }
    return 0;
}
