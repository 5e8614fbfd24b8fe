/* stats.h - statistics helpers for fogrt's distribution tests.

   Used by tests/test_sampling.c, tests/test_bsdf_stats.c, tests/test_media.c and
   tests/test_microfacet.c; docs/testing.md explains how to read what they print. Everything here is a static function of plain C99 with no state
   shared between programs, so a test file includes it after "fogrt.h" and uses what it needs.
   (The functions are `static inline` only so that a file that uses a few of them gets no
   unused-function warning.)

   What is here, in reading order:
     1. The suite's test count and the Sidak-corrected significance level.
     2. The chi-square distribution: regularized incomplete gamma, p-value.
     3. Pearson's chi-square statistic with Mitsuba 3's pooling of small cells.
     4. A grid over the sphere of directions in (cos theta, phi), observed counts, and
        expected counts from a pdf (adaptive cubature) or from an exact CDF.
     5. The Kolmogorov-Smirnov test in 1-D with the Kolmogorov distribution's p-value.
     6. A binomial test (how often did a two-way choice go one way?).
     7. Verdicts: the one-line message for each test, and the tables dumped on failure.

   A "positive" test checks that fogrt samples the distribution it claims; it must be
   accepted. A "negative control" feeds the same routine a deliberately wrong model and must
   be REJECTED: it proves the test has the power to see a real bug.                        */
#ifndef FOGRT_TESTS_STATS_H
#define FOGRT_TESTS_STATS_H

#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef STATS_PI
#define STATS_PI 3.14159265358979323846
#endif

/* ==========================================================================================
   1. How many tests, and the significance level
   ==========================================================================================
   Every statistical test below fails with probability alpha' even when fogrt is right (the
   seeds are fixed, so a given build either always passes or always fails; but a change of
   seed or sample count redraws the dice). To keep the chance of ANY false failure in the
   whole suite at STATS_ALPHA, each test uses the Sidak-corrected level
       alpha' = 1 - (1 - alpha)^(1 / number of tests).
   The count includes every positive chi-square test, and also the KS and binomial tests
   (a binomial score test is a chi-square test on two cells; counting KS too is the
   conservative choice). Negative controls are not counted: they cannot fail falsely by
   chance at this level, only through a lack of power, which is what they check.
   Each program checks at its end that it ran exactly its share, so these numbers stay right
   when someone adds or removes a test.                                                      */
#define STATS_ALPHA 0.01
#ifdef FOGRT_MINIMAL   /* Part I alone: the tests of Part II's samplers skip */
#define STATS_TESTS_SAMPLING   71   /* tests/test_sampling.c without equiangular, glow, footprint, map */
#else
#define STATS_TESTS_SAMPLING   90   /* tests/test_sampling.c: 74 chi-square + 16 KS */
#endif
#ifdef FOGRT_MINIMAL   /* Part I alone: the binomial tests of the exact Fresnel (Part II, C) skip */
#define STATS_TESTS_BSDF_STATS 11   /* tests/test_bsdf_stats.c: 5 chi-square + 6 binomial */
#else
#define STATS_TESTS_BSDF_STATS 17   /* tests/test_bsdf_stats.c: 5 chi-square + 12 binomial */
#endif
#ifdef FOGRT_NO_MEDIA   /* appendix G left out (also by FOGRT_MINIMAL): its tests skip */
#define STATS_TESTS_MEDIA      0
#else
#define STATS_TESTS_MEDIA      20   /* tests/test_media.c: 19 chi-square + 1 KS */
#endif
#ifdef FOGRT_NO_MICROFACET   /* appendix I left out (also by FOGRT_MINIMAL): its tests skip */
#define STATS_TESTS_MICROFACET 0
#else
#define STATS_TESTS_MICROFACET 16   /* tests/test_microfacet.c: 16 chi-square */
#endif
#define STATS_SUITE_TESTS (STATS_TESTS_SAMPLING + STATS_TESTS_BSDF_STATS + STATS_TESTS_MEDIA + STATS_TESTS_MICROFACET)

/* Where failing tests dump their tables (relative to the repository root, where tests run). */
#ifndef STATS_DUMP_DIR
#define STATS_DUMP_DIR "build"
#endif

/* alpha' = 1 - (1 - alpha)^(1/count), written with log1p/expm1 so it stays accurate when
   alpha' is tiny. */
static inline double stats_sidak_alpha(double alpha, int count)
{
    return -expm1(log1p(-alpha) / (double)count);
}

static inline double stats_alpha(void)
{
    return stats_sidak_alpha(STATS_ALPHA, STATS_SUITE_TESTS);
}

