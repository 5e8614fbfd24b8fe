/* convergence.c - error against render time, for several estimators of one scene.

   Usage: convergence [options]
     --scene default|FILE.dae   the scene (default: fogrt's embedded fog-filled Cornell box,
                                lit by a ceiling lamp and a spot light in the fog)
     --reference REF.pfm        measure against this image (else a long render of this program,
                                cached as OUT/<scene>_ref.pfm with its variance in
                                OUT/<scene>_ref_var.pfm; delete them to render it again)
     --out DIR                  output directory (default build/convergence)
     --size W H                 image size (default 160 120)
     --seconds S                CPU seconds per configuration (default 15)
     --ref-seconds S            CPU seconds of the reference render (default 60)
     --only-reference           render (or check) the cached reference and stop
     --replot DATA.csv          no rendering: draw the plot of a data file this program wrote
                                again, next to it (make convergence-png)

   Every configuration renders progressively to 1, 2, 4, 8, ... samples per pixel while the
   next doubling fits in its time budget; after each step its relative MSE against the
   reference is measured:
       relMSE = (sum_p (L_p - R_p)^2 - sum_p Var[R_p]) / sum_p R_p^2     (luminance)
   where Var[R_p] is the reference's own variance (known when this program rendered it; a
   reference given without OUT-style _var.pfm next to it is taken as exact). This is the
   quantity fogrt_image_error estimates from the samples themselves (its relative_error
   squared, which uses the image's own sum_p L_p^2), and both are written.

   Time is the process's CPU time (all threads): on a shared machine it depends much less on
   what else runs than wall time does (both are in the CSV).

   Writes OUT/<scene>.csv (one row per ladder point, with everything the plot needs) and
   OUT/<scene>.svg (log-log relMSE against seconds, one line per configuration, the fitted
   slope of each line in the legend, a dashed reference line of slope -1 and an efficiency
   table, 1 / (relMSE x seconds)). An unbiased estimator falls with slope -1; a line that
   flattens has hit its bias (the one-bounce integrator misses the light that bounced more
   than once). A line that jumps up at one step has met a firefly: one sample of very large
   weight (a fog collision close to a lamp, where a light sample's 1 / r^2 is huge and,
   without MIS or equiangular sampling, nothing tempers it) lands at that step and is then
   averaged down as 1/spp. The CSV's worst_pixel_share (the largest share of the squared
   error one pixel holds, at worst_x, worst_y) shows it: over half at such a step, a few
   percent elsewhere; the plot's caption lists those steps. */
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <time.h>
#include <errno.h>
#include <sys/stat.h>
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#define FOGRT_LOAD_IMPLEMENTATION
#include "fogrt_load.h"
#include "svgplot.h"
#include "plotfont.h"   /* pf_wrap: the caption's lines */

#define MAX_POINTS 24

