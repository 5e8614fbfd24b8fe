/* test_microfacet.c - the rough metal (fogrt.h, Part II, I): CS184's microfacet conductor.

   What is checked, and against what:
   - the sampler against its own pdf: chi-square on a grid centred on the mirror direction
     (rows fine where the lobe is), for alpha from 0.01 to 1 at normal, oblique and grazing
     incidence and from the back side, with the share of draws that give no direction as a
     cell of its own; negative controls (a wrong alpha, a wrong wo) must be rejected;
   - eval against values computed apart: a table from Python (cmath's complex Fresnel from
     the s and p amplitudes, math.erf) at listed angles, and a double-precision evaluation
     written here (complex arithmetic by hand) at random pairs;
   - reciprocity, and the two sides alike;
   - energy: a white furnace (eta = k = 0 reflects everything): albedo at most 1, and close
     to 1 for small alpha; a render of a perfect-conductor sphere under a white sky;
   - alpha -> 0: the lobe closes on the mirror direction and the weight tends to the Fresnel
     reflectance there; a render at alpha 1e-3 matches the mirror's;
   - stiff inputs (alpha 1e-4 and 1000, k = 0, eta near 1, eta = k = 0, grazing) give finite
     values, and renders with fog and lamps give no NaN;
   - the loader: tests/data/dae_microfacet.dae, as CS184 writes <microfacet>.
   Built with FOGRT_NO_MICROFACET (or FOGRT_MINIMAL) only two tests run: the material is
   refused, and the loader falls back to a mirror or a diffuse surface with a warning.     */
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#define FOGRT_LOAD_IMPLEMENTATION
#include "fogrt_load.h"
#include "unity.h"
#include "stats.h"
#include "test_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void setUp(void) {}
void tearDown(void) {}

#define DATA_DIR "tests/data/"
static fogrt_material_desc metal(float alpha, fogrt_vec3 eta, fogrt_vec3 k)
{
    fogrt_material_desc m;
    memset(&m, 0, sizeof m);
    m.type = FOGRT_BSDF_MICROFACET;
    m.alpha = alpha; m.eta = eta; m.k = k;
    return m;
}
#ifndef FOGRT_NO_MICROFACET
/* CS184-like RGB indices of aluminium and silver. */
static const fogrt_vec3 AL_ETA = { 1.6574599f, 0.8803689f, 0.5212287f }, AL_K = { 9.2238691f, 6.2695232f, 4.8370012f };
static const fogrt_vec3 AG_ETA = { 0.059881f, 0.059881f, 0.047366f }, AG_K = { 4.0f, 3.5f, 2.8f };

static fogrt_vec3 dir_deg(double theta, double phi)
{
    double t = theta * STATS_PI / 180.0, p = phi * STATS_PI / 180.0;
    return v3((float)(sin(t) * cos(p)), (float)(sin(t) * sin(p)), (float)cos(t));
}
static bool finite3(fogrt_vec3 v) { return isfinite(v.x) && isfinite(v.y) && isfinite(v.z); }

/* ==========================================================================================
   The reference, in double: the formula of fogrt.h's appendix I written out again, with the
   conductor's Fresnel from the complex amplitudes rs, rp (not fogrt's real-valued form)
   ========================================================================================== */
typedef struct cplx { double re, im; } cplx;
static cplx c_make(double re, double im) { cplx c; c.re = re; c.im = im; return c; }
static cplx c_add(cplx a, cplx b) { return c_make(a.re + b.re, a.im + b.im); }
static cplx c_sub(cplx a, cplx b) { return c_make(a.re - b.re, a.im - b.im); }
static cplx c_mul(cplx a, cplx b) { return c_make(a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re); }
static cplx c_div(cplx a, cplx b)
{
    double d = b.re * b.re + b.im * b.im;
    return c_make((a.re * b.re + a.im * b.im) / d, (a.im * b.re - a.re * b.im) / d);
}
static cplx c_sqrt(cplx a)   /* principal root */
{
    double r = sqrt(sqrt(a.re * a.re + a.im * a.im)), t = 0.5 * atan2(a.im, a.re);
    return c_make(r * cos(t), r * sin(t));
}
static double c_abs2(cplx a) { return a.re * a.re + a.im * a.im; }

static double ref_fresnel(double eta, double k, double ci)
{
    cplx n = c_make(eta, k), one = c_make(1, 0), c = c_make(ci, 0);
    if (eta == 0.0 && k == 0.0) return 1.0;   /* n = 0: every wave reflected */
    cplx ct = c_sqrt(c_sub(one, c_div(c_make(1.0 - ci * ci, 0), c_mul(n, n))));
    cplx rs = c_div(c_sub(c, c_mul(n, ct)), c_add(c, c_mul(n, ct)));
    cplx rp = c_div(c_sub(c_mul(n, c), ct), c_add(c_mul(n, c), ct));
    return 0.5 * (c_abs2(rs) + c_abs2(rp));
}
static double ref_lambda(double alpha, const double w[3])
{
    double s = sqrt(w[0] * w[0] + w[1] * w[1]), a;
    if (s == 0.0) return 0.0;
    a = w[2] / (alpha * s);
    return 0.5 * (erf(a) - 1.0) + exp(-a * a) / (2.0 * a * sqrt(STATS_PI));
}
static double ref_d(double alpha, const double h[3])
{
    double t2 = (h[0] * h[0] + h[1] * h[1]) / (h[2] * h[2]);
    return exp(-t2 / (alpha * alpha)) / (STATS_PI * alpha * alpha * pow(h[2], 4));
}
/* f(wo, wi) per channel, both on the +z side. */
static void ref_eval(double alpha, fogrt_vec3 eta, fogrt_vec3 k, fogrt_vec3 wo_f, fogrt_vec3 wi_f, double out[3])
{
    double wo[3] = { wo_f.x, wo_f.y, wo_f.z }, wi[3] = { wi_f.x, wi_f.y, wi_f.z }, h[3], len = 0, oh = 0, g, d;
    double e[3] = { eta.x, eta.y, eta.z }, kk[3] = { k.x, k.y, k.z };
    for (int i = 0; i < 3; i++) { h[i] = wo[i] + wi[i]; len += h[i] * h[i]; }
    len = sqrt(len);
    for (int i = 0; i < 3; i++) { h[i] /= len; oh += wo[i] * h[i]; }
    g = 1.0 / (1.0 + ref_lambda(alpha, wo) + ref_lambda(alpha, wi));
    d = ref_d(alpha, h);
    for (int c = 0; c < 3; c++) out[c] = ref_fresnel(e[c], kk[c], oh) * g * d / (4.0 * wo[2] * wi[2]);
}