/* Positive tests run by this program (compared with its share by the last RUN_TEST). */
static inline int *stats_test_counter(void)
{
    static int count = 0;
    return &count;
}

/* ==========================================================================================
   2. The chi-square distribution
   ==========================================================================================
   If X ~ chi-square with k degrees of freedom, P(X > x) = Q(k/2, x/2) where Q is the
   regularized upper incomplete gamma function Q(a, x) = Gamma(a, x) / Gamma(a).
   Q = 1 - P; P has a power series that converges fast for x < a + 1, Q has a continued
   fraction that converges fast for x >= a + 1. We always evaluate the one that converges
   and take the complement, so both tails stay accurate.                                      */

/* exp(-x) x^a / Gamma(a): the common factor of both expansions, in logs to avoid overflow. */
static inline double stats__gamma_prefactor(double a, double x)
{
    return exp(a * log(x) - x - lgamma(a));
}

/* P(a, x) = prefactor * sum_{n>=0} x^n / (a (a+1) ... (a+n)). */
static inline double stats__gamma_p_series(double a, double x)
{
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < 100000; n++) {
        term *= x / (a + n);
        sum += term;
        if (term < sum * 1e-16) break;
    }
    return sum * stats__gamma_prefactor(a, x);
}

/* Q(a, x) = prefactor * 1/(x+1-a - 1(1-a)/(x+3-a - 2(2-a)/(x+5-a - ...))), evaluated from
   the front with the modified Lentz method (each step multiplies the estimate by C*D). */
static inline double stats__gamma_q_fraction(double a, double x)
{
    const double tiny = 1e-300;
    double b = x + 1.0 - a;        /* the current partial denominator */
    double C = 1.0 / tiny;         /* ratio of successive numerators   */
    double D = 1.0 / b;            /* ratio of successive denominators */
    double f = D;                  /* the fraction so far              */
    for (int n = 1; n < 100000; n++) {
        double an = -(double)n * ((double)n - a);   /* partial numerator */
        b += 2.0;
        D = an * D + b;
        if (fabs(D) < tiny) D = tiny;
        C = b + an / C;
        if (fabs(C) < tiny) C = tiny;
        D = 1.0 / D;
        f *= C * D;
        if (fabs(C * D - 1.0) < 1e-16) break;
    }
    return f * stats__gamma_prefactor(a, x);
}

/* Regularized upper incomplete gamma Q(a, x), a > 0, x >= 0. */
static inline double stats_gamma_q(double a, double x)
{
    if (x <= 0.0) return 1.0;
    if (x < a + 1.0) return 1.0 - stats__gamma_p_series(a, x);
    return stats__gamma_q_fraction(a, x);
}

/* p-value of a chi-square statistic: the probability of a value at least this large when
   the model is right. */
static inline double stats_chi2_pvalue(double chi2, int dof)
{
    if (dof < 1) return 0.0;
    return stats_gamma_q(0.5 * dof, 0.5 * chi2);
}

/* ==========================================================================================
   3. Pearson's chi-square with pooling (as in Mitsuba 3's chi2 test)
   ==========================================================================================
   chi2 = sum over cells (observed - expected)^2 / expected. The chi-square approximation
   of its distribution needs expected counts of about 5 or more, so: sort the cells by
   expected count; skip cells where both counts are 0; add cells with expected < 5 to a
   pool, and each time the pool's expected total passes 5, count the pool as one cell and
   empty it (a last pool below 5 is dropped). dof = number of terms - 1 (the counts are
   constrained to add up to the sample count). A cell with expected 0 but observed > 0
   means a sample landed where the pdf says none can: that alone fails the test.          */
typedef struct stats_chi2_result {
    double chi2;
    int dof;
    double p_value;
    int cells;              /* cells in the table */
    int pooled_cells;       /* cells that went into pools */
    int impossible_cells;   /* cells with expected 0 and observed > 0 */
    int impossible_cell;    /* the first such cell (index), or -1 */
    double observed_total, expected_total;
} stats_chi2_result;

typedef struct stats__cell { double expected, observed; int index; } stats__cell;

static inline int stats__cell_cmp(const void *a, const void *b)
{
    const stats__cell *x = (const stats__cell *)a, *y = (const stats__cell *)b;
    if (x->expected < y->expected) return -1;
    if (x->expected > y->expected) return 1;
    return x->index - y->index;   /* a total order: the result never depends on qsort */
}

