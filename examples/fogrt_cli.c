/* fogrt - the command-line renderer.

   Renders a CS184 .dae scene, an OBJ or PLY mesh (placed in the default fog-filled Cornell
   box) or, with no scene argument, the embedded default scene. CS184's flags keep CS184's
   meanings, so `fogrt -t 8 -s 64 -l 16 -m 6 -r 480 360 -f out.png scene.dae` works as the
   students type it; the fog and method flags are fogrt's own. `fogrt -h` lists them all with
   their defaults.

   Exit status: 0 on success, 2 for bad input (an unknown flag, a value out of range, a
   missing, malformed or non-regular scene, camera or reference file, an image above the
   memory limit), 1 when rendering or writing an output fails, 130 when interrupted
   (SIGINT or SIGTERM: the image rendered so far is written first). Every error is one line
   on stderr naming the flag or the file:line.

   Outputs are written to a temporary file in the same directory and renamed over the old
   file, so a failed or interrupted write never leaves a truncated image where a good one
   was; every write, the fsync and the close are checked.

   Build: make (the rule is in mk/cli.mk; PNG and JPG output use stb_image_write from
   libstb-dev, through its in-memory callback API). */
#define _XOPEN_SOURCE 700
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <stdarg.h>
#include <errno.h>
#include <math.h>
#include <float.h>
#include <time.h>
#include <signal.h>
#include <ctype.h>
#include <fcntl.h>
#include <unistd.h>
#include <sys/types.h>
#include <sys/stat.h>

#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#define FOGRT_LOAD_IMPLEMENTATION
#include "fogrt_load.h"

#define FOGRT_STB_READ_HDR
#include "stb_write.h"           /* stb_image_write, its warnings silenced */
#ifdef FOGRT_CLI_EXR
#include <tinyexr.h>            /* Debian's libtinyexr-dev (C declarations, -ltinyexr) */
#endif

/* --trace: in examples/fogrt_cli_trace.c, a second copy of the renderer compiled with
   FOGRT_TRACE, so that the renders of this program carry no trace hooks. */
int cli_trace_path(const fogrt_scene *scene, const fogrt_render_desc *rd, int width, int height, int x, int y,
                   uint32_t sample, FILE *out);

/* ------------------------------------------------------------------------------------------
   Options and their defaults (keep in step with usage())
   ------------------------------------------------------------------------------------------ */
#define CLI_MAX_SIDE 32768
/* Image memory limit, checked before anything is allocated: the accumulation buffer (84
   bytes per pixel: double RGB sum, double sum of squares, 32-bit count, and per each of the
   4 sample streams a double luminance sum and a 32-bit count), the resolved float image
   (12), the 8-bit image (3), the encoded output (up to 13), the reference (12) and the
   --pixel-rates (4): 128. (Making the rates borrows 48 more for a moment; when that fails
   the render goes on with every pixel alike.) */
#define CLI_BYTES_PER_PIXEL 128.0
#define CLI_MAX_IMAGE_BYTES (2.0 * 1024.0 * 1024.0 * 1024.0)
/* Ceilings of an open-ended render (--target-error without -s). */
#define CLI_CEILING_SPP 65536
#define CLI_RATES_PILOT 8         /* --pixel-rates: spp taken alike before the rates are made */
#define CLI_CEILING_SECONDS 3600.0
/* Threads: at most 4 per processor, and never more than this. */
#define CLI_MAX_THREADS 256
/* Progressive batches are sized to take about this long, so the error estimate updates
   and an interrupt is answered within a second or two. */
#define CLI_BATCH_SECONDS 0.5
/* Without a terminal, the progress line is printed every this many seconds. */
#define CLI_LOG_PROGRESS_SECONDS 5.0
/* Camera coordinates, lens radius and focal distance beyond this overflow float ray maths. */
#define CLI_MAX_CAMERA_COORD 1e18f
/* -m 0 is emission only (fogrt_render_desc.max_depth 0, the core's API of issue 13). */
#define CLI_MIN_DEPTH 0
#define CLI_PI 3.14159265358979323846

