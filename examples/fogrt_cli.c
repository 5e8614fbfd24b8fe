/* fogrt - the command-line renderer.

   Renders a CS184 .dae scene, an OBJ or PLY mesh (placed in the default fog-filled Cornell
   box) or, with no scene argument, the embedded default scene. CS184's flags keep CS184's
   meanings, so `fogrt -t 8 -s 64 -l 16 -m 6 -r 480 360 -f out.png scene.dae` works as the
   students type it; the fog and method flags are fogrt's own. `fogrt -h` lists them all with
   their syntax and defaults. The flags the preview shares (-r -t -l -m -H -g --g --density
   --albedo --phase --emission --medium --interface --integrator --fresnel --seed --exposure)
   are parsed by examples/cli_common.h, once for both programs. Long flags also take
   `--flag=value`.

   Exit status: 0 on success, 2 for bad input (an unknown flag, a value out of range, a
   missing, malformed or non-regular scene, camera, environment or reference file, an output
   that is an input or another output, an image above the memory limit), 1 when rendering
   or writing an output fails, 130 when interrupted (SIGINT, SIGTERM or SIGHUP: the image
   rendered so far is written first). Every error is one line on stderr naming the flag or
   the file:line.

   Outputs are written to a temporary file in the same directory and renamed over the old
   file, so a failed or interrupted write never leaves a truncated image where a good one
   was; every write, the fsync and the close are checked. No output may be (or resolve to,
   through a symlink or a hard link) an input of the run or another output.

   Build: make (the rule is in mk/cli.mk; PNG and JPG output use stb_image_write from
   libstb-dev, through its in-memory callback API; OpenEXR input and output use Debian's
   libtinyexr-dev when installed). */
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
#include <sys/time.h>

#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#define FOGRT_LOAD_IMPLEMENTATION
#include "fogrt_load.h"
#include "cli_common.h"

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
/* Image memory limit, checked before anything is allocated: the accumulation buffer (84
   bytes per pixel: double RGB sum, double sum of squares, 32-bit count, and per each of the
   4 sample streams a double luminance sum and a 32-bit count), the resolved float image
   (12), the 8-bit image (3), the encoded output (up to 13), the reference (12) and the
   --pixel-rates (4): 128. (Making the rates borrows 48 more for a moment; when that fails
   the render goes on with every pixel alike.) */
#define CLI_BYTES_PER_PIXEL 128.0
#define CLI_MAX_IMAGE_BYTES (2.0 * 1024.0 * 1024.0 * 1024.0)
/* An environment map may hold at most this many pixels (its float RGB copy here, the
   library's copy and its sampling tables take about 40 bytes per pixel: 2.5 GiB). */
#define CLI_MAX_ENV_PIXELS (64.0 * 1024.0 * 1024.0)
/* Ceilings of an open-ended render (--target-error without -s). */
#define CLI_CEILING_SPP 65536
#define CLI_RATES_PILOT 8         /* --pixel-rates: spp taken alike before the rates are made */
#define CLI_CEILING_SECONDS 3600.0
/* A progressive batch takes at most this many camera samples (divided by -l): a --log row
   and a new error estimate about every 0.2 to 0.4 s for the default scene on 2 cores. A
   count, not a time, so that the rows are the same on any machine and thread count. */
#define CLI_BATCH_SAMPLES 65536.0
/* Without a terminal, the progress line is printed every this many seconds. */
#define CLI_LOG_PROGRESS_SECONDS 5.0
/* Camera coordinates, lens radius and focal distance beyond this overflow float ray maths. */
#define CLI_MAX_CAMERA_COORD 1e18f
#define CLI_PI 3.14159265358979323846

typedef enum cli_fog_where { CLI_FOG_DEFAULT, CLI_FOG_ALL, CLI_FOG_SCENE, CLI_FOG_BOX } cli_fog_where;

typedef struct cli_options {
    cli_common c;                       /* the flags shared with the preview */
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
    cli_fog_where fog_where;            /* --fog-bounds */
    fogrt_vec3 fog_lo, fog_hi;          /* --fog-bounds X0,Y0,Z0,X1,Y1,Z1 */
    int trace_x, trace_y; uint32_t trace_sample; bool trace;  /* --trace */
    const char *scene;
} cli_options;

/* Every flag the parser takes, for "did you mean" (tests/test_cli.sh checks that -h and the
   README's table list the same ones). */
static const char *const cli_flag_names[] = {
    "-r", "-t", "-l", "-m", "-H", "-g", "--g", "--density", "--albedo", "--phase", "--emission", "--medium",
    "--interface", "--integrator", "--fresnel", "--seed", "--exposure", "-h", "--help",
    "-s", "-o", "-f", "-b", "-d", "-a", "-c", "-e",
    "--camera-pos", "--look-at", "--up", "--fov", "--cs184-framing", "--print-camera",
    "--fog-bounds", "--equiangular", "--lights", "--glow", "--footprint", "--expected-emission", "--mis",
    "--pixel-rates", "--bvh", "--time", "--target-error", "--quiet", "--log", "--reference", "--trace",
    NULL
};

static void usage(FILE *f)
{
    fprintf(f,
        "usage: fogrt [options] [scene.dae | mesh.obj | mesh.ply]\n"
        "Renders a CS184 COLLADA scene, an OBJ/PLY mesh placed in the default fog-filled Cornell\n"
        "box, or (no scene) the embedded default scene. Long flags also take --flag=value.\n"
        "\n"
        "Flags shared with the preview (the same meanings and limits in both):\n");
    cli_common_usage(f, 800, 600);
    fprintf(f,
        "  (-r: the view keeps CS184's 800x600 framing at every size, see --cs184-framing; the\n"
        "  image buffers, %.0f bytes per pixel, may use at most %.0f MiB)\n"
        "\n"
        "CS184 flags (same meanings as the CS184 pathtracer):\n"
        "  -s N         samples per pixel in [1, 16777216] (default 64); with --pixel-rates on\n"
        "               (the default) their mean over the image, more where the noise is\n"
        "  -o 0|1       CS184's isAccumBounces: 1 counts light of every bounce up to -m, 0 only\n"
        "               light that bounced exactly -m times (default 1)\n"
        "  -f FILE      output image: .png or .jpg (tone mapped: --exposure, then sRGB), .pfm\n"
        "               or .exr (linear 32-bit float, never scaled) or .ppm (default out.png,\n"
        "               with a note on stderr: CS184 opens its viewer here, fogrt's is\n"
        "               `make preview`)\n"
        "  -b R         thin-lens radius >= 0 (default 0 = pinhole)\n"
        "  -d D         focal distance > 0 (default: the distance to the camera's target)\n"
        "  -a B T       adaptive sampling: check every B samples, stop a pixel once its 95%%\n"
        "               confidence half-width is <= T x its mean (default off; -s is the cap);\n"
        "               also writes CS184's sampling-rate image <name>_rate.png (samples /\n"
        "               -s per pixel: blue 0, green 0.5, red 1)\n"
        "  -c FILE      camera settings file as CS184 writes it (default: the scene's camera)\n"
        "  -e FILE      environment map, latitude-longitude as CS184 maps its -e: .exr, .hdr\n"
        "               or .pfm (default none); with fog and --fog-bounds all the fog then\n"
        "               fills the box of the geometry, so the sky shows\n"
        "\n", CLI_BYTES_PER_PIXEL, CLI_MAX_IMAGE_BYTES / (1024.0 * 1024.0));
    fprintf(f,
        "Camera flags:\n"
        "  --camera-pos X,Y,Z  eye position (default: the scene's camera)\n"
        "  --look-at X,Y,Z     point looked at (default: the scene's camera)\n"
        "  --up X,Y,Z          up direction, any length but 0 (default: the scene's camera, else +y)\n"
        "  --fov DEG           full horizontal field of view in degrees, (0, 180) (default:\n"
        "                      the scene's); a free camera is a pinhole unless -b is given\n"
        "  --cs184-framing     CS184's view for -r W H: its focal length in pixels (875 for\n"
        "                      the shipped files) is kept, so the field of view changes with\n"
        "                      the size (default off: the 800x600 frame is kept whole)\n"
        "  --print-camera      print the camera that would be used and exit (default off)\n"
        "  Pixel filter: each sample lands on a stratified point of its pixel (4 independently\n"
        "  scrambled (0,2)-sequences per pixel; with -a independent uniform points) and is\n"
        "  weighted 1 (a box filter one pixel wide).\n"
        "\n");
    fprintf(f,
        "Fog and method flags:\n"
        "  --fog-bounds B   where the fog is: all (all space, the paper's; a .dae room is then\n"
        "                   in fog inside and out), scene (the box of the scene's geometry:\n"
        "                   the room, not the space around it), or X0,Y0,Z0,X1,Y1,Z1 (a box)\n"
        "                   (default all); the progress header and the summary say where it is\n"
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
        "  --bvh H          sah or volume (the paper's volume heuristic) (default sah)\n"
        "  --time SECONDS   stop after about this long, within a sample, even inside the first\n"
        "                   pass (default: no limit; without -s the sample count is then\n"
        "                   unlimited)\n"
        "  --target-error E stop when the estimated relative RMS error is <= E (default: none;\n"
        "                   E >= 1.2e-7, float's precision); without -s the render also stops\n"
        "                   at %d spp or after %.0f s, whichever comes first, even if the\n"
        "                   estimate never gets there\n"
        "  --quiet          no progress line and no summary (errors and warnings still shown)\n"
        "                   (default off)\n"
        "  --trace X,Y[,S]  print the events of sample S (default 0) of pixel (X, Y), column and\n"
        "                   row from the top, in Algorithm 1's order, and exit without an image\n"
        "                   (default off)\n"
        "\n", CLI_RATES_PILOT, CLI_CEILING_SPP, CLI_CEILING_SECONDS);
    fprintf(f,
        "Error against time (the progress line and the summary show the same numbers):\n"
        "  --log FILE.csv   append one row per progressive batch to a fogrt log (default none):\n"
        "                   a new file is created at the start with the header row; an existing\n"
        "                   file must be a fogrt log (that header its first line). A log that\n"
        "                   cannot be written is a warning: the image is still written, exit 1.\n"
        "                   Columns:\n"
        "                     seconds       render time so far\n"
        "                     spp           mean samples per pixel so far\n"
        "                     samples_per_second\n"
        "                     est_rel_mse   the render's own estimate (fogrt_image_error):\n"
        "                                   sum_p Var[mean_p] / sum_p mean_p^2 (luminance)\n"
        "                     est_rel_error sqrt(est_rel_mse) (both empty below 2 spp,\n"
        "                                   where there is no estimate yet, and when black)\n"
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
        "Ctrl-C, SIGTERM or SIGHUP stops within a sample (the render checks before each one),\n"
        "writes the image so far (and the --log row), prints the summary marked interrupted and\n"
        "exits 130; while the scene loads it quits at once; a second signal quits at once\n"
        "without writing.\n"
        "No output (-f, the -a rate image, --log) may be an input (scene, -c, -e, --reference)\n"
        "or another output, also through a symlink or a hard link: refused before rendering.\n"
        "Exit status: 0 ok, 2 bad input (flag, value, scene/camera/environment/reference file,\n"
        "an output that is an input), 1 render or write failure (the file is named), 130\n"
        "interrupted.\n");
}

