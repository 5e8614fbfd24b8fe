/* figures.c - the paper's experiments (its figures 2, 3 and 4) and three more, with numbers.

   Usage: figures [--out DIR] [--doc FILE.md] [--shared DIR] [--size W H] [--quick]
     --out DIR      where the PNG images and SVG plots go (default build/figures; make
                    figures-docs writes docs/figures)
     --doc FILE     the Markdown report (default build/figures/experiments.md); image
                    links in it are relative to the report's directory
     --shared DIR   the shared data directory holding scenes/cs184/CBbunny_upSpot.dae
                    (default ../shared); when that scene is missing its panels are skipped
                    with a message and the default scene stands in where it can
     --size W H     image size (default 200 150)
     --quick        a quarter of the samples everywhere (a smoke run; not for the docs)
     --only NAME    one experiment: fig2, fig3, fig4, equiangular, bvh or fresnel

   Every caption in the report gives the samples per pixel, the CPU seconds (process CPU
   time, all threads) and a measured error; every PNG carries a caption of its own (what it
   shows, its settings, samples per pixel and error, no times):
     - "relMSE vs reference": (sum_p (L_p - R_p)^2 - sum_p Var[R_p]) / sum_p R_p^2 on
       luminance, R a long path NEE+MIS render with another seed, Var[R_p] its own noise;
       this includes bias (a method that misses light shows it here).
     - "noise relMSE (halves)": the image is rendered as two independent halves A and B
       (different seeds); sum_p ((A_p - B_p)/2)^2 / sum_p M_p^2 (M the combined image) is a
       direct measurement of the combined image's variance (no bias, no reference needed).
     - "estimated": fogrt_image_error's relative_error squared (the render's own estimate).
   Uses only the public APIs of fogrt.h and fogrt_load.h; PNGs go through stb_image_write
   (Debian libstb-dev). */
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
#include "stb_write.h"           /* stb_image_write, its warnings silenced */
#include "plotfont.h"            /* the captions drawn into the PNGs */

/* ---- settings ---------------------------------------------------------------------------- */
static int W = 200, H = 150;
static int quick = 0;
static const char *out_dir = "build/figures";
static const char *doc_path = "build/figures/experiments.md";
static char figs_rel[512] = "figures";   /* out_dir as seen from the report's directory */
static char spot_path[1024];
static int have_spot = 0;
static FILE *md;   /* the report */
static int failures = 0;
static const char *only = NULL;   /* --only NAME: one experiment (development) */

static int spp_of(int n) { return quick ? (n >= 4 ? n / 4 : 1) : n; }

static double cpu_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
static double lum3(const double *c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

static void log_stderr(fogrt_log_level level, const char *msg, void *user)
{
    (void)user;
    if (level == FOGRT_LOG_ERROR || level == FOGRT_LOG_WARNING)
        fprintf(stderr, "fogrt: %s: %s\n", level == FOGRT_LOG_ERROR ? "error" : "warning", msg);
}

/* Stops the program with one line when a fogrt call fails. */
static void check(fogrt_result r, const char *what)
{
    if (r == FOGRT_RESULT_OK) return;
    fprintf(stderr, "figures: %s: %s\n", what, fogrt_result_string(r));
    exit(1);
}

/* ---- scenes ------------------------------------------------------------------------------ */
typedef enum scene_kind { SCENE_SPOT, SCENE_DEFAULT, SCENE_POINT, SCENE_BEAM_TO_CAMERA, SCENE_BEAM_AWAY } scene_kind;
static const char *scene_title(scene_kind k)
{
    return k == SCENE_SPOT ? "CBbunny_upSpot.dae (the paper's spot-light scene)" :
           k == SCENE_DEFAULT ? "fogrt's default scene (ceiling lamp + spot light, glass sphere)" :
           k == SCENE_POINT ? "point light in fog (the CS184 box, built in code)" :
           k == SCENE_BEAM_TO_CAMERA ? "spot light aimed at the camera (the CS184 box, built in code)" :
           "spot light aimed away from the camera (the CS184 box, built in code)";
}

/* The scene in a few words, for a picture's caption. */
static const char *scene_short(scene_kind k)
{
    return k == SCENE_SPOT ? "CBbunny_upSpot" : k == SCENE_DEFAULT ? "default scene" : k == SCENE_POINT ? "point light in fog" :
           k == SCENE_BEAM_TO_CAMERA ? "spot aimed at the camera" : "spot aimed away";
}

static void add_quad(fogrt_scene *s, const float *p, uint32_t mat)
{
    static const uint32_t idx[6] = { 0, 1, 2, 0, 2, 3 };
    fogrt_mesh_desc m;
    memset(&m, 0, sizeof m);
    m.positions = p; m.vertex_count = 4; m.indices = idx; m.triangle_count = 2; m.material = mat;
    check(fogrt_scene_add_mesh(s, &m), "add_mesh");
}
static fogrt_vec3 vec3(float x, float y, float z) { fogrt_vec3 v; v.x = x; v.y = y; v.z = z; return v; }

/* The CS184 Cornell box (x, z in [-1, 1], y in [0, 1.5], open toward the camera at +z), lit
   only by one light at the middle of the box, looked at straight on: a point light, or a
   spot light (25 degree cone) aimed at the camera or away from it (at the back wall). */
#define POINT_LIGHT_Z 0.0f
#define EQ_SIGMA 0.1f   /* the fog of the equiangular experiment: thin, where equiangular sampling matters most */
static void build_point_scene(fogrt_scene *s, scene_kind kind)
{
    fogrt_material_desc mat;
    fogrt_light_desc ld;
    fogrt_camera_desc cd;
    uint32_t white, red, blue;
    static const float floor_q[12] = { -1, 0, -1, -1, 0, 1, 1, 0, 1, 1, 0, -1 };
    static const float ceil_q[12] = { -1, 1.5f, -1, 1, 1.5f, -1, 1, 1.5f, 1, -1, 1.5f, 1 };
    static const float back_q[12] = { -1, 0, -1, 1, 0, -1, 1, 1.5f, -1, -1, 1.5f, -1 };
    static const float left_q[12] = { -1, 0, -1, -1, 1.5f, -1, -1, 1.5f, 1, -1, 0, 1 };
    static const float right_q[12] = { 1, 0, -1, 1, 0, 1, 1, 1.5f, 1, 1, 1.5f, -1 };
    memset(&mat, 0, sizeof mat);
    mat.type = FOGRT_BSDF_DIFFUSE;
    mat.reflectance = vec3(0.73f, 0.73f, 0.73f); check(fogrt_scene_add_material(s, &mat, &white), "material");
    mat.reflectance = vec3(0.65f, 0.06f, 0.05f); check(fogrt_scene_add_material(s, &mat, &red), "material");
    mat.reflectance = vec3(0.08f, 0.12f, 0.60f); check(fogrt_scene_add_material(s, &mat, &blue), "material");
    add_quad(s, floor_q, white); add_quad(s, ceil_q, white); add_quad(s, back_q, white);
    add_quad(s, left_q, red); add_quad(s, right_q, blue);
    memset(&ld, 0, sizeof ld);
    ld.type = kind == SCENE_POINT ? FOGRT_LIGHT_POINT : FOGRT_LIGHT_SPOT;
    ld.position = vec3(0.0f, 0.75f, POINT_LIGHT_Z);
    ld.intensity = vec3(2.0f, 2.0f, 2.0f);
    ld.direction = vec3(0.0f, 0.0f, kind == SCENE_BEAM_TO_CAMERA ? 1.0f : -1.0f);
    ld.cutoff_deg = 25.0f; ld.beam_deg = 20.0f;
    check(fogrt_scene_add_light(s, &ld), "light");
    memset(&cd, 0, sizeof cd);
    cd.position = vec3(0.0f, 0.75f, 3.6f);
    cd.look_at = ld.position;
    cd.fov_deg = 38.0f;
    check(fogrt_scene_set_camera(s, &cd), "camera");
}

/* A built scene of the given kind with the given fog (sigma_t < 0: the scene's own fog). */
static fogrt_scene *make_scene(scene_kind kind, float sigma_t, float albedo, float g, fogrt_bvh_heuristic bvh)
{
    fogrt_scene_desc sd;
    fogrt_scene *s = NULL;
    fogrt_build_desc bd = fogrt_build_defaults();
    memset(&sd, 0, sizeof sd);
    sd.logger.func = log_stderr;
    check(fogrt_scene_create(&sd, &s), "scene_create");
    if (kind == SCENE_SPOT) {
        fogrt_load_options opt;
        fogrt_load_report rep;
        memset(&opt, 0, sizeof opt);
        opt.image_width = W; opt.image_height = H;
        if (fogrt_load_file(s, spot_path, &opt, &rep) != FOGRT_RESULT_OK) {
            fprintf(stderr, "%s:%d: %s\n", rep.file, rep.line, rep.message);
            exit(1);
        }
    } else if (kind == SCENE_DEFAULT) {
        check(fogrt_scene_add_default(s), "add_default");
    } else {
        build_point_scene(s, kind);
    }
    if (sigma_t >= 0.0f) {
        fogrt_medium_desc m;
        memset(&m, 0, sizeof m);   /* unbounded: the fog fills all space, as in the paper */
        m.sigma_t = sigma_t; m.albedo = vec3(albedo, albedo, albedo); m.g = g;
        check(fogrt_scene_set_medium(s, &m), "set_medium");
    }
    bd.heuristic = bvh;
    check(fogrt_scene_build(s, &bd), "build");
    return s;
}

/* Image position (pixels) of a world point, by the pinhole model fogrt's camera uses. */
static void project(const fogrt_scene *s, fogrt_vec3 p, double *px, double *py)
{
    fogrt_camera_desc c;
    double f[3], r[3], u[3], d[3], up[3], n, t, tx, ty, z;
    fogrt_scene_get_camera(s, &c);
    f[0] = c.look_at.x - c.position.x; f[1] = c.look_at.y - c.position.y; f[2] = c.look_at.z - c.position.z;
    n = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]); f[0] /= n; f[1] /= n; f[2] /= n;
    up[0] = c.up.x; up[1] = c.up.y; up[2] = c.up.z;
    if (up[0] == 0.0 && up[1] == 0.0 && up[2] == 0.0) up[1] = 1.0;
    r[0] = f[1] * up[2] - f[2] * up[1]; r[1] = f[2] * up[0] - f[0] * up[2]; r[2] = f[0] * up[1] - f[1] * up[0];
    n = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]); r[0] /= n; r[1] /= n; r[2] /= n;
    u[0] = r[1] * f[2] - r[2] * f[1]; u[1] = r[2] * f[0] - r[0] * f[2]; u[2] = r[0] * f[1] - r[1] * f[0];
    d[0] = p.x - c.position.x; d[1] = p.y - c.position.y; d[2] = p.z - c.position.z;
    t = tan(0.5 * (double)c.fov_deg * 3.14159265358979 / 180.0);
    if (c.fov_is_horizontal) { tx = t; ty = t * H / W; } else { ty = t; tx = t * W / H; }
    z = d[0] * f[0] + d[1] * f[1] + d[2] * f[2];
    *px = 0.5 * W * (1.0 + (d[0] * r[0] + d[1] * r[1] + d[2] * r[2]) / z / tx);
    *py = 0.5 * H * (1.0 - (d[0] * u[0] + d[1] * u[1] + d[2] * u[2]) / z / ty);
}

