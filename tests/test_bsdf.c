/* test_bsdf.c - the four BSDFs, Fresnel, reflection and refraction.
 *
 * Checks that sampling, evaluation and the pdf of each BSDF agree (weight = f |cos| / pdf,
 * the sampled pdf equals fogrt_bsdf_pdf), that sampled directions are unit vectors on the
 * right side, that no sample gains energy, that the specular BSDFs follow the law of
 * reflection and Snell's law (with total internal reflection), that glass picks its lobe with
 * probability F, and that the Fresnel formulas give their textbook values. */
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
#include <string.h>

void setUp(void) {}
void tearDown(void) {}

#define PI_D 3.14159265358979323846

/* ------------------------------------------------------------------------------------------
   Helpers (test_rng, v3 and vdot come from test_util.h)
   ------------------------------------------------------------------------------------------ */
static float vlen(fogrt_vec3 a) { return sqrtf(vdot(a, a)); }
static fogrt_vec3 vnorm(fogrt_vec3 a) { float l = vlen(a); return v3(a.x / l, a.y / l, a.z / l); }

/* A direction with polar angle theta (from +z) and azimuth phi. */
static fogrt_vec3 polar(double theta, double phi)
{
    return v3((float)(sin(theta) * cos(phi)), (float)(sin(theta) * sin(phi)), (float)cos(theta));
}
/* A random direction with |z| >= zmin, in the upper (side > 0) or lower hemisphere. */
static fogrt_vec3 random_wo(test_rng *r, float side, float zmin)
{
    for (;;) {
        fogrt_vec3 w = v3(2 * rng_uniform(r) - 1, 2 * rng_uniform(r) - 1, rng_uniform(r));
        float l = vlen(w);
        if (l < 0.1f || l > 1.0f) continue;
        w = vnorm(w);
        if (w.z < zmin) continue;
        w.z *= side;
        return w;
    }
}

/* A random direction on the whole sphere. */
static fogrt_vec3 random_dir(test_rng *r)
{
    for (;;) {
        fogrt_vec3 w = v3(2 * rng_uniform(r) - 1, 2 * rng_uniform(r) - 1, 2 * rng_uniform(r) - 1);
        float l = vlen(w);
        if (l > 0.1f && l <= 1.0f) return vnorm(w);
    }
}

static fogrt_material_desc material(fogrt_bsdf_type type, fogrt_vec3 reflectance, fogrt_vec3 transmittance, float ior)
{
    fogrt_material_desc m;
    memset(&m, 0, sizeof m);
    m.type = type;
    m.reflectance = reflectance;
    m.transmittance = transmittance;
    m.ior = ior;
    return m;
}

static void assert_unit(fogrt_vec3 w, const char *what)
{
    TEST_ASSERT_FLOAT_WITHIN_MESSAGE(2e-6f, 1.0f, vlen(w), what);
}

static void assert_vec_within(float tol, fogrt_vec3 want, fogrt_vec3 got, const char *what)
{
    TEST_ASSERT_FLOAT_WITHIN_MESSAGE(tol, want.x, got.x, what);
    TEST_ASSERT_FLOAT_WITHIN_MESSAGE(tol, want.y, got.y, what);
    TEST_ASSERT_FLOAT_WITHIN_MESSAGE(tol, want.z, got.z, what);
}

/* Snell's law for a refracted pair in the local frame (normal +z): n_o sin_o = n_i sin_i,
   opposite sides, and wi's tangential part points opposite to wo's (same plane). */
static void assert_snell(fogrt_vec3 wo, fogrt_vec3 wi, float ior, const char *what)
{
    float n_o = wo.z > 0 ? 1.0f : ior, n_i = wo.z > 0 ? ior : 1.0f;
    float sin_o = sqrtf(wo.x * wo.x + wo.y * wo.y), sin_i = sqrtf(wi.x * wi.x + wi.y * wi.y);
    TEST_ASSERT_TRUE_MESSAGE(wo.z * wi.z < 0.0f, what);
    TEST_ASSERT_FLOAT_WITHIN_MESSAGE(2e-5f, n_o * sin_o, n_i * sin_i, what);
    TEST_ASSERT_FLOAT_WITHIN_MESSAGE(2e-5f, 0.0f, wo.x * wi.y - wo.y * wi.x, what);   /* same plane */
    TEST_ASSERT_TRUE_MESSAGE(wo.x * wi.x + wo.y * wi.y <= 1e-7f, what);              /* other side of n */
}

/* Fresnel reflectance in double precision, written out from the s and p amplitudes: the
   reference for the float implementation. cos_i > 0 outside; eta = n_inside / n_outside. */
static double fresnel_reference(double cos_i, double eta)
{
    double sin2_t, cos_t, rs, rp;
    if (cos_i < 0) { cos_i = -cos_i; eta = 1.0 / eta; }
    sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1.0) return 1.0;
    cos_t = sqrt(1.0 - sin2_t);
    rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    return 0.5 * (rs * rs + rp * rp);
}

/* ------------------------------------------------------------------------------------------
   Diffuse
   ------------------------------------------------------------------------------------------ */

