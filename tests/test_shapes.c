/* test_shapes.c - appendix H of fogrt.h, media inside shapes (fogrt_scene_set_interior).

   Analytic cases, where every sample is 0 or 1 (absorbing media, a uniform sky of radiance
   1 and nothing else that emits), so an image mean is a binomial proportion with a known
   standard error:
     - the camera at the centre of two nested interface spheres: exp(-(sigma_1 r_1 +
       sigma_2 (r_2 - r_1))) in every direction (a renderer that did not find the camera's
       medium would swap inside and outside at the first surface);
     - a concave interface shape (a U-shaped prism) seen through both arms: exp(-2 sigma w),
       not the exp(-3 sigma w) of a medium between the first and the last surface;
     - a glass sphere filled with absorbing fog, on its axis: the series of internal
       reflections R0 + (1 - R0)^2 T / (1 - R0 T) (Schlick at normal incidence, T the
       transmittance of one diameter), an estimate computed here without the renderer.
   The nested spheres again with a chromatic inner medium (sigma_t per channel, the free
   flights drawn with one hero channel per path): each channel's closed form, from the
   spread of 8 renders (a hero drawn with the wrong probabilities is off by 19%).
   A white furnace: a glass sphere filled with non-absorbing fog in a uniform sky, every
   path that ends leaves with weight 1, so every pixel is exactly 1.
   Invisible interfaces (block means of two images within their standard errors): an
   interface sphere without a medium of its own in a fog-free box, and one holding the same
   fog as the room, render as the scene without it. Light sampling and MIS on and off agree
   for a fog cube lit by an area light through its interface. And the refusals: a medium on
   an open mesh, media that overlap, a bounded interior, shape numbers out of range; a
   refused build leaves the scene as it was. Fixed seeds throughout. */
/* Public API only: make test links this program with one shared build of the
   implementation (compiled with FOGRT_TESTS_SHARED_IMPL) instead of compiling it again. */
#ifndef FOGRT_TESTS_SHARED_IMPL
#define FOGRT_IMPLEMENTATION
#endif
#include "fogrt.h"
#include "unity.h"
#include "test_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void setUp(void) {}
void tearDown(void) {}

#ifdef FOGRT_NO_SHAPES
#define SHAPES_ONLY() TEST_IGNORE_MESSAGE("needs appendix H of fogrt.h: built with FOGRT_NO_SHAPES (or FOGRT_NO_MEDIA, FOGRT_MINIMAL)")
#else
#define SHAPES_ONLY() ((void)0)

static fogrt_medium_desc medium(float sigma_t, float albedo, float g)
{
    fogrt_medium_desc m;
    memset(&m, 0, sizeof m);
    m.sigma_t = sigma_t; m.albedo = v3(albedo, albedo, albedo); m.g = g;
    return m;
}
static uint32_t add_material(fogrt_scene *s, fogrt_bsdf_type type, float ior)
{
    fogrt_material_desc m;
    uint32_t id = 0;
    memset(&m, 0, sizeof m);
    m.type = type; m.ior = ior;
    m.reflectance = v3(1, 1, 1); m.transmittance = v3(1, 1, 1);
    CHECK_OK(fogrt_scene_add_material(s, &m, &id));
    return id;
}
static fogrt_scene *new_scene(void)
{
    fogrt_scene *s = NULL;
    CHECK_OK(fogrt_scene_create(NULL, &s));
    return s;
}
/* A render of the built scene: spp samples per pixel (an eighth under the sanitizers; every
   tolerance below follows the render's own standard error), fixed seed. */
static void render(const fogrt_scene *s, int w, int h, int spp, const fogrt_render_desc *d, fogrt_image *img)
{
    fogrt_render_desc rd = d ? *d : fogrt_render_defaults();
    rd.seed = 7;
    CHECK_OK(fogrt_image_alloc(img, w, h, NULL));
    CHECK_OK(fogrt_render(s, &rd, img, SAN_REDUCED(spp, 8), NULL));
}
/* The image's mean red value (the sky and the media are grey) and, the samples being 0 or
   1 in the analytic cases, the binomial standard error of it. */
