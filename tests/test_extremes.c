/* test_extremes.c - the extreme-case matrix: parameters at and beyond their limits.

   Every case is a row in a table with a one-line comment saying what must happen. Across all
   of them: every returned value, weight, pdf and pixel must be finite and non-negative,
   every direction unit length (|len - 1| < 1e-5), no sample may be dropped by the NaN
   firewall (fogrt_image.rejected == 0), renders must finish with a bounded number of rays,
   and invalid input must return the documented error and leave the scene as it was. */
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#include "unity.h"
#include "test_util.h"

#ifdef FOGRT_MINIMAL
#define FRESNEL_MODES 1   /* Schlick's alone: the exact Fresnel is Part II's (C) */
#else
#define FRESNEL_MODES 2   /* Schlick's and the exact one */
#endif

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void setUp(void) {}
void tearDown(void) {}

#define COUNT(a) ((int)(sizeof(a) / sizeof((a)[0])))

/* The two ends of the uniform numbers fogrt's RNG can return: 0 and 1 - 2^-24. */
#define U_MAX 0x1.fffffep-1f
static const float U_EDGES[] = { 0.0f, U_MAX };
static const float U_ALL[] = { 0.0f, 1e-7f, 0.5f, 0.9999999f, U_MAX };

static float len3(fogrt_vec3 v) { return sqrtf(v.x * v.x + v.y * v.y + v.z * v.z); }
static fogrt_vec3 unit3(float x, float y, float z)
{
    float l = sqrtf(x * x + y * y + z * z);
    return v3(x / l, y / l, z / l);
}
static bool finite_nonneg(float x) { return isfinite(x) && x >= 0.0f; }
static bool finite_nonneg3(fogrt_vec3 v) { return finite_nonneg(v.x) && finite_nonneg(v.y) && finite_nonneg(v.z); }
static bool is_unit(fogrt_vec3 v) { return isfinite(len3(v)) && fabsf(len3(v) - 1.0f) < 1e-5f; }

/* ---- a logger that counts messages ----------------------------------------------------- */
typedef struct log_counts { int warnings, errors; } log_counts;
static void count_log(fogrt_log_level level, const char *message, void *user_data)
{
    log_counts *c = (log_counts *)user_data;
    (void)message;
    if (level == FOGRT_LOG_WARNING) c->warnings++;
    if (level == FOGRT_LOG_ERROR) c->errors++;
}

/* ---- scenes and renders ---------------------------------------------------------------- */

/* The embedded Cornell box (triangles, spheres incl. glass, an area light and a soft spot
   light) with the given fog. */
static fogrt_scene *default_with_fog(float sigma_t, float albedo, float g, log_counts *logc)
{
    fogrt_scene *scene = NULL;
    fogrt_scene_desc sd;
    memset(&sd, 0, sizeof sd);
    if (logc) { sd.logger.func = count_log; sd.logger.user_data = logc; }
    CHECK_OK(fogrt_scene_create(&sd, &scene));
    CHECK_OK(fogrt_scene_add_default(scene));
    set_medium(scene, sigma_t, v3(albedo, albedo, albedo), g);
    return scene;
}

static fogrt_render_desc small_desc(int w, int h)
{
    fogrt_render_desc rd;
    rd = fogrt_render_defaults();
    rd.width = w; rd.height = h; rd.seed = 77;
    rd.threads = 1;   /* tiny images: a parallel region per row would cost more than it saves */
    return rd;
}

typedef struct render_result { double mean; fogrt_render_stats stats; } render_result;

/* Renders a built scene; asserts every pixel finite and non-negative and nothing rejected. */
static render_result render_built_checked(fogrt_scene *scene, const fogrt_render_desc *rd, int spp, const char *what)
{
    fogrt_image img;
    render_result r;
    int p, c, n = rd->width * rd->height;
    char msg[320];
    memset(&r, 0, sizeof r);
    CHECK_OK(fogrt_image_alloc(&img, rd->width, rd->height, NULL));
    CHECK_OK(fogrt_render(scene, rd, &img, spp, &r.stats));
    snprintf(msg, sizeof msg, "%s: %llu samples rejected", what, (unsigned long long)img.rejected);
    TEST_ASSERT_EQUAL_UINT64_MESSAGE(0, img.rejected, msg);
    TEST_ASSERT_EQUAL_UINT64_MESSAGE(0, r.stats.rejected, msg);
    for (p = 0; p < n; ++p) {
        for (c = 0; c < 3; ++c) {
            float v = img.sum[3 * p + c] / (float)img.count[p];
            snprintf(msg, sizeof msg, "%s: pixel %d channel %d = %g", what, p, c, v);
            TEST_ASSERT_TRUE_MESSAGE(finite_nonneg(v), msg);
            r.mean += v / (3.0 * n);
        }
        TEST_ASSERT_TRUE_MESSAGE(finite_nonneg(img.sum_sq[p]), what);
    }
    fogrt_image_free(&img);
    return r;
}
/* The same after building the scene. The build's roulette pilot (thousands of camera paths,
   against the render's few hundred) is most of the cost; under the sanitizers it runs in
   every fourth of these builds only, still across the cases' extreme parameters, and the
   others build without it (k = 1). */
static render_result render_checked(fogrt_scene *scene, const fogrt_render_desc *rd, int spp, const char *what)
{
    fogrt_build_desc bd = fogrt_build_defaults();
#ifdef FOGRT_TESTS_SANITIZE
    static int builds = 0;
    bd.roulette_pilot = builds++ % 4 == 0;
#endif
    CHECK_OK(fogrt_scene_build(scene, &bd));
    return render_built_checked(scene, rd, spp, what);
}

/* ======================================================================================== */
/* Henyey-Greenstein asymmetry g                                                           */
/* ======================================================================================== */

typedef struct g_case { float g, stored; bool warns; } g_case;
static const g_case G_CASES[] = {
    { -1.0f, -FOGRT_HG_G_MAX, true },          /* full back-scatter: clamped to -0.9999, warns */
    { -0.999999f, -FOGRT_HG_G_MAX, true },     /* beyond the limit: clamped, warns */
    { -1e-7f, -1e-7f, false },                 /* tiny: kept as is (no isotropic snap) */
    { 0.0f, 0.0f, false },                     /* isotropic */
    { 1e-7f, 1e-7f, false },                   /* tiny forward: kept */
    { 0.999999f, FOGRT_HG_G_MAX, true },       /* beyond the limit: clamped, warns */
    { 1.0f, FOGRT_HG_G_MAX, true },            /* full forward: clamped to 0.9999, warns */
};

/* Outgoing directions for the samplers: axis-parallel (+-, incl. -0 components), diagonal. */
static fogrt_vec3 wo_case(int i)
{
    switch (i) {
    case 0: return v3(0, 0, 1);
    case 1: return v3(0, 0, -1);                /* the frame's sign flip */
    case 2: return v3(1, 0, 0);
    case 3: return v3(-0.0f, -1, 0.0f);         /* negative zeros */
    case 4: return unit3(1, -2, 3);
    default: return unit3(-1e-4f, 1e-4f, -1);   /* almost -z */
    }
}
#define WO_CASES 6

/* set_medium stores g (clamped beyond FOGRT_HG_G_MAX with a warning), and every HG routine
   gives finite answers at the extreme uniforms: mu in [-1, 1] with mu(0) = -1, monotone in
   u; wi unit; pdf > 0 and finite; and for moderate g the returned pdf equals fogrt_hg_pdf. */
static void test_g_matrix(void)
{
    int i, j, a, b;
    for (i = 0; i < COUNT(G_CASES); ++i) {
        const g_case *gc = &G_CASES[i];
        log_counts logc = { 0, 0 };
        fogrt_scene *scene = default_with_fog(0.5f, 0.9f, gc->g, &logc);
        fogrt_medium_desc med;
        float prev_mu = -2.0f;
        char msg[320];
        fogrt_scene_get_medium(scene, &med);
        snprintf(msg, sizeof msg, "g %.9g: stored %.9g, %d warnings", gc->g, med.g, logc.warnings);
        TEST_ASSERT_TRUE_MESSAGE(med.g == gc->stored, msg);
        TEST_ASSERT_TRUE_MESSAGE(gc->warns ? logc.warnings >= 1 : logc.warnings == 0, msg);
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, logc.errors, msg);
        /* the inverse CDF of mu */
        for (a = 0; a < COUNT(U_ALL); ++a) {
            float mu = fogrt_sample_hg_mu(gc->g, U_ALL[a]);
            snprintf(msg, sizeof msg, "g %.9g u %.9g: mu %.9g (previous %.9g)", gc->g, U_ALL[a], mu, prev_mu);
            TEST_ASSERT_TRUE_MESSAGE(isfinite(mu) && mu >= -1.0f && mu <= 1.0f, msg);
            TEST_ASSERT_TRUE_MESSAGE(mu >= prev_mu, msg);   /* an inverse CDF is monotone */
            if (a == 0) TEST_ASSERT_TRUE_MESSAGE(mu == -1.0f, msg);
            TEST_ASSERT_TRUE_MESSAGE(finite_nonneg(fogrt_hg_phase(gc->g, mu)) && fogrt_hg_phase(gc->g, mu) > 0.0f, msg);
            prev_mu = mu;
        }
        /* full direction samples */
        for (j = 0; j < WO_CASES; ++j) {
            fogrt_vec3 wo = wo_case(j);
            for (a = 0; a < COUNT(U_ALL); ++a) {
                for (b = 0; b < COUNT(U_ALL); ++b) {
                    float pdf = -1.0f, pdf_eval;
                    fogrt_vec3 wi = fogrt_sample_hg(gc->g, wo, U_ALL[a], U_ALL[b], &pdf);
                    pdf_eval = fogrt_hg_pdf(gc->g, wo, wi);
                    snprintf(msg, sizeof msg, "g %.9g wo %d u %g %g: wi (%g %g %g) |wi| %.9g pdf %g eval %g",
                             gc->g, j, U_ALL[a], U_ALL[b], wi.x, wi.y, wi.z, len3(wi), pdf, pdf_eval);
                    TEST_ASSERT_TRUE_MESSAGE(is_unit(wi), msg);
                    TEST_ASSERT_TRUE_MESSAGE(finite_nonneg(pdf) && pdf > 0.0f, msg);
                    TEST_ASSERT_TRUE_MESSAGE(finite_nonneg(pdf_eval) && pdf_eval > 0.0f, msg);
                    if (fabsf(gc->g) < 0.5f)
                        TEST_ASSERT_TRUE_MESSAGE(fabsf(pdf - pdf_eval) <= 1e-3f * pdf, msg);
                }
            }
        }
        fogrt_scene_destroy(scene);
    }
}

/* The Cornell box in fog with each g renders to finite, non-negative pixels (NEE + MIS and
   NEE alone: the phase function peaks at 1.6e7 per steradian at |g| = 0.9999). The three
   modes are render settings, so they render one build of each scene (the build, whose
   roulette pilot is most of the cost, does not depend on them); a g that the scene stores
   as an earlier case's (the clamped ones: test_g_matrix checks what is stored) makes the
   same scene and is not rendered again. */
static void test_g_renders(void)
{
    int i, j, mode;
    for (i = 0; i < COUNT(G_CASES); ++i) {
        fogrt_scene *scene;
        for (j = 0; j < i && G_CASES[j].stored != G_CASES[i].stored; ++j) {}
        if (j < i) continue;
        scene = default_with_fog(0.8f, 0.9f, G_CASES[i].g, NULL);
        CHECK_OK(fogrt_scene_build(scene, NULL));
        for (mode = 0; mode < 3; ++mode) {
            fogrt_render_desc rd = small_desc(16, 12);
            char what[160];
            rd.nee = !(mode == 1);
            rd.mis = !(mode == 2);
            snprintf(what, sizeof what, "g %.9g mode %d", G_CASES[i].g, mode);
            (void)render_built_checked(scene, &rd, 2, what);
        }
        fogrt_scene_destroy(scene);
    }
}

/* ======================================================================================== */
/* Extinction sigma_t                                                                      */
/* ======================================================================================== */

static const float SIGMA_CASES[] = {
    0.0f,     /* no fog: free flight never collides (t = +inf), T = 1 */
    1e-12f,   /* fog in name only: every ray reaches the surface */
    1e-6f,    /* nearly clear */
    1.0f,     /* ordinary fog */
    1e3f,     /* thick: mean free path 1 mm in a 2 m box */
    1e6f,     /* opaque */
    1e12f,    /* steps of 1e-12 do not even move a float point: must still finish */
};

/* Free-flight sampling at the extreme uniforms, for every sigma_t: t >= 0 (0 at u = 0, the
   16.6 mean free paths of the largest u), +inf only without fog; the pdf and CDF are finite
   and in range. */
static void test_sigma_sampling(void)
{
    int i, a;
    for (i = 0; i < COUNT(SIGMA_CASES); ++i) {
        float sigma_t = SIGMA_CASES[i];
        for (a = 0; a < COUNT(U_ALL); ++a) {
            float t = fogrt_sample_exponential(sigma_t, U_ALL[a]);
            char msg[320];
            snprintf(msg, sizeof msg, "sigma_t %g u %.9g: t %g", sigma_t, U_ALL[a], t);
            if (sigma_t == 0.0f) {
                TEST_ASSERT_TRUE_MESSAGE(isinf(t) && t > 0.0f, msg);
                continue;
            }
            TEST_ASSERT_TRUE_MESSAGE(finite_nonneg(t), msg);
            if (U_ALL[a] == 0.0f) TEST_ASSERT_TRUE_MESSAGE(t == 0.0f, msg);
            /* -ln(2^-24) = 16.64 mean free paths at most */
            TEST_ASSERT_TRUE_MESSAGE(t * sigma_t <= 16.7f, msg);
            TEST_ASSERT_TRUE_MESSAGE(finite_nonneg(fogrt_exponential_pdf(sigma_t, t)), msg);
            {
                float cdf = fogrt_exponential_cdf(sigma_t, t);
                TEST_ASSERT_TRUE_MESSAGE(isfinite(cdf) && cdf >= 0.0f && cdf <= 1.0f, msg);
                /* the inverse of the sampler gives u back (to float precision in 1 - u) */
                TEST_ASSERT_TRUE_MESSAGE(fabsf(cdf - U_ALL[a]) <= 2e-6f, msg);
            }
            TEST_ASSERT_TRUE_MESSAGE(finite_nonneg(fogrt_transmittance(sigma_t, t)), msg);
        }
    }
}