/* For many wo on both sides: a sample's weight equals eval |cos| / pdf, its pdf equals
   fogrt_bsdf_pdf, wi is a unit vector on wo's side (two-sided), the weight never exceeds 1
   for a reflectance <= 1, and the lobe is not delta. */
static void test_diffuse_sample_eval_pdf_agree(void)
{
    fogrt_material_desc m = material(FOGRT_BSDF_DIFFUSE, v3(0.8f, 0.45f, 1.0f), v3(0, 0, 0), 0);
    test_rng r = { 1 };
    int i, produced = 0;
    for (i = 0; i < 20000; i++) {
        float side = (i & 1) ? -1.0f : 1.0f;
        fogrt_vec3 wo = random_wo(&r, side, 0.01f), f;
        fogrt_bsdf_sample s;
        char msg[160];
        float u_lobe = rng_uniform(&r), u1 = rng_uniform(&r), u2 = rng_uniform(&r);
        snprintf(msg, sizeof msg, "wo=(%g,%g,%g) u=(%g,%g)", wo.x, wo.y, wo.z, u1, u2);
        if (!fogrt_sample_bsdf(&m, FOGRT_FRESNEL_DEFAULT, wo, u_lobe, u1, u2, &s)) continue;
        produced++;
        assert_unit(s.wi, msg);
        TEST_ASSERT_TRUE_MESSAGE(s.wi.z * wo.z > 0.0f, msg);
        TEST_ASSERT_FALSE_MESSAGE(s.is_delta, msg);
        TEST_ASSERT_FALSE_MESSAGE(s.is_transmission, msg);
        TEST_ASSERT_TRUE_MESSAGE(s.pdf > 0.0f, msg);
        TEST_ASSERT_FLOAT_WITHIN_MESSAGE(1e-6f * s.pdf, fogrt_bsdf_pdf(&m, wo, s.wi), s.pdf, msg);
        f = fogrt_bsdf_eval(&m, wo, s.wi);
        TEST_ASSERT_FLOAT_WITHIN_MESSAGE(1e-5f, f.x * fabsf(s.wi.z) / s.pdf, s.weight.x, msg);
        TEST_ASSERT_FLOAT_WITHIN_MESSAGE(1e-5f, f.y * fabsf(s.wi.z) / s.pdf, s.weight.y, msg);
        TEST_ASSERT_FLOAT_WITHIN_MESSAGE(1e-5f, f.z * fabsf(s.wi.z) / s.pdf, s.weight.z, msg);
        TEST_ASSERT_TRUE_MESSAGE(s.weight.x <= 1.0f && s.weight.y <= 1.0f && s.weight.z <= 1.0f, msg);
        TEST_ASSERT_TRUE_MESSAGE(s.weight.x >= 0.0f && s.weight.y >= 0.0f && s.weight.z >= 0.0f, msg);
    }
    /* Only a zero-probability corner (wi on the horizon) may produce nothing. */
    TEST_ASSERT_GREATER_THAN(19990, produced);
}

/* Lambert's law: f = reflectance / pi on wo's side, 0 across the surface; the pdf is
   cos / pi on wo's side and 0 across. */
static void test_diffuse_eval_values(void)
{
    fogrt_material_desc m = material(FOGRT_BSDF_DEFAULT, v3(0.5f, 0.25f, 1.0f), v3(0, 0, 0), 0);
    fogrt_vec3 wo = vnorm(v3(0.3f, -0.2f, 0.9f)), wi = vnorm(v3(-0.5f, 0.1f, 0.4f)), f;
    fogrt_vec3 wi_below = v3(wi.x, wi.y, -wi.z), wo_below = v3(wo.x, wo.y, -wo.z);
    f = fogrt_bsdf_eval(&m, wo, wi);
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.5f / (float)PI_D, f.x);
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.25f / (float)PI_D, f.y);
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 1.0f / (float)PI_D, f.z);
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, wi.z / (float)PI_D, fogrt_bsdf_pdf(&m, wo, wi));
    /* Two-sided: the same from below. */
    f = fogrt_bsdf_eval(&m, wo_below, wi_below);
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.5f / (float)PI_D, f.x);
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, wi.z / (float)PI_D, fogrt_bsdf_pdf(&m, wo_below, wi_below));
    /* No transmission. */
    f = fogrt_bsdf_eval(&m, wo, wi_below);
    TEST_ASSERT_EQUAL_FLOAT(0.0f, f.x + f.y + f.z);
    TEST_ASSERT_EQUAL_FLOAT(0.0f, fogrt_bsdf_pdf(&m, wo, wi_below));
}

/* Integrated over the hemisphere with a midpoint rule (not by sampling): the pdf has total
   mass 1 and f |cos| integrates to the reflectance (energy conservation with equality). */