/* ==========================================================================================
   The sampler against its pdf
   ========================================================================================== */
typedef struct mf_pdf_args { fogrt_material_desc m; fogrt_vec3 wo; } mf_pdf_args;
static double mf_pdf_callback(const double w[3], void *user)
{
    const mf_pdf_args *a = (const mf_pdf_args *)user;
    return fogrt_bsdf_pdf(&a->m, a->wo, v3((float)w[0], (float)w[1], (float)w[2]));
}
#define MF_ROWS 40
#define MF_COLS 40
#define MF_CELLS (MF_ROWS * MF_COLS + 1)   /* + the draws that give no direction */

/* The grid: its axis on the mirror direction of wo, rows in 1 - cos from the axis spaced as
   u = s t / (1 - t) over equal steps of t, with s = 2 alpha^2 the lobe's own scale: about
   half the rows inside the lobe at every alpha, the rest out to the far side. */
static void mf_grid(stats_sphere_grid *g, fogrt_vec3 wo, float alpha)
{
    double s = 2.0 * (double)alpha * (double)alpha, T = 2.0 / (2.0 + s);
    stats_grid_init(g, MF_ROWS, MF_COLS);
    stats_grid_set_axis(g, -wo.x, -wo.y, wo.z);
    for (int j = 0; j <= MF_ROWS; j++) {
        double t = T * (double)(MF_ROWS - j) / MF_ROWS, u = s * t / (1.0 - t);
        g->cos_edge[j] = j == 0 ? -1.0 : j == MF_ROWS ? 1.0 : 1.0 - u;
    }
}

typedef struct mf_case { float alpha, theta, phi; int negative; } mf_case;
enum { MF_POSITIVE, MF_WRONG_ALPHA, MF_WRONG_WO };

/* Draws n samples into observed (the last cell: no direction), checking each one's pdf and
   weight against eval; returns the samples that were not unit or not finite. */
static long mf_draw(const fogrt_material_desc *m, fogrt_vec3 wo, const stats_sphere_grid *g, long n, uint64_t seed,
                    double *observed, long *bad_pdf, long *bad_weight)
{
    fogrt_rng rng;
    long invalid = 0;
    fogrt_rng_seed(&rng, seed, 3);
    memset(observed, 0, sizeof(double) * MF_CELLS);
    for (long i = 0; i < n; i++) {
        float ul = fogrt_rng_float(&rng), u1 = fogrt_rng_float(&rng), u2 = fogrt_rng_float(&rng);
        fogrt_bsdf_sample s;
        if (!fogrt_sample_bsdf(m, FOGRT_FRESNEL_DEFAULT, wo, ul, u1, u2, &s)) { observed[MF_CELLS - 1] += 1.0; continue; }
        int cell = stats_grid_cell(g, s.wi.x, s.wi.y, s.wi.z);
        if (cell < 0 || !(s.wi.z * wo.z > 0.0f)) { invalid++; continue; }
        observed[cell] += 1.0;
        float pdf = fogrt_bsdf_pdf(m, wo, s.wi);
        fogrt_vec3 f = fogrt_bsdf_eval(m, wo, s.wi);
        double want = (double)f.y * fabs((double)s.wi.z) / (double)pdf;
        if (!(s.pdf == pdf) || s.is_delta || s.is_transmission) ++*bad_pdf;
        if (!(fabs((double)s.weight.y - want) <= 2e-3 * want + 1e-6)) ++*bad_weight;
    }
    return invalid;
}

static void mf_chi2_case(stats_tally *t, const mf_case *c, int k, double *observed, double *expected)
{
    fogrt_material_desc m = metal(c->alpha, AL_ETA, AL_K);
    fogrt_vec3 wo = dir_deg(c->theta, c->phi);
    stats_sphere_grid g;
    double edges[MF_ROWS + 2], phi_edge[MF_COLS + 1], total;
    long n = SAN_REDUCED(200000L, 4), bad_pdf = 0, bad_weight = 0, invalid;
    char name[64], param[200], msg[400];
    mf_pdf_args a;
    mf_grid(&g, wo, c->alpha);
    invalid = mf_draw(&m, wo, &g, n, 50000u + (uint64_t)k, observed, &bad_pdf, &bad_weight);
    a.m = m; a.wo = wo;
    if (c->negative == MF_WRONG_ALPHA) a.m.alpha = c->alpha * 1.15f;
    if (c->negative == MF_WRONG_WO) a.wo = dir_deg(c->theta + 3.0f, c->phi);
    total = stats_grid_expected_from_pdf(&g, mf_pdf_callback, &a, (double)n, expected);
    expected[MF_CELLS - 1] = fmax(0.0, 1.0 - total) * (double)n;
    memcpy(edges, g.cos_edge, sizeof(double) * (MF_ROWS + 1));
    edges[MF_ROWS + 1] = 2.0;   /* the extra row: its first cell holds the draws without a direction */
    for (int j = 0; j <= MF_COLS; j++) phi_edge[j] = -STATS_PI + 2.0 * STATS_PI * j / MF_COLS;
    snprintf(name, sizeof name, "microfacet_a%g_t%g%s", (double)c->alpha, (double)c->theta, c->negative ? "_neg" : "");
    snprintf(param, sizeof param, "alpha=%g, wo=(%.4f,%.4f,%.4f)%s; pdf integrates to %.5f", (double)c->alpha,
             (double)wo.x, (double)wo.y, (double)wo.z,
             c->negative == MF_WRONG_ALPHA ? ", model: alpha x 1.15" : c->negative == MF_WRONG_WO ? ", model: wo 3 degrees lower" : "",
             total);
    if (!c->negative) {
        snprintf(msg, sizeof msg, "%s: %ld samples whose pdf is not fogrt_bsdf_pdf's (or flagged delta/transmission), %ld whose "
                 "weight is not f cos / pdf, %ld not unit or on the wrong side", param, bad_pdf, bad_weight, invalid);
        TEST_ASSERT_TRUE_MESSAGE(total <= 1.0 + 1e-3, msg);
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, bad_pdf, msg);
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, bad_weight, msg);
    }
    REPORT(*t, stats_chi2_verdict(name, "fogrt_sample_bsdf (microfacet) vs fogrt_bsdf_pdf", param, MF_ROWS + 1, MF_COLS,
                                  edges, "cos from the mirror direction", phi_edge, "phi", observed, expected, invalid,
                                  c->negative != MF_POSITIVE));
}

