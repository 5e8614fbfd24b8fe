/* check.h - the coursework kit's checker (docs/coursework.md): runs the checks of one step on
   the functions a student wrote (declared in coursework.h), prints one line per check and
   draws a picture per sampler check.

   The checker receives the student's functions as pointers (cw_fns), so one program can
   judge several solutions side by side: examples/coursework/check_step.c judges the file a
   student hands in, tests/test_coursework.c judges fogrt's reference solutions and the
   wrong solutions under tests/coursework/wrong/. Include it once, after fogrt.h.

   How a check decides
   - Samplers: the checker draws N uniform numbers from fixed seeds, bins the student's
     samples and compares the counts with the analytic density of the paper's equation by
     Pearson's chi-square (tests/stats.h: cells with expected counts below 5 are pooled).
     The bins are equal-probability bins of the right distribution, so every bin expects the
     same count and a sampler that puts its mass elsewhere stands out wherever it does.
     A check fails when p < CW_ALPHA = 1e-4. The seeds are fixed, so a given solution always
     gets the same verdict; a correct solution whose samples differ from fogrt's (another
     but equally right formula, another u mapping) draws a fresh outcome and is rejected
     with probability 1e-4 per check: the false-failure rate is below 1 in 1000 by the
     threshold, not by luck of the seed. Checks that test several parameter sets at once
     split the level among them (Bonferroni), so each check line keeps the 1e-4.
   - Formulas (a pdf, eq. 8, eq. 9, Schlick, a split cost): compared with the checker's own
     double-precision evaluation at fixed points, with a tolerance of float rounding times a
     safety factor (stated on each line). A correct float implementation cannot fail them.
   - Edge cases: finite, in-range answers at u = 0, u = 1 - 2^-24, g = 0, g = +-0.99,
     extreme sigma_t and grazing directions.
   A failing check says what it saw and the usual cause ("more samples near mu = -1 than
   HG allows: is g's sign flipped?"); the picture shows the histogram against the density. */
#ifndef FOGRT_COURSEWORK_CHECK_H
#define FOGRT_COURSEWORK_CHECK_H

#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "coursework.h"
#include "../../tests/stats.h"
#include "../plotfont.h"
#include "../stb_write.h"

#define CW_ALPHA 1e-4
#define CW_N 200000             /* samples per sampler check */
#define CW_MAX_CHECKS 48
#define CW_HMAX 64              /* bins of a 1-D histogram */
#define CW_PI 3.14159265358979323846

/* The student's functions; a step uses its own members and ignores the rest. */
typedef struct cw_fns {
    float (*sample_free_flight)(float sigma_t, float u);
    float (*free_flight_pdf)(float sigma_t, float t);
    float (*transmittance)(float sigma_t, float distance);
    float (*transmittance_estimate)(float sigma_t, float distance, float u);
    float (*hg_phase)(float g, float mu);
    float (*sample_hg_mu)(float g, float u);
    fogrt_vec3 (*sample_hg)(float g, fogrt_vec3 wo, float u1, float u2);
    float (*split_cost)(int heuristic, const cw_aabb *parent, const cw_aabb *left, int n_left,
                        const cw_aabb *right, int n_right);
    cw_split (*best_split)(int heuristic, const cw_aabb *parent, const cw_bins *bins);
    int (*sample_diffuse)(fogrt_vec3 wo, float u1, float u2, cw_bsdf_sample *s);
    float (*diffuse_pdf)(fogrt_vec3 wo, fogrt_vec3 wi);
    int (*sample_mirror)(fogrt_vec3 wo, cw_bsdf_sample *s);
    float (*fresnel_schlick)(float eta, float cos_i);
    int (*sample_glass)(float eta, fogrt_vec3 wo, float u_lobe, cw_bsdf_sample *s);
    float (*sample_equiangular)(float delta, float h, float a, float b, float u, float *pdf);
    float (*equiangular_pdf)(float delta, float h, float a, float b, float t);
    fogrt_vec3 (*direct_surface)(const fogrt_scene *scene, const fogrt_surface *sf, fogrt_vec3 wo, fogrt_rng *rng);
    fogrt_vec3 (*direct_fog)(const fogrt_scene *scene, fogrt_vec3 p, fogrt_vec3 wo, fogrt_rng *rng);
    fogrt_vec3 (*path_radiance)(const fogrt_scene *scene, fogrt_vec3 o, fogrt_vec3 d, fogrt_rng *rng, void *user);
    float (*mis_weight)(float pdf_this, float pdf_other);
    fogrt_vec3 (*mis_radiance)(const fogrt_scene *scene, fogrt_vec3 o, fogrt_vec3 d, fogrt_rng *rng, void *user);
} cw_fns;

typedef struct cw_result {
    char name[64];
    int pass;
    double seconds;
    char line[1400];
} cw_result;

/* One run of a step's checks. img_dir NULL: no pictures; quiet: print nothing. */
typedef struct cw_run {
    const char *img_dir;
    int quiet;
    int count, passed;
    double seconds;
    cw_result r[CW_MAX_CHECKS];
    clock_t t0;            /* start of the check being run */
} cw_run;

/* ==========================================================================================
   Reporting
   ========================================================================================== */
static void cw_begin(cw_run *run) { run->t0 = clock(); }

/* Records a check: measure is what was measured (statistic, p-value or values against the
   tolerance), advice what a failure means (printed on failure only), png the picture. */
static void cw_emit(cw_run *run, const char *name, int pass, const char *measure, const char *advice, const char *png)
{
    cw_result *r;
    double s = (double)(clock() - run->t0) / CLOCKS_PER_SEC;
    if (run->count >= CW_MAX_CHECKS) return;
    r = &run->r[run->count++];
    snprintf(r->name, sizeof r->name, "%s", name);
    r->pass = pass;
    r->seconds = s;
    run->seconds += s;
    if (pass) run->passed++;
    snprintf(r->line, sizeof r->line, "%-30s %s %5.2f s  %s%s%s%s%s", name, pass ? "PASS" : "FAIL", s, measure,
             !pass && advice && *advice ? "  -- " : "", !pass && advice ? advice : "",
             png && *png ? "  [picture " : "", png && *png ? png : "");
    if (png && *png) strncat(r->line, "]", sizeof r->line - strlen(r->line) - 1);
    if (!run->quiet) { printf("%s\n", r->line); fflush(stdout); }
    run->t0 = clock();
}

/* The first failing check's line, or NULL. */
static inline const cw_result *cw_first_failure(const cw_run *run)
{
    int i;
    for (i = 0; i < run->count; ++i) if (!run->r[i].pass) return &run->r[i];
    return NULL;
}

/* A failing check whose name starts with name and whose line contains text, or NULL. */
static inline const cw_result *cw_find_failure(const cw_run *run, const char *name, const char *text)
{
    int i;
    for (i = 0; i < run->count; ++i)
        if (!run->r[i].pass && strncmp(run->r[i].name, name, strlen(name)) == 0 && strstr(run->r[i].line, text))
            return &run->r[i];
    return NULL;
}

static void cw_fmt(char *out, size_t size, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(out, size, fmt, ap);
    va_end(ap);
}

/* ==========================================================================================
   Random numbers: fogrt's PCG32 (public API), one fixed stream per check
   ========================================================================================== */
static float cw_u(fogrt_rng *r) { return fogrt_rng_float(r); }
/* 0 for every verdict the kit gives; other values redraw every check's samples (used to
   measure the checker's false-failure rate on the reference solutions, docs/coursework.md). */
static uint64_t cw_seed_offset = 0;
static void cw_seed(fogrt_rng *r, uint64_t check) { fogrt_rng_seed(r, 0xC0FFEE12345ull + cw_seed_offset, check); }
#define CW_U_MAX (1.0f - 0x1p-24f)   /* the largest u the kit passes */

/* ==========================================================================================
   Pictures: a histogram (bars) against a model (line), with title, axes and legend
   ========================================================================================== */
typedef struct cw_plot {
    const char *title, *xlabel, *ylabel, *bar_label, *line_label;
    int n;
    const double *x0, *x1, *bar, *line;   /* bar i covers [x0[i], x1[i]]; line NULL: none */
    double xmin, xmax;                    /* the x range drawn */
    int logy;                             /* 1: log scale; -1: chosen from the data's range */
    int points;                           /* 1: the line joins the bars' centres (else steps) */
    int bars_signed;                      /* 1: bars may be negative (y range from the data) */
    int cn;                               /* > 0: the model is this curve (cx, cy) instead of line */
    const double *cx, *cy;
} cw_plot;

static const unsigned char CW_BAR[3] = {140, 185, 225};

/* A 2-pixel line between any two points (Bresenham with the error doubled once per step,
   so diagonal segments end where they should). */
static void cw_line(pf_canvas *c, int x0, int y0, int x1, int y1, const unsigned char col[3])
{
    int dx = abs(x1 - x0), dy = -abs(y1 - y0), sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1, err = dx + dy;
    for (;;) {
        int e2 = 2 * err;
        pf_rect(c, x0, y0, 2, 2, col);
        if (x0 == x1 && y0 == y1) break;
        if (e2 >= dy) { err += dy; x0 += sx; }
        if (e2 <= dx) { err += dx; y0 += sy; }
    }
}

static void cw__axis_label(char *buf, size_t size, double v)
{
    if (v != 0.0 && (fabs(v) < 1e-3 || fabs(v) >= 1e5)) snprintf(buf, size, "%.1e", v);
    else snprintf(buf, size, "%.4g", v);
}

static void cw_draw_plot(pf_canvas *c, int X, int Y, int W, int H, const cw_plot *p)
{
    int px0 = X + 78, py0 = Y + 36, pw = W - 78 - 16, ph = H - 36 - 58, i, k;
    double ymin = 0.0, ymax = 0.0, lmin = HUGE_VAL;
    int logy = p->logy;
    int ts = pf_text_width(p->title, 2) <= W - 8 ? 2 : 1;
    pf_text_at(c, X + W / 2, Y + 8, p->title, ts, PF_BLACK, 1);
    for (i = 0; i < p->n; ++i) {
        double v[2];
        int j;
        v[0] = p->bar ? p->bar[i] : 0.0;
        v[1] = p->line ? p->line[i] : 0.0;
        for (j = 0; j < 2; ++j) {
            if (!isfinite(v[j])) continue;
            if (v[j] > ymax) ymax = v[j];
            if (v[j] < ymin) ymin = v[j];
            if (v[j] > 0.0 && v[j] < lmin) lmin = v[j];
        }
    }
    for (i = 0; i < p->cn; ++i)
        if (isfinite(p->cy[i])) {
            if (p->cy[i] > ymax) ymax = p->cy[i];
            if (p->cy[i] > 0.0 && p->cy[i] < lmin) lmin = p->cy[i];
        }
    if (!p->bars_signed) ymin = 0.0;
    if (logy < 0) logy = (ymax > 0.0 && lmin < HUGE_VAL && ymax / lmin > 60.0) ? 1 : 0;
    if (logy) {
        ymax = log10(ymax > 0.0 ? ymax : 1.0) + 0.6;          /* room for the legend above the data */
        ymin = log10(lmin < HUGE_VAL ? lmin : 1e-3) - 0.3;
        if (ymax - ymin > 8.0) ymin = ymax - 8.0;
    } else {
        double span = ymax - ymin;
        if (!(span > 0.0)) span = 1.0;
        ymax += 0.25 * span;                                 /* room for the legend above the data */
        if (p->bars_signed && ymin < 0.0) ymin -= 0.08 * span;
    }
#define CW_YPIX(v) (py0 + ph - (int)lround(((logy ? log10(fmax((v), 1e-300)) : (v)) - ymin) / (ymax - ymin) * ph))
#define CW_XPIX(x) (px0 + (int)lround((fmin(fmax((x), p->xmin), p->xmax) - p->xmin) / (p->xmax - p->xmin) * pw))
    /* grid lines and tick labels */
    for (k = 0; k <= 4; ++k) {
        char lab[32];
        double xv = p->xmin + (p->xmax - p->xmin) * k / 4.0, yv = ymin + (ymax - ymin) * k / 4.0;
        int xp = px0 + pw * k / 4, yp = py0 + ph - ph * k / 4;
        pf_line(c, xp, py0, xp, py0 + ph, PF_LIGHT, 1, 0);
        pf_line(c, px0, yp, px0 + pw, yp, PF_LIGHT, 1, 0);
        cw__axis_label(lab, sizeof lab, xv);
        pf_text_at(c, xp, py0 + ph + 5, lab, 1, PF_GREY, 1);
        cw__axis_label(lab, sizeof lab, logy ? pow(10.0, yv) : yv);
        pf_text_at(c, px0 - 5, yp - 4, lab, 1, PF_GREY, 2);
    }
    /* bars */
    if (p->bar)
        for (i = 0; i < p->n; ++i) {
            int xa, xb, ya, yb;
            if (!isfinite(p->bar[i]) || p->x1[i] <= p->xmin || p->x0[i] >= p->xmax) continue;
            if (logy && !(p->bar[i] > 0.0)) continue;
            xa = CW_XPIX(p->x0[i]); xb = CW_XPIX(p->x1[i]);
            ya = CW_YPIX(p->bar[i]); yb = logy ? py0 + ph : CW_YPIX(0.0);
            if (ya > yb) { int t = ya; ya = yb; yb = t; }
            if (ya < py0) ya = py0;
            if (yb > py0 + ph) yb = py0 + ph;
            if (xb <= xa) xb = xa + 1;
            pf_rect(c, xa, ya, xb - xa, yb - ya + 1, CW_BAR);
        }
    /* the model: a curve ... */
    if (p->cn > 0) {
        int have = 0, lx = 0, ly = 0;
        for (i = 0; i < p->cn; ++i) {
            int x, y;
            if (!isfinite(p->cy[i]) || p->cx[i] < p->xmin || p->cx[i] > p->xmax || (logy && !(p->cy[i] > 0.0))) {
                have = 0;
                continue;
            }
            x = CW_XPIX(p->cx[i]);
            y = CW_YPIX(p->cy[i]);
            if (y < py0) y = py0;
            if (y > py0 + ph) y = py0 + ph;
            if (have) cw_line(c, lx, ly, x, y, PF_ORANGE);
            lx = x; ly = y; have = 1;
        }
    }
    /* ... or a value per bar */
    else if (p->line) {
        int have = 0, lx = 0, ly = 0;
        for (i = 0; i < p->n; ++i) {
            int xa, xb, y;
            if (!isfinite(p->line[i]) || p->x1[i] <= p->xmin || p->x0[i] >= p->xmax) { have = 0; continue; }
            if (logy && !(p->line[i] > 0.0)) { have = 0; continue; }
            y = CW_YPIX(p->line[i]);
            if (y < py0) y = py0;
            if (y > py0 + ph) y = py0 + ph;
            if (p->points) {
                xa = CW_XPIX(0.5 * (p->x0[i] + p->x1[i]));
                if (have) cw_line(c, lx, ly, xa, y, PF_ORANGE);
                pf_rect(c, xa - 2, y - 2, 5, 5, PF_ORANGE);
                lx = xa; ly = y; have = 1;
            } else {
                xa = CW_XPIX(p->x0[i]); xb = CW_XPIX(p->x1[i]);
                if (have) cw_line(c, lx, ly, xa, y, PF_ORANGE);
                cw_line(c, xa, y, xb, y, PF_ORANGE);
                lx = xb; ly = y; have = 1;
            }
        }
    }
#undef CW_YPIX
#undef CW_XPIX
    pf_frame(c, px0, py0, pw + 1, ph + 1, PF_BLACK);
    pf_text_at(c, px0 + pw / 2, py0 + ph + 20, p->xlabel, 2, PF_BLACK, 1);
    {
        char yl[96];
        snprintf(yl, sizeof yl, "%s%s", p->ylabel, logy ? " (log scale)" : "");
        pf_text_up(c, X + 4, py0 + ph / 2, yl, 1, PF_BLACK);
    }
    /* legend, top right inside the plot */
    {
        int lx = px0 + pw - 8 - 12 - 6 * (int)fmax(strlen(p->bar_label ? p->bar_label : ""),
                                                   strlen(p->line_label ? p->line_label : "")) - 12, ly = py0 + 8;
        int rows = (p->bar && p->bar_label) + ((p->line || p->cn > 0) && p->line_label);
        if (rows) {                                   /* a white card, so bars do not run through it */
            pf_rect(c, lx - 4, ly - 4, px0 + pw - lx, 14 * rows + 4, PF_WHITE);
            pf_frame(c, lx - 4, ly - 4, px0 + pw - lx, 14 * rows + 4, PF_LIGHT);
        }
        if (p->bar && p->bar_label) {
            pf_rect(c, lx, ly, 12, 9, CW_BAR);
            pf_text(c, lx + 18, ly, p->bar_label, 1, PF_BLACK);
            ly += 14;
        }
        if ((p->line || p->cn > 0) && p->line_label) {
            pf_line(c, lx, ly + 4, lx + 11, ly + 4, PF_ORANGE, 2, 0);
            pf_text(c, lx + 18, ly, p->line_label, 1, PF_BLACK);
        }
    }
}

/* Writes the canvas with a verdict strip under it as img_dir/stem.png; path gets the name
   ("" when pictures are off or the file could not be written). */
static void cw_save(const cw_run *run, const char *stem, pf_canvas *c, const char *verdict, int pass, char *path, size_t size)
{
    pf_canvas out;
    const char *lines[1];
    path[0] = '\0';
    if (!run->img_dir) return;
    lines[0] = verdict;
    out = pf_captioned(c->rgb, c->w, c->h, lines, 1, 1);
    pf_rect(&out, 0, c->h, out.w, 2, pass ? PF_GREEN : PF_ORANGE);   /* the verdict's colour, above the text */
    snprintf(path, size, "%s/%s.png", run->img_dir, stem);
    if (!stbi_write_png(path, out.w, out.h, 3, out.rgb, 3 * out.w)) path[0] = '\0';
    pf_canvas_free(&out);
}

/* One plot alone in a picture. */
static void cw_picture(const cw_run *run, const char *stem, const cw_plot *p, const char *verdict, int pass,
                       char *path, size_t size)
{
    pf_canvas c;
    path[0] = '\0';
    if (!run->img_dir) return;
    c = pf_canvas_make(760, 400, PF_WHITE);
    cw_draw_plot(&c, 0, 0, 760, 400, p);
    cw_save(run, stem, &c, verdict, pass, path, size);
    pf_canvas_free(&c);
}

/* Two plots side by side (a 2-D check's two marginals). */
static void cw_picture2(const cw_run *run, const char *stem, const cw_plot *a, const cw_plot *b, const char *verdict,
                        int pass, char *path, size_t size)
{
    pf_canvas c;
    path[0] = '\0';
    if (!run->img_dir) return;
    c = pf_canvas_make(1240, 400, PF_WHITE);
    cw_draw_plot(&c, 0, 0, 620, 400, a);
    cw_draw_plot(&c, 620, 0, 620, 400, b);
    cw_save(run, stem, &c, verdict, pass, path, size);
    pf_canvas_free(&c);
}

/* A histogram on the sphere (stats.h's grid, nc x np cells) as its two marginals: the
   density in cos theta and the density in phi, observed against expected. */
static void cw_picture_sphere(const cw_run *run, const char *stem, const stats_sphere_grid *grid, const double *obs,
                              const double *expd, const char *title_a, const char *xlabel_a, const char *line_a, int logy_a,
                              const char *title_b, const char *line_b, const char *verdict, int pass, char *path, size_t size)
{
    double ax0[STATS_GRID_MAX_COS], ax1[STATS_GRID_MAX_COS], ab[STATS_GRID_MAX_COS], al[STATS_GRID_MAX_COS];
    double bx0[64], bx1[64], bb[64], bl[64];
    int nc = grid->n_cos, np = grid->n_phi > 64 ? 64 : grid->n_phi, i, j;
    cw_plot a, b;
    path[0] = '\0';
    if (!run->img_dir) return;
    for (i = 0; i < nc; ++i) {
        double w = grid->cos_edge[i + 1] - grid->cos_edge[i], o = 0.0, e = 0.0;
        for (j = 0; j < grid->n_phi; ++j) { o += obs[i * grid->n_phi + j]; e += expd[i * grid->n_phi + j]; }
        ax0[i] = grid->cos_edge[i]; ax1[i] = grid->cos_edge[i + 1]; ab[i] = o / (CW_N * w); al[i] = e / (CW_N * w);
    }
    for (j = 0; j < np; ++j) {
        double o = 0.0, e = 0.0, w = 2.0 * CW_PI / np;
        for (i = 0; i < nc; ++i) { o += obs[i * grid->n_phi + j]; e += expd[i * grid->n_phi + j]; }
        bx0[j] = -CW_PI + w * j; bx1[j] = bx0[j] + w; bb[j] = o / (CW_N * w); bl[j] = e / (CW_N * w);
    }
    memset(&a, 0, sizeof a); memset(&b, 0, sizeof b);
    a.title = title_a; a.xlabel = xlabel_a; a.ylabel = "density per unit cos theta"; a.bar_label = "your directions";
    a.line_label = line_a; a.n = nc; a.x0 = ax0; a.x1 = ax1; a.bar = ab; a.line = al; a.xmin = -1.0; a.xmax = 1.0;
    a.logy = logy_a;
    b.title = title_b; b.xlabel = "phi (radians)"; b.ylabel = "density per radian"; b.bar_label = "your directions";
    b.line_label = line_b; b.n = np; b.x0 = bx0; b.x1 = bx1; b.bar = bb; b.line = bl; b.xmin = -CW_PI; b.xmax = CW_PI;
    cw_picture2(run, stem, &a, &b, verdict, pass, path, size);
}

/* ==========================================================================================
   1-D histograms against a model CDF
   ========================================================================================== */
typedef struct cw_hist {
    int nb;
    double edge[CW_HMAX + 1];   /* increasing; edge[nb] may be +infinity */
    double obs[CW_HMAX], expd[CW_HMAX];
    long n, invalid;
    double first_invalid, first_invalid_u;
    double sum;                 /* of the valid samples */
} cw_hist;

typedef double (*cw_cdf_fn)(double x, const void *user);

static void cw_hist_init(cw_hist *h, int nb)
{
    memset(h, 0, sizeof *h);
    h->nb = nb;
}
/* Adds one sample; outside [edge[0], edge[nb]] (beyond slack) or not finite: invalid. */
static void cw_hist_add(cw_hist *h, double x, double u, double slack)
{
    int lo = 0, hi = h->nb;
    h->n++;
    if (!isfinite(x) || x < h->edge[0] - slack || x > h->edge[h->nb] + slack) {
        if (h->invalid++ == 0) { h->first_invalid = x; h->first_invalid_u = u; }
        return;
    }
    h->sum += x;
    if (x <= h->edge[0]) { h->obs[0] += 1.0; return; }
    if (x >= h->edge[h->nb]) { h->obs[h->nb - 1] += 1.0; return; }
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (h->edge[mid] <= x) lo = mid; else hi = mid;
    }
    h->obs[lo] += 1.0;
}
/* Expected counts from the model's CDF. */
static void cw_hist_expect(cw_hist *h, cw_cdf_fn cdf, const void *user)
{
    int i;
    for (i = 0; i < h->nb; ++i) h->expd[i] = (double)h->n * (cdf(h->edge[i + 1], user) - cdf(h->edge[i], user));
}

typedef struct cw_fit { double chi2, p; int dof; } cw_fit;
static cw_fit cw_hist_fit(const double *obs, const double *expd, int n)
{
    cw_fit f;
    stats_chi2_result r = stats_chi2(obs, expd, n);
    f.chi2 = r.chi2; f.dof = r.dof; f.p = r.dof >= 1 ? r.p_value : 0.0;
    return f;
}

/* The bin where observed and expected differ most, in standard deviations. */
static int cw_worst_bin(const double *obs, const double *expd, int n, double *z)
{
    int i, w = 0;
    double best = -1.0;
    for (i = 0; i < n; ++i) {
        double e = expd[i] > 0.0 ? expd[i] : 1e-9, d = fabs(obs[i] - e) / sqrt(e);
        if (d > best) { best = d; w = i; }
    }
    *z = (obs[w] - expd[w]) / sqrt(expd[w] > 0.0 ? expd[w] : 1e-9);
    return w;
}

/* Bars and line as densities (count / (N width)) for a picture; a last infinite bin is cut
   at xmax. */
static void cw_hist_density(const cw_hist *h, double xmax, double *x0, double *x1, double *bar, double *line)
{
    int i;
    for (i = 0; i < h->nb; ++i) {
        double a = h->edge[i], b = isinf(h->edge[i + 1]) ? fmax(xmax, a) : h->edge[i + 1], w = b - a;
        x0[i] = a; x1[i] = b;
        bar[i] = (w > 0.0 && !isinf(h->edge[i + 1])) ? h->obs[i] / ((double)h->n * w) : NAN;
        line[i] = (w > 0.0 && !isinf(h->edge[i + 1])) ? h->expd[i] / ((double)h->n * w) : NAN;
    }
}

/* The integral of a student's 1-D density over [a, b] (adaptive Simpson, tests/stats.h). */
typedef struct cw__pdf1 { double (*f)(double x, const void *user); const void *user; } cw__pdf1;
static double cw__pdf1_eval(double x, void *user)
{
    const cw__pdf1 *p = (const cw__pdf1 *)user;
    double v = p->f(x, p->user);
    return isfinite(v) ? v : 0.0;
}
static double cw_integrate(double (*f)(double x, const void *user), const void *user, double a, double b)
{
    cw__pdf1 p;
    p.f = f; p.user = user;
    return stats_integrate_1d(cw__pdf1_eval, &p, a, b, 1e-7, 22);
}

/* Normal two-sided p-value of z. */
static double cw_normal_p(double z) { return erfc(fabs(z) / sqrt(2.0)); }

static int cw_finite3(fogrt_vec3 v) { return isfinite(v.x) && isfinite(v.y) && isfinite(v.z); }
static double cw_len3(fogrt_vec3 v) { return sqrt((double)v.x * v.x + (double)v.y * v.y + (double)v.z * v.z); }
static fogrt_vec3 cw_v3(double x, double y, double z)
{
    fogrt_vec3 v;
    double l = sqrt(x * x + y * y + z * z);
    v.x = (float)(x / l); v.y = (float)(y / l); v.z = (float)(z / l);
    return v;
}

/* ==========================================================================================
   Step 1: free-flight sampling (eq. 4-6)
   ========================================================================================== */
static double cw__exp_cdf(double t, const void *user)
{
    double s = *(const double *)user;
    return t <= 0.0 ? 0.0 : (isinf(t) ? 1.0 : -expm1(-s * t));
}
typedef struct cw__ff { const cw_fns *f; double sigma; } cw__ff;
static double cw__ff_pdf(double t, const void *user)
{
    const cw__ff *p = (const cw__ff *)user;
    return p->f->free_flight_pdf((float)p->sigma, (float)t);
}