static void test_diffuse_integrals(void)
{
    fogrt_material_desc m = material(FOGRT_BSDF_DIFFUSE, v3(0.7f, 0.7f, 0.7f), v3(0, 0, 0), 0);
    fogrt_vec3 wo = vnorm(v3(0.4f, 0.1f, 0.6f));
    const int n_theta = 200, n_phi = 400;
    double pdf_sum = 0, albedo_sum = 0;
    int i, j;
    for (i = 0; i < n_theta; i++) {
        double theta = (i + 0.5) * (PI_D / 2) / n_theta, dtheta = (PI_D / 2) / n_theta;
        for (j = 0; j < n_phi; j++) {
            double phi = (j + 0.5) * 2 * PI_D / n_phi, domega = sin(theta) * dtheta * (2 * PI_D / n_phi);
            fogrt_vec3 wi = polar(theta, phi);
            pdf_sum += fogrt_bsdf_pdf(&m, wo, wi) * domega;
            albedo_sum += fogrt_bsdf_eval(&m, wo, wi).x * cos(theta) * domega;
        }
    }
    TEST_ASSERT_DOUBLE_WITHIN(1e-4, 1.0, pdf_sum);
    TEST_ASSERT_DOUBLE_WITHIN(1e-4, 0.7, albedo_sum);
}

/* The sampled directions follow the cosine distribution, checked through its moments with
   200k samples (fixed seed): E[cos] = 2/3, E[cos^2] = 1/2, E[x] = E[y] = 0, E[x^2] = 1/4.
   A sampler whose pdf is computed from the direction passes the test above even if it draws
   from the wrong distribution; this one does not. Tolerance: 5 standard errors. */
static void test_diffuse_sample_moments(void)
{
    fogrt_material_desc m = material(FOGRT_BSDF_DIFFUSE, v3(1, 1, 1), v3(0, 0, 0), 0);
    fogrt_vec3 wo = vnorm(v3(-0.3f, 0.5f, 0.2f));
    test_rng r = { 7 };
    const int n = 200000;
    double c1 = 0, c2 = 0, x1 = 0, y1 = 0, x2 = 0;
    int i;
    for (i = 0; i < n; i++) {
        fogrt_bsdf_sample s;
        float u1 = rng_uniform(&r), u2 = rng_uniform(&r);
        TEST_ASSERT_TRUE(fogrt_sample_bsdf(&m, FOGRT_FRESNEL_DEFAULT, wo, 0.5f, u1, u2, &s) || u1 == 0.0f || u2 == 0.0f);
        c1 += s.wi.z; c2 += (double)s.wi.z * s.wi.z;
        x1 += s.wi.x; y1 += s.wi.y; x2 += (double)s.wi.x * s.wi.x;
    }
    c1 /= n; c2 /= n; x1 /= n; y1 /= n; x2 /= n;
    /* Standard deviations of the summands: cos: sqrt(1/2 - 4/9) = 0.236; cos^2: sqrt(1/3 -
       1/4) = 0.289; x: 0.5; x^2: sqrt(E[x^4] - 1/16) = sqrt(1/8 - 1/16) = 0.25. */
    TEST_ASSERT_DOUBLE_WITHIN(5 * 0.236 / sqrt(n), 2.0 / 3.0, c1);
    TEST_ASSERT_DOUBLE_WITHIN(5 * 0.289 / sqrt(n), 0.5, c2);
    TEST_ASSERT_DOUBLE_WITHIN(5 * 0.5 / sqrt(n), 0.0, x1);
    TEST_ASSERT_DOUBLE_WITHIN(5 * 0.5 / sqrt(n), 0.0, y1);
    TEST_ASSERT_DOUBLE_WITHIN(5 * 0.25 / sqrt(n), 0.25, x2);
}

/* ------------------------------------------------------------------------------------------
   Mirror
   ------------------------------------------------------------------------------------------ */

/* The law of reflection: wi = (-wo.x, -wo.y, wo.z), from either side, whatever the random
   numbers; weight = reflectance, pdf 1 (a delta chosen with probability 1), and eval and
   pdf are zero even for the exact mirror direction (a delta has no density). */
static void test_mirror(void)
{
    fogrt_material_desc m = material(FOGRT_BSDF_MIRROR, v3(0.9f, 0.5f, 0.1f), v3(0, 0, 0), 0);
    test_rng r = { 3 };
    int i;
    for (i = 0; i < 2000; i++) {
        fogrt_vec3 wo = random_wo(&r, (i & 1) ? -1.0f : 1.0f, 0.001f), f;
        fogrt_bsdf_sample s;
        TEST_ASSERT_TRUE(fogrt_sample_bsdf(&m, FOGRT_FRESNEL_DEFAULT, wo, rng_uniform(&r), rng_uniform(&r), rng_uniform(&r), &s));
        TEST_ASSERT_EQUAL_FLOAT(-wo.x, s.wi.x);
        TEST_ASSERT_EQUAL_FLOAT(-wo.y, s.wi.y);
        TEST_ASSERT_EQUAL_FLOAT(wo.z, s.wi.z);
        TEST_ASSERT_TRUE(s.is_delta);
        TEST_ASSERT_FALSE(s.is_transmission);
        TEST_ASSERT_EQUAL_FLOAT(1.0f, s.pdf);
        TEST_ASSERT_EQUAL_FLOAT(0.9f, s.weight.x);
        TEST_ASSERT_EQUAL_FLOAT(0.5f, s.weight.y);
        TEST_ASSERT_EQUAL_FLOAT(0.1f, s.weight.z);
        f = fogrt_bsdf_eval(&m, wo, s.wi);
        TEST_ASSERT_EQUAL_FLOAT(0.0f, f.x + f.y + f.z);
        TEST_ASSERT_EQUAL_FLOAT(0.0f, fogrt_bsdf_pdf(&m, wo, s.wi));
    }
}