static inline stats_chi2_result stats_chi2(const double *observed, const double *expected, int n)
{
    const double min_expected = 5.0;
    stats_chi2_result r;
    memset(&r, 0, sizeof r);
    r.cells = n;
    r.impossible_cell = -1;
    stats__cell *cells = (stats__cell *)malloc(sizeof(stats__cell) * (size_t)(n > 0 ? n : 1));
    if (!cells) { r.dof = 0; r.p_value = 0.0; return r; }
    for (int i = 0; i < n; i++) {
        cells[i].expected = expected[i];
        cells[i].observed = observed[i];
        cells[i].index = i;
        r.observed_total += observed[i];
        r.expected_total += expected[i];
    }
    qsort(cells, (size_t)n, sizeof cells[0], stats__cell_cmp);

    double pool_expected = 0.0, pool_observed = 0.0;
    int terms = 0;
    for (int i = 0; i < n; i++) {
        double e = cells[i].expected, o = cells[i].observed;
        if (e <= 0.0) {
            if (o > 0.0) {
                if (r.impossible_cells++ == 0) r.impossible_cell = cells[i].index;
            }
            continue;                      /* expected 0, observed 0: nothing to say */
        }
        if (e < min_expected) {
            pool_expected += e;
            pool_observed += o;
            r.pooled_cells++;
            if (pool_expected > min_expected) {
                double diff = pool_observed - pool_expected;
                r.chi2 += diff * diff / pool_expected;
                terms++;
                pool_expected = pool_observed = 0.0;
            }
        } else {
            double diff = o - e;
            r.chi2 += diff * diff / e;
            terms++;
        }
    }
    free(cells);
    r.dof = terms - 1;
    r.p_value = (r.impossible_cells > 0) ? 0.0 : stats_chi2_pvalue(r.chi2, r.dof);
    return r;
}

/* ==========================================================================================
   4. A grid over the sphere of directions
   ==========================================================================================
   Cells are rectangles in (cos theta, phi): equal steps in cos theta and in phi cut the
   sphere into equal solid angles (d omega = d cos_theta d phi), so a uniform distribution
   gives equal counts. theta and phi are measured in a frame (x, y, z) of our choice:
   cos_theta = dot(w, z), phi = atan2(dot(w, y), dot(w, x)) in [-pi, pi]. A test may put z
   along the axis of the distribution (the propagation direction for HG, the direction to a
   sphere light) and may choose unequal cos theta edges (for example equal-probability
   edges, so that a peaked distribution is resolved where its mass is).                      */
#define STATS_GRID_MAX_COS 512

typedef struct stats_sphere_grid {
    int n_cos, n_phi;
    double cos_edge[STATS_GRID_MAX_COS + 1];   /* increasing; cos_edge[0] = -1, [n_cos] = 1 */
    double x[3], y[3], z[3];                    /* orthonormal frame of the grid */
} stats_sphere_grid;

/* n_cos x n_phi cells, equal steps, world frame. Use an even n_cos to put an edge on the
   horizon (z = 0) for hemisphere distributions. */
static inline void stats_grid_init(stats_sphere_grid *g, int n_cos, int n_phi)
{
    memset(g, 0, sizeof *g);
    if (n_cos > STATS_GRID_MAX_COS) n_cos = STATS_GRID_MAX_COS;
    g->n_cos = n_cos;
    g->n_phi = n_phi;
    for (int i = 0; i <= n_cos; i++) g->cos_edge[i] = -1.0 + 2.0 * i / n_cos;
    g->cos_edge[n_cos] = 1.0;
    g->x[0] = 1.0; g->y[1] = 1.0; g->z[2] = 1.0;
}

/* Makes the grid's z axis point along (zx, zy, zz) (need not be unit) and completes the
   frame with any two perpendicular unit vectors. Computed in double, independently of
   fogrt's own frame code. */
static inline void stats_grid_set_axis(stats_sphere_grid *g, double zx, double zy, double zz)
{
    double len = sqrt(zx * zx + zy * zy + zz * zz);
    double z[3] = {zx / len, zy / len, zz / len};
    /* Start x from the world axis least aligned with z, then Gram-Schmidt. */
    double a[3] = {0.0, 0.0, 0.0};
    int k = (fabs(z[0]) <= fabs(z[1]) && fabs(z[0]) <= fabs(z[2])) ? 0 : (fabs(z[1]) <= fabs(z[2]) ? 1 : 2);
    a[k] = 1.0;
    double d = a[0] * z[0] + a[1] * z[1] + a[2] * z[2];
    double x[3] = {a[0] - d * z[0], a[1] - d * z[1], a[2] - d * z[2]};
    len = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    for (int i = 0; i < 3; i++) { x[i] /= len; g->x[i] = x[i]; g->z[i] = z[i]; }
    g->y[0] = z[1] * x[2] - z[2] * x[1];   /* y = z cross x */
    g->y[1] = z[2] * x[0] - z[0] * x[2];
    g->y[2] = z[0] * x[1] - z[1] * x[0];
}

