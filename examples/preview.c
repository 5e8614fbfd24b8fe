/* preview - fogrt's interactive preview: watch the fog converge and turn its knobs live.

   Opens a GLFW window showing the progressive render of the embedded default scene, or of a
   CS184 .dae / OBJ / PLY file given on the command line (loaded and placed as `fogrt` does).
   The image refines without end; any change of a parameter (fog, g, density, albedo, the
   sampling method, the depth, the camera) restarts the accumulation at once. `preview -h`
   lists the flags and the keys; `h` or F1 in the window shows the keys again.

   How it stays responsive: one worker thread renders in batches (right after a change a
   quick pass at 1/4 and one at 1/2 resolution, then one sample per pixel at a time over the
   full image, accumulating) while the main thread only handles input and draws. fogrt_render
   calls a progress callback between blocks of rows; when a parameter changes, the callback
   tells it to stop, so the worker starts over within a fraction of one batch. On Linux the
   render threads run at nice 5, so the input thread gets a core the moment it wakes.

   Scripted mode (tests, screenshots, measurements): --frames N runs N frames, each showing
   exactly one more finished batch; --keys "10:f,20:w,30:s,40:drag:60,0" applies key presses
   (and mouse drags / wheel steps) at given frames; --screenshot FILE writes the window's
   content after the last frame as PNG. The same arguments give the same pictures. At exit one
   summary line reports frames per second, samples per second, how often input was polled and
   the latency from a key press to the restart and to the first new frame.

   Build: make preview (mk/preview.mk; GLFW 3 through pkg-config, Debian libglfw3-dev; PNG via
   stb_image_write and the overlay font via stb_easy_font, both from Debian libstb-dev).
   Exit status: 0 ok, 2 bad input (flag, value, scene file), 1 no window / render failure. */
#define _POSIX_C_SOURCE 200809L
#define _DEFAULT_SOURCE           /* Linux: syscall(SYS_gettid) to lower the render threads' priority */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <stdarg.h>
#include <errno.h>
#include <math.h>
#include <time.h>
#include <pthread.h>
#include <signal.h>
#if defined(__linux__)
#include <unistd.h>
#include <sys/syscall.h>
#include <sys/resource.h>
#endif

#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#define FOGRT_LOAD_IMPLEMENTATION
#include "fogrt_load.h"
#include "cli_common.h"

#include <GLFW/glfw3.h>   /* also brings <GL/gl.h>: legacy OpenGL 1.x is all we use */

#define FOGRT_STB_EASY_FONT
#include "stb_write.h"           /* stb_image_write, its warnings silenced */

/* ------------------------------------------------------------------------------------------
   What the user can change, and the program's options
   ------------------------------------------------------------------------------------------ */
/* The image's buffers, checked against a limit before anything is allocated (as fogrt
   checks its own): the shown, resolved and 8-bit images (27 bytes per pixel), the full,
   1/2 and 1/4 resolution passes' accumulation (84 x (1 + 1/4 + 1/16)), an `s` save's
   PFM and PNG (16): 160 per pixel. Without it -r 16384 16384 --scale 1 asked for 40 GiB. */
#define PREVIEW_BYTES_PER_PIXEL 160.0
#define PREVIEW_MAX_IMAGE_BYTES (2.0 * 1024.0 * 1024.0 * 1024.0)
typedef struct view_params {
    bool fog;                 /* off: sigma_t 0, density kept for when it comes back on */
    float density;            /* sigma_t, the paper's lambda */
    fogrt_vec3 albedo;
    float g;
    bool nee;                 /* light sampling; false = hemisphere sampling (CLI -H) */
    bool path;                /* path tracing; false = one bounce (CLI --integrator direct) */
    bool equiangular;
    int max_depth;            /* -1 = unlimited */
    float yaw, pitch, zoom;   /* camera orbit relative to the scene's camera */
} view_params;

typedef struct preview_options {
    int width, height;        /* -r: image size in pixels */
    int scale;                /* --scale: window pixels per image pixel */
    int threads;              /* -t */
    int light_samples;        /* -l */
    int max_depth;            /* -m */
    bool hemisphere;          /* -H */
    fogrt_integrator integrator;
    fogrt_fresnel fresnel;
    uint64_t seed;
    int batch;                /* --batch: samples per pixel per batch */
    float density; bool density_set;
    fogrt_vec3 albedo; bool albedo_set;
    float g; bool g_set; bool paper_g;
    cli_common common;        /* the common flags as parsed: appendix G's --g G1,G2,W, --phase, --emission,
                                 appendix H's --medium NAME and --interface */
    float exposure;           /* --exposure, as the multiplier 2^EV */
    const char *scene;
    const char *save_dir;
    int frames;               /* --frames: scripted mode when > 0 */
    const char *keys;         /* --keys */
    const char *screenshot;   /* --screenshot */
} preview_options;


static const char *controls_text =
    "Keys and mouse:\n"
    "  h, F1     this help (printed to the terminal and drawn in the window)\n"
    "  f         fog on / off\n"
    "  q / w     Henyey-Greenstein g down / up by 0.1 (the paper's keys)\n"
    "  z / x     density (sigma_t) down / up by a factor of 1.25\n"
    "  c / v     albedo down / up by 0.05\n"
    "  n         light sampling (next-event estimation) / hemisphere sampling\n"
    "  p         path tracing / one bounce (direct lighting)\n"
    "  e         equiangular sampling of point and spot lights on / off\n"
    "  [ / ]     maximum depth down / up\n"
    "  - / +     exposure down / up by half a stop (= also works as +)\n"
    "  drag      orbit the camera around its target (left mouse button)\n"
    "  wheel     zoom (move toward / away from the target)\n"
    "  o         back to the scene's own camera\n"
    "  r         restart the accumulation\n"
    "  s         save the image as PNG and PFM, the settings in the file name\n"
    "  Esc       quit\n";

static void usage(FILE *f)
{
    fprintf(f,
        "usage: preview [options] [scene.dae | mesh.obj | mesh.ply]\n"
        "Interactive progressive preview of the embedded default scene (no scene argument), a\n"
        "CS184 COLLADA scene, or an OBJ/PLY mesh placed in the default fog-filled Cornell box.\n"
        "Long flags also take --flag=value.\n"
        "\n"
        "Flags shared with fogrt (the same meanings and limits in both):\n");
    cli_common_usage(f, 320, 240);
    fprintf(f,
        "  (-r: the window is --scale times it, and the image's buffers, 160 bytes per pixel,\n"
        "  may take at most 2 GiB; -m: the ] key goes on to unlimited depth)\n"
        "(fogrt's other flags, -s, -f, -a, --time, --target-error and the rest, do not apply:\n"
        "the preview refines until you quit.)\n"
        "\n"
        "Preview flags:\n"
        "  --scale K      window pixels per image pixel, 1..8 (default 2)\n"
        "  --batch N      samples per pixel per batch, 1..64 (default 1)\n"
        "  --save-dir DIR where `s` writes its PNG and PFM (default .)\n"
        "  --frames N     scripted mode: run N frames, each showing one more finished batch, then\n"
        "                 exit (default 0: interactive)\n"
        "  --keys LIST    scripted key presses: FRAME:KEY,... KEY is a key above (f, w, [, ...),\n"
        "                 F1, esc, drag:DX,DY (a mouse drag by DX,DY window pixels) or wheel:N\n"
        "                 e.g. --keys \"10:f,20:w,20:w,30:s,40:drag:60,0\" (default none)\n"
        "  --screenshot F write the window's content as PNG after the last frame (or at exit)\n"
        "                 (default none)\n"
        "\n%s"
        "\nSaves and screenshots are written as fogrt writes its images: a temporary file, every\n"
        "write checked, then renamed over the old file; neither may be the scene file.\n"
        "At exit a summary line gives frames/s, samples/s, input polls/s and the key-to-restart\n"
        "and key-to-new-frame latency. Exit status: 0 ok, 2 bad input, 1 no window, a render\n"
        "failure or a screenshot that could not be written (the file is named).\n",
        controls_text);
}

/* ------------------------------------------------------------------------------------------
   The render and build descs, and the image free: the only calls that depend on how
   fogrt.h spells its settings (kept together so an API change is one place to edit)
   ------------------------------------------------------------------------------------------ */