static void cw_step1(const cw_fns *f, cw_run *run)
{
    static const double sigmas[2] = {0.3, 5.0};
    int k, i;
    char name[64], m[512], adv[512], png[256], stem[64], title[160];
    for (k = 0; k < 2; ++k) {
        double sigma = sigmas[k], mean, x0[CW_HMAX], x1[CW_HMAX], bar[CW_HMAX], line[CW_HMAX];
        cw_hist h;
        cw_fit fit;
        fogrt_rng rng;
        cw__ff ff;
        int pass, nb = 40;
        cw_plot p;
        /* the samples against eq. 6 */
        cw_begin(run);
        cw_hist_init(&h, nb);
        for (i = 0; i < nb; ++i) h.edge[i] = -log1p(-(double)i / nb) / sigma;
        h.edge[nb] = HUGE_VAL;
        cw_seed(&rng, 100 + k);
        for (i = 0; i < CW_N; ++i) {
            float u = cw_u(&rng);
            cw_hist_add(&h, f->sample_free_flight((float)sigma, u), u, 0.0);
        }
        cw_hist_expect(&h, cw__exp_cdf, &sigma);
        fit = cw_hist_fit(h.obs, h.expd, nb);
        pass = h.invalid == 0 && fit.p >= CW_ALPHA;
        mean = h.n > h.invalid ? h.sum / (double)(h.n - h.invalid) : NAN;
        cw_fmt(m, sizeof m, "chi2 = %.1f, dof %d, p = %.3g (fail if p < %g); mean t = %.4g, 1/sigma_t = %.4g",
               fit.chi2, fit.dof, fit.p, CW_ALPHA, mean, 1.0 / sigma);
        if (h.invalid)
            cw_fmt(adv, sizeof adv, "%ld samples were negative, infinite or NaN (first: t = %g at u = %.9g): a distance "
                   "is finite and >= 0 for every u in [0, 1)", h.invalid, h.first_invalid, h.first_invalid_u);
        else if (mean * sigma > 1.05)
            cw_fmt(adv, sizeof adv, "samples go too far: mean t = %.4g but eq. 6 gives 1/sigma_t = %.4g (%.3gx)%s", mean,
                   1.0 / sigma, mean * sigma,
                   fabs(mean - sigma) < 0.05 * sigma ? ": are you multiplying by sigma_t instead of dividing?" : "");
        else if (mean * sigma < 0.95)
            cw_fmt(adv, sizeof adv, "samples stop too soon: mean t = %.4g but eq. 6 gives 1/sigma_t = %.4g (%.3gx)%s", mean,
                   1.0 / sigma, mean * sigma,
                   fabs(mean - sigma) < 0.05 * sigma ? ": are you multiplying by sigma_t instead of dividing?" : "");
        else
            cw_fmt(adv, sizeof adv, "the mean is right but the shape is not exponential: invert eq. 6, t = -log(1 - u) / sigma_t");
        cw_hist_density(&h, h.edge[nb - 1] * 1.15, x0, x1, bar, line);
        memset(&p, 0, sizeof p);
        cw_fmt(title, sizeof title, "Step 1: free-flight distances, sigma_t = %g (eq. 6)", sigma);
        p.title = title; p.xlabel = "distance t"; p.ylabel = "density"; p.bar_label = "your samples";
        p.line_label = "sigma_t exp(-sigma_t t)"; p.n = nb - 1; p.x0 = x0; p.x1 = x1; p.bar = bar; p.line = line;
        p.xmin = 0.0; p.xmax = h.edge[nb - 1]; p.logy = 0;
        cw_fmt(stem, sizeof stem, "step1_chi2_sigma%g", sigma);
        cw_fmt(name, sizeof name, "step1.chi2 sigma_t=%g", sigma);
        {
            char verdict[1400];
            cw_fmt(verdict, sizeof verdict, "%s %s: %s%s%s", name, pass ? "PASS" : "FAIL", m, pass ? "" : " -- ", pass ? "" : adv);
            cw_picture(run, stem, &p, verdict, pass, png, sizeof png);
        }
        cw_emit(run, name, pass, m, adv, png);

        /* the student's pdf against the student's own samples */
        cw_begin(run);
        ff.f = f; ff.sigma = sigma;
        {
            double total = 0.0, z;
            int w;
            for (i = 0; i < nb; ++i) {
                double b = isinf(h.edge[i + 1]) ? h.edge[i] + 60.0 / sigma : h.edge[i + 1];
                h.expd[i] = (double)h.n * cw_integrate(cw__ff_pdf, &ff, h.edge[i], b);
                total += h.expd[i];
            }
            fit = cw_hist_fit(h.obs, h.expd, nb);
            pass = h.invalid == 0 && fit.p >= CW_ALPHA;
            w = cw_worst_bin(h.obs, h.expd, nb, &z);
            cw_fmt(m, sizeof m, "chi2 = %.1f, dof %d, p = %.3g (fail if p < %g); your pdf's mass over the bins %.4g",
                   fit.chi2, fit.dof, fit.p, CW_ALPHA, total / (double)h.n);
            if (h.invalid)
                cw_fmt(adv, sizeof adv, "the sampler gave invalid distances (see step1.chi2)");
            else if (fabs(total / (double)h.n - 1.0) > 0.01)
                cw_fmt(adv, sizeof adv, "your pdf integrates to %.4g, not 1, so it cannot describe your samples "
                       "(see step1.pdf_integral)", total / (double)h.n);
            else
                cw_fmt(adv, sizeof adv, "your pdf and your sampler disagree most for t in [%.3g, %.3g): %.0f samples "
                       "there, your pdf predicts %.0f: the pdf must be the density of the samples you draw",
                       h.edge[w], h.edge[w + 1], h.obs[w], h.expd[w]);
            cw_hist_density(&h, h.edge[nb - 1] * 1.15, x0, x1, bar, line);
            cw_fmt(title, sizeof title, "Step 1: your pdf against your samples, sigma_t = %g", sigma);
            p.title = title; p.line_label = "your pdf";
            cw_fmt(stem, sizeof stem, "step1_pdf_vs_hist_sigma%g", sigma);
            cw_fmt(name, sizeof name, "step1.pdf_vs_hist sigma_t=%g", sigma);
            {
                char verdict[1400];
                cw_fmt(verdict, sizeof verdict, "%s %s: %s%s%s", name, pass ? "PASS" : "FAIL", m, pass ? "" : " -- ", pass ? "" : adv);
                cw_picture(run, stem, &p, verdict, pass, png, sizeof png);
            }
            cw_emit(run, name, pass, m, adv, png);
        }
    }

    /* the pdf integrates to one and is zero before the ray starts */
    cw_begin(run);
    {
        static const double s3[3] = {0.02, 1.0, 40.0};
        double worst = 0.0, worst_i = 1.0, worst_s = 1.0, neg = 0.0;
        for (k = 0; k < 3; ++k) {
            cw__ff ff;
            double I;
            ff.f = f; ff.sigma = s3[k];
            I = cw_integrate(cw__ff_pdf, &ff, 0.0, 40.0 / s3[k]) + cw_integrate(cw__ff_pdf, &ff, 40.0 / s3[k], 80.0 / s3[k]);
            if (!(fabs(I - 1.0) <= worst)) { worst = fabs(I - 1.0); worst_i = I; worst_s = s3[k]; }
            neg = fmax(neg, fabs(f->free_flight_pdf((float)s3[k], -1.0f)));
        }
        {
            int pass = worst <= 2e-3 && neg == 0.0;
            cw_fmt(m, sizeof m, "integral of the pdf over t >= 0: %.6g at sigma_t = %g (expected 1 +- 0.002); pdf(t = -1) = %g",
                   worst_i, worst_s, neg);
            if (neg != 0.0)
                cw_fmt(adv, sizeof adv, "your pdf is not zero at t < 0: eq. 6's CDF is 0 for t < 0, so no distance is negative");
            else if (fabs(worst_i * worst_s - 1.0) < 0.01)
                cw_fmt(adv, sizeof adv, "the pdf integrates to 1/sigma_t: the density is the derivative of eq. 6, "
                       "sigma_t exp(-sigma_t t), with sigma_t in front");
            else if (fabs(worst_i - worst_s * worst_s) < 0.01 * worst_s * worst_s)
                cw_fmt(adv, sizeof adv, "the pdf integrates to sigma_t^2: write it as sigma_t exp(-sigma_t t), not sigma_t^2 ...");
            else
                cw_fmt(adv, sizeof adv, "a density must integrate to 1: the derivative of eq. 6 is sigma_t exp(-sigma_t t)");
            cw_emit(run, "step1.pdf_integral", pass, m, adv, NULL);
        }
    }

    /* the sample is eq. 6's inverse CDF at the u given */
    cw_begin(run);
    {
        double worst = 0.0, wu = 0.0, wt = 0.0;
        int decreasing = 0, n = 0;
        float prev = -1.0f;
        for (i = 0; i <= 64; ++i) {
            float u = i < 64 ? (float)i / 64.0f : CW_U_MAX, t = f->sample_free_flight(1.0f, u);
            double F = isfinite(t) ? -expm1(-(double)t) : (isinf(t) && t > 0 ? 1.0 : NAN), d = fabs(F - u);
            if (i > 0 && t < prev) decreasing++;
            prev = t;
            if (!(d <= worst)) { worst = d; wu = u; wt = t; }
            n++;
        }
        {
            int pass = worst <= 1e-5;
            cw_fmt(m, sizeof m, "largest |F(t(u)) - u| = %.3g at u = %.6g (t = %g, sigma_t = 1; tolerance 1e-5)", worst, wu, wt);
            if (decreasing > n / 2)
                cw_fmt(adv, sizeof adv, "t gets smaller as u grows: -log(u)/sigma_t has the right distribution but is not "
                       "eq. 6's inverse (stratified or low-discrepancy u lose their order, and u = 0 gives infinity); "
                       "the paper samples t = -log(1 - z)/lambda");
            else
                cw_fmt(adv, sizeof adv, "t(u) must solve F(t) = u with eq. 6's F(t) = 1 - exp(-sigma_t t)");
            cw_emit(run, "step1.inverse_cdf", pass, m, adv, NULL);
        }
    }

    /* edge cases: finite answers where a careless formula overflows */
    cw_begin(run);
    {
        static const float cs[6][2] = {{1.0f, 0.0f}, {1.0f, CW_U_MAX}, {1e-6f, 0.5f}, {1e6f, 0.5f}, {1e6f, CW_U_MAX}, {1e-6f, CW_U_MAX}};
        int bad = -1, total = 0, ok = 0, wrong_value = 0;
        float got = 0.0f;
        double want_v = 0.0;
        const char *what = "";
        for (i = 0; i < 6; ++i) {
            float t = f->sample_free_flight(cs[i][0], cs[i][1]);
            double want = -log1p(-(double)cs[i][1]) / cs[i][0];
            total++;
            if (isfinite(t) && t >= 0.0f && fabs(t - want) <= 1e-3 * want + 1e-30) ok++;
            else if (bad < 0) { bad = i; got = t; what = "t"; wrong_value = isfinite(t) && t >= 0.0f; want_v = want; }
        }
        {
            static const float ps[4][2] = {{1e6f, 0.0f}, {1e-6f, 1e6f}, {1.0f, 1e30f}, {40.0f, 0.0f}};
            for (i = 0; i < 4; ++i) {
                float v = f->free_flight_pdf(ps[i][0], ps[i][1]);
                double want = ps[i][0] * exp(-(double)ps[i][0] * ps[i][1]);
                total++;
                if (isfinite(v) && v >= 0.0f && fabs(v - want) <= 1e-3 * want + 1e-30) ok++;
                else if (bad < 0) { bad = 6 + i; got = v; what = "pdf"; wrong_value = isfinite(v) && v >= 0.0f; want_v = want; }
            }
            {
                int pass = ok == total;
                cw_fmt(m, sizeof m, "%d of %d edge cases finite and right within 1e-3 (u = 0, u = 1 - 2^-24, sigma_t 1e-6 "
                       "and 1e6)", ok, total);
                if (bad >= 0 && wrong_value && bad < 6)
                    cw_fmt(adv, sizeof adv, "sigma_t = %g, u = %.9g gave t = %g, eq. 6 inverted gives %.7g", cs[bad][0],
                           cs[bad][1], got, want_v);
                else if (bad >= 6 && wrong_value)
                    cw_fmt(adv, sizeof adv, "pdf(sigma_t = %g, t = %g) = %g, the exponential density sigma_t exp(-sigma_t t) "
                           "is %.7g", ps[bad - 6][0], ps[bad - 6][1], got, want_v);
                else if (bad == 0)
                    cw_fmt(adv, sizeof adv, "u = 0 gave t = %g: log(u) is -infinity at u = 0, which the kit (and fogrt's "
                           "random numbers) pass; u lies in [0, 1), so use log(1 - u) as the paper does", got);
                else if (bad >= 0 && bad < 6)
                    cw_fmt(adv, sizeof adv, "sigma_t = %g, u = %.9g gave %s = %g: a distance must be finite and >= 0",
                           cs[bad][0], cs[bad][1], what, got);
                else if (bad >= 6)
                    cw_fmt(adv, sizeof adv, "pdf(sigma_t = %g, t = %g) = %g: it must be finite and >= 0",
                           ps[bad - 6][0], ps[bad - 6][1], got);
                else adv[0] = '\0';
                cw_emit(run, "step1.edges", pass, m, adv, NULL);
            }
        }
    }
}

/* ==========================================================================================
   Step 2: transmittance (eq. 7-8)
   ========================================================================================== */
static void cw_step2(const cw_fns *f, cw_run *run)
{
    static const float sig[6] = {0.0f, 0.01f, 0.3f, 1.0f, 5.0f, 100.0f};
    static const float dist[7] = {0.0f, 0.001f, 0.1f, 1.0f, 2.0f, 10.0f, 100.0f};
    char m[512], adv[512], png[256];
    int i, j;
    /* eq. 8 itself */
    cw_begin(run);
    {
        double worst = 0.0;
        int wi = 0, wj = 0, linear = 0, inverse = 0, cases = 0;
        for (i = 0; i < 6; ++i)
            for (j = 0; j < 7; ++j) {
                double T = f->transmittance(sig[i], dist[j]), ref = exp(-(double)sig[i] * dist[j]);
                double err = fabs(T - ref) / (1e-6 + 1e-5 * ref);
                if (!(err <= worst)) { worst = err; wi = i; wj = j; }
                if (sig[i] * dist[j] > 0.05f && sig[i] * dist[j] < 0.9f) {
                    cases++;
                    if (fabs(T - (1.0 - (double)sig[i] * dist[j])) < 1e-4) linear++;
                    if (sig[i] > 0.0f && fabs(T - exp(-(double)dist[j] / sig[i])) < 1e-5 * exp(-(double)dist[j] / sig[i]) + 1e-6) inverse++;
                }
            }
        {
            double T = f->transmittance(sig[wi], dist[wj]), ref = exp(-(double)sig[wi] * dist[wj]);
            int pass = worst <= 1.0;
            cw_fmt(m, sizeof m, "largest error at sigma_t = %g, d = %g: T = %.7g, eq. 8 gives %.7g (tolerance 1e-6 + 1e-5 T)",
                   sig[wi], dist[wj], T, ref);
            if (cases && linear == cases)
                cw_fmt(adv, sizeof adv, "T = 1 - sigma_t d is only eq. 8's first-order approximation: eq. 7 integrates to "
                       "exp(-sigma_t d), which never reaches 0");
            else if (cases && inverse == cases)
                cw_fmt(adv, sizeof adv, "T = exp(-d / sigma_t) divides by sigma_t; eq. 8 multiplies: exp(-sigma_t d)");
            else
                cw_fmt(adv, sizeof adv, "eq. 8: T = exp(-sigma_t d) (1 in clear air, 0 at infinite distance)");
            cw_emit(run, "step2.eq8", pass, m, adv, NULL);
        }
    }
    /* what eq. 7 implies: T(0) = 1, 0 <= T <= 1, decreasing, T(a + b) = T(a) T(b) */
    cw_begin(run);
    {
        int bad = 0;
        char what[256] = "";
        for (i = 1; i < 6 && !bad; ++i) {
            double t0 = f->transmittance(sig[i], 0.0f);
            if (fabs(t0 - 1.0) > 1e-6) { bad = 1; cw_fmt(what, sizeof what, "T(d = 0) = %g at sigma_t = %g, not 1", t0, sig[i]); }
            for (j = 1; j < 7 && !bad; ++j) {
                double a = f->transmittance(sig[i], dist[j]), b = f->transmittance(sig[i], dist[j - 1]);
                double h = f->transmittance(sig[i], 0.5f * dist[j]);
                if (!(a >= 0.0 && a <= 1.0)) { bad = 1; cw_fmt(what, sizeof what, "T = %g at sigma_t = %g, d = %g is outside [0, 1]", a, sig[i], dist[j]); }
                else if (a > b + 1e-7) { bad = 1; cw_fmt(what, sizeof what, "T grows with distance (sigma_t = %g, d = %g -> %g)", sig[i], dist[j - 1], dist[j]); }
                else if (fabs(h * h - a) > 1e-5 * a + 1e-6) {
                    bad = 1;
                    cw_fmt(what, sizeof what, "T(%g)^2 = %.6g but T(%g) = %.6g at sigma_t = %g: eq. 7 makes every stretch of fog "
                           "attenuate independently, so T(a + b) = T(a) T(b)", 0.5 * dist[j], h * h, dist[j], a, sig[i]);
                }
            }
        }
        cw_fmt(m, sizeof m, "T(0) = 1, 0 <= T <= 1, non-increasing, T(a + b) = T(a) T(b) on a grid: %s", bad ? "violated" : "hold");
        cw_emit(run, "step2.properties", !bad, m, what, NULL);
    }
    /* edges */
    cw_begin(run);
    {
        static const float es[5][3] = {{0.0f, 1e30f, 1.0f}, {1.0f, 1e30f, 0.0f}, {1e6f, 1.0f, 0.0f}, {1e-6f, 1e6f, 0.36787944f}, {0.0f, 0.0f, 1.0f}};
        int ok = 0, bad = -1;
        float got = 0.0f, inf_ok;
        for (i = 0; i < 5; ++i) {
            float T = f->transmittance(es[i][0], es[i][1]);
            if (isfinite(T) && fabs(T - es[i][2]) <= 1e-5f) ok++;
            else if (bad < 0) { bad = i; got = T; }
        }
        inf_ok = f->transmittance(0.0f, INFINITY);
        if (isfinite(inf_ok) && inf_ok == 1.0f) ok++;
        else if (bad < 0) { bad = 5; got = inf_ok; }
        inf_ok = f->transmittance(2.0f, INFINITY);
        if (inf_ok == 0.0f) ok++;
        else if (bad < 0) { bad = 6; got = inf_ok; }
        cw_fmt(m, sizeof m, "%d of 7 edge cases right (clear air at any distance, infinite distance, sigma_t d huge or tiny)", ok);
        if (bad == 5)
            cw_fmt(adv, sizeof adv, "sigma_t = 0, d = infinity gave %g: 0 * infinity is NaN in floating point; clear air "
                   "transmits everything, T = 1 (test sigma_t = 0 or d = 0 first)", got);
        else if (bad == 6)
            cw_fmt(adv, sizeof adv, "sigma_t = 2, d = infinity gave %g, not 0", got);
        else if (bad >= 0)
            cw_fmt(adv, sizeof adv, "sigma_t = %g, d = %g gave %g, expected %g", es[bad][0], es[bad][1], got, es[bad][2]);
        else adv[0] = '\0';
        cw_emit(run, "step2.edges", ok == 7, m, adv, NULL);
    }
    /* the one-sample estimator: its mean is eq. 8 */
    cw_begin(run);
    {
        static const float ds[6] = {0.1f, 0.5f, 1.0f, 2.0f, 3.0f, 5.0f};
        double x0[6], x1[6], bar[6], line[6], worst_p = 1.0, worst_z = 0.0, wmean = 0.0, wT = 0.0, wd = 0.0;
        int n = 40000, flipped = 0;
        fogrt_rng rng;
        cw_plot p;
        char verdict[1400];
        for (j = 0; j < 6; ++j) {
            double s = 0.0, s2 = 0.0, mean, var, T = exp(-(double)ds[j]), z, pv;
            long bad = 0;
            cw_seed(&rng, 200 + j);
            for (i = 0; i < n; ++i) {
                double e = f->transmittance_estimate(1.0f, ds[j], cw_u(&rng));
                if (!isfinite(e)) { bad++; continue; }
                s += e; s2 += e * e;
            }
            mean = s / n;
            var = fmax(s2 / n - mean * mean, 0.0);
            if (bad) z = HUGE_VAL;
            else if (var > 0.0) z = (mean - T) / sqrt(var / n);
            else z = fabs(mean - T) <= 1e-6 ? 0.0 : HUGE_VAL;
            pv = cw_normal_p(z) * 6.0;     /* Bonferroni over the six distances */
            if (pv > 1.0) pv = 1.0;
            if (fabs(mean - (1.0 - T)) < 0.02) flipped++;
            x0[j] = ds[j] - 0.12; x1[j] = ds[j] + 0.12; bar[j] = mean; line[j] = T;
            if (pv < worst_p || j == 0) { worst_p = pv; worst_z = z; wmean = mean; wT = T; wd = ds[j]; }
        }
        {
            int pass = worst_p >= CW_ALPHA;
            cw_fmt(m, sizeof m, "worst distance d = %g: mean estimate %.5f vs T = %.5f, z = %.2f, p = %.3g "
                   "(Bonferroni over 6 distances; fail if p < %g), %d estimates each", wd, wmean, wT, worst_z, worst_p, CW_ALPHA, n);
            if (flipped >= 4)
                cw_fmt(adv, sizeof adv, "your estimate averages 1 - T: it scores the flights that collide before d; T is "
                       "the probability of NO collision (eq. 4), so score 1 when the free flight goes past d");
            else
                cw_fmt(adv, sizeof adv, "the estimate's mean must be exp(-sigma_t d): draw a free-flight distance t with u "
                       "and return 1 if t >= d, else 0 (or any other unbiased estimate)");
            memset(&p, 0, sizeof p);
            p.title = "Step 2: mean of your transmittance estimates, sigma_t = 1 (eq. 8)";
            p.xlabel = "distance d"; p.ylabel = "transmittance"; p.bar_label = "mean of your estimates";
            p.line_label = "exp(-sigma_t d)"; p.n = 6; p.x0 = x0; p.x1 = x1; p.bar = bar; p.line = line;
            p.xmin = 0.0; p.xmax = 5.5; p.points = 1; p.logy = 0;
            {
                static double cx[111], cy[111];
                for (i = 0; i < 111; ++i) { cx[i] = 0.05 * i; cy[i] = exp(-cx[i]); }
                p.cn = 111; p.cx = cx; p.cy = cy;
            }
            cw_fmt(verdict, sizeof verdict, "step2.estimator %s: %s%s%s", pass ? "PASS" : "FAIL", m, pass ? "" : " -- ", pass ? "" : adv);
            cw_picture(run, "step2_estimator", &p, verdict, pass, png, sizeof png);
            cw_emit(run, "step2.estimator", pass, m, adv, png);
        }
    }
}

/* ==========================================================================================
   Step 3: Henyey-Greenstein (eq. 9-12)
   ========================================================================================== */
static double cw_hg_ref(double g, double mu)
{
    return (1.0 - g * g) / (4.0 * CW_PI * pow(1.0 + g * g - 2.0 * g * mu, 1.5));
}
/* P(mu' <= mu) under HG, in a form without a division by g. */
static double cw__hg_cdf(double mu, const void *user)
{
    double g = *(const double *)user, s;
    if (mu <= -1.0) return 0.0;
    if (mu >= 1.0) return 1.0;
    if (g == 0.0) return 0.5 * (mu + 1.0);
    s = sqrt(1.0 + g * g - 2.0 * g * mu);
    /* (1 - g^2)/(2g) (1/s - 1/(1+g)) = (1 - g^2)(1 + g - s) / (2 g s (1 + g)), and
       1 + g - s = ((1+g)^2 - s^2)/(1 + g + s) = 2g(1 + mu)/(1 + g + s) */
    return (1.0 - g) * (1.0 + mu) / (s * (1.0 + g + s));
}
/* The mu at which the HG CDF reaches q (eq. 11 in a form exact at g = 0). */
static double cw__hg_quantile(double g, double q)
{
    double D = (1.0 - g) + 2.0 * g * q;
    return (2.0 * q - (1.0 - g)) / D + 2.0 * g * (1.0 - g) * (1.0 + g) * q * (1.0 - q) / (D * D);
}
typedef struct cw__hgp { const cw_fns *f; double g; } cw__hgp;
static double cw__hg_student_mu(double mu, const void *user)
{
    const cw__hgp *p = (const cw__hgp *)user;
    return 2.0 * CW_PI * p->f->hg_phase((float)p->g, (float)mu);
}