/* Renders across sigma_t: finite pixels, and a bounded number of rays. Each path vertex
   traces one ray, one equiangular shadow ray per point light for the fog segment before it,
   and at most one next-event shadow ray per light (the box has one area light and one spot
   light, light_samples = 1), and a path has at most max_depth + 1 vertices, so
   rays <= camera_rays * (max_depth + 1) * (1 + 2 + 1). With max_depth -1 (unlimited) Russian
   roulette alone must end the walks, also at albedo 1 where fogrt's survival cap of 0.95
   makes the expected length about 3 + 20 vertices: allow 200 rays per camera ray on
   average. */
static void test_sigma_renders(void)
{
    int i, v;
    for (i = 0; i < COUNT(SIGMA_CASES); ++i) {
        for (v = 0; v < 3; ++v) {
            /* v = 0: albedo 0.9, default max_depth (64); 1: albedo 0.5, unlimited depth;
               2: albedo 1, unlimited depth, NEE off (only roulette ends the walk) */
            float albedo = v == 0 ? 0.9f : v == 1 ? 0.5f : 1.0f;
            fogrt_scene *scene = default_with_fog(SIGMA_CASES[i], albedo, 0.3f, NULL);
            fogrt_render_desc rd = small_desc(16, 12);
            render_result r;
            char what[160];
            uint64_t bound;
            rd.max_depth = v == 0 ? 64 : -1;
            rd.nee = !(v == 2);
            snprintf(what, sizeof what, "sigma_t %g variant %d", SIGMA_CASES[i], v);
            r = render_checked(scene, &rd, 2, what);
            bound = v == 0 ? r.stats.camera_rays * 65u * 4u : r.stats.camera_rays * 200u;
            snprintf(what, sizeof what, "sigma_t %g variant %d: %llu rays for %llu camera rays",
                     SIGMA_CASES[i], v, (unsigned long long)r.stats.rays,
                     (unsigned long long)r.stats.camera_rays);
            TEST_ASSERT_EQUAL_UINT64(16u * 12u * 2u, r.stats.camera_rays);
            TEST_ASSERT_TRUE_MESSAGE(r.stats.rays >= r.stats.camera_rays, what);
            TEST_ASSERT_TRUE_MESSAGE(r.stats.rays <= bound, what);
            /* opaque fog: the camera sits in it, so almost nothing reaches the camera */
            if (SIGMA_CASES[i] >= 1e6f && v != 2) TEST_ASSERT_TRUE_MESSAGE(r.mean < 1e-3, what);
            fogrt_scene_destroy(scene);
        }
    }
}

/* ======================================================================================== */
/* Every sampler at u = 0 and u = 1 - 2^-24                                                */
/* ======================================================================================== */

/* Equiangular distance sampling at the extreme uniforms, for lights near and far from the
   ray, finite and infinite segments: t finite and inside [a, b], pdf finite, positive and
   equal to fogrt_equiangular_pdf(t). */
static void test_equiangular_extremes(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("B: equiangular sampling");
#else
    /* columns: closest approach delta, distance h of the light from the line, segment [a, b] */
    static const struct { float delta, h, a, b; } eq[] = {
        { 1.0f, 0.5f, 0.0f, 3.0f },               /* ordinary */
        { 1.0f, 0.5f, 0.0f, INFINITY },           /* an escaping ray: b = +inf */
        { -5.0f, 1e-4f, 0.0f, 10.0f },            /* light behind the start, close to the line */
        { 0.0f, 1e-4f, 0.0f, 1e4f },              /* light at the start, long segment */
        { 100.0f, 0.1f, 0.0f, 1.0f },             /* light far beyond the segment's end */
        { 0.5f, 1e-30f, 0.0f, 1.0f },             /* h tiny but > 0 (h^2 underflows): finite peak 1/(pi h) */
    };
    int a, k;
    for (k = 0; k < COUNT(eq); ++k) {
        for (a = 0; a < COUNT(U_ALL); ++a) {
            float pdf = -1.0f, t = fogrt_sample_equiangular(eq[k].delta, eq[k].h, eq[k].a, eq[k].b, U_ALL[a], &pdf);
            float pdf_eval = fogrt_equiangular_pdf(eq[k].delta, eq[k].h, eq[k].a, eq[k].b, t);
            char msg[320];
            snprintf(msg, sizeof msg, "equiangular case %d u %.9g: t %.9g pdf %g eval %g", k, U_ALL[a], t, pdf, pdf_eval);
            TEST_ASSERT_TRUE_MESSAGE(isfinite(t) && t >= eq[k].a && t <= eq[k].b, msg);
            TEST_ASSERT_TRUE_MESSAGE(finite_nonneg(pdf) && pdf > 0.0f, msg);
            TEST_ASSERT_TRUE_MESSAGE(fabsf(pdf - pdf_eval) <= 1e-5f * pdf, msg);
        }
    }
#endif
}

/* Cosine hemisphere, uniform sphere, triangle and sphere-cone sampling at the corners of the
   unit square: unit directions on the right side, barycentrics in the triangle, pdfs finite
   and positive, cone samples inside the cone. */
static void test_samplers_at_extreme_uniforms(void)
{
    /* sphere-cone cases: point and sphere (centre, radius); each line says where p is */
    static const struct { fogrt_vec3 p, c; float r; } cones[] = {
        { { 0, 0, 0 }, { 0, 0, 5 }, 1.0f },           /* outside, ordinary */
        { { 0, 0, 0 }, { 0, 0, 1 }, 1.0f },           /* on the surface */
        { { 0, 0, 0 }, { 0.1f, 0, 0 }, 1.0f },        /* inside: uniform sphere */
        { { 0, 0, 0 }, { 3e3f, -4e3f, 0 }, 1e-3f },   /* far and tiny: cone of 2e-7 rad */
        { { 1e4f, 1e4f, 1e4f }, { 1e4f, 1e4f, 1.0001e4f }, 1e-4f }, /* tiny, far from the origin */
        { { 0, 0, 0 }, { 0, -7, 0 }, 6.9999f },       /* almost touching: cone of almost pi/2 */
    };
    int a, b, k;
    for (a = 0; a < 2; ++a) {
        for (b = 0; b < 2; ++b) {
            float u1 = U_EDGES[a], u2 = U_EDGES[b], b1 = -1.0f, b2 = -1.0f;
            fogrt_vec3 w;
            char msg[320];
            w = fogrt_sample_cosine_hemisphere(u1, u2);
            snprintf(msg, sizeof msg, "cosine hemisphere u %g %g: (%g %g %g)", u1, u2, w.x, w.y, w.z);
            TEST_ASSERT_TRUE_MESSAGE(is_unit(w) && w.z >= 0.0f, msg);
            TEST_ASSERT_TRUE_MESSAGE(finite_nonneg(fogrt_cosine_hemisphere_pdf(w.z)), msg);
            w = fogrt_sample_uniform_sphere(u1, u2);
            snprintf(msg, sizeof msg, "uniform sphere u %g %g: (%g %g %g)", u1, u2, w.x, w.y, w.z);
            TEST_ASSERT_TRUE_MESSAGE(is_unit(w), msg);
            TEST_ASSERT_TRUE_MESSAGE(fogrt_uniform_sphere_pdf() > 0.0f, msg);
            fogrt_sample_triangle(u1, u2, &b1, &b2);
            snprintf(msg, sizeof msg, "triangle u %g %g: b %g %g", u1, u2, b1, b2);
            TEST_ASSERT_TRUE_MESSAGE(finite_nonneg(b1) && finite_nonneg(b2) && b1 + b2 <= 1.0f + 1e-6f, msg);
            for (k = 0; k < COUNT(cones); ++k) {
                float pdf = -1.0f, pdf_eval, d2, cos_max, cos_w;
                fogrt_vec3 pc = v3(cones[k].c.x - cones[k].p.x, cones[k].c.y - cones[k].p.y, cones[k].c.z - cones[k].p.z);
                w = fogrt_sample_sphere_solid_angle(cones[k].c, cones[k].r, cones[k].p, u1, u2, &pdf);
                pdf_eval = fogrt_sphere_solid_angle_pdf(cones[k].c, cones[k].r, cones[k].p);
                snprintf(msg, sizeof msg, "sphere cone %d u %g %g: w (%g %g %g) pdf %g eval %g",
                         k, u1, u2, w.x, w.y, w.z, pdf, pdf_eval);
                TEST_ASSERT_TRUE_MESSAGE(is_unit(w), msg);
                TEST_ASSERT_TRUE_MESSAGE(finite_nonneg(pdf) && pdf > 0.0f, msg);
                TEST_ASSERT_TRUE_MESSAGE(fabsf(pdf - pdf_eval) <= 1e-5f * pdf, msg);
                /* outside the sphere: the direction lies in the cone (to float precision) */
                d2 = pc.x * pc.x + pc.y * pc.y + pc.z * pc.z;
                if (d2 > cones[k].r * cones[k].r * 1.0001f) {
                    cos_max = sqrtf(1.0f - cones[k].r * cones[k].r / d2);
                    cos_w = (w.x * pc.x + w.y * pc.y + w.z * pc.z) / sqrtf(d2);
                    TEST_ASSERT_TRUE_MESSAGE(cos_w >= cos_max - 1e-5f, msg);
                }
            }
        }
    }
}

/* ======================================================================================== */
/* BSDF sampling                                                                           */
/* ======================================================================================== */

typedef struct bsdf_case { fogrt_bsdf_type type; float ior; } bsdf_case;
static const bsdf_case BSDF_CASES[] = {
    { FOGRT_BSDF_DEFAULT, 0.0f },     /* default = diffuse */
    { FOGRT_BSDF_DIFFUSE, 0.0f },     /* cosine-weighted, weight = reflectance */
    { FOGRT_BSDF_MIRROR, 0.0f },      /* delta reflection, pdf 1 */
    { FOGRT_BSDF_REFRACTION, 1.0f },  /* ior 1: straight through, never TIR */
    { FOGRT_BSDF_REFRACTION, 1.5f },  /* TIR from inside beyond 41.8 degrees: reflects */
    { FOGRT_BSDF_REFRACTION, 10.0f }, /* TIR from inside beyond 5.7 degrees */
    { FOGRT_BSDF_GLASS, 1.0f },       /* ior 1: Fresnel 0 (exact), refracts straight through */
    { FOGRT_BSDF_GLASS, 1.5f },       /* reflect with probability F */
    { FOGRT_BSDF_GLASS, 10.0f },      /* R0 = 0.67: mostly reflects */
    { FOGRT_BSDF_GLASS, 0.5f },       /* object less dense than the fog: TIR from outside */
};

/* Incident directions (local frame): normal, grazing, near-horizon, from inside, horizon. */
static const fogrt_vec3 BSDF_WO[] = {
    { 0.0f, 0.0f, 1.0f },             /* normal incidence */
    { 0.6f, 0.0f, 0.8f },             /* 37 degrees */
    { 0.99999994f, 0.0f, 3.4526698e-4f }, /* grazing (89.98 degrees) */
    { 1.0f, 0.0f, 1e-7f },            /* grazing to float precision */
    { 0.0f, 0.0f, -1.0f },            /* from inside, normal */
    { 0.0f, 0.8f, -0.6f },            /* from inside, 53 degrees: TIR for ior 1.5 */
    { 1.0f, 0.0f, 0.0f },             /* exactly on the horizon: may return false */
};

/* Exact Fresnel at index ratio 1 (no interface): 0 at every angle, grazing ones included
   (1 - cos^2 must not round to 1 and look like total internal reflection); and at eta 1.5
   near grazing, the float value against the formula in double (the transmitted cosine from
   cos_t^2 = (cos_i^2 + eta^2 - 1) / eta^2). */
#ifndef FOGRT_MINIMAL   /* the reference of Part II's test below */
static double fresnel_double(double eta, double c)
{
    double ct, rp, rs;
    if (c < 0.0) { eta = 1.0 / eta; c = -c; }
    ct = (c * c + eta * eta - 1.0) / (eta * eta);
    if (ct <= 0.0) return 1.0;
    ct = sqrt(ct);
    rp = (eta * c - ct) / (eta * c + ct);
    rs = (c - eta * ct) / (c + eta * ct);
    return 0.5 * (rp * rp + rs * rs);
}
#endif
static void test_fresnel_grazing(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("C: exact Fresnel");
#else
    static const float cosines[] = { 1.0f, 0.5f, 1e-2f, 1e-4f, 3e-5f, 1e-6f, 1e-9f, 0.0f, -1e-9f, -1e-6f, -1e-4f, -0.5f, -1.0f };
    int i;
    for (i = 0; i < COUNT(cosines); ++i) {
        char msg[160];
        float f1 = fogrt_fresnel_dielectric(1.0f, cosines[i]), f15 = fogrt_fresnel_dielectric(1.5f, cosines[i]);
        double want = fresnel_double(1.5, (double)cosines[i]);
        snprintf(msg, sizeof msg, "cos %g: F(eta 1) = %g (want 0), F(eta 1.5) = %.9g (double %.9g)",
                 (double)cosines[i], (double)f1, (double)f15, want);
        TEST_ASSERT_TRUE_MESSAGE(f1 == 0.0f, msg);
        TEST_ASSERT_TRUE_MESSAGE(cosines[i] == 0.0f ? f15 == 1.0f : fabs(f15 - want) <= 2e-6 + 1e-5 * want, msg);
    }
#endif
}

