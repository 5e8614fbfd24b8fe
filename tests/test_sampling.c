/* test_sampling.c - do fogrt's samplers draw the distributions they claim?

   For each sampler: a chi-square goodness-of-fit test on a grid of cells (directions on the
   sphere, or barycentric cells of a triangle), or a Kolmogorov-Smirnov test (free-flight
   distances), each followed by a negative control: the same routine, the same samples, a
   deliberately wrong model, which must be rejected. Then the deterministic companions:
   moments, pdf normalisation by quadrature, sampler pdf = evaluated pdf, spot falloff
   values, and extreme uniforms. tests/stats.h has the statistics; docs/testing.md explains
   how to read a failure. Fixed seeds: a given build always passes or always fails.        */
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#include "unity.h"
#include "stats.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void setUp(void) {}
void tearDown(void) {}

static fogrt_vec3 v3(float x, float y, float z) { fogrt_vec3 v; v.x = x; v.y = y; v.z = z; return v; }
static double len3(fogrt_vec3 v) { return sqrt((double)v.x * v.x + (double)v.y * v.y + (double)v.z * v.z); }

/* The g values of the brief: both signs, |g| up to 0.99, and the tiny |g| where the
   textbook inverse CDF divides 0 by 0. */
static const float HG_G[] = {-0.99f, -0.9f, -0.5f, -1e-4f, 0.0f, 1e-6f, 0.3f, 0.7f, 0.9f, 0.99f};
#define HG_G_COUNT ((int)(sizeof HG_G / sizeof HG_G[0]))

/* Outgoing directions: wo = +z and -z (the two branches of the orthonormal-basis code),
   an x-axis direction, and a generic one (its components are exact in real numbers:
   0.48^2 + 0.6^2 + 0.64^2 = 1). */
static const float HG_WO[4][3] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {-0.48f, 0.6f, 0.64f}};
#define HG_WO_COUNT 4

/* Ends a RUN_TEST that looped over cases: prints nothing new (each case printed its line)
   and fails once, naming the first failing case. */
#define TALLY_ASSERT(t)                                                                      \
    do {                                                                                     \
        if ((t).failures > 0) {                                                              \
            char tally_msg_[900];                                                            \
            snprintf(tally_msg_, sizeof tally_msg_, "%d of %d cases failed; first: %s",    \
                     (t).failures, (t).cases, (t).first_failure);                           \
            TEST_FAIL_MESSAGE(tally_msg_);                                                   \
        }                                                                                    \
    } while (0)

/* Prints a verdict's line and adds it to the tally. */
#define REPORT(t, v)                                                                         \
    do {                                                                                     \
        stats_verdict report_v_ = (v);                                                       \
        TEST_MESSAGE(report_v_.message);                                                     \
        stats_tally_add(&(t), &report_v_);                                                   \
    } while (0)

/* ==========================================================================================
   Drawing samples into a sphere grid
   ========================================================================================== */
typedef struct dir_sampler {
    /* Returns a direction; sets *ok = false if the sampler reported failure. */
    fogrt_vec3 (*sample)(void *user, float u1, float u2, bool *ok);
    void *user;
} dir_sampler;

/* Draws n directions with two uniforms each from a fixed seed and counts them per cell.
   Returns the number of invalid samples (failed, not finite, not unit length). */
static long count_directions(const stats_sphere_grid *grid, dir_sampler s, long n, uint64_t seed, double *observed)
{
    fogrt_rng rng;
    long invalid = 0;
    fogrt_rng_seed(&rng, seed, 7);
    memset(observed, 0, sizeof(double) * (size_t)(grid->n_cos * grid->n_phi));
    for (long i = 0; i < n; i++) {
        float u1 = fogrt_rng_float(&rng), u2 = fogrt_rng_float(&rng);
        bool ok = true;
        fogrt_vec3 w = s.sample(s.user, u1, u2, &ok);
        int cell = ok ? stats_grid_cell(grid, w.x, w.y, w.z) : -1;
        if (cell < 0) invalid++;
        else observed[cell] += 1.0;
    }
    return invalid;
}

/* The chi-square verdict of a sphere grid (rows: cos theta, columns: phi). */
static stats_verdict grid_verdict(const char *name, const char *distribution, const char *parameter,
                                  const stats_sphere_grid *g, const double *observed, const double *expected,
                                  long invalid, bool negative)
{
    double phi_edge[STATS_GRID_MAX_COS + 1];
    int n_phi = g->n_phi <= STATS_GRID_MAX_COS ? g->n_phi : STATS_GRID_MAX_COS;
    for (int j = 0; j <= n_phi; j++) phi_edge[j] = -STATS_PI + 2.0 * STATS_PI * j / g->n_phi;
    return stats_chi2_verdict(name, distribution, parameter, g->n_cos, g->n_phi, g->cos_edge, "cos theta",
                              g->n_phi <= STATS_GRID_MAX_COS ? phi_edge : NULL, "phi", observed, expected,
                              invalid, negative);
}

static double *alloc_cells(const stats_sphere_grid *g)
{
    double *p = (double *)calloc((size_t)(g->n_cos * g->n_phi), sizeof(double));
    TEST_ASSERT_NOT_NULL(p);
    return p;
}

/* ==========================================================================================
   Henyey-Greenstein
   ========================================================================================== */

/* The HG CDF of mu = cos(d, wi) in double: F(mu) = (1-g^2)/(2g) [s^-1 - (1+g)^-1] with
   s^2 = 1 + g^2 - 2 g mu, rearranged as (1-g)(1+mu) / (s (1+g+s)) so that it has no
   division by g and no cancellation (s^2 written as a sum of non-negative terms). */
static double hg_cdf(double mu, double g)
{
    double base = g >= 0.0 ? (1.0 - g) * (1.0 - g) + 2.0 * g * (1.0 - mu)
                           : (1.0 + g) * (1.0 + g) - 2.0 * g * (1.0 + mu);
    double s = sqrt(base);
    return (1.0 - g) * (1.0 + mu) / (s * (1.0 + g + s));
}

/* The HG phase function in double, per steradian. */
static double hg_phase_ref(double mu, double g)
{
    double base = g >= 0.0 ? (1.0 - g) * (1.0 - g) + 2.0 * g * (1.0 - mu)
                           : (1.0 + g) * (1.0 + g) - 2.0 * g * (1.0 + mu);
    return (1.0 - g) * (1.0 + g) / (4.0 * STATS_PI * base * sqrt(base));
}

/* Grid rows at equal-probability quantiles of mu for HG(g), so a peaked lobe is resolved
   where its mass is. Rows narrower than HG_MIN_ROW are merged: fogrt's mu is a float, and
   near mu = +-1 floats are 6e-8 apart, so a row must span many float steps for the counts
   not to depend on rounding. */