static int bad_flag(const char *flag, const char *fmt, ...)
{
    va_list ap;
    char msg[512];
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return cli_bad_flag(flag, "%s", msg);
}

/* "X,Y" or "X,Y,SAMPLE": a pixel inside the image (checked later, with -r) and a sample
   index below 2^32. */
static bool parse_trace(const char *s, cli_options *o)
{
    char buf[128], *p[3], *comma;
    int n = 0, k;
    unsigned long long v[3] = {0, 0, 0};
    if (strlen(s) >= sizeof buf) return false;
    strcpy(buf, s);
    p[n++] = buf;
    while ((comma = strchr(p[n - 1], ',')) != NULL) {
        if (n == 3) return false;
        *comma = 0;
        p[n++] = comma + 1;
    }
    if (n < 2) return false;
    for (k = 0; k < n; ++k) {
        char *end;
        if (!(p[k][0] >= '0' && p[k][0] <= '9')) return false;
        errno = 0;
        v[k] = strtoull(p[k], &end, 10);
        if (errno || *end) return false;
    }
    if (v[0] >= CLI_MAX_SIDE || v[1] >= CLI_MAX_SIDE || v[2] > 0xFFFFFFFFull) return false;
    o->trace_x = (int)v[0]; o->trace_y = (int)v[1]; o->trace_sample = (uint32_t)v[2];
    return true;
}