static double cpu_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
static double wall_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
static double lum(const float *c) { return 0.2126 * (double)c[0] + 0.7152 * (double)c[1] + 0.0722 * (double)c[2]; }
static double lum_d(const double *c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

static void log_stderr(fogrt_log_level level, const char *msg, void *user)
{
    (void)user;
    if (level == FOGRT_LOG_ERROR || level == FOGRT_LOG_WARNING)
        fprintf(stderr, "fogrt: %s: %s\n", level == FOGRT_LOG_ERROR ? "error" : "warning", msg);
}

/* ---- PFM reading (fogrt writes them; reading is this program's job) ---------------------- */
/* Reads a little-endian colour PFM ("PF", negative scale) into *rgb (rows from the top).
   Returns 0 on success; on failure prints one line naming the file and returns -1. */
static int read_pfm(const char *path, int *w, int *h, float **rgb)
{
    FILE *f = fopen(path, "rb");
    char magic[3] = { 0 };
    double scale;
    int y, c;
    *rgb = NULL;
    if (!f) { fprintf(stderr, "convergence: %s: %s\n", path, strerror(errno)); return -1; }
    if (fscanf(f, "%2s %d %d %lf", magic, w, h, &scale) != 4 || strcmp(magic, "PF") != 0 ||
        *w <= 0 || *h <= 0 || *w > 16384 || *h > 16384) {
        fprintf(stderr, "convergence: %s: not a colour PFM (want 'PF', width, height, scale)\n", path);
        fclose(f); return -1;
    }
    if (scale > 0.0) { fprintf(stderr, "convergence: %s: big-endian PFM is not supported\n", path); fclose(f); return -1; }
    c = fgetc(f);                                   /* the single white-space byte after the scale */
    if (c == '\r') c = fgetc(f);
    *rgb = (float *)malloc(sizeof(float) * 3 * (size_t)*w * (size_t)*h);
    if (!*rgb || c == EOF) { fprintf(stderr, "convergence: %s: out of memory or truncated\n", path); fclose(f); free(*rgb); *rgb = NULL; return -1; }
    for (y = *h - 1; y >= 0; --y)                  /* bottom row first */
        if (fread(*rgb + (size_t)y * (size_t)*w * 3, sizeof(float) * 3, (size_t)*w, f) != (size_t)*w) {
            fprintf(stderr, "convergence: %s: truncated (%d x %d pixels expected)\n", path, *w, *h);
            fclose(f); free(*rgb); *rgb = NULL; return -1;
        }
    fclose(f);
    return 0;
}
static int file_exists(const char *path) { struct stat st; return stat(path, &st) == 0; }

/* ---- the configurations ------------------------------------------------------------------ */
typedef struct config {
    const char *name;         /* legend and CSV */
    fogrt_render_desc rd;
    int rates_after;          /* > 0: adaptive sampling, the rates made after this many spp */
} config;

static int make_configs(config *c)
{
    int n = 0;
    fogrt_render_desc d = fogrt_render_defaults();
    memset(c, 0, sizeof(config) * 6);
    c[n].name = "path NEE+MIS";          c[n].rd = d; ++n;
    c[n].name = "path NEE+MIS, pixel rates"; c[n].rd = d; c[n].rates_after = 8; ++n;   /* the CLI's default */
    c[n].name = "path NEE, no MIS";      c[n].rd = d; c[n].rd.mis = false; ++n;
    c[n].name = "path, no NEE (paper: no IS)"; c[n].rd = d; c[n].rd.nee = false; ++n;
    c[n].name = "path, equiangular off"; c[n].rd = d; c[n].rd.equiangular = false; ++n;
    c[n].name = "one-bounce direct";     c[n].rd = d; c[n].rd.integrator = FOGRT_INTEGRATOR_DIRECT; ++n;
    return n;
}

typedef struct ladder {
    int n;
    int spp[MAX_POINTS];
    double cpu[MAX_POINTS], wall[MAX_POINTS];
    double meas[MAX_POINTS], est[MAX_POINTS];
    double worst[MAX_POINTS];   /* the one pixel's share of the squared error (a firefly: most of it) */
    int worst_x[MAX_POINTS], worst_y[MAX_POINTS];   /* and where it is */
    double slope, efficiency;
} ladder;

/* Measured relMSE of img against the reference (ref_var may be NULL: an exact reference);
   *worst gets the largest share of the squared error that one pixel holds. */
static double measured_rel_mse(const fogrt_image *img, const float *ref, const float *ref_var, double *worst, size_t *where)
{
    size_t i, n = (size_t)img->width * (size_t)img->height;
    double se = 0.0, var = 0.0, norm = 0.0, top = 0.0;
    *where = 0;
    for (i = 0; i < n; ++i) {
        double m = img->count[i] ? lum_d(img->sum + 3 * i) / img->count[i] : 0.0, r = lum(ref + 3 * i);
        se += (m - r) * (m - r);
        norm += r * r;
        if ((m - r) * (m - r) > top) { top = (m - r) * (m - r); *where = i; }
        if (ref_var) var += (double)ref_var[3 * i];
    }
    *worst = se > 0.0 ? top / se : 0.0;
    return norm > 0.0 ? (se - var) / norm : 0.0;
}

/* Least-squares slope of log relMSE against log seconds, over the points with >= 4 spp. */
static double fit_slope(const ladder *L)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int k, m = 0;
    for (k = 0; k < L->n; ++k) {
        double x, y;
        if (L->spp[k] < 4 || !(L->meas[k] > 0.0) || !(L->cpu[k] > 0.0)) continue;
        x = log(L->cpu[k]); y = log(L->meas[k]);
        sx += x; sy += y; sxx += x * x; sxy += x * y; ++m;
    }
    if (m < 2 || m * sxx - sx * sx <= 0.0) return NAN;
    return (m * sxy - sx * sy) / (m * sxx - sx * sx);
}