/* fogrt_sample_bsdf of the rough metal draws what fogrt_bsdf_pdf says, for alpha 0.01 to 1 at
   normal, oblique (60 degrees) and grazing (85 degrees) incidence and from the back side;
   every sample reports that pdf and the weight f cos / pdf; the pdf integrates to at most 1
   (draws without a direction are counted against the rest). Negative controls: the model
   with alpha 15% too large, and with wo 3 degrees off. Fails if sampling and pdf disagree,
   which biases every render where MIS weighs a light sample against the BSDF's. */
static void test_sampler_chi2(void)
{
    static const mf_case cases[] = {
        { 0.01f, 0, 0, 0 }, { 0.01f, 60, 30, 0 }, { 0.01f, 85, 0, 0 },
        { 0.05f, 0, 0, 0 }, { 0.05f, 60, 30, 0 }, { 0.05f, 85, 0, 0 },
        { 0.2f, 0, 0, 0 }, { 0.2f, 60, 30, 0 }, { 0.2f, 85, 0, 0 }, { 0.2f, 135, 200, 0 },
        { 0.5f, 0, 0, 0 }, { 0.5f, 60, 30, 0 }, { 0.5f, 85, 0, 0 },
        { 1.0f, 0, 0, 0 }, { 1.0f, 60, 30, 0 }, { 1.0f, 85, 0, 0 },
        { 0.2f, 60, 30, MF_WRONG_ALPHA }, { 0.05f, 60, 30, MF_WRONG_WO }, { 0.5f, 85, 0, MF_WRONG_ALPHA },
    };
    stats_tally t = { 0, 0, "" };
    double *observed = (double *)calloc(MF_CELLS + MF_COLS, sizeof(double));
    double *expected = (double *)calloc(MF_CELLS + MF_COLS, sizeof(double));
    TEST_ASSERT_TRUE(observed && expected);
    for (int k = 0; k < (int)(sizeof cases / sizeof cases[0]); k++) mf_chi2_case(&t, &cases[k], k, observed, expected);
    free(observed);
    free(expected);
    TALLY_ASSERT(t);
}

/* ==========================================================================================
   Eval against values computed apart
   ========================================================================================== */
/* f of aluminium at listed angles (degrees), from Python: cmath for the Fresnel amplitudes
   rs = (c - n ct)/(c + n ct), rp = (n c - ct)/(n c + ct) with n = eta + i k, math.erf for
   Lambda. Fails if D, G, F or the 1/(4 cos cos) is off anywhere. */
static void test_eval_listed_angles(void)
{
    static const struct { float alpha, to, po, ti, pi; double f[3]; } rows[] = {
        { 0.05f, 0, 0, 5, 180, { 13.885959, 13.7326988, 13.7492201 } },
        { 0.05f, 30, 0, 32, 180, { 35.6009481, 35.2057813, 35.2504623 } },
        { 0.5f, 60, 0, 45, 150, { 0.621938493, 0.614890406, 0.616114331 } },
        { 0.5f, 80, 90, 70, 270, { 3.1450865, 3.13831878, 3.19173142 } },
        { 1.0f, 10, 0, 85, 30, { 0.335258871, 0.331513324, 0.331972208 } },
        { 0.2f, 45, 0, 45, 180, { 3.67796127, 3.63652132, 3.6424538 } },
        { 0.01f, 20, 0, 20.5f, 180, { 693.520925, 685.858141, 686.690077 } },
    };
    char msg[300];
    for (int r = 0; r < (int)(sizeof rows / sizeof rows[0]); r++) {
        fogrt_material_desc m = metal(rows[r].alpha, AL_ETA, AL_K);
        fogrt_vec3 wo = dir_deg(rows[r].to, rows[r].po), wi = dir_deg(rows[r].ti, rows[r].pi);
        fogrt_vec3 f = fogrt_bsdf_eval(&m, wo, wi);
        double got[3] = { f.x, f.y, f.z }, ref[3];
        ref_eval(rows[r].alpha, AL_ETA, AL_K, wo, wi, ref);
        for (int c = 0; c < 3; c++) {
            snprintf(msg, sizeof msg, "alpha %g, wo (%g, %g) deg, wi (%g, %g) deg, channel %d: fogrt %.7g, Python %.9g, "
                     "this file's double %.9g", (double)rows[r].alpha, (double)rows[r].to, (double)rows[r].po,
                     (double)rows[r].ti, (double)rows[r].pi, c, got[c], rows[r].f[c], ref[c]);
            TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(2e-4 * rows[r].f[c], rows[r].f[c], got[c], msg);
            TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-5 * rows[r].f[c], rows[r].f[c], ref[c], msg);
        }
    }
}

/* At random pairs of directions, alphas and indices (silver, aluminium, eta near 1 with
   k = 0, a perfect conductor): fogrt's float eval within 1e-3 of the double reference
   (where f cos is not negligible), reciprocal, the same on the back side, 0 across the
   surface, and pdf >= 0 finite. Fails on a wrong formula, a broken symmetry, or a lost
   digit at small alpha. */
