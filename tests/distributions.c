/* distributions.c - the distribution checks of the test suite, made visible
   (`make distributions`, docs/distributions.md).

   For every sampler that tests/test_sampling.c and tests/test_bsdf_stats.c check, this
   program draws samples with a fixed seed, bins them, computes the expected count of every
   bin from the model (an exact CDF or cell probability, in double), and writes one small
   PNG with three panels: observed | expected | residual (observed - expected) / sqrt(var).
   The chi-square statistic, its degrees of freedom and the p-value come from tests/stats.h,
   the same code the suite uses, and are written into docs/distributions.md between the
   markers <!-- BEGIN generated --> and <!-- END generated -->. Two negative controls (a
   sampler with a known bug, and a model with the wrong sign convention) are drawn the same
   way and must be rejected.
   Usage: distributions OUT_DIR MARKDOWN_FILE   (run from the repository root)
   Exit status 1 if a positive check is rejected or a negative control is not.            */
#define _POSIX_C_SOURCE 200809L   /* open_memstream */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#include "stats.h"
#include "examples/stb_write.h"           /* stb_image_write, its warnings silenced */
#include "examples/plotfont.h"

#define N_SAMPLES 200000
#define MAX_CELLS 4096
#define MAX_ROWS 64

/* One check: a table of rows x cols cells (rows = 1: a 1-D histogram, drawn as bars). */
typedef struct check {
    char name[48], title[96], params[320], model[224];
    int rows, cols;
    char xq[96], yq[96], unit[64];   /* the axes' quantities and the density's unit */
    double x0, x1;                   /* the x axis (columns or bins) from x0 to x1 */
    double redge[MAX_ROWS + 1];      /* 2-D: the y value of each row's top edge, then the bottom */
    double obs[MAX_CELLS], exp_[MAX_CELLS], var[MAX_CELLS];   /* var 0: use exp_ */
    bool negative, binomial;
    double chi2, p;
    int dof;
    bool pass;
} check;

static check C;                       /* the check being filled (one at a time) */
static FILE *md_out;                  /* the generated part of the index page */
static const char *out_dir;
static int failures;

/* ---- drawing: one PNG per check that stands alone on a projector ----
   A header (title, verdict, sampler and model), then for a 1-D check two plots (the
   density observed as bars with the model's as a line; the residual of every bin) and for
   a 2-D check three heat maps (observed, expected, residual) with their colour scales.
   Every plot has its axes, tick labels and the quantity with its unit. */
#define TXT 2                 /* text scale: 10 x 14 pixel glyphs */
#define CHAR_W (PF_ADVANCE * TXT)
static const unsigned char INK[3] = {30, 30, 30}, GOOD[3] = {0, 120, 60}, BAD[3] = {200, 30, 30};

/* The glass check's angles (its bars are these, not a continuous x). */
static const double glass_cos[6] = {0.95, 0.8, 0.6, 0.4, 0.2, 0.05};

/* A dark-to-bright ramp (black, purple, orange, pale yellow) for densities. */
static void ramp(double v, unsigned char c[3])
{
    static const double key[4][3] = {{0.02, 0.02, 0.06}, {0.45, 0.10, 0.50}, {0.95, 0.50, 0.15}, {1.0, 0.97, 0.75}};
    double x = fmin(fmax(v, 0.0), 1.0) * 3.0;
    int i = x >= 3.0 ? 2 : (int)x, k;
    for (k = 0; k < 3; ++k) c[k] = (unsigned char)(255.0 * (key[i][k] + (x - i) * (key[i + 1][k] - key[i][k])) + 0.5);
}
/* Residual colours: blue (-4 and below), white (0), red (+4 and above); green = impossible. */
static void diverging(double r, unsigned char c[3])
{
    double a = fmin(fabs(r) / 4.0, 1.0);
    if (r == HUGE_VAL) { c[0] = 25; c[1] = 230; c[2] = 50; return; }
    c[0] = (unsigned char)(255.0 * (r < 0 ? 1.0 - a : 1.0) + 0.5);
    c[1] = (unsigned char)(255.0 * (1.0 - a) + 0.5);
    c[2] = (unsigned char)(255.0 * (r > 0 ? 1.0 - a : 1.0) + 0.5);
}
static double residual(int i)
{
    double v = C.binomial || C.var[i] > 0.0 ? C.var[i] : C.exp_[i];
    if (v <= 0.0) return C.obs[i] != C.exp_[i] ? HUGE_VAL : 0.0;   /* a certain outcome: exact */
    return (C.obs[i] - C.exp_[i]) / sqrt(v);
}
/* What a bar or cell shows: samples per unit of the axes (per unit of x, per steradian, ...),
   or for the glass check the fraction of samples that reflected. */
static double cell_size(int i)
{
    double dx = (C.x1 - C.x0) / C.cols;
    if (C.binomial) return 1.0;
    return C.rows > 1 ? dx * fabs(C.redge[i / C.cols] - C.redge[i / C.cols + 1]) : dx;
}
static double shown(const double *v, int i)
{
    return C.binomial ? v[i] / (N_SAMPLES / 10) : v[i] / (N_SAMPLES * cell_size(i));
}
static void tick_label(double v, char *buf, size_t size)
{
    if (fabs(v) < 1e-12) v = 0.0;
    snprintf(buf, size, "%.3g", v);
}

/* Text wrapped to `chars` per line from (x, y); returns the y under the last line. */
static int wrapped(pf_canvas *c, int x, int y, const char *text, int chars, const unsigned char col[3])
{
    char lines[16][256], clean[512];
    int n, k, j = 0;
    for (k = 0; text[k] && j < (int)sizeof clean - 1; ++k) if (text[k] != '`') clean[j++] = text[k];   /* Markdown code marks */
    clean[j] = '\0';
    n = pf_wrap(clean, chars, lines, 16);
    for (k = 0; k < n; ++k, y += PF_LINE * TXT) pf_text(c, x, y, lines[k], TXT, col);
    return y;
}