/* Parses argv into o. Returns 0, or the exit status (2 bad input, -1 help printed). */
static int parse_args(int argc, char **argv, cli_options *o)
{
    cli_arg A;
    int i, k;
    memset(o, 0, sizeof *o);
    cli_common_defaults(&o->c, 800, 600);
    o->spp = 64; o->accumulate = 1;
    o->output = "out.png";
    o->equiangular = true; o->mis = true; o->glow = true; o->footprint = true; o->expected = true; o->pixel_rates = true;
#ifdef FOGRT_MINIMAL   /* built on Part I of fogrt.h alone: the paper's method is the default */
    o->equiangular = o->glow = o->footprint = o->expected = o->pixel_rates = false;
#endif
    o->bvh = FOGRT_BVH_SAH;
    A.argc = argc; A.argv = argv;
    for (i = 1; i < argc; i = A.i + 1) {
        const char *a, *v;
        cli_arg_at(&A, i);
        a = A.name;
#define NEED(n) do { if (!cli_has(&A, (n))) return bad_flag(a, "needs %d value%s", (n), (n) > 1 ? "s" : ""); } while (0)
        if (cli_is(&A, "-h") || cli_is(&A, "--help")) { usage(stdout); return -1; }
        if ((k = cli_common_flag(&A, &o->c)) >= 0) { if (k) return k; }
        else if (cli_is(&A, "-s")) { NEED(1); v = cli_next(&A); if (!cli_parse_int(v, 1, 1 << 24, &o->spp)) return bad_flag(a, "samples per pixel must be an integer in [1, 16777216], got '%s'", v); o->spp_set = true; }
        else if (cli_is(&A, "-o")) { NEED(1); v = cli_next(&A); if (!cli_parse_int(v, 0, 1, &o->accumulate)) return bad_flag(a, "must be 0 (only light that bounced exactly -m times) or 1 (all bounces), got '%s'", v); }
        else if (cli_is(&A, "-f")) {
            NEED(1);
            o->output = cli_next(&A);
            o->output_set = true;
            if (!cli_ends_with(o->output, ".png") && !cli_ends_with(o->output, ".jpg") && !cli_ends_with(o->output, ".jpeg") &&
                !cli_ends_with(o->output, ".pfm") && !cli_ends_with(o->output, ".ppm") && !cli_ends_with(o->output, ".exr"))
                return bad_flag(a, "output '%s' must end in .png, .jpg, .pfm, .exr or .ppm", o->output);
#ifndef FOGRT_CLI_EXR
            if (cli_ends_with(o->output, ".exr"))
                return bad_flag(a, "output '%s': this fogrt was built without OpenEXR support (install libtinyexr-dev and rebuild), or write a .pfm", o->output);
#endif
        }
        else if (cli_is(&A, "--camera-pos")) { NEED(1); v = cli_next(&A); if (!cli_parse_vec3(v, &o->cam_pos)) return bad_flag(a, "needs X,Y,Z (three numbers), got '%s'", v); o->cam_pos_set = true; }
        else if (cli_is(&A, "--look-at")) { NEED(1); v = cli_next(&A); if (!cli_parse_vec3(v, &o->cam_look)) return bad_flag(a, "needs X,Y,Z (three numbers), got '%s'", v); o->cam_look_set = true; }
        else if (cli_is(&A, "--up")) {
            NEED(1); v = cli_next(&A);
            if (!cli_parse_direction(v, &o->cam_up)) return bad_flag(a, "needs X,Y,Z (three finite numbers, not all 0), got '%s'", v);
            o->cam_up_set = true;
        }
        else if (cli_is(&A, "--fov")) { NEED(1); v = cli_next(&A); if (!cli_parse_float(v, &o->fov) || !(o->fov > 0 && o->fov < 180)) return bad_flag(a, "field of view must be a number of degrees in (0, 180), got '%s'", v); o->fov_set = true; }
        else if (cli_is(&A, "--cs184-framing")) o->cs184_framing = true;
        else if (cli_is(&A, "--print-camera")) o->print_camera = true;
        else if (cli_is(&A, "--log")) { NEED(1); o->log_path = cli_next(&A); }
        else if (cli_is(&A, "--reference")) {
            NEED(1);
            o->reference = cli_next(&A);
            if (!cli_ends_with(o->reference, ".pfm")) return bad_flag(a, "reference '%s' must be a .pfm image", o->reference);
        }
        else if (cli_is(&A, "--lights")) {
            NEED(1); v = cli_next(&A);
            if (strcmp(v, "all") == 0) o->by_power = false;
            else if (strcmp(v, "power") == 0) o->by_power = true;
            else return bad_flag(a, "must be all or power, got '%s'", v);
        }
        else if (cli_is(&A, "--pixel-rates")) { NEED(1); v = cli_next(&A); if (!cli_parse_onoff(v, &o->pixel_rates)) return bad_flag(a, "must be on or off, got '%s'", v); }
        else if (cli_is(&A, "--glow")) { NEED(1); v = cli_next(&A); if (!cli_parse_onoff(v, &o->glow)) return bad_flag(a, "must be on or off, got '%s'", v); }
        else if (cli_is(&A, "--footprint")) { NEED(1); v = cli_next(&A); if (!cli_parse_onoff(v, &o->footprint)) return bad_flag(a, "must be on or off, got '%s'", v); }
        else if (cli_is(&A, "--expected-emission")) { NEED(1); v = cli_next(&A); if (!cli_parse_onoff(v, &o->expected)) return bad_flag(a, "must be on or off, got '%s'", v); }
        else if (cli_is(&A, "--equiangular")) { NEED(1); v = cli_next(&A); if (!cli_parse_onoff(v, &o->equiangular)) return bad_flag(a, "must be on or off, got '%s'", v); }
        else if (cli_is(&A, "--mis")) { NEED(1); v = cli_next(&A); if (!cli_parse_onoff(v, &o->mis)) return bad_flag(a, "must be on or off, got '%s'", v); }
        else if (cli_is(&A, "-b")) { NEED(1); v = cli_next(&A); if (!cli_parse_float(v, &o->lens_radius) || o->lens_radius < 0) return bad_flag(a, "lens radius must be a number >= 0, got '%s'", v); o->lens_set = true; }
        else if (cli_is(&A, "-d")) { NEED(1); v = cli_next(&A); if (!cli_parse_float(v, &o->focal) || !(o->focal > 0)) return bad_flag(a, "focal distance must be a number > 0, got '%s'", v); o->focal_set = true; }
        else if (cli_is(&A, "-a")) {
            const char *b, *t;
            NEED(2);
            b = cli_next(&A); t = cli_next(&A);
            if (!cli_parse_int(b, 1, 1 << 20, &o->batch) || !cli_parse_float(t, &o->tolerance) || !(o->tolerance > 0))
                return bad_flag(a, "needs a batch size >= 1 and a tolerance > 0, got '%s %s'", b, t);
            o->adaptive = true;
        }
        else if (cli_is(&A, "-c")) { NEED(1); o->camera_file = cli_next(&A); }
        else if (cli_is(&A, "--bvh")) {
            NEED(1); v = cli_next(&A);
            if (strcmp(v, "sah") == 0) o->bvh = FOGRT_BVH_SAH;
            else if (strcmp(v, "volume") == 0) o->bvh = FOGRT_BVH_VOLUME;
            else return bad_flag(a, "must be sah or volume, got '%s'", v);
        }
        else if (cli_is(&A, "--time")) {
            float t;
            NEED(1); v = cli_next(&A);
            if (!cli_parse_float(v, &t) || !(t > 0)) return bad_flag(a, "time must be a number of seconds > 0, got '%s'", v);
            o->time_budget = (double)t;
        }
        else if (cli_is(&A, "--target-error")) {
            float e;
            NEED(1); v = cli_next(&A);
            if (!cli_parse_float(v, &e) || !(e > 0)) return bad_flag(a, "target error must be a number > 0, got '%s'", v);
            /* The image is kept and written in 32-bit floats, each rounded to 2^-24 of itself:
               an error below float's epsilon is not one the image can show, and the
               estimate would fall toward it for hours (an hour's ceiling at 800x600) */
            if (e < FLT_EPSILON)
                return bad_flag(a, "target error %s is below %.2g (FLT_EPSILON): no 32-bit float image resolves a smaller relative error", v, (double)FLT_EPSILON);
            o->target_error = (double)e;
        }
        else if (cli_is(&A, "--quiet")) o->quiet = true;
        else if (cli_is(&A, "-e")) { NEED(1); o->env_map = cli_next(&A); }
        else if (cli_is(&A, "--fog-bounds")) {
            double b[6];
            NEED(1); v = cli_next(&A);
            if (strcmp(v, "all") == 0) o->fog_where = CLI_FOG_ALL;
            else if (strcmp(v, "scene") == 0) o->fog_where = CLI_FOG_SCENE;
            else {
                if (!cli_parse_list(v, b, 6) || !(b[0] < b[3] && b[1] < b[4] && b[2] < b[5]) ||
                    fabs(b[0]) > 1e30 || fabs(b[1]) > 1e30 || fabs(b[2]) > 1e30 || fabs(b[3]) > 1e30 || fabs(b[4]) > 1e30 || fabs(b[5]) > 1e30)
                    return bad_flag(a, "must be all, scene, or X0,Y0,Z0,X1,Y1,Z1 with X0 < X1, Y0 < Y1, Z0 < Z1, got '%s'", v);
                o->fog_lo.x = (float)b[0]; o->fog_lo.y = (float)b[1]; o->fog_lo.z = (float)b[2];
                o->fog_hi.x = (float)b[3]; o->fog_hi.y = (float)b[4]; o->fog_hi.z = (float)b[5];
                if (!(o->fog_lo.x < o->fog_hi.x && o->fog_lo.y < o->fog_hi.y && o->fog_lo.z < o->fog_hi.z))
                    return bad_flag(a, "the box '%s' is thinner than float precision on an axis", v);
                o->fog_where = CLI_FOG_BOX;
            }
        }
        else if (cli_is(&A, "--trace")) {
            NEED(1); v = cli_next(&A);
            if (!parse_trace(v, o))
                return bad_flag(a, "must be X,Y or X,Y,SAMPLE (pixel column and row from the top, each below %d; sample index in [0, 4294967295]), got '%s'",
                                CLI_MAX_SIDE, v);
            o->trace = true;
        }
        else if (a[0] == '-' && a[1] != 0) return cli_unknown_flag(a, cli_flag_names);
        else {
            if (o->scene) return bad_flag(argv[i], "only one scene file may be given (already have '%s')", o->scene);
            o->scene = argv[i];
        }
        if (A.inline_value && !A.inline_used) return bad_flag(a, "takes no value, got '%s'", argv[i]);
#undef NEED
    }
    /* the flags shared with the preview, under the names the rest of this file uses */
    o->width = o->c.width; o->height = o->c.height; o->threads = o->c.threads;
    o->light_samples = o->c.light_samples; o->max_depth = o->c.max_depth; o->hemisphere = o->c.hemisphere;
    o->g = o->c.fog.g; o->g_set = o->c.fog.g_set; o->paper_g = o->c.fog.paper_g;
    o->density = o->c.fog.density; o->density_set = o->c.fog.density_set;
    o->albedo = o->c.fog.albedo; o->albedo_set = o->c.fog.albedo_set;
    o->integrator = o->c.integrator; o->fresnel = o->c.fresnel; o->seed = o->c.seed;
    o->exposure_ev = o->c.exposure_ev;

    if ((k = cli_common_media_check(&o->c)) != 0) return k;
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
#ifdef FOGRT_MINIMAL
    {   /* what needs Part II of fogrt.h, refused by a fogrt built on Part I alone */
        const char *part2 = o->equiangular ? "--equiangular" : o->glow ? "--glow" : o->footprint ? "--footprint" :
                            o->expected ? "--expected-emission" : o->pixel_rates ? "--pixel-rates" :
                            o->by_power ? "--lights" : o->fresnel == FOGRT_FRESNEL_EXACT ? "--fresnel" :
                            o->env_map ? "-e" : o->trace ? "--trace" :
                            o->fog_where == CLI_FOG_SCENE || o->fog_where == CLI_FOG_BOX ? "--fog-bounds" : NULL;
        if (part2) return bad_flag(part2, "needs Part II of fogrt.h: this fogrt was built with FOGRT_MINIMAL (Part I, the paper's method, alone)");
    }
#endif

    return 0;
}

/* ------------------------------------------------------------------------------------------
   The calls that follow the core's API (fogrt_render_desc), kept in one place
   ------------------------------------------------------------------------------------------ */
/* Set by the first SIGINT/SIGTERM/SIGHUP (see on_signal below). */
static volatile sig_atomic_t cli_interrupted = 0;
/* Set when the time limit (--time, or --target-error's ceiling) runs out during a batch: a
   timer (SIGALRM) sets it, so a first pass that takes longer than the limit stops too. */
static volatile sig_atomic_t cli_time_up = 0;
/* Either of the two: fogrt_render_desc.cancel reads it as an int before every sample (so
   that -l 65536 stops within one sample, not one row): sig_atomic_t must be int, as it is
   on glibc and musl. */
