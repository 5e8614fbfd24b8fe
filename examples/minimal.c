/* minimal.c - the complete program from the README: a scene built in code, rendered
   progressively until its own error estimate drops below 15% (at most 1024 samples per
   pixel), written to out.png. Every call's result is checked. Compiles as C99 and as C++. */
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#define STB_IMAGE_WRITE_IMPLEMENTATION   /* stb_image_write for the PNG: Debian's libstb-dev */
#include <stb/stb_image_write.h>    /* (fogrt itself needs only libc and libm) */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static fogrt_vec3 rgb(float r, float g, float b) { fogrt_vec3 c; c.x = r; c.y = g; c.z = b; return c; }

/* Stop with the message when a fogrt call fails. */
#define CHECK(call) do { fogrt_result r_ = (call); if (r_ != FOGRT_RESULT_OK) { \
    fprintf(stderr, "%s: %s\n", #call, fogrt_result_string(r_)); return 1; } } while (0)

static int build_scene(fogrt_scene *scene)
{
    static const float floor_xyz[] = { -2,0,-2,  -2,0,2,  2,0,2,  2,0,-2 };   /* counter-clockwise from above */
    static const float lamp_xyz[]  = { -0.3f,2,-0.3f,  0.3f,2,-0.3f,  0.3f,2,0.3f,  -0.3f,2,0.3f }; /* faces down */
    static const uint32_t quad[] = { 0,1,2, 0,2,3 };
    fogrt_material_desc white, lamp;
    fogrt_mesh_desc mesh;
    fogrt_medium_desc fog;
    fogrt_camera_desc cam;
    uint32_t m_white, m_lamp;

    memset(&white, 0, sizeof white); memset(&lamp, 0, sizeof lamp);    /* zero: diffuse, black */
    memset(&mesh, 0, sizeof mesh); memset(&fog, 0, sizeof fog); memset(&cam, 0, sizeof cam);
    white.reflectance = rgb(0.8f, 0.8f, 0.8f);
    lamp.emission = rgb(10, 10, 10);
    CHECK(fogrt_scene_add_material(scene, &white, &m_white));
    CHECK(fogrt_scene_add_material(scene, &lamp, &m_lamp));
    mesh.positions = floor_xyz; mesh.vertex_count = 4; mesh.indices = quad; mesh.triangle_count = 2;
    mesh.material = m_white;
    CHECK(fogrt_scene_add_mesh(scene, &mesh));
    mesh.positions = lamp_xyz; mesh.material = m_lamp;
    CHECK(fogrt_scene_add_mesh(scene, &mesh));
    CHECK(fogrt_scene_add_sphere(scene, rgb(0, 0.5f, 0), 0.5f, m_white));
    fog.sigma_t = 0.2f; fog.albedo = rgb(0.9f, 0.9f, 0.9f); fog.g = 0.5f;
    CHECK(fogrt_scene_set_medium(scene, &fog));
    cam.position = rgb(0, 1, 5); cam.look_at = rgb(0, 0.7f, 0); cam.fov_deg = 40;
    CHECK(fogrt_scene_set_camera(scene, &cam));
    CHECK(fogrt_scene_build(scene, NULL));                  /* BVH + feature analysis */
    return 0;
}

static int render(const fogrt_scene *scene, fogrt_image *img)
{
    fogrt_render_desc rd = fogrt_render_defaults();         /* read back, change, pass on */
    fogrt_error_estimate err;
    int spp = 0;
    do {                                                    /* progressive */
        CHECK(fogrt_render(scene, &rd, img, 8, NULL));
        spp += 8;
        fogrt_image_error(img, &err);
        printf("%d spp, relative error %.3f\n", spp, err.relative_error);
        if (err.mean_luminance == 0.0) { fprintf(stderr, "the image is black\n"); return 1; }
    } while (err.relative_error > 0.15 && spp < 1024);
    return 0;
}

int main(void)
{
    fogrt_scene *scene = NULL;
    fogrt_image img;
    float *pixels;
    int status;

    CHECK(fogrt_scene_create(NULL, &scene));
    CHECK(fogrt_image_alloc(&img, 320, 240, NULL));
    status = build_scene(scene);
    if (status == 0) status = render(scene, &img);
    pixels = (float *)malloc(sizeof(float) * 3 * 320 * 240);
    if (status == 0 && !pixels) { fprintf(stderr, "out of memory\n"); status = 1; }
    if (status == 0) {                                      /* tone mapped (0 EV, sRGB) to a PNG */
        unsigned char *rgb8 = (unsigned char *)malloc(3 * 320 * 240);
        fogrt_image_resolve(&img, pixels);
        if (rgb8) fogrt_tonemap_rgb8(pixels, 320, 240, 0.0f, FOGRT_TONEMAP_SRGB, rgb8);
        if (!rgb8 || !stbi_write_png("out.png", 320, 240, 3, rgb8, 3 * 320)) {
            fprintf(stderr, "could not write out.png\n");
            status = 1;
        }
        free(rgb8);
    }
    free(pixels);
    fogrt_image_free(&img);
    fogrt_scene_destroy(scene);
    return status;
}
