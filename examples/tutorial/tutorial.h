/* tutorial.h - the few helpers every numbered tutorial example shares (docs/tutorial.md).

   Not part of fogrt: the examples include it once, after defining FOGRT_IMPLEMENTATION and
   including fogrt.h. It holds what would otherwise be repeated in all eight programs: a
   clock, a logger, the Cornell box they all render (built from fogrt's public API, so you
   can read how a scene is made), a render call that prints its time and error, and the PNG
   writer (stb_image_write, Debian package libstb-dev). The image of each example is a row
   of panels, one per setting it compares, under a title and each with its caption (drawn
   with examples/plotfont.h), so the picture can be shown without the text around it.                                                  */
#ifndef FOGRT_TUTORIAL_H
#define FOGRT_TUTORIAL_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "../stb_write.h"           /* stb_image_write, its warnings silenced */
#include "../plotfont.h"            /* the titles and captions drawn into the PNG */

/* Panel size of the tutorial images: small, so `make tutorial` stays quick. An example may
   define its own before including this file. */
#ifndef TUT_W
#define TUT_W 160
#endif
#ifndef TUT_H
#define TUT_H 120
#endif

static inline double tut_now(void)
{
    struct timespec ts;   /* the example defines _POSIX_C_SOURCE before its first include */
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static inline void tut_log(fogrt_log_level level, const char *msg, void *user)
{
    (void)user;
    fprintf(stderr, "fogrt: %s: %s\n", level == FOGRT_LOG_ERROR ? "error" : "warning", msg);
}

/* Stops the program with one line when a fogrt call fails. */
static inline void tut_check(fogrt_result r, const char *what)
{
    if (r != FOGRT_RESULT_OK) {
        fprintf(stderr, "tutorial: %s: %s\n", what, fogrt_result_string(r));
        exit(1);
    }
}

static inline fogrt_scene *tut_scene_create(void)
{
    fogrt_scene_desc sd;
    fogrt_scene *scene = NULL;
    memset(&sd, 0, sizeof sd);
    sd.logger.func = tut_log;
    tut_check(fogrt_scene_create(&sd, &scene), "fogrt_scene_create");
    return scene;
}

static inline uint32_t tut_material(fogrt_scene *scene, fogrt_bsdf_type type, float r, float g, float b)
{
    fogrt_material_desc m;
    uint32_t id;
    memset(&m, 0, sizeof m);
    m.type = type;
    m.reflectance.x = r; m.reflectance.y = g; m.reflectance.z = b;
    m.transmittance = m.reflectance;
    m.ior = 1.5f;
    tut_check(fogrt_scene_add_material(scene, &m, &id), "fogrt_scene_add_material");
    return id;
}

/* One quad (two triangles) with corners a, b, c, d in counter-clockwise order seen from
   the side it faces (the side an area light emits from). */
static inline void tut_quad(fogrt_scene *scene, const float corners[12], uint32_t material)
{
    static const uint32_t idx[6] = {0, 1, 2, 0, 2, 3};
    fogrt_mesh_desc md;
    memset(&md, 0, sizeof md);
    md.positions = corners; md.vertex_count = 4;
    md.indices = idx; md.triangle_count = 2;
    md.material = material;
    tut_check(fogrt_scene_add_mesh(scene, &md), "fogrt_scene_add_mesh");
}

/* The CS184 Cornell box: walls x = +-1 (red left, blue right), floor y = 0, ceiling y = 1.5,
   back wall z = -1, open at z = +1 where the camera looks in from z = 3.5. light_size > 0
   adds a square area light of that half-width just below the ceiling (radiance `emit`).
   The walls are added first, as triangles 0..9 (wall k is triangles 2k and 2k+1), in this
   order: floor, ceiling, back, left, right. */
static const float tut_walls[5][12] = {
    {-1, 0, 1, 1, 0, 1, 1, 0, -1, -1, 0, -1},                     /* floor, faces +y */
    {-1, 1.5f, -1, 1, 1.5f, -1, 1, 1.5f, 1, -1, 1.5f, 1},         /* ceiling, faces -y */
    {-1, 0, -1, 1, 0, -1, 1, 1.5f, -1, -1, 1.5f, -1},             /* back, faces +z */
    {-1, 0, 1, -1, 0, -1, -1, 1.5f, -1, -1, 1.5f, 1},             /* left, faces +x */
    {1, 0, -1, 1, 0, 1, 1, 1.5f, 1, 1, 1.5f, -1}};                /* right, faces -x */

static inline void tut_cornell_box(fogrt_scene *scene, float light_size, float emit)
{
    uint32_t white = tut_material(scene, FOGRT_BSDF_DIFFUSE, 0.75f, 0.75f, 0.75f);
    fogrt_camera_desc cam;
    tut_quad(scene, tut_walls[0], white);
    tut_quad(scene, tut_walls[1], white);
    tut_quad(scene, tut_walls[2], white);
    tut_quad(scene, tut_walls[3], tut_material(scene, FOGRT_BSDF_DIFFUSE, 0.75f, 0.2f, 0.2f));
    tut_quad(scene, tut_walls[4], tut_material(scene, FOGRT_BSDF_DIFFUSE, 0.2f, 0.25f, 0.75f));
    if (light_size > 0.0f) {
        float s = light_size, y = 1.499f;
        const float lamp[12] = {-s, y, -s, s, y, -s, s, y, s, -s, y, s};   /* faces down */
        fogrt_material_desc m;
        uint32_t id;
        memset(&m, 0, sizeof m);
        m.emission.x = m.emission.y = m.emission.z = emit;
        tut_check(fogrt_scene_add_material(scene, &m, &id), "fogrt_scene_add_material");
        tut_quad(scene, lamp, id);
    }
    memset(&cam, 0, sizeof cam);
    cam.position.x = 0.0f; cam.position.y = 0.75f; cam.position.z = 3.5f;
    cam.look_at.x = 0.0f; cam.look_at.y = 0.75f; cam.look_at.z = 0.0f;
    cam.fov_deg = 36.0f;
    tut_check(fogrt_scene_set_camera(scene, &cam), "fogrt_scene_set_camera");
}

/* The four BSDFs of the paper on four spheres in a row across the box, left to right:
   diffuse, mirror, refraction (transmission only) and glass (Fresnel: reflect or refract). */
static inline void tut_four_spheres(fogrt_scene *scene)
{
    const fogrt_bsdf_type type[4] = {FOGRT_BSDF_DIFFUSE, FOGRT_BSDF_MIRROR, FOGRT_BSDF_REFRACTION, FOGRT_BSDF_GLASS};
    int k;
    for (k = 0; k < 4; ++k) {
        fogrt_vec3 c;
        c.x = -0.72f + 0.48f * (float)k; c.y = 0.23f; c.z = -0.1f + 0.25f * (float)(k % 2);
        tut_check(fogrt_scene_add_sphere(scene, c, 0.22f, tut_material(scene, type[k], 0.9f, 0.9f, 0.9f)),
                  "fogrt_scene_add_sphere");
    }
}

static inline void tut_fog(fogrt_scene *scene, float sigma_t, float albedo, float g)
{
    fogrt_medium_desc md;
    memset(&md, 0, sizeof md);                   /* unbounded: the fog fills all space */
    md.sigma_t = sigma_t;
    md.albedo.x = md.albedo.y = md.albedo.z = albedo;
    md.g = g;
    tut_check(fogrt_scene_set_medium(scene, &md), "fogrt_scene_set_medium");
}

/* A row of n panels of TUT_W x TUT_H, in 8-bit sRGB, written as one PNG at the end: a title
   on top, the panels drawn twice their size (so that the picture reads on a projector), and
   under each panel its caption: what it shows, then its samples per pixel and error (the
   numbers that are the same on every run; times are not, so they stay in the transcript). */
#define TUT_MAX_PANELS 8
#define TUT_ZOOM 2
typedef struct tut_strip {
    int n;
    unsigned char *rgb8;
    char title[256];
    char caption[TUT_MAX_PANELS][2][128];
} tut_strip;

static inline tut_strip tut_strip_make(int n, const char *title)
{
    tut_strip s;
    memset(&s, 0, sizeof s);
    s.n = n;
    snprintf(s.title, sizeof s.title, "%s", title);
    s.rgb8 = (unsigned char *)calloc((size_t)n * TUT_W * TUT_H * 3, 1);
    if (!s.rgb8 || n > TUT_MAX_PANELS) { fprintf(stderr, "tutorial: out of memory or too many panels\n"); exit(1); }
    return s;
}

/* The caption of panel k: what it is (black), and a second line (grey), e.g. its numbers. */
static inline void tut_strip_caption(tut_strip *s, int k, const char *what, const char *detail)
{
    snprintf(s->caption[k][0], sizeof s->caption[k][0], "%s", what);
    snprintf(s->caption[k][1], sizeof s->caption[k][1], "%s", detail ? detail : "");
}

/* Copies one panel (linear RGB floats, TUT_W x TUT_H) into slot k, with an exposure. */
static inline void tut_strip_put(tut_strip *s, int k, const float *rgb, float exposure)
{
    unsigned char panel[TUT_W * TUT_H * 3];
    int y;
    fogrt_tonemap_rgb8(rgb, TUT_W, TUT_H, log2f(exposure), FOGRT_TONEMAP_SRGB, panel);   /* a multiplier here, stops there */
    for (y = 0; y < TUT_H; ++y)
        memcpy(s->rgb8 + ((size_t)y * s->n * TUT_W + (size_t)k * TUT_W) * 3, panel + (size_t)y * TUT_W * 3, TUT_W * 3);
}

static inline void tut_strip_write(tut_strip *s, const char *path)
{
    const int scale = 2, gap = 12, pw = TUT_W * TUT_ZOOM, ph = TUT_H * TUT_ZOOM, line = PF_LINE * scale;
    const int width = s->n * pw + (s->n + 1) * gap, chars = (pw - 4) / (PF_ADVANCE * scale);
    char wrapped[16][256];
    int title_lines = pf_wrap(s->title, (width - 2 * gap) / (PF_ADVANCE * scale), wrapped, 4), caption_lines = 0, k, j, y;
    pf_canvas c;
    for (k = 0; k < s->n; ++k) {
        int m = pf_wrap(s->caption[k][0], chars, NULL, 8) + pf_wrap(s->caption[k][1], chars, NULL, 8);
        if (m > caption_lines) caption_lines = m;
    }
    c = pf_canvas_make(width, gap + title_lines * line + gap / 2 + ph + gap / 2 + caption_lines * line + gap, PF_WHITE);
    for (j = 0; j < title_lines; ++j) pf_text(&c, gap, gap + j * line, wrapped[j], scale, PF_BLACK);
    y = gap + title_lines * line + gap / 2;
    for (k = 0; k < s->n; ++k) {
        int x0 = gap + k * (pw + gap), px, py, part, yy = y + ph + gap / 2;
        for (py = 0; py < ph; ++py)       /* each pixel drawn as a TUT_ZOOM x TUT_ZOOM block */
            for (px = 0; px < pw; ++px)
                pf_put(&c, x0 + px, y + py, s->rgb8 + (((size_t)(py / TUT_ZOOM) * s->n + (size_t)k) * TUT_W + (size_t)(px / TUT_ZOOM)) * 3);
        for (part = 0; part < 2; ++part) {
            int m = pf_wrap(s->caption[k][part], chars, wrapped, 8);
            for (j = 0; j < m; ++j, yy += line) pf_text(&c, x0 + 2, yy, wrapped[j], scale, part ? PF_GREY : PF_BLACK);
        }
    }
    if (!stbi_write_png(path, c.w, c.h, 3, c.rgb, c.w * 3)) {
        fprintf(stderr, "tutorial: could not write %s\n", path);
        exit(1);
    }
    printf("wrote %s (%d panel%s of %dx%d)\n", path, s->n, s->n == 1 ? "" : "s", TUT_W, TUT_H);
    pf_canvas_free(&c);
    free(s->rgb8);
}

/* Renders spp samples per pixel into a fresh TUT_W x TUT_H image, prints one line
   "label: time, error, efficiency" and puts the result in panel k of the strip. Returns the
   seconds. */
static inline double tut_render(const fogrt_scene *scene, const fogrt_render_desc *rd, int spp, const char *label,
                         tut_strip *strip, int k, float exposure)
{
    fogrt_image img;
    fogrt_error_estimate err;
    fogrt_render_stats st;
    float *rgb = (float *)malloc(sizeof(float) * 3 * TUT_W * TUT_H);
    double t0, seconds;
    if (!rgb) { fprintf(stderr, "tutorial: out of memory\n"); exit(1); }
    tut_check(fogrt_image_alloc(&img, TUT_W, TUT_H, NULL), "fogrt_image_alloc");
    t0 = tut_now();
    tut_check(fogrt_render(scene, rd, &img, spp, &st), "fogrt_render");
    seconds = tut_now() - t0;
    fogrt_image_error(&img, &err);
    /* efficiency 1 / (error^2 x time): the fair way to compare two estimators */
    printf("%-34s %4d spp  %6.2f s  relative error %.4f  efficiency %7.1f  (%.2f Mrays/s)\n", label, spp,
           seconds, err.relative_error, 1.0 / (err.relative_error * err.relative_error * seconds),
           (double)st.rays / seconds * 1e-6);
    fogrt_image_resolve(&img, rgb);
    if (strip) {
        char detail[96];
        snprintf(detail, sizeof detail, "%d spp, relative error %.4f", spp, err.relative_error);
        tut_strip_put(strip, k, rgb, exposure);
        tut_strip_caption(strip, k, label, detail);
    }
    fogrt_image_free(&img);
    free(rgb);
    return seconds;
}

#endif /* FOGRT_TUTORIAL_H */
