/* bench/build_cost.c - the scene build of one mesh alone, for callgrind or a stopwatch
   (docs/benchmarks.md, table "Wide BVH": the binned split in SSE lanes).

   The mesh is bench.c's displaced sphere: R rings of R segments, 2 R (R - 1) triangles
   (R = 300: 179,400; R = 700: 978,600). fogrt_scene_build runs with the defaults but the
   roulette's pilot (which traces rays), REPS times; the program prints the node count, a
   hash of the nodes (two headers that build the same tree print the same hash) and, for
   REPS > 1, the least CPU time of one build.

     cc -std=c99 -O2 -g -I. -o build/build_cost bench/build_cost.c -lm
     valgrind --tool=callgrind --toggle-collect=fogrt_scene_build build/build_cost 300
     build/build_cost 700 7

   Usage: build_cost [R [REPS]]   (-I another directory builds another fogrt.h) */
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* bench.c's make_displaced_sphere, R rings of R segments. */
static void sphere_mesh(uint32_t rings, float **pos, uint32_t **idx, uint32_t *vc, uint32_t *tc)
{
    const float pi = 3.14159265358979f;
    uint32_t segs = rings, j, i, v = 0, t = 0;
    float *p;
    uint32_t *x;
    *vc = 2 + (rings - 1) * segs;
    *tc = 2 * segs * (rings - 1);
    p = *pos = (float *)malloc(sizeof(float) * 3 * *vc);
    x = *idx = (uint32_t *)malloc(sizeof(uint32_t) * 3 * *tc);
    if (!p || !x) { fprintf(stderr, "build_cost: out of memory\n"); exit(1); }
    p[v++] = 0.0f; p[v++] = 1.0f; p[v++] = 0.0f;
    for (j = 1; j < rings; j++) {
        float th = pi * (float)j / (float)rings;
        for (i = 0; i < segs; i++) {
            float ph = 2.0f * pi * (float)i / (float)segs;
            float r = 1.0f + 0.08f * sinf(9.0f * th) * cosf(7.0f * ph) + 0.03f * sinf(31.0f * th + 5.0f * ph);
            p[v++] = r * sinf(th) * cosf(ph); p[v++] = r * cosf(th); p[v++] = r * sinf(th) * sinf(ph);
        }
    }
    p[v++] = 0.0f; p[v++] = -1.0f; p[v++] = 0.0f;
#define RING_VERTEX(ring, seg) (1u + ((ring) - 1u) * segs + ((seg) % segs))
    for (i = 0; i < segs; i++) { x[t++] = 0; x[t++] = RING_VERTEX(1, i + 1); x[t++] = RING_VERTEX(1, i); }
    for (j = 1; j + 1 < rings; j++)
        for (i = 0; i < segs; i++) {
            uint32_t a = RING_VERTEX(j, i), b = RING_VERTEX(j, i + 1), c = RING_VERTEX(j + 1, i), d = RING_VERTEX(j + 1, i + 1);
            x[t++] = a; x[t++] = b; x[t++] = d; x[t++] = a; x[t++] = d; x[t++] = c;
        }
    for (i = 0; i < segs; i++) { x[t++] = *vc - 1; x[t++] = RING_VERTEX(rings - 1, i); x[t++] = RING_VERTEX(rings - 1, i + 1); }
#undef RING_VERTEX
}

int main(int argc, char **argv)
{
    uint32_t rings = argc > 1 ? (uint32_t)atoi(argv[1]) : 300, vc, tc, mat, nc;
    int rep, reps = argc > 2 ? atoi(argv[2]) : 1;
    float *pos;
    uint32_t *idx;
    fogrt_scene *scene;
    fogrt_material_desc m;
    fogrt_mesh_desc mesh;
    fogrt_build_desc bd;
    const fogrt_bvh_node *nodes;
    unsigned long long hash = 1469598103934665603ULL;   /* FNV-1a over the nodes' bytes */
    double best = 1e30;
    size_t k;
    if (rings < 3 || rings > 10000 || reps < 1) { fprintf(stderr, "usage: build_cost [R (3..10000) [REPS]]\n"); return 2; }
    sphere_mesh(rings, &pos, &idx, &vc, &tc);
    if (fogrt_scene_create(NULL, &scene) != FOGRT_RESULT_OK) return 1;
    memset(&m, 0, sizeof m);
    m.reflectance.x = m.reflectance.y = m.reflectance.z = 0.5f;
    memset(&mesh, 0, sizeof mesh);
    mesh.positions = pos; mesh.vertex_count = vc; mesh.indices = idx; mesh.triangle_count = tc;
    if (fogrt_scene_add_material(scene, &m, &mat) != FOGRT_RESULT_OK) return 1;
    mesh.material = mat;
    if (fogrt_scene_add_mesh(scene, &mesh) != FOGRT_RESULT_OK) return 1;
    bd = fogrt_build_defaults();
    bd.roulette_pilot = false;
    for (rep = 0; rep < reps; rep++) {
        clock_t c0 = clock();
        double dt;
        if (fogrt_scene_build(scene, &bd) != FOGRT_RESULT_OK) return 1;
        dt = (double)(clock() - c0) / CLOCKS_PER_SEC;
        if (dt < best) best = dt;
    }
    fogrt_scene_get_bvh(scene, &nodes, &nc, NULL);
    for (k = 0; k < nc * sizeof *nodes; k++) hash = (hash ^ ((const unsigned char *)nodes)[k]) * 1099511628211ULL;
    printf("%u triangles: %u nodes, hash %016llx", tc, nc, hash);
    if (reps > 1) printf(", least CPU time of %d builds %.3f s", reps, best);
    printf("\n");
    fogrt_scene_destroy(scene);
    free(pos); free(idx);
    return 0;
}
