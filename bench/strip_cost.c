/* strip_cost.c - fixed renders for bench/callgrind.sh: does a scene pay for a feature it
   does not use?

   fogrt promises that a scene pays only for what it uses: a scene without fog costs what a
   FOGRT_NO_MEDIUM build costs, a scene without glass what a FOGRT_NO_GLASS build costs, a
   render with Schlick's Fresnel what a FOGRT_NO_EXACT_FRESNEL build costs, fog with the
   paper's phase function and no emission what a FOGRT_NO_MEDIA build costs, a scene without
   rough metals what a FOGRT_NO_MICROFACET build costs. callgrind.sh
   builds this program normally and with the strip macro, runs both under callgrind counting
   only the instructions executed inside fogrt_render, and compares the totals.

     strip_cost medium   the default scene with its fog switched off
     strip_cost glass    a fog-filled box with a diffuse and a mirror sphere (no glass)
     strip_cost exact    the default scene (glass sphere, fog), rendered with Schlick
     strip_cost media    the default scene: grey HG fog, no emission (FOGRT_NO_MEDIA: appendix G)
     strip_cost microfacet  the glass-free box (diffuse and mirror, no rough metal: appendix I)

   Small renders with a fixed seed and sample count on one thread (build without -fopenmp),
   so the count is the same on every run. Prints the mean radiance and a checksum of the
   image, so that the two builds can be seen to render the same picture.                  */
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define WIDTH 64
#define HEIGHT 48
#define SPP 8

static void check(fogrt_result r, const char *what)
{
    if (r != FOGRT_RESULT_OK) {
        fprintf(stderr, "strip_cost: %s failed: %s\n", what, fogrt_result_string(r));
        exit(1);
    }
}
static fogrt_vec3 v3(float x, float y, float z) { fogrt_vec3 v; v.x = x; v.y = y; v.z = z; return v; }

/* The glass-free scene: the floor and back wall of a box, a lamp, a diffuse and a mirror
   sphere, a spot light, fog. The same in every build. */
static void glass_free_scene(fogrt_scene *scene)
{
    static const float quads[3][12] = {
        { -1, 0, -1,  -1, 0, 1,  1, 0, 1,  1, 0, -1 },                                 /* floor */
        { -1, 0, -1,  1, 0, -1,  1, 1.5f, -1,  -1, 1.5f, -1 },                         /* back */
        { -0.35f, 1.49f, -0.35f,  0.35f, 1.49f, -0.35f,  0.35f, 1.49f, 0.35f,  -0.35f, 1.49f, 0.35f } };
    static const uint32_t idx[6] = { 0, 1, 2, 0, 2, 3 };
    fogrt_material_desc m;
    fogrt_mesh_desc mesh;
    fogrt_light_desc l;
    fogrt_medium_desc fog;
    fogrt_camera_desc cam;
    uint32_t ids[4], i;
    memset(&m, 0, sizeof m);
    m.reflectance = v3(0.7f, 0.7f, 0.7f); check(fogrt_scene_add_material(scene, &m, &ids[0]), "material");
    m.type = FOGRT_BSDF_MIRROR; m.reflectance = v3(0.9f, 0.9f, 0.9f); check(fogrt_scene_add_material(scene, &m, &ids[1]), "material");
    m.type = FOGRT_BSDF_DIFFUSE; m.reflectance = v3(0, 0, 0); m.emission = v3(8, 6, 3);
    check(fogrt_scene_add_material(scene, &m, &ids[2]), "material");
    for (i = 0; i < 3; ++i) {
        memset(&mesh, 0, sizeof mesh);
        mesh.positions = quads[i]; mesh.vertex_count = 4; mesh.indices = idx; mesh.triangle_count = 2;
        mesh.material = i == 2 ? ids[2] : ids[0];
        check(fogrt_scene_add_mesh(scene, &mesh), "mesh");
    }
    check(fogrt_scene_add_sphere(scene, v3(-0.45f, 0.35f, -0.35f), 0.35f, ids[0]), "sphere");
    check(fogrt_scene_add_sphere(scene, v3(0.45f, 0.35f, 0.25f), 0.35f, ids[1]), "sphere");
    memset(&l, 0, sizeof l);
    l.type = FOGRT_LIGHT_SPOT; l.position = v3(-0.8f, 1.4f, 0.6f); l.direction = v3(1.1f, -1.4f, -0.6f);
    l.intensity = v3(16, 20, 26); l.cutoff_deg = 16; l.beam_deg = 11;
    check(fogrt_scene_add_light(scene, &l), "light");
    memset(&cam, 0, sizeof cam);
    cam.position = v3(0, 0.75f, 3.6f); cam.look_at = v3(0, 0.7f, 0); cam.fov_deg = 38;
    check(fogrt_scene_set_camera(scene, &cam), "camera");
#ifndef FOGRT_NO_MEDIUM
    memset(&fog, 0, sizeof fog);
    fog.sigma_t = 0.3f; fog.albedo = v3(0.9f, 0.9f, 0.9f); fog.g = 0.6f;
    check(fogrt_scene_set_medium(scene, &fog), "medium");
#else
    (void)fog;
#endif
}