typedef struct cli_options {
    int spp; bool spp_set;              /* -s */
    int light_samples;                  /* -l */
    int threads;                        /* -t */
    int max_depth;                      /* -m */
    int accumulate;                     /* -o: 1 all bounces up to -m, 0 only exactly -m */
    int width, height;                  /* -r */
    const char *output; bool output_set;   /* -f */
    float exposure_ev;                  /* --exposure */
    fogrt_vec3 cam_pos, cam_look, cam_up;  /* --camera-pos, --look-at, --up */
    bool cam_pos_set, cam_look_set, cam_up_set;
    float fov; bool fov_set;            /* --fov: full horizontal field of view */
    bool cs184_framing;
    bool print_camera;
    const char *log_path;               /* --log */
    const char *reference;              /* --reference */
    bool equiangular, mis, glow, expected; /* --equiangular, --mis, --glow, --expected-emission */
    bool footprint;                        /* --footprint */
    bool pixel_rates;                      /* --pixel-rates */
    bool by_power;                      /* --lights power */
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
    const char *env_map;                /* -e */
    fogrt_vec3 fog_lo, fog_hi; bool fog_bounds_set;   /* --fog-bounds */
    int trace_x, trace_y, trace_sample; bool trace;  /* --trace */
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
        "  -s N         samples per pixel (default 64); with --pixel-rates on (the default)\n"
        "               their mean over the image, more where the noise is\n"
        "  -l N         samples per area light at each light-sampling step (default 1)\n"
        "  -t N         threads (default 0 = all cores; capped at 4 per processor, at most %d)\n"
        "  -m N         maximum ray depth: bounces after the camera ray, N >= 0; 0 = emission\n"
        "               only (default 64; Russian roulette ends paths earlier)\n"
        "  -o 0|1       CS184's isAccumBounces: 1 counts light of every bounce up to -m, 0 only\n"
        "               light that bounced exactly -m times (default 1)\n"
        "  -r W H       image size in pixels (default 800 600, CS184's window); the view keeps\n"
        "               CS184's 800x600 framing at every size (see --cs184-framing); the\n"
        "               image buffers (%.0f bytes per pixel) may use at most %.0f MiB\n"
        "  -f FILE      output image: .png or .jpg (tone mapped: --exposure, then sRGB), .pfm\n"
        "               (linear float, never scaled) or .ppm (default out.png, with a note on\n"
        "               stderr: CS184 opens its viewer here, fogrt's is `make preview`)\n"
        "  -b R         thin-lens radius (default 0 = pinhole)\n"
        "  -d D         focal distance (default: the distance to the camera's target)\n"
        "  -a B T       adaptive sampling: check every B samples, stop a pixel once its 95%%\n"
        "               confidence half-width is <= T x its mean (default off; -s is the cap);\n"
        "               also writes CS184's sampling-rate image <name>_rate.png (samples /\n"
        "               -s per pixel: blue 0, green 0.5, red 1)\n"
        "  -H           hemisphere sampling: no light sampling, emitters found by hitting them\n"
        "               (point and spot lights then contribute nothing) (default off)\n"
        "  -c FILE      camera settings file as CS184 writes it (default: the scene's camera)\n"
        "  -g G         Henyey-Greenstein g in [-1, 1], as in the paper's renderer; like the\n"
        "               paper it also switches fog on (density 0.2) when the scene has none\n"
        "               and --density is not given\n"
        "  -h           this help\n"
        "\n", CLI_MAX_THREADS, CLI_BYTES_PER_PIXEL, CLI_MAX_IMAGE_BYTES / (1024.0 * 1024.0));
    fprintf(f,
        "Camera and output flags:\n"
        "  --camera-pos X,Y,Z  eye position (default: the scene's camera)\n"
        "  --look-at X,Y,Z     point looked at (default: the scene's camera)\n"
        "  --up X,Y,Z          up direction (default: the scene's camera, else +y)\n"
        "  --fov DEG           full horizontal field of view in degrees, (0, 180) (default:\n"
        "                      the scene's); a free camera is a pinhole unless -b is given\n"
        "  --cs184-framing     CS184's view for -r W H: its focal length in pixels (875 for\n"
        "                      the shipped files) is kept, so the field of view changes with\n"
        "                      the size (default off: the 800x600 frame is kept whole)\n"
        "  --print-camera      print the camera that would be used and exit (default off)\n"
        "  --exposure EV       PNG/JPG brightness: the image is multiplied by 2^EV before the\n"
        "                      sRGB curve, EV in [-64, 64] (default 0); PFM is never scaled\n"
        "  Pixel filter: each sample lands on a stratified point of its pixel (4 independently\n"
        "  scrambled (0,2)-sequences per pixel; with -a independent uniform points) and is\n"
        "  weighted 1 (a box filter one pixel wide).\n"
        "\n");
    fprintf(f,
        "Fog and method flags:\n"
        "  --density S      extinction sigma_t >= 0 per scene unit, the paper's lambda (default:\n"
        "                   the scene's own: 0.3 for the default scene and OBJ/PLY, 0 for .dae)\n"
        "  --albedo A       single-scattering albedo in [0, 1], a scalar or r,g,b (default: the\n"
        "                   scene's: 0.9; .dae files 0.9)\n"
        "  --g G            Henyey-Greenstein g in [-1, 1], > 0 forward (default: the scene's:\n"
        "                   0.6; .dae files 0)\n"
        "  --integrator I   path (global illumination, the paper's Algorithm 1) or direct\n"
        "                   (one bounce, the paper's baseline) (default path)\n"
        "  --equiangular on|off  equiangular distance sampling toward point and spot lights in\n"
        "                   fog; off: they are found only by next-event estimation at fog\n"
        "                   collisions, as in the paper (default on)\n"
        "  --lights L       all: every light sampled at every vertex, as CS184 does; power:\n"
        "                   one light per vertex, chosen in proportion to its power (default all)\n"
        "  --glow on|off    in fog, some scattered directions (up to half) aim at the glow around\n"
        "                   point and spot lights (needs --equiangular on) (default on)\n"
        "  --footprint on|off  a fifth of those aimed at a spot light aim at the plane it\n"
        "                   lights most (the lit floor under it; needs --glow on) (default on)\n"
        "  --expected-emission on|off  in fog, a ray adds the light of the lamp it reaches, and\n"
        "                   of the point and spot lights at the surface it reaches, times the\n"
        "                   fog's transmittance, whether or not it scatters first; off: the\n"
        "                   paper's way, that light only when the ray gets there (default on)\n"
        "  --mis on|off     multiple importance sampling of light and BSDF/phase samples; off:\n"
        "                   light sampling alone (default on)\n"
        "  --pixel-rates on|off  adaptive sampling: after the first %d spp, taken alike in every\n"
        "                   pixel, each pixel gets samples in proportion to the noise around\n"
        "                   it (fogrt_image_sample_rates: its neighbours', never its own, so\n"
        "                   the image stays unbiased); -s and the spp shown are then the mean\n"
        "                   over the pixels (default on)\n"
        "  --fresnel F      schlick or exact (default schlick)\n"
        "  --bvh H          sah or volume (the paper's volume heuristic) (default sah)\n"
        "  --seed N         random seed (default 0); the image is the same on any thread count\n"
        "  --time SECONDS   stop after about this long (default: no limit; without -s the\n"
        "                   sample count is then unlimited)\n"
        "  --target-error E stop when the estimated relative RMS error is <= E (default: none);\n"
        "                   without -s the render also stops at %d spp or after %.0f s,\n"
        "                   whichever comes first, even if the estimate never gets there\n"
        "  --quiet          no progress line and no summary (errors and warnings still shown)\n"
        "\n", CLI_RATES_PILOT, CLI_CEILING_SPP, CLI_CEILING_SECONDS);
    fprintf(f,
        "Error against time (the progress line and the summary show the same numbers):\n"
        "  --log FILE.csv   append one row per progressive batch (default none); the header\n"
        "                   row, written when the file is new, names the columns:\n"
        "                     seconds       render time so far\n"
        "                     spp           mean samples per pixel so far\n"
        "                     samples_per_second\n"
        "                     est_rel_mse   the render's own estimate (fogrt_image_error):\n"
        "                                   sum_p Var[mean_p] / sum_p mean_p^2 (luminance)\n"
        "                     est_rel_error sqrt(est_rel_mse)\n"
        "                     ref_rel_mse   with --reference: sum_p (Y_p - Yref_p)^2 /\n"
        "                                   sum_p Yref_p^2, Y the luminance of a pixel (the\n"
        "                                   same ratio the estimate estimates)\n"
        "                     ref_rmse      sqrt(mean over pixels and channels of (x - ref)^2)\n"
        "                     ref_ratio_r, ref_ratio_g, ref_ratio_b   sum x / sum ref per\n"
        "                                   channel (1 = unbiased brightness)\n"
        "                     event         batch, final or interrupted\n"
        "  --reference REF.pfm  measure the error against this image (same size as -r; a\n"
        "                   linear PFM, e.g. a long fogrt render) (default none)\n"
        "\n"
        "Ctrl-C (or SIGTERM) stops within a second or two, writes the image so far (and the\n"
        "--log row), prints the summary marked interrupted and exits 130; a second Ctrl-C\n"
        "quits at once without writing.\n"
        "Exit status: 0 ok, 2 bad input (flag, value, scene/camera/reference file), 1 render or\n"
        "write failure (the file is named), 130 interrupted.\n");
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
/* "X,Y,Z": three finite numbers */
static bool parse_vec3(const char *s, fogrt_vec3 *out)
{
    char buf[256], *a, *b;
    float v[3];
    if (strlen(s) >= sizeof buf) return false;
    strcpy(buf, s);
    a = strchr(buf, ',');
    if (!a) return false;
    *a++ = 0;
    b = strchr(a, ',');
    if (!b) return false;
    *b++ = 0;
    if (!parse_float(buf, &v[0]) || !parse_float(a, &v[1]) || !parse_float(b, &v[2])) return false;
    out->x = v[0]; out->y = v[1]; out->z = v[2];
    return true;
}
static bool parse_onoff(const char *s, bool *out)
{
    if (strcmp(s, "on") == 0) { *out = true; return true; }
    if (strcmp(s, "off") == 0) { *out = false; return true; }
    return false;
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
    o->spp = 64; o->light_samples = 1; o->threads = 0; o->max_depth = 64; o->accumulate = 1;
    o->width = 800; o->height = 600; o->output = "out.png";
    o->equiangular = true; o->mis = true; o->glow = true; o->footprint = true; o->expected = true; o->pixel_rates = true;
    o->integrator = FOGRT_INTEGRATOR_PATH; o->fresnel = FOGRT_FRESNEL_SCHLICK; o->bvh = FOGRT_BVH_SAH;
    for (i = 1; i < argc; ++i) {
        const char *a = argv[i];
#define NEED(n) do { if (i + (n) >= argc) return bad_flag(a, "needs %d value%s", (n), (n) > 1 ? "s" : ""); } while (0)
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) { usage(stdout); return -1; }
        else if (strcmp(a, "-s") == 0) { NEED(1); if (!parse_int(argv[++i], 1, 1 << 24, &o->spp)) return bad_flag(a, "samples per pixel must be an integer in [1, 16777216], got '%s'", argv[i]); o->spp_set = true; }
        else if (strcmp(a, "-l") == 0) { NEED(1); if (!parse_int(argv[++i], 1, 1 << 16, &o->light_samples)) return bad_flag(a, "light samples must be an integer in [1, 65536], got '%s'", argv[i]); }
        else if (strcmp(a, "-t") == 0) { NEED(1); if (!parse_int(argv[++i], 0, 4096, &o->threads)) return bad_flag(a, "threads must be an integer in [0, 4096], got '%s'", argv[i]); }
        else if (strcmp(a, "-m") == 0) { NEED(1); if (!parse_int(argv[++i], CLI_MIN_DEPTH, 1 << 20, &o->max_depth)) return bad_flag(a, "maximum ray depth must be an integer in [%d, 1048576], got '%s'", CLI_MIN_DEPTH, argv[i]); }
        else if (strcmp(a, "-o") == 0) { NEED(1); if (!parse_int(argv[++i], 0, 1, &o->accumulate)) return bad_flag(a, "must be 0 (only light that bounced exactly -m times) or 1 (all bounces), got '%s'", argv[i]); }
        else if (strcmp(a, "-r") == 0) {
            NEED(2);
            if (!parse_int(argv[i + 1], 1, CLI_MAX_SIDE, &o->width) || !parse_int(argv[i + 2], 1, CLI_MAX_SIDE, &o->height))
                return bad_flag(a, "width and height must be integers in [1, %d], got '%s %s'", CLI_MAX_SIDE, argv[i + 1], argv[i + 2]);
            i += 2;
        }
        else if (strcmp(a, "-f") == 0) {
            NEED(1);
            o->output = argv[++i];
            o->output_set = true;
            if (!ends_with(o->output, ".png") && !ends_with(o->output, ".jpg") && !ends_with(o->output, ".jpeg") &&
                !ends_with(o->output, ".pfm") && !ends_with(o->output, ".ppm"))
                return bad_flag(a, "output '%s' must end in .png, .jpg, .pfm or .ppm", o->output);
        }
        else if (strcmp(a, "--exposure") == 0) { NEED(1); if (!parse_float(argv[++i], &o->exposure_ev) || o->exposure_ev < -64 || o->exposure_ev > 64) return bad_flag(a, "exposure must be a number of stops in [-64, 64], got '%s'", argv[i]); }
        else if (strcmp(a, "--camera-pos") == 0) { NEED(1); if (!parse_vec3(argv[++i], &o->cam_pos)) return bad_flag(a, "needs X,Y,Z (three numbers), got '%s'", argv[i]); o->cam_pos_set = true; }
        else if (strcmp(a, "--look-at") == 0) { NEED(1); if (!parse_vec3(argv[++i], &o->cam_look)) return bad_flag(a, "needs X,Y,Z (three numbers), got '%s'", argv[i]); o->cam_look_set = true; }
        else if (strcmp(a, "--up") == 0) {
            NEED(1);
            if (!parse_vec3(argv[++i], &o->cam_up) || (o->cam_up.x == 0 && o->cam_up.y == 0 && o->cam_up.z == 0))
                return bad_flag(a, "needs X,Y,Z (three numbers, not all 0), got '%s'", argv[i]);
            o->cam_up_set = true;
        }
        else if (strcmp(a, "--fov") == 0) { NEED(1); if (!parse_float(argv[++i], &o->fov) || !(o->fov > 0 && o->fov < 180)) return bad_flag(a, "field of view must be a number of degrees in (0, 180), got '%s'", argv[i]); o->fov_set = true; }
        else if (strcmp(a, "--cs184-framing") == 0) o->cs184_framing = true;
        else if (strcmp(a, "--print-camera") == 0) o->print_camera = true;
        else if (strcmp(a, "--log") == 0) { NEED(1); o->log_path = argv[++i]; }
        else if (strcmp(a, "--reference") == 0) {
            NEED(1);
            o->reference = argv[++i];
            if (!ends_with(o->reference, ".pfm")) return bad_flag(a, "reference '%s' must be a .pfm image", o->reference);
        }
        else if (strcmp(a, "--lights") == 0) {
            NEED(1); ++i;
            if (strcmp(argv[i], "all") == 0) o->by_power = false;
            else if (strcmp(argv[i], "power") == 0) o->by_power = true;
            else return bad_flag(a, "must be all or power, got '%s'", argv[i]);
        }
        else if (strcmp(a, "--pixel-rates") == 0) { NEED(1); if (!parse_onoff(argv[++i], &o->pixel_rates)) return bad_flag(a, "must be on or off, got '%s'", argv[i]); }
        else if (strcmp(a, "--glow") == 0) { NEED(1); if (!parse_onoff(argv[++i], &o->glow)) return bad_flag(a, "must be on or off, got '%s'", argv[i]); }
        else if (strcmp(a, "--footprint") == 0) { NEED(1); if (!parse_onoff(argv[++i], &o->footprint)) return bad_flag(a, "must be on or off, got '%s'", argv[i]); }
        else if (strcmp(a, "--expected-emission") == 0) { NEED(1); if (!parse_onoff(argv[++i], &o->expected)) return bad_flag(a, "must be on or off, got '%s'", argv[i]); }
        else if (strcmp(a, "--equiangular") == 0) { NEED(1); if (!parse_onoff(argv[++i], &o->equiangular)) return bad_flag(a, "must be on or off, got '%s'", argv[i]); }
        else if (strcmp(a, "--mis") == 0) { NEED(1); if (!parse_onoff(argv[++i], &o->mis)) return bad_flag(a, "must be on or off, got '%s'", argv[i]); }
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
        else if (strcmp(a, "--density") == 0) { NEED(1); if (!parse_float(argv[++i], &o->density) || o->density < 0) return bad_flag(a, "density must be a finite number >= 0 (float: at most 3.4e38), got '%s'", argv[i]); o->density_set = true; }
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
        else if (strcmp(a, "-e") == 0) { NEED(1); o->env_map = argv[++i]; }
        else if (strcmp(a, "--fog-bounds") == 0) {
            float v[6];
            char tail;
            NEED(1); ++i;
            if (sscanf(argv[i], "%f,%f,%f,%f,%f,%f%c", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &tail) != 6 ||
                !(v[0] < v[3] && v[1] < v[4] && v[2] < v[5]) || !isfinite(v[0] + v[1] + v[2] + v[3] + v[4] + v[5]))
                return bad_flag(a, "must be X0,Y0,Z0,X1,Y1,Z1 with X0 < X1, Y0 < Y1, Z0 < Z1, got '%s'", argv[i]);
            o->fog_lo.x = v[0]; o->fog_lo.y = v[1]; o->fog_lo.z = v[2];
            o->fog_hi.x = v[3]; o->fog_hi.y = v[4]; o->fog_hi.z = v[5];
            o->fog_bounds_set = true;
        }
        else if (strcmp(a, "--trace") == 0) {
            char tail;
            int n;
            NEED(1); ++i;
            o->trace_sample = 0;
            n = sscanf(argv[i], "%d,%d,%d%c", &o->trace_x, &o->trace_y, &o->trace_sample, &tail);
            if ((n != 2 && n != 3) || o->trace_x < 0 || o->trace_y < 0 || o->trace_sample < 0)
                return bad_flag(a, "must be X,Y or X,Y,SAMPLE (pixel column, row from the top, sample index >= 0), got '%s'", argv[i]);
            o->trace = true;
        }
        else if (a[0] == '-' && a[1] != 0) return bad_flag(a, "unknown flag");
        else {
            if (o->scene) return bad_flag(a, "only one scene file may be given (already have '%s')", o->scene);
            o->scene = a;
        }
#undef NEED
    }
    if (o->adaptive && (o->time_budget > 0 || o->target_error > 0))
        return bad_flag("-a", "cannot be combined with --time or --target-error");
    {   /* the image memory, before anything is allocated */
        double bytes = (double)o->width * (double)o->height * CLI_BYTES_PER_PIXEL;
        if (bytes > CLI_MAX_IMAGE_BYTES) {
            char flag[64];
            snprintf(flag, sizeof flag, "-r %d %d", o->width, o->height);
            return bad_flag(flag, "the image buffers would need %.1f GiB (%.0f bytes per pixel), above the limit of %.1f GiB",
                            bytes / (1024.0 * 1024.0 * 1024.0), CLI_BYTES_PER_PIXEL, CLI_MAX_IMAGE_BYTES / (1024.0 * 1024.0 * 1024.0));
        }
    }
    if (o->trace && (o->trace_x >= o->width || o->trace_y >= o->height))
        return bad_flag("--trace", "pixel (%d, %d) is outside the %dx%d image (-r)", o->trace_x, o->trace_y, o->width, o->height);
    if (o->cs184_framing && o->fov_set)
        return bad_flag("--cs184-framing", "cannot be combined with --fov (--fov sets the view itself)");

    return 0;
}