/* The unit world direction at grid coordinates (cos_theta, phi). */
static inline void stats_grid_direction(const stats_sphere_grid *g, double cos_theta, double phi, double w[3])
{
    double s = sqrt(fmax(0.0, (1.0 - cos_theta) * (1.0 + cos_theta)));
    double lx = s * cos(phi), ly = s * sin(phi);
    for (int i = 0; i < 3; i++) w[i] = lx * g->x[i] + ly * g->y[i] + cos_theta * g->z[i];
}

/* Grid coordinates of a sampled direction. The direction is renormalised in double first
   (so a float rounding of its length does not move it across a cell edge); one whose length
   is off by more than 1e-4, or that is not finite, is reported as invalid (-1). */
static inline int stats_grid_cell(const stats_sphere_grid *g, double wx, double wy, double wz)
{
    double len2 = wx * wx + wy * wy + wz * wz;
    if (!isfinite(len2) || fabs(sqrt(len2) - 1.0) > 1e-4) return -1;
    double len = sqrt(len2);
    double w[3] = {wx / len, wy / len, wz / len};
    double lx = w[0] * g->x[0] + w[1] * g->x[1] + w[2] * g->x[2];
    double ly = w[0] * g->y[0] + w[1] * g->y[1] + w[2] * g->y[2];
    double lz = w[0] * g->z[0] + w[1] * g->z[1] + w[2] * g->z[2];
    /* cos theta row: the last edge <= lz (binary search over the edges). */
    int lo = 0, hi = g->n_cos;   /* invariant: cos_edge[lo] <= lz < cos_edge[hi] (or lz = 1) */
    if (lz >= 1.0) lo = g->n_cos - 1;
    else if (lz <= -1.0) lo = 0;
    else {
        while (hi - lo > 1) {
            int mid = (lo + hi) / 2;
            if (g->cos_edge[mid] <= lz) lo = mid; else hi = mid;
        }
    }
    double phi = atan2(ly, lx);
    int col = (int)floor((phi + STATS_PI) / (2.0 * STATS_PI) * g->n_phi);
    if (col < 0) col = 0;
    if (col >= g->n_phi) col = g->n_phi - 1;
    return lo * g->n_phi + col;
}

/* A pdf over directions: density per steradian at the unit world direction w. */
typedef double (*stats_dir_pdf)(const double w[3], void *user);
/* The exact probability of one grid cell, when a closed-form CDF is known. */
typedef double (*stats_cell_prob)(double cos0, double cos1, double phi0, double phi1, void *user);

/* Cubature of the pdf over one (cos, phi) rectangle: 3 x 3 Gauss-Legendre points. */
static inline double stats__rect_gauss(const stats_sphere_grid *g, stats_dir_pdf pdf, void *user,
                                       double c0, double c1, double p0, double p1)
{
    const double node[3] = {-0.77459666924148337704, 0.0, 0.77459666924148337704};
    const double weight[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
    double cm = 0.5 * (c0 + c1), ch = 0.5 * (c1 - c0);
    double pm = 0.5 * (p0 + p1), ph = 0.5 * (p1 - p0);
    double sum = 0.0;
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
            double w[3];
            stats_grid_direction(g, cm + ch * node[i], pm + ph * node[j], w);
            sum += weight[i] * weight[j] * pdf(w, user);
        }
    }
    return sum * ch * ph;
}

/* Adaptive cubature: split the rectangle in four; if the four children agree with the
   parent to within tol, accept their sum, else refine each child (depth-limited, so a
   discontinuity such as the edge of a cone costs a bounded amount of work). */
static inline double stats__rect_adaptive(const stats_sphere_grid *g, stats_dir_pdf pdf, void *user,
                                          double c0, double c1, double p0, double p1,
                                          double whole, double tol, int depth)
{
    double cm = 0.5 * (c0 + c1), pm = 0.5 * (p0 + p1);
    double q[4];
    q[0] = stats__rect_gauss(g, pdf, user, c0, cm, p0, pm);
    q[1] = stats__rect_gauss(g, pdf, user, cm, c1, p0, pm);
    q[2] = stats__rect_gauss(g, pdf, user, c0, cm, pm, p1);
    q[3] = stats__rect_gauss(g, pdf, user, cm, c1, pm, p1);
    double sum = q[0] + q[1] + q[2] + q[3];
    if (depth <= 0 || fabs(sum - whole) <= tol) return sum;
    return stats__rect_adaptive(g, pdf, user, c0, cm, p0, pm, q[0], 0.5 * tol, depth - 1)
         + stats__rect_adaptive(g, pdf, user, cm, c1, p0, pm, q[1], 0.5 * tol, depth - 1)
         + stats__rect_adaptive(g, pdf, user, c0, cm, pm, p1, q[2], 0.5 * tol, depth - 1)
         + stats__rect_adaptive(g, pdf, user, cm, c1, pm, p1, q[3], 0.5 * tol, depth - 1);
}