/* ---- rendering and measuring ------------------------------------------------------------- */
typedef struct shot {
    fogrt_image img;
    double seconds;   /* CPU seconds spent on img so far */
} shot;

static void shot_init(shot *s) { check(fogrt_image_alloc(&s->img, W, H, NULL), "image_alloc"); s->seconds = 0.0; }
/* Adds samples until img has `total` per pixel. */
static void shot_render(shot *s, const fogrt_scene *scene, const fogrt_render_desc *rd, int total)
{
    double t0 = cpu_seconds();
    int have = (int)s->img.count[0];
    if (total > have) check(fogrt_render(scene, rd, &s->img, total - have, NULL), "render");
    s->seconds += cpu_seconds() - t0;
}
static double pix_lum(const fogrt_image *img, size_t i) { return img->count[i] ? lum3(img->sum + 3 * i) / img->count[i] : 0.0; }
/* The variance of pixel i's mean luminance: fogrt's between-stream estimate (the sample
   variance would overestimate it, the pixel positions being stratified). */
static double pix_var(const fogrt_image *img, size_t i) { return fogrt_image_pixel_variance(img, i); }
static double mean_lum(const fogrt_image *img)
{
    size_t i, n = (size_t)W * H;
    double s = 0.0;
    for (i = 0; i < n; ++i) s += pix_lum(img, i);
    return s / (double)n;
}
/* Measured relMSE against a reference render, its own noise subtracted. */
static double rel_mse_vs(const fogrt_image *img, const fogrt_image *ref)
{
    size_t i, n = (size_t)W * H;
    double se = 0.0, var = 0.0, norm = 0.0;
    for (i = 0; i < n; ++i) {
        double d = pix_lum(img, i) - pix_lum(ref, i), r = pix_lum(ref, i);
        se += d * d; var += pix_var(ref, i); norm += r * r;
    }
    return norm > 0.0 ? (se - var) / norm : 0.0;
}
static double estimated(const fogrt_image *img)
{
    fogrt_error_estimate e;
    fogrt_image_error(img, &e);
    return e.relative_error * e.relative_error;
}

/* Two independent halves (seeds a and b) of spp/2 samples each; *merged gets both. */
typedef struct halves { double noise, est, seconds, mean; } halves;
static halves render_halves(const fogrt_scene *scene, fogrt_render_desc rd, int spp, shot *merged)
{
    shot a, b;
    halves h;
    size_t i, n = (size_t)W * H;
    double se = 0.0, norm = 0.0;
    shot_init(&a); shot_init(&b);
    rd.seed = 1; shot_render(&a, scene, &rd, spp / 2);
    rd.seed = 2; shot_render(&b, scene, &rd, spp - spp / 2);
    shot_init(merged);
    for (i = 0; i < n; ++i) {
        int c;
        double la = pix_lum(&a.img, i), lb = pix_lum(&b.img, i), m;
        for (c = 0; c < 3; ++c) merged->img.sum[3 * i + c] = a.img.sum[3 * i + c] + b.img.sum[3 * i + c];
        merged->img.sum_sq[i] = a.img.sum_sq[i] + b.img.sum_sq[i];
        merged->img.count[i] = a.img.count[i] + b.img.count[i];
        /* stream r of the merge holds both halves' stream r: still independent of the others */
        for (c = 0; c < FOGRT_IMAGE_STREAMS; ++c) {
            merged->img.stream_sum[FOGRT_IMAGE_STREAMS * i + c] = a.img.stream_sum[FOGRT_IMAGE_STREAMS * i + c] + b.img.stream_sum[FOGRT_IMAGE_STREAMS * i + c];
            merged->img.stream_count[FOGRT_IMAGE_STREAMS * i + c] = a.img.stream_count[FOGRT_IMAGE_STREAMS * i + c] + b.img.stream_count[FOGRT_IMAGE_STREAMS * i + c];
        }
        m = pix_lum(&merged->img, i);
        se += 0.25 * (la - lb) * (la - lb);
        norm += m * m;
    }
    merged->seconds = a.seconds + b.seconds;
    h.noise = norm > 0.0 ? se / norm : 0.0;
    h.est = estimated(&merged->img);
    h.seconds = merged->seconds;
    h.mean = mean_lum(&merged->img);
    fogrt_image_free(&a.img); fogrt_image_free(&b.img);
    return h;
}

/* An exposure that puts the 99th percentile of a reference image's luminance at 0.9. */
static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}
static float exposure_for(const fogrt_image *img)
{
    size_t i, n = (size_t)W * H;
    double *v = (double *)malloc(sizeof(double) * n), p;
    if (!v) return 1.0f;
    for (i = 0; i < n; ++i) v[i] = pix_lum(img, i);
    qsort(v, n, sizeof(double), cmp_double);
    p = v[(size_t)(0.99 * (double)(n - 1))];
    free(v);
    return p > 0.0 ? (float)(0.9 / p) : 1.0f;
}