static int run_ladder(const fogrt_scene *scene, const config *c, int w, int h, double budget,
                      const float *ref, const float *ref_var, ladder *L)
{
    fogrt_image img;
    fogrt_error_estimate e;
    fogrt_result r;
    fogrt_render_desc rd = c->rd;
    float *rates = NULL;
    double c0, w0;
    size_t worst_at;
    int done = 0, target = 1;
    memset(L, 0, sizeof *L);
    if ((r = fogrt_image_alloc(&img, w, h, NULL)) != FOGRT_RESULT_OK ||
        (c->rates_after > 0 && !(rates = (float *)malloc(sizeof(float) * (size_t)w * (size_t)h)))) {
        fprintf(stderr, "convergence: %s\n", fogrt_result_string(r ? r : FOGRT_RESULT_OUT_OF_MEMORY));
        fogrt_image_free(&img); return -1;
    }
    c0 = cpu_seconds(); w0 = wall_seconds();
    while (L->n < MAX_POINTS) {
        if ((r = fogrt_render(scene, &rd, &img, target - done, NULL)) != FOGRT_RESULT_OK) {
            fprintf(stderr, "convergence: %s: %s\n", c->name, fogrt_result_string(r));
            fogrt_image_free(&img); free(rates); return -1;
        }
        done = target;
        /* adaptive sampling: the rates once, from the samples taken alike (chapter 15) */
        if (rates && !rd.sample_rate && done >= c->rates_after &&
            fogrt_image_sample_rates(&img, rates) == FOGRT_RESULT_OK) rd.sample_rate = rates;
        L->spp[L->n] = done;
        L->cpu[L->n] = cpu_seconds() - c0;
        L->wall[L->n] = wall_seconds() - w0;
        L->meas[L->n] = measured_rel_mse(&img, ref, ref_var, &L->worst[L->n], &worst_at);
        fogrt_image_error(&img, &e);
        L->est[L->n] = e.relative_error * e.relative_error;
        L->worst_x[L->n] = (int)(worst_at % (size_t)w); L->worst_y[L->n] = (int)(worst_at / (size_t)w);
        printf("  %-28s %5d spp %8.2f s cpu  relMSE measured %.4e estimated %.4e  worst pixel %4.1f%% (%d, %d)\n", c->name, done,
               L->cpu[L->n], L->meas[L->n], L->est[L->n], 100.0 * L->worst[L->n], L->worst_x[L->n], L->worst_y[L->n]);
        fflush(stdout);
        L->n++;
        if (2.0 * L->cpu[L->n - 1] > budget) break;   /* the next doubling would not fit */
        target *= 2;
    }
    L->slope = fit_slope(L);
    L->efficiency = L->meas[L->n - 1] > 0.0 ? 1.0 / (L->meas[L->n - 1] * L->cpu[L->n - 1]) : (double)NAN;
    fogrt_image_free(&img);
    free(rates);
    return 0;
}

/* The reference: path NEE+MIS with its own seed, rendered for ref_budget CPU seconds, saved
   with its per-pixel variance of the mean luminance (all three channels). */