/* The render desc for the current view. */
static fogrt_render_desc preview_render_desc(const view_params *v, const preview_options *o, int width, int height)
{
    fogrt_render_desc rd = fogrt_render_defaults();
    rd.width = width; rd.height = height;
    rd.integrator = v->path ? FOGRT_INTEGRATOR_PATH : FOGRT_INTEGRATOR_DIRECT;
    rd.fresnel = o->fresnel;
    rd.max_depth = v->max_depth;
    rd.nee = v->nee;
    rd.equiangular = v->equiangular;
    rd.light_samples = o->light_samples;
    rd.seed = o->seed;
    rd.threads = o->threads;
    return rd;
}
static fogrt_result preview_build(fogrt_scene *scene)
{
    fogrt_build_desc bd = fogrt_build_defaults();
    bd.release_binary = true;               /* the preview only renders: no tree to inspect */
    return fogrt_scene_build(scene, &bd);
}
static void preview_image_free(fogrt_image *img)
{
    fogrt_image_free(img);
}

/* ------------------------------------------------------------------------------------------
   Flags
   ------------------------------------------------------------------------------------------ */
static int bad_flag(const char *flag, const char *fmt, ...)
{
    va_list ap;
    char msg[512];
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return cli_bad_flag(flag, "%s", msg);
}

static bool to_int(const char *s, int lo, int hi, int *out) { return cli_parse_int(s, lo, hi, out); }

/* The flags the preview takes, for "did you mean"; and fogrt's own, which do not apply. */
static const char *const preview_flag_names[] = {
    "-r", "-t", "-l", "-m", "-H", "-g", "--g", "--density", "--albedo", "--phase", "--emission", "--medium",
    "--interface", "--integrator", "--fresnel", "--seed", "--exposure", "-h", "--help",
    "--scale", "--batch", "--save-dir", "--frames", "--keys", "--screenshot", NULL
};
static const char *const fogrt_only_flags[] = {
    "-s", "-o", "-f", "-b", "-d", "-a", "-c", "-e", "--camera-pos", "--look-at", "--up", "--fov",
    "--cs184-framing", "--print-camera", "--fog-bounds", "--equiangular", "--lights", "--glow",
    "--footprint", "--expected-emission", "--mis", "--pixel-rates", "--bvh", "--time",
    "--target-error", "--quiet", "--log", "--reference", "--trace", NULL
};

/* Returns 0, 2 (bad input, message printed) or -1 (help printed). */
static int parse_flags(int argc, char **argv, preview_options *o)
{
    cli_arg A;
    cli_common c;
    int i, k;
    memset(o, 0, sizeof *o);
    cli_common_defaults(&c, 320, 240);
    o->scale = 2; o->batch = 1; o->save_dir = ".";
    A.argc = argc; A.argv = argv;
    for (i = 1; i < argc; i = A.i + 1) {
        const char *a, *v;
        cli_arg_at(&A, i);
        a = A.name;
#define NEED(n) do { if (!cli_has(&A, (n))) return bad_flag(a, "needs %d value%s", (n), (n) > 1 ? "s" : ""); } while (0)
        if (cli_is(&A, "-h") || cli_is(&A, "--help")) { usage(stdout); return -1; }
        if ((k = cli_common_flag(&A, &c)) >= 0) { if (k) return k; }
        else if (cli_is(&A, "--scale")) { NEED(1); v = cli_next(&A); if (!to_int(v, 1, 8, &o->scale)) return bad_flag(a, "scale must be an integer in [1, 8], got '%s'", v); }
        else if (cli_is(&A, "--batch")) { NEED(1); v = cli_next(&A); if (!to_int(v, 1, 64, &o->batch)) return bad_flag(a, "batch must be an integer in [1, 64], got '%s'", v); }
        else if (cli_is(&A, "--save-dir")) { NEED(1); o->save_dir = cli_next(&A); }
        else if (cli_is(&A, "--frames")) { NEED(1); v = cli_next(&A); if (!to_int(v, 1, 1000000, &o->frames)) return bad_flag(a, "frames must be an integer in [1, 1000000], got '%s'", v); }
        else if (cli_is(&A, "--keys")) { NEED(1); o->keys = cli_next(&A); }
        else if (cli_is(&A, "--screenshot")) {
            NEED(1);
            o->screenshot = cli_next(&A);
            if (!cli_ends_with(o->screenshot, ".png")) return bad_flag(a, "screenshot '%s' must end in .png", o->screenshot);
        }
        else if (a[0] == '-' && a[1] != '\0') {
            for (k = 0; fogrt_only_flags[k]; ++k)
                if (strcmp(a, fogrt_only_flags[k]) == 0)
                    return bad_flag(a, "does not apply to the preview, which refines until you quit (use fogrt for a fixed render)");
            return cli_unknown_flag(a, preview_flag_names);
        }
        else {
            if (o->scene) return bad_flag(argv[i], "only one scene file may be given (already have '%s')", o->scene);
            o->scene = argv[i];
        }
        if (A.inline_value && !A.inline_used) return bad_flag(a, "takes no value, got '%s'", argv[i]);
#undef NEED
    }
    o->width = c.width; o->height = c.height; o->threads = c.threads; o->light_samples = c.light_samples;
    o->max_depth = c.max_depth; o->hemisphere = c.hemisphere; o->integrator = c.integrator; o->fresnel = c.fresnel;
    o->seed = c.seed; o->density = c.fog.density; o->density_set = c.fog.density_set; o->albedo = c.fog.albedo;
    o->albedo_set = c.fog.albedo_set; o->g = c.fog.g; o->g_set = c.fog.g_set; o->paper_g = c.fog.paper_g;
    o->exposure = exp2f(c.exposure_ev);           /* --exposure is stops, as in fogrt */
    o->common = c;
    if ((k = cli_common_media_check(&c)) != 0) return k;
    if (o->keys && o->frames == 0) return bad_flag("--keys", "needs --frames (scripted mode)");
    if (o->width * o->scale > 16384 || o->height * o->scale > 16384)
        return bad_flag("--scale", "window of %dx%d pixels is too large (at most 16384 on a side)", o->width * o->scale, o->height * o->scale);
    {
        double bytes = (double)o->width * (double)o->height * PREVIEW_BYTES_PER_PIXEL;
        if (bytes > PREVIEW_MAX_IMAGE_BYTES) {
            char flag[64];
            snprintf(flag, sizeof flag, "-r %d %d", o->width, o->height);
            return bad_flag(flag, "the image buffers would need %.1f GiB (%.0f bytes per pixel), above the limit of %.1f GiB",
                            bytes / (1024.0 * 1024.0 * 1024.0), PREVIEW_BYTES_PER_PIXEL, PREVIEW_MAX_IMAGE_BYTES / (1024.0 * 1024.0 * 1024.0));
        }
    }
    return 0;
}

/* ------------------------------------------------------------------------------------------
   Scripted key presses: "FRAME:KEY,..."; KEY is one character, F1, esc, drag:DX,DY or wheel:N
   ------------------------------------------------------------------------------------------ */
enum { PK_F1 = 256, PK_ESC, PK_DRAG, PK_WHEEL };

typedef struct script_event { int frame; int key; float dx, dy; } script_event;

static bool read_number(const char **p, float *out)
{
    char *end;
    double v = strtod(*p, &end);
    if (end == *p || !isfinite(v) || fabs(v) > 1e6) return false;
    *out = (float)v;
    *p = end;
    return true;
}

