/* bvh_paths.c - fogrt_scene_build with Part I's scalar binned split, for test_bvh.c.
 *
 * The library builds each node's split in SSE lanes (appendix A, seam 2) and must give the
 * tree that Part I's scalar code gives, bit for bit. One program cannot hold both with a
 * single copy of fogrt.h, so this file is compiled twice and linked into test_bvh, each copy
 * private to its object file (FOGRT_STATIC):
 *   -DFOGRT_WBVH_NO_SIMD  -DBVH_PATHS_NAME=bvh_paths_nosimd   the full build, the split scalar
 *   -DFOGRT_NO_WIDE_BVH   -DBVH_PATHS_NAME=bvh_paths_nowide   no appendix A at all
 * (mk/test_bvh.mk). Either exports one function, declared in test_bvh.c. */
#define FOGRT_STATIC
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"

#include <stdlib.h>
#include <string.h>

/* The tree of tri_count triangles (3 vertices each, as 9 floats) and sph_count spheres
   (x, y, z, radius), built with desc: its nodes and primitive order, copied into malloc'ed
   arrays the caller frees. Returns the node count, or 0 when the build or a copy fails. */
uint32_t BVH_PATHS_NAME(const float *tri, uint32_t tri_count, const float *sph, uint32_t sph_count,
                        const fogrt_build_desc *desc, fogrt_bvh_node **nodes, uint32_t **prim_index);
uint32_t BVH_PATHS_NAME(const float *tri, uint32_t tri_count, const float *sph, uint32_t sph_count,
                        const fogrt_build_desc *desc, fogrt_bvh_node **nodes, uint32_t **prim_index)
{
    fogrt_scene *s = NULL;
    fogrt_material_desc m;
    fogrt_mesh_desc mesh;
    uint32_t id, i, count = 0, n = tri_count + sph_count;
    bool ok;
    *nodes = NULL; *prim_index = NULL;
    if (fogrt_scene_create(NULL, &s) != FOGRT_RESULT_OK) return 0;
    memset(&m, 0, sizeof m);
    m.reflectance.x = m.reflectance.y = m.reflectance.z = 0.5f;
    ok = fogrt_scene_add_material(s, &m, &id) == FOGRT_RESULT_OK;
    if (ok && tri_count > 0) {
        memset(&mesh, 0, sizeof mesh);
        mesh.positions = tri; mesh.vertex_count = 3 * tri_count; mesh.triangle_count = tri_count; mesh.material = id;
        ok = fogrt_scene_add_mesh(s, &mesh) == FOGRT_RESULT_OK;
    }
    for (i = 0; ok && i < sph_count; ++i) {
        fogrt_vec3 c;
        c.x = sph[4 * i]; c.y = sph[4 * i + 1]; c.z = sph[4 * i + 2];
        ok = fogrt_scene_add_sphere(s, c, sph[4 * i + 3], id) == FOGRT_RESULT_OK;
    }
    ok = ok && fogrt_scene_build(s, desc) == FOGRT_RESULT_OK;
    if (ok) {
        *nodes = (fogrt_bvh_node *)malloc(sizeof(fogrt_bvh_node) * s->node_count);
        *prim_index = (uint32_t *)malloc(sizeof(uint32_t) * (n + 1));
        if (*nodes && *prim_index) {
            memcpy(*nodes, s->nodes, sizeof(fogrt_bvh_node) * s->node_count);
            memcpy(*prim_index, s->prim_index, sizeof(uint32_t) * n);
            count = s->node_count;
        }
    }
    fogrt_scene_destroy(s);
    return count;
}
