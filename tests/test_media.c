/* test_media.c - appendix G of fogrt.h, media beyond the paper: the two-lobe HG and Rayleigh
   phase functions, the medium desc's new fields, and emitting fog.

   Phase functions: chi-square tests of each sampler against its exact CDF (rows at the
   model's quantiles of cos theta around d = -wo) and against its own pdf (cubature on a
   world grid), a Kolmogorov-Smirnov test of Rayleigh's inverse CDF, each with negative
   controls that must be rejected (tests/stats.h; docs/testing.md explains the output); then
   the deterministic companions: normalisation and mean cosine by quadrature, the pdf a
   sampler returns against the pdf function, Rayleigh's inverse CDF swept over u, HG2's
   degenerate weights against HG bit for bit, and the validation of every new desc field.
   In the renderer: next-event estimation and MIS on and off, and the paper's settings
   against the defaults (equiangular and glow sampling in their plain forms), agree within
   their standard errors for both phase functions. Fixed seeds throughout.              */
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#include "unity.h"
#include "test_util.h"
#include "stats.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void setUp(void) {}
void tearDown(void) {}

#ifdef FOGRT_NO_MEDIA
#define MEDIA_ONLY() TEST_IGNORE_MESSAGE("needs appendix G of fogrt.h: built with FOGRT_NO_MEDIA (or FOGRT_MINIMAL)")
#endif

/* ==========================================================================================
   The models, in double
   ========================================================================================== */
#ifndef FOGRT_NO_MEDIA
enum { M_HG2, M_RAYLEIGH, M_ISO };
typedef struct phase_model { int kind; double g1, g2, w; } phase_model;

/* HG's CDF of mu, (1 - g)(1 + mu) / (s (1 + g + s)) with s^2 = 1 + g^2 - 2 g mu written as
   a sum of non-negative terms: no division by g, no cancellation. */
static double hg_cdf(double g, double mu)
{
    double base = g >= 0.0 ? (1.0 - g) * (1.0 - g) + 2.0 * g * (1.0 - mu) : (1.0 + g) * (1.0 + g) - 2.0 * g * (1.0 + mu);
    double s = sqrt(base);
    return (1.0 - g) * (1.0 + mu) / (s * (1.0 + g + s));
}
static double model_cdf(const phase_model *m, double mu)
{
    if (mu <= -1.0) return 0.0;
    if (mu >= 1.0) return 1.0;
    if (m->kind == M_RAYLEIGH) return (mu * mu * mu + 3.0 * mu + 4.0) / 8.0;
    if (m->kind == M_ISO) return 0.5 * (1.0 + mu);
    return m->w * hg_cdf(m->g1, mu) + (1.0 - m->w) * hg_cdf(m->g2, mu);
}

static fogrt_medium_desc desc_of(const phase_model *m)
{
    fogrt_medium_desc d;
    memset(&d, 0, sizeof d);
    d.sigma_t = 1.0f; d.albedo = v3(0.8f, 0.8f, 0.8f);
    d.phase = m->kind == M_RAYLEIGH ? FOGRT_PHASE_RAYLEIGH : FOGRT_PHASE_HG2;
    d.g = (float)m->g1; d.g2 = (float)m->g2; d.w = (float)m->w;
    return d;
}

/* ==========================================================================================
   Drawing directions into a sphere grid
   ========================================================================================== */
typedef struct dir_source {
    const fogrt_medium_desc *d;
    fogrt_vec3 wo;
    bool unscaled_lobe;        /* the negative control's sampler: the lobe's u not rescaled */
} dir_source;

/* A two-lobe sampler with the classic mistake: the lobe is chosen by u1 < w, but the lobe
   then samples with u1 itself, so lobe 1 only sees u in [0, w) and lobe 2 only [w, 1). */
static fogrt_vec3 sample_hg2_unscaled(const fogrt_medium_desc *d, fogrt_vec3 wo, float u1, float u2)
{
    return fogrt_sample_hg(u1 < d->w ? d->g : d->g2, wo, u1, u2, NULL);
}

static long draw(const stats_sphere_grid *grid, const dir_source *src, long n, uint64_t seed, double *observed)
{
    fogrt_rng rng;
    long invalid = 0, i;
    fogrt_rng_seed(&rng, seed, 3);
    memset(observed, 0, sizeof(double) * (size_t)(grid->n_cos * grid->n_phi));
    for (i = 0; i < n; ++i) {
        float u1 = fogrt_rng_float(&rng), u2 = fogrt_rng_float(&rng), pdf = 0.0f;
        fogrt_vec3 w = src->unscaled_lobe ? sample_hg2_unscaled(src->d, src->wo, u1, u2)
                                          : fogrt_sample_phase(src->d, src->wo, u1, u2, &pdf);
        int cell = stats_grid_cell(grid, w.x, w.y, w.z);
        if (cell < 0 || (!src->unscaled_lobe && !(pdf > 0.0f && isfinite(pdf)))) invalid++;
        else observed[cell] += 1.0;
    }
    return invalid;
}

/* Rows at the model's quantiles of mu (rows narrower than 4e-6 merged: fogrt's mu is a
   float, so a row must span many float steps). */
static void quantile_rows(stats_sphere_grid *grid, const phase_model *m, int rows)
{
    int n = 0, k, it;
    grid->cos_edge[n++] = -1.0;
    for (k = 1; k < rows; ++k) {
        double target = (double)k / rows, lo = -1.0, hi = 1.0, edge;
        for (it = 0; it < 200 && hi - lo > 1e-15; ++it) {
            double mid = 0.5 * (lo + hi);
            if (model_cdf(m, mid) < target) lo = mid; else hi = mid;
        }
        edge = 0.5 * (lo + hi);
        if (edge - grid->cos_edge[n - 1] >= 4e-6 && 1.0 - edge >= 4e-6) grid->cos_edge[n++] = edge;
    }
    grid->cos_edge[n] = 1.0;
    grid->n_cos = n;
}
static double cell_prob(double c0, double c1, double p0, double p1, void *user)
{
    const phase_model *m = (const phase_model *)user;
    return (model_cdf(m, c1) - model_cdf(m, c0)) * (p1 - p0) / (2.0 * STATS_PI);
}
static stats_verdict grid_verdict(const char *name, const char *what, const char *param, const stats_sphere_grid *g,
                                  const double *observed, const double *expected, long invalid, bool negative)
{
    return stats_chi2_verdict(name, what, param, g->n_cos, g->n_phi, g->cos_edge, "cos theta", NULL, "phi",
                              observed, expected, invalid, negative);
}