static double image_mean(const fogrt_image *img, double *se)
{
    double sum = 0.0, n = 0.0, p;
    int i;
    for (i = 0; i < img->width * img->height; ++i) { sum += img->sum[3 * i]; n += img->count[i]; }
    p = sum / n;
    if (se) *se = sqrt(fmax(p * (1.0 - p), 1e-12) / n);
    return p;
}
/* Builds the scene under a uniform sky of radiance 1 seen from `from` toward `to` (vertical
   fov fov_deg), renders it and checks the image mean against the closed form `expect`
   within 4 binomial standard errors; destroys the scene. */
static void check_sky_mean(fogrt_scene *s, fogrt_vec3 from, fogrt_vec3 to, float fov_deg, int w, int h, int spp,
                           const fogrt_render_desc *d, double expect, const char *what)
{
    fogrt_image img;
    double se, mean;
    CHECK_OK(fogrt_scene_set_environment(s, v3(1, 1, 1), false));
    set_camera(s, from, to, fov_deg);
    CHECK_OK(fogrt_scene_build(s, NULL));
    render(s, w, h, spp, d, &img);
    mean = image_mean(&img, &se);
    printf("%s: mean %.5f, expected %.5f (z %+.2f)\n", what, mean, expect, (mean - expect) / se);
    TEST_ASSERT_TRUE(fabs(mean - expect) < 4.0 * se);
    fogrt_image_free(&img);
    fogrt_scene_destroy(s);
}
/* The largest |z| over 4 x 4 blocks of two images' mean luminance (each block's standard
   error from fogrt's per-pixel variance estimates). */
static double max_block_z(const fogrt_image *a, const fogrt_image *b)
{
    double worst = 0.0;
    int bx, by, x, y, W = a->width, H = a->height;
    for (by = 0; by < 4; ++by)
        for (bx = 0; bx < 4; ++bx) {
            double ma = 0.0, mb = 0.0, va = 0.0, vb = 0.0, n = 0.0, z;
            for (y = by * H / 4; y < (by + 1) * H / 4; ++y)
                for (x = bx * W / 4; x < (bx + 1) * W / 4; ++x) {
                    int p = y * W + x;
                    ma += pixel_luminance(a, p); mb += pixel_luminance(b, p);
                    va += pixel_luminance_variance(a, p); vb += pixel_luminance_variance(b, p);
                    n += 1.0;
                }
            z = fabs(ma - mb) / sqrt(fmax(va + vb, 1e-30));
            if (z > worst) worst = z;
            (void)n;
        }
    return worst;
}
/* A sphere mesh-free shape: the interface material, a sphere, a medium inside it. */
static uint32_t add_filled_sphere(fogrt_scene *s, uint32_t material, fogrt_vec3 c, float r, const fogrt_medium_desc *m)
{
    fogrt_scene_info info;
    fogrt_scene_get_info(s, &info);
    CHECK_OK(fogrt_scene_add_sphere(s, c, r, material));
    if (m) CHECK_OK(fogrt_scene_set_interior(s, FOGRT_SHAPE_SPHERE, info.sphere_count, m));
    return info.sphere_count;
}
/* A closed prism: the polygon poly (n points in the x-y plane, counter-clockwise) from
   z = z0 to z = z1, its caps triangulated by the caller's triangles (indices into poly). */