static int render_reference(const fogrt_scene *scene, int w, int h, double ref_budget,
                            const char *ref_path, const char *var_path)
{
    fogrt_image img;
    fogrt_render_desc rd = fogrt_render_defaults();
    fogrt_error_estimate e;
    fogrt_result r;
    float *rgb, *var;
    double c0 = cpu_seconds(), w0 = wall_seconds(), per_spp;
    int done = 0, batch = 4;
    size_t i, n = (size_t)w * (size_t)h;
    rd.seed = 0xC0FFEE;   /* independent of the configurations' samples (seed 0) */
    if ((r = fogrt_image_alloc(&img, w, h, NULL)) != FOGRT_RESULT_OK) { fprintf(stderr, "convergence: %s\n", fogrt_result_string(r)); return -1; }
    printf("reference: path NEE+MIS, %d x %d, %.0f CPU seconds -> %s\n", w, h, ref_budget, ref_path);
    for (;;) {
        if ((r = fogrt_render(scene, &rd, &img, batch, NULL)) != FOGRT_RESULT_OK) {
            fprintf(stderr, "convergence: reference: %s\n", fogrt_result_string(r)); fogrt_image_free(&img); return -1;
        }
        done += batch;
        per_spp = (cpu_seconds() - c0) / done;
        if ((cpu_seconds() - c0) + batch * per_spp > ref_budget) break;
        if (batch < 64) batch *= 2;
    }
    fogrt_image_error(&img, &e);
    printf("reference: %d spp, %.1f s cpu, %.1f s wall, estimated relMSE %.3e\n", done, cpu_seconds() - c0,
           wall_seconds() - w0, e.relative_error * e.relative_error);
    rgb = (float *)malloc(sizeof(float) * 3 * n);
    var = (float *)malloc(sizeof(float) * 3 * n);
    if (!rgb || !var) { fprintf(stderr, "convergence: out of memory\n"); return -1; }
    fogrt_image_resolve(&img, rgb);
    for (i = 0; i < n; ++i) {
        double v = fogrt_image_pixel_variance(&img, i);   /* between-stream: unbiased for stratified positions */
        var[3 * i] = var[3 * i + 1] = var[3 * i + 2] = (float)v;
    }
    if (fogrt_write_pfm(ref_path, w, h, rgb) != FOGRT_RESULT_OK || fogrt_write_pfm(var_path, w, h, var) != FOGRT_RESULT_OK) {
        fprintf(stderr, "convergence: cannot write %s / %s\n", ref_path, var_path);
        free(rgb); free(var); fogrt_image_free(&img); return -1;
    }
    free(rgb); free(var);
    fogrt_image_free(&img);
    return 0;
}

/* ---- the data file and the plot ------------------------------------------------------------ */
/* The CSV holds everything the plot needs, so `convergence --replot` (make convergence-png)
   draws it again from the data without rendering. */
static void names_from_configs(const config *c, int nc, char names[][64])
{
    int i;
    for (i = 0; i < nc; ++i) snprintf(names[i], 64, "%s", c[i].name);
}

/* Closes a file this program wrote: a write that failed (a full disk) is one message and -1,
   never "wrote". */
static int close_written(FILE *f, const char *path)
{
    int failed = ferror(f) != 0;
    if (fclose(f) != 0) failed = 1;
    if (failed) { fprintf(stderr, "convergence: write failed: %s: %s\n", path, strerror(errno)); return -1; }
    printf("wrote %s\n", path);
    return 0;
}

static int write_csv(const char *out, const char *name, int w, int h, const char (*names)[64], const ladder *lad, int nc)
{
    char path[1024];
    FILE *f;
    int i, k;
    snprintf(path, sizeof path, "%s/%s.csv", out, name);
    if (!(f = fopen(path, "w"))) { fprintf(stderr, "convergence: cannot write %s: %s\n", path, strerror(errno)); return -1; }
    fprintf(f, "scene,width,height,configuration,spp,cpu_seconds,wall_seconds,measured_rel_mse,estimated_rel_mse,efficiency,worst_pixel_share,worst_x,worst_y\n");
    for (i = 0; i < nc; ++i)
        for (k = 0; k < lad[i].n; ++k)
            fprintf(f, "%s,%d,%d,\"%s\",%d,%.4f,%.4f,%.6e,%.6e,%.6e,%.4f,%d,%d\n", name, w, h, names[i], lad[i].spp[k], lad[i].cpu[k],
                    lad[i].wall[k], lad[i].meas[k], lad[i].est[k],
                    lad[i].meas[k] > 0.0 ? 1.0 / (lad[i].meas[k] * lad[i].cpu[k]) : (double)NAN, lad[i].worst[k],
                    lad[i].worst_x[k], lad[i].worst_y[k]);
    return close_written(f, path);
}

