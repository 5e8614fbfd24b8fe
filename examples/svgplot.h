/* svgplot.h - a small line plot written as SVG with plain fprintf, for examples/convergence.c
   and examples/figures.c. No dependencies beyond <stdio.h> and <math.h>.

   One plot: axes (linear or logarithmic, chosen per axis) with tick labels and axis titles,
   any number of series (polyline + point markers, optional dashed line, optional colour; a
   guide line such as a reference slope without markers), a legend on the right, and optional
   lines of monospace text under the plot (a table, a caption). Sizes are meant for a
   projector: 16 px text on a 1000 x 700 picture. Include it in one
   C file; everything is static. */
#ifndef SVGPLOT_H_INCLUDED
#define SVGPLOT_H_INCLUDED

#include <math.h>
#include <stdio.h>
#include <string.h>

typedef struct svgplot_series {
    const char *label;
    const char *sublabel;  /* optional second legend line (e.g. a fitted slope), or NULL */
    const double *x, *y;   /* n points; points with a non-finite or (log axis) non-positive value are skipped */
    int n;
    int dashed;
    const char *colour;    /* NULL: the next of the palette */
    int no_markers;        /* a guide line (a reference slope): no point markers */
} svgplot_series;

typedef struct svgplot_desc {
    const char *title;
    const char *x_label, *y_label;   /* with units */
    int log_x, log_y;
    const char *const *notes;        /* lines of text under the plot (a table), or NULL */
    int note_count;
    int width, height;               /* 0: 1000 x 700 */
} svgplot_desc;

/* Colours that stay apart for colour-blind readers (Okabe-Ito), then repeat. */
static const char *svgplot__colour(int i)
{
    static const char *c[] = { "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000", "#999999" };
    return c[i % 8];
}

/* XML-escapes s into f. */
static void svgplot__text(FILE *f, const char *s)
{
    for (; *s; ++s) {
        if (*s == '<') fputs("&lt;", f);
        else if (*s == '>') fputs("&gt;", f);
        else if (*s == '&') fputs("&amp;", f);
        else fputc(*s, f);
    }
}

static int svgplot__usable(double v, int log_axis) { return isfinite(v) && (!log_axis || v > 0.0); }

/* Data range of one axis over every series, padded a little (a decade step on log axes is
   rounded out to whole 1-2-5 steps). */
static void svgplot__range(const svgplot_series *s, int ns, int axis, int log_axis, double *lo, double *hi)
{
    int i, k;
    *lo = INFINITY; *hi = -INFINITY;
    for (i = 0; i < ns; ++i)
        for (k = 0; k < s[i].n; ++k) {
            double v = axis ? s[i].y[k] : s[i].x[k], o = axis ? s[i].x[k] : s[i].y[k];
            if (!svgplot__usable(v, log_axis) || !isfinite(o)) continue;
            if (v < *lo) *lo = v;
            if (v > *hi) *hi = v;
        }
    if (!(*lo <= *hi)) { *lo = log_axis ? 0.1 : 0.0; *hi = 1.0; }
    if (log_axis) {
        double a = log10(*lo), b = log10(*hi);
        if (b - a < 0.3) { a -= 0.15; b += 0.15; }
        *lo = pow(10.0, a - 0.03 * (b - a)); *hi = pow(10.0, b + 0.03 * (b - a));
    } else {
        double pad = (*hi - *lo) * 0.05;
        if (pad == 0.0) pad = fabs(*hi) > 0.0 ? fabs(*hi) * 0.1 : 1.0;
        *lo -= pad; *hi += pad;
    }
}

static double svgplot__map(double v, double lo, double hi, int log_axis, double p0, double p1)
{
    double t = log_axis ? (log10(v) - log10(lo)) / (log10(hi) - log10(lo)) : (v - lo) / (hi - lo);
    return p0 + t * (p1 - p0);
}

/* Tick values: on a log axis the powers of ten (and 2 and 5 times them when the range spans
   fewer than 3 decades); on a linear axis a 1-2-5 step giving 4 to 10 ticks. */
static int svgplot__ticks(double lo, double hi, int log_axis, double *out, int max)
{
    int n = 0;
    if (log_axis) {
        int e, e0 = (int)floor(log10(lo)), e1 = (int)ceil(log10(hi));
        int fine = e1 - e0 <= 3;
        for (e = e0; e <= e1; ++e) {
            static const double m[3] = { 1.0, 2.0, 5.0 };
            int j;
            for (j = 0; j < (fine ? 3 : 1); ++j) {
                double v = m[j] * pow(10.0, e);
                if (v >= lo && v <= hi && n < max) out[n++] = v;
            }
        }
    } else {
        double span = hi - lo, step = pow(10.0, floor(log10(span / 5.0))), v;
        if (span / step > 10.0) step *= 2.0;
        if (span / step > 10.0) step *= 2.5;
        for (v = ceil(lo / step) * step; v <= hi && n < max; v += step) out[n++] = fabs(v) < 1e-12 * step ? 0.0 : v;
    }
    return n;
}