#define HG_MIN_ROW 4e-6
static void hg_quantile_rows(stats_sphere_grid *grid, double g, int rows)
{
    int n = 0;
    grid->cos_edge[n++] = -1.0;
    for (int k = 1; k < rows; k++) {
        double target = (double)k / rows, lo = -1.0, hi = 1.0;
        for (int it = 0; it < 200 && hi - lo > 1e-15; it++) {
            double mid = 0.5 * (lo + hi);
            if (hg_cdf(mid, g) < target) lo = mid; else hi = mid;
        }
        double edge = 0.5 * (lo + hi);
        if (edge - grid->cos_edge[n - 1] >= HG_MIN_ROW && 1.0 - edge >= HG_MIN_ROW) grid->cos_edge[n++] = edge;
    }
    grid->cos_edge[n] = 1.0;
    grid->n_cos = n;
}

typedef struct hg_args { fogrt_vec3 wo; float g; } hg_args;

static fogrt_vec3 hg_sampler(void *user, float u1, float u2, bool *ok)
{
    const hg_args *a = (const hg_args *)user;
    float pdf = 0.0f;
    fogrt_vec3 wi = fogrt_sample_hg(a->wo, a->g, u1, u2, &pdf);
    *ok = pdf > 0.0f && isfinite(pdf);
    return wi;
}

/* Exact cell probability of HG in the grid whose z axis is d: the CDF difference in mu,
   times the cell's share of the (uniform) azimuth. */
static double hg_cell_prob(double c0, double c1, double p0, double p1, void *user)
{
    double g = *(const double *)user;
    return (hg_cdf(c1, g) - hg_cdf(c0, g)) * (p1 - p0) / (2.0 * STATS_PI);
}

/* fogrt_sample_hg at every g and several wo follows the exact HG law around d = -wo
   (mu from the CDF, phi uniform). Fails if the mu formula, the sign convention (g > 0
   forward) or the frame around d is wrong, e.g. a non-orthonormal basis skews phi. */
static void test_hg_chi2_exact_cdf(void)
{
    stats_tally t = {0, 0, ""};
    stats_sphere_grid grid;
    stats_grid_init(&grid, 50, 10);     /* the largest grid used below */
    double *observed = alloc_cells(&grid), *expected = alloc_cells(&grid);
    for (int gi = 0; gi < HG_G_COUNT; gi++) {
        for (int wi = 0; wi < HG_WO_COUNT; wi++) {
            hg_args a;
            a.g = HG_G[gi];
            a.wo = v3(HG_WO[wi][0], HG_WO[wi][1], HG_WO[wi][2]);
            double g = a.g;
            stats_grid_init(&grid, 50, 10);
            hg_quantile_rows(&grid, g, 50);
            stats_grid_set_axis(&grid, -(double)a.wo.x, -(double)a.wo.y, -(double)a.wo.z);  /* z = d */
            dir_sampler s = {hg_sampler, &a};
            const long n = 100000;
            long invalid = count_directions(&grid, s, n, 1000 + 10 * (uint64_t)gi + (uint64_t)wi, observed);
            stats_grid_expected_from_cells(&grid, hg_cell_prob, &g, (double)n, expected);
            char name[64], param[96];
            snprintf(name, sizeof name, "hg_exact_g%g_wo%d", g, wi);
            snprintf(param, sizeof param, "g=%g, wo=(%g,%g,%g), frame z = d = -wo", g, (double)a.wo.x,
                     (double)a.wo.y, (double)a.wo.z);
            REPORT(t, grid_verdict(name, "fogrt_sample_hg vs exact HG CDF", param, &grid, observed, expected,
                                   invalid, false));
            /* Negative control: the same samples against HG(-g), i.e. the opposite sign
               convention (mu measured from wo instead of d). */
            if (wi == 3 && fabs(g) >= 0.3) {
                double neg_g = -g;
                stats_grid_expected_from_cells(&grid, hg_cell_prob, &neg_g, (double)n, expected);
                snprintf(param, sizeof param, "sampled with g=%g, model HG(%g) (sign convention flipped)", g, neg_g);
                REPORT(t, grid_verdict(name, "fogrt_sample_hg vs exact HG CDF", param, &grid, observed, expected,
                                       invalid, true));
            }
        }
    }
    free(observed);
    free(expected);
    TALLY_ASSERT(t);
}

typedef struct hg_pdf_args { fogrt_vec3 wo; float g; bool flip; } hg_pdf_args;

/* fogrt_hg_pdf as a pdf over world directions (flip: evaluate at -wo, the wrong sign). */
static double hg_pdf_callback(const double w[3], void *user)
{
    const hg_pdf_args *a = (const hg_pdf_args *)user;
    fogrt_vec3 wi = v3((float)w[0], (float)w[1], (float)w[2]);
    fogrt_vec3 wo = a->flip ? v3(-a->wo.x, -a->wo.y, -a->wo.z) : a->wo;
    return fogrt_hg_pdf(wo, wi, a->g);
}

/* fogrt_sample_hg agrees with fogrt_hg_pdf on a plain world grid (expected counts by
   cubature of the pdf, as Mitsuba's test does). Fails if sampling and evaluation disagree,
   the case that biases MIS and next-event estimation in the fog. */
static void test_hg_chi2_against_pdf(void)
{
    stats_tally t = {0, 0, ""};
    const float gs[2] = {0.3f, -0.5f};
    stats_sphere_grid grid;
    stats_grid_init(&grid, 40, 80);
    double *observed = alloc_cells(&grid), *expected = alloc_cells(&grid);
    for (int k = 0; k < 2; k++) {
        hg_args a;
        a.g = gs[k];
        a.wo = v3(HG_WO[3][0], HG_WO[3][1], HG_WO[3][2]);
        dir_sampler s = {hg_sampler, &a};
        const long n = 200000;
        long invalid = count_directions(&grid, s, n, 2000 + (uint64_t)k, observed);
        hg_pdf_args pa = {a.wo, a.g, false};
        double total = stats_grid_expected_from_pdf(&grid, hg_pdf_callback, &pa, (double)n, expected);
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-4, 1.0, total, "fogrt_hg_pdf does not integrate to 1 over the sphere");
        char name[64], param[96];
        snprintf(name, sizeof name, "hg_pdf_g%g", (double)a.g);
        snprintf(param, sizeof param, "g=%g, wo=(%g,%g,%g), world grid", (double)a.g, (double)a.wo.x,
                 (double)a.wo.y, (double)a.wo.z);
        REPORT(t, grid_verdict(name, "fogrt_sample_hg vs fogrt_hg_pdf", param, &grid, observed, expected,
                               invalid, false));
        /* Negative control: the pdf evaluated with wo flipped. */
        pa.flip = true;
        stats_grid_expected_from_pdf(&grid, hg_pdf_callback, &pa, (double)n, expected);
        snprintf(param, sizeof param, "g=%g, pdf evaluated at -wo (wrong convention)", (double)a.g);
        REPORT(t, grid_verdict(name, "fogrt_sample_hg vs fogrt_hg_pdf", param, &grid, observed, expected,
                               invalid, true));
    }
    free(observed);
    free(expected);
    TALLY_ASSERT(t);
}