/* Equiangular sampling with the light almost on the ray's line: h from 1e-2 down to 1e-7 of
   the segment. t must agree with the inverse CDF evaluated in long double to a few float ulps
   (relative to the segment's scale), and the pdf with the exact pdf at the returned t to
   1e-5; this is the accuracy the header states. */
static void test_equiangular_near_line(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("B: equiangular sampling");
#else
    static const double hs[] = { 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7 };
    const float delta = 0.37f, a = 0.0f, b = 1.0f;
    int i, k;
    for (i = 0; i < COUNT(hs); ++i) {
        float h = (float)hs[i];
        long double ta = atan2l((long double)a - delta, (long double)h), tb = atan2l((long double)b - delta, (long double)h);
        double worst_t = 0.0, worst_pdf = 0.0;
        char msg[200];
        for (k = 1; k < 4096; ++k) {
            float u = (float)k / 4096.0f, pdf, t = fogrt_sample_equiangular(delta, h, a, b, u, &pdf);
            long double tr = delta + (long double)h * tanl(ta + (long double)u * (tb - ta)), dt = (long double)t - delta;
            long double pr = (long double)h / ((tb - ta) * ((long double)h * h + dt * dt));
            double et = (double)fabsl((long double)t - tr) / 5.96e-8, ep = (double)(fabsl((long double)pdf - pr) / pr);
            if (et > worst_t) worst_t = et;
            if (ep > worst_pdf) worst_pdf = ep;
        }
        snprintf(msg, sizeof msg, "h %g: worst |t - t_exact| %.2f x 2^-24, worst pdf error %.2g", hs[i], worst_t, worst_pdf);
        TEST_MESSAGE(msg);
        TEST_ASSERT_TRUE_MESSAGE(worst_t <= 4.0 && worst_pdf <= 1e-5, msg);
        if (hs[i] == 1e-4) {   /* negative control: the same sampler with float angles misses the bound */
            float fa = atan2f(a - delta, h), fb = atan2f(b - delta, h);
            double worst_float = 0.0;
            for (k = 1; k < 4096; ++k) {
                float u = (float)k / 4096.0f, t = delta + h * tanf(fa + u * (fb - fa));
                long double tr = delta + (long double)h * tanl(ta + (long double)u * (tb - ta));
                double et = (double)fabsl((long double)t - tr) / 5.96e-8;
                if (et > worst_float) worst_float = et;
            }
            snprintf(msg, sizeof msg, "negative control, float angles at h 1e-4: worst error %.1f x 2^-24 (must exceed 4)", worst_float);
            TEST_MESSAGE(msg);
            TEST_ASSERT_TRUE_MESSAGE(worst_float > 4.0, msg);
        }
    }
#endif
}

/* The angles of the HG-weighted samplers in float (fogrt__atan2_pos, fogrt__psi_of,
   fogrt__cos_sin, chapter 6) against long double: atan2 to a few float ulps of relative
   error at every ratio (small angles keep their digits), and the equiangular distance with
   the phase function next to the ray's line (h down to 1e-7, g at both signs and near +-1)
   within 4 x 2^-24 of the same table inverted with long double angles. */
static void test_hg_angles_precision(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("B: HG per unit angle, equiangular sampling with HG");
#else
    static const double hs[] = { 1e-2, 1e-4, 1e-6, 1e-7 };
    static const float gs[] = { 0.6f, -0.5f, 0.99f, -0.99f, 0.0f };
    double worst_atan = 0.0;
    char msg[200];
    int i, j, k;
    for (i = -300; i <= 300; ++i) {                      /* ratios 1e-30 .. 1e30 */
        float y = powf(10.0f, (float)i / 10.0f), x = 1.0f;
        double e = fabs((double)fogrt__atan2_pos(y, x) / atan2((double)y, (double)x) - 1.0);
        if (e > worst_atan) worst_atan = e;
    }
    TEST_ASSERT_EQUAL_FLOAT(0.0f, fogrt__atan2_pos(0.0f, 1.0f));
    TEST_ASSERT_EQUAL_FLOAT(1.5707963f, fogrt__atan2_pos(1.0f, 0.0f));
    TEST_ASSERT_TRUE(fogrt__atan2_pos(0.0f, 0.0f) == 0.0f);
    snprintf(msg, sizeof msg, "fogrt__atan2_pos: worst relative error %.2g (ratios 1e-30 to 1e30)", worst_atan);
    TEST_MESSAGE(msg);
    TEST_ASSERT_TRUE_MESSAGE(worst_atan <= 4e-7, msg);
    {   /* psi next to 0 and pi: its distance to the end keeps its digits; the naive float
           pi/2 + atan((t - delta) / h) does not (negative control) */
        double exact = (double)atan2l(1e-7L, 1.0L);
        double ours0 = fogrt__psi_of(0.0f, 1.0f, 1e-7f), ours1 = FOGRT__PI_D - fogrt__psi_of(1.0f, 0.0f, 1e-7f);
        double naive = (double)(atan2f(-1.0f, 1e-7f) + 1.57079633f);
        snprintf(msg, sizeof msg, "psi at 1e-7 from 0 and from pi: relative errors %.2g, %.2g; naive float %.2g (must exceed 0.1)",
                 fabs(ours0 / exact - 1.0), fabs(ours1 / exact - 1.0), fabs(naive / exact - 1.0));
        TEST_MESSAGE(msg);
        TEST_ASSERT_TRUE_MESSAGE(fabs(ours0 / exact - 1.0) <= 4e-7 && fabs(ours1 / exact - 1.0) <= 4e-7 &&
                                 fabs(naive / exact - 1.0) > 0.1, msg);
    }
    for (j = 0; j < COUNT(gs); ++j) {
        fogrt__hg_table *T = (fogrt__hg_table *)malloc(sizeof *T);
        TEST_ASSERT_NOT_NULL(T);
        fogrt__hg_table_build(T, gs[j]);
        for (i = 0; i < COUNT(hs); ++i) {
            const float delta = 0.37f, a = 0.0f, b = 1.0f, h = (float)hs[i];
            double worst_t = 0.0, worst_pdf = 0.0;
            double ca = fogrt__hgt_at(T, T->c, (double)atan2l((long double)h, (long double)delta - a), NULL);
            double cb = fogrt__hgt_at(T, T->c, (double)atan2l((long double)h, (long double)delta - b), NULL);
            for (k = 1; k < 2048; ++k) {
                float u = (float)k / 2048.0f, pdf, t = fogrt__sample_equiangular_hg(T, delta, h, a, b, u, &pdf);
                double dens, psi = fogrt__hgt_invert(T, T->c, T->c_start, ca + (double)u * (cb - ca), &dens);
                long double tr = (long double)delta - (long double)h * cosl((long double)psi) / sinl((long double)psi), dt;
                if (tr < a) tr = a;
                if (tr > b) tr = b;
                dt = (long double)t - delta;
                {
                    double pr = (double)((long double)dens / ((long double)(cb - ca) * ((long double)h + dt * dt / h)));
                    double et = (double)fabsl((long double)t - tr) / 5.96e-8, ep = pr > 0.0 ? fabs((double)pdf / pr - 1.0) : 0.0;
                    TEST_ASSERT_TRUE(t >= a && t <= b && pdf >= 0.0f && isfinite(pdf));
                    if (et > worst_t) worst_t = et;
                    if (ep > worst_pdf) worst_pdf = ep;
                }
            }
            snprintf(msg, sizeof msg, "equiangular with HG, g %g, h %g: worst |t - t_exact| %.2f x 2^-24, pdf %.2g", (double)gs[j], hs[i], worst_t, worst_pdf);
            TEST_MESSAGE(msg);
            TEST_ASSERT_TRUE_MESSAGE(worst_t <= 4.0 && worst_pdf <= 1e-5, msg);
        }
        free(T);
    }
#endif
}

/* fogrt__clip_to_cone (chapter 14) against the inside test along the line: for random lines
   (from inside and outside the cone, some along its axis, finite and infinite segments,
   cones of 5 to 80 degrees) every point clearly inside the forward cone lies in the
   returned interval and no point clearly outside does. */
static void test_clip_to_cone_lines(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("B: cone clipping");
#else
    static const float cutoffs[] = { 5.0f, 30.0f, 60.0f, 80.0f };
    fogrt_rng rng;
    long bad = 0, inside_pts = 0;
    int c, i, k;
    char msg[160];
    fogrt_rng_seed(&rng, 77, 5);
    for (c = 0; c < COUNT(cutoffs); ++c)
        for (i = 0; i < 20000; ++i) {
            fogrt_light_desc l;
            float cos_c = cosf(cutoffs[c] * 3.14159265f / 180.0f), lo = 0.0f, hi, B;
            fogrt__v3 o, d;
            bool hit;
            memset(&l, 0, sizeof l);
            l.type = FOGRT_LIGHT_SPOT; l.cutoff_deg = cutoffs[c];
            l.position = fogrt__v(0.1f, 1.4f, -0.2f);
            l.direction = fogrt__normalize(fogrt__v(0.2f, -1.0f, 0.1f));
            o = fogrt__v(4.0f * fogrt_rng_float(&rng) - 2.0f, 3.0f * fogrt_rng_float(&rng) - 1.5f, 4.0f * fogrt_rng_float(&rng) - 2.0f);
            d = fogrt__normalize(fogrt__v(2.0f * fogrt_rng_float(&rng) - 1.0f, 2.0f * fogrt_rng_float(&rng) - 1.0f, 2.0f * fogrt_rng_float(&rng) - 1.0f));
            if (i % 4 == 0) d = fogrt__normalize(fogrt__add(l.direction, fogrt__scale(d, 0.3f)));   /* along the axis */
            if (i % 8 == 1) d = fogrt__neg(d);
            B = (i & 1) ? 6.0f : 0.1f + 3.0f * fogrt_rng_float(&rng);
            hi = (i & 1) ? INFINITY : B;
            hit = fogrt__clip_to_cone(&l, cos_c, o, d, &lo, &hi);
            for (k = 0; k <= 400; ++k) {
                float t = k == 400 ? B : B * (float)k / 400.0f;   /* the last point exactly at the end */
                fogrt__v3 x = fogrt__sub(fogrt__madd(o, d, t), l.position);
                float ax = fogrt__dot(x, l.direction), x2 = fogrt__dot(x, x), g = ax * ax - cos_c * cos_c * x2;
                bool in = ax > 0.0f && g > 1e-3f * x2, out = ax < -1e-3f * sqrtf(x2) || g < -1e-3f * x2;
                bool within = hit && t >= lo && t <= hi;
                inside_pts += in;
                if ((in && !within) || (out && hit && t > lo && t < hi)) ++bad;
            }
        }
    snprintf(msg, sizeof msg, "%ld of the points tested clearly inside; %ld misplaced", inside_pts, bad);
    TEST_MESSAGE(msg);
    TEST_ASSERT_TRUE_MESSAGE(bad == 0 && inside_pts > 100000, msg);
#endif
}

/* fogrt_sample_bsdf fed u = 0 and 1 - 2^-24 in all three uniforms, for every BSDF, ior,
   Fresnel mode and incident direction. When it returns true: wi unit and on the side its
   lobe says; weight finite and non-negative; pdf finite and positive; for non-delta lobes the
   pdf matches fogrt_bsdf_pdf and eval is finite. Refraction at ior 1 passes straight through. */
