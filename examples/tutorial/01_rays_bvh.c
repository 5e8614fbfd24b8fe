/* 01_rays_bvh.c - tutorial step 1: camera rays and the BVH (docs/tutorial.md, section 1).

   No light transport yet: one ray per pixel, its closest hit from fogrt_scene_intersect, and
   two pictures of what the ray found: the distance t (depth) and the surface normal. The
   scene is the Cornell box plus a tessellated sphere (a mesh of a few thousand triangles)
   and an analytic sphere, built twice: with the surface area heuristic and with the paper's
   volume heuristic. For each tree it prints the node count, the SAH cost and the time to
   trace the image, and checks every hit against testing all primitives one by one.
   Usage: 01_rays_bvh [out.png]                                                             */
#define _POSIX_C_SOURCE 199309L
#include <math.h>
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#include "tutorial.h"

#define RINGS 40                 /* the mesh sphere: RINGS x SEGS quads */
#define SEGS 60
static float mesh_v[(RINGS + 1) * (SEGS + 1) * 3];
static uint32_t mesh_i[RINGS * SEGS * 6];
static const fogrt_vec3 mesh_c = {-0.45f, 0.4f, -0.3f}, ball_c = {0.5f, 0.3f, 0.2f};
static const float mesh_r = 0.4f, ball_r = 0.3f;

static void add_mesh_sphere(fogrt_scene *scene, uint32_t material)
{
    fogrt_mesh_desc md;
    int i, j, n = 0;
    for (i = 0; i <= RINGS; ++i)
        for (j = 0; j <= SEGS; ++j) {
            float th = 3.14159265f * (float)i / RINGS, ph = 6.2831853f * (float)j / SEGS;
            float *v = &mesh_v[3 * (i * (SEGS + 1) + j)];
            v[0] = mesh_c.x + mesh_r * sinf(th) * cosf(ph);
            v[1] = mesh_c.y + mesh_r * cosf(th);
            v[2] = mesh_c.z - mesh_r * sinf(th) * sinf(ph);
        }
    for (i = 0; i < RINGS; ++i)
        for (j = 0; j < SEGS; ++j) {
            uint32_t a = (uint32_t)(i * (SEGS + 1) + j), b = a + SEGS + 1;
            mesh_i[n++] = a; mesh_i[n++] = b; mesh_i[n++] = b + 1;
            mesh_i[n++] = a; mesh_i[n++] = b + 1; mesh_i[n++] = a + 1;
        }
    memset(&md, 0, sizeof md);
    md.positions = mesh_v; md.vertex_count = (RINGS + 1) * (SEGS + 1);
    md.indices = mesh_i; md.triangle_count = RINGS * SEGS * 2;
    md.material = material;
    tut_check(fogrt_scene_add_mesh(scene, &md), "fogrt_scene_add_mesh");
}

/* The geometric normal of primitive `prim` at p. Primitive ids: triangles in the order they
   were added (the 10 wall triangles, the 2 of the lamp, then the mesh), then the spheres. */
static fogrt_vec3 normal_at(uint32_t prim, fogrt_vec3 p)
{
    const float *a, *b, *c;
    fogrt_vec3 n;
    float len;
    if (prim < 10) {                                  /* wall prim/2: corners 0, 1, 2 */
        a = tut_walls[prim / 2]; b = a + 3; c = a + 6;
    } else if (prim < 12) {                           /* the lamp faces down */
        n.x = 0.0f; n.y = -1.0f; n.z = 0.0f;
        return n;
    } else if (prim < 12 + RINGS * SEGS * 2) {
        const uint32_t *t = &mesh_i[3 * (prim - 12)];
        a = &mesh_v[3 * t[0]]; b = &mesh_v[3 * t[1]]; c = &mesh_v[3 * t[2]];
    } else {                                          /* the analytic sphere */
        n.x = (p.x - ball_c.x) / ball_r; n.y = (p.y - ball_c.y) / ball_r; n.z = (p.z - ball_c.z) / ball_r;
        return n;
    }
    n.x = (b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]);
    n.y = (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]);
    n.z = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    len = sqrtf(n.x * n.x + n.y * n.y + n.z * n.z);
    n.x /= len; n.y /= len; n.z /= len;
    return n;
}

/* Traces one ray per pixel; fills depth and normal images (linear RGB) when given. With
   mismatch, also asks brute force (outside the timing) and counts the hits that differ. */
