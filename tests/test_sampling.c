/* test_sampling.c - do fogrt's samplers draw the distributions they claim?

   For each sampler: a chi-square goodness-of-fit test on a grid of cells (directions on the
   sphere, barycentric cells of a triangle or of every triangle of an emissive mesh), or a
   Kolmogorov-Smirnov test (free-flight and equiangular distances), each followed by a
   negative control: the same routine, the same samples, a deliberately wrong model, which
   must be rejected. Then the deterministic companions: moments, pdf normalisation by
   quadrature, sampler pdf = evaluated pdf, the values and distances lights return, an
   inverse-CDF sweep, spot falloff values, and extreme uniforms. tests/stats.h has the
   statistics; docs/testing.md explains how to read a failure. Fixed seeds: a given build
   always passes or always fails.                                                          */
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#include "unity.h"
#include "stats.h"
#ifndef FOGRT_MINIMAL
#include "footprint_case.h"   /* Part II's footprints (B) */
#endif
/* Under FOGRT_MINIMAL (Part I alone) a test of Part II skips with one line naming it. */
#define PART_II_ONLY(what) TEST_IGNORE_MESSAGE("needs Part II of fogrt.h (" what "): built with FOGRT_MINIMAL")

/* The private light samplers of fogrt.h (chapter 12) with their uniforms drawn here and the
   sample unpacked: the value (radiance / pdf for a point light, Le for an area light), the
   direction, the distance and the pdf. A failed sample is black with pdf 0. */
static fogrt_vec3 sample_point_light_(const fogrt_scene *s, const fogrt_light_desc *l, fogrt_vec3 x, float u1,
                                      float u2, fogrt_vec3 *wi, float *dist)
{
    float u[2];
    fogrt_light_sample ls;
    u[0] = u1; u[1] = u2;
    *wi = fogrt__v(0.0f, 0.0f, 0.0f); *dist = 0.0f;
    if (!fogrt__sample_point_light(s, l, x, u, &ls)) return fogrt__v(0.0f, 0.0f, 0.0f);
    *wi = ls.wi; *dist = ls.dist;
    return ls.Le;
}
static fogrt_vec3 sample_area_light_(const fogrt_scene *s, const fogrt__area_light *a, fogrt_vec3 p, fogrt_rng *rng,
                                     fogrt_vec3 *wi, float *dist, float *pdf)
{
    float u[3];
    fogrt_light_sample ls;
    u[0] = fogrt_rng_float(rng); u[1] = fogrt_rng_float(rng); u[2] = fogrt_rng_float(rng);
    *pdf = 0.0f;
    if (!fogrt__sample_area_light(s, a, p, u, &ls)) return fogrt__v(0.0f, 0.0f, 0.0f);
    *wi = ls.wi; *dist = ls.dist; *pdf = ls.pdf;
    return ls.Le;
}

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

/* TALLY_ASSERT and REPORT live in stats.h. */

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
    fogrt_vec3 wi = fogrt_sample_hg(a->g, a->wo, u1, u2, &pdf);
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
    return fogrt_hg_pdf(a->g, wo, wi);
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

/* ==========================================================================================
   Henyey-Greenstein at |g| >= 0.99: the peak, resolved
   ========================================================================================== */
/* P(angle to the peak < theta) for HG with |g| = a, the peak being d (g > 0) or -d (g < 0).
   Written with 1 - cos(theta) = 2 sin^2(theta / 2), so it is exact in double down to any
   angle: P = (1 + a) 2 s / (B (B + 1 - a)), s = sin^2(theta/2), B = sqrt((1 - a)^2 + 4 a s). */
static double hg_peak_cdf(double a, double theta)
{
    double s = sin(0.5 * theta), B;
    s *= s;
    B = sqrt((1.0 - a) * (1.0 - a) + 4.0 * a * s);
    return (1.0 + a) * 2.0 * s / (B * (B + 1.0 - a));
}

/* The textbook direction sample, as fogrt did before: mu from the inverse CDF, then
   sin(theta) = sqrt((1 - mu)(1 + mu)) in float. Near the peak mu rounds to 1 and the angle
   collapses to 0: the negative control of the peak test. */
static fogrt_vec3 hg_sample_textbook(float g, fogrt_vec3 wo, float u1, float u2)
{
    float mu = fogrt_sample_hg_mu(g, u1), s = sqrtf((1.0f - mu) * (1.0f + mu)), phi = 6.2831853f * u2;
    fogrt__frame f = fogrt__frame_from_z(fogrt__neg(wo));
    return fogrt__normalize(fogrt__to_world(&f, fogrt__v(s * cosf(phi), s * sinf(phi), mu)));
}

/* Rows: the angle to the peak, log-spaced from 1e-6 rad (cell 0: below it) to pi, so that the
   cells next to the peak are tiny; columns: 4 azimuth slices around the peak. Expected
   counts from the exact CDF above. The angle of a float direction w from the peak p is
   2 asin(|w - p| / 2), which keeps its precision at small angles. Fails if samples pile up
   on the peak direction (mu rounding to 1, sin(theta) = 0) or leave a hole around it. */
#define HG_PEAK_ROWS 40
#define HG_PEAK_COLS 4
static long hg_peak_counts(float g, fogrt_vec3 wo, bool textbook, long n, uint64_t seed, const double *edge,
                           double *observed)
{
    fogrt_rng rng;
    long invalid = 0;
    fogrt_vec3 d = fogrt__normalize(fogrt__neg(wo)), p = g > 0.0f ? d : fogrt__neg(d);
    fogrt__frame f = fogrt__frame_from_z(p);
    fogrt_rng_seed(&rng, seed, 3);
    memset(observed, 0, sizeof(double) * HG_PEAK_ROWS * HG_PEAK_COLS);
    for (long i = 0; i < n; i++) {
        float u1 = fogrt_rng_float(&rng), u2 = fogrt_rng_float(&rng), pdf;
        fogrt_vec3 w = textbook ? hg_sample_textbook(g, wo, u1, u2) : fogrt_sample_hg(g, wo, u1, u2, &pdf);
        double dx = (double)w.x - p.x, dy = (double)w.y - p.y, dz = (double)w.z - p.z;
        double theta = 2.0 * asin(fmin(1.0, 0.5 * sqrt(dx * dx + dy * dy + dz * dz)));
        double phi = atan2(fogrt__dot(w, f.t), fogrt__dot(w, f.s)) + STATS_PI;
        int row = 0, col = (int)(phi / (2.0 * STATS_PI) * HG_PEAK_COLS);
        if (!isfinite(theta) || !(fabs(fogrt__dot(w, w) - 1.0f) < 1e-5f)) { invalid++; continue; }
        while (row < HG_PEAK_ROWS - 1 && theta >= edge[row + 1]) row++;
        observed[row * HG_PEAK_COLS + (col < HG_PEAK_COLS ? col : HG_PEAK_COLS - 1)] += 1.0;
    }
    return invalid;
}
static void test_hg_peak_resolved(void)
{
    static const float gs[4] = {0.99f, -0.99f, 0.999f, -0.999f};
    static const int wos[3] = {0, 2, 3};                  /* +z, x axis, a generic direction */
    double edge[HG_PEAK_ROWS + 1], col_edge[HG_PEAK_COLS + 1], observed[HG_PEAK_ROWS * HG_PEAK_COLS],
           expected[HG_PEAK_ROWS * HG_PEAK_COLS];
    stats_tally t = {0, 0, ""};
    const long n = 400000;
    edge[0] = 0.0;
    for (int r = 1; r < HG_PEAK_ROWS; r++) edge[r] = 1e-6 * pow(STATS_PI / 1e-6, (r - 1.0) / (HG_PEAK_ROWS - 1.0));
    edge[HG_PEAK_ROWS] = STATS_PI;
    for (int c = 0; c <= HG_PEAK_COLS; c++) col_edge[c] = -STATS_PI + 2.0 * STATS_PI * c / HG_PEAK_COLS;
    for (int k = 0; k < 4; k++) {
        double a = fabs((double)gs[k]);
        for (int r = 0; r < HG_PEAK_ROWS; r++)
            for (int c = 0; c < HG_PEAK_COLS; c++)
                expected[r * HG_PEAK_COLS + c] = (double)n * (hg_peak_cdf(a, edge[r + 1]) - hg_peak_cdf(a, edge[r])) / HG_PEAK_COLS;
        for (int w = 0; w < 3; w++) {
            fogrt_vec3 wo = v3(HG_WO[wos[w]][0], HG_WO[wos[w]][1], HG_WO[wos[w]][2]);
            char name[64], param[128];
            long invalid = hg_peak_counts(gs[k], wo, false, n, 4100 + (uint64_t)(10 * k + w), edge, observed);
            snprintf(name, sizeof name, "hg_peak_g%g_wo%d", (double)gs[k], wos[w]);
            snprintf(param, sizeof param, "g=%g, wo=(%g,%g,%g), angle to the peak log-spaced from 1e-6 rad",
                     (double)gs[k], (double)wo.x, (double)wo.y, (double)wo.z);
            REPORT(t, stats_chi2_verdict(name, "fogrt_sample_hg near its peak", param, HG_PEAK_ROWS, HG_PEAK_COLS,
                                         edge, "angle to peak", col_edge, "phi", observed, expected, invalid, false));
            if (w == 0 && a < 0.995) {   /* negative control: sin(theta) from a rounded mu */
                invalid = hg_peak_counts(gs[k], wo, true, n, 4100 + (uint64_t)(10 * k + w), edge, observed);
                snprintf(param, sizeof param, "g=%g, textbook sin(theta) = sqrt((1-mu)(1+mu)) in float", (double)gs[k]);
                REPORT(t, stats_chi2_verdict(name, "HG direction with a rounded mu", param, HG_PEAK_ROWS, HG_PEAK_COLS,
                                             edge, "angle to peak", col_edge, "phi", observed, expected, invalid, true));
            }
        }
    }
    TALLY_ASSERT(t);
}

/* ==========================================================================================
   The glow around a lamp (fogrt_sample_glow): the angle to the lamp, resolved to 1e-6 rad
   ========================================================================================== */
/* P(alpha' < alpha) for the density (pi - alpha) / (pi^3 sin alpha): 1 - (pi - alpha)^2 / pi^2,
   written as alpha (2 pi - alpha) / pi^2 so it keeps its digits at small angles. */
#ifndef FOGRT_MINIMAL   /* helpers of Part II's test below */
static double glow_cdf(double alpha) { return alpha * (2.0 * STATS_PI - alpha) / (STATS_PI * STATS_PI); }
static double glow_wrong_cdf(double alpha) { return alpha / STATS_PI; }   /* uniform in alpha */
/* Counts of the angle to the lamp direction p (log-spaced rows as in the HG peak test) and 4
   azimuth slices; also counts the samples whose returned pdf differs from fogrt_glow_pdf and
   from the density at the sample's angle (computed in double) by more than 1e-3. */
static long glow_counts(fogrt_vec3 p, long n, uint64_t seed, const double *edge, double *observed, long *bad_pdf)
{
    fogrt_rng rng;
    long invalid = 0;
    fogrt__frame f = fogrt__frame_from_z(p);
    fogrt_rng_seed(&rng, seed, 5);
    memset(observed, 0, sizeof(double) * HG_PEAK_ROWS * HG_PEAK_COLS);
    *bad_pdf = 0;
    for (long i = 0; i < n; i++) {
        float u1 = fogrt_rng_float(&rng), u2 = fogrt_rng_float(&rng), pdf;
        fogrt_vec3 w = fogrt_sample_glow(p, u1, u2, &pdf);
        double dx = (double)w.x - p.x, dy = (double)w.y - p.y, dz = (double)w.z - p.z;
        double alpha = 2.0 * asin(fmin(1.0, 0.5 * sqrt(dx * dx + dy * dy + dz * dz)));
        double phi = atan2(fogrt__dot(w, f.t), fogrt__dot(w, f.s)) + STATS_PI, want;
        int row = 0, col = (int)(phi / (2.0 * STATS_PI) * HG_PEAK_COLS);
        if (!isfinite(alpha) || !(fabs(fogrt__dot(w, w) - 1.0f) < 1e-5f) || !(pdf > 0.0f) || !isfinite(pdf)) { invalid++; continue; }
        want = alpha > 1e-3 ? (STATS_PI - alpha) / (STATS_PI * STATS_PI * STATS_PI * sin(alpha)) : 0.0;
        if (alpha > 1e-3 && alpha < STATS_PI - 1e-3 &&
            (fabs(pdf - want) > 1e-3 * want || fabs(fogrt_glow_pdf(p, w) - want) > 1e-3 * want)) (*bad_pdf)++;
        while (row < HG_PEAK_ROWS - 1 && alpha >= edge[row + 1]) row++;
        observed[row * HG_PEAK_COLS + (col < HG_PEAK_COLS ? col : HG_PEAK_COLS - 1)] += 1.0;
    }
    return invalid;
}
static double glow_pdf_1d(double alpha, void *user)
{
    fogrt_vec3 p = *(const fogrt_vec3 *)user;
    fogrt__frame f = fogrt__frame_from_z(p);
    fogrt_vec3 w = fogrt__to_world(&f, v3((float)sin(alpha), 0.0f, (float)cos(alpha)));
    return 2.0 * STATS_PI * sin(alpha) * fogrt_glow_pdf(p, w);
}
#endif
/* fogrt_sample_glow: the angle to the lamp follows the glow's CDF from 1e-6 rad to pi, the
   azimuth is uniform, the pdf it returns is fogrt_glow_pdf and the closed form, and
   fogrt_glow_pdf integrates to 1. Negative control: the same samples against a density
   uniform in the angle (the sin alpha Jacobian left out), which must be rejected. */