/* ------------------------------------------------------------------------------------------
   Refraction only
   ------------------------------------------------------------------------------------------ */

/* Entering (wo.z > 0) and leaving below the critical angle: wi obeys Snell's law, is a unit
   vector across the surface, a delta transmission with pdf 1 and weight = transmittance. */
static void test_refraction_snell(void)
{
    static const float iors[] = { 1.5f, 1.33f, 2.4f, 0.8f };
    fogrt_material_desc m;
    test_rng r = { 5 };
    size_t k;
    int i;
    for (k = 0; k < sizeof iors / sizeof iors[0]; k++) {
        m = material(FOGRT_BSDF_REFRACTION, v3(0.3f, 0.3f, 0.3f), v3(0.9f, 0.8f, 0.7f), iors[k]);
        for (i = 0; i < 2000; i++) {
            float side = (i & 1) ? -1.0f : 1.0f;
            fogrt_vec3 wo = random_wo(&r, side, 0.01f), f;
            fogrt_bsdf_sample s;
            char msg[160];
            /* eta seen from wo's side: can this direction refract? */
            float eta = side > 0 ? iors[k] : 1.0f / iors[k];
            float sin2_o = wo.x * wo.x + wo.y * wo.y;
            snprintf(msg, sizeof msg, "ior %g wo=(%g,%g,%g)", iors[k], wo.x, wo.y, wo.z);
            if (sin2_o / (eta * eta) >= 0.999f) continue;   /* near or beyond TIR: next test */
            TEST_ASSERT_TRUE_MESSAGE(fogrt_sample_bsdf(&m, FOGRT_FRESNEL_DEFAULT, wo, rng_uniform(&r),
                                                           rng_uniform(&r), rng_uniform(&r), &s), msg);
            assert_unit(s.wi, msg);
            assert_snell(wo, s.wi, iors[k], msg);
            TEST_ASSERT_TRUE_MESSAGE(s.is_delta && s.is_transmission, msg);
            TEST_ASSERT_EQUAL_FLOAT_MESSAGE(1.0f, s.pdf, msg);
            TEST_ASSERT_EQUAL_FLOAT_MESSAGE(0.9f, s.weight.x, msg);
            TEST_ASSERT_EQUAL_FLOAT_MESSAGE(0.7f, s.weight.z, msg);
            f = fogrt_bsdf_eval(&m, wo, s.wi);
            TEST_ASSERT_EQUAL_FLOAT(0.0f, f.x + f.y + f.z);
            TEST_ASSERT_EQUAL_FLOAT(0.0f, fogrt_bsdf_pdf(&m, wo, s.wi));
        }
    }
}

/* From inside glass (ior 1.5) the critical angle is asin(1/1.5) = 41.81 degrees: 0.1 degree
   below it the ray leaves at almost 90 degrees; 0.1 degree above it it is totally reflected
   (wi = mirror of wo, still inside, not a transmission). Normal incidence goes straight on. */
static void test_refraction_total_internal_reflection(void)
{
    fogrt_material_desc m = material(FOGRT_BSDF_REFRACTION, v3(1, 1, 1), v3(1, 1, 1), 1.5f);
    double critical = asin(1.0 / 1.5);
    fogrt_bsdf_sample s;
    fogrt_vec3 wo;
    int i;
    /* Just below the critical angle, from inside (wo.z < 0). */
    wo = polar(PI_D - (critical - 0.1 * PI_D / 180), 0.7);
    TEST_ASSERT_TRUE(fogrt_sample_bsdf(&m, FOGRT_FRESNEL_DEFAULT, wo, 0.5f, 0.5f, 0.5f, &s));
    TEST_ASSERT_TRUE(s.is_transmission);
    assert_snell(wo, s.wi, 1.5f, "just below the critical angle");
    TEST_ASSERT_TRUE(s.wi.z > 0.0f && s.wi.z < 0.1f);   /* leaves close to grazing */
    /* Beyond it, at several angles up to grazing. */
    for (i = 0; i < 50; i++) {
        double theta = critical + 0.1 * PI_D / 180 + i * (PI_D / 2 - critical - 0.2 * PI_D / 180) / 49;
        wo = polar(PI_D - theta, 0.3 * i);
        TEST_ASSERT_TRUE(fogrt_sample_bsdf(&m, FOGRT_FRESNEL_DEFAULT, wo, 0.99f, 0.5f, 0.5f, &s));
        TEST_ASSERT_FALSE_MESSAGE(s.is_transmission, "refracted beyond the critical angle");
        TEST_ASSERT_TRUE(s.is_delta);
        assert_vec_within(1e-6f, v3(-wo.x, -wo.y, wo.z), s.wi, "TIR is a mirror reflection");
        TEST_ASSERT_EQUAL_FLOAT(1.0f, s.pdf);
    }
    /* Normal incidence from both sides: straight through. */
    TEST_ASSERT_TRUE(fogrt_sample_bsdf(&m, FOGRT_FRESNEL_DEFAULT, v3(0, 0, 1), 0.5f, 0.5f, 0.5f, &s));
    assert_vec_within(1e-6f, v3(0, 0, -1), s.wi, "normal incidence from outside");
    TEST_ASSERT_TRUE(fogrt_sample_bsdf(&m, FOGRT_FRESNEL_DEFAULT, v3(0, 0, -1), 0.5f, 0.5f, 0.5f, &s));
    assert_vec_within(1e-6f, v3(0, 0, 1), s.wi, "normal incidence from inside");
    /* From outside there is never TIR, even at grazing incidence. */
    wo = polar(89.9 * PI_D / 180, 1.0);
    TEST_ASSERT_TRUE(fogrt_sample_bsdf(&m, FOGRT_FRESNEL_DEFAULT, wo, 0.99f, 0.5f, 0.5f, &s));
    TEST_ASSERT_TRUE(s.is_transmission);
    assert_snell(wo, s.wi, 1.5f, "grazing from outside");
    /* Exactly on the horizon nothing is produced. */
    TEST_ASSERT_FALSE(fogrt_sample_bsdf(&m, FOGRT_FRESNEL_DEFAULT, v3(1, 0, 0), 0.5f, 0.5f, 0.5f, &s));
}