/* Tick values at a 1-2-5 step, 3 to 8 of them, between lo and hi (in either order). */
static int nice_ticks(double lo, double hi, double *t, int max)
{
    double a = fmin(lo, hi), b = fmax(lo, hi), span = b - a, step, v;
    int n = 0;
    if (!(span > 0.0)) { t[0] = a; return 1; }
    step = pow(10.0, floor(log10(span / 4.0)));
    if (span / step > 8.0) step *= 2.0;
    if (span / step > 8.0) step *= 2.5;
    for (v = ceil(a / step - 1e-9) * step; v <= b + 1e-9 * span && n < max; v += step) t[n++] = fabs(v) < 1e-9 * step ? 0.0 : v;
    return n;
}

/* x axis under a plot at (px, py, pw, ph): ticks over C.x0..C.x1 (the glass check: its
   angles, at every other bar), and the quantity centred below. */
static void x_axis(pf_canvas *c, int px, int py, int pw, int ph, const char *quantity)
{
    double t[16], at;
    int k, n = C.binomial ? 6 : nice_ticks(C.x0, C.x1, t, 16);
    char buf[32];
    for (k = 0; k < n; ++k) {
        int x;
        if (C.binomial) {
            at = (2 * k + 0.5) / 12.0;
            tick_label(glass_cos[(2 * k) % 6] * (k < 3 ? 1.0 : -1.0), buf, sizeof buf);
        } else {
            at = (t[k] - C.x0) / (C.x1 - C.x0);
            tick_label(t[k], buf, sizeof buf);
        }
        x = px + (int)(at * (pw - 1) + 0.5);
        pf_rect(c, x, py + ph, 1, 6, INK);
        pf_text_at(c, x, py + ph + 9, buf, TXT, INK, 1);
    }
    pf_text_at(c, px + pw / 2, py + ph + 9 + PF_LINE * TXT + 2, quantity, TXT, INK, 1);
}
/* y axis left of a plot: the value vb sits at height fb and vt at ft (heights 0 bottom,
   1 top, linear between); ticks at nice values in that range. */
static void y_axis(pf_canvas *c, int px, int py, int ph, double vb, double fb, double vt, double ft,
                   const char *quantity, int margin)
{
    double t[16];
    int k, n = nice_ticks(vb, vt, t, 16);
    char buf[32];
    for (k = 0; k < n; ++k) {
        double f = fb + (t[k] - vb) / (vt - vb) * (ft - fb);
        int y = py + ph - 1 - (int)(f * (ph - 1) + 0.5);
        pf_rect(c, px - 6, y, 6, 1, INK);
        tick_label(t[k], buf, sizeof buf);
        pf_text_at(c, px - 9, y - PF_GLYPH_H * TXT / 2 + 2, buf, TXT, INK, 2);
    }
    pf_text_up(c, px - margin, py + ph / 2, quantity, TXT, INK);
}
/* A vertical colour scale at (x, y), h high: lo at the bottom, hi at the top. */
static void colour_bar(pf_canvas *c, int x, int y, int h, double lo, double hi, bool residual_scale, const char *quantity)
{
    double t[16];
    int j, n = nice_ticks(lo, hi, t, 16), widest = 0;
    char buf[32];
    for (j = 0; j < h; ++j) {
        unsigned char col[3];
        double v = lo + (hi - lo) * (h - 1 - j) / (h - 1);
        if (residual_scale) diverging(v, col); else ramp((v - lo) / (hi - lo), col);
        pf_rect(c, x, y + j, 18, 1, col);
    }
    pf_frame(c, x, y, 18, h, INK);
    for (j = 0; j < n; ++j) {
        int yy = y + h - 1 - (int)((t[j] - lo) / (hi - lo) * (h - 1) + 0.5);
        tick_label(t[j], buf, sizeof buf);
        pf_rect(c, x + 18, yy, 4, 1, INK);
        pf_text(c, x + 25, yy - PF_GLYPH_H * TXT / 2 + 2, buf, TXT, INK);
        if (pf_text_width(buf, TXT) > widest) widest = pf_text_width(buf, TXT);
    }
    pf_text_up(c, x + 25 + widest + 6, y + h / 2, quantity, TXT, INK);
}

/* 1-D: bars of the observed density with the expected one as a step line; and the residuals. */
static int draw_1d(pf_canvas *c, int top)
{
    const int pw = 460, ph = 260, left = 110, block = 600;
    double ytop = 0.0;
    int i, p;
    for (i = 0; i < C.cols; ++i) ytop = fmax(ytop, fmax(shown(C.obs, i), shown(C.exp_, i)));
    ytop *= 1.08;
    for (p = 0; p < 2; ++p) {
        int px = p * block + left, py = top + PF_LINE * TXT + 6;
        pf_text(c, px, top, p == 0 ? "observed (bars) and expected (line)" : "residual (observed - expected) / sd", TXT, INK);
        pf_rect(c, px, py, pw, ph, PF_WHITE);
        for (i = 0; i < C.cols; ++i) {
            int xa = px + i * pw / C.cols, xb = px + (i + 1) * pw / C.cols - 1;
            if (p == 0) {
                int hb = (int)(shown(C.obs, i) / ytop * (ph - 1) + 0.5), he = (int)(shown(C.exp_, i) / ytop * (ph - 1) + 0.5);
                pf_rect(c, xa + 1, py + ph - hb, xb - xa, hb, PF_BLUE);
                pf_rect(c, xa, py + ph - 1 - he - 1, xb - xa + 1, 3, PF_ORANGE);
            } else {
                double r = residual(i), rv = r == HUGE_VAL ? 4.0 : fmax(-4.0, fmin(4.0, r));
                int y0 = py + ph / 2, y1 = py + ph / 2 - (int)(rv / 4.0 * (ph / 2 - 1));
                unsigned char col[3];
                diverging(r, col);
                pf_rect(c, xa + 1, y1 < y0 ? y1 : y0, xb - xa, abs(y1 - y0) + 1, col);
                pf_frame(c, xa + 1, y1 < y0 ? y1 : y0, xb - xa, abs(y1 - y0) + 1, PF_GREY);
            }
        }
        if (p == 1) {
            pf_line(c, px, py + ph / 2, px + pw - 1, py + ph / 2, INK, 1, 0);
            pf_line(c, px, py + ph / 4, px + pw - 1, py + ph / 4, PF_GREY, 1, 5);
            pf_line(c, px, py + 3 * ph / 4, px + pw - 1, py + 3 * ph / 4, PF_GREY, 1, 5);
        }
        pf_frame(c, px - 1, py - 1, pw + 2, ph + 2, INK);
        x_axis(c, px, py, pw, ph, C.xq);
        if (p == 0) y_axis(c, px, py, ph, 0.0, 0.0, ytop, 1.0, C.unit, left - 8);
        else y_axis(c, px, py, ph, -4.0, 0.0, 4.0, 1.0, "residual [sd]", left - 8);
    }
    {   /* the legend, under the left plot */
        int y = top + PF_LINE * TXT + 6 + ph + 9 + 2 * PF_LINE * TXT + 8, x = left;
        pf_rect(c, x, y, 24, 14, PF_BLUE);
        pf_text(c, x + 32, y, "observed", TXT, INK);
        x += 32 + pf_text_width("observed", TXT) + 30;
        pf_rect(c, x, y + 5, 24, 3, PF_ORANGE);
        pf_text(c, x + 32, y, "expected (model)", TXT, INK);
        pf_text(c, block + left, y, "dashed: +-2 sd; beyond +-4 cut off", TXT, PF_GREY);
        return y + PF_LINE * TXT + 10;
    }
}

