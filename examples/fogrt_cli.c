/* fogrt - the command-line renderer.

   Renders a CS184 .dae scene, an OBJ or PLY mesh (placed in the default fog-filled Cornell
   box) or, with no scene argument, the embedded default scene. CS184's flags keep CS184's
   meanings, so `fogrt -t 8 -s 64 -l 16 -m 6 -r 480 360 -f out.png scene.dae` works as the
   students type it; the fog and method flags are fogrt's own. `fogrt -h` lists them all with
   their defaults.

   Exit status: 0 on success, 2 for bad input (an unknown flag, a value out of range, a
   missing or malformed scene file, an image too large to allocate), 1 when rendering or
   writing the output fails. Every error is one line on stderr naming the flag or the
   file:line.

   Build: make (the rule is in mk/cli.mk; PNG output uses stb_image_write from libstb-dev). */
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <stdarg.h>
#include <errno.h>
#include <math.h>
#include <time.h>

#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#define FOGRT_LOAD_IMPLEMENTATION
#include "fogrt_load.h"

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wpedantic"
#endif
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb/stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

/* ------------------------------------------------------------------------------------------
   Options and their defaults (keep in step with usage())
   ------------------------------------------------------------------------------------------ */
#define CLI_MAX_SIDE 32768

typedef struct cli_options {
    int spp; bool spp_set;              /* -s */
    int light_samples;                  /* -l */
    int threads;                        /* -t */
    int max_depth;                      /* -m */
    int width, height;                  /* -r */
    const char *output;                 /* -f */
    float lens_radius; bool lens_set;   /* -b */
    float focal; bool focal_set;        /* -d */
    int batch; float tolerance; bool adaptive;   /* -a */
    bool hemisphere;                    /* -H */
    const char *camera_file;            /* -c */
    float density; bool density_set;    /* --density */
    fogrt_vec3 albedo; bool albedo_set; /* --albedo */
    float g; bool g_set; bool paper_g;  /* --g, -g */
    fogrt_integrator integrator;
    fogrt_fresnel fresnel;
    fogrt_bvh_heuristic bvh;
    uint64_t seed;
    double time_budget;                 /* --time, 0 = none */
    double target_error;                /* --target-error, 0 = none */
    bool quiet;
    const char *scene;
} cli_options;

static void usage(FILE *f)
{
    fprintf(f,
        "usage: fogrt [options] [scene.dae | mesh.obj | mesh.ply]\n"
        "Renders a CS184 COLLADA scene, an OBJ/PLY mesh placed in the default fog-filled Cornell\n"
        "box, or (no scene) the embedded default scene.\n"
        "\n"
        "CS184 flags (same meanings as the CS184 pathtracer):\n"
        "  -s N         samples per pixel (default 64)\n"
        "  -l N         samples per area light at each light-sampling step (default 1)\n"
        "  -t N         threads (default 0 = all cores)\n"
        "  -m N         maximum ray depth: bounces after the camera ray, N >= 1 (default 64;\n"
        "               Russian roulette ends paths earlier)\n"
        "  -r W H       image size in pixels (default 800 600, CS184's window); the view keeps\n"
        "               CS184's 800x600 framing at every size\n"
        "  -f FILE      output image: .png, .pfm (linear float) or .ppm (default out.png)\n"
        "  -b R         thin-lens radius (default 0 = pinhole)\n"
        "  -d D         focal distance (default: the distance to the camera's target)\n"
        "  -a B T       adaptive sampling: check every B samples, stop a pixel once its 95%%\n"
        "               confidence half-width is <= T x its mean (default off; -s is the cap)\n"
        "  -H           hemisphere sampling: no light sampling, emitters found by hitting them\n"
        "               (point and spot lights then contribute nothing) (default off)\n"
        "  -c FILE      camera settings file as CS184 writes it (default: the scene's camera)\n"
        "  -g G         Henyey-Greenstein g in [-1, 1], as in the paper's renderer; like the\n"
        "               paper it also switches fog on (density 0.2) when the scene has none\n"
        "               and --density is not given\n"
        "  -h           this help\n"
        "\n"
        "Fog and method flags:\n"
        "  --density S      extinction sigma_t >= 0 per scene unit, the paper's lambda (default:\n"
        "                   the scene's own: 0.3 for the default scene and OBJ/PLY, 0 for .dae)\n"
        "  --albedo A       single-scattering albedo in [0, 1], a scalar or r,g,b (default: the\n"
        "                   scene's: 0.9; .dae files 0.9)\n"
        "  --g G            Henyey-Greenstein g in [-1, 1], > 0 forward (default: the scene's:\n"
        "                   0.6; .dae files 0)\n"
        "  --integrator I   path (global illumination, the paper's Algorithm 1) or direct\n"
        "                   (one bounce, the paper's baseline) (default path)\n"
        "  --fresnel F      schlick or exact (default schlick)\n"
        "  --bvh H          sah or volume (the paper's volume heuristic) (default sah)\n"
        "  --seed N         random seed (default 0); the image is the same on any thread count\n"
        "  --time SECONDS   stop after about this long (default: no limit; without -s the\n"
        "                   sample count is then unlimited)\n"
        "  --target-error E stop when the estimated relative RMS error is <= E (default: none;\n"
        "                   without -s the sample count is then unlimited)\n"
        "  --quiet          no progress line and no summary (errors and warnings still shown)\n"
        "\n"
        "Exit status: 0 ok, 2 bad input (flag, value, scene file), 1 render or write failure.\n");
}