static void add_prism(fogrt_scene *s, const float (*poly)[2], int n, const int (*cap)[3], int ncap, float z0, float z1,
                      uint32_t material)
{
    float pos[2 * 16 * 3];
    uint32_t idx[3 * (2 * 16 + 2 * 16)];
    fogrt_mesh_desc md;
    int i, t = 0;
    for (i = 0; i < n; ++i) {
        pos[3 * i] = poly[i][0]; pos[3 * i + 1] = poly[i][1]; pos[3 * i + 2] = z0;
        pos[3 * (n + i)] = poly[i][0]; pos[3 * (n + i) + 1] = poly[i][1]; pos[3 * (n + i) + 2] = z1;
    }
    for (i = 0; i < n; ++i) {                            /* the side walls */
        uint32_t a = (uint32_t)i, b = (uint32_t)((i + 1) % n);
        idx[t++] = a; idx[t++] = b; idx[t++] = b + (uint32_t)n;
        idx[t++] = a; idx[t++] = b + (uint32_t)n; idx[t++] = a + (uint32_t)n;
    }
    for (i = 0; i < ncap; ++i) {                         /* the caps */
        idx[t++] = (uint32_t)cap[i][0]; idx[t++] = (uint32_t)cap[i][2]; idx[t++] = (uint32_t)cap[i][1];
        idx[t++] = (uint32_t)(cap[i][0] + n); idx[t++] = (uint32_t)(cap[i][1] + n); idx[t++] = (uint32_t)(cap[i][2] + n);
    }
    memset(&md, 0, sizeof md);
    md.positions = pos; md.vertex_count = (uint32_t)(2 * n);
    md.indices = idx; md.triangle_count = (uint32_t)(t / 3);
    md.material = material;
    CHECK_OK(fogrt_scene_add_mesh(s, &md));
}
/* The U: x in [0, 3], y in [0, 2], the notch x in [1, 2], y in [1, 2]; caps as three
   rectangles whose shared edges are split where the outline is. */
static const float u_poly[10][2] = { {0, 0}, {1, 0}, {2, 0}, {3, 0}, {3, 2}, {2, 2}, {2, 1}, {1, 1}, {1, 2}, {0, 2} };
static const int u_cap[8][3] = { {0, 1, 7}, {0, 7, 8}, {0, 8, 9}, {1, 2, 6}, {1, 6, 7}, {2, 3, 4}, {2, 4, 5}, {2, 5, 6} };
#endif

/* ==========================================================================================
   Analytic cases
   ========================================================================================== */
static void test_camera_inside_nested_media(void)
{
    SHAPES_ONLY();
#ifndef FOGRT_NO_SHAPES
    fogrt_scene *s = new_scene();
    fogrt_medium_desc outer = medium(0.3f, 0.0f, 0.0f), inner = medium(0.7f, 0.0f, 0.0f);
    uint32_t iface = add_material(s, FOGRT_BSDF_INTERFACE, 0.0f);
    (void)add_filled_sphere(s, iface, v3(0, 0, 0), 2.0f, &outer);
    (void)add_filled_sphere(s, iface, v3(0, 0, 0), 1.0f, &inner);
    check_sky_mean(s, v3(0, 0, 0), v3(0, 0, -1), 90.0f, 32, 32, 64, NULL, exp(-(0.7 * 1.0 + 0.3 * (2.0 - 1.0))),
                   "camera inside nested media");
#endif
}

static void test_concave_interface_shape(void)
{
    SHAPES_ONLY();
#ifndef FOGRT_NO_SHAPES
    fogrt_scene *s = new_scene();
    fogrt_medium_desc fog = medium(0.5f, 0.0f, 0.0f);
    uint32_t iface = add_material(s, FOGRT_BSDF_INTERFACE, 0.0f);
    add_prism(s, u_poly, 10, u_cap, 8, 0.0f, 1.0f, iface);
    CHECK_OK(fogrt_scene_set_interior(s, FOGRT_SHAPE_MESH, 0, &fog));
    printf("concave shape: the medium's hull would give %.5f\n", exp(-3.0 * 0.5));
    check_sky_mean(s, v3(-10.0f, 1.5f, 0.5f), v3(0.0f, 1.5f, 0.5f), 1.0f, 16, 16, 64, NULL,   /* through both arms */
                   exp(-2.0 * 0.5), "concave shape");
#endif
}