/* Parses the whole list (events are then sorted by frame). Returns false with a message. */
static bool parse_script(const char *text, int frames, script_event **out, int *count, char *msg, size_t msg_size)
{
    const char *p = text;
    script_event *ev = NULL;
    int n = 0, cap = 0;
    while (*p) {
        const char *item = p;
        script_event e;
        char *end;
        long frame;
        memset(&e, 0, sizeof e);
        errno = 0;
        frame = strtol(p, &end, 10);
        if (end == p || errno != 0 || *end != ':') { snprintf(msg, msg_size, "item '%.20s': expected FRAME:KEY", item); goto fail; }
        if (frame < 1 || frame > frames) { snprintf(msg, msg_size, "item '%.20s': frame %ld outside 1..%d (--frames)", item, frame, frames); goto fail; }
        e.frame = (int)frame;
        p = end + 1;
        if (strncmp(p, "drag:", 5) == 0) {
            p += 5;
            e.key = PK_DRAG;
            if (!read_number(&p, &e.dx) || *p != ',') { snprintf(msg, msg_size, "item '%.20s': expected drag:DX,DY, each within +-1e6 pixels", item); goto fail; }
            p++;
            if (!read_number(&p, &e.dy)) { snprintf(msg, msg_size, "item '%.20s': expected drag:DX,DY, each within +-1e6 pixels", item); goto fail; }
        } else if (strncmp(p, "wheel:", 6) == 0) {
            p += 6;
            e.key = PK_WHEEL;
            if (!read_number(&p, &e.dy)) { snprintf(msg, msg_size, "item '%.20s': expected wheel:N, N within +-1e6", item); goto fail; }
        } else if ((strncmp(p, "F1", 2) == 0 || strncmp(p, "f1", 2) == 0) && (p[2] == ',' || p[2] == '\0')) {
            e.key = PK_F1; p += 2;
        } else if (strncmp(p, "esc", 3) == 0 && (p[3] == ',' || p[3] == '\0')) {
            e.key = PK_ESC; p += 3;
        } else if (*p && strchr("hfqwzxcvnpe[]-+=ros", *p) && (p[1] == ',' || p[1] == '\0')) {
            e.key = (unsigned char)*p; p += 1;
        } else {
            snprintf(msg, msg_size, "item '%.20s': unknown key (see the list in preview -h)", item);
            goto fail;
        }
        if (*p == ',') { p++; if (!*p) { snprintf(msg, msg_size, "trailing ','"); goto fail; } }
        else if (*p) { snprintf(msg, msg_size, "item '%.20s': expected ',' after the key", item); goto fail; }
        if (n == cap) {
            script_event *grown;
            cap = cap ? 2 * cap : 16;
            grown = (script_event *)realloc(ev, sizeof *ev * (size_t)cap);
            if (!grown) { snprintf(msg, msg_size, "out of memory"); goto fail; }
            ev = grown;
        }
        ev[n++] = e;
    }
    {   /* stable insertion sort by frame: events of one frame keep their order */
        int i, j;
        for (i = 1; i < n; ++i) {
            script_event t = ev[i];
            for (j = i; j > 0 && ev[j - 1].frame > t.frame; --j) ev[j] = ev[j - 1];
            ev[j] = t;
        }
    }
    *out = ev;
    *count = n;
    return true;
fail:
    free(ev);
    return false;
}

/* ------------------------------------------------------------------------------------------
   Shared state between the main (input, drawing) thread and the render worker
   ------------------------------------------------------------------------------------------ */
static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct latency { int n; double sum, max; } latency;
static void latency_add(latency *l, double seconds)
{
    l->n++;
    l->sum += seconds;
    if (seconds > l->max) l->max = seconds;
}

typedef struct app {
    preview_options opt;
    fogrt_scene *scene;
    fogrt_camera_desc base_camera;
    fogrt_vec3 chroma;         /* chromatic fog (--density R,G,B): sigma_t per channel over the density; else 0 */
    char scene_name[64];

    pthread_mutex_t mu;
    pthread_cond_t cv;
    /* main -> worker (under mu) */
    view_params want;          /* the parameters asked for */
    unsigned gen;              /* bumped on every change */
    double change_time;        /* when gen last changed */
    bool quit;
    uint64_t batches_allowed;  /* scripted mode: the worker renders only this many batches */
    /* worker -> main (under mu) */
    bool busy;                 /* inside fogrt_render */
    uint64_t batches_done;     /* finished batches (of any generation) */
    float *shown;              /* the last finished batch, resolved: linear RGB */
    int shown_w, shown_h;
    unsigned shown_gen;
    view_params shown_params;
    uint64_t shown_spp;        /* 0: one of the quick low-resolution passes */
    double shown_seconds;      /* since the restart of its generation */
    double shown_samples;      /* camera samples since that restart */
    double shown_error;        /* fogrt_image_error, -1 unknown */
    uint64_t shown_serial;     /* bumped on every new image */
    uint64_t samples_total;    /* in finished batches */
    double render_seconds;     /* inside fogrt_render, finished or cancelled */
    unsigned cancels;          /* renders stopped by a change */
    latency key_to_restart;
    bool failed;
    char failure[256];

    /* main thread only */
    GLFWwindow *window;
    GLuint texture;
    float *rgb;                /* copy of shown */
    unsigned char *rgb8;       /* tonemapped */
    int rgb_w, rgb_h;
    unsigned rgb_gen;
    view_params rgb_params;
    uint64_t rgb_spp;
    double rgb_seconds, rgb_samples, rgb_error;
    uint64_t drawn_serial;
    float exposure;
    bool help;
    bool redraw;               /* exposure or overlay changed: draw again without a new image */
    bool dragging;
    double drag_x, drag_y;
    bool save_pending;
    unsigned first_frame_gen;  /* the generation whose first frame is awaited for latency */
    bool awaiting_frame;
    double awaited_change_time;
    latency key_to_frame;
    uint64_t frames;           /* new images drawn */
    double t_start, t_first_frame, t_last_frame;
    double last_poll, max_poll_gap, max_startup_gap;
    uint64_t polls;
    double last_title;
} app;

/* ------------------------------------------------------------------------------------------
   The scene: loaded with the same calls as the fogrt command
   ------------------------------------------------------------------------------------------ */
static void log_line(fogrt_log_level level, const char *message, void *user)
{
    (void)user;
    fprintf(stderr, "preview: %s%s\n", level == FOGRT_LOG_ERROR ? "error: " : level == FOGRT_LOG_WARNING ? "warning: " : "", message);
}
static void load_note(fogrt_log_level level, const char *message, void *user)
{
    (void)level; (void)user;
    fprintf(stderr, "preview: %s\n", message);   /* already "file:line: warning: ..." */
}

/* Returns 0 or an exit status with one message printed. Fills a->scene, a->want, base camera. */
static int load_scene(app *a)
{
    const preview_options *o = &a->opt;
    fogrt_scene_desc sd;
    fogrt_load_options lo;
    fogrt_load_report rep;
    fogrt_medium_desc md;
    fogrt_result r;
    bool is_dae = false;
    view_params *v = &a->want;
    cli_shapes shapes;
    int st;

    memset(&sd, 0, sizeof sd);
    sd.logger.func = log_line;
    if (fogrt_scene_create(&sd, &a->scene) != FOGRT_RESULT_OK) { fprintf(stderr, "preview: out of memory\n"); return 1; }
    memset(&lo, 0, sizeof lo);
    lo.image_width = o->width; lo.image_height = o->height;
    lo.logger.func = load_note;
    cli_shapes_init(&shapes, o->scene);
    if (o->common.media_count) { lo.on_shape = cli_on_shape; lo.on_shape_user = &shapes; }   /* --medium's names */
    if (o->scene) {
        const char *kind = cli_sniff_kind(o->scene, false);
        is_dae = cli_ends_with(o->scene, ".dae");
        if (kind) {
            fprintf(stderr, "preview: %s: %s, not a scene: the preview reads .dae, .obj, .ply\n", o->scene, kind);
            return 2;
        }
        if (!is_dae && !cli_ends_with(o->scene, ".obj") && !cli_ends_with(o->scene, ".ply")) {
            fprintf(stderr, "preview: %s: unknown scene type: the preview reads .dae, .obj, .ply\n", o->scene);
            return 2;
        }
    }
    if (!is_dae) {   /* the default scene, and the box an OBJ/PLY mesh is placed in */
        r = fogrt_scene_add_default(a->scene);
        if (r) { fprintf(stderr, "preview: default scene: %s\n", fogrt_result_string(r)); return 1; }
    }
    if (o->scene) {
        r = fogrt_load_file(a->scene, o->scene, &lo, &rep);
        if (r) {
            if (rep.line > 0) fprintf(stderr, "preview: %s:%d: %s\n", rep.file, rep.line, rep.message);
            else fprintf(stderr, "preview: %s: %s\n", rep.file, rep.message[0] ? rep.message : fogrt_result_string(r));
            return r == FOGRT_RESULT_OUT_OF_MEMORY ? 1 : 2;
        }
    }
    st = cli_apply_media(a->scene, &a->opt.common, &shapes);   /* --medium NAME ... */
    cli_shapes_free(&shapes);
    if (st) return st;
    {   /* a short name for saved files: the scene file's base name without extension */
        const char *base = o->scene ? o->scene : "default";
        const char *slash = strrchr(base, '/');
        size_t k = 0;
        if (slash) base = slash + 1;
        for (; *base && *base != '.' && k + 1 < sizeof a->scene_name; ++base) {
            char c = *base;
            a->scene_name[k++] = ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_') ? c : '_';
        }
        a->scene_name[k] = '\0';
        if (k == 0) strcpy(a->scene_name, "scene");
    }

    /* The fog: the scene's own, changed by the flags (as the fogrt command does) */
    fogrt_scene_get_medium(a->scene, &md);
    if (is_dae && md.sigma_t == 0.0f) { md.albedo.x = md.albedo.y = md.albedo.z = 0.9f; md.g = 0.0f; }
    if (o->density_set) md.sigma_t = o->density;
    else if (o->paper_g && md.sigma_t == 0.0f) md.sigma_t = 0.2f;
    if (o->albedo_set) md.albedo = o->albedo;
    if (o->g_set) md.g = o->g;
    cli_common_media_apply(&o->common.fog, &md);  /* --density R,G,B, --g G1,G2,W, --phase, --emission */
    r = fogrt_scene_set_medium(a->scene, &md);
    if (r) { fprintf(stderr, "preview: --density/--albedo/--g/--phase/--emission: %s\n", fogrt_result_string(r)); return 2; }
    r = preview_build(a->scene);
    if (r && o->common.media_count && r != FOGRT_RESULT_OUT_OF_MEMORY)
        return cli_media_build_failed(&o->common, fogrt_scene_last_error(a->scene), r);
    if (r) {
        fprintf(stderr, "preview: %s: %s\n", o->scene ? o->scene : "default scene", fogrt_result_string(r));
        return r == FOGRT_RESULT_EMPTY_SCENE ? 2 : 1;
    }
    fogrt_scene_get_camera(a->scene, &a->base_camera);

    fogrt_scene_get_medium(a->scene, &md);        /* as stored: equal channels are grey fog */
    memset(&a->chroma, 0, sizeof a->chroma);
    if (md.sigma_t > 0.0f && (md.sigma_t_rgb.x != 0.0f || md.sigma_t_rgb.y != 0.0f || md.sigma_t_rgb.z != 0.0f)) {
        a->chroma.x = md.sigma_t_rgb.x / md.sigma_t; a->chroma.y = md.sigma_t_rgb.y / md.sigma_t; a->chroma.z = md.sigma_t_rgb.z / md.sigma_t;
    }
    memset(v, 0, sizeof *v);
    v->fog = md.sigma_t > 0.0f;
    v->density = md.sigma_t > 0.0f ? md.sigma_t : 0.2f;
    v->albedo = md.albedo;
    v->g = md.g;
    v->nee = !o->hemisphere;
    v->path = o->integrator != FOGRT_INTEGRATOR_DIRECT;
    v->equiangular = true;
    v->max_depth = o->max_depth;
    v->zoom = 1.0f;
    return 0;
}