/* ------------------------------------------------------------------------------------------
   Glass
   ------------------------------------------------------------------------------------------ */

/* Glass reflects when u_lobe < F and refracts otherwise, with pdf F and 1 - F, for both
   Fresnel modes and from both sides; F is the one of fogrt_fresnel_schlick /
   fogrt_fresnel_dielectric at cos_i = wo.z. Reflection is tinted by the reflectance,
   transmission by the transmittance. */
static void test_glass_lobe_choice(void)
{
#ifdef FOGRT_MINIMAL   /* Schlick's alone: the exact Fresnel is Part II's (C) */
    static const fogrt_fresnel modes[] = { FOGRT_FRESNEL_DEFAULT, FOGRT_FRESNEL_SCHLICK };
#else
    static const fogrt_fresnel modes[] = { FOGRT_FRESNEL_DEFAULT, FOGRT_FRESNEL_SCHLICK, FOGRT_FRESNEL_EXACT };
#endif
    fogrt_material_desc m = material(FOGRT_BSDF_GLASS, v3(0.95f, 0.9f, 0.85f), v3(0.8f, 0.7f, 0.6f), 1.5f);
    test_rng r = { 9 };
    size_t k;
    int i, reflections = 0, refractions = 0, tir = 0;
    for (k = 0; k < sizeof modes / sizeof modes[0]; k++)
        for (i = 0; i < 3000; i++) {
            fogrt_vec3 wo = random_wo(&r, (i & 1) ? -1.0f : 1.0f, 0.01f);
#ifdef FOGRT_MINIMAL
            float F = fogrt_fresnel_schlick(1.5f, wo.z);
#else
            float F = modes[k] == FOGRT_FRESNEL_EXACT ? fogrt_fresnel_dielectric(1.5f, wo.z)
                                                      : fogrt_fresnel_schlick(1.5f, wo.z);
#endif
            float below = F * 0.999f, above = F + (1.0f - F) * 0.001f;
            fogrt_bsdf_sample s;
            char msg[160];
            snprintf(msg, sizeof msg, "mode %d wo=(%g,%g,%g) F=%g", (int)modes[k], wo.x, wo.y, wo.z, F);
            TEST_ASSERT_TRUE_MESSAGE(F > 0.0f && F <= 1.0f, msg);
            /* u_lobe just below F: the reflection lobe. */
            TEST_ASSERT_TRUE_MESSAGE(fogrt_sample_bsdf(&m, modes[k], wo, below, 0.5f, 0.5f, &s), msg);
            TEST_ASSERT_FALSE_MESSAGE(s.is_transmission, msg);
            TEST_ASSERT_TRUE_MESSAGE(s.is_delta, msg);
            assert_vec_within(1e-6f, v3(-wo.x, -wo.y, wo.z), s.wi, msg);
            TEST_ASSERT_FLOAT_WITHIN_MESSAGE(1e-6f, F, s.pdf, msg);
            TEST_ASSERT_EQUAL_FLOAT_MESSAGE(0.95f, s.weight.x, msg);
            TEST_ASSERT_EQUAL_FLOAT_MESSAGE(0.85f, s.weight.z, msg);
            reflections++;
            if (F >= 1.0f) { tir++; continue; }   /* TIR: there is no refraction lobe */
            /* u_lobe just above F: the refraction lobe. */
            TEST_ASSERT_TRUE_MESSAGE(fogrt_sample_bsdf(&m, modes[k], wo, above, 0.5f, 0.5f, &s), msg);
            TEST_ASSERT_TRUE_MESSAGE(s.is_transmission, msg);
            TEST_ASSERT_TRUE_MESSAGE(s.is_delta, msg);
            assert_unit(s.wi, msg);
            assert_snell(wo, s.wi, 1.5f, msg);
            TEST_ASSERT_FLOAT_WITHIN_MESSAGE(1e-6f, 1.0f - F, s.pdf, msg);
            TEST_ASSERT_EQUAL_FLOAT_MESSAGE(0.8f, s.weight.x, msg);
            TEST_ASSERT_EQUAL_FLOAT_MESSAGE(0.6f, s.weight.z, msg);
            refractions++;
        }
    /* Both lobes and TIR (from inside, beyond 41.8 degrees) really were exercised. */
    TEST_ASSERT_GREATER_THAN(1000, refractions);
    TEST_ASSERT_GREATER_THAN(500, tir);
    TEST_ASSERT_GREATER_THAN(refractions, reflections);
}