/* ------------------------------------------------------------------------------------------
   The calls that follow the core's API (issue 13's fogrt_render_desc), kept in one place
   ------------------------------------------------------------------------------------------ */
static void fill_render_desc(const cli_options *o, int threads, fogrt_render_desc *rd)
{
    *rd = fogrt_render_defaults();
    rd->width = o->width; rd->height = o->height;
    rd->integrator = o->integrator;
    rd->fresnel = o->fresnel;
    rd->max_depth = o->max_depth;                       /* 0: emission only */
    rd->min_depth = o->accumulate ? 0 : o->max_depth;   /* -o 0: exactly -m bounces */
    rd->light_samples = o->light_samples;
    rd->nee = !o->hemisphere;
    rd->mis = o->mis;
    rd->equiangular = o->equiangular;
    rd->glow = o->glow;
    rd->footprint = o->footprint;
    rd->expected_emission = o->expected;
    rd->light_by_power = o->by_power;
    rd->seed = o->seed;
    rd->threads = threads;
}
static void release_image(fogrt_image *img)
{
    fogrt_image_free(img);
}

/* ------------------------------------------------------------------------------------------
   Signals: the first SIGINT/SIGTERM asks the render to stop at the next row block and write
   what it has; the second quits at once (removing a half-written temporary file).
   ------------------------------------------------------------------------------------------ */
static volatile sig_atomic_t cli_interrupted = 0;
static volatile sig_atomic_t cli_temp_live = 0;
static volatile sig_atomic_t cli_tty = 0;     /* stderr is a terminal */
static char cli_temp_path[4096];

static void write_stderr_raw(const char *s, size_t n)
{
    while (n > 0) {
        ssize_t k = write(2, s, n);
        if (k <= 0) return;
        s += k; n -= (size_t)k;
    }
}
static void on_signal(int sig)
{
    static const char again[] = "\nfogrt: interrupted again: quitting without writing\n";
    static const char first[] = "\nfogrt: interrupted: stopping and writing the image so far (Ctrl-C again quits at once)\n";
    if (cli_interrupted) {
        if (cli_temp_live) unlink(cli_temp_path);
        write_stderr_raw(again + !cli_tty, sizeof again - 1 - (size_t)!cli_tty);
        _exit(130);
    }
    cli_interrupted = sig;
    if (cli_tty) write_stderr_raw(first, sizeof first - 1);      /* ends the \r progress line */
    else write_stderr_raw(first + 1, sizeof first - 2);
}
static void install_signals(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    signal(SIGXFSZ, SIG_IGN);    /* a file-size limit makes write() fail (EFBIG), not kill us */
}

/* ------------------------------------------------------------------------------------------
   Messages: the core's error lines are kept and folded into the CLI's one line
   ------------------------------------------------------------------------------------------ */
typedef struct cli_log { char error[512]; } cli_log;

static void log_core(fogrt_log_level level, const char *message, void *user)
{
    cli_log *L = (cli_log *)user;
    if (level == FOGRT_LOG_ERROR) {            /* printed by fail_line(), with the context */
        if (L && !L->error[0]) snprintf(L->error, sizeof L->error, "%s", message);
        return;
    }
    /* the CLI says this one itself, naming the scene file (after the build) */
    if (strncmp(message, "scene: nothing emits light", 26) == 0) return;
    fprintf(stderr, "fogrt: %s%s\n", level == FOGRT_LOG_WARNING ? "warning: " : "", message);
}
static void log_load(fogrt_log_level level, const char *message, void *user)
{
    (void)level; (void)user;
    fprintf(stderr, "fogrt: %s\n", message);     /* already "file:line: warning: ..." */
}
/* The one line of a failed core call: "fogrt: WHERE: the core's message (or the result)". */
static void fail_line(cli_log *L, const char *where, fogrt_result r)
{
    fprintf(stderr, "fogrt: %s: %s\n", where, L->error[0] ? L->error : fogrt_result_string(r));
    L->error[0] = 0;
}
static void fail_load(cli_log *L, const char *prefix, const fogrt_load_report *rep, fogrt_result r)
{
    const char *msg = rep->message[0] ? rep->message : (L->error[0] ? L->error : fogrt_result_string(r));
    if (rep->line > 0) fprintf(stderr, "fogrt: %s%s:%d: %s", prefix, rep->file, rep->line, msg);
    else fprintf(stderr, "fogrt: %s%s: %s", prefix, rep->file, msg);
    if (L->error[0] && msg != L->error && !strstr(msg, L->error)) fprintf(stderr, " (%s)", L->error);
    fputc('\n', stderr);
    L->error[0] = 0;
}

/* ------------------------------------------------------------------------------------------
   Checks made before anything is loaded or allocated
   ------------------------------------------------------------------------------------------ */
static const char *file_kind(mode_t m)
{
    if (S_ISDIR(m)) return "a directory";
    if (S_ISFIFO(m)) return "a FIFO";
    if (S_ISCHR(m)) return "a character device";
    if (S_ISBLK(m)) return "a block device";
    if (S_ISSOCK(m)) return "a socket";
    return "not a regular file";
}
/* Scene, -c and --reference files must be regular files: a FIFO would block in open(). */
static int check_input_file(const char *prefix, const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0) {
        fprintf(stderr, "fogrt: %s%s: cannot open: %s\n", prefix, path, strerror(errno));
        return 2;
    }
    if (!S_ISREG(st.st_mode)) {
        fprintf(stderr, "fogrt: %s%s: is %s, not a regular file\n", prefix, path, file_kind(st.st_mode));
        return 2;
    }
    return 0;
}