/* One sampler against an exact model: grid rows at the model's quantiles, z along d = -wo.
   model may differ from the sampled desc (a negative control). */
static stats_verdict exact_cdf_case(const char *name, const dir_source *src, const phase_model *model, uint64_t seed,
                                    const char *param, bool negative)
{
    static stats_sphere_grid grid;
    static double observed[50 * 10], expected[50 * 10];
    const long n = 100000;
    long invalid;
    stats_grid_init(&grid, 50, 10);
    quantile_rows(&grid, model, 50);
    stats_grid_set_axis(&grid, -(double)src->wo.x, -(double)src->wo.y, -(double)src->wo.z);
    invalid = draw(&grid, src, n, seed, observed);
    stats_grid_expected_from_cells(&grid, cell_prob, (void *)model, (double)n, expected);
    return grid_verdict(name, "fogrt_sample_phase vs the exact CDF", param, &grid, observed, expected, invalid, negative);
}
#endif

/* ==========================================================================================
   Chi-square: each sampler against its exact CDF
   ========================================================================================== */
#ifndef FOGRT_NO_MEDIA
static const phase_model HG2_CASES[] = {
    {M_HG2, 0.8, -0.4, 0.7}, {M_HG2, 0.95, -0.7, 0.5}, {M_HG2, -0.3, 0.6, 0.25}, {M_HG2, 0.5, 0.5, 0.4},
    {M_HG2, 0.9, -0.9, 0.0}, {M_HG2, 0.6, -0.3, 1.0}, {M_HG2, 0.99, -0.99, 0.5},
};
#define HG2_COUNT ((int)(sizeof HG2_CASES / sizeof HG2_CASES[0]))
static const float WO[3][3] = {{-0.48f, 0.6f, 0.64f}, {0, 0, 1}, {0, 0, -1}};
#endif

/* fogrt_sample_phase with two lobes at 7 (g1, g2, w), including one lobe alone (w = 0 and
   1), equal lobes and peaked ones, from a generic wo and from +z, follows w F(g1) + (1 - w)
   F(g2) around d. Negative controls: the same samples against the lobes weighted 1 - w
   (lobe picked the wrong way round) and against g2 of the other sign; and the sampler that
   forgets to rescale u1 for the chosen lobe, against the right model. */
static void test_hg2_chi2_exact_cdf(void)
{
#ifdef FOGRT_NO_MEDIA
    MEDIA_ONLY();
#else
    stats_tally t = {0, 0, ""};
    int c, k;
    char name[64], param[160];
    for (c = 0; c < HG2_COUNT; ++c) {
        for (k = 0; k < 2; ++k) {
            const phase_model *m = &HG2_CASES[c];
            fogrt_medium_desc d = desc_of(m);
            dir_source src;
            src.d = &d; src.wo = v3(WO[k][0], WO[k][1], WO[k][2]); src.unscaled_lobe = false;
            snprintf(name, sizeof name, "hg2_%g_%g_%g_wo%d", m->g1, m->g2, m->w, k);
            snprintf(param, sizeof param, "two lobes g1=%g g2=%g w=%g, wo=(%g,%g,%g)", m->g1, m->g2, m->w,
                     (double)src.wo.x, (double)src.wo.y, (double)src.wo.z);
            REPORT(t, exact_cdf_case(name, &src, m, 500 + 10 * (uint64_t)c + (uint64_t)k, param, false));
            if (c == 0 && k == 0) {
                phase_model swapped = *m, flipped = *m;
                swapped.w = 1.0 - m->w;
                flipped.g2 = -m->g2;
                snprintf(param, sizeof param, "sampled g1=%g g2=%g w=%g, model with w=%g (lobes swapped)", m->g1, m->g2, m->w, swapped.w);
                REPORT(t, exact_cdf_case(name, &src, &swapped, 500, param, true));
                snprintf(param, sizeof param, "sampled g2=%g, model with g2=%g (sign flipped)", m->g2, flipped.g2);
                REPORT(t, exact_cdf_case(name, &src, &flipped, 500, param, true));
                src.unscaled_lobe = true;
                snprintf(param, sizeof param, "lobe chosen by u1 < w, then u1 not rescaled, against the right model");
                REPORT(t, exact_cdf_case(name, &src, m, 500, param, true));
            }
        }
    }
    TALLY_ASSERT(t);
#endif
}

/* fogrt_sample_phase with Rayleigh from +z, -z and a generic wo follows (mu^3 + 3 mu + 4)/8.
   Negative control: the same samples against isotropic scattering. */
static void test_rayleigh_chi2_exact_cdf(void)
{
#ifdef FOGRT_NO_MEDIA
    MEDIA_ONLY();
#else
    stats_tally t = {0, 0, ""};
    phase_model m = {M_RAYLEIGH, 0, 0, 0}, iso = {M_ISO, 0, 0, 0};
    fogrt_medium_desc d = desc_of(&m);
    char name[64], param[160];
    int k;
    for (k = 0; k < 3; ++k) {
        dir_source src;
        src.d = &d; src.wo = v3(WO[k][0], WO[k][1], WO[k][2]); src.unscaled_lobe = false;
        snprintf(name, sizeof name, "rayleigh_wo%d", k);
        snprintf(param, sizeof param, "Rayleigh, wo=(%g,%g,%g)", (double)src.wo.x, (double)src.wo.y, (double)src.wo.z);
        REPORT(t, exact_cdf_case(name, &src, &m, 700 + (uint64_t)k, param, false));
        if (k == 0) REPORT(t, exact_cdf_case(name, &src, &iso, 700, "sampled Rayleigh, model isotropic", true));
    }
    TALLY_ASSERT(t);
#endif
}