/* The mean cosine between d = -wo and the sampled direction equals g, within 4 standard
   errors (from the sample variance). This pins the sign convention on its own: g > 0 must
   scatter forward. Fails if g's sign is flipped or the lobe has the wrong width. */
static void test_hg_mean_cosine_is_g(void)
{
    char msg[256];
    for (int gi = 0; gi < HG_G_COUNT; gi++) {
        float g = HG_G[gi];
        fogrt_vec3 wo = v3(HG_WO[3][0], HG_WO[3][1], HG_WO[3][2]);
        double d[3] = {-(double)wo.x, -(double)wo.y, -(double)wo.z}, dl = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        fogrt_rng rng;
        fogrt_rng_seed(&rng, 3000 + (uint64_t)gi, 1);
        const long n = 400000;
        double sum = 0.0, sum2 = 0.0;
        for (long i = 0; i < n; i++) {
            float u1 = fogrt_rng_float(&rng), u2 = fogrt_rng_float(&rng);
            fogrt_vec3 wi = fogrt_sample_hg(wo, g, u1, u2, NULL);
            double mu = (wi.x * d[0] + wi.y * d[1] + wi.z * d[2]) / (dl * len3(wi));
            sum += mu;
            sum2 += mu * mu;
        }
        double mean = sum / n, var = (sum2 - n * mean * mean) / (n - 1), se = sqrt(var / n);
        snprintf(msg, sizeof msg, "HG mean cosine: g=%g, mean mu=%.6f, s.e.=%.2e, (mean-g)/s.e.=%.2f (limit 4)",
                 (double)g, mean, se, (mean - g) / se);
        TEST_MESSAGE(msg);
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(4.0 * se, (double)g, mean, msg);
    }
}

/* The pdf that fogrt_sample_hg returns equals fogrt_hg_pdf(wo, wi, g) and the HG formula
   in double at the returned direction. The tolerance follows the conditioning: near the
   peak of a strong lobe the pdf changes by 3|g|/(1+g^2-2g mu) relative per unit of mu, and
   the float direction carries mu errors of a few 1e-7. */
static void test_hg_sample_pdf_matches_eval(void)
{
    char msg[256];
    for (int gi = 0; gi < HG_G_COUNT; gi++) {
        for (int wi_ = 0; wi_ < HG_WO_COUNT; wi_++) {
            float g = HG_G[gi];
            fogrt_vec3 wo = v3(HG_WO[wi_][0], HG_WO[wi_][1], HG_WO[wi_][2]);
            fogrt_rng rng;
            fogrt_rng_seed(&rng, 4000 + (uint64_t)gi, (uint64_t)wi_);
            for (int i = 0; i < 2000; i++) {
                float u1 = fogrt_rng_float(&rng), u2 = fogrt_rng_float(&rng), pdf = -1.0f;
                if (i == 0) u1 = 0.0f;
                if (i == 1) u1 = 1.0f - 0x1p-24f;
                fogrt_vec3 wi = fogrt_sample_hg(wo, g, u1, u2, &pdf);
                float eval = fogrt_hg_pdf(wo, wi, g);
                double mu = -((double)wo.x * wi.x + (double)wo.y * wi.y + (double)wo.z * wi.z) / (len3(wo) * len3(wi));
                double ref = hg_phase_ref(mu, g);
                double base = g >= 0.0f ? (1.0 - g) * (1.0 - g) + 2.0 * g * (1.0 - mu)
                                        : (1.0 + g) * (1.0 + g) - 2.0 * g * (1.0 + mu);
                double rel_tol = 1e-5 + 3.0 * fabs((double)g) / base * 4e-7;
                snprintf(msg, sizeof msg, "g=%g wo#%d u1=%.9g: sampler pdf %.9g, fogrt_hg_pdf %.9g, double %.9g (tol %.2g rel)",
                         (double)g, wi_, (double)u1, (double)pdf, (double)eval, ref, rel_tol);
                TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(rel_tol * ref, (double)eval, (double)pdf, msg);
                TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(rel_tol * ref, ref, (double)pdf, msg);
            }
        }
    }
}

static double hg_phase_callback(double mu, void *user)
{
    return fogrt_hg_phase((float)mu, *(const float *)user);
}

/* fogrt_hg_phase integrates to 1 over the sphere, 2 pi int p(mu) dmu (adaptive Simpson on
   float-exact dyadic nodes), for many g including 0.99, and is positive everywhere.
   Fails on a missing 4 pi, a (1 - g)^2 for (1 - g^2), or a cancelling denominator. */
static void test_hg_phase_normalised(void)
{
    const float gs[] = {-0.99f, -0.9f, -0.7f, -0.5f, -0.3f, -0.1f, -1e-4f, 0.0f, 1e-6f, 1e-3f,
                        0.1f, 0.3f, 0.5f, 0.7f, 0.8f, 0.9f, 0.95f, 0.99f};
    char msg[160];
    for (size_t k = 0; k < sizeof gs / sizeof gs[0]; k++) {
        float g = gs[k];
        double integral = 2.0 * STATS_PI * stats_integrate_1d(hg_phase_callback, &g, -1.0, 1.0, 1e-8, 30);
        snprintf(msg, sizeof msg, "2 pi int fogrt_hg_phase(mu, %g) dmu = %.9f (want 1 within 1e-6)", (double)g, integral);
        TEST_MESSAGE(msg);
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-6, 1.0, integral, msg);
        TEST_ASSERT_TRUE_MESSAGE(fogrt_hg_phase(-1.0f, g) > 0.0f && fogrt_hg_phase(1.0f, g) > 0.0f, msg);
    }
}

/* ==========================================================================================
   Cosine hemisphere and uniform sphere
   ========================================================================================== */
static fogrt_vec3 cosine_sampler(void *user, float u1, float u2, bool *ok)
{
    (void)user; *ok = true;
    return fogrt_sample_cosine_hemisphere(u1, u2);
}
static double cosine_pdf_callback(const double w[3], void *user)
{
    (void)user;
    return fogrt_cosine_hemisphere_pdf((float)w[2]);
}
static double uniform_hemisphere_pdf(const double w[3], void *user)
{
    (void)user;
    return w[2] > 0.0 ? 1.0 / (2.0 * STATS_PI) : 0.0;
}