/* No glass sample gains energy, and averaged over a stratified u_lobe the glass splits the
   light into F parts reflected and 1 - F parts transmitted. Red reflectance and green
   transmittance let the two parts be told apart: the mean weight is (F, 1 - F, 0). */
static void test_glass_energy(void)
{
    fogrt_material_desc m = material(FOGRT_BSDF_GLASS, v3(1, 0, 0), v3(0, 1, 0), 1.5f);
    test_rng r = { 11 };
    int i, j;
    for (i = 0; i < 200; i++) {
        fogrt_vec3 wo = random_wo(&r, (i & 1) ? -1.0f : 1.0f, 0.01f);
#ifdef FOGRT_MINIMAL   /* Schlick's: the exact Fresnel is Part II's (C) */
        const fogrt_fresnel mode = FOGRT_FRESNEL_SCHLICK;
        float F = fogrt_fresnel_schlick(1.5f, wo.z);
#else
        const fogrt_fresnel mode = FOGRT_FRESNEL_EXACT;
        float F = fogrt_fresnel_dielectric(1.5f, wo.z);
#endif
        double red = 0, green = 0;
        const int n = 1000;
        for (j = 0; j < n; j++) {
            fogrt_bsdf_sample s;
            float u_lobe = ((float)j + 0.5f) / (float)n;   /* stratified over [0,1) */
            TEST_ASSERT_TRUE(fogrt_sample_bsdf(&m, mode, wo, u_lobe, 0.5f, 0.5f, &s));
            TEST_ASSERT_TRUE(s.weight.x <= 1.0f && s.weight.y <= 1.0f && s.weight.z <= 1.0f);
            TEST_ASSERT_TRUE(s.weight.x >= 0.0f && s.weight.y >= 0.0f && s.weight.z >= 0.0f);
            red += s.weight.x;
            green += s.weight.y;
        }
        TEST_ASSERT_DOUBLE_WITHIN(1.0 / n, F, red / n);
        TEST_ASSERT_DOUBLE_WITHIN(1.0 / n, 1.0 - F, green / n);
    }
}

/* ------------------------------------------------------------------------------------------
   Fresnel, reflect, refract
   ------------------------------------------------------------------------------------------ */

/* Textbook values: normal incidence on eta 1.5 reflects ((1.5-1)/(1.5+1))^2 = 0.04 with both
   formulas and from both sides; grazing incidence reflects everything; total internal
   reflection gives 1; eta = 1 (no interface) reflects nothing with the exact formula; at
   Brewster's angle (tan = 1.5) only the s part remains: F = 0.0739645. */
static void test_fresnel_known_values(void)
{
    double brewster = atan(1.5);
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.04f, fogrt_fresnel_schlick(1.5f, 1.0f));
#ifndef FOGRT_MINIMAL   /* here and below: the exact Fresnel is Part II's (C) */
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.04f, fogrt_fresnel_dielectric(1.5f, 1.0f));
#endif
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.04f, fogrt_fresnel_schlick(1.5f, -1.0f));
#ifndef FOGRT_MINIMAL
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.04f, fogrt_fresnel_dielectric(1.5f, -1.0f));
#endif
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 1.0f, fogrt_fresnel_schlick(1.5f, 0.0f));
#ifndef FOGRT_MINIMAL
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 1.0f, fogrt_fresnel_dielectric(1.5f, 0.0f));
#endif
    /* From inside at 60 degrees (beyond 41.8): TIR. */
    TEST_ASSERT_EQUAL_FLOAT(1.0f, fogrt_fresnel_schlick(1.5f, -0.5f));
#ifndef FOGRT_MINIMAL
    TEST_ASSERT_EQUAL_FLOAT(1.0f, fogrt_fresnel_dielectric(1.5f, -0.5f));
#endif
    /* eta 1: nothing to reflect, at any angle. */
#ifndef FOGRT_MINIMAL
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.0f, fogrt_fresnel_dielectric(1.0f, 1.0f));
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.0f, fogrt_fresnel_dielectric(1.0f, 0.3f));
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.0f, fogrt_fresnel_dielectric(1.0f, -0.7f));
#endif
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.0f, fogrt_fresnel_schlick(1.0f, 1.0f));
#ifndef FOGRT_MINIMAL
    /* Brewster's angle: r_p = 0, F = r_s^2 / 2. */
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.0739645f, fogrt_fresnel_dielectric(1.5f, (float)cos(brewster)));
#else
    (void)brewster;