static void test_filled_glass_on_axis(void)
{
    SHAPES_ONLY();
#ifndef FOGRT_NO_SHAPES
    fogrt_scene *s = new_scene();
    fogrt_medium_desc smoke = medium(0.5f, 0.0f, 0.0f);
    fogrt_render_desc d = fogrt_render_defaults();
    uint32_t glass = add_material(s, FOGRT_BSDF_GLASS, 1.5f);
    double r0 = 0.04, T = exp(-0.5 * 2.0);
    (void)add_filled_sphere(s, glass, v3(0, 0, 0), 1.0f, &smoke);
    d.max_depth = 1000; d.rr_depth = 1000;               /* no roulette: every sample 0 or 1 */
    check_sky_mean(s, v3(0, 0, 10), v3(0, 0, 0), 0.01f, 4, 4, 16384, &d, r0 + (1.0 - r0) * (1.0 - r0) * T / (1.0 - r0 * T),
                   "filled glass on its axis (the series)");
#endif
}

static void test_filled_glass_white_furnace(void)
{
    SHAPES_ONLY();
#ifndef FOGRT_NO_SHAPES
    fogrt_scene *s = new_scene();
    fogrt_medium_desc smoke = medium(2.0f, 1.0f, 0.5f);
    fogrt_image img;
    fogrt_render_desc d = fogrt_render_defaults();
    uint32_t glass = add_material(s, FOGRT_BSDF_GLASS, 1.5f);
    int i, off = 0;
    (void)add_filled_sphere(s, glass, v3(0, 0, 0), 1.0f, &smoke);
    CHECK_OK(fogrt_scene_set_environment(s, v3(1, 1, 1), false));
    set_camera(s, v3(0, 0, 4), v3(0, 0, 0), 40.0f);
    CHECK_OK(fogrt_scene_build(s, NULL));
    d.max_depth = 100000; d.rr_depth = 100000;
    render(s, 16, 16, 16, &d, &img);
    for (i = 0; i < 16 * 16; ++i) off += fabs(img.sum[3 * i] / img.count[i] - 1.0) > 1e-6;
    printf("filled glass white furnace: %d of 256 pixels differ from 1\n", off);
    TEST_ASSERT_EQUAL_INT(0, off);
    fogrt_image_free(&img);
    fogrt_scene_destroy(s);
#endif
}

static void test_chromatic_media_nested(void)
{
    SHAPES_ONLY();
#ifndef FOGRT_NO_SHAPES
    /* The camera inside nested absorbing spheres, the inner one chromatic: each channel
       exp(-(sigma_inner,c r_1 + sigma_outer (r_2 - r_1))), from the means of 8 renders of
       different seeds (the hero channel's samples are no longer 0 or 1). */
    fogrt_scene *s = new_scene();
    fogrt_medium_desc outer = medium(0.3f, 0.0f, 0.0f), inner = medium(1.5f, 0.0f, 0.0f);
    fogrt_render_desc d = fogrt_render_defaults();
    uint32_t iface = add_material(s, FOGRT_BSDF_INTERFACE, 0.0f);
    const float sig[3] = { 0.2f, 0.7f, 1.5f };
    double m[3] = { 0, 0, 0 }, m2[3] = { 0, 0, 0 };
    int b, c, i;
    inner.sigma_t_rgb = v3(sig[0], sig[1], sig[2]);
    (void)add_filled_sphere(s, iface, v3(0, 0, 0), 2.0f, &outer);
    (void)add_filled_sphere(s, iface, v3(0, 0, 0), 1.0f, &inner);
    CHECK_OK(fogrt_scene_set_environment(s, v3(1, 1, 1), false));
    set_camera(s, v3(0, 0, 0), v3(0, 0, -1), 90.0f);
    CHECK_OK(fogrt_scene_build(s, NULL));
    for (b = 0; b < 8; ++b) {
        fogrt_image img;
        double sum[3] = { 0, 0, 0 }, n = 0;
        d.seed = 100 + (uint64_t)b;
        CHECK_OK(fogrt_image_alloc(&img, 16, 16, NULL));
        CHECK_OK(fogrt_render(s, &d, &img, SAN_REDUCED(64, 8), NULL));
        for (i = 0; i < 16 * 16; ++i) { for (c = 0; c < 3; ++c) sum[c] += img.sum[3 * i + c]; n += img.count[i]; }
        for (c = 0; c < 3; ++c) { m[c] += sum[c] / n / 8.0; m2[c] += (sum[c] / n) * (sum[c] / n) / 8.0; }
        fogrt_image_free(&img);
    }
    for (c = 0; c < 3; ++c) {
        double expect = exp(-(sig[c] * 1.0 + 0.3 * 1.0)), se = sqrt(fmax(m2[c] - m[c] * m[c], 1e-12) / 7.0);
        printf("chromatic nested media, channel %d: mean %.5f, expected %.5f (z %+.2f)\n", c, m[c], expect, (m[c] - expect) / se);
        TEST_ASSERT_TRUE(fabs(m[c] - expect) < 4.0 * se);
    }
    fogrt_scene_destroy(s);
#endif
}

