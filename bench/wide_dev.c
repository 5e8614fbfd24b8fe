/* wide_dev.c - development harness for the wide BVH (fogrt.h chapter 10b). Run: make wide-dev.

   1. Correctness, on the CS184 bunny, six random soups (mixed sizes, axis-aligned triangles
      on a grid, degenerate triangles: repeated vertex, collinear, a point; spheres, tiny and
      overlapping; one soup of spheres only), a small lumpy sphere and the 1M-triangle mesh,
      with rays of every family: random, bounce, shadow, and "hard" ones (axis-parallel from
      vertex coordinates, along a triangle edge, in a face of the scene box, from inside leaf
      boxes with and without a finite interval, aimed exactly at vertices and edge midpoints,
      non-finite origins, directions and intervals, empty intervals). Every ray is traced by
      the binary traversal and by fogrt__wbvh_traverse, closest hit and any hit:
        - the reference is fogrt__traverse with the wide traversal's culling slack (the copy
          traverse_slack below, two lines changed); the answers must be the same miss, or
          t within 1 ulp with the same primitive, u and v; any hit the same;
        - a different primitive at bitwise the same t (a shared edge) is counted as a tie,
          after checking that both primitives really are hit at that t;
        - rays along a triangle edge may be tested against a triangle the binary tree's
          tighter leaf box excluded by rounding (the wide tree merges small leaves): counted,
          and allowed only when the wide hit is real, closer than the binary one and not
          closer than brute force's (FOGRT_WBVH_LEAF=0 makes these 0);
        - the unchanged fogrt__traverse is compared too and its differences counted, with
          how often brute force agrees with it and with the wide traversal.
      The binary tree itself (chapter 9's build) is also checked against brute force on a
      sample of random rays.
   2. Speed, one thread: Mrays/s of the binary traversal, the wide traversal and Embree 3
      (rtcIntersect1 / rtcOccluded1, when HAVE_EMBREE) on the same rays, the three passes
      rotating order within each repetition; medians of the repetitions, and the median of the
      per-repetition ratios (same-run ratios). Ray sets: random (closest hit), bounce
      (closest hit), shadow (any hit, from surface points to random points in the bounds).
      Also the build seconds (fogrt_scene_build, of which the wide collapse; Embree's
      rtcCommitScene on one thread) and the bytes per triangle (Embree's: what its memory
      monitor saw allocated during rtcCommitScene).

   Usage: wide_dev [--check-only | --speed-only | --build-only] [--reps N] [--rays N] [--no-big] [--hugepages]
     --build-only: build the bunny and the 1M mesh once each and stop, for counting the
                  build's instructions: valgrind --tool=callgrind
                  --toggle-collect=fogrt_scene_build build/bench/wide_dev --build-only
     --hugepages: the wide tree's big arrays in transparent huge pages (Linux madvise), as
                  Embree allocates its own; fogrt itself only ever calls the allocator.
     WIDE_DEV_VERBOSE=1 in the environment prints every disallowed difference.          */
#define _POSIX_C_SOURCE 200112L
#define _DEFAULT_SOURCE 1
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#define FOGRT_LOAD_IMPLEMENTATION
#include "fogrt_load.h"

/* The binary traversal to compare with. Once fogrt__traverse dispatches to the wide tree,
   build with -DBINARY_TRAVERSE=<the binary one's new name> (e.g. fogrt__bvh2_traverse). */
#ifndef BINARY_TRAVERSE
#define BINARY_TRAVERSE fogrt__bvh2_traverse
#endif

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#ifdef HAVE_EMBREE
#include <embree3/rtcore.h>
#endif
#ifdef __linux__
#include <sys/mman.h>
#endif

/* --hugepages: an allocator that asks Linux for transparent huge pages for big blocks (what
   Embree's allocator does), to see how much of the 1M mesh's cost is TLB misses. */
static void *huge_alloc(size_t size, void *user)
{
    void *p = NULL;
    (void)user;
    if (size < (4u << 20)) return malloc(size);
    if (posix_memalign(&p, 2u << 20, size) != 0) return NULL;
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    madvise(p, size, MADV_HUGEPAGE);
#endif
    return p;
}
static void huge_free(void *p, void *user) { (void)user; free(p); }
static fogrt_allocator g_wide_alloc;

#ifndef FOGRT_SHARED_DIR
#define FOGRT_SHARED_DIR "../shared"
#endif

static double wall(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
static double cpu(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
static void *xmalloc(size_t n)
{
    void *p = malloc(n ? n : 1);
    if (!p) { fprintf(stderr, "wide_dev: out of memory (%lu bytes)\n", (unsigned long)n); exit(1); }
    return p;
}
static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}
static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}
static void check(fogrt_result r, const char *what)
{
    if (r != FOGRT_RESULT_OK) { fprintf(stderr, "wide_dev: %s: %s\n", what, fogrt_result_string(r)); exit(1); }
}