static fogrt_vec3 v3(float x, float y, float z) { fogrt_vec3 r; r.x = x; r.y = y; r.z = z; return r; }

/* The scene's camera orbited around its target by (yaw, pitch) and moved by zoom. */
static fogrt_camera_desc orbit_camera(const fogrt_camera_desc *base, const view_params *v)
{
    fogrt_camera_desc c = *base;
    float ox = base->position.x - base->look_at.x, oy = base->position.y - base->look_at.y, oz = base->position.z - base->look_at.z;
    float r = sqrtf(ox * ox + oy * oy + oz * oz);
    float yaw = atan2f(ox, oz) + v->yaw;
    float pitch = asinf(fmaxf(-1.0f, fminf(1.0f, oy / r))) + v->pitch;
    const float limit = 1.5f;   /* about 86 degrees: never straight up or down */
    if (pitch > limit) pitch = limit;
    if (pitch < -limit) pitch = -limit;
    r *= v->zoom;
    c.position = v3(base->look_at.x + r * cosf(pitch) * sinf(yaw), base->look_at.y + r * sinf(pitch),
                    base->look_at.z + r * cosf(pitch) * cosf(yaw));
    c.up = v3(0.0f, 1.0f, 0.0f);
    c.focal_distance = 0.0f;     /* in focus at the target */
    return c;
}

static bool same_medium(const view_params *a, const view_params *b)
{
    return a->fog == b->fog && a->density == b->density && a->g == b->g &&
           a->albedo.x == b->albedo.x && a->albedo.y == b->albedo.y && a->albedo.z == b->albedo.z;
}
static bool same_camera(const view_params *a, const view_params *b)
{
    return a->yaw == b->yaw && a->pitch == b->pitch && a->zoom == b->zoom;
}

/* ------------------------------------------------------------------------------------------
   The render worker
   ------------------------------------------------------------------------------------------ */
typedef struct cancel_ctx { app *a; unsigned gen; } cancel_ctx;

/* Called by fogrt_render between row blocks: stop when the parameters changed or we quit. */
static bool keep_going(const fogrt_progress *p, void *user)
{
    cancel_ctx *c = (cancel_ctx *)user;
    bool go;
    (void)p;
    pthread_mutex_lock(&c->a->mu);
    go = !c->a->quit && c->a->gen == c->gen;
    pthread_mutex_unlock(&c->a->mu);
    return go;
}

static void worker_fail(app *a, const char *what, fogrt_result r)
{
    pthread_mutex_lock(&a->mu);
    a->failed = true;
    a->quit = true;
    snprintf(a->failure, sizeof a->failure, "%s: %s", what, fogrt_result_string(r));
    pthread_cond_broadcast(&a->cv);
    pthread_mutex_unlock(&a->mu);
    glfwPostEmptyEvent();
}

static void *worker_main(void *arg)
{
    app *a = (app *)arg;
    const preview_options *o = &a->opt;
    /* pass[0] and pass[1]: the quick 1/4 and 1/2 resolution passes (when the image is large
       enough for them); pass[2]: the full image, where samples accumulate */
    static const int pass_scale[3] = {4, 2, 1};
    fogrt_image pass[3];
    int first_pass = 0, level = 0, k;
    bool have_view = false;
    view_params cur;
    unsigned gen = 0;
    uint64_t spp = 0;
    double t_gen = 0.0, gen_samples = 0.0;
    fogrt_result r;

#if defined(__linux__)
    /* The render threads (this one and the OpenMP threads it starts, which inherit it) run at
       a lower priority, so the input and drawing thread gets a core the moment it wakes. */
    setpriority(PRIO_PROCESS, (id_t)syscall(SYS_gettid), 5);
#endif
    cli_thread_default(o->threads);
    memset(&cur, 0, sizeof cur);
    memset(pass, 0, sizeof pass);
    while (first_pass < 2 && (o->width / pass_scale[first_pass] < 32 || o->height / pass_scale[first_pass] < 24)) first_pass++;
    for (k = first_pass; k < 3; ++k)
        if (fogrt_image_alloc(&pass[k], o->width / pass_scale[k], o->height / pass_scale[k], NULL) != FOGRT_RESULT_OK) {
            worker_fail(a, "image", FOGRT_RESULT_OUT_OF_MEMORY);
            for (k = first_pass; k < 3; ++k) preview_image_free(&pass[k]);
            return NULL;
        }
    for (;;) {
        view_params next;
        unsigned next_gen;
        double change_time;
        fogrt_image *img;
        fogrt_render_desc rd;
        fogrt_render_stats st;
        cancel_ctx cc;
        int spp_batch;
        double t0;

        pthread_mutex_lock(&a->mu);
        while (!a->quit && o->frames > 0 && a->batches_done >= a->batches_allowed)
            pthread_cond_wait(&a->cv, &a->mu);
        if (a->quit) { pthread_mutex_unlock(&a->mu); break; }
        next = a->want;
        next_gen = a->gen;
        change_time = a->change_time;
        a->busy = true;
        pthread_mutex_unlock(&a->mu);

        /* A new generation: apply the changes to the scene, clear the accumulation */
        if (!have_view || next_gen != gen) {
            if (!have_view || !same_medium(&cur, &next)) {
                fogrt_medium_desc md;
                fogrt_scene_get_medium(a->scene, &md);   /* the rest (box, phase, emission) as set */
                md.sigma_t = next.fog ? next.density : 0.0f;
                md.sigma_t_rgb.x = md.sigma_t * a->chroma.x;     /* chromatic: the density scales every channel */
                md.sigma_t_rgb.y = md.sigma_t * a->chroma.y;
                md.sigma_t_rgb.z = md.sigma_t * a->chroma.z;
                md.albedo = next.albedo;
                md.g = next.g;
                r = fogrt_scene_set_medium(a->scene, &md);
                if (!r) r = preview_build(a->scene);
                if (r) { worker_fail(a, "fog parameters", r); break; }
            }
            if (!have_view || !same_camera(&cur, &next)) {
                fogrt_camera_desc cam = orbit_camera(&a->base_camera, &next);
                r = fogrt_scene_set_camera(a->scene, &cam);
                if (r) { worker_fail(a, "camera", r); break; }
            }
            cur = next;
            gen = next_gen;
            have_view = true;
            for (k = first_pass; k < 3; ++k) fogrt_image_clear(&pass[k]);
            level = first_pass;
            spp = 0;
            gen_samples = 0.0;
            t_gen = now_seconds();
            pthread_mutex_lock(&a->mu);
            if (change_time > 0.0) latency_add(&a->key_to_restart, t_gen - change_time);
            pthread_mutex_unlock(&a->mu);
        }

        /* One batch: the quick passes first, then full-resolution samples */
        img = &pass[level];
        spp_batch = level == 2 ? o->batch : 1;
        rd = preview_render_desc(&cur, o, img->width, img->height);
        cc.a = a; cc.gen = gen;
        rd.progress = keep_going;
        rd.user_data = &cc;
        t0 = now_seconds();
        r = fogrt_render(a->scene, &rd, img, spp_batch, &st);
        t0 = now_seconds() - t0;
        pthread_mutex_lock(&a->mu);
        a->render_seconds += t0;
        pthread_mutex_unlock(&a->mu);
        if (r == FOGRT_RESULT_CANCELLED) {
            pthread_mutex_lock(&a->mu);
            a->busy = false;
            a->cancels++;
            pthread_cond_broadcast(&a->cv);
            pthread_mutex_unlock(&a->mu);
            continue;
        }
        if (r) { worker_fail(a, "render", r); break; }
        gen_samples += (double)st.camera_rays;
        if (level == 2) spp += (uint64_t)spp_batch;
        else level++;

        /* Publish it (only if it still shows what is asked for) */
        {
            fogrt_error_estimate ee;
            double err = -1.0;
            if (img == &pass[2] && spp >= 2) { fogrt_image_error(img, &ee); err = ee.relative_error; }
            pthread_mutex_lock(&a->mu);
            a->samples_total += st.camera_rays;
            a->batches_done++;
            a->busy = false;
            if (a->gen == gen) {
                fogrt_image_resolve(img, a->shown);
                a->shown_w = img->width; a->shown_h = img->height;
                a->shown_gen = gen;
                a->shown_params = cur;
                a->shown_spp = img == &pass[2] ? spp : 0;
                a->shown_seconds = now_seconds() - t_gen;
                a->shown_samples = gen_samples;
                a->shown_error = err;
                a->shown_serial++;
            }
            pthread_cond_broadcast(&a->cv);
            pthread_mutex_unlock(&a->mu);
            glfwPostEmptyEvent();
        }
    }
    for (k = first_pass; k < 3; ++k) preview_image_free(&pass[k]);
    return NULL;
}