static void test_bsdf_sample_extremes(void)
{
    int i, j, fr, a, b, c;
    for (i = 0; i < COUNT(BSDF_CASES); ++i) {
        fogrt_material_desc m;
        memset(&m, 0, sizeof m);
        m.type = BSDF_CASES[i].type;
        m.ior = BSDF_CASES[i].ior;
        m.reflectance = v3(0.9f, 0.5f, 0.1f);
        m.transmittance = v3(0.8f, 1.0f, 0.3f);
        for (j = 0; j < COUNT(BSDF_WO); ++j) {
            fogrt_vec3 wo = BSDF_WO[j];
            for (fr = 0; fr < FRESNEL_MODES; ++fr) {
                for (a = 0; a < 2; ++a) for (b = 0; b < 2; ++b) for (c = 0; c < 2; ++c) {
                    fogrt_bsdf_sample bs;
                    bool ok;
                    char msg[320];
                    memset(&bs, 0x7f, sizeof bs);   /* garbage in: the call must overwrite */
                    ok = fogrt_sample_bsdf(&m, fr ? FOGRT_FRESNEL_EXACT : FOGRT_FRESNEL_SCHLICK,
                                               wo, U_EDGES[a], U_EDGES[b], U_EDGES[c], &bs);
                    snprintf(msg, sizeof msg, "bsdf %d ior %g wo %d fresnel %d u %d%d%d: ok %d wi (%g %g %g) "
                             "w (%g %g %g) pdf %g delta %d trans %d", (int)m.type, m.ior, j, fr, a, b, c,
                             ok, bs.wi.x, bs.wi.y, bs.wi.z, bs.weight.x, bs.weight.y, bs.weight.z, bs.pdf,
                             bs.is_delta, bs.is_transmission);
                    if (!ok) {
                        /* allowed only where no direction exists: the horizon, or the corner
                           of the disk map where the cosine hemisphere sample has z = 0 */
                        TEST_ASSERT_TRUE_MESSAGE(wo.z == 0.0f || (!bs.is_delta && m.type <= FOGRT_BSDF_DIFFUSE), msg);
                        continue;
                    }
                    TEST_ASSERT_TRUE_MESSAGE(is_unit(bs.wi), msg);
                    TEST_ASSERT_TRUE_MESSAGE(finite_nonneg3(bs.weight), msg);
                    TEST_ASSERT_TRUE_MESSAGE(finite_nonneg(bs.pdf) && bs.pdf > 0.0f, msg);
                    /* reflection stays on wo's side, transmission crosses */
                    if (bs.is_transmission) TEST_ASSERT_TRUE_MESSAGE(bs.wi.z * wo.z < 0.0f, msg);
                    else TEST_ASSERT_TRUE_MESSAGE(bs.wi.z * wo.z > 0.0f, msg);
                    if (!bs.is_delta) {
                        fogrt_vec3 f = fogrt_bsdf_eval(&m, wo, bs.wi);
                        float pdf = fogrt_bsdf_pdf(&m, wo, bs.wi);
                        TEST_ASSERT_TRUE_MESSAGE(finite_nonneg3(f), msg);
                        TEST_ASSERT_TRUE_MESSAGE(fabsf(pdf - bs.pdf) <= 1e-5f * bs.pdf, msg);
                    } else if (bs.is_transmission && m.ior == 1.0f) {
                        /* ior 1: no bending */
                        TEST_ASSERT_TRUE_MESSAGE(fabsf(bs.wi.x + wo.x) < 1e-5f && fabsf(bs.wi.y + wo.y) < 1e-5f &&
                                                 fabsf(bs.wi.z + wo.z) < 1e-5f, msg);
                    } else if (bs.is_delta && bs.pdf == 1.0f && !bs.is_transmission) {
                        /* a certain reflection is the mirror direction */
                        TEST_ASSERT_TRUE_MESSAGE(fabsf(bs.wi.x + wo.x) < 1e-6f && fabsf(bs.wi.z - wo.z) < 1e-6f, msg);
                    }
                }
            }
        }
    }
}

/* Refraction, Fresnel and total internal reflection at the limits: TIR returns false and
   Fresnel 1 (both formulas); ior 1 gives Fresnel 0 (exact) and no bending; ior 10 works
   from both sides; normal incidence; every direction unit length. */
static void test_refraction_extremes(void)
{
    /* columns: wo (world), n, eta, expect_tir; each line says the situation */
    static const struct { fogrt_vec3 wo, n; float eta; bool tir; } cases[] = {
        { { 0, 0, 1 }, { 0, 0, 1 }, 1.5f, false },                  /* normal incidence, entering */
        { { 0, 0, -1 }, { 0, 0, 1 }, 1.5f, false },                 /* normal incidence, leaving */
        { { 0.8f, 0, -0.6f }, { 0, 0, 1 }, 1.5f, true },            /* leaving at 53 deg > 41.8: TIR */
        { { 0.6f, 0, -0.8f }, { 0, 0, 1 }, 1.5f, false },           /* leaving at 37 deg: refracts */
        { { 0.99999994f, 0, 3.4526698e-4f }, { 0, 0, 1 }, 1.5f, false }, /* grazing entry */
        { { 0.6f, 0, 0.8f }, { 0, 0, 1 }, 1.0f, false },            /* ior 1 */
        { { 0.6f, 0, -0.8f }, { 0, 0, 1 }, 1.0f, false },           /* ior 1 from inside */
        { { 0.6f, 0, 0.8f }, { 0, 0, 1 }, 10.0f, false },           /* ior 10 entering */
        { { 0.0995f, 0, -0.995037f }, { 0, 0, 1 }, 10.0f, false },  /* ior 10 leaving at 5.71 deg < 5.74 */
        { { 0.2f, 0, -0.9797959f }, { 0, 0, 1 }, 10.0f, true },     /* ior 10 leaving at 11.5 deg: TIR */
        { { 0.6f, 0, 0.8f }, { 0, 0, 1 }, 0.5f, true },             /* object thinner than outside: TIR outside */
    };
    int i;
    for (i = 0; i < COUNT(cases); ++i) {
        fogrt_vec3 wi = v3(9, 9, 9);
        bool refracted = fogrt_refract(cases[i].n, cases[i].eta, cases[i].wo, &wi);
        float cos_i = cases[i].wo.z;   /* n = +z */
        float Fs = fogrt_fresnel_schlick(cases[i].eta, cos_i);
#ifdef FOGRT_MINIMAL
        float Fe = -1.0f;   /* the exact Fresnel is Part II's (C): not checked */
#else
        float Fe = fogrt_fresnel_dielectric(cases[i].eta, cos_i);
#endif
        char msg[320];
        snprintf(msg, sizeof msg, "case %d eta %g: refracted %d wi (%g %g %g) F schlick %g exact %g",
                 i, cases[i].eta, refracted, wi.x, wi.y, wi.z, Fs, Fe);
        TEST_ASSERT_TRUE_MESSAGE(refracted == !cases[i].tir, msg);
        TEST_ASSERT_TRUE_MESSAGE(isfinite(Fs) && Fs >= 0.0f && Fs <= 1.0f, msg);
#ifndef FOGRT_MINIMAL
        TEST_ASSERT_TRUE_MESSAGE(isfinite(Fe) && Fe >= 0.0f && Fe <= 1.0f, msg);
#endif
        if (cases[i].tir) {
#ifndef FOGRT_MINIMAL
            TEST_ASSERT_TRUE_MESSAGE(Fe == 1.0f, msg);
#endif
            /* Schlick is only defined from the dense side's TIR (cos_i < 0) */
            if (cos_i < 0.0f) TEST_ASSERT_TRUE_MESSAGE(Fs == 1.0f, msg);
            continue;
        }
        TEST_ASSERT_TRUE_MESSAGE(is_unit(wi), msg);
        TEST_ASSERT_TRUE_MESSAGE(wi.z * cos_i < 0.0f, msg);   /* crosses the surface */
        {
            /* Snell: sin_t * n_t = sin_i * n_i */
            float sin_i = sqrtf(fmaxf(0.0f, 1.0f - cos_i * cos_i));
            float sin_t = sqrtf(fmaxf(0.0f, 1.0f - wi.z * wi.z));
            float ratio = cos_i > 0.0f ? cases[i].eta : 1.0f / cases[i].eta;
            TEST_ASSERT_TRUE_MESSAGE(fabsf(sin_t * ratio - sin_i) <= 2e-5f * fmaxf(1.0f, ratio), msg);
        }
        if (cases[i].eta == 1.0f) {
#ifndef FOGRT_MINIMAL
            TEST_ASSERT_TRUE_MESSAGE(Fe == 0.0f, msg);
#endif
            TEST_ASSERT_TRUE_MESSAGE(fabsf(wi.x + cases[i].wo.x) < 1e-6f && fabsf(wi.z + cases[i].wo.z) < 1e-6f, msg);
        }
    }
    /* normal incidence into ior 1.5: both formulas give 0.04 */
#ifndef FOGRT_MINIMAL
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.04f, fogrt_fresnel_dielectric(1.5f, 1.0f));
#endif
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.04f, fogrt_fresnel_schlick(1.5f, 1.0f));
    /* grazing: everything reflects */
#ifndef FOGRT_MINIMAL
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 1.0f, fogrt_fresnel_dielectric(1.5f, 1e-7f));
#endif
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 1.0f, fogrt_fresnel_schlick(1.5f, 1e-7f));
}

/* Glass and refraction spheres with ior 1, 1.5 and 10, in and out of fog, both Fresnel
   formulas, through the whole renderer: TIR paths, rays that enter and leave and the fog's
   absence inside must all give finite pixels. */
static void test_specular_renders(void)
{
    static const float iors[] = { 1.0f, 1.5f, 10.0f };
    int i, t, fr;
    for (i = 0; i < COUNT(iors); ++i) {
        for (t = 0; t < 2; ++t) {
            for (fr = 0; fr < 2; ++fr) {
                fogrt_scene *scene = default_with_fog(fr ? 0.5f : 0.0f, 0.9f, 0.5f, NULL);
                fogrt_material_desc m;
                fogrt_render_desc rd = small_desc(16, 12);
                uint32_t id = 0;
                char what[160];
                memset(&m, 0, sizeof m);
                m.type = t ? FOGRT_BSDF_REFRACTION : FOGRT_BSDF_GLASS;
                m.reflectance = v3(1, 1, 1); m.transmittance = v3(1, 1, 1); m.ior = iors[i];
                CHECK_OK(fogrt_scene_add_material(scene, &m, &id));
                CHECK_OK(fogrt_scene_add_sphere(scene, v3(0.0f, 0.9f, 0.6f), 0.3f, id));
#ifdef FOGRT_MINIMAL
                rd.fresnel = FOGRT_FRESNEL_SCHLICK;   /* the exact Fresnel is Part II's (C) */
#else
                rd.fresnel = fr ? FOGRT_FRESNEL_EXACT : FOGRT_FRESNEL_SCHLICK;
#endif
                snprintf(what, sizeof what, "ior %g type %d fresnel %d", iors[i], t, fr);
                (void)render_checked(scene, &rd, 2, what);
                fogrt_scene_destroy(scene);
            }
        }
    }
}

/* ======================================================================================== */
/* Rays: axis-parallel, from a surface, grazing                                            */
/* ======================================================================================== */

/* A unit box [-1,1]^3 of 12 triangles and a sphere of radius 0.5 at the origin. */
static fogrt_scene *box_and_sphere(void)
{
    static const float pos[8 * 3] = { -1, -1, -1,  1, -1, -1,  1, 1, -1,  -1, 1, -1,
                                      -1, -1, 1,   1, -1, 1,   1, 1, 1,   -1, 1, 1 };
    static const uint32_t idx[36] = { 0, 1, 2, 0, 2, 3,  4, 6, 5, 4, 7, 6,  0, 4, 5, 0, 5, 1,
                                      3, 2, 6, 3, 6, 7,  0, 3, 7, 0, 7, 4,  1, 5, 6, 1, 6, 2 };
    fogrt_scene *scene = NULL;
    fogrt_mesh_desc md;
    uint32_t id;
    CHECK_OK(fogrt_scene_create(NULL, &scene));
    id = add_basic_material(scene, FOGRT_BSDF_DEFAULT, v3(0.5f, 0.5f, 0.5f), v3(0, 0, 0));
    memset(&md, 0, sizeof md);
    md.positions = pos; md.vertex_count = 8; md.indices = idx; md.triangle_count = 12; md.material = id;
    CHECK_OK(fogrt_scene_add_mesh(scene, &md));
    CHECK_OK(fogrt_scene_add_sphere(scene, v3(0, 0, 0), 0.5f, id));
    CHECK_OK(fogrt_scene_build(scene, NULL));
    return scene;
}

/* Closest hits of extreme rays: the BVH must agree with brute force (same hit or miss, same
   t and primitive), and where the answer is known, give it. */
static void test_extreme_rays(void)
{
    /* columns: origin, direction, tmin, expected t (< 0: just compare with brute force) */
    static const struct { fogrt_vec3 o, d; float tmin, t; } rays[] = {
        { { 0, 0, -3 }, { 0, 0, 1 }, 0.0f, 2.0f },            /* +z axis: hits the box at z = -1 */
        { { 0, 0, 3 }, { 0, 0, -1 }, 0.0f, 2.0f },            /* -z axis */
        { { 3, 0, 0 }, { -1, 0, 0 }, 0.0f, 2.0f },            /* -x axis */
        { { 0, -3, 0 }, { 0, 1, 0 }, 0.0f, 2.0f },            /* +y axis */
        { { -0.0f, -0.0f, -3 }, { -0.0f, 0.0f, 1 }, 0.0f, 2.0f }, /* negative zeros everywhere */
        { { 0, 0, 0 }, { 1, 0, 0 }, 0.0f, 0.5f },             /* from the centre: inside the sphere */
        { { 0.5f, 0, 0 }, { 1, 0, 0 }, 1e-4f, 0.5f },         /* starting on the sphere, leaving it */
        { { 0.5f, 0, 0 }, { -1, 0, 0 }, 1e-4f, 1.0f },        /* starting on the sphere, through it */
        { { -1, 0.3f, 0.2f }, { 1, 0, 0 }, 1e-4f, 0.65358984f }, /* starting on a box face, inward: 1 - sqrt(0.12) */
        { { 0.7f, 0.7f, 0.7f }, { 0, 0, 1 }, 0.0f, 0.3f },    /* axis-parallel from inside the box */
        { { -2, -1, 0 }, { 1, 0, 0 }, 0.0f, -1.0f },          /* in the plane of the floor: grazing */
        { { -2, -1, -1 }, { 1, 0, 0 }, 0.0f, -1.0f },         /* along a box edge */
        { { -3, 1, 1 }, { 1, 0, 0 }, 0.0f, -1.0f },           /* along the opposite edge */
        { { 0, 0.5f, -3 }, { 0, 0, 1 }, 0.0f, 2.0f },         /* tangent to the sphere (top) */
        { { -3, -0.999f, 0 }, { 0.9999995f, 1e-3f, 0 }, 0.0f, -1.0f }, /* grazing the floor */
        { { 0, 0, -3 }, { 0, 0, 1 }, 2.4f, 2.5f },            /* tmin past the box face: the sphere */
        { { 0, 0, -3 }, { 0, 0, 1 }, 0.0f, 2.0f },            /* repeat, for the stack */
    };
    fogrt_scene *scene = box_and_sphere();
    int i;
    for (i = 0; i < COUNT(rays); ++i) {
        fogrt_hit h1, h2;
        fogrt_vec3 d = unit3(rays[i].d.x, rays[i].d.y, rays[i].d.z);
        bool b1, b2;
        char msg[320];
        memset(&h1, 0, sizeof h1); memset(&h2, 0, sizeof h2);
        if (rays[i].d.x == 0.0f && rays[i].d.y == 0.0f) d = rays[i].d;   /* keep the signed zeros */
        b1 = fogrt_scene_intersect(scene, rays[i].o, d, rays[i].tmin, INFINITY, &h1);
        b2 = fogrt_scene_intersect_brute(scene, rays[i].o, d, rays[i].tmin, INFINITY, &h2);
        snprintf(msg, sizeof msg, "ray %d: bvh %d t %.9g prim %u, brute %d t %.9g prim %u, expected t %g",
                 i, b1, h1.t, h1.prim, b2, h2.t, h2.prim, rays[i].t);
        TEST_ASSERT_TRUE_MESSAGE(b1 == b2, msg);
        if (b1) {
            TEST_ASSERT_TRUE_MESSAGE(h1.t == h2.t, msg);
            TEST_ASSERT_TRUE_MESSAGE(isfinite(h1.t) && h1.t > rays[i].tmin, msg);
        }
        if (rays[i].t >= 0.0f) {
            TEST_ASSERT_TRUE_MESSAGE(b1, msg);
            TEST_ASSERT_TRUE_MESSAGE(fabsf(h1.t - rays[i].t) <= 1e-5f * (1.0f + rays[i].t), msg);
        }
        /* occlusion agrees with the closest hit */
        TEST_ASSERT_TRUE_MESSAGE(fogrt_scene_occluded(scene, rays[i].o, d, rays[i].tmin, INFINITY) == b1, msg);
    }
    fogrt_scene_destroy(scene);
}