static void cw_step3(const cw_fns *f, cw_run *run)
{
    static const double gs_eq[6] = {-0.9, -0.5, 0.0, 0.3, 0.8, 0.99};
    char name[64], m[600], adv[600], png[256], stem[64], title[160], verdict[1400];
    int i, k;
    /* eq. 9 pointwise */
    cw_begin(run);
    {
        double worst = 0.0, wg = 0.0, wmu = 0.0;
        int n = 0, flipped = 0, times4pi = 0, permu = 0;
        for (k = 0; k < 6; ++k)
            for (i = 0; i <= 40; ++i) {
                double g = (float)gs_eq[k], mu = (float)(-1.0 + 2.0 * i / 40.0), ref = cw_hg_ref(g, mu);
                double v = f->hg_phase((float)g, (float)mu);
                /* float rounding of 1 + g^2 - 2 g mu is relative to its terms, and the
                   power 3/2 carries it on: near the peak (g -> 1, mu = 1) the base is
                   (1 - g)^2, and a correct float formula is off by ~1e-6 terms / base */
                double base = 1.0 + g * g - 2.0 * g * mu, terms = 1.0 + g * g + 2.0 * fabs(g * mu);
                double err = fabs(v - ref) / ((1e-4 + 1e-6 * terms / base) * ref + 1e-9);
                n++;
                if (!(err <= worst)) { worst = err; wg = g; wmu = mu; }
                {
                    /* the same float allowance as for eq. 9 itself, at the flipped peak */
                    double fb = 1.0 + g * g + 2.0 * g * mu, fr = cw_hg_ref(-g, mu);
                    if (fabs(v - fr) <= (1e-4 + 1e-6 * terms / fb) * fr + 1e-9) flipped++;
                }
                if (fabs(v - 4.0 * CW_PI * ref) <= 1e-4 * 4.0 * CW_PI * ref) times4pi++;
                if (fabs(v - 2.0 * CW_PI * ref) <= 1e-4 * 2.0 * CW_PI * ref) permu++;
            }
        {
            int pass = worst <= 1.0;
            cw_fmt(m, sizeof m, "largest error at g = %g, mu = %g: %.7g against eq. 9's %.7g (relative tolerance 1e-4, more "
                   "near the peak where float rounding grows)", wg, wmu, f->hg_phase((float)wg, (float)wmu), cw_hg_ref(wg, wmu));
            if (flipped >= n * 9 / 10)
                cw_fmt(adv, sizeof adv, "your values are HG with -g: is g's sign flipped? (g > 0 must favour mu = +1, the "
                       "direction the light was already going)");
            else if (times4pi == n)
                cw_fmt(adv, sizeof adv, "your values are 4 pi times eq. 9: the 1/(4 pi) in front is missing");
            else if (permu == n)
                cw_fmt(adv, sizeof adv, "your values are 2 pi times eq. 9, the density per unit mu; eq. 9 is per steradian");
            else
                cw_fmt(adv, sizeof adv, "eq. 9: p(mu) = (1 - g^2) / (4 pi (1 + g^2 - 2 g mu)^(3/2))");
            cw_emit(run, "step3.eq9", pass, m, adv, NULL);
        }
    }
    /* normalisation over the sphere */
    cw_begin(run);
    {
        double worst = 0.0, wI = 1.0, wg = 0.0;
        for (k = 0; k < 6; ++k) {
            cw__hgp hp;
            double I;
            hp.f = f; hp.g = gs_eq[k];
            I = cw_integrate(cw__hg_student_mu, &hp, -1.0, 1.0);
            if (!(fabs(I - 1.0) <= worst)) { worst = fabs(I - 1.0); wI = I; wg = gs_eq[k]; }
        }
        cw_fmt(m, sizeof m, "integral over the sphere, 2 pi * integral of p(mu) dmu: %.6g at g = %g (expected 1 +- 0.002)", wI, wg);
        if (fabs(wI - 4.0 * CW_PI) < 0.05)
            cw_fmt(adv, sizeof adv, "the phase function integrates to 4 pi = 12.57: eq. 9's 1/(4 pi) is missing");
        else if (fabs(wI - 2.0 * CW_PI) < 0.05)
            cw_fmt(adv, sizeof adv, "the phase function integrates to 2 pi: it is the density per unit mu; eq. 9 is per steradian");
        else
            cw_fmt(adv, sizeof adv, "a phase function is a density over directions: its integral over the sphere is 1");
        cw_emit(run, "step3.phase_integral", worst <= 2e-3, m, adv, NULL);
    }
    /* mu samples against eq. 9's CDF, and the student's phase against the samples */
    {
        static const double gs[4] = {-0.7, 0.0, 0.3, 0.9};
        for (k = 0; k < 4; ++k) {
            double g = gs[k], mean, x0[CW_HMAX], x1[CW_HMAX], bar[CW_HMAX], line[CW_HMAX], z;
            int nb = 50, pass, w;
            cw_hist h;
            cw_fit fit;
            fogrt_rng rng;
            cw_plot p;
            cw__hgp hp;
            double total = 0.0;
            cw_begin(run);
            cw_hist_init(&h, nb);
            for (i = 0; i <= nb; ++i) h.edge[i] = i == 0 ? -1.0 : (i == nb ? 1.0 : cw__hg_quantile(g, (double)i / nb));
            cw_seed(&rng, 300 + k);
            for (i = 0; i < CW_N; ++i) {
                float u = cw_u(&rng);
                cw_hist_add(&h, f->sample_hg_mu((float)g, u), u, 1e-5);
            }
            cw_hist_expect(&h, cw__hg_cdf, &g);
            fit = cw_hist_fit(h.obs, h.expd, nb);
            pass = h.invalid == 0 && fit.p >= CW_ALPHA;
            mean = h.n > h.invalid ? h.sum / (double)(h.n - h.invalid) : NAN;
            cw_fmt(m, sizeof m, "chi2 = %.1f, dof %d, p = %.3g (fail if p < %g); mean mu = %.4f, HG's mean is g = %g",
                   fit.chi2, fit.dof, fit.p, CW_ALPHA, mean, g);
            if (h.invalid)
                cw_fmt(adv, sizeof adv, "%ld samples were NaN or outside [-1, 1] (first: mu = %g at u = %.9g)%s", h.invalid,
                       h.first_invalid, h.first_invalid_u,
                       g == 0.0 ? ": at g = 0 eq. 11 divides 0 by 0; HG is then isotropic, mu = 2u - 1" : "");
            else if (g != 0.0 && mean * g < 0.0 && fabs(mean + g) < 0.05)
                cw_fmt(adv, sizeof adv, "more samples near mu = %s1 than HG with g = %g allows (mean mu = %.3f, should be %g): "
                       "is g's sign flipped?", g > 0 ? "-" : "+", g, mean, g);
            else if (fabs(mean - g) > 0.02)
                cw_fmt(adv, sizeof adv, "mean mu = %.3f but HG's mean cosine is g = %g: the samples lean %s than eq. 9",
                       mean, g, mean > g ? "further forward" : "further backward");
            else
                cw_fmt(adv, sizeof adv, "the mean is right but the shape is not HG's: check eq. 11 term by term");
            cw_hist_density(&h, 1.0, x0, x1, bar, line);
            memset(&p, 0, sizeof p);
            cw_fmt(title, sizeof title, "Step 3: sampled mu = cos(theta), g = %g (eq. 11)", g);
            p.title = title; p.xlabel = "mu = cos(theta) from the propagation direction"; p.ylabel = "density per unit mu";
            p.bar_label = "your samples"; p.line_label = "HG, eq. 9 (x 2 pi)"; p.n = nb; p.x0 = x0; p.x1 = x1;
            p.bar = bar; p.line = line; p.xmin = -1.0; p.xmax = 1.0; p.logy = -1;
            cw_fmt(stem, sizeof stem, "step3_mu_chi2_g%g", g);
            cw_fmt(name, sizeof name, "step3.mu_chi2 g=%g", g);
            cw_fmt(verdict, sizeof verdict, "%s %s: %s%s%s", name, pass ? "PASS" : "FAIL", m, pass ? "" : " -- ", pass ? "" : adv);
            cw_picture(run, stem, &p, verdict, pass, png, sizeof png);
            cw_emit(run, name, pass, m, adv, png);

            /* the student's phase function integrated over the same bins */
            cw_begin(run);
            hp.f = f; hp.g = g;
            for (i = 0; i < nb; ++i) {
                h.expd[i] = (double)h.n * cw_integrate(cw__hg_student_mu, &hp, h.edge[i], h.edge[i + 1]);
                total += h.expd[i];
            }
            fit = cw_hist_fit(h.obs, h.expd, nb);
            pass = h.invalid == 0 && fit.p >= CW_ALPHA;
            w = cw_worst_bin(h.obs, h.expd, nb, &z);
            cw_fmt(m, sizeof m, "chi2 = %.1f, dof %d, p = %.3g (fail if p < %g); your phase function's mass %.4g",
                   fit.chi2, fit.dof, fit.p, CW_ALPHA, total / (double)h.n);
            if (h.invalid) cw_fmt(adv, sizeof adv, "the sampler gave invalid mu (see step3.mu_chi2)");
            else if (fabs(total / (double)h.n - 1.0) > 0.01)
                cw_fmt(adv, sizeof adv, "your phase function integrates to %.4g over the sphere, not 1 (see step3.phase_integral)",
                       total / (double)h.n);
            else
                cw_fmt(adv, sizeof adv, "your phase function and your sampler disagree most for mu in [%.3f, %.3f): %.0f "
                       "samples, your eq. 9 predicts %.0f; sampling and evaluation must use the same g and the same mu",
                       h.edge[w], h.edge[w + 1], h.obs[w], h.expd[w]);
            cw_hist_density(&h, 1.0, x0, x1, bar, line);
            cw_fmt(title, sizeof title, "Step 3: your phase function against your samples, g = %g", g);
            p.line_label = "your eq. 9 (x 2 pi)";
            cw_fmt(stem, sizeof stem, "step3_pdf_vs_hist_g%g", g);
            cw_fmt(name, sizeof name, "step3.pdf_vs_hist g=%g", g);
            cw_fmt(verdict, sizeof verdict, "%s %s: %s%s%s", name, pass ? "PASS" : "FAIL", m, pass ? "" : " -- ", pass ? "" : adv);
            cw_picture(run, stem, &p, verdict, pass, png, sizeof png);
            cw_emit(run, name, pass, m, adv, png);
        }
    }
    /* full directions on the sphere around d = -wo (eq. 11 and 12) */
    {
        static const double cases[2][4] = {{0.5, 0.3, -0.5, 0.8}, {-0.3, 0.0, 0.0, -1.0}};
        for (k = 0; k < 2; ++k) {
            static stats_sphere_grid grid;
            static double obs[20 * 16], expd[20 * 16];
            double g = cases[k][0], dsum = 0.0;
            fogrt_vec3 wo = cw_v3(cases[k][1], cases[k][2], cases[k][3]);
            int nc = 20, np = 16, j, pass, empty_cols = 0;
            long invalid = 0;
            fogrt_rng rng;
            cw_fit fit, fit_mu;
            double mo[20], me[20], po[16], pe[16];
            cw_begin(run);
            stats_grid_init(&grid, nc, np);
            stats_grid_set_axis(&grid, -wo.x, -wo.y, -wo.z);
            for (i = 1; i < nc; ++i) grid.cos_edge[i] = cw__hg_quantile(g, (double)i / nc);
            memset(obs, 0, sizeof obs);
            cw_seed(&rng, 320 + k);
            for (i = 0; i < CW_N; ++i) {
                float u1 = cw_u(&rng), u2 = cw_u(&rng);
                fogrt_vec3 wi = f->sample_hg((float)g, wo, u1, u2);
                int cell = cw_finite3(wi) ? stats_grid_cell(&grid, wi.x, wi.y, wi.z) : -1;
                if (cell < 0) { invalid++; continue; }
                obs[cell] += 1.0;
                dsum += -(wi.x * (double)wo.x + wi.y * (double)wo.y + wi.z * (double)wo.z);
            }
            for (i = 0; i < nc; ++i)
                for (j = 0; j < np; ++j)
                    expd[i * np + j] = CW_N * (cw__hg_cdf(grid.cos_edge[i + 1], &g) - cw__hg_cdf(grid.cos_edge[i], &g)) / np;
            fit = cw_hist_fit(obs, expd, nc * np);
            memset(mo, 0, sizeof mo); memset(me, 0, sizeof me); memset(po, 0, sizeof po); memset(pe, 0, sizeof pe);
            for (i = 0; i < nc; ++i)
                for (j = 0; j < np; ++j) {
                    mo[i] += obs[i * np + j]; me[i] += expd[i * np + j];
                    po[j] += obs[i * np + j]; pe[j] += expd[i * np + j];
                }
            for (j = 0; j < np; ++j) if (po[j] < 0.3 * pe[j]) empty_cols++;
            fit_mu = cw_hist_fit(mo, me, nc);
            pass = invalid == 0 && fit.p >= CW_ALPHA;
            {
                double mean = dsum / (double)(CW_N - invalid > 0 ? CW_N - invalid : 1);
                cw_fmt(m, sizeof m, "chi2 = %.1f, dof %d, p = %.3g (fail if p < %g) on %d x %d cells (mu, phi) around d = -wo; "
                       "mean cos(d, wi) = %.4f, g = %g", fit.chi2, fit.dof, fit.p, CW_ALPHA, nc, np, mean, g);
                if (invalid)
                    cw_fmt(adv, sizeof adv, "%ld directions were not finite or not unit length: build wi from sin(theta), "
                           "cos(theta) and phi in an orthonormal frame around d", invalid);
                else if (fabs(mean + g) < 0.03 && g != 0.0)
                    cw_fmt(adv, sizeof adv, "the directions scatter around wo instead of the propagation direction d = -wo: "
                           "mu is measured from d, so g > 0 keeps the light going the way it went");
                else if (empty_cols >= np / 4)
                    cw_fmt(adv, sizeof adv, "%d of %d azimuth sectors around d are (nearly) empty: phi must cover the whole "
                           "circle, phi = 2 pi xi2 (eq. 12)", empty_cols, np);
                else if (fit_mu.p >= CW_ALPHA)
                    cw_fmt(adv, sizeof adv, "the angle from d is right but the azimuth is not uniform: phi = 2 pi xi2 "
                           "(eq. 12) in a frame perpendicular to d");
                else
                    cw_fmt(adv, sizeof adv, "the angle to d does not follow HG: use your cw_sample_hg_mu for cos(theta) "
                           "and measure it from d = -wo");
            }
            cw_fmt(title, sizeof title, "Step 3: directions, g = %g: angle from d = -wo", g);
            cw_fmt(stem, sizeof stem, "step3_direction_chi2_g%g", g);
            cw_fmt(name, sizeof name, "step3.direction_chi2 g=%g", g);
            cw_fmt(verdict, sizeof verdict, "%s %s: %s%s%s", name, pass ? "PASS" : "FAIL", m, pass ? "" : " -- ", pass ? "" : adv);
            cw_picture_sphere(run, stem, &grid, obs, expd, title, "mu = cos(d, wi)", "HG", -1,
                              "... and azimuth phi around d (eq. 12)", "uniform", verdict, pass, png, sizeof png);
            cw_emit(run, name, pass, m, adv, png);
        }
    }
    /* edges */
    cw_begin(run);
    {
        static const float eg[5] = {0.0f, 0.99f, -0.99f, 1e-4f, -1e-4f};
        static const float eu[3] = {0.0f, 0.5f, CW_U_MAX};
        int ok = 0, total = 0, bad = 0, mirrored = 0, mu_bad = 0;
        char what[400] = "";
        for (k = 0; k < 5; ++k)
            for (i = 0; i < 3; ++i) {
                float mu = f->sample_hg_mu(eg[k], eu[i]);
                double ref = cw__hg_quantile(eg[k], eu[i]);
                total++;
                if (isfinite(mu) && fabs(mu) <= 1.0f + 1e-5f && fabs(mu - ref) <= 2e-3) ok++;
                else {
                    mu_bad++;
                    /* the same distribution run the other way: mu(u) = quantile(1 - u) */
                    if (isfinite(mu) && fabs(mu - cw__hg_quantile(eg[k], 1.0 - (double)eu[i])) <= 2e-3) mirrored++;
                }
                if (!(isfinite(mu) && fabs(mu) <= 1.0f + 1e-5f && fabs(mu - ref) <= 2e-3) && !bad++) {
                    if (eg[k] == 0.0f && !isfinite(mu))
                        cw_fmt(what, sizeof what, "g = 0 gave mu = %s at u = %g: eq. 11 divides by 2g; at g = 0 HG is "
                               "isotropic, mu = 2u - 1 (use it when |g| is tiny)", isnan(mu) ? "nan" : "infinity", eu[i]);
                    else
                        cw_fmt(what, sizeof what, "g = %g, u = %.9g gave mu = %.7g, eq. 11 gives %.7g", eg[k], eu[i], mu, ref);
                }
                {
                    fogrt_vec3 wo = cw_v3(0.0, 0.6, 0.8), wi = f->sample_hg(eg[k], wo, eu[i], eu[2 - i]);
                    total++;
                    if (cw_finite3(wi) && fabs(cw_len3(wi) - 1.0) < 1e-4) ok++;
                    else if (!bad++)
                        cw_fmt(what, sizeof what, "cw_sample_hg(g = %g, u1 = %.9g) gave (%g, %g, %g), not a unit vector",
                               eg[k], eu[i], wi.x, wi.y, wi.z);
                }
            }
        for (k = 0; k < 3; ++k)
            for (i = -1; i <= 1; i += 2) {
                float v = f->hg_phase(eg[k], (float)i);
                total++;
                if (isfinite(v) && v >= 0.0f) ok++;
                else if (!bad++) cw_fmt(what, sizeof what, "p(g = %g, mu = %d) = %g", eg[k], i, v);
            }
        if (mu_bad > 0 && mirrored == mu_bad)
            cw_fmt(what, sizeof what, "your mu runs the other way: mu(u) is eq. 11's mu(1 - u), falling from +1 at u = 0. "
                   "The distribution is right (the chi-square checks pass), but the kit's convention (coursework.h, step 3) "
                   "is eq. 11 as the paper writes it, mu rising with u from -1 at u = 0: this check failed on the "
                   "convention alone");
        cw_fmt(m, sizeof m, "%d of %d edge cases finite and right (g = 0, +-1e-4, +-0.99; u = 0, 0.5, 1 - 2^-24)", ok, total);
        cw_emit(run, "step3.edges", ok == total, m, what, NULL);
    }
}

/* ==========================================================================================
   Step 4: the BVH split choice (eq. 1-2)
   ========================================================================================== */
static double cw_box_area(const cw_aabb *b)
{
    double e0 = (double)b->hi[0] - b->lo[0], e1 = (double)b->hi[1] - b->lo[1], e2 = (double)b->hi[2] - b->lo[2];
    if (e0 < 0.0 || e1 < 0.0 || e2 < 0.0) return 0.0;
    return 2.0 * (e0 * e1 + e1 * e2 + e2 * e0);
}
static double cw_box_volume(const cw_aabb *b)
{
    double e0 = (double)b->hi[0] - b->lo[0], e1 = (double)b->hi[1] - b->lo[1], e2 = (double)b->hi[2] - b->lo[2];
    if (e0 < 0.0 || e1 < 0.0 || e2 < 0.0) return 0.0;
    return e0 * e1 * e2;
}
static double cw_ref_cost(int heuristic, const cw_aabb *parent, const cw_aabb *l, int nl, const cw_aabb *r, int nr)
{
    if (heuristic == CW_VOLUME) return nl * cw_box_volume(l) + nr * cw_box_volume(r);
    return 1.0 + (nl * cw_box_area(l) + nr * cw_box_area(r)) / fmax(cw_box_area(parent), 1e-300);
}
static void cw_box_empty(cw_aabb *b)
{
    int a;
    for (a = 0; a < 3; ++a) { b->lo[a] = FLT_MAX; b->hi[a] = -FLT_MAX; }
}
static void cw_box_grow(cw_aabb *b, const cw_aabb *c)
{
    int a;
    for (a = 0; a < 3; ++a) { b->lo[a] = fminf(b->lo[a], c->lo[a]); b->hi[a] = fmaxf(b->hi[a], c->hi[a]); }
}

/* A node: its primitives' boxes, binned as fogrt bins them (equal slices of the centroid
   range; every centroid in bin 0 on an axis where they coincide). */
typedef struct cw_node {
    int n;
    cw_aabb prim[256];
    cw_aabb parent;
    cw_bins bins;
} cw_node;

static void cw_node_bin(cw_node *nd, int n_bins)
{
    double clo[3], chi[3];
    int i, a;
    cw_box_empty(&nd->parent);
    for (a = 0; a < 3; ++a) { clo[a] = HUGE_VAL; chi[a] = -HUGE_VAL; }
    for (i = 0; i < nd->n; ++i) {
        cw_box_grow(&nd->parent, &nd->prim[i]);
        for (a = 0; a < 3; ++a) {
            double c = 0.5 * ((double)nd->prim[i].lo[a] + nd->prim[i].hi[a]);
            clo[a] = fmin(clo[a], c); chi[a] = fmax(chi[a], c);
        }
    }
    memset(&nd->bins, 0, sizeof nd->bins);
    nd->bins.n_bins = n_bins;
    for (a = 0; a < 3; ++a) for (i = 0; i < n_bins; ++i) cw_box_empty(&nd->bins.box[a][i]);
    for (i = 0; i < nd->n; ++i)
        for (a = 0; a < 3; ++a) {
            double c = 0.5 * ((double)nd->prim[i].lo[a] + nd->prim[i].hi[a]);
            int k = chi[a] > clo[a] ? (int)((c - clo[a]) / (chi[a] - clo[a]) * n_bins) : 0;
            if (k >= n_bins) k = n_bins - 1;
            if (k < 0) k = 0;
            nd->bins.count[a][k]++;
            cw_box_grow(&nd->bins.box[a][k], &nd->prim[i]);
        }
}
/* The two sides of plane k on axis a. */
static void cw_node_sides(const cw_node *nd, int a, int k, cw_aabb *l, int *nl, cw_aabb *r, int *nr)
{
    int j;
    cw_box_empty(l); cw_box_empty(r);
    *nl = *nr = 0;
    for (j = 0; j < nd->bins.n_bins; ++j) {
        if (!nd->bins.count[a][j]) continue;
        if (j < k) { cw_box_grow(l, &nd->bins.box[a][j]); *nl += nd->bins.count[a][j]; }
        else { cw_box_grow(r, &nd->bins.box[a][j]); *nr += nd->bins.count[a][j]; }
    }
}
/* The reference's cheapest plane; cost HUGE_VAL and plane -1 when nothing splits. */
static cw_split cw_ref_best(int heuristic, const cw_node *nd, double *cost)
{
    cw_split s;
    int a, k;
    s.axis = 0; s.plane = -1; s.cost = 0.0f;
    *cost = HUGE_VAL;
    for (a = 0; a < 3; ++a)
        for (k = 1; k < nd->bins.n_bins; ++k) {
            cw_aabb l, r;
            int nl, nr;
            double c;
            cw_node_sides(nd, a, k, &l, &nl, &r, &nr);
            if (!nl || !nr) continue;
            c = cw_ref_cost(heuristic, &nd->parent, &l, nl, &r, nr);
            if (c < *cost) { *cost = c; s.axis = a; s.plane = k; s.cost = (float)c; }
        }
    return s;
}

static double cw_rand_range(fogrt_rng *r, double a, double b) { return a + (b - a) * cw_u(r); }

/* Random primitive sets of four kinds: uniform, two clusters, long along x, flat in z. */
static void cw_make_node(cw_node *nd, fogrt_rng *r, int kind, int n)
{
    int i, a;
    nd->n = n;
    for (i = 0; i < n; ++i) {
        double c[3], e[3];
        for (a = 0; a < 3; ++a) { c[a] = cw_rand_range(r, 0.0, 1.0); e[a] = cw_rand_range(r, 0.002, 0.08); }
        if (kind == 1) { double off = cw_u(r) < 0.3 ? 0.0 : 2.5; c[1] = c[1] * 0.3 + off; c[0] *= 0.5; }
        if (kind == 2) { c[0] *= 8.0; e[0] *= 3.0; }
        if (kind == 3) { c[2] = 0.0; e[2] = 0.0; e[1] *= 2.0; }
        for (a = 0; a < 3; ++a) { nd->prim[i].lo[a] = (float)(c[a] - e[a]); nd->prim[i].hi[a] = (float)(c[a] + e[a]); }
    }
}

static const char *cw_kind_name(int kind)
{
    static const char *names[4] = {"uniform", "two clusters", "long along x", "flat in z"};
    return names[kind & 3];
}

/* The cost formulas on random boxes, with the usual mistakes recognised. */
static void cw_step4_cost(const cw_fns *f, cw_run *run, int heuristic)
{
    fogrt_rng rng;
    int i, n = 20000, matches[6] = {0, 0, 0, 0, 0, 0};
    double worst = 0.0;
    char m[600], adv[600];
    cw_aabb wl, wr, wp;
    int wnl = 0, wnr = 0;
    memset(&wl, 0, sizeof wl); wr = wp = wl;
    float wgot = 0.0f;
    cw_begin(run);
    cw_seed(&rng, heuristic == CW_SAH ? 400 : 401);
    for (i = 0; i < n; ++i) {
        cw_aabb l, r, p;
        int a, nl = 1 + (int)(cw_u(&rng) * 100.0f), nr = 1 + (int)(cw_u(&rng) * 100.0f);
        double ref, got, al, ar, ap, vl, vr, vp, alt[6];
        for (a = 0; a < 3; ++a) {
            double lo = cw_rand_range(&rng, -1.0, 1.0), hi = lo + cw_rand_range(&rng, 0.01, 2.0);
            double lo2 = cw_rand_range(&rng, -1.0, 1.0), hi2 = lo2 + cw_rand_range(&rng, 0.01, 2.0);
            l.lo[a] = (float)lo; l.hi[a] = (float)hi; r.lo[a] = (float)lo2; r.hi[a] = (float)hi2;
        }
        p = l;
        cw_box_grow(&p, &r);
        ref = cw_ref_cost(heuristic, &p, &l, nl, &r, nr);
        got = f->split_cost(heuristic, &p, &l, nl, &r, nr);
        al = cw_box_area(&l); ar = cw_box_area(&r); ap = cw_box_area(&p);
        vl = cw_box_volume(&l); vr = cw_box_volume(&r); vp = cw_box_volume(&p);
        if (heuristic == CW_SAH) {
            alt[0] = nl * al + nr * ar;                       /* no division, no traversal cost */
            alt[1] = (nl * al + nr * ar) / ap;                /* no traversal cost */
            alt[2] = 1.0 + (nl * vl + nr * vr) / vp;          /* volumes */
            alt[3] = 1.0 + (nl * ar + nr * al) / ap;          /* counts swapped */
            alt[4] = 1.0 + (nl * al + nr * ar);               /* no division */
            alt[5] = HUGE_VAL;
        } else {
            alt[0] = nl * vr + nr * vl;                       /* the product summed the wrong way */
            alt[1] = (double)(nl + nr) * (vl + vr);
            alt[2] = nl * al + nr * ar;                       /* areas */
            alt[3] = (nl * vl + nr * vr) / vp;                /* divided by the parent */
            alt[4] = 1.0 + nl * vl + nr * vr;
            alt[5] = HUGE_VAL;
        }
        for (a = 0; a < 6; ++a) if (fabs(got - alt[a]) <= 1e-4 * fabs(alt[a])) matches[a]++;
        {
            double err = fabs(got - ref) / (1e-4 * fabs(ref) + 1e-12);
            if (!(err <= worst)) { worst = err; wl = l; wr = r; wp = p; wnl = nl; wnr = nr; wgot = (float)got; }
        }
    }
    {
        int pass = worst <= 1.0, a, best = -1;
        const char *hname = heuristic == CW_SAH ? "SAH" : "volume heuristic";
        for (a = 0; a < 6; ++a) if (matches[a] > n * 9 / 10) { best = a; break; }
        cw_fmt(m, sizeof m, "%d random splits; worst: N_l = %d, N_r = %d, you gave %.7g, the %s gives %.7g (relative tolerance 1e-4)",
               n, wnl, wnr, wgot, hname, cw_ref_cost(heuristic, &wp, &wl, wnl, &wr, wnr));
        if (heuristic == CW_SAH) {
            static const char *why[5] = {
                ("you return N_l A_l + N_r A_r: divide by the parent's area A (a ray that hits the parent hits a child with "
                 "probability A_child / A) and add the traversal cost 1"),
                "you return (N_l A_l + N_r A_r) / A: the SAH adds the traversal cost, 1 + ...",
                "you used volumes; the SAH weighs each side by its surface area",
                "each side's count must multiply its own area: N_l A_l + N_r A_r",
                "you did not divide by the parent's area A: 1 + (N_l A_l + N_r A_r) / A"};
            cw_fmt(adv, sizeof adv, "%s", best >= 0 && best < 5 ? why[best] : "SAH: 1 + (N_l A_l + N_r A_r) / A, A = 2 (dx dy + dy dz + dz dx)");
        } else {
            static const char *why[5] = {
                ("the volume heuristic's product is summed the wrong way (N_l V_r + N_r V_l): eq. 1 pairs each side's count "
                 "with its own volume, H = N_l V_l + N_r V_r"),
                "you multiply the sums, (N_l + N_r)(V_l + V_r): eq. 1 is a sum of products, N_l V_l + N_r V_r",
                "you used surface areas: eq. 1 weighs each side by its volume V = dx dy dz",
                "eq. 1 has no division by the parent's volume: H = N_l V_l + N_r V_r",
                "eq. 1 has no traversal cost: H = N_l V_l + N_r V_r"};
            cw_fmt(adv, sizeof adv, "%s", best >= 0 && best < 5 ? why[best] : "eq. 1: H = N_l V_l + N_r V_r");
        }
        cw_emit(run, heuristic == CW_SAH ? "step4.sah_cost" : "step4.volume_cost", pass, m, adv, NULL);
    }
}