/* ------------------------------------------------------------------------------------------
   Input: every key goes through apply_key (the window's callbacks and the script alike)
   ------------------------------------------------------------------------------------------ */
static const int depth_steps[] = {0, 1, 2, 3, 4, 5, 6, 8, 10, 12, 16, 24, 32, 48, 64, 128, 256, -1};
#define DEPTH_STEPS ((int)(sizeof depth_steps / sizeof depth_steps[0]))

/* The next step up or down from depth; -1 (unlimited) ranks above every number. */
static long depth_rank(int d) { return d < 0 ? 1L << 40 : (long)d; }
static int depth_step(int depth, int dir)
{
    int i;
    if (dir > 0) {
        for (i = 0; i < DEPTH_STEPS; ++i)
            if (depth_rank(depth_steps[i]) > depth_rank(depth))
                return depth_steps[i];
    } else {
        for (i = DEPTH_STEPS - 1; i >= 0; --i)
            if (depth_rank(depth_steps[i]) < depth_rank(depth))
                return depth_steps[i];
    }
    return depth;
}

static float clampf(float x, float lo, float hi) { return x < lo ? lo : x > hi ? hi : x; }
static float round3(float x) { return floorf(x * 1000.0f + 0.5f) / 1000.0f; }

static void describe(const view_params *v, float exposure, char *buf, size_t size)
{
    char alb[48], depth[16];
    if (v->albedo.x == v->albedo.y && v->albedo.y == v->albedo.z) snprintf(alb, sizeof alb, "%.2f", (double)v->albedo.x);
    else snprintf(alb, sizeof alb, "%.2f,%.2f,%.2f", (double)v->albedo.x, (double)v->albedo.y, (double)v->albedo.z);
    if (v->max_depth < 0) snprintf(depth, sizeof depth, "unlimited");
    else snprintf(depth, sizeof depth, "%d", v->max_depth);
    snprintf(buf, size, "g %.2f, density %.3g%s, albedo %s | %s, %s, equiangular %s, depth %s, exposure %+.1f EV",
             (double)v->g, (double)v->density, v->fog ? "" : " (fog off)", alb,
             v->path ? "path" : "one bounce", v->nee ? "light sampling" : "hemisphere sampling",
             v->equiangular ? "on" : "off", depth, log2((double)exposure));
}

static void print_help(const app *a)
{
    char d[256];
    describe(&a->want, a->exposure, d, sizeof d);
    printf("%snow: %s\n", controls_text, d);
    fflush(stdout);
}

/* Changes the asked-for parameters (under the lock) and restarts. */
static void change(app *a, void (*edit)(view_params *, float, float), float x, float y)
{
    pthread_mutex_lock(&a->mu);
    edit(&a->want, x, y);
    a->gen++;
    a->change_time = now_seconds();
    pthread_cond_broadcast(&a->cv);
    pthread_mutex_unlock(&a->mu);
}
static void edit_none(view_params *v, float x, float y) { (void)v; (void)x; (void)y; }
static void edit_fog(view_params *v, float x, float y) { (void)x; (void)y; v->fog = !v->fog; }
static void edit_g(view_params *v, float x, float y) { (void)y; v->g = round3(clampf(v->g + x, -0.99f, 0.99f)); }
static void edit_density(view_params *v, float x, float y)
{
    (void)y;
    v->fog = true;
    v->density = clampf(v->density * x, 0.001f, 100.0f);
    v->density = v->density >= 0.1f ? round3(v->density) : v->density;
}
static void edit_albedo(view_params *v, float x, float y)
{
    (void)y;
    v->albedo.x = round3(clampf(v->albedo.x + x, 0.0f, 1.0f));
    v->albedo.y = round3(clampf(v->albedo.y + x, 0.0f, 1.0f));
    v->albedo.z = round3(clampf(v->albedo.z + x, 0.0f, 1.0f));
}
static void edit_nee(view_params *v, float x, float y) { (void)x; (void)y; v->nee = !v->nee; }
static void edit_path(view_params *v, float x, float y) { (void)x; (void)y; v->path = !v->path; }
static void edit_equiangular(view_params *v, float x, float y) { (void)x; (void)y; v->equiangular = !v->equiangular; }
static void edit_depth(view_params *v, float x, float y) { (void)y; v->max_depth = depth_step(v->max_depth, x > 0 ? 1 : -1); }
static void edit_orbit(view_params *v, float x, float y)
{
    const float per_pixel = 0.005f;   /* radians per window pixel: across a 640-pixel window ~180 degrees */
    v->yaw -= x * per_pixel;
    v->pitch = clampf(v->pitch + y * per_pixel, -3.0f, 3.0f);
}
static void edit_zoom(view_params *v, float x, float y) { (void)x; v->zoom = clampf(v->zoom * powf(0.9f, y), 0.05f, 20.0f); }
static void edit_camera_reset(view_params *v, float x, float y) { (void)x; (void)y; v->yaw = v->pitch = 0.0f; v->zoom = 1.0f; }

static void apply_key(app *a, int key, float dx, float dy)
{
    switch (key) {
    case 'h': case PK_F1: a->help = !a->help; a->redraw = true; print_help(a); break;
    case 'f': change(a, edit_fog, 0, 0); break;
    case 'q': change(a, edit_g, -0.1f, 0); break;
    case 'w': change(a, edit_g, 0.1f, 0); break;
    case 'z': change(a, edit_density, 1.0f / 1.25f, 0); break;
    case 'x': change(a, edit_density, 1.25f, 0); break;
    case 'c': change(a, edit_albedo, -0.05f, 0); break;
    case 'v': change(a, edit_albedo, 0.05f, 0); break;
    case 'n': change(a, edit_nee, 0, 0); break;
    case 'p': change(a, edit_path, 0, 0); break;
    case 'e': change(a, edit_equiangular, 0, 0); break;
    case '[': change(a, edit_depth, -1, 0); break;
    case ']': change(a, edit_depth, 1, 0); break;
    case '-': a->exposure = clampf(a->exposure / sqrtf(2.0f), 1.0f / 1024.0f, 1024.0f); a->redraw = true; break;
    case '+': case '=': a->exposure = clampf(a->exposure * sqrtf(2.0f), 1.0f / 1024.0f, 1024.0f); a->redraw = true; break;
    case 'o': change(a, edit_camera_reset, 0, 0); break;
    case 'r': change(a, edit_none, 0, 0); break;
    case 's': a->save_pending = true; break;
    case PK_ESC: glfwSetWindowShouldClose(a->window, GLFW_TRUE); break;
    case PK_DRAG: if (dx != 0.0f || dy != 0.0f) change(a, edit_orbit, dx, dy); break;
    case PK_WHEEL: if (dy != 0.0f) change(a, edit_zoom, 0, dy); break;
    default: break;
    }
}