static volatile sig_atomic_t cli_stop = 0;
typedef char cli_sig_atomic_is_int[sizeof(sig_atomic_t) == sizeof(int) ? 1 : -1];
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
    rd->cancel = (const volatile int *)&cli_stop;
}
static void release_image(fogrt_image *img)
{
    fogrt_image_free(img);
}

/* ------------------------------------------------------------------------------------------
   Signals: the first SIGINT/SIGTERM/SIGHUP asks the render to stop at the next row block
   and write what it has; the second quits at once (removing a half-written temporary file).
   ------------------------------------------------------------------------------------------ */
static volatile sig_atomic_t cli_tty = 0;     /* stderr is a terminal */
static volatile sig_atomic_t cli_rendering = 0;   /* samples may exist: stop and write them */

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
    static const char early[] = "\nfogrt: interrupted before rendering: nothing written\n";
    if (!cli_rendering) {      /* loading or building: nothing to save, and no loop to ask */
        if (cli_temp_live) unlink(cli_temp_path);
        write_stderr_raw(early + !cli_tty, sizeof early - 1 - (size_t)!cli_tty);
        _exit(130);
    }
    if (cli_interrupted) {
        if (cli_temp_live) unlink(cli_temp_path);
        write_stderr_raw(again + !cli_tty, sizeof again - 1 - (size_t)!cli_tty);
        _exit(130);
    }
    cli_interrupted = sig;
    cli_stop = 1;
    if (cli_tty) write_stderr_raw(first, sizeof first - 1);      /* ends the \r progress line */
    else write_stderr_raw(first + 1, sizeof first - 2);
}
static void on_alarm(int sig)
{
    (void)sig;
    cli_time_up = 1;
    cli_stop = 1;
}
/* The time limit's timer: SIGALRM `seconds` from now (0: none, and any pending one off). */
static void arm_time_limit(double seconds)
{
    struct itimerval it;
    struct sigaction sa;
    memset(&it, 0, sizeof it);
    if (seconds > 0) {
        memset(&sa, 0, sizeof sa);
        sa.sa_handler = on_alarm;
        sigemptyset(&sa.sa_mask);
        sa.sa_flags = SA_RESTART;
        sigaction(SIGALRM, &sa, NULL);
        if (seconds > 1e8) seconds = 1e8;
        it.it_value.tv_sec = (time_t)seconds;
        it.it_value.tv_usec = (suseconds_t)((seconds - floor(seconds)) * 1e6);
        if (it.it_value.tv_sec == 0 && it.it_value.tv_usec == 0) it.it_value.tv_usec = 1;
    }
    setitimer(ITIMER_REAL, &it, NULL);
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
    sigaction(SIGHUP, &sa, NULL);   /* a closed terminal: the same as SIGTERM */
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
/* Scene, -c and --reference files must be regular files: a FIFO would block in open(). */
static int check_input_file(const char *prefix, const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0) {
        fprintf(stderr, "fogrt: %s%s: cannot open: %s\n", prefix, path, strerror(errno));
        return 2;
    }
    if (!S_ISREG(st.st_mode)) {
        fprintf(stderr, "fogrt: %s%s: is %s, not a regular file\n", prefix, path, cli_file_kind(st.st_mode));
        return 2;
    }
    return 0;
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
/* A library's message as one line: its newlines become "; ", trailing ones go. */
static const char *one_line(const char *msg, char *buf, size_t n)
{
    size_t k = 0;
    const char *p;
    if (!msg || n == 0) return "unknown error";
    for (p = msg; *p && k + 3 < n; ++p) {
        if (*p == '\n' || *p == '\r') {
            while (p[1] == '\n' || p[1] == '\r') ++p;
            if (p[1] == 0) break;
            buf[k++] = ';'; buf[k++] = ' ';
        } else {
            buf[k++] = (unsigned char)*p < 0x20 ? ' ' : *p;
        }
    }
    buf[k] = 0;
    return buf;
}

#ifdef FOGRT_CLI_EXR
/* OpenEXR, linear 32-bit float RGB (channels B, G, R, as readers expect them sorted), ZIP
   compressed, rows from the top. */
static bool encode_exr(int W, int H, const float *rgb, cli_membuf *out)
{
    EXRHeader hd;
    EXRImage im;
    EXRChannelInfo ch[3];
    int types[3], req[3], c;
    float *plane[3];
    unsigned char *mem = NULL;
    const char *err = NULL;
    size_t i, n = (size_t)W * (size_t)H, size;
    char line[256];
    InitEXRHeader(&hd);
    InitEXRImage(&im);
    for (c = 0; c < 3; ++c) plane[c] = (float *)malloc(sizeof(float) * n);
    if (!plane[0] || !plane[1] || !plane[2]) { free(plane[0]); free(plane[1]); free(plane[2]); return false; }
    for (i = 0; i < n; ++i) { plane[0][i] = rgb[3 * i + 2]; plane[1][i] = rgb[3 * i + 1]; plane[2][i] = rgb[3 * i]; }
    memset(ch, 0, sizeof ch);
    strcpy(ch[0].name, "B"); strcpy(ch[1].name, "G"); strcpy(ch[2].name, "R");
    for (c = 0; c < 3; ++c) { types[c] = TINYEXR_PIXELTYPE_FLOAT; req[c] = TINYEXR_PIXELTYPE_FLOAT; ch[c].x_sampling = ch[c].y_sampling = 1; }
    hd.num_channels = 3;
    hd.channels = ch;
    hd.pixel_types = types;
    hd.requested_pixel_types = req;
    hd.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP;
    im.images = (unsigned char **)plane;
    im.num_channels = 3;
    im.width = W;
    im.height = H;
    size = SaveEXRImageToMemory(&im, &hd, &mem, &err);
    for (c = 0; c < 3; ++c) free(plane[c]);
    if (size == 0 || !mem) {
        fprintf(stderr, "fogrt: -f: the OpenEXR encoder failed: %s\n", one_line(err, line, sizeof line));
        if (err) FreeEXRErrorMessage(err);
        free(mem);
        out->failed = true;
        return false;
    }
    cli_membuf_put(out, mem, size);
    free(mem);
    return !out->failed;
}
#endif

/* PFM or EXR (linear, unscaled), PPM, PNG or JPG by extension. */
static bool encode_image(const char *path, int W, int H, const float *rgb, float exposure_ev,
                         unsigned char *rgb8, cli_membuf *out)
{
    char header[64];
    int n;
    if (cli_ends_with(path, ".pfm")) return cli_encode_pfm(W, H, rgb, out);
#ifdef FOGRT_CLI_EXR
    if (cli_ends_with(path, ".exr")) return encode_exr(W, H, rgb, out);
#endif
    if (rgb) fogrt_tonemap_rgb8(rgb, W, H, exposure_ev, FOGRT_TONEMAP_SRGB, rgb8);
    if (cli_ends_with(path, ".ppm")) {
        n = snprintf(header, sizeof header, "P6\n%d %d\n255\n", W, H);
        cli_membuf_put(out, header, (size_t)n);
        cli_membuf_put(out, rgb8, 3 * (size_t)W * (size_t)H);
        return !out->failed;
    }
    if (cli_ends_with(path, ".jpg") || cli_ends_with(path, ".jpeg"))
        return stbi_write_jpg_to_func(cli_membuf_stb, out, W, H, 3, rgb8, 90) != 0 && !out->failed;
    return stbi_write_png_to_func(cli_membuf_stb, out, W, H, 3, rgb8, W * 3) != 0 && !out->failed;
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
    {   /* the declared size against the file's, before allocating for it */
        struct stat st;
        long at = ftell(f);
        if (fstat(fileno(f), &st) == 0 && at >= 0 && (double)st.st_size - (double)at < (double)n * 4.0) {
            fprintf(stderr, "fogrt: %s %s: the file is too short for its width x height (%dx%d needs %.0f bytes of pixels, it has %.0f)\n",
                    flag, path, w, h, (double)n * 4.0, fmax(0.0, (double)st.st_size - (double)at));
            fclose(f);
            return NULL;
        }
    }
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

/* A Radiance .hdr (RGBE, flat or run-length encoded scanlines, the standard -Y H +X W
   orientation), read here so that its declared size is checked against the file before
   anything is allocated and a truncated file is refused, never padded with black. */
static float *read_hdr(const char *path, int *out_w, int *out_h)
{
    FILE *f;
    struct stat st;
    unsigned char *buf = NULL, *p, *end, *row = NULL;
    float *px = NULL;
    const char *err = NULL;
    char errbuf[160];
    long w = 0, h = 0;
    int y, c, x;
    double min_row, min_bytes;
    f = fopen(path, "rb");
    if (!f) { fprintf(stderr, "fogrt: -e %s: cannot open: %s\n", path, strerror(errno)); return NULL; }
    if (fstat(fileno(f), &st) != 0 || st.st_size < 0 || (double)st.st_size > 4.0 * 1024 * 1024 * 1024) {
        fprintf(stderr, "fogrt: -e %s: cannot read: %s\n", path, fstat(fileno(f), &st) != 0 ? strerror(errno) : "larger than 4 GiB");
        fclose(f);
        return NULL;
    }
    buf = (unsigned char *)malloc((size_t)st.st_size + 1);
    if (!buf) { fclose(f); fprintf(stderr, "fogrt: -e %s: out of memory\n", path); return NULL; }
    if (fread(buf, 1, (size_t)st.st_size, f) != (size_t)st.st_size) { err = "read error"; goto fail; }
    fclose(f); f = NULL;
    buf[st.st_size] = 0;
    p = buf; end = buf + st.st_size;
    if (st.st_size < 2 || p[0] != '#' || p[1] != '?') { err = "not a Radiance HDR image (it must start with \"#?\")"; goto fail; }
    for (;;) {                                  /* header lines up to the empty one */
        unsigned char *nl = (unsigned char *)memchr(p, '\n', (size_t)(end - p));
        if (!nl) { err = "the header ends early (no empty line before the size)"; goto fail; }
        if (nl == p) { p = nl + 1; break; }
        if ((size_t)(nl - p) >= 7 && memcmp(p, "FORMAT=", 7) == 0 &&
            !((size_t)(nl - p) >= 22 && memcmp(p + 7, "32-bit_rle_rgbe", 15) == 0 && (nl - p == 22 || p[22] == '\r'))) { err = "only FORMAT=32-bit_rle_rgbe is supported"; goto fail; }
        p = nl + 1;
    }
    {
        char line[96], ys[4], xs[4];
        unsigned char *nl = (unsigned char *)memchr(p, '\n', (size_t)(end - p));
        int k = 0;
        if (!nl || nl - p >= (long)sizeof line) { err = "no size line after the header"; goto fail; }
        memcpy(line, p, (size_t)(nl - p)); line[nl - p] = 0;
        if (sscanf(line, "%3s %ld %3s %ld%n", ys, &h, xs, &w, &k) != 4 || line[k] != 0) { err = "bad size line (expected \"-Y H +X W\")"; goto fail; }
        if (strcmp(ys, "-Y") != 0 || strcmp(xs, "+X") != 0) { err = "only the standard orientation \"-Y H +X W\" is supported"; goto fail; }
        if (w < 1 || h < 1 || w > CLI_MAX_SIDE || h > CLI_MAX_SIDE) { snprintf(errbuf, sizeof errbuf, "bad size %ldx%ld (each side in [1, %d])", w, h, CLI_MAX_SIDE); err = errbuf; goto fail; }
        if ((double)w * (double)h > CLI_MAX_ENV_PIXELS) {
            snprintf(errbuf, sizeof errbuf, "%ldx%ld pixels, more than the limit of %.0f M pixels", w, h, CLI_MAX_ENV_PIXELS / (1024.0 * 1024.0));
            err = errbuf; goto fail;
        }
        p = nl + 1;
    }
    /* The fewest bytes a scanline can take: run-length encoded, 4 channels of runs of 127
       (2 bytes each) after its 4-byte header; flat, 4 bytes a pixel. */
    min_row = (w >= 8 && w < 32768) ? 4.0 + 8.0 * (double)((w + 126) / 127) : 4.0 * (double)w;
    min_bytes = min_row * (double)h;
    if ((double)(end - p) < min_bytes) {
        snprintf(errbuf, sizeof errbuf, "the file is too short for its %ldx%ld pixels (at least %.0f bytes of scanlines, it has %ld)",
                 w, h, min_bytes, (long)(end - p));
        err = errbuf; goto fail;
    }
    px = (float *)malloc(sizeof(float) * 3 * (size_t)w * (size_t)h);
    row = (unsigned char *)malloc(4 * (size_t)w);
    if (!px || !row) { err = "out of memory"; goto fail; }
    for (y = 0; y < h; ++y) {
        if (w >= 8 && w < 32768 && end - p >= 4 && p[0] == 2 && p[1] == 2 && !(p[2] & 0x80)) {
            if (((long)p[2] << 8 | p[3]) != w) { snprintf(errbuf, sizeof errbuf, "scanline %d says it is %d pixels wide, not %ld", y, (int)p[2] << 8 | p[3], w); err = errbuf; goto fail; }
            p += 4;
            for (c = 0; c < 4; ++c) {                 /* each channel as runs and literals */
                x = 0;
                while (x < w) {
                    int count;
                    if (p >= end) goto truncated;
                    count = *p++;
                    if (count > 128) {
                        count -= 128;
                        if (count > w - x) { snprintf(errbuf, sizeof errbuf, "scanline %d: a run passes the end of the line", y); err = errbuf; goto fail; }
                        if (p >= end) goto truncated;
                        for (; count > 0; --count, ++x) row[4 * x + c] = *p;
                        ++p;
                    } else {
                        if (count == 0 || count > w - x) { snprintf(errbuf, sizeof errbuf, "scanline %d: a bad run length", y); err = errbuf; goto fail; }
                        if (end - p < count) goto truncated;
                        for (; count > 0; --count, ++x) row[4 * x + c] = *p++;
                    }
                }
            }
        } else {
            if (end - p < 4 * w) goto truncated;
            memcpy(row, p, 4 * (size_t)w);
            p += 4 * w;
        }
        for (x = 0; x < w; ++x) {
            const unsigned char *q = row + 4 * x;
            float *o = px + 3 * ((size_t)y * (size_t)w + (size_t)x);
            if (q[3] == 0) { o[0] = o[1] = o[2] = 0.0f; }
            else {
                float s = (float)ldexp(1.0, (int)q[3] - 136);     /* mantissa / 256 x 2^(e - 128) */
                o[0] = (float)q[0] * s; o[1] = (float)q[1] * s; o[2] = (float)q[2] * s;
            }
        }
    }
    free(row); free(buf);
    *out_w = (int)w; *out_h = (int)h;
    return px;
truncated:
    snprintf(errbuf, sizeof errbuf, "the file is truncated: it ends in scanline %d of %ld", y + 1, h);
    err = errbuf;
fail:
    fprintf(stderr, "fogrt: -e %s: %s\n", path, err);
    if (f) fclose(f);
    free(buf); free(row); free(px);
    return NULL;
}

#ifdef FOGRT_CLI_EXR
/* An OpenEXR map through tinyexr, its header read first: the size it declares must fit the
   pixel limit and the file (every scanline block has an 8-byte offset and an 8-byte block
   header; uncompressed blocks hold all their pixels) before tinyexr allocates for it. */
static float *read_exr(const char *path, int *w, int *h)
{
    EXRVersion ver;
    EXRHeader hd;
    const char *err = NULL;
    float *rgba = NULL, *px;
    char line[320];
    size_t i, n;
    struct stat st;
    double width, height, lines, chunks, need, bpp = 0;
    int c, r;
    if (ParseEXRVersionFromFile(&ver, path) != TINYEXR_SUCCESS) {
        fprintf(stderr, "fogrt: -e %s: not an OpenEXR image (or too short for its header)\n", path);
        return NULL;
    }
    if (ver.multipart || ver.non_image) { fprintf(stderr, "fogrt: -e %s: multi-part and deep OpenEXR images are not supported\n", path); return NULL; }
    InitEXRHeader(&hd);
    if ((r = ParseEXRHeaderFromFile(&hd, &ver, path, &err)) != TINYEXR_SUCCESS) {
        fprintf(stderr, "fogrt: -e %s: cannot read the OpenEXR header: %s\n", path, one_line(err, line, sizeof line));
        if (err) FreeEXRErrorMessage(err);
        FreeEXRHeader(&hd);                     /* what it read before it failed */
        return NULL;
    }
    width = (double)hd.data_window.max_x - (double)hd.data_window.min_x + 1.0;
    height = (double)hd.data_window.max_y - (double)hd.data_window.min_y + 1.0;
    for (c = 0; c < hd.num_channels; ++c) bpp += hd.pixel_types[c] == TINYEXR_PIXELTYPE_HALF ? 2.0 : 4.0;
    switch (hd.compression_type) {
    case TINYEXR_COMPRESSIONTYPE_ZIP: lines = 16; break;
    case TINYEXR_COMPRESSIONTYPE_PIZ: lines = 32; break;
    default: lines = 1; break;
    }
    chunks = hd.tiled ? 1.0 : ceil(height / lines);
    need = (double)hd.header_len + chunks * 16.0 +
           (!hd.tiled && hd.compression_type == TINYEXR_COMPRESSIONTYPE_NONE ? width * height * bpp : 0.0);
    FreeEXRHeader(&hd);
    if (!(width >= 1 && height >= 1) || width * height > CLI_MAX_ENV_PIXELS) {
        fprintf(stderr, "fogrt: -e %s: %.0fx%.0f pixels, outside [1, %.0f M pixels]\n", path, width, height, CLI_MAX_ENV_PIXELS / (1024.0 * 1024.0));
        return NULL;
    }
    if (stat(path, &st) == 0 && (double)st.st_size < need) {
        fprintf(stderr, "fogrt: -e %s: the file is too short for its %.0fx%.0f pixels (at least %.0f bytes, it has %.0f)\n",
                path, width, height, need, (double)st.st_size);
        return NULL;
    }
    if (LoadEXR(&rgba, w, h, path, &err) != TINYEXR_SUCCESS) {
        fprintf(stderr, "fogrt: -e %s: cannot read the OpenEXR image: %s\n", path, one_line(err, line, sizeof line));
        if (err) FreeEXRErrorMessage(err);
        return NULL;
    }
    n = (size_t)*w * (size_t)*h;
    px = (float *)malloc(sizeof(float) * 3 * n);
    if (px) for (i = 0; i < n; ++i) { px[3 * i] = rgba[4 * i]; px[3 * i + 1] = rgba[4 * i + 1]; px[3 * i + 2] = rgba[4 * i + 2]; }
    else fprintf(stderr, "fogrt: -e %s: out of memory\n", path);
    free(rgba);
    return px;
}
#endif

/* -e: an environment map, .pfm, .hdr or .exr (tinyexr, when the CLI was built with
   libtinyexr-dev), as linear RGB; NULL with one message on failure. */
static float *read_env_map(const char *path, int *w, int *h)
{
    if (cli_ends_with(path, ".pfm")) return read_pfm_for("-e", path, 0, 0, w, h);
    if (cli_ends_with(path, ".hdr")) return read_hdr(path, w, h);
    if (cli_ends_with(path, ".exr")) {
#ifdef FOGRT_CLI_EXR
        return read_exr(path, w, h);
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
    if (cli_stop) return false;           /* the rows already started finish; the rest wait */
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
        if (est == est) { log_number(f, est * est, false); log_number(f, est, false); }
        else fputs(",,", f);                    /* no estimate yet (under 2 spp) or a black image */
        if (p->ref) {
            log_number(f, p->m.rel_mse, false); log_number(f, p->m.rmse, false);
            log_number(f, p->m.ratio[0], false); log_number(f, p->m.ratio[1], false); log_number(f, p->m.ratio[2], false);
        } else {
            fputs(",,,,,", f);
        }
        fprintf(f, "%s\n", event);
        if (fflush(f) != 0 || ferror(f)) {
            fprintf(stderr, "fogrt: warning: --log %s: write failed: %s: rendering on without the log (exit status 1)\n", p->log_path, strerror(errno));
            p->log_failed = true;
        }
    }
}

/* ------------------------------------------------------------------------------------------
   Rendering: progressive batches through fogrt_render, or CS184's per-pixel adaptive loop
   ------------------------------------------------------------------------------------------ */
/* The spp of the next batch, from the inputs alone (never the clock), so that with a seed
   --log's rows, the estimate in them and the image are the same on every run and thread
   count: doubling at first (1, 1, 2, 4, ... spp: early error points), the --pixel-rates
   pilot ended exactly at its spp, then at most CLI_BATCH_SAMPLES samples per batch (at
   least 1 spp), and never past the goal. */
static uint64_t batch_spp(const render_state *p, uint64_t done, bool rates_pending)
{
    double cap = floor(CLI_BATCH_SAMPLES / (p->pixels * (double)(p->o->light_samples > 0 ? p->o->light_samples : 1)));
    uint64_t b = done > 0 ? done : 1;
    if (cap < (double)b) b = cap >= 1.0 ? (uint64_t)cap : 1;
    if (rates_pending && b > CLI_RATES_PILOT - done) b = CLI_RATES_PILOT - done;
    if (b > ((uint64_t)1 << 20)) b = (uint64_t)1 << 20;
    if (b < 1) b = 1;
    if (p->spp_target && b > p->spp_target - done) b = p->spp_target - done;
    return b;
}

/* Batches of batch_spp, so the estimate updates and the log gets a row often. A time limit
   (--time, or --target-error's ceiling) is the one input read from the clock: it stops the
   render between batches, and the last batch is cut to the time left at the speed measured
   so far (a run that a time limit stops depends on time; any other does not); a batch still
   running when the limit passes (a first pass slower than the whole limit) is cancelled by
   a timer, within a sample. An interrupt cancels the batch the same way. Every sample taken
   stays counted. */
static fogrt_result render_progressive(const fogrt_scene *scene, fogrt_render_desc *rd, fogrt_image *img,
                                       render_state *p, const char **stopped_by)
{
    uint64_t done = 0;
    double rate = 0.0;                 /* samples per pixel per second */
    fogrt_result r = FOGRT_RESULT_OK;
    rd->progress = on_progress;
    rd->user_data = p;
    *stopped_by = NULL;
    arm_time_limit(p->seconds_limit);
    for (;;) {
        fogrt_render_stats st;
        uint64_t b;
        double elapsed = now_seconds() - p->t0;
        if (cli_interrupted) break;
        if (p->spp_target && done >= p->spp_target) { *stopped_by = "samples"; break; }
        if (p->seconds_limit > 0 && elapsed >= p->seconds_limit && done > 0) { *stopped_by = "time"; break; }
        b = batch_spp(p, done, p->rates && !rd->sample_rate);
        if (p->seconds_limit > 0 && rate > 0 && (double)b > (p->seconds_limit - elapsed) * rate)
            b = (uint64_t)fmax(1.0, floor((p->seconds_limit - elapsed) * rate));
        p->spp_done = done;
        p->spp_batch = (int)b;
        r = fogrt_render(scene, rd, img, (int)b, &st);
        p->rays += st.rays;
        if (r == FOGRT_RESULT_CANCELLED && !cli_interrupted) {     /* the time ran out mid-batch */
            *stopped_by = "time";
            take_measurement(p, img, "batch");
        }
        if (r == FOGRT_RESULT_CANCELLED) { r = FOGRT_RESULT_OK; break; }
        if (r) break;
        done += b;
        p->spp_done = done; p->spp_batch = 0;
        /* --pixel-rates: once, after the pilot's spp taken alike; kept to the end (unbiased) */
        if (p->rates && !rd->sample_rate && done >= CLI_RATES_PILOT) {
#ifndef FOGRT_MINIMAL
            if (fogrt_image_sample_rates(img, p->rates) == FOGRT_RESULT_OK) rd->sample_rate = p->rates;
            else
#endif
            p->rates = NULL;    /* out of memory: every pixel alike, as without the flag */
        }
        rate = (double)done / fmax(now_seconds() - p->t0, 1e-6);
        take_measurement(p, img, "batch");
        print_progress(p, (double)done, false);
        if (p->o->target_error > 0 && p->est_error >= 0 && p->est_error <= p->o->target_error) { *stopped_by = "error"; break; }
        /* nothing can light the scene: every sample is 0, the estimate stays n/a for ever */
        if (p->o->target_error > 0 && p->black) { *stopped_by = "black"; break; }
    }
    arm_time_limit(0.0);
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
            if (cli_interrupted) break;      /* a row of many samples stops mid-row too */
            fogrt_rng_seed(&rng, rd->seed, (uint64_t)pix);
            while (taken < (uint32_t)o->spp && !cli_interrupted) {
                int k;
                for (k = 0; k < o->batch && taken < (uint32_t)o->spp && !cli_interrupted; ++k, ++taken) {
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

/* The box of the scene's geometry, an axis without thickness (a lone plane) given a little;
   false when there is none. */
static bool scene_box(const fogrt_scene_info *info, fogrt_vec3 *lo, fogrt_vec3 *hi)
{
    float l[3], h[3], ext = 0.0f;
    int k;
    l[0] = info->bounds_min.x; l[1] = info->bounds_min.y; l[2] = info->bounds_min.z;
    h[0] = info->bounds_max.x; h[1] = info->bounds_max.y; h[2] = info->bounds_max.z;
    for (k = 0; k < 3; ++k) {
        if (!(isfinite(l[k]) && isfinite(h[k]) && l[k] <= h[k])) return false;
        if (h[k] - l[k] > ext) ext = h[k] - l[k];
    }
    for (k = 0; k < 3; ++k)
        if (!(h[k] - l[k] > 1e-6f * ext)) {
            float pad = 1e-3f * (ext > 0.0f ? ext : 1.0f) + 1e-6f * fmaxf(fabsf(l[k]), fabsf(h[k]));
            l[k] -= pad; h[k] += pad;
        }
    lo->x = l[0]; lo->y = l[1]; lo->z = l[2];
    hi->x = h[0]; hi->y = h[1]; hi->z = h[2];
    return true;
}

/* Where the fog is, for the progress header and the summary line. */
static void describe_fog(const fogrt_medium_desc *md, const fogrt_scene_info *info, char *buf, size_t n)
{
    char density[80];
    if (!(md->sigma_t > 0.0f)) { snprintf(buf, n, "no fog"); return; }
    if (md->sigma_t_rgb.x != 0.0f || md->sigma_t_rgb.y != 0.0f || md->sigma_t_rgb.z != 0.0f)   /* chromatic */
        snprintf(density, sizeof density, "%g,%g,%g", (double)md->sigma_t_rgb.x, (double)md->sigma_t_rgb.y, (double)md->sigma_t_rgb.z);
    else
        snprintf(density, sizeof density, "%g", (double)md->sigma_t);
    if (md->bounded)
        snprintf(buf, n, "fog (density %s) in the box %.4g,%.4g,%.4g to %.4g,%.4g,%.4g", density,
                 (double)md->bounds_min.x, (double)md->bounds_min.y, (double)md->bounds_min.z,
                 (double)md->bounds_max.x, (double)md->bounds_max.y, (double)md->bounds_max.z);
    else if (info->has_environment)
        snprintf(buf, n, "fog (density %s) in the box of the geometry %.4g,%.4g,%.4g to %.4g,%.4g,%.4g (the sky shows through)", density,
                 (double)info->bounds_min.x, (double)info->bounds_min.y, (double)info->bounds_min.z,
                 (double)info->bounds_max.x, (double)info->bounds_max.y, (double)info->bounds_max.z);
    else
        snprintf(buf, n, "fog (density %s) everywhere, also outside the scene's geometry (--fog-bounds scene keeps it inside)",
                 density);
}

/* The sample goal as the header says it. */
static const char *ps_target_text(const cli_options *o, char *buf, size_t n)
{
    if (o->spp_set || (o->time_budget <= 0 && o->target_error <= 0)) snprintf(buf, n, "%d spp", o->spp);
    else if (o->time_budget > 0) snprintf(buf, n, "for %g s", o->time_budget);
    else snprintf(buf, n, "to a relative error of %g", o->target_error);
    return buf;
}

/* The scene file's kind: by extension, and by content when it is plainly something else. */
static int check_scene_kind(const char *path)
{
    const char *kind = cli_sniff_kind(path, false);
    bool known = cli_ends_with(path, ".dae") || cli_ends_with(path, ".obj") || cli_ends_with(path, ".ply");
    if (kind) {
        fprintf(stderr, "fogrt: %s: %s, not a scene: fogrt reads .dae, .obj, .ply\n", path, kind);
        return 2;
    }
    if (!known) {
        fprintf(stderr, "fogrt: %s: unknown scene type: fogrt reads .dae, .obj, .ply\n", path);
        return 2;
    }
    return 0;
}

/* --log: a new file gets the header row at once; an existing one must be a fogrt log (its first
   line that header), else appending would damage a file that is something else. A character
   device (/dev/null, a terminal) gets the header like a new file. NULL with *status set after
   one message: 2 refused (the run stops), 1 cannot be written (the caller renders on: the
   image is what the run is for, the log a side file). */
static FILE *open_log(const char *path, int *status)
{
    struct stat st;
    FILE *f;
    bool fresh = true;
    if (stat(path, &st) == 0) {
        if (!S_ISREG(st.st_mode) && !S_ISCHR(st.st_mode)) {
            fprintf(stderr, "fogrt: --log %s: is %s, not a regular file\n", path, cli_file_kind(st.st_mode));
            *status = 2; return NULL;
        }
        if (S_ISREG(st.st_mode) && st.st_size > 0) {
            char first[256];
            size_t n;
            f = fopen(path, "rb");
            if (!f) { fprintf(stderr, "fogrt: warning: --log %s: cannot read: %s: rendering without the log (exit status 1)\n", path, strerror(errno)); *status = 1; return NULL; }
            n = fread(first, 1, strlen(log_header), f);
            fclose(f);
            if (n != strlen(log_header) || memcmp(first, log_header, n) != 0) {
                fprintf(stderr, "fogrt: --log %s: exists and is not a fogrt log (its first line is not the header row): "
                        "not appending to it; give a new file or an earlier --log\n", path);
                *status = 2; return NULL;
            }
            fresh = false;
        }
    }
    f = fopen(path, "a");
    if (!f) { fprintf(stderr, "fogrt: warning: --log %s: cannot write: %s: rendering without the log (exit status 1)\n", path, strerror(errno)); *status = 1; return NULL; }
    if (fresh && (fputs(log_header, f) < 0 || fflush(f) != 0)) {
        fprintf(stderr, "fogrt: warning: --log %s: write failed: %s: rendering without the log (exit status 1)\n", path, strerror(errno));
        fclose(f);
        *status = 1; return NULL;
    }
    return f;
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

/* The output of --print-camera and --trace is all the run makes: lost, it is a failure (exit
   1 and one line), whether stdout was closed (cli_std_streams put /dev/null there) or a write
   to it failed. */
static int stdout_status(const char *flag, int status)
{
    if (cli_stdout_closed) {
        fprintf(stderr, "fogrt: %s: stdout is closed: nothing was printed\n", flag);
        return 1;
    }
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "fogrt: %s: cannot write to stdout: %s\n", flag, strerror(errno));
        return 1;
    }
    return status;
}

/* The program; main only makes the process fit to run it first (its own frame is small, so
   that a stack limit too small for this one is refused with a message, not a crash). */
#if defined(__GNUC__)
__attribute__((noinline))
#endif
/* A refused build: one line, and the exit status (2: the scene or the flags, 1: memory). A
   refusal of media inside objects is told by their --medium flags. */
static int build_failed(const cli_options *o, cli_log *L, const fogrt_scene *scene, fogrt_result r)
{
    if (o->c.media_count && r != FOGRT_RESULT_OUT_OF_MEMORY && r != FOGRT_RESULT_EMPTY_SCENE) {
        const char *msg = L->error[0] ? L->error : fogrt_scene_last_error(scene);
        int st = cli_media_build_failed(&o->c, msg, r);
        L->error[0] = 0;
        return st;
    }
    fail_line(L, o->scene ? o->scene : "default scene", r);
    return r == FOGRT_RESULT_EMPTY_SCENE ? 2 : 1;
}

static int run(int argc, char **argv)
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
    cli_output out, rate_out;
    cli_membuf enc;
    cli_shapes shapes;
    char rate_name[4096], where[4200], err_a[64], err_b[64], reason[256], target[64], fog_text[1024], samplers[512];
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
    cli_shapes_init(&shapes, NULL);
    status = parse_args(argc, argv, &o);
    if (status == -1) return 0;
    if (status) return status;
    cli_tty = isatty(2) != 0;
    install_signals();
    if ((threads = cli_resolve_threads(o.threads)) == 0) return 2;

    /* Inputs must be regular files (a FIFO would block the loader) of the right kind */
    if (o.scene && (status = check_input_file("", o.scene)) != 0) return status;
    if (o.scene && (status = check_scene_kind(o.scene)) != 0) return status;
    if (o.camera_file && (status = check_input_file("-c ", o.camera_file)) != 0) return status;
    if (o.camera_file && (why = cli_sniff_kind(o.camera_file, true)) != NULL) {
        fprintf(stderr, "fogrt: -c %s: %s, not a CS184 camera settings file (text, as CS184 writes it)\n", o.camera_file, why);
        return 2;
    }
    if (o.reference && (status = check_input_file("--reference ", o.reference)) != 0) return status;
    if (o.env_map && (status = check_input_file("-e ", o.env_map)) != 0) return status;
    if (!o.print_camera && !o.trace) {
        /* No output may be an input or another output (checked before anything is written) */
        cli_file in[4], outs[3];
        int nin = 0, nout = 0;
        if (o.scene) cli_identify(&in[nin++], "", o.scene);
        if (o.camera_file) cli_identify(&in[nin++], "-c", o.camera_file);
        if (o.env_map) cli_identify(&in[nin++], "-e", o.env_map);
        if (o.reference) cli_identify(&in[nin++], "--reference", o.reference);
        cli_identify(&outs[nout++], "-f", o.output);
        if (o.adaptive) {
            rate_path(o.output, rate_name, sizeof rate_name);
            cli_identify(&outs[nout++], "-a (the rate image)", rate_name);
        }
        if (o.log_path) cli_identify(&outs[nout++], "--log", o.log_path);
        if ((status = cli_check_aliases(in, nin, outs, nout)) != 0) return status;

        if (!cli_prepare_output(&out, "-f", o.output)) return 1;
        if (o.adaptive && !cli_prepare_output(&rate_out, "-a (the rate image)", rate_name)) return 1;
        if (o.reference && !(ref = read_reference(o.reference, o.width, o.height))) return 2;
        if (o.log_path) {           /* created (or checked) before anything is loaded or rendered */
            ps.log = open_log(o.log_path, &status);
            if (!ps.log && status != 1) { free(ref); return status; }
            ps.log_failed = !ps.log;
            status = 0;
            ps.log_path = o.log_path;
        }
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
    cli_shapes_init(&shapes, o.scene);
    if (o.c.media_count) { lo.on_shape = cli_on_shape; lo.on_shape_user = &shapes; }   /* --medium's names */
    if (!o.scene) {
        r = fogrt_scene_add_default(scene);
        if (r) { fail_line(&logbuf, "default scene", r); status = 1; goto done; }
    } else {
        is_dae = cli_ends_with(o.scene, ".dae");
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
    cli_common_media_apply(&o.c.fog, &md);       /* --density R,G,B, --g G1,G2,W, --phase, --emission */
    if (o.fog_where == CLI_FOG_BOX) { md.bounded = true; md.bounds_min = o.fog_lo; md.bounds_max = o.fog_hi; }
    if (o.fog_where == CLI_FOG_ALL) md.bounded = false;
    r = fogrt_scene_set_medium(scene, &md);
    if (r) { fail_line(&logbuf, o.fog_where == CLI_FOG_BOX ? "--density/--albedo/--g/--phase/--emission/--fog-bounds" : "--density/--albedo/--g/--phase/--emission", r); status = 2; goto done; }
    if ((status = cli_apply_media(scene, &o.c, &shapes)) != 0) goto done;   /* --medium NAME ... */
    if (o.env_map) {                             /* -e: the environment map light */
        int ew = 0, eh = 0;
        float *env;
        if (check_input_file("-e ", o.env_map) != 0) { status = 2; goto done; }
        env = read_env_map(o.env_map, &ew, &eh);
        if (!env) { status = 2; goto done; }
#ifndef FOGRT_MINIMAL
        r = fogrt_scene_set_environment_map(scene, ew, eh, env, 1.0f);
#else
        r = FOGRT_RESULT_UNSUPPORTED;                   /* refused with the flags above */
#endif
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
    if (o.print_camera) { print_camera(&cam, o.width, o.height); status = stdout_status("--print-camera", 0); goto done; }

    /* Build */
    bd = fogrt_build_defaults();
    bd.heuristic = o.bvh;
    bd.release_binary = true;                    /* fogrt only renders: no tree to inspect */
    /* The roulette's pilot (Part II, C) traces 64 x 48 x 16 camera paths at build time: a
       render of fewer than four times as many samples pays more for it than it can gain. */
    if ((o.spp_set || (o.time_budget <= 0 && o.target_error <= 0)) &&
        (double)o.width * (double)o.height * (double)o.spp < 4.0 * 64 * 48 * 16)
        bd.roulette_pilot = false;
    if (o.fog_where == CLI_FOG_SCENE && md.sigma_t > 0.0f) {
        /* The scene's box is known once it is built: a quick build (no roulette pilot) for
           it, the fog set to that box, then the real build. */
        fogrt_build_desc quick = bd;
        quick.roulette_pilot = false;
        r = fogrt_scene_build(scene, &quick);
        if (r) { status = build_failed(&o, &logbuf, scene, r); goto done; }
        fogrt_scene_get_info(scene, &info);
        if (!scene_box(&info, &md.bounds_min, &md.bounds_max)) {
            fprintf(stderr, "fogrt: --fog-bounds scene: %s has no finite geometry to bound the fog\n", o.scene ? o.scene : "the scene");
            status = 2; goto done;
        }
        md.bounded = true;
        r = fogrt_scene_set_medium(scene, &md);
        if (r) { fail_line(&logbuf, "--fog-bounds scene", r); status = 2; goto done; }
    }
    r = fogrt_scene_build(scene, &bd);
    if (r) { status = build_failed(&o, &logbuf, scene, r); goto done; }
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
        status = stdout_status("--trace", status);
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
    /* Render: a header line saying what is rendered and where the fog is */
    describe_fog(&md, &info, fog_text, sizeof fog_text);
    cli_describe_media(&o.c, fog_text + strlen(fog_text), sizeof fog_text - strlen(fog_text));
    if (!o.quiet)
        fprintf(stderr, "fogrt: rendering %s (%dx%d, %s, %d thread%s): %s\n", o.scene ? o.scene : "the default scene",
                o.width, o.height, o.adaptive ? "adaptive" : ps_target_text(&o, target, sizeof target), threads, threads == 1 ? "" : "s", fog_text);
    fill_render_desc(&o, threads, &rd);
    cli_rendering = 1;
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
    if (ee.samples == 0 && !cli_interrupted) {     /* one sample took longer than the limit */
        fprintf(stderr, "fogrt: the time limit (%g s) ran out before any sample was taken: nothing written\n", ps.seconds_limit);
        status = 1; goto done;
    }
    if (ee.samples == 0) {
        fprintf(stderr, "fogrt: interrupted before any sample was taken: nothing written\n");
        status = 130; goto done;
    }
    if (!warned_black && ee.mean_luminance == 0.0) {
        fprintf(stderr, "fogrt: warning: every pixel is black: nothing the camera sees is lit\n");
        ps.black = true;
    }
    if (!o.adaptive && !cli_interrupted && o.target_error > 0 && stopped_by && strcmp(stopped_by, "black") == 0)
        fprintf(stderr, "fogrt: warning: --target-error %g cannot be reached: a black image has no error estimate: stopped at %llu spp\n",
                o.target_error, (unsigned long long)ps.spp_done);
    else if (!o.adaptive && !cli_interrupted && o.target_error > 0 && stopped_by && strcmp(stopped_by, "error") != 0)
        fprintf(stderr, "fogrt: warning: --target-error %g not reached (estimate %s): stopped at the %s ceiling (%llu spp, %.0f s)\n",
                o.target_error, (format_error(&ps, ps.est_error, err_a, sizeof err_a), err_a), stopped_by,
                (unsigned long long)ps.spp_target, ps.seconds_limit);

    /* Write: the image, then CS184's sampling-rate image */
    fogrt_image_resolve(&img, rgb);
    if (!encode_image(o.output, o.width, o.height, rgb, o.exposure_ev, rgb8, &enc)) {
        fprintf(stderr, "fogrt: -f %s: could not encode the image (out of memory)\n", o.output);
        status = 1; goto done;
    }
    if (!cli_write_output(&out, &enc)) { status = 1; goto done; }
    if (o.adaptive) {
        enc.size = 0;
        rate_image(&img, o.spp, rgb8);
        if (!encode_image(rate_name, o.width, o.height, NULL, 0.0f, rgb8, &enc) || !cli_write_output(&rate_out, &enc)) {
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
                "rel. error %s%s, %llu non-finite samples dropped; %s; samplers: %s\n",
                cli_interrupted ? "interrupted: " : "", o.output, o.adaptive ? " and " : "", o.adaptive ? rate_name : "",
                o.width, o.height, o.adaptive ? "adaptive, mean " : "", spp_mean, target, elapsed, t_load,
                elapsed > 0 ? (double)ee.samples / elapsed * 1e-6 : 0.0, err_a, err_b,
                (unsigned long long)img.rejected, fog_text, fogrt_render_samplers(scene, &rd, samplers, sizeof samplers));
    }
    if (ps.log_failed) {
        fprintf(stderr, "fogrt: --log %s: not written in full (the warning above says why): exit status 1, the image is written\n", o.log_path);
        status = 1;
    } else if (cli_interrupted) status = 130;

done:
    if (ps.log && fclose(ps.log) != 0 && status == 0) {
        fprintf(stderr, "fogrt: --log %s: write failed: %s\n", o.log_path, strerror(errno));
        status = 1;
    }
    free(enc.data);
    free(rgb); free(rgb8); free(ref); free(rates);
    release_image(&img);
    fogrt_scene_destroy(scene);
    cli_shapes_free(&shapes);
    return status;
}

int main(int argc, char **argv)
{
    cli_std_streams();          /* before any file is opened: 0-2 are never an image */
    cli_sane_omp_env(argv);
    cli_prog = "fogrt";
    if (!cli_check_stack()) return 2;
    return run(argc, argv);
}
