/* bench_embree.c - the Embree 3 side of bench/bench.c: the same triangles (and spheres) in an
   Embree scene, the same rays traced one at a time with rtcIntersect1 (closest hit) or
   rtcOccluded1 (any hit), and the bytes the scene allocates.

   Built and linked (-lembree3) by mk/bench.mk only when /usr/include/embree3/rtcore.h exists
   (Debian: apt-get install libembree-dev). bench.c then defines HAVE_EMBREE and calls the
   functions below; their prototypes are repeated there.

   Rays are packed 8 floats each: ox oy oz tmin dx dy dz tmax (the layout bench.c uses). A hit
   returns t and the primitive id in fogrt's numbering: triangles first, then spheres, so the
   two tracers can be compared ray by ray. A miss returns t = -1 and prim = UINT32_MAX. An
   any-hit query returns t = 0 when the ray is occluded, -1 when it is not.

   Memory: the device's memory monitor callback sums every allocation and release Embree makes
   (bytes > 0 allocated, < 0 freed). The device builds on one thread (threads=1), so the
   callback is never called from two threads at once. */
#include <embree3/rtcore.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#ifdef _OPENMP
#include <omp.h>
#endif

typedef struct bench_embree {
    RTCDevice device;
    RTCScene scene;
    uint32_t triangle_count;
    long long live, peak;          /* bytes allocated now, and the most since peak was reset */
    long long before_commit;       /* live just before rtcCommitScene: the geometry buffers */
    long long commit_peak, commit_final;   /* peak during and live after it, above before_commit */
} bench_embree;

static bool bench_embree__monitor(void *user, ssize_t bytes, bool post)
{
    bench_embree *e = (bench_embree *)user;
    (void)post;           /* an allocation is reported before it (post false), a release after */
    e->live += (long long)bytes;
    if (e->live > e->peak) e->peak = e->live;
    return true;          /* never refuse an allocation */
}

/* Wall-clock seconds (the same clock as bench.c uses). */
static double bench_embree__now(void)
{
#ifdef _OPENMP
    return omp_get_wtime();
#else
    return (double)clock() / CLOCKS_PER_SEC;
#endif
}

static void bench_embree__error(void *user, enum RTCError code, const char *message)
{
    (void)user;
    fprintf(stderr, "embree error %d: %s\n", (int)code, message ? message : "");
}

const char *bench_embree_version(void) { return RTC_VERSION_STRING; }

/* Builds the Embree scene: geometry 0 holds the triangles, geometry 1 the spheres (x, y, z, r
   per sphere), so primID + (geomID ? triangle_count : 0) is fogrt's primitive id. Embree's
   builder runs on build_threads threads (1 makes its build time comparable with fogrt's
   single-threaded build). *build_seconds receives the time of rtcCommitScene alone. */