static void on_char(GLFWwindow *w, unsigned int codepoint)
{
    app *a = (app *)glfwGetWindowUserPointer(w);
    if (codepoint < 128) apply_key(a, (int)codepoint, 0, 0);
}
static void on_key(GLFWwindow *w, int key, int scancode, int action, int mods)
{
    app *a = (app *)glfwGetWindowUserPointer(w);
    (void)scancode; (void)mods;
    if (action == GLFW_RELEASE) return;
    if (key == GLFW_KEY_F1) apply_key(a, PK_F1, 0, 0);
    else if (key == GLFW_KEY_ESCAPE) apply_key(a, PK_ESC, 0, 0);
    else if (key == GLFW_KEY_KP_ADD) apply_key(a, '+', 0, 0);
    else if (key == GLFW_KEY_KP_SUBTRACT) apply_key(a, '-', 0, 0);
}
static void on_mouse_button(GLFWwindow *w, int button, int action, int mods)
{
    app *a = (app *)glfwGetWindowUserPointer(w);
    (void)mods;
    if (button != GLFW_MOUSE_BUTTON_LEFT) return;
    a->dragging = action == GLFW_PRESS;
    glfwGetCursorPos(w, &a->drag_x, &a->drag_y);
}
static void on_cursor(GLFWwindow *w, double x, double y)
{
    app *a = (app *)glfwGetWindowUserPointer(w);
    if (!a->dragging) return;
    apply_key(a, PK_DRAG, (float)(x - a->drag_x), (float)(y - a->drag_y));
    a->drag_x = x; a->drag_y = y;
}
static void on_scroll(GLFWwindow *w, double xoff, double yoff)
{
    app *a = (app *)glfwGetWindowUserPointer(w);
    (void)xoff;
    apply_key(a, PK_WHEEL, 0, (float)yoff);
}
/* Before the window is open the last GLFW message goes into the one "cannot open" line. */
static bool glfw_report = false;
static char glfw_message[256];
static void on_glfw_error(int code, const char *message)
{
    if (glfw_report) fprintf(stderr, "preview: GLFW error %d: %s\n", code, message);
    else snprintf(glfw_message, sizeof glfw_message, "%s", message);
}

/* Ctrl-C / SIGTERM end the preview like closing the window (the summary is still printed). */
static volatile sig_atomic_t stop_signal = 0;
static void on_signal(int sig) { stop_signal = sig; }

/* One event poll; counts how often input is handled and the longest gap between polls. */
static void poll_events(app *a, double timeout)
{
    double t;
    if (timeout > 0.0) glfwWaitEventsTimeout(timeout);
    else glfwPollEvents();
    if (stop_signal) glfwSetWindowShouldClose(a->window, GLFW_TRUE);
    t = now_seconds();
    /* start-up (window, the first frames: Mesa compiles its shaders on first use) apart */
    if (a->polls > 0 && a->frames < 3 && t - a->last_poll > a->max_startup_gap) a->max_startup_gap = t - a->last_poll;
    if (a->polls > 0 && a->frames >= 3 && t - a->last_poll > a->max_poll_gap) a->max_poll_gap = t - a->last_poll;
    a->last_poll = t;
    a->polls++;
}

/* ------------------------------------------------------------------------------------------
   Drawing, the title bar, saving
   ------------------------------------------------------------------------------------------ */
/* Takes the newest image from the worker. Returns true when there is a new one. */
static bool take_image(app *a)
{
    bool fresh;
    pthread_mutex_lock(&a->mu);
    fresh = a->shown_serial != 0 && a->shown_serial != a->drawn_serial;
    if (fresh) {
        memcpy(a->rgb, a->shown, sizeof(float) * 3 * (size_t)a->shown_w * (size_t)a->shown_h);
        a->rgb_w = a->shown_w; a->rgb_h = a->shown_h;
        a->rgb_gen = a->shown_gen;
        a->rgb_params = a->shown_params;
        a->rgb_spp = a->shown_spp;
        a->rgb_seconds = a->shown_seconds;
        a->rgb_samples = a->shown_samples;
        a->rgb_error = a->shown_error;
        a->drawn_serial = a->shown_serial;
    }
    pthread_mutex_unlock(&a->mu);
    return fresh;
}

/* Text with stb_easy_font (quads, no texture) on a dark panel. Lines that start with two
   spaces are a table: the text after column 12 is drawn aligned at tab_x. */
static void draw_text(float x, float y, float scale, const char *text, float tab_x, float alpha)
{
    static char vbuf[400000];
    char line[256];
    const char *p = text;
    float width = 0.0f, height = 0.0f, ly;
    int pass;
    for (pass = 0; pass < 2; ++pass) {   /* 0: measure the panel, 1: draw */
        p = text;
        ly = 0.0f;
        glPushMatrix();
        glTranslatef(x, y, 0.0f);
        glScalef(scale, scale, 1.0f);
        if (pass == 1) {
            glDisable(GL_TEXTURE_2D);
            glEnable(GL_BLEND);
            glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
            glColor4f(0.0f, 0.0f, 0.0f, alpha);
            glBegin(GL_QUADS);
            glVertex2f(-4.0f, -4.0f); glVertex2f(width + 4.0f, -4.0f);
            glVertex2f(width + 4.0f, height + 2.0f); glVertex2f(-4.0f, height + 2.0f);
            glEnd();
            glDisable(GL_BLEND);
            glColor3f(1.0f, 1.0f, 0.85f);
            glEnableClientState(GL_VERTEX_ARRAY);
        }
        while (*p) {
            size_t n = strcspn(p, "\n");
            bool table = n > 12 && p[0] == ' ' && p[1] == ' ';
            int part;
            if (n >= sizeof line) n = sizeof line - 1;
            for (part = 0; part < (table ? 2 : 1); ++part) {
                float px = table && part == 1 ? tab_x : 0.0f, w;
                size_t from = table && part == 1 ? 12 : 0, to = table && part == 0 ? 12 : n;
                memcpy(line, p + from, to - from);
                line[to - from] = '\0';
                w = px + (float)stb_easy_font_width(line);
                if (w > width) width = w;
                if (pass == 1) {
                    int quads = stb_easy_font_print(px, ly, line, NULL, vbuf, (int)sizeof vbuf);
                    glVertexPointer(2, GL_FLOAT, 16, vbuf);
                    glDrawArrays(GL_QUADS, 0, quads * 4);
                }
            }
            ly += 12.0f;
            p += strcspn(p, "\n");
            if (*p == '\n') p++;
        }
        height = ly;
        if (pass == 1) glDisableClientState(GL_VERTEX_ARRAY);
        glPopMatrix();
    }
}

static void draw(app *a)
{
    int fw, fh, ww, wh;
    float sx, sy;
    glfwGetFramebufferSize(a->window, &fw, &fh);
    glfwGetWindowSize(a->window, &ww, &wh);
    glViewport(0, 0, fw, fh);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    if (a->rgb_w > 0) {
        float img_aspect = (float)a->rgb_w / (float)a->rgb_h, win_aspect = (float)fw / (float)(fh > 0 ? fh : 1);
        fogrt_tonemap_rgb8(a->rgb, a->rgb_w, a->rgb_h, log2f(a->exposure), FOGRT_TONEMAP_SRGB, a->rgb8);
        glBindTexture(GL_TEXTURE_2D, a->texture);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB, a->rgb_w, a->rgb_h, 0, GL_RGB, GL_UNSIGNED_BYTE, a->rgb8);
        /* letterbox: keep the image's aspect in any window shape */
        sx = 1.0f; sy = 1.0f;
        if (win_aspect > img_aspect) sx = img_aspect / win_aspect;
        else sy = win_aspect / img_aspect;
        glMatrixMode(GL_PROJECTION); glLoadIdentity();
        glMatrixMode(GL_MODELVIEW); glLoadIdentity();
        glEnable(GL_TEXTURE_2D);
        glColor3f(1.0f, 1.0f, 1.0f);
        glBegin(GL_QUADS);   /* texture row 0 is the image's top row */
        glTexCoord2f(0.0f, 1.0f); glVertex2f(-sx, -sy);
        glTexCoord2f(1.0f, 1.0f); glVertex2f(sx, -sy);
        glTexCoord2f(1.0f, 0.0f); glVertex2f(sx, sy);
        glTexCoord2f(0.0f, 0.0f); glVertex2f(-sx, sy);
        glEnd();
        glDisable(GL_TEXTURE_2D);
    }
    if (a->help) {
        char status[300], text[2048];
        float scale = ww >= 900 ? 2.0f : 1.0f;
        describe(&a->want, a->exposure, status, sizeof status);
        snprintf(text, sizeof text, "%s\nnow: %s", controls_text, status);
        glMatrixMode(GL_PROJECTION); glLoadIdentity();
        glOrtho(0.0, (double)ww, (double)wh, 0.0, -1.0, 1.0);   /* window pixels, y down */
        glMatrixMode(GL_MODELVIEW); glLoadIdentity();
        draw_text(10.0f, 10.0f, scale, text, 60.0f, 0.7f);
    }
}