/* ==========================================================================================
   Chi-square: each sampler against its own pdf (what MIS and next-event estimation use)
   ========================================================================================== */
#ifndef FOGRT_NO_MEDIA
typedef struct pdf_args { const fogrt_medium_desc *d; fogrt_vec3 wo; int wrong; } pdf_args;
static double pdf_callback(const double w[3], void *user)
{
    const pdf_args *a = (const pdf_args *)user;
    fogrt_vec3 wi = v3((float)w[0], (float)w[1], (float)w[2]);
    if (a->wrong == 1) return fogrt_phase_pdf(a->d, v3(-a->wo.x, -a->wo.y, -a->wo.z), wi);   /* wo's sign */
    if (a->wrong == 2) return 1.0 / (4.0 * STATS_PI);                                          /* isotropic */
    return fogrt_phase_pdf(a->d, a->wo, wi);
}
#endif
/* fogrt_sample_phase against cubature of fogrt_phase_pdf on a plain 40 x 80 world grid, for
   two lobes (0.8, -0.4, 0.7) and Rayleigh; the pdf must integrate to 1. Negative controls:
   the two-lobe pdf evaluated at -wo, and Rayleigh's replaced by the isotropic pdf. */
static void test_phase_chi2_against_pdf(void)
{
#ifdef FOGRT_NO_MEDIA
    MEDIA_ONLY();
#else
    static stats_sphere_grid grid;
    static double observed[40 * 80], expected[40 * 80];
    stats_tally t = {0, 0, ""};
    phase_model models[2] = {{M_HG2, 0.8, -0.4, 0.7}, {M_RAYLEIGH, 0, 0, 0}};
    int k;
    for (k = 0; k < 2; ++k) {
        fogrt_medium_desc d = desc_of(&models[k]);
        dir_source src;
        pdf_args pa;
        const long n = 200000;
        long invalid;
        double total;
        char name[64];
        src.d = &d; src.wo = v3(WO[0][0], WO[0][1], WO[0][2]); src.unscaled_lobe = false;
        stats_grid_init(&grid, 40, 80);
        invalid = draw(&grid, &src, n, 900 + (uint64_t)k, observed);
        pa.d = &d; pa.wo = src.wo; pa.wrong = 0;
        total = stats_grid_expected_from_pdf(&grid, pdf_callback, &pa, (double)n, expected);
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-4, 1.0, total, "fogrt_phase_pdf does not integrate to 1 over the sphere");
        snprintf(name, sizeof name, "phase_pdf_%s", k ? "rayleigh" : "hg2");
        REPORT(t, grid_verdict(name, "fogrt_sample_phase vs fogrt_phase_pdf", k ? "Rayleigh, world grid" : "two lobes 0.8, -0.4, 0.7, world grid",
                               &grid, observed, expected, invalid, false));
        pa.wrong = k ? 2 : 1;
        stats_grid_expected_from_pdf(&grid, pdf_callback, &pa, (double)n, expected);
        REPORT(t, grid_verdict(name, "fogrt_sample_phase vs fogrt_phase_pdf", k ? "pdf replaced by the isotropic one" : "pdf evaluated at -wo",
                               &grid, observed, expected, invalid, true));
    }
    TALLY_ASSERT(t);
#endif
}

/* ==========================================================================================
   Kolmogorov-Smirnov: Rayleigh's mu
   ========================================================================================== */
#ifndef FOGRT_NO_MEDIA
static double rayleigh_cdf_cb(double mu, void *user) { (void)user; return model_cdf(&(phase_model){M_RAYLEIGH, 0, 0, 0}, mu); }
static double iso_cdf_cb(double mu, void *user) { (void)user; return mu <= -1.0 ? 0.0 : mu >= 1.0 ? 1.0 : 0.5 * (1.0 + mu); }
#endif
/* fogrt_sample_rayleigh_mu on 2e5 uniforms against F(mu) = (mu^3 + 3 mu + 4) / 8; negative
   control: against the uniform mu of isotropic scattering. */
static void test_rayleigh_mu_ks(void)
{
#ifdef FOGRT_NO_MEDIA
    MEDIA_ONLY();
#else
    enum { N = 200000 };
    static double x[N];
    stats_tally t = {0, 0, ""};
    stats_ks_result r;
    fogrt_rng rng;
    long invalid = 0;
    int i;
    fogrt_rng_seed(&rng, 77, 1);
    for (i = 0; i < N; ++i) {
        float mu = fogrt_sample_rayleigh_mu(fogrt_rng_float(&rng));
        if (!(mu >= -1.0f && mu <= 1.0f)) invalid++;
        x[i] = (double)mu;
    }
    r = stats_ks(x, N, rayleigh_cdf_cb, NULL);
    REPORT(t, stats_ks_verdict("rayleigh_mu", "fogrt_sample_rayleigh_mu", "2e5 uniforms", &r, x, rayleigh_cdf_cb, NULL, invalid, false));
    r = stats_ks(x, N, iso_cdf_cb, NULL);
    REPORT(t, stats_ks_verdict("rayleigh_mu", "fogrt_sample_rayleigh_mu", "against uniform mu", &r, x, iso_cdf_cb, NULL, invalid, true));
    TALLY_ASSERT(t);
#endif
}

/* ==========================================================================================
   Deterministic companions
   ========================================================================================== */
/* Rayleigh's inverse CDF over 12289 uniforms (a grid, the 2048 smallest and largest floats
   of [0, 1]): mu is monotone, F(mu(u)) is u to within the float rounding of mu (F' <= 3/4,
   so 6e-8 in mu is 4.5e-8 in u; 1.5e-7 allowed), mu(1 - u) = -mu(u) where 1 - u is exact,
   and the ends are exact: mu(0) = -1, mu(1/2) = 0, mu(1) = 1. The first and last uniforms
   give finite unit directions with finite positive pdfs. */