static double trace_image(const fogrt_scene *scene, bool brute, float *depth, float *normal, int *mismatch)
{
    double check_s = 0.0;
    double t0 = tut_now();
    int x, y;
    for (y = 0; y < TUT_H; ++y)
        for (x = 0; x < TUT_W; ++x) {
            fogrt_vec3 o, d, p, n;
            fogrt_hit hit, ref;
            float *dp = depth ? &depth[3 * (y * TUT_W + x)] : NULL, *np = normal ? &normal[3 * (y * TUT_W + x)] : NULL;
            bool found;
            fogrt_camera_ray(scene, TUT_W, TUT_H, x + 0.5f, y + 0.5f, 0.5f, 0.5f, &o, &d);
            found = brute ? fogrt_scene_intersect_brute(scene, o, d, 0.0f, INFINITY, &hit)
                          : fogrt_scene_intersect(scene, o, d, 0.0f, INFINITY, &hit);
            if (mismatch) {
                double c0 = tut_now();
                bool ref_found = fogrt_scene_intersect_brute(scene, o, d, 0.0f, INFINITY, &ref);
                if (ref_found != found || (found && (ref.t != hit.t || ref.prim != hit.prim))) ++*mismatch;
                check_s += tut_now() - c0;
            }
            if (!dp) continue;
            /* depth: t = 2.3 (the nearest point in view) white, t = 4.6 (the back corners) black */
            dp[0] = dp[1] = dp[2] = found ? powf(fminf(fmaxf((4.6f - hit.t) / 2.3f, 0.0f), 1.0f), 2.2f) : 0.0f;
            if (!found) { np[0] = np[1] = np[2] = 0.0f; continue; }
            p.x = o.x + hit.t * d.x; p.y = o.y + hit.t * d.y; p.z = o.z + hit.t * d.z;
            n = normal_at(hit.prim, p);
            if (n.x * d.x + n.y * d.y + n.z * d.z > 0.0f) { n.x = -n.x; n.y = -n.y; n.z = -n.z; }  /* face the eye */
            np[0] = powf(0.5f + 0.5f * n.x, 2.2f);   /* shown as 0.5 + 0.5 n after the sRGB curve */
            np[1] = powf(0.5f + 0.5f * n.y, 2.2f); np[2] = powf(0.5f + 0.5f * n.z, 2.2f);
        }
    return tut_now() - t0 - check_s;
}

int main(int argc, char **argv)
{
    const char *png = argc > 1 ? argv[1] : "01_rays_bvh.png";
    const char *names[2] = {"SAH", "volume heuristic (paper)"};
    float *depth = (float *)malloc(sizeof(float) * 3 * TUT_W * TUT_H), *normal = (float *)malloc(sizeof(float) * 3 * TUT_W * TUT_H);
    tut_strip strip = tut_strip_make(2,
        "Step 1, rays and the BVH: one camera ray per pixel into the Cornell box with a "
        "mesh sphere (4800 triangles, left) and an analytic sphere; no light yet");
    int h, k;
    if (!depth || !normal) return 1;
    for (h = 0; h < 2; ++h) {
        fogrt_scene *scene = tut_scene_create();
        fogrt_build_desc bd = fogrt_build_defaults();
        const fogrt_bvh_node *nodes;
        const uint32_t *prim_index;
        uint32_t node_count;
        fogrt_scene_info info;
        int mismatch = 0;
        double t0, build_s, bvh_s, brute_s;
        tut_cornell_box(scene, 0.3f, 12.0f);   /* the lamp only matters from step 2 on */
        add_mesh_sphere(scene, tut_material(scene, FOGRT_BSDF_DIFFUSE, 0.8f, 0.8f, 0.8f));
        tut_check(fogrt_scene_add_sphere(scene, ball_c, ball_r, 0), "fogrt_scene_add_sphere");
        bd.heuristic = h == 0 ? FOGRT_BVH_SAH : FOGRT_BVH_VOLUME;
        bd.roulette_pilot = false;      /* time the BVH alone: the pilot (chapter 15) renders */
        t0 = tut_now();
        tut_check(fogrt_scene_build(scene, &bd), "fogrt_scene_build");
        build_s = tut_now() - t0;
        fogrt_scene_get_bvh(scene, &nodes, &node_count, &prim_index);
        fogrt_scene_get_info(scene, &info);
        bvh_s = trace_image(scene, false, h == 0 ? depth : NULL, h == 0 ? normal : NULL, &mismatch);
        for (k = 0; k < 4; ++k) bvh_s = fmin(bvh_s, trace_image(scene, false, NULL, NULL, NULL));  /* best of 5 */
        brute_s = trace_image(scene, true, NULL, NULL, NULL);
        printf("%-26s %u triangles + %u sphere: %u nodes, SAH cost %.2f, built in %.1f ms\n", names[h],
               info.triangle_count, info.sphere_count, node_count, fogrt_bvh_sah_cost(scene), 1e3 * build_s);
        printf("%-26s %d rays: BVH %.2f ms, every primitive %.1f ms (%.0fx), %d hits differ from brute force\n", "",
               TUT_W * TUT_H, 1e3 * bvh_s, 1e3 * brute_s, brute_s / bvh_s, mismatch);
        fogrt_scene_destroy(scene);
    }
    tut_strip_put(&strip, 0, depth, 1.0f);
    tut_strip_caption(&strip, 0, "depth: distance t to the closest hit", "white t = 2.3, black t = 4.6 scene units");
    tut_strip_put(&strip, 1, normal, 1.0f);
    tut_strip_caption(&strip, 1, "surface normal n, turned to face the eye", "colour 0.5 + 0.5 n: x red, y green, z blue");
    printf("time and error: one ray per pixel, no Monte Carlo, so no error estimate yet\n");
    tut_strip_write(&strip, png);
    free(depth); free(normal);
    return 0;
}