/* The renderer from extreme starting points: fogrt_trace of rays starting exactly on a
   surface (both directions), grazing a surface, along axes and edges, in fog and without,
   returns finite non-negative radiance. */
static void test_trace_extreme_rays(void)
{
    static const struct { fogrt_vec3 o, d; } rays[] = {
        { { 0, 0, 0 }, { 0, -1, 0 } },            /* from the floor (y = 0), into it */
        { { 0, 0, 0 }, { 0, 1, 0 } },             /* from the floor, away */
        { { 0.3f, 0.0f, 0.2f }, { 1, 0, 0 } },    /* along the floor, in its plane */
        { { -1, 0.7f, 0 }, { 1, 1e-6f, 0 } },     /* from the left wall, almost along the floor */
        { { -0.9f, 1e-6f, 0.5f }, { 1, -1e-6f, 0 } }, /* grazing the floor at 1e-6 rad */
        { { -1, 0, -1 }, { 1, 0, 0 } },           /* along the box's back bottom edge */
        { { 0.45f, 0.7f, 0.25f }, { 0, -1, 0 } }, /* from the top of the glass sphere, inward */
        { { 0.45f, 0.35f, 0.25f }, { 0, 0, 1 } }, /* from inside the glass sphere */
        { { 0, 0.75f, 3.6f }, { -0.0f, 0.0f, -1 } }, /* the camera position, -z axis, signed zeros */
    };
    int i, f, k;
    for (f = 0; f < 2; ++f) {
        fogrt_scene *scene = default_with_fog(f ? 0.7f : 0.0f, 0.9f, 0.6f, NULL);
        fogrt_render_desc rd;
        fogrt_rng rng;
        CHECK_OK(fogrt_scene_build(scene, NULL));
        rd = fogrt_render_defaults();
        fogrt_rng_seed(&rng, 5, (uint64_t)f);
        for (i = 0; i < COUNT(rays); ++i) {
            for (k = 0; k < 64; ++k) {
                fogrt_vec3 L = fogrt_trace(scene, &rd, rays[i].o, rays[i].d, &rng, NULL);
                char msg[320];
                snprintf(msg, sizeof msg, "fog %d ray %d: L (%g %g %g)", f, i, L.x, L.y, L.z);
                TEST_ASSERT_TRUE_MESSAGE(finite_nonneg3(L), msg);
            }
        }
        fogrt_scene_destroy(scene);
    }
}

/* ======================================================================================== */
/* Degenerate triangles                                                                    */
/* ======================================================================================== */

/* Zero-area triangles (a point, a segment, collinear points) are kept but never hit, and an
   emissive one is no light: a scene with them renders the same image, bit for bit, as the
   scene without them. A sliver of area ~1e-12 that emits renders finite pixels. */
static void test_degenerate_triangles(void)
{
    static const float degen[] = {
        0.2f, 0.5f, 0.0f,   0.2f, 0.5f, 0.0f,   0.2f, 0.5f, 0.0f,     /* all three vertices equal */
        -0.5f, 0.6f, 0.0f,  0.5f, 0.6f, 0.0f,   0.5f, 0.6f, 0.0f,     /* two equal: a segment */
        -0.5f, 0.8f, -0.5f, 0.0f, 0.8f, 0.0f,   0.5f, 0.8f, 0.5f,     /* collinear */
    };
    static const float sliver[] = { -0.5f, 0.9f, 0.0f,  0.5f, 0.9f, 0.0f,  0.0f, 0.9f, 1e-12f };
    fogrt_scene *plain = default_with_fog(0.4f, 0.9f, 0.5f, NULL);
    fogrt_scene *with = default_with_fog(0.4f, 0.9f, 0.5f, NULL);
    fogrt_material_desc m;
    fogrt_mesh_desc md;
    fogrt_scene_info info;
    fogrt_image a, b;
    fogrt_render_desc rd = small_desc(16, 12);
    uint32_t emit = 0, before;
    int k;
    memset(&m, 0, sizeof m);
    m.emission = v3(5, 5, 5);
    CHECK_OK(fogrt_scene_add_material(plain, &m, &emit));
    CHECK_OK(fogrt_scene_add_material(with, &m, &emit));
    fogrt_scene_get_info(with, &info);
    before = info.triangle_count;
    memset(&md, 0, sizeof md);
    md.positions = degen; md.vertex_count = 9; md.triangle_count = 3; md.material = emit;
    CHECK_OK(fogrt_scene_add_mesh(with, &md));
    fogrt_scene_get_info(with, &info);
    TEST_ASSERT_EQUAL_UINT32(before + 3, info.triangle_count);   /* kept */
    CHECK_OK(fogrt_scene_build(plain, NULL));
    CHECK_OK(fogrt_scene_build(with, NULL));
    {
        fogrt_scene_info pi;
        fogrt_scene_get_info(plain, &pi);
        fogrt_scene_get_info(with, &info);
        TEST_ASSERT_EQUAL_UINT32(pi.area_light_count, info.area_light_count);   /* not lights */
    }
    /* rays straight at them pass through */
    for (k = 0; k < 3; ++k) {
        fogrt_vec3 o = v3(degen[9 * k + 3], degen[9 * k + 4], 0.9f), d = v3(0, 0, -1);
        fogrt_hit h1, h2;
        bool b1 = fogrt_scene_intersect(with, o, d, 0.0f, INFINITY, &h1);
        bool b2 = fogrt_scene_intersect(plain, o, d, 0.0f, INFINITY, &h2);
        TEST_ASSERT_TRUE(b1 == b2);
        if (b1) TEST_ASSERT_TRUE(h1.t == h2.t && !(h1.prim >= before && h1.prim < before + 3));
    }
    CHECK_OK(fogrt_image_alloc(&a, 16, 12, NULL));
    CHECK_OK(fogrt_image_alloc(&b, 16, 12, NULL));
    CHECK_OK(fogrt_render(plain, &rd, &a, 2, NULL));
    CHECK_OK(fogrt_render(with, &rd, &b, 2, NULL));
    TEST_ASSERT_EQUAL_UINT64(0, b.rejected);
    TEST_ASSERT_EQUAL_MEMORY_MESSAGE(a.sum, b.sum, sizeof(double) * 3 * 16 * 12,
                                     "degenerate triangles changed the image");
    fogrt_image_free(&a);
    fogrt_image_free(&b);
    /* an emitting sliver: a light of tiny area */
    md.positions = sliver; md.vertex_count = 3; md.triangle_count = 1;
    CHECK_OK(fogrt_scene_add_mesh(with, &md));
    (void)render_checked(with, &rd, 4, "emitting sliver");
    fogrt_scene_destroy(plain);
    fogrt_scene_destroy(with);
}

/* ======================================================================================== */
/* Scene scale                                                                             */
/* ======================================================================================== */

/* A fog-filled room of size 2s with diffuse walls, a ceiling lamp, a diffuse and a glass
   sphere and a point light; sigma_t = 0.6 / s and the point light's intensity times s^2, so every radiance is
   scale-free. */
static fogrt_scene *scaled_room(float s)
{
    fogrt_scene *scene = NULL;
    fogrt_material_desc m;
    fogrt_mesh_desc md;
    fogrt_light_desc l;
    uint32_t wall, lamp, glass = 0;
    float pos[8 * 3];
    static const uint32_t idx[30] = { 0, 1, 2, 0, 2, 3,  4, 6, 5, 4, 7, 6,  0, 4, 5, 0, 5, 1,
                                      3, 2, 6, 3, 6, 7,  0, 3, 7, 0, 7, 4 };   /* no +x wall */
    int k;
    for (k = 0; k < 8; ++k) {
        pos[3 * k + 0] = ((k == 1 || k == 2 || k == 5 || k == 6) ? 1.0f : -1.0f) * s;
        pos[3 * k + 1] = ((k == 2 || k == 3 || k == 6 || k == 7) ? 1.0f : -1.0f) * s;
        pos[3 * k + 2] = (k >= 4 ? 1.0f : -1.0f) * s;
    }
    CHECK_OK(fogrt_scene_create(NULL, &scene));
    wall = add_basic_material(scene, FOGRT_BSDF_DEFAULT, v3(0.6f, 0.5f, 0.4f), v3(0, 0, 0));
    lamp = add_basic_material(scene, FOGRT_BSDF_DEFAULT, v3(0, 0, 0), v3(8, 8, 8));
    memset(&md, 0, sizeof md);
    md.positions = pos; md.vertex_count = 8; md.indices = idx; md.triangle_count = 10; md.material = wall;
    CHECK_OK(fogrt_scene_add_mesh(scene, &md));
    /* the lamp: a 0.6 x 0.6 square just under the ceiling, facing down */
    add_quad_corners(scene, v3(-0.3f * s, 0.99f * s, -0.3f * s), v3(0.3f * s, 0.99f * s, -0.3f * s),
                     v3(0.3f * s, 0.99f * s, 0.3f * s), v3(-0.3f * s, 0.99f * s, 0.3f * s), lamp);
    CHECK_OK(fogrt_scene_add_sphere(scene, v3(-0.3f * s, -0.6f * s, 0.1f * s), 0.4f * s, wall));
    /* a glass sphere: refraction offsets and fog-free interiors must scale too */
    memset(&m, 0, sizeof m);
    m.type = FOGRT_BSDF_GLASS; m.ior = 1.5f;
    m.reflectance = v3(1, 1, 1); m.transmittance = v3(1, 1, 1);
    CHECK_OK(fogrt_scene_add_material(scene, &m, &glass));
    CHECK_OK(fogrt_scene_add_sphere(scene, v3(-0.5f * s, 0.2f * s, -0.3f * s), 0.3f * s, glass));
    memset(&l, 0, sizeof l);
    l.position = v3(0.5f * s, -0.2f * s, -0.4f * s);
    l.intensity = v3(2.0f * s * s, 2.0f * s * s, 2.0f * s * s);
    CHECK_OK(fogrt_scene_add_light(scene, &l));
    set_medium(scene, 0.6f / s, v3(0.9f, 0.9f, 0.9f), 0.4f);
    set_camera(scene, v3(0.9f * s, 0.1f * s, 0.2f * s), v3(-1.0f * s, -0.2f * s, 0.0f), 70.0f);
    CHECK_OK(fogrt_scene_build(scene, NULL));
    return scene;
}

/* The same room at scales 1e-4, 1 and 1e4 (sigma_t scaled inversely) gives the same image up
   to noise: the means of four image quadrants agree within 1% and 5 combined standard
   errors (the same seed gives the same random numbers, so in fact they agree to rounding).
   Fails on absolute epsilons (self-intersection acne at 1e4, light leaks or lost
   geometry at 1e-4) and on a point-light clamp that does not scale with the scene. */