/* fogrt_sample_cosine_hemisphere follows fogrt_cosine_hemisphere_pdf (cos / pi, zero
   below the horizon). Negative control: a uniform hemisphere. Fails if the concentric map
   or the lift to the hemisphere is wrong. */
static void test_cosine_hemisphere_chi2(void)
{
    stats_tally t = {0, 0, ""};
    stats_sphere_grid grid;
    stats_grid_init(&grid, 40, 40);     /* even: an edge on the horizon */
    double *observed = alloc_cells(&grid), *expected = alloc_cells(&grid);
    dir_sampler s = {cosine_sampler, NULL};
    const long n = 400000;
    long invalid = count_directions(&grid, s, n, 5000, observed);
    double total = stats_grid_expected_from_pdf(&grid, cosine_pdf_callback, NULL, (double)n, expected);
    TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-4, 1.0, total, "fogrt_cosine_hemisphere_pdf does not integrate to 1");
    REPORT(t, grid_verdict("cosine_hemisphere", "fogrt_sample_cosine_hemisphere", "world grid", &grid, observed,
                           expected, invalid, false));
    stats_grid_expected_from_pdf(&grid, uniform_hemisphere_pdf, NULL, (double)n, expected);
    REPORT(t, grid_verdict("cosine_hemisphere", "fogrt_sample_cosine_hemisphere", "model: uniform hemisphere",
                           &grid, observed, expected, invalid, true));
    free(observed);
    free(expected);
    TALLY_ASSERT(t);
}

static fogrt_vec3 uniform_sphere_sampler(void *user, float u1, float u2, bool *ok)
{
    (void)user; *ok = true;
    return fogrt_sample_uniform_sphere(u1, u2);
}
static double uniform_sphere_pdf_callback(const double w[3], void *user)
{
    (void)w; (void)user;
    return fogrt_uniform_sphere_pdf();
}
/* A 10% tilt toward +z: a subtle error the test must still see. */
static double tilted_sphere_pdf(const double w[3], void *user)
{
    (void)user;
    return (1.0 + 0.1 * w[2]) / (4.0 * STATS_PI);
}

/* fogrt_sample_uniform_sphere is uniform over the sphere. Negative control: a density
   only 10% higher at the north pole than at the equator. Fails if z or phi is mapped
   wrongly (e.g. z = cos(pi u1), which bunches samples at the poles). */
static void test_uniform_sphere_chi2(void)
{
    stats_tally t = {0, 0, ""};
    stats_sphere_grid grid;
    stats_grid_init(&grid, 40, 80);
    double *observed = alloc_cells(&grid), *expected = alloc_cells(&grid);
    dir_sampler s = {uniform_sphere_sampler, NULL};
    const long n = 400000;
    long invalid = count_directions(&grid, s, n, 6000, observed);
    stats_grid_expected_from_pdf(&grid, uniform_sphere_pdf_callback, NULL, (double)n, expected);
    REPORT(t, grid_verdict("uniform_sphere", "fogrt_sample_uniform_sphere", "world grid", &grid, observed,
                           expected, invalid, false));
    stats_grid_expected_from_pdf(&grid, tilted_sphere_pdf, NULL, (double)n, expected);
    REPORT(t, grid_verdict("uniform_sphere", "fogrt_sample_uniform_sphere", "model: (1 + 0.1 z) / 4 pi",
                           &grid, observed, expected, invalid, true));
    free(observed);
    free(expected);
    TALLY_ASSERT(t);
}

/* ==========================================================================================
   Solid angle sampling of a sphere
   ========================================================================================== */
typedef struct sphere_args { fogrt_vec3 p, c; float r; double model_r; long misses, bad_pdf; } sphere_args;

/* Does the ray from p along unit w hit the sphere (c, r)? In double, independent of fogrt. */
static bool ray_hits_sphere(const sphere_args *a, const double w[3], double r)
{
    double pc[3] = {(double)a->c.x - a->p.x, (double)a->c.y - a->p.y, (double)a->c.z - a->p.z};
    double along = pc[0] * w[0] + pc[1] * w[1] + pc[2] * w[2];
    double d2 = pc[0] * pc[0] + pc[1] * pc[1] + pc[2] * pc[2];
    if (d2 <= r * r) return true;                      /* inside: every direction */
    return along > 0.0 && d2 - along * along <= r * r;
}

static fogrt_vec3 sphere_sampler(void *user, float u1, float u2, bool *ok)
{
    sphere_args *a = (sphere_args *)user;
    float pdf = 0.0f;
    fogrt_vec3 w = fogrt_sample_sphere_solid_angle(a->p, a->c, a->r, u1, u2, &pdf);
    double l = len3(w), wd[3] = {w.x / l, w.y / l, w.z / l};
    /* Every direction must hit the sphere (with 1e-4 relative slack for float rounding at
       the rim); a miss is an invalid sample. */
    if (!ray_hits_sphere(a, wd, a->r * (1.0 + 1e-4))) { a->misses++; *ok = false; }
    else *ok = pdf > 0.0f && isfinite(pdf);
    /* The pdf returned with the sample is the one fogrt_sphere_solid_angle_pdf reports. */
    if (pdf != fogrt_sphere_solid_angle_pdf(a->p, a->c, a->r)) a->bad_pdf++;
    return w;
}

/* 1 - cos(theta_max) of the cone subtended by a sphere of radius r at distance dist,
   as sin^2 / (1 + cos) in double. */
static double cone_one_minus_cos(double r, double dist)
{
    double s2 = r * r / (dist * dist);
    return s2 / (1.0 + sqrt(1.0 - s2));
}

/* The model pdf: fogrt's pdf value inside the cone of the sphere (hit test in double), 0
   outside. With model_r != r (negative control) it is the uniform cone of a sphere of
   radius model_r, computed here in double. */
static double sphere_pdf_callback(const double w[3], void *user)
{
    const sphere_args *a = (const sphere_args *)user;
    if (a->model_r == a->r) {
        return ray_hits_sphere(a, w, a->r) ? fogrt_sphere_solid_angle_pdf(a->p, a->c, a->r) : 0.0;
    }
    double pc[3] = {(double)a->c.x - a->p.x, (double)a->c.y - a->p.y, (double)a->c.z - a->p.z};
    double dist = sqrt(pc[0] * pc[0] + pc[1] * pc[1] + pc[2] * pc[2]);
    return ray_hits_sphere(a, w, a->model_r) ? 1.0 / (2.0 * STATS_PI * cone_one_minus_cos(a->model_r, dist)) : 0.0;
}

