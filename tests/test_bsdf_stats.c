/* test_bsdf_stats.c - do the BSDFs sample what they evaluate, and obey the laws of optics?

   Diffuse: a chi-square test of fogrt_sample_bsdf against fogrt_bsdf_pdf at several
   outgoing directions, including from the back side (reflecting surfaces are two-sided).
   Delta BSDFs (mirror, refraction, glass) have no density to test; instead: the exact
   reflection and refraction directions (Snell's law checked numerically), and for glass a
   binomial test that the reflect/refract choice happens with probability F, the Fresnel
   reflectance, for both Fresnel modes, at several angles from outside and inside. Each
   statistical family has negative controls. tests/stats.h has the statistics;
   docs/testing.md explains how to read a failure.                                          */
/* Public API only: make test links this program with one shared build of the
   implementation (compiled with FOGRT_TESTS_SHARED_IMPL) instead of compiling it again. */
#ifndef FOGRT_TESTS_SHARED_IMPL
#define FOGRT_IMPLEMENTATION
#endif
#include "fogrt.h"
#include "unity.h"
#include "stats.h"
#include "test_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void setUp(void) {}
void tearDown(void) {}

static double len3(fogrt_vec3 v) { return sqrt((double)v.x * v.x + (double)v.y * v.y + (double)v.z * v.z); }

/* A unit direction from its cosine to the normal (+z) and an azimuth. */
static fogrt_vec3 dir_from(double cos_theta, double phi)
{
    double s = sqrt(fmax(0.0, 1.0 - cos_theta * cos_theta));
    return v3((float)(s * cos(phi)), (float)(s * sin(phi)), (float)cos_theta);
}

static fogrt_material_desc make_material(fogrt_bsdf_type type, float ior)
{
    fogrt_material_desc m;
    memset(&m, 0, sizeof m);
    m.type = type;
    m.reflectance = v3(0.8f, 0.6f, 0.4f);
    m.transmittance = v3(0.9f, 0.95f, 1.0f);
    m.ior = ior;
    return m;
}

/* TALLY_ASSERT and REPORT live in stats.h. */

/* ==========================================================================================
   Diffuse: chi-square against its own pdf
   ========================================================================================== */
typedef struct bsdf_pdf_args { const fogrt_material_desc *m; fogrt_vec3 wo; int model; } bsdf_pdf_args;
enum { MODEL_FOGRT_PDF, MODEL_UNIFORM_HEMISPHERE, MODEL_OTHER_SIDE };

/* The model pdf over directions: fogrt_bsdf_pdf, or (negative controls) a uniform
   hemisphere on wo's side, or the cosine lobe on the side opposite to wo. */
static double bsdf_pdf_callback(const double w[3], void *user)
{
    const bsdf_pdf_args *a = (const bsdf_pdf_args *)user;
    double side = a->wo.z < 0.0f ? -1.0 : 1.0;
    switch (a->model) {
    case MODEL_UNIFORM_HEMISPHERE: return side * w[2] > 0.0 ? 1.0 / (2.0 * STATS_PI) : 0.0;
    case MODEL_OTHER_SIDE: return side * w[2] < 0.0 ? fabs(w[2]) / STATS_PI : 0.0;
    default: return fogrt_bsdf_pdf(a->m, a->wo, v3((float)w[0], (float)w[1], (float)w[2]));
    }
}

/* fogrt_sample_bsdf of the diffuse BSDF follows fogrt_bsdf_pdf at normal, oblique and
   grazing incidence and from the back (wo.z < 0: the lobe must flip to the back side), and
   each sample reports that pdf and the weight f cos / pdf = reflectance. Negative controls:
   a uniform hemisphere, and the lobe on the wrong side. Fails if the sampler and the pdf
   disagree (biased MIS) or the back side is not mirrored. */