static void test_eval_random_pairs_reciprocity(void)
{
    static const float alphas[] = { 1e-4f, 0.01f, 0.05f, 0.2f, 0.5f, 1.0f, 3.0f };
    const fogrt_vec3 etas[4] = { AG_ETA, AL_ETA, { 1.001f, 1.0001f, 1.01f }, { 0, 0, 0 } };
    const fogrt_vec3 ks[4] = { AG_K, AL_K, { 0, 0, 0 }, { 0, 0, 0 } };
    test_rng r = { 4242 };
    char msg[400];
    long checked = 0;
    for (int i = 0; i < 20000; i++) {
        float alpha = alphas[i % 7];
        int mat = (i / 7) % 4;
        fogrt_material_desc m = metal(alpha, etas[mat], ks[mat]);
        fogrt_vec3 wo = dir_deg(89.9 * rng_uniform(&r), 360.0 * rng_uniform(&r)), wi;
        if (i % 2) wi = dir_deg(89.9 * rng_uniform(&r), 360.0 * rng_uniform(&r));
        else wi = dir_deg(acos((double)wo.z) * 180.0 / STATS_PI + alpha * 40.0 * (rng_uniform(&r) - 0.5f),
                          atan2((double)-wo.y, (double)-wo.x) * 180.0 / STATS_PI + 20.0 * (rng_uniform(&r) - 0.5f));
        if (!(wi.z > 0.0f)) continue;
        fogrt_vec3 f = fogrt_bsdf_eval(&m, wo, wi), fr = fogrt_bsdf_eval(&m, wi, wo);
        fogrt_vec3 fb = fogrt_bsdf_eval(&m, v3(wo.x, wo.y, -wo.z), v3(wi.x, wi.y, -wi.z));
        fogrt_vec3 fx = fogrt_bsdf_eval(&m, wo, v3(wi.x, wi.y, -wi.z));
        float pdf = fogrt_bsdf_pdf(&m, wo, wi);
        double ref[3], got[3] = { f.x, f.y, f.z }, gr[3] = { fr.x, fr.y, fr.z }, gb[3] = { fb.x, fb.y, fb.z };
        ref_eval(alpha, etas[mat], ks[mat], wo, wi, ref);
        snprintf(msg, sizeof msg, "alpha %g, index %d, wo (%.6f %.6f %.6f), wi (%.6f %.6f %.6f): f %.7g (double %.9g), "
                 "f(wi, wo) %.7g, back side %.7g, across %.3g, pdf %.4g", (double)alpha, mat, (double)wo.x, (double)wo.y,
                 (double)wo.z, (double)wi.x, (double)wi.y, (double)wi.z, got[0], ref[0], gr[0], gb[0], (double)fx.x,
                 (double)pdf);
        TEST_ASSERT_TRUE_MESSAGE(fx.x == 0.0f && fx.y == 0.0f && fx.z == 0.0f, msg);
        TEST_ASSERT_TRUE_MESSAGE(pdf >= 0.0f && isfinite(pdf) && finite3(f), msg);
        /* the float half vector's rounding (1e-7) moves Beckmann's exponent t^2 / alpha^2 by
           2e-7 t / alpha^2: allowed for, it grows as alpha falls */
        double hx = (double)wo.x + wi.x, hy = (double)wo.y + wi.y, hz = (double)wo.z + wi.z;
        double tol = 1e-3 + 4e-7 * sqrt(hx * hx + hy * hy) / hz / ((double)alpha * alpha);
        for (int c = 0; c < 3; c++) {
            double scale = fmax(ref[c], 1e-3 / (double)wi.z);   /* f cos below 1e-3: absolute */
            TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(tol * scale, ref[c], got[c], msg);
            /* float: G summed in another order, F at wi.h instead of wo.h (equal in exact
               arithmetic); F of a nearly index-matched metal, ~(eta - 1)^2, keeps fewer digits */
            TEST_ASSERT_DOUBLE_WITHIN_MESSAGE((mat == 2 ? 3e-3 : 1e-4) * scale, got[c], gr[c], msg);
            TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-6 * scale, got[c], gb[c], msg);
        }
        checked++;
    }
    snprintf(msg, sizeof msg, "%ld pairs checked against the double reference, reciprocity and the back side", checked);
    TEST_MESSAGE(msg);
}

/* ==========================================================================================
   Energy
   ========================================================================================== */
/* The albedo int f cos dwi of a perfect conductor (eta = k = 0: F = 1) as the mean weight
   of n samples (a draw without a direction counts 0), with its standard error. */
static double mf_albedo(float alpha, double theta, long n, double *se)
{
    fogrt_material_desc m = metal(alpha, v3(0, 0, 0), v3(0, 0, 0));
    fogrt_vec3 wo = dir_deg(theta, 10.0);
    fogrt_rng rng;
    double sum = 0, sum2 = 0;
    fogrt_rng_seed(&rng, 777, (uint64_t)(alpha * 1000.0f) + (uint64_t)theta);
    for (long i = 0; i < n; i++) {
        fogrt_bsdf_sample s;
        float u1 = fogrt_rng_float(&rng), u2 = fogrt_rng_float(&rng);
        double w = fogrt_sample_bsdf(&m, FOGRT_FRESNEL_DEFAULT, wo, 0.5f, u1, u2, &s) ? (double)s.weight.x : 0.0;
        sum += w; sum2 += w * w;
    }
    *se = std_error_of_mean(sum, sum2, n);
    return sum / (double)n;
}

/* White furnace: a perfect conductor reflects at most what arrives (albedo <= 1 within 4
   standard errors; Smith's shadowing loses some at large alpha and grazing angles), and a
   nearly smooth one nearly all of it (>= 0.99 for alpha <= 0.05 up to 60 degrees). Fails if
   the weight or the pdf is off by a factor, or G lets light be made. */