/* One message naming the flag, then exit status 2. */
static int bad_flag(const char *flag, const char *fmt, ...)
{
    va_list ap;
    fprintf(stderr, "fogrt: %s: ", flag);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fprintf(stderr, " (fogrt -h lists the flags)\n");
    return 2;
}

static bool parse_int(const char *s, long lo, long hi, int *out)
{
    char *end;
    long v;
    errno = 0;
    v = strtol(s, &end, 10);
    if (errno || end == s || *end || v < lo || v > hi) return false;
    *out = (int)v;
    return true;
}
static bool parse_float(const char *s, float *out)
{
    char *end;
    double v;
    errno = 0;
    v = strtod(s, &end);
    if (errno || end == s || *end || !(v == v) || v > 3.0e38 || v < -3.0e38) return false;
    *out = (float)v;
    return true;
}
static bool parse_u64(const char *s, uint64_t *out)
{
    char *end;
    unsigned long long v;
    if (*s == '-' || *s == '+') return false;
    errno = 0;
    v = strtoull(s, &end, 10);
    if (errno || end == s || *end) return false;
    *out = (uint64_t)v;
    return true;
}
/* "0.9" or "0.9,0.8,0.7" */
static bool parse_albedo(const char *s, fogrt_vec3 *out)
{
    char buf[128], *a, *b;
    float v[3];
    if (strlen(s) >= sizeof buf) return false;
    strcpy(buf, s);
    a = strchr(buf, ',');
    if (!a) {
        if (!parse_float(buf, &v[0])) return false;
        v[1] = v[2] = v[0];
    } else {
        *a++ = 0;
        b = strchr(a, ',');
        if (!b) return false;
        *b++ = 0;
        if (!parse_float(buf, &v[0]) || !parse_float(a, &v[1]) || !parse_float(b, &v[2])) return false;
    }
    if (v[0] < 0 || v[0] > 1 || v[1] < 0 || v[1] > 1 || v[2] < 0 || v[2] > 1) return false;
    out->x = v[0]; out->y = v[1]; out->z = v[2];
    return true;
}
static bool ends_with(const char *s, const char *ext)
{
    size_t n = strlen(s), m = strlen(ext), i;
    if (n < m) return false;
    for (i = 0; i < m; ++i) {
        char c = s[n - m + i];
        if (c >= 'A' && c <= 'Z') c = (char)(c - 'A' + 'a');
        if (c != ext[i]) return false;
    }
    return true;
}