bench_embree *bench_embree_create(const float *positions, uint32_t vertex_count,
                                  const uint32_t *indices, uint32_t triangle_count,
                                  const float *spheres, uint32_t sphere_count,
                                  int build_threads, double *build_seconds)
{
    char config[64];
    bench_embree *e = (bench_embree *)calloc(1, sizeof *e);
    if (!e) return NULL;
    snprintf(config, sizeof config, "threads=%d", build_threads > 0 ? build_threads : 0);
    e->device = rtcNewDevice(config);
    if (!e->device) { free(e); return NULL; }
    rtcSetDeviceErrorFunction(e->device, bench_embree__error, NULL);
    rtcSetDeviceMemoryMonitorFunction(e->device, bench_embree__monitor, e);
    e->scene = rtcNewScene(e->device);
    e->triangle_count = triangle_count;

    if (triangle_count > 0) {
        RTCGeometry geom = rtcNewGeometry(e->device, RTC_GEOMETRY_TYPE_TRIANGLE);
        float *vb = (float *)rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                     3 * sizeof(float), vertex_count);
        unsigned *ib = (unsigned *)rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                           3 * sizeof(unsigned), triangle_count);
        memcpy(vb, positions, sizeof(float) * 3 * vertex_count);
        memcpy(ib, indices, sizeof(unsigned) * 3 * triangle_count);
        rtcCommitGeometry(geom);
        rtcAttachGeometryByID(e->scene, geom, 0);
        rtcReleaseGeometry(geom);
    }
    if (sphere_count > 0) {
        RTCGeometry geom = rtcNewGeometry(e->device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
        float *sb = (float *)rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4,
                                                     4 * sizeof(float), sphere_count);
        memcpy(sb, spheres, sizeof(float) * 4 * sphere_count);
        rtcCommitGeometry(geom);
        rtcAttachGeometryByID(e->scene, geom, 1);
        rtcReleaseGeometry(geom);
    }
    {
        double t0;
        e->before_commit = e->peak = e->live;
        t0 = bench_embree__now();
        rtcCommitScene(e->scene);
        if (build_seconds) *build_seconds = bench_embree__now() - t0;
        e->commit_peak = e->peak - e->before_commit;
        e->commit_final = e->live - e->before_commit;
    }
    if (rtcGetDeviceError(e->device) != RTC_ERROR_NONE) {
        rtcReleaseScene(e->scene);
        rtcReleaseDevice(e->device);
        free(e);
        return NULL;
    }
    return e;
}

/* Ray i of the rays array (origin, tnear, direction, tfar) as an Embree ray. */
static void bench_embree_ray(const float *r, struct RTCRay *ray)
{
    ray->org_x = r[0]; ray->org_y = r[1]; ray->org_z = r[2]; ray->tnear = r[3];
    ray->dir_x = r[4]; ray->dir_y = r[5]; ray->dir_z = r[6]; ray->time = 0.0f;
    ray->tfar = r[7];
    ray->mask = 0xFFFFFFFFu; ray->id = 0; ray->flags = 0;
}

/* Every ray, on `threads` OpenMP threads, one query per ray: closest hit (rtcIntersect1: t
   and the primitive, or t = -1 and UINT32_MAX on a miss), or with any_hit any hit
   (rtcOccluded1, tnear < t < tfar as Embree counts it: t = 0 when ray i is occluded, -1
   when not; the primitive is UINT32_MAX). */
void bench_embree_trace(const bench_embree *e, const float *rays, size_t ray_count, int threads, bool any_hit,
                        float *t_out, uint32_t *prim_out)
{
    long i, n = (long)ray_count;
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1024) num_threads(threads)
#else
    (void)threads;
#endif
    for (i = 0; i < n; i++) {
        const float *r = rays + 8 * (size_t)i;
        struct RTCIntersectContext context;
        struct RTCRayHit rh;
        rtcInitIntersectContext(&context);
        bench_embree_ray(r, &rh.ray);
        prim_out[i] = UINT32_MAX;
        if (any_hit) {
            rtcOccluded1(e->scene, &context, &rh.ray);
            t_out[i] = rh.ray.tfar < 0.0f ? 0.0f : -1.0f;   /* Embree sets tfar = -inf on a hit */
            continue;
        }
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(e->scene, &context, &rh);
        t_out[i] = -1.0f;
        if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
            t_out[i] = rh.ray.tfar;
            prim_out[i] = rh.hit.primID + (rh.hit.geomID == 1 ? e->triangle_count : 0u);
        }
    }
}

/* Bytes Embree allocated for the scene: the geometry buffers set before rtcCommitScene, and
   what rtcCommitScene added (its peak while building, and what it kept). */
void bench_embree_memory(const bench_embree *e, double *buffers, double *commit_peak, double *commit_final)
{
    *buffers = (double)e->before_commit;
    *commit_peak = (double)e->commit_peak;
    *commit_final = (double)e->commit_final;
}

void bench_embree_destroy(bench_embree *e)
{
    if (!e) return;
    rtcReleaseScene(e->scene);
    rtcReleaseDevice(e->device);
    free(e);
}