static void test_diffuse_chi2(void)
{
    stats_tally t = {0, 0, ""};
    fogrt_material_desc m = make_material(FOGRT_BSDF_DIFFUSE, 0.0f);
    const double wo_cos[5] = {1.0, 0.8, 0.0447, -0.866, -1.0};
    const double wo_phi[5] = {0.0, 0.0, 0.3, 2.2, 0.0};
    stats_sphere_grid grid;
    stats_grid_init(&grid, 40, 40);    /* even: an edge on the horizon */
    double *observed = (double *)calloc(40 * 40, sizeof(double)), *expected = (double *)calloc(40 * 40, sizeof(double));
    double phi_edge[41];
    for (int j = 0; j <= 40; j++) phi_edge[j] = -STATS_PI + 2.0 * STATS_PI * j / 40.0;
    TEST_ASSERT_TRUE(observed && expected);
    for (int k = 0; k < 5; k++) {
        fogrt_vec3 wo = dir_from(wo_cos[k], wo_phi[k]);
        fogrt_rng rng;
        fogrt_rng_seed(&rng, 20000 + (uint64_t)k, 1);
        const long n = 200000;
        long invalid = 0, bad_pdf = 0, bad_weight = 0;
        memset(observed, 0, sizeof(double) * 40 * 40);
        for (long i = 0; i < n; i++) {
            float ul = fogrt_rng_float(&rng), u1 = fogrt_rng_float(&rng), u2 = fogrt_rng_float(&rng);
            fogrt_bsdf_sample s;
            if (!fogrt_sample_bsdf(&m, FOGRT_FRESNEL_DEFAULT, wo, ul, u1, u2, &s)) { invalid++; continue; }
            int cell = stats_grid_cell(&grid, s.wi.x, s.wi.y, s.wi.z);
            if (cell < 0) { invalid++; continue; }
            observed[cell] += 1.0;
            float want_pdf = fogrt_bsdf_pdf(&m, wo, s.wi);
            if (!(fabsf(s.pdf - want_pdf) <= 1e-6f * want_pdf) || s.is_delta || s.is_transmission) bad_pdf++;
            if (fabsf(s.weight.x - m.reflectance.x) > 1e-6f || fabsf(s.weight.y - m.reflectance.y) > 1e-6f ||
                fabsf(s.weight.z - m.reflectance.z) > 1e-6f) bad_weight++;
        }
        bsdf_pdf_args a = {&m, wo, MODEL_FOGRT_PDF};
        double total = stats_grid_expected_from_pdf(&grid, bsdf_pdf_callback, &a, (double)n, expected);
        char name[64], param[160], msg[400];
        snprintf(name, sizeof name, "diffuse_wo%d", k);
        snprintf(param, sizeof param, "wo=(%.4f,%.4f,%.4f)", (double)wo.x, (double)wo.y, (double)wo.z);
        snprintf(msg, sizeof msg, "diffuse %s: fogrt_bsdf_pdf integrates to %.6f over the sphere; %ld samples with "
                 "a pdf != fogrt_bsdf_pdf or delta flags, %ld with weight != reflectance", param, total, bad_pdf, bad_weight);
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-4, 1.0, total, msg);
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, bad_pdf, msg);
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, bad_weight, msg);
        REPORT(t, stats_chi2_verdict(name, "fogrt_sample_bsdf (diffuse) vs fogrt_bsdf_pdf", param, 40, 40,
                                     grid.cos_edge, "cos theta", phi_edge, "phi", observed, expected, invalid, false));
        if (k == 0 || k == 3) {
            a.model = k == 0 ? MODEL_UNIFORM_HEMISPHERE : MODEL_OTHER_SIDE;
            stats_grid_expected_from_pdf(&grid, bsdf_pdf_callback, &a, (double)n, expected);
            snprintf(param, sizeof param, "wo=(%.4f,%.4f,%.4f), model: %s", (double)wo.x, (double)wo.y, (double)wo.z,
                     k == 0 ? "uniform hemisphere" : "cosine lobe on the side opposite to wo");
            REPORT(t, stats_chi2_verdict(name, "fogrt_sample_bsdf (diffuse) vs fogrt_bsdf_pdf", param, 40, 40,
                                         grid.cos_edge, "cos theta", phi_edge, "phi", observed, expected, invalid, true));
        }
    }
    free(observed);
    free(expected);
    TALLY_ASSERT(t);
}

/* Diffuse eval: f = reflectance / pi when wo and wi are on the same side (front or back),
   0 across the surface, and reciprocal, f(wo, wi) = f(wi, wo), for random pairs; the pdf is
   |cos theta_i| / pi. Fails on a one-sided diffuse or a missing 1/pi. */
static void test_diffuse_eval_values_and_reciprocity(void)
{
    fogrt_material_desc m = make_material(FOGRT_BSDF_DEFAULT, 0.0f);   /* DEFAULT = diffuse */
    fogrt_rng rng;
    fogrt_rng_seed(&rng, 21000, 2);
    char msg[200];
    for (int i = 0; i < 5000; i++) {
        fogrt_vec3 wo = fogrt_sample_uniform_sphere(fogrt_rng_float(&rng), fogrt_rng_float(&rng));
        fogrt_vec3 wi = fogrt_sample_uniform_sphere(fogrt_rng_float(&rng), fogrt_rng_float(&rng));
        if (wo.z == 0.0f || wi.z == 0.0f) continue;
        fogrt_vec3 f = fogrt_bsdf_eval(&m, wo, wi), r = fogrt_bsdf_eval(&m, wi, wo);
        bool same_side = (wo.z > 0.0f) == (wi.z > 0.0f);
        double want = same_side ? 1.0 / STATS_PI : 0.0;
        snprintf(msg, sizeof msg, "wo=(%g,%g,%g) wi=(%g,%g,%g): f=(%g,%g,%g), f(wi,wo)=(%g,%g,%g)", (double)wo.x,
                 (double)wo.y, (double)wo.z, (double)wi.x, (double)wi.y, (double)wi.z, (double)f.x, (double)f.y,
                 (double)f.z, (double)r.x, (double)r.y, (double)r.z);
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-7, want * m.reflectance.x, (double)f.x, msg);
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-7, want * m.reflectance.y, (double)f.y, msg);
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-7, want * m.reflectance.z, (double)f.z, msg);
        TEST_ASSERT_TRUE_MESSAGE(f.x == r.x && f.y == r.y && f.z == r.z, msg);
        double pdf_want = same_side ? fabs((double)wi.z) / STATS_PI : 0.0;
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-7, pdf_want, (double)fogrt_bsdf_pdf(&m, wo, wi), msg);
    }
}