/* Reads a CSV write_csv wrote back into names, lad and nc (the rows of one configuration
   are consecutive; its name is quoted, as it may hold a comma). Returns 0, or -1 with one line naming the file. */
static int read_csv(const char *path, char *name, size_t name_size, int *w, int *h, char names[][64], ladder *lad, int *nc)
{
    FILE *f = fopen(path, "r");
    char line[512];
    int row = 0;
    *nc = 0;
    if (!f) { fprintf(stderr, "convergence: %s: %s (run make convergence first)\n", path, strerror(errno)); return -1; }
    if (!fgets(line, sizeof line, f) || strncmp(line, "scene,width,height,configuration,", 33) != 0) {
        fprintf(stderr, "convergence: %s: not a convergence data file of this version (run make convergence again)\n", path);
        fclose(f); return -1;
    }
    while (fgets(line, sizeof line, f)) {
        char sc[128], cf[64];
        int spp, ww, hh, wx, wy;
        double cpu, wall, meas, est, eff, worst;
        ladder *L;
        ++row;
        if (sscanf(line, "%127[^,],%d,%d,\"%63[^\"]\",%d,%lf,%lf,%lf,%lf,%lf,%lf,%d,%d", sc, &ww, &hh, cf, &spp, &cpu, &wall, &meas, &est, &eff, &worst, &wx, &wy) != 13) {
            fprintf(stderr, "convergence: %s: row %d is not scene,width,height,configuration,spp,... \n", path, row);
            fclose(f); return -1;
        }
        if (*nc == 0 || strcmp(names[*nc - 1], cf) != 0) {
            if (*nc == 8) { fprintf(stderr, "convergence: %s: more than 8 configurations\n", path); fclose(f); return -1; }
            snprintf(names[*nc], 64, "%s", cf);
            memset(&lad[*nc], 0, sizeof lad[*nc]);
            ++*nc;
        }
        L = &lad[*nc - 1];
        if (L->n == MAX_POINTS) continue;
        snprintf(name, name_size, "%s", sc);
        *w = ww; *h = hh;
        L->spp[L->n] = spp; L->cpu[L->n] = cpu; L->wall[L->n] = wall; L->meas[L->n] = meas; L->est[L->n] = est; L->worst[L->n] = worst;
        L->worst_x[L->n] = wx; L->worst_y[L->n] = wy;
        L->n++;
    }
    fclose(f);
    if (*nc == 0) { fprintf(stderr, "convergence: %s: no rows\n", path); return -1; }
    for (row = 0; row < *nc; ++row) {
        ladder *L = &lad[row];
        L->slope = fit_slope(L);
        L->efficiency = L->meas[L->n - 1] > 0.0 ? 1.0 / (L->meas[L->n - 1] * L->cpu[L->n - 1]) : (double)NAN;
    }
    return 0;
}

/* The steps where a firefly came in: the error rose from the step before, and one pixel
   holds more than half of it. Listed per configuration, for the plot's caption. */
static void firefly_list(const char (*names)[64], const ladder *lad, int nc, char *buf, size_t size)
{
    int i, k;
    size_t used = 0;
    buf[0] = '\0';
    for (i = 0; i < nc; ++i) {
        int first = 1;
        for (k = 1; k < lad[i].n && used + 90 < size; ++k) {
            if (!(lad[i].worst[k] > 0.5 && lad[i].meas[k] > lad[i].meas[k - 1])) continue;
            if (first) used += (size_t)snprintf(buf + used, size - used, "%s%s: ", used ? "; " : "", names[i]);
            else used += (size_t)snprintf(buf + used, size - used, ", ");
            used += (size_t)snprintf(buf + used, size - used, "%d spp (%.0f%% in pixel %d, %d)", lad[i].spp[k],
                                     100.0 * lad[i].worst[k], lad[i].worst_x[k], lad[i].worst_y[k]);
            first = 0;
        }
    }
}