/* ==========================================================================================
   Invisible interfaces, light sampling
   ========================================================================================== */
#ifndef FOGRT_NO_SHAPES
/* The closed box with its lamp, fog sigma_t (0: none), and optionally an interface sphere
   holding `inside` (NULL: no medium of its own). */
static fogrt_scene *box_scene(float sigma_t, bool sphere, const fogrt_medium_desc *inside)
{
    fogrt_scene *s = new_scene();
    (void)add_closed_box(s, 0.3f, 12.0f);
    if (sigma_t > 0.0f) set_medium(s, sigma_t, v3(0.8f, 0.8f, 0.8f), 0.3f);
    if (sphere) (void)add_filled_sphere(s, add_material(s, FOGRT_BSDF_INTERFACE, 0.0f), v3(0.1f, 0.8f, 0.0f), 0.5f, inside);
    set_camera(s, v3(0, 1, 0.95f), v3(0, 1, -1), 70.0f);
    CHECK_OK(fogrt_scene_build(s, NULL));
    return s;
}
static double compare_boxes(fogrt_scene *a, fogrt_scene *b, const fogrt_render_desc *d, int spp)
{
    fogrt_image ia, ib;
    double z;
    render(a, 32, 32, spp, d, &ia);
    render(b, 32, 32, spp, d, &ib);
    z = max_block_z(&ia, &ib);
    fogrt_image_free(&ia); fogrt_image_free(&ib);
    fogrt_scene_destroy(a); fogrt_scene_destroy(b);
    return z;
}
#endif

static void test_empty_interface_is_invisible(void)
{
    SHAPES_ONLY();
#ifndef FOGRT_NO_SHAPES
    double z = compare_boxes(box_scene(0.0f, false, NULL), box_scene(0.0f, true, NULL), NULL, 64);
    printf("empty interface sphere in a fog-free box: worst block |z| %.2f of 16\n", z);
    TEST_ASSERT_TRUE(z < 4.0);
#endif
}

static void test_interface_holding_the_room_fog_is_invisible(void)
{
    SHAPES_ONLY();
#ifndef FOGRT_NO_SHAPES
    fogrt_medium_desc same = medium(0.6f, 0.8f, 0.3f);
    double z = compare_boxes(box_scene(0.6f, false, NULL), box_scene(0.6f, true, &same), NULL, 64);
    printf("interface sphere holding the room's fog: worst block |z| %.2f of 16\n", z);
    TEST_ASSERT_TRUE(z < 4.0);
#endif
}

static void test_denser_interior_is_visible(void)
{
    SHAPES_ONLY();
#ifndef FOGRT_NO_SHAPES
    /* The negative control of the two above: the same comparison must see a sphere whose
       fog absorbs (five times as dense, albedo 0). */
    fogrt_medium_desc dense = medium(3.0f, 0.0f, 0.3f);
    double z = compare_boxes(box_scene(0.6f, false, NULL), box_scene(0.6f, true, &dense), NULL, 64);
    printf("interface sphere with denser fog: worst block |z| %.2f of 16\n", z);
    TEST_ASSERT_TRUE(z > 6.0);
#endif
}