static void test_glow_sampling(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("B: the glow of a lamp");
#else
    static const float dirs[2][3] = {{0.0f, 0.0f, 1.0f}, {0.48f, -0.6f, 0.64f}};
    double edge[HG_PEAK_ROWS + 1], col_edge[HG_PEAK_COLS + 1], observed[HG_PEAK_ROWS * HG_PEAK_COLS],
           expected[HG_PEAK_ROWS * HG_PEAK_COLS], wrong[HG_PEAK_ROWS * HG_PEAK_COLS];
    stats_tally t = {0, 0, ""};
    const long n = 400000;
    char msg[160];
    edge[0] = 0.0;
    for (int r = 1; r < HG_PEAK_ROWS; r++) edge[r] = 1e-6 * pow(STATS_PI / 1e-6, (r - 1.0) / (HG_PEAK_ROWS - 1.0));
    edge[HG_PEAK_ROWS] = STATS_PI;
    for (int c = 0; c <= HG_PEAK_COLS; c++) col_edge[c] = -STATS_PI + 2.0 * STATS_PI * c / HG_PEAK_COLS;
    for (int r = 0; r < HG_PEAK_ROWS; r++)
        for (int c = 0; c < HG_PEAK_COLS; c++) {
            expected[r * HG_PEAK_COLS + c] = (double)n * (glow_cdf(edge[r + 1]) - glow_cdf(edge[r])) / HG_PEAK_COLS;
            wrong[r * HG_PEAK_COLS + c] = (double)n * (glow_wrong_cdf(edge[r + 1]) - glow_wrong_cdf(edge[r])) / HG_PEAK_COLS;
        }
    for (int k = 0; k < 2; k++) {
        fogrt_vec3 p = v3(dirs[k][0], dirs[k][1], dirs[k][2]);
        long bad_pdf, invalid = glow_counts(p, n, 4200 + (uint64_t)k, edge, observed, &bad_pdf);
        /* below 1e-6 rad: 6e-7 of the mass; the tolerance 1e-8, 1e4 times under the check's,
           gives the same integral to 7 digits as 1e-9 did, at a twentieth of its cost */
        double integral = stats_integrate_1d(glow_pdf_1d, &p, 1e-6, STATS_PI, 1e-8, 40);
        char name[64], param[128];
        snprintf(name, sizeof name, "glow_dir%d", k);
        snprintf(param, sizeof param, "to_light=(%g,%g,%g), angle log-spaced from 1e-6 rad", (double)p.x, (double)p.y, (double)p.z);
        REPORT(t, stats_chi2_verdict(name, "fogrt_sample_glow", param, HG_PEAK_ROWS, HG_PEAK_COLS, edge, "angle to lamp",
                                     col_edge, "phi", observed, expected, invalid, false));
        if (k == 0)
            REPORT(t, stats_chi2_verdict(name, "fogrt_sample_glow", "against a density uniform in the angle (wrong)",
                                         HG_PEAK_ROWS, HG_PEAK_COLS, edge, "angle to lamp", col_edge, "phi", observed,
                                         wrong, invalid, true));
        snprintf(msg, sizeof msg, "glow %d: %ld of %ld samples with a pdf off the closed form; integral of the pdf %.7f",
                 k, bad_pdf, n, integral);
        TEST_MESSAGE(msg);
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, (int)bad_pdf, msg);
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-4, 1.0, integral, msg);
    }
    TALLY_ASSERT(t);
#endif
}

/* ==========================================================================================
   The phase function per unit angle (chapter 5's table): equiangular sampling with HG and
   the glow with HG, against CDFs integrated independently on a fine grid
   ========================================================================================== */
#define HGF_N 40000
typedef struct hg_fine { double g, c[HGF_N + 1]; } hg_fine;   /* int_0^psi HG(cos x) dx, psi = pi i / N */
#ifndef FOGRT_MINIMAL   /* helpers of Part II's test below */
static double hg_angle_ref(double g, double psi)
{
    double base = 1.0 + g * g - 2.0 * g * cos(psi);
    return (1.0 - g * g) / (4.0 * STATS_PI * base * sqrt(base));
}
static void hg_fine_build(hg_fine *f, double g)
{
    f->g = g;
    f->c[0] = 0.0;
    for (int i = 0; i < HGF_N; i++) {   /* Simpson per cell */
        double a = STATS_PI * i / HGF_N, b = STATS_PI * (i + 1) / HGF_N;
        f->c[i + 1] = f->c[i] + (b - a) / 6.0 * (hg_angle_ref(g, a) + 4.0 * hg_angle_ref(g, 0.5 * (a + b)) + hg_angle_ref(g, b));
    }
}
static double hg_fine_at(const hg_fine *f, double psi)   /* linear between grid points */
{
    double x = fmin(fmax(psi, 0.0), STATS_PI) / STATS_PI * HGF_N;
    int i = (int)fmin(x, HGF_N - 1.0);
    return f->c[i] + (f->c[i + 1] - f->c[i]) * (x - i);
}
typedef struct eqhg_model { const hg_fine *f; double delta, h, a, b, ca, cb; bool plain; } eqhg_model;
static double eqhg_psi(const eqhg_model *m, double t) { return isinf(t) ? STATS_PI : atan2(t - m->delta, m->h) + 0.5 * STATS_PI; }
static double eqhg_cdf(double t, void *user)
{
    const eqhg_model *m = (const eqhg_model *)user;
    if (t <= m->a) return 0.0;
    if (t >= m->b) return 1.0;
    if (m->plain) return (eqhg_psi(m, t) - eqhg_psi(m, m->a)) / (eqhg_psi(m, m->b) - eqhg_psi(m, m->a));
    return (hg_fine_at(m->f, eqhg_psi(m, t)) - m->ca) / (m->cb - m->ca);
}
#endif
/* fogrt__sample_equiangular_hg draws t with density proportional to HG(mu(t)) / r(t)^2 (the
   single-scattering integrand of a point light): KS against the CDF integrated on a
   40000-point grid, for g = 0.6, 0.95 and -0.7, a light over the segment and an escaping
   ray; the pdf it returns is within 3% of that density (the table's resolution: the weight
   HG / (r^2 pdf) stays nearly constant) and integrates to 1. Negative control: g = 0.6 samples
   against plain equiangular (the phase function left out). */
static void test_equiangular_hg_ks(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("B: equiangular sampling with HG");
#else
    static const float gs[3] = {0.6f, 0.95f, -0.7f};
    static const float seg[2][4] = {{1.0f, 0.5f, 0.0f, 3.0f}, {-0.5f, 0.2f, 0.0f, INFINITY}};   /* delta, h, a, b */
    stats_tally t = {0, 0, ""};
    enum { N = 200000 };
    double *x = (double *)malloc(sizeof(double) * N);
    hg_fine *f = (hg_fine *)malloc(sizeof *f);
    fogrt__hg_table *T = (fogrt__hg_table *)malloc(sizeof *T);
    char msg[300];
    TEST_ASSERT_TRUE(x && f && T);
    for (int k = 0; k < 3; k++) {
        fogrt__hg_table_build(T, gs[k]);
        hg_fine_build(f, gs[k]);
        for (int c = 0; c < 2; c++) {
            eqhg_model m = {f, seg[c][0], seg[c][1], seg[c][2], seg[c][3], 0, 0, false};
            fogrt_rng rng;
            long invalid = 0, bad_pdf = 0;
            double worst = 0.0;
            m.ca = hg_fine_at(f, eqhg_psi(&m, m.a)); m.cb = hg_fine_at(f, eqhg_psi(&m, m.b));
            fogrt_rng_seed(&rng, 12000 + (uint64_t)(10 * k + c), 9);
            for (int i = 0; i < N; i++) {
                float pdf = -1.0f, u = fogrt_rng_float(&rng);
                float s = fogrt__sample_equiangular_hg(T, seg[c][0], seg[c][1], seg[c][2], seg[c][3], u, &pdf);
                double dt = (double)s - m.delta, r2 = m.h * m.h + dt * dt, want;
                x[i] = s;
                if (!isfinite(s) || !(s >= m.a && s <= m.b) || !(pdf > 0.0f) || !isfinite(pdf)) { invalid++; continue; }
                want = hg_angle_ref(gs[k], eqhg_psi(&m, s)) * m.h / (r2 * (m.cb - m.ca));
                worst = fmax(worst, fabs(pdf / want - 1.0));
                if (fabs(pdf / want - 1.0) > 0.03) bad_pdf++;
            }
            stats_ks_result r = stats_ks(x, N, eqhg_cdf, &m);
            char name[64], param[128];
            snprintf(name, sizeof name, "equiangular_hg_g%g_%d", (double)gs[k], c);
            snprintf(param, sizeof param, "g=%g, delta=%g, h=%g, [%g, %g]", (double)gs[k], m.delta, m.h, m.a, m.b);
            REPORT(t, stats_ks_verdict(name, "fogrt__sample_equiangular_hg", param, &r, x, eqhg_cdf, &m, invalid, false));
            if (k == 0 && c == 0) {
                m.plain = true;
                r = stats_ks(x, N, eqhg_cdf, &m);
                REPORT(t, stats_ks_verdict(name, "fogrt__sample_equiangular_hg", "against plain equiangular (no phase)",
                                           &r, x, eqhg_cdf, &m, invalid, true));
            }
            snprintf(msg, sizeof msg, "%s: %ld of %d pdfs more than 3%% off HG / r^2 (worst %.4f)", name, bad_pdf, N, worst);
            TEST_MESSAGE(msg);
            TEST_ASSERT_EQUAL_INT_MESSAGE(0, (int)bad_pdf, msg);
        }
    }
    free(x); free(f); free(T);
    TALLY_ASSERT(t);
#endif
}
/* The glow with HG: the angle to the lamp has density G(alpha) = int_alpha^pi HG(cos x) dx
   (up to the table's bin averages): chi-square on the glow rows against the CDF of G from
   the fine grid, for g = 0.6 and -0.5; fogrt__glow_hg_pdf integrates to 1 over the sphere. */
typedef struct glowhg_args { const hg_fine *f; double z; } glowhg_args;
#ifndef FOGRT_MINIMAL   /* helpers of Part II's test below */
static double glowhg_cdf(const glowhg_args *a, double alpha)   /* int_0^alpha G / int_0^pi G */
{
    double sum = 0.0, top = a->f->c[HGF_N];
    int n = (int)fmin(HGF_N, ceil(alpha / STATS_PI * HGF_N));
    for (int i = 0; i < n; i++) {
        double x0 = STATS_PI * i / HGF_N, x1 = fmin(alpha, STATS_PI * (i + 1) / HGF_N);
        sum += (top - 0.5 * (hg_fine_at(a->f, x0) + hg_fine_at(a->f, x1))) * (x1 - x0);
    }
    return sum / a->z;
}
typedef struct glowhg_pdf_args { const fogrt__hg_table *T; fogrt_vec3 p; } glowhg_pdf_args;
static double glowhg_pdf_1d(double alpha, void *user)
{
    const glowhg_pdf_args *a = (const glowhg_pdf_args *)user;
    fogrt__frame fr = fogrt__frame_from_z(a->p);
    fogrt_vec3 w = fogrt__to_world(&fr, v3((float)sin(alpha), 0.0f, (float)cos(alpha)));
    return 2.0 * STATS_PI * sin(alpha) * fogrt__glow_hg_pdf(a->T, a->p, w);
}
/* The integral of f over [a, b] by 4-point Gauss-Legendre on each piece between the table's
   edges. fogrt__glow_hg_pdf is constant per unit alpha inside each of the table's bins
   (G averaged per bin, turned per steradian by 1 / sin alpha, which the 2 pi sin alpha of
   the integrand undoes) and jumps at the edges, so on the pieces the rule is exact up to the
   float rounding of the direction (a few 1e-7 of the pdf, far below the check's 2e-4): one
   evaluation at a node inside a bin sees that bin's density, a wrong bin or a wrong
   normalisation shows in full, and 4 nodes see any variation inside a bin that a wrong sin
   alpha would make. No node lies on an end, so the whole of (0, pi) is integrated. In real
   numbers the integral is 2 pi k_norm K(pi) = 1; this gives 1.0000001 (g = 0.6) and
   1.0000000 (g = -0.5) from 4096 calls. (Adaptive Simpson, which knows nothing of the
   edges, took hundreds of millions of calls at tolerance 1e-9 on [1e-6, pi - 1e-6] and
   still left 5e-5 at the jumps.) */