static void test_white_furnace_albedo(void)
{
    static const float alphas[] = { 0.01f, 0.05f, 0.2f, 0.5f, 1.0f };
    static const double thetas[] = { 0, 30, 60, 80, 89 };
    char msg[200], line[600] = "albedo (rows alpha 0.01 0.05 0.2 0.5 1; columns 0 30 60 80 89 degrees):";
    for (int a = 0; a < 5; a++) {
        for (int t = 0; t < 5; t++) {
            double se, alb = mf_albedo(alphas[a], thetas[t], SAN_REDUCED(100000L, 4), &se);
            snprintf(msg, sizeof msg, " %.4f", alb);
            strncat(line, msg, sizeof line - strlen(line) - 1);
            snprintf(msg, sizeof msg, "alpha %g, theta %g: albedo %.5f +- %.5f", (double)alphas[a], thetas[t], alb, se);
            TEST_ASSERT_TRUE_MESSAGE(alb <= 1.0 + 4.0 * se + 1e-6, msg);
            if (alphas[a] <= 0.05f && thetas[t] <= 60.0) TEST_ASSERT_TRUE_MESSAGE(alb >= 0.99, msg);
            if (alphas[a] <= 0.2f && thetas[t] <= 60.0) TEST_ASSERT_TRUE_MESSAGE(alb >= 0.95, msg);
        }
        strncat(line, a < 4 ? ";" : "", sizeof line - strlen(line) - 1);
    }
    TEST_MESSAGE(line);
}

/* A scene: a closed white box with a ceiling lamp (test_util.h), two spheres of the given
   materials, a camera inside; fog if sigma_t > 0. */
static fogrt_scene *metal_box(const fogrt_material_desc *a, const fogrt_material_desc *b, float sigma_t, bool lamp)
{
    fogrt_scene *s = NULL;
    uint32_t ia, ib;
    CHECK_OK(fogrt_scene_create(NULL, &s));
    add_closed_box(s, 0.3f, 12.0f);
    CHECK_OK(fogrt_scene_add_material(s, a, &ia));
    CHECK_OK(fogrt_scene_add_material(s, b, &ib));
    CHECK_OK(fogrt_scene_add_sphere(s, v3(-0.45f, 0.4f, -0.3f), 0.4f, ia));
    CHECK_OK(fogrt_scene_add_sphere(s, v3(0.5f, 0.35f, 0.2f), 0.35f, ib));
    if (lamp) {
        fogrt_light_desc l;
        memset(&l, 0, sizeof l);
        l.type = FOGRT_LIGHT_SPOT; l.position = v3(-0.7f, 1.8f, 0.6f); l.direction = v3(1.0f, -1.6f, -0.8f);
        l.intensity = v3(6, 6, 6); l.cutoff_deg = 25; l.beam_deg = 18;
        CHECK_OK(fogrt_scene_add_light(s, &l));
    }
    set_camera(s, v3(0, 1.0f, 0.95f), v3(0, 0.55f, -0.3f), 70.0f);
    if (sigma_t > 0.0f) set_medium(s, sigma_t, v3(0.9f, 0.9f, 0.9f), 0.4f);
    CHECK_OK(fogrt_scene_build(s, NULL));
    return s;
}
/* Renders w x h at spp samples; returns the mean of channel c and the count of non-finite
   values (which must be none), and the image's standard error of that mean. */
static double render_mean(const fogrt_scene *s, const fogrt_render_desc *rd, int w, int h, int spp, int *bad, float *rgb)
{
    fogrt_image img;
    double sum = 0.0;
    CHECK_OK(fogrt_image_alloc(&img, w, h, NULL));
    CHECK_OK(fogrt_render(s, rd, &img, spp, NULL));
    fogrt_image_resolve(&img, rgb);
    *bad = 0;
    for (int i = 0; i < 3 * w * h; i++) {
        if (!isfinite(rgb[i]) || rgb[i] < 0.0f) ++*bad;
        else sum += rgb[i];
    }
    fogrt_image_free(&img);
    return sum / (3.0 * w * h);
}

/* A perfect-conductor sphere alone under a white sky (radiance 1, no fog, no lamp): each
   ray that meets it reflects once and leaves, so its pixels show the albedo: at most 1,
   near 1 for alpha 0.05. Checked on the pixels the sphere covers. */
static void test_furnace_render(void)
{
    static const float alphas[] = { 0.05f, 0.5f };
    char msg[200];
    for (int a = 0; a < 2; a++) {
        fogrt_scene *s = NULL;
        fogrt_material_desc m = metal(alphas[a], v3(0, 0, 0), v3(0, 0, 0));
        fogrt_render_desc rd = fogrt_render_defaults();
        uint32_t id;
        int w = 32, h = 32, bad = 0, n = 0;
        double sum = 0, lo = 2, hi = 0;
        float *rgb = (float *)malloc(sizeof(float) * 3 * 32 * 32);
        TEST_ASSERT_NOT_NULL(rgb);
        CHECK_OK(fogrt_scene_create(NULL, &s));
        CHECK_OK(fogrt_scene_add_material(s, &m, &id));
        CHECK_OK(fogrt_scene_add_sphere(s, v3(0, 0, 0), 1.0f, id));
        CHECK_OK(fogrt_scene_set_environment(s, v3(1, 1, 1), false));
        set_camera(s, v3(0, 0, 4), v3(0, 0, 0), 40.0f);
        CHECK_OK(fogrt_scene_build(s, NULL));
        rd.seed = 9; rd.width = w; rd.height = h;
        (void)render_mean(s, &rd, w, h, SAN_REDUCED(256, 4), &bad, rgb);
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++) {
                double dx = (x + 0.5) / w - 0.5, dy = (y + 0.5) / h - 0.5;
                /* rays within 7 degrees of the axis meet the sphere (radius 1 at distance 4)
                   at most 29 degrees from its normal */
                if (2.0 * sqrt(dx * dx + dy * dy) * tan(20.0 * STATS_PI / 180.0) > tan(7.0 * STATS_PI / 180.0)) continue;
                double v = rgb[3 * (y * w + x)];
                sum += v; n++;
                lo = fmin(lo, v); hi = fmax(hi, v);
            }
        snprintf(msg, sizeof msg, "alpha %g: %d pixels on the sphere, mean %.5f, min %.4f, max %.4f; %d not finite",
                 (double)alphas[a], n, n ? sum / n : 0.0, lo, hi, bad);
        TEST_MESSAGE(msg);
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, bad, msg);
        TEST_ASSERT_TRUE_MESSAGE(n > 50 && sum / n <= 1.0 + 2e-3, msg);
        TEST_ASSERT_TRUE_MESSAGE(sum / n >= (alphas[a] < 0.1f ? 0.99 : 0.9), msg);
        free(rgb);
        fogrt_scene_destroy(s);
    }
}