/* Parses argv into o. Returns 0, or the exit status (2 bad input, -1 help printed). */
static int parse_args(int argc, char **argv, cli_options *o)
{
    int i;
    memset(o, 0, sizeof *o);
    o->spp = 64; o->light_samples = 1; o->threads = 0; o->max_depth = 64;
    o->width = 800; o->height = 600; o->output = "out.png";
    o->integrator = FOGRT_INTEGRATOR_PATH; o->fresnel = FOGRT_FRESNEL_SCHLICK; o->bvh = FOGRT_BVH_SAH;
    for (i = 1; i < argc; ++i) {
        const char *a = argv[i];
#define NEED(n) do { if (i + (n) >= argc) return bad_flag(a, "needs %d value%s", (n), (n) > 1 ? "s" : ""); } while (0)
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) { usage(stdout); return -1; }
        else if (strcmp(a, "-s") == 0) { NEED(1); if (!parse_int(argv[++i], 1, 1 << 24, &o->spp)) return bad_flag(a, "samples per pixel must be an integer in [1, 16777216], got '%s'", argv[i]); o->spp_set = true; }
        else if (strcmp(a, "-l") == 0) { NEED(1); if (!parse_int(argv[++i], 1, 1 << 16, &o->light_samples)) return bad_flag(a, "light samples must be an integer in [1, 65536], got '%s'", argv[i]); }
        else if (strcmp(a, "-t") == 0) { NEED(1); if (!parse_int(argv[++i], 0, 4096, &o->threads)) return bad_flag(a, "threads must be an integer in [0, 4096], got '%s'", argv[i]); }
        else if (strcmp(a, "-m") == 0) { NEED(1); if (!parse_int(argv[++i], 1, 1 << 20, &o->max_depth)) return bad_flag(a, "maximum ray depth must be an integer >= 1, got '%s'", argv[i]); }
        else if (strcmp(a, "-r") == 0) {
            NEED(2);
            if (!parse_int(argv[i + 1], 1, CLI_MAX_SIDE, &o->width) || !parse_int(argv[i + 2], 1, CLI_MAX_SIDE, &o->height))
                return bad_flag(a, "width and height must be integers in [1, %d], got '%s %s'", CLI_MAX_SIDE, argv[i + 1], argv[i + 2]);
            i += 2;
        }
        else if (strcmp(a, "-f") == 0) {
            NEED(1);
            o->output = argv[++i];
            if (!ends_with(o->output, ".png") && !ends_with(o->output, ".pfm") && !ends_with(o->output, ".ppm"))
                return bad_flag(a, "output '%s' must end in .png, .pfm or .ppm", o->output);
        }
        else if (strcmp(a, "-b") == 0) { NEED(1); if (!parse_float(argv[++i], &o->lens_radius) || o->lens_radius < 0) return bad_flag(a, "lens radius must be a number >= 0, got '%s'", argv[i]); o->lens_set = true; }
        else if (strcmp(a, "-d") == 0) { NEED(1); if (!parse_float(argv[++i], &o->focal) || !(o->focal > 0)) return bad_flag(a, "focal distance must be a number > 0, got '%s'", argv[i]); o->focal_set = true; }
        else if (strcmp(a, "-a") == 0) {
            NEED(2);
            if (!parse_int(argv[i + 1], 1, 1 << 20, &o->batch) || !parse_float(argv[i + 2], &o->tolerance) || !(o->tolerance > 0))
                return bad_flag(a, "needs a batch size >= 1 and a tolerance > 0, got '%s %s'", argv[i + 1], argv[i + 2]);
            o->adaptive = true;
            i += 2;
        }
        else if (strcmp(a, "-H") == 0) o->hemisphere = true;
        else if (strcmp(a, "-c") == 0) { NEED(1); o->camera_file = argv[++i]; }
        else if (strcmp(a, "-g") == 0 || strcmp(a, "--g") == 0) {
            NEED(1);
            if (!parse_float(argv[++i], &o->g) || o->g < -1 || o->g > 1) return bad_flag(a, "g must be a number in [-1, 1], got '%s'", argv[i]);
            o->g_set = true;
            if (a[1] == 'g') o->paper_g = true;
        }
        else if (strcmp(a, "--density") == 0) { NEED(1); if (!parse_float(argv[++i], &o->density) || o->density < 0) return bad_flag(a, "density must be a number >= 0, got '%s'", argv[i]); o->density_set = true; }
        else if (strcmp(a, "--albedo") == 0) { NEED(1); if (!parse_albedo(argv[++i], &o->albedo)) return bad_flag(a, "albedo must be a number in [0, 1] or r,g,b with each in [0, 1], got '%s'", argv[i]); o->albedo_set = true; }
        else if (strcmp(a, "--integrator") == 0) {
            NEED(1); ++i;
            if (strcmp(argv[i], "path") == 0) o->integrator = FOGRT_INTEGRATOR_PATH;
            else if (strcmp(argv[i], "direct") == 0) o->integrator = FOGRT_INTEGRATOR_DIRECT;
            else return bad_flag(a, "must be path or direct, got '%s'", argv[i]);
        }
        else if (strcmp(a, "--fresnel") == 0) {
            NEED(1); ++i;
            if (strcmp(argv[i], "schlick") == 0) o->fresnel = FOGRT_FRESNEL_SCHLICK;
            else if (strcmp(argv[i], "exact") == 0) o->fresnel = FOGRT_FRESNEL_EXACT;
            else return bad_flag(a, "must be schlick or exact, got '%s'", argv[i]);
        }
        else if (strcmp(a, "--bvh") == 0) {
            NEED(1); ++i;
            if (strcmp(argv[i], "sah") == 0) o->bvh = FOGRT_BVH_SAH;
            else if (strcmp(argv[i], "volume") == 0) o->bvh = FOGRT_BVH_VOLUME;
            else return bad_flag(a, "must be sah or volume, got '%s'", argv[i]);
        }
        else if (strcmp(a, "--seed") == 0) { NEED(1); if (!parse_u64(argv[++i], &o->seed)) return bad_flag(a, "seed must be a non-negative integer, got '%s'", argv[i]); }
        else if (strcmp(a, "--time") == 0) {
            float t;
            NEED(1);
            if (!parse_float(argv[++i], &t) || !(t > 0)) return bad_flag(a, "time must be a number of seconds > 0, got '%s'", argv[i]);
            o->time_budget = (double)t;
        }
        else if (strcmp(a, "--target-error") == 0) {
            float e;
            NEED(1);
            if (!parse_float(argv[++i], &e) || !(e > 0)) return bad_flag(a, "target error must be a number > 0, got '%s'", argv[i]);
            o->target_error = (double)e;
        }
        else if (strcmp(a, "--quiet") == 0) o->quiet = true;
        else if (a[0] == '-' && a[1] != 0) return bad_flag(a, "unknown flag");
        else {
            if (o->scene) return bad_flag(a, "only one scene file may be given (already have '%s')", o->scene);
            o->scene = a;
        }
#undef NEED
    }
    if (o->adaptive && (o->time_budget > 0 || o->target_error > 0))
        return bad_flag("-a", "cannot be combined with --time or --target-error");
    return 0;
}