static double integrate_on_edges(stats_fn1 f, void *user, const double *edges, int n_edges, double a, double b)
{
    static const double node[4] = {-0.86113631159405258, -0.33998104358485626, 0.33998104358485626, 0.86113631159405258};
    static const double weight[4] = {0.34785484513745386, 0.65214515486254614, 0.65214515486254614, 0.34785484513745386};
    double sum = 0.0, x0 = a;
    int i = 0, q;
    while (x0 < b) {
        double x1, mid, half;
        while (i < n_edges && edges[i] <= x0) i++;
        x1 = i < n_edges && edges[i] < b ? edges[i] : b;
        mid = 0.5 * (x0 + x1); half = 0.5 * (x1 - x0);
        for (q = 0; q < 4; q++) sum += half * weight[q] * f(mid + half * node[q], user);
        x0 = x1;
    }
    return sum;
}
#endif
static void test_glow_hg_sampling(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("B: the glow with HG");
#else
    static const float gs[2] = {0.6f, -0.5f};
    double edge[HG_PEAK_ROWS + 1], col_edge[HG_PEAK_COLS + 1], observed[HG_PEAK_ROWS * HG_PEAK_COLS],
           expected[HG_PEAK_ROWS * HG_PEAK_COLS], cdf_edge[HG_PEAK_ROWS + 1];
    stats_tally t = {0, 0, ""};
    const long n = 300000;
    hg_fine *f = (hg_fine *)malloc(sizeof *f);
    fogrt__hg_table *T = (fogrt__hg_table *)malloc(sizeof *T);
    fogrt_vec3 p = v3(0.48f, -0.6f, 0.64f);
    TEST_ASSERT_TRUE(f && T);
    edge[0] = 0.0;
    for (int r = 1; r < HG_PEAK_ROWS; r++) edge[r] = 1e-5 * pow(STATS_PI / 1e-5, (r - 1.0) / (HG_PEAK_ROWS - 1.0));
    edge[HG_PEAK_ROWS] = STATS_PI;
    for (int c = 0; c <= HG_PEAK_COLS; c++) col_edge[c] = -STATS_PI + 2.0 * STATS_PI * c / HG_PEAK_COLS;
    for (int k = 0; k < 2; k++) {
        glowhg_args a;
        glowhg_pdf_args pa;
        fogrt_rng rng;
        fogrt__frame fr = fogrt__frame_from_z(p);
        long invalid = 0, pdf_off = 0;
        double worst = 0.0;
        char name[64], param[128], msg[160];
        fogrt__hg_table_build(T, gs[k]);
        hg_fine_build(f, gs[k]);
        a.f = f; a.z = 1.0;
        a.z = glowhg_cdf(&a, STATS_PI);
        for (int r = 0; r <= HG_PEAK_ROWS; r++) cdf_edge[r] = glowhg_cdf(&a, edge[r]);
        for (int r = 0; r < HG_PEAK_ROWS; r++)
            for (int c = 0; c < HG_PEAK_COLS; c++) expected[r * HG_PEAK_COLS + c] = (double)n * (cdf_edge[r + 1] - cdf_edge[r]) / HG_PEAK_COLS;
        memset(observed, 0, sizeof observed);
        fogrt_rng_seed(&rng, 4300 + (uint64_t)k, 5);
        for (long i = 0; i < n; i++) {
            float u1 = fogrt_rng_float(&rng), u2 = fogrt_rng_float(&rng);
            float pdf_drawn, pdf_eval;
            fogrt_vec3 w = fogrt__sample_glow_hg(T, p, u1, u2, &pdf_drawn);
            double dx = (double)w.x - p.x, dy = (double)w.y - p.y, dz = (double)w.z - p.z;
            double alpha = 2.0 * asin(fmin(1.0, 0.5 * sqrt(dx * dx + dy * dy + dz * dz)));
            double phi = atan2(fogrt__dot(w, fr.t), fogrt__dot(w, fr.s)) + STATS_PI;
            int row = 0, col = (int)(phi / (2.0 * STATS_PI) * HG_PEAK_COLS);
            if (!isfinite(alpha) || !(fabs(fogrt__dot(w, w) - 1.0f) < 1e-5f)) { invalid++; continue; }
            /* the density it returns is the one fogrt__glow_hg_pdf finds at the direction,
               where a float direction holds the angle (from 1e-3 rad: to 1e-4 of it; at an
               edge of the table the direction may still fall in the next bin) */
            pdf_eval = fogrt__glow_hg_pdf(T, p, w);
            if (alpha < 1e-3) { if (!(pdf_drawn > 0.0f)) pdf_off++; }
            else if (!(pdf_drawn > 0.0f) || !(fabs(pdf_drawn / pdf_eval - 1.0) < 0.05)) pdf_off++;
            else worst = fmax(worst, fabs(pdf_drawn / pdf_eval - 1.0));
            while (row < HG_PEAK_ROWS - 1 && alpha >= edge[row + 1]) row++;
            observed[row * HG_PEAK_COLS + (col < HG_PEAK_COLS ? col : HG_PEAK_COLS - 1)] += 1.0;
        }
        snprintf(name, sizeof name, "glow_hg_g%g", (double)gs[k]);
        snprintf(param, sizeof param, "g=%g, to_light=(%g,%g,%g)", (double)gs[k], (double)p.x, (double)p.y, (double)p.z);
        REPORT(t, stats_chi2_verdict(name, "fogrt__sample_glow_hg", param, HG_PEAK_ROWS, HG_PEAK_COLS, edge, "angle to lamp",
                                     col_edge, "phi", observed, expected, invalid, false));
        snprintf(msg, sizeof msg, "glow_hg g=%g: drawn pdf against fogrt__glow_hg_pdf: %ld off by 5%% or more, else at most %.2e",
                 (double)gs[k], pdf_off, worst);
        TEST_MESSAGE(msg);
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, (int)pdf_off, msg);
        pa.T = T; pa.p = p;
        double integral = integrate_on_edges(glowhg_pdf_1d, &pa, T->edge, FOGRT__HGT_N + 1, 0.0, STATS_PI);
        snprintf(msg, sizeof msg, "glow_hg g=%g: the pdf integrates to %.7f", (double)gs[k], integral);
        TEST_MESSAGE(msg);
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(2e-4, 1.0, integral, msg);
    }
    free(f); free(T);
    TALLY_ASSERT(t);
#endif
}

/* ==========================================================================================
   The footprint of a spot light on a plane (chapter 6, aimed at by 14 d')
   ========================================================================================== */
/* footprint_case(): tests/footprint_case.h, shared with the Mitsuba harness's shim */
/* The sampler's map (u1, u2) -> wi, in double for the finite differences below (central,
   step h): the density it gives per steradian is 1 / |dwi/du1 x dwi/du2|. */
#ifndef FOGRT_MINIMAL   /* helpers of Part II's test below */
static double footprint_jacobian_pdf(const fogrt__footprint *F, fogrt_vec3 x, float u1, float u2, double h)
{
    double d[2][3];
    int a;
    for (a = 0; a < 2; ++a) {
        fogrt_vec3 lo, hi;
        float du = (float)h;
        bool ok = a == 0 ? fogrt__sample_footprint_cone(F, x, u1 - du, u2, &lo) && fogrt__sample_footprint_cone(F, x, u1 + du, u2, &hi)
                         : fogrt__sample_footprint_cone(F, x, u1, u2 - du, &lo) && fogrt__sample_footprint_cone(F, x, u1, u2 + du, &hi);
        if (!ok) return -1.0;
        d[a][0] = ((double)hi.x - lo.x) / (2.0 * du); d[a][1] = ((double)hi.y - lo.y) / (2.0 * du); d[a][2] = ((double)hi.z - lo.z) / (2.0 * du);
    }
    {
        double cx = d[0][1] * d[1][2] - d[0][2] * d[1][1], cy = d[0][2] * d[1][0] - d[0][0] * d[1][2], cz = d[0][0] * d[1][1] - d[0][1] * d[1][0];
        return 1.0 / sqrt(cx * cx + cy * cy + cz * cz);
    }
}
#endif
/* fogrt__sample_footprint_cone and fogrt__footprint_cone_pdf (chapter 6: the footprint through the lamp's cone) for that lamp, seen from a
   point in the fog above the floor and from one below it:
   - the cone direction behind each direction drawn (from the point where it meets the
     floor back to the lamp) is uniform in the cone: chi-square on 10 x 20 cells of
     (cos theta, phi) around the axis, whose expected counts are exact; negative control: a
     cone uniform in theta instead of cos theta, which must be rejected;
   - fogrt__footprint_cone_pdf at 2000 directions drawn is the density of the sampler's map,
     1 / |dwi/du1 x dwi/du2| by finite differences, to 1%; negative control: the same
     without the turn from area on the floor to solid angle at x (|y - x|^2 / cos_x), off
     by more than 10% at most of them. The cone's edge, where the density jumps, never
     enters a cell's expected count (a sphere grid's quadrature would miss its slivers). */
static void test_footprint_sampling(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("B: the footprint of a lamp");
#else
    enum { ROWS = 10, COLS = 20 };
    static const float xs[2][3] = {{0.3f, 0.5f, 0.2f}, {-0.4f, -0.3f, 0.1f}};
    const fogrt__footprint F = footprint_case();
    const double cos_c = 1.0 - (double)F.one_minus_cos;
    stats_tally t = {0, 0, ""};
    double row_edge[ROWS + 1], col_edge[COLS + 1], observed[ROWS * COLS], expected[ROWS * COLS], wrong[ROWS * COLS];
    int k, i, j;
    for (i = 0; i <= ROWS; ++i) row_edge[i] = cos_c + (1.0 - cos_c) * i / ROWS;
    for (j = 0; j <= COLS; ++j) col_edge[j] = -STATS_PI + 2.0 * STATS_PI * j / COLS;
    for (i = 0; i < ROWS; ++i) {
        double th0 = acos(row_edge[i + 1]), th1 = acos(row_edge[i]), thc = acos(cos_c);
        for (j = 0; j < COLS; ++j) wrong[i * COLS + j] = (th1 - th0) / thc / COLS;
    }
    for (k = 0; k < 2; ++k) {
        const fogrt_vec3 x = v3(xs[k][0], xs[k][1], xs[k][2]);
        const long n = 200000;
        long invalid = 0, bad_pdf = 0, wrong_ok = 0, checked = 0;
        double worst = 0.0;
        char param[96], msg[256];
        fogrt_rng rng;
        fogrt_rng_seed(&rng, 9100 + (uint64_t)k, 3);
        memset(observed, 0, sizeof observed);
        for (long m = 0; m < n; ++m) {
            float u1 = fogrt_rng_float(&rng), u2 = fogrt_rng_float(&rng);
            fogrt_vec3 wi, y, ly;
            double dn, tt, len, ct, phi;
            int r, c;
            if (!fogrt__sample_footprint_cone(&F, x, u1, u2, &wi)) { invalid++; continue; }
            dn = fogrt__dot(wi, F.n);
            tt = (double)fogrt__dot(fogrt__sub(F.p, x), F.n) / dn;
            y = fogrt__madd(x, wi, (float)tt);
            ly = fogrt__sub(y, F.light);
            len = sqrt((double)fogrt__dot(ly, ly));
            ct = fogrt__dot(ly, F.cone.n) / len;
            phi = atan2((double)fogrt__dot(ly, F.cone.t), (double)fogrt__dot(ly, F.cone.s));
            r = (int)floor((ct - cos_c) / (1.0 - cos_c) * ROWS); c = (int)floor((phi + STATS_PI) / (2.0 * STATS_PI) * COLS);
            if (!(tt > 0.0) || r < -1 || r > ROWS || c < 0 || c > COLS) { invalid++; continue; }
            r = r < 0 ? 0 : (r >= ROWS ? ROWS - 1 : r); c = c >= COLS ? COLS - 1 : c;   /* float rounding at the edges */
            observed[r * COLS + c] += 1.0;
            if (m % 100 == 0 && u1 > 0.01f && u1 < 0.99f) {       /* the pdf against the map's density */
                double want = footprint_jacobian_pdf(&F, x, u1, u2, 1e-3), got = fogrt__footprint_cone_pdf(&F, x, wi);
                double area = got * fabs(dn) / (tt * tt);          /* the model without the turn */
                if (want > 0.0) {
                    double e = fabs(got / want - 1.0);
                    checked++;
                    if (e > worst) worst = e;
                    if (e > 0.01) bad_pdf++;
                    if (fabs(area / want - 1.0) <= 0.1) wrong_ok++;
                }
            }
        }
        for (i = 0; i < ROWS * COLS; ++i) expected[i] = (double)n / (ROWS * COLS);
        snprintf(param, sizeof param, "30-degree spot over a floor, x = (%g, %g, %g)", (double)xs[k][0], (double)xs[k][1], (double)xs[k][2]);
        REPORT(t, stats_chi2_verdict("footprint", "cone direction behind fogrt__sample_footprint_cone", param, ROWS, COLS, row_edge,
                                     "cos theta", col_edge, "phi", observed, expected, invalid, false));
        for (i = 0; i < ROWS * COLS; ++i) expected[i] = (double)n * wrong[i];
        REPORT(t, stats_chi2_verdict("footprint", "cone direction behind fogrt__sample_footprint_cone", "model uniform in theta",
                                     ROWS, COLS, row_edge, "cos theta", col_edge, "phi", observed, expected, invalid, true));
        snprintf(msg, sizeof msg, "footprint x = (%g, %g, %g): fogrt__footprint_cone_pdf against the map's density at %ld directions: "
                 "%ld off by 1%% or more (worst %.2e); the area model within 10%% at %ld", (double)xs[k][0], (double)xs[k][1],
                 (double)xs[k][2], checked, bad_pdf, worst, wrong_ok);
        TEST_MESSAGE(msg);
        TEST_ASSERT_TRUE_MESSAGE(checked >= 1500 && bad_pdf == 0, msg);
        TEST_ASSERT_TRUE_MESSAGE(wrong_ok < checked / 2, msg);
    }
    TALLY_ASSERT(t);
#endif
}

/* The footprint's second way (chapter 6): from a point outside the sphere around the lit
   patch, half the directions are uniform in the cone the sphere subtends, half go through
   the lamp's cone as above, and fogrt__footprint_pdf is that mixture's density. If it is,
   then over the directions drawn (a failed draw counts as 0), h(wi) / pdf(wi) has the mean
   of the integral of h over the directions it can draw; for h = 1 and h = cos to the axis,
   both inside the sphere's cone, that is 2 pi omc and pi omc (2 - omc). Checked to 4.5
   standard errors at 400000 draws from two points; negative controls: the density
   without the lamp's-cone part (a mixture that forgets a component) and with the two
   shares swapped the other way (0.3 / 0.7) must both miss. The build's bound holds every
   rim point. */