/* The student's choice on random binned nodes against the cheapest plane. */
static void cw_step4_choice(const cw_fns *f, cw_run *run, int heuristic)
{
    static cw_node nd;
    fogrt_rng rng;
    int s, sets = 400, good = 0, first_bad = -1, only_x = 0, worst_pick = 0, empty_pick = 0, own_cheapest = 0;
    char m[700], adv[700], png[256], title[200], verdict[1400];
    cw_split bad_pick, bad_best;
    double bad_cost = 0.0, bad_best_cost = 0.0;
    int bad_n = 0, bad_kind = 0;
    const char *hname = heuristic == CW_SAH ? "SAH" : "volume heuristic";
    cw_begin(run);
    memset(&bad_pick, 0, sizeof bad_pick); bad_best = bad_pick;
    cw_seed(&rng, heuristic == CW_SAH ? 410 : 411);
    for (s = 0; s < sets; ++s) {
        int kind = s % 4, n = 2 + (int)(cw_u(&rng) * 150.0f), ok;
        double best_cost, got_cost = HUGE_VAL;
        cw_split best, got;
        cw_make_node(&nd, &rng, kind, n);
        cw_node_bin(&nd, 12);
        best = cw_ref_best(heuristic, &nd, &best_cost);
        got = f->best_split(heuristic, &nd.parent, &nd.bins);
        if (best.plane < 0) ok = got.plane == -1;
        else if (got.axis < 0 || got.axis > 2 || got.plane < 1 || got.plane >= nd.bins.n_bins) ok = 0;
        else {
            cw_aabb l, r;
            int nl, nr;
            cw_node_sides(&nd, got.axis, got.plane, &l, &nl, &r, &nr);
            if (!nl || !nr) { ok = 0; got_cost = HUGE_VAL; }
            else {
                got_cost = cw_ref_cost(heuristic, &nd.parent, &l, nl, &r, nr);
                ok = got_cost <= best_cost * (1.0 + 1e-5) + 1e-9;
            }
        }
        if (ok) { good++; continue; }
        if (first_bad < 0) {
            int a, k;
            double axis_best[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, worst = -1.0;
            first_bad = s; bad_pick = got; bad_best = best; bad_cost = got_cost; bad_best_cost = best_cost;
            bad_n = n; bad_kind = kind;
            if (got.plane >= 1 && got.plane < nd.bins.n_bins && got.axis >= 0 && got.axis < 3) {
                cw_aabb l, r;
                int nl, nr;
                cw_node_sides(&nd, got.axis, got.plane, &l, &nl, &r, &nr);
                if (!nl || !nr) empty_pick = 1;
            }
            /* the planes priced by the reference and by the student's own cw_split_cost: a
               choice that is the cheapest under the student's cost points at the cost */
            double own_min = HUGE_VAL, own_max = -HUGE_VAL, own_got = NAN;
            for (a = 0; a < 3; ++a)
                for (k = 1; k < nd.bins.n_bins; ++k) {
                    cw_aabb l, r;
                    int nl, nr;
                    double c, o;
                    cw_node_sides(&nd, a, k, &l, &nl, &r, &nr);
                    if (!nl || !nr) continue;
                    c = cw_ref_cost(heuristic, &nd.parent, &l, nl, &r, nr);
                    o = f->split_cost(heuristic, &nd.parent, &l, nl, &r, nr);
                    if (c < axis_best[a]) axis_best[a] = c;
                    if (c > worst) worst = c;
                    if (o < own_min) own_min = o;
                    if (o > own_max) own_max = o;
                    if (a == got.axis && k == got.plane) own_got = o;
                }
            if (got.axis >= 0 && got.axis < 3 && fabs(got_cost - axis_best[got.axis]) <= 1e-6 * axis_best[got.axis] + 1e-12)
                only_x = 1;
            if (fabs(own_got - own_min) <= 1e-6 * fabs(own_min) + 1e-12) own_cheapest = 1;
            else if (fabs(own_got - own_max) <= 1e-6 * fabs(own_max) + 1e-12 || fabs(got_cost - worst) <= 1e-6 * worst + 1e-12)
                worst_pick = 1;
        }
    }
    {
        int pass = good == sets;
        cw_fmt(m, sizeof m, "the cheapest plane (%s, 12 bins per axis) chosen on %d of %d random nodes", hname, good, sets);
        if (pass) adv[0] = '\0';
        else if (empty_pick || (bad_pick.plane >= 0 && bad_best.plane < 0))
            cw_fmt(adv, sizeof adv, "node %d (%d primitives, %s): you chose axis %d plane %d, which leaves one side empty: a "
                   "plane with no primitive on one side is not a split (skip it%s)", first_bad, bad_n, cw_kind_name(bad_kind),
                   bad_pick.axis, bad_pick.plane, bad_best.plane < 0 ? "; return plane -1 when no plane splits" : "");
        else if (bad_pick.plane < 1 || bad_pick.axis < 0 || bad_pick.axis > 2)
            cw_fmt(adv, sizeof adv, "node %d (%d primitives, %s): you returned axis %d plane %d; planes run from 1 to n_bins - 1 "
                   "(the best is axis %d plane %d)", first_bad, bad_n, cw_kind_name(bad_kind), bad_pick.axis, bad_pick.plane,
                   bad_best.axis, bad_best.plane);
        else
            cw_fmt(adv, sizeof adv, "node %d (%d primitives, %s): you chose axis %d plane %d (cost %.5g), the cheapest is axis %d "
                   "plane %d (%.5g)%s", first_bad, bad_n, cw_kind_name(bad_kind), bad_pick.axis, bad_pick.plane, bad_cost,
                   bad_best.axis, bad_best.plane, bad_best_cost,
                   own_cheapest ? (heuristic == CW_SAH ? ": it is the cheapest under your cw_split_cost, so the cost is what "
                                   "differs (see step4.sah_cost)" : ": it is the cheapest under your cw_split_cost, so the "
                                   "cost is what differs (see step4.volume_cost)")
                   : worst_pick ? ": you kept the most expensive plane, keep the smallest cost"
                   : only_x ? ": it is the cheapest plane on its own axis, not over all three: did you search one axis "
                              "only (the longest, say)? Eq. 2 takes the best plane over x, y and z"
                   : ": count each side from the bins' counts and grow each side's box from the bins' boxes");
    }
    /* the picture: the student's cost of every plane of one node, against the reference */
    if (run->img_dir) {
        double x0[3 * CW_MAX_BINS], x1[3 * CW_MAX_BINS], bar[3 * CW_MAX_BINS], line[3 * CW_MAX_BINS];
        int a, k, np = 0;
        cw_split got, best;
        double bc;
        cw_plot p;
        cw_seed(&rng, 412);
        cw_make_node(&nd, &rng, 1, 60);
        cw_node_bin(&nd, 12);
        best = cw_ref_best(heuristic, &nd, &bc);
        got = f->best_split(heuristic, &nd.parent, &nd.bins);
        for (a = 0; a < 3; ++a)
            for (k = 1; k < nd.bins.n_bins; ++k) {
                cw_aabb l, r;
                int nl, nr;
                cw_node_sides(&nd, a, k, &l, &nl, &r, &nr);
                x0[np] = np + 0.15; x1[np] = np + 0.85;
                bar[np] = (nl && nr) ? f->split_cost(heuristic, &nd.parent, &l, nl, &r, nr) : NAN;
                line[np] = (nl && nr) ? cw_ref_cost(heuristic, &nd.parent, &l, nl, &r, nr) : NAN;
                np++;
            }
        memset(&p, 0, sizeof p);
        cw_fmt(title, sizeof title, "Step 4: %s of each plane; best %c%d, yours %c%d", hname,
               "xyz"[best.axis % 3], best.plane, got.axis >= 0 && got.axis < 3 ? "xyz"[got.axis] : '?', got.plane);
        p.title = title; p.xlabel = "candidate plane: x1..x11, y1..y11, z1..z11"; p.ylabel = "cost of the split";
        p.bar_label = "your cw_split_cost"; p.line_label = heuristic == CW_SAH ? "SAH" : "eq. 1";
        p.n = np; p.x0 = x0; p.x1 = x1; p.bar = bar; p.line = line; p.xmin = 0.0; p.xmax = np; p.points = 1; p.logy = 0;
        cw_fmt(verdict, sizeof verdict, "%s %s: %s%s%s", heuristic == CW_SAH ? "step4.sah_choice" : "step4.volume_choice",
               good == sets ? "PASS" : "FAIL", m, good == sets ? "" : " -- ", good == sets ? "" : adv);
        cw_picture(run, heuristic == CW_SAH ? "step4_sah_choice" : "step4_volume_choice", &p, verdict, good == sets, png,
                   sizeof png);
    } else png[0] = '\0';
    cw_emit(run, heuristic == CW_SAH ? "step4.sah_choice" : "step4.volume_choice", good == sets, m, adv, png);
}

/* The cost cw_best_split returns with its plane: a builder compares it with the cost of a
   leaf, so it must be the heuristic's value of the plane returned, on the same scale as
   cw_split_cost, whichever plane was chosen. */
static void cw_step4_best_cost(const cw_fns *f, cw_run *run, int heuristic)
{
    static cw_node nd;
    fogrt_rng rng;
    int s, sets = 400, judged = 0, good = 0, zero = 0, unscaled = 0, no_trav = 0, own = 0, first = -1;
    double want = 0.0, gave = 0.0;
    char m[500], adv[600];
    const char *name = heuristic == CW_SAH ? "step4.sah_best_cost" : "step4.volume_best_cost";
    cw_begin(run);
    cw_seed(&rng, heuristic == CW_SAH ? 413 : 414);
    for (s = 0; s < sets; ++s) {
        int kind = s % 4, n = 2 + (int)(cw_u(&rng) * 150.0f), nl, nr;
        cw_aabb l, r;
        cw_split got;
        double ref, al, ar, ap;
        cw_make_node(&nd, &rng, kind, n);
        cw_node_bin(&nd, 12);
        got = f->best_split(heuristic, &nd.parent, &nd.bins);
        if (got.axis < 0 || got.axis > 2 || got.plane < 1 || got.plane >= nd.bins.n_bins) continue;
        cw_node_sides(&nd, got.axis, got.plane, &l, &nl, &r, &nr);
        if (!nl || !nr) continue;               /* an invalid plane is step4.*_choice's to judge */
        judged++;
        ref = cw_ref_cost(heuristic, &nd.parent, &l, nl, &r, nr);
        if (isfinite(got.cost) && fabs(got.cost - ref) <= 1e-4 * fabs(ref) + 1e-9) { good++; continue; }
        al = cw_box_area(&l); ar = cw_box_area(&r); ap = cw_box_area(&nd.parent);
        if (got.cost == 0.0f) zero++;
        if (heuristic == CW_SAH) {
            double raw = nl * al + nr * ar;
            if (fabs(got.cost - raw) <= 1e-4 * raw || fabs(got.cost - (1.0 + raw)) <= 1e-4 * (1.0 + raw)) unscaled++;
            else if (fabs(got.cost - raw / ap) <= 1e-4 * raw / ap) no_trav++;
        }
        {
            double o = f->split_cost(heuristic, &nd.parent, &l, nl, &r, nr);
            if (fabs(got.cost - o) <= 1e-5 * fabs(o) + 1e-12) own++;
        }
        if (first < 0) { first = s; want = ref; gave = got.cost; }
    }
    {
        int bad = judged - good, pass = judged > 0 && bad == 0;
        cw_fmt(m, sizeof m, "the cost returned with the plane equals the %s of that plane on %d of %d random nodes "
               "(relative tolerance 1e-4)", heuristic == CW_SAH ? "SAH" : "volume heuristic (eq. 1)", good, judged);
        if (pass) adv[0] = '\0';
        else if (judged == 0)
            cw_fmt(adv, sizeof adv, "cw_best_split returned no valid plane on any node, so its cost could not be judged: "
                   "see %s", heuristic == CW_SAH ? "step4.sah_choice" : "step4.volume_choice");
        else if (zero == bad)
            cw_fmt(adv, sizeof adv, "cw_best_split returns cost 0: the cw_split it returns carries the chosen plane's cost "
                   "(node %d: %.6g)", first, want);
        else if (unscaled > bad / 2)
            cw_fmt(adv, sizeof adv, "node %d: cw_best_split returned %.6g, the SAH of its plane is %.6g: the returned cost "
                   "lacks the division by the parent's area A (and the traversal cost 1); comparing N_l A_l + N_r A_r "
                   "picks the same plane, but the cost returned is the SAH's, 1 + (N_l A_l + N_r A_r) / A", first, gave, want);
        else if (no_trav > bad / 2)
            cw_fmt(adv, sizeof adv, "node %d: cw_best_split returned %.6g, the SAH of its plane is %.6g: the traversal cost "
                   "1 is missing from the returned cost", first, gave, want);
        else if (own > bad / 2)
            cw_fmt(adv, sizeof adv, "node %d: cw_best_split returned %.6g, the %s of its plane is %.6g; it is what your "
                   "cw_split_cost gives, so the cost formula is what differs (see %s)", first, gave,
                   heuristic == CW_SAH ? "SAH" : "volume heuristic", want,
                   heuristic == CW_SAH ? "step4.sah_cost" : "step4.volume_cost");
        else
            cw_fmt(adv, sizeof adv, "node %d: cw_best_split returned cost %.6g with its plane, whose %s is %.6g: return the "
                   "cost of the plane you return (eq. 2 keeps the minimum, and the minimum's value)", first, gave,
                   heuristic == CW_SAH ? "SAH" : "volume heuristic", want);
        cw_emit(run, name, pass, m, adv, NULL);
    }
}

/* Nodes where a careless choice goes wrong. */
static void cw_step4_edges(const cw_fns *f, cw_run *run)
{
    static cw_node nd;
    fogrt_rng rng;
    int ok = 0, total = 0, i, h;
    char m[400], adv[500] = "";
    cw_begin(run);
    cw_seed(&rng, 420);
    for (h = 0; h < 2; ++h) {
        cw_split got, best;
        double bc;
        /* flat: every volume is 0, any plane that splits is as good as any other */
        cw_make_node(&nd, &rng, 3, 40);
        cw_node_bin(&nd, 12);
        best = cw_ref_best(h, &nd, &bc);
        got = f->best_split(h, &nd.parent, &nd.bins);
        total++;
        {
            cw_aabb l, r;
            int nl = 0, nr = 0;
            if (got.plane >= 1 && got.plane < 12 && got.axis >= 0 && got.axis < 3) cw_node_sides(&nd, got.axis, got.plane, &l, &nl, &r, &nr);
            if (nl && nr && (h == CW_VOLUME || cw_ref_cost(h, &nd.parent, &l, nl, &r, nr) <= bc * (1 + 1e-5))) ok++;
            else if (!adv[0])
                cw_fmt(adv, sizeof adv, "flat node (every box has zero height, %s): you returned axis %d plane %d; %s", h ? "volume" : "SAH",
                       got.axis, got.plane, h ? "every split then costs 0 under eq. 1, so a plane with primitives on both "
                       "sides must still be returned (start from no plane, not from cost 0)" : "not the cheapest plane");
        }
        /* centroids that differ only along z: only z planes split */
        cw_make_node(&nd, &rng, 0, 30);
        for (i = 0; i < nd.n; ++i) { nd.prim[i].lo[0] = nd.prim[i].lo[1] = 0.0f; nd.prim[i].hi[0] = nd.prim[i].hi[1] = 0.1f; }
        cw_node_bin(&nd, 12);
        best = cw_ref_best(h, &nd, &bc);
        got = f->best_split(h, &nd.parent, &nd.bins);
        total++;
        if (got.axis == 2 && got.plane == best.plane) ok++;
        else if (!adv[0])
            cw_fmt(adv, sizeof adv, "primitives stacked along z only (%s): you returned axis %d plane %d, the best is z plane %d; "
                   "on x and y all centroids sit in bin 0, so no plane there splits", h ? "volume" : "SAH", got.axis, got.plane, best.plane);
        /* every centroid in one place: nothing splits */
        nd.n = 5;
        for (i = 0; i < 5; ++i) { int a; for (a = 0; a < 3; ++a) { nd.prim[i].lo[a] = 0.0f; nd.prim[i].hi[a] = 1.0f; } }
        cw_node_bin(&nd, 12);
        got = f->best_split(h, &nd.parent, &nd.bins);
        total++;
        if (got.plane == -1) ok++;
        else if (!adv[0])
            cw_fmt(adv, sizeof adv, "five identical boxes (%s): you returned axis %d plane %d, but no plane splits them: return "
                   "plane -1", h ? "volume" : "SAH", got.axis, got.plane);
        /* two primitives */
        cw_make_node(&nd, &rng, 0, 2);
        cw_node_bin(&nd, 12);
        best = cw_ref_best(h, &nd, &bc);
        got = f->best_split(h, &nd.parent, &nd.bins);
        total++;
        {
            cw_aabb l, r;
            int nl = 0, nr = 0;
            if (got.plane >= 1 && got.plane < 12 && got.axis >= 0 && got.axis < 3) cw_node_sides(&nd, got.axis, got.plane, &l, &nl, &r, &nr);
            if (nl == 1 && nr == 1 && cw_ref_cost(h, &nd.parent, &l, nl, &r, nr) <= bc * (1 + 1e-5) + 1e-12) ok++;
            else if (!adv[0])
                cw_fmt(adv, sizeof adv, "two primitives (%s): you returned axis %d plane %d (%d left, %d right); the best is axis %d "
                       "plane %d", h ? "volume" : "SAH", got.axis, got.plane, nl, nr, best.axis, best.plane);
        }
    }
    cw_fmt(m, sizeof m, "%d of %d special nodes right (flat, stacked along one axis, identical boxes, two primitives)", ok, total);
    cw_emit(run, "step4.edges", ok == total, m, adv, NULL);
}

static void cw_step4(const cw_fns *f, cw_run *run)
{
    cw_step4_cost(f, run, CW_SAH);
    cw_step4_cost(f, run, CW_VOLUME);
    cw_step4_choice(f, run, CW_SAH);
    cw_step4_choice(f, run, CW_VOLUME);
    cw_step4_best_cost(f, run, CW_SAH);
    cw_step4_best_cost(f, run, CW_VOLUME);
    cw_step4_edges(f, run);
}

/* ==========================================================================================
   Step 5: BSDF sampling
   ========================================================================================== */
/* Schlick with the cosine on the thinner side, written from the formula (the reference). */
static double cw_schlick_ref(double eta, double cos_i)
{
    double r0 = (eta - 1.0) / (eta + 1.0), c;
    r0 *= r0;
    if (cos_i < 0.0) {               /* leaving: the transmitted angle is outside */
        double sin2_t = (1.0 - cos_i * cos_i) * eta * eta;
        if (sin2_t >= 1.0) return 1.0;
        c = sqrt(1.0 - sin2_t);
    } else c = cos_i;
    return r0 + (1.0 - r0) * pow(1.0 - c, 5.0);
}
typedef struct cw__dpdf { const cw_fns *f; fogrt_vec3 wo; } cw__dpdf;
static double cw__diffuse_pdf_dir(const double w[3], void *user)
{
    const cw__dpdf *d = (const cw__dpdf *)user;
    fogrt_vec3 wi;
    float v;
    wi.x = (float)w[0]; wi.y = (float)w[1]; wi.z = (float)w[2];
    v = d->f->diffuse_pdf(d->wo, wi);
    return isfinite(v) ? v : 0.0;
}
/* Exact probability of a (cos, phi) cell of the world grid under cosine sampling on the
   side of sign s. */
static double cw_cos_cell(double c0, double c1, double dphi, double s)
{
    double a = s > 0 ? fmax(c0, 0.0) : fmax(-c1, 0.0), b = s > 0 ? fmax(c1, 0.0) : fmax(-c0, 0.0);
    return (b * b - a * a) * dphi / (2.0 * CW_PI);
}

static void cw_step5_diffuse(const cw_fns *f, cw_run *run)
{
    static const double wos[2][3] = {{0.3, 0.2, 0.9}, {-0.5, 0.1, -0.6}};
    static stats_sphere_grid grid;
    static double obs[20 * 16], expd[20 * 16];
    static float sw[CW_N], sp[CW_N], sx[CW_N], sy[CW_N], sz[CW_N];
    char name[64], m[600], adv[600], png[256], stem[64], title[160], verdict[1400];
    int k, i, j, nc = 20, np = 16;
    for (k = 0; k < 2; ++k) {
        fogrt_vec3 wo = cw_v3(wos[k][0], wos[k][1], wos[k][2]);
        double side = wo.z > 0 ? 1.0 : -1.0, cos_sum = 0.0, other = 0.0;
        long invalid = 0, none = 0, valid = 0;
        fogrt_rng rng;
        cw_fit fit;
        int pass;
        cw_begin(run);
        stats_grid_init(&grid, nc, np);
        memset(obs, 0, sizeof obs);
        cw_seed(&rng, 500 + k);
        for (i = 0; i < CW_N; ++i) {
            cw_bsdf_sample s;
            int cell;
            memset(&s, 0, sizeof s);
            sw[i] = NAN;
            if (!f->sample_diffuse(wo, cw_u(&rng), cw_u(&rng), &s)) { none++; continue; }
            cell = cw_finite3(s.wi) ? stats_grid_cell(&grid, s.wi.x, s.wi.y, s.wi.z) : -1;
            if (cell < 0) { invalid++; continue; }
            obs[cell] += 1.0;
            cos_sum += fabs(s.wi.z);
            if (s.wi.z * side < 0) other += 1.0;
            sw[valid] = s.weight; sp[valid] = s.pdf; sx[valid] = s.wi.x; sy[valid] = s.wi.y; sz[valid] = s.wi.z;
            valid++;
        }
        for (i = 0; i < nc; ++i)
            for (j = 0; j < np; ++j)
                expd[i * np + j] = CW_N * cw_cos_cell(grid.cos_edge[i], grid.cos_edge[i + 1], 2.0 * CW_PI / np, side);
        fit = cw_hist_fit(obs, expd, nc * np);
        /* "no sample" is allowed where u lands exactly on the horizon (u = 0 in a sqrt(u)
           mapping): a few in 200000 at most */
        pass = invalid == 0 && none <= 5 && fit.p >= CW_ALPHA;
        {
            double mc = valid ? cos_sum / valid : NAN;
            cw_fmt(m, sizeof m, "chi2 = %.1f, dof %d, p = %.3g (fail if p < %g) on %d x %d cells (cos theta, phi); mean |cos| "
                   "= %.4f (cosine-weighted: 2/3)", fit.chi2, fit.dof, fit.p, CW_ALPHA, nc, np, mc);
            if (none > 5) cw_fmt(adv, sizeof adv, "no sample returned %ld times: only directions exactly on the horizon may be "
                                 "refused", none);
            else if (invalid) cw_fmt(adv, sizeof adv, "%ld directions were not finite or not unit length", invalid);
            else if (other > 0.5 * valid)
                cw_fmt(adv, sizeof adv, "%.0f%% of the directions went to the other side of the surface than wo (wo.z = %.2f): "
                       "a diffuse surface reflects on wo's side, flip wi.z when wo.z < 0", 100.0 * other / valid, wo.z);
            else if (fabs(mc - 0.5) < 0.01)
                cw_fmt(adv, sizeof adv, "too few samples near the normal (mean |cos| %.3f; cosine-weighted gives 2/3, uniform "
                       "1/2): this looks like uniform hemisphere sampling; take r = sqrt(u1), or z = sqrt(1 - u1)", mc);
            else
                cw_fmt(adv, sizeof adv, "the directions are not cosine-distributed around the normal (pdf cos(theta)/pi)");
        }
        cw_fmt(title, sizeof title, "Step 5: diffuse samples, wo.z = %.2f: cos theta", wo.z);
        cw_fmt(stem, sizeof stem, "step5_diffuse_chi2_%s", side > 0 ? "above" : "below");
        cw_fmt(name, sizeof name, "step5.diffuse_chi2 wo.z=%.2f", wo.z);
        cw_fmt(verdict, sizeof verdict, "%s %s: %s%s%s", name, pass ? "PASS" : "FAIL", m, pass ? "" : " -- ", pass ? "" : adv);
        cw_picture_sphere(run, stem, &grid, obs, expd, title, "cos theta = wi.z", "cosine-weighted", 0,
                          "... and azimuth phi around the normal", "uniform", verdict, pass, png, sizeof png);
        cw_emit(run, name, pass, m, adv, png);

        /* the student's pdf against the student's samples, and its integral */
        cw_begin(run);
        {
            cw__dpdf dp;
            double total, z;
            int w;
            dp.f = f; dp.wo = wo;
            total = stats_grid_expected_from_pdf(&grid, cw__diffuse_pdf_dir, &dp, (double)CW_N, expd);
            fit = cw_hist_fit(obs, expd, nc * np);
            pass = invalid == 0 && none <= 5 && fit.p >= CW_ALPHA && fabs(total - 1.0) <= 2e-3;
            w = cw_worst_bin(obs, expd, nc * np, &z);
            cw_fmt(m, sizeof m, "chi2 = %.1f, dof %d, p = %.3g (fail if p < %g); integral of your pdf over the sphere %.5f "
                   "(expected 1 +- 0.002)", fit.chi2, fit.dof, fit.p, CW_ALPHA, total);
            if (invalid || none > 5) cw_fmt(adv, sizeof adv, "the sampler failed (see step5.diffuse_chi2)");
            else if (fabs(total - 2.0) < 0.01)
                cw_fmt(adv, sizeof adv, "your pdf integrates to 2 over the sphere: it is nonzero on both sides; it must be "
                       "zero on the side opposite wo");
            else if (fabs(total - CW_PI) < 0.01)
                cw_fmt(adv, sizeof adv, "your pdf integrates to pi: cos(theta)/pi, not cos(theta)");
            else if (fabs(total - 1.0) > 2e-3)
                cw_fmt(adv, sizeof adv, "your pdf integrates to %.4f over the sphere, not 1: per steradian it is |cos theta|/pi "
                       "on wo's side, 0 on the other", total);
            else
                cw_fmt(adv, sizeof adv, "your pdf and your sampler disagree most at cos theta in [%.2f, %.2f): %.0f samples, your "
                       "pdf predicts %.0f", grid.cos_edge[w / np], grid.cos_edge[w / np + 1], obs[w], expd[w]);
            cw_fmt(title, sizeof title, "Step 5: your pdf against your samples, wo.z = %.2f", wo.z);
            cw_fmt(stem, sizeof stem, "step5_diffuse_pdf_%s", side > 0 ? "above" : "below");
            cw_fmt(name, sizeof name, "step5.diffuse_pdf wo.z=%.2f", wo.z);
            cw_fmt(verdict, sizeof verdict, "%s %s: %s%s%s", name, pass ? "PASS" : "FAIL", m, pass ? "" : " -- ", pass ? "" : adv);
            cw_picture_sphere(run, stem, &grid, obs, expd, title, "cos theta = wi.z", "your cw_diffuse_pdf", 0,
                              "... and azimuth phi around the normal", "your cw_diffuse_pdf", verdict, pass, png, sizeof png);
            cw_emit(run, name, pass, m, adv, png);
        }

        /* each sample's weight and pdf */
        cw_begin(run);
        {
            double wsum = 0.0, werr = 0.0, fcos = 0.0, fonly = 0.0;
            long nw = 0, bad_w = 0, bad_p = 0;
            for (i = 0; i < valid; ++i) {
                fogrt_vec3 wi;
                double c = fabs(sz[i]), pdf_ref = c / CW_PI, mine;
                wi.x = sx[i]; wi.y = sy[i]; wi.z = sz[i];
                mine = f->diffuse_pdf(wo, wi);
                if (!(fabs(sw[i] - 1.0) <= 1e-4)) { bad_w++; werr = fmax(werr, fabs(sw[i] - 1.0)); }
                if (!(fabs(sp[i] - pdf_ref) <= 1e-4 * pdf_ref + 1e-6) || !(fabs(mine - pdf_ref) <= 1e-4 * pdf_ref + 1e-6)) bad_p++;
                wsum += sw[i]; nw++;
                if (fabs(sw[i] - c / CW_PI) <= 1e-4) fcos += 1.0;
                if (fabs(sw[i] - 1.0 / CW_PI / (pdf_ref > 0 ? pdf_ref : 1)) <= 1e-3 * sw[i]) fonly += 1.0;
            }
            pass = nw > 0 && bad_w == 0 && bad_p == 0;
            cw_fmt(m, sizeof m, "mean weight %.5f (f |cos| / pdf = 1 for a white diffuse surface), %ld weights off by more than "
                   "1e-4 (largest error %.3g), %ld pdfs off cos/pi by more than 1e-4", nw ? wsum / nw : NAN, bad_w, werr, bad_p);
            if (nw == 0) cw_fmt(adv, sizeof adv, "no valid samples to weigh");
            else if (fcos > 0.9 * nw)
                cw_fmt(adv, sizeof adv, "your weight is f |cos| = |cos|/pi: did you forget to divide by the pdf? With cosine-"
                       "weighted sampling f |cos| / pdf = 1 for a white surface");
            else if (fonly > 0.9 * nw)
                cw_fmt(adv, sizeof adv, "your weight is f / pdf: the cosine of eq. 3 is missing (f |cos| / pdf)");
            else if (bad_p)
                cw_fmt(adv, sizeof adv, "the pdf stored in the sample (or cw_diffuse_pdf) is not |cos theta|/pi at the sampled "
                       "direction");
            else cw_fmt(adv, sizeof adv, "the weight is f |cos| / pdf (eq. 3); with f = 1/pi and pdf = |cos|/pi it is exactly 1");
            cw_fmt(name, sizeof name, "step5.diffuse_weight wo.z=%.2f", wo.z);
            cw_emit(run, name, pass, m, adv, NULL);
        }
    }
}

static void cw_step5_specular(const cw_fns *f, cw_run *run)
{
    fogrt_rng rng;
    char m[600], adv[600] = "", png[256], verdict[1400];
    int i, k;
    /* mirror */
    cw_begin(run);
    {
        int ok = 0, n = 2000, back = 0, through = 0;
        cw_seed(&rng, 510);
        for (i = 0; i < n; ++i) {
            double z = cw_rand_range(&rng, -1.0, 1.0);
            fogrt_vec3 wo = cw_v3(cw_rand_range(&rng, -1, 1), cw_rand_range(&rng, -1, 1), fabs(z) < 0.01 ? 0.5 : z);
            cw_bsdf_sample s;
            memset(&s, 0, sizeof s);
            if (f->sample_mirror(wo, &s) && fabs(s.wi.x + wo.x) < 1e-5 && fabs(s.wi.y + wo.y) < 1e-5 && fabs(s.wi.z - wo.z) < 1e-5
                && fabs(s.weight - 1.0f) < 1e-5f && fabs(s.pdf - 1.0f) < 1e-5f) ok++;
            else {
                if (fabs(s.wi.x + wo.x) < 1e-5 && fabs(s.wi.y + wo.y) < 1e-5 && fabs(s.wi.z + wo.z) < 1e-5) back++;
                if (fabs(s.wi.x - wo.x) < 1e-5 && fabs(s.wi.y - wo.y) < 1e-5 && fabs(s.wi.z + wo.z) < 1e-5) through++;
                if (!adv[0])
                    cw_fmt(adv, sizeof adv, "wo = (%.3f, %.3f, %.3f) gave wi = (%.3f, %.3f, %.3f), pdf %g, weight %g; the mirror "
                           "direction is (-wo.x, -wo.y, wo.z) with pdf 1 (the lobe is always chosen) and weight 1",
                           wo.x, wo.y, wo.z, s.wi.x, s.wi.y, s.wi.z, s.pdf, s.weight);
            }
        }
        if (back > n / 2) cw_fmt(adv, sizeof adv, "wi = -wo sends the light back where it came from; a mirror reflects about the "
                                 "normal: wi = (-wo.x, -wo.y, wo.z)");
        else if (through > n / 2) cw_fmt(adv, sizeof adv, "wi = (wo.x, wo.y, -wo.z) goes through the surface; reflection stays on "
                                         "wo's side: wi = (-wo.x, -wo.y, wo.z)");
        cw_fmt(m, sizeof m, "%d of %d random wo (both sides) reflected exactly, pdf 1, weight 1 (tolerance 1e-5)", ok, n);
        cw_emit(run, "step5.mirror", ok == n, m, adv, NULL);
    }
    /* Schlick */
    cw_begin(run);
    adv[0] = '\0';
    {
        static const float etas[3] = {1.5f, 1.33f, 2.4f};
        double worst = 0.0, wc = 0.0, we = 0.0, wv = 0.0;
        int inside_icos = 0, inside_n = 0, r0_bad = 0;
        for (k = 0; k < 3; ++k)
            for (i = 0; i <= 200; ++i) {
                double c = -1.0 + 2.0 * i / 200.0, ref, v, err;
                if (i == 100) continue;
                ref = cw_schlick_ref(etas[k], (float)c);
                v = f->fresnel_schlick(etas[k], (float)c);
                err = fabs(v - ref);
                if (!(err <= worst)) { worst = err; wc = c; we = etas[k]; wv = v; }
                if (c < 0.0) {
                    double r0 = ((etas[k] - 1.0) / (etas[k] + 1.0)), alt;
                    r0 *= r0;
                    alt = r0 + (1.0 - r0) * pow(1.0 - fabs(c), 5.0);
                    inside_n++;
                    if (fabs(v - alt) <= 1e-4) inside_icos++;
                }
                if (i == 200 && fabs(v - ref) > 1e-4) r0_bad = 1;
            }
        cw_fmt(m, sizeof m, "largest |F - Schlick| = %.3g at eta = %g, cos_i = %g (you: %.6f, Schlick: %.6f; tolerance 1e-4)",
               worst, we, wc, wv, cw_schlick_ref(we, wc));
        if (inside_icos > inside_n * 9 / 10)
            cw_fmt(adv, sizeof adv, "from inside the glass (cos_i < 0) you used the incident cosine: Schlick needs the cosine on "
                   "the thinner (outside) side, the transmitted cos_t = sqrt(1 - eta^2 (1 - cos_i^2)), and F = 1 past the "
                   "critical angle");
        else if (r0_bad)
            cw_fmt(adv, sizeof adv, "at normal incidence F must be R0 = ((eta - 1)/(eta + 1))^2 = %.5f for eta = 1.5", 0.04);
        else if (wc < 0.0)
            cw_fmt(adv, sizeof adv, "wrong from inside (cos_i < 0): use |cos_t| on the outside; total internal reflection gives 1");
        else
            cw_fmt(adv, sizeof adv, "Schlick: F = R0 + (1 - R0)(1 - cos)^5 with R0 = ((eta - 1)/(eta + 1))^2");
        cw_emit(run, "step5.schlick", worst <= 1e-4, m, adv, NULL);
    }
    /* glass: how often it reflects, against Schlick (binomial, Bonferroni over 7 angles; at
       cos_i = -0.5 light inside the glass is past the critical angle and must always reflect) */
    cw_begin(run);
    {
        static const float cs[7] = {0.95f, 0.5f, 0.1f, -0.95f, -0.8f, -0.76f, -0.5f};
        double x0[7], x1[7], bar[7], line[7], worst_p = 1.0, wf = 0, wF = 0, wc = 0;
        int n = 20000, flipped = 0, bad_dir = 0;
        cw_plot p;
        for (k = 0; k < 7; ++k) {
            fogrt_vec3 wo = cw_v3(sqrt(1.0 - (double)cs[k] * cs[k]), 0.0, cs[k]);
            double F = cw_schlick_ref(1.5, wo.z), pv;
            long refl = 0;
            cw_seed(&rng, 520 + k);
            for (i = 0; i < n; ++i) {
                cw_bsdf_sample s;
                memset(&s, 0, sizeof s);
                if (!f->sample_glass(1.5f, wo, cw_u(&rng), &s) || !cw_finite3(s.wi)) { bad_dir++; continue; }
                if (s.wi.z * wo.z > 0.0f) refl++;
            }
            {
                stats_binomial_result b = stats_binomial(refl, n, F);
                pv = fmin(1.0, b.p_value * 7.0);
                if (fabs(b.frequency - (1.0 - F)) < 0.01 && fabs(F - 0.5) > 0.05) flipped++;
                x0[k] = cs[k] - 0.03; x1[k] = cs[k] + 0.03; bar[k] = b.frequency; line[k] = F;
                if (pv < worst_p || k == 0) { worst_p = pv; wf = b.frequency; wF = F; wc = cs[k]; }
            }
        }
        {
            int pass = worst_p >= CW_ALPHA && bad_dir == 0;
            cw_fmt(m, sizeof m, "worst angle cos_i = %g: reflected %.4f of %d, Schlick F = %.4f, p = %.3g (binomial, Bonferroni "
                   "over 7 angles; fail if p < %g)", wc, wf, n, wF, worst_p, CW_ALPHA);
            if (bad_dir) cw_fmt(adv, sizeof adv, "%d samples returned no direction or a non-finite one", bad_dir);
            else if (flipped >= 4)
                cw_fmt(adv, sizeof adv, "you reflect with probability 1 - F: reflect when u_lobe < F, refract otherwise");
            else
                cw_fmt(adv, sizeof adv, "at cos_i = %g you reflect %.3f of the time, Schlick says %.3f: choose reflection with "
                       "probability F of your cw_fresnel_schlick (1 on total internal reflection)", wc, wf, wF);
            memset(&p, 0, sizeof p);
            p.title = "Step 5: how often glass (eta 1.5) reflects";
            p.xlabel = "cos_i = wo.z (< 0: from inside)"; p.ylabel = "fraction reflected"; p.bar_label = "your glass";
            p.line_label = "Schlick's F"; p.n = 7; p.x0 = x0; p.x1 = x1; p.bar = bar; p.line = line; p.xmin = -1.0; p.xmax = 1.0;
            p.points = 1;
            {
                static double cx[401], cy[401];
                for (i = 0; i < 401; ++i) { cx[i] = -1.0 + 2.0 * i / 400.0; cy[i] = cw_schlick_ref(1.5, cx[i]); }
                p.cn = 401; p.cx = cx; p.cy = cy;
            }
            {
                /* the six in order of cos */
                int a, b;
                for (a = 0; a < 7; ++a)
                    for (b = a + 1; b < 7; ++b)
                        if (x0[b] < x0[a]) {
                            double t;
                            t = x0[a]; x0[a] = x0[b]; x0[b] = t; t = x1[a]; x1[a] = x1[b]; x1[b] = t;
                            t = bar[a]; bar[a] = bar[b]; bar[b] = t; t = line[a]; line[a] = line[b]; line[b] = t;
                        }
            }
            cw_fmt(verdict, sizeof verdict, "step5.glass_choice %s: %s%s%s", pass ? "PASS" : "FAIL", m, pass ? "" : " -- ", pass ? "" : adv);
            cw_picture(run, "step5_glass_choice", &p, verdict, pass, png, sizeof png);
            cw_emit(run, "step5.glass_choice", pass, m, adv, png);
        }
    }
    /* glass: directions, pdf, weight */
    cw_begin(run);
    adv[0] = '\0';
    {
        int n = 3000, ok = 0;
        cw_seed(&rng, 530);
        for (i = 0; i < n; ++i) {
            double z = cw_rand_range(&rng, -1.0, 1.0), ph = cw_rand_range(&rng, 0.0, 2.0 * CW_PI), sz = sqrt(1.0 - z * z);
            fogrt_vec3 wo = cw_v3(sz * cos(ph), sz * sin(ph), fabs(z) < 0.02 ? 0.3 : z);
            float u = i % 50 == 0 ? CW_U_MAX : (i % 50 == 1 ? 0.0f : cw_u(&rng));
            /* pdf tolerances below: 1e-3 relative plus 2e-4, because near the critical angle
               F depends on cos_i through the square root of a small difference, and a correct
               float Schlick is off by up to ~1e-4 there */
            double F = cw_schlick_ref(1.5, wo.z);
            cw_bsdf_sample s;
            int good = 1;
            char why[400] = "";
            memset(&s, 0, sizeof s);
            if (!f->sample_glass(1.5f, wo, u, &s) || !cw_finite3(s.wi) || fabs(cw_len3(s.wi) - 1.0) > 1e-4) {
                good = 0;
                cw_fmt(why, sizeof why, "no direction or not a unit vector: wo = (%.3f, %.3f, %.3f) gave (%g, %g, %g)", wo.x, wo.y,
                       wo.z, s.wi.x, s.wi.y, s.wi.z);
            } else if (s.wi.z * wo.z > 0.0f) {      /* reflected */
                if (fabs(s.wi.x + wo.x) > 1e-4 || fabs(s.wi.y + wo.y) > 1e-4 || fabs(s.wi.z - wo.z) > 1e-4) {
                    good = 0;
                    cw_fmt(why, sizeof why, "reflection of wo = (%.3f, %.3f, %.3f) went to (%.3f, %.3f, %.3f), not (-wo.x, -wo.y, wo.z)",
                           wo.x, wo.y, wo.z, s.wi.x, s.wi.y, s.wi.z);
                } else if (fabs(s.pdf - F) > 1e-3 * F + 2e-4 || fabs(s.weight - 1.0f) > 1e-3f) {
                    good = 0;
                    cw_fmt(why, sizeof why, "a reflection at cos_i = %.3f has pdf %g and weight %g; expected pdf F = %.5f and "
                           "weight F / F = 1%s", wo.z, s.pdf, s.weight, F,
                           fabs(s.weight - F) < 1e-3 ? " (your weight is F: divide by the pdf F)" : "");
                }
            } else {                                 /* refracted */
                double eta = wo.z > 0 ? 1.5 : 1.0 / 1.5;   /* n_t / n_i */
                double si = sqrt(fmax(0.0, 1.0 - (double)wo.z * wo.z)), st = sqrt(fmax(0.0, 1.0 - (double)s.wi.z * s.wi.z));
                double dot_t = s.wi.x * (double)wo.x + s.wi.y * (double)wo.y;
                if (F >= 1.0) {
                    good = 0;
                    cw_fmt(why, sizeof why, "refracted at cos_i = %.3f from inside, beyond the critical angle: total internal "
                           "reflection must always reflect", wo.z);
                } else if (fabs(st * eta - si) > 2e-3 || (si > 1e-3 && dot_t > 0.0)) {
                    good = 0;
                    cw_fmt(why, sizeof why, "refraction of wo = (%.3f, %.3f, %.3f) gave wi = (%.3f, %.3f, %.3f): sin_t = %.4f but "
                           "Snell gives %.4f%s", wo.x, wo.y, wo.z, s.wi.x, s.wi.y, s.wi.z, st, si / eta,
                           fabs(st - si * eta) >= 2e-3 ? ""
                           : wo.z < 0 ? " (you used the ratio of entering the glass: leaving it (wo.z < 0) the ratio is "
                                        "inverted, sin_t = eta sin_i with eta = 1.5 here)"
                                      : " (you used the ratio of leaving the glass: entering it (wo.z > 0) sin_t = "
                                        "sin_i / eta with eta = 1.5 here)");
                } else if (fabs(s.pdf - (1.0 - F)) > 1e-3 * (1.0 - F) + 2e-4 || fabs(s.weight - 1.0f) > 1e-3f) {
                    good = 0;
                    cw_fmt(why, sizeof why, "a refraction at cos_i = %.3f has pdf %g and weight %g; expected pdf 1 - F = %.5f and "
                           "weight 1", wo.z, s.pdf, s.weight, 1.0 - F);
                }
            }
            if (good) ok++;
            else if (!adv[0]) cw_fmt(adv, sizeof adv, "%s", why);
        }
        cw_fmt(m, sizeof m, "%d of %d glass samples right: mirror or Snell direction, pdf F or 1 - F, weight 1 (both sides, "
               "u_lobe 0 and 1 - 2^-24 included)", ok, n);
        cw_emit(run, "step5.glass_dirs", ok == n, m, adv, NULL);
    }
    /* edges */
    cw_begin(run);
    adv[0] = '\0';
    {
        fogrt_vec3 wos[4];
        float us[2] = {0.0f, CW_U_MAX};
        int ok = 0, total = 0, a, b;
        wos[0] = cw_v3(0, 0, 1); wos[1] = cw_v3(1, 0, 1e-6); wos[2] = cw_v3(0, 0, -1); wos[3] = cw_v3(0.6, 0.8, -1e-6);
        for (a = 0; a < 4; ++a)
            for (b = 0; b < 2; ++b) {
                cw_bsdf_sample s;
                memset(&s, 0, sizeof s);
                total++;
                /* refusing (0) is fine here: these u may put wi on the horizon */
                if (!f->sample_diffuse(wos[a], us[b], us[1 - b], &s)
                    || (cw_finite3(s.wi) && fabs(cw_len3(s.wi) - 1.0) < 1e-4 && isfinite(s.pdf) && isfinite(s.weight)
                        && s.pdf >= 0.0f && s.wi.z * wos[a].z >= 0.0f
                        && fabs(s.pdf - fabs(s.wi.z) / CW_PI) <= 1e-3 * fabs(s.wi.z) / CW_PI + 1e-6
                        && (s.pdf == 0.0f || fabs(s.weight - 1.0f) <= 1e-3f))) ok++;
                else if (!adv[0])
                    cw_fmt(adv, sizeof adv, "diffuse at wo = (%g, %g, %g), u = %g, %g gave wi = (%g, %g, %g), pdf %g, weight %g",
                           wos[a].x, wos[a].y, wos[a].z, us[b], us[1 - b], s.wi.x, s.wi.y, s.wi.z, s.pdf, s.weight);
                memset(&s, 0, sizeof s);
                total++;
                /* a unit wi that is the mirror direction or crosses the surface */
                if (f->sample_glass(1.5f, wos[a], us[b], &s) && cw_finite3(s.wi) && fabs(cw_len3(s.wi) - 1.0) < 1e-4
                    && isfinite(s.pdf) && isfinite(s.weight) && s.pdf > 0.0f
                    && ((fabs(s.wi.x + wos[a].x) < 1e-4 && fabs(s.wi.y + wos[a].y) < 1e-4 && fabs(s.wi.z - wos[a].z) < 1e-4)
                        || s.wi.z * wos[a].z < 0.0f)) ok++;
                else if (!adv[0])
                    cw_fmt(adv, sizeof adv, "glass at wo = (%g, %g, %g), u_lobe = %g gave wi = (%g, %g, %g), pdf %g, weight %g",
                           wos[a].x, wos[a].y, wos[a].z, us[b], s.wi.x, s.wi.y, s.wi.z, s.pdf, s.weight);
            }
        cw_fmt(m, sizeof m, "%d of %d edge cases finite and consistent (diffuse: wo's side, pdf |cos|/pi, weight 1; glass: "
               "the mirror direction or through the surface) at normal incidence, grazing wo on both sides, u = 0 and "
               "1 - 2^-24", ok, total);
        cw_emit(run, "step5.edges", ok == total, m, adv, NULL);
    }
}

static void cw_step5(const cw_fns *f, cw_run *run)
{
    cw_step5_diffuse(f, run);
    cw_step5_specular(f, run);
}

/* ==========================================================================================
   Step 9: equiangular sampling
   ========================================================================================== */
typedef struct cw__eq { double delta, h, a, b; const cw_fns *f; } cw__eq;
static double cw__eq_theta(const cw__eq *e, double t) { return atan2(t - e->delta, e->h); }
static double cw__eq_cdf(double t, const void *user)
{
    const cw__eq *e = (const cw__eq *)user;
    double ta = cw__eq_theta(e, e->a), tb = isinf(e->b) ? 0.5 * CW_PI : cw__eq_theta(e, e->b);
    if (t <= e->a) return 0.0;
    if (t >= e->b) return 1.0;
    return (cw__eq_theta(e, t) - ta) / (tb - ta);
}
static double cw__eq_quantile(const cw__eq *e, double q)
{
    double ta = cw__eq_theta(e, e->a), tb = isinf(e->b) ? 0.5 * CW_PI : cw__eq_theta(e, e->b);
    return e->delta + e->h * tan(ta + q * (tb - ta));
}
static double cw__eq_density(const cw__eq *e, double t)
{
    double ta = cw__eq_theta(e, e->a), tb = isinf(e->b) ? 0.5 * CW_PI : cw__eq_theta(e, e->b);
    if (t < e->a || t > e->b) return 0.0;
    return e->h / ((tb - ta) * (e->h * e->h + (t - e->delta) * (t - e->delta)));
}
static double cw__eq_student_pdf(double t, const void *user)
{
    const cw__eq *e = (const cw__eq *)user;
    return e->f->equiangular_pdf((float)e->delta, (float)e->h, (float)e->a, (float)e->b, (float)t);
}

static void cw_step9(const cw_fns *f, cw_run *run)
{
    static const double cases[4][4] = {{0.0, 1.0, -5.0, 5.0}, {2.0, 0.2, 0.0, HUGE_VAL}, {-1.0, 0.5, 0.0, 3.0}, {10.0, 0.05, 0.0, 4.0}};
    char name[64], m[600], adv[600], png[256], stem[64], title[160], verdict[1400];
    int k, i;
    double pdf_worst = 0.0;
    char pdf_adv[600] = "";
    int pdf_checked = 0;
    for (k = 0; k < 4; ++k) {
        cw__eq e;
        cw_hist h;
        cw_fit fit;
        fogrt_rng rng;
        int nb = 40, pass, no_delta = 0;
        double x0[CW_HMAX], x1[CW_HMAX], bar[CW_HMAX], line[CW_HMAX], mean, tmax;
        cw_plot p;
        e.delta = cases[k][0]; e.h = cases[k][1]; e.a = cases[k][2]; e.b = cases[k][3]; e.f = f;
        cw_begin(run);
        cw_hist_init(&h, nb);
        h.edge[0] = e.a; h.edge[nb] = e.b;
        for (i = 1; i < nb; ++i) h.edge[i] = cw__eq_quantile(&e, (double)i / nb);
        cw_seed(&rng, 900 + k);
        for (i = 0; i < CW_N; ++i) {
            float u = cw_u(&rng), pdf = -1.0f;
            float t = f->sample_equiangular((float)e.delta, (float)e.h, (float)e.a, (float)e.b, u, &pdf);
            cw_hist_add(&h, t, u, 1e-4 * (1.0 + fabs(e.a)));
            if (i < 4000 && isfinite(t) && t >= e.a && t <= e.b) {
                double ref = cw__eq_density(&e, t), mine = f->equiangular_pdf((float)e.delta, (float)e.h, (float)e.a, (float)e.b, t);
                double err = fmax(fabs(pdf - ref), fabs(mine - ref)) / (1e-3 * ref + 1e-9);
                pdf_checked++;
                if (err > pdf_worst) {
                    pdf_worst = err;
                    if (err > 1.0)
                        cw_fmt(pdf_adv, sizeof pdf_adv, "at delta = %g, h = %g, [a, b] = [%g, %g], t = %.5g: the sampler's pdf %.6g, "
                               "cw_equiangular_pdf %.6g, the density is %.6g%s", e.delta, e.h, e.a, e.b, t, pdf, mine, ref,
                               fabs(mine - ref / e.h) < 1e-3 * ref / e.h ? ": the factor h in the numerator is missing, "
                               "p(t) = h / ((theta_b - theta_a)(h^2 + (t - delta)^2))" : "");
                }
            }
        }
        cw_hist_expect(&h, cw__eq_cdf, &e);
        fit = cw_hist_fit(h.obs, h.expd, nb);
        pass = h.invalid == 0 && fit.p >= CW_ALPHA;
        mean = h.n > h.invalid ? h.sum / (double)(h.n - h.invalid) : NAN;
        {
            /* did the sampler forget delta? compare with the same distribution centred on 0 */
            cw__eq z = e;
            cw_hist hz = h;
            cw_fit fz;
            z.delta = 0.0;
            cw_hist_expect(&hz, cw__eq_cdf, &z);
            fz = cw_hist_fit(hz.obs, hz.expd, nb);
            if (e.delta != 0.0 && fz.p > 1e-3) no_delta = 1;
        }
        cw_fmt(m, sizeof m, "chi2 = %.1f, dof %d, p = %.3g (fail if p < %g); delta %g, h %g, [a, b] = [%g, %g]",
               fit.chi2, fit.dof, fit.p, CW_ALPHA, e.delta, e.h, e.a, e.b);
        if (h.invalid)
            cw_fmt(adv, sizeof adv, "%ld samples were NaN, infinite or outside [a, b] (first: t = %g at u = %.9g)", h.invalid,
                   h.first_invalid, h.first_invalid_u);
        else if (no_delta)
            cw_fmt(adv, sizeof adv, "your samples crowd around t = 0 instead of the light's closest approach t = delta = %g: the "
                   "angles are measured from delta, theta(t) = atan((t - delta)/h), t = delta + h tan(theta)", e.delta);
        else
            cw_fmt(adv, sizeof adv, "mean t %.4g; the samples do not follow 1/(h^2 + (t - delta)^2): t = delta + h tan(theta_a "
                   "+ u (theta_b - theta_a))", mean);
        tmax = isinf(e.b) ? h.edge[nb - 1] : e.b;
        cw_hist_density(&h, tmax, x0, x1, bar, line);
        memset(&p, 0, sizeof p);
        cw_fmt(title, sizeof title, "Step 9: equiangular t, delta = %g, h = %g, [%g, %g]", e.delta, e.h, e.a, e.b);
        p.title = title; p.xlabel = "distance t along the ray"; p.ylabel = "density"; p.bar_label = "your samples";
        p.line_label = "h / ((theta_b - theta_a)(h^2 + (t - delta)^2))"; p.n = isinf(e.b) ? nb - 1 : nb; p.x0 = x0; p.x1 = x1;
        p.bar = bar; p.line = line; p.xmin = e.a; p.xmax = tmax; p.logy = -1;
        cw_fmt(stem, sizeof stem, "step9_chi2_case%d", k + 1);
        cw_fmt(name, sizeof name, "step9.chi2 case %d", k + 1);
        cw_fmt(verdict, sizeof verdict, "%s %s: %s%s%s", name, pass ? "PASS" : "FAIL", m, pass ? "" : " -- ", pass ? "" : adv);
        cw_picture(run, stem, &p, verdict, pass, png, sizeof png);
        cw_emit(run, name, pass, m, adv, png);

        /* the student's pdf integrated over the same bins against the student's samples
           (split at delta, where a narrow peak sits) */
        cw_begin(run);
        {
            double total = 0.0, z;
            int w;
            for (i = 0; i < nb; ++i) {
                double lo = h.edge[i], hi = isinf(h.edge[i + 1]) ? e.delta + 1e5 * e.h + fabs(lo) : h.edge[i + 1];
                h.expd[i] = (double)h.n * ((e.delta > lo && e.delta < hi)
                                           ? cw_integrate(cw__eq_student_pdf, &e, lo, e.delta) + cw_integrate(cw__eq_student_pdf, &e, e.delta, hi)
                                           : cw_integrate(cw__eq_student_pdf, &e, lo, hi));
                total += h.expd[i];
            }
            fit = cw_hist_fit(h.obs, h.expd, nb);
            pass = h.invalid == 0 && fit.p >= CW_ALPHA;
            w = cw_worst_bin(h.obs, h.expd, nb, &z);
            cw_fmt(m, sizeof m, "chi2 = %.1f, dof %d, p = %.3g (fail if p < %g); your pdf's mass over [a, b] %.4g",
                   fit.chi2, fit.dof, fit.p, CW_ALPHA, total / (double)h.n);
            if (h.invalid) cw_fmt(adv, sizeof adv, "the sampler gave invalid t (see step9.chi2 case %d)", k + 1);
            else if (fabs(total / (double)h.n - 1.0) > 0.01)
                cw_fmt(adv, sizeof adv, "your pdf integrates to %.4g over [a, b], not 1 (see step9.pdf_integral)", total / (double)h.n);
            else
                cw_fmt(adv, sizeof adv, "your pdf and your sampler disagree most for t in [%.4g, %.4g): %.0f samples, your pdf "
                       "predicts %.0f", h.edge[w], h.edge[w + 1], h.obs[w], h.expd[w]);
            cw_hist_density(&h, tmax, x0, x1, bar, line);
            cw_fmt(title, sizeof title, "Step 9: your pdf against your samples, delta = %g, h = %g", e.delta, e.h);
            p.title = title; p.line_label = "your cw_equiangular_pdf";
            cw_fmt(stem, sizeof stem, "step9_pdf_vs_hist_case%d", k + 1);
            cw_fmt(name, sizeof name, "step9.pdf_vs_hist case %d", k + 1);
            cw_fmt(verdict, sizeof verdict, "%s %s: %s%s%s", name, pass ? "PASS" : "FAIL", m, pass ? "" : " -- ", pass ? "" : adv);
            cw_picture(run, stem, &p, verdict, pass, png, sizeof png);
            cw_emit(run, name, pass, m, adv, png);
        }
    }
    /* the pdf the sampler returns and the pdf function, at the samples */
    cw_begin(run);
    cw_fmt(m, sizeof m, "%d samples: largest pdf error %.3g x the tolerance (relative 1e-3)", pdf_checked, pdf_worst);
    cw_emit(run, "step9.pdf_at_samples", pdf_checked > 0 && pdf_worst <= 1.0, m,
            pdf_adv[0] ? pdf_adv : "the sampler's pdf and cw_equiangular_pdf must both be the density of t", NULL);
    /* the pdf integrates to one over [a, b] */
    cw_begin(run);
    {
        double worst = 0.0, wI = 1.0, wexp = 1.0, wh = 1.0;
        int wk = 0;
        for (k = 0; k < 4; ++k) {
            cw__eq e;
            double end, I, want, outside;
            e.delta = cases[k][0]; e.h = cases[k][1]; e.a = cases[k][2]; e.b = cases[k][3]; e.f = f;
            end = isinf(e.b) ? e.delta + 2000.0 * e.h : e.b;
            /* split at delta, where a narrow peak sits */
            if (e.delta > e.a && e.delta < end) I = cw_integrate(cw__eq_student_pdf, &e, e.a, e.delta) + cw_integrate(cw__eq_student_pdf, &e, e.delta, end);
            else I = cw_integrate(cw__eq_student_pdf, &e, e.a, end);
            want = cw__eq_cdf(end, &e);
            outside = fabs(f->equiangular_pdf((float)e.delta, (float)e.h, (float)e.a, (float)e.b, (float)e.a - 1.0f));
            if (outside > 0.0) I = HUGE_VAL;
            if (!(fabs(I / want - 1.0) <= worst)) { worst = fabs(I / want - 1.0); wI = I; wexp = want; wk = k; wh = e.h; }
        }
        cw_fmt(m, sizeof m, "integral of your pdf over [a, b] in case %d: %.6g, expected %.6g (relative tolerance 2e-3)", wk + 1, wI, wexp);
        if (isinf(wI)) cw_fmt(adv, sizeof adv, "your pdf is not zero before a: t outside [a, b] has density 0");
        else if (fabs(wI / wexp - 1.0 / wh) < 0.01 / wh)
            cw_fmt(adv, sizeof adv, "your pdf integrates to 1/h: the factor h in the numerator is missing, p(t) = h / ((theta_b - "
                   "theta_a)(h^2 + (t - delta)^2))");
        else cw_fmt(adv, sizeof adv, "a density must integrate to 1 over [a, b]: divide by theta_b - theta_a, with the angles "
                    "measured from delta");
        cw_emit(run, "step9.pdf_integral", worst <= 2e-3, m, adv, NULL);
    }
    /* edges */
    cw_begin(run);
    adv[0] = '\0';
    {
        static const float ec[5][4] = {{0.0f, 1.0f, -5.0f, 5.0f}, {2.0f, 0.2f, 0.0f, 1e30f}, {3.0f, 1e-4f, 0.0f, 6.0f},
                                       {1e3f, 1e-3f, 0.0f, 1.0f}, {0.0f, 1.0f, 0.0f, 0.0f}};
        int ok = 0, total = 0, j, nbad = 0, mirrored = 0;
        float us[3] = {0.0f, 0.5f, CW_U_MAX};
        for (k = 0; k < 5; ++k)
            for (j = 0; j < 3; ++j) {
                float b = k == 1 ? INFINITY : ec[k][3], pdf = -1.0f;
                float t = f->sample_equiangular(ec[k][0], ec[k][1], ec[k][2], b, us[j], &pdf);
                cw__eq em;
                double tm;
                em.delta = ec[k][0]; em.h = ec[k][1]; em.a = ec[k][2]; em.b = b; em.f = f;
                tm = cw__eq_quantile(&em, 1.0 - (double)us[j]);      /* the same sampler run from b */
                /* u = 0 must give t = a, up to float rounding of delta + h tan(theta_a) */
                float slack = 1e-3f * (1.0f + fabsf(ec[k][2]) + fabsf(ec[k][2] - ec[k][0]));
                int good = isfinite(t) && t >= ec[k][2] - slack && t <= b + slack && isfinite(pdf) && pdf >= 0.0f
                           && (us[j] != 0.0f || fabsf(t - ec[k][2]) <= slack);
                if (good && k < 2) {            /* well-conditioned cases: the pdf is the density at t */
                    cw__eq e;
                    double want;
                    e.delta = ec[k][0]; e.h = ec[k][1]; e.a = ec[k][2]; e.b = b; e.f = f;
                    want = cw__eq_density(&e, t);
                    good = fabs(pdf - want) <= 1e-2 * want + 1e-9;
                }
                if (k == 4) good = isfinite(t) && isfinite(pdf);   /* an empty segment: anything finite */
                total++;
                if (!good && k < 4) {
                    nbad++;
                    if ((isfinite(t) && fabs(t - tm) <= 1e-3 * (1.0 + fabs(tm))) || (!isfinite(t) && !(fabs(tm) < 1e30))
                        || (fabs(t) > 1e30 && !(fabs(tm) < 1e30)))
                        mirrored++;
                }
                if (good) ok++;
                else if (!adv[0])
                    cw_fmt(adv, sizeof adv, "delta = %g, h = %g, [a, b] = [%g, %g], u = %.9g gave t = %g, pdf = %g: t must be finite, "
                           "in [a, b] (t = a at u = 0) and the pdf finite, the density at t", ec[k][0], ec[k][1], ec[k][2], b, us[j], t, pdf);
            }
        if (nbad > 0 && mirrored == nbad)
            cw_fmt(adv, sizeof adv, "your t runs the other way: t(u) is the inverse CDF at 1 - u, starting from b at u = 0. "
                   "The distribution is right (the chi-square checks pass), but the kit's convention (coursework.h, step 9) "
                   "is t = a at u = 0, rising with u (from b, u = 0 would give t = infinity when b is): this check failed "
                   "on the convention alone");
        cw_fmt(m, sizeof m, "%d of %d edge cases right (u = 0 and 1 - 2^-24, b = infinity, h = 1e-4, light far past the "
               "segment, a = b)", ok, total);
        cw_emit(run, "step9.edges", ok == total, m, adv, NULL);
    }
}

/* ==========================================================================================
   Steps 6-8: renders. The student's estimator renders a small scene through fogrt_render
   (desc.radiance: fogrt's threads, pixel streams and error estimate), and fogrt renders the
   same scene with its own Algorithm 1 (fogrt_render_paper_defaults() with the same
   settings, an independent seed). The two images are compared by their means: the
   difference of the mean luminance over the image, and over each of 12 regions, divided by
   its standard error, which comes from both images' per-pixel variance estimates
   (fogrt_image_pixel_variance: the spread of each pixel's four independent streams).
   A check fails when the whole image is off by more than CW_Z_IMAGE standard errors or a
   region by more than CW_Z_REGION (the level 1e-4 split over 12 regions): a correct
   estimator fails with probability about 1.5e-4 per check. Furnaces compare with the exact
   value 1 the same way (plus a tolerance of CW_FURNACE_TOL for the faceted sphere).
   The standard error counts the reference's variance and the larger of the two images'
   (cw_diff_var), never the student's alone, and an image more than CW_NOISE_MAX times as
   noisy as fogrt's fails (cw_noise_median). Where a method is about noise (MIS), its noise
   is checked against fogrt's more tightly (cw_noise_check).
   The scenes are built here in code; every reference image is rendered at check time.
   ========================================================================================== */
#define CW_W 48
#define CW_H 36
#define CW_RX 4                 /* regions across and down */
#define CW_RY 3
#define CW_Z_IMAGE 4.0          /* two-sided p = 6.3e-5 */
#define CW_Z_REGION 4.46        /* two-sided p = 8.2e-6 = 1e-4 / 12 regions */
#define CW_FURNACE_TOL 0.004
#define CW_NOISE_MAX 4.0        /* one sample's variance at most 4 times fogrt's (the median over the pixels) */
#define CW_SCALE 5              /* picture pixels per image pixel */

enum {
    CW_SC_BOX,                  /* Cornell-like box, no fog: ceiling area light and a point light */
    CW_SC_FOG,                  /* the box in fog: an emissive sphere and a point light with a radius */
    CW_SC_FOG_AREA,             /* the box in fog: the ceiling area light and a point light with a radius */
    CW_SC_FURNACE_1,            /* closed sphere, reflectance 1, emission 0.5, no fog */
    CW_SC_FURNACE_H,            /* closed sphere, reflectance 0.5, emission 0.5, no fog */
    CW_SC_FURNACE_FOG,          /* the same filled with fog of albedo 1 */
    CW_SC_FLOOR,                /* a floor, a point light and a small blocker (step 6 formulas) */
    CW_SC_FLOOR_FOG,            /* the same in fog */
    CW_SC_POINT_FOG_A,          /* a point light in fog, g = 0.6 */
    CW_SC_POINT_FOG_B,          /* a point light in fog, g = -0.3 */
    CW_SC_AREA_FLOOR,           /* a floor under a square area light */
    CW_SC_LIGHT_WALL,           /* a floor meeting a large emitting wall: light sampling alone is noisy there */
    CW_SC_TWO_POINTS,           /* a floor lit by two point lights (step 6: every light, once) */
    CW_SC_COUNT
};
static const char *const cw_scene_name[CW_SC_COUNT] = {
    "box", "fog", "fog_area", "furnace", "furnace", "furnace_fog", "floor", "floor_fog", "point_fog", "point_fog",
    "area_floor", "light_wall", "two_points"};

static fogrt_vec3 cw_f3(float x, float y, float z) { fogrt_vec3 v; v.x = x; v.y = y; v.z = z; return v; }
static uint32_t cw__material(fogrt_scene *s, float r, float g, float b, float e)
{
    fogrt_material_desc m;
    uint32_t id = 0;
    memset(&m, 0, sizeof m);
    m.type = FOGRT_BSDF_DIFFUSE;
    m.reflectance = cw_f3(r, g, b);
    m.emission = cw_f3(e, e, e);
    fogrt_scene_add_material(s, &m, &id);
    return id;
}
/* The parallelogram p, p + e1, p + e1 + e2, p + e2; its front faces along e1 x e2. */
static void cw__quad(fogrt_scene *s, fogrt_vec3 p, fogrt_vec3 e1, fogrt_vec3 e2, uint32_t mat)
{
    float v[12];
    static const uint32_t idx[6] = {0, 1, 2, 0, 2, 3};
    fogrt_mesh_desc m;
    v[0] = p.x; v[1] = p.y; v[2] = p.z;
    v[3] = p.x + e1.x; v[4] = p.y + e1.y; v[5] = p.z + e1.z;
    v[6] = p.x + e1.x + e2.x; v[7] = p.y + e1.y + e2.y; v[8] = p.z + e1.z + e2.z;
    v[9] = p.x + e2.x; v[10] = p.y + e2.y; v[11] = p.z + e2.z;
    memset(&m, 0, sizeof m);
    m.positions = v; m.vertex_count = 4; m.indices = idx; m.triangle_count = 2; m.material = mat;
    fogrt_scene_add_mesh(s, &m);
}
static void cw__point_light(fogrt_scene *s, fogrt_vec3 p, fogrt_vec3 I, float radius)
{
    fogrt_light_desc l;
    memset(&l, 0, sizeof l);
    l.type = FOGRT_LIGHT_POINT; l.position = p; l.intensity = I; l.radius = radius;
    fogrt_scene_add_light(s, &l);
}
static void cw__medium(fogrt_scene *s, float sigma_t, float albedo, float g)
{
    fogrt_medium_desc m;
    memset(&m, 0, sizeof m);
    m.sigma_t = sigma_t; m.albedo = cw_f3(albedo, albedo, albedo); m.g = g;
    fogrt_scene_set_medium(s, &m);
}
static void cw__camera(fogrt_scene *s, fogrt_vec3 eye, fogrt_vec3 at, float fov)
{
    fogrt_camera_desc c;
    memset(&c, 0, sizeof c);
    c.position = eye; c.look_at = at; c.fov_deg = fov;
    fogrt_scene_set_camera(s, &c);
}
/* The box: x and z in [-1, 1], y in [0, 2], open toward the camera (+z); red left wall,
   green right wall, a white sphere on the floor. */
static void cw__box(fogrt_scene *s)
{
    uint32_t white = cw__material(s, 0.7f, 0.7f, 0.7f, 0.0f), red = cw__material(s, 0.7f, 0.15f, 0.1f, 0.0f);
    uint32_t green = cw__material(s, 0.15f, 0.6f, 0.15f, 0.0f);
    cw__quad(s, cw_f3(-1, 0, -1), cw_f3(0, 0, 2), cw_f3(2, 0, 0), white);   /* floor, facing +y */
    cw__quad(s, cw_f3(-1, 2, -1), cw_f3(2, 0, 0), cw_f3(0, 0, 2), white);   /* ceiling */
    cw__quad(s, cw_f3(-1, 0, -1), cw_f3(2, 0, 0), cw_f3(0, 2, 0), white);   /* back */
    cw__quad(s, cw_f3(-1, 0, -1), cw_f3(0, 2, 0), cw_f3(0, 0, 2), red);     /* left */
    cw__quad(s, cw_f3(1, 0, -1), cw_f3(0, 0, 2), cw_f3(0, 2, 0), green);    /* right */
    fogrt_scene_add_sphere(s, cw_f3(0.4f, 0.35f, -0.3f), 0.35f, white);
    cw__camera(s, cw_f3(0.0f, 1.0f, 3.6f), cw_f3(0.0f, 1.0f, 0.0f), 38.0f);
}
static void cw__ceiling_light(fogrt_scene *s, float half, float le)
{
    uint32_t m = cw__material(s, 0.0f, 0.0f, 0.0f, le);
    cw__quad(s, cw_f3(-half, 1.995f, -half), cw_f3(2 * half, 0, 0), cw_f3(0, 0, 2 * half), m);   /* facing down */
}
/* A closed sphere of radius 1 around the origin in 24 x 48 facets, facing inward. */
static void cw__enclosure(fogrt_scene *s, float rho, float le)
{
    enum { NT = 24, NP = 48 };
    static float v[NT * NP * 2 * 9];
    uint32_t mat = cw__material(s, rho, rho, rho, le), nt = 0;
    int i, j, k;
    fogrt_mesh_desc m;
    for (i = 0; i < NT; ++i)
        for (j = 0; j < NP; ++j) {
            double t0 = CW_PI * i / NT, t1 = CW_PI * (i + 1) / NT, p0 = 2 * CW_PI * j / NP, p1 = 2 * CW_PI * (j + 1) / NP;
            double c[4][3];
            static const int tri[2][3] = {{0, 1, 2}, {0, 2, 3}};
            c[0][0] = sin(t0) * cos(p0); c[0][1] = cos(t0); c[0][2] = sin(t0) * sin(p0);
            c[1][0] = sin(t1) * cos(p0); c[1][1] = cos(t1); c[1][2] = sin(t1) * sin(p0);
            c[2][0] = sin(t1) * cos(p1); c[2][1] = cos(t1); c[2][2] = sin(t1) * sin(p1);
            c[3][0] = sin(t0) * cos(p1); c[3][1] = cos(t0); c[3][2] = sin(t0) * sin(p1);
            for (k = 0; k < 2; ++k) {
                const double *a = c[tri[k][0]], *b = c[tri[k][1]], *d = c[tri[k][2]];
                double e1[3], e2[3], n[3], mid[3];
                int q;
                for (q = 0; q < 3; ++q) { e1[q] = b[q] - a[q]; e2[q] = d[q] - a[q]; mid[q] = a[q] + b[q] + d[q]; }
                n[0] = e1[1] * e2[2] - e1[2] * e2[1]; n[1] = e1[2] * e2[0] - e1[0] * e2[2]; n[2] = e1[0] * e2[1] - e1[1] * e2[0];
                if (n[0] * n[0] + n[1] * n[1] + n[2] * n[2] < 1e-14) continue;          /* at a pole */
                if (n[0] * mid[0] + n[1] * mid[1] + n[2] * mid[2] > 0.0) { const double *t = b; b = d; d = t; }   /* inward */
                for (q = 0; q < 3; ++q) {
                    v[nt * 9 + q] = (float)a[q]; v[nt * 9 + 3 + q] = (float)b[q]; v[nt * 9 + 6 + q] = (float)d[q];
                }
                nt++;
            }
        }
    memset(&m, 0, sizeof m);
    m.positions = v; m.vertex_count = 3 * nt; m.triangle_count = nt; m.material = mat;
    fogrt_scene_add_mesh(s, &m);
    cw__camera(s, cw_f3(0.0f, 0.0f, 0.0f), cw_f3(0.3f, -0.2f, -1.0f), 60.0f);
}

static fogrt_scene *cw_scene_cache[CW_SC_COUNT];
/* The scene, built once per program (the checks only read it). NULL if fogrt refused it. */
static const fogrt_scene *cw_scene(int which)
{
    fogrt_scene *s = NULL;
    if (cw_scene_cache[which]) return cw_scene_cache[which];
    if (fogrt_scene_create(NULL, &s) != FOGRT_RESULT_OK) return NULL;
    switch (which) {
    case CW_SC_BOX:
        cw__box(s);
        cw__ceiling_light(s, 0.3f, 9.0f);
        cw__point_light(s, cw_f3(-0.5f, 1.4f, 0.3f), cw_f3(0.6f, 0.6f, 0.6f), 0.0f);
        break;
    case CW_SC_FOG:
        cw__box(s);
        cw__medium(s, 0.5f, 0.85f, 0.5f);
        fogrt_scene_add_sphere(s, cw_f3(-0.4f, 1.45f, -0.3f), 0.15f, cw__material(s, 0.0f, 0.0f, 0.0f, 9.0f));
        cw__point_light(s, cw_f3(0.45f, 1.3f, 0.3f), cw_f3(0.8f, 0.8f, 0.8f), 0.08f);
        break;
    case CW_SC_FOG_AREA:
        cw__box(s);
        cw__medium(s, 0.5f, 0.85f, 0.5f);
        cw__ceiling_light(s, 0.3f, 9.0f);
        cw__point_light(s, cw_f3(0.45f, 1.3f, 0.3f), cw_f3(0.8f, 0.8f, 0.8f), 0.08f);
        break;
    case CW_SC_FURNACE_1: cw__enclosure(s, 1.0f, 0.5f); break;
    case CW_SC_FURNACE_H: cw__enclosure(s, 0.5f, 0.5f); break;
    case CW_SC_FURNACE_FOG:
        cw__enclosure(s, 0.5f, 0.5f);
        cw__medium(s, 1.0f, 1.0f, 0.3f);
        break;
    case CW_SC_FLOOR:
    case CW_SC_FLOOR_FOG:
        cw__quad(s, cw_f3(-5, 0, -5), cw_f3(0, 0, 10), cw_f3(10, 0, 0), cw__material(s, 0.6f, 0.6f, 0.6f, 0.0f));
        /* a small blocker halfway between the light and the floor point (-1.2, 0, 0.8) */
        cw__quad(s, cw_f3(-0.55f, 0.6f, 0.2f), cw_f3(0, 0, 0.2f), cw_f3(0.2f, 0, 0), cw__material(s, 0.5f, 0.5f, 0.5f, 0.0f));
        cw__point_light(s, cw_f3(0.3f, 1.2f, -0.2f), cw_f3(2.0f, 1.5f, 1.0f), 0.0f);
        if (which == CW_SC_FLOOR_FOG) cw__medium(s, 0.7f, 0.9f, 0.4f);
        break;
    case CW_SC_POINT_FOG_A:
    case CW_SC_POINT_FOG_B:
        cw__quad(s, cw_f3(-5, -10, -5), cw_f3(0, 0, 10), cw_f3(10, 0, 0), cw__material(s, 0.5f, 0.5f, 0.5f, 0.0f));
        cw__point_light(s, cw_f3(0.2f, 1.0f, -0.3f), cw_f3(1.0f, 2.0f, 3.0f), 0.0f);
        cw__medium(s, 0.4f, 0.8f, which == CW_SC_POINT_FOG_A ? 0.6f : -0.3f);
        break;
    case CW_SC_AREA_FLOOR:
        cw__quad(s, cw_f3(-5, 0, -5), cw_f3(0, 0, 10), cw_f3(10, 0, 0), cw__material(s, 0.6f, 0.6f, 0.6f, 0.0f));
        cw__quad(s, cw_f3(-0.4f, 1.0f, -0.4f), cw_f3(0.8f, 0, 0), cw_f3(0, 0, 0.8f), cw__material(s, 0.0f, 0.0f, 0.0f, 4.0f));
        break;
    case CW_SC_LIGHT_WALL:
        /* Floor points near the wall see it over most of their hemisphere, and a point on the
           wall drawn by its area lands close to them with density 1/r^2 far from what the
           cosine gives: BSDF sampling finds that light with little noise, light sampling with
           much. The fog makes phase sampling matter the same way near the wall. */
        cw__quad(s, cw_f3(-2, 0, -1), cw_f3(0, 0, 3), cw_f3(4, 0, 0), cw__material(s, 0.7f, 0.7f, 0.7f, 0.0f));
        cw__quad(s, cw_f3(-2, 0, -1), cw_f3(4, 0, 0), cw_f3(0, 1.2f, 0), cw__material(s, 0.0f, 0.0f, 0.0f, 1.5f));
        cw__medium(s, 0.3f, 0.9f, 0.2f);
        cw__camera(s, cw_f3(0.0f, 1.6f, 1.8f), cw_f3(0.0f, 0.0f, -0.6f), 50.0f);
        break;
    case CW_SC_TWO_POINTS:
        cw__quad(s, cw_f3(-5, 0, -5), cw_f3(0, 0, 10), cw_f3(10, 0, 0), cw__material(s, 0.6f, 0.6f, 0.6f, 0.0f));
        cw__point_light(s, cw_f3(-0.8f, 1.0f, 0.2f), cw_f3(2.0f, 1.0f, 0.5f), 0.0f);
        cw__point_light(s, cw_f3(0.9f, 1.5f, -0.4f), cw_f3(0.5f, 1.0f, 3.0f), 0.0f);
        break;
    default: break;
    }
    {
        fogrt_build_desc b = fogrt_build_defaults();
        b.roulette_pilot = false;      /* Part II's pilot sets nothing that the paper's renderer uses */
        if (fogrt_scene_build(s, &b) != FOGRT_RESULT_OK) { fogrt_scene_destroy(s); return NULL; }
    }
    cw_scene_cache[which] = s;
    return s;
}

/* ---- rendering ---------------------------------------------------------------------------- */
typedef struct cw_img {
    float rgb[3 * CW_W * CW_H];
    double lum[CW_W * CW_H], var[CW_W * CW_H];
    double svar[CW_W * CW_H];   /* the variance of one sample's luminance (the estimator's noise) */
    double rel_err;             /* fogrt_image_error */
    uint64_t rejected;          /* non-finite samples */
    int ok;
} cw_img;

/* Renders spp samples per pixel of scene with desc (its radiance, seed and settings). */
static void cw_render(int scene, fogrt_render_desc desc, int spp, cw_img *out)
{
    fogrt_image img;
    fogrt_error_estimate e;
    const fogrt_scene *s = cw_scene(scene);
    int i;
    memset(out, 0, sizeof *out);
    if (!s || fogrt_image_alloc(&img, CW_W, CW_H, NULL) != FOGRT_RESULT_OK) return;
    desc.width = CW_W; desc.height = CW_H;
    if (fogrt_render(s, &desc, &img, spp, NULL) == FOGRT_RESULT_OK) {
        fogrt_image_resolve(&img, out->rgb);
        for (i = 0; i < CW_W * CW_H; ++i) {
            out->lum[i] = 0.2126 * out->rgb[3 * i] + 0.7152 * out->rgb[3 * i + 1] + 0.0722 * out->rgb[3 * i + 2];
            out->var[i] = fogrt_image_pixel_variance(&img, (size_t)i);
            if (img.count[i] > 1) {
                double n = img.count[i], mean = (0.2126 * img.sum[3 * i] + 0.7152 * img.sum[3 * i + 1] +
                                                 0.0722 * img.sum[3 * i + 2]) / n;
                out->svar[i] = fmax(img.sum_sq[i] / n - mean * mean, 0.0) * n / (n - 1.0);
            }
        }
        fogrt_image_error(&img, &e);
        out->rel_err = e.relative_error;
        out->rejected = img.rejected;
        out->ok = 1;
    }
    fogrt_image_free(&img);
}

/* fogrt's own images, rendered once per program and settings (a test program judges many
   solutions against the same references). */
typedef struct cw_ref_key { int scene, integrator, mis, max_depth, rr_depth, spp; uint64_t seed; } cw_ref_key;
#define CW_REF_CACHE 16
static struct { cw_ref_key key; cw_img *img; } cw_ref_cache[CW_REF_CACHE];
static const cw_img *cw_reference(int scene, int integrator, int mis, int max_depth, int rr_depth, int spp)
{
    cw_ref_key k;
    fogrt_render_desc d = fogrt_render_paper_defaults();
    int i;
    memset(&k, 0, sizeof k);
    k.scene = scene; k.integrator = integrator; k.mis = mis; k.max_depth = max_depth; k.rr_depth = rr_depth;
    k.spp = spp; k.seed = 0x5EED0000ull + cw_seed_offset;
    for (i = 0; i < CW_REF_CACHE && cw_ref_cache[i].img; ++i)
        if (memcmp(&cw_ref_cache[i].key, &k, sizeof k) == 0) return cw_ref_cache[i].img;
    if (i == CW_REF_CACHE) { free(cw_ref_cache[0].img); i = 0; }    /* full: reuse the first slot */
    cw_ref_cache[i].key = k;
    cw_ref_cache[i].img = (cw_img *)malloc(sizeof(cw_img));
    if (!cw_ref_cache[i].img) return NULL;
    d.integrator = (fogrt_integrator)integrator; d.mis = mis != 0;
    d.max_depth = max_depth; d.rr_depth = rr_depth; d.seed = k.seed;
    cw_render(scene, d, spp, cw_ref_cache[i].img);
    return cw_ref_cache[i].img;
}

/* ---- comparing two images ------------------------------------------------------------------ */
typedef struct cw_cmp {
    double mean_a, mean_b;      /* mean luminance of the student's image and the reference */
    double z;                   /* (mean_a - mean_b) / its standard error */
    double se_rel;              /* that standard error relative to mean_b */
    double zreg;                /* the region farthest off, in standard errors (signed) */
    int reg;                    /* which region (row-major, CW_RX x CW_RY) */
    double reg_ratio;           /* its mean ratio */
} cw_cmp;

/* The variance of the difference of two images' sums: the reference's variance vb, and the
   larger of the two for the student's image, which a right estimator makes as noisy as
   fogrt's. So the student's own estimate never stands alone (a heavy-tailed estimator
   underestimates its own noise), and an image noisier than fogrt's only widens the margin:
   one much noisier fails the noise limit of cw_render_check instead. Without a reference
   (a furnace, exact), the student's own. */
static double cw_diff_var(double va, double vb, int have_ref)
{
    if (!have_ref) return va;
    return vb + fmax(va, vb);
}

/* b NULL: the reference is the constant `value` with no error (a furnace). tol: a relative
   difference that is not counted (added to the standard error as a floor). */
static cw_cmp cw_compare(const cw_img *a, const cw_img *b, double value, double tol)
{
    cw_cmp c;
    int rx, ry, x, y;
    double sa = 0.0, sb = 0.0, v = 0.0, best = -1.0;
    memset(&c, 0, sizeof c);
    for (ry = 0; ry < CW_RY; ++ry)
        for (rx = 0; rx < CW_RX; ++rx) {
            double ra = 0.0, rb = 0.0, rv, va = 0.0, vb = 0.0, n = 0.0, z;
            for (y = ry * CW_H / CW_RY; y < (ry + 1) * CW_H / CW_RY; ++y)
                for (x = rx * CW_W / CW_RX; x < (rx + 1) * CW_W / CW_RX; ++x) {
                    int i = y * CW_W + x;
                    ra += a->lum[i]; va += a->var[i];
                    if (b) { rb += b->lum[i]; vb += b->var[i]; } else rb += value;
                    n += 1.0;
                }
            rv = cw_diff_var(va, vb, b != NULL);
            sa += ra; sb += rb; v += rv;
            {
                double den = sqrt(rv + (tol * rb) * (tol * rb));
                z = den > 0.0 ? (ra - rb) / den : (ra == rb ? 0.0 : HUGE_VAL);
            }
            if (!(fabs(z) <= best)) { best = fabs(z); c.zreg = z; c.reg = ry * CW_RX + rx; c.reg_ratio = rb > 0.0 ? ra / rb : NAN; }
            (void)n;
        }
    c.mean_a = sa / (CW_W * CW_H);
    c.mean_b = sb / (CW_W * CW_H);
    {
        double den = sqrt(v + (tol * sb) * (tol * sb));
        c.z = den > 0.0 ? (sa - sb) / den : (sa == sb ? 0.0 : HUGE_VAL);
        c.se_rel = sb > 0.0 ? den / sb : 0.0;
    }
    return c;
}
static int cw_cmp_pass(const cw_cmp *c) { return fabs(c->z) <= CW_Z_IMAGE && fabs(c->zreg) <= CW_Z_REGION; }
static const char *cw_region_name(int r)
{
    static const char *const names[CW_RX * CW_RY] = {
        "top left", "top, left of centre", "top, right of centre", "top right",
        "middle left", "middle, left of centre", "middle, right of centre", "middle right",
        "bottom left", "bottom, left of centre", "bottom, right of centre", "bottom right"};
    return r >= 0 && r < CW_RX * CW_RY ? names[r] : "?";
}

/* ---- the picture: the student's image, the reference, the difference -------------------- */
static void cw__tonemap(const cw_img *im, double exposure_scale, unsigned char *out)
{
    float buf[3 * CW_W * CW_H];
    int i;
    for (i = 0; i < 3 * CW_W * CW_H; ++i) buf[i] = (float)(im->rgb[i] * exposure_scale);
    fogrt_tonemap_rgb8(buf, CW_W, CW_H, 0.0f, FOGRT_TONEMAP_SRGB, out);
}
static void cw__blit_scaled(pf_canvas *c, int X, int Y, const unsigned char *rgb)
{
    int x, y, i, j;
    for (y = 0; y < CW_H; ++y)
        for (x = 0; x < CW_W; ++x)
            for (j = 0; j < CW_SCALE; ++j)
                for (i = 0; i < CW_SCALE; ++i) pf_put(c, X + x * CW_SCALE + i, Y + y * CW_SCALE + j, rgb + 3 * (y * CW_W + x));
}
/* a: the student's image; b: the reference (NULL: the constant value of a furnace). */
static void cw_render_picture(const cw_run *run, const char *stem, const char *title, const char *label_b,
                              const cw_img *a, const cw_img *b, double value, const char *verdict, int pass,
                              char *path, size_t size)
{
    unsigned char ta[3 * CW_W * CW_H], tb[3 * CW_W * CW_H], td[3 * CW_W * CW_H];
    double lums[CW_W * CW_H], p95, scale, meanb = 0.0;
    int i, j, pw = CW_W * CW_SCALE, ph = CW_H * CW_SCALE, X0 = 16, gap = 24, top = 40;
    pf_canvas c;
    path[0] = '\0';
    if (!run->img_dir) return;
    for (i = 0; i < CW_W * CW_H; ++i) { lums[i] = b ? b->lum[i] : value; meanb += lums[i]; }
    meanb /= CW_W * CW_H;
    for (i = 1; i < CW_W * CW_H; ++i) {              /* insertion sort: 1728 numbers, once */
        double t = lums[i];
        for (j = i - 1; j >= 0 && lums[j] > t; --j) lums[j + 1] = lums[j];
        lums[j + 1] = t;
    }
    p95 = lums[(int)(0.95 * (CW_W * CW_H - 1))];
    scale = p95 > 0.0 ? 0.8 / p95 : 1.0;
    cw__tonemap(a, scale, ta);
    if (b) cw__tonemap(b, scale, tb);
    else {
        cw_img flat;
        for (i = 0; i < 3 * CW_W * CW_H; ++i) flat.rgb[i] = (float)value;
        cw__tonemap(&flat, scale, tb);
    }
    for (i = 0; i < CW_W * CW_H; ++i) {     /* difference / the reference's mean: blue darker, red brighter */
        double d = meanb > 0.0 ? (a->lum[i] - (b ? b->lum[i] : value)) / meanb : 0.0, t = fmin(fabs(d) / 0.5, 1.0);
        unsigned char lo = (unsigned char)lround(255.0 * (1.0 - t));
        if (!isfinite(d)) { td[3 * i] = 0; td[3 * i + 1] = 0; td[3 * i + 2] = 0; continue; }
        td[3 * i] = d > 0.0 ? 255 : lo; td[3 * i + 1] = lo; td[3 * i + 2] = d < 0.0 ? 255 : lo;
    }
    c = pf_canvas_make(X0 * 2 + 3 * pw + 2 * gap, top + ph + 66, PF_WHITE);
    pf_text_at(&c, c.w / 2, 10, title, pf_text_width(title, 2) <= c.w - 8 ? 2 : 1, PF_BLACK, 1);
    cw__blit_scaled(&c, X0, top, ta);
    cw__blit_scaled(&c, X0 + pw + gap, top, tb);
    cw__blit_scaled(&c, X0 + 2 * (pw + gap), top, td);
    pf_text_at(&c, X0 + pw / 2, top + ph + 6, "your estimator", 2, PF_BLACK, 1);
    pf_text_at(&c, X0 + pw + gap + pw / 2, top + ph + 6, label_b, 2, PF_BLACK, 1);
    pf_text_at(&c, X0 + 2 * (pw + gap) + pw / 2, top + ph + 6, "difference", 2, PF_BLACK, 1);
    pf_text_at(&c, X0 + 2 * (pw + gap) + pw / 2, top + ph + 28, "red: yours brighter, blue: darker", 1, PF_GREY, 1);
    pf_text_at(&c, X0 + 2 * (pw + gap) + pw / 2, top + ph + 40, "(full colour at 50% of the mean)", 1, PF_GREY, 1);
    pf_text_at(&c, X0 + 2 * (pw + gap) + pw / 2, top + ph + 52, "noise is expected; a pattern is not", 1, PF_GREY, 1);
    pf_text_at(&c, X0 + pw / 2, top + ph + 28, "same exposure as the reference", 1, PF_GREY, 1);
    cw_save(run, stem, &c, verdict, pass, path, size);
    pf_canvas_free(&c);
}

/* The median over the pixels of the ratio of one sample's variance, the student's image's
   over the reference's. A median, not a ratio of sums: a correct estimator with rare large
   samples (light sampling near a facet's edge) puts a few pixels' variance far off in
   either image, which moves a sum by orders of magnitude but the median not at all, while
   an estimator that is noisier everywhere moves it by its full factor. */
static int cw__cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}
static double cw_noise_median(const cw_img *a, const cw_img *b)
{
    static double r[CW_W * CW_H];
    int i, n = 0;
    for (i = 0; i < CW_W * CW_H; ++i) {
        if (b->svar[i] > 0.0) r[n++] = a->svar[i] / b->svar[i];
        else if (a->svar[i] > 0.0) r[n++] = HUGE_VAL;
    }
    if (n == 0) return 1.0;
    qsort(r, (size_t)n, sizeof r[0], cw__cmp_double);
    return n % 2 ? r[n / 2] : 0.5 * (r[n / 2 - 1] + r[n / 2]);
}