/* Expected counts: n_samples times the integral of the pdf over each cell. The tolerance
   asks for an error below 0.02 sqrt(expected) counts per cell, so the cubature adds at
   most about 0.0004 per cell to chi2 (its standard deviation is sqrt(2 dof)). Returns the
   integral of the pdf over the whole sphere (should be 1). */
static inline double stats_grid_expected_from_pdf(const stats_sphere_grid *g, stats_dir_pdf pdf, void *user,
                                                  double n_samples, double *expected)
{
    double total = 0.0;
    double dphi = 2.0 * STATS_PI / g->n_phi;
    for (int i = 0; i < g->n_cos; i++) {
        for (int j = 0; j < g->n_phi; j++) {
            double c0 = g->cos_edge[i], c1 = g->cos_edge[i + 1];
            double p0 = -STATS_PI + j * dphi, p1 = p0 + dphi;
            double whole = stats__rect_gauss(g, pdf, user, c0, c1, p0, p1);
            double count = fmax(whole * n_samples, 1.0);
            double tol = 0.02 * sqrt(count) / n_samples;
            double prob = stats__rect_adaptive(g, pdf, user, c0, c1, p0, p1, whole, tol, 6);
            expected[i * g->n_phi + j] = prob * n_samples;
            total += prob;
        }
    }
    return total;
}

/* Expected counts from an exact cell probability. Returns the total probability. */
static inline double stats_grid_expected_from_cells(const stats_sphere_grid *g, stats_cell_prob prob, void *user,
                                                    double n_samples, double *expected)
{
    double total = 0.0;
    double dphi = 2.0 * STATS_PI / g->n_phi;
    for (int i = 0; i < g->n_cos; i++) {
        for (int j = 0; j < g->n_phi; j++) {
            double p0 = -STATS_PI + j * dphi;
            double p = prob(g->cos_edge[i], g->cos_edge[i + 1], p0, p0 + dphi, user);
            expected[i * g->n_phi + j] = p * n_samples;
            total += p;
        }
    }
    return total;
}

/* 1-D adaptive Simpson quadrature of f over [a, b] (absolute tolerance tol). Starting from
   [-1, 1] the nodes are dyadic, -1 + k 2^-n, so they are exact floats down to steps of
   2^-24: a pdf taking a float argument is then evaluated exactly where we think it is. */
typedef double (*stats_fn1)(double x, void *user);

static inline double stats__simpson_step(stats_fn1 f, void *user, double a, double b, double fa, double fm,
                                         double fb, double whole, double tol, int depth)
{
    double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
    double flm = f(lm, user), frm = f(rm, user);
    double left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
    double right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
    double diff = left + right - whole;
    if (depth <= 0 || fabs(diff) <= 15.0 * tol) return left + right + diff / 15.0;
    return stats__simpson_step(f, user, a, m, fa, flm, fm, left, 0.5 * tol, depth - 1)
         + stats__simpson_step(f, user, m, b, fm, frm, fb, right, 0.5 * tol, depth - 1);
}

static inline double stats_integrate_1d(stats_fn1 f, void *user, double a, double b, double tol, int max_depth)
{
    /* Start from 16 panels so that a narrow peak cannot hide between the first nodes. */
    double sum = 0.0;
    const int panels = 16;
    for (int k = 0; k < panels; k++) {
        double x0 = a + (b - a) * k / panels, x1 = a + (b - a) * (k + 1) / panels;
        double f0 = f(x0, user), f1 = f(x1, user), fm = f(0.5 * (x0 + x1), user);
        double whole = (x1 - x0) / 6.0 * (f0 + 4.0 * fm + f1);
        sum += stats__simpson_step(f, user, x0, x1, f0, fm, f1, whole, tol / panels, max_depth);
    }
    return sum;
}

/* ==========================================================================================
   5. Kolmogorov-Smirnov in 1-D
   ==========================================================================================
   D = sup_x |F_n(x) - F(x)| between the empirical CDF of n samples and the model CDF F.
   For a continuous F and a right model, sqrt(n) D tends to the Kolmogorov distribution:
       P(K > t) = 2 sum_{k>=1} (-1)^(k-1) exp(-2 k^2 t^2)                   (fast for t >= 1)
                = 1 - sqrt(2 pi)/t sum_{k>=1} exp(-(2k-1)^2 pi^2 / (8 t^2))  (fast for t < 1)
   We use Stephens' finite-n correction t = D (sqrt(n) + 0.12 + 0.11 / sqrt(n)).           */