/* Writes OUT/name.png and returns the path relative to the report (static buffer). The
   image is drawn at twice its size with a caption under it, what it shows (`what`) and its
   settings and numbers (`detail`), so that it reads on a projector without the report.
   Captions hold samples per pixel and errors, never times: with a fixed sample count the
   picture is the same on every run of one build. */
static const char *save_png(const char *name, const fogrt_image *img, float exposure, const char *what, const char *detail)
{
    static char rel[8][600];
    static int slot = 0;
    char path[1024];
    const char *lines[2];
    const int zoom = 2;
    float *rgb = (float *)malloc(sizeof(float) * 3 * (size_t)W * H);
    unsigned char *rgb8 = (unsigned char *)malloc(3 * (size_t)W * H), *big = (unsigned char *)malloc(3 * (size_t)W * H * zoom * zoom);
    pf_canvas c;
    int x, y;
    if (!rgb || !rgb8 || !big) { fprintf(stderr, "figures: out of memory\n"); exit(1); }
    fogrt_image_resolve(img, rgb);
    fogrt_tonemap_rgb8(rgb, W, H, log2f(exposure), FOGRT_TONEMAP_SRGB, rgb8);   /* a multiplier here, stops there */
    for (y = 0; y < H * zoom; ++y)
        for (x = 0; x < W * zoom; ++x) memcpy(big + 3 * ((size_t)y * W * zoom + x), rgb8 + 3 * ((size_t)(y / zoom) * W + x / zoom), 3);
    lines[0] = what; lines[1] = detail;
    c = pf_captioned(big, W * zoom, H * zoom, lines, 2, 2);
    snprintf(path, sizeof path, "%s/%s.png", out_dir, name);
    if (!stbi_write_png(path, c.w, c.h, 3, c.rgb, c.w * 3)) { fprintf(stderr, "figures: cannot write %s\n", path); exit(1); }
    pf_canvas_free(&c);
    free(rgb); free(rgb8); free(big);
    printf("  wrote %s\n", path);
    slot = (slot + 1) % 8;
    snprintf(rel[slot], sizeof rel[slot], "%s/%s.png", figs_rel, name);
    return rel[slot];
}

/* Writes OUT/name.svg (a plot) and returns the path relative to the report. */
static const char *save_svg(const char *name, const svgplot_desc *d, const svgplot_series *s, int ns)
{
    static char rel[600];
    char path[1024];
    FILE *f;
    snprintf(path, sizeof path, "%s/%s.svg", out_dir, name);
    if (!(f = fopen(path, "w"))) { fprintf(stderr, "figures: cannot write %s: %s\n", path, strerror(errno)); exit(1); }
    svgplot_write(f, d, s, ns);
    fclose(f);
    printf("  wrote %s\n", path);
    snprintf(rel, sizeof rel, "%s/%s.svg", figs_rel, name);
    return rel;
}

static void shot_free(shot *s) { fogrt_image_free(&s->img); }

/* The reference of a scene: path NEE+MIS, its own seed. */
static void render_reference(const fogrt_scene *scene, int spp, shot *ref)
{
    fogrt_render_desc rd = fogrt_render_paper_defaults();
    rd.seed = 0xC0FFEE;
    shot_init(ref);
    shot_render(ref, scene, &rd, spp);
    printf("  reference: %d spp, %.1f CPU s, estimated relMSE %.2e\n", (int)ref->img.count[0], ref->seconds, estimated(&ref->img));
}

/* ---- Figure 2: one bounce vs global illumination, with and without light sampling --------- */
static void figure2_scene(scene_kind kind, const char *tag)
{
    static const char *names[4] = { "one bounce, NEE", "one bounce, no NEE", "global illumination, NEE+MIS", "global illumination, no NEE" };
    fogrt_scene *scene = kind == SCENE_SPOT ? make_scene(kind, 0.2f, 0.9f, 0.0f, FOGRT_BVH_SAH)
                                            : make_scene(kind, -1.0f, 0.0f, 0.0f, FOGRT_BVH_SAH);
    shot ref;
    float expo;
    int c, lo = spp_of(4) < 4 ? 1 : 4, hi = spp_of(256);
    printf("figure 2, %s\n", scene_title(kind));
    render_reference(scene, spp_of(1024), &ref);
    expo = exposure_for(&ref.img);
    fprintf(md, "\n### %s\n\nReference: path NEE+MIS, %d spp, %.1f CPU s (estimated relMSE %.1e); mean luminance %.4g. "
                "Columns: %d and %d samples per pixel.\n\n| method | %d spp | %d spp |\n|---|---|---|\n",
            scene_title(kind), (int)ref.img.count[0], ref.seconds, estimated(&ref.img), mean_lum(&ref.img), lo, hi, lo, hi);
    for (c = 0; c < 4; ++c) {
        fogrt_render_desc rd = fogrt_render_paper_defaults();
        shot s;
        char name[64], cell[2][700];
        int k;
        rd.integrator = c < 2 ? FOGRT_INTEGRATOR_DIRECT : FOGRT_INTEGRATOR_PATH;
        rd.nee = (c % 2) == 0;
        shot_init(&s);
        for (k = 0; k < 2; ++k) {
            const char *png;
            double meas, est, ratio;
            char what[160], detail[160];
            shot_render(&s, scene, &rd, k ? hi : lo);
            snprintf(name, sizeof name, "fig2_%s_%s%s_%d", tag, c < 2 ? "direct" : "path", rd.nee ? "_nee" : "_nonee", k ? hi : lo);
            meas = rel_mse_vs(&s.img, &ref.img); est = estimated(&s.img);
            ratio = mean_lum(&s.img) / mean_lum(&ref.img);
            snprintf(what, sizeof what, "Fig. 2, %s: %s", scene_short(kind), names[c]);
            snprintf(detail, sizeof detail, "%d spp; relMSE vs reference %.3g; mean / reference %.3f", k ? hi : lo, meas, ratio);
            png = save_png(name, &s.img, expo, what, detail);
            snprintf(cell[k], sizeof cell[k], "![%s, %d spp](%s)<br>%d spp, %.2f s; relMSE vs ref **%.3g**, estimated %.3g; mean/ref %.3f",
                     names[c], k ? hi : lo, png, k ? hi : lo, s.seconds, meas, est, ratio);
            printf("  %-30s %4d spp %6.2f s  relMSE vs ref %.3e  estimated %.3e  mean/ref %.3f\n", names[c], k ? hi : lo, s.seconds, meas, est, ratio);
        }
        fprintf(md, "| %s | %s | %s |\n", names[c], cell[0], cell[1]);
        shot_free(&s);
    }
    shot_free(&ref);
    fogrt_scene_destroy(scene);
}

static void figure2(void)
{
    fprintf(md, "\n## Figure 2: one bounce versus global illumination, with and without light sampling\n\n"
                "The paper's Figure 2 compares its one-bounce baseline with full path tracing (Algorithm 1), each with "
                "and without importance sampling of the lights (next-event estimation, NEE), at a low and a high "
                "sample count; it saw a black image without importance sampling at low counts and heavy noise at high "
                "counts. Here every panel is measured against the path NEE+MIS reference, so the one-bounce rows show "
                "their bias (the light that bounced more than once is missing: mean/ref < 1) and the no-NEE rows show "
                "what light sampling buys. Same exposure in every panel of a scene.\n");
    if (have_spot) figure2_scene(SCENE_SPOT, "spot");
    else fprintf(md, "\n(The spot-light scene was skipped: %s is missing.)\n", spot_path);
    figure2_scene(SCENE_DEFAULT, "default");
    fprintf(md, "\nReading the numbers. In CBbunny_upSpot the only light is a spot light, a point: a path that does not "
                "sample it can never hit it, so without NEE the image is exactly black at every sample count (mean/ref 0, "
                "relMSE 1: all of the image is missing), and the render's own estimate says 0 because there is no "
                "variance to see. The paper's \"heavy noise at high counts\" needs a light with an area: in the default "
                "scene the ceiling lamp can be hit, so without NEE the image is sparse fireflies at %d spp and noisy "
                "but complete for the lamp at %d spp, while the spot light (radius 0.02, NEE only) stays missing. "
                "The one-bounce images converge, fast, to a darker image than the reference (mean/ref < 1).\n",
            spp_of(4) < 4 ? 1 : 4, spp_of(256));
}

