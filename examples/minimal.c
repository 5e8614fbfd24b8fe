/* minimal.c - the complete program from the README: a scene built in code, rendered
   progressively until its own error estimate drops below 15%, written to out.pfm. */
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#include <stdio.h>
#include <stdlib.h>

int main(void)
{
    fogrt_scene *scene = NULL;
    fogrt_material_desc white = {0}, lamp = {0};
    fogrt_medium_desc fog = {0};
    fogrt_camera_desc cam = {0};
    fogrt_render_desc rd = {0};            /* zero means "default" everywhere */
    fogrt_error_estimate err = {0};
    fogrt_image img;
    uint32_t m_white, m_lamp;
    float floor_xyz[] = { -2,0,-2,  -2,0,2,  2,0,2,  2,0,-2 };   /* counter-clockwise from above */
    float lamp_xyz[]  = { -0.3f,2,-0.3f,  0.3f,2,-0.3f,  0.3f,2,0.3f,  -0.3f,2,0.3f }; /* faces down */
    uint32_t quad[] = { 0,1,2, 0,2,3 };
    fogrt_mesh_desc mesh = {0};

    if (fogrt_scene_create(NULL, &scene) != FOGRT_RESULT_OK) return 1;
    white.reflectance = (fogrt_vec3){0.8f, 0.8f, 0.8f};
    lamp.emission = (fogrt_vec3){10, 10, 10};
    fogrt_scene_add_material(scene, &white, &m_white);
    fogrt_scene_add_material(scene, &lamp, &m_lamp);
    mesh.positions = floor_xyz; mesh.vertex_count = 4; mesh.indices = quad; mesh.triangle_count = 2;
    mesh.material = m_white;
    fogrt_scene_add_mesh(scene, &mesh);
    mesh.positions = lamp_xyz; mesh.material = m_lamp;
    fogrt_scene_add_mesh(scene, &mesh);
    fogrt_scene_add_sphere(scene, (fogrt_vec3){0, 0.5f, 0}, 0.5f, m_white);
    fog.sigma_t = 0.2f; fog.albedo = (fogrt_vec3){0.9f, 0.9f, 0.9f}; fog.g = 0.5f;
    fogrt_scene_set_medium(scene, &fog);
    cam.position = (fogrt_vec3){0, 1, 5}; cam.look_at = (fogrt_vec3){0, 0.7f, 0}; cam.fov_deg = 40;
    fogrt_scene_set_camera(scene, &cam);
    fogrt_result r = fogrt_scene_build(scene, NULL);          /* BVH + feature analysis */
    if (r != FOGRT_RESULT_OK) { fprintf(stderr, "%s\n", fogrt_result_string(r)); return 1; }

    fogrt_image_alloc(&img, 320, 240, NULL);
    while (err.relative_error == 0 || err.relative_error > 0.15) {   /* progressive */
        fogrt_render(scene, &rd, &img, 8, NULL);
        fogrt_image_error(&img, &err);
        printf("%llu samples, relative error %.3f\n", (unsigned long long)err.samples, err.relative_error);
    }
    float *rgb = malloc(sizeof(float) * 3 * 320 * 240);
    fogrt_image_resolve(&img, rgb);
    fogrt_write_pfm("out.pfm", 320, 240, rgb);
    free(rgb);
    fogrt_image_free(&img, NULL);
    fogrt_scene_destroy(scene);
    return 0;
}