static void test_scene_scale(void)
{
    static const float scales[] = { 1.0f, 1e-4f, 1e4f };
    const int w = 16, h = 12, spp = 32;
    double quad_mean[3][4], quad_var[3][4];
    int si, x, y, q;
    for (si = 0; si < 3; ++si) {
        fogrt_scene *scene = scaled_room(scales[si]);
        fogrt_render_desc rd = small_desc(w, h);
        fogrt_image img;
        CHECK_OK(fogrt_image_alloc(&img, w, h, NULL));
        CHECK_OK(fogrt_render(scene, &rd, &img, spp, NULL));
        TEST_ASSERT_EQUAL_UINT64(0, img.rejected);
        for (q = 0; q < 4; ++q) { quad_mean[si][q] = 0.0; quad_var[si][q] = 0.0; }
        for (y = 0; y < h; ++y) {
            for (x = 0; x < w; ++x) {
                int p = y * w + x, qq = (y >= h / 2) * 2 + (x >= w / 2);
                double lum = pixel_luminance(&img, p);
                TEST_ASSERT_TRUE(finite_nonneg((float)lum));
                quad_mean[si][qq] += lum / (w * h / 4);
                quad_var[si][qq] += pixel_luminance_variance(&img, p) / ((w * h / 4.0) * (w * h / 4.0));
            }
        }
        fogrt_image_free(&img);
        fogrt_scene_destroy(scene);
    }
    for (si = 1; si < 3; ++si) {
        for (q = 0; q < 4; ++q) {
            double diff = fabs(quad_mean[si][q] - quad_mean[0][q]);
            double se = sqrt(quad_var[si][q] + quad_var[0][q]);
            char msg[320];
            snprintf(msg, sizeof msg, "scale %g quadrant %d: mean %.5f vs %.5f at scale 1 (se %.5f)",
                     scales[si], q, quad_mean[si][q], quad_mean[0][q], se);
            TEST_ASSERT_TRUE_MESSAGE(quad_mean[0][q] > 0.0, msg);
            /* the renders use the same random numbers, so only rounding separates them: far
               below the noise; 1% (or 5 standard errors, whichever is smaller) */
            TEST_ASSERT_TRUE_MESSAGE(diff <= fmin(5.0 * se, 0.01 * quad_mean[0][q]), msg);
        }
    }
}

/* ======================================================================================== */
/* Point and spot lights at the limits                                                     */
/* ======================================================================================== */

/* A diffuse floor (y = 0, 10 x 10), a camera above, one point light; optional fog. */
static fogrt_scene *floor_with_light(fogrt_light_desc l, float sigma_t)
{
    fogrt_scene *scene = NULL;
    uint32_t id;
    CHECK_OK(fogrt_scene_create(NULL, &scene));
    id = add_basic_material(scene, FOGRT_BSDF_DEFAULT, v3(0.7f, 0.7f, 0.7f), v3(0, 0, 0));
    add_quad_corners(scene, v3(-5, 0, -5), v3(-5, 0, 5), v3(5, 0, 5), v3(5, 0, -5), id);
    CHECK_OK(fogrt_scene_add_light(scene, &l));
    set_medium(scene, sigma_t, v3(0.9f, 0.9f, 0.9f), 0.2f);
    set_camera(scene, v3(0.2f, 1.5f, 1.0f), v3(0, 0, 0), 0.0f);   /* fov 0: the default 45 degrees */
    return scene;
}

/* Point lights where 1/r^2 blows up: on the floor, 1e-6 above it, 1e-6 inside it, with a
   tiny and a zero radius, in clear and dense fog (scattering points ~1e-6 from the light),
   and rays traced from the light's own position. Pixels finite, nothing rejected. */
static void test_point_light_singularities(void)
{
    /* columns: light position, radius, sigma_t */
    static const struct { fogrt_vec3 p; float radius, sigma_t; } cases[] = {
        { { 0, 0, 0 }, 0.0f, 0.0f },            /* on the floor: cos = 0 there, r = 0 at the point */
        { { 0, 1e-6f, 0 }, 0.0f, 0.0f },        /* 1e-6 above the floor: r^2 = 1e-12 below it */
        { { 0, -1e-6f, 0 }, 0.0f, 0.0f },       /* 1e-6 below the floor: lights the underside only */
        { { 0, 1e-6f, 0 }, 1e-7f, 0.0f },       /* a sphere light of radius 1e-7 at 1e-6 */
        { { 0, 0, 0 }, 1e-3f, 0.0f },           /* a sphere light cut by the floor */
        { { 0, 0.5f, 0 }, 0.0f, 1.0f },         /* in fog: scattering points near the light */
        { { 0, 0.5f, 0 }, 0.0f, 1e6f },         /* dense fog: scattering points ~1e-6 away */
        { { 0.2f, 1.5f, 1.0f }, 0.0f, 0.5f },   /* at the camera position, in fog */
    };
    int i, k;
    for (i = 0; i < COUNT(cases); ++i) {
        fogrt_light_desc l;
        fogrt_scene *scene;
        fogrt_render_desc rd = small_desc(16, 12);
        fogrt_rng rng;
        char what[160];
        memset(&l, 0, sizeof l);
        l.position = cases[i].p;
        l.intensity = v3(3, 3, 3);
        l.radius = cases[i].radius;
        scene = floor_with_light(l, cases[i].sigma_t);
        snprintf(what, sizeof what, "point light case %d", i);
        (void)render_checked(scene, &rd, 4, what);
        /* traced from the light itself, in every axis direction */
        fogrt_rng_seed(&rng, 3, (uint64_t)i);
        for (k = 0; k < 6 * 16; ++k) {
            int ax = (k / 2) % 3;
            fogrt_vec3 d = v3(ax == 0 ? 1.0f : 0.0f, ax == 1 ? 1.0f : 0.0f, ax == 2 ? 1.0f : 0.0f);
            fogrt_vec3 L;
            if (k & 1) d = v3(-d.x, -d.y, -d.z);
            L = fogrt_trace(scene, &rd, cases[i].p, d, &rng, NULL);
            TEST_ASSERT_TRUE_MESSAGE(finite_nonneg3(L), what);
        }
        fogrt_scene_destroy(scene);
    }
}

/* Spot profiles at cutoff 0 and 90 degrees and at 180 (known values), and spot lights with
   those cutoffs in a render: a zero-width cone lights nothing, a 90-degree hard cone pointing
   down lights the floor exactly like a point light; in fog every cone from a line to a full
   sphere renders finite pixels. */
static void test_spot_cutoffs(void)
{
    /* columns: cos_theta, cutoff, beam, expected fraction */
    static const struct { float cos_theta, cutoff, beam, expected; } prof[] = {
        { 1.0f, 0.0f, 0.0f, 1.0f },              /* cutoff 0: full on the axis itself */
        { 0.9999f, 0.0f, 0.0f, 0.0f },           /* ... and nothing 0.8 degrees off it */
        { -1.0f, 0.0f, 0.0f, 0.0f },             /* ... nor behind */
        { 1e-3f, 90.0f, 90.0f, 1.0f },           /* cutoff 90 hard: the whole front half-space */
        { 0.0f, 90.0f, 90.0f, 1.0f },            /* ... including its boundary plane */
        { -1e-3f, 90.0f, 90.0f, 0.0f },          /* ... and nothing behind */
        { 0.5f, 90.0f, 0.0f, 1.0f / 3.0f },      /* linear: theta 60 of 90 */
        { 0.70710678f, 90.0f, 0.0f, 0.5f },      /* linear: theta 45 of 90 */
        { -1.0f, 180.0f, 180.0f, 1.0f },         /* cutoff 180: a point light */
        { -1.0f, 180.0f, 0.0f, 0.0f },           /* linear to 0 straight behind */
    };
    int i;
    for (i = 0; i < COUNT(prof); ++i) {
        float f = fogrt_spot_falloff(prof[i].cutoff, prof[i].beam, prof[i].cos_theta);
        char msg[320];
        snprintf(msg, sizeof msg, "spot cos %g cutoff %g beam %g: %g expected %g", prof[i].cos_theta,
                 prof[i].cutoff, prof[i].beam, f, prof[i].expected);
        TEST_ASSERT_TRUE_MESSAGE(fabsf(f - prof[i].expected) <= 1e-4f, msg);
    }
    {
        /* renders: point light vs 90-degree hard spot pointing down vs 0-degree spot */
        fogrt_light_desc l;
        fogrt_scene *point, *spot90, *spot0;
        fogrt_render_desc rd = small_desc(16, 12);
        fogrt_rng rng;
        int k;
        memset(&l, 0, sizeof l);
        l.position = v3(0.3f, 1.0f, -0.2f);
        l.intensity = v3(2, 2, 2);
        point = floor_with_light(l, 0.0f);
        l.type = FOGRT_LIGHT_SPOT;
        l.direction = v3(0, -1, 0);
        l.cutoff_deg = 90.0f; l.beam_deg = 90.0f;
        spot90 = floor_with_light(l, 0.0f);
        l.cutoff_deg = 0.0f; l.beam_deg = 0.0f;
        spot0 = floor_with_light(l, 0.0f);
        CHECK_OK(fogrt_scene_build(point, NULL));
        CHECK_OK(fogrt_scene_build(spot90, NULL));
        CHECK_OK(fogrt_scene_build(spot0, NULL));
        fogrt_rng_seed(&rng, 9, 0);
        for (k = 0; k < 32; ++k) {
            /* straight down onto the floor: the first vertex's NEE is deterministic */
            fogrt_vec3 o = v3(fogrt_rng_float(&rng) * 4.0f - 2.0f, 2.0f, fogrt_rng_float(&rng) * 4.0f - 2.0f);
            fogrt_render_desc one = rd;
            fogrt_rng r1, r2, r3;
            fogrt_vec3 a, b, c;
            one.max_depth = 1;
            one.integrator = FOGRT_INTEGRATOR_DIRECT;
            fogrt_rng_seed(&r1, 1, (uint64_t)k); r2 = r1; r3 = r1;
            a = fogrt_trace(point, &one, o, v3(0, -1, 0), &r1, NULL);
            b = fogrt_trace(spot90, &one, o, v3(0, -1, 0), &r2, NULL);
            c = fogrt_trace(spot0, &one, o, v3(0, -1, 0), &r3, NULL);
            TEST_ASSERT_TRUE(finite_nonneg3(a) && a.x > 0.0f);
            TEST_ASSERT_FLOAT_WITHIN(1e-6f * a.x, a.x, b.x);
            TEST_ASSERT_TRUE(c.x == 0.0f && c.y == 0.0f && c.z == 0.0f);
        }
        (void)render_checked(spot0, &rd, 2, "spot cutoff 0");
        (void)render_checked(spot90, &rd, 2, "spot cutoff 90");
        fogrt_scene_destroy(point);
        fogrt_scene_destroy(spot90);
        fogrt_scene_destroy(spot0);
    }
    {
        /* in fog, where the ray segment is clipped to the cone: (cutoff, beam) per line */
        static const float cones[][2] = {
            { 0.0f, 0.0f },        /* a line: nothing to clip to */
            { 1e-3f, 0.0f },       /* a needle */
            { 45.0f, 30.0f },      /* ordinary */
            { 89.999f, 89.999f },  /* almost a half space: nearly flat cone */
            { 90.0f, 90.0f },      /* exactly a half space */
            { 179.9f, 10.0f },     /* almost everything */
            { 180.0f, 180.0f },    /* a point light */
        };
        for (i = 0; i < COUNT(cones); ++i) {
            fogrt_light_desc l;
            fogrt_scene *scene;
            fogrt_render_desc rd = small_desc(16, 12);
            char what[160];
            memset(&l, 0, sizeof l);
            l.type = FOGRT_LIGHT_SPOT;
            l.position = v3(0.3f, 1.0f, -0.2f);
            l.direction = v3(0.1f, -1.0f, 0.3f);
            l.intensity = v3(2, 2, 2);
            l.cutoff_deg = cones[i][0]; l.beam_deg = cones[i][1];
            scene = floor_with_light(l, 0.8f);
            snprintf(what, sizeof what, "spot cutoff %g in fog", cones[i][0]);
            (void)render_checked(scene, &rd, 4, what);
            fogrt_scene_destroy(scene);
        }
    }
}

/* A light of intensity 0 (the only light, no emitters, no environment) gives an image that is
   exactly black, in clear and foggy air, with every integrator. */
static void test_zero_intensity_light(void)
{
    int f, mode;
    for (f = 0; f < 2; ++f) {
        for (mode = 0; mode < 3; ++mode) {
            fogrt_light_desc l;
            fogrt_scene *scene;
            fogrt_render_desc rd = small_desc(16, 12);
            render_result r;
            memset(&l, 0, sizeof l);
            l.type = f ? FOGRT_LIGHT_SPOT : FOGRT_LIGHT_POINT;
            l.position = v3(0, 1, 0);
            l.direction = v3(0, -1, 0);
            l.cutoff_deg = 40.0f; l.beam_deg = 20.0f;
            scene = floor_with_light(l, f ? 0.8f : 0.0f);
            rd.integrator = mode == 2 ? FOGRT_INTEGRATOR_DIRECT : FOGRT_INTEGRATOR_PATH;
            rd.nee = !(mode == 1);
            r = render_checked(scene, &rd, 2, "zero intensity");
            TEST_ASSERT_TRUE_MESSAGE(r.mean == 0.0, "a light of intensity 0 must give a black image");
            fogrt_scene_destroy(scene);
        }
    }
}

/* ======================================================================================== */
/* Invalid parameters                                                                      */
/* ======================================================================================== */

/* What we compare to prove that the scene did not change. */
typedef struct snapshot {
    fogrt_scene_info info;
    fogrt_medium_desc medium;
    fogrt_camera_desc camera;
    fogrt_material_desc materials[16];
    fogrt_light_desc lights[4];
} snapshot;

static void take_snapshot(const fogrt_scene *scene, snapshot *s)
{
    uint32_t i;
    memset(s, 0, sizeof *s);
    fogrt_scene_get_info(scene, &s->info);
    fogrt_scene_get_medium(scene, &s->medium);
    fogrt_scene_get_camera(scene, &s->camera);
    for (i = 0; i < s->info.material_count && i < 16; ++i) CHECK_OK(fogrt_scene_get_material(scene, i, &s->materials[i]));
    for (i = 0; i < s->info.light_count && i < 4; ++i) CHECK_OK(fogrt_scene_get_light(scene, i, &s->lights[i]));
}