/* 2-D: observed and expected heat maps on one colour scale, and the residual map. */
static int draw_2d(pf_canvas *c, int top)
{
    const int pw = 300, ph = 240, left = 110, gap = 44, bar = 120;
    const int px[3] = {left, left + pw + gap, left + 2 * pw + gap + bar + gap};
    const char *head[3] = {"observed", "expected (model)", "residual (obs - exp) / sd"};
    double dtop = 0.0;
    int i, p, x, y, py = top + PF_LINE * TXT + 6;
    for (i = 0; i < C.rows * C.cols; ++i) dtop = fmax(dtop, fmax(shown(C.obs, i), shown(C.exp_, i)));
    for (p = 0; p < 3; ++p) {
        pf_text(c, px[p], top, head[p], TXT, INK);
        for (y = 0; y < ph; ++y)
            for (x = 0; x < pw; ++x) {
                int cell = (y * C.rows / ph) * C.cols + x * C.cols / pw;
                unsigned char col[3];
                if (p < 2) ramp(shown(p == 0 ? C.obs : C.exp_, cell) / dtop, col);
                else diverging(residual(cell), col);
                pf_put(c, px[p] + x, py + y, col);
            }
        pf_frame(c, px[p] - 1, py - 1, pw + 2, ph + 2, INK);
        x_axis(c, px[p], py, pw, ph, C.xq);
    }
    /* rows of equal steps from the top; a cone's grid ends in one row that holds everything
       below it, left out of the scale and named in the label */
    if (fabs((C.redge[C.rows] - C.redge[C.rows - 1]) - (C.redge[1] - C.redge[0])) < 1e-9) {
        y_axis(c, px[0], py, ph, C.redge[C.rows], 0.0, C.redge[0], 1.0, C.yq, left - 8);
    } else {
        char q[128];
        snprintf(q, sizeof q, "%s (last row to %g)", C.yq, C.redge[C.rows]);
        y_axis(c, px[0], py, ph, C.redge[C.rows - 1], 1.0 / C.rows, C.redge[0], 1.0, q, left - 8);
    }
    colour_bar(c, px[1] + pw + 14, py, ph, 0.0, dtop, false, C.unit);
    colour_bar(c, px[2] + pw + 14, py, ph, -4.0, 4.0, true, "[sd]");
    pf_text(c, px[2], py + ph + 9 + 2 * PF_LINE * TXT + 8, "green: samples where p = 0", TXT, PF_GREY);
    return py + ph + 9 + 3 * PF_LINE * TXT + 14;
}

/* The whole picture: header, plots; written to OUT_DIR/name.png. */
static void draw_and_write(bool rejected, const char *path)
{
    const int width = C.rows > 1 ? 1330 : 1200, chars = (width - 20) / CHAR_W;
    pf_canvas c = pf_canvas_make(width, 900, PF_WHITE), out;
    char line[512];
    int y = 12, bottom;
    snprintf(line, sizeof line, "%s%s", C.negative ? "Negative control: " : "", C.title);
    if (pf_text_width(line, 3) <= width - 20) { pf_text(&c, 10, y, line, 3, PF_BLACK); y += PF_LINE * 3; }
    else y = wrapped(&c, 10, y, line, chars, PF_BLACK);
    snprintf(line, sizeof line, "chi2 = %.2f, dof = %d, p = %.3g: %s at alpha' = %.3g%s", C.chi2, C.dof, C.p,
             rejected ? "rejected" : "accepted", stats_alpha(),
             C.negative ? (rejected ? " (as a negative control must be)" : " (NEGATIVE CONTROL NOT REJECTED)") : "");
    y = wrapped(&c, 10, y, line, chars, C.pass ? GOOD : BAD);
    snprintf(line, sizeof line, "%d samples. %s.", N_SAMPLES, C.params);
    y = wrapped(&c, 10, y + 4, line, chars, PF_GREY);
    snprintf(line, sizeof line, "Model: %s.", C.model);
    y = wrapped(&c, 10, y, line, chars, PF_GREY);
    bottom = C.rows > 1 ? draw_2d(&c, y + 14) : draw_1d(&c, y + 14);
    if (bottom > c.h) bottom = c.h;   /* a caption longer than any today's: cut, not overrun */
    out = pf_canvas_make(width, bottom, PF_WHITE);   /* cropped to what was drawn */
    memcpy(out.rgb, c.rgb, (size_t)3 * (size_t)width * (size_t)bottom);
    if (!stbi_write_png(path, out.w, out.h, 3, out.rgb, out.w * 3)) {
        fprintf(stderr, "distributions: could not write %s\n", path);
        exit(1);
    }
    pf_canvas_free(&c); pf_canvas_free(&out);
}