/* ---- Figure 3: a density sweep ------------------------------------------------------------ */
static void figure3(void)
{
    static const float sig[6] = { 0.02f, 0.05f, 0.1f, 0.2f, 0.5f, 1.0f };
    double xs[6], mean[6], noise[6];
    scene_kind kind = have_spot ? SCENE_SPOT : SCENE_DEFAULT;
    int i, spp = spp_of(64);
    float expo = 1.0f;
    svgplot_series s[2];
    svgplot_desc d;
    const char *svg;
    printf("figure 3: density sweep, %s\n", scene_title(kind));
    fprintf(md, "\n## Figure 3: density sweep\n\n%s, path NEE+MIS, albedo 0.9, isotropic (g = 0), %d spp "
                "(two independent halves of %d), the same exposure in every panel (set by sigma_t = 0.2). The paper "
                "swept lambda = sigma_t from 0.02 to 0.2 per scene unit; the CS184 box is 2 units wide and 1.5 high, "
                "so lambda = 0.2 lets exp(-0.4) = 67%% of the light straight across it, 0.02 lets 96%% through. "
                "The sweep goes on to 0.5 and 1.0 (37%% and 14%% across), where the fog swallows the back of the box and "
                "the camera, 3.8 units in front of the box in the same fog, sees mostly the fog's own glow.\n\n"
                "| sigma_t | transmittance across the box | image | CPU s | noise relMSE (halves) | estimated | mean luminance |\n|---|---|---|---|---|---|---|\n",
            scene_title(kind), spp, spp / 2);
    {   /* the sweep's exposure comes from sigma_t = 0.2 */
        fogrt_scene *s2 = make_scene(kind, 0.2f, 0.9f, 0.0f, FOGRT_BVH_SAH);
        shot m2;
        (void)render_halves(s2, fogrt_render_paper_defaults(), spp_of(16), &m2);
        expo = exposure_for(&m2.img);
        shot_free(&m2);
        fogrt_scene_destroy(s2);
    }
    for (i = 0; i < 6; ++i) {
        fogrt_scene *scene = make_scene(kind, sig[i], 0.9f, 0.0f, FOGRT_BVH_SAH);
        fogrt_render_desc rd = fogrt_render_paper_defaults();
        shot m;
        halves h;
        char name[64];
        const char *png;
        char what[160], detail[160];
        h = render_halves(scene, rd, spp, &m);
        snprintf(name, sizeof name, "fig3_sigma_%g", (double)sig[i]);
        snprintf(what, sizeof what, "Fig. 3, %s: sigma_t %g per scene unit", scene_short(kind), (double)sig[i]);
        snprintf(detail, sizeof detail, "path NEE+MIS, albedo 0.9, g 0; %d spp; noise relMSE %.3g", spp, h.noise);
        png = save_png(name, &m.img, expo, what, detail);
        xs[i] = sig[i]; mean[i] = h.mean; noise[i] = h.noise;
        fprintf(md, "| %g | %.2f | ![sigma_t %g](%s) | %.2f | %.3g | %.3g | %.4g |\n", (double)sig[i], exp(-2.0 * (double)sig[i]),
                (double)sig[i], png, h.seconds, h.noise, h.est, h.mean);
        printf("  sigma_t %-5g %3d spp %6.2f s  noise relMSE %.3e  estimated %.3e  mean %.4g\n", (double)sig[i], spp, h.seconds, h.noise, h.est, h.mean);
        shot_free(&m);
        fogrt_scene_destroy(scene);
    }
    memset(&d, 0, sizeof d);
    memset(s, 0, sizeof s);
    d.title = "Figure 3: density sweep (path NEE+MIS)";
    d.x_label = "sigma_t, the paper's lambda [1 / scene unit] (CS184 box: 2 units wide)";
    d.y_label = "value [linear luminance; relMSE dimensionless]";
    d.log_x = d.log_y = 1;
    s[0].label = "mean image luminance"; s[0].x = xs; s[0].y = mean; s[0].n = 6;
    s[1].label = "noise relMSE (halves)"; s[1].sublabel = "at the same spp"; s[1].x = xs; s[1].y = noise; s[1].n = 6; s[1].dashed = 1;
    svg = save_svg("fig3_density", &d, s, 2);
    fprintf(md, "\n![density sweep plot](%s)\n", svg);
}

/* ---- Figure 4: a g sweep ------------------------------------------------------------------- */
/* Mean luminance within 20 pixels of the light's image point (the spot light's beam as the
   camera sees it, aimed at it or away from it). */
static double glow(const fogrt_scene *scene, const fogrt_image *img)
{
    double lx, ly, in = 0;
    int nin = 0, x, y;
    project(scene, vec3(0.0f, 0.75f, POINT_LIGHT_Z), &lx, &ly);
    for (y = 0; y < H; ++y)
        for (x = 0; x < W; ++x)
            if (hypot(x + 0.5 - lx, y + 0.5 - ly) <= 20.0) { in += pix_lum(img, (size_t)y * W + x); ++nin; }
    return nin ? in / nin : 0.0;
}