/* ---- a small RNG of our own (splitmix64), so ray sets do not depend on fogrt's ---- */
typedef struct rng { uint64_t s; } rng;
static uint64_t rng_u64(rng *r)
{
    uint64_t z = (r->s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}
static float rng_f(rng *r) { return (float)(rng_u64(r) >> 40) * (1.0f / 16777216.0f); }
static uint32_t rng_below(rng *r, uint32_t n) { return (uint32_t)(rng_u64(r) % (n ? n : 1)); }
static fogrt__v3 rng_dir(rng *r)
{
    float z = 1.0f - 2.0f * rng_f(r), phi = 6.28318531f * rng_f(r), s = sqrtf(fmaxf(0.0f, 1.0f - z * z));
    return fogrt__v(s * cosf(phi), s * sinf(phi), z);
}

/* ---- rays: ox oy oz tmin dx dy dz tmax ---- */
typedef struct ray { fogrt__v3 o, d; float tmin, tmax; } ray;
typedef struct rays { const char *name; ray *r; size_t n, cap; bool shadow; } rays;
static void rays_push(rays *s, fogrt__v3 o, fogrt__v3 d, float tmin, float tmax)
{
    if (s->n == s->cap) {
        ray *nr;
        s->cap = s->cap ? 2 * s->cap : 1024;
        nr = (ray *)xmalloc(sizeof(ray) * s->cap);
        if (s->r) { memcpy(nr, s->r, sizeof(ray) * s->n); free(s->r); }
        s->r = nr;
    }
    s->r[s->n].o = o; s->r[s->n].d = d; s->r[s->n].tmin = tmin; s->r[s->n].tmax = tmax;
    s->n++;
}
static fogrt__v3 rand_in_box(rng *g, fogrt__v3 lo, fogrt__v3 hi, float grow)
{
    fogrt__v3 e = fogrt__sub(hi, lo);
    return fogrt__v(lo.x - grow * e.x + (1.0f + 2.0f * grow) * e.x * rng_f(g),
                    lo.y - grow * e.y + (1.0f + 2.0f * grow) * e.y * rng_f(g),
                    lo.z - grow * e.z + (1.0f + 2.0f * grow) * e.z * rng_f(g));
}
static float scene_extent(const fogrt_scene *s)
{
    fogrt__v3 e = fogrt__sub(s->bmax, s->bmin);
    return fmaxf(e.x, fmaxf(e.y, e.z));
}
/* Geometric normal of primitive id at p. */
static fogrt__v3 prim_normal(const fogrt_scene *s, uint32_t id, fogrt__v3 p)
{
    fogrt__v3 n;
    float len;
    if (id < s->tri_count) {
        const fogrt__v3 *v = &s->tri_v[3 * id];
        n = fogrt__cross(fogrt__sub(v[1], v[0]), fogrt__sub(v[2], v[0]));
    } else {
        n = fogrt__sub(p, s->sph_c[id - s->tri_count]);
    }
    len = fogrt__length(n);
    return len > 0.0f ? fogrt__scale(n, 1.0f / len) : fogrt__v(0, 0, 1);
}
/* A cosine-distributed direction around n. */
static fogrt__v3 cosine_dir(rng *g, fogrt__v3 n)
{
    fogrt__v3 t = fabsf(n.x) < 0.9f ? fogrt__v(0.0f, n.z, -n.y) : fogrt__v(-n.z, 0.0f, n.x), b, d;
    float r1 = rng_f(g), r2 = rng_f(g), rr = sqrtf(r1), phi = 6.28318531f * r2;
    t = fogrt__scale(t, 1.0f / fogrt__length(t));
    b = fogrt__cross(n, t);
    d = fogrt__add(fogrt__add(fogrt__scale(t, rr * cosf(phi)), fogrt__scale(b, rr * sinf(phi))),
                   fogrt__scale(n, sqrtf(fmaxf(0.0f, 1.0f - r1))));
    return fogrt__scale(d, 1.0f / fogrt__length(d));
}

static rays make_random(const fogrt_scene *s, size_t n, uint64_t seed)
{
    rays out;
    rng g;
    size_t i;
    memset(&out, 0, sizeof out);
    out.name = "random";
    g.s = seed;
    for (i = 0; i < n; ++i) rays_push(&out, rand_in_box(&g, s->bmin, s->bmax, 0.0f), rng_dir(&g), 0.0f, INFINITY);
    return out;
}
/* A diffuse bounce from the hits of camera-like rays: rays from random points on a sphere
   around the scene aimed at random points inside it (so they are incoherent but start where
   a path tracer's second segment starts: on a surface). shadow: instead of a bounce, a
   shadow ray from that surface point to a random point in the bounds (tmax = its distance). */
static rays make_bounce(const fogrt_scene *s, size_t n, uint64_t seed, bool shadow)
{
    rays out;
    rng g;
    size_t tries = 0;
    float ext = scene_extent(s), eps = 1e-4f * ext;
    fogrt__v3 c = fogrt__scale(fogrt__add(s->bmin, s->bmax), 0.5f);
    memset(&out, 0, sizeof out);
    out.name = shadow ? "shadow" : "bounce";
    out.shadow = shadow;
    g.s = seed;
    while (out.n < n && tries++ < 20 * n) {
        fogrt__v3 o = fogrt__add(c, fogrt__scale(rng_dir(&g), 1.5f * ext)), target = rand_in_box(&g, s->bmin, s->bmax, 0.0f);
        fogrt__v3 d = fogrt__sub(target, o), p, nrm;
        fogrt_hit h;
        d = fogrt__scale(d, 1.0f / fogrt__length(d));
        if (!BINARY_TRAVERSE(s, o, d, 0.0f, INFINITY, &h, false)) continue;
        p = fogrt__madd(o, d, h.t);
        nrm = prim_normal(s, h.prim, p);
        if (fogrt__dot(nrm, d) > 0.0f) nrm = fogrt__scale(nrm, -1.0f);
        p = fogrt__madd(p, nrm, eps);
        if (!shadow) {
            rays_push(&out, p, cosine_dir(&g, nrm), 0.0f, INFINITY);
        } else {
            fogrt__v3 to = fogrt__sub(rand_in_box(&g, s->bmin, s->bmax, 0.0f), p);
            float len = fogrt__length(to);
            if (!(len > 0.0f)) continue;
            rays_push(&out, p, fogrt__scale(to, 1.0f / len), 0.0f, len * (1.0f - 1e-4f));
        }
    }
    return out;
}
/* The hard families for the correctness check. */
static void add_hard_rays(const fogrt_scene *s, rays *out, size_t n, uint64_t seed)
{
    rng g;
    size_t i;
    uint32_t np = s->tri_count + s->sph_count;
    float ext = scene_extent(s);
    g.s = seed;
    for (i = 0; i < n; ++i) {
        uint32_t fam = (uint32_t)(i % 8), id = rng_below(&g, np);
        fogrt__v3 o, d, v0 = fogrt__v(0, 0, 0), e = fogrt__v(1, 0, 0);
        float tmin = 0.0f, tmax = INFINITY;
        if (id < s->tri_count) {
            v0 = s->tri_v[3 * id];
            e = fogrt__sub(s->tri_v[3 * id + 1 + rng_below(&g, 2)], v0);
        } else if (np) {
            v0 = s->sph_c[id - s->tri_count];
        }
        switch (fam) {
        case 0: {   /* axis-parallel from a point whose coordinates are vertex coordinates */
            int a = (int)rng_below(&g, 3);
            float sg = rng_below(&g, 2) ? 1.0f : -1.0f;
            o = rand_in_box(&g, s->bmin, s->bmax, 0.1f);
            if (rng_below(&g, 2)) o.x = v0.x;
            if (rng_below(&g, 2)) o.y = v0.y;
            if (rng_below(&g, 2)) o.z = v0.z;
            d = fogrt__v(a == 0 ? sg : 0.0f, a == 1 ? sg : 0.0f, a == 2 ? sg : 0.0f);
            if (rng_below(&g, 4) == 0) d = fogrt__scale(d, -1.0f), d.x = d.x == 0.0f ? -0.0f : d.x;
            break; }
        case 1: {   /* grazing: from a vertex along an edge, or in a triangle's plane */
            float len = fogrt__length(e);
            o = fogrt__madd(v0, e, -0.5f - rng_f(&g));
            d = len > 0.0f ? fogrt__scale(e, 1.0f / len) : rng_dir(&g);
            break; }
        case 2: {   /* grazing a face of the scene's box, axis-parallel in the other two */
            int a = (int)rng_below(&g, 3), b2 = (a + 1 + (int)rng_below(&g, 2)) % 3;
            o = rand_in_box(&g, s->bmin, s->bmax, 0.0f);
            if (a == 0) o.x = rng_below(&g, 2) ? s->bmin.x : s->bmax.x;
            if (a == 1) o.y = rng_below(&g, 2) ? s->bmin.y : s->bmax.y;
            if (a == 2) o.z = rng_below(&g, 2) ? s->bmin.z : s->bmax.z;
            d = rng_dir(&g);
            if (a == 0) d.x = 0.0f;
            if (a == 1) d.y = 0.0f;
            if (a == 2) d.z = 0.0f;
            if (b2 == 0) d.x = 0.0f;
            if (b2 == 1) d.y = 0.0f;
            if (b2 == 2) d.z = 0.0f;
            if (fogrt__length(d) == 0.0f) d = fogrt__v(a == 0 ? 0.0f : 1.0f, a == 0 ? 1.0f : 0.0f, 0.0f);
            d = fogrt__scale(d, 1.0f / fogrt__length(d));
            break; }
        case 3:     /* from inside a leaf box (the primitive's centroid), random direction */
        case 4:
            if (id < s->tri_count)
                o = fogrt__scale(fogrt__add(fogrt__add(s->tri_v[3 * id], s->tri_v[3 * id + 1]), s->tri_v[3 * id + 2]), 1.0f / 3.0f);
            else o = v0;
            o = fogrt__madd(o, rng_dir(&g), 1e-3f * ext * rng_f(&g));
            d = rng_dir(&g);
            if (fam == 4) { tmin = 1e-3f * ext * rng_f(&g); tmax = tmin + ext * rng_f(&g); }
            break;
        case 5:     /* random, with a finite interval */
            o = rand_in_box(&g, s->bmin, s->bmax, 0.2f);
            d = rng_dir(&g);
            tmin = 0.1f * ext * rng_f(&g); tmax = tmin + 0.5f * ext * rng_f(&g);
            break;
        case 6: {   /* aimed at a vertex or an edge's midpoint exactly (shared edges) */
            fogrt__v3 target = rng_below(&g, 2) ? v0 : fogrt__madd(v0, e, 0.5f);
            o = rand_in_box(&g, s->bmin, s->bmax, 0.3f);
            d = fogrt__sub(target, o);
            if (!(fogrt__length(d) > 0.0f)) d = fogrt__v(0, 1, 0);
            d = fogrt__scale(d, 1.0f / fogrt__length(d));
            break; }
        default: {  /* odd inputs: NaN and infinite parts, empty intervals, tiny directions */
            uint32_t k = rng_below(&g, 7);
            o = rand_in_box(&g, s->bmin, s->bmax, 0.1f);
            d = rng_dir(&g);
            if (k == 0) o.y = NAN;
            if (k == 1) d.z = NAN;
            if (k == 2) { tmin = 1.0f; tmax = 0.5f; }
            if (k == 3) tmin = tmax = 0.25f * ext;
            if (k == 4) o.x = INFINITY;
            if (k == 5) d = fogrt__v(1e-20f, -1e-20f, 1.0f);
            if (k == 6) tmax = NAN;
            break; }
        }
        rays_push(out, o, d, tmin, tmax);
    }
}

/* ---- correctness ---- */
/* The binary traversal with the culling slack: fogrt.h's own. */
#define traverse_slack fogrt__bvh2_traverse

static bool ulp1(float a, float b)
{
    int32_t ia, ib;
    memcpy(&ia, &a, 4); memcpy(&ib, &b, 4);
    if (ia < 0) ia = (int32_t)0x80000000 - ia;
    if (ib < 0) ib = (int32_t)0x80000000 - ib;
    return (ia > ib ? ia - ib : ib - ia) <= 1;
}
typedef struct tally { size_t rays, bad_closest, bad_any, ties, hits, wide_right, bin_right, vs_orig, edge_closer, edge_any, bad_path, path_rays; } tally;
static float prim_t(const fogrt_scene *s, uint32_t id, const ray *r)
{
    float t = -1.0f, u, v;
    if (id < s->tri_count) {
        const fogrt__v3 *tv = &s->tri_v[3 * id];
        if (!fogrt__hit_triangle(r->o, r->d, tv[0], fogrt__sub(tv[1], tv[0]), fogrt__sub(tv[2], tv[0]), r->tmin, r->tmax, &t, &u, &v)) t = -1.0f;
    } else if (!fogrt__hit_sphere(r->o, r->d, s->sph_c[id - s->tri_count], s->sph_r[id - s->tri_count], r->tmin, r->tmax, &t)) {
        t = -1.0f;
    }
    return t;
}
static void compare(const fogrt_scene *s, const fogrt__wbvh *w, const rays *set, tally *tl, const char *what)
{
    size_t i, printed = 0;
    for (i = 0; i < set->n; ++i) {
        const ray *r = &set->r[i];
        fogrt_hit a, b;
        bool ha, hb, aa, ab, edge;
        memset(&a, 0, sizeof a); memset(&b, 0, sizeof b);
        {   /* against the unchanged fogrt__traverse: counted, with brute force's verdict */
            fogrt_hit o1, c1;
            bool h1;
            memset(&o1, 0, sizeof o1);
            h1 = BINARY_TRAVERSE(s, r->o, r->d, r->tmin, r->tmax, &o1, false);
            ha = traverse_slack(s, r->o, r->d, r->tmin, r->tmax, &a, false);
            if (h1 != ha || (ha && (o1.t != a.t || o1.prim != a.prim))) {
                bool hc = fogrt_scene_intersect_brute(s, r->o, r->d, r->tmin, r->tmax, &c1);
                tl->vs_orig++;
                if (hc == ha && (!ha || c1.t == a.t)) tl->wide_right++;
                if (hc == h1 && (!h1 || c1.t == o1.t)) tl->bin_right++;
            }
        }
        hb = fogrt__wbvh_traverse(s, w, r->o, r->d, r->tmin, r->tmax, &b, false);
        {
            fogrt_hit tmp;
            bool a_orig = BINARY_TRAVERSE(s, r->o, r->d, r->tmin, r->tmax, &tmp, true);
            aa = traverse_slack(s, r->o, r->d, r->tmin, r->tmax, &tmp, true);
            ab = fogrt__wbvh_traverse(s, w, r->o, r->d, r->tmin, r->tmax, &tmp, true);
            if (a_orig != aa) aa = !ab;                   /* the unpatched one differs: report it */
        }
        if (w->avx2) {   /* the AVX2 path against the SSE (or plain C) one: bit for bit the same */
            fogrt__wbvh w4 = *w;
            fogrt_hit c, tmp;
            bool hc, ac;
            memset(&c, 0, sizeof c);
            w4.avx2 = false;
            hc = fogrt__wbvh_traverse(s, &w4, r->o, r->d, r->tmin, r->tmax, &c, false);
            ac = fogrt__wbvh_traverse(s, &w4, r->o, r->d, r->tmin, r->tmax, &tmp, true);
            tl->path_rays++;
            if (hc != hb || ac != ab || (hb && (memcmp(&c.t, &b.t, 4) || c.prim != b.prim || memcmp(&c.u, &b.u, 4) || memcmp(&c.v, &b.v, 4)))) {
                tl->bad_path++;
                if (printed++ < 5) fprintf(stderr, "  %s: AVX2 and SSE paths differ at ray %lu\n", what, (unsigned long)i);
            }
        }
        tl->rays++;
        tl->hits += ha;
        edge = !strcmp(set->name, "hard") && i % 8 == 1;   /* along a triangle edge */
        if (aa != ab || aa != ha) {
            fogrt_hit c;
            if (edge && ab && !aa && fogrt_scene_intersect_brute(s, r->o, r->d, r->tmin, r->tmax, &c)) { tl->edge_any++; continue; }
            tl->bad_any++;
            if (printed++ < 5) fprintf(stderr, "  %s: any-hit differs at ray %lu (binary %d, wide %d, closest %d)\n",
                                       what, (unsigned long)i, aa, ab, ha);
        }
        if (ha != hb || (ha && (!ulp1(a.t, b.t) || a.prim != b.prim || a.u != b.u || a.v != b.v))) {
            /* A tie: another primitive hit at exactly the same t. */
            if (ha && hb && a.t == b.t && a.prim != b.prim && prim_t(s, b.prim, r) == b.t && prim_t(s, a.prim, r) == a.t) {
                tl->ties++;
            } else {
                /* A ray along a triangle edge: the wide tree's merged leaf box may let it test
                   a triangle the binary tree's tighter box excluded by rounding. Allowed only
                   when the wide hit is real, closer than the binary one and not closer than
                   brute force's. */
                fogrt_hit c;
                bool hc = fogrt_scene_intersect_brute(s, r->o, r->d, r->tmin, r->tmax, &c);
                if (edge && hb && (!ha || b.t < a.t) && hc && c.t <= b.t && prim_t(s, b.prim, r) == b.t) { tl->edge_closer++; continue; }
                tl->bad_closest++;
                if (printed++ < 5 || getenv("WIDE_DEV_VERBOSE"))
                    fprintf(stderr, "  %s: closest differs at ray %lu: binary %d t=%.9g prim %u, wide %d t=%.9g prim %u\n",
                            what, (unsigned long)i, ha, ha ? a.t : 0.0, ha ? a.prim : 0, hb, hb ? b.t : 0.0, hb ? b.prim : 0);
            }
        }
    }
}
/* The tree itself against brute force on a sample: the patched binary traversal must
   find the same t (any primitive at that t). Returns the number of disagreements. */
static size_t brute_check(const fogrt_scene *s, size_t n, uint64_t seed)
{
    rays set = make_random(s, n, seed);
    size_t i, bad = 0;
    for (i = 0; i < set.n; ++i) {
        const ray *r = &set.r[i];
        fogrt_hit a, c;
        bool ha = traverse_slack(s, r->o, r->d, r->tmin, r->tmax, &a, false);
        bool hc = fogrt_scene_intersect_brute(s, r->o, r->d, r->tmin, r->tmax, &c);
        if (ha != hc || (ha && a.t != c.t)) bad++;
    }
    free(set.r);
    return bad;
}
static bool check_scene(const char *name, const fogrt_scene *s, size_t n_per_family, uint64_t seed, size_t *total_rays)
{
    size_t brute_n = (size_t)(2e8 / (s->tri_count + s->sph_count + 1)), brute_bad = 0;
    fogrt__wbvh w;
    tally tl;
    rays sets[4];
    int k;
    memset(&tl, 0, sizeof tl);
    if (!fogrt__wbvh_build(s, &w, &s->allocator)) { fprintf(stderr, "wide_dev: out of memory\n"); exit(1); }
    sets[0] = make_random(s, n_per_family, seed);
    sets[1] = make_bounce(s, n_per_family, seed + 1, false);
    sets[2] = make_bounce(s, n_per_family / 2, seed + 2, true);
    memset(&sets[3], 0, sizeof sets[3]);
    sets[3].name = "hard";
    add_hard_rays(s, &sets[3], 2 * n_per_family, seed + 3);
    for (k = 0; k < 4; ++k) { compare(s, &w, &sets[k], &tl, name); free(sets[k].r); }
    if (brute_n > 20000) brute_n = 20000;
    if (brute_n) brute_bad = brute_check(s, brute_n, seed + 4);
    printf("  %-28s %7u prims %6lu rays %4.1f%% hit | closest differ %lu, any-hit differ %lu, ties %lu | unpatched fogrt__traverse differs on %lu (brute force agrees: with wide %lu, with unpatched %lu)\n",
           name, s->tri_count + s->sph_count, (unsigned long)tl.rays, 100.0 * (double)tl.hits / (double)(tl.rays ? tl.rays : 1),
           (unsigned long)tl.bad_closest, (unsigned long)tl.bad_any, (unsigned long)tl.ties,
           (unsigned long)tl.vs_orig, (unsigned long)tl.wide_right, (unsigned long)tl.bin_right);
    printf("    rays along an edge where the wide tree finds a real hit the binary tree's boxes missed: %lu closer hits, %lu any-hit\n",
           (unsigned long)tl.edge_closer, (unsigned long)tl.edge_any);
    if (tl.path_rays) printf("    AVX2 path vs SSE path (closest and any hit, bit for bit): %lu of %lu rays differ\n",
                             (unsigned long)tl.bad_path, (unsigned long)tl.path_rays);
    if (brute_n) printf("    binary tree vs brute force: %lu of %lu random rays differ; SAH cost %.3f\n",
                        (unsigned long)brute_bad, (unsigned long)brute_n, fogrt_bvh_sah_cost(s));
    else printf("    SAH cost %.3f\n", fogrt_bvh_sah_cost(s));
    *total_rays += tl.rays;
    fogrt__wbvh_free(&w, &s->allocator);
    return tl.bad_closest == 0 && tl.bad_any == 0 && tl.bad_path == 0 && brute_bad == 0;
}

/* ---- scenes ---- */
static uint32_t add_material(fogrt_scene *s)
{
    fogrt_material_desc m;
    uint32_t id = 0;
    memset(&m, 0, sizeof m);
    m.type = FOGRT_BSDF_DIFFUSE;
    m.reflectance.x = m.reflectance.y = m.reflectance.z = 0.5f;
    check(fogrt_scene_add_material(s, &m, &id), "add_material");
    return id;
}
static void add_mesh(fogrt_scene *s, const float *pos, uint32_t nv, const uint32_t *idx, uint32_t nt, uint32_t mat)
{
    fogrt_mesh_desc mesh;
    memset(&mesh, 0, sizeof mesh);
    mesh.positions = pos; mesh.vertex_count = nv; mesh.indices = idx; mesh.triangle_count = nt; mesh.material = mat;
    check(fogrt_scene_add_mesh(s, &mesh), "add_mesh");
}
/* A lumpy sphere as a latitude-longitude grid: 2 * seg * (rings - 1) triangles. */
static fogrt_scene *lumpy_sphere(uint32_t rings, uint32_t seg)
{
    fogrt_scene *s = NULL;
    uint32_t nv = 2 + (rings - 1) * seg, nt = 2 * seg * (rings - 1), j, i, v = 0, t = 0;
    float *pos = (float *)xmalloc(sizeof(float) * 3 * nv);
    uint32_t *idx = (uint32_t *)xmalloc(sizeof(uint32_t) * 3 * nt);
    check(fogrt_scene_create(NULL, &s), "scene_create");
    pos[v++] = 0.0f; pos[v++] = 1.0f; pos[v++] = 0.0f;
    for (j = 1; j < rings; ++j)
        for (i = 0; i < seg; ++i) {
            float th = 3.14159265f * (float)j / (float)rings, ph = 6.28318531f * (float)i / (float)seg;
            float r = 1.0f + 0.08f * sinf(9.0f * th) * cosf(7.0f * ph) + 0.03f * sinf(31.0f * th + 5.0f * ph);
            pos[v++] = r * sinf(th) * cosf(ph); pos[v++] = r * cosf(th); pos[v++] = r * sinf(th) * sinf(ph);
        }
    pos[v++] = 0.0f; pos[v++] = -1.0f; pos[v++] = 0.0f;
#define RV(ring, k) (1u + ((ring) - 1u) * seg + ((k) % seg))
    for (i = 0; i < seg; ++i) { idx[t++] = 0; idx[t++] = RV(1, i + 1); idx[t++] = RV(1, i); }
    for (j = 1; j + 1 < rings; ++j)
        for (i = 0; i < seg; ++i) {
            uint32_t a = RV(j, i), b = RV(j, i + 1), c = RV(j + 1, i), d = RV(j + 1, i + 1);
            idx[t++] = a; idx[t++] = b; idx[t++] = d; idx[t++] = a; idx[t++] = d; idx[t++] = c;
        }
    for (i = 0; i < seg; ++i) { idx[t++] = nv - 1; idx[t++] = RV(rings - 1, i); idx[t++] = RV(rings - 1, i + 1); }
#undef RV
    add_mesh(s, pos, nv, idx, nt, add_material(s));
    free(pos); free(idx);
    return s;
}
/* A soup: random triangles of mixed sizes, axis-aligned triangles on a coarse grid (many
   shared box faces), degenerate ones (a repeated vertex, collinear vertices, a point), and
   spheres (some overlapping, some tiny). */
static fogrt_scene *soup(uint64_t seed, uint32_t ntri, uint32_t nsph)
{
    fogrt_scene *s = NULL;
    rng g;
    uint32_t i, mat, k;
    float *pos = (float *)xmalloc(sizeof(float) * 9 * ntri);
    uint32_t *idx = (uint32_t *)xmalloc(sizeof(uint32_t) * 3 * ntri);
    g.s = seed;
    check(fogrt_scene_create(NULL, &s), "scene_create");
    mat = add_material(s);
    for (i = 0; i < ntri; ++i) {
        float *p = pos + 9 * i;
        uint32_t kind = rng_below(&g, 10);
        float size = rng_below(&g, 4) == 0 ? 0.5f : 0.05f;
        fogrt__v3 c = fogrt__v(rng_f(&g), rng_f(&g), rng_f(&g));
        for (k = 0; k < 3; ++k) {
            p[3 * k + 0] = c.x + size * (rng_f(&g) - 0.5f);
            p[3 * k + 1] = c.y + size * (rng_f(&g) - 0.5f);
            p[3 * k + 2] = c.z + size * (rng_f(&g) - 0.5f);
        }
        if (kind <= 2) {            /* axis-aligned, on a 1/8 grid */
            int a = (int)rng_below(&g, 3);
            float plane = (float)rng_below(&g, 9) / 8.0f;
            for (k = 0; k < 9; ++k) p[k] = floorf(p[k] * 8.0f) / 8.0f;
            for (k = 0; k < 3; ++k) p[3 * k + (uint32_t)a] = plane;
            if (kind == 2) { p[3] = p[0]; p[4] = p[1] + 0.125f; p[5] = p[2]; p[6] = p[0] + 0.125f; p[7] = p[1]; p[8] = p[2]; p[3 + a] = p[6 + a] = plane; }
        } else if (kind == 3) {     /* repeated vertex */
            p[6] = p[0]; p[7] = p[1]; p[8] = p[2];
        } else if (kind == 4) {     /* collinear */
            for (k = 0; k < 3; ++k) p[6 + k] = 2.0f * p[3 + k] - p[k];
        } else if (kind == 5 && rng_below(&g, 4) == 0) {   /* a point */
            for (k = 3; k < 9; ++k) p[k] = p[k % 3];
        }
        idx[3 * i] = 3 * i; idx[3 * i + 1] = 3 * i + 1; idx[3 * i + 2] = 3 * i + 2;
    }
    if (ntri) add_mesh(s, pos, 3 * ntri, idx, ntri, mat);
    for (i = 0; i < nsph; ++i) {
        fogrt_vec3 c;
        c.x = rng_f(&g); c.y = rng_f(&g); c.z = rng_f(&g);
        check(fogrt_scene_add_sphere(s, c, rng_below(&g, 5) == 0 ? 1e-4f : 0.02f + 0.1f * rng_f(&g), mat), "add_sphere");
    }
    free(pos); free(idx);
    return s;
}
static fogrt_scene *load_bunny(void)
{
    fogrt_scene *s = NULL;
    fogrt_load_options opt;
    fogrt_load_report rep;
    const char *path = FOGRT_SHARED_DIR "/scenes/cs184/CBbunny.dae";
    memset(&opt, 0, sizeof opt);
    check(fogrt_scene_create(NULL, &s), "scene_create");
    if (fogrt_load_file(s, path, &opt, &rep) != FOGRT_RESULT_OK) {
        fprintf(stderr, "wide_dev: cannot load %s (%s:%d: %s); skipping the bunny\n", path, rep.file, rep.line, rep.message);
        fogrt_scene_destroy(s);
        return NULL;
    }
    return s;
}

/* ---- Embree, for comparison (our own small wrapper) ---- */
#ifdef HAVE_EMBREE
typedef struct emb { RTCDevice dev; RTCScene scene; double build_s; long long bytes, peak; } emb;
static bool emb_memory(void *user, ssize_t bytes, bool post)
{
    emb *e = (emb *)user;
    (void)post;
    e->bytes += (long long)bytes;
    if (e->bytes > e->peak) e->peak = e->bytes;
    return true;
}
static void emb_create(emb *e, const fogrt_scene *s)
{
    long long before;
    double t0;
    memset(e, 0, sizeof *e);
    e->dev = rtcNewDevice("threads=1");
    rtcSetDeviceMemoryMonitorFunction(e->dev, emb_memory, e);
    e->scene = rtcNewScene(e->dev);
    if (s->tri_count) {
        RTCGeometry g = rtcNewGeometry(e->dev, RTC_GEOMETRY_TYPE_TRIANGLE);
        float *vb = (float *)rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 12, 3 * (size_t)s->tri_count);
        unsigned *ib = (unsigned *)rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 12, s->tri_count);
        uint32_t i;
        for (i = 0; i < 3 * s->tri_count; ++i) { vb[3 * i] = s->tri_v[i].x; vb[3 * i + 1] = s->tri_v[i].y; vb[3 * i + 2] = s->tri_v[i].z; ib[i] = i; }
        rtcCommitGeometry(g);
        rtcAttachGeometryByID(e->scene, g, 0);
        rtcReleaseGeometry(g);
    }
    if (s->sph_count) {
        RTCGeometry g = rtcNewGeometry(e->dev, RTC_GEOMETRY_TYPE_SPHERE_POINT);
        float *sb = (float *)rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 16, s->sph_count);
        uint32_t i;
        for (i = 0; i < s->sph_count; ++i) { sb[4 * i] = s->sph_c[i].x; sb[4 * i + 1] = s->sph_c[i].y; sb[4 * i + 2] = s->sph_c[i].z; sb[4 * i + 3] = s->sph_r[i]; }
        rtcCommitGeometry(g);
        rtcAttachGeometryByID(e->scene, g, 1);
        rtcReleaseGeometry(g);
    }
    before = e->bytes;
    t0 = wall();
    rtcCommitScene(e->scene);
    e->build_s = wall() - t0;
    e->bytes -= before;          /* what the build added: the BVH and its leaf data */
}
static void emb_destroy(emb *e) { rtcReleaseScene(e->scene); rtcReleaseDevice(e->dev); }
#endif

