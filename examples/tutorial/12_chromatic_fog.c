/* 12_chromatic_fog.c - tutorial step 12: fog whose density differs per colour channel
   (docs/tutorial.md, section 12; beyond the paper: fogrt.h, Part II, G).

   The paper's sigma_t is one number: the fog dims every colour alike. Real haze scatters
   blue more than red (fogrt_medium_desc.sigma_t_rgb). One free flight cannot follow three
   densities at once, so a path draws its distances with one channel, its "hero", picked at
   random, and weighs every channel by its own transmittance over the channels' mean density
   (one-sample spectral MIS). Panels: grey fog of the mean density; the chromatic fog with
   the same mean, blue three times as dense as red (the spot's cone turns orange toward its
   end, the far wall red); and its green channel against a grey fog of green's density alone,
   which must be the same image.
   Usage: 12_chromatic_fog [out.png [samples_per_pixel]]                                    */
#define _POSIX_C_SOURCE 199309L
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#define TUT_W 200
#define TUT_H 150
#include "tutorial.h"

static void spot_scene(fogrt_scene *scene)
{
    fogrt_light_desc l;
    tut_cornell_box(scene, 0.0f, 0.0f);              /* no lamp: the spot light alone */
    tut_four_spheres(scene);
    memset(&l, 0, sizeof l);
    l.type = FOGRT_LIGHT_SPOT;
    l.position.x = -0.8f; l.position.y = 1.4f; l.position.z = 0.6f;
    l.direction.x = 1.1f; l.direction.y = -1.4f; l.direction.z = -0.6f;
    l.intensity.x = l.intensity.y = l.intensity.z = 24.0f;
    l.cutoff_deg = 18.0f; l.beam_deg = 12.0f;
    tut_check(fogrt_scene_add_light(scene, &l), "fogrt_scene_add_light");
}
static void fog_rgb(fogrt_scene *scene, float r, float g, float b)
{
    fogrt_medium_desc md;
    memset(&md, 0, sizeof md);
    md.sigma_t_rgb.x = r; md.sigma_t_rgb.y = g; md.sigma_t_rgb.z = b;
    md.albedo.x = md.albedo.y = md.albedo.z = 0.9f;
    md.g = 0.5f;
    tut_check(fogrt_scene_set_medium(scene, &md), "fogrt_scene_set_medium");
}

int main(int argc, char **argv)
{
    const char *png = argc > 1 ? argv[1] : "12_chromatic_fog.png";
    int spp = argc > 2 ? atoi(argv[2]) : 64;
    static const float sig[3][3] = { {0.4f, 0.4f, 0.4f}, {0.2f, 0.4f, 0.6f}, {0.6f, 0.4f, 0.2f} };
    static const char *label[3] = { "grey fog, sigma_t 0.4", "sigma_t 0.2, 0.4, 0.6 (r, g, b)", "sigma_t 0.6, 0.4, 0.2" };
    tut_strip strip = tut_strip_make(3,
        "Step 12, chromatic fog: sigma_t per colour channel (the same mean in all three), a spot "
        "light in the box; one hero channel per path draws the free flights");
    fogrt_render_desc rd = fogrt_render_defaults();
    int k;
    if (spp < 1) { fprintf(stderr, "12_chromatic_fog: samples_per_pixel must be >= 1\n"); return 2; }
    for (k = 0; k < 3; ++k) {
        fogrt_scene *scene = tut_scene_create();
        spot_scene(scene);
        fog_rgb(scene, sig[k][0], sig[k][1], sig[k][2]);
        tut_check(fogrt_scene_build(scene, NULL), "fogrt_scene_build");
        (void)tut_render(scene, &rd, spp, label[k], &strip, k, 1.0f);
        fogrt_scene_destroy(scene);
    }
    tut_strip_write(&strip, png);
    return 0;
}