static inline double stats_kolmogorov_q(double t)
{
    if (t <= 0.0) return 1.0;
    if (t < 1.0) {
        double s = 0.0;
        for (int k = 1; k < 50; k++) {
            double m = 2.0 * k - 1.0;
            s += exp(-m * m * STATS_PI * STATS_PI / (8.0 * t * t));
        }
        return 1.0 - sqrt(2.0 * STATS_PI) / t * s;
    }
    double s = 0.0, sign = 1.0;
    for (int k = 1; k < 100; k++) {
        double term = exp(-2.0 * k * k * t * t);
        s += sign * term;
        sign = -sign;
        if (term < 1e-300) break;
    }
    return fmax(0.0, fmin(1.0, 2.0 * s));
}

typedef struct stats_ks_result {
    double D;          /* largest distance between the empirical CDF and the model */
    double at;         /* where it occurs */
    double p_value;
    int n;
} stats_ks_result;

static inline int stats__double_cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* KS test of the samples x[0..n) (sorted in place) against the model CDF. */
static inline stats_ks_result stats_ks(double *x, int n, stats_fn1 cdf, void *user)
{
    stats_ks_result r;
    memset(&r, 0, sizeof r);
    r.n = n;
    qsort(x, (size_t)n, sizeof x[0], stats__double_cmp);
    for (int i = 0; i < n; i++) {
        double F = cdf(x[i], user);
        double above = (double)(i + 1) / n - F;  /* the empirical CDF just after x[i] */
        double below = F - (double)i / n;        /* ... and just before it */
        double d = fmax(above, below);
        if (!(d <= r.D)) { r.D = d; r.at = x[i]; }   /* NaN also lands here */
    }
    double sn = sqrt((double)n);
    r.p_value = (r.D == r.D) ? stats_kolmogorov_q(r.D * (sn + 0.12 + 0.11 / sn)) : 0.0;
    return r;
}

/* ==========================================================================================
   6. Binomial test
   ==========================================================================================
   k successes in n independent trials of probability p. The score statistic
   z^2 = (k - n p)^2 / (n p (1 - p)) is Pearson's chi-square on the two cells (success,
   failure) and has 1 degree of freedom; the normal approximation behind it is good when
   n p (1 - p) is at least about 10 (the tests assert that). p = 0 or 1 is not random: then
   k must be 0 or n exactly.                                                                */
typedef struct stats_binomial_result {
    double chi2;
    double p_value;
    double frequency;      /* k / n */
    double std_error;      /* sqrt(p (1 - p) / n) */
} stats_binomial_result;

static inline stats_binomial_result stats_binomial(long k, long n, double p)
{
    stats_binomial_result r;
    r.frequency = (double)k / (double)n;
    r.std_error = sqrt(p * (1.0 - p) / (double)n);
    if (p <= 0.0 || p >= 1.0) {
        bool ok = (p <= 0.0) ? (k == 0) : (k == n);
        r.chi2 = ok ? 0.0 : HUGE_VAL;
        r.p_value = ok ? 1.0 : 0.0;
        return r;
    }
    double diff = (double)k - (double)n * p;
    r.chi2 = diff * diff / ((double)n * p * (1.0 - p));
    r.p_value = stats_chi2_pvalue(r.chi2, 1);
    return r;
}

/* ==========================================================================================
   7. Verdicts, messages and dumped tables
   ==========================================================================================
   Every test ends in a stats_verdict: pass says whether it came out as it must (accepted for
   a positive test, rejected for a negative control) and message is one line for
   TEST_MESSAGE, naming the distribution, its parameters, the statistic, dof, p-value and
   the level. A positive test that fails also writes its tables to
   STATS_DUMP_DIR/chi2_<name>.txt (or ks_<name>.txt) and names the file in the message.    */
typedef struct stats_verdict {
    bool pass;
    char message[768];
} stats_verdict;

/* A file-name-safe copy of name (letters, digits, '.', '-', '_'; everything else '_'). */
static inline void stats__safe_name(char *out, size_t size, const char *name)
{
    size_t i = 0;
    for (; name[i] && i + 1 < size; i++) {
        char c = name[i];
        bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                  c == '.' || c == '-' || c == '_';
        out[i] = ok ? c : '_';
    }
    out[i] = '\0';
}