/* Scores the current check, draws it, writes its PNG and its section of the index page. */
static void finish(void)
{
    char path[512];
    double alpha = stats_alpha();
    bool rejected;
    if (C.binomial) {   /* independent binomials: chi2 = sum z^2, dof = the random ones */
        int i;
        bool impossible = false;
        C.chi2 = 0.0; C.dof = 0;
        for (i = 0; i < C.cols; ++i) {
            if (C.var[i] <= 0.0) { impossible |= C.obs[i] != C.exp_[i]; continue; }   /* F = 0 or 1 */
            C.chi2 += residual(i) * residual(i);
            ++C.dof;
        }
        C.p = impossible ? 0.0 : stats_chi2_pvalue(C.chi2, C.dof);
    } else {
        stats_chi2_result r = stats_chi2(C.obs, C.exp_, C.rows * C.cols);
        C.chi2 = r.chi2; C.dof = r.dof; C.p = r.p_value;
    }
    rejected = C.p < alpha || C.dof < 1;
    C.pass = C.negative ? rejected : !rejected;
    if (!C.pass) ++failures;
    snprintf(path, sizeof path, "%s/%s.png", out_dir, C.name);
    draw_and_write(rejected, path);
    printf("%-24s chi2 = %10.2f  dof = %4d  p = %-10.4g %s\n", C.name, C.chi2, C.dof, C.p,
           C.negative ? (rejected ? "rejected (negative control: as it must be)" : "NOT REJECTED (negative control failed)")
                      : (rejected ? "REJECTED" : "accepted"));
    fprintf(md_out, "### %s%s\n\n![%s: observed, expected, residual](distributions/%s.png)\n\n",
            C.negative ? "Negative control: " : "", C.title, C.title, C.name);
    fprintf(md_out, "%s. Model: %s. %d samples.  \n**chi2 = %.2f, dof = %d, p = %.3g**: %s at alpha' = %.3g%s.\n\n",
            C.params, C.model, N_SAMPLES, C.chi2, C.dof, C.p,
            rejected ? "rejected" : "accepted", alpha,
            C.negative ? (rejected ? " (a negative control must be rejected: the test sees this bug)"
                                   : " (**the negative control was not rejected: the test has lost its power**)") : "");
}

static void start(const char *name, const char *title, int rows, int cols)
{
    memset(&C, 0, sizeof C);
    snprintf(C.name, sizeof C.name, "%s", name);
    snprintf(C.title, sizeof C.title, "%s", title);
    C.rows = rows; C.cols = cols;
}

/* ---- the samplers ---- */
/* HG CDF of mu = cos(d, wi), with 1 + g^2 - 2 g mu written as (1 - g)^2 + 2 g (1 - mu). */
static double hg_cdf(double g, double one_minus_mu)
{
    double base;
    if (fabs(g) < 1e-9) return 1.0 - 0.5 * one_minus_mu;
    base = g >= 0 ? (1 - g) * (1 - g) + 2 * g * one_minus_mu : (1 + g) * (1 + g) - 2 * g * (2.0 - one_minus_mu);
    return (1 - g * g) / (2 * g) * (1.0 / sqrt(base) - 1.0 / (1 + g));
}

/* model_g != g: a negative control (the model of the wrong sign convention). */
static void check_hg(double g, double model_g, const char *name)
{
    const int bins = 40;
    const double lo = -6.0, hi = log10(2.0);   /* log bins: log10 of the distance from the peak */
    const bool linear = fabs(g) < 0.3, back = g < 0.0;   /* which way the peak lies */
    fogrt_rng rng;
    fogrt_vec3 wo = {0.3f, -0.5f, 0.81240384f};       /* generic, unit */
    int i;
    start(name, "", 1, bins);
    C.negative = model_g != g;
    if (C.negative) snprintf(C.title, sizeof C.title, "Henyey-Greenstein g = %g against the model of g = %g (sign flipped)", g, model_g);
    else snprintf(C.title, sizeof C.title, "Henyey-Greenstein, g = %g", g);
    if (linear)
        snprintf(C.params, sizeof C.params, "`fogrt_sample_hg`, wo = (0.3, -0.5, 0.812), %d equal bins of cos theta "
                 "(theta from d = -wo) from -1 (left: backward) to 1 (right: forward)", bins);
    else
        snprintf(C.params, sizeof C.params, "`fogrt_sample_hg`, wo = (0.3, -0.5, 0.812), %d bins of log10(1 %s cos theta) "
                 "(theta from d = -wo: the distance from the %s peak) from -6 (left; the first bin from 0) to log10(2) (right)",
                 bins, back ? "+" : "-", back ? "backward" : "forward");
    C.x0 = linear ? -1.0 : lo; C.x1 = linear ? 1.0 : hi;
    if (linear) snprintf(C.xq, sizeof C.xq, "cos theta (theta from d = -wo)");
    else snprintf(C.xq, sizeof C.xq, "log10(1 %s cos theta), 1st bin: -inf", back ? "+" : "-");
    snprintf(C.unit, sizeof C.unit, "density [per unit of x]");
    snprintf(C.model, sizeof C.model, "the exact HG CDF in cos theta for g = %g, in double%s", model_g,
             C.negative ? " (wrong on purpose: mu measured from wo instead of d = -wo)" : "");
    fogrt_rng_seed(&rng, 1401, (uint64_t)(g * 1000 + 5000));
    for (i = 0; i < N_SAMPLES; ++i) {
        float pdf, u1 = fogrt_rng_float(&rng), u2 = fogrt_rng_float(&rng);
        fogrt_vec3 w = fogrt_sample_hg((float)g, wo, u1, u2, &pdf);
        double mu = -((double)w.x * wo.x + (double)w.y * wo.y + (double)w.z * wo.z), x, b;
        double s2 = fmax((double)w.x * w.x + (double)w.y * w.y + (double)w.z * w.z - mu * mu, 0.0);   /* sin^2 */
        if (linear) b = (mu + 1.0) / 2.0 * bins;
        else {   /* 1 -+ mu without cancellation near the peak: sin^2 / (1 +- mu) */
            x = back ? (mu < 0 ? s2 / (1 - mu) : 1 + mu) : (mu > 0 ? s2 / (1 + mu) : 1 - mu);
            b = x > 0 ? (log10(x) - lo) / (hi - lo) * bins : 0;
        }
        C.obs[b < 0 ? 0 : (b >= bins ? bins - 1 : (int)b)] += 1;
    }
    for (i = 0; i < bins; ++i) {
        /* hg_cdf(g, 1 - mu) = P(cos <= mu); bin edges as 1 - mu (omm) of its two ends */
        double e0, e1;
        if (linear) { e0 = 1.0 - (-1.0 + 2.0 * i / bins); e1 = 1.0 - (-1.0 + 2.0 * (i + 1) / bins); }
        else {
            double x0 = i == 0 ? 0.0 : pow(10.0, lo + (hi - lo) * i / bins);
            double x1 = i == bins - 1 ? 2.0 : pow(10.0, lo + (hi - lo) * (i + 1) / bins);
            if (back) { e0 = 2.0 - x0; e1 = 2.0 - x1; }   /* x = 1 + mu */
            else { e0 = x1; e1 = x0; }                    /* x = 1 - mu */
        }
        C.exp_[i] = N_SAMPLES * fabs(hg_cdf(model_g, e1) - hg_cdf(model_g, e0));
    }
    finish();
}