/* ==========================================================================================
   Delta BSDFs: exact directions
   ========================================================================================== */
/* Snell's law, checked numerically in the local frame: the transmitted direction is on
   the other side, in the plane of incidence (opposite azimuth), of unit length, and
   n_i sin(theta_i) = n_t sin(theta_t). eta = n_inside / n_outside; the outside is +z. */
static void assert_snell(fogrt_vec3 wo, fogrt_vec3 wi, float eta, const char *what)
{
    double n_i = wo.z > 0.0f ? 1.0 : eta, n_t = wo.z > 0.0f ? eta : 1.0;
    double sin_i = sqrt((double)wo.x * wo.x + (double)wo.y * wo.y) / len3(wo);
    double sin_t = sqrt((double)wi.x * wi.x + (double)wi.y * wi.y) / len3(wi);
    char msg[300];
    snprintf(msg, sizeof msg, "%s: wo=(%g,%g,%g) wi=(%g,%g,%g): n_i sin_i = %.7f, n_t sin_t = %.7f", what, (double)wo.x,
             (double)wo.y, (double)wo.z, (double)wi.x, (double)wi.y, (double)wi.z, n_i * sin_i, n_t * sin_t);
    TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-5, 1.0, len3(wi), msg);
    TEST_ASSERT_TRUE_MESSAGE((wo.z > 0.0f) != (wi.z > 0.0f), msg);                  /* crossed over */
    TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(2e-6, n_i * sin_i, n_t * sin_t, msg);          /* Snell */
    /* In the plane of incidence, on the far side of the normal: wi_xy = -k wo_xy, k > 0. */
    double cross = (double)wo.x * wi.y - (double)wo.y * wi.x, dot = (double)wo.x * wi.x + (double)wo.y * wi.y;
    TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(2e-6, 0.0, cross, msg);
    TEST_ASSERT_TRUE_MESSAGE(dot <= 1e-7, msg);
}

static void assert_mirror(fogrt_vec3 wo, fogrt_vec3 wi, const char *what)
{
    char msg[300];
    snprintf(msg, sizeof msg, "%s: wo=(%g,%g,%g) wi=(%g,%g,%g), want (-wo.x, -wo.y, wo.z)", what, (double)wo.x,
             (double)wo.y, (double)wo.z, (double)wi.x, (double)wi.y, (double)wi.z);
    TEST_ASSERT_FLOAT_WITHIN_MESSAGE(1e-6f, -wo.x, wi.x, msg);
    TEST_ASSERT_FLOAT_WITHIN_MESSAGE(1e-6f, -wo.y, wi.y, msg);
    TEST_ASSERT_FLOAT_WITHIN_MESSAGE(1e-6f, wo.z, wi.z, msg);
}

/* Mirror: wi = (-wo.x, -wo.y, wo.z) on both sides, pdf 1, weight = reflectance, a delta
   (eval and pdf 0). fogrt_reflect about a tilted normal keeps the angle to it and the
   plane. Fails on a sign error in the reflection law. */
static void test_mirror_directions(void)
{
    fogrt_material_desc m = make_material(FOGRT_BSDF_MIRROR, 0.0f);
    const double cs[6] = {1.0, 0.7, 0.1, -0.3, -0.9, -1.0};
    for (int k = 0; k < 6; k++) {
        fogrt_vec3 wo = dir_from(cs[k], 0.4 + k);
        fogrt_bsdf_sample s;
        TEST_ASSERT_TRUE(fogrt_sample_bsdf(&m, FOGRT_FRESNEL_DEFAULT, wo, 0.5f, 0.3f, 0.7f, &s));
        assert_mirror(wo, s.wi, "mirror");
        TEST_ASSERT_TRUE(s.is_delta && !s.is_transmission);
        TEST_ASSERT_EQUAL_FLOAT(1.0f, s.pdf);
        TEST_ASSERT_EQUAL_FLOAT(m.reflectance.x, s.weight.x);
        TEST_ASSERT_EQUAL_FLOAT(m.reflectance.z, s.weight.z);
    }
    /* fogrt_reflect about an arbitrary unit normal. */
    fogrt_rng rng;
    fogrt_rng_seed(&rng, 22000, 1);
    for (int i = 0; i < 1000; i++) {
        fogrt_vec3 n = fogrt_sample_uniform_sphere(fogrt_rng_float(&rng), fogrt_rng_float(&rng));
        fogrt_vec3 wo = fogrt_sample_uniform_sphere(fogrt_rng_float(&rng), fogrt_rng_float(&rng));
        fogrt_vec3 wi = fogrt_reflect(n, wo);
        double dn_o = (double)wo.x * n.x + (double)wo.y * n.y + (double)wo.z * n.z;
        double dn_i = (double)wi.x * n.x + (double)wi.y * n.y + (double)wi.z * n.z;
        /* wi + wo is along n: its component perpendicular to n vanishes. */
        double sx = (double)wi.x + wo.x - 2.0 * dn_o * n.x, sy = (double)wi.y + wo.y - 2.0 * dn_o * n.y,
               sz = (double)wi.z + wo.z - 2.0 * dn_o * n.z;
        TEST_ASSERT_DOUBLE_WITHIN(1e-6, dn_o, dn_i);
        TEST_ASSERT_DOUBLE_WITHIN(2e-6, 0.0, sqrt(sx * sx + sy * sy + sz * sz));
        TEST_ASSERT_DOUBLE_WITHIN(1e-5, 1.0, len3(wi));
    }
}