/* ------------------------------------------------------------------------------------------
   Time and the progress line
   ------------------------------------------------------------------------------------------ */
static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct progress_state {
    const cli_options *o;
    double t0, last_print;
    uint64_t spp_target;          /* 0: unlimited */
    uint64_t spp_done;            /* before the current call */
    int spp_batch;                /* added by the current call */
    double rel_error;             /* last estimate; < 0 unknown */
    double pixels;
    bool printed;
} progress_state;

static void format_seconds(double s, char *buf, size_t n)
{
    if (!(s >= 0) || s > 1e7) snprintf(buf, n, "?");
    else if (s < 60) snprintf(buf, n, "%.1fs", s);
    else if (s < 3600) snprintf(buf, n, "%dm%02ds", (int)(s / 60), (int)fmod(s, 60));
    else snprintf(buf, n, "%dh%02dm", (int)(s / 3600), (int)fmod(s / 60, 60));
}

/* Fraction done: the furthest of the active stopping rules (samples, time, error). */
static double progress_fraction(const progress_state *p, double spp_now, double elapsed)
{
    double f = 0.0;
    if (p->spp_target) f = spp_now / (double)p->spp_target;
    if (p->o->time_budget > 0) f = fmax(f, elapsed / p->o->time_budget);
    if (p->o->target_error > 0 && p->rel_error > 0 && spp_now > 0) {
        /* the error falls as 1/sqrt(samples): samples needed = now (err / target)^2 */
        double need = spp_now * (p->rel_error / p->o->target_error) * (p->rel_error / p->o->target_error);
        f = fmax(f, spp_now / fmax(need, spp_now));
    }
    return f > 1.0 ? 1.0 : f;
}