/* What an image noisier than fogrt's means in the check at hand (NULL: the general advice). */
static const char *cw_noise_hint;
/* The student's image of the last render check and its verdict (the noise check reads them). */
static cw_img cw_student_img;
static int cw_student_pass;

/* One render check: the student's image (desc with its radiance and user data) against
   fogrt's (ref NULL: a furnace of constant value). hint_dark / hint_bright: what a too dark
   or too bright image usually means in this step. Returns whether it passed; *cmp gets the
   statistics (for the caller's own diagnosis). */
static int cw_render_check(cw_run *run, const char *name, const char *stem, const char *title, int scene,
                           fogrt_render_desc desc, int spp, const cw_img *ref, double value,
                           const char *hint_dark, const char *hint_bright, cw_cmp *out)
{
    cw_cmp c;
    char m[700], adv[1100], png[256], verdict[1900], noise_note[300] = "";
    double noise = 1.0;
    int pass, noisy;
    desc.seed = 0xC0DE0000ull + cw_seed_offset;
    cw_render(scene, desc, spp, &cw_student_img);
    if (!cw_student_img.ok || (ref && !ref->ok)) {
        cw_emit(run, name, 0, "fogrt_render failed (scene or reference)", "", NULL);
        if (out) memset(out, 0, sizeof *out);
        return 0;
    }
    c = cw_compare(&cw_student_img, ref, value, ref ? 0.0 : CW_FURNACE_TOL);
    if (ref) noise = cw_noise_median(&cw_student_img, ref);
    noisy = !(noise <= CW_NOISE_MAX);
    pass = cw_cmp_pass(&c) && cw_student_img.rejected == 0 && !noisy;
    if (ref)
        cw_fmt(m, sizeof m, "mean %.5g vs fogrt's %.5g (ratio %.4f, relative error of the difference %.2g%%): z = %.2f "
               "(fail if |z| > %g); worst region %s z = %.2f (fail if > %g); noise (median over the pixels of one sample's "
               "variance, yours over fogrt's) %.3g (fail if > %g)",
               c.mean_a, c.mean_b, c.mean_b > 0.0 ? c.mean_a / c.mean_b : NAN, 100.0 * c.se_rel, c.z, CW_Z_IMAGE,
               cw_region_name(c.reg), c.zreg, CW_Z_REGION, noise, CW_NOISE_MAX);
    else
        cw_fmt(m, sizeof m, "mean %.5g, exact %.5g (standard error %.2g%% + tolerance %.2g%%): z = %.2f (fail if |z| > %g); "
               "worst region %s z = %.2f (fail if > %g)", c.mean_a, value, 100.0 * sqrt(fmax(c.se_rel * c.se_rel -
               CW_FURNACE_TOL * CW_FURNACE_TOL, 0.0)), 100.0 * CW_FURNACE_TOL, c.z, CW_Z_IMAGE, cw_region_name(c.reg), c.zreg, CW_Z_REGION);
    if (cw_student_img.rejected)
        cw_fmt(adv, sizeof adv, "%llu samples were NaN or infinite (fogrt dropped them): a division by a zero pdf, or "
               "a direction that is not unit length?", (unsigned long long)cw_student_img.rejected);
    else if (!(c.mean_a > 0.0))
        cw_fmt(adv, sizeof adv, "your image is black: nothing is returned yet (is the TODO still there?)");
    else if (noisy && cw_cmp_pass(&c) && cw_noise_hint)
        cw_fmt(adv, sizeof adv, "right on average, but one sample's variance is %.3g times fogrt's (the median pixel): %s",
               noise, cw_noise_hint);
    else if (noisy && cw_cmp_pass(&c))
        cw_fmt(adv, sizeof adv, "one sample's variance is %.3g times fogrt's (the median pixel), and the mean %.4g times "
               "fogrt's (%s within "
               "the noise): this step's estimator is fogrt's, so its noise should be too; rare samples with huge weights "
               "(a division by a small pdf that does not cancel against f, a weight multiplied in twice) make an image "
               "this noisy, and so much noise can hide a wrong mean", noise, c.mean_b > 0.0 ? c.mean_a / c.mean_b : NAN,
               fabs(c.mean_a / c.mean_b - 1.0) < 0.05 ? "close" : "not close, yet");
    else if (c.z < -CW_Z_IMAGE || (fabs(c.z) <= CW_Z_IMAGE && c.zreg < 0.0))
        cw_fmt(adv, sizeof adv, "too dark%s by a factor ~%.3g%s: %s", fabs(c.z) <= CW_Z_IMAGE ? " in one region" : "",
               fabs(c.z) <= CW_Z_IMAGE ? 1.0 / c.reg_ratio : c.mean_b / c.mean_a,
               fabs(c.z) <= CW_Z_IMAGE ? "" : " overall", hint_dark);
    else
        cw_fmt(adv, sizeof adv, "too bright%s by a factor ~%.3g%s: %s", fabs(c.z) <= CW_Z_IMAGE ? " in one region" : "",
               fabs(c.z) <= CW_Z_IMAGE ? c.reg_ratio : c.mean_a / c.mean_b,
               fabs(c.z) <= CW_Z_IMAGE ? "" : " overall", hint_bright);
    if (noisy && !cw_cmp_pass(&c) && !cw_student_img.rejected && c.mean_a > 0.0) {
        cw_fmt(noise_note, sizeof noise_note, "; and your image is %.3g times as noisy as fogrt's: some samples "
               "carry huge weights (a division by a pdf that f does not cancel?)", noise);
        strncat(adv, noise_note, sizeof adv - strlen(adv) - 1);
    }
    cw_fmt(verdict, sizeof verdict, "%s %s: %s%s%s", name, pass ? "PASS" : "FAIL", m, pass ? "" : " -- ", pass ? "" : adv);
    {
        char t2[200];
        if (ref) cw_fmt(t2, sizeof t2, "%s (relative error of yours %.2g%%, of fogrt's %.2g%%)", title, 100.0 * cw_student_img.rel_err,
                        100.0 * ref->rel_err);
        else cw_fmt(t2, sizeof t2, "%s (relative error of yours %.2g%%)", title, 100.0 * cw_student_img.rel_err);
        cw_render_picture(run, stem, t2, ref ? "fogrt (reference)" : "exact: 1 everywhere", &cw_student_img, ref, value, verdict, pass,
                          png, sizeof png);
    }
    cw_emit(run, name, pass, m, adv, png);
    if (out) *out = c;
    cw_student_pass = pass;
    return pass;
}