/* Refraction BSDF: entering and leaving obey Snell's law numerically, with pdf 1 and the
   transmission flag; beyond the critical angle from inside it reflects (mirror direction).
   fogrt_refract about arbitrary normals obeys Snell and returns false exactly on total
   internal reflection. Fails on eta used upside down, or a wrong side convention. */
static void test_refraction_snell(void)
{
    const float etas[3] = {1.5f, 1.33f, 2.4f};
    for (int e = 0; e < 3; e++) {
        fogrt_material_desc m = make_material(FOGRT_BSDF_REFRACTION, etas[e]);
        const double cs[7] = {1.0, 0.8, 0.3, 0.02, -0.98, -0.9, -1.0};
        for (int k = 0; k < 7; k++) {
            fogrt_vec3 wo = dir_from(cs[k], 1.1 + k);
            fogrt_bsdf_sample s;
            double sin2_t = wo.z < 0.0f ? (1.0 - cs[k] * cs[k]) * etas[e] * etas[e] : 0.0;
            TEST_ASSERT_TRUE(fogrt_sample_bsdf(&m, FOGRT_FRESNEL_DEFAULT, wo, 0.5f, 0.5f, 0.5f, &s));
            TEST_ASSERT_TRUE(s.is_delta);
            TEST_ASSERT_EQUAL_FLOAT(1.0f, s.pdf);
            if (sin2_t < 1.0) {
                TEST_ASSERT_TRUE(s.is_transmission);
                assert_snell(wo, s.wi, etas[e], "refraction BSDF");
            } else {
                TEST_ASSERT_FALSE(s.is_transmission);
                assert_mirror(wo, s.wi, "refraction BSDF, total internal reflection");
            }
        }
        /* Beyond the critical angle from inside: sin_i = 0.9 > 1 / eta for every eta here. */
        fogrt_vec3 wo = dir_from(-sqrt(1.0 - 0.81), 0.3);
        fogrt_bsdf_sample s;
        TEST_ASSERT_TRUE(fogrt_sample_bsdf(&m, FOGRT_FRESNEL_DEFAULT, wo, 0.999f, 0.5f, 0.5f, &s));
        TEST_ASSERT_FALSE(s.is_transmission);
        assert_mirror(wo, s.wi, "refraction BSDF, total internal reflection");
    }
    /* fogrt_refract about arbitrary normals, from both sides. */
    fogrt_rng rng;
    fogrt_rng_seed(&rng, 23000, 1);
    char msg[300];
    for (int i = 0; i < 2000; i++) {
        float eta = 1.5f;
        fogrt_vec3 n = fogrt_sample_uniform_sphere(fogrt_rng_float(&rng), fogrt_rng_float(&rng));
        fogrt_vec3 wo = fogrt_sample_uniform_sphere(fogrt_rng_float(&rng), fogrt_rng_float(&rng)), wi = v3(0, 0, 0);
        double cos_o = (double)wo.x * n.x + (double)wo.y * n.y + (double)wo.z * n.z;
        double ratio = cos_o > 0.0 ? 1.0 / eta : eta;                /* n_i / n_t */
        double sin2_t = ratio * ratio * (1.0 - cos_o * cos_o);
        if (fabs(sin2_t - 1.0) < 1e-4) continue;                      /* too close to call */
        bool ok = fogrt_refract(n, eta, wo, &wi);
        snprintf(msg, sizeof msg, "fogrt_refract wo=(%g,%g,%g) n=(%g,%g,%g): sin^2 t = %.6f, returned %d", (double)wo.x,
                 (double)wo.y, (double)wo.z, (double)n.x, (double)n.y, (double)n.z, sin2_t, (int)ok);
        TEST_ASSERT_TRUE_MESSAGE(ok == (sin2_t < 1.0), msg);
        if (!ok) continue;
        double cos_i = (double)wi.x * n.x + (double)wi.y * n.y + (double)wi.z * n.z;
        /* |sin| from the cross products with n; Snell: n_i sin_i = n_t sin_t. */
        double cx = (double)wo.y * n.z - (double)wo.z * n.y, cy = (double)wo.z * n.x - (double)wo.x * n.z,
               cz = (double)wo.x * n.y - (double)wo.y * n.x;
        double dx = (double)wi.y * n.z - (double)wi.z * n.y, dy = (double)wi.z * n.x - (double)wi.x * n.z,
               dz = (double)wi.x * n.y - (double)wi.y * n.x;
        double sin_o = sqrt(cx * cx + cy * cy + cz * cz), sin_i = sqrt(dx * dx + dy * dy + dz * dz);
        TEST_ASSERT_TRUE_MESSAGE((cos_o > 0.0) != (cos_i > 0.0), msg);                   /* other side */
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(3e-6, ratio * sin_o, sin_i, msg);               /* Snell */
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(3e-6, 0.0, (double)wi.x * cx + (double)wi.y * cy + (double)wi.z * cz, msg);
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-5, 1.0, len3(wi), msg);
    }
}