static void test_light_sampling_and_mis_agree(void)
{
    SHAPES_ONLY();
#ifndef FOGRT_NO_SHAPES
    fogrt_medium_desc fog = medium(1.2f, 0.9f, 0.5f);
    fogrt_render_desc bsdf_only = fogrt_render_defaults(), nee_only = fogrt_render_defaults();
    double z1, z2;
    bsdf_only.nee = false;
    nee_only.mis = false;
    {
        fogrt_scene *a = box_scene(0.0f, true, &fog), *b = box_scene(0.0f, true, &fog);
        fogrt_image ia, ib;
        render(a, 32, 32, 1024, &bsdf_only, &ia);
        render(b, 32, 32, 64, NULL, &ib);
        z1 = max_block_z(&ia, &ib);
        fogrt_image_free(&ia); fogrt_image_free(&ib);
        fogrt_scene_destroy(a); fogrt_scene_destroy(b);
    }
    {
        fogrt_scene *a = box_scene(0.0f, true, &fog), *b = box_scene(0.0f, true, &fog);
        fogrt_image ia, ib;
        render(a, 32, 32, 64, &nee_only, &ia);
        render(b, 32, 32, 64, NULL, &ib);
        z2 = max_block_z(&ia, &ib);
        fogrt_image_free(&ia); fogrt_image_free(&ib);
        fogrt_scene_destroy(a); fogrt_scene_destroy(b);
    }
    printf("fog sphere lit through its interface: BSDF sampling alone against MIS, worst block |z| %.2f; "
           "light sampling alone against MIS %.2f\n", z1, z2);
    TEST_ASSERT_TRUE(z1 < 4.0);
    TEST_ASSERT_TRUE(z2 < 4.0);
#endif
}

/* ==========================================================================================
   Refusals
   ========================================================================================== */
static void test_refusals(void)
{
    SHAPES_ONLY();
#ifndef FOGRT_NO_SHAPES
    fogrt_scene *s = new_scene();
    fogrt_medium_desc fog = medium(1.0f, 0.5f, 0.0f), boxed = fog;
    fogrt_scene_info info;
    uint32_t iface = add_material(s, FOGRT_BSDF_INTERFACE, 0.0f);
    boxed.bounded = true; boxed.bounds_min = v3(-1, -1, -1); boxed.bounds_max = v3(1, 1, 1);
    add_quad(s, v3(-1, 0, -1), v3(2, 0, 0), v3(0, 0, 2), iface);   /* mesh 0: open */
    (void)add_filled_sphere(s, iface, v3(0, 1, 0), 0.5f, &fog);      /* sphere 0 */
    CHECK_OK(fogrt_scene_set_environment(s, v3(1, 1, 1), false));
    CHECK_OK(fogrt_scene_build(s, NULL));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_INVALID_ARGUMENT, fogrt_scene_set_interior(s, FOGRT_SHAPE_MESH, 1, &fog));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_INVALID_ARGUMENT, fogrt_scene_set_interior(s, FOGRT_SHAPE_SPHERE, 1, &fog));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_INVALID_ARGUMENT, fogrt_scene_set_interior(s, (fogrt_shape_kind)7, 0, &fog));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_INVALID_MEDIUM, fogrt_scene_set_interior(s, FOGRT_SHAPE_SPHERE, 0, &boxed));
    fog.sigma_t = -1.0f;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_INVALID_MEDIUM, fogrt_scene_set_interior(s, FOGRT_SHAPE_SPHERE, 0, &fog));
    fog.sigma_t = 1.0f;
    fogrt_scene_get_info(s, &info);
    TEST_ASSERT_TRUE(info.built);                        /* refused calls changed nothing */
    CHECK_OK(fogrt_scene_set_interior(s, FOGRT_SHAPE_MESH, 0, &fog));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_INVALID_GEOMETRY, fogrt_scene_build(s, NULL));
    printf("open mesh: %s\n", fogrt_scene_last_error(s));
    TEST_ASSERT_NOT_NULL(strstr(fogrt_scene_last_error(s), "open edge"));
    CHECK_OK(fogrt_scene_set_interior(s, FOGRT_SHAPE_MESH, 0, NULL));
    (void)add_filled_sphere(s, iface, v3(0.6f, 1, 0), 0.5f, &fog);   /* sphere 1 overlaps sphere 0 */
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_INVALID_GEOMETRY, fogrt_scene_build(s, NULL));
    printf("overlap: %s\n", fogrt_scene_last_error(s));
    TEST_ASSERT_NOT_NULL(strstr(fogrt_scene_last_error(s), "overlap"));
    CHECK_OK(fogrt_scene_set_interior(s, FOGRT_SHAPE_SPHERE, 1, NULL));   /* an empty interface is */
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_INVALID_GEOMETRY, fogrt_scene_build(s, NULL));   /* a boundary too */
    fogrt_scene_destroy(s);