#ifndef FOGRT_MINIMAL   /* helpers of Part II's test below */
static void footprint_mixture_means(const fogrt__footprint *F, fogrt_vec3 x, int which, double *mean, double *se,
                                    double *target, uint64_t seed)
{
    /* which: 0 the header's density, 1 without the cone part, 2 shares 0.3 / 0.7 */
    const long n = 400000;
    fogrt_vec3 axis;
    float omc;
    double s1 = 0.0, s2 = 0.0, c1 = 0.0, c2 = 0.0;
    fogrt_rng rng;
    long m;
    TEST_ASSERT_TRUE(fogrt__footprint_sphere(F, x, &axis, &omc));
    fogrt_rng_seed(&rng, seed, 5);
    for (m = 0; m < n; ++m) {
        float u1 = fogrt_rng_float(&rng), u2 = fogrt_rng_float(&rng), pdf;
        fogrt_vec3 wi, chord;
        double h, hc;
        if (!fogrt__sample_footprint(F, x, u1, u2, &wi)) continue;
        chord = fogrt__sub(wi, axis);
        if (!(0.5f * fogrt__dot(chord, chord) <= omc)) continue;      /* h = 0 outside the sphere's cone */
        pdf = fogrt__footprint_pdf(F, x, wi);
        if (which == 1) pdf = FOGRT__FOOTPRINT_CAP / (2.0f * FOGRT__PI * omc);
        if (which == 2) pdf = 0.3f / (2.0f * FOGRT__PI * omc) + 0.7f * fogrt__footprint_cone_pdf(F, x, wi);
        TEST_ASSERT_TRUE(pdf > 0.0f);
        h = 1.0 / pdf; hc = (double)fogrt__dot(axis, wi) / pdf;
        s1 += h; s2 += h * h; c1 += hc; c2 += hc * hc;
    }
    mean[0] = s1 / n; se[0] = sqrt(fmax(s2 / n - mean[0] * mean[0], 0.0) / n);   /* 0: 1/pdf constant (a control) */
    mean[1] = c1 / n; se[1] = sqrt(fmax(c2 / n - mean[1] * mean[1], 0.0) / n);
    target[0] = 2.0 * STATS_PI * omc;
    target[1] = STATS_PI * omc * (2.0 - (double)omc);
}
#endif
static void test_footprint_mixture(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("B: the footprint of a lamp");
#else
    static const float xs[2][3] = {{-1.2f, 1.1f, 1.0f}, {1.6f, 0.4f, -0.3f}};
    fogrt__footprint F = footprint_case();
    int k, j, which;
    char msg[256];
    fogrt__footprint_bound(&F);
    TEST_ASSERT_TRUE_MESSAGE(F.radius > 0.0f, "the build found no sphere around a patch the whole cone lights");
    for (j = 0; j < 64; ++j) {                            /* every rim point inside the sphere */
        fogrt_vec3 w = fogrt__in_cone(&F.cone, F.one_minus_cos, (float)j / 64.0f);
        float t = fogrt__dot(fogrt__sub(F.p, F.light), F.n) / fogrt__dot(w, F.n);
        TEST_ASSERT_TRUE(fogrt__length(fogrt__sub(fogrt__madd(F.light, w, t), F.center)) <= F.radius);
    }
    for (k = 0; k < 2; ++k) {
        const fogrt_vec3 x = v3(xs[k][0], xs[k][1], xs[k][2]);
        for (which = 0; which < 3; ++which) {
            double mean[2], se[2], target[2], z0, z1;
            footprint_mixture_means(&F, x, which, mean, se, target, 9300 + (uint64_t)k);
            z0 = se[0] > 0.0 ? fabs(mean[0] - target[0]) / se[0] : (mean[0] == target[0] ? 0.0 : HUGE_VAL);
            z1 = se[1] > 0.0 ? fabs(mean[1] - target[1]) / se[1] : (mean[1] == target[1] ? 0.0 : HUGE_VAL);
            snprintf(msg, sizeof msg, "footprint mixture, x = (%g, %g, %g), %s: mean of 1/pdf %.5f (want %.5f, %.1f se), "
                     "of cos/pdf %.5f (want %.5f, %.1f se)", (double)xs[k][0], (double)xs[k][1], (double)xs[k][2],
                     which == 0 ? "fogrt__footprint_pdf" : which == 1 ? "control: without the cone part" : "control: shares 0.3 / 0.7",
                     mean[0], target[0], z0, mean[1], target[1], z1);
            TEST_MESSAGE(msg);
            if (which == 0) TEST_ASSERT_TRUE_MESSAGE(z0 < 4.5 && z1 < 4.5, msg);
            else TEST_ASSERT_TRUE_MESSAGE(z0 > 8.0 || z1 > 8.0, msg);
        }
    }
#endif
}

/* ==========================================================================================
   The environment map: sampled directions follow the map's pdf
   ========================================================================================== */
#ifndef FOGRT_MINIMAL   /* helpers of Part II's test below */
static double env_pdf_callback(const double w[3], void *user)
{
    return fogrt__env_pdf((const fogrt_scene *)user, fogrt__v((float)w[0], (float)w[1], (float)w[2]));
}
/* A map with a bright spot, a dim band and black pixels: the directions next-event estimation
   draws (fogrt__sample_env) against fogrt__env_pdf integrated over a sphere grid, the pdf MIS
   uses on escape; and that pdf integrates to 1. Negative control: the same samples against
   the pdf without its 1/sin(theta) (a uniform-in-(x, y) density), which must be rejected. */
static fogrt_vec3 env_sampler(void *user, float u1, float u2, bool *ok)
{
    static fogrt_rng rng;
    static bool seeded = false;
    fogrt_light_sample ls;
    float u[3];
    if (!seeded) { fogrt_rng_seed(&rng, 555, 1); seeded = true; }
    u[0] = u1; u[1] = u2; u[2] = fogrt_rng_float(&rng);
    *ok = fogrt__sample_env((const fogrt_scene *)user, u, &ls);
    return ls.wi;
}
static double env_pdf_no_sin(const double w[3], void *user)
{
    double s = sqrt(fmax(0.0, 1.0 - w[1] * w[1]));
    return env_pdf_callback(w, user) * s;   /* wrong: drops the Jacobian's sin(theta) */
}
#endif
static void test_env_map_sampling(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("C: environment-map sampling");
#else
    enum { EW = 16, EH = 8 };
    static float map[EW * EH * 3];
    stats_tally t = {0, 0, ""};
    stats_sphere_grid grid;
    fogrt_scene *scene = NULL;
    double *observed, *expected, total;
    int i, j;
    for (j = 0; j < EH; ++j)
        for (i = 0; i < EW; ++i) {
            float v = (j == 2 && i == 5) ? 40.0f : (j == 5 ? 3.0f : (i % 4 == 0 ? 0.0f : 0.5f));
            map[3 * (j * EW + i)] = v; map[3 * (j * EW + i) + 1] = 0.5f * v; map[3 * (j * EW + i) + 2] = v;
        }
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_create(NULL, &scene));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_set_environment_map(scene, EW, EH, map, 1.0f));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    stats_grid_init(&grid, 40, 80);
    stats_grid_set_axis(&grid, 0.0, 1.0, 0.0);
    observed = alloc_cells(&grid); expected = alloc_cells(&grid);
    {
        dir_sampler s = {env_sampler, scene};
        const long n = 300000;
        long invalid = count_directions(&grid, s, n, 8800, observed);
        total = stats_grid_expected_from_pdf(&grid, env_pdf_callback, scene, (double)n, expected);
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(2e-3, 1.0, total, "fogrt__env_pdf does not integrate to 1 over the sphere");
        REPORT(t, grid_verdict("env_map", "fogrt__sample_env vs fogrt__env_pdf", "16x8 map: spot, band, black columns",
                               &grid, observed, expected, invalid, false));
        stats_grid_expected_from_pdf(&grid, env_pdf_no_sin, scene, (double)n, expected);
        REPORT(t, grid_verdict("env_map", "fogrt__sample_env vs fogrt__env_pdf", "model without the 1/sin(theta) Jacobian",
                               &grid, observed, expected, invalid, true));
    }
    free(observed); free(expected);
    fogrt_scene_destroy(scene);
    TALLY_ASSERT(t);
#endif
}

/* fogrt_hg_pdf next to the peak at g = +-0.999: directions 1e-6 to 1e-2 rad from it, the
   value against HG in double at the exact angle between the float vectors (from their chord).
   Negative control: the phase function of the rounded dot product, which is off by far more
   there. Fails if the pdf MIS and next-event estimation use loses its precision at the peak. */
static void test_hg_pdf_at_the_peak(void)
{
    static const float gs[2] = {0.999f, -0.999f};
    int k, i;
    for (k = 0; k < 2; k++) {
        double worst = 0.0, worst_dot = 0.0;
        float g = gs[k];
        fogrt_vec3 wo = v3(0.28f, -0.6f, 0.7483315f);   /* about unit */
        fogrt_vec3 d, peak;
        char msg[200];
        wo = fogrt__normalize(wo);
        d = fogrt__neg(wo);
        peak = g > 0.0f ? d : wo;
        for (i = 0; i <= 40; i++) {
            double theta = 1e-6 * pow(1e4, i / 40.0);
            fogrt__frame f = fogrt__frame_from_z(peak);
            fogrt_vec3 wi = fogrt__normalize(fogrt__to_world(&f, fogrt__v((float)sin(theta), 0.0f, (float)cos(theta))));
            double cx = (double)wi.x - peak.x, cy = (double)wi.y - peak.y, cz = (double)wi.z - peak.z;
            double ang = 2.0 * asin(0.5 * sqrt(cx * cx + cy * cy + cz * cz)), a = fabs((double)g);
            double base = (1.0 - a) * (1.0 - a) + 4.0 * a * sin(0.5 * ang) * sin(0.5 * ang);
            double exact = (1.0 - a * a) / (4.0 * STATS_PI * base * sqrt(base));
            double got = fogrt_hg_pdf(g, wo, wi), dotted = fogrt_hg_phase(g, -fogrt__dot(wo, wi));
            worst = fmax(worst, fabs(got - exact) / exact);
            worst_dot = fmax(worst_dot, fabs(dotted - exact) / exact);
        }
        snprintf(msg, sizeof msg, "g %g: worst relative error of fogrt_hg_pdf %.2g (rounded dot product: %.2g)",
                 (double)g, worst, worst_dot);
        TEST_MESSAGE(msg);
        TEST_ASSERT_TRUE_MESSAGE(worst < 1e-4, msg);
        TEST_ASSERT_TRUE_MESSAGE(worst_dot > 1e-3, msg);   /* the negative control sees the problem */
    }
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
            fogrt_vec3 wi = fogrt_sample_hg(g, wo, u1, u2, NULL);
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

/* The pdf that fogrt_sample_hg returns equals fogrt_hg_pdf(g, wo, wi) and the HG formula
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
                fogrt_vec3 wi = fogrt_sample_hg(g, wo, u1, u2, &pdf);
                float eval = fogrt_hg_pdf(g, wo, wi);
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
    return fogrt_hg_phase(*(const float *)user, (float)mu);
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
        snprintf(msg, sizeof msg, "2 pi int fogrt_hg_phase(%g, mu) dmu = %.9f (want 1 within 1e-6)", (double)g, integral);
        TEST_MESSAGE(msg);
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-6, 1.0, integral, msg);
        TEST_ASSERT_TRUE_MESSAGE(fogrt_hg_phase(g, -1.0f) > 0.0f && fogrt_hg_phase(g, 1.0f) > 0.0f, msg);
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
    fogrt_vec3 w = fogrt_sample_sphere_solid_angle(a->c, a->r, a->p, u1, u2, &pdf);
    double l = len3(w), wd[3] = {w.x / l, w.y / l, w.z / l};
    /* Every direction must hit the sphere (with 1e-4 relative slack for float rounding at
       the rim); a miss is an invalid sample. */
    if (!ray_hits_sphere(a, wd, a->r * (1.0 + 1e-4))) { a->misses++; *ok = false; }
    else *ok = pdf > 0.0f && isfinite(pdf);
    /* The pdf returned with the sample is the one fogrt_sphere_solid_angle_pdf reports. */
    if (pdf != fogrt_sphere_solid_angle_pdf(a->c, a->r, a->p)) a->bad_pdf++;
    return w;
}

/* 1 - cos(theta_max) of the cone subtended by a sphere of radius r at distance dist,
   as sin^2 / (1 + cos) in double. */
static double cone_one_minus_cos(double r, double dist)
{
    double s2 = r * r / (dist * dist);
    return s2 / (1.0 + sqrt(1.0 - s2));
}

/* Uniform over the cone of directions from p that see a sphere of radius r around c (all
   directions from inside), in double, independent of fogrt. */
static double cone_model_pdf(const sphere_args *a, const double w[3], double r)
{
    double pc[3] = {(double)a->c.x - a->p.x, (double)a->c.y - a->p.y, (double)a->c.z - a->p.z};
    double dist = sqrt(pc[0] * pc[0] + pc[1] * pc[1] + pc[2] * pc[2]);
    if (dist <= r) return 1.0 / (4.0 * STATS_PI);
    return ray_hits_sphere(a, w, r) ? 1.0 / (2.0 * STATS_PI * cone_one_minus_cos(r, dist)) : 0.0;
}

/* The model pdf: fogrt's pdf value inside the cone of the sphere (hit test in double), 0
   outside. With model_r != r (negative control) it is the uniform cone of a sphere of
   radius model_r, computed here in double. */
static double sphere_pdf_callback(const double w[3], void *user)
{
    const sphere_args *a = (const sphere_args *)user;
    if (a->model_r == a->r) {
        return ray_hits_sphere(a, w, a->r) ? fogrt_sphere_solid_angle_pdf(a->c, a->r, a->p) : 0.0;
    }
    return cone_model_pdf(a, w, a->model_r);
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
   Point and spot lights with a radius: spherical emitters
   ==========================================================================================
   A light with radius R > 0 is a sphere of uniform radiance I(theta) / (pi R^2), where
   I(theta) is the spot profile at x seen from the light's centre. fogrt__sample_point_light
   draws wi uniformly in the cone the sphere subtends at x (every direction from inside),
   returns the incident radiance divided by that pdf, and the distance to the emitting point. */

/* A scene holding one light (fogrt keeps its own copy, with the spot axis normalised). */
static fogrt_scene *light_scene(const fogrt_light_desc *desc)
{
    fogrt_scene *scene = NULL;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_create(NULL, &scene));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_light(scene, desc));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    return scene;
}

/* I(theta) / (pi R^2) per channel, in double: the spot profile clamp((cutoff - theta) /
   (cutoff - beam), 0, 1) at the angle between the axis and x - centre (1 for a point light). */
static void light_radiance_ref(const fogrt_light_desc *d, fogrt_vec3 x, double out[3])
{
    double falloff = 1.0;
    if (d->type == FOGRT_LIGHT_SPOT) {
        double v[3] = {(double)x.x - d->position.x, (double)x.y - d->position.y, (double)x.z - d->position.z};
        double a[3] = {d->direction.x, d->direction.y, d->direction.z};
        double c = (v[0] * a[0] + v[1] * a[1] + v[2] * a[2]) /
                   (sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) * sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]));
        double theta = acos(fmax(-1.0, fmin(1.0, c))) * 180.0 / STATS_PI;
        falloff = fmax(0.0, fmin(1.0, (d->cutoff_deg - theta) / ((double)d->cutoff_deg - d->beam_deg)));
    }
    double area = STATS_PI * (double)d->radius * d->radius;
    out[0] = falloff * d->intensity.x / area;
    out[1] = falloff * d->intensity.y / area;
    out[2] = falloff * d->intensity.z / area;
}