static int cap_threads(int requested)
{
#ifdef _OPENMP
    int procs = omp_get_num_procs();
#elif defined(_SC_NPROCESSORS_ONLN)
    int procs = (int)sysconf(_SC_NPROCESSORS_ONLN);
#else
    int procs = 1;
#endif
    int cap = 4 * (procs > 0 ? procs : 1);
    if (cap > CLI_MAX_THREADS) cap = CLI_MAX_THREADS;
    if (requested > cap) {
        fprintf(stderr, "fogrt: -t %d: using %d threads (at most 4 per processor, %d processors, and at most %d)\n",
                requested, cap, procs, CLI_MAX_THREADS);
        return cap;
    }
    return requested;
}

/* The camera in float range. Returns NULL, or the true reason it cannot be used. */
static const char *camera_problem(const fogrt_camera_desc *c, char *buf, size_t n)
{
    float dx, dy, dz, len2, ulen2;
    const float m = CLI_MAX_CAMERA_COORD;
    if (!(isfinite(c->position.x) && isfinite(c->position.y) && isfinite(c->position.z) &&
          isfinite(c->look_at.x) && isfinite(c->look_at.y) && isfinite(c->look_at.z) &&
          isfinite(c->up.x) && isfinite(c->up.y) && isfinite(c->up.z)))
        return "camera position, target or up is not finite";
    dx = c->look_at.x - c->position.x;
    dy = c->look_at.y - c->position.y;
    dz = c->look_at.z - c->position.z;
    if (!(isfinite(dx) && isfinite(dy) && isfinite(dz))) {
        snprintf(buf, n, "the eye-to-target difference overflows float (eye %g,%g,%g, target %g,%g,%g)",
                 (double)c->position.x, (double)c->position.y, (double)c->position.z,
                 (double)c->look_at.x, (double)c->look_at.y, (double)c->look_at.z);
        return buf;
    }
    len2 = dx * dx + dy * dy + dz * dz;
    if (!isfinite(len2)) {
        snprintf(buf, n, "the eye-to-target distance %g overflows float when squared", sqrt((double)dx * (double)dx + (double)dy * (double)dy + (double)dz * (double)dz));
        return buf;
    }
    if (len2 == 0.0f) return "the camera looks at its own position (eye equals target)";
    ulen2 = c->up.x * c->up.x + c->up.y * c->up.y + c->up.z * c->up.z;
    if (!isfinite(ulen2)) return "the up vector overflows float when squared";
    if (fabsf(c->position.x) > m || fabsf(c->position.y) > m || fabsf(c->position.z) > m ||
        fabsf(c->look_at.x) > m || fabsf(c->look_at.y) > m || fabsf(c->look_at.z) > m) {
        snprintf(buf, n, "camera position or target beyond %g scene units: float ray arithmetic would overflow", (double)m);
        return buf;
    }
    if (!(c->lens_radius <= m)) {
        snprintf(buf, n, "lens radius %g beyond %g scene units: float ray arithmetic would overflow", (double)c->lens_radius, (double)m);
        return buf;
    }
    if (!(c->focal_distance <= m)) {
        snprintf(buf, n, "focal distance %g beyond %g scene units: float ray arithmetic would overflow", (double)c->focal_distance, (double)m);
        return buf;
    }
    return NULL;
}

static double horizontal_fov(const fogrt_camera_desc *c, int W, int H)
{
    double t = tan(0.5 * (double)c->fov_deg * CLI_PI / 180.0), aspect = (double)W / (double)H;
    if (!c->fov_is_horizontal) t *= aspect;
    return 2.0 * atan(t) * 180.0 / CLI_PI;
}
static double vertical_fov(const fogrt_camera_desc *c, int W, int H)
{
    double t = tan(0.5 * (double)c->fov_deg * CLI_PI / 180.0), aspect = (double)W / (double)H;
    if (c->fov_is_horizontal) t /= aspect;
    return 2.0 * atan(t) * 180.0 / CLI_PI;
}
/* CS184 keeps its focal length in pixels, set by the 800x600 window: f = 300 / tan(v/2) at
   800x600, and at W x H tan(v'/2) = (H/2) / f. cam holds the 800x600 framing on entry. */
static void cs184_reframe(fogrt_camera_desc *cam, int H)
{
    double tan_y = tan(0.5 * vertical_fov(cam, 800, 600) * CLI_PI / 180.0);
    cam->fov_deg = (float)(2.0 * atan(tan_y * (double)H / 600.0) * 180.0 / CLI_PI);
    cam->fov_is_horizontal = false;
}

/* ------------------------------------------------------------------------------------------
   Output files: encoded in memory, then written to a temporary file in the same directory,
   fsync'ed, closed and renamed over the target; every step checked.
   ------------------------------------------------------------------------------------------ */
typedef struct membuf { unsigned char *data; size_t size, cap; bool failed; } membuf;

static void membuf_put(membuf *b, const void *p, size_t n)
{
    if (b->failed || n == 0) return;
    if (b->size + n > b->cap) {
        size_t cap = b->cap ? b->cap : 4096;
        unsigned char *q;
        while (cap < b->size + n) cap *= 2;
        q = (unsigned char *)realloc(b->data, cap);
        if (!q) { b->failed = true; return; }
        b->data = q; b->cap = cap;
    }
    memcpy(b->data + b->size, p, n);
    b->size += n;
}
static void membuf_stb(void *context, void *data, int size)
{
    if (size > 0) membuf_put((membuf *)context, data, (size_t)size);
}

/* PFM (linear, unscaled, little endian, bottom row first), PPM, PNG or JPG by extension. */
static bool encode_image(const char *path, int W, int H, const float *rgb, float exposure,
                         unsigned char *rgb8, membuf *out)
{
    char header[64];
    int y, n;
    if (ends_with(path, ".pfm")) {
        n = snprintf(header, sizeof header, "PF\n%d %d\n-1.0\n", W, H);
        membuf_put(out, header, (size_t)n);
        for (y = H - 1; y >= 0; --y) {
            const float *row = rgb + (size_t)y * (size_t)W * 3;
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
            size_t i;
            for (i = 0; i < (size_t)W * 3; ++i) {
                unsigned char b[4], t;
                memcpy(b, &row[i], 4);
                t = b[0]; b[0] = b[3]; b[3] = t; t = b[1]; b[1] = b[2]; b[2] = t;
                membuf_put(out, b, 4);
            }
#else
            membuf_put(out, row, sizeof(float) * 3 * (size_t)W);
#endif
        }
        return !out->failed;
    }
    if (rgb) fogrt_tonemap_rgb8(rgb, W, H, exposure, FOGRT_TONEMAP_SRGB, rgb8);
    if (ends_with(path, ".ppm")) {
        n = snprintf(header, sizeof header, "P6\n%d %d\n255\n", W, H);
        membuf_put(out, header, (size_t)n);
        membuf_put(out, rgb8, 3 * (size_t)W * (size_t)H);
        return !out->failed;
    }
    if (ends_with(path, ".jpg") || ends_with(path, ".jpeg"))
        return stbi_write_jpg_to_func(membuf_stb, out, W, H, 3, rgb8, 90) != 0 && !out->failed;
    return stbi_write_png_to_func(membuf_stb, out, W, H, 3, rgb8, W * 3) != 0 && !out->failed;
}

/* Where an output goes. A symlink is followed (its target is replaced, not the link); an
   existing character device (/dev/null, /dev/full) is written in place; a regular file or a
   new name is written through a temporary file next to it. */
typedef struct out_target {
    const char *flag, *name;       /* for messages: "-f", the path as given */
    char path[4096];               /* the file actually replaced */
    bool direct;
} out_target;

static void split_dir(const char *path, char *dir, size_t n, const char **base)
{
    const char *slash = strrchr(path, '/');
    if (!slash) { snprintf(dir, n, "."); *base = path; }
    else if (slash == path) { snprintf(dir, n, "/"); *base = slash + 1; }
    else { snprintf(dir, n, "%.*s", (int)(slash - path), path); *base = slash + 1; }
}
static int make_temp(const out_target *t)
{
    char dir[4096];
    const char *base;
    int fd;
    split_dir(t->path, dir, sizeof dir, &base);
    if ((size_t)snprintf(cli_temp_path, sizeof cli_temp_path, "%s/.%s.tmp-XXXXXX", dir, base) >= sizeof cli_temp_path) {
        errno = ENAMETOOLONG;
        return -1;
    }
    fd = mkstemp(cli_temp_path);
    if (fd >= 0) cli_temp_live = 1;
    return fd;
}
static void drop_temp(void)
{
    if (cli_temp_live) { unlink(cli_temp_path); cli_temp_live = 0; }
}
static bool out_fail(const out_target *t, const char *what)
{
    fprintf(stderr, "fogrt: %s %s: %s: %s\n", t->flag, t->name, what, strerror(errno));
    return false;
}
/* Checks before rendering that the output can be written (so a long render never ends in a
   lost image): the same steps as the real write, on an empty temporary file. */