static void figure4(void)
{
    static const float gs[5] = { -0.9f, -0.5f, 0.0f, 0.5f, 0.9f };
    static const scene_kind rows[3] = { SCENE_BEAM_TO_CAMERA, SCENE_BEAM_AWAY, SCENE_SPOT };
    static const char *tags[3] = { "tocamera", "away", "upspot" };
    static char cells[3][5][700];
    double xs[5], gl[2][5];
    int i, k, nrows = have_spot ? 3 : 2, spp_single = spp_of(128), spp_path = spp_of(64);
    float expo[3];
    printf("figure 4: g sweep\n");
    for (k = 0; k < nrows; ++k) {   /* exposures from the row's brightest image, so that its halo is not clipped */
        float g_expo = k == 0 ? 0.9f : k == 1 ? -0.9f : 0.0f;
        fogrt_scene *scene = make_scene(rows[k], rows[k] == SCENE_SPOT ? 0.5f : 0.3f, 0.9f, g_expo, FOGRT_BVH_SAH);
        fogrt_render_desc rd = fogrt_render_paper_defaults();
        shot m;
        if (k < 2) rd.integrator = FOGRT_INTEGRATOR_DIRECT;
        (void)render_halves(scene, rd, spp_of(16), &m);
        expo[k] = exposure_for(&m.img);
        shot_free(&m);
        fogrt_scene_destroy(scene);
    }
    for (k = 0; k < nrows; ++k)
        for (i = 0; i < 5; ++i) {
            fogrt_scene *scene = make_scene(rows[k], rows[k] == SCENE_SPOT ? 0.5f : 0.3f, 0.9f, gs[i], FOGRT_BVH_SAH);
            fogrt_render_desc rd = fogrt_render_paper_defaults();
            shot m;
            halves h;
            char name[64];
            const char *png;
            xs[i] = gs[i];
            if (k < 2) rd.integrator = FOGRT_INTEGRATOR_DIRECT;
            char what[160], detail[160];
            h = render_halves(scene, rd, k < 2 ? spp_single : spp_path, &m);
            snprintf(name, sizeof name, "fig4_%s_g_%g", tags[k], (double)gs[i]);
            snprintf(what, sizeof what, "Fig. 4, %s: g = %g", scene_short(rows[k]), (double)gs[i]);
            snprintf(detail, sizeof detail, "%s, fog sigma_t %g, albedo 0.9; %d spp; noise relMSE %.3g",
                     k < 2 ? "one bounce" : "path NEE+MIS", rows[k] == SCENE_SPOT ? 0.5 : 0.3, k < 2 ? spp_single : spp_path, h.noise);
            png = save_png(name, &m.img, expo[k], what, detail);
            if (k < 2) gl[k][i] = glow(scene, &m.img);
            snprintf(cells[k][i], sizeof cells[k][i], "![g %g](%s)<br>%s%d spp, %.2f s, noise %.3g, est. %.3g", (double)gs[i], png,
                     k < 2 ? "GLOW" : "", k < 2 ? spp_single : spp_path, h.seconds, h.noise, h.est);
            printf("  %-9s g %5.2f %3d spp %6.2f s  glow %.4g  noise relMSE %.3e  estimated %.3e\n", tags[k], (double)gs[i],
                   k < 2 ? spp_single : spp_path, h.seconds, k < 2 ? gl[k][i] : 0.0, h.noise, h.est);
            shot_free(&m);
            fogrt_scene_destroy(scene);
        }
    fprintf(md, "\n## Figure 4: the Henyey-Greenstein g sweep\n\n"
                "g > 0 scatters forward (on along the light's direction of travel), g < 0 back toward where the light "
                "came from. Fog sigma_t 0.3 (upSpot: 0.5), albedo 0.9, two independent halves per image, the same "
                "exposure along each row (set by its brightest image: g = 0.9 in row 1, -0.9 in row 2, 0 in row 3). Rows 1 and 2 use the one-bounce integrator (%d spp): single "
                "scattering shows the phase function alone, where multiple scattering would blur it and, at |g| = 0.9, "
                "add fireflies. %s\n\n"
                "1. a spot light (25 degree cone, in the middle of the CS184 box) **aimed at the camera**: its light "
                "travels toward the camera and reaches it through the fog only by scattering at small angles, i.e. "
                "forward. This is the halo around the light.\n"
                "2. the same spot light **aimed away** from the camera, at the back wall: the camera sees the beam "
                "(in front of the lit patch of wall) only by back scattering.\n%s"
                "\n**glow** = mean luminance within 20 pixels of the light's image point, relative to g = 0 (rows 1 and 2).\n\n| g |",
            spp_single, have_spot ? "Row 3 is the paper's scene with full path tracing (64 spp)." : "",
            have_spot ? "3. CBbunny_upSpot.dae, the paper's scene: the spot light under the ceiling shines down, seen from the side.\n" : "");
    (void)spp_path;
    for (k = 0; k < nrows; ++k) fprintf(md, " %s |", k == 0 ? "aimed at the camera" : k == 1 ? "aimed away" : "upSpot (paper)");
    fprintf(md, "\n|---|");
    for (k = 0; k < nrows; ++k) fprintf(md, "---|");
    fprintf(md, "\n");
    for (i = 0; i < 5; ++i) {
        fprintf(md, "| %g |", (double)gs[i]);
        for (k = 0; k < nrows; ++k) {
            char *g = strstr(cells[k][i], "GLOW");
            if (g) {   /* the glow relative to g = 0, now that g = 0 is known */
                char tail[700];
                snprintf(tail, sizeof tail, "%s", g + 4);
                fprintf(md, " %.*sglow **%.2f**; %s |", (int)(g - cells[k][i]), cells[k][i], gl[k][2] > 0 ? gl[k][i] / gl[k][2] : 0.0, tail);
            } else {
                fprintf(md, " %s |", cells[k][i]);
            }
        }
        fprintf(md, "\n");
    }
    {
        svgplot_series s[2];
        svgplot_desc d;
        const char *svg;
        static double rel[2][5];
        memset(&d, 0, sizeof d);
        memset(s, 0, sizeof s);
        for (k = 0; k < 2; ++k) for (i = 0; i < 5; ++i) rel[k][i] = gl[k][2] > 0 ? gl[k][i] / gl[k][2] : 0.0;
        d.title = "Figure 4: a spot light's beam seen through fog, against g";
        d.x_label = "Henyey-Greenstein g [dimensionless; g > 0 scatters forward]";
        d.y_label = "glow within 20 px of the light, relative to g = 0";
        d.log_y = 1;
        s[0].label = "spot aimed at the camera"; s[0].sublabel = "seen by forward scattering"; s[0].x = xs; s[0].y = rel[0]; s[0].n = 5;
        s[1].label = "spot aimed away"; s[1].sublabel = "seen by back scattering"; s[1].x = xs; s[1].y = rel[1]; s[1].n = 5; s[1].dashed = 1;
        svg = save_svg("fig4_g", &d, s, 2);
        fprintf(md, "\n![g sweep plot](%s)\n\nAimed at the camera, the light wears a bright halo at g = 0.9 (glow %.2f times "
                    "that at g = 0) which all but vanishes at g = -0.9 (%.2f); aimed away, the beam is brightest at g = -0.9 "
                    "(%.2f) and dimmest at g = 0.9 (%.2f). So g > 0 scatters forward, along the direction the light travels, "
                    "as pbrt and fogrt define it (and as the paper's code does, although its text says the opposite: see "
                    "docs/paper-map.md).\n",
                svg, rel[0][4], rel[0][0], rel[1][0], rel[1][4]);
        if (!(rel[0][4] > 1.0 && rel[0][0] < 1.0 && rel[1][0] > 1.0 && rel[1][4] < 1.0)) {
            fprintf(stderr, "figures: the glow does not follow the sign of g\n"); ++failures;
        }
    }
}

/* ---- Beyond the paper: equiangular sampling ------------------------------------------------ */
typedef struct ladder_pts { int n; double t[24], e[24]; int spp[24]; } ladder_pts;

static void ladder_run(const fogrt_scene *scene, const fogrt_render_desc *rd, const shot *ref, double budget, shot *s, ladder_pts *L)
{
    int target = 1;
    shot_init(s);
    L->n = 0;
    while (L->n < 24) {
        shot_render(s, scene, rd, target);
        L->t[L->n] = s->seconds; L->e[L->n] = rel_mse_vs(&s->img, &ref->img); L->spp[L->n] = target;
        L->n++;
        if (2.0 * s->seconds > budget) break;
        target *= 2;
    }
}
/* log-log interpolation of a ladder at time t (extrapolated with slope -1 past its ends). */
static double ladder_at(const ladder_pts *L, double t)
{
    int k;
    if (t >= L->t[L->n - 1]) return L->e[L->n - 1] * L->t[L->n - 1] / t;
    for (k = L->n - 1; k > 0; --k)
        if (L->t[k - 1] <= t && L->e[k] > 0 && L->e[k - 1] > 0) {
            double a = (log(t) - log(L->t[k - 1])) / (log(L->t[k]) - log(L->t[k - 1]));
            return exp(log(L->e[k - 1]) + a * (log(L->e[k]) - log(L->e[k - 1])));
        }
    return L->e[0] * L->t[0] / t;
}