static void test_rayleigh_inverse_cdf(void)
{
#ifdef FOGRT_NO_MEDIA
    MEDIA_ONLY();
#else
    float prev = -2.0f, pdf;
    double worst = 0.0;
    int i, pass;
    char msg[160];
    TEST_ASSERT_EQUAL_FLOAT(-1.0f, fogrt_sample_rayleigh_mu(0.0f));
    TEST_ASSERT_EQUAL_FLOAT(0.0f, fogrt_sample_rayleigh_mu(0.5f));
    TEST_ASSERT_EQUAL_FLOAT(1.0f, fogrt_sample_rayleigh_mu(1.0f));
    for (pass = 0; pass < 3; ++pass) {
        int n = pass == 1 ? 8192 : 2048;
        for (i = 0; i <= n; ++i) {
            float u = pass == 0 ? (float)i * 0x1p-35f : pass == 1 ? (float)i / (float)n : 1.0f - (float)(n - i) * 0x1p-24f;
            float mu = fogrt_sample_rayleigh_mu(u);
            double err = fabs(model_cdf(&(phase_model){M_RAYLEIGH, 0, 0, 0}, (double)mu) - (double)u);
            snprintf(msg, sizeof msg, "u = %.9g: mu = %.9g, F(mu) - u = %.3g", (double)u, (double)mu, err);
            TEST_ASSERT_TRUE_MESSAGE(mu >= prev && mu >= -1.0f && mu <= 1.0f, msg);
            TEST_ASSERT_TRUE_MESSAGE(err <= 1.5e-7, msg);
            if (pass == 1) TEST_ASSERT_EQUAL_FLOAT_MESSAGE(-mu, fogrt_sample_rayleigh_mu(1.0f - u), msg);
            worst = fmax(worst, err);
            prev = mu;
        }
        prev = -2.0f;
    }
    for (i = 0; i < 2; ++i) {
        fogrt_vec3 w = fogrt_sample_rayleigh(v3(0.3f, -0.5f, 0.812f), i ? 0.99999994f : 0.0f, i ? 0.99999994f : 0.0f, &pdf);
        TEST_ASSERT_FLOAT_WITHIN(1e-5f, 1.0f, sqrtf(w.x * w.x + w.y * w.y + w.z * w.z));
        TEST_ASSERT_TRUE(isfinite(pdf) && pdf > 0.0f);
    }
    snprintf(msg, sizeof msg, "largest |F(mu(u)) - u| over the sweep: %.3g", worst);
    TEST_MESSAGE(msg);
#endif
}

#ifndef FOGRT_NO_MEDIA
typedef struct moment_args { const fogrt_medium_desc *d; int power; } moment_args;
static double moment_integrand(double mu, void *user)
{
    const moment_args *a = (const moment_args *)user;
    return 2.0 * STATS_PI * (double)fogrt_phase(a->d, (float)mu) * (a->power ? mu : 1.0);
}
#endif
/* Each phase function integrates to 1 over the sphere and has the mean cosine it should:
   w g1 + (1 - w) g2 for two lobes, 0 for Rayleigh (quadrature over mu of fogrt_phase). */
static void test_phase_normalised_and_mean_cosine(void)
{
#ifdef FOGRT_NO_MEDIA
    MEDIA_ONLY();
#else
    phase_model ms[4] = {{M_HG2, 0.8, -0.4, 0.7}, {M_HG2, 0.95, -0.7, 0.5}, {M_HG2, -0.3, 0.6, 0.25}, {M_RAYLEIGH, 0, 0, 0}};
    int k;
    char msg[128];
    for (k = 0; k < 4; ++k) {
        fogrt_medium_desc d = desc_of(&ms[k]);
        moment_args a;
        double norm, mean, want = ms[k].kind == M_RAYLEIGH ? 0.0 : ms[k].w * ms[k].g1 + (1.0 - ms[k].w) * ms[k].g2;
        a.d = &d; a.power = 0;
        norm = stats_integrate_1d(moment_integrand, &a, -1.0, 1.0, 1e-9, 40);
        a.power = 1;
        mean = stats_integrate_1d(moment_integrand, &a, -1.0, 1.0, 1e-9, 40);
        snprintf(msg, sizeof msg, "case %d: integral %.7f, mean cosine %.6f (want %.6f)", k, norm, mean, want);
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(2e-5, 1.0, norm, msg);
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(2e-5, want, mean, msg);
    }
#endif
}

/* The pdf fogrt_sample_phase returns equals fogrt_phase_pdf at the direction it returns
   (relative 2e-5, the chords' rounding), and the directions are unit: MIS needs both. */
static void test_sample_pdf_matches_eval(void)
{
#ifdef FOGRT_NO_MEDIA
    MEDIA_ONLY();
#else
    phase_model ms[3] = {{M_HG2, 0.8, -0.4, 0.7}, {M_HG2, 0.95, -0.7, 0.5}, {M_RAYLEIGH, 0, 0, 0}};
    fogrt_rng rng;
    int k, i;
    char msg[160];
    fogrt_rng_seed(&rng, 11, 0);
    for (k = 0; k < 3; ++k) {
        fogrt_medium_desc d = desc_of(&ms[k]);
        for (i = 0; i < 20000; ++i) {
            fogrt_vec3 wo = fogrt_sample_uniform_sphere(fogrt_rng_float(&rng), fogrt_rng_float(&rng)), wi;
            float pdf = 0.0f, p;
            wi = fogrt_sample_phase(&d, wo, fogrt_rng_float(&rng), fogrt_rng_float(&rng), &pdf);
            p = fogrt_phase_pdf(&d, wo, wi);
            snprintf(msg, sizeof msg, "case %d sample %d: sampler pdf %.9g, fogrt_phase_pdf %.9g", k, i, (double)pdf, (double)p);
            TEST_ASSERT_FLOAT_WITHIN_MESSAGE(1e-5f, 1.0f, sqrtf(wi.x * wi.x + wi.y * wi.y + wi.z * wi.z), msg);
            TEST_ASSERT_TRUE_MESSAGE(fabsf(pdf - p) <= 2e-5f * p, msg);
        }
    }
#endif
}