static bool prepare_output(out_target *t, const char *flag, const char *name)
{
    struct stat st;
    int fd;
    t->flag = flag; t->name = name; t->direct = false;
    if (strlen(name) >= sizeof t->path) { errno = ENAMETOOLONG; return out_fail(t, "cannot write"); }
    snprintf(t->path, sizeof t->path, "%s", name);
    if (stat(name, &st) == 0) {
        if (S_ISREG(st.st_mode)) {
            char *real = realpath(name, NULL);
            if (real) { snprintf(t->path, sizeof t->path, "%s", real); free(real); }
        } else if (S_ISCHR(st.st_mode)) {
            t->direct = true;
            fd = open(name, O_WRONLY | O_NOCTTY);
            if (fd < 0) return out_fail(t, "cannot write");
            close(fd);
            return true;
        } else {
            fprintf(stderr, "fogrt: %s %s: is %s, not a regular file\n", flag, name, file_kind(st.st_mode));
            return false;
        }
    } else if (errno != ENOENT) {
        return out_fail(t, "cannot write");
    }
    fd = make_temp(t);
    if (fd < 0) { cli_temp_live = 0; return out_fail(t, "cannot write"); }
    close(fd);
    drop_temp();
    return true;
}
static bool write_all(int fd, const unsigned char *p, size_t n)
{
    while (n > 0) {
        ssize_t k = write(fd, p, n > ((size_t)1 << 30) ? ((size_t)1 << 30) : n);
        if (k < 0 && errno == EINTR) continue;
        if (k <= 0) { if (k == 0) errno = EIO; return false; }
        p += k; n -= (size_t)k;
    }
    return true;
}
static bool write_output(out_target *t, const membuf *b)
{
    struct stat st;
    mode_t mode, mask;
    int fd, e;
    if (t->direct) {
        fd = open(t->path, O_WRONLY | O_NOCTTY | O_TRUNC);
        if (fd < 0) return out_fail(t, "cannot write");
        if (!write_all(fd, b->data, b->size)) { e = errno; close(fd); errno = e; return out_fail(t, "write failed"); }
        if (close(fd) != 0) return out_fail(t, "write failed");
        return true;
    }
    mask = umask(0); umask(mask);
    mode = stat(t->path, &st) == 0 ? (st.st_mode & 07777) : (mode_t)(0666 & ~mask);
    fd = make_temp(t);
    if (fd < 0) { cli_temp_live = 0; return out_fail(t, "cannot write"); }
    if (fchmod(fd, mode) != 0 || !write_all(fd, b->data, b->size) ||
        (fsync(fd) != 0 && errno != EINVAL && errno != EROFS)) {
        e = errno; close(fd); drop_temp(); errno = e;
        return out_fail(t, "write failed");
    }
    if (close(fd) != 0) { e = errno; drop_temp(); errno = e; return out_fail(t, "write failed"); }
    if (rename(cli_temp_path, t->path) != 0) { e = errno; drop_temp(); errno = e; return out_fail(t, "could not replace the file"); }
    cli_temp_live = 0;
    return true;
}

/* <name>_rate.png beside the output: CS184's sampling-rate image, samples / max per pixel,
   blue (0) to green (0.5) to red (1), as CS184's pathtracer colours it. */
static void rate_path(const char *output, char *buf, size_t n)
{
    const char *dot = strrchr(output, '.'), *slash = strrchr(output, '/');
    size_t stem = (dot && (!slash || dot > slash)) ? (size_t)(dot - output) : strlen(output);
    snprintf(buf, n, "%.*s_rate.png", (int)stem, output);
}
static void rate_image(const fogrt_image *img, int max_spp, unsigned char *rgb8)
{
    size_t i, n = (size_t)img->width * (size_t)img->height;
    for (i = 0; i < n; ++i) {
        double r = (double)img->count[i] / (double)max_spp, c[3];
        if (r > 1.0) r = 1.0;
        if (r <= 0.5) { double w = (0.5 - r) / 0.5; c[0] = 0.0; c[1] = 1.0 - w; c[2] = w; }
        else { double w = (1.0 - r) / 0.5; c[0] = 1.0 - w; c[1] = w; c[2] = 0.0; }
        rgb8[3 * i + 0] = (unsigned char)(c[0] * 255.0 + 0.5);
        rgb8[3 * i + 1] = (unsigned char)(c[1] * 255.0 + 0.5);
        rgb8[3 * i + 2] = (unsigned char)(c[2] * 255.0 + 0.5);
    }
}

/* ------------------------------------------------------------------------------------------
   The reference image (--reference REF.pfm) and the measured error
   ------------------------------------------------------------------------------------------ */
/* Reads an RGB PFM into rows from the top for flag (its messages name the flag and the
   file); returns NULL after printing one line. want_w, want_h > 0: the size it must have;
   otherwise the size goes to out_w and out_h. */
static float *read_pfm_for(const char *flag, const char *path, int want_w, int want_h, int *out_w, int *out_h)
{
    FILE *f;
    char tok[3][32];
    int c, t, w = 0, h = 0;
    double scale;
    size_t n, i;
    float *px = NULL, *tmp;
    char *end;
    const char *err = NULL;
    f = fopen(path, "rb");
    if (!f) { fprintf(stderr, "fogrt: %s %s: cannot open: %s\n", flag, path, strerror(errno)); return NULL; }
    if (fgetc(f) != 'P' || fgetc(f) != 'F' || !isspace(c = fgetc(f))) { err = "not an RGB PFM (it must start with \"PF\")"; goto fail; }
    for (t = 0; t < 3; ++t) {             /* width, height, scale: whitespace-separated */
        size_t k = 0;
        while ((c = fgetc(f)) != EOF && isspace(c)) {}
        while (c != EOF && !isspace(c) && k + 1 < sizeof tok[t]) { tok[t][k++] = (char)c; c = fgetc(f); }
        tok[t][k] = 0;
        if (c == EOF || k == 0) { err = "the header ends early (PF, width, height, scale)"; goto fail; }
    }
    w = (int)strtol(tok[0], &end, 10);
    if (*end || w <= 0 || w > CLI_MAX_SIDE) { err = "bad width in the header"; goto fail; }
    h = (int)strtol(tok[1], &end, 10);
    if (*end || h <= 0 || h > CLI_MAX_SIDE) { err = "bad height in the header"; goto fail; }
    scale = strtod(tok[2], &end);
    if (*end || !(scale != 0.0) || !isfinite(scale)) { err = "bad scale in the header (a non-zero number; negative = little endian)"; goto fail; }
    if (want_w > 0 && (w != want_w || h != want_h)) {
        fprintf(stderr, "fogrt: --reference %s: is %dx%d, the render is %dx%d (-r %d %d)\n", path, w, h, want_w, want_h, want_w, want_h);
        fclose(f);
        return NULL;
    }
    n = (size_t)w * (size_t)h * 3;
    px = (float *)malloc(sizeof(float) * n);
    tmp = (float *)malloc(sizeof(float) * 3 * (size_t)w);
    if (!px || !tmp) { free(tmp); err = "out of memory"; goto fail; }
    for (t = h - 1; t >= 0; --t) {        /* PFM rows are stored bottom first */
        if (fread(tmp, sizeof(float) * 3, (size_t)w, f) != (size_t)w) { free(tmp); err = "the file is too short for its width x height"; goto fail; }
        for (i = 0; i < 3 * (size_t)w; ++i) {
            unsigned char b[4], s;
            bool little = scale < 0.0;
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
            little = !little;
#endif
            if (!little) {
                memcpy(b, &tmp[i], 4);
                s = b[0]; b[0] = b[3]; b[3] = s; s = b[1]; b[1] = b[2]; b[2] = s;
                memcpy(&tmp[i], b, 4);
            }
            if (!isfinite(tmp[i])) { free(tmp); err = "holds a non-finite value"; goto fail; }
        }
        memcpy(px + (size_t)t * 3 * (size_t)w, tmp, sizeof(float) * 3 * (size_t)w);
    }
    free(tmp);
    fclose(f);
    if (out_w) *out_w = w;
    if (out_h) *out_h = h;
    return px;
fail:
    fprintf(stderr, "fogrt: %s %s: %s\n", flag, path, err);
    free(px);
    fclose(f);
    return NULL;
}

static float *read_reference(const char *path, int want_w, int want_h)
{
    return read_pfm_for("--reference", path, want_w, want_h, NULL, NULL);
}

/* -e: an environment map, .pfm (read here), .hdr (stb_image) or .exr (tinyexr, when the CLI
   was built with libtinyexr-dev), as linear RGB; NULL with one message on failure. */
static float *read_env_map(const char *path, int *w, int *h)
{
    if (ends_with(path, ".pfm")) return read_pfm_for("-e", path, 0, 0, w, h);
    if (ends_with(path, ".hdr")) {
        int n = 0;
        float *px = stbi_loadf(path, w, h, &n, 3);
        if (!px) fprintf(stderr, "fogrt: -e %s: cannot read the HDR image: %s\n", path, stbi_failure_reason());
        return px;
    }
    if (ends_with(path, ".exr")) {
#ifdef FOGRT_CLI_EXR
        float *rgba = NULL, *px;
        const char *err = NULL;
        size_t i, n;
        if (LoadEXR(&rgba, w, h, path, &err) != TINYEXR_SUCCESS) {
            fprintf(stderr, "fogrt: -e %s: cannot read the OpenEXR image: %s\n", path, err ? err : "unknown error");
            if (err) FreeEXRErrorMessage(err);
            return NULL;
        }
        n = (size_t)*w * (size_t)*h;
        px = (float *)malloc(sizeof(float) * 3 * n);
        if (px) for (i = 0; i < n; ++i) { px[3 * i] = rgba[4 * i]; px[3 * i + 1] = rgba[4 * i + 1]; px[3 * i + 2] = rgba[4 * i + 2]; }
        else fprintf(stderr, "fogrt: -e %s: out of memory\n", path);
        free(rgba);
        return px;
#else
        fprintf(stderr, "fogrt: -e %s: this fogrt was built without OpenEXR support (install libtinyexr-dev and rebuild), or give a .hdr or .pfm map\n", path);
        return NULL;
#endif
    }
    fprintf(stderr, "fogrt: -e %s: unknown environment map type (expected .exr, .hdr or .pfm)\n", path);
    return NULL;
}

typedef struct measured { double rel_mse, rmse, ratio[3]; } measured;   /* NAN: undefined */

