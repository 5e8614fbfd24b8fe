/* bench/variance_sources.c - `make variance-sources`: which samples carry an image's noise.

   The error of fogrt_image_error is a sum over pixels of the variance of their means. This
   program takes it apart sample by sample. It renders every sample of a small image
   through fogrt_trace_path (the renderer compiled with FOGRT_TRACE), and a callback notes,
   per sample, its luminance L, the largest single contribution (its source and bounce),
   the largest throughput along the path and whether the path survived a roulette. A
   sample's share of the noise is (L - its pixel's mean)^2, the term it adds to its
   pixel's sample variance. The program then prints the shares of the noise (and of the
   image) by:
     - how bright the sample is against its pixel's mean (are a few rare samples the noise?);
     - the source of its largest contribution (emission, environment, light sample at the
       vertex, light sampled behind a fog collision (14 b'), equiangular): which estimator
       finds the light the noise comes from;
     - the bounce of that contribution (where along the path);
     - the largest throughput along the path (do weights grow where they should not?);
   and the brightest samples, each as the `fogrt --trace X,Y,SAMPLE -r W H` command that
   prints it event by event (the same sample: the camera of a .dae is the file's).

   docs/benchmarks.md ("make variance-sources") gives its figures for the paper's spot-lit fog.

   Usage: bench/variance_sources [scene.dae|.obj|.ply] [--density S] [--g G] [--albedo A]
                                 [-r W H] [-s SPP] [--top N]
   Without a scene: the embedded default scene. The fog flags work as the CLI's do on a
   .dae (albedo 0.9 and g 0 unless given). Defaults: -r 120 90, -s 64, --top 5. */
#define FOGRT_TRACE
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#ifdef HAVE_FOGRT_LOAD
#define FOGRT_LOAD_IMPLEMENTATION
#include "fogrt_load.h"
#endif
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>

enum { SRC_NONE, SRC_EMISSION, SRC_ENVIRONMENT, SRC_LIGHT, SRC_BEHIND, SRC_EQUIANGULAR, SRC_NUM };
static const char *const src_names[SRC_NUM] = { "nothing gathered", "emission", "environment",
                                                 "light sample at the vertex", "light behind a collision (b')",
                                                 "equiangular" };
#define MAX_BOUNCE 12                   /* the last row holds this bounce and all later ones */

typedef struct sample_rec {
    float L;                            /* the sample's luminance */
    float largest;                      /* its largest single contribution */
    float max_beta;                     /* the largest throughput along the path */
    unsigned char source, bounce;       /* of the largest contribution */
} sample_rec;

static int source_of(const char *s)
{
    if (!s) return SRC_NONE;
    if (strcmp(s, "emission") == 0) return SRC_EMISSION;
    if (strcmp(s, "environment") == 0) return SRC_ENVIRONMENT;
    if (strcmp(s, "equiangular") == 0) return SRC_EQUIANGULAR;
    if (strcmp(s, "light behind") == 0) return SRC_BEHIND;
    return SRC_LIGHT;                   /* "light sample" */
}

static void on_event(const fogrt_trace_event *e, void *user)
{
    sample_rec *r = (sample_rec *)user;
    float b = fogrt__max3(e->beta);     /* the header's own helpers (this file includes its implementation) */
    if (e->kind != FOGRT_TRACE_CAMERA && e->kind != FOGRT_TRACE_END && b > r->max_beta) r->max_beta = b;
    if (e->kind == FOGRT_TRACE_CONTRIBUTION && e->flag) {
        float l = fogrt__luminance(e->value);
        if (l > r->largest) {
            r->largest = l;
            r->source = (unsigned char)source_of(e->source);
            r->bounce = (unsigned char)(e->bounce < MAX_BOUNCE ? e->bounce : MAX_BOUNCE);
        }
    }
}

typedef struct share { double var, mean, n; } share;

static void add_share(share *s, double d2, double L) { s->var += d2; s->mean += L; s->n += 1.0; }

static void print_share(const char *name, const share *s, double var, double mean, double n)
{
    printf("  %-34s %7.3f%% of the samples  %6.1f%% of the noise  %6.1f%% of the image\n", name,
           n > 0 ? 100.0 * s->n / n : 0.0, var > 0 ? 100.0 * s->var / var : 0.0, mean > 0 ? 100.0 * s->mean / mean : 0.0);
}