static void assert_same_snapshot(const snapshot *a, const snapshot *b, const char *what)
{
    uint32_t i;
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(a->info.triangle_count, b->info.triangle_count, what);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(a->info.sphere_count, b->info.sphere_count, what);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(a->info.material_count, b->info.material_count, what);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(a->info.light_count, b->info.light_count, what);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(a->info.area_light_count, b->info.area_light_count, what);
    TEST_ASSERT_TRUE_MESSAGE(a->info.has_environment == b->info.has_environment, what);
    TEST_ASSERT_TRUE_MESSAGE(a->info.built == b->info.built, what);
    TEST_ASSERT_EQUAL_MEMORY_MESSAGE(&a->medium, &b->medium, sizeof a->medium, what);
    TEST_ASSERT_EQUAL_MEMORY_MESSAGE(&a->camera.position, &b->camera.position, sizeof(fogrt_vec3), what);
    TEST_ASSERT_EQUAL_MEMORY_MESSAGE(&a->camera.look_at, &b->camera.look_at, sizeof(fogrt_vec3), what);
    TEST_ASSERT_EQUAL_MEMORY_MESSAGE(&a->camera.up, &b->camera.up, sizeof(fogrt_vec3), what);
    TEST_ASSERT_TRUE_MESSAGE(a->camera.fov_deg == b->camera.fov_deg && a->camera.lens_radius == b->camera.lens_radius &&
                             a->camera.focal_distance == b->camera.focal_distance &&
                             a->camera.fov_is_horizontal == b->camera.fov_is_horizontal, what);
    for (i = 0; i < a->info.material_count && i < 16; ++i)
        TEST_ASSERT_EQUAL_MEMORY_MESSAGE(&a->materials[i], &b->materials[i], sizeof(fogrt_material_desc), what);
    for (i = 0; i < a->info.light_count && i < 4; ++i)
        TEST_ASSERT_EQUAL_MEMORY_MESSAGE(&a->lights[i], &b->lights[i], sizeof(fogrt_light_desc), what);
}

/* Renders 8 x 6 at 2 spp into a fresh image and returns a copy of its sums (caller frees). */
static double *render_copy(const fogrt_scene *scene)
{
    fogrt_image img;
    fogrt_render_desc rd = small_desc(8, 6);
    double *copy = (double *)malloc(sizeof(double) * 3 * 8 * 6);
    TEST_ASSERT_NOT_NULL(copy);
    CHECK_OK(fogrt_image_alloc(&img, 8, 6, NULL));
    CHECK_OK(fogrt_render(scene, &rd, &img, 2, NULL));
    memcpy(copy, img.sum, sizeof(double) * 3 * 8 * 6);
    fogrt_image_free(&img);
    return copy;
}

#define NAN_F ((float)NAN)
#define INF_F ((float)INFINITY)

/* Every invalid call returns its documented error, logs one error, and leaves the scene as
   it was: the same counts, materials, lights, camera and medium, still built, and the same
   image bit for bit. */
static void test_invalid_parameters(void)
{
    /* media: all INVALID_MEDIUM */
    static const fogrt_medium_desc bad_media[] = {
        { -1.0f, { 1, 1, 1 }, 0.0f, false, { 0, 0, 0 }, { 0, 0, 0 }, FOGRT_PHASE_HG, 0, 0, { 0, 0, 0 }, { 0, 0, 0 } },          /* negative sigma_t */
        { -1e-30f, { 1, 1, 1 }, 0.0f, false, { 0, 0, 0 }, { 0, 0, 0 }, FOGRT_PHASE_HG, 0, 0, { 0, 0, 0 }, { 0, 0, 0 } },        /* negative by a hair */
        { NAN_F, { 1, 1, 1 }, 0.0f, false, { 0, 0, 0 }, { 0, 0, 0 }, FOGRT_PHASE_HG, 0, 0, { 0, 0, 0 }, { 0, 0, 0 } },          /* NaN sigma_t */
        { INF_F, { 1, 1, 1 }, 0.0f, false, { 0, 0, 0 }, { 0, 0, 0 }, FOGRT_PHASE_HG, 0, 0, { 0, 0, 0 }, { 0, 0, 0 } },          /* infinite sigma_t (exp(-inf * 0) = NaN) */
        { 1.0f, { 1.5f, 1, 1 }, 0.0f, false, { 0, 0, 0 }, { 0, 0, 0 }, FOGRT_PHASE_HG, 0, 0, { 0, 0, 0 }, { 0, 0, 0 } },        /* albedo above 1 */
        { 1.0f, { 1, -0.1f, 1 }, 0.0f, false, { 0, 0, 0 }, { 0, 0, 0 }, FOGRT_PHASE_HG, 0, 0, { 0, 0, 0 }, { 0, 0, 0 } },       /* negative albedo */
        { 1.0f, { 1, 1, NAN_F }, 0.0f, false, { 0, 0, 0 }, { 0, 0, 0 }, FOGRT_PHASE_HG, 0, 0, { 0, 0, 0 }, { 0, 0, 0 } },       /* NaN albedo */
        { 1.0f, { 1, 1, 1 }, 1.0001f, false, { 0, 0, 0 }, { 0, 0, 0 }, FOGRT_PHASE_HG, 0, 0, { 0, 0, 0 }, { 0, 0, 0 } },        /* |g| > 1 */
        { 1.0f, { 1, 1, 1 }, -1.5f, false, { 0, 0, 0 }, { 0, 0, 0 }, FOGRT_PHASE_HG, 0, 0, { 0, 0, 0 }, { 0, 0, 0 } },          /* g < -1 */
        { 1.0f, { 1, 1, 1 }, NAN_F, false, { 0, 0, 0 }, { 0, 0, 0 }, FOGRT_PHASE_HG, 0, 0, { 0, 0, 0 }, { 0, 0, 0 } },          /* NaN g */
        { 1.0f, { 1, 1, 1 }, -INF_F, false, { 0, 0, 0 }, { 0, 0, 0 }, FOGRT_PHASE_HG, 0, 0, { 0, 0, 0 }, { 0, 0, 0 } },         /* infinite g */
        { 1.0f, { 1, 1, 1 }, 0.0f, true, { 0, 0, 0 }, { -1, 1, 1 }, FOGRT_PHASE_HG, 0, 0, { 0, 0, 0 }, { 0, 0, 0 } },   /* bounds: min above max */
        { 1.0f, { 1, 1, 1 }, 0.0f, true, { 0, 0, 0 }, { 0, 1, 1 }, FOGRT_PHASE_HG, 0, 0, { 0, 0, 0 }, { 0, 0, 0 } },    /* bounds: no thickness */
        { 1.0f, { 1, 1, 1 }, 0.0f, true, { NAN_F, 0, 0 }, { 1, 1, 1 }, FOGRT_PHASE_HG, 0, 0, { 0, 0, 0 }, { 0, 0, 0 } },/* bounds: NaN */
        { 1.0f, { 1, 1, 1 }, 0.0f, true, { 0, 0, 0 }, { 1, 2e30f, 1 }, FOGRT_PHASE_HG, 0, 0, { 0, 0, 0 }, { 0, 0, 0 } },/* bounds beyond 1e30 */
    };
    /* materials: all INVALID_MATERIAL */
    static const fogrt_material_desc bad_materials[] = {
        { FOGRT_BSDF_DIFFUSE, { -0.1f, 0, 0 }, { 0, 0, 0 }, { 0, 0, 0 }, 0.0f, 0.0f, { 0, 0, 0 }, { 0, 0, 0 } },  /* negative reflectance */
        { FOGRT_BSDF_DIFFUSE, { NAN_F, 0, 0 }, { 0, 0, 0 }, { 0, 0, 0 }, 0.0f, 0.0f, { 0, 0, 0 }, { 0, 0, 0 } },  /* NaN reflectance */
        { FOGRT_BSDF_GLASS, { 1, 1, 1 }, { 1, INF_F, 1 }, { 0, 0, 0 }, 1.5f, 0.0f, { 0, 0, 0 }, { 0, 0, 0 } },   /* infinite transmittance */
        { FOGRT_BSDF_DIFFUSE, { 0, 0, 0 }, { 0, 0, 0 }, { 0, 0, -1 }, 0.0f, 0.0f, { 0, 0, 0 }, { 0, 0, 0 } },     /* negative emission */
        { FOGRT_BSDF_DIFFUSE, { 0, 0, 0 }, { 0, 0, 0 }, { INF_F, 0, 0 }, 0.0f, 0.0f, { 0, 0, 0 }, { 0, 0, 0 } },  /* infinite emission */
        { FOGRT_BSDF_GLASS, { 1, 1, 1 }, { 1, 1, 1 }, { 0, 0, 0 }, -1.5f, 0.0f, { 0, 0, 0 }, { 0, 0, 0 } },      /* ior < 0 */
        { FOGRT_BSDF_GLASS, { 1, 1, 1 }, { 1, 1, 1 }, { 0, 0, 0 }, NAN_F, 0.0f, { 0, 0, 0 }, { 0, 0, 0 } },      /* NaN ior */
        { FOGRT_BSDF_GLASS, { 1, 1, 1 }, { 1, 1, 1 }, { 0, 0, 0 }, INF_F, 0.0f, { 0, 0, 0 }, { 0, 0, 0 } },      /* infinite ior */
        { (fogrt_bsdf_type)99, { 1, 1, 1 }, { 0, 0, 0 }, { 0, 0, 0 }, 0.0f, 0.0f, { 0, 0, 0 }, { 0, 0, 0 } },     /* unknown BSDF */
    };
    /* lights: all INVALID_LIGHT */
    static const fogrt_light_desc bad_lights[] = {
        { FOGRT_LIGHT_POINT, { 0, 1, 0 }, { 0, 0, 0 }, { -1, 1, 1 }, 0, 0, 0 },      /* negative intensity */
        { FOGRT_LIGHT_POINT, { 0, 1, 0 }, { 0, 0, 0 }, { NAN_F, 1, 1 }, 0, 0, 0 },   /* NaN intensity */
        { FOGRT_LIGHT_POINT, { 0, INF_F, 0 }, { 0, 0, 0 }, { 1, 1, 1 }, 0, 0, 0 },   /* infinite position */
        { FOGRT_LIGHT_POINT, { 0, 1, 0 }, { 0, 0, 0 }, { 1, 1, 1 }, 0, 0, -0.1f },   /* negative radius */
        { FOGRT_LIGHT_SPOT, { 0, 1, 0 }, { 0, -1, 0 }, { 1, 1, 1 }, 180.5f, 10, 0 }, /* cutoff > 180 */
        { FOGRT_LIGHT_SPOT, { 0, 1, 0 }, { 0, -1, 0 }, { 1, 1, 1 }, -1.0f, 0, 0 },   /* cutoff < 0 */
        { FOGRT_LIGHT_SPOT, { 0, 1, 0 }, { 0, -1, 0 }, { 1, 1, 1 }, 30.0f, 40, 0 },  /* beam > cutoff */
        { FOGRT_LIGHT_SPOT, { 0, 1, 0 }, { 0, -1, 0 }, { 1, 1, 1 }, 30.0f, -5, 0 },  /* beam < 0 */
        { FOGRT_LIGHT_SPOT, { 0, 1, 0 }, { 0, -1, 0 }, { 1, 1, 1 }, NAN_F, 0, 0 },   /* NaN cutoff */
        { FOGRT_LIGHT_SPOT, { 0, 1, 0 }, { 0, 0, 0 }, { 1, 1, 1 }, 30.0f, 10, 0 },   /* zero spot axis */
        { (fogrt_light_type)77, { 0, 1, 0 }, { 0, 0, 0 }, { 1, 1, 1 }, 0, 0, 0 },    /* unknown type */
    };
    /* cameras: all INVALID_CAMERA */
    static const fogrt_camera_desc bad_cameras[] = {
        { { 0, 1, 3 }, { 0, 1, 3 }, { 0, 0, 0 }, 45.0f, false, 0.0f, 0.0f },    /* eye equals target */
        { { 0, 1, 3 }, { 0, 1, 0 }, { 0, 0, 0 }, 180.0f, false, 0.0f, 0.0f },   /* fov 180 */
        { { 0, 1, 3 }, { 0, 1, 0 }, { 0, 0, 0 }, -10.0f, false, 0.0f, 0.0f },   /* negative fov */
        { { 0, 1, 3 }, { 0, 1, 0 }, { 0, 0, 0 }, NAN_F, false, 0.0f, 0.0f },    /* NaN fov */
        { { 0, 1, 3 }, { 0, 1, 0 }, { 0, 0, 0 }, 45.0f, false, -0.1f, 0.0f },   /* negative lens */
        { { NAN_F, 1, 3 }, { 0, 1, 0 }, { 0, 0, 0 }, 45.0f, false, 0.0f, 0.0f }, /* NaN eye */
        { { 0, 1, 3 }, { 0, 1, 0 }, { 0, 0, 1 }, 45.0f, false, 0.0f, 0.0f },    /* up along the view axis */
    };
    /* spheres: (centre, radius, material) with the expected result */
    static const struct { fogrt_vec3 c; float r; uint32_t mat; fogrt_result expected; } bad_spheres[] = {
        { { 0, 0, 0 }, 0.0f, 0, FOGRT_RESULT_INVALID_GEOMETRY },       /* radius 0 */
        { { 0, 0, 0 }, -1.0f, 0, FOGRT_RESULT_INVALID_GEOMETRY },      /* negative radius */
        { { 0, 0, 0 }, NAN_F, 0, FOGRT_RESULT_INVALID_GEOMETRY },      /* NaN radius */
        { { 0, 0, 0 }, INF_F, 0, FOGRT_RESULT_INVALID_GEOMETRY },      /* infinite radius */
        { { 0, NAN_F, 0 }, 1.0f, 0, FOGRT_RESULT_INVALID_GEOMETRY },   /* NaN centre */
        { { 0, 0, 0 }, 1.0f, 1000, FOGRT_RESULT_INVALID_MATERIAL },    /* material out of range */
    };
    /* meshes */
    static const float good_pos[9] = { 0, 0, 0,  1, 0, 0,  0, 1, 0 };
    static const float nan_pos[9] = { 0, 0, 0,  1, NAN_F, 0,  0, 1, 0 };
    static const float inf_nrm[9] = { 0, 0, 1,  0, 0, 1,  0, INF_F, 1 };
    static const uint32_t bad_idx[3] = { 0, 1, 3 };
    static const uint32_t bad_tri_mat[1] = { 1000 };
    fogrt_scene *scene = default_with_fog(0.3f, 0.9f, 0.6f, NULL);
    log_counts logc = { 0, 0 };
    snapshot before, after;
    double *img_before, *img_after;
    int i;
    /* a scene with a logger: rebuild it through fogrt_scene_desc */
    fogrt_scene_destroy(scene);
    scene = default_with_fog(0.3f, 0.9f, 0.6f, &logc);
    CHECK_OK(fogrt_scene_build(scene, NULL));
    take_snapshot(scene, &before);
    img_before = render_copy(scene);
    logc.errors = 0;

#define EXPECT_ERROR(call, expected, what)                                          \
    do {                                                                            \
        int errors_before_ = logc.errors;                                           \
        fogrt_result r_ = (call);                                                   \
        char m_[160];                                                               \
        snprintf(m_, sizeof m_, "%s (case %d): got '%s'", what, i, fogrt_result_string(r_)); \
        TEST_ASSERT_EQUAL_INT_MESSAGE(expected, r_, m_);                            \
        TEST_ASSERT_EQUAL_INT_MESSAGE(errors_before_ + 1, logc.errors, m_);         \
        take_snapshot(scene, &after);                                               \
        assert_same_snapshot(&before, &after, m_);                                  \
    } while (0)

    for (i = 0; i < COUNT(bad_media); ++i)
        EXPECT_ERROR(fogrt_scene_set_medium(scene, &bad_media[i]), FOGRT_RESULT_INVALID_MEDIUM, "medium");
    for (i = 0; i < COUNT(bad_materials); ++i) {
        uint32_t id = 12345;
        EXPECT_ERROR(fogrt_scene_add_material(scene, &bad_materials[i], &id), FOGRT_RESULT_INVALID_MATERIAL, "material");
        TEST_ASSERT_EQUAL_UINT32(12345, id);   /* the output id is not written */
    }
    for (i = 0; i < COUNT(bad_lights); ++i)
        EXPECT_ERROR(fogrt_scene_add_light(scene, &bad_lights[i]), FOGRT_RESULT_INVALID_LIGHT, "light");
    for (i = 0; i < COUNT(bad_cameras); ++i)
        EXPECT_ERROR(fogrt_scene_set_camera(scene, &bad_cameras[i]), FOGRT_RESULT_INVALID_CAMERA, "camera");
    for (i = 0; i < COUNT(bad_spheres); ++i)
        EXPECT_ERROR(fogrt_scene_add_sphere(scene, bad_spheres[i].c, bad_spheres[i].r, bad_spheres[i].mat),
                     bad_spheres[i].expected, "sphere");
    i = 0;
    {
        fogrt_mesh_desc md;
        memset(&md, 0, sizeof md);
        md.positions = nan_pos; md.vertex_count = 3; md.triangle_count = 1;   /* NaN position */
        EXPECT_ERROR(fogrt_scene_add_mesh(scene, &md), FOGRT_RESULT_INVALID_GEOMETRY, "mesh NaN position");
        md.positions = good_pos; md.normals = inf_nrm;                         /* infinite normal */
        EXPECT_ERROR(fogrt_scene_add_mesh(scene, &md), FOGRT_RESULT_INVALID_GEOMETRY, "mesh infinite normal");
        md.normals = NULL; md.indices = bad_idx;                               /* index out of range */
        EXPECT_ERROR(fogrt_scene_add_mesh(scene, &md), FOGRT_RESULT_INVALID_GEOMETRY, "mesh index");
        md.indices = NULL; md.triangle_count = 2;                              /* 3 vertices, 2 triangles */
        EXPECT_ERROR(fogrt_scene_add_mesh(scene, &md), FOGRT_RESULT_INVALID_GEOMETRY, "mesh vertex count");
        md.triangle_count = 1; md.material = 1000;                             /* material out of range */
        EXPECT_ERROR(fogrt_scene_add_mesh(scene, &md), FOGRT_RESULT_INVALID_MATERIAL, "mesh material");
        md.material = 0; md.triangle_materials = bad_tri_mat;                  /* per-triangle material */
        EXPECT_ERROR(fogrt_scene_add_mesh(scene, &md), FOGRT_RESULT_INVALID_MATERIAL, "mesh triangle material");
    }
    {
        /* environment: negative or NaN radiance (documented as bad data; the code is
           INVALID_ARGUMENT) */
        EXPECT_ERROR(fogrt_scene_set_environment(scene, v3(-1, 0, 0), false), FOGRT_RESULT_INVALID_ARGUMENT, "environment");
        EXPECT_ERROR(fogrt_scene_set_environment(scene, v3(0, NAN_F, 0), true), FOGRT_RESULT_INVALID_ARGUMENT, "environment");
    }
    {
        /* a bad build desc does not throw the built scene away */
        fogrt_build_desc bd;
        bd = fogrt_build_defaults();
        bd.bins = 65;                                                          /* more than 64 bins */
        EXPECT_ERROR(fogrt_scene_build(scene, &bd), FOGRT_RESULT_INVALID_ARGUMENT, "build bins");
        bd = fogrt_build_defaults();
        bd.c_int = -1.0f;                                                      /* negative cost */
        EXPECT_ERROR(fogrt_scene_build(scene, &bd), FOGRT_RESULT_INVALID_ARGUMENT, "build cost");
    }
#undef EXPECT_ERROR
    /* still built, and the same image bit for bit */
    img_after = render_copy(scene);
    TEST_ASSERT_EQUAL_MEMORY_MESSAGE(img_before, img_after, sizeof(float) * 3 * 8 * 6,
                                     "a rejected call changed the rendered image");
    free(img_before);
    free(img_after);
    fogrt_scene_destroy(scene);
}