static void update_title(app *a)
{
    char title[512], d[256], err[32];
    double rate = a->rgb_seconds > 0.0 ? a->rgb_samples / a->rgb_seconds : 0.0;
    if (a->rgb_error >= 0.0) snprintf(err, sizeof err, "%.1f%%", 100.0 * a->rgb_error);
    else snprintf(err, sizeof err, "?");
    describe(&a->rgb_params, a->exposure, d, sizeof d);
    snprintf(title, sizeof title, "fogrt preview - %llu spp%s, %.1f s, %.3g M samples/s, error %s | %s",
             (unsigned long long)a->rgb_spp, a->rgb_spp == 0 ? " (quick low-res pass)" : "", a->rgb_seconds, rate * 1e-6, err, d);
    glfwSetWindowTitle(a->window, title);
    a->last_title = now_seconds();
}

/* One output as fogrt writes it (examples/cli_common.h): never the scene file, written to a
   temporary file with every write checked, then renamed over the old file. */
static bool write_file(const app *a, const char *flag, const char *path, const cli_membuf *b)
{
    cli_output out;
    if (b->failed) { fprintf(stderr, "preview: %s %s: could not encode the image (out of memory)\n", flag, path); return false; }
    if (a->opt.scene) {
        cli_file in, o;
        cli_identify(&in, "", a->opt.scene);
        cli_identify(&o, flag, path);
        if (cli_check_aliases(&in, 1, &o, 1) != 0) return false;
    }
    return cli_prepare_output(&out, flag, path) && cli_write_output(&out, b);
}

/* s: the shown image as PNG (tonemapped) and PFM (linear), the settings in the name.
   Returns false when nothing was saved (the message names the file): a scripted run then
   exits with status 1, an interactive one goes on. */
static bool save_image(app *a)
{
    char name[512], path[1024];
    const view_params *v = &a->rgb_params;
    cli_membuf b;
    size_t n;
    bool ok;
    if (a->rgb_spp == 0) { fprintf(stderr, "preview: s: nothing to save yet (no full-resolution sample)\n"); return false; }
    snprintf(name, sizeof name, "fogrt-preview_%s_g%.2f_density%.3g%s_albedo%.2f_%s_%s_eq%s_depth%d_%dx%d_%llu-spp",
             a->scene_name, (double)v->g, (double)v->density, v->fog ? "" : "-off", (double)v->albedo.x,
             v->path ? "path" : "direct", v->nee ? "nee" : "hemisphere", v->equiangular ? "on" : "off",
             v->max_depth, a->rgb_w, a->rgb_h, (unsigned long long)a->rgb_spp);
    snprintf(path, sizeof path, "%s/%s.pfm", a->opt.save_dir, name);
    memset(&b, 0, sizeof b);
    cli_encode_pfm(a->rgb_w, a->rgb_h, a->rgb, &b);
    ok = write_file(a, "s:", path, &b);
    free(b.data);
    if (!ok) return false;
    n = strlen(path);
    memcpy(path + n - 4, ".png", 4);
    fogrt_tonemap_rgb8(a->rgb, a->rgb_w, a->rgb_h, log2f(a->exposure), FOGRT_TONEMAP_SRGB, a->rgb8);
    memset(&b, 0, sizeof b);
    if (!stbi_write_png_to_func(cli_membuf_stb, &b, a->rgb_w, a->rgb_h, 3, a->rgb8, a->rgb_w * 3)) b.failed = true;
    ok = write_file(a, "s:", path, &b);
    free(b.data);
    if (!ok) return false;
    path[n - 4] = '\0';
    printf("preview: saved %s.png and %s.pfm\n", path, path);
    fflush(stdout);
    return true;
}

/* The window's content (the back buffer just drawn) as PNG, rows flipped to top-first. */
static bool write_screenshot(app *a, const char *path)
{
    int fw, fh, y;
    unsigned char *px, *row;
    size_t stride;
    cli_membuf b;
    bool ok;
    glfwGetFramebufferSize(a->window, &fw, &fh);
    stride = 3 * (size_t)fw;
    px = (unsigned char *)malloc(stride * (size_t)fh);
    row = (unsigned char *)malloc(stride);
    if (!px || !row) { free(px); free(row); fprintf(stderr, "preview: --screenshot %s: out of memory\n", path); return false; }
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, fw, fh, GL_RGB, GL_UNSIGNED_BYTE, px);
    for (y = 0; y < fh / 2; ++y) {
        memcpy(row, px + stride * (size_t)y, stride);
        memcpy(px + stride * (size_t)y, px + stride * (size_t)(fh - 1 - y), stride);
        memcpy(px + stride * (size_t)(fh - 1 - y), row, stride);
    }
    memset(&b, 0, sizeof b);
    if (!stbi_write_png_to_func(cli_membuf_stb, &b, fw, fh, 3, px, (int)stride)) b.failed = true;
    ok = write_file(a, "--screenshot", path, &b);
    free(b.data);
    free(px); free(row);
    return ok;
}

/* Draws the newest image if there is one; keeps the frame and latency counts. */
static bool present(app *a, bool force)
{
    bool fresh = take_image(a);
    double t;
    if (!fresh && !force && !a->redraw) return false;
    a->redraw = false;
    draw(a);
    t = now_seconds();
    if (fresh) {
        a->frames++;
        if (a->frames == 1) a->t_first_frame = t;
        a->t_last_frame = t;
        if (a->awaiting_frame && a->rgb_gen == a->first_frame_gen) {
            latency_add(&a->key_to_frame, t - a->awaited_change_time);
            a->awaiting_frame = false;
        }
    }
    return true;
}

/* After each key: the first frame of the newest generation is the one the latency waits for. */
static void note_change(app *a)
{
    pthread_mutex_lock(&a->mu);
    if (a->gen != a->first_frame_gen) {
        a->first_frame_gen = a->gen;
        a->awaiting_frame = true;
        a->awaited_change_time = a->change_time;
    }
    pthread_mutex_unlock(&a->mu);
}

static void print_summary(app *a)
{
    double t_end = now_seconds(), wall = t_end - a->t_start;
    double fps = a->frames > 1 && a->t_last_frame > a->t_first_frame ? (double)(a->frames - 1) / (a->t_last_frame - a->t_first_frame) : 0.0;
    double polls_per_s = wall > 0.0 ? (double)a->polls / wall : 0.0;
    char k1[96], k2[96];
    if (a->key_to_restart.n) snprintf(k1, sizeof k1, "%.1f ms mean, %.1f ms max", 1e3 * a->key_to_restart.sum / a->key_to_restart.n, 1e3 * a->key_to_restart.max);
    else snprintf(k1, sizeof k1, "no key pressed");
    if (a->key_to_frame.n) snprintf(k2, sizeof k2, "%.1f ms mean, %.1f ms max", 1e3 * a->key_to_frame.sum / a->key_to_frame.n, 1e3 * a->key_to_frame.max);
    else snprintf(k2, sizeof k2, "no key pressed");
    printf("preview: %llu frames in %.2f s, %.1f frames/s, %.3g M samples/s (%.3g M/s while rendering, %.0f%% of the time), "
           "input polled %.0f times/s (longest gap %.0f ms, %.0f ms in the first frames), key to restart %s, "
           "key to new frame %s (%d changes, %u renders cancelled)\n",
           (unsigned long long)a->frames, wall, fps, wall > 0.0 ? (double)a->samples_total / wall * 1e-6 : 0.0,
           a->render_seconds > 0.0 ? (double)a->samples_total / a->render_seconds * 1e-6 : 0.0,
           wall > 0.0 ? 100.0 * a->render_seconds / wall : 0.0,
           polls_per_s, 1e3 * a->max_poll_gap, 1e3 * a->max_startup_gap, k1, k2, a->key_to_frame.n, a->cancels);
    fflush(stdout);
}