/* HG2 with w = 1 is HG(g1), with w = 0 HG(g2), sample for sample (the same direction and
   pdf, bit for bit); a desc with phase FOGRT_PHASE_HG is HG(g) whatever g2 and w hold. */
static void test_hg2_degenerate_is_hg(void)
{
#ifdef FOGRT_NO_MEDIA
    MEDIA_ONLY();
#else
    fogrt_rng rng;
    fogrt_medium_desc hg;
    int i;
    memset(&hg, 0, sizeof hg);
    hg.phase = FOGRT_PHASE_HG; hg.g = 0.7f; hg.g2 = -0.5f; hg.w = 0.3f;
    fogrt_rng_seed(&rng, 12, 0);
    for (i = 0; i < 5000; ++i) {
        fogrt_vec3 wo = fogrt_sample_uniform_sphere(fogrt_rng_float(&rng), fogrt_rng_float(&rng));
        float u1 = fogrt_rng_float(&rng), u2 = fogrt_rng_float(&rng), p1, p2, p3, p4;
        fogrt_vec3 a = fogrt_sample_hg2(0.7f, -0.5f, 1.0f, wo, u1, u2, &p1), b = fogrt_sample_hg(0.7f, wo, u1, u2, &p2);
        fogrt_vec3 c = fogrt_sample_hg2(0.2f, -0.5f, 0.0f, wo, u1, u2, &p3), e = fogrt_sample_hg(-0.5f, wo, u1, u2, &p4);
        fogrt_vec3 f;
        TEST_ASSERT_TRUE(memcmp(&a, &b, sizeof a) == 0 && memcmp(&c, &e, sizeof c) == 0 && p1 == p2 && p3 == p4);
        f = fogrt_sample_phase(&hg, wo, u1, u2, &p1);
        TEST_ASSERT_TRUE(memcmp(&f, &b, sizeof f) == 0 && p1 == p2);
        TEST_ASSERT_EQUAL_FLOAT(fogrt_hg_phase(0.7f, wo.z), fogrt_phase(&hg, wo.z));
    }
#endif
}

/* ==========================================================================================
   The medium desc's new fields
   ========================================================================================== */
typedef struct log_record { int errors, warnings; char last[512]; } log_record;
static void record_log(fogrt_log_level level, const char *message, void *user)
{
    log_record *r = (log_record *)user;
    if (level == FOGRT_LOG_ERROR) r->errors++;
    if (level == FOGRT_LOG_WARNING) r->warnings++;
    snprintf(r->last, sizeof r->last, "%s", message);
}
static fogrt_scene *logged_scene(log_record *log)
{
    fogrt_scene_desc sd;
    fogrt_scene *s = NULL;
    memset(&sd, 0, sizeof sd);
    memset(log, 0, sizeof *log);
    sd.logger.func = record_log; sd.logger.user_data = log;
    CHECK_OK(fogrt_scene_create(&sd, &s));
    return s;
}
static fogrt_medium_desc fog_desc(void)
{
    fogrt_medium_desc m;
    memset(&m, 0, sizeof m);
    m.sigma_t = 0.5f; m.albedo = v3(0.8f, 0.8f, 0.8f); m.g = 0.3f;
    return m;
}

/* Every bad value of a new field is refused with INVALID_MEDIUM, one logged line naming the
   field, and leaves the scene's medium as it was; |g2| above FOGRT_HG_G_MAX is clamped with
   a warning, as g is. Under FOGRT_NO_MEDIA any use of the fields is refused (UNSUPPORTED,
   naming the macro) and zeroed fields still work. */
static void test_medium_desc_validation(void)
{
    log_record log;
    fogrt_scene *s = logged_scene(&log);
    fogrt_medium_desc m = fog_desc(), got;
#ifndef FOGRT_NO_MEDIA
    static const struct { const char *field; int what; float value; } bad[] = {
        {"medium.phase", 0, 3.0f}, {"medium.phase", 0, -1.0f}, {"medium.g2", 1, 1.5f}, {"medium.g2", 1, -1.01f},
        {"medium.g2", 1, NAN}, {"medium.w", 2, -0.1f}, {"medium.w", 2, 1.0001f}, {"medium.w", 2, NAN},
        {"medium.emission", 3, -1.0f}, {"medium.emission", 3, INFINITY}, {"medium.emission", 3, NAN},
    };
    size_t i;
    CHECK_OK(fogrt_scene_set_medium(s, &m));
    for (i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        fogrt_medium_desc b = fog_desc();
        char msg[600];
        b.phase = FOGRT_PHASE_HG2; b.g2 = -0.2f; b.w = 0.5f;
        if (bad[i].what == 0) b.phase = (fogrt_phase_type)(int)bad[i].value;
        if (bad[i].what == 1) b.g2 = bad[i].value;
        if (bad[i].what == 2) b.w = bad[i].value;
        if (bad[i].what == 3) b.emission = v3(1.0f, bad[i].value, 1.0f);
        log.errors = 0;
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_INVALID_MEDIUM, fogrt_scene_set_medium(s, &b));
        snprintf(msg, sizeof msg, "case %d: the message '%s' should name %s", (int)i, log.last, bad[i].field);
        TEST_ASSERT_EQUAL_INT_MESSAGE(1, log.errors, msg);
        TEST_ASSERT_NOT_NULL_MESSAGE(strstr(log.last, bad[i].field), msg);
        fogrt_scene_get_medium(s, &got);
        TEST_ASSERT_TRUE_MESSAGE(memcmp(&got, &m, sizeof m) == 0, "a refused desc changed the medium");
    }
    m.phase = FOGRT_PHASE_HG2; m.g2 = -1.0f; m.w = 0.0f; m.emission = v3(0, 2, 0);
    CHECK_OK(fogrt_scene_set_medium(s, &m));
    fogrt_scene_get_medium(s, &got);
    TEST_ASSERT_EQUAL_FLOAT(-FOGRT_HG_G_MAX, got.g2);
    TEST_ASSERT_NOT_NULL(strstr(log.last, "medium.g2"));
    TEST_ASSERT_EQUAL_INT(1, log.warnings);