/* fogrt_sample_sphere_solid_angle is uniform over the cone of directions that see the
   sphere, for a large, a medium and a tiny (0.01 rad) cone, and uniform over all
   directions from inside; every direction hits the sphere. Negative control: the cone of
   a sphere 5% larger. Fails if cos(theta_max) cancels in float, the cone is mis-sized, or
   the frame around the axis is wrong. */
static void test_sphere_solid_angle_chi2(void)
{
    stats_tally t = {0, 0, ""};
    const float P[4][3] = {{0.2f, 0.1f, -0.3f}, {0.0f, 0.0f, 0.0f}, {0.1f, 0.2f, 0.3f}, {0.1f, 0.2f, 0.3f}};
    const float C[4][3] = {{0.95f, 0.1f, -1.3f}, {2.0f, 1.5f, -1.5f}, {-29.9f, 40.2f, 0.3f}, {0.2f, 0.0f, 0.4f}};
    const float R[4] = {1.0f, 0.5f, 0.5f, 1.0f};
    const char *label[4] = {"large cone", "medium cone", "tiny cone (0.01 rad)", "p inside the sphere"};
    stats_sphere_grid grid;
    double *observed = NULL, *expected = NULL;
    for (int k = 0; k < 4; k++) {
        sphere_args a;
        a.p = v3(P[k][0], P[k][1], P[k][2]);
        a.c = v3(C[k][0], C[k][1], C[k][2]);
        a.r = R[k];
        a.model_r = a.r;
        a.misses = 0;
        a.bad_pdf = 0;
        double pc[3] = {(double)a.c.x - a.p.x, (double)a.c.y - a.p.y, (double)a.c.z - a.p.z};
        double dist = sqrt(pc[0] * pc[0] + pc[1] * pc[1] + pc[2] * pc[2]);
        bool inside = dist <= a.r;
        if (inside) {
            stats_grid_init(&grid, 20, 40);
        } else {
            /* Frame z toward the centre; one catch-all row below the cone, then 40 equal
               rows from 1.25 (1 - cos theta_max) below 1 up to 1. */
            double omc = cone_one_minus_cos(a.r, dist), lo = 1.0 - 1.25 * omc;
            stats_grid_init(&grid, 41, 20);
            grid.cos_edge[0] = -1.0;
            for (int i = 1; i <= 41; i++) grid.cos_edge[i] = lo + (1.0 - lo) * (i - 1) / 40.0;
            grid.cos_edge[41] = 1.0;
            stats_grid_set_axis(&grid, pc[0], pc[1], pc[2]);
        }
        if (!observed) { stats_sphere_grid big; stats_grid_init(&big, 41, 40); observed = alloc_cells(&big); expected = alloc_cells(&big); }
        dir_sampler s = {sphere_sampler, &a};
        const long n = 100000;
        long invalid = count_directions(&grid, s, n, 7000 + (uint64_t)k, observed);
        double total = stats_grid_expected_from_pdf(&grid, sphere_pdf_callback, &a, (double)n, expected);
        char name[64], param[160], msg[160];
        snprintf(name, sizeof name, "sphere_solid_angle_%d", k);
        snprintf(param, sizeof param, "%s: |c-p|=%.4g r=%g, %ld directions missed the sphere", label[k], dist,
                 (double)a.r, a.misses);
        snprintf(msg, sizeof msg, "%s: the pdf integrates to %.7f over the directions that see the sphere", label[k], total);
        TEST_MESSAGE(msg);
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-4, 1.0, total, msg);
        snprintf(msg, sizeof msg, "%s: %ld samples returned a pdf other than fogrt_sphere_solid_angle_pdf", label[k], a.bad_pdf);
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, a.bad_pdf, msg);
        REPORT(t, grid_verdict(name, "fogrt_sample_sphere_solid_angle", param, &grid, observed, expected, invalid,
                               false));
        if (!inside) {
            a.model_r = 1.05 * a.r;
            stats_grid_expected_from_pdf(&grid, sphere_pdf_callback, &a, (double)n, expected);
            snprintf(param, sizeof param, "%s, model: the cone of a sphere of radius %g", label[k], a.model_r);
            REPORT(t, grid_verdict(name, "fogrt_sample_sphere_solid_angle", param, &grid, observed, expected,
                                   invalid, true));
        }
    }
    free(observed);
    free(expected);
    TALLY_ASSERT(t);
}

/* ==========================================================================================
   Triangle
   ========================================================================================== */
/* The naive map b1 = u1, b2 = (1 - u1) u2 has density 1/(1 - b1) on the triangle. Its
   probability on the cell [x0,x1] x [y0,y1] (below the diagonal, or cut by it). */
static double naive_triangle_cell(double x0, double x1, double y0, double y1, bool diagonal)
{
    if (!diagonal) return (y1 - y0) * log((1.0 - x0) / (1.0 - x1));
    /* int_{x0}^{x1} (1 - x - y0) / (1 - x) dx; the log term vanishes when y0 = 0. */
    return (x1 - x0) - (y0 > 0.0 ? y0 * log((1.0 - x0) / (1.0 - x1)) : 0.0);
}

/* fogrt_sample_triangle is uniform over the triangle: a chi-square test on a K x K grid in
   (b1, b2), where the cells below the diagonal b1 + b2 = 1 have probability 2/K^2 and the
   cells it cuts in half 1/K^2. Negative control: the naive map's density 1/(1 - b1).
   Fails if the sqrt is dropped (samples bunch at a vertex) or barycentrics leave the
   triangle. */
static void test_triangle_chi2(void)
{
    stats_tally t = {0, 0, ""};
    enum { K = 40 };
    double observed[K * K], expected[K * K], edge[K + 1];
    memset(observed, 0, sizeof observed);
    for (int i = 0; i <= K; i++) edge[i] = (double)i / K;
    fogrt_rng rng;
    fogrt_rng_seed(&rng, 8000, 3);
    const long n = 200000;
    long invalid = 0;
    for (long s = 0; s < n; s++) {
        float u1 = fogrt_rng_float(&rng), u2 = fogrt_rng_float(&rng), b1 = -1.0f, b2 = -1.0f;
        fogrt_sample_triangle(u1, u2, &b1, &b2);
        if (!(b1 >= 0.0f && b2 >= 0.0f && (double)b1 + b2 <= 1.0 + 1e-6)) { invalid++; continue; }
        int i = (int)(b1 * K), j = (int)(b2 * K);
        if (i > K - 1) i = K - 1;
        if (j > K - 1) j = K - 1;
        while (i + j > K - 1) { if (i > j) i--; else j--; }   /* a point exactly on the diagonal */
        observed[i * K + j] += 1.0;
    }
    for (int i = 0; i < K; i++)
        for (int j = 0; j < K; j++)
            expected[i * K + j] = n * (i + j < K - 1 ? 2.0 : (i + j == K - 1 ? 1.0 : 0.0)) / (K * K);
    REPORT(t, stats_chi2_verdict("triangle", "fogrt_sample_triangle", "K=40 grid in (b1, b2)", K, K, edge, "b1", edge,
                                 "b2", observed, expected, invalid, false));
    for (int i = 0; i < K; i++)
        for (int j = 0; j < K; j++)
            expected[i * K + j] = i + j > K - 1 ? 0.0
                                : n * naive_triangle_cell(edge[i], edge[i + 1], edge[j], edge[j + 1], i + j == K - 1);
    REPORT(t, stats_chi2_verdict("triangle", "fogrt_sample_triangle", "model: naive map b1=u1, b2=(1-u1)u2", K, K,
                                 edge, "b1", edge, "b2", observed, expected, invalid, true));
    TALLY_ASSERT(t);
}