static int write_svg(const char *out, const char *name, int w, int h, const char (*names)[64], const ladder *lad, int nc)
{
    static char notes[20][200];
    const char *note_ptr[20];
    char labels[8][96], title[200], path[1024], spikes[600];
    svgplot_series s[9];
    svgplot_desc d;
    double rx[2], ry[2];
    int i, nn = 0, k, anchor = -1;
    FILE *f;
    memset(s, 0, sizeof s);
    snprintf(notes[nn++], sizeof notes[0], "%-28s %6s %8s %11s %6s %11s %7s", "configuration", "spp", "CPU s",
             "relMSE", "slope", "1/(MSE*s)", "vs first");
    for (i = 0; i < nc; ++i) {
        const ladder *L = &lad[i];
        snprintf(notes[nn++], sizeof notes[0], "%-28s %6d %8.2f %11.3e %6.2f %11.3e %7.3f", names[i],
                 L->spp[L->n - 1], L->cpu[L->n - 1], L->meas[L->n - 1], L->slope, L->efficiency,
                 L->efficiency / lad[0].efficiency);
        snprintf(labels[i], sizeof labels[i], "slope %.2f, %d spp in %.1f s", L->slope, L->spp[L->n - 1], L->cpu[L->n - 1]);
        s[i].label = names[i]; s[i].sublabel = labels[i]; s[i].x = L->cpu; s[i].y = L->meas; s[i].n = L->n;
    }
    /* the slope -1 of an unbiased estimator at constant efficiency, through the first
       configuration's point at 4 spp, across the time range of the plot */
    for (k = 0; k < lad[0].n; ++k) if (lad[0].spp[k] >= 4 && lad[0].meas[k] > 0.0 && lad[0].cpu[k] > 0.0) { anchor = k; break; }
    if (anchor >= 0) {
        double tmin = INFINITY, tmax = 0.0;
        for (i = 0; i < nc; ++i)
            for (k = 0; k < lad[i].n; ++k)
                if (lad[i].cpu[k] > 0.0 && lad[i].meas[k] > 0.0) { tmin = fmin(tmin, lad[i].cpu[k]); tmax = fmax(tmax, lad[i].cpu[k]); }
        rx[0] = tmin; rx[1] = tmax;
        ry[0] = lad[0].meas[anchor] * lad[0].cpu[anchor] / tmin; ry[1] = lad[0].meas[anchor] * lad[0].cpu[anchor] / tmax;
        s[nc].label = "reference slope -1"; s[nc].sublabel = "unbiased: error x time constant";
        s[nc].x = rx; s[nc].y = ry; s[nc].n = 2; s[nc].dashed = 1; s[nc].colour = "#000000"; s[nc].no_markers = 1;
    }
    printf("\nefficiency at the last point (relMSE measured; slope fitted over >= 4 spp):\n");
    for (i = 0; i < nn; ++i) printf("  %s\n", notes[i]);
    snprintf(notes[nn++], sizeof notes[0], " ");
    snprintf(notes[nn++], sizeof notes[0], "Each line is one render made progressive (1, 2, 4, ... spp), measured after every doubling.");
    snprintf(notes[nn++], sizeof notes[0], "Lines that flatten have hit their bias (without NEE the spot light, a point, is never found;");
    snprintf(notes[nn++], sizeof notes[0], "one bounce misses the light that bounced more). Upward jumps are fireflies: one sample of very");
    snprintf(notes[nn++], sizeof notes[0], "large weight lands at that step and is averaged down as 1/spp after it. The render's own error");
    snprintf(notes[nn++], sizeof notes[0], "estimate jumps with it: it is in the samples, not in the timer or the reference.");
    firefly_list(names, lad, nc, spikes, sizeof spikes);
    if (spikes[0]) {
        char wrapped_lines[6][256];
        int n = pf_wrap(spikes, 92, wrapped_lines, 6), j;
        snprintf(notes[nn++], sizeof notes[0], "Jumps here, with the one pixel's share of the squared error:");
        for (j = 0; j < n && nn < 20; ++j) snprintf(notes[nn++], sizeof notes[0], "  %.150s", wrapped_lines[j]);
    }
    for (i = 0; i < nn; ++i) note_ptr[i] = notes[i];
    memset(&d, 0, sizeof d);
    snprintf(title, sizeof title, "%s scene, %d x %d: relative MSE against render time", name, w, h);
    d.title = title;
    d.x_label = "render time [CPU seconds, all threads]";
    d.y_label = "relative MSE [dimensionless] (luminance, against the reference)";
    d.log_x = d.log_y = 1;
    d.notes = note_ptr; d.note_count = nn;
    d.height = 560 + 18 * nn;
    snprintf(path, sizeof path, "%s/%s.svg", out, name);
    if (!(f = fopen(path, "w"))) { fprintf(stderr, "convergence: cannot write %s: %s\n", path, strerror(errno)); return -1; }
    svgplot_write(f, &d, s, anchor >= 0 ? nc + 1 : nc);
    return close_written(f, path);
}