/* ==========================================================================================
   Step 6: direct lighting by light sampling (eq. 3)
   ========================================================================================== */
/* The direct-lighting image with the student's functions: the camera ray's emission, then
   at the first vertex (the nearer of the surface and the fog collision, eq. 6) the
   student's light sampling, times the fog's albedo at a collision. fogrt's
   FOGRT_INTEGRATOR_DIRECT without MIS renders the same quantity. */
static fogrt_vec3 cw__direct_radiance(const fogrt_scene *s, fogrt_vec3 o, fogrt_vec3 d, fogrt_rng *rng, void *user)
{
    const cw_fns *f = (const cw_fns *)user;
    fogrt_medium_desc m;
    fogrt_hit hit;
    fogrt_surface sf;
    fogrt_vec3 L = {0.0f, 0.0f, 0.0f}, wo, Ld;
    float t_fog = INFINITY;
    int found = fogrt_scene_intersect(s, o, d, 0.0f, INFINITY, &hit);
    fogrt_scene_get_medium(s, &m);
    wo = cw_f3(-d.x, -d.y, -d.z);
    if (m.sigma_t > 0.0f) t_fog = fogrt_sample_exponential(m.sigma_t, fogrt_rng_float(rng));
    if (t_fog < (found ? hit.t : INFINITY)) {
        Ld = f->direct_fog(s, cw_f3(o.x + d.x * t_fog, o.y + d.y * t_fog, o.z + d.z * t_fog), wo, rng);
        return cw_f3(Ld.x * m.albedo.x, Ld.y * m.albedo.y, Ld.z * m.albedo.z);
    }
    if (!found) return L;
    fogrt_scene_surface(s, o, d, &hit, &sf);
    if (sf.front) L = sf.material.emission;
    if (sf.material.reflectance.x + sf.material.reflectance.y + sf.material.reflectance.z > 0.0f) {
        Ld = f->direct_surface(s, &sf, wo, rng);
        L.x += Ld.x; L.y += Ld.y; L.z += Ld.z;
    }
    return L;
}