#else
    CHECK_OK(fogrt_scene_set_medium(s, &m));
    m.phase = FOGRT_PHASE_RAYLEIGH;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_UNSUPPORTED, fogrt_scene_set_medium(s, &m));
    TEST_ASSERT_NOT_NULL(strstr(log.last, "FOGRT_NO_MEDIA"));
    m = fog_desc(); m.emission = v3(1, 1, 1);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_UNSUPPORTED, fogrt_scene_set_medium(s, &m));
    fogrt_scene_get_medium(s, &got);
    TEST_ASSERT_EQUAL_INT(FOGRT_PHASE_HG, got.phase);
    (void)log;
#endif
    fogrt_scene_destroy(s);
}

/* ==========================================================================================
   In the renderer
   ========================================================================================== */
#ifndef FOGRT_NO_MEDIA
/* The image's mean luminance and its standard error from the render's own per-pixel
   variances (pixels independent). */
static void render_mean(const fogrt_scene *s, const fogrt_render_desc *rd, int w, int h, int spp, double *mean, double *se)
{
    fogrt_image img;
    double m = 0.0, var = 0.0;
    int p;
    CHECK_OK(fogrt_image_alloc(&img, w, h, NULL));
    CHECK_OK(fogrt_render(s, rd, &img, spp, NULL));
    TEST_ASSERT_EQUAL_UINT64(0, img.rejected);
    for (p = 0; p < w * h; ++p) {
        m += pixel_luminance(&img, p) / (w * h);
        var += pixel_luminance_variance(&img, p) / ((double)w * h * w * h);
    }
    *mean = m; *se = sqrt(var);
    fogrt_image_free(&img);
}
/* A closed box in fog of the given phase, lit by its ceiling lamp (lamp > 0) or by a spot
   light (lamp = 0), the camera inside. The fog fills the box below y = 1.5 only, so that no
   fog point comes near a lamp: light sampling without MIS, and the paper's light sampling
   of a spot light, then have finite variance (next to a lamp their 1/r^2 has none, and
   their standard errors would mean nothing). */
static fogrt_scene *phase_box(fogrt_phase_type phase, float lamp, fogrt_vec3 emission)
{
    fogrt_scene *s = NULL;
    fogrt_medium_desc m;
    CHECK_OK(fogrt_scene_create(NULL, &s));
    add_closed_box(s, 0.4f, lamp);
    if (!(lamp > 0.0f)) {
        fogrt_light_desc l;
        memset(&l, 0, sizeof l);
        l.type = FOGRT_LIGHT_SPOT; l.position = v3(-0.6f, 1.8f, -0.3f); l.direction = v3(0.7f, -1.6f, 0.2f);
        l.intensity = v3(3, 3, 3); l.cutoff_deg = 25; l.beam_deg = 18;
        CHECK_OK(fogrt_scene_add_light(s, &l));
    }
    memset(&m, 0, sizeof m);
    m.sigma_t = 0.8f; m.albedo = v3(0.85f, 0.85f, 0.85f); m.phase = phase;
    m.g = 0.8f; m.g2 = -0.4f; m.w = 0.7f; m.emission = emission;
    m.bounded = true; m.bounds_min = v3(-1, 0, -1); m.bounds_max = v3(1, 1.5f, 1);
    CHECK_OK(fogrt_scene_set_medium(s, &m));
    set_camera(s, v3(0, 1.0f, 0.95f), v3(0, 0.9f, -1), 60.0f);
    CHECK_OK(fogrt_scene_build(s, NULL));
    return s;
}
typedef struct estimator { const char *name; bool paper, nee, mis; int spp; } estimator;
/* The estimators' image means agree with the first one's within 4 combined standard errors. */
static void estimators_agree(const char *what, const fogrt_scene *s, const estimator *e, int n)
{
    double m0 = 0.0, s0 = 0.0;
    int k;
    for (k = 0; k < n; ++k) {
        fogrt_render_desc rd = e[k].paper ? fogrt_render_paper_defaults() : fogrt_render_defaults();
        double m, se;
        char msg[256];
        rd.seed = 100 + (uint64_t)k; rd.nee = e[k].nee; rd.mis = e[k].mis; rd.threads = 0;
        render_mean(s, &rd, 16, 12, e[k].spp, &m, &se);
        if (k == 0) { m0 = m; s0 = se; }
        snprintf(msg, sizeof msg, "%s, %s: mean %.5f +- %.5f, against %s %.5f +- %.5f (%.2f combined s.e.)", what, e[k].name,
                 m, se, e[0].name, m0, s0, fabs(m - m0) / sqrt(se * se + s0 * s0 + 1e-300));
        TEST_MESSAGE(msg);
        if (k > 0) TEST_ASSERT_TRUE_MESSAGE(fabs(m - m0) <= 4.0 * sqrt(se * se + s0 * s0), msg);
        TEST_ASSERT_TRUE_MESSAGE(m > 0.0 && se > 0.0 && se < 0.05 * m, msg);
    }
}
#endif

/* Two lobes and Rayleigh in a lamp-lit box: next-event estimation with MIS, without MIS
   and none at all give the same image mean: the phase function's sampler and its pdf in the
   MIS weights agree. In a spot-lit box the defaults (equiangular and glow sampling, here in
   their plain forms: B's table is built for g = 0) agree with the paper's light sampling
   alone. */