/* Direction samplers on a (cos theta, phi) grid around +z: rows from cos = +1 (top) down. */
typedef double (*cell_prob)(double c0, double c1, double dphi);
static double cos_prob(double c0, double c1, double dphi)
{
    c0 = fmax(c0, 0.0); c1 = fmax(c1, 0.0);
    return (c1 * c1 - c0 * c0) / 2.0 * dphi / STATS_PI;      /* pdf cos / pi */
}
static double cos_prob_down(double c0, double c1, double dphi) { return cos_prob(-c1, -c0, dphi); }
static double sphere_prob(double c0, double c1, double dphi) { return (c1 - c0) * dphi / (4 * STATS_PI); }
static double cone_cos_max;
static double cone_prob(double c0, double c1, double dphi)
{
    c0 = fmax(c0, cone_cos_max);
    return c1 > c0 ? (c1 - c0) * dphi / (2 * STATS_PI * (1 - cone_cos_max)) : 0.0;
}

/* which: 0 cosine hemisphere, 1 uniform sphere, 2 sphere cone, 3 the diffuse BSDF seen from
   below (its lobe must flip to -z), 4 a point light with a radius (the emitter's cone). */
static void check_directions(const char *name, const char *title, int which, cell_prob prob, double cos_lo,
                             const char *params, const char *model)
{
    const int rows = 20, cols = 24;
    fogrt_rng rng;
    int i, r, c;
    fogrt_scene *scene = NULL;
    fogrt_light_desc light;
    fogrt_material_desc diffuse;
    memset(&light, 0, sizeof light);
    light.type = FOGRT_LIGHT_POINT;
    light.position.z = 3.0f; light.radius = 1.0f;
    light.intensity.x = light.intensity.y = light.intensity.z = 1.0f;
    memset(&diffuse, 0, sizeof diffuse);
    diffuse.type = FOGRT_BSDF_DIFFUSE;
    diffuse.reflectance.x = diffuse.reflectance.y = diffuse.reflectance.z = 0.8f;
    if (which == 4 && (fogrt_scene_create(NULL, &scene) != FOGRT_RESULT_OK ||
                       fogrt_scene_add_light(scene, &light) != FOGRT_RESULT_OK ||
                       fogrt_scene_build(scene, NULL) != FOGRT_RESULT_OK)) {
        fprintf(stderr, "distributions: could not build the point-light scene\n");
        exit(1);
    }
    start(name, title, rows, cols);
    snprintf(C.params, sizeof C.params, "%s; grid of %d rows of cos theta (top: +z, equal steps down to %.3g, the last "
             "row down to -1) x %d columns of phi", params, rows, cos_lo, cols);
    snprintf(C.model, sizeof C.model, "%s", model);
    C.x0 = -STATS_PI; C.x1 = STATS_PI;
    snprintf(C.xq, sizeof C.xq, "phi [rad]");
    snprintf(C.yq, sizeof C.yq, "cos theta");
    snprintf(C.unit, sizeof C.unit, "density [1/sr]");
    for (r = 0; r < rows; ++r) C.redge[r] = 1.0 - (1.0 - cos_lo) * r / rows;
    C.redge[rows] = -1.0;
    fogrt_rng_seed(&rng, 1402, (uint64_t)which);
    for (i = 0; i < N_SAMPLES; ++i) {
        float u1 = fogrt_rng_float(&rng), u2 = fogrt_rng_float(&rng), pdf;
        fogrt_vec3 w, ctr = {0.0f, 0.0f, 3.0f}, p = {0.0f, 0.0f, 0.0f};
        double phi, z;
        if (which == 0) w = fogrt_sample_cosine_hemisphere(u1, u2);
        else if (which == 1) w = fogrt_sample_uniform_sphere(u1, u2);
        else if (which == 2) w = fogrt_sample_sphere_solid_angle(ctr, 1.0f, p, u1, u2, &pdf);
        else if (which == 3) {
            fogrt_vec3 wo = {0.8660254f, 0.0f, -0.5f};      /* 60 degrees, below the surface */
            fogrt_bsdf_sample bs;
            if (!fogrt_sample_bsdf(&diffuse, FOGRT_FRESNEL_SCHLICK, wo, 0.5f, u1, u2, &bs)) continue;
            w = bs.wi;
        } else {
            float u[2];
            fogrt_light_sample ls;
            u[0] = u1; u[1] = u2;
            if (!fogrt__sample_point_light(scene, &scene->lights[0], p, u, &ls)) continue;
            w = ls.wi;
        }
        z = w.z; phi = atan2(w.y, w.x);
        r = (int)((1.0 - z) / (1.0 - cos_lo) * rows);         /* row 0: z = 1 */
        c = (int)((phi + STATS_PI) / (2 * STATS_PI) * cols);
        if (r >= rows) r = rows - 1;                          /* below cos_lo: the last row */
        C.obs[(r < 0 ? 0 : r) * cols + (c < 0 ? 0 : (c >= cols ? cols - 1 : c))] += 1;
    }
    fogrt_scene_destroy(scene);
    for (r = 0; r < rows; ++r) {
        double c1 = 1.0 - (1.0 - cos_lo) * r / rows, c0 = r == rows - 1 ? -1.0 : 1.0 - (1.0 - cos_lo) * (r + 1) / rows;
        for (c = 0; c < cols; ++c) C.exp_[r * cols + c] = N_SAMPLES * prob(c0, c1, 2 * STATS_PI / cols);
    }
    finish();
}