/* ==========================================================================================
   Fresnel
   ========================================================================================== */
/* Exact unpolarised Fresnel reflectance in double; cos_i < 0 from inside. */
static double fresnel_exact_ref(double cos_i, double eta)
{
    if (cos_i < 0.0) { cos_i = -cos_i; eta = 1.0 / eta; }
    double sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1.0) return 1.0;
    double cos_t = sqrt(1.0 - sin2_t);
    double rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    double rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    return 0.5 * (rs * rs + rp * rp);
}

/* The exact Fresnel is Part II's (C): under FOGRT_MINIMAL the checks of
   fogrt_fresnel_dielectric are left out, the glass is sampled with Schlick's alone, and
   messages and negative controls show the double reference in its place. */
#ifdef FOGRT_MINIMAL
#define EXACT_F(eta, c) ((float)fresnel_exact_ref((double)(c), (double)(eta)))
#define FRESNEL_MODES 1
#define SNELL_MODE FOGRT_FRESNEL_SCHLICK
#else
#define EXACT_F(eta, c) fogrt_fresnel_dielectric((eta), (c))
#define FRESNEL_MODES 2
#define SNELL_MODE FOGRT_FRESNEL_EXACT
#endif

/* Schlick in double, with the cosine on the thinner (outside) side. */
static double fresnel_schlick_ref(double cos_i, double eta)
{
    double r0 = (eta - 1.0) / (eta + 1.0), c = cos_i;
    r0 *= r0;
    if (cos_i < 0.0) {
        double sin2_t = (1.0 - cos_i * cos_i) * eta * eta;
        if (sin2_t >= 1.0) return 1.0;
        c = sqrt(1.0 - sin2_t);
    }
    return r0 + (1.0 - r0) * pow(1.0 - c, 5.0);
}

/* Known values: at normal incidence eta = 1.5 reflects ((1.5-1)/(1.5+1))^2 = 0.04 with both
   forms, from either side; grazing incidence reflects 1; beyond the critical angle 1. At
   other angles both forms match their double-precision formulas, and the exact form is
   reciprocal: F at theta_i outside equals F at theta_t inside. Fails on a wrong R0, a
   Schlick using the inside cosine when leaving, or s/p terms mixed up. */
static void test_fresnel_known_values(void)
{
    char msg[300];
    TEST_ASSERT_FLOAT_WITHIN(1e-7f, 0.04f, fogrt_fresnel_schlick(1.5f, 1.0f));
#ifndef FOGRT_MINIMAL
    TEST_ASSERT_FLOAT_WITHIN(1e-7f, 0.04f, fogrt_fresnel_dielectric(1.5f, 1.0f));
#endif
    TEST_ASSERT_FLOAT_WITHIN(1e-7f, 0.04f, fogrt_fresnel_schlick(1.5f, -1.0f));
#ifndef FOGRT_MINIMAL
    TEST_ASSERT_FLOAT_WITHIN(1e-7f, 0.04f, fogrt_fresnel_dielectric(1.5f, -1.0f));
#endif
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 1.0f, fogrt_fresnel_schlick(1.5f, 0.0f));
#ifndef FOGRT_MINIMAL
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 1.0f, fogrt_fresnel_dielectric(1.5f, 0.0f));
#endif
    TEST_ASSERT_EQUAL_FLOAT(1.0f, fogrt_fresnel_schlick(1.5f, -0.5f));       /* sin_t = 1.3: TIR */
#ifndef FOGRT_MINIMAL
    TEST_ASSERT_EQUAL_FLOAT(1.0f, fogrt_fresnel_dielectric(1.5f, -0.5f));