static void print_progress(progress_state *p, double spp_now, bool force)
{
    double t = now_seconds(), elapsed = t - p->t0, f, remaining, rate;
    char e[32], r[32], err[32];
    if (p->o->quiet || (!force && t - p->last_print < 0.25)) return;
    p->last_print = t;
    f = progress_fraction(p, spp_now, elapsed);
    remaining = f > 0 ? elapsed * (1.0 - f) / f : -1.0;
    rate = elapsed > 0 ? spp_now * p->pixels / elapsed : 0.0;
    format_seconds(elapsed, e, sizeof e);
    format_seconds(remaining, r, sizeof r);
    if (p->rel_error >= 0) snprintf(err, sizeof err, "%.2f%%", 100.0 * p->rel_error);
    else snprintf(err, sizeof err, "?");
    fprintf(stderr, "\rfogrt: %5.1f%%  %6.1f spp  elapsed %s  remaining %s  %.3g M samples/s  rel. error %s   ",
            100.0 * f, spp_now, e, r, rate * 1e-6, err);
    fflush(stderr);
    p->printed = true;
}

static bool on_progress(const fogrt_progress *pr, void *user)
{
    progress_state *p = (progress_state *)user;
    double spp_now = (double)p->spp_done + (double)p->spp_batch * pr->rows_done / (pr->rows_total > 0 ? pr->rows_total : 1);
    print_progress(p, spp_now, false);
    return true;
}

/* ------------------------------------------------------------------------------------------
   Rendering: progressive batches through fogrt_render, or CS184's per-pixel adaptive loop
   ------------------------------------------------------------------------------------------ */
static fogrt_result render_progressive(const fogrt_scene *scene, fogrt_render_desc *rd, fogrt_image *img,
                                       progress_state *p, uint64_t *rays, uint64_t *spp_out)
{
    const cli_options *o = p->o;
    uint64_t done = 0, batch = 1;
    double rate = 0.0;                 /* samples per pixel per second */
    fogrt_result r = FOGRT_RESULT_OK;
    rd->progress = on_progress;
    rd->user_data = p;
    for (;;) {
        fogrt_render_stats st;
        fogrt_error_estimate ee;
        uint64_t b = batch;
        double t_start = now_seconds(), elapsed = t_start - p->t0;
        if (p->spp_target && done >= p->spp_target) break;
        if (p->spp_target && b > p->spp_target - done) b = p->spp_target - done;
        if (o->time_budget > 0) {
            double left = o->time_budget - elapsed;
            if (left <= 0 && done > 0) break;
            if (rate > 0 && (double)b > left * rate) b = (uint64_t)fmax(1.0, floor(left * rate));
        }
        p->spp_done = done;
        p->spp_batch = (int)b;
        r = fogrt_render(scene, rd, img, (int)b, &st);
        if (r) break;
        *rays += st.rays;
        done += b;
        fogrt_image_error(img, &ee);
        p->rel_error = done >= 2 ? ee.relative_error : -1.0;
        p->spp_done = done; p->spp_batch = 0;
        rate = (double)done / fmax(now_seconds() - p->t0, 1e-6);
        print_progress(p, (double)done, false);
        if (o->target_error > 0 && done >= 2 && ee.relative_error <= o->target_error) break;
        if (o->time_budget > 0 && now_seconds() - p->t0 >= o->time_budget) break;
        if (batch < 64) batch *= 2;
    }
    *spp_out = done;
    return r;
}

/* CS184 -a: per pixel, after every `batch` samples, stop once 1.96 sigma / sqrt(n) <= tol mu
   (luminance); -s is the cap. Each pixel has its own random stream (seed, pixel). */