/* ==========================================================================================
   Spot light with a radius
   ========================================================================================== */
typedef struct light_args { fogrt_vec3 c; float r; } light_args;

/* A light of radius r is spread uniformly over a sphere (fogrt_light_desc): the position is
   c + r * fogrt_sample_uniform_sphere(u1, u2). We return the direction (p - c) / r seen from
   the centre, in double, so the float rounding of p shows up as a length error. */
static fogrt_vec3 light_position_sampler(void *user, float u1, float u2, bool *ok)
{
    const light_args *a = (const light_args *)user;
    fogrt_vec3 w = fogrt_sample_uniform_sphere(u1, u2);
    fogrt_vec3 p = v3(a->c.x + a->r * w.x, a->c.y + a->r * w.y, a->c.z + a->r * w.z);
    double dx = ((double)p.x - a->c.x) / a->r, dy = ((double)p.y - a->c.y) / a->r, dz = ((double)p.z - a->c.z) / a->r;
    *ok = true;
    return v3((float)dx, (float)dy, (float)dz);
}

/* The classic mistake: theta uniform in [0, pi] instead of cos theta uniform. Exact cell
   probability (theta1 - theta0)/pi times the phi share. */
static double uniform_theta_cell(double c0, double c1, double p0, double p1, void *user)
{
    (void)user;
    return (acos(c0) - acos(c1)) / STATS_PI * (p1 - p0) / (2.0 * STATS_PI);
}

/* Positions on a spot light with radius (r = 0.05 at an off-centre point) are uniform over
   its sphere. Negative control: theta uniform instead of cos theta. Fails if the position
   distribution is not area-uniform, which would make soft shadows lopsided. */
static void test_spot_light_radius_positions_chi2(void)
{
    stats_tally t = {0, 0, ""};
    light_args a;
    a.c = v3(2.5f, 4.0f, -1.0f);
    a.r = 0.05f;
    stats_sphere_grid grid;
    stats_grid_init(&grid, 30, 60);
    double *observed = alloc_cells(&grid), *expected = alloc_cells(&grid);
    dir_sampler s = {light_position_sampler, &a};
    const long n = 300000;
    long invalid = count_directions(&grid, s, n, 9000, observed);
    stats_grid_expected_from_pdf(&grid, uniform_sphere_pdf_callback, NULL, (double)n, expected);
    REPORT(t, grid_verdict("spot_radius_positions", "spot light position c + r fogrt_sample_uniform_sphere",
                           "c=(2.5,4,-1), r=0.05", &grid, observed, expected, invalid, false));
    stats_grid_expected_from_cells(&grid, uniform_theta_cell, NULL, (double)n, expected);
    REPORT(t, grid_verdict("spot_radius_positions", "spot light position c + r fogrt_sample_uniform_sphere",
                           "model: theta uniform in [0, pi]", &grid, observed, expected, invalid, true));
    free(observed);
    free(expected);
    TALLY_ASSERT(t);
}

/* fogrt_spot_falloff(cos theta, cutoff, beam) equals clamp((cutoff - theta)/(cutoff - beam),
   0, 1), and for beam == cutoff a hard cone, at angles inside the beam, on the ramp and
   outside, for cutoffs of 0, 30, 45, 90 and 180 degrees. The expected value is computed in
   double from the same float cosine, so only fogrt's own rounding remains (1e-5). Fails
   if the ramp is in cos instead of the angle, or degrees and radians are mixed. */
static void test_spot_falloff_values(void)
{
    struct { float cutoff, beam, theta; double want; } c[] = {
        {30, 10, 0, 1.0}, {30, 10, 5, 1.0}, {30, 10, 9.5f, 1.0}, {30, 10, 20, 0.5}, {30, 10, 25, 0.25},
        {30, 10, 29, 0.05}, {30, 10, 31, 0.0}, {30, 10, 60, 0.0}, {30, 10, 180, 0.0},
        {90, 0, 0, 1.0}, {90, 0, 45, 0.5}, {90, 0, 60, 1.0 / 3.0}, {90, 0, 89, 1.0 / 90.0}, {90, 0, 120, 0.0},
        {90, 90, 0, 1.0}, {90, 90, 89.9f, 1.0}, {90, 90, 90.1f, 0.0}, {90, 90, 179, 0.0},
        {45, 45, 44.9f, 1.0}, {45, 45, 45.1f, 0.0},
        {0, 0, 0.5f, 0.0}, {0, 0, 90, 0.0}, {0, 0, 180, 0.0},
        {180, 0, 90, 0.5}, {180, 0, 135, 0.25}, {180, 0, 180, 0.0}, {180, 90, 45, 1.0}, {180, 90, 135, 0.5},
    };
    char msg[200];
    for (size_t k = 0; k < sizeof c / sizeof c[0]; k++) {
        float cos_theta = (float)cos(c[k].theta * STATS_PI / 180.0);
        /* The exact formula at the angle this float cosine really has. */
        double theta = acos((double)cos_theta) * 180.0 / STATS_PI, want;
        if (c[k].cutoff > c[k].beam) want = fmin(1.0, fmax(0.0, (c[k].cutoff - theta) / (c[k].cutoff - c[k].beam)));
        else want = theta <= c[k].cutoff ? 1.0 : 0.0;
        float got = fogrt_spot_falloff(cos_theta, c[k].cutoff, c[k].beam);
        snprintf(msg, sizeof msg, "fogrt_spot_falloff(cos %g deg, cutoff %g, beam %g) = %.7f, want %.7f (nominal %.7f)",
                 (double)c[k].theta, (double)c[k].cutoff, (double)c[k].beam, (double)got, want, c[k].want);
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-6, c[k].want, want, "test table: nominal value disagrees with the formula");
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-5, want, (double)got, msg);
    }
    /* cutoff 0: a zero-width cone; on the axis itself only "finite, in [0, 1]" is defined. */
    float axis = fogrt_spot_falloff(1.0f, 0.0f, 0.0f);
    TEST_ASSERT_TRUE_MESSAGE(axis >= 0.0f && axis <= 1.0f, "fogrt_spot_falloff(1, 0, 0) outside [0, 1]");
}