#endif
    /* The glass BSDF at normal incidence picks reflection with probability (pdf) 0.04. */
    fogrt_material_desc glass = make_material(FOGRT_BSDF_GLASS, 1.5f);
    fogrt_bsdf_sample s;
    TEST_ASSERT_TRUE(fogrt_sample_bsdf(&glass, SNELL_MODE, v3(0, 0, 1), 0.0f, 0.5f, 0.5f, &s));
    TEST_ASSERT_FLOAT_WITHIN(1e-7f, 0.04f, s.pdf);
    TEST_ASSERT_TRUE(fogrt_sample_bsdf(&glass, FOGRT_FRESNEL_SCHLICK, v3(0, 0, 1), 0.99f, 0.5f, 0.5f, &s));
    TEST_ASSERT_FLOAT_WITHIN(1e-7f, 0.96f, s.pdf);

    /* Near the critical angle F changes steeply with the cosine, so each check allows, on
       top of 1e-5 relative, the change in F that a shift of the cosine by 4 float ulps
       (2.4e-7) causes: fogrt computes in float, the reference in double. */
    const float etas[3] = {1.5f, 1.33f, 2.4f};
    const double ulps = 4.0 * 0x1p-24;
    for (int e = 0; e < 3; e++) {
        for (int k = -99; k <= 99; k++) {
            float c = (float)k / 100.0f;
            double ex = fresnel_exact_ref(c, etas[e]), sc = fresnel_schlick_ref(c, etas[e]);
            double ex_tol = 2e-6 + 1e-5 * ex + 0.5 * fabs(fresnel_exact_ref(c + ulps, etas[e]) - fresnel_exact_ref(c - ulps, etas[e]));
            double sc_tol = 2e-6 + 1e-5 * sc + 0.5 * fabs(fresnel_schlick_ref(c + ulps, etas[e]) - fresnel_schlick_ref(c - ulps, etas[e]));
            snprintf(msg, sizeof msg, "eta=%g cos_i=%g: exact %.7f (want %.7f +- %.2g), Schlick %.7f (want %.7f +- %.2g)",
                     (double)etas[e], (double)c, (double)EXACT_F(etas[e], c), ex, ex_tol,
                     (double)fogrt_fresnel_schlick(etas[e], c), sc, sc_tol);
#ifndef FOGRT_MINIMAL
            TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(ex_tol, ex, (double)fogrt_fresnel_dielectric(etas[e], c), msg);
#endif
            TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(sc_tol, sc, (double)fogrt_fresnel_schlick(etas[e], c), msg);
#ifndef FOGRT_MINIMAL
            if (k > 0) {
                /* Reciprocity: the transmitted angle seen from inside reflects the same. */
                float cos_t = (float)sqrt(1.0 - (1.0 - (double)c * c) / ((double)etas[e] * etas[e]));
                double back = fogrt_fresnel_dielectric(etas[e], -cos_t);
                double back_tol = ex_tol + 0.5 * fabs(fresnel_exact_ref(-cos_t + ulps, etas[e]) -
                                                      fresnel_exact_ref(-cos_t - ulps, etas[e]));
                snprintf(msg, sizeof msg, "eta=%g: F(cos_i=%g outside) = %.7f but F(cos_t=%.7f inside) = %.7f (tol %.2g)",
                         (double)etas[e], (double)c, (double)fogrt_fresnel_dielectric(etas[e], c), (double)cos_t, back,
                         back_tol);
                TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(back_tol, (double)fogrt_fresnel_dielectric(etas[e], c), back, msg);
            }
#endif
        }
    }
}

/* Schlick for any eta (also eta < 1, an object optically thinner than the outside, such
   as an air bubble in water): total internal reflection can then happen from OUTSIDE, and
   the thinner side, whose cosine Schlick needs, is the inside. In double. */
static double fresnel_schlick_general_ref(double cos_i, double eta)
{
    double n_i = cos_i >= 0.0 ? 1.0 : eta, n_t = cos_i >= 0.0 ? eta : 1.0, c_i = fabs(cos_i);
    double sin2_t = (n_i / n_t) * (n_i / n_t) * (1.0 - c_i * c_i);
    if (sin2_t >= 1.0) return 1.0;
    double c_t = sqrt(1.0 - sin2_t), r0 = (eta - 1.0) / (eta + 1.0);
    r0 *= r0;
    double c = n_i <= n_t ? c_i : c_t;             /* the cosine on the thinner side */
    return r0 + (1.0 - r0) * pow(1.0 - c, 5.0);
}

/* eta < 1 (allowed: only ior <= 0 is rejected): both Fresnel forms return 1 on total
   internal reflection, which now happens from outside (fogrt.h: "Both return 1 on total
   internal reflection"), and Schlick uses the cosine on the thinner side, which is now
   the inside. Also: the same interface seen from the other side, eta -> 1/eta with the
   side flipped, reflects the same. Fails if Schlick assumes eta > 1. */
static void test_fresnel_eta_below_one(void)
{
    char msg[300];
    const float etas[2] = {0.8f, 1.0f / 1.33f};
    const double ulps = 4.0 * 0x1p-24;
    /* First the contract: beyond the critical angle (cos < 0.6 for eta = 0.8) from outside. */
    const float beyond[3] = {0.5f, 0.3f, 0.1f};
    for (int k = 0; k < 3; k++) {
        snprintf(msg, sizeof msg, "eta=0.8, cos_i=%g from outside: sin_t = %.3f > 1, total internal reflection, but "
                 "fogrt_fresnel_schlick = %.7f and fogrt_fresnel_dielectric = %.7f (want 1)", (double)beyond[k],
                 sqrt(1.0 - (double)beyond[k] * beyond[k]) / 0.8, (double)fogrt_fresnel_schlick(0.8f, beyond[k]),
                 (double)EXACT_F(0.8f, beyond[k]));
#ifndef FOGRT_MINIMAL
        TEST_ASSERT_EQUAL_FLOAT_MESSAGE(1.0f, fogrt_fresnel_dielectric(0.8f, beyond[k]), msg);
#endif
        TEST_ASSERT_EQUAL_FLOAT_MESSAGE(1.0f, fogrt_fresnel_schlick(0.8f, beyond[k]), msg);
    }
    for (int e = 0; e < 2; e++) {
        for (int k = -99; k <= 99; k++) {
            float c = (float)k / 100.0f;
            double ex = fresnel_exact_ref(c, etas[e]), sc = fresnel_schlick_general_ref(c, etas[e]);
            double ex_tol = 2e-6 + 1e-5 * ex + 0.5 * fabs(fresnel_exact_ref(c + ulps, etas[e]) - fresnel_exact_ref(c - ulps, etas[e]));
            double sc_tol = 2e-6 + 1e-5 * sc +
                            0.5 * fabs(fresnel_schlick_general_ref(c + ulps, etas[e]) - fresnel_schlick_general_ref(c - ulps, etas[e]));
            float got_ex = EXACT_F(etas[e], c), got_sc = fogrt_fresnel_schlick(etas[e], c);
            float mirror_sc = fogrt_fresnel_schlick(1.0f / etas[e], -c);   /* same interface, other side */
            snprintf(msg, sizeof msg, "eta=%g cos_i=%g%s: exact %.7f (want %.7f), Schlick %.7f (want %.7f; "
                     "the same interface seen from the other side, fogrt_fresnel_schlick(%g, %g) = %.7f)",
                     (double)etas[e], (double)c, ex == 1.0 ? " (total internal reflection)" : "", (double)got_ex, ex,
                     (double)got_sc, sc, (double)-c, 1.0 / etas[e], (double)mirror_sc);
#ifndef FOGRT_MINIMAL
            TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(ex_tol, ex, (double)got_ex, msg);
#else
            (void)ex_tol;
#endif
            TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(sc_tol, sc, (double)got_sc, msg);
        }
    }
}