/* ---- timing ---- */
typedef enum tracer { T_BINARY, T_WIDE, T_EMBREE, T_NUM } tracer;
static const char *tracer_name[T_NUM] = { "binary", "wide", "embree" };
static volatile float sink;
static double trace_pass(tracer k, const fogrt_scene *s, const fogrt__wbvh *w, const rays *set, void *embree, double *cpu_s)
{
    size_t i;
    float acc = 0.0f;
    double t0 = wall(), c0 = cpu();
    (void)embree;
    for (i = 0; i < set->n; ++i) {
        const ray *r = &set->r[i];
        fogrt_hit h;
        bool hit = false;
        h.t = 0.0f;
        if (k == T_BINARY) hit = BINARY_TRAVERSE(s, r->o, r->d, r->tmin, r->tmax, &h, set->shadow);
        else if (k == T_WIDE) hit = fogrt__wbvh_traverse(s, w, r->o, r->d, r->tmin, r->tmax, &h, set->shadow);
#ifdef HAVE_EMBREE
        else {
            emb *e = (emb *)embree;
            struct RTCIntersectContext ctx;
            rtcInitIntersectContext(&ctx);
            if (set->shadow) {
                struct RTCRay ry;
                ry.org_x = r->o.x; ry.org_y = r->o.y; ry.org_z = r->o.z; ry.tnear = r->tmin;
                ry.dir_x = r->d.x; ry.dir_y = r->d.y; ry.dir_z = r->d.z; ry.time = 0.0f; ry.tfar = r->tmax;
                ry.mask = 0xFFFFFFFFu; ry.id = 0; ry.flags = 0;
                rtcOccluded1(e->scene, &ctx, &ry);
                hit = ry.tfar < 0.0f;
            } else {
                struct RTCRayHit rh;
                rh.ray.org_x = r->o.x; rh.ray.org_y = r->o.y; rh.ray.org_z = r->o.z; rh.ray.tnear = r->tmin;
                rh.ray.dir_x = r->d.x; rh.ray.dir_y = r->d.y; rh.ray.dir_z = r->d.z; rh.ray.time = 0.0f; rh.ray.tfar = r->tmax;
                rh.ray.mask = 0xFFFFFFFFu; rh.ray.id = 0; rh.ray.flags = 0;
                rh.hit.geomID = RTC_INVALID_GEOMETRY_ID; rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
                rtcIntersect1(e->scene, &ctx, &rh);
                hit = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
                h.t = rh.ray.tfar;
            }
        }
#endif
        acc += hit ? h.t + 1.0f : 0.0f;
    }
    sink = acc;
    *cpu_s += cpu() - c0;
    return wall() - t0;
}

