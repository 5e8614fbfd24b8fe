/* One side of the A/B harness: a whole fogrt (FOGRT_STATIC) from FOGRT_AB_HEADER, behind
   functions named AB_SIDE##_... */
#define FOGRT_STATIC
#define FOGRT_IMPLEMENTATION
#include FOGRT_AB_HEADER
#define AB_CAT(a, b) a##b
#define AB_XCAT(a, b) AB_CAT(a, b)
#define AB_NAME(x) AB_XCAT(AB_SIDE, x)
void *AB_NAME(_build)(const float *pos, uint32_t nv, const uint32_t *idx, uint32_t nt);
void AB_NAME(_trace)(const void *s, const float *rays, size_t n, bool any, float *t, uint32_t *p);
size_t AB_NAME(_memory)(const void *s);
void AB_NAME(_destroy)(void *s);
void *AB_NAME(_build)(const float *pos, uint32_t nv, const uint32_t *idx, uint32_t nt)
{
    fogrt_scene *s = NULL;
    fogrt_material_desc m;
    fogrt_mesh_desc mesh;
    uint32_t mat = 0;
    if (fogrt_scene_create(NULL, &s) != FOGRT_RESULT_OK) return NULL;
    memset(&m, 0, sizeof m);
    m.type = FOGRT_BSDF_DIFFUSE;
    m.reflectance.x = m.reflectance.y = m.reflectance.z = 0.5f;
    fogrt_scene_add_material(s, &m, &mat);
    memset(&mesh, 0, sizeof mesh);
    mesh.positions = pos; mesh.vertex_count = nv; mesh.indices = idx; mesh.triangle_count = nt; mesh.material = mat;
    fogrt_scene_add_mesh(s, &mesh);
    if (fogrt_scene_build(s, NULL) != FOGRT_RESULT_OK) return NULL;
    return s;
}
__attribute__((noinline)) void AB_NAME(_trace)(const void *sv, const float *rays, size_t n, bool any, float *t, uint32_t *p)
{
    const fogrt_scene *s = (const fogrt_scene *)sv;
    size_t i;
    for (i = 0; i < n; i++) {
        const float *r = rays + 8 * i;
        fogrt_vec3 o, d;
        fogrt_hit hit;
        o.x = r[0]; o.y = r[1]; o.z = r[2];
        d.x = r[4]; d.y = r[5]; d.z = r[6];
        t[i] = -1.0f; p[i] = UINT32_MAX;
        if (any) { if (fogrt_scene_occluded(s, o, d, r[3], r[7])) t[i] = 0.0f; }
        else if (fogrt_scene_intersect(s, o, d, r[3], r[7], &hit)) { t[i] = hit.t; p[i] = hit.prim; }
    }
}
size_t AB_NAME(_memory)(const void *s) { return fogrt_scene_get_memory((const fogrt_scene *)s); }
void AB_NAME(_destroy)(void *s) { fogrt_scene_destroy((fogrt_scene *)s); }