/* ==========================================================================================
   Glass: how often does it reflect?
   ========================================================================================== */
typedef struct glass_counts { long reflect, n, bad; } glass_counts;

/* Samples the glass BSDF n times at wo and counts reflections; every sample must also have
   pdf = F (reflect) or 1 - F (refract), the reflect or Snell direction, and flags that
   agree with the side wi is on. Returns the counts (bad = samples that broke a rule). */
static glass_counts sample_glass(const fogrt_material_desc *m, fogrt_fresnel mode, fogrt_vec3 wo, long n, uint64_t seed)
{
    glass_counts c = {0, n, 0};
    float F = mode == FOGRT_FRESNEL_EXACT ? EXACT_F(m->ior, wo.z) : fogrt_fresnel_schlick(m->ior, wo.z);
    fogrt_rng rng;
    fogrt_rng_seed(&rng, seed, 4);
    for (long i = 0; i < n; i++) {
        float ul = fogrt_rng_float(&rng), u1 = fogrt_rng_float(&rng), u2 = fogrt_rng_float(&rng);
        fogrt_bsdf_sample s;
        if (!fogrt_sample_bsdf(m, mode, wo, ul, u1, u2, &s)) { c.bad++; continue; }
        bool reflected = (s.wi.z > 0.0f) == (wo.z > 0.0f);
        if (reflected) {
            c.reflect++;
            if (s.is_transmission || fabsf(s.pdf - F) > 1e-6f || s.wi.x != -wo.x || s.wi.y != -wo.y || s.wi.z != wo.z ||
                s.weight.x != m->reflectance.x)
                c.bad++;
        } else {
            if (!s.is_transmission || fabsf(s.pdf - (1.0f - F)) > 1e-6f) c.bad++;
        }
        if (!s.is_delta) c.bad++;
    }
    return c;
}

/* The glass BSDF reflects with probability F, the Fresnel term of the chosen mode, at
   normal, oblique and grazing incidence from outside and at two angles from inside:
   a binomial test on 1e5 choices each (and every transmitted direction obeys Snell).
   From inside beyond the critical angle it always reflects. Negative controls: the Schlick
   frequencies at grazing incidence against the exact F, the exact frequencies from inside
   against F computed as if outside (the wrong side), and Schlick from inside against the
   Schlick that wrongly uses the inside cosine. Fails if u_lobe is compared with 1 - F, the
   Fresnel side is mixed up, or the mode argument is ignored. */