/* Uniform points on a triangle, binned in (b1, b2) on a K x K grid; the upper half of the
   square is outside the triangle. naive: the classic bug b1 = u1, b2 = (1 - u1) u2. */
static void check_triangle(bool naive)
{
    const int K = 20;
    fogrt_rng rng;
    int i, r, c;
    start(naive ? "triangle_naive" : "triangle", naive ? "Triangle, naive map b1 = u1, b2 = (1 - u1) u2"
                                                     : "Uniform point on a triangle", K, K);
    C.negative = naive;
    snprintf(C.params, sizeof C.params, "%s, barycentrics (b1, b2) on a %d x %d grid: b1 down, b2 across; "
             "cells past the diagonal b1 + b2 = 1 are outside", naive ? "the naive map" : "`fogrt_sample_triangle`", K, K);
    snprintf(C.model, sizeof C.model, "uniform on the triangle: each cell's area inside it (half on the diagonal)");
    C.x0 = 0.0; C.x1 = 1.0;
    snprintf(C.xq, sizeof C.xq, "b2 (barycentric)");
    snprintf(C.yq, sizeof C.yq, "b1 (barycentric)");
    snprintf(C.unit, sizeof C.unit, "density [per unit area]");
    for (r = 0; r <= K; ++r) C.redge[r] = (double)r / K;
    fogrt_rng_seed(&rng, 1403, 0);
    for (i = 0; i < N_SAMPLES; ++i) {
        float u1 = fogrt_rng_float(&rng), u2 = fogrt_rng_float(&rng), b1, b2;
        if (naive) { b1 = u1; b2 = (1.0f - u1) * u2; }
        else fogrt_sample_triangle(u1, u2, &b1, &b2);
        r = (int)(b1 * K); c = (int)(b2 * K);
        C.obs[(r >= K ? K - 1 : r) * K + (c >= K ? K - 1 : c)] += 1;
    }
    for (r = 0; r < K; ++r)
        for (c = 0; c < K; ++c)
            C.exp_[r * K + c] = N_SAMPLES * 2.0 / (K * K) * (r + c < K - 1 ? 1.0 : (r + c == K - 1 ? 0.5 : 0.0));
    finish();
}

/* Exact area of triangle (ax,az)(bx,bz)(cx,cz) inside the rectangle [x0,x1] x [z0,z1]:
   clip the polygon against the four sides (Sutherland-Hodgman), then the shoelace sum. */
static double clip_area(const double tri[6], double x0, double x1, double z0, double z1)
{
    double poly[32], next[32], area = 0.0;
    int n = 3, side, i;
    memcpy(poly, tri, sizeof(double) * 6);
    for (side = 0; side < 4; ++side) {
        int m = 0, axis = side / 2;
        double lim = side == 0 ? x0 : side == 1 ? x1 : side == 2 ? z0 : z1, sgn = side % 2 ? -1.0 : 1.0;
        for (i = 0; i < n; ++i) {
            const double *a = &poly[2 * i], *b = &poly[2 * ((i + 1) % n)];
            double da = sgn * (a[axis] - lim), db = sgn * (b[axis] - lim);
            if (da >= 0) { next[2 * m] = a[0]; next[2 * m + 1] = a[1]; ++m; }
            if ((da >= 0) != (db >= 0)) {
                double t = da / (da - db);
                next[2 * m] = a[0] + t * (b[0] - a[0]); next[2 * m + 1] = a[1] + t * (b[1] - a[1]); ++m;
            }
        }
        n = m; memcpy(poly, next, sizeof(double) * 2 * (size_t)m);
    }
    for (i = 0; i < n; ++i) area += poly[2 * i] * poly[2 * ((i + 1) % n) + 1] - poly[2 * ((i + 1) % n)] * poly[2 * i + 1];
    return 0.5 * fabs(area);
}

/* Points on an emissive mesh of two triangles of areas 1 and 0.25 (together the triangle
   (-0.5,0) (2,0) (0,1) in the plane y = 0), from fogrt's area-light sampler as next-event
   estimation calls it, seen from a point above. */