typedef struct point_light_args {
    const fogrt_scene *scene;
    const fogrt_light_desc *l;     /* the scene's copy */
    sphere_args geom;              /* p = x, c = centre, r = R: the cone model in double */
    double radiance[3];            /* I(theta) / (pi R^2) */
    double cone_pdf;               /* 1 / (2 pi (1 - cos theta_max)), or 1 / (4 pi) inside */
    long bad_value, bad_dist;
    char first_bad[320];
} point_light_args;

/* Draws one direction with fogrt__sample_point_light and checks the two numbers that come
   with it: value x cone pdf = I(theta) / (pi R^2) per channel (to 2e-6: a few float roundings
   of pi R^2 pdf and of 1 - cos theta_max), and the distance, which must end on the near side
   of the sphere (|y - c| = R to 1e-5 of the scene's size; t at most sqrt(d^2 - R^2), the
   tangent length) or be 0 from inside. */
static fogrt_vec3 point_light_sampler(void *user, float u1, float u2, bool *ok)
{
    point_light_args *a = (point_light_args *)user;
    fogrt_vec3 wi = v3(0.0f, 0.0f, 0.0f);
    float dist = -1.0f;
    fogrt_vec3 value = sample_point_light_(a->scene, a->l, a->geom.p, u1, u2, &wi, &dist);
    double val[3] = {value.x, value.y, value.z};
    bool value_ok = true;
    for (int k = 0; k < 3; k++)
        if (!(fabs(val[k] * a->cone_pdf - a->radiance[k]) <= 2e-6 * a->radiance[k])) value_ok = false;
    double pc[3] = {(double)a->geom.c.x - a->geom.p.x, (double)a->geom.c.y - a->geom.p.y,
                    (double)a->geom.c.z - a->geom.p.z};
    double d = sqrt(pc[0] * pc[0] + pc[1] * pc[1] + pc[2] * pc[2]), R = a->geom.r;
    bool dist_ok;
    if (d <= R) {
        dist_ok = dist == 0.0f;
    } else {
        double y[3] = {-pc[0] + (double)wi.x * dist, -pc[1] + (double)wi.y * dist, -pc[2] + (double)wi.z * dist};
        double radial = sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]) - R, tol = 1e-5 * (d + R);
        dist_ok = fabs(radial) <= tol && dist >= d - R - tol && dist <= sqrt((d - R) * (d + R)) + tol;
    }
    if (!value_ok && a->bad_value++ == 0)
        snprintf(a->first_bad, sizeof a->first_bad,
                 "value (%.9g, %.9g, %.9g) x cone pdf %.9g != I(theta)/(pi R^2) = (%.9g, %.9g, %.9g)",
                 val[0], val[1], val[2], a->cone_pdf, a->radiance[0], a->radiance[1], a->radiance[2]);
    if (value_ok && !dist_ok && a->bad_dist++ == 0)
        snprintf(a->first_bad, sizeof a->first_bad,
                 "dist %.9g along wi (%.7g, %.7g, %.7g) does not end on the near side of the sphere (d=%.7g, R=%g)",
                 (double)dist, (double)wi.x, (double)wi.y, (double)wi.z, d, R);
    *ok = isfinite(val[0]) && val[0] > 0.0 && isfinite(dist);
    return wi;
}

/* The model for the directions: uniform in the cone of the sphere of radius model_r (in
   double, independent of fogrt), or over all directions from inside. */
static double cone_model_callback(const double w[3], void *user)
{
    const sphere_args *a = (const sphere_args *)user;
    return cone_model_pdf(a, w, a->model_r);
}

/* The classic mistake: theta uniform in [0, theta_max] instead of cos theta. Exact cell
   probability: the share of [0, theta_max] inside the row, times the phi share. */
static double angle_uniform_cone_cell(double c0, double c1, double p0, double p1, void *user)
{
    double theta_max = *(const double *)user;
    double lo = acos(fmin(1.0, c1)), hi = fmin(acos(fmax(-1.0, c0)), theta_max);
    return hi > lo ? (hi - lo) / theta_max * (p1 - p0) / (2.0 * STATS_PI) : 0.0;
}

/* Three lights with a radius: a point light seen from outside (a cone of 16 degrees), a spot
   light whose profile is on its ramp at x, far away (a cone of 0.013 rad), and a point light
   seen from inside its sphere. */
static fogrt_light_desc radius_light(int k, fogrt_vec3 *x, const char **label)
{
    fogrt_light_desc d;
    memset(&d, 0, sizeof d);
    d.intensity = v3(3.0f, 2.0f, 0.5f);
    if (k == 0) {
        d.type = FOGRT_LIGHT_POINT; d.position = v3(1.0f, 2.0f, -0.5f); d.radius = 0.3f;
        *x = v3(0.2f, 1.5f, 0.1f);
        *label = "point light, x outside (cone of 16 deg)";
    } else if (k == 1) {
        d.type = FOGRT_LIGHT_SPOT; d.position = v3(0.5f, 3.0f, -1.0f); d.radius = 0.05f;
        d.direction = v3(0.2f, -2.0f, 0.1f);          /* not unit length: fogrt normalises it */
        d.cutoff_deg = 40.0f; d.beam_deg = 20.0f;
        *x = v3(3.0f, 0.0f, -1.2f);                   /* 34 degrees off the axis: on the ramp */
        *label = "spot light, x on the ramp, far (cone of 0.013 rad)";
    } else {
        d.type = FOGRT_LIGHT_POINT; d.position = v3(0.0f, 1.0f, 0.0f); d.radius = 1.0f;
        *x = v3(0.3f, 1.2f, -0.4f);
        *label = "point light, x inside the sphere";
    }
    return d;
}

/* Fills the arguments of point_light_sampler for the scene's light seen from x. */
static void point_light_setup(point_light_args *a, const fogrt_scene *scene, fogrt_vec3 x)
{
    memset(a, 0, sizeof *a);
    a->scene = scene;
    a->l = &scene->lights[0];
    a->geom.p = x;
    a->geom.c = a->l->position;
    a->geom.r = a->l->radius;
    a->geom.model_r = a->l->radius;
    light_radiance_ref(a->l, x, a->radiance);
    double pc[3] = {(double)a->geom.c.x - x.x, (double)a->geom.c.y - x.y, (double)a->geom.c.z - x.z};
    double d = sqrt(pc[0] * pc[0] + pc[1] * pc[1] + pc[2] * pc[2]);
    a->cone_pdf = d <= a->geom.r ? 1.0 / (4.0 * STATS_PI)
                                 : 1.0 / (2.0 * STATS_PI * cone_one_minus_cos(a->geom.r, d));
}

/* The directions fogrt__sample_point_light draws for a light with a radius are uniform in
   the cone the sphere subtends at x (uniform over the sphere of directions from inside), and
   every sample's value x cone pdf equals I(theta) / (pi R^2), with a distance that ends on
   the near side of the sphere. Negative controls: theta uniform in the cone (outside), a
   density 10% higher toward +z (inside). Fails if the emitter is sampled by area or by
   angle instead of solid angle, the cone is mis-sized, the value is not radiance / pdf, or
   the spot profile is not applied. */
static void test_point_light_radius_directions_chi2(void)
{
    stats_tally t = {0, 0, ""};
    stats_sphere_grid grid;
    double *observed = NULL, *expected = NULL;
    for (int k = 0; k < 3; k++) {
        fogrt_vec3 x;
        const char *label;
        fogrt_light_desc desc = radius_light(k, &x, &label);
        fogrt_scene *scene = light_scene(&desc);
        point_light_args a;
        point_light_setup(&a, scene, x);
        double pc[3] = {(double)a.geom.c.x - x.x, (double)a.geom.c.y - x.y, (double)a.geom.c.z - x.z};
        double d = sqrt(pc[0] * pc[0] + pc[1] * pc[1] + pc[2] * pc[2]);
        bool inside = d <= a.geom.r;
        double omc = inside ? 2.0 : cone_one_minus_cos(a.geom.r, d);
        if (inside) {
            stats_grid_init(&grid, 20, 40);
        } else {
            /* Frame z toward the centre; one catch-all row below the cone, then 40 equal rows
               from 1.25 (1 - cos theta_max) below 1 up to 1 (as for the solid-angle test). */
            double lo = 1.0 - 1.25 * omc;
            stats_grid_init(&grid, 41, 20);
            for (int i = 1; i <= 41; i++) grid.cos_edge[i] = lo + (1.0 - lo) * (i - 1) / 40.0;
            grid.cos_edge[41] = 1.0;
            stats_grid_set_axis(&grid, pc[0], pc[1], pc[2]);
        }
        if (!observed) {
            stats_sphere_grid big;
            stats_grid_init(&big, 41, 40);
            observed = alloc_cells(&big);
            expected = alloc_cells(&big);
        }
        dir_sampler s = {point_light_sampler, &a};
        const long n = 100000;
        long invalid = count_directions(&grid, s, n, 9000 + (uint64_t)k, observed);
        double total = stats_grid_expected_from_pdf(&grid, cone_model_callback, &a.geom, (double)n, expected);
        char name[64], param[200], msg[800];
        snprintf(msg, sizeof msg, "%s: the cone model integrates to %.7f", label, total);
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-4, 1.0, total, msg);
        snprintf(msg, sizeof msg, "%s: %ld samples with a wrong value, %ld with a wrong distance; first: %s", label,
                 a.bad_value, a.bad_dist, a.first_bad);
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, a.bad_value + a.bad_dist, msg);
        snprintf(name, sizeof name, "point_light_radius_%d", k);
        snprintf(param, sizeof param, "%s: |c-x|=%.4g R=%g", label, d, (double)a.geom.r);
        REPORT(t, grid_verdict(name, "fogrt__sample_point_light directions", param, &grid, observed, expected,
                               invalid, false));
        if (inside) {
            stats_grid_expected_from_pdf(&grid, tilted_sphere_pdf, NULL, (double)n, expected);
            snprintf(param, sizeof param, "%s, model: (1 + 0.1 z) / 4 pi", label);
        } else {
            double theta_max = 2.0 * asin(sqrt(0.5 * omc));
            stats_grid_expected_from_cells(&grid, angle_uniform_cone_cell, &theta_max, (double)n, expected);
            snprintf(param, sizeof param, "%s, model: theta uniform in [0, theta_max]", label);
        }
        REPORT(t, grid_verdict(name, "fogrt__sample_point_light directions", param, &grid, observed, expected,
                               invalid, true));
        fogrt_scene_destroy(scene);
    }
    free(observed);
    free(expected);
    TALLY_ASSERT(t);
}

/* A uniform sphere acts on the outside like a point at its centre: the irradiance it gives a
   small surface at x with normal n is I(theta) (n . axis) / d^2 whenever the whole sphere is
   above n's horizon, at every distance (the integral of w over the cone is pi sin^2 theta_max
   times the axis). So the mean of value x (n . wi) over 1e5 samples must equal the point
   light's I(theta) cos / d^2, within 4 standard errors plus 2e-6 relative (the float rounding
   of the value, which is the same for every sample). Near (d = 1.5 R), medium, and far
   (d = 200 R) lights, facing and tilted surfaces, a spot light on its ramp. Fails if the
   radiance is not I/(pi R^2), the value is not radiance / pdf, or the cone is sampled
   unevenly (the mean cosine changes). */
static void test_point_light_radius_irradiance(void)
{
    struct { int type; float c[3], R, x[3], tilt_deg; } cs[] = {
        {FOGRT_LIGHT_POINT, {0.0f, 0.0f, 0.0f}, 0.3f, {0.36f, 0.0f, 0.27f}, 0.0f},    /* d = 1.5 R */
        {FOGRT_LIGHT_POINT, {0.0f, 0.0f, 0.0f}, 0.3f, {0.36f, 0.0f, 0.27f}, 45.0f},   /* 41.8 + 45 < 90 */
        {FOGRT_LIGHT_POINT, {1.0f, 2.0f, -0.5f}, 0.3f, {0.2f, 1.5f, 0.1f}, 70.0f},    /* 15.6 + 70 < 90 */
        {FOGRT_LIGHT_POINT, {1.0f, 2.0f, -0.5f}, 0.01f, {1.0f, 0.4f, 0.7f}, 0.0f},    /* d = 200 R */
        {FOGRT_LIGHT_SPOT, {0.5f, 3.0f, -1.0f}, 0.05f, {3.0f, 0.0f, -1.2f}, 30.0f},   /* on the ramp */
    };
    char msg[400];
    for (size_t k = 0; k < sizeof cs / sizeof cs[0]; k++) {
        fogrt_light_desc desc;
        memset(&desc, 0, sizeof desc);
        desc.type = (fogrt_light_type)cs[k].type;
        desc.position = v3(cs[k].c[0], cs[k].c[1], cs[k].c[2]);
        desc.radius = cs[k].R;
        desc.intensity = v3(3.0f, 2.0f, 0.5f);
        desc.direction = v3(0.2f, -2.0f, 0.1f);
        desc.cutoff_deg = 40.0f;
        desc.beam_deg = 20.0f;
        fogrt_scene *scene = light_scene(&desc);
        fogrt_vec3 x = v3(cs[k].x[0], cs[k].x[1], cs[k].x[2]);
        double I[3];
        light_radiance_ref(&scene->lights[0], x, I);          /* I(theta) / (pi R^2) */
        /* the normal: tilted by tilt_deg away from the axis toward the centre */
        stats_sphere_grid frame;
        stats_grid_init(&frame, 2, 2);
        double pc[3] = {(double)desc.position.x - x.x, (double)desc.position.y - x.y, (double)desc.position.z - x.z};
        double d2 = pc[0] * pc[0] + pc[1] * pc[1] + pc[2] * pc[2];
        stats_grid_set_axis(&frame, pc[0], pc[1], pc[2]);
        double tilt = cs[k].tilt_deg * STATS_PI / 180.0, nrm[3];
        for (int i = 0; i < 3; i++) nrm[i] = cos(tilt) * frame.z[i] + sin(tilt) * frame.x[i];
        fogrt_rng rng;
        fogrt_rng_seed(&rng, 9500 + (uint64_t)k, 2);
        const long n = 100000;
        double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
        for (long s = 0; s < n; s++) {
            float u1 = fogrt_rng_float(&rng), u2 = fogrt_rng_float(&rng), dist;
            fogrt_vec3 wi;
            fogrt_vec3 v = sample_point_light_(scene, &scene->lights[0], x, u1, u2, &wi, &dist);
            double c = nrm[0] * wi.x + nrm[1] * wi.y + nrm[2] * wi.z;
            double e[3] = {v.x * c, v.y * c, v.z * c};
            for (int i = 0; i < 3; i++) { sum[i] += e[i]; sum2[i] += e[i] * e[i]; }
        }
        for (int i = 0; i < 3; i++) {
            double want = I[i] * STATS_PI * (double)desc.radius * desc.radius * cos(tilt) / d2;   /* I cos / d^2 */
            double mean = sum[i] / n, var = fmax(0.0, (sum2[i] - n * mean * mean) / (n - 1)), se = sqrt(var / n);
            double tol = 4.0 * se + 2e-6 * want;
            snprintf(msg, sizeof msg,
                     "light with radius %g at d=%.4g (%s), surface tilted %g deg, channel %d: mean value x cos = %.9g, "
                     "I cos/d^2 = %.9g, diff %.3g (s.e. %.2g, limit %.2g)",
                     (double)desc.radius, sqrt(d2), cs[k].type == FOGRT_LIGHT_SPOT ? "spot" : "point",
                     (double)cs[k].tilt_deg, i, mean, want, mean - want, se, tol);
            if (i == 0) TEST_MESSAGE(msg);
            TEST_ASSERT_TRUE_MESSAGE(want > 0.0, msg);
            TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(tol, want, mean, msg);
        }
        fogrt_scene_destroy(scene);
    }
}