typedef struct opts { int reps; size_t rays; bool check, speed, big; } opts;
static double g_wall_total, g_cpu_total;

static void speed_scene(const char *name, const fogrt_scene *s, double bin_build_s, const opts *op)
{
    enum { MAXR = 31 };
    fogrt__wbvh w;
    rays sets[3];
    double t0, wide_build_s, wb[MAXR];
    int k, rep, nt = 2;
    void *embree = NULL;
    size_t bin_bytes = sizeof(fogrt_bvh_node) * s->node_count + sizeof(uint32_t) * fogrt__tree_refs(s);
    uint32_t np = s->tri_count + s->sph_count;
#ifdef HAVE_EMBREE
    emb e;
    double eb[MAXR];
    nt = 3;
    for (rep = 0; rep < op->reps; ++rep) { if (rep) emb_destroy(&e); emb_create(&e, s); eb[rep] = e.build_s; }
    embree = &e;
#endif
    for (rep = 0; rep < op->reps; ++rep) {
        t0 = wall();
        if (!fogrt__wbvh_build(s, &w, &g_wide_alloc)) { fprintf(stderr, "wide_dev: out of memory\n"); exit(1); }
        wb[rep] = wall() - t0;
        if (rep + 1 < op->reps) fogrt__wbvh_free(&w, &g_wide_alloc);
    }
    wide_build_s = median(wb, op->reps);
    printf("\n== %s: %u triangles, %u spheres ==\n", name, s->tri_count, s->sph_count);
    printf("build   fogrt_scene_build %.4f s | of which the wide collapse %.4f s", bin_build_s, wide_build_s);
#ifdef HAVE_EMBREE
    {
        double em = median(eb, op->reps);
        printf(" | embree rtcCommitScene %.4f s | fogrt/embree %.2f", em, bin_build_s / em);
    }
#endif
    printf("\nmemory  binary tree %.1f B/tri (nodes %u x 32 + index 4; its packed primitives, 40 more, are made only for the binary layout) | wide %.1f B/tri (%u nodes x %u + %u packets x %u)",
           (double)bin_bytes / np, s->node_count, (double)fogrt__wbvh_bytes(&w) / np, w.node_count,
           (unsigned)sizeof(fogrt__wnode), w.tri_packets, (unsigned)sizeof(fogrt__wtri));
#ifdef HAVE_EMBREE
    printf(" | embree %.1f B/tri (build allocations)", (double)e.bytes / np);
#endif
    printf("\n%-7s %8s | %8s %8s %8s | %8s %8s %8s   (Mrays/s, 1 thread, median of %d; ratios: median of same-run ratios)\n",
           "rays", "count", "binary", "wide", "embree", "w/b", "b/e", "w/e", op->reps);
    sets[0] = make_random(s, op->rays, 12345);
    sets[1] = make_bounce(s, op->rays / 2, 777, false);
    sets[2] = make_bounce(s, op->rays / 2, 999, true);
    for (k = 0; k < 3; ++k) {
        double mr[T_NUM][MAXR], rwb[MAXR], rbe[MAXR], rwe[MAXR];
        int t;
        for (rep = 0; rep < op->reps; ++rep) {
            for (t = 0; t < nt; ++t) {
                int tt = (t + rep) % nt;              /* rotate the order in each repetition */
                double c = 0.0, dt = trace_pass((tracer)tt, s, &w, &sets[k], embree, &c);
                mr[tt][rep] = (double)sets[k].n / dt * 1e-6;
                g_wall_total += dt; g_cpu_total += c;
            }
            rwb[rep] = mr[T_WIDE][rep] / mr[T_BINARY][rep];
            rbe[rep] = nt > 2 ? mr[T_BINARY][rep] / mr[T_EMBREE][rep] : 0.0;
            rwe[rep] = nt > 2 ? mr[T_WIDE][rep] / mr[T_EMBREE][rep] : 0.0;
        }
        printf("%-7s %8lu |", sets[k].name, (unsigned long)sets[k].n);
        for (t = 0; t < T_NUM; ++t) {
            if (t < nt) printf(" %8.2f", median(mr[t], op->reps)); else printf(" %8s", "-");
        }
        printf(" | %8.2f %8.2f %8.2f\n", median(rwb, op->reps), median(rbe, op->reps), median(rwe, op->reps));
        free(sets[k].r);
    }
    (void)tracer_name;
    fogrt__wbvh_free(&w, &g_wide_alloc);
#ifdef HAVE_EMBREE
    emb_destroy(&e);
#endif
}