static void render_adaptive(const fogrt_scene *scene, const fogrt_render_desc *rd, fogrt_image *img,
                            progress_state *p, uint64_t *rays_out, uint64_t *samples_out)
{
    const cli_options *o = p->o;
    int W = img->width, H = img->height, y, rows_done = 0;
    uint64_t rays = 0, samples = 0, rejected = 0;
#ifdef _OPENMP
    int nthreads = o->threads > 0 ? o->threads : omp_get_max_threads();
#pragma omp parallel for schedule(dynamic, 1) num_threads(nthreads) reduction(+ : rays, samples, rejected)
#endif
    for (y = 0; y < H; ++y) {
        int x;
        for (x = 0; x < W; ++x) {
            size_t pix = (size_t)y * (size_t)W + (size_t)x;
            fogrt_rng rng;
            double s1 = 0.0, s2 = 0.0;
            uint32_t n = 0, taken = 0;
            fogrt_rng_seed(&rng, rd->seed, (uint64_t)pix);
            while (taken < (uint32_t)o->spp) {
                int k;
                for (k = 0; k < o->batch && taken < (uint32_t)o->spp; ++k, ++taken) {
                    fogrt_vec3 org, dir, L;
                    float jx = fogrt_rng_float(&rng), jy = fogrt_rng_float(&rng);
                    float l1 = fogrt_rng_float(&rng), l2 = fogrt_rng_float(&rng), lum;
                    fogrt_camera_ray(scene, W, H, (float)x + jx, (float)y + jy, l1, l2, &org, &dir);
                    L = fogrt_trace(scene, rd, org, dir, &rng, &rays);
                    if (!(L.x - L.x == 0.0f && L.y - L.y == 0.0f && L.z - L.z == 0.0f)) { rejected++; continue; }
                    lum = 0.2126f * L.x + 0.7152f * L.y + 0.0722f * L.z;
                    img->sum[3 * pix] += L.x; img->sum[3 * pix + 1] += L.y; img->sum[3 * pix + 2] += L.z;
                    img->sum_sq[pix] += lum * lum;
                    s1 += (double)lum; s2 += (double)lum * (double)lum;
                    n++;
                }
                if (n >= 2) {
                    double mu = s1 / n, var = fmax(0.0, (s2 - s1 * s1 / n) / (n - 1));
                    if (1.96 * sqrt(var / n) <= (double)o->tolerance * mu) break;
                }
            }
            img->count[pix] = n;
            samples += taken;
        }
#ifdef _OPENMP
#pragma omp critical
#endif
        {
            rows_done++;
#ifdef _OPENMP
            if (omp_get_thread_num() == 0)
#endif
            {
                p->spp_done = 0; p->spp_batch = o->spp;
                print_progress(p, (double)o->spp * rows_done / H, false);
            }
        }
    }
    img->rejected += rejected;
    *rays_out = rays;
    *samples_out = samples;
}

/* ------------------------------------------------------------------------------------------
   Output
   ------------------------------------------------------------------------------------------ */
static bool write_image(const char *path, int W, int H, const float *rgb, unsigned char *rgb8)
{
    if (ends_with(path, ".pfm")) return fogrt_write_pfm(path, W, H, rgb) == FOGRT_RESULT_OK;
    fogrt_tonemap_rgb8(rgb, W, H, 1.0f, FOGRT_TONEMAP_SRGB, rgb8);
    if (ends_with(path, ".ppm")) return fogrt_write_ppm(path, W, H, rgb8) == FOGRT_RESULT_OK;
    return stbi_write_png(path, W, H, 3, rgb8, W * 3) != 0;
}

/* Checks early that the output can be written (so a long render never ends in a lost image). */
static bool output_writable(const char *path)
{
    FILE *f = fopen(path, "rb");
    bool existed = f != NULL;
    if (f) fclose(f);
    f = fopen(path, "ab");
    if (!f) return false;
    fclose(f);
    if (!existed) remove(path);
    return true;
}

static void log_to_stderr(fogrt_log_level level, const char *message, void *user)
{
    (void)user;
    fprintf(stderr, "fogrt: %s%s\n", level == FOGRT_LOG_ERROR ? "error: " : level == FOGRT_LOG_WARNING ? "warning: " : "", message);
}
static void load_warning(fogrt_log_level level, const char *message, void *user)
{
    (void)level; (void)user;
    fprintf(stderr, "fogrt: %s\n", message);     /* already "file:line: warning: ..." */
}

/* ------------------------------------------------------------------------------------------
   main
   ------------------------------------------------------------------------------------------ */