static void test_phase_estimators_agree(void)
{
#ifdef FOGRT_NO_MEDIA
    MEDIA_ONLY();
#else
    static const estimator lamp[3] = {
        {"NEE+MIS", false, true, true, 64}, {"NEE, no MIS", false, true, false, 64}, {"no NEE", false, false, true, 256}};
    static const estimator spot[2] = {{"defaults (equiangular, glow)", false, true, true, 48}, {"paper (light sampling)", true, true, true, 96}};
    fogrt_phase_type phases[2] = {FOGRT_PHASE_HG2, FOGRT_PHASE_RAYLEIGH};
    int k;
    for (k = 0; k < 2; ++k) {
        fogrt_scene *s = phase_box(phases[k], 6.0f, v3(0, 0, 0));
        estimators_agree(k ? "Rayleigh, lamp" : "two lobes, lamp", s, lamp, 3);
        fogrt_scene_destroy(s);
        s = phase_box(phases[k], 0.0f, v3(0, 0, 0));
        {   /* B's table is isotropic fog's (g = 0) for another phase than HG */
            fogrt__hg_table *iso = (fogrt__hg_table *)malloc(sizeof *iso);
            TEST_ASSERT_NOT_NULL(iso);
            fogrt__hg_table_build(iso, 0.0f);
            TEST_ASSERT_NOT_NULL(s->x->hg);
            TEST_ASSERT_TRUE_MESSAGE(memcmp(iso->k, s->x->hg->k, sizeof iso->k) == 0, "the glow's table is not isotropic fog's");
            free(iso);
        }
        estimators_agree(k ? "Rayleigh, spot" : "two lobes, spot", s, spot, 2);
        fogrt_scene_destroy(s);
    }
#endif
}

/* ==========================================================================================
   Emitting fog
   ========================================================================================== */
#ifndef FOGRT_NO_MEDIA
/* Fog that fills all space (or, bounded, the box lo..hi), a black sphere far away (a scene
   needs geometry), no light, the camera at the origin looking along +z with a narrow view. */
static fogrt_scene *emitting_fog(float sigma_t, fogrt_vec3 albedo, fogrt_phase_type phase, fogrt_vec3 le, bool bounded,
                                 fogrt_vec3 lo, fogrt_vec3 hi)
{
    fogrt_scene *s = NULL;
    fogrt_medium_desc m;
    CHECK_OK(fogrt_scene_create(NULL, &s));
    CHECK_OK(fogrt_scene_add_sphere(s, v3(1000, 0, 0), 1.0f, add_basic_material(s, FOGRT_BSDF_DIFFUSE, v3(0, 0, 0), v3(0, 0, 0))));
    memset(&m, 0, sizeof m);
    m.sigma_t = sigma_t; m.albedo = albedo; m.g = 0.5f; m.phase = phase; m.emission = le;
    m.bounded = bounded; m.bounds_min = lo; m.bounds_max = hi;
    CHECK_OK(fogrt_scene_set_medium(s, &m));
    set_camera(s, v3(0, 0, 0), v3(0, 0, 1), 0.1f);
    CHECK_OK(fogrt_scene_build(s, NULL));
    return s;
}
/* The per-channel mean of n samples of one camera ray (fogrt_trace) and its standard error. */
static void trace_mean(const fogrt_scene *s, const fogrt_render_desc *rd, int n, double mean[3], double se[3])
{
    double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
    fogrt_rng rng;
    int i, c;
    fogrt_rng_seed(&rng, 4242, 0);
    for (i = 0; i < n; ++i) {
        fogrt_vec3 L = fogrt_trace(s, rd, v3(0, 0, 0), v3(0.1f, 0.2f, 1.0f), &rng, NULL);
        double l[3] = {L.x, L.y, L.z};
        for (c = 0; c < 3; ++c) { sum[c] += l[c]; sum2[c] += l[c] * l[c]; }
    }
    for (c = 0; c < 3; ++c) { mean[c] = sum[c] / n; se[c] = std_error_of_mean(sum[c], sum2[c], n); }
}
#endif

/* Fog filling all space, seen from inside, looks exactly Le whatever its albedo (below 1)
   and phase function: sum_k albedo^k (1 - albedo) Le = Le. Grey albedos 0, 0.5 and 0.9 in
   a render, its image mean within 4 of the render's own standard errors (albedo 0: every
   sample is Le, to float rounding); a chromatic albedo (0.2, 0.6, 0.95) with Rayleigh
   scattering per channel, from samples of one ray. Both with the defaults (each segment's
   emission in closed form) and the paper's settings (the collision estimator). */
static void test_emission_unbounded_fog_is_le(void)
{
#ifdef FOGRT_NO_MEDIA
    MEDIA_ONLY();
#else
    const fogrt_vec3 le = v3(0.5f, 1.0f, 2.0f);
    const double le_lum = luminance(0.5, 1.0, 2.0);
    static const float albedos[3] = {0.0f, 0.5f, 0.9f};
    char msg[256];
    int k, paper, c;
    for (paper = 0; paper < 2; ++paper) {
        fogrt_render_desc rd = paper ? fogrt_render_paper_defaults() : fogrt_render_defaults();
        rd.max_depth = -1; rd.seed = 5;
        for (k = 0; k < 3; ++k) {
            fogrt_scene *s = emitting_fog(1.0f, v3(albedos[k], albedos[k], albedos[k]), FOGRT_PHASE_HG, le, false, le, le);
            double m, se;
            render_mean(s, &rd, 8, 8, 64, &m, &se);
            snprintf(msg, sizeof msg, "%s, albedo %g: image mean luminance %.6f +- %.6f, Le's %.6f (%.2g s.e.)",
                     paper ? "paper (collision estimator)" : "defaults", (double)albedos[k], m, se, le_lum,
                     se > 0.0 ? fabs(m - le_lum) / se : 0.0);
            TEST_MESSAGE(msg);
            if (k == 0) TEST_ASSERT_TRUE_MESSAGE(fabs(m - le_lum) <= 1e-6 * le_lum, msg);
            else TEST_ASSERT_TRUE_MESSAGE(se > 0.0 && fabs(m - le_lum) <= 4.0 * se, msg);
            fogrt_scene_destroy(s);
        }
        {
            fogrt_scene *s = emitting_fog(2.0f, v3(0.2f, 0.6f, 0.95f), FOGRT_PHASE_RAYLEIGH, le, false, le, le);
            double mean[3], se[3], want[3] = {0.5, 1.0, 2.0};
            trace_mean(s, &rd, 20000, mean, se);
            for (c = 0; c < 3; ++c) {
                snprintf(msg, sizeof msg, "%s, albedo (0.2, 0.6, 0.95), Rayleigh, channel %d: %.5f +- %.5f, Le %.1f (%.2f s.e.)",
                         paper ? "paper" : "defaults", c, mean[c], se[c], want[c], fabs(mean[c] - want[c]) / se[c]);
                TEST_MESSAGE(msg);
                TEST_ASSERT_TRUE_MESSAGE(se[c] > 0.0 && fabs(mean[c] - want[c]) <= 4.0 * se[c], msg);
            }
            fogrt_scene_destroy(s);
        }
    }
#endif
}