static fogrt_result (*volatile render_fn)(const fogrt_scene *, const fogrt_render_desc *, fogrt_image *,
                                          int, fogrt_render_stats *);

int main(int argc, char **argv)
{
    const char *mode = argc > 1 ? argv[1] : "medium";
    fogrt_scene *scene = NULL;
    fogrt_render_desc rd;
    fogrt_render_stats stats;
    fogrt_image img;
    float *rgb;
    double mean = 0.0;
    uint32_t checksum = 2166136261u;   /* FNV-1a over the bytes of the resolved image */
    size_t i;

    check(fogrt_scene_create(NULL, &scene), "fogrt_scene_create");
    if (strcmp(mode, "glass") == 0 || strcmp(mode, "microfacet") == 0) {
        glass_free_scene(scene);
    } else {
        check(fogrt_scene_add_default(scene), "fogrt_scene_add_default");
        if (strcmp(mode, "medium") == 0) {
            fogrt_medium_desc medium;
            fogrt_scene_get_medium(scene, &medium);
            medium.sigma_t = 0.0f;                              /* no fog */
            check(fogrt_scene_set_medium(scene, &medium), "fogrt_scene_set_medium");
        } else if (strcmp(mode, "exact") != 0 && strcmp(mode, "media") != 0) {
            fprintf(stderr, "strip_cost: unknown mode '%s' (medium, glass, exact, media or microfacet)\n", mode);
            return 2;
        }
    }
    check(fogrt_scene_build(scene, NULL), "fogrt_scene_build");
    check(fogrt_image_alloc(&img, WIDTH, HEIGHT, NULL), "fogrt_image_alloc");

    rd = fogrt_render_defaults();
    rd.seed = 2024; rd.threads = 1;
    rd.fresnel = FOGRT_FRESNEL_SCHLICK;
    /* Called through a volatile pointer so that the compiler cannot inline fogrt_render into
       main: callgrind.sh counts the instructions executed inside the function of that name. */
    render_fn = fogrt_render;
    check(render_fn(scene, &rd, &img, SPP, &stats), "fogrt_render");

    rgb = (float *)malloc(sizeof(float) * 3 * WIDTH * HEIGHT);
    if (!rgb) { fprintf(stderr, "strip_cost: out of memory\n"); return 1; }
    fogrt_image_resolve(&img, rgb);
    for (i = 0; i < (size_t)3 * WIDTH * HEIGHT; i++) {
        const unsigned char *b = (const unsigned char *)&rgb[i];
        size_t k;
        mean += rgb[i];
        for (k = 0; k < sizeof(float); k++) checksum = (checksum ^ b[k]) * 16777619u;
    }
    mean /= 3.0 * WIDTH * HEIGHT;
    printf("%s, %s: %dx%d, %d spp, features 0x%x, %llu rays, mean radiance %.6f, image checksum %08x\n",
           STRIP_COST_BUILD, mode, WIDTH, HEIGHT, SPP, (unsigned)fogrt_scene_get_features(scene),
           (unsigned long long)stats.rays, mean, (unsigned)checksum);
    free(rgb);
    fogrt_image_free(&img);
    fogrt_scene_destroy(scene);
    return 0;
}