/* ==========================================================================================
   Free-flight distances: Kolmogorov-Smirnov
   ========================================================================================== */
static double exponential_cdf(double x, void *user)
{
    double sigma_t = *(const double *)user;
    return x <= 0.0 ? 0.0 : -expm1(-sigma_t * x);
}

/* fogrt_sample_exponential draws t with CDF 1 - exp(-sigma_t t), for sigma_t from 1e-3
   (mean free path 1000) to 50, by a KS test on 1e5 distances. Negative control: the same
   distances against sigma_t 5% larger. Fails if sigma_t multiplies instead of divides, the
   logarithm is of the wrong argument, or the tail is cut too early. */
static void test_exponential_ks(void)
{
    stats_tally t = {0, 0, ""};
    const float sig[4] = {1e-3f, 0.3f, 1.0f, 50.0f};
    enum { N = 100000 };
    double *x = (double *)malloc(sizeof(double) * N);
    TEST_ASSERT_NOT_NULL(x);
    for (int k = 0; k < 4; k++) {
        fogrt_rng rng;
        fogrt_rng_seed(&rng, 10000 + (uint64_t)k, 5);
        long invalid = 0;
        for (int i = 0; i < N; i++) {
            float d = fogrt_sample_exponential(fogrt_rng_float(&rng), sig[k]);
            if (!(d >= 0.0f) || !isfinite(d)) invalid++;
            x[i] = d;
        }
        double sigma = sig[k];
        stats_ks_result r = stats_ks(x, N, exponential_cdf, &sigma);
        char name[64], param[96];
        snprintf(name, sizeof name, "exponential_sigma%g", sigma);
        snprintf(param, sizeof param, "sigma_t=%g", sigma);
        REPORT(t, stats_ks_verdict(name, "fogrt_sample_exponential", param, &r, x, exponential_cdf, &sigma, invalid,
                                   false));
        double wrong = 1.05 * sigma;
        r = stats_ks(x, N, exponential_cdf, &wrong);
        snprintf(param, sizeof param, "sampled with sigma_t=%g, model sigma_t=%g", sigma, wrong);
        REPORT(t, stats_ks_verdict(name, "fogrt_sample_exponential", param, &r, x, exponential_cdf, &wrong, invalid,
                                   true));
    }
    free(x);
    TALLY_ASSERT(t);
}

/* The free-flight triplet agrees: pdf = sigma_t exp(-sigma_t t), invert(sample(u)) = u,
   and sigma_t = 0 never collides (t = +inf, pdf 0). Fails on a wrong pdf normalisation or
   an inverse that does not match the sampler. */
static void test_exponential_pdf_and_inverse(void)
{
    const float sig[4] = {1e-3f, 0.3f, 1.0f, 50.0f};
    const float us[6] = {0.0f, 1e-6f, 0.25f, 0.5f, 0.9f, 1.0f - 0x1p-24f};
    char msg[200];
    for (int k = 0; k < 4; k++) {
        for (int i = 0; i < 6; i++) {
            float t = fogrt_sample_exponential(us[i], sig[k]);
            float back = fogrt_invert_exponential(t, sig[k]);
            double pdf_want = sig[k] * exp(-(double)sig[k] * t);
            snprintf(msg, sizeof msg, "sigma_t=%g u=%.9g: t=%.9g, invert=%.9g, pdf=%.9g want %.9g", (double)sig[k],
                     (double)us[i], (double)t, (double)back, (double)fogrt_exponential_pdf(t, sig[k]), pdf_want);
            TEST_ASSERT_TRUE_MESSAGE(isfinite(t) && t >= 0.0f, msg);
            TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(2e-7 + 4e-7 * us[i], (double)us[i], (double)back, msg);
            TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-5 * pdf_want, pdf_want, (double)fogrt_exponential_pdf(t, sig[k]), msg);
        }
    }
    TEST_ASSERT_TRUE(isinf(fogrt_sample_exponential(0.5f, 0.0f)) && fogrt_sample_exponential(0.5f, 0.0f) > 0.0f);
    TEST_ASSERT_EQUAL_FLOAT(0.0f, fogrt_exponential_pdf(1.0f, 0.0f));
}

/* ==========================================================================================
   Normalisation and extremes
   ========================================================================================== */
static double cosine_pdf_1d(double mu, void *user)
{
    (void)user;
    return fogrt_cosine_hemisphere_pdf((float)mu);
}

typedef struct cone_args { double cos_max; float pdf; } cone_args;
/* pdf times "does the direction at cosine mu from the axis see the sphere?" */
static double cone_pdf_1d(double mu, void *user)
{
    const cone_args *a = (const cone_args *)user;
    return mu >= a->cos_max ? (double)a->pdf : 0.0;
}

/* The direction pdfs integrate to 1 over the sphere: cosine hemisphere (2 pi int over
   mu in [-1, 1], so it must be 0 below the horizon), uniform sphere, and the solid angle
   pdf over the cone each sphere subtends (cone edge from the geometry in double; sizes down
   to 1e-3 rad, where 1 - cos theta_max = 5e-7 cancels badly if formed naively in float). */
static void test_pdfs_normalised(void)
{
    char msg[200];
    double cosine = 2.0 * STATS_PI * stats_integrate_1d(cosine_pdf_1d, NULL, -1.0, 1.0, 1e-10, 30);
    snprintf(msg, sizeof msg, "cosine hemisphere pdf integrates to %.9f", cosine);
    TEST_MESSAGE(msg);
    TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-6, 1.0, cosine, msg);
    TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-6, 1.0, 4.0 * STATS_PI * fogrt_uniform_sphere_pdf(), "uniform sphere pdf");

    const float ratio[5] = {0.9f, 0.5f, 0.1f, 0.01f, 1e-3f};   /* r / |c - p| */
    for (int k = 0; k < 5; k++) {
        fogrt_vec3 p = v3(0.3f, -0.2f, 0.1f), c = v3(0.3f + 6.0f, -0.2f + 8.0f, 0.1f);   /* |c - p| = 10 */
        float r = 10.0f * ratio[k];
        double dist = sqrt(36.0 + 64.0);
        cone_args a;
        a.cos_max = sqrt(1.0 - (double)r * r / (dist * dist));
        a.pdf = fogrt_sphere_solid_angle_pdf(p, c, r);
        double integral = 2.0 * STATS_PI * stats_integrate_1d(cone_pdf_1d, &a, -1.0, 1.0, 1e-12, 60);
        double exact = 2.0 * STATS_PI * cone_one_minus_cos(r, dist) * a.pdf;
        snprintf(msg, sizeof msg, "sphere solid angle pdf, r/|c-p| = %g: integral over the cone %.7f (closed form %.7f)",
                 (double)ratio[k], integral, exact);
        TEST_MESSAGE(msg);
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-5, 1.0, exact, msg);
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-5, 1.0, integral, msg);
    }
    /* From inside, the uniform sphere. */
    float inside = fogrt_sphere_solid_angle_pdf(v3(0.1f, 0.0f, 0.0f), v3(0.0f, 0.0f, 0.0f), 1.0f);
    TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-6, 1.0, 4.0 * STATS_PI * inside, "solid angle pdf from inside the sphere");
}