/* ==========================================================================================
   Area lights: emissive meshes and spheres
   ==========================================================================================
   Every emissive mesh is one area light: fogrt__sample_area_light picks one of its
   triangles with probability area / total area (binary search in a CDF), then a uniform
   point on it, and returns the emission, the direction and distance to the point, and the
   solid-angle pdf dist^2 / (cos_l total area). An emissive sphere is sampled by the cone it
   subtends. The test scene: mesh A (6 triangles: 4 emissive ones of areas 0.07 to 2.6 in
   three planes, one black one and one degenerate one, neither of which may be picked), mesh
   B (3 triangles of areas 2, 0.02 and 1: the second light, whose CDF does not start at 0),
   and an emissive sphere. Each emissive triangle has its own material, with emission.x =
   1 + its index, so the emission returned names the triangle that was picked.             */
#define AREA_TRIS 9
static const float AREA_V[AREA_TRIS][9] = {
    /* mesh A */
    {-1.0f, -1.0f, 0.0f,   0.0f, -1.0f, 0.0f,  -1.0f, 0.0f, 0.0f},     /* 0: area 0.5 */
    { 0.0f, -1.0f, 0.0f,   2.0f, -1.0f, 0.0f,   0.0f, 0.5f, 0.0f},     /* 1: area 1.5 */
    {-1.0f, 0.0f, 0.0f,    0.0f, 0.5f, 0.0f,   -1.0f, 1.0f, 0.0f},     /* 2: black */
    { 1.0f, 1.0f, 0.0f,    1.5f, 1.0f, 0.0f,    2.0f, 1.0f, 0.0f},     /* 3: emissive, zero area */
    {-1.5f, 1.0f, 0.2f,   -1.1f, 1.0f, 0.2f,   -1.5f, 1.3f, 0.4f},     /* 4: area 0.072, tilted */
    { 0.5f, 0.8f, -0.5f,   3.0f, 0.8f, 0.0f,    0.5f, 2.8f, -0.2f},    /* 5: area 2.58, tilted */
    /* mesh B, in the plane x = 3, facing -x */
    { 3.0f, -1.0f, 0.0f,   3.0f, -1.0f, 2.0f,   3.0f, 1.0f, 0.0f},     /* 6: area 2 */
    { 3.0f, 1.2f, 0.0f,    3.0f, 1.2f, 0.2f,    3.0f, 1.4f, 0.0f},     /* 7: area 0.02 */
    { 3.0f, 1.5f, 0.5f,    3.0f, 1.5f, 1.5f,    3.0f, 3.5f, 0.5f},     /* 8: area 1 */
};
#define AREA_MESH_A 6                   /* triangles 0..5 are mesh A, 6..8 mesh B */
static const float AREA_P[3] = {0.2f, 0.1f, 3.0f};           /* the receiving point */
static const float AREA_SPHERE_C[3] = {-2.0f, 0.5f, 1.0f}, AREA_SPHERE_R = 0.6f;   /* |c - p| = 3 */

/* Triangle geometry in double: edges, unit normal, area. */
typedef struct tri_geom { double v0[3], e1[3], e2[3], n[3], area; } tri_geom;

static tri_geom triangle_geometry(int t)
{
    tri_geom g;
    for (int i = 0; i < 3; i++) {
        g.v0[i] = AREA_V[t][i];
        g.e1[i] = (double)AREA_V[t][3 + i] - AREA_V[t][i];
        g.e2[i] = (double)AREA_V[t][6 + i] - AREA_V[t][i];
    }
    double c[3] = {g.e1[1] * g.e2[2] - g.e1[2] * g.e2[1], g.e1[2] * g.e2[0] - g.e1[0] * g.e2[2],
                   g.e1[0] * g.e2[1] - g.e1[1] * g.e2[0]};
    double len = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    g.area = 0.5 * len;
    for (int i = 0; i < 3; i++) g.n[i] = len > 0.0 ? c[i] / len : 0.0;
    return g;
}

static bool area_tri_emissive(int t) { return t != 2 && triangle_geometry(t).area > 0.0; }

/* Builds the scene: mesh A, mesh B, the emissive sphere. */
static fogrt_scene *area_light_scene(void)
{
    fogrt_scene *scene = NULL;
    uint32_t mat[AREA_TRIS], sphere_mat;
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_create(NULL, &scene));
    for (int t = 0; t < AREA_TRIS; t++) {
        fogrt_material_desc m;
        memset(&m, 0, sizeof m);
        m.reflectance = v3(0.5f, 0.5f, 0.5f);
        if (t != 2) m.emission = v3(1.0f + (float)t, 0.5f, 0.25f);
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_material(scene, &m, &mat[t]));
    }
    fogrt_material_desc sm;
    memset(&sm, 0, sizeof sm);
    sm.emission = v3(7.0f, 6.0f, 5.0f);
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_material(scene, &sm, &sphere_mat));
    for (int mesh = 0; mesh < 2; mesh++) {
        int first = mesh == 0 ? 0 : AREA_MESH_A, count = mesh == 0 ? AREA_MESH_A : AREA_TRIS - AREA_MESH_A;
        fogrt_mesh_desc md;
        memset(&md, 0, sizeof md);
        md.positions = &AREA_V[first][0];
        md.vertex_count = 3 * (uint32_t)count;
        md.triangle_count = (uint32_t)count;
        md.triangle_materials = &mat[first];
        TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_add_mesh(scene, &md));
    }
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK,
                          fogrt_scene_add_sphere(scene, v3(AREA_SPHERE_C[0], AREA_SPHERE_C[1], AREA_SPHERE_C[2]),
                                                 AREA_SPHERE_R, sphere_mat));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_OK, fogrt_scene_build(scene, NULL));
    return scene;
}

/* Points picked on mesh light L (0: mesh A, 1: mesh B) are uniform by area over the whole
   mesh: a chi-square test on cells (triangle, K x K barycentric cell), with expected counts
   n (area / total area) x (2/K^2 below the diagonal, 1/K^2 on it). Each sample must lie on
   the triangle its emission names (plane distance and barycentric slack 1e-5), and its pdf
   must equal dist^2 / (cos_l total area) computed in double (to 1e-5 + 4e-7 / cos_l: the
   float direction's error in cos_l) and the MIS partner fogrt__area_light_pdf at that point.
   Negative control: each triangle picked with the same probability (uniform by index).
   Fails if the CDF is not by area, the binary search is off by one, a light reads another
   light's CDF range, a black or degenerate triangle is picked, or the pdf forgets cos_l. */
static void test_area_light_mesh_chi2(void)
{
    stats_tally t = {0, 0, ""};
    enum { K = 10, MAXT = AREA_MESH_A };
    fogrt_scene *scene = area_light_scene();
    fogrt_vec3 p = v3(AREA_P[0], AREA_P[1], AREA_P[2]);
    char msg[800];
    snprintf(msg, sizeof msg, "area_light_count = %u, want 3 (mesh A, mesh B, sphere)", scene->area_light_count);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(3, scene->area_light_count, msg);
    for (int L = 0; L < 2; L++) {
        int first = L == 0 ? 0 : AREA_MESH_A, last = L == 0 ? AREA_MESH_A : AREA_TRIS;
        int cell_tri[MAXT], tri_cell[AREA_TRIS], T = 0;   /* emissive triangles of this light */
        tri_geom geom[AREA_TRIS];
        double total_area = 0.0;
        for (int k = first; k < last; k++) {
            geom[k] = triangle_geometry(k);
            tri_cell[k] = -1;
            if (!area_tri_emissive(k)) continue;
            tri_cell[k] = T;
            cell_tri[T++] = k;
            total_area += geom[k].area;
            /* set-up check: p sees the front of every emissive triangle (cos_l > 0 at each vertex) */
            for (int v = 0; v < 3; v++) {
                double q[3] = {(double)p.x - AREA_V[k][3 * v], (double)p.y - AREA_V[k][3 * v + 1],
                               (double)p.z - AREA_V[k][3 * v + 2]};
                TEST_ASSERT_TRUE_MESSAGE(q[0] * geom[k].n[0] + q[1] * geom[k].n[1] + q[2] * geom[k].n[2] > 0.0,
                                         "test set-up: p must face every emissive triangle");
            }
        }
        const fogrt__area_light *light = &scene->area_lights[L];
        snprintf(msg, sizeof msg, "mesh light %d: %u triangles, area %.9g; want %d triangles, area %.9g", L,
                 light->count, (double)light->area, T, total_area);
        TEST_MESSAGE(msg);
        TEST_ASSERT_EQUAL_UINT32_MESSAGE((uint32_t)T, light->count, msg);
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-6 * total_area, total_area, (double)light->area, msg);

        double observed[MAXT * K * K], expected[MAXT * K * K];
        memset(observed, 0, sizeof observed);
        fogrt_rng rng;
        fogrt_rng_seed(&rng, 9700 + (uint64_t)L, 11);
        const long n = L == 0 ? 200000 : 100000;
        long invalid = 0, bad_pdf = 0, bad_mis = 0;
        char first_bad[320] = "";
        for (long s = 0; s < n; s++) {
            fogrt_vec3 wi = v3(0.0f, 0.0f, 0.0f);
            float dist = -1.0f, pdf = -1.0f;
            fogrt_vec3 Le = sample_area_light_(scene, light, p, &rng, &wi, &dist, &pdf);
            int k = (int)Le.x - 1;
            if (!(pdf > 0.0f) || !(Le.x == (float)(k + 1)) || k < first || k >= last || tri_cell[k] < 0 ||
                Le.y != 0.5f || Le.z != 0.25f || !isfinite(dist)) {
                invalid++;
                continue;
            }
            /* the point, its plane distance and barycentrics on triangle k, in double */
            const tri_geom *g = &geom[k];
            double q[3], y[3];
            for (int i = 0; i < 3; i++) {
                double pi_ = i == 0 ? p.x : (i == 1 ? p.y : p.z), wii = i == 0 ? wi.x : (i == 1 ? wi.y : wi.z);
                y[i] = pi_ + wii * dist;
                q[i] = y[i] - g->v0[i];
            }
            double a11 = g->e1[0] * g->e1[0] + g->e1[1] * g->e1[1] + g->e1[2] * g->e1[2];
            double a22 = g->e2[0] * g->e2[0] + g->e2[1] * g->e2[1] + g->e2[2] * g->e2[2];
            double a12 = g->e1[0] * g->e2[0] + g->e1[1] * g->e2[1] + g->e1[2] * g->e2[2];
            double r1 = q[0] * g->e1[0] + q[1] * g->e1[1] + q[2] * g->e1[2];
            double r2 = q[0] * g->e2[0] + q[1] * g->e2[1] + q[2] * g->e2[2];
            double det = a11 * a22 - a12 * a12;
            double b1 = (r1 * a22 - r2 * a12) / det, b2 = (r2 * a11 - r1 * a12) / det;
            double plane = fabs(q[0] * g->n[0] + q[1] * g->n[1] + q[2] * g->n[2]);
            const double slack = 1e-5;
            if (plane > slack || b1 < -slack || b2 < -slack || b1 + b2 > 1.0 + slack) {
                if (invalid++ == 0)
                    snprintf(first_bad, sizeof first_bad, "point not on triangle %d: plane distance %.3g, b = (%.6g, %.6g)",
                             k, plane, b1, b2);
                continue;
            }
            int i = (int)floor(fmax(0.0, b1) * K), j = (int)floor(fmax(0.0, b2) * K);
            if (i > K - 1) i = K - 1;
            if (j > K - 1) j = K - 1;
            while (i + j > K - 1) { if (i > j) i--; else j--; }   /* on (or a rounding past) the diagonal */
            observed[(tri_cell[k] * K + i) * K + j] += 1.0;
            /* the solid-angle pdf, in double */
            double cos_l = -(wi.x * g->n[0] + wi.y * g->n[1] + wi.z * g->n[2]);
            double want = (double)dist * dist / (cos_l * total_area), tol = (1e-5 + 4e-7 / cos_l) * want;
            float mis = fogrt__area_light_pdf(scene, (uint32_t)k, p, v3((float)y[0], (float)y[1], (float)y[2]),
                                              v3((float)g->n[0], (float)g->n[1], (float)g->n[2]));
            if (!(fabs(pdf - want) <= tol) && bad_pdf++ == 0)
                snprintf(first_bad, sizeof first_bad, "triangle %d: pdf %.9g, dist^2/(cos_l A) = %.9g (cos_l %.6f)", k,
                         (double)pdf, want, cos_l);
            if (!(fabs(mis - want) <= tol) && bad_mis++ == 0)
                snprintf(first_bad, sizeof first_bad, "triangle %d: fogrt__area_light_pdf %.9g, want %.9g", k,
                         (double)mis, want);
        }
        snprintf(msg, sizeof msg, "mesh light %d: %ld samples with a pdf other than dist^2/(cos_l A), %ld with "
                 "another fogrt__area_light_pdf; first: %s", L, bad_pdf, bad_mis, first_bad);
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, bad_pdf + bad_mis, msg);

        double edge[MAXT * K + 1];
        for (int r = 0; r <= T * K; r++) edge[r] = (double)r / K;   /* row r: triangle r / K, b1 cell r % K */
        char name[64], param[200];
        snprintf(name, sizeof name, "area_light_mesh_%d", L);
        for (int neg = 0; neg < 2; neg++) {
            for (int c = 0; c < T; c++) {
                double share = neg ? 1.0 / T : geom[cell_tri[c]].area / total_area;
                for (int i = 0; i < K; i++)
                    for (int j = 0; j < K; j++)
                        expected[(c * K + i) * K + j] = n * share * (i + j < K - 1 ? 2.0 : (i + j == K - 1 ? 1.0 : 0.0)) / (K * K);
            }
            snprintf(param, sizeof param, "mesh %c, %d emissive triangles of areas %.3g..%.3g, K=%d cells each%s",
                     L == 0 ? 'A' : 'B', T, L == 0 ? geom[4].area : geom[7].area, L == 0 ? geom[5].area : geom[6].area,
                     K, neg ? ", model: uniform by triangle index" : "");
            if (!neg && invalid) {
                snprintf(msg, sizeof msg, "mesh light %d: first invalid sample: %s", L,
                         first_bad[0] ? first_bad : "black, zero-pdf or foreign triangle");
                TEST_MESSAGE(msg);
            }
            REPORT(t, stats_chi2_verdict(name, "fogrt__sample_area_light points", param, T * K, K, edge,
                                         "triangle + b1", edge, "b2", observed, expected, invalid, neg == 1));
        }
    }
    fogrt_scene_destroy(scene);
    TALLY_ASSERT(t);
}