static void svgplot_write(FILE *f, const svgplot_desc *d, const svgplot_series *s, int ns)
{
    int W = d->width ? d->width : 1000, H = d->height ? d->height : 700;
    double x0 = 100, y0 = 56, x1 = W - 290, y1 = H - 80 - 18.0 * d->note_count;
    double xlo, xhi, ylo, yhi, ticks[64];
    int i, k, nt;
    if (y1 < y0 + 150) y1 = y0 + 150;
    svgplot__range(s, ns, 0, d->log_x, &xlo, &xhi);
    svgplot__range(s, ns, 1, d->log_y, &ylo, &yhi);
    fprintf(f, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" viewBox=\"0 0 %d %d\" "
               "font-family=\"Helvetica, Arial, sans-serif\" font-size=\"16\">\n", W, H, W, H);
    fprintf(f, "<rect width=\"%d\" height=\"%d\" fill=\"white\"/>\n", W, H);
    if (d->title) {
        fprintf(f, "<text x=\"%.1f\" y=\"32\" font-size=\"20\" font-weight=\"bold\">", x0);
        svgplot__text(f, d->title);
        fprintf(f, "</text>\n");
    }
    /* grid and tick labels */
    nt = svgplot__ticks(xlo, xhi, d->log_x, ticks, 64);
    for (k = 0; k < nt; ++k) {
        double px = svgplot__map(ticks[k], xlo, xhi, d->log_x, x0, x1);
        fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n", px, y0, px, y1);
        fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">%g</text>\n", px, y1 + 22, ticks[k]);
    }
    nt = svgplot__ticks(ylo, yhi, d->log_y, ticks, 64);
    for (k = 0; k < nt; ++k) {
        double py = svgplot__map(ticks[k], ylo, yhi, d->log_y, y1, y0);
        fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n", x0, py, x1, py);
        fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">%g</text>\n", x0 - 6, py + 4, ticks[k]);
    }
    fprintf(f, "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"none\" stroke=\"black\"/>\n",
            x0, y0, x1 - x0, y1 - y0);
    if (d->x_label) {
        fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">", 0.5 * (x0 + x1), y1 + 48);
        svgplot__text(f, d->x_label);
        fprintf(f, "</text>\n");
    }
    if (d->y_label) {
        fprintf(f, "<text transform=\"translate(24 %.1f) rotate(-90)\" text-anchor=\"middle\">", 0.5 * (y0 + y1));
        svgplot__text(f, d->y_label);
        fprintf(f, "</text>\n");
    }
    /* series and legend */
    for (i = 0; i < ns; ++i) {
        const char *c = s[i].colour ? s[i].colour : svgplot__colour(i);
        double ly = y0 + 10 + 42.0 * i;
        fprintf(f, "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"2\"%s points=\"", c,
                s[i].dashed ? " stroke-dasharray=\"6 4\"" : "");
        for (k = 0; k < s[i].n; ++k)
            if (svgplot__usable(s[i].x[k], d->log_x) && svgplot__usable(s[i].y[k], d->log_y))
                fprintf(f, "%.1f,%.1f ", svgplot__map(s[i].x[k], xlo, xhi, d->log_x, x0, x1),
                        svgplot__map(s[i].y[k], ylo, yhi, d->log_y, y1, y0));
        fprintf(f, "\"/>\n");
        for (k = 0; k < s[i].n && !s[i].no_markers; ++k)
            if (svgplot__usable(s[i].x[k], d->log_x) && svgplot__usable(s[i].y[k], d->log_y))
                fprintf(f, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"2.5\" fill=\"%s\"/>\n",
                        svgplot__map(s[i].x[k], xlo, xhi, d->log_x, x0, x1),
                        svgplot__map(s[i].y[k], ylo, yhi, d->log_y, y1, y0), c);
        fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" stroke-width=\"2\"%s/>\n",
                x1 + 15, ly, x1 + 40, ly, c, s[i].dashed ? " stroke-dasharray=\"6 4\"" : "");
        fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" font-size=\"15\">", x1 + 46, ly + 5);
        svgplot__text(f, s[i].label ? s[i].label : "");
        fprintf(f, "</text>\n");
        if (s[i].sublabel) {
            fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" font-size=\"13\" fill=\"#444\">", x1 + 46, ly + 21);
            svgplot__text(f, s[i].sublabel);
            fprintf(f, "</text>\n");
        }
    }
    for (k = 0; k < d->note_count; ++k) {
        fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" font-family=\"DejaVu Sans Mono, Menlo, monospace\" font-size=\"14\" xml:space=\"preserve\">",
                x0 - 60, y1 + 78 + 18.0 * k);
        svgplot__text(f, d->notes[k]);
        fprintf(f, "</text>\n");
    }
    fprintf(f, "</svg>\n");
}

#endif /* SVGPLOT_H_INCLUDED */