/* ------------------------------------------------------------------------------------------
   main
   ------------------------------------------------------------------------------------------ */
/* Scripted frame: let the worker finish one more batch of the current generation. */
static bool scripted_frame(app *a, const script_event *ev, int nev, int *next_ev, int frame)
{
    bool has_keys = *next_ev < nev && ev[*next_ev].frame == frame;
    double t_limit;
    pthread_mutex_lock(&a->mu);
    a->batches_allowed = a->batches_done + 1;
    pthread_cond_broadcast(&a->cv);
    pthread_mutex_unlock(&a->mu);
    if (has_keys) {
        /* Press the keys while the worker is busy, as a user would: its batch is cancelled. */
        bool busy = false;
        t_limit = now_seconds() + 2.0;
        while (!busy && now_seconds() < t_limit) {
            pthread_mutex_lock(&a->mu);
            busy = a->busy || a->quit || a->batches_done >= a->batches_allowed;
            pthread_mutex_unlock(&a->mu);
            if (!busy) poll_events(a, 0.001);
        }
        while (*next_ev < nev && ev[*next_ev].frame == frame) {
            apply_key(a, ev[*next_ev].key, ev[*next_ev].dx, ev[*next_ev].dy);
            (*next_ev)++;
        }
        note_change(a);
    }
    for (;;) {   /* wait for a finished batch of the newest generation */
        bool ready, quit;
        pthread_mutex_lock(&a->mu);
        quit = a->quit;
        ready = a->shown_gen == a->gen && a->shown_serial != a->drawn_serial && a->batches_done >= a->batches_allowed;
        if (!ready && a->batches_done >= a->batches_allowed) {
            a->batches_allowed = a->batches_done + 1;       /* that batch was for old parameters */
            pthread_cond_broadcast(&a->cv);
        }
        pthread_mutex_unlock(&a->mu);
        if (quit) return false;
        if (ready) break;
        poll_events(a, 0.01);
        if (glfwWindowShouldClose(a->window)) return false;
    }
    return true;
}

int main(int argc, char **argv)
{
    static app A;
    app *a = &A;
    script_event *ev = NULL;
    int nev = 0, next_ev = 0, status = 0, frame, stopped_at = 0;
    pthread_t worker;
    bool worker_started = false;
    size_t pixels;

    cli_std_streams();          /* before any file is opened: 0-2 are never a saved image */
    cli_sane_omp_env(argv);
    cli_prog = "preview";
    if (!cli_check_stack()) return 2;
    status = parse_flags(argc, argv, &a->opt);
    if (status == -1) return 0;
    if (status) return status;
    if ((a->opt.threads = cli_resolve_threads(a->opt.threads)) == 0) return 2;
    if (a->opt.screenshot) {    /* never the scene file; writable, found out before the window opens */
        cli_output out;
        if (a->opt.scene) {
            cli_file in, o;
            cli_identify(&in, "", a->opt.scene);
            cli_identify(&o, "--screenshot", a->opt.screenshot);
            if (cli_check_aliases(&in, 1, &o, 1) != 0) return 2;
        }
        if (!cli_prepare_output(&out, "--screenshot", a->opt.screenshot)) return 1;
    }
    if (a->opt.keys) {
        char msg[160];
        if (!parse_script(a->opt.keys, a->opt.frames, &ev, &nev, msg, sizeof msg)) {
            fprintf(stderr, "preview: --keys: %s\n", msg);
            return 2;
        }
    }
    status = load_scene(a);
    if (status) { fogrt_scene_destroy(a->scene); free(ev); return status; }
    a->exposure = a->opt.exposure;

    pixels = (size_t)a->opt.width * (size_t)a->opt.height;
    a->shown = (float *)malloc(sizeof(float) * 3 * pixels);
    a->rgb = (float *)malloc(sizeof(float) * 3 * pixels);
    a->rgb8 = (unsigned char *)malloc(3 * pixels);
    if (!a->shown || !a->rgb || !a->rgb8) {
        fprintf(stderr, "preview: -r %d %d: image too large to allocate\n", a->opt.width, a->opt.height);
        status = 2;
        goto done;
    }

    /* The window */
    glfwSetErrorCallback(on_glfw_error);
    if (!glfwInit()) {
        fprintf(stderr, "preview: cannot open a window: %s (no display? try xvfb-run)\n", glfw_message[0] ? glfw_message : "GLFW init failed");
        status = 1;
        goto done;
    }
    a->window = glfwCreateWindow(a->opt.width * a->opt.scale, a->opt.height * a->opt.scale, "fogrt preview", NULL, NULL);
    if (!a->window) {
        fprintf(stderr, "preview: cannot create an OpenGL window: %s\n", glfw_message[0] ? glfw_message : "unknown GLFW error");
        glfwTerminate();
        status = 1;
        goto done;
    }
    glfw_report = true;
    {
        struct sigaction sa;
        memset(&sa, 0, sizeof sa);
        sa.sa_handler = on_signal;
        sigemptyset(&sa.sa_mask);
        sigaction(SIGINT, &sa, NULL);
        sigaction(SIGTERM, &sa, NULL);
        sigaction(SIGHUP, &sa, NULL);
    }
    glfwMakeContextCurrent(a->window);
    glfwSwapInterval(1);
    glfwSetWindowUserPointer(a->window, a);
    glfwSetCharCallback(a->window, on_char);
    glfwSetKeyCallback(a->window, on_key);
    glfwSetMouseButtonCallback(a->window, on_mouse_button);
    glfwSetCursorPosCallback(a->window, on_cursor);
    glfwSetScrollCallback(a->window, on_scroll);
    glGenTextures(1, &a->texture);
    glBindTexture(GL_TEXTURE_2D, a->texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);

    /* The worker */
    pthread_mutex_init(&a->mu, NULL);
    pthread_cond_init(&a->cv, NULL);
    a->t_start = now_seconds();
    a->change_time = 0.0;
    if (pthread_create(&worker, NULL, worker_main, a) != 0) { fprintf(stderr, "preview: cannot start the render thread\n"); status = 1; goto close; }
    worker_started = true;
    if (a->opt.frames == 0) printf("preview: press h or F1 for the keys, Esc to quit\n");

    if (a->opt.frames > 0) {
        for (frame = 1; frame <= a->opt.frames && !glfwWindowShouldClose(a->window); ++frame) {
            if (!scripted_frame(a, ev, nev, &next_ev, frame)) break;
            present(a, true);
            update_title(a);
            if (a->save_pending) { a->save_pending = false; if (!save_image(a)) status = 1; }
            if (frame == a->opt.frames && a->opt.screenshot && !write_screenshot(a, a->opt.screenshot)) status = 1;
            glfwSwapBuffers(a->window);
        }
        stopped_at = frame <= a->opt.frames ? frame : 0;
    } else {
        while (!glfwWindowShouldClose(a->window)) {
            poll_events(a, 1.0 / 60.0);   /* returns at once on input or a new image */
            note_change(a);
            if (present(a, false)) {
                glfwSwapBuffers(a->window);
                update_title(a);
            } else if (now_seconds() - a->last_title > 0.25 && a->frames > 0) {
                update_title(a);
            }
            if (a->save_pending) { a->save_pending = false; (void)save_image(a); }   /* said why; go on */
            pthread_mutex_lock(&a->mu);
            if (a->quit) glfwSetWindowShouldClose(a->window, GLFW_TRUE);
            pthread_mutex_unlock(&a->mu);
        }
        if (a->opt.screenshot) {
            draw(a);
            if (!write_screenshot(a, a->opt.screenshot)) status = 1;
        }
    }

close:
    if (worker_started) {
        pthread_mutex_lock(&a->mu);
        a->quit = true;
        pthread_cond_broadcast(&a->cv);
        pthread_mutex_unlock(&a->mu);
        pthread_join(worker, NULL);
        if (a->failed) { fprintf(stderr, "preview: %s\n", a->failure); status = 1; }
        else {
            print_summary(a);
            if (stopped_at && a->opt.screenshot) {
                fprintf(stderr, "preview: --screenshot %s: not written (the window closed at frame %d of %d)\n",
                        a->opt.screenshot, stopped_at, a->opt.frames);
                status = 1;
            }
        }
    }
    pthread_cond_destroy(&a->cv);
    pthread_mutex_destroy(&a->mu);
    glDeleteTextures(1, &a->texture);
    glfwDestroyWindow(a->window);
    glfwTerminate();
done:
    free(a->shown); free(a->rgb); free(a->rgb8);
    free(ev);
    fogrt_scene_destroy(a->scene);
    return status;
}