#endif
    /* Water (1.33) at normal incidence: ((1.33 - 1) / (1.33 + 1))^2 = 0.0200593. */
#ifndef FOGRT_MINIMAL
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.0200593f, fogrt_fresnel_dielectric(1.33f, 1.0f));
#endif
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.0200593f, fogrt_fresnel_schlick(1.33f, 1.0f));
}

/* Schlick's approximation in double precision, with the cosine taken on the optically
   thinner side (the transmitted cosine when the ray comes from the denser side): the
   reference for fogrt_fresnel_schlick. eta < 1 means the inside is the thinner side. */
static double schlick_reference(double cos_i, double eta)
{
    double r0 = ((eta - 1) / (eta + 1)) * ((eta - 1) / (eta + 1)), c;
    if (eta < 1) { cos_i = -cos_i; eta = 1 / eta; }
    c = cos_i;
    if (cos_i < 0) {
        double sin2_t = (1.0 - cos_i * cos_i) * eta * eta;
        if (sin2_t >= 1.0) return 1.0;
        c = sqrt(1.0 - sin2_t);
    }
    return r0 + (1 - r0) * pow(1 - c, 5);
}

/* Both formulas against double-precision references over all angles and both sides (fails on
   a swapped eta, a wrong cosine or a missing TIR branch), and Schlick within its known
   worst-case distance of the exact curve: 0.0357 for eta 1.5 (at cos 0.088, computed
   offline in double), so a Schlick that used cos_i inside the glass (off by up to 0.9 near
   the critical angle) fails. */
static void test_fresnel_curves(void)
{
    static const float etas[] = { 1.5f, 1.33f, 2.4f, 1.0f / 1.5f };
    size_t k;
    int i;
    for (k = 0; k < sizeof etas / sizeof etas[0]; k++)
        for (i = -1000; i <= 1000; i++) {
            float cos_i = (float)i / 1000.0f;
            double ref = fresnel_reference(cos_i, etas[k]);
            float schlick = fogrt_fresnel_schlick(etas[k], cos_i);
            char msg[96];
            if (i == 0) continue;
            snprintf(msg, sizeof msg, "eta %g cos_i %g", etas[k], cos_i);
#ifndef FOGRT_MINIMAL   /* the exact Fresnel is Part II's (C); Schlick is checked against ref below */
            TEST_ASSERT_FLOAT_WITHIN_MESSAGE(2e-5f, (float)ref, fogrt_fresnel_dielectric(etas[k], cos_i), msg);
#endif
            TEST_ASSERT_FLOAT_WITHIN_MESSAGE(2e-5f, (float)schlick_reference(cos_i, etas[k]), schlick, msg);
            if (etas[k] == 1.5f)
                TEST_ASSERT_FLOAT_WITHIN_MESSAGE(0.036f, (float)ref, schlick, msg);
            TEST_ASSERT_TRUE_MESSAGE(schlick >= 0.0f && schlick <= 1.0f, msg);
        }
}

/* Reciprocity: light crossing an interface one way reflects as much as light crossing it
   the other way along the same path. F(outside, cos_i) = F(inside, -cos_t) for both formulas
   - Schlick only if it uses the cosine on the outside when the ray is inside (using cos_i
   there is the classic mistake). Starts at cos_i = 0.05: closer to grazing, one rounding of
   cos_t moves the matching outside angle by more than the tolerance (d cos_i / d cos_t =
   eta^2 cos_t / cos_i = 33 at 0.05, 170 at 0.01). */
static void test_fresnel_reciprocity(void)
{
    int i;
    for (i = 5; i < 100; i++) {
        float cos_i = (float)i / 100.0f, eta = 1.5f;
        float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta), cos_t = sqrtf(1.0f - sin2_t);
        char msg[64];
        snprintf(msg, sizeof msg, "cos_i %g cos_t %g", cos_i, cos_t);
#ifndef FOGRT_MINIMAL   /* the exact Fresnel is Part II's (C) */
        TEST_ASSERT_FLOAT_WITHIN_MESSAGE(2e-5f, fogrt_fresnel_dielectric(eta, cos_i), fogrt_fresnel_dielectric(eta, -cos_t), msg);
#endif
        TEST_ASSERT_FLOAT_WITHIN_MESSAGE(2e-5f, fogrt_fresnel_schlick(eta, cos_i), fogrt_fresnel_schlick(eta, -cos_t), msg);
    }
}

/* fogrt_reflect is an involution that keeps the angle to n; fogrt_refract obeys Snell's law
   in any frame and refracting back recovers the original direction; refract from inside
   beyond the critical angle reports total internal reflection. */