static double cw_lum3(fogrt_vec3 v) { return 0.2126 * v.x + 0.7152 * v.y + 0.0722 * v.z; }
static double cw_lumd(const double *v) { return 0.2126 * v[0] + 0.7152 * v[1] + 0.0722 * v[2]; }
/* Whether all ratios r[i] (n of them) equal the model m[i] within tol (relative). */
static int cw_ratios_match(const double *r, const double *model, int n, double tol)
{
    int i, k = 0;
    for (i = 0; i < n; ++i) {
        if (!(model[i] > 0.0) || !isfinite(r[i])) continue;
        if (fabs(r[i] / model[i] - 1.0) > tol) return 0;
        k++;
    }
    return k > 0;
}

/* The surface formula: a point light over a floor, at 7 floor points (one behind a
   blocker, one seen from under the floor), without and with fog: one sample is exact. */
static void cw_step6_surface_formula(const cw_fns *f, cw_run *run)
{
    static const float pts[7][6] = {   /* floor point, eye */
        {0.0f, 0, 0.0f, 0.0f, 2.0f, 3.0f}, {0.9f, 0, -0.6f, -1.0f, 1.5f, 2.0f}, {2.0f, 0, 1.5f, 0.0f, 3.0f, 0.0f},
        {-0.4f, 0, -1.3f, 2.0f, 0.5f, 1.0f}, {0.3f, 0, -0.2f, 0.3f, 3.0f, 2.0f},
        {-1.2f, 0, 0.8f, 0.0f, 2.0f, 3.0f},     /* the blocker hides the light */
        {0.5f, 0, 0.5f, 0.5f, -1.0f, 1.0f}};    /* seen from below: the light is behind the surface */
    const fogrt_vec3 I = {2.0f, 1.5f, 1.0f}, lp = {0.3f, 1.2f, -0.2f};
    char m[600], adv[700];
    double worst = 0.0, r_cos[14], m_cos[14], r_t[14], m_t[14], r_pi[14], m_pi[14], ratio[14];
    int sc, k, nr = 0, nt = 0, bad_blocked = 0, bad_behind = 0, bad_nan = 0, worst_k = 0, worst_sc = 0;
    double got_w = 0.0, exp_w = 0.0;
    cw_begin(run);
    for (sc = 0; sc < 2; ++sc) {
        const fogrt_scene *s = cw_scene(sc ? CW_SC_FLOOR_FOG : CW_SC_FLOOR);
        fogrt_medium_desc med;
        if (!s) continue;
        fogrt_scene_get_medium(s, &med);
        for (k = 0; k < 7; ++k) {
            fogrt_vec3 e = cw_f3(pts[k][3], pts[k][4], pts[k][5]), q = cw_f3(pts[k][0], pts[k][1], pts[k][2]), d, L;
            fogrt_hit hit;
            fogrt_surface sf;
            fogrt_rng rng;
            double wi[3], r, cosv, T, expd[3], nside, err;
            int c;
            d = cw_v3(q.x - e.x, q.y - e.y, q.z - e.z);
            if (!fogrt_scene_intersect(s, e, d, 0.0f, INFINITY, &hit)) continue;
            fogrt_scene_surface(s, e, d, &hit, &sf);
            wi[0] = lp.x - sf.p.x; wi[1] = lp.y - sf.p.y; wi[2] = lp.z - sf.p.z;
            r = sqrt(wi[0] * wi[0] + wi[1] * wi[1] + wi[2] * wi[2]);
            nside = e.y > 0.0f ? 1.0 : -1.0;           /* the normal on the viewer's side */
            cosv = nside * wi[1] / r;
            T = med.sigma_t > 0.0f ? exp(-(double)med.sigma_t * r) : 1.0;
            for (c = 0; c < 3; ++c) expd[c] = (k == 5 || cosv <= 0.0) ? 0.0 : 0.6 / CW_PI * cosv * (&I.x)[c] / (r * r) * T;
            cw_seed(&rng, 600 + 10 * sc + k);
            L = f->direct_surface(s, &sf, cw_f3(-d.x, -d.y, -d.z), &rng);
            if (!cw_finite3(L)) { bad_nan++; err = HUGE_VAL; }
            else {
                err = 0.0;
                for (c = 0; c < 3; ++c) err = fmax(err, fabs((&L.x)[c] - expd[c]) / (1e-4 * expd[c] + 1e-7));
            }
            if (k == 5 && cw_lum3(L) > 1e-6) bad_blocked++;
            if (k == 6 && cw_lum3(L) > 1e-6) bad_behind++;
            if (!(err <= worst)) { worst = err; worst_k = k; worst_sc = sc; got_w = cw_lum3(L); exp_w = cw_lumd(expd); }
            if (k < 5 && cw_lumd(expd) > 0.0 && nr < 14) {
                ratio[nr] = cw_lum3(L) / cw_lumd(expd);
                r_cos[nr] = ratio[nr]; m_cos[nr] = 1.0 / cosv;
                r_pi[nr] = ratio[nr]; m_pi[nr] = CW_PI;
                if (sc) { r_t[nt] = ratio[nr]; m_t[nt] = 1.0 / T; nt++; }
                nr++;
            }
        }
    }
    {
        int pass = worst <= 1.0;
        int nofog_ok = 1, i;
        for (i = 0; i < nr - nt && i < 5; ++i) if (fabs(ratio[i] - 1.0) > 1e-3) nofog_ok = 0;
        cw_fmt(m, sizeof m, "largest error at floor point %d%s: %.6g, expected %.6g (rho/pi cos I/r^2%s; tolerance 1e-4 "
               "relative); 14 points, a point light, one sample is exact", worst_k, worst_sc ? " in fog" : "", got_w, exp_w,
               worst_sc ? " T" : "");
        if (bad_nan)
            cw_fmt(adv, sizeof adv, "%d results were NaN or infinite", bad_nan);
        else if (cw_ratios_match(r_cos, m_cos, nr, 2e-3))
            cw_fmt(adv, sizeof adv, "your light is off by 1/cos(theta) at every point: the cosine between wi and the normal "
                   "(eq. 3's cos theta_i) is missing from the light sample");
        else if (cw_ratios_match(r_pi, m_pi, nr, 2e-3))
            cw_fmt(adv, sizeof adv, "pi times too bright everywhere: the diffuse BSDF is reflectance / pi, not the reflectance");
        else if (nofog_ok && nt > 0 && cw_ratios_match(r_t, m_t, nt, 2e-3))
            cw_fmt(adv, sizeof adv, "right without fog, too bright in fog by 1/T: the shadow ray through the fog loses "
                   "exp(-sigma_t dist) (eq. 8); multiply by the transmittance over ls.dist");
        else if (bad_blocked)
            cw_fmt(adv, sizeof adv, "light reaches the floor point behind the blocker: test the shadow ray with "
                   "fogrt_scene_visible before adding a light sample");
        else if (bad_behind)
            cw_fmt(adv, sizeof adv, "seen from under the floor, the light above it still shines: f is 0 when wi and wo are on "
                   "opposite sides of the surface (use |cos| only with that test, or fogrt_bsdf_eval)");
        else
            cw_fmt(adv, sizeof adv, "eq. 3 with one point light: f Le |cos| T / pdf = (rho/pi) |cos theta| (I/r^2) T / 1, "
                   "cos theta between wi and sf->n");
        cw_emit(run, "step6.surface_formula", pass, m, adv, NULL);
    }
}

/* The fog formula: a point light in fog of g = 0.6 and g = -0.3, at 5 points and 3 wo. */
static void cw_step6_fog_formula(const cw_fns *f, cw_run *run)
{
    static const float pts[5][3] = {{0, 0, 0}, {1, 1, 1}, {0.2f, 0.5f, -0.3f}, {-2, 0.3f, 0.5f}, {0.5f, 1.5f, -1}};
    static const float wos[3][3] = {{1, 0.2f, 0.3f}, {-0.3f, -1, 0.2f}, {0.1f, 0.6f, -0.8f}};
    const fogrt_vec3 I = {1.0f, 2.0f, 3.0f}, lp = {0.2f, 1.0f, -0.3f};
    char m[600], adv[700];
    double worst = 0.0, ratio[30], m_ph[30], m_t[30], m_flip[30], m_al[30], m_4pi[30], got_w = 0.0, exp_w = 0.0;
    int sc, k, j, n = 0, bad_nan = 0;
    float wg = 0.0f;
    cw_begin(run);
    for (sc = 0; sc < 2; ++sc) {
        const fogrt_scene *s = cw_scene(sc ? CW_SC_POINT_FOG_B : CW_SC_POINT_FOG_A);
        fogrt_medium_desc med;
        if (!s) continue;
        fogrt_scene_get_medium(s, &med);
        for (k = 0; k < 5; ++k)
            for (j = 0; j < 3; ++j) {
                fogrt_vec3 p = cw_f3(pts[k][0], pts[k][1], pts[k][2]), wo = cw_v3(wos[j][0], wos[j][1], wos[j][2]), L;
                fogrt_rng rng;
                double wi[3], r, mu, T, ph, expd[3], err = 0.0;
                int c;
                wi[0] = lp.x - p.x; wi[1] = lp.y - p.y; wi[2] = lp.z - p.z;
                r = sqrt(wi[0] * wi[0] + wi[1] * wi[1] + wi[2] * wi[2]);
                mu = -(wo.x * wi[0] + wo.y * wi[1] + wo.z * wi[2]) / r;
                T = exp(-(double)med.sigma_t * r);
                ph = cw_hg_ref(med.g, mu);
                for (c = 0; c < 3; ++c) expd[c] = ph * (&I.x)[c] / (r * r) * T;
                cw_seed(&rng, 700 + 100 * sc + 3 * k + j);
                L = f->direct_fog(s, p, wo, &rng);
                if (!cw_finite3(L)) { bad_nan++; err = HUGE_VAL; }
                else for (c = 0; c < 3; ++c) err = fmax(err, fabs((&L.x)[c] - expd[c]) / (2e-4 * expd[c] + 1e-7));
                if (!(err <= worst)) { worst = err; got_w = cw_lum3(L); exp_w = cw_lumd(expd); wg = med.g; }
                ratio[n] = cw_lum3(L) / cw_lumd(expd);
                m_ph[n] = 1.0 / ph; m_t[n] = 1.0 / T; m_flip[n] = cw_hg_ref(-med.g, mu) / ph;
                m_al[n] = med.albedo.x; m_4pi[n] = 4.0 * CW_PI;
                n++;
            }
    }
    {
        int pass = worst <= 1.0;
        cw_fmt(m, sizeof m, "largest error (g = %g): %.6g, expected %.6g (p_HG(mu) I/r^2 T; tolerance 2e-4 relative); "
               "30 cases, a point light in fog, g = 0.6 and -0.3", wg, got_w, exp_w);
        if (bad_nan) cw_fmt(adv, sizeof adv, "%d results were NaN or infinite", bad_nan);
        else if (cw_ratios_match(ratio, m_t, n, 2e-3))
            cw_fmt(adv, sizeof adv, "too bright by exactly 1/T: the transmittance exp(-sigma_t dist) of the shadow ray "
                   "(eq. 8) is missing");
        else if (cw_ratios_match(ratio, m_flip, n, 2e-3))
            cw_fmt(adv, sizeof adv, "you evaluate HG with the wrong angle: mu is the cosine between the propagation "
                   "direction -wo and wi (fogrt_hg_pdf(g, wo, wi) does it), or g's sign is flipped");
        else if (cw_ratios_match(ratio, m_ph, n, 2e-3))
            cw_fmt(adv, sizeof adv, "the phase function is missing: in fog f is p_HG(mu) (eq. 9), not 1");
        else if (cw_ratios_match(ratio, m_4pi, n, 2e-3))
            cw_fmt(adv, sizeof adv, "4 pi too bright: the phase function is a density per steradian, with 1/(4 pi)");
        else if (cw_ratios_match(ratio, m_al, n, 2e-3))
            cw_fmt(adv, sizeof adv, "off by the albedo: cw_direct_fog returns the in-scattered light without the albedo "
                   "(the caller applies it at the collision)");
        else
            cw_fmt(adv, sizeof adv, "eq. 3 in fog with one point light: p_HG(mu) (I/r^2) T / 1, mu = dot(-wo, wi), "
                   "T = exp(-sigma_t r)");
        cw_emit(run, "step6.fog_formula", pass, m, adv, NULL);
    }
}

/* Two point lights over a floor: one sample of each is exact, so every call must return the
   sum of both lights' (rho/pi) cos I/r^2. One light picked at random and multiplied by the
   number of lights is unbiased too, but it is not the contract, and its answer changes from
   call to call. */
static void cw_step6_every_light(const cw_fns *f, cw_run *run)
{
    static const float pts[5][2] = {{0, 0}, {-0.8f, 0.3f}, {0.9f, -0.4f}, {1.5f, 1.0f}, {-2.0f, -1.5f}};
    static const float lp[2][3] = {{-0.8f, 1.0f, 0.2f}, {0.9f, 1.5f, -0.4f}};
    static const float Iv[2][3] = {{2.0f, 1.0f, 0.5f}, {0.5f, 1.0f, 3.0f}};
    const fogrt_scene *s = cw_scene(CW_SC_TWO_POINTS);
    const double rho = 0.6;
    char m[500], adv[700];
    double worst = 0.0, wgot = 0.0, wexp = 0.0;
    int k, j, calls = 0, one_light = 0, bad = 0, wk = 0;
    cw_begin(run);
    if (!s) { cw_emit(run, "step6.every_light", 0, "scene failed", "", NULL); return; }
    for (k = 0; k < 5; ++k) {
        fogrt_vec3 q = cw_f3(pts[k][0], 0.0f, pts[k][1]), e = cw_f3(pts[k][0] + 0.3f, 1.2f, pts[k][1] + 1.0f), d, wo;
        fogrt_hit hit;
        fogrt_surface sf;
        double each[2], sum;
        int l;
        d = cw_v3(q.x - e.x, q.y - e.y, q.z - e.z);
        if (!fogrt_scene_intersect(s, e, d, 0.0f, INFINITY, &hit)) continue;
        fogrt_scene_surface(s, e, d, &hit, &sf);
        wo = cw_f3(-d.x, -d.y, -d.z);
        for (l = 0; l < 2; ++l) {
            double w[3], r2, c;
            w[0] = lp[l][0] - sf.p.x; w[1] = lp[l][1] - sf.p.y; w[2] = lp[l][2] - sf.p.z;
            r2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
            c = w[1] / sqrt(r2);
            each[l] = rho / CW_PI * c / r2 * (0.2126 * Iv[l][0] + 0.7152 * Iv[l][1] + 0.0722 * Iv[l][2]);
        }
        sum = each[0] + each[1];
        for (j = 0; j < 8; ++j) {
            fogrt_rng rng;
            double got, err;
            cw_seed(&rng, 740 + 8 * k + j);
            got = cw_lum3(f->direct_surface(s, &sf, wo, &rng));
            calls++;
            err = isfinite(got) ? fabs(got - sum) / (1e-4 * sum) : HUGE_VAL;
            if (err > 1.0) {
                bad++;
                if (fabs(got - 2.0 * each[0]) <= 1e-3 * sum || fabs(got - 2.0 * each[1]) <= 1e-3 * sum) one_light++;
            }
            if (!(err <= worst)) { worst = err; wgot = got; wexp = sum; wk = k; }
        }
    }
    {
        int pass = calls > 0 && bad == 0;
        cw_fmt(m, sizeof m, "%d of %d calls at 5 floor points lit by two point lights return the sum of both lights' "
               "(rho/pi) cos I/r^2 (relative tolerance 1e-4); worst at point %d: %.6g, expected %.6g", calls - bad, calls,
               wk, wgot, wexp);
        if (pass) adv[0] = '\0';
        else if (one_light > bad / 2)
            cw_fmt(adv, sizeof adv, "your answer is twice one light's, a different light from call to call: you pick one "
                   "light at random and multiply by the number of lights. That is unbiased, but the contract (coursework.h, "
                   "step 6) asks for ONE sample of EVERY light, lights 0 .. fogrt_scene_light_total() - 1, summed");
        else
            cw_fmt(adv, sizeof adv, "with point lights one sample of each light is exact: sum f Le |cos| T / pdf over "
                   "every light (lights 0 .. fogrt_scene_light_total() - 1), each with its own three random numbers");
        cw_emit(run, "step6.every_light", pass, m, adv, NULL);
    }
}

/* The area light's estimate at floor points against the integral (quadrature in double),
   and against what the usual mistakes would average to. */