/* Checks a direction is finite and of unit length (1e-5). */
static void assert_unit(fogrt_vec3 w, const char *what)
{
    TEST_ASSERT_TRUE_MESSAGE(isfinite(w.x) && isfinite(w.y) && isfinite(w.z), what);
    TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-5, 1.0, len3(w), what);
}

/* u = 0 and u = 1 - 2^-24 (the RNG's extremes) give finite unit directions and finite
   positive pdfs, for every sampler, every g (also +-1 and +-FOGRT_HG_G_MAX) and both
   axis-parallel wo. Fails on 0/0 at g = 0, log(0), or sqrt of a tiny negative number. */
static void test_extreme_uniforms(void)
{
    const float ue[2] = {0.0f, 1.0f - 0x1p-24f};
    const float gx[] = {-1.0f, -FOGRT_HG_G_MAX, -0.99f, -0.5f, -1e-4f, 0.0f, 1e-6f, 0.5f, 0.99f, FOGRT_HG_G_MAX, 1.0f};
    char msg[200];
    for (int a = 0; a < 2; a++) {
        for (int b = 0; b < 2; b++) {
            float u1 = ue[a], u2 = ue[b];
            for (size_t gi = 0; gi < sizeof gx / sizeof gx[0]; gi++) {
                for (int w = 0; w < HG_WO_COUNT; w++) {
                    float pdf = -1.0f;
                    fogrt_vec3 wo = v3(HG_WO[w][0], HG_WO[w][1], HG_WO[w][2]);
                    fogrt_vec3 wi = fogrt_sample_hg(wo, gx[gi], u1, u2, &pdf);
                    snprintf(msg, sizeof msg, "fogrt_sample_hg g=%g wo#%d u=(%.9g, %.9g): wi=(%g,%g,%g) pdf=%g",
                             (double)gx[gi], w, (double)u1, (double)u2, (double)wi.x, (double)wi.y, (double)wi.z,
                             (double)pdf);
                    assert_unit(wi, msg);
                    TEST_ASSERT_TRUE_MESSAGE(isfinite(pdf) && pdf > 0.0f, msg);
                    float mu = fogrt_sample_hg_mu(gx[gi], u1);
                    TEST_ASSERT_TRUE_MESSAGE(mu >= -1.0f && mu <= 1.0f, msg);
                }
            }
            snprintf(msg, sizeof msg, "u=(%.9g, %.9g)", (double)u1, (double)u2);
            assert_unit(fogrt_sample_cosine_hemisphere(u1, u2), msg);
            TEST_ASSERT_TRUE_MESSAGE(fogrt_sample_cosine_hemisphere(u1, u2).z >= 0.0f, msg);
            assert_unit(fogrt_sample_uniform_sphere(u1, u2), msg);
            float pdf = -1.0f;
            assert_unit(fogrt_sample_sphere_solid_angle(v3(0, 0, 0), v3(0, 0, 5), 1.0f, u1, u2, &pdf), msg);
            TEST_ASSERT_TRUE_MESSAGE(isfinite(pdf) && pdf > 0.0f, msg);
            assert_unit(fogrt_sample_sphere_solid_angle(v3(0, 0, 0), v3(0, 0, -100), 0.1f, u1, u2, &pdf), msg);
            TEST_ASSERT_TRUE_MESSAGE(isfinite(pdf) && pdf > 0.0f, msg);
            assert_unit(fogrt_sample_sphere_solid_angle(v3(0, 0, 0), v3(0, 0, 0.5f), 1.0f, u1, u2, &pdf), msg);
            TEST_ASSERT_TRUE_MESSAGE(isfinite(pdf) && pdf > 0.0f, msg);
            float b1 = -1.0f, b2 = -1.0f;
            fogrt_sample_triangle(u1, u2, &b1, &b2);
            TEST_ASSERT_TRUE_MESSAGE(b1 >= 0.0f && b2 >= 0.0f && b1 + b2 <= 1.0f, msg);
            float tdist = fogrt_sample_exponential(u1, 0.3f);
            TEST_ASSERT_TRUE_MESSAGE(isfinite(tdist) && tdist >= 0.0f, msg);
        }
    }
}

/* This program ran exactly the number of statistical tests that stats.h counts for it in
   the Sidak correction. Fails when a test is added or removed without updating
   STATS_TESTS_SAMPLING (or when an earlier test stopped before running all its cases). */
static void test_sidak_count_is_right(void)
{
    char msg[200];
    snprintf(msg, sizeof msg, "ran %d statistical tests, stats.h says STATS_TESTS_SAMPLING = %d (suite total %d, alpha' = %.3g)",
             *stats_test_counter(), STATS_TESTS_SAMPLING, STATS_SUITE_TESTS, stats_alpha());
    TEST_MESSAGE(msg);
    TEST_ASSERT_EQUAL_INT_MESSAGE(STATS_TESTS_SAMPLING, *stats_test_counter(), msg);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_hg_chi2_exact_cdf);
    RUN_TEST(test_hg_chi2_against_pdf);
    RUN_TEST(test_hg_mean_cosine_is_g);
    RUN_TEST(test_hg_sample_pdf_matches_eval);
    RUN_TEST(test_hg_phase_normalised);
    RUN_TEST(test_cosine_hemisphere_chi2);
    RUN_TEST(test_uniform_sphere_chi2);
    RUN_TEST(test_sphere_solid_angle_chi2);
    RUN_TEST(test_triangle_chi2);
    RUN_TEST(test_spot_light_radius_positions_chi2);
    RUN_TEST(test_spot_falloff_values);
    RUN_TEST(test_exponential_ks);
    RUN_TEST(test_exponential_pdf_and_inverse);
    RUN_TEST(test_pdfs_normalised);
    RUN_TEST(test_extreme_uniforms);
    RUN_TEST(test_sidak_count_is_right);
    return UNITY_END();
}