static void check_area_light(void)
{
    const int rows = 16, cols = 40;
    const float pos[12] = {0, 0, 0, 0, 0, 1, 2, 0, 0, -0.5f, 0, 0};
    const uint32_t idx[6] = {0, 1, 2, 0, 3, 1};               /* both face +y, toward p */
    const double tri[6] = {-0.5, 0, 2, 0, 0, 1};
    fogrt_scene *s = NULL;
    fogrt_material_desc m;
    fogrt_mesh_desc md;
    uint32_t id;
    fogrt_vec3 p = {0.4f, 1.0f, 0.3f};
    fogrt_rng rng;
    int i, r, c;
    start("area_light", "Area light: points on an emissive mesh", rows, cols);
    snprintf(C.params, sizeof C.params, "`fogrt__sample_area_light` (private; what next-event estimation calls), "
             "a mesh of two triangles of areas 1 and 0.25, sampled points binned in (z down, x across)");
    snprintf(C.model, sizeof C.model, "uniform by area over the whole mesh: each cell's exact area inside it");
    C.x0 = -0.5; C.x1 = 2.0;
    snprintf(C.xq, sizeof C.xq, "x [scene units]");
    snprintf(C.yq, sizeof C.yq, "z [scene units]");
    snprintf(C.unit, sizeof C.unit, "density [1 / unit^2]");
    for (r = 0; r <= rows; ++r) C.redge[r] = (double)r / rows;
    memset(&m, 0, sizeof m); m.emission.x = m.emission.y = m.emission.z = 1.0f;
    memset(&md, 0, sizeof md);
    md.positions = pos; md.vertex_count = 4; md.indices = idx; md.triangle_count = 2;
    if (fogrt_scene_create(NULL, &s) != FOGRT_RESULT_OK || fogrt_scene_add_material(s, &m, &id) != FOGRT_RESULT_OK ||
        (md.material = id, fogrt_scene_add_mesh(s, &md)) != FOGRT_RESULT_OK || fogrt_scene_build(s, NULL) != FOGRT_RESULT_OK ||
        s->area_light_count != 1) {
        fprintf(stderr, "distributions: could not build the area-light scene\n");
        exit(1);
    }
    fogrt_rng_seed(&rng, 1404, 0);
    for (i = 0; i < N_SAMPLES; ++i) {
        float u[3];
        fogrt_light_sample ls;
        double x, z;
        u[0] = fogrt_rng_float(&rng); u[1] = fogrt_rng_float(&rng); u[2] = fogrt_rng_float(&rng);
        if (!fogrt__sample_area_light(s, &s->area_lights[0], p, u, &ls)) continue;
        x = p.x + (double)ls.wi.x * ls.dist; z = p.z + (double)ls.wi.z * ls.dist;
        r = (int)floor(z * rows); c = (int)floor((x + 0.5) / 2.5 * cols);
        C.obs[(r < 0 ? 0 : (r >= rows ? rows - 1 : r)) * cols + (c < 0 ? 0 : (c >= cols ? cols - 1 : c))] += 1;
    }
    for (r = 0; r < rows; ++r)
        for (c = 0; c < cols; ++c)
            C.exp_[r * cols + c] = N_SAMPLES / 1.25 *
                clip_area(tri, -0.5 + 2.5 * c / cols, -0.5 + 2.5 * (c + 1) / cols, (double)r / rows, (double)(r + 1) / rows);
    fogrt_scene_destroy(s);
    finish();
}

/* 1-D samplers with an exact CDF: free flight and equiangular. */
static double eq_delta = 2.0, eq_h = 0.3, eq_a = 0.0, eq_b = 6.0;
static double eq_cdf(double t)
{
    double ta = atan((eq_a - eq_delta) / eq_h), tb = atan((eq_b - eq_delta) / eq_h);
    return (atan((t - eq_delta) / eq_h) - ta) / (tb - ta);
}
static void check_1d(bool equiangular)
{
    const int bins = 40;
    const double sigma_t = 0.5, t_max = 10.0;        /* free flight: the last bin holds t > t_max */
    fogrt_rng rng;
    int i;
    start(equiangular ? "equiangular" : "free_flight", equiangular ? "Equiangular distance sampling"
                                                                   : "Free flight (exponential distance)", 1, bins);
    if (equiangular) {
        snprintf(C.params, sizeof C.params, "`fogrt_sample_equiangular`, light at h = 0.3 from the ray, closest at "
                 "t = 2, segment [0, 6], %d bins of t", bins);
        snprintf(C.model, sizeof C.model, "the CDF (theta(t) - theta_a) / (theta_b - theta_a), theta(t) = atan((t - delta) / h)");
    } else {
        snprintf(C.params, sizeof C.params, "`fogrt_sample_exponential`, sigma_t = 0.5, %d bins of t over [0, 10], "
                 "the last bin also holds t > 10", bins);
        snprintf(C.model, sizeof C.model, "the CDF 1 - exp(-sigma_t t) (eq. 5)");
    }
    C.x0 = 0.0; C.x1 = equiangular ? eq_b : t_max;
    snprintf(C.xq, sizeof C.xq, equiangular ? "distance t along the ray [scene units]"
                                            : "t [scene units] (last bin: t > 9.75)");
    snprintf(C.unit, sizeof C.unit, "density [1 / scene unit]");
    fogrt_rng_seed(&rng, 1405, equiangular);
    for (i = 0; i < N_SAMPLES; ++i) {
        float u = fogrt_rng_float(&rng), pdf, t;
        double b;
        t = equiangular ? fogrt_sample_equiangular((float)eq_delta, (float)eq_h, (float)eq_a, (float)eq_b, u, &pdf)
                        : fogrt_sample_exponential((float)sigma_t, u);
        b = t / (equiangular ? eq_b : t_max) * bins;
        C.obs[b < 0 ? 0 : (b >= bins ? bins - 1 : (int)b)] += 1;
    }
    for (i = 0; i < bins; ++i) {
        double t0 = (equiangular ? eq_b : t_max) * i / bins, t1 = (equiangular ? eq_b : t_max) * (i + 1) / bins;
        C.exp_[i] = N_SAMPLES * (equiangular ? eq_cdf(t1) - eq_cdf(t0)
                                             : (i == bins - 1 ? exp(-sigma_t * t0) : exp(-sigma_t * t0) - exp(-sigma_t * t1)));
    }
    finish();
}

/* How often glass reflects: at 12 angles (6 from outside, 6 from inside), the count of
   reflections in 20000 samples against n F; the residual is (k - nF) / sqrt(n F (1 - F)). */