static void cw_step6_area_estimate(const cw_fns *f, cw_run *run)
{
    static const float pts[6][2] = {{0, 0}, {0.4f, 0.4f}, {0.8f, 0}, {1.5f, -1}, {-2.5f, 0.5f}, {0.1f, -0.3f}};
    const int N = 4000, Q = 200;
    const double rho = 0.6, Le = 4.0, h = 1.0, A = 0.64, zc = 4.31;   /* z: two-sided 1e-4 / 6 */
    const fogrt_scene *s = cw_scene(CW_SC_AREA_FLOOR);
    char m[600], adv[700];
    double worst = 0.0, wz = 0.0, wmean = 0.0, wexp = 0.0, lr[3] = {0, 0, 0};
    int k, i, j, wk = 0, bad = 0;
    cw_begin(run);
    if (!s) { cw_emit(run, "step6.area_estimate", 0, "scene failed", "", NULL); return; }
    for (k = 0; k < 6; ++k) {
        fogrt_vec3 q = cw_f3(pts[k][0], 0.0f, pts[k][1]), e = cw_f3(pts[k][0] + 0.2f, 0.5f, pts[k][1] + 1.5f), d;
        fogrt_hit hit;
        fogrt_surface sf;
        fogrt_rng rng;
        double sum = 0.0, sum2 = 0.0, mean, se, z, ic = 0.0, inp = 0.0, inc = 0.0;
        d = cw_v3(q.x - e.x, q.y - e.y, q.z - e.z);
        if (!fogrt_scene_intersect(s, e, d, 0.0f, INFINITY, &hit)) continue;
        fogrt_scene_surface(s, e, d, &hit, &sf);
        cw_seed(&rng, 800 + k);
        for (i = 0; i < N; ++i) {
            double v = cw_lum3(f->direct_surface(s, &sf, cw_f3(-d.x, -d.y, -d.z), &rng));
            if (!isfinite(v)) { bad++; continue; }
            sum += v; sum2 += v * v;
        }
        for (i = 0; i < Q; ++i)                 /* midpoint rule over the light */
            for (j = 0; j < Q; ++j) {
                double x = -0.4 + 0.8 * (i + 0.5) / Q - sf.p.x, z2 = -0.4 + 0.8 * (j + 0.5) / Q - sf.p.z;
                double dd = sqrt(x * x + h * h + z2 * z2), dA = A / ((double)Q * Q);
                ic += h * h / (dd * dd * dd * dd) * dA;      /* cos cos' / d^2 */
                inp += h / dd * dA / A;                       /* cos, averaged over the light's area */
                inc += h / (dd * dd * dd) * dA;               /* cos' / d^2 */
            }
        ic *= rho / CW_PI * Le; inp *= rho / CW_PI * Le; inc *= rho / CW_PI * Le;
        mean = sum / N;
        se = sqrt(fmax(sum2 / N - mean * mean, 0.0) / (N - 1)) + 1e-6 * ic;
        z = (mean - ic) / se;
        lr[0] += fabs(log(mean / ic)); lr[1] += fabs(log(mean / inp)); lr[2] += fabs(log(mean / inc));
        if (!(fabs(z) <= worst)) { worst = fabs(z); wz = z; wk = k; wmean = mean; wexp = ic; }
    }
    {
        int pass = worst <= zc && !bad;
        cw_fmt(m, sizeof m, "6 floor points under a square light, %d estimates each: worst at point %d: mean %.5g, the "
               "integral is %.5g, z = %.2f (fail if |z| > %.2f: 1e-4 over 6 points)", N, wk, wmean, wexp, wz, zc);
        if (bad) cw_fmt(adv, sizeof adv, "%d estimates were NaN or infinite", bad);
        else if (lr[1] < 0.05 * 6 && lr[1] < lr[0])
            cw_fmt(adv, sizeof adv, "your means match f Le cos without the division by the pdf (the light's average "
                   "over its area): missing 1/pdf? eq. 3 divides every sample by the density it was drawn with, ls.pdf");
        else if (lr[2] < 0.05 * 6 && lr[2] < lr[0])
            cw_fmt(adv, sizeof adv, "your means match the estimate without the cosine at the floor: the cos theta of "
                   "eq. 3 is missing");
        else
            cw_fmt(adv, sizeof adv, "%s by a factor ~%.3g at point %d: each sample is f Le |cos| T / ls.pdf, summed over "
                   "the lights", wz < 0 ? "too dark" : "too bright", wz < 0 ? wexp / wmean : wmean / wexp, wk);
        cw_emit(run, "step6.area_estimate", pass, m, adv, NULL);
    }
}

static void cw_step6(const cw_fns *f, cw_run *run)
{
    fogrt_render_desc d = fogrt_render_paper_defaults();
    cw_step6_surface_formula(f, run);
    cw_step6_fog_formula(f, run);
    cw_step6_every_light(f, run);
    cw_step6_area_estimate(f, run);
    d.radiance = cw__direct_radiance;
    d.user_data = (void *)f;
    cw_begin(run);
    cw_render_check(run, "step6.render box", "step6_render_box", "Step 6: direct light in the box (area and point light)",
                    CW_SC_BOX, d, 128, cw_reference(CW_SC_BOX, FOGRT_INTEGRATOR_DIRECT, 0, 1, 3, 128), 0.0,
                    "compare step6.surface_formula and step6.area_estimate, which name the usual causes (a missing 1/pdf, "
                    "a missing cosine)", "compare step6.surface_formula and step6.area_estimate; is every light sampled once?", NULL);
    cw_begin(run);
    cw_render_check(run, "step6.render fog", "step6_render_fog", "Step 6: direct light in fog (sphere light, point light)",
                    CW_SC_FOG, d, 256, cw_reference(CW_SC_FOG, FOGRT_INTEGRATOR_DIRECT, 0, 1, 3, 256), 0.0,
                    "in fog: the phase function (eq. 9) and the transmittance (eq. 8) of each shadow ray; see step6.fog_formula",
                    "in fog: a shadow ray loses exp(-sigma_t dist) (eq. 8) at a fog point and at a surface in fog too", NULL);
    cw_begin(run);
    cw_render_check(run, "step6.furnace", "step6_furnace", "Step 6: furnace: a closed white sphere emitting 0.5",
                    CW_SC_FURNACE_1, d, 16, NULL, 1.0,
                    "a closed sphere that emits 0.5 and reflects everything sees 0.5 + 0.5 = 1 in direct light: light is "
                    "lost (a missing 1/pdf, or a cosine too many?)",
                    "a closed sphere that emits 0.5 and reflects everything sees 0.5 + 0.5 = 1 in direct light: light is "
                    "made (the 1/pi of the diffuse BSDF missing, or the emission counted in the light sample too?)", NULL);
}


/* ==========================================================================================
   Step 7: Algorithm 1 with eq. 13 and Russian roulette
   ========================================================================================== */
static const cw_img *cw_path_reference(int scene, int mis, const cw_path_settings *set, int spp)
{
    return cw_reference(scene, FOGRT_INTEGRATOR_PATH, mis, set->max_depth, set->rr_depth, spp);
}

/* The noise of the student's last render (cw_student_img) against the reference's: the
   variance of one sample's luminance, summed over the image and over each region. MIS does
   not change the mean, only the variance, so this is where a missing strategy shows. */
#define CW_NOISE_RATIO 1.3        /* correct MIS: 0.985-1.00 over 12 seeds; without MIS: 2.2-103 */
static void cw_noise_check(cw_run *run, const char *name, const cw_img *ref, const char *advice)
{
    const cw_img *a = &cw_student_img;
    double sa = 0.0, sr = 0.0, worst = 0.0;
    int rx, ry, x, y, wreg = 0, pass;
    char m[500], adv[900];
    if (!a->ok || !ref || !ref->ok) { cw_emit(run, name, 0, "no image to judge (see the render check above)", "", NULL); return; }
    if (!cw_student_pass) {
        cw_emit(run, name, 0, "not judged: the noise of an image is compared only once its mean is right",
                "see the render check above, which this image failed", NULL);
        return;
    }
    for (ry = 0; ry < CW_RY; ++ry)
        for (rx = 0; rx < CW_RX; ++rx) {
            double va = 0.0, vr = 0.0;
            for (y = ry * CW_H / CW_RY; y < (ry + 1) * CW_H / CW_RY; ++y)
                for (x = rx * CW_W / CW_RX; x < (rx + 1) * CW_W / CW_RX; ++x) { va += a->svar[y * CW_W + x]; vr += ref->svar[y * CW_W + x]; }
            sa += va; sr += vr;
            if (vr > 0.0 && va / vr > worst) { worst = va / vr; wreg = ry * CW_RX + rx; }
        }
    {
        double ratio = sr > 0.0 ? sa / sr : (sa > 0.0 ? HUGE_VAL : 1.0);
        pass = ratio <= CW_NOISE_RATIO && a->rejected == 0;
        cw_fmt(m, sizeof m, "variance of one sample, summed over the image: %.3g times fogrt's (fail if > %g); the noisiest "
               "region against fogrt's: %s, %.3g times", ratio, CW_NOISE_RATIO, cw_region_name(wreg), worst);
        cw_fmt(adv, sizeof adv, "%s", advice);
    }
    cw_emit(run, name, pass, m, adv, NULL);
}

/* Single scattering along a ray in infinite fog lit by a point light, in double: with
   s = 1 - exp(-sigma_t t) (the free flight's CDF, eq. 6) the first collision is uniform in
   s, and the estimate there is albedo p_HG(mu) T(r) I / r^2 (step 6 times the albedo). Gives
   the mean and the variance of that estimate per unit intensity; flight_sigma != sigma_t
   gives the mean of an estimator that draws its free flights with flight_sigma instead. */
static void cw_single_scatter(double sigma_t, double albedo, double g, const double o[3], const double d[3],
                              const double lp[3], double flight_sigma, double *mean, double *var)
{
    const int M = 200000;
    double s1 = 0.0, s2 = 0.0;
    int i;
    for (i = 0; i < M; ++i) {
        double u = (i + 0.5) / M, t = -log1p(-u) / flight_sigma, w[3], r, mu, v;
        int c;
        for (c = 0; c < 3; ++c) w[c] = lp[c] - (o[c] + d[c] * t);
        r = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
        mu = (d[0] * w[0] + d[1] * w[1] + d[2] * w[2]) / r;
        v = albedo * cw_hg_ref(g, mu) * exp(-sigma_t * r) / (r * r);
        s1 += v; s2 += v * v;
    }
    *mean = s1 / M;
    *var = s2 / M - (s1 / M) * (s1 / M);
}

/* Fog alone, against the exact answer: max_depth 1 along three rays in the infinite fog of
   a point light (no surface in their way), 200000 estimates each, against the
   single-scattering integral. Resolves a bias of 1-2% in fog, which the images cannot.
   Steps 7 and 8 alike: a point light takes no MIS weight, so both estimators agree here. */
static void cw_fog_single(cw_run *run, const char *name, uint64_t seed0,
                          fogrt_vec3 (*radiance)(const fogrt_scene *, fogrt_vec3, fogrt_vec3, fogrt_rng *, void *))
{
    static const double rays[3][6] = {{-3.0, 1.5, -0.3, 1.0, 0.0, 0.0},         /* passes 0.5 above the light */
                                      {0.9, 0.2, 1.5, -0.3, 0.35, -0.9},        /* toward the light, past it */
                                      {1.5, 2.0, 0.5, 0.1, 1.0, 0.2}};          /* away: back-scattering only */
    const double zc = 4.15;                                  /* two-sided 1e-4 over the three rays */
    const int N = 200000;
    static cw_path_settings set;
    const fogrt_scene *s = cw_scene(CW_SC_POINT_FOG_A);
    fogrt_medium_desc med;
    char m[700], adv[800];
    double worst = 0.0, wz = 0.0, wratio = 1.0, wnoise = 1.0, wse = 0.0, ratios[3], m_sig[3], m_noal[3], m_al2[3];
    double maxnoise = 0.0, lp[3], Il;
    int k, wk = 0, nonfinite = 0;
    cw_begin(run);
    if (!s) { cw_emit(run, name, 0, "scene failed", "", NULL); return; }
    fogrt_scene_get_medium(s, &med);
    lp[0] = 0.2; lp[1] = 1.0; lp[2] = -0.3;                  /* CW_SC_POINT_FOG_A's light */
    Il = 0.2126 * 1.0 + 0.7152 * 2.0 + 0.0722 * 3.0;
    set.max_depth = 1; set.rr_depth = 1000;
    for (k = 0; k < 3; ++k) {
        double o[3], d[3], len, mean, var, sum = 0.0, sum2 = 0.0, got, se, z, bug, vb;
        fogrt_rng rng;
        int i, c;
        for (c = 0; c < 3; ++c) { o[c] = rays[k][c]; d[c] = rays[k][3 + c]; }
        len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        for (c = 0; c < 3; ++c) d[c] /= len;
        cw_single_scatter(med.sigma_t, med.albedo.x, med.g, o, d, lp, med.sigma_t, &mean, &var);
        mean *= Il; var *= Il * Il;
        cw_seed(&rng, seed0 + k);
        for (i = 0; i < N; ++i) {
            fogrt_vec3 L = radiance(s, cw_f3((float)o[0], (float)o[1], (float)o[2]), cw_v3(d[0], d[1], d[2]), &rng, &set);
            double x = cw_lum3(L);
            if (!isfinite(x)) { nonfinite++; continue; }
            sum += x; sum2 += x * x;
        }
        got = sum / N;
        vb = sum2 / N - got * got;
        se = sqrt(var / N);                                  /* the exact estimator's variance, not the student's */
        z = (got - mean) / se;
        ratios[k] = got / mean;
        cw_single_scatter(med.sigma_t, med.albedo.x, med.g, o, d, lp, med.sigma_t * med.albedo.x, &bug, &vb);
        vb = sum2 / N - got * got;
        m_sig[k] = bug * Il / mean;
        m_noal[k] = 1.0 / med.albedo.x; m_al2[k] = med.albedo.x;
        if (vb / var > maxnoise) maxnoise = vb / var;
        if (!(fabs(z) <= worst)) { worst = fabs(z); wz = z; wk = k; wratio = got / mean; wnoise = vb / var; wse = se / mean; }
    }
    {
        int pass = worst <= zc && !nonfinite && maxnoise <= CW_NOISE_MAX;
        cw_fmt(m, sizeof m, "3 rays through fog lit by a point light, max_depth 1, %d estimates each, against the single-"
               "scattering integral: worst ray %d: mean %.4f times exact (standard error %.2g%%, from the exact estimator's "
               "variance), z = %.2f (fail if |z| > %g); noise %.3g times the exact estimator's (fail if > %g)",
               N, wk + 1, wratio, 100.0 * wse, wz, zc, wnoise, CW_NOISE_MAX);
        if (nonfinite) cw_fmt(adv, sizeof adv, "%d estimates were NaN or infinite", nonfinite);
        else if (worst <= zc)
            cw_fmt(adv, sizeof adv, "right on average, but %.3g times as noisy as Algorithm 1 at max_depth 1 (a free flight, "
                   "the albedo, one light sample): is a weight divided by a pdf that the estimate does not need?", maxnoise);
        else if (cw_ratios_match(ratios, m_sig, 3, 0.01))
            cw_fmt(adv, sizeof adv, "your fog matches free flights drawn with sigma_s = albedo x sigma_t: eq. 6 draws the "
                   "distance to the next collision with sigma_t (absorption and scattering both stop the flight); the albedo "
                   "then accounts for the absorbed part");
        else if (cw_ratios_match(ratios, m_noal, 3, 0.01))
            cw_fmt(adv, sizeof adv, "too bright by 1/albedo in fog: multiply the throughput by the medium's albedo at each "
                   "fog collision (Algorithm 1)");
        else if (cw_ratios_match(ratios, m_al2, 3, 0.01))
            cw_fmt(adv, sizeof adv, "too dark by the albedo in fog: the albedo is applied twice (at the collision and in the "
                   "light sample?)");
        else
            cw_fmt(adv, sizeof adv, "%s by a factor %.4f in fog, at the first vertex: a free flight with sigma_t (eq. 6), the "
                   "throughput times the albedo, then the light sample of step 6: p_HG(mu) (eq. 9) I/r^2 T (eq. 8), mu the "
                   "cosine between the ray's direction and wi", wz > 0 ? "too bright" : "too dark", wz > 0 ? wratio : 1.0 / wratio);
        cw_emit(run, name, pass, m, adv, NULL);
    }
}
static void cw_step7_fog_single(const cw_fns *f, cw_run *run) { cw_fog_single(run, "step7.fog_single", 760, f->path_radiance); }

static void cw_step7(const cw_fns *f, cw_run *run)
{
    static cw_path_settings set;
    fogrt_render_desc d = fogrt_render_paper_defaults();
    char dark[600], bright[600];
    int direct_ok, bounces_ok;
    d.radiance = f->path_radiance;
    d.user_data = &set;

    set.max_depth = 1; set.rr_depth = 1000;
    cw_begin(run);
    direct_ok = cw_render_check(run, "step7.direct", "step7_direct", "Step 7: max_depth 1 in fog: camera ray and direct light",
        CW_SC_FOG, d, 256, cw_path_reference(CW_SC_FOG, 0, &set, 256), 0.0,
        "with max_depth = 1 the image is the camera ray's emission plus light sampling at the first vertex (your step 6 "
        "code), times the fog's albedo at a collision: is light sampling done at the first vertex, and the albedo applied once?",
        "with max_depth = 1 the image is the camera ray's emission plus light sampling at the first vertex: is emission "
        "counted on rays after a bounce too (light sampling already counts it)? Is the albedo applied at fog collisions?", NULL);

    cw_step7_fog_single(f, run);

    set.max_depth = 6; set.rr_depth = 1000;
    cw_begin(run);
    cw_fmt(dark, sizeof dark, "without the roulette (rr_depth = 1000), up to 6 bounces, light is lost: %s",
           direct_ok ? "the first vertex is right (step7.direct), so look at what a bounce multiplies the throughput by: eq. 13's "
           "f cos / pdf at a surface (the sample's weight, with the pdf divided once; cos of the NEW direction wi and the "
           "normal, not of the ray that arrived), 1 after HG sampling, the albedo at a fog collision (once); and "
           "max_depth counted as scattering events" : "start with step7.direct");
    cw_fmt(bright, sizeof bright, "without the roulette (rr_depth = 1000), up to 6 bounces, light is made: %s",
           direct_ok ? "is emission counted on rays after a bounce (light sampling already counts it)? Is the albedo "
           "forgotten at a fog collision, or the pdf not divided? After HG sampling the weight is p_HG / pdf = 1, no division "
           "by the phase function's pdf; at a surface eq. 13's cosine is the new direction wi's, not the arriving ray's"
           : "start with step7.direct");
    bounces_ok = cw_render_check(run, "step7.bounces", "step7_bounces", "Step 7: up to 6 bounces in fog, no roulette",
        CW_SC_FOG, d, 128, cw_path_reference(CW_SC_FOG, 0, &set, 128), 0.0, dark, bright, NULL);


    /* Inside a closed white sphere every light sample returns the same 0.5 and every bounce
       keeps the throughput at 1, so with 8 bounces and no roulette each path gives
       0.5 + 8 x 0.5 = 4.5 up to the facets, nearly without noise: a depth counted another way
       shows in the mean, a roulette played before rr_depth in the noise. */
    set.max_depth = 8; set.rr_depth = 1000;
    cw_begin(run);
    {
        const cw_img *ref = cw_path_reference(CW_SC_FURNACE_1, 0, &set, 16);
        cw_noise_hint = "without the roulette this estimator has almost no noise here (only the facets'): with "
            "rr_depth = 1000 no path may end by the coin flip (the contract: roulette only once more than rr_depth "
            "scattering events happened). Is the roulette played before rr_depth events?";
        cw_render_check(run, "step7.depth", "step7_depth", "Step 7: 8 bounces in a closed white sphere emitting 0.5, no roulette",
            CW_SC_FURNACE_1, d, 16, ref, 0.0,
            "every vertex's light sample adds 0.5 here, 0.5 + 8 x 0.5 in all: are fewer than max_depth = 8 light samples "
            "taken (max_depth counts scattering events after the camera ray; light sampling happens while fewer than "
            "max_depth events came before)?",
            "every vertex's light sample adds 0.5 here, 0.5 + 8 x 0.5 in all: is light sampled at more than 8 vertices, "
            "or emission counted on bounced rays?", NULL);
        cw_noise_hint = NULL;
    }

    set.max_depth = -1; set.rr_depth = 0;
    cw_begin(run);
    cw_fmt(dark, sizeof dark, "%s", bounces_ok ? "right without the roulette (step7.bounces), too dark with it from the "
           "first bounce on: after surviving the coin flip with probability q, divide the throughput by q (missing 1/q?), "
           "so that the path's expected value is unchanged" : "start with step7.bounces");
    cw_fmt(bright, sizeof bright, "%s", bounces_ok ? "right without the roulette (step7.bounces), too bright with it: is "
           "the throughput divided by q when the path does not survive the coin flip, or by q twice?" : "start with step7.bounces");
    cw_render_check(run, "step7.roulette", "step7_roulette", "Step 7: no depth limit, roulette from the first bounce (fog)",
        CW_SC_FOG, d, 128, cw_path_reference(CW_SC_FOG, 0, &set, 128), 0.0, dark, bright, NULL);

    set.max_depth = -1; set.rr_depth = 3;
    cw_begin(run);
    cw_render_check(run, "step7.box", "step7_box", "Step 7: global illumination in the box, no fog",
        CW_SC_BOX, d, 64, cw_path_reference(CW_SC_BOX, 0, &set, 64), 0.0,
        "light is lost at the bounces between the walls: eq. 13's weight f cos / pdf (for the diffuse BSDF it is the "
        "reflectance; the cosine is the new direction wi's, not the arriving ray's), and 1/q after the roulette",
        "light is made at the bounces: emission counted on bounced rays as well as by light sampling, or the pdf not "
        "divided, or eq. 13's cosine taken from the ray that arrived instead of the new direction wi (f cos / pdf is the "
        "reflectance for cosine-weighted diffuse sampling)", NULL);

    set.max_depth = -1; set.rr_depth = 1;
    cw_begin(run);
    cw_render_check(run, "step7.furnace", "step7_furnace", "Step 7: furnace: a closed sphere emitting 0.5, reflecting half",
        CW_SC_FURNACE_H, d, 32, NULL, 1.0,
        "walls that emit 0.5 and reflect half are seen at 0.5 (1 + 1/2 + 1/4 + ...) = 1: light is lost over long paths "
        "(missing 1/q after the roulette? the reflectance applied twice?)",
        "walls that emit 0.5 and reflect half are seen at 0.5 (1 + 1/2 + 1/4 + ...) = 1: light is made (emission counted "
        "by bounced rays and by light sampling both? a missing 1/pi?)", NULL);
}


/* ==========================================================================================
   Step 8: next-event estimation with MIS (power heuristic)
   ========================================================================================== */
static void cw_step8_weights(const cw_fns *f, cw_run *run)
{
    static const float p[9] = {1e-6f, 0.01f, 0.1f, 0.3f, 1.0f, 2.5f, 10.0f, 300.0f, 1e5f};
    char m[400], adv[500];
    double worst = 0.0, wa = 0.0, wb = 0.0, got = 0.0, sum_bad = 0.0, balance = 0.0;
    int i, j, n = 0, nbal = 0, edge_bad = 0;
    cw_begin(run);
    for (i = 0; i < 9; ++i)
        for (j = 0; j < 9; ++j) {
            double a = p[i], b = p[j], ref = a * a / (a * a + b * b), w = f->mis_weight(p[i], p[j]);
            double w2 = f->mis_weight(p[j], p[i]), err = fabs(w - ref) / (1e-5 + 1e-5 * ref);
            if (!isfinite(w)) err = HUGE_VAL;
            if (!(err <= worst)) { worst = err; wa = a; wb = b; got = w; }
            sum_bad = fmax(sum_bad, fabs(w + w2 - 1.0));
            if (fabs(w - a / (a + b)) < 1e-4) nbal++;
            n++;
        }
    balance = (double)nbal / n;
    if (!(f->mis_weight(0.0f, 1.0f) == 0.0f) || !(fabs(f->mis_weight(1.0f, 0.0f) - 1.0) < 1e-6)) edge_bad = 1;
    {
        int pass = worst <= 1.0 && !edge_bad;
        cw_fmt(m, sizeof m, "81 pairs of pdfs from 1e-6 to 1e5: largest error at (%g, %g): %.7g, power heuristic %.7g "
               "(tolerance 1e-5); w(a, b) + w(b, a) - 1 at most %.2g; w(0, 1) = %g, w(1, 0) = %g", wa, wb, got,
               wa * wa / (wa * wa + wb * wb), sum_bad, f->mis_weight(0.0f, 1.0f), f->mis_weight(1.0f, 0.0f));
        if (sum_bad > 1e-4)
            cw_fmt(adv, sizeof adv, "the two weights of one direction do not sum to one (up to %.3g off): MIS is then "
                   "biased; the power heuristic is a^2 / (a^2 + b^2)", sum_bad);
        else if (balance > 0.9)
            cw_fmt(adv, sizeof adv, "this is the balance heuristic a / (a + b): unbiased too, but the kit asks for the "
                   "power heuristic a^2 / (a^2 + b^2), as fogrt uses");
        else if (edge_bad)
            cw_fmt(adv, sizeof adv, "a strategy that cannot produce the direction (pdf_this = 0) gets weight 0, and the only "
                   "one that can (pdf_other = 0) gets 1 (no NaN from 0/0)");
        else
            cw_fmt(adv, sizeof adv, "the power heuristic: pdf_this^2 / (pdf_this^2 + pdf_other^2), written so that a "
                   "pdf of 1e5 does not overflow when squared in float");
        cw_emit(run, "step8.weights", pass, m, adv, NULL);
    }
}

static void cw_step8(const cw_fns *f, cw_run *run)
{
    static cw_path_settings set;
    fogrt_render_desc d = fogrt_render_paper_defaults();
    const char *bright = "light is counted more than once: each area light is found by light sampling AND by rays that hit "
        "it; weight the light sample with w(ls.pdf, pdf of the BSDF/phase for wi) and the emission a bounced ray finds "
        "with w(pdf of that ray's direction, fogrt_scene_light_pdf(scene, x, hit, sf)), so that the two weights sum to one "
        "(emission counted at full weight?)";
    const char *dark = "light is missing: a weight applied on one side only (the light sample weighted but the emission "
        "bounced rays find not counted?), or the two weights computed from different pdfs; point lights take weight 1";
    cw_step8_weights(f, run);
    cw_begin(run);
    cw_fog_single(run, "step8.fog_single", 770, f->mis_radiance);
    d.radiance = f->mis_radiance;
    d.user_data = &set;
    set.max_depth = -1; set.rr_depth = 3;
    cw_begin(run);
    cw_render_check(run, "step8.box", "step8_box", "Step 8: MIS in the box, no fog (area and point light)",
        CW_SC_BOX, d, 64, cw_path_reference(CW_SC_BOX, 1, &set, 64), 0.0, dark, bright, NULL);
    cw_begin(run);
    cw_render_check(run, "step8.fog", "step8_fog", "Step 8: MIS in fog (area light, point light)",
        CW_SC_FOG_AREA, d, 128, cw_path_reference(CW_SC_FOG_AREA, 1, &set, 128), 0.0, dark, bright, NULL);
    /* the noise: no roulette (its q is the student's choice and changes the variance too) */
    set.max_depth = 4; set.rr_depth = 1000;
    cw_begin(run);
    {
        const cw_img *ref = cw_path_reference(CW_SC_LIGHT_WALL, 1, &set, 64);
        cw_render_check(run, "step8.wall", "step8_wall", "Step 8: a floor by an emitting wall, in fog (up to 4 bounces)",
            CW_SC_LIGHT_WALL, d, 64, ref, 0.0, dark, bright, NULL);
        cw_begin(run);
        cw_noise_check(run, "step8.noise", ref,
            "your image is right on average but much noisier than MIS makes it: near the emitting wall light sampling "
            "alone is noisy, and BSDF sampling (phase sampling in fog) finds that light with little noise. Is the "
            "strategy of BSDF and phase sampling missing, the emission a bounced ray hits left out (step 7's "
            "estimator)? Count it with w(pdf of the ray's direction, fogrt_scene_light_pdf(scene, x, hit, sf)), and "
            "weight each light sample with w(ls.pdf, the BSDF's or phase function's pdf of wi) (eq. 3, power heuristic)");
    }
    set.max_depth = -1; set.rr_depth = 1;
    cw_begin(run);
    cw_render_check(run, "step8.furnace", "step8_furnace", "Step 8: furnace: a sphere emitting 0.5, reflecting half, fog of albedo 1",
        CW_SC_FURNACE_FOG, d, 32, NULL, 1.0, dark, bright, NULL);
}

/* ==========================================================================================
   Dispatch
   ========================================================================================== */
static inline const char *cw_step_title(int step)
{
    switch (step) {
    case 1: return "free-flight sampling (section 3.1, eq. 4-6)";
    case 2: return "transmittance (section 3.2, eq. 7-8)";
    case 3: return "Henyey-Greenstein phase function (section 3.3, eq. 9-12)";
    case 4: return "BVH split: SAH and the volume heuristic (section 2.1, eq. 1-2)";
    case 5: return "BSDF sampling: diffuse, mirror, glass with Schlick (sections 2.2, 4.2)";
    case 6: return "direct lighting by light sampling, surface and fog (section 2.3, eq. 3)";
    case 7: return "Algorithm 1 with eq. 13 and Russian roulette (section 3.4)";
    case 8: return "next-event estimation with MIS, surfaces and fog (sections 2.3, 3.4)";
    case 9: return "equiangular sampling toward a point light (bonus)";
    default: return NULL;
    }
}

/* Runs one step's checks; returns the number that failed (-1: no such step). */
static int cw_run_step(int step, const cw_fns *f, cw_run *run)
{
    int before = run->count, passed = run->passed;
    switch (step) {
    case 1: cw_step1(f, run); break;
    case 2: cw_step2(f, run); break;
    case 3: cw_step3(f, run); break;
    case 4: cw_step4(f, run); break;
    case 5: cw_step5(f, run); break;
    case 6: cw_step6(f, run); break;
    case 7: cw_step7(f, run); break;
    case 8: cw_step8(f, run); break;
    case 9: cw_step9(f, run); break;
    default: return -1;
    }
    return (run->count - before) - (run->passed - passed);
}

#endif