/* An emissive sphere light is sampled by solid angle: directions uniform in the cone it
   subtends at p, every pdf equal to fogrt_sphere_solid_angle_pdf, the emission of its
   material, and a distance that ends on the near side of the sphere; from inside the sphere
   (it emits outward only) the sample is unusable: black, pdf 0. Negative control: the cone
   of a sphere 5% larger. Fails if the sphere is sampled by area, or the pdf is not that of
   the cone (biasing MIS). */
static void test_area_light_sphere_chi2(void)
{
    stats_tally t = {0, 0, ""};
    fogrt_scene *scene = area_light_scene();
    const fogrt__area_light *light = &scene->area_lights[2];
    TEST_ASSERT_TRUE_MESSAGE(light->sphere != UINT32_MAX, "the third area light should be the sphere");
    sphere_args a;
    memset(&a, 0, sizeof a);
    a.p = v3(AREA_P[0], AREA_P[1], AREA_P[2]);
    a.c = v3(AREA_SPHERE_C[0], AREA_SPHERE_C[1], AREA_SPHERE_C[2]);
    a.r = AREA_SPHERE_R;
    a.model_r = a.r;
    double pc[3] = {(double)a.c.x - a.p.x, (double)a.c.y - a.p.y, (double)a.c.z - a.p.z};
    double d = sqrt(pc[0] * pc[0] + pc[1] * pc[1] + pc[2] * pc[2]), omc = cone_one_minus_cos(a.r, d);
    stats_sphere_grid grid;
    stats_grid_init(&grid, 41, 20);
    for (int i = 1; i <= 41; i++) grid.cos_edge[i] = 1.0 - 1.25 * omc + 1.25 * omc * (i - 1) / 40.0;
    grid.cos_edge[41] = 1.0;
    stats_grid_set_axis(&grid, pc[0], pc[1], pc[2]);
    double *observed = alloc_cells(&grid), *expected = alloc_cells(&grid);
    fogrt_rng rng;
    fogrt_rng_seed(&rng, 9800, 13);
    const long n = 100000;
    long invalid = 0, bad = 0;
    char first_bad[320] = "", msg[800];
    float want_pdf = fogrt_sphere_solid_angle_pdf(a.c, a.r, a.p);
    for (long s = 0; s < n; s++) {
        fogrt_vec3 wi = v3(0.0f, 0.0f, 0.0f);
        float dist = -1.0f, pdf = -1.0f;
        fogrt_vec3 Le = sample_area_light_(scene, light, a.p, &rng, &wi, &dist, &pdf);
        int cell = pdf > 0.0f ? stats_grid_cell(&grid, wi.x, wi.y, wi.z) : -1;
        if (cell < 0) { invalid++; continue; }
        observed[cell] += 1.0;
        double y[3] = {-pc[0] + (double)wi.x * dist, -pc[1] + (double)wi.y * dist, -pc[2] + (double)wi.z * dist};
        double radial = sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]) - a.r, tol = 1e-5 * (d + a.r);
        bool ok = pdf == want_pdf && Le.x == 7.0f && Le.y == 6.0f && Le.z == 5.0f && fabs(radial) <= tol &&
                  dist <= sqrt((d - a.r) * (d + a.r)) + tol;
        if (!ok && bad++ == 0)
            snprintf(first_bad, sizeof first_bad, "pdf %.9g (want %.9g), Le (%g, %g, %g), dist %.9g: |y - c| - r = %.3g",
                     (double)pdf, (double)want_pdf, (double)Le.x, (double)Le.y, (double)Le.z, (double)dist, radial);
    }
    snprintf(msg, sizeof msg, "sphere light: %ld samples with a wrong pdf, emission or distance; first: %s", bad, first_bad);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, bad, msg);
    double total = stats_grid_expected_from_pdf(&grid, cone_model_callback, &a, (double)n, expected);
    TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-4, 1.0, total, "the sphere's cone model does not integrate to 1");
    REPORT(t, grid_verdict("area_light_sphere", "fogrt__sample_area_light sphere directions",
                           "|c-p|=3 r=0.6 (cone of 11.5 deg)", &grid, observed, expected, invalid, false));
    a.model_r = 1.05 * a.r;
    stats_grid_expected_from_pdf(&grid, cone_model_callback, &a, (double)n, expected);
    REPORT(t, grid_verdict("area_light_sphere", "fogrt__sample_area_light sphere directions",
                           "model: the cone of a sphere of radius 0.63", &grid, observed, expected, invalid, true));
    /* from inside the emitting sphere: nothing to sample */
    fogrt_vec3 wi;
    float dist, pdf = -1.0f;
    fogrt_vec3 Le = sample_area_light_(scene, light, v3(-1.8f, 0.6f, 1.1f), &rng, &wi, &dist, &pdf);
    snprintf(msg, sizeof msg, "from inside the sphere light: Le (%g, %g, %g), pdf %g; want black, 0", (double)Le.x,
             (double)Le.y, (double)Le.z, (double)pdf);
    TEST_ASSERT_TRUE_MESSAGE(pdf == 0.0f && Le.x == 0.0f && Le.y == 0.0f && Le.z == 0.0f, msg);
    free(observed);
    free(expected);
    fogrt_scene_destroy(scene);
    TALLY_ASSERT(t);
}

/* fogrt_spot_falloff(cutoff, beam, cos theta) equals clamp((cutoff - theta)/(cutoff - beam),
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
        float got = fogrt_spot_falloff(c[k].cutoff, c[k].beam, cos_theta);
        snprintf(msg, sizeof msg, "fogrt_spot_falloff(cutoff %g, beam %g, cos %g deg) = %.7f, want %.7f (nominal %.7f)",
                 (double)c[k].theta, (double)c[k].cutoff, (double)c[k].beam, (double)got, want, c[k].want);
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-6, c[k].want, want, "test table: nominal value disagrees with the formula");
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-5, want, (double)got, msg);
    }
    /* cutoff 0: a zero-width cone; on the axis itself only "finite, in [0, 1]" is defined. */
    float axis = fogrt_spot_falloff(0.0f, 0.0f, 1.0f);
    TEST_ASSERT_TRUE_MESSAGE(axis >= 0.0f && axis <= 1.0f, "fogrt_spot_falloff(0, 0, 1) outside [0, 1]");
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
            float d = fogrt_sample_exponential(sig[k], fogrt_rng_float(&rng));
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
            float t = fogrt_sample_exponential(sig[k], us[i]);
            float back = fogrt_exponential_cdf(sig[k], t);
            double pdf_want = sig[k] * exp(-(double)sig[k] * t);
            snprintf(msg, sizeof msg, "sigma_t=%g u=%.9g: t=%.9g, invert=%.9g, pdf=%.9g want %.9g", (double)sig[k],
                     (double)us[i], (double)t, (double)back, (double)fogrt_exponential_pdf(sig[k], t), pdf_want);
            TEST_ASSERT_TRUE_MESSAGE(isfinite(t) && t >= 0.0f, msg);
            TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(2e-7 + 4e-7 * us[i], (double)us[i], (double)back, msg);
            TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-5 * pdf_want, pdf_want, (double)fogrt_exponential_pdf(sig[k], t), msg);
        }
    }
    TEST_ASSERT_TRUE(isinf(fogrt_sample_exponential(0.0f, 0.5f)) && fogrt_sample_exponential(0.0f, 0.5f) > 0.0f);
    TEST_ASSERT_EQUAL_FLOAT(0.0f, fogrt_exponential_pdf(0.0f, 1.0f));
}

/* ==========================================================================================
   Equiangular distance sampling toward a point light
   ==========================================================================================
   The light is at distance h from the ray's line, its closest approach at t = delta; on the
   segment [a, b] (b may be +infinity) fogrt_sample_equiangular draws t with density
   proportional to 1 / (h^2 + (t - delta)^2). With theta(t) = atan((t - delta) / h) the angle
   seen from the light, the CDF is (theta(t) - theta(a)) / (theta(b) - theta(a)): theta is
   uniform, which is how the sampler works and how the tests below measure it.              */
typedef struct eq_case {
    float delta, h, a, b;
    float neg_delta, neg_h;     /* the negative control's model */
    const char *label;
} eq_case;

/* The KS cases. Negative controls: h doubled where the light is over the segment; where it
   lies beyond an end, the density there is about 1 / (t - delta)^2 whatever h is, so the
   control moves the light 10% farther along the ray instead. */
#ifndef FOGRT_MINIMAL   /* cases and model of Part II's tests below */
static const eq_case EQ_CASES[] = {
    {1.0f, 0.5f, 0.0f, 3.0f, 1.0f, 1.0f, "light over the segment"},
    {1.0f, 0.5f, 0.0f, INFINITY, 1.0f, 1.0f, "escaping ray, b = +inf"},
    {-2.0f, 0.3f, 0.0f, 5.0f, -2.2f, 0.3f, "light behind the start"},
    {9.0f, 0.4f, 0.0f, 4.0f, 9.5f, 0.4f, "light beyond the end"},
    {0.7f, 1e-3f, 0.0f, 2.0f, 0.7f, 2e-3f, "light 1e-3 from the line"},
    {-3.0f, 0.05f, 0.0f, INFINITY, -3.3f, 0.05f, "light behind the start, b = +inf"},
};
#define EQ_CASE_COUNT ((int)(sizeof EQ_CASES / sizeof EQ_CASES[0]))

typedef struct eq_model { double delta, h, a, b, theta_a, range; } eq_model;   /* range = theta_b - theta_a */

/* theta(t) in double; theta(+inf) = pi/2 exactly. */
static double eq_theta(const eq_model *m, double t)
{
    return isinf(t) ? 0.5 * STATS_PI : atan2(t - m->delta, m->h);
}

static eq_model eq_model_of(float delta, float h, float a, float b)
{
    eq_model m;
    m.delta = delta; m.h = h; m.a = a; m.b = b;
    m.theta_a = eq_theta(&m, m.a);
    m.range = eq_theta(&m, m.b) - m.theta_a;
    return m;
}

static double eq_cdf(double t, void *user)
{
    const eq_model *m = (const eq_model *)user;
    if (t <= m->a) return 0.0;
    if (t >= m->b) return 1.0;
    return (eq_theta(m, t) - m->theta_a) / m->range;
}

#endif
/* fogrt_sample_equiangular draws t with the exact equiangular CDF, for a light over the
   segment, beyond either end, 1e-3 from the line, and for b = +inf (a ray escaping into open
   fog): a KS test on 2e5 distances per case. Every sample also returns the pdf that
   fogrt_equiangular_pdf gives at t (to 1e-6) and h / ((theta_b - theta_a)(h^2 + (t-delta)^2))
   in double (to 1e-5 plus the float conditioning: 2.4e-7 / (theta_b - theta_a) from the two
   atan2f, and the rounding of t - delta). Negative controls: see EQ_CASES. Fails if theta
   is not uniform (e.g. t uniform, or h^2 where h belongs), the interval is clipped wrongly,
   or b = +inf is mishandled. */