static void beyond_equiangular(void)
{
    fogrt_scene *scene = make_scene(SCENE_POINT, EQ_SIGMA, 0.9f, 0.3f, FOGRT_BVH_SAH);
    fogrt_render_desc on = fogrt_render_defaults(), off = fogrt_render_defaults();
    shot ref, s_on, s_off;
    ladder_pts L_on, L_off;
    double budget = quick ? 3.0 : 12.0, t_eq, e_on, e_off;
    float expo;
    svgplot_series s[3];
    svgplot_desc d;
    char sub[2][80];
    double rx[2], ry[2];
    int anchor;
    const char *svg, *png_on, *png_off;
    printf("beyond: equiangular on vs off\n");
    off.equiangular = false;
    render_reference(scene, spp_of(1024), &ref);
    expo = exposure_for(&ref.img);
    ladder_run(scene, &on, &ref, budget, &s_on, &L_on);
    ladder_run(scene, &off, &ref, budget, &s_off, &L_off);
    t_eq = L_on.t[L_on.n - 1] < L_off.t[L_off.n - 1] ? L_on.t[L_on.n - 1] : L_off.t[L_off.n - 1];
    e_on = ladder_at(&L_on, t_eq); e_off = ladder_at(&L_off, t_eq);
    {
        char detail[160];
        snprintf(detail, sizeof detail, "fog sigma_t %g, albedo 0.9, g 0.3; %d spp; relMSE vs reference %.3g", (double)EQ_SIGMA,
                 L_on.spp[L_on.n - 1], L_on.e[L_on.n - 1]);
        png_on = save_png("beyond_equiangular_on", &s_on.img, expo, "Point light in fog: equiangular sampling on", detail);
    }
    {
        char keep[600], detail[160];
        snprintf(keep, sizeof keep, "%s", png_on);
        snprintf(detail, sizeof detail, "fog sigma_t %g, albedo 0.9, g 0.3; %d spp; relMSE vs reference %.3g", (double)EQ_SIGMA,
                 L_off.spp[L_off.n - 1], L_off.e[L_off.n - 1]);
        png_off = save_png("beyond_equiangular_off", &s_off.img, expo, "Point light in fog: equiangular off (the paper)", detail);
        printf("  equiangular on : %d spp %.2f s relMSE %.3e\n  equiangular off: %d spp %.2f s relMSE %.3e\n  at equal time %.2f s: on %.3e off %.3e ratio %.1f\n",
               L_on.spp[L_on.n - 1], L_on.t[L_on.n - 1], L_on.e[L_on.n - 1], L_off.spp[L_off.n - 1], L_off.t[L_off.n - 1],
               L_off.e[L_off.n - 1], t_eq, e_on, e_off, e_off / e_on);
        if (!(e_off / e_on > 3.0)) { fprintf(stderr, "figures: equiangular gain %.2f is not above 3\n", e_off / e_on); ++failures; }
        fprintf(md, "\n## Beyond the paper: equiangular sampling of a point light in fog\n\n"
                    "The point-light scene (a point light in the middle of the CS184 box; fog sigma_t %g, albedo 0.9, g 0.3), path NEE+MIS with equiangular sampling on "
                    "(fogrt's default: every fog segment of every path gathers the point light at a distance drawn with "
                    "pdf ~ 1/r^2, which cancels the light's 1/r^2) and off (the paper's method: the light is found only "
                    "by next-event estimation at the fog collisions free-flight sampling happens to produce). Reference: "
                    "equiangular on, %d spp, %.1f CPU s. Each ladder doubled its samples (1, 2, 4, ...) while the next step "
                    "fit in %.0f CPU seconds.\n\n"
                    "| equiangular on | equiangular off |\n|---|---|\n"
                    "| ![on](%s)<br>%d spp, %.2f s; relMSE vs ref **%.3g**, estimated %.3g | ![off](%s)<br>%d spp, %.2f s; relMSE vs ref **%.3g**, estimated %.3g |\n\n"
                    "At equal time (%.2f CPU s, log-log interpolation along each ladder) the relative MSE is %.3g with "
                    "equiangular sampling and %.3g without: **%.1fx** lower with it (expected: well over 3x).\n",
                (double)EQ_SIGMA, (int)ref.img.count[0], ref.seconds, budget, keep, L_on.spp[L_on.n - 1], L_on.t[L_on.n - 1], L_on.e[L_on.n - 1],
                estimated(&s_on.img), png_off, L_off.spp[L_off.n - 1], L_off.t[L_off.n - 1], L_off.e[L_off.n - 1],
                estimated(&s_off.img), t_eq, e_on, e_off, e_off / e_on);
    }
    memset(&d, 0, sizeof d);
    memset(s, 0, sizeof s);
    {
        static const char *notes[3] = {
            "Each line is one render made progressive (1, 2, 4, ... spp). Without equiangular sampling a fog",
            "collision close to the light now and then gives one sample of huge weight (1 / r^2): the line jumps",
            "up at that step, then falls as 1/spp. With it the light's 1 / r^2 cancels: slope -1 throughout." };
        d.notes = notes; d.note_count = 3;
        d.height = 760;
    }
    d.title = "Point light in fog: equiangular sampling on vs off";
    d.x_label = "render time [CPU seconds, all threads]";
    d.y_label = "relative MSE [dimensionless] vs reference";
    d.log_x = d.log_y = 1;
    snprintf(sub[0], sizeof sub[0], "%d spp in %.1f s", L_on.spp[L_on.n - 1], L_on.t[L_on.n - 1]);
    snprintf(sub[1], sizeof sub[1], "%d spp in %.1f s", L_off.spp[L_off.n - 1], L_off.t[L_off.n - 1]);
    s[0].label = "equiangular on"; s[0].sublabel = sub[0]; s[0].x = L_on.t; s[0].y = L_on.e; s[0].n = L_on.n;
    s[1].label = "equiangular off (paper)"; s[1].sublabel = sub[1]; s[1].x = L_off.t; s[1].y = L_off.e; s[1].n = L_off.n; s[1].dashed = 1;
    /* the slope -1 of an unbiased estimator, through the first ladder's point at 4 spp */
    for (anchor = 0; anchor < L_on.n - 1 && L_on.spp[anchor] < 4; ++anchor) {}
    rx[0] = fmin(L_on.t[0], L_off.t[0]); rx[1] = fmax(L_on.t[L_on.n - 1], L_off.t[L_off.n - 1]);
    ry[0] = L_on.e[anchor] * L_on.t[anchor] / rx[0]; ry[1] = L_on.e[anchor] * L_on.t[anchor] / rx[1];
    s[2].label = "reference slope -1"; s[2].sublabel = "unbiased: error x time constant"; s[2].x = rx; s[2].y = ry; s[2].n = 2;
    s[2].dashed = 1; s[2].colour = "#000000"; s[2].no_markers = 1;
    svg = save_svg("beyond_equiangular", &d, s, 3);
    fprintf(md, "\n![equiangular convergence](%s)\n", svg);
    shot_free(&ref); shot_free(&s_on); shot_free(&s_off);
    fogrt_scene_destroy(scene);
}