int main(int argc, char **argv)
{
    cli_options o;
    fogrt_scene_desc sd;
    fogrt_scene *scene = NULL;
    fogrt_load_options lo;
    fogrt_load_report rep;
    fogrt_medium_desc md;
    fogrt_camera_desc cam;
    fogrt_build_desc bd;
    fogrt_render_desc rd;
    fogrt_image img;
    fogrt_error_estimate ee;
    progress_state ps;
    float *rgb = NULL;
    unsigned char *rgb8 = NULL;
    uint64_t rays = 0, spp_done = 0, samples = 0;
    bool is_dae = false;
    fogrt_result r;
    double t0, t_load, elapsed;
    int status = 0;

    status = parse_args(argc, argv, &o);
    if (status == -1) return 0;
    if (status) return status;
    if (!output_writable(o.output)) {
        fprintf(stderr, "fogrt: -f %s: cannot write: %s\n", o.output, strerror(errno));
        return 2;
    }

    /* The scene */
    t0 = now_seconds();
    memset(&sd, 0, sizeof sd);
    sd.logger.func = log_to_stderr;
    if (fogrt_scene_create(&sd, &scene) != FOGRT_RESULT_OK) { fprintf(stderr, "fogrt: out of memory\n"); return 1; }
    memset(&lo, 0, sizeof lo);
    lo.image_width = o.width; lo.image_height = o.height;
    lo.logger.func = load_warning;
    if (!o.scene) {
        r = fogrt_scene_add_default(scene);
        if (r) { fprintf(stderr, "fogrt: default scene: %s\n", fogrt_result_string(r)); fogrt_scene_destroy(scene); return 1; }
    } else {
        is_dae = ends_with(o.scene, ".dae");
        if (!is_dae && !ends_with(o.scene, ".obj") && !ends_with(o.scene, ".ply")) {
            fprintf(stderr, "fogrt: %s: unknown scene type (expected .dae, .obj or .ply)\n", o.scene);
            fogrt_scene_destroy(scene);
            return 2;
        }
        if (!is_dae) {               /* a mesh: into the default fog-filled Cornell box */
            r = fogrt_scene_add_default(scene);
            if (r) { fprintf(stderr, "fogrt: default scene: %s\n", fogrt_result_string(r)); fogrt_scene_destroy(scene); return 1; }
        }
        r = fogrt_load_file(scene, o.scene, &lo, &rep);
        if (r) {
            if (rep.line > 0) fprintf(stderr, "fogrt: %s:%d: %s\n", rep.file, rep.line, rep.message);
            else fprintf(stderr, "fogrt: %s: %s\n", rep.file, rep.message[0] ? rep.message : fogrt_result_string(r));
            fogrt_scene_destroy(scene);
            return r == FOGRT_RESULT_OUT_OF_MEMORY ? 1 : 2;
        }
    }

    /* The fog: the scene's own, changed by the flags */
    fogrt_scene_get_medium(scene, &md);
    if (is_dae && md.sigma_t == 0.0f) {          /* .dae files carry no fog: fogrt's defaults */
        md.albedo = fogrt__ld_v3(0.9f, 0.9f, 0.9f);
        md.g = 0.0f;
    }
    if (o.density_set) md.sigma_t = o.density;
    else if (o.paper_g && md.sigma_t == 0.0f) md.sigma_t = 0.2f;   /* the paper's -g switches fog on */
    if (o.albedo_set) md.albedo = o.albedo;
    if (o.g_set) md.g = o.g;
    r = fogrt_scene_set_medium(scene, &md);
    if (r) { fprintf(stderr, "fogrt: --density/--albedo/--g: %s\n", fogrt_result_string(r)); fogrt_scene_destroy(scene); return 2; }

    /* The camera: -c replaces it; -b and -d set the lens */
    if (o.camera_file) {
        r = fogrt_load_camera_file(o.camera_file, o.width, o.height, &cam, &rep);
        if (r) {
            if (rep.line > 0) fprintf(stderr, "fogrt: -c %s:%d: %s\n", rep.file, rep.line, rep.message);
            else fprintf(stderr, "fogrt: -c %s: %s\n", rep.file, rep.message);
            fogrt_scene_destroy(scene);
            return 2;
        }
    } else {
        fogrt_scene_get_camera(scene, &cam);
    }
    if (o.lens_set) cam.lens_radius = o.lens_radius;
    if (o.focal_set) cam.focal_distance = o.focal;
    r = fogrt_scene_set_camera(scene, &cam);
    if (r) {
        fprintf(stderr, "fogrt: %s: %s\n", o.camera_file ? "-c" : (o.lens_set || o.focal_set) ? "-b/-d" : "camera", fogrt_result_string(r));
        fogrt_scene_destroy(scene);
        return 2;
    }

    /* Build */
    bd = fogrt_build_defaults();
    bd.heuristic = o.bvh;
    r = fogrt_scene_build(scene, &bd);
    if (r) {
        fprintf(stderr, "fogrt: %s: %s\n", o.scene ? o.scene : "default scene", fogrt_result_string(r));
        fogrt_scene_destroy(scene);
        return r == FOGRT_RESULT_EMPTY_SCENE ? 2 : 1;
    }
    t_load = now_seconds() - t0;

    /* The image and the output buffers, all allocated before rendering */
    r = fogrt_image_alloc(&img, o.width, o.height, NULL);
    if (!r) {
        rgb = (float *)malloc(sizeof(float) * 3 * (size_t)o.width * (size_t)o.height);
        rgb8 = (unsigned char *)malloc(3 * (size_t)o.width * (size_t)o.height);
        if (!rgb || !rgb8) { fogrt_image_free(&img); r = FOGRT_RESULT_OUT_OF_MEMORY; }
    }
    if (r) {
        fprintf(stderr, "fogrt: -r %d %d: image too large to allocate (%s)\n", o.width, o.height, fogrt_result_string(r));
        free(rgb); free(rgb8);
        fogrt_scene_destroy(scene);
        return 2;
    }

    /* Render */
    rd = fogrt_render_defaults();
    rd.width = o.width; rd.height = o.height;
    rd.integrator = o.integrator;
    rd.fresnel = o.fresnel;
    rd.max_depth = o.max_depth;
    rd.light_samples = o.light_samples;
    rd.nee = !o.hemisphere;
    rd.seed = o.seed;
    rd.threads = o.threads;
    memset(&ps, 0, sizeof ps);
    ps.o = &o;
    ps.t0 = now_seconds();
    ps.rel_error = -1.0;
    ps.pixels = (double)o.width * (double)o.height;
    ps.spp_target = (o.spp_set || (o.time_budget <= 0 && o.target_error <= 0)) ? (uint64_t)o.spp : 0;
    if (o.adaptive) {
        render_adaptive(scene, &rd, &img, &ps, &rays, &samples);
        spp_done = (uint64_t)o.spp;
        r = FOGRT_RESULT_OK;
    } else {
        r = render_progressive(scene, &rd, &img, &ps, &rays, &spp_done);
        samples = spp_done * (uint64_t)o.width * (uint64_t)o.height;
    }
    elapsed = now_seconds() - ps.t0;
    if (ps.printed) fprintf(stderr, "\n");
    if (r) {
        fprintf(stderr, "fogrt: render failed: %s\n", fogrt_result_string(r));
        status = 1;
    } else {
        fogrt_image_resolve(&img, rgb);
        fogrt_image_error(&img, &ee);
        if (!write_image(o.output, o.width, o.height, rgb, rgb8)) {
            fprintf(stderr, "fogrt: -f %s: could not write the image\n", o.output);
            status = 1;
        } else if (!o.quiet) {
            fprintf(stderr, "fogrt: wrote %s (%dx%d): %s%.1f spp in %.2f s (load %.2f s), %.3g M samples/s, "
                    "rel. error %.2f%%, %llu non-finite samples dropped\n",
                    o.output, o.width, o.height, o.adaptive ? "adaptive, mean " : "",
                    (double)samples / ((double)o.width * o.height), elapsed, t_load,
                    elapsed > 0 ? (double)samples / elapsed * 1e-6 : 0.0, 100.0 * ee.relative_error,
                    (unsigned long long)img.rejected);
        }
    }
    (void)spp_done;
    free(rgb); free(rgb8);
    fogrt_image_free(&img);
    fogrt_scene_destroy(scene);
    return status;
}