static void test_reflect_refract_round_trips(void)
{
    test_rng r = { 13 };
    int i, refracted = 0, tir = 0;
    for (i = 0; i < 5000; i++) {
        fogrt_vec3 n = random_dir(&r), wo = random_dir(&r), wr, wt, back;
        float eta = 1.0f + 1.5f * rng_uniform(&r), cos_o;
        char msg[160];
        cos_o = vdot(wo, n);
        if (fabsf(cos_o) < 0.02f) continue;
        snprintf(msg, sizeof msg, "n=(%g,%g,%g) wo=(%g,%g,%g) eta=%g", n.x, n.y, n.z, wo.x, wo.y, wo.z, eta);
        wr = fogrt_reflect(n, wo);
        assert_unit(wr, msg);
        TEST_ASSERT_FLOAT_WITHIN_MESSAGE(1e-5f, cos_o, vdot(wr, n), msg);
        assert_vec_within(2e-6f, wo, fogrt_reflect(n, wr), msg);
        if (fogrt_refract(n, eta, wo, &wt)) {
            /* Snell with the eta of wo's side: outside (cos_o > 0) n_o = 1, inside n_o = eta. */
            float n_o = cos_o > 0 ? 1.0f : eta, n_t = cos_o > 0 ? eta : 1.0f;
            float sin_o = sqrtf(fmaxf(0.0f, 1.0f - cos_o * cos_o)), cos_t = vdot(wt, n);
            float sin_t = sqrtf(fmaxf(0.0f, 1.0f - cos_t * cos_t));
            refracted++;
            assert_unit(wt, msg);
            TEST_ASSERT_TRUE_MESSAGE(cos_o * cos_t < 0.0f, msg);
            TEST_ASSERT_FLOAT_WITHIN_MESSAGE(1e-4f, n_o * sin_o, n_t * sin_t, msg);
            TEST_ASSERT_TRUE_MESSAGE(fogrt_refract(n, eta, wt, &back), msg);
            assert_vec_within(5e-5f, wo, back, msg);
        } else {
            /* Only from inside, beyond the critical angle. */
            tir++;
            TEST_ASSERT_TRUE_MESSAGE(cos_o < 0.0f, msg);
            TEST_ASSERT_TRUE_MESSAGE((1.0f - cos_o * cos_o) * eta * eta >= 0.999f, msg);
        }
    }
    TEST_ASSERT_GREATER_THAN(2000, refracted);
    TEST_ASSERT_GREATER_THAN(200, tir);
}

/* The BSDF samplers answer for the specular types exactly as fogrt_reflect / fogrt_refract
   with n = +z do, so the world-space helpers and the local-frame BSDFs cannot drift apart. */
static void test_bsdf_matches_helpers(void)
{
    fogrt_material_desc glass = material(FOGRT_BSDF_GLASS, v3(1, 1, 1), v3(1, 1, 1), 1.5f);
    test_rng r = { 17 };
    int i;
    for (i = 0; i < 1000; i++) {
        fogrt_vec3 wo = random_wo(&r, (i & 1) ? -1.0f : 1.0f, 0.01f), wt;
        fogrt_bsdf_sample s;
        TEST_ASSERT_TRUE(fogrt_sample_bsdf(&glass, FOGRT_FRESNEL_SCHLICK, wo, 0.0f, 0.5f, 0.5f, &s));
        assert_vec_within(1e-6f, fogrt_reflect(v3(0, 0, 1), wo), s.wi, "reflection lobe");
        if (fogrt_refract(v3(0, 0, 1), 1.5f, wo, &wt)) {
            TEST_ASSERT_TRUE(fogrt_sample_bsdf(&glass, FOGRT_FRESNEL_SCHLICK, wo, 0.99999f, 0.5f, 0.5f, &s));
            TEST_ASSERT_TRUE(s.is_transmission);
            assert_vec_within(1e-6f, wt, s.wi, "refraction lobe");
        }
    }
}

/* A zero ior means the documented default 1.5 in the BSDF functions too. */
static void test_default_ior(void)
{
    fogrt_material_desc m0 = material(FOGRT_BSDF_REFRACTION, v3(1, 1, 1), v3(1, 1, 1), 0.0f);
    fogrt_vec3 wo = vnorm(v3(0.5f, 0.2f, 0.6f));
    fogrt_bsdf_sample s;
    TEST_ASSERT_TRUE(fogrt_sample_bsdf(&m0, FOGRT_FRESNEL_DEFAULT, wo, 0.5f, 0.5f, 0.5f, &s));
    assert_snell(wo, s.wi, 1.5f, "ior 0 = 1.5");
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_diffuse_sample_eval_pdf_agree);
    RUN_TEST(test_diffuse_eval_values);
    RUN_TEST(test_diffuse_integrals);
    RUN_TEST(test_diffuse_sample_moments);
    RUN_TEST(test_mirror);
    RUN_TEST(test_refraction_snell);
    RUN_TEST(test_refraction_total_internal_reflection);
    RUN_TEST(test_glass_lobe_choice);
    RUN_TEST(test_glass_energy);
    RUN_TEST(test_fresnel_known_values);
    RUN_TEST(test_fresnel_curves);
    RUN_TEST(test_fresnel_reciprocity);
    RUN_TEST(test_reflect_refract_round_trips);
    RUN_TEST(test_bsdf_matches_helpers);
    RUN_TEST(test_default_ior);
    return UNITY_END();
}