static const char *base_name(const char *path, char *buf, size_t size)
{
    const char *b = strrchr(path, '/'), *dot;
    size_t len;
    b = b ? b + 1 : path;
    dot = strrchr(b, '.');
    len = dot ? (size_t)(dot - b) : strlen(b);
    if (len >= size) len = size - 1;
    memcpy(buf, b, len); buf[len] = '\0';
    return buf;
}

static int usage(const char *msg)
{
    fprintf(stderr, "convergence: %s\nusage: convergence [--scene default|FILE.dae] [--reference REF.pfm] [--out DIR]\n"
                    "                   [--size W H] [--seconds S] [--ref-seconds S] [--only-reference]\n"
                    "       convergence --replot DATA.csv\n", msg);
    return 2;
}

int main(int argc, char **argv)
{
    const char *scene_arg = "default", *ref_arg = NULL, *out = "build/convergence";
    int w = 160, h = 120, only_ref = 0, i, nc, rw = 0, rh = 0, status;
    double budget = 15.0, ref_budget = 60.0;
    char name[128], ref_path[1024], var_path[1024], line[160];
    config cfg[8];
    ladder lad[8];
    char names[8][64];
    const char *replot = NULL;
    fogrt_scene_desc sd;
    fogrt_scene *scene = NULL;
    fogrt_result r;
    float *ref = NULL, *ref_var = NULL;

    setvbuf(stdout, NULL, _IOLBF, 0);   /* progress lines appear as they happen, also in a log file */
    for (i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--scene") && i + 1 < argc) scene_arg = argv[++i];
        else if (!strcmp(argv[i], "--reference") && i + 1 < argc) ref_arg = argv[++i];
        else if (!strcmp(argv[i], "--out") && i + 1 < argc) out = argv[++i];
        else if (!strcmp(argv[i], "--size") && i + 2 < argc) { w = atoi(argv[i + 1]); h = atoi(argv[i + 2]); i += 2; }
        else if (!strcmp(argv[i], "--seconds") && i + 1 < argc) budget = atof(argv[++i]);
        else if (!strcmp(argv[i], "--ref-seconds") && i + 1 < argc) ref_budget = atof(argv[++i]);
        else if (!strcmp(argv[i], "--only-reference")) only_ref = 1;
        else if (!strcmp(argv[i], "--replot") && i + 1 < argc) replot = argv[++i];
        else { snprintf(line, sizeof line, "unknown or incomplete option '%s'", argv[i]); return usage(line); }
    }
    if (w <= 0 || h <= 0 || w > 4096 || h > 4096) return usage("--size: W and H must be 1..4096");
    if (!(budget > 0.0) || !(ref_budget > 0.0)) return usage("--seconds and --ref-seconds must be positive");
    if (replot) {   /* the plot again from the data, in the data file's directory */
        char dir[1024];
        const char *slash = strrchr(replot, '/');
        snprintf(dir, sizeof dir, "%.*s", slash ? (int)(slash - replot) : 1, slash ? replot : ".");
        if (read_csv(replot, name, sizeof name, &w, &h, names, lad, &nc) != 0) return 1;
        return write_svg(dir, name, w, h, (const char(*)[64])names, lad, nc) != 0;
    }
    if (mkdir(out, 0777) != 0 && errno != EEXIST) { fprintf(stderr, "convergence: cannot create %s: %s\n", out, strerror(errno)); return 1; }

    memset(&sd, 0, sizeof sd);
    sd.logger.func = log_stderr;
    if ((r = fogrt_scene_create(&sd, &scene)) != FOGRT_RESULT_OK) { fprintf(stderr, "convergence: %s\n", fogrt_result_string(r)); return 1; }
    if (!strcmp(scene_arg, "default")) {
        strcpy(name, "default");
        r = fogrt_scene_add_default(scene);
    } else {
        fogrt_load_options opt;
        fogrt_load_report rep;
        memset(&opt, 0, sizeof opt);
        opt.image_width = w; opt.image_height = h; opt.logger.func = log_stderr;
        base_name(scene_arg, name, sizeof name);
        r = fogrt_load_file(scene, scene_arg, &opt, &rep);
        if (r != FOGRT_RESULT_OK) { fprintf(stderr, "%s:%d: %s\n", rep.file, rep.line, rep.message); fogrt_scene_destroy(scene); return 1; }
    }
    if (r == FOGRT_RESULT_OK) r = fogrt_scene_build(scene, NULL);
    if (r != FOGRT_RESULT_OK) { fprintf(stderr, "convergence: %s: %s\n", scene_arg, fogrt_result_string(r)); fogrt_scene_destroy(scene); return 1; }

    /* the reference */
    if (ref_arg) {
        snprintf(ref_path, sizeof ref_path, "%s", ref_arg);
        snprintf(var_path, sizeof var_path, "%.*s_var.pfm", (int)(strlen(ref_arg) > 4 ? strlen(ref_arg) - 4 : strlen(ref_arg)), ref_arg);
    } else {
        snprintf(ref_path, sizeof ref_path, "%s/%s_%dx%d_ref.pfm", out, name, w, h);
        snprintf(var_path, sizeof var_path, "%s/%s_%dx%d_ref_var.pfm", out, name, w, h);
        if (!file_exists(ref_path) || !file_exists(var_path)) {
            if (render_reference(scene, w, h, ref_budget, ref_path, var_path) != 0) { fogrt_scene_destroy(scene); return 1; }
        } else {
            printf("reference: cached %s (delete it to render a new one)\n", ref_path);
        }
    }
    if (read_pfm(ref_path, &rw, &rh, &ref) != 0) { fogrt_scene_destroy(scene); return ref_arg ? 2 : 1; }   /* a bad --reference is bad input */
    if (rw != w || rh != h) {
        fprintf(stderr, "convergence: %s is %d x %d, the render is %d x %d (use --size %d %d)\n", ref_path, rw, rh, w, h, rw, rh);
        free(ref); fogrt_scene_destroy(scene); return 2;
    }
    if (file_exists(var_path)) {
        int vw = 0, vh = 0;
        if (read_pfm(var_path, &vw, &vh, &ref_var) != 0 || vw != w || vh != h) {
            fprintf(stderr, "convergence: %s does not match %s; ignoring it\n", var_path, ref_path);
            free(ref_var); ref_var = NULL;
        }
    } else {
        printf("reference: no %s: its own noise is not subtracted\n", var_path);
    }
    if (only_ref) { free(ref); free(ref_var); fogrt_scene_destroy(scene); return 0; }

    /* the configurations */
    nc = make_configs(cfg);
    for (i = 0; i < nc; ++i) {
        printf("%s: %s, %d x %d, %.0f CPU seconds\n", name, cfg[i].name, w, h, budget);
        if (run_ladder(scene, &cfg[i], w, h, budget, ref, ref_var, &lad[i]) != 0) { free(ref); free(ref_var); fogrt_scene_destroy(scene); return 1; }
    }

    names_from_configs(cfg, nc, names);
    /* the plot is written even when the data file cannot be (and the run then exits 1) */
    status = write_csv(out, name, w, h, (const char(*)[64])names, lad, nc) != 0;
    status |= write_svg(out, name, w, h, (const char(*)[64])names, lad, nc) != 0;
    if (status) { free(ref); free(ref_var); fogrt_scene_destroy(scene); return 1; }
    free(ref); free(ref_var);
    fogrt_scene_destroy(scene);
    return 0;
}