/* ---- Beyond the paper: SAH vs the volume heuristic ----------------------------------------- */
static void beyond_bvh(void)
{
    static const char *hname[2] = { "SAH (fogrt's default)", "volume heuristic (the paper's)" };
    scene_kind kind = have_spot ? SCENE_SPOT : SCENE_DEFAULT;
    shot img[2];
    int k, spp = spp_of(16);
    double diff = 0.0;
    printf("beyond: SAH vs volume heuristic, %s\n", scene_title(kind));
    fprintf(md, "\n## Beyond the paper: SAH versus the paper's volume heuristic\n\n%s with fog (sigma_t 0.2, albedo 0.9). "
                "Build: the fastest of 3 builds of the tree alone (one thread; without the roulette's pilot render that "
                "follows a build by default). SAH cost: fogrt_bvh_sah_cost (1 per inner node, 1 per "
                "primitive in a leaf, area-weighted), the same measure for both trees. Mrays/s: closest-hit queries of "
                "%d x %d x 8 jittered camera rays and as many diffuse bounce rays from their hit points, one thread. "
                "Render: path NEE+MIS, %d spp, same seed.\n\n"
                "| heuristic | build s | SAH cost | nodes | Mrays/s (camera) | Mrays/s (bounce) | render CPU s |\n|---|---|---|---|---|---|---|\n",
            scene_title(kind), W, H, spp);
    for (k = 0; k < 2; ++k) {
        fogrt_scene *scene = NULL;
        fogrt_scene_desc sd;
        fogrt_build_desc bd = fogrt_build_defaults();
        fogrt_render_desc rd = fogrt_render_defaults();
        const fogrt_bvh_node *nodes;
        const uint32_t *prims;
        uint32_t node_count;
        double best = 1e30, t0, t_cam, t_bounce;
        long hits = 0, rays = 0, brays = 0;
        int rep, x, y, j;
        fogrt_rng rng;
        memset(&sd, 0, sizeof sd);
        sd.logger.func = log_stderr;
        check(fogrt_scene_create(&sd, &scene), "scene_create");
        if (kind == SCENE_SPOT) {
            fogrt_load_options opt;
            fogrt_load_report rp;
            memset(&opt, 0, sizeof opt);
            opt.image_width = W; opt.image_height = H;
            if (fogrt_load_file(scene, spot_path, &opt, &rp) != FOGRT_RESULT_OK) { fprintf(stderr, "%s:%d: %s\n", rp.file, rp.line, rp.message); exit(1); }
            { fogrt_medium_desc m; memset(&m, 0, sizeof m); m.sigma_t = 0.2f; m.albedo = vec3(0.9f, 0.9f, 0.9f); m.g = 0.0f; check(fogrt_scene_set_medium(scene, &m), "medium"); }
        } else {
            check(fogrt_scene_add_default(scene), "add_default");
        }
        bd.heuristic = k ? FOGRT_BVH_VOLUME : FOGRT_BVH_SAH;
        bd.roulette_pilot = false;   /* time the tree alone: the pilot that follows a build renders */
        for (rep = 0; rep < 3; ++rep) {
            struct timespec a, b;
            clock_gettime(CLOCK_MONOTONIC, &a);
            check(fogrt_scene_build(scene, &bd), "build");
            clock_gettime(CLOCK_MONOTONIC, &b);
            t0 = (double)(b.tv_sec - a.tv_sec) + 1e-9 * (double)(b.tv_nsec - a.tv_nsec);
            if (t0 < best) best = t0;
        }
        bd.roulette_pilot = fogrt_build_defaults().roulette_pilot;   /* the render below as fogrt runs by default */
        check(fogrt_scene_build(scene, &bd), "build");
        fogrt_scene_get_bvh(scene, &nodes, &node_count, &prims);
        /* ray queries, one thread: camera rays first, then one diffuse-like bounce from each hit */
        {
            size_t cap = (size_t)W * H * 8, nh = 0, q;
            fogrt_vec3 *hp = (fogrt_vec3 *)malloc(sizeof(fogrt_vec3) * cap), *hd = (fogrt_vec3 *)malloc(sizeof(fogrt_vec3) * cap);
            fogrt_vec3 *co = (fogrt_vec3 *)malloc(sizeof(fogrt_vec3) * cap), *cd = (fogrt_vec3 *)malloc(sizeof(fogrt_vec3) * cap);
            if (!hp || !hd || !co || !cd) { fprintf(stderr, "figures: out of memory\n"); exit(1); }
            fogrt_rng_seed(&rng, 7, 0);
            for (y = 0; y < H; ++y)
                for (x = 0; x < W; ++x)
                    for (j = 0; j < 8; ++j) {
                        q = ((size_t)y * W + x) * 8 + j;
                        fogrt_camera_ray(scene, W, H, x + fogrt_rng_float(&rng), y + fogrt_rng_float(&rng), 0.5f, 0.5f, &co[q], &cd[q]);
                    }
            t0 = cpu_seconds();
            for (q = 0; q < cap; ++q) {
                fogrt_hit hit;
                if (fogrt_scene_intersect(scene, co[q], cd[q], 0.0f, INFINITY, &hit)) {
                    hp[nh] = vec3(co[q].x + cd[q].x * hit.t, co[q].y + cd[q].y * hit.t, co[q].z + cd[q].z * hit.t);
                    hd[nh] = cd[q];
                    ++nh;
                }
            }
            t_cam = cpu_seconds() - t0;
            rays = (long)cap; hits = (long)nh;
            for (q = 0; q < nh; ++q) {   /* a random direction back to the side the ray came from */
                fogrt_vec3 nd = fogrt_sample_uniform_sphere(fogrt_rng_float(&rng), fogrt_rng_float(&rng));
                if (nd.x * hd[q].x + nd.y * hd[q].y + nd.z * hd[q].z > 0.0f) { nd.x = -nd.x; nd.y = -nd.y; nd.z = -nd.z; }
                hd[q] = nd;
            }
            t0 = cpu_seconds();
            for (q = 0; q < nh; ++q) {
                fogrt_hit hit;
                (void)fogrt_scene_intersect(scene, hp[q], hd[q], 1e-4f, INFINITY, &hit);
            }
            t_bounce = cpu_seconds() - t0;
            brays = (long)nh;
            free(hp); free(hd); free(co); free(cd);
        }
        shot_init(&img[k]);
        shot_render(&img[k], scene, &rd, spp);
        fprintf(md, "| %s | %.4f | %.2f | %u | %.2f | %.2f | %.2f |\n", hname[k], best, (double)fogrt_bvh_sah_cost(scene), node_count,
                rays / t_cam * 1e-6, brays / t_bounce * 1e-6, img[k].seconds);
        printf("  %-32s build %.4f s  SAH cost %.2f  nodes %u  %.2f / %.2f Mrays/s  render %.2f s (%ld of %ld camera rays hit)\n", hname[k], best,
               (double)fogrt_bvh_sah_cost(scene), node_count, rays / t_cam * 1e-6, brays / t_bounce * 1e-6, img[k].seconds, hits, rays);
        fogrt_scene_destroy(scene);
    }
    {
        size_t i, n = (size_t)W * H * 3;
        for (i = 0; i < n; ++i) { double a = fabs(img[0].img.sum[i] - img[1].img.sum[i]); if (a > diff) diff = a; }
    }
    fprintf(md, "\nThe two trees give the same image (largest difference of any pixel's sample sum: %g); only the "
                "time differs. The timings are one run on a shared machine.\n", diff);
    if (diff != 0.0) { fprintf(stderr, "figures: SAH and volume-heuristic images differ (%g)\n", diff); ++failures; }
    shot_free(&img[0]); shot_free(&img[1]);
}

/* ---- Beyond the paper: Schlick vs exact Fresnel --------------------------------------------- */
static void beyond_fresnel(void)
{
    fogrt_scene *scene = make_scene(SCENE_DEFAULT, -1.0f, 0.0f, 0.0f, FOGRT_BVH_SAH);
    fogrt_render_desc rd = fogrt_render_defaults();
    shot s[2];
    double se = 0.0, norm = 0.0, se_box = 0.0, norm_box = 0.0, var = 0.0, var_box = 0.0, cx, cy, ex, ey, r;
    int spp = spp_of(256), k, x, y;
    float expo;
    const char *png[2];
    char keep[600];
    fogrt_image dimg;
    printf("beyond: Schlick vs exact Fresnel\n");
    for (k = 0; k < 2; ++k) {
        rd.fresnel = k ? FOGRT_FRESNEL_EXACT : FOGRT_FRESNEL_SCHLICK;
        rd.seed = 5;   /* the same seed: paths agree until a Fresnel choice differs */
        shot_init(&s[k]);
        shot_render(&s[k], scene, &rd, spp);
    }
    /* the glass sphere's box in the image */
    project(scene, vec3(0.45f, 0.35f, 0.25f), &cx, &cy);
    project(scene, vec3(0.45f + 0.35f, 0.35f, 0.25f), &ex, &ey);
    r = fabs(ex - cx) * 1.15;
    check(fogrt_image_alloc(&dimg, W, H, NULL), "image_alloc");
    for (y = 0; y < H; ++y)
        for (x = 0; x < W; ++x) {
            size_t i = (size_t)y * W + x;
            double a = pix_lum(&s[0].img, i), b = pix_lum(&s[1].img, i), v = pix_var(&s[1].img, i);
            int in_box = fabs(x + 0.5 - cx) <= r && fabs(y + 0.5 - cy) <= r, c;
            se += (a - b) * (a - b); norm += b * b; var += v;
            if (in_box) { se_box += (a - b) * (a - b); norm_box += b * b; var_box += v; }
            for (c = 0; c < 3; ++c) dimg.sum[3 * i + c] = fabs(s[0].img.sum[3 * i + c] - s[1].img.sum[3 * i + c]);
            dimg.count[i] = s[0].img.count[i];
        }
    expo = exposure_for(&s[1].img);
    {
        char detail[160];
        snprintf(detail, sizeof detail, "path NEE+MIS, %d spp, seed 5; estimated relMSE %.3g", spp, estimated(&s[0].img));
        png[0] = save_png("beyond_fresnel_schlick", &s[0].img, expo, "Default scene, glass sphere: Schlick's Fresnel (the paper)", detail);
    }
    snprintf(keep, sizeof keep, "%s", png[0]);
    {
        char detail[160];
        snprintf(detail, sizeof detail, "path NEE+MIS, %d spp, seed 5; estimated relMSE %.3g", spp, estimated(&s[1].img));
        png[1] = save_png("beyond_fresnel_exact", &s[1].img, expo, "Default scene, glass sphere: exact dielectric Fresnel", detail);
    }
    {
        char keep2[600];
        const char *pd;
        snprintf(keep2, sizeof keep2, "%s", png[1]);
        pd = save_png("beyond_fresnel_difference_x10", &dimg, expo * 10.0f, "|Schlick - exact|, 10 x brighter",
                      "the same seed for both: black where the two agree");
        fprintf(md, "\n## Beyond the paper: Schlick versus exact Fresnel on the glass sphere\n\n"
                    "The default scene (glass sphere of ior 1.5 in fog), path NEE+MIS, %d spp, the same seed for both, so "
                    "the two images share their random numbers and differ only where a Fresnel reflect/refract choice "
                    "or weight differs.\n\n| Schlick (the paper's) | exact dielectric | difference x10 |\n|---|---|---|\n"
                    "| ![Schlick](%s)<br>%.2f CPU s, estimated relMSE %.3g | ![exact](%s)<br>%.2f CPU s, estimated relMSE %.3g | ![difference](%s) |\n\n"
                    "Relative squared difference sum_p (S_p - E_p)^2 / sum_p E_p^2: **%.3g** over the whole image, "
                    "**%.3g** in the box around the glass sphere (%.0f x %.0f pixels); for scale, one image's own noise "
                    "(estimated relMSE) is %.3g over the whole image and %.3g in that box. In the box that is an RMS "
                    "difference of %.1f%% of the sphere's brightness; it includes the noise of the paths whose Fresnel "
                    "choice went differently (they use their random numbers differently from then on), so it is an upper "
                    "bound on Schlick's error here. Time: Schlick %.2f s, exact %.2f s (%+.1f%%; one run on a shared "
                    "machine).\n",
                spp, keep, s[0].seconds, estimated(&s[0].img), keep2, s[1].seconds, estimated(&s[1].img), pd,
                norm > 0 ? se / norm : 0.0, norm_box > 0 ? se_box / norm_box : 0.0, 2 * r, 2 * r,
                norm > 0 ? var / norm : 0.0, norm_box > 0 ? var_box / norm_box : 0.0,
                norm_box > 0 ? 100.0 * sqrt(se_box / norm_box) : 0.0, s[0].seconds, s[1].seconds,
                100.0 * (s[1].seconds / s[0].seconds - 1.0));
        printf("  Schlick %.2f s, exact %.2f s; rel. squared difference %.3e (sphere box %.3e); noise %.3e (box %.3e)\n",
               s[0].seconds, s[1].seconds, norm > 0 ? se / norm : 0.0, norm_box > 0 ? se_box / norm_box : 0.0,
               norm > 0 ? var / norm : 0.0, norm_box > 0 ? var_box / norm_box : 0.0);
    }
    fogrt_image_free(&dimg);
    shot_free(&s[0]); shot_free(&s[1]);
    fogrt_scene_destroy(scene);
}