static int usage(const char *msg)
{
    fprintf(stderr, "variance_sources: %s\nusage: variance_sources [scene] [--density S] [--g G] [--albedo A] "
            "[-r W H] [-s SPP] [--top N]\n", msg);
    return 2;
}

int main(int argc, char **argv)
{
    const char *path = NULL;
    int W = 120, H = 90, S = 64, top = 5, i, y;
    float density = -1.0f, g = -2.0f, albedo = -1.0f;
    fogrt_scene *scene = NULL;
    fogrt_medium_desc md;
    fogrt_render_desc rd;
    fogrt_result r;
    sample_rec *rec;
    double *mean;
    size_t n, p, k;
    for (i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--density") == 0 && i + 1 < argc) density = (float)atof(argv[++i]);
        else if (strcmp(argv[i], "--g") == 0 && i + 1 < argc) g = (float)atof(argv[++i]);
        else if (strcmp(argv[i], "--albedo") == 0 && i + 1 < argc) albedo = (float)atof(argv[++i]);
        else if (strcmp(argv[i], "-r") == 0 && i + 2 < argc) { W = atoi(argv[i + 1]); H = atoi(argv[i + 2]); i += 2; }
        else if (strcmp(argv[i], "-s") == 0 && i + 1 < argc) S = atoi(argv[++i]);
        else if (strcmp(argv[i], "--top") == 0 && i + 1 < argc) top = atoi(argv[++i]);
        else if (argv[i][0] == '-') return usage("unknown flag or missing value");
        else path = argv[i];
    }
    if (W < 1 || H < 1 || W > 4096 || H > 4096 || S < 2 || S > 65536 || top < 0)
        return usage("-r W H in [1, 4096], -s SPP in [2, 65536], --top N >= 0");
    if (fogrt_scene_create(NULL, &scene) != FOGRT_RESULT_OK) return usage("out of memory");
    if (path) {
#ifdef HAVE_FOGRT_LOAD
        r = fogrt_load_file(scene, path, NULL, NULL);
        if (r != FOGRT_RESULT_OK) {
            fprintf(stderr, "variance_sources: %s: %s\n", path, fogrt_result_string(r));
            fogrt_scene_destroy(scene);
            return 2;
        }
#else
        fogrt_scene_destroy(scene);
        return usage("built without fogrt_load.h: no scene files");
#endif
    } else {
        fogrt_scene_add_default(scene);
    }
    fogrt_scene_get_medium(scene, &md);
    if (path && md.sigma_t == 0.0f) { md.albedo.x = md.albedo.y = md.albedo.z = 0.9f; md.g = 0.0f; }   /* as the CLI */
    if (density >= 0.0f) md.sigma_t = density;
    if (g >= -1.0f) md.g = g;
    if (albedo >= 0.0f) md.albedo.x = md.albedo.y = md.albedo.z = albedo;
    if ((r = fogrt_scene_set_medium(scene, &md)) != FOGRT_RESULT_OK || (r = fogrt_scene_build(scene, NULL)) != FOGRT_RESULT_OK) {
        fprintf(stderr, "variance_sources: %s\n", fogrt_result_string(r));
        fogrt_scene_destroy(scene);
        return 2;
    }
    rd = fogrt_render_defaults();
    n = (size_t)W * (size_t)H;
    rec = (sample_rec *)calloc(n * (size_t)S, sizeof *rec);
    mean = (double *)calloc(n, sizeof *mean);
    if (!rec || !mean) { free(rec); free(mean); fogrt_scene_destroy(scene); return usage("out of memory"); }
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1)
#endif
    for (y = 0; y < H; ++y) {
        int x, s;
        for (x = 0; x < W; ++x)
            for (s = 0; s < S; ++s) {
                sample_rec *q = &rec[((size_t)y * (size_t)W + (size_t)x) * (size_t)S + (size_t)s];
                fogrt_vec3 L = fogrt_trace_path(scene, &rd, W, H, x, y, (uint32_t)s, on_event, q);
                q->L = fogrt__luminance(L);
            }
    }
    {
        static const double rel_edges[] = { 0.0, 2.0, 5.0, 20.0, 100.0, 1e300 };
        static const double beta_edges[] = { 0.0, 1.5, 2.0, 4.0, 8.0, 1e300 };
        share by_rel[5], by_src[SRC_NUM], by_bounce[MAX_BOUNCE + 1], by_beta[5];
        double var = 0.0, total = 0.0, count = (double)n * (double)S, mean_sq = 0.0;
        char name[64];
        memset(by_rel, 0, sizeof by_rel); memset(by_src, 0, sizeof by_src);
        memset(by_bounce, 0, sizeof by_bounce); memset(by_beta, 0, sizeof by_beta);
        for (p = 0; p < n; ++p) {
            double m = 0.0;
            for (k = 0; k < (size_t)S; ++k) m += rec[p * (size_t)S + k].L;
            mean[p] = m / S;
            mean_sq += mean[p] * mean[p];
        }
        for (p = 0; p < n; ++p)
            for (k = 0; k < (size_t)S; ++k) {
                const sample_rec *q = &rec[p * (size_t)S + k];
                double L = q->L, d2 = (L - mean[p]) * (L - mean[p]), rel = mean[p] > 0.0 ? L / mean[p] : 0.0;
                int j;
                var += d2; total += L;
                for (j = 0; j < 5 && !(rel < rel_edges[j + 1]); ++j) {}
                add_share(&by_rel[j < 5 ? j : 4], d2, L);
                add_share(&by_src[q->largest > 0.0f ? (int)q->source : (int)SRC_NONE], d2, L);
                add_share(&by_bounce[q->bounce], d2, L);
                for (j = 0; j < 5 && !(q->max_beta < beta_edges[j + 1]); ++j) {}
                add_share(&by_beta[j < 5 ? j : 4], d2, L);
            }
        printf("variance_sources: %s, %dx%d, %d spp, sigma_t %g, albedo %g, g %g\n", path ? path : "the default scene",
               W, H, S, (double)md.sigma_t, (double)md.albedo.y, (double)md.g);
        printf("relative error of one such render (sum of the pixels' variances over the sum of their squared means): %.2f%%\n",
               mean_sq > 0.0 ? 100.0 * sqrt(var / ((double)S - 1.0) / (double)S / mean_sq) : 0.0);
        printf("by the sample's luminance against its pixel's mean:\n");
        for (i = 0; i < 5; ++i) {
            if (rel_edges[i + 1] < 1e300) snprintf(name, sizeof name, "%g to %g times", rel_edges[i], rel_edges[i + 1]);
            else snprintf(name, sizeof name, "%g times or more", rel_edges[i]);
            print_share(name, &by_rel[i], var, total, count);
        }
        printf("by the source of the sample's largest contribution:\n");
        for (i = 0; i < SRC_NUM; ++i) print_share(src_names[i], &by_src[i], var, total, count);
        printf("by the bounce of that contribution (paths that gathered nothing count at 0):\n");
        for (i = 0; i <= MAX_BOUNCE; ++i) {
            snprintf(name, sizeof name, i < MAX_BOUNCE ? "bounce %d" : "bounce %d or later", i);
            print_share(name, &by_bounce[i], var, total, count);
        }
        printf("by the largest throughput along the path:\n");
        for (i = 0; i < 5; ++i) {
            if (beta_edges[i + 1] < 1e300) snprintf(name, sizeof name, "%g to %g", beta_edges[i], beta_edges[i + 1]);
            else snprintf(name, sizeof name, "%g or more", beta_edges[i]);
            print_share(name, &by_beta[i], var, total, count);
        }
        if (top > 0) printf("the %d samples that add the most noise (each printed event by event by the command):\n", top);
        for (i = 0; i < top; ++i) {         /* a plain search per line: top is small */
            size_t best = (size_t)-1;
            double best_d2 = -1.0;
            for (p = 0; p < n * (size_t)S; ++p) {
                double d = rec[p].L - mean[p / (size_t)S];
                if (rec[p].largest >= 0.0f && d * d > best_d2) { best_d2 = d * d; best = p; }
            }
            if (best == (size_t)-1 || !(best_d2 > 0.0)) break;
            p = best / (size_t)S;
            printf("  %5.1f times its pixel's mean, %4.1f%% of the noise: fogrt --trace %d,%d,%d -r %d %d ...\n",
                   mean[p] > 0.0 ? rec[best].L / mean[p] : 0.0, var > 0.0 ? 100.0 * best_d2 / var : 0.0,
                   (int)(p % (size_t)W), (int)(p / (size_t)W), (int)(best % (size_t)S), W, H);
            rec[best].largest = -1.0f;      /* not again */
        }
    }
    free(rec); free(mean);
    fogrt_scene_destroy(scene);
    return 0;
}