/* Writes a rows x cols table of observed and expected counts and of the residuals
   (observed - expected) / sqrt(expected), one table row per line, so the three blocks can
   be read by eye or loaded in numpy/gnuplot. row_edges (rows + 1) and col_edges
   (cols + 1) label the cells; either may be NULL. Returns false if the file could not be
   opened (e.g. the build directory does not exist). */
static inline bool stats_dump_table(const char *path, const char *title, int rows, int cols,
                                    const double *row_edges, const char *row_label,
                                    const double *col_edges, const char *col_label,
                                    const double *observed, const double *expected)
{
    FILE *f = fopen(path, "w");
    if (!f) return false;
    fprintf(f, "# %s\n# %d rows (%s) x %d columns (%s)\n", title, rows, row_label, cols, col_label);
    if (row_edges) {
        fprintf(f, "# row edges (%s):", row_label);
        for (int i = 0; i <= rows; i++) fprintf(f, " %.9g", row_edges[i]);
        fprintf(f, "\n");
    }
    if (col_edges) {
        fprintf(f, "# column edges (%s):", col_label);
        for (int j = 0; j <= cols; j++) fprintf(f, " %.9g", col_edges[j]);
        fprintf(f, "\n");
    }
    const char *block[3] = {"observed counts", "expected counts",
                            "residuals (observed - expected) / sqrt(expected); 'inf' = sample where none can be"};
    for (int b = 0; b < 3; b++) {
        fprintf(f, "\n# %s\n", block[b]);
        for (int i = 0; i < rows; i++) {
            for (int j = 0; j < cols; j++) {
                int c = i * cols + j;
                double v;
                if (b == 0) v = observed[c];
                else if (b == 1) v = expected[c];
                else v = expected[c] > 0.0 ? (observed[c] - expected[c]) / sqrt(expected[c])
                                           : (observed[c] > 0.0 ? HUGE_VAL : 0.0);
                fprintf(f, b == 2 ? "%s%7.2f" : "%s%.6g", j ? " " : "", v);
            }
            fprintf(f, "\n");
        }
    }
    fclose(f);
    return true;
}

/* Counts a positive test; with negative = true nothing is counted. */
static inline void stats__count(bool negative)
{
    if (!negative) (*stats_test_counter())++;
}

/* The verdict of a chi-square test on a rows x cols table.
     name          short file-name stem, e.g. "hg_g0.3_wo1"
     distribution  what is sampled, e.g. "fogrt_sample_hg"
     parameter     e.g. "g=0.3 wo=(0,0,1)"
     invalid       samples that were not finite / not unit / outside the domain (any
                   invalid sample fails a positive test)
     negative      true for a negative control (it must be rejected)                     */
static inline stats_verdict stats_chi2_verdict(const char *name, const char *distribution, const char *parameter,
                                               int rows, int cols, const double *row_edges, const char *row_label,
                                               const double *col_edges, const char *col_label,
                                               const double *observed, const double *expected,
                                               long invalid, bool negative)
{
    stats_verdict v;
    stats__count(negative);
    stats_chi2_result r = stats_chi2(observed, expected, rows * cols);
    double alpha = stats_alpha();
    bool rejected = r.p_value < alpha || r.dof < 1 || invalid > 0;
    v.pass = negative ? rejected : !rejected;

    char extra[256] = "";
    if (invalid > 0)
        snprintf(extra, sizeof extra, "; %ld invalid samples (not finite, not unit length or outside the domain)", invalid);
    else if (r.impossible_cells > 0)
        snprintf(extra, sizeof extra, "; %d cells got samples where the model expects none (first: row %d col %d)",
                 r.impossible_cells, r.impossible_cell / cols, r.impossible_cell % cols);
    else if (r.dof < 1)
        snprintf(extra, sizeof extra, "; too few cells after pooling for a test");

    char file[256] = "";
    if (!v.pass && !negative) {
        char safe[160], path[224];
        stats__safe_name(safe, sizeof safe, name);
        snprintf(path, sizeof path, "%s/chi2_%s.txt", STATS_DUMP_DIR, safe);
        char title[400];
        snprintf(title, sizeof title, "%s [%s]: chi2 = %.3f, dof = %d, p = %.3g", distribution, parameter,
                 r.chi2, r.dof, r.p_value);
        if (stats_dump_table(path, title, rows, cols, row_edges, row_label, col_edges, col_label, observed, expected))
            snprintf(file, sizeof file, "; tables in %s", path);
        else
            snprintf(file, sizeof file, "; could not write %s", path);
    }

    const char *outcome;
    if (negative) outcome = rejected ? "rejected, as a negative control must be"
                                     : "NOT REJECTED: this negative control shows the test cannot see the error";
    else outcome = rejected ? "REJECTED: the samples do not follow the model" : "accepted";
    snprintf(v.message, sizeof v.message,
             "%schi2 %s [%s]: chi2=%.2f dof=%d p=%.4g (alpha'=%.3g; %.0f samples, %d cells, %d pooled)%s: %s%s",
             negative ? "negative control " : "", distribution, parameter, r.chi2, r.dof, r.p_value, alpha,
             r.observed_total, r.cells, r.pooled_cells, extra, outcome, file);
    return v;
}