static double lum3(const float *c) { return 0.2126 * (double)c[0] + 0.7152 * (double)c[1] + 0.0722 * (double)c[2]; }
static void measure(const float *rgb, const float *ref, size_t pixels, measured *m)
{
    double num = 0, den = 0, sq = 0, sum[3] = {0, 0, 0}, rsum[3] = {0, 0, 0};
    size_t i;
    int k;
    for (i = 0; i < pixels; ++i) {
        double d = lum3(rgb + 3 * i) - lum3(ref + 3 * i), yr = lum3(ref + 3 * i);
        num += d * d;
        den += yr * yr;
        for (k = 0; k < 3; ++k) {
            double e = (double)rgb[3 * i + k] - (double)ref[3 * i + k];
            sq += e * e;
            sum[k] += (double)rgb[3 * i + k];
            rsum[k] += (double)ref[3 * i + k];
        }
    }
    m->rel_mse = den > 0 ? num / den : nan("");
    m->rmse = pixels ? sqrt(sq / (3.0 * (double)pixels)) : nan("");
    for (k = 0; k < 3; ++k) m->ratio[k] = rsum[k] > 0 ? sum[k] / rsum[k] : nan("");
}

/* ------------------------------------------------------------------------------------------
   Time, the progress line and the --log rows
   ------------------------------------------------------------------------------------------ */
static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct render_state {
    const cli_options *o;
    int threads;
    double t0, last_print;
    uint64_t spp_target;          /* the sample goal or ceiling */
    double seconds_limit;         /* --time, or the ceiling of --target-error; 0 none */
    uint64_t spp_done;            /* completed batches */
    int spp_batch;                /* in the current fogrt_render call */
    double est_error;             /* the estimate; < 0 unknown, NAN n/a */
    double ref_error;             /* measured against --reference; < 0 unknown */
    bool black;                   /* nothing can light the image: error n/a */
    bool show_target;             /* spp_target is the -s goal (not a ceiling) */
    double pixels;
    bool tty, printed;
    FILE *log; const char *log_path; bool log_failed;
    const float *ref; float *rgb; /* reference and scratch (resolved image) */
    float *rates;                 /* --pixel-rates: width x height, made once after the pilot */
    measured m;
    uint64_t rays;
} render_state;

static void format_seconds(double s, char *buf, size_t n)
{
    if (!(s >= 0) || s > 1e7) snprintf(buf, n, "?");
    else if (s < 60) snprintf(buf, n, "%.1fs", s);
    else if (s < 3600) snprintf(buf, n, "%dm%02ds", (int)(s / 60), (int)fmod(s, 60));
    else snprintf(buf, n, "%dh%02dm", (int)(s / 3600), (int)fmod(s / 60, 60));
}
/* "1.23%", or "n/a" for a black image or a non-finite estimate, "?" before it exists. */
static void format_error(const render_state *p, double e, char *buf, size_t n)
{
    if (p->black || e != e || isinf(e)) snprintf(buf, n, "n/a");
    else if (e < 0) snprintf(buf, n, "?");
    else snprintf(buf, n, "%.2f%%", 100.0 * e);
}

/* Fraction done: the furthest of the active stopping rules (samples, time, error). */
static double progress_fraction(const render_state *p, double spp_now, double elapsed)
{
    double f = 0.0;
    if (p->spp_target) f = spp_now / (double)p->spp_target;
    if (p->seconds_limit > 0) f = fmax(f, elapsed / p->seconds_limit);
    if (p->o->target_error > 0 && p->est_error > 0 && isfinite(p->est_error) && spp_now > 0) {
        /* the error falls as 1/sqrt(samples): samples needed = now (err / target)^2 */
        double q = p->est_error / p->o->target_error, need = spp_now * q * q;
        f = fmax(f, spp_now / fmax(need, spp_now));
    }
    return f > 1.0 ? 1.0 : f;
}

/* On a terminal one line rewritten with \r; in a log a new line every few seconds. */
static void print_progress(render_state *p, double spp_now, bool force)
{
    double t = now_seconds(), elapsed = t - p->t0, f, remaining, rate;
    char e[32], r[32], err[32], ref[48], spp[64];
    if (p->o->quiet) return;
    if (!force && t - p->last_print < (p->tty ? 0.25 : CLI_LOG_PROGRESS_SECONDS)) return;
    p->last_print = t;
    f = progress_fraction(p, spp_now, elapsed);
    remaining = f > 0 ? elapsed * (1.0 - f) / f : -1.0;
    rate = elapsed > 0 ? spp_now * p->pixels / elapsed : 0.0;
    format_seconds(elapsed, e, sizeof e);
    format_seconds(remaining, r, sizeof r);
    format_error(p, p->est_error, err, sizeof err);
    ref[0] = 0;
    if (p->ref && p->ref_error >= 0) {
        char m[32];
        format_error(p, p->ref_error, m, sizeof m);
        snprintf(ref, sizeof ref, " (measured %s)", m);
    }
    if (p->o->adaptive) snprintf(spp, sizeof spp, "rows %.0f/%d", spp_now / (double)p->o->spp * p->o->height, p->o->height);
    else if (p->show_target) snprintf(spp, sizeof spp, "spp %llu/%llu", (unsigned long long)p->spp_done, (unsigned long long)p->spp_target);
    else snprintf(spp, sizeof spp, "spp %llu", (unsigned long long)p->spp_done);
    fprintf(stderr, "%sfogrt: %5.1f%%  %s  elapsed %s  remaining %s  %.3g M samples/s  rel. error %s%s%s",
            p->tty ? "\r" : "", 100.0 * f, spp, e, r, rate * 1e-6, err, ref, p->tty ? "   " : "\n");
    fflush(stderr);
    p->printed = p->tty;
}

static bool on_progress(const fogrt_progress *pr, void *user)
{
    render_state *p = (render_state *)user;
    double spp_now = (double)p->spp_done + (double)p->spp_batch * pr->rows_done / (pr->rows_total > 0 ? pr->rows_total : 1);
    if (cli_interrupted) return false;    /* the rows already started finish; the rest wait */
    print_progress(p, spp_now, false);
    return true;
}

static const char *log_header =
    "seconds,spp,samples_per_second,est_rel_mse,est_rel_error,ref_rel_mse,ref_rmse,ref_ratio_r,ref_ratio_g,ref_ratio_b,event\n";

static void log_number(FILE *f, double v, bool last)
{
    if (v == v && !isinf(v)) fprintf(f, "%.6g", v);
    else if (v == v) fprintf(f, "inf");
    else fprintf(f, "nan");
    if (!last) fputc(',', f);
}
/* The error now: the estimate, and with --reference the measured one; one --log row. */
static void take_measurement(render_state *p, const fogrt_image *img, const char *event)
{
    fogrt_error_estimate ee;
    double seconds = now_seconds() - p->t0, spp;
    fogrt_image_error(img, &ee);
    spp = (double)ee.samples / p->pixels;
    p->est_error = ee.samples >= 2 * (uint64_t)p->pixels ? ee.relative_error : -1.0;
    if (ee.samples > 0 && ee.mean_luminance == 0.0) p->est_error = nan("");   /* black: n/a */
    if (p->ref) {
        fogrt_image_resolve(img, p->rgb);
        measure(p->rgb, p->ref, (size_t)p->pixels, &p->m);
        p->ref_error = p->m.rel_mse == p->m.rel_mse ? sqrt(p->m.rel_mse) : nan("");
    }
    if (p->log && !p->log_failed) {
        double est = p->est_error >= 0 ? p->est_error : nan("");
        FILE *f = p->log;
        if (p->black) est = nan("");
        log_number(f, seconds, false);
        log_number(f, spp, false);
        log_number(f, seconds > 0 ? spp * p->pixels / seconds : nan(""), false);
        log_number(f, est * est, false);
        log_number(f, est, false);
        if (p->ref) {
            log_number(f, p->m.rel_mse, false); log_number(f, p->m.rmse, false);
            log_number(f, p->m.ratio[0], false); log_number(f, p->m.ratio[1], false); log_number(f, p->m.ratio[2], false);
        } else {
            fputs(",,,,,", f);
        }
        fprintf(f, "%s\n", event);
        if (fflush(f) != 0 || ferror(f)) {
            fprintf(stderr, "fogrt: --log %s: write failed: %s\n", p->log_path, strerror(errno));
            p->log_failed = true;
        }
    }
}

/* ------------------------------------------------------------------------------------------
   Rendering: progressive batches through fogrt_render, or CS184's per-pixel adaptive loop
   ------------------------------------------------------------------------------------------ */
/* Batches are sized from the measured speed to take about CLI_BATCH_SECONDS (1, 2, 4, ...
   samples per pixel at first), so the estimate updates and Ctrl-C is answered quickly. An
   interrupt cancels the batch through the progress callback: fogrt_render then skips the
   rows not yet started and every finished row keeps its samples. */
static fogrt_result render_progressive(const fogrt_scene *scene, fogrt_render_desc *rd, fogrt_image *img,
                                       render_state *p, const char **stopped_by)
{
    uint64_t done = 0;
    double rate = 0.0;                 /* samples per pixel per second */
    fogrt_result r = FOGRT_RESULT_OK;
    rd->progress = on_progress;
    rd->user_data = p;
    *stopped_by = NULL;
    for (;;) {
        fogrt_render_stats st;
        uint64_t b;
        double elapsed = now_seconds() - p->t0;
        if (cli_interrupted) break;
        if (p->spp_target && done >= p->spp_target) { *stopped_by = "samples"; break; }
        if (p->seconds_limit > 0 && elapsed >= p->seconds_limit && done > 0) { *stopped_by = "time"; break; }
        b = rate > 0 ? (uint64_t)(rate * CLI_BATCH_SECONDS) : 1;
        if (b > done) b = done > 0 ? done : 1;      /* doubling at first: early error points */
        if (p->rates && !rd->sample_rate && b > CLI_RATES_PILOT - done) b = CLI_RATES_PILOT - done;
        if (b > ((uint64_t)1 << 20)) b = (uint64_t)1 << 20;
        if (b < 1) b = 1;
        if (p->spp_target && b > p->spp_target - done) b = p->spp_target - done;
        if (p->seconds_limit > 0 && rate > 0 && (double)b > (p->seconds_limit - elapsed) * rate)
            b = (uint64_t)fmax(1.0, floor((p->seconds_limit - elapsed) * rate));
        p->spp_done = done;
        p->spp_batch = (int)b;
        r = fogrt_render(scene, rd, img, (int)b, &st);
        p->rays += st.rays;
        if (r == FOGRT_RESULT_CANCELLED) { r = FOGRT_RESULT_OK; break; }
        if (r) return r;
        done += b;
        p->spp_done = done; p->spp_batch = 0;
        /* --pixel-rates: once, after the pilot's spp taken alike; kept to the end (unbiased) */
        if (p->rates && !rd->sample_rate && done >= CLI_RATES_PILOT) {
            if (fogrt_image_sample_rates(img, p->rates) == FOGRT_RESULT_OK) rd->sample_rate = p->rates;
            else p->rates = NULL;    /* out of memory: every pixel alike, as without the flag */
        }
        rate = (double)done / fmax(now_seconds() - p->t0, 1e-6);
        take_measurement(p, img, "batch");
        print_progress(p, (double)done, false);
        if (p->o->target_error > 0 && p->est_error >= 0 && p->est_error <= p->o->target_error) { *stopped_by = "error"; break; }
    }
    if (cli_interrupted) take_measurement(p, img, "interrupted");
    return r;
}