static void test_equiangular_ks(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("B: equiangular sampling");
#else
    stats_tally t = {0, 0, ""};
    enum { N = 200000 };
    double *x = (double *)malloc(sizeof(double) * N);
    TEST_ASSERT_NOT_NULL(x);
    char msg[800];
    for (int k = 0; k < EQ_CASE_COUNT; k++) {
        const eq_case *c = &EQ_CASES[k];
        eq_model m = eq_model_of(c->delta, c->h, c->a, c->b);
        double range = m.range;
        fogrt_rng rng;
        fogrt_rng_seed(&rng, 11000 + (uint64_t)k, 9);
        long invalid = 0, bad_pdf = 0;
        char first_bad[300] = "";
        for (int i = 0; i < N; i++) {
            float pdf = -1.0f, u = fogrt_rng_float(&rng);
            float s = fogrt_sample_equiangular(c->delta, c->h, c->a, c->b, u, &pdf);
            x[i] = s;
            if (!isfinite(s) || !(s >= c->a && s <= c->b) || !(pdf > 0.0f) || !isfinite(pdf)) { invalid++; continue; }
            double eval = fogrt_equiangular_pdf(c->delta, c->h, c->a, c->b, s);
            double dt = (double)s - c->delta, den = (double)c->h * c->h + dt * dt;
            double ref = c->h / (range * den);
            double rel = 1e-5 + 2.4e-7 / range + 1.2e-7 * fmax(fabs((double)s), fabs((double)c->delta)) * 2.0 * fabs(dt) / den;
            if (!(fabs(pdf - eval) <= 1e-6 * eval) || !(fabs(pdf - ref) <= rel * ref)) {
                if (bad_pdf++ == 0)
                    snprintf(first_bad, sizeof first_bad, "u=%.9g t=%.9g: pdf %.9g, fogrt_equiangular_pdf %.9g, double %.9g",
                             (double)u, (double)s, (double)pdf, eval, ref);
            }
        }
        snprintf(msg, sizeof msg, "equiangular %s: %ld of %d samples with a wrong pdf; first: %s", c->label, bad_pdf, N,
                 first_bad);
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, bad_pdf, msg);
        char name[64], param[200];
        snprintf(name, sizeof name, "equiangular_%d", k);
        snprintf(param, sizeof param, "%s: delta=%g h=%g [%g, %g]", c->label, (double)c->delta, (double)c->h,
                 (double)c->a, (double)c->b);
        stats_ks_result r = stats_ks(x, N, eq_cdf, &m);
        REPORT(t, stats_ks_verdict(name, "fogrt_sample_equiangular", param, &r, x, eq_cdf, &m, invalid, false));
        eq_model wrong = eq_model_of(c->neg_delta, c->neg_h, c->a, c->b);
        r = stats_ks(x, N, eq_cdf, &wrong);
        snprintf(param, sizeof param, "%s: sampled with delta=%g h=%g, model delta=%g h=%g", c->label, (double)c->delta,
                 (double)c->h, (double)c->neg_delta, (double)c->neg_h);
        REPORT(t, stats_ks_verdict(name, "fogrt_sample_equiangular", param, &r, x, eq_cdf, &wrong, invalid, true));
    }
    free(x);
    TALLY_ASSERT(t);
#endif
}

/* fogrt_equiangular_pdf(t) dt integrated over [a, b] (through t = delta + h sinh v, which
   turns the 1 / (h^2 + (t - delta)^2) peak and the 1/t^2 tail into the smooth, exponentially
   decaying 1 / cosh v; v up to 40 stands for b = +inf, the tail beyond is 1e-17) gives 1, to
   2e-6 plus the float conditioning (2.4e-7 / (theta_b - theta_a) from atan2f, and
   1.2e-7 (|delta| / h + 2) for evaluating at float t; composite Simpson, 8192 panels). The
   pdf is 0 outside [a, b]. Fails on
   a missing h in the numerator, theta_b - theta_a taken wrongly or b = +inf mishandled. */
#ifndef FOGRT_MINIMAL   /* helpers of Part II's test below */
static double eq_pdf_in_v(const eq_case *c, double v)
{
    float s = (float)(c->delta + (double)c->h * sinh(v));
    s = s < c->a ? c->a : (s > c->b ? c->b : s);      /* the end nodes must not round outside */
    return fogrt_equiangular_pdf(c->delta, c->h, c->a, c->b, s) * (double)c->h * cosh(v);
}

/* Composite Simpson with a fixed number of panels: the integrand is smooth, but it is
   evaluated at float t, so its rounding noise (1e-7 relative) would keep an adaptive rule
   refining forever. With 8192 panels over at most 50 units of v the rule's own error is
   below 1e-9. */
static double eq_integrate_v(const eq_case *c, double va, double vb)
{
    const int panels = 8192;
    double step = (vb - va) / panels, sum = eq_pdf_in_v(c, va) + eq_pdf_in_v(c, vb);
    for (int i = 1; i < panels; i++) sum += (i % 2 ? 4.0 : 2.0) * eq_pdf_in_v(c, va + i * step);
    return sum * step / 3.0;
}

#endif
static void test_equiangular_pdf_normalised(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("B: equiangular sampling");
#else
    char msg[300];
    for (int k = 0; k < EQ_CASE_COUNT; k++) {
        const eq_case *c = &EQ_CASES[k];
        double range = eq_model_of(c->delta, c->h, c->a, c->b).range;
        double va = asinh(((double)c->a - c->delta) / c->h);
        double vb = isinf(c->b) ? 40.0 : asinh(((double)c->b - c->delta) / c->h);
        double integral = eq_integrate_v(c, va, vb);
        double tol = 2e-6 + 2.4e-7 / range + 1.2e-7 * (fabs((double)c->delta) / c->h + 2.0);
        snprintf(msg, sizeof msg, "equiangular %s: int fogrt_equiangular_pdf dt over [%g, %g] = %.9f (want 1 within %.2g)",
                 c->label, (double)c->a, (double)c->b, integral, tol);
        TEST_MESSAGE(msg);
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(tol, 1.0, integral, msg);
        TEST_ASSERT_EQUAL_FLOAT_MESSAGE(0.0f, fogrt_equiangular_pdf(c->delta, c->h, c->a, c->b, c->a - 0.5f), msg);
        if (!isinf(c->b))
            TEST_ASSERT_EQUAL_FLOAT_MESSAGE(0.0f, fogrt_equiangular_pdf(c->delta, c->h, c->a, c->b, c->b + 0.5f), msg);
    }
#endif
}

/* fogrt_sample_equiangular is the inverse CDF to float accuracy, monotone, and inside
   [a, b], over 12288 uniforms: a grid of 4096, the 4096 smallest floats from 0 and the 4096
   largest below 1 (the RNG returns u up to 1 - 2^-24). Measured in theta, where the map is
   well conditioned: theta(t) must equal theta_a + u (theta_b - theta_a) within 6e-7 rad (a
   few float ulps of pi/2 for the two atan2f, the product and the sum) plus the rounding of t
   seen in theta, 2.4e-7 (|t| + |t - delta|) h / (h^2 + (t - delta)^2). Cases: those of the
   KS test, and lights 1e-4 from the line far behind the start (with b = 10 and b = +inf), at
   the start of a segment of 1e4, 100 beyond a segment of 1, and b = 1e9. Fails if a theta
   rounded past +-pi/2 wraps tan around to the other end of the segment (the sample jumps
   from near b to a), or the formula loses the tail. */
static void test_equiangular_inverse_cdf(void)
{
#ifdef FOGRT_MINIMAL
    PART_II_ONLY("B: equiangular sampling");
#else
    static const eq_case extra[] = {
        {-5.0f, 1e-4f, 0.0f, INFINITY, 0, 0, "light far behind the start, 1e-4 from the line, b = +inf"},
        {-5.0f, 1e-4f, 0.0f, 10.0f, 0, 0, "light far behind the start, 1e-4 from the line"},
        {0.0f, 1e-4f, 0.0f, 1e4f, 0, 0, "light at the start of a long segment"},
        {100.0f, 0.1f, 0.0f, 1.0f, 0, 0, "light 100 beyond a segment of 1"},
        {0.0f, 1.0f, 0.0f, 1e9f, 0, 0, "b = 1e9"},
    };
    enum { M = 3 * 4096 };
    static double us[M];
    int m = 0;
    for (int k = 0; k < 4096; k++) us[m++] = k / 4096.0;
    float lo = 0.0f, hi = 1.0f;
    for (int k = 0; k < 4096; k++) { us[m++] = lo; lo = nextafterf(lo, 1.0f); }
    for (int k = 0; k < 4096; k++) { hi = nextafterf(hi, 0.0f); us[m++] = hi; }
    qsort(us, M, sizeof us[0], stats__double_cmp);
    int failed_cases = 0, cases = 0;
    char first[800] = "", msg[800];
    for (int k = 0; k < EQ_CASE_COUNT + (int)(sizeof extra / sizeof extra[0]); k++) {
        const eq_case *c = k < EQ_CASE_COUNT ? &EQ_CASES[k] : &extra[k - EQ_CASE_COUNT];
        eq_model md = eq_model_of(c->delta, c->h, c->a, c->b);
        double ta = md.theta_a, range = md.range;
        long bad = 0;
        char first_bad[300] = "";
        float prev = -INFINITY;
        for (int i = 0; i < M; i++) {
            float u = (float)us[i], pdf = -1.0f;
            float s = fogrt_sample_equiangular(c->delta, c->h, c->a, c->b, u, &pdf);
            double dt = (double)s - c->delta, den = (double)c->h * c->h + dt * dt;
            double err = fabs(eq_theta(&md, s) - (ta + (double)u * range));
            double tol = 6e-7 + 2.4e-7 * (fabs((double)s) + fabs(dt)) * c->h / den;
            bool ok = isfinite(s) && s >= c->a && s <= c->b && s >= prev && pdf > 0.0f && err <= tol;
            if (!ok) {
                if (bad++ == 0)
                    snprintf(first_bad, sizeof first_bad, "u=%.9g: t=%.9g (previous u gave %.9g), theta off by %.3g "
                             "rad (limit %.2g), pdf %g", (double)u, (double)s, (double)prev, err, tol, (double)pdf);
            }
            prev = s;
        }
        cases++;
        snprintf(msg, sizeof msg, "equiangular inverse CDF, %s (delta=%g h=%g [%g, %g], theta_b - theta_a = %.3g): "
                 "%ld of %d uniforms wrong%s%s", c->label, (double)c->delta, (double)c->h, (double)c->a, (double)c->b,
                 range, bad, M, bad ? "; first: " : "", first_bad);
        TEST_MESSAGE(msg);
        if (bad && failed_cases++ == 0) memcpy(first, msg, sizeof first);
    }
    if (failed_cases) {
        char fail[900];
        snprintf(fail, sizeof fail, "%d of %d cases failed; first: %s", failed_cases, cases, first);
        TEST_FAIL_MESSAGE(fail);
    }
#endif
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
        a.pdf = fogrt_sphere_solid_angle_pdf(c, r, p);
        double integral = 2.0 * STATS_PI * stats_integrate_1d(cone_pdf_1d, &a, -1.0, 1.0, 1e-12, 60);
        double exact = 2.0 * STATS_PI * cone_one_minus_cos(r, dist) * a.pdf;
        snprintf(msg, sizeof msg, "sphere solid angle pdf, r/|c-p| = %g: integral over the cone %.7f (closed form %.7f)",
                 (double)ratio[k], integral, exact);
        TEST_MESSAGE(msg);
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-5, 1.0, exact, msg);
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-5, 1.0, integral, msg);
    }
    /* From inside, the uniform sphere. */
    float inside = fogrt_sphere_solid_angle_pdf(v3(0.0f, 0.0f, 0.0f), 1.0f, v3(0.1f, 0.0f, 0.0f));
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
                    fogrt_vec3 wi = fogrt_sample_hg(gx[gi], wo, u1, u2, &pdf);
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
            assert_unit(fogrt_sample_sphere_solid_angle(v3(0, 0, 5), 1.0f, v3(0, 0, 0), u1, u2, &pdf), msg);
            TEST_ASSERT_TRUE_MESSAGE(isfinite(pdf) && pdf > 0.0f, msg);
            assert_unit(fogrt_sample_sphere_solid_angle(v3(0, 0, -100), 0.1f, v3(0, 0, 0), u1, u2, &pdf), msg);
            TEST_ASSERT_TRUE_MESSAGE(isfinite(pdf) && pdf > 0.0f, msg);
#ifndef FOGRT_MINIMAL   /* the glow is Part II's (B) */
            for (int w = 0; w < HG_WO_COUNT; w++) {      /* the glow: u1 = 0 aims at the lamp itself */
                fogrt_vec3 to = v3(HG_WO[w][0], HG_WO[w][1], HG_WO[w][2]), wi = fogrt_sample_glow(to, u1, u2, &pdf);
                float pe = fogrt_glow_pdf(to, wi);
                assert_unit(wi, msg);
                TEST_ASSERT_TRUE_MESSAGE(isfinite(pdf) && pdf > 0.0f && isfinite(pe) && pe > 0.0f, msg);
            }
#endif
            assert_unit(fogrt_sample_sphere_solid_angle(v3(0, 0, 0.5f), 1.0f, v3(0, 0, 0), u1, u2, &pdf), msg);
            TEST_ASSERT_TRUE_MESSAGE(isfinite(pdf) && pdf > 0.0f, msg);
            float b1 = -1.0f, b2 = -1.0f;
            fogrt_sample_triangle(u1, u2, &b1, &b2);
            TEST_ASSERT_TRUE_MESSAGE(b1 >= 0.0f && b2 >= 0.0f && b1 + b2 <= 1.0f, msg);
            float tdist = fogrt_sample_exponential(0.3f, u1);
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
    RUN_TEST(test_hg_peak_resolved);
    RUN_TEST(test_hg_pdf_at_the_peak);
    RUN_TEST(test_env_map_sampling);
    RUN_TEST(test_hg_mean_cosine_is_g);
    RUN_TEST(test_hg_sample_pdf_matches_eval);
    RUN_TEST(test_hg_phase_normalised);
    RUN_TEST(test_cosine_hemisphere_chi2);
    RUN_TEST(test_uniform_sphere_chi2);
    RUN_TEST(test_sphere_solid_angle_chi2);
    RUN_TEST(test_glow_sampling);
    RUN_TEST(test_equiangular_hg_ks);
    RUN_TEST(test_glow_hg_sampling);
    RUN_TEST(test_footprint_sampling);
    RUN_TEST(test_footprint_mixture);
    RUN_TEST(test_triangle_chi2);
    RUN_TEST(test_point_light_radius_directions_chi2);
    RUN_TEST(test_point_light_radius_irradiance);
    RUN_TEST(test_area_light_mesh_chi2);
    RUN_TEST(test_area_light_sphere_chi2);
    RUN_TEST(test_spot_falloff_values);
    RUN_TEST(test_exponential_ks);
    RUN_TEST(test_exponential_pdf_and_inverse);
    RUN_TEST(test_equiangular_ks);
    RUN_TEST(test_equiangular_pdf_normalised);
    RUN_TEST(test_equiangular_inverse_cdf);
    RUN_TEST(test_pdfs_normalised);
    RUN_TEST(test_extreme_uniforms);
    RUN_TEST(test_sidak_count_is_right);
    return UNITY_END();
}