/* The verdict of a KS test. model_cdf is evaluated again to dump the two CDFs at 101
   evenly spaced ranks when a positive test fails. x must be the sorted samples. */
static inline stats_verdict stats_ks_verdict(const char *name, const char *distribution, const char *parameter,
                                             const stats_ks_result *r, const double *x, stats_fn1 cdf, void *user,
                                             long invalid, bool negative)
{
    stats_verdict v;
    stats__count(negative);
    double alpha = stats_alpha();
    bool rejected = r->p_value < alpha || invalid > 0;
    v.pass = negative ? rejected : !rejected;
    char file[256] = "";
    if (!v.pass && !negative) {
        char safe[160], path[224];
        stats__safe_name(safe, sizeof safe, name);
        snprintf(path, sizeof path, "%s/ks_%s.txt", STATS_DUMP_DIR, safe);
        FILE *f = fopen(path, "w");
        if (f) {
            fprintf(f, "# %s [%s]: D = %.5g at x = %.6g, n = %d, p = %.3g\n", distribution, parameter, r->D, r->at,
                    r->n, r->p_value);
            fprintf(f, "# x  empirical_cdf  model_cdf\n");
            for (int k = 0; k <= 100; k++) {
                int i = (int)((double)k / 100.0 * (r->n - 1));
                fprintf(f, "%.9g %.6f %.6f\n", x[i], (double)(i + 1) / r->n, cdf(x[i], user));
            }
            fclose(f);
            snprintf(file, sizeof file, "; CDFs in %s", path);
        } else {
            snprintf(file, sizeof file, "; could not write %s", path);
        }
    }
    char extra[128] = "";
    if (invalid > 0) snprintf(extra, sizeof extra, "; %ld invalid samples", invalid);
    const char *outcome;
    if (negative) outcome = rejected ? "rejected, as a negative control must be"
                                     : "NOT REJECTED: this negative control shows the test cannot see the error";
    else outcome = rejected ? "REJECTED: the samples do not follow the model" : "accepted";
    snprintf(v.message, sizeof v.message, "%sKS %s [%s]: D=%.5f at x=%.5g, n=%d, sqrt(n)D=%.3f p=%.4g (alpha'=%.3g)%s: %s%s",
             negative ? "negative control " : "", distribution, parameter, r->D, r->at, r->n,
             r->D * sqrt((double)r->n), r->p_value, alpha, extra, outcome, file);
    return v;
}

/* The verdict of a binomial test: k of n trials went one way, the model says probability p. */
static inline stats_verdict stats_binomial_verdict(const char *distribution, const char *parameter,
                                                   long k, long n, double p, bool negative)
{
    stats_verdict v;
    stats__count(negative);
    stats_binomial_result r = stats_binomial(k, n, p);
    double alpha = stats_alpha();
    bool rejected = r.p_value < alpha;
    v.pass = negative ? rejected : !rejected;
    const char *outcome;
    if (negative) outcome = rejected ? "rejected, as a negative control must be"
                                     : "NOT REJECTED: this negative control shows the test cannot see the error";
    else outcome = rejected ? "REJECTED: the frequency does not match the probability" : "accepted";
    snprintf(v.message, sizeof v.message,
             "%sbinomial %s [%s]: %ld of %ld = %.5f, model %.5f +- %.5f (1 s.e.), chi2=%.2f dof=1 p=%.4g (alpha'=%.3g): %s",
             negative ? "negative control " : "", distribution, parameter, k, n, r.frequency, p, r.std_error, r.chi2,
             r.p_value, alpha, outcome);
    return v;
}

/* Collects the verdicts of one RUN_TEST so that every case runs and prints its line, and
   the test then fails once, naming the first case that went wrong. */
typedef struct stats_tally {
    int cases, failures;
    char first_failure[768];
} stats_tally;

static inline void stats_tally_add(stats_tally *t, const stats_verdict *v)
{
    t->cases++;
    if (!v->pass) {
        if (t->failures++ == 0) memcpy(t->first_failure, v->message, sizeof t->first_failure);
    }
}

/* Test-side helpers on top of the tally (they expand to Unity macros, so include unity.h first). */
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

#endif /* FOGRT_TESTS_STATS_H */