/* ==========================================================================================
   alpha -> 0: the mirror
   ========================================================================================== */
/* As alpha falls from 0.1 to 1e-4 the sampled directions close on the mirror direction
   (mean angle below 2 alpha) and the mean weight tends to aluminium's Fresnel reflectance
   at that angle (within 0.5% from alpha 1e-3 down). Fails if the lobe is centred wrong or
   the weight keeps a factor that does not vanish with alpha. */
static void test_alpha_to_zero_directions(void)
{
    static const float alphas[] = { 0.1f, 0.01f, 1e-3f, 1e-4f };
    fogrt_vec3 wo = dir_deg(40.0, 20.0), mirror = v3(-wo.x, -wo.y, wo.z);
    double F[3] = { ref_fresnel(AL_ETA.x, AL_K.x, wo.z), ref_fresnel(AL_ETA.y, AL_K.y, wo.z), ref_fresnel(AL_ETA.z, AL_K.z, wo.z) };
    char msg[300];
    for (int a = 0; a < 4; a++) {
        fogrt_material_desc m = metal(alphas[a], AL_ETA, AL_K);
        fogrt_rng rng;
        double angle = 0, wsum[3] = { 0, 0, 0 };
        long n = 20000, got = 0;
        fogrt_rng_seed(&rng, 31, (uint64_t)a);
        for (long i = 0; i < n; i++) {
            fogrt_bsdf_sample s;
            float u1 = fogrt_rng_float(&rng), u2 = fogrt_rng_float(&rng);
            if (!fogrt_sample_bsdf(&m, FOGRT_FRESNEL_DEFAULT, wo, 0.5f, u1, u2, &s)) continue;
            angle += acos(fmin(1.0, (double)vdot(s.wi, mirror)));
            wsum[0] += s.weight.x; wsum[1] += s.weight.y; wsum[2] += s.weight.z;
            got++;
        }
        snprintf(msg, sizeof msg, "alpha %g: %ld of %ld drew a direction, mean angle to the mirror direction %.3g rad, "
                 "mean weight (%.5f %.5f %.5f), Fresnel at 40 degrees (%.5f %.5f %.5f)", (double)alphas[a], got, n,
                 angle / (double)got, wsum[0] / n, wsum[1] / n, wsum[2] / n, F[0], F[1], F[2]);
        TEST_MESSAGE(msg);
        TEST_ASSERT_TRUE_MESSAGE(angle / (double)got < 2.0 * alphas[a] + 1e-6, msg);
        if (alphas[a] <= 1e-3f) {
            TEST_ASSERT_EQUAL_INT_MESSAGE(n, got, msg);
            for (int c = 0; c < 3; c++) TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(5e-3 * F[c], F[c], wsum[c] / n, msg);
        }
    }
}

/* In a fog-filled box lit by an area lamp, two perfect-conductor spheres of alpha 1e-3 and
   1e-4 render as mirror spheres of reflectance 1 do: the image means within 2%. The two
   estimators differ (light samples weighed by MIS against a narrow lobe, or none against a
   delta one), so this checks the rough metal through the whole integrator. (Not with a
   point or spot lamp: the light it sends off a mirror is a caustic no path tracer finds,
   while a rough metal's is found, ever more rarely and brightly as alpha falls.) */
static void test_alpha_to_zero_render(void)
{
    fogrt_material_desc rough = metal(1e-3f, v3(0, 0, 0), v3(0, 0, 0)), rough_al = metal(1e-4f, v3(0, 0, 0), v3(0, 0, 0));
    fogrt_material_desc mirror, mirror_al;
    fogrt_render_desc rd = fogrt_render_defaults();
    int w = 48, h = 36, bad1 = 0, bad2 = 0;
    float *rgb = (float *)malloc(sizeof(float) * 3 * 48 * 36);
    char msg[300];
    TEST_ASSERT_NOT_NULL(rgb);
    memset(&mirror, 0, sizeof mirror);
    mirror.type = FOGRT_BSDF_MIRROR; mirror.reflectance = v3(1, 1, 1);
    mirror_al = mirror;
    rd.seed = 5; rd.width = w; rd.height = h;
    fogrt_scene *sr = metal_box(&rough, &rough_al, 0.3f, false), *sm = metal_box(&mirror, &mirror_al, 0.3f, false);
    double mr = render_mean(sr, &rd, w, h, SAN_REDUCED(128, 8), &bad1, rgb);
    double mm = render_mean(sm, &rd, w, h, SAN_REDUCED(128, 8), &bad2, rgb);
    snprintf(msg, sizeof msg, "fog-filled box: rough metal alpha 1e-3 mean %.5f, mirror mean %.5f (%+.2f%%); non-finite %d, %d",
             mr, mm, 100.0 * (mr / mm - 1.0), bad1, bad2);
    TEST_MESSAGE(msg);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, bad1 + bad2, msg);
    TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(0.02 * mm, mm, mr, msg);
    fogrt_scene_destroy(sr);
    fogrt_scene_destroy(sm);
    free(rgb);
}

/* ==========================================================================================
   Stiff and extreme inputs
   ========================================================================================== */
/* alpha 1e-4, 1 and 1000, k = 0 with eta near 1 (reflects almost nothing), eta = k = 0,
   silver; wo and wi from normal to within 1e-7 of the horizon, u at 0 and just below 1:
   sample, eval and pdf are finite and non-negative, samples unit and on wo's side. Fails
   on any NaN or infinity an image could receive. */