/* ---- main ---------------------------------------------------------------------------------- */
static int usage(const char *msg)
{
    fprintf(stderr, "figures: %s\nusage: figures [--out DIR] [--doc FILE.md] [--shared DIR] [--size W H] [--quick]\n"
                    "               [--only fig2|fig3|fig4|equiangular|bvh|fresnel]\n", msg);
    return 2;
}

/* figs_rel: out_dir relative to the report's directory, when out_dir is below it. */
static void relative_figs_dir(void)
{
    const char *slash = strrchr(doc_path, '/');
    size_t dlen = slash ? (size_t)(slash - doc_path) : 0;
    if (dlen == 0 && !slash) snprintf(figs_rel, sizeof figs_rel, "%s", out_dir);
    else if (strlen(out_dir) == dlen && strncmp(out_dir, doc_path, dlen) == 0) snprintf(figs_rel, sizeof figs_rel, ".");
    else if (strncmp(out_dir, doc_path, dlen) == 0 && out_dir[dlen] == '/') snprintf(figs_rel, sizeof figs_rel, "%s", out_dir + dlen + 1);
    else if (out_dir[0] != '/' && doc_path[0] != '/' && !strstr(doc_path, "..")) {
        /* both relative to the working directory: up from the report's directory, then down */
        size_t k, used = 0;
        for (k = 0; k <= dlen && used + 4 < sizeof figs_rel; ++k)
            if (k == dlen || doc_path[k] == '/') { memcpy(figs_rel + used, "../", 3); used += 3; }
        snprintf(figs_rel + used, sizeof figs_rel - used, "%s", out_dir);
    } else {
        snprintf(figs_rel, sizeof figs_rel, "%s", out_dir);
    }
}

int main(int argc, char **argv)
{
    const char *shared = "../shared";
    double t0 = cpu_seconds();
    struct timespec w0, w1;
    int i;
    setvbuf(stdout, NULL, _IOLBF, 0);   /* progress lines appear as they happen, also in a log file */
    clock_gettime(CLOCK_MONOTONIC, &w0);
    for (i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--out") && i + 1 < argc) out_dir = argv[++i];
        else if (!strcmp(argv[i], "--doc") && i + 1 < argc) doc_path = argv[++i];
        else if (!strcmp(argv[i], "--shared") && i + 1 < argc) shared = argv[++i];
        else if (!strcmp(argv[i], "--size") && i + 2 < argc) { W = atoi(argv[i + 1]); H = atoi(argv[i + 2]); i += 2; }
        else if (!strcmp(argv[i], "--quick")) quick = 1;
        else if (!strcmp(argv[i], "--only") && i + 1 < argc) only = argv[++i];
        else { char m[300]; snprintf(m, sizeof m, "unknown or incomplete option '%s'", argv[i]); return usage(m); }
    }
    if (W < 64 || H < 48 || W > 2048 || H > 2048) return usage("--size: W must be 64..2048 and H 48..2048");
    if (only && strcmp(only, "fig2") && strcmp(only, "fig3") && strcmp(only, "fig4") && strcmp(only, "equiangular") &&
        strcmp(only, "bvh") && strcmp(only, "fresnel"))
        return usage("--only: fig2, fig3, fig4, equiangular, bvh or fresnel");
    if (mkdir(out_dir, 0777) != 0 && errno != EEXIST) { fprintf(stderr, "figures: cannot create %s: %s\n", out_dir, strerror(errno)); return 1; }
    relative_figs_dir();
    snprintf(spot_path, sizeof spot_path, "%s/scenes/cs184/CBbunny_upSpot.dae", shared);
    { FILE *f = fopen(spot_path, "rb"); have_spot = f != NULL; if (f) fclose(f); }
    if (!have_spot) printf("figures: %s not found: its panels are skipped (the default scene stands in where it can)\n", spot_path);
    if (!(md = fopen(doc_path, "w"))) { fprintf(stderr, "figures: cannot write %s: %s\n", doc_path, strerror(errno)); return 1; }
    fprintf(md, "# Experiments: the paper's figures, with numbers\n\n"
                "Generated by `make figures` (examples/figures.c) "
                "on %d x %d images%s; do not edit by hand. Each image carries its caption (what it shows, samples per pixel, "
                "error) and is drawn at twice its size for a projector. "
                "Every caption gives samples per pixel (spp), CPU seconds (process CPU time over all threads, on a "
                "shared 2-core machine: compare times within one table, not across runs) and a measured error:\n\n"
                "- **relMSE vs ref**: (sum_p (L_p - R_p)^2 - sum_p Var[R_p]) / sum_p R_p^2 on luminance, R a long path "
                "NEE+MIS render with another seed and Var[R_p] its own noise (subtracted). It includes bias.\n"
                "- **noise relMSE (halves)**: the image rendered as two independent halves A and B (seeds 1 and 2); "
                "sum_p ((A_p - B_p)/2)^2 / sum_p M_p^2 measures the combined image M's variance directly (no reference; "
                "no bias term, which the path integrator does not have).\n"
                "- **estimated**: the render's own estimate, fogrt_image_error's relative_error squared.\n\n"
                "The paper is \"Volumetric Ray Tracer in Homogeneous Media\" (CS184); docs/paper-map.md maps it to "
                "fogrt. Its lambda is fogrt's sigma_t. `make convergence` plots error against time for the estimators "
                "(build/convergence/).\n",
            W, H, quick ? " (--quick: a quarter of the samples)" : "");
#define RUN(name, fn) if (!only || !strcmp(only, name)) fn()
    RUN("fig2", figure2);
    RUN("fig3", figure3);
    RUN("fig4", figure4);
    RUN("equiangular", beyond_equiangular);
    RUN("bvh", beyond_bvh);
    RUN("fresnel", beyond_fresnel);
#undef RUN
    clock_gettime(CLOCK_MONOTONIC, &w1);
    fprintf(md, "\n---\nTotal: %.0f CPU seconds, %.0f seconds wall.\n", cpu_seconds() - t0,
            (double)(w1.tv_sec - w0.tv_sec) + 1e-9 * (double)(w1.tv_nsec - w0.tv_nsec));
    fclose(md);
    printf("wrote %s (%.0f CPU s)\n", doc_path, cpu_seconds() - t0);
    if (failures) { fprintf(stderr, "figures: %d expectation(s) not met (see above)\n", failures); return 1; }
    return 0;
}