/* An absorbing slab (albedo 0) of optical depth 1.4 (sigma_t 2, thickness 0.7) seen from
   vacuum in front of it gives Le (1 - exp(-1.4)) per channel: with the defaults in every
   sample (to 2e-6), with the paper's collision estimator within 4 of the render's own
   standard errors. The view is 0.1 degrees wide, so every ray crosses the slab within
   1e-6 of its thickness. */
static void test_emission_absorbing_slab(void)
{
#ifdef FOGRT_NO_MEDIA
    MEDIA_ONLY();
#else
    const double tau = 2.0 * 0.7, f = -expm1(-tau), want[3] = {1.0 * f, 2.0 * f, 3.0 * f};
    fogrt_scene *s = emitting_fog(2.0f, v3(0, 0, 0), FOGRT_PHASE_HG, v3(1, 2, 3), true, v3(-50, -50, 2.0f), v3(50, 50, 2.7f));
    fogrt_render_desc rd = fogrt_render_defaults();
    fogrt_image img;
    float rgb[3 * 8 * 8];
    double m, se;
    char msg[256];
    int p, c;
    rd.seed = 6;
    CHECK_OK(fogrt_image_alloc(&img, 8, 8, NULL));
    CHECK_OK(fogrt_render(s, &rd, &img, 16, NULL));
    fogrt_image_resolve(&img, rgb);
    for (p = 0; p < 8 * 8; ++p)
        for (c = 0; c < 3; ++c) {
            snprintf(msg, sizeof msg, "defaults: pixel %d channel %d is %.7f, Le (1 - exp(-1.4)) = %.7f", p, c, (double)rgb[3 * p + c], want[c]);
            TEST_ASSERT_TRUE_MESSAGE(fabs((double)rgb[3 * p + c] - want[c]) <= 2e-6 * want[c], msg);
        }
    fogrt_image_free(&img);
    snprintf(msg, sizeof msg, "defaults: every sample Le (1 - exp(-1.4)) = (%.6f, %.6f, %.6f)", want[0], want[1], want[2]);
    TEST_MESSAGE(msg);
    rd = fogrt_render_paper_defaults();
    rd.seed = 7;
    render_mean(s, &rd, 8, 8, 256, &m, &se);
    snprintf(msg, sizeof msg, "paper (collision estimator): image mean luminance %.5f +- %.5f, Le (1 - exp(-1.4)) %.5f (%.2f s.e.)",
             m, se, luminance(want[0], want[1], want[2]), fabs(m - luminance(want[0], want[1], want[2])) / se);
    TEST_MESSAGE(msg);
    TEST_ASSERT_TRUE_MESSAGE(se > 0.0 && fabs(m - luminance(want[0], want[1], want[2])) <= 4.0 * se, msg);
    fogrt_scene_destroy(s);
#endif
}

/* Emitting fog with Rayleigh scattering in the lamp-lit box: next-event estimation with
   MIS, without MIS and none, and the paper's settings (the collision estimator for the
   fog's emission, and for the lamp seen through fog), give the same image mean. */
static void test_emission_estimators_agree(void)
{
#ifdef FOGRT_NO_MEDIA
    MEDIA_ONLY();
#else
    static const estimator e[4] = {
        {"NEE+MIS", false, true, true, 64}, {"NEE, no MIS", false, true, false, 64}, {"no NEE", false, false, true, 256},
        {"paper", true, true, true, 128}};
    fogrt_scene *s = phase_box(FOGRT_PHASE_RAYLEIGH, 6.0f, v3(0.3f, 0.2f, 0.1f));
    estimators_agree("Rayleigh, emitting (0.3, 0.2, 0.1), lamp", s, e, 4);
    fogrt_scene_destroy(s);
#endif
}

/* This program ran exactly the number of statistical tests stats.h counts for it. */
static void test_sidak_count_is_right(void)
{
    char msg[200];
    snprintf(msg, sizeof msg, "ran %d statistical tests, stats.h says STATS_TESTS_MEDIA = %d (suite total %d, alpha' = %.3g)",
             *stats_test_counter(), STATS_TESTS_MEDIA, STATS_SUITE_TESTS, stats_alpha());
    TEST_MESSAGE(msg);
    TEST_ASSERT_EQUAL_INT_MESSAGE(STATS_TESTS_MEDIA, *stats_test_counter(), msg);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_hg2_chi2_exact_cdf);
    RUN_TEST(test_rayleigh_chi2_exact_cdf);
    RUN_TEST(test_phase_chi2_against_pdf);
    RUN_TEST(test_rayleigh_mu_ks);
    RUN_TEST(test_rayleigh_inverse_cdf);
    RUN_TEST(test_phase_normalised_and_mean_cosine);
    RUN_TEST(test_sample_pdf_matches_eval);
    RUN_TEST(test_hg2_degenerate_is_hg);
    RUN_TEST(test_medium_desc_validation);
    RUN_TEST(test_phase_estimators_agree);
    RUN_TEST(test_emission_unbounded_fog_is_le);
    RUN_TEST(test_emission_absorbing_slab);
    RUN_TEST(test_emission_estimators_agree);
    RUN_TEST(test_sidak_count_is_right);
    return UNITY_END();
}