static void check_glass(void)
{
    const double *cosines = glass_cos;
    const int n = N_SAMPLES / 10;
    fogrt_material_desc m;
    fogrt_rng rng;
    int k, i;
    start("glass_lobe", "Glass: reflect or refract (the Fresnel choice)", 1, 12);
    C.binomial = true;
    snprintf(C.xq, sizeof C.xq, "cos theta: outside | inside");
    snprintf(C.unit, sizeof C.unit, "fraction reflected");
    snprintf(C.params, sizeof C.params, "`fogrt_sample_bsdf` on glass (ior 1.5, Schlick), %d samples at each of 12 "
             "angles: cos theta = 0.95 .. 0.05 from outside (left), then the same from inside (right); bar = reflections", n);
    snprintf(C.model, sizeof C.model, "binomial, reflect with probability F = `fogrt_fresnel_schlick` (F = 1 past the critical angle: all must reflect); chi2 = sum of z^2 over the other angles");
    memset(&m, 0, sizeof m);
    m.type = FOGRT_BSDF_GLASS; m.ior = 1.5f;
    m.reflectance.x = m.reflectance.y = m.reflectance.z = 1.0f; m.transmittance = m.reflectance;
    fogrt_rng_seed(&rng, 1406, 0);
    for (k = 0; k < 12; ++k) {
        double ci = cosines[k % 6] * (k < 6 ? 1.0 : -1.0), F = fogrt_fresnel_schlick(1.5f, (float)ci);
        fogrt_vec3 wo;
        wo.x = (float)sqrt(1.0 - ci * ci); wo.y = 0.0f; wo.z = (float)ci;
        for (i = 0; i < n; ++i) {
            fogrt_bsdf_sample bs;
            float ul = fogrt_rng_float(&rng), u1 = fogrt_rng_float(&rng), u2 = fogrt_rng_float(&rng);
            if (fogrt_sample_bsdf(&m, FOGRT_FRESNEL_SCHLICK, wo, ul, u1, u2, &bs) && !bs.is_transmission) C.obs[k] += 1;
        }
        C.exp_[k] = n * F;
        C.var[k] = n * F * (1.0 - F);   /* 0 on total internal reflection: then all n must reflect */
    }
    finish();
}

int main(int argc, char **argv)
{
    const char *md_path;
    char *text, *begin, *end, *gen = NULL;
    size_t gen_size = 0;
    long size;
    FILE *f;
    if (argc != 3) { fprintf(stderr, "usage: distributions OUT_DIR MARKDOWN_FILE\n"); return 2; }
    out_dir = argv[1]; md_path = argv[2];
    md_out = open_memstream(&gen, &gen_size);
    if (!md_out) return 1;
    fprintf(md_out, "<!-- BEGIN generated by `make distributions` (tests/distributions.c): do not edit by hand -->\n\n");

    check_hg(0.0, 0.0, "hg_g0");
    check_hg(0.5, 0.5, "hg_g0.5");
    check_hg(-0.5, -0.5, "hg_g-0.5");
    check_hg(0.9, 0.9, "hg_g0.9");
    check_hg(0.99, 0.99, "hg_g0.99");
    check_directions("cosine_hemisphere", "Cosine-weighted hemisphere", 0, cos_prob, -1.0,
                     "`fogrt_sample_cosine_hemisphere`", "pdf cos theta / pi above the horizon, 0 below (exact cell probabilities)");
    check_directions("uniform_sphere", "Uniform sphere", 1, sphere_prob, -1.0,
                     "`fogrt_sample_uniform_sphere`", "pdf 1 / (4 pi): equal counts in every cell");
    cone_cos_max = sqrt(1.0 - 1.0 / 9.0);
    check_directions("sphere_cone", "Sphere cone (solid-angle sampling)", 2, cone_prob, 1.0 - 1.25 * (1.0 - cone_cos_max),
                     "`fogrt_sample_sphere_solid_angle`, a sphere of radius 1 at distance 3 on +z (a cone of 19.5 degrees)",
                     "uniform in solid angle inside the cone cos theta >= sqrt(8/9), 0 outside");
    check_directions("diffuse_bsdf_below", "Diffuse BSDF, seen from below", 3, cos_prob_down, -1.0,
                     "`fogrt_sample_bsdf` on a diffuse material, wo at 60 degrees on the back side (wo.z = -0.5)",
                     "pdf |cos theta| / pi on the side of wo (below), 0 above: the two-sided diffuse lobe");
    check_directions("point_light_radius", "Point light with a radius", 4, cone_prob, 1.0 - 1.25 * (1.0 - cone_cos_max),
                     "`fogrt__sample_point_light` (private; what next-event estimation calls), a light of radius 1 at "
                     "distance 3 on +z, seen from the origin",
                     "uniform in solid angle inside the cone the sphere subtends, cos theta >= sqrt(8/9), 0 outside");
    check_triangle(false);
    check_area_light();
    check_1d(false);
    check_1d(true);
    check_glass();
    check_triangle(true);
    check_hg(0.5, -0.5, "hg_sign_flipped");
    fprintf(md_out, "<!-- END generated -->");
    fclose(md_out);

    /* Splice the generated part into the index page between its markers. */
    if (!(f = fopen(md_path, "rb"))) { fprintf(stderr, "distributions: cannot read %s\n", md_path); return 1; }
    fseek(f, 0, SEEK_END); size = ftell(f); fseek(f, 0, SEEK_SET);
    text = (char *)calloc((size_t)size + 1, 1);
    if (!text || fread(text, 1, (size_t)size, f) != (size_t)size) { fclose(f); return 1; }
    fclose(f);
    begin = strstr(text, "<!-- BEGIN generated");
    end = begin ? strstr(begin, "<!-- END generated -->") : NULL;
    if (!begin || !end) { fprintf(stderr, "distributions: %s has no generated-section markers\n", md_path); return 1; }
    end += strlen("<!-- END generated -->");
    if (!(f = fopen(md_path, "wb"))) { fprintf(stderr, "distributions: cannot write %s\n", md_path); return 1; }
    fwrite(text, 1, (size_t)(begin - text), f);
    fputs(gen, f);
    fputs(end, f);
    fclose(f);
    printf("wrote %s/*.png and the results section of %s\n", out_dir, md_path);
    free(text); free(gen);
    if (failures) fprintf(stderr, "distributions: %d check%s came out wrong\n", failures, failures == 1 ? "" : "s");
    return failures ? 1 : 0;
}