/* Invalid render requests return INVALID_ARGUMENT (or NOT_BUILT) and add nothing to the
   image; samples_per_pixel 0 is a valid no-op. */
static void test_invalid_render_requests(void)
{
    fogrt_scene *scene = default_with_fog(0.3f, 0.9f, 0.6f, NULL);
    fogrt_image img;
    fogrt_render_desc rd = small_desc(8, 6);
    fogrt_render_stats st;
    int i;
    /* columns: what to break in the desc, and the samples per pixel */
    static const struct { int field, value, spp; } bad[] = {
        { 0, 9, 1 },     /* width differs from the image */
        { 1, 5, 1 },     /* height differs from the image */
        { 2, -2, 1 },    /* max_depth below -1 */
        { 3, -1, 1 },    /* negative rr_depth */
        { 4, -3, 1 },    /* negative light_samples */
        { 5, 42, 1 },    /* unknown integrator */
        { 6, 42, 1 },    /* unknown Fresnel mode */
        { 7, 0, -1 },    /* negative samples per pixel */
    };
    CHECK_OK(fogrt_image_alloc(&img, 8, 6, NULL));
    /* before the build */
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_NOT_BUILT, fogrt_render(scene, &rd, &img, 1, NULL));
    CHECK_OK(fogrt_scene_build(scene, NULL));
    for (i = 0; i < COUNT(bad); ++i) {
        fogrt_render_desc b = rd;
        int k;
        switch (bad[i].field) {
        case 0: b.width = bad[i].value; break;
        case 1: b.height = bad[i].value; break;
        case 2: b.max_depth = bad[i].value; break;
        case 3: b.rr_depth = bad[i].value; break;
        case 4: b.light_samples = bad[i].value; break;
        case 5: b.integrator = (fogrt_integrator)bad[i].value; break;
        case 6: b.fresnel = (fogrt_fresnel)bad[i].value; break;
        default: break;
        }
        TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_RESULT_INVALID_ARGUMENT, fogrt_render(scene, &b, &img, bad[i].spp, NULL),
                                      "invalid render desc accepted");
        for (k = 0; k < 8 * 6; ++k) TEST_ASSERT_EQUAL_UINT32(0, img.count[k]);
    }
    /* zero samples: fine, nothing added */
    CHECK_OK(fogrt_render(scene, &rd, &img, 0, &st));
    TEST_ASSERT_EQUAL_UINT64(0, st.camera_rays);
    TEST_ASSERT_EQUAL_UINT32(0, img.count[0]);
    /* a change after the build needs a new build */
    {
        fogrt_medium_desc med;
        fogrt_scene_get_medium(scene, &med);
        med.sigma_t = 0.5f;
        CHECK_OK(fogrt_scene_set_medium(scene, &med));
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_NOT_BUILT, fogrt_render(scene, &rd, &img, 1, NULL));
    }
    fogrt_image_free(&img);
    fogrt_scene_destroy(scene);
}

/* ======================================================================================== */
/* Running out of memory                                                                   */
/* ======================================================================================== */

/* An allocator that fails from the n-th allocation on (and counts what is live and how
   many requests it refused). */
typedef struct failing_allocator { long allowed, live, refused; } failing_allocator;
static void *failing_alloc(size_t size, void *user)
{
    failing_allocator *f = (failing_allocator *)user;
    void *p;
    if (f->allowed <= 0) { f->refused++; return NULL; }
    p = malloc(size);
    if (p) { f->allowed--; f->live++; }
    return p;
}
static void failing_free(void *ptr, void *user)
{
    failing_allocator *f = (failing_allocator *)user;
    if (!ptr) return;
    f->live--;
    free(ptr);
}

/* Building the default scene with an allocator that fails after 0, 1, 2, ... allocations:
   every call returns OK or OUT_OF_MEMORY (never crashes), a failed call leaves a scene that
   can still be destroyed, and nothing leaks (every block freed). The loop ends with the
   first n at which no allocation was refused: every later n runs the same successful
   calls again (each with the build's roulette pilot, the costly part). */
static void test_out_of_memory(void)
{
    long n, refused = 1;
    for (n = 0; refused > 0; ++n) {
        failing_allocator fa;
        fogrt_scene_desc sd;
        fogrt_scene *scene = NULL;
        fogrt_result r;
        char msg[320];
        TEST_ASSERT_TRUE_MESSAGE(n < 1000, "every allocation still refused after 1000 allowed");
        fa.allowed = n; fa.live = 0; fa.refused = 0;
        memset(&sd, 0, sizeof sd);
        sd.allocator.alloc_fn = failing_alloc;
        sd.allocator.free_fn = failing_free;
        sd.allocator.user_data = &fa;
        r = fogrt_scene_create(&sd, &scene);
        snprintf(msg, sizeof msg, "allocations allowed %ld: %s", n, fogrt_result_string(r));
        if (r == FOGRT_RESULT_OK) {
            r = fogrt_scene_add_default(scene);
            TEST_ASSERT_TRUE_MESSAGE(r == FOGRT_RESULT_OK || r == FOGRT_RESULT_OUT_OF_MEMORY, msg);
            if (r == FOGRT_RESULT_OK) {
                r = fogrt_scene_build(scene, NULL);
                TEST_ASSERT_TRUE_MESSAGE(r == FOGRT_RESULT_OK || r == FOGRT_RESULT_OUT_OF_MEMORY, msg);
                if (r == FOGRT_RESULT_OK) {
                    fogrt_image img;
                    r = fogrt_image_alloc(&img, 4, 3, &sd.allocator);
                    TEST_ASSERT_TRUE_MESSAGE(r == FOGRT_RESULT_OK || r == FOGRT_RESULT_OUT_OF_MEMORY, msg);
                    if (r == FOGRT_RESULT_OK) {
                        fogrt_render_desc rd = small_desc(4, 3);
                        CHECK_OK(fogrt_render(scene, &rd, &img, 1, NULL));
                        TEST_ASSERT_EQUAL_UINT64(0, img.rejected);
                        fogrt_image_free(&img);
                    }
                }
            }
            fogrt_scene_destroy(scene);
        } else {
            TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_RESULT_OUT_OF_MEMORY, r, msg);
            TEST_ASSERT_NULL(scene);
        }
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, (int)fa.live, msg);
        refused = fa.refused;
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_g_matrix);
    RUN_TEST(test_g_renders);
    RUN_TEST(test_sigma_sampling);
    RUN_TEST(test_sigma_renders);
    RUN_TEST(test_samplers_at_extreme_uniforms);
    RUN_TEST(test_equiangular_extremes);
    RUN_TEST(test_equiangular_near_line);
    RUN_TEST(test_hg_angles_precision);
    RUN_TEST(test_clip_to_cone_lines);
    RUN_TEST(test_fresnel_grazing);
    RUN_TEST(test_bsdf_sample_extremes);
    RUN_TEST(test_refraction_extremes);
    RUN_TEST(test_specular_renders);
    RUN_TEST(test_extreme_rays);
    RUN_TEST(test_trace_extreme_rays);
    RUN_TEST(test_degenerate_triangles);
    RUN_TEST(test_scene_scale);
    RUN_TEST(test_point_light_singularities);
    RUN_TEST(test_spot_cutoffs);
    RUN_TEST(test_zero_intensity_light);
    RUN_TEST(test_invalid_parameters);
    RUN_TEST(test_invalid_render_requests);
    RUN_TEST(test_out_of_memory);
    return UNITY_END();
}