static void test_glass_fresnel_frequency(void)
{
    stats_tally t = {0, 0, ""};
    fogrt_material_desc m = make_material(FOGRT_BSDF_GLASS, 1.5f);
    const double cs[6] = {1.0, 0.7, 0.3, 0.05, -0.95, -0.8};
    const fogrt_fresnel modes[2] = {FOGRT_FRESNEL_SCHLICK, FOGRT_FRESNEL_EXACT};
    const long n = 100000;
    char param[160], msg[200];
    for (int k = 0; k < 6; k++) {
        fogrt_vec3 wo = dir_from(cs[k], 0.7);
        for (int md = 0; md < FRESNEL_MODES; md++) {   /* Schlick, and the exact Fresnel (Part II) */
            float F = md ? EXACT_F(m.ior, wo.z) : fogrt_fresnel_schlick(m.ior, wo.z);
            glass_counts c = sample_glass(&m, modes[md], wo, n, 24000 + 10 * (uint64_t)k + (uint64_t)md);
            snprintf(msg, sizeof msg, "glass cos_o=%g %s: %ld samples broke a rule (pdf != F or 1-F, direction, flags)",
                     cs[k], md ? "exact" : "Schlick", c.bad);
            TEST_ASSERT_EQUAL_INT_MESSAGE(0, c.bad, msg);
            TEST_ASSERT_GREATER_OR_EQUAL_MESSAGE(10, (long)(n * (double)F * (1.0 - F)), "binomial test needs n F (1-F) >= 10");
            snprintf(param, sizeof param, "eta=1.5, cos(wo)=%g, %s Fresnel, F=%.5f", cs[k], md ? "exact" : "Schlick", (double)F);
            REPORT(t, stats_binomial_verdict("glass reflect frequency", param, c.reflect, c.n, F, false));

            if (md == 0 && k == 3) {   /* Schlick frequencies at grazing vs the exact F */
                double Fx = EXACT_F(m.ior, wo.z);
                snprintf(param, sizeof param, "cos(wo)=%g, sampled with Schlick (F=%.5f), model exact F=%.5f", cs[k], (double)F, Fx);
                REPORT(t, stats_binomial_verdict("glass reflect frequency", param, c.reflect, c.n, Fx, true));
            }
            if (md == 1 && k == 5) {   /* exact from inside vs F as if from outside */
                double Fo = EXACT_F(m.ior, -wo.z);
                snprintf(param, sizeof param, "cos(wo)=%g inside, exact F=%.5f, model F from outside=%.5f", cs[k], (double)F, Fo);
                REPORT(t, stats_binomial_verdict("glass reflect frequency", param, c.reflect, c.n, Fo, true));
            }
            if (md == 0 && k == 5) {   /* Schlick from inside with the inside cosine */
                double r0 = 0.04, Fw = r0 + (1.0 - r0) * pow(1.0 - fabs(cs[k]), 5.0);
                snprintf(param, sizeof param, "cos(wo)=%g inside, Schlick F=%.5f, model Schlick of cos_i=%.5f", cs[k], (double)F, Fw);
                REPORT(t, stats_binomial_verdict("glass reflect frequency", param, c.reflect, c.n, Fw, true));
            }
        }
    }
    /* Total internal reflection from inside: every sample reflects, with pdf 1. */
    for (int md = 0; md < FRESNEL_MODES; md++) {
        fogrt_vec3 wo = dir_from(-0.5, 2.0);
        glass_counts c = sample_glass(&m, modes[md], wo, 10000, 25000 + (uint64_t)md);
        snprintf(msg, sizeof msg, "glass, total internal reflection (%s): %ld of %ld reflected, %ld broke a rule",
                 md ? "exact" : "Schlick", c.reflect, c.n, c.bad);
        TEST_MESSAGE(msg);
        TEST_ASSERT_EQUAL_INT_MESSAGE(c.n, c.reflect, msg);
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, c.bad, msg);
    }
    /* Every transmitted direction of the glass obeys Snell's law. */
    for (int k = 0; k < 6; k++) {
        fogrt_vec3 wo = dir_from(cs[k], 0.7);
        fogrt_bsdf_sample s;
        TEST_ASSERT_TRUE(fogrt_sample_bsdf(&m, SNELL_MODE, wo, 1.0f - 0x1p-24f, 0.5f, 0.5f, &s));
        TEST_ASSERT_TRUE(s.is_transmission);
        assert_snell(wo, s.wi, m.ior, "glass transmission");
    }
    TALLY_ASSERT(t);
}

/* Delta BSDFs have no density: eval and pdf are 0 for any pair of directions (the
   integrator must not add them through next-event estimation). */
static void test_delta_bsdfs_eval_and_pdf_are_zero(void)
{
    const fogrt_bsdf_type types[3] = {FOGRT_BSDF_MIRROR, FOGRT_BSDF_REFRACTION, FOGRT_BSDF_GLASS};
    for (int k = 0; k < 3; k++) {
        fogrt_material_desc m = make_material(types[k], 1.5f);
        fogrt_vec3 wo = dir_from(0.6, 0.2), wi_refl = v3(-wo.x, -wo.y, wo.z);
        fogrt_vec3 f = fogrt_bsdf_eval(&m, wo, wi_refl);
        TEST_ASSERT_TRUE(f.x == 0.0f && f.y == 0.0f && f.z == 0.0f);
        TEST_ASSERT_EQUAL_FLOAT(0.0f, fogrt_bsdf_pdf(&m, wo, wi_refl));
        TEST_ASSERT_EQUAL_FLOAT(0.0f, fogrt_bsdf_pdf(&m, wo, dir_from(-0.5, 1.0)));
    }
}

/* This program ran exactly the number of statistical tests that stats.h counts for it. */
static void test_sidak_count_is_right(void)
{
    char msg[200];
    snprintf(msg, sizeof msg, "ran %d statistical tests, stats.h says STATS_TESTS_BSDF_STATS = %d (suite total %d, alpha' = %.3g)",
             *stats_test_counter(), STATS_TESTS_BSDF_STATS, STATS_SUITE_TESTS, stats_alpha());
    TEST_MESSAGE(msg);
    TEST_ASSERT_EQUAL_INT_MESSAGE(STATS_TESTS_BSDF_STATS, *stats_test_counter(), msg);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_diffuse_chi2);
    RUN_TEST(test_diffuse_eval_values_and_reciprocity);
    RUN_TEST(test_mirror_directions);
    RUN_TEST(test_refraction_snell);
    RUN_TEST(test_fresnel_known_values);
    RUN_TEST(test_fresnel_eta_below_one);
    RUN_TEST(test_glass_fresnel_frequency);
    RUN_TEST(test_delta_bsdfs_eval_and_pdf_are_zero);
    RUN_TEST(test_sidak_count_is_right);
    return UNITY_END();
}