static void test_extreme_inputs_finite(void)
{
    static const float alphas[] = { 1e-4f, 1e-3f, 0.05f, 1.0f, 1e3f };
    static const float cosines[] = { 1.0f, 0.5f, 1e-2f, 1e-4f, 1e-7f, -1e-7f, -0.3f };
    static const float us[] = { 0.0f, 0.5f, 0.999f, 1.0f - 0x1p-24f };
    const fogrt_vec3 etas[4] = { { 1.0001f, 1.0f, 0.9999f }, { 0, 0, 0 }, AG_ETA, { 1e4f, 0.5f, 3.0f } };
    const fogrt_vec3 ks[4] = { { 0, 0, 0 }, { 0, 0, 0 }, AG_K, { 0, 1e4f, 0 } };
    char msg[300];
    long cases = 0;
    for (int a = 0; a < 5; a++)
        for (int e = 0; e < 4; e++)
            for (int c = 0; c < 7; c++)
                for (int i = 0; i < 4; i++)
                    for (int j = 0; j < 4; j++) {
                        fogrt_material_desc m = metal(alphas[a], etas[e], ks[e]);
                        float co = cosines[c], so = sqrtf(fmaxf(0.0f, 1.0f - co * co));
                        fogrt_vec3 wo = v3(so * 0.6f, so * 0.8f, co), wi = dir_deg(85.0 * us[j], 360.0 * us[i]);
                        fogrt_bsdf_sample s;
                        bool ok = fogrt_sample_bsdf(&m, FOGRT_FRESNEL_DEFAULT, wo, 0.5f, us[i], us[j], &s);
                        fogrt_vec3 f = fogrt_bsdf_eval(&m, wo, co < 0 ? v3(wi.x, wi.y, -wi.z) : wi);
                        float pdf = fogrt_bsdf_pdf(&m, wo, co < 0 ? v3(wi.x, wi.y, -wi.z) : wi);
                        snprintf(msg, sizeof msg, "alpha %g, index %d, cos_o %g, u (%g, %g): sample %d weight (%g %g %g) pdf %g "
                                 "wi.z %g; eval (%g %g %g) pdf %g", (double)alphas[a], e, (double)co, (double)us[i],
                                 (double)us[j], ok, (double)s.weight.x, (double)s.weight.y, (double)s.weight.z,
                                 (double)s.pdf, (double)s.wi.z, (double)f.x, (double)f.y, (double)f.z, (double)pdf);
                        TEST_ASSERT_TRUE_MESSAGE(finite3(f) && f.x >= 0 && f.y >= 0 && f.z >= 0, msg);
                        TEST_ASSERT_TRUE_MESSAGE(isfinite(pdf) && pdf >= 0.0f, msg);
                        if (ok) {
                            TEST_ASSERT_TRUE_MESSAGE(finite3(s.weight) && s.weight.x >= 0 && s.weight.y >= 0 && s.weight.z >= 0, msg);
                            TEST_ASSERT_TRUE_MESSAGE(isfinite(s.pdf) && s.pdf > 0.0f && s.wi.z * co > 0.0f, msg);
                            TEST_ASSERT_FLOAT_WITHIN_MESSAGE(1e-5f, 1.0f, sqrtf(vdot(s.wi, s.wi)), msg);
                        }
                        cases++;
                    }
    snprintf(msg, sizeof msg, "%ld (alpha, index, wo, u) cases finite", cases);
    TEST_MESSAGE(msg);
}

/* The extreme materials in renders: fog, a spot lamp in it, an area lamp, both spheres
   alpha 1e-4 with eta near 1 and k = 0 / alpha 1 perfect conductor, then alpha 1000
   silver / alpha 1e-4 silver: no pixel is NaN, infinite or negative, with both the full
   integrator and the paper's. */
static void test_extreme_renders_finite(void)
{
    fogrt_material_desc pairs[2][2] = {
        { metal(1e-4f, v3(1.0001f, 1.0f, 1.0001f), v3(0, 0, 0)), metal(1.0f, v3(0, 0, 0), v3(0, 0, 0)) },
        { metal(1e3f, AG_ETA, AG_K), metal(1e-4f, AG_ETA, AG_K) },
    };
    float *rgb = (float *)malloc(sizeof(float) * 3 * 32 * 24);
    char msg[200];
    TEST_ASSERT_NOT_NULL(rgb);
    for (int p = 0; p < 2; p++)
        for (int paper = 0; paper < 2; paper++) {
            fogrt_scene *s = metal_box(&pairs[p][0], &pairs[p][1], 0.5f, true);
            fogrt_render_desc rd = paper ? fogrt_render_paper_defaults() : fogrt_render_defaults();
            int bad = 0;
            rd.seed = 11; rd.width = 32; rd.height = 24;
            double mean = render_mean(s, &rd, 32, 24, SAN_REDUCED(32, 4), &bad, rgb);
            snprintf(msg, sizeof msg, "pair %d, %s integrator: mean %.4f, %d values not finite or negative", p,
                     paper ? "the paper's" : "the full", mean, bad);
            TEST_MESSAGE(msg);
            TEST_ASSERT_EQUAL_INT_MESSAGE(0, bad, msg);
            TEST_ASSERT_TRUE_MESSAGE(mean > 0.0, msg);
            fogrt_scene_destroy(s);
        }
    free(rgb);
}

/* fogrt_scene_add_material refuses a rough metal it cannot render: alpha 0, negative, NaN
   or infinite; a negative or NaN eta or k. A valid one is kept as given. */
static void test_material_checks(void)
{
    fogrt_scene *s = NULL;
    fogrt_material_desc bad[7], m;
    uint32_t id;
    int n = 0;
    CHECK_OK(fogrt_scene_create(NULL, &s));
    bad[n++] = metal(0.0f, AL_ETA, AL_K);
    bad[n++] = metal(-0.1f, AL_ETA, AL_K);
    bad[n++] = metal(NAN, AL_ETA, AL_K);
    bad[n++] = metal(INFINITY, AL_ETA, AL_K);
    bad[n++] = metal(0.1f, v3(-1, 1, 1), AL_K);
    bad[n++] = metal(0.1f, AL_ETA, v3(1, NAN, 1));
    bad[n++] = metal(0.1f, AL_ETA, v3(1, 1, INFINITY));
    for (int i = 0; i < n; i++) TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_INVALID_MATERIAL, fogrt_scene_add_material(s, &bad[i], &id));
    m = metal(0.25f, AG_ETA, AG_K);
    CHECK_OK(fogrt_scene_add_material(s, &m, &id));
    CHECK_OK(fogrt_scene_get_material(s, id, &m));
    TEST_ASSERT_EQUAL_INT(FOGRT_BSDF_MICROFACET, m.type);
    TEST_ASSERT_EQUAL_FLOAT(0.25f, m.alpha);
    TEST_ASSERT_EQUAL_FLOAT(AG_K.y, m.k.y);
    fogrt_scene_destroy(s);
}