#endif
}

/* fogrt_scene_set_shape_material: every triangle of the one mesh, or the one sphere, takes
   the material, and nothing else does (how a loaded shape becomes an interface). */
static void test_set_shape_material(void)
{
    SHAPES_ONLY();
#ifndef FOGRT_NO_SHAPES
    fogrt_scene *s = new_scene();
    uint32_t grey = add_material(s, FOGRT_BSDF_DIFFUSE, 0.0f), iface = add_material(s, FOGRT_BSDF_INTERFACE, 0.0f);
    fogrt_scene_info info;
    uint32_t t;
    add_quad(s, v3(-1, 0, -1), v3(2, 0, 0), v3(0, 0, 2), grey);   /* mesh 0 */
    add_quad(s, v3(-1, 1, -1), v3(2, 0, 0), v3(0, 0, 2), grey);   /* mesh 1 */
    add_quad(s, v3(-1, 2, -1), v3(2, 0, 0), v3(0, 0, 2), grey);   /* mesh 2 */
    (void)add_filled_sphere(s, grey, v3(0, 1, 0), 0.5f, NULL);      /* sphere 0 */
    (void)add_filled_sphere(s, grey, v3(0, 3, 0), 0.5f, NULL);      /* sphere 1 */
    CHECK_OK(fogrt_scene_set_shape_material(s, FOGRT_SHAPE_MESH, 1, iface));
    CHECK_OK(fogrt_scene_set_shape_material(s, FOGRT_SHAPE_SPHERE, 1, iface));
    fogrt_scene_get_info(s, &info);
    for (t = 0; t < info.triangle_count; ++t)
        TEST_ASSERT_EQUAL_UINT(t / 2 == 1 ? iface : grey, fogrt_scene_get_prim_material(s, t));
    TEST_ASSERT_EQUAL_UINT(grey, fogrt_scene_get_prim_material(s, info.triangle_count));
    TEST_ASSERT_EQUAL_UINT(iface, fogrt_scene_get_prim_material(s, info.triangle_count + 1));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_INVALID_ARGUMENT, fogrt_scene_set_shape_material(s, FOGRT_SHAPE_MESH, 3, iface));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_INVALID_ARGUMENT, fogrt_scene_set_shape_material(s, FOGRT_SHAPE_SPHERE, 2, iface));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_INVALID_ARGUMENT, fogrt_scene_set_shape_material(s, (fogrt_shape_kind)7, 0, iface));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_INVALID_MATERIAL, fogrt_scene_set_shape_material(s, FOGRT_SHAPE_MESH, 0, 2));
    fogrt_scene_destroy(s);
#endif
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_camera_inside_nested_media);
    RUN_TEST(test_concave_interface_shape);
    RUN_TEST(test_filled_glass_on_axis);
    RUN_TEST(test_filled_glass_white_furnace);
    RUN_TEST(test_chromatic_media_nested);
    RUN_TEST(test_empty_interface_is_invisible);
    RUN_TEST(test_interface_holding_the_room_fog_is_invisible);
    RUN_TEST(test_denser_interior_is_visible);
    RUN_TEST(test_light_sampling_and_mis_agree);
    RUN_TEST(test_refusals);
    RUN_TEST(test_set_shape_material);
    return UNITY_END();
}