/* The wide layout leaves out chapter 10's packed primitives (its packets hold their own
   copy); the binary traversal this harness compares with needs them, one per reference of
   the tree (a long sliver's pieces are several). */
static void binary_prims(fogrt_scene *s)
{
    uint32_t n = (uint32_t)fogrt__tree_refs(s);
    if (s->prims) return;
    s->prims = (fogrt__prim *)fogrt__alloc(&s->allocator, sizeof(fogrt__prim) * (n + 1));
    if (!s->prims) { fprintf(stderr, "wide_dev: out of memory\n"); exit(1); }
    fogrt__pack_prims(s, n);
}
static fogrt_scene *built(fogrt_scene *s, double *build_s, int reps)
{
    double t[31];
    int r;
    for (r = 0; r < reps; ++r) {
        double t0 = wall();
        check(fogrt_scene_build(s, NULL), "scene_build");
        t[r] = wall() - t0;
    }
    *build_s = median(t, reps);
    binary_prims(s);
    return s;
}

int main(int argc, char **argv)
{
    opts op;
    int i;
    fogrt_scene *bunny, *big = NULL;
    double bunny_build = 0.0, big_build = 0.0;
    bool ok = true;
    op.reps = 5; op.rays = 1u << 19; op.check = op.speed = op.big = true;
    for (i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--check-only")) op.speed = false;
        else if (!strcmp(argv[i], "--speed-only")) op.check = false;
        else if (!strcmp(argv[i], "--build-only")) op.check = op.speed = false;
        else if (!strcmp(argv[i], "--no-big")) op.big = false;
        else if (!strcmp(argv[i], "--hugepages")) { g_wide_alloc.alloc_fn = huge_alloc; g_wide_alloc.free_fn = huge_free; }
        else if (!strcmp(argv[i], "--reps") && i + 1 < argc) op.reps = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--rays") && i + 1 < argc) op.rays = (size_t)atol(argv[++i]);
        else { fprintf(stderr, "wide_dev: unknown argument '%s' (use --check-only, --speed-only, --build-only, --no-big, --hugepages, --reps N, --rays N)\n", argv[i]); return 2; }
    }
    if (op.reps < 1 || op.reps > 31 || op.rays < 1000) { fprintf(stderr, "wide_dev: --reps 1..31, --rays >= 1000\n"); return 2; }
#ifdef FOGRT_WBVH_SSE
    {
        fogrt__wbvh probe;
        memset(&probe, 0, sizeof probe);
        probe.avx2 = fogrt__wbvh_avx2_usable();
        printf("wide BVH: width %d, %s path\n", FOGRT__WBVH_W, probe.avx2 ? "AVX2 (checked against SSE)" : "SSE");
    }
#else
    printf("wide BVH: width %d, scalar path\n", FOGRT__WBVH_W);
#endif
    bunny = load_bunny();
    if (bunny) built(bunny, &bunny_build, 1);
    if (op.big) built(big = lumpy_sphere(501, 1000), &big_build, 1);
    if (op.check) {
        size_t total = 0;
        uint64_t seed;
        printf("correctness: wide vs binary traversal with the slack (closest hit: same miss or t within 1 ulp and same prim; any hit: same)\n");
        if (bunny) ok &= check_scene("CS184 bunny", bunny, 100000, 11, &total);
        for (seed = 1; seed <= 6; ++seed) {
            char name[64];
            fogrt_scene *s = soup(seed, seed == 6 ? 0 : (uint32_t)(200u << seed), seed == 1 ? 0 : (uint32_t)(10u * seed * seed));
            built(s, &bunny_build, 1);
            snprintf(name, sizeof name, "soup %lu (%u tris, %u spheres)", (unsigned long)seed, s->tri_count, s->sph_count);
            ok &= check_scene(name, s, 20000, 100 + seed, &total);
            fogrt_scene_destroy(s);
        }
        {
            fogrt_scene *s = lumpy_sphere(40, 37);
            built(s, &bunny_build, 1);
            ok &= check_scene("lumpy sphere (2.8k tris)", s, 40000, 300, &total);
            fogrt_scene_destroy(s);
        }
        if (big) ok &= check_scene("1M-triangle lumpy sphere", big, 30000, 400, &total);
        printf("correctness: %lu rays in all, %s\n", (unsigned long)total, ok ? "all agree" : "DISAGREEMENTS (see above)");
    }
    if (op.speed) {
        int sc;
        for (sc = 0; sc < 2; ++sc) {
            fogrt_scene *s = sc ? big : bunny;
            double to[31];
            int r;
            if (!s) continue;
            for (r = 0; r < op.reps; ++r) built(s, &to[r], 1);
            printf("\nbuild   SAH cost %.2f, %u binary nodes", fogrt_bvh_sah_cost(s), s->node_count);
            speed_scene(sc ? "1M-triangle lumpy sphere" : "CS184 bunny", s, median(to, op.reps), &op);
        }
        printf("\nthe timed passes got %.0f%% of a CPU (below ~90%%: the machine is busy, figures too low)\n",
               100.0 * g_cpu_total / (g_wall_total > 0 ? g_wall_total : 1));
    }
    if (bunny) fogrt_scene_destroy(bunny);
    if (big) fogrt_scene_destroy(big);
    return ok ? 0 : 1;
}