/* CS184 -a: per pixel, after every `batch` samples, stop once 1.96 sigma / sqrt(n) <= tol mu
   (luminance); -s is the cap. Each pixel has its own random stream (seed, pixel). */
static void render_adaptive(const fogrt_scene *scene, const fogrt_render_desc *rd, fogrt_image *img,
                            render_state *p)
{
    const cli_options *o = p->o;
    int W = img->width, H = img->height, y, rows_done = 0;
    uint64_t rays = 0, rejected = 0;
#ifdef _OPENMP
    int nthreads = p->threads > 0 ? p->threads : omp_get_max_threads();
#pragma omp parallel for schedule(dynamic, 1) num_threads(nthreads) reduction(+ : rays, rejected)
#endif
    for (y = 0; y < H; ++y) {
        int x;
        if (cli_interrupted) continue;       /* rows not started stay empty */
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
                    img->sum[3 * pix] += (double)L.x; img->sum[3 * pix + 1] += (double)L.y; img->sum[3 * pix + 2] += (double)L.z;
                    img->sum_sq[pix] += (double)lum * (double)lum;
                    /* independent samples: dealt round-robin to the image's streams, so
                       fogrt_image_error's between-stream estimate applies as to fogrt_render's */
                    img->stream_sum[FOGRT_IMAGE_STREAMS * pix + n % FOGRT_IMAGE_STREAMS] += (double)lum;
                    img->stream_count[FOGRT_IMAGE_STREAMS * pix + n % FOGRT_IMAGE_STREAMS]++;
                    s1 += (double)lum; s2 += (double)lum * (double)lum;
                    n++;
                }
                if (n >= 2) {
                    double mu = s1 / n, var = fmax(0.0, (s2 - s1 * s1 / n) / (n - 1));
                    if (1.96 * sqrt(var / n) <= (double)o->tolerance * mu) break;
                }
            }
            img->count[pix] = n;
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
    p->rays += rays;
    take_measurement(p, img, cli_interrupted ? "interrupted" : "final");
}

/* ------------------------------------------------------------------------------------------
   main
   ------------------------------------------------------------------------------------------ */
static void print_camera(const fogrt_camera_desc *c, int W, int H)
{
    printf("camera: position %.9g,%.9g,%.9g  look_at %.9g,%.9g,%.9g  up %.9g,%.9g,%.9g  fov %.4f x %.4f deg (horizontal x vertical) at %dx%d  lens_radius %g  focal_distance %g\n",
           (double)c->position.x, (double)c->position.y, (double)c->position.z,
           (double)c->look_at.x, (double)c->look_at.y, (double)c->look_at.z,
           (double)c->up.x, (double)c->up.y, (double)c->up.z,
           horizontal_fov(c, W, H), vertical_fov(c, W, H), W, H, (double)c->lens_radius, (double)c->focal_distance);
}