/* This program ran exactly the number of statistical tests that stats.h counts for it. */
static void test_sidak_count_is_right(void)
{
    char msg[200];
    snprintf(msg, sizeof msg, "ran %d statistical tests, stats.h says STATS_TESTS_MICROFACET = %d (suite total %d, alpha' = %.3g)",
             *stats_test_counter(), STATS_TESTS_MICROFACET, STATS_SUITE_TESTS, stats_alpha());
    TEST_MESSAGE(msg);
    TEST_ASSERT_EQUAL_INT_MESSAGE(STATS_TESTS_MICROFACET, *stats_test_counter(), msg);
}
#endif /* FOGRT_NO_MICROFACET */

/* ==========================================================================================
   The loader
   ========================================================================================== */
static int warnings_seen;
static void count_warning(fogrt_log_level level, const char *message, void *user)
{
    (void)message; (void)user;
    if (level == FOGRT_LOG_WARNING) warnings_seen++;
}
static fogrt_material_desc sphere_material(const fogrt_scene *s, uint32_t k)
{
    fogrt_material_desc m;
    fogrt_scene_info info;
    fogrt_scene_get_info(s, &info);
    CHECK_OK(fogrt_scene_get_material(s, fogrt_scene_get_prim_material(s, info.triangle_count + k), &m));
    return m;
}

/* tests/data/dae_microfacet.dae, <microfacet> as CS184 writes it: aluminium alpha 0.05 with
   a <reflectance> child (ignored), silver alpha 0.5, and one with alpha 0 (clamped to 1e-4,
   the one warning). Built without the rough metal: a mirror, a diffuse surface and a
   mirror of the normal-incidence Fresnel colour, a warning each. */
static void test_loader_microfacet(void)
{
    fogrt_scene *s = NULL;
    fogrt_load_options o;
    fogrt_load_report rep;
    fogrt_material_desc m;
    memset(&o, 0, sizeof o);
    o.logger.func = count_warning;
    warnings_seen = 0;
    CHECK_OK(fogrt_scene_create(NULL, &s));
    fogrt_result r = fogrt_load_file(s, DATA_DIR "dae_microfacet.dae", &o, &rep);
    TEST_ASSERT_EQUAL_INT_MESSAGE(FOGRT_RESULT_OK, r, rep.message);
    {
        fogrt_scene_info info;
        fogrt_scene_get_info(s, &info);
        TEST_ASSERT_EQUAL_UINT32(3, info.sphere_count);
    }
    m = sphere_material(s, 0);
#ifndef FOGRT_NO_MICROFACET
    TEST_ASSERT_EQUAL_INT(FOGRT_BSDF_MICROFACET, m.type);
    TEST_ASSERT_EQUAL_FLOAT(0.05f, m.alpha);
    TEST_ASSERT_EQUAL_FLOAT(1.6574599f, m.eta.x);
    TEST_ASSERT_EQUAL_FLOAT(4.8370012f, m.k.z);
    TEST_ASSERT_TRUE(m.reflectance.x == 0.0f && m.reflectance.y == 0.0f);   /* CS184's unused child: not read */
    m = sphere_material(s, 1);
    TEST_ASSERT_EQUAL_INT(FOGRT_BSDF_MICROFACET, m.type);
    TEST_ASSERT_EQUAL_FLOAT(0.5f, m.alpha);
    TEST_ASSERT_EQUAL_FLOAT(0.059881f, m.eta.y);
    TEST_ASSERT_EQUAL_FLOAT(3.5f, m.k.y);
    m = sphere_material(s, 2);
    TEST_ASSERT_EQUAL_INT(FOGRT_BSDF_MICROFACET, m.type);
    TEST_ASSERT_EQUAL_FLOAT(1e-4f, m.alpha);
    TEST_ASSERT_EQUAL_UINT32(1, rep.warnings);
#else
    TEST_ASSERT_EQUAL_INT(FOGRT_BSDF_MIRROR, m.type);
    TEST_ASSERT_EQUAL_INT(FOGRT_BSDF_DIFFUSE, sphere_material(s, 1).type);
    TEST_ASSERT_EQUAL_INT(FOGRT_BSDF_MIRROR, sphere_material(s, 2).type);
    TEST_ASSERT_EQUAL_UINT32(3, rep.warnings);
#endif
    TEST_ASSERT_EQUAL_INT((int)rep.warnings, warnings_seen);
    fogrt_scene_destroy(s);
}

#ifdef FOGRT_NO_MICROFACET
/* Built without appendix I: the material is refused as unsupported, naming the macro. */
static void test_stripped_refuses(void)
{
    fogrt_scene *s = NULL;
    fogrt_material_desc m = metal(0.2f, v3(1, 1, 1), v3(1, 1, 1));
    uint32_t id;
    CHECK_OK(fogrt_scene_create(NULL, &s));
    TEST_ASSERT_EQUAL_INT(FOGRT_RESULT_UNSUPPORTED, fogrt_scene_add_material(s, &m, &id));
    fogrt_scene_destroy(s);
}
#endif

int main(void)
{
    UNITY_BEGIN();
#ifndef FOGRT_NO_MICROFACET
    RUN_TEST(test_sampler_chi2);
    RUN_TEST(test_eval_listed_angles);
    RUN_TEST(test_eval_random_pairs_reciprocity);
    RUN_TEST(test_white_furnace_albedo);
    RUN_TEST(test_furnace_render);
    RUN_TEST(test_alpha_to_zero_directions);
    RUN_TEST(test_alpha_to_zero_render);
    RUN_TEST(test_extreme_inputs_finite);
    RUN_TEST(test_extreme_renders_finite);
    RUN_TEST(test_material_checks);
    RUN_TEST(test_sidak_count_is_right);
#else
    RUN_TEST(test_stripped_refuses);
#endif
    RUN_TEST(test_loader_microfacet);
    return UNITY_END();
}
