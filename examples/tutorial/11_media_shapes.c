/* 11_media_shapes.c - tutorial step 11: media inside shapes (docs/tutorial.md, section 11;
   beyond the paper: fogrt.h, Part II, H).

   The paper's fog fills all space outside refractive objects. fogrt_scene_set_interior
   gives a closed shape a medium of its own instead:
     1. a glass sphere filled with smoke, in a box without fog (the smoke is lit through the
        glass, and the glass refracts the box around it);
     2. a fog volume shaped as a U, whose surface is an interface (FOGRT_BSDF_INTERFACE: no
        reflection, no refraction, it only bounds the medium): a concave fog shape;
     3. the smoke-filled glass again, now inside the room's own fog: media nest.
   Usage: 11_media_shapes [out.png [samples_per_pixel]]                                     */
#define _POSIX_C_SOURCE 199309L
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#define TUT_W 200
#define TUT_H 150
#include "tutorial.h"

static fogrt_medium_desc tut_medium(float sigma_t, float albedo, float g)
{
    fogrt_medium_desc m;
    memset(&m, 0, sizeof m);
    m.sigma_t = sigma_t;
    m.albedo.x = m.albedo.y = m.albedo.z = albedo;
    m.g = g;
    return m;
}

/* The glass sphere on the floor, filled with smoke (sphere 0 of the scene). */
static void smoke_glass(fogrt_scene *scene)
{
    fogrt_medium_desc smoke = tut_medium(5.0f, 0.95f, 0.3f);
    fogrt_vec3 c;
    c.x = 0.0f; c.y = 0.45f; c.z = -0.1f;
    tut_check(fogrt_scene_add_sphere(scene, c, 0.45f, tut_material(scene, FOGRT_BSDF_GLASS, 1.0f, 1.0f, 1.0f)),
              "fogrt_scene_add_sphere");
    tut_check(fogrt_scene_set_interior(scene, FOGRT_SHAPE_SPHERE, 0, &smoke), "fogrt_scene_set_interior");
}

/* A U-shaped prism standing on the floor (10 outline points, its caps as 8 triangles), with
   an interface surface and dense fog inside; it is the scene's mesh number `mesh`. */
static void fog_u(fogrt_scene *scene, uint32_t mesh)
{
    static const float outline[10][2] = {{0, 0}, {1, 0}, {2, 0}, {3, 0}, {3, 2}, {2, 2}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
    static const int cap[8][3] = {{0, 1, 7}, {0, 7, 8}, {0, 8, 9}, {1, 2, 6}, {1, 6, 7}, {2, 3, 4}, {2, 4, 5}, {2, 5, 6}};
    fogrt_medium_desc fog = tut_medium(6.0f, 0.9f, 0.0f);
    float pos[60];
    uint32_t idx[3 * (20 + 16)];
    fogrt_mesh_desc md;
    int i, t = 0;
    for (i = 0; i < 10; ++i) {   /* 0.3 units a cell, centred, 0.4 deep, just above the floor
                                    (an interface must not lie in another surface's plane) */
        float x = -0.45f + 0.3f * outline[i][0], y = 0.005f + 0.3f * outline[i][1];
        pos[3 * i] = x; pos[3 * i + 1] = y; pos[3 * i + 2] = -0.5f;
        pos[30 + 3 * i] = x; pos[30 + 3 * i + 1] = y; pos[30 + 3 * i + 2] = -0.1f;
    }
    for (i = 0; i < 10; ++i) {                     /* walls, then the two caps */
        uint32_t a = (uint32_t)i, b = (uint32_t)((i + 1) % 10);
        idx[t++] = a; idx[t++] = b; idx[t++] = b + 10;
        idx[t++] = a; idx[t++] = b + 10; idx[t++] = a + 10;
    }
    for (i = 0; i < 8; ++i) {
        idx[t++] = (uint32_t)cap[i][0]; idx[t++] = (uint32_t)cap[i][2]; idx[t++] = (uint32_t)cap[i][1];
        idx[t++] = (uint32_t)cap[i][0] + 10; idx[t++] = (uint32_t)cap[i][1] + 10; idx[t++] = (uint32_t)cap[i][2] + 10;
    }
    memset(&md, 0, sizeof md);
    md.positions = pos; md.vertex_count = 20;
    md.indices = idx; md.triangle_count = (uint32_t)(t / 3);
    md.material = tut_material(scene, FOGRT_BSDF_INTERFACE, 0.0f, 0.0f, 0.0f);
    tut_check(fogrt_scene_add_mesh(scene, &md), "fogrt_scene_add_mesh");
    tut_check(fogrt_scene_set_interior(scene, FOGRT_SHAPE_MESH, mesh, &fog), "fogrt_scene_set_interior");
}

int main(int argc, char **argv)
{
    const char *png = argc > 1 ? argv[1] : "11_media_shapes.png";
    int spp = argc > 2 ? atoi(argv[2]) : 64;
    tut_strip strip = tut_strip_make(3,
        "Step 11, media inside shapes: smoke in a glass sphere, a concave fog volume behind an "
        "interface, and the filled glass inside the room's fog");
    fogrt_render_desc rd = fogrt_render_defaults();
    fogrt_scene *scene;
    int k;
    if (spp < 1) { fprintf(stderr, "11_media_shapes: samples_per_pixel must be >= 1\n"); return 2; }
    for (k = 0; k < 3; ++k) {
        static const char *label[3] = { "smoke in a glass sphere", "a U of fog (interface)", "the glass in the room's fog" };
        scene = tut_scene_create();
        tut_cornell_box(scene, 0.3f, 12.0f);         /* meshes 0-5: five walls and the lamp */
        if (k == 1) fog_u(scene, 6);
        else smoke_glass(scene);
        if (k == 2) tut_fog(scene, 0.3f, 0.9f, 0.5f);
        tut_check(fogrt_scene_build(scene, NULL), "fogrt_scene_build");
        (void)tut_render(scene, &rd, spp, label[k], &strip, k, 1.0f);
        fogrt_scene_destroy(scene);
    }
    tut_strip_write(&strip, png);
    return 0;
}