int main(int argc, char **argv)
{
    cli_options o;
    cli_log logbuf;
    fogrt_scene_desc sd;
    fogrt_scene *scene = NULL;
    fogrt_scene_info info;
    fogrt_load_options lo;
    fogrt_load_report rep;
    fogrt_medium_desc md;
    fogrt_camera_desc cam;
    fogrt_build_desc bd;
    fogrt_render_desc rd;
    fogrt_image img;
    fogrt_error_estimate ee;
    render_state ps;
    out_target out, rate_out;
    membuf enc;
    char rate_name[4096], where[4200], err_a[64], err_b[64], reason[256], target[32];
    const char *why, *stopped_by = NULL, *cam_where;
    float *rgb = NULL, *ref = NULL, *rates = NULL;
    unsigned char *rgb8 = NULL;
    bool is_dae = false, warned_black = false;
    fogrt_result r;
    double t0, t_load, elapsed, spp_mean;
    int status = 0, threads, frame_w, frame_h;

    memset(&logbuf, 0, sizeof logbuf);
    memset(&ps, 0, sizeof ps);
    memset(&enc, 0, sizeof enc);
    memset(&img, 0, sizeof img);
    status = parse_args(argc, argv, &o);
    if (status == -1) return 0;
    if (status) return status;
    cli_tty = isatty(2) != 0;
    install_signals();
    threads = cap_threads(o.threads);

    /* Inputs must be regular files (a FIFO would block the loader); outputs must be writable */
    if (o.scene && (status = check_input_file("", o.scene)) != 0) return status;
    if (o.camera_file && (status = check_input_file("-c ", o.camera_file)) != 0) return status;
    if (o.reference && (status = check_input_file("--reference ", o.reference)) != 0) return status;
    if (o.env_map && (status = check_input_file("-e ", o.env_map)) != 0) return status;
    if (!o.print_camera && !o.trace) {
        if (!prepare_output(&out, "-f", o.output)) return 1;
        if (o.adaptive) {
            rate_path(o.output, rate_name, sizeof rate_name);
            if (!prepare_output(&rate_out, "-f", rate_name)) return 1;
        }
        if (o.reference && !(ref = read_reference(o.reference, o.width, o.height))) return 2;
        if (!o.output_set && !o.quiet)
            fprintf(stderr, "fogrt: no -f given: writing %s (CS184 would open its viewer here; for fogrt's live preview run `make preview`, then `build/preview [scene]`)\n", o.output);
    }

    /* The scene */
    t0 = now_seconds();
    memset(&sd, 0, sizeof sd);
    sd.logger.func = log_core;
    sd.logger.user_data = &logbuf;
    if (fogrt_scene_create(&sd, &scene) != FOGRT_RESULT_OK) { fprintf(stderr, "fogrt: out of memory\n"); free(ref); return 1; }
    memset(&lo, 0, sizeof lo);
    frame_w = o.cs184_framing ? 800 : o.width;     /* CS184 framing: start from its 800x600 window */
    frame_h = o.cs184_framing ? 600 : o.height;
    lo.image_width = frame_w; lo.image_height = frame_h;
    lo.logger.func = log_load;
    if (!o.scene) {
        r = fogrt_scene_add_default(scene);
        if (r) { fail_line(&logbuf, "default scene", r); status = 1; goto done; }
    } else {
        is_dae = ends_with(o.scene, ".dae");
        if (!is_dae && !ends_with(o.scene, ".obj") && !ends_with(o.scene, ".ply")) {
            fprintf(stderr, "fogrt: %s: unknown scene type (expected .dae, .obj or .ply)\n", o.scene);
            status = 2; goto done;
        }
        if (!is_dae) {               /* a mesh: into the default fog-filled Cornell box */
            r = fogrt_scene_add_default(scene);
            if (r) { fail_line(&logbuf, "default scene", r); status = 1; goto done; }
        }
        r = fogrt_load_file(scene, o.scene, &lo, &rep);
        if (r) { fail_load(&logbuf, "", &rep, r); status = r == FOGRT_RESULT_OUT_OF_MEMORY ? 1 : 2; goto done; }
    }

    /* The fog: the scene's own, changed by the flags */
    fogrt_scene_get_medium(scene, &md);
    if (is_dae && md.sigma_t == 0.0f) {          /* .dae files carry no fog: fogrt's defaults */
        md.albedo.x = md.albedo.y = md.albedo.z = 0.9f;
        md.g = 0.0f;
    }
    if (o.density_set) md.sigma_t = o.density;
    else if (o.paper_g && md.sigma_t == 0.0f) md.sigma_t = 0.2f;   /* the paper's -g switches fog on */
    if (o.albedo_set) md.albedo = o.albedo;
    if (o.g_set) md.g = o.g;
    if (o.fog_bounds_set) { md.bounded = true; md.bounds_min = o.fog_lo; md.bounds_max = o.fog_hi; }
    r = fogrt_scene_set_medium(scene, &md);
    if (r) { fail_line(&logbuf, o.fog_bounds_set ? "--density/--albedo/--g/--fog-bounds" : "--density/--albedo/--g", r); status = 2; goto done; }
    if (o.env_map) {                             /* -e: the environment map light */
        int ew = 0, eh = 0;
        float *env;
        if (check_input_file("-e ", o.env_map) != 0) { status = 2; goto done; }
        env = read_env_map(o.env_map, &ew, &eh);
        if (!env) { status = 2; goto done; }
        r = fogrt_scene_set_environment_map(scene, ew, eh, env, 1.0f);
        free(env);
        if (r) { snprintf(where, sizeof where, "-e %s", o.env_map); fail_line(&logbuf, where, r); status = r == FOGRT_RESULT_OUT_OF_MEMORY ? 1 : 2; goto done; }
    }

    /* The camera: -c replaces the scene's; --cs184-framing re-frames it; the free-camera
       flags override parts of it; -b and -d set the lens */
    cam_where = o.scene ? o.scene : "default scene camera";
    if (o.camera_file) {
        r = fogrt_load_camera_file(o.camera_file, frame_w, frame_h, &cam, &rep);
        if (r) { fail_load(&logbuf, "-c ", &rep, r); status = 2; goto done; }
        cam_where = "-c";
    } else {
        fogrt_scene_get_camera(scene, &cam);
    }
    if (o.cs184_framing) cs184_reframe(&cam, o.height);
    if (o.cam_pos_set) cam.position = o.cam_pos;
    if (o.cam_look_set) cam.look_at = o.cam_look;
    if (o.cam_up_set) { cam.up = o.cam_up; cam_where = "--up"; }
    if (o.fov_set) { cam.fov_deg = o.fov; cam.fov_is_horizontal = true; cam_where = "--fov"; }
    if (o.cam_pos_set || o.cam_look_set) {       /* a free camera: pinhole unless -b */
        cam.lens_radius = 0.0f;
        cam.focal_distance = 0.0f;
        cam_where = o.cam_up_set ? "--camera-pos/--look-at/--up" : "--camera-pos/--look-at";
    }
    if (o.lens_set) { cam.lens_radius = o.lens_radius; cam_where = "-b"; }
    if (o.focal_set) { cam.focal_distance = o.focal; cam_where = "-d"; }
    if (cam.up.x == 0 && cam.up.y == 0 && cam.up.z == 0) cam.up.y = 1.0f;
    if ((why = camera_problem(&cam, reason, sizeof reason)) != NULL) {
        if (strcmp(cam_where, "-c") == 0) fprintf(stderr, "fogrt: -c %s: %s\n", o.camera_file, why);
        else fprintf(stderr, "fogrt: %s: %s\n", cam_where, why);
        status = 2; goto done;
    }
    r = fogrt_scene_set_camera(scene, &cam);
    if (r) {
        snprintf(where, sizeof where, "%s%s", strcmp(cam_where, "-c") == 0 ? "-c " : cam_where,
                 strcmp(cam_where, "-c") == 0 ? o.camera_file : "");
        fail_line(&logbuf, where, r);
        status = 2; goto done;
    }
    if (o.print_camera) { print_camera(&cam, o.width, o.height); status = 0; goto done; }

    /* Build */
    bd = fogrt_build_defaults();
    bd.heuristic = o.bvh;
    r = fogrt_scene_build(scene, &bd);
    if (r) { fail_line(&logbuf, o.scene ? o.scene : "default scene", r); status = r == FOGRT_RESULT_EMPTY_SCENE ? 2 : 1; goto done; }
    t_load = now_seconds() - t0;

    /* Can anything light the image? (A black render's error is n/a, never 0.00%.) */
    fogrt_scene_get_info(scene, &info);
    if (info.light_count == 0 && info.area_light_count == 0 && !info.has_environment) {
        fprintf(stderr, "fogrt: warning: %s has no light, no emitting surface and no environment: the image will be black\n", o.scene ? o.scene : "the scene");
        ps.black = warned_black = true;
    } else if (o.hemisphere && info.area_light_count == 0 && !info.has_environment) {
        fprintf(stderr, "fogrt: warning: -H finds light only by hitting emitters, and %s has only point and spot lights: the image will be black\n", o.scene ? o.scene : "the scene");
        ps.black = warned_black = true;
    }

    /* --trace: follow one pixel sample event by event, print it, and stop */
    if (o.trace) {
        fill_render_desc(&o, threads, &rd);
        status = cli_trace_path(scene, &rd, o.width, o.height, o.trace_x, o.trace_y, (uint32_t)o.trace_sample, stdout);
        goto done;
    }

    /* The image and the output buffers, all allocated before rendering */
    r = fogrt_image_alloc(&img, o.width, o.height, NULL);
    if (!r) {
        rgb = (float *)malloc(sizeof(float) * 3 * (size_t)o.width * (size_t)o.height);
        rgb8 = (unsigned char *)malloc(3 * (size_t)o.width * (size_t)o.height);
        if (o.pixel_rates && !o.adaptive) rates = (float *)malloc(sizeof(float) * (size_t)o.width * (size_t)o.height);
        if (!rgb || !rgb8 || (o.pixel_rates && !o.adaptive && !rates)) r = FOGRT_RESULT_OUT_OF_MEMORY;
    }
    if (r) {
        fprintf(stderr, "fogrt: -r %d %d: image too large to allocate (%s)\n", o.width, o.height, fogrt_result_string(r));
        status = 2; goto done;
    }
    if (o.log_path) {
        struct stat st;
        if (stat(o.log_path, &st) == 0 && !S_ISREG(st.st_mode)) {
            fprintf(stderr, "fogrt: --log %s: is %s, not a regular file\n", o.log_path, file_kind(st.st_mode));
            status = 2; goto done;
        }
        ps.log = fopen(o.log_path, "a");
        if (!ps.log) { fprintf(stderr, "fogrt: --log %s: cannot write: %s\n", o.log_path, strerror(errno)); status = 1; goto done; }
        ps.log_path = o.log_path;
        if (fseek(ps.log, 0, SEEK_END) != 0 || ftell(ps.log) == 0) fputs(log_header, ps.log);
    }

    /* Render */
    fill_render_desc(&o, threads, &rd);
    ps.o = &o;
    ps.threads = threads;
    ps.tty = isatty(2) != 0;
    ps.t0 = now_seconds();
    ps.last_print = ps.t0;
    ps.est_error = -1.0;
    ps.ref_error = -1.0;
    ps.pixels = (double)o.width * (double)o.height;
    ps.ref = ref;
    ps.rgb = rgb;
    ps.rates = rates;
    ps.show_target = o.spp_set || (o.time_budget <= 0 && o.target_error <= 0);
    if (ps.show_target) ps.spp_target = (uint64_t)o.spp;
    else if (o.target_error > 0) ps.spp_target = CLI_CEILING_SPP;
    else ps.spp_target = (uint64_t)1 << 24;        /* --time alone: the -s maximum */
    ps.seconds_limit = o.time_budget > 0 ? o.time_budget : (!o.spp_set && o.target_error > 0 ? CLI_CEILING_SECONDS : 0.0);
    r = FOGRT_RESULT_OK;
    if (o.adaptive) render_adaptive(scene, &rd, &img, &ps);
    else r = render_progressive(scene, &rd, &img, &ps, &stopped_by);
    elapsed = now_seconds() - ps.t0;
    if (ps.printed) fprintf(stderr, "\n");
    if (r) { fail_line(&logbuf, "render failed", r); status = 1; goto done; }

    fogrt_image_error(&img, &ee);
    spp_mean = (double)ee.samples / ps.pixels;
    if (ee.samples == 0) {
        fprintf(stderr, "fogrt: interrupted before any sample was taken: nothing written\n");
        status = 130; goto done;
    }
    if (!warned_black && ee.mean_luminance == 0.0) {
        fprintf(stderr, "fogrt: warning: every pixel is black: nothing the camera sees is lit\n");
        ps.black = true;
    }
    if (!o.adaptive && !cli_interrupted && o.target_error > 0 && stopped_by && strcmp(stopped_by, "error") != 0)
        fprintf(stderr, "fogrt: warning: --target-error %g not reached (estimate %s): stopped at the %s ceiling (%llu spp, %.0f s)\n",
                o.target_error, (format_error(&ps, ps.est_error, err_a, sizeof err_a), err_a), stopped_by,
                (unsigned long long)ps.spp_target, ps.seconds_limit);

    /* Write: the image, then CS184's sampling-rate image */
    fogrt_image_resolve(&img, rgb);
    if (!encode_image(o.output, o.width, o.height, rgb, exp2f(o.exposure_ev), rgb8, &enc)) {
        fprintf(stderr, "fogrt: -f %s: could not encode the image (out of memory)\n", o.output);
        status = 1; goto done;
    }
    if (!write_output(&out, &enc)) { status = 1; goto done; }
    if (o.adaptive) {
        enc.size = 0;
        rate_image(&img, o.spp, rgb8);
        if (!encode_image(rate_name, o.width, o.height, NULL, 1.0f, rgb8, &enc) || !write_output(&rate_out, &enc)) {
            if (enc.failed) fprintf(stderr, "fogrt: -f %s: could not encode the image (out of memory)\n", rate_name);
            status = 1; goto done;
        }
    }
    if (!o.quiet) {
        /* one sample per pixel has no variance estimate: n/a, not 0.00% */
        format_error(&ps, ps.black || ee.samples < 2 * (uint64_t)ps.pixels ? nan("") : ee.relative_error, err_a, sizeof err_a);
        err_b[0] = 0;
        if (ref) {
            char m[32];
            format_error(&ps, ps.ref_error, m, sizeof m);
            snprintf(err_b, sizeof err_b, " (measured %s)", m);
        }
        target[0] = 0;
        if (o.adaptive || ps.show_target) snprintf(target, sizeof target, "/%d", o.spp);
        fprintf(stderr, "fogrt: %swrote %s%s%s (%dx%d): %s%.6g%s spp in %.2f s (load %.2f s), %.3g M samples/s, "
                "rel. error %s%s, %llu non-finite samples dropped\n",
                cli_interrupted ? "interrupted: " : "", o.output, o.adaptive ? " and " : "", o.adaptive ? rate_name : "",
                o.width, o.height, o.adaptive ? "adaptive, mean " : "", spp_mean, target, elapsed, t_load,
                elapsed > 0 ? (double)ee.samples / elapsed * 1e-6 : 0.0, err_a, err_b,
                (unsigned long long)img.rejected);
    }
    if (ps.log_failed) status = 1;
    else if (cli_interrupted) status = 130;

done:
    if (ps.log && fclose(ps.log) != 0 && status == 0) {
        fprintf(stderr, "fogrt: --log %s: write failed: %s\n", o.log_path, strerror(errno));
        status = 1;
    }
    free(enc.data);
    free(rgb); free(rgb8); free(ref); free(rates);
    release_image(&img);
    fogrt_scene_destroy(scene);
    return status;
}
