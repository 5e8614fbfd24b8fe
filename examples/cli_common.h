/* cli_common.h - what the fogrt command (examples/fogrt_cli.c) and the preview
   (examples/preview.c) share, so that a flag means one thing in both and both treat files,
   threads and standard streams alike:

   - the parser of the flags they have in common (-r -t -l -m -H -g --g --density --albedo
     --phase --emission --medium --interface --integrator --fresnel --seed --exposure), their
     help lines, `--flag=value`, and "did you mean" for a misspelt flag;
   - media inside the scene's objects (--medium NAME): the names the loader reports, NAME
     found among them, the media and interfaces handed to the scene, and the scene build's
     refusals told by the flag;
   - standard descriptors 0-2 reopened on /dev/null when closed, SIGPIPE ignored;
   - the thread count: capped, checked against OMP_STACKSIZE, and lowered when the system
     cannot start that many threads;
   - file identity: no output may be an input of the run or another output;
   - what a scene file that is not a scene is ("a PNG image, not a scene");
   - outputs written through a temporary file, every write checked, then renamed.

   Include it after fogrt.h, fogrt_load.h and the feature-test macros (POSIX 2008). Every
   function is static; the unused ones cost nothing. Not part of the library: fogrt.h stays
   libc-only, this is POSIX. */
#ifndef FOGRT_CLI_COMMON_H
#define FOGRT_CLI_COMMON_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <stdarg.h>
#include <errno.h>
#include <math.h>
#include <limits.h>
#include <signal.h>
#include <fcntl.h>
#include <unistd.h>
#include <pthread.h>
#include <sys/types.h>
#include <sys/stat.h>
#include <sys/resource.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#if defined(__GNUC__)
#define CLI_FN static __attribute__((unused))
#else
#define CLI_FN static
#endif

#ifndef PATH_MAX
#define PATH_MAX 4096
#endif

/* The program's name in every message ("fogrt" or "preview"). */
static const char *cli_prog = "fogrt";
/* Set by cli_std_streams when the program started with fd 1 closed: output meant for stdout
   (--print-camera, --trace) would go to /dev/null, so the program says so and fails instead. */
static int cli_stdout_closed = 0;

/* Threads: at most 4 per processor, and never more than this (OMP_NUM_THREADS included):
   the library's own cap when it has one. */
#ifdef FOGRT_MAX_THREADS
#define CLI_MAX_THREADS FOGRT_MAX_THREADS
#else
#define CLI_MAX_THREADS 256
#endif
/* A render thread's stack: fogrt's traversal and integrator need about 32 KiB (measured:
   OMP_STACKSIZE=32K renders, 16K crashes); a smaller OMP_STACKSIZE than this is refused. */
#define CLI_MIN_STACK_KIB 256
#define CLI_MAX_SIDE 32768

/* ------------------------------------------------------------------------------------------
   Standard streams
   ------------------------------------------------------------------------------------------ */
/* A closed 0, 1 or 2 would be handed out by the next open(): the output image would become
   "stderr", and messages would land in it. Reopened on /dev/null first thing in main. A
   reader of stderr that goes away must not kill the run (SIGPIPE): writes to it just fail;
   nor must a file-size limit (SIGXFSZ): the write fails and is reported. */
CLI_FN void cli_std_streams(void)
{
    int fd;
    for (fd = 0; fd <= 2; ++fd) {
        if (fcntl(fd, F_GETFD) == -1 && errno == EBADF) {
            int k;
            if (fd == 1) cli_stdout_closed = 1;
            k = open("/dev/null", fd == 0 ? O_RDONLY : O_WRONLY);
            if (k >= 0 && k != fd) { dup2(k, fd); close(k); }
        }
    }
    signal(SIGPIPE, SIG_IGN);
    signal(SIGXFSZ, SIG_IGN);    /* a file-size limit makes write() fail (EFBIG), not kill us */
}

/* ------------------------------------------------------------------------------------------
   Flags: the cursor over argv, `--flag=value`, messages and suggestions
   ------------------------------------------------------------------------------------------ */
typedef struct cli_arg {
    int argc;
    char **argv;
    int i;                      /* argv[i] is the flag being parsed */
    char name[64];              /* the flag without its "=value" */
    const char *inline_value;   /* the value after '=' in --flag=value, else NULL */
    bool inline_used;
} cli_arg;

/* Points the cursor at argv[i]; "--flag=value" is split (short flags keep their '='). */
CLI_FN void cli_arg_at(cli_arg *A, int i)
{
    const char *a = A->argv[i], *eq = NULL;
    A->i = i;
    A->inline_value = NULL;
    A->inline_used = false;
    if (a[0] == '-' && a[1] == '-' && (eq = strchr(a, '=')) != NULL && (size_t)(eq - a) < sizeof A->name) {
        snprintf(A->name, sizeof A->name, "%.*s", (int)(eq - a), a);
        A->inline_value = eq + 1;
    } else {
        snprintf(A->name, sizeof A->name, "%s", a);
    }
}
CLI_FN bool cli_is(const cli_arg *A, const char *flag) { return strcmp(A->name, flag) == 0; }
/* Values left for the flag: the =value, then the following arguments. */
CLI_FN bool cli_has(const cli_arg *A, int n)
{
    int left = A->argc - 1 - A->i + (A->inline_value && !A->inline_used ? 1 : 0);
    return left >= n;
}
CLI_FN const char *cli_next(cli_arg *A)
{
    if (A->inline_value && !A->inline_used) { A->inline_used = true; return A->inline_value; }
    if (A->i + 1 < A->argc) return A->argv[++A->i];
    return "";
}

/* One message naming the flag, then exit status 2. */
CLI_FN int cli_bad_flag(const char *flag, const char *fmt, ...)
{
    va_list ap;
    fprintf(stderr, "%s: %s: ", cli_prog, flag);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fprintf(stderr, " (%s -h lists the flags)\n", cli_prog);
    return 2;
}

/* Edit distance (insertions, deletions, substitutions, swaps of neighbours), for "did you
   mean": short strings only. */
CLI_FN int cli_distance(const char *a, const char *b)
{
    int d[40][40], i, j, n = (int)strlen(a), m = (int)strlen(b);
    if (n > 38 || m > 38) return 99;
    for (i = 0; i <= n; ++i) d[i][0] = i;
    for (j = 0; j <= m; ++j) d[0][j] = j;
    for (i = 1; i <= n; ++i)
        for (j = 1; j <= m; ++j) {
            int c = d[i - 1][j - 1] + (a[i - 1] != b[j - 1]);
            if (d[i - 1][j] + 1 < c) c = d[i - 1][j] + 1;
            if (d[i][j - 1] + 1 < c) c = d[i][j - 1] + 1;
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] && d[i - 2][j - 2] + 1 < c) c = d[i - 2][j - 2] + 1;
            d[i][j] = c;
        }
    return d[n][m];
}
/* The unknown flag's message, with the nearest known flag when one is near: a third of its
   letters wrong at most, or the only flag it starts. Letters, not dashes, are compared (the
   dashes are the same in most flags, so "-x" would otherwise be one edit from "-r"), and a
   suggestion keeps at least one of the flag's letters. known ends with NULL. */
CLI_FN const char *cli_flag_letters(const char *f) { while (*f == '-') ++f; return f; }
CLI_FN int cli_unknown_flag(const char *flag, const char *const *known)
{
    const char *best = NULL, *prefix = NULL;
    int best_d = 99, prefixes = 0, k;
    size_t n = strlen(flag), letters = strlen(cli_flag_letters(flag));
    for (k = 0; known[k]; ++k) {
        int d = cli_distance(cli_flag_letters(flag), cli_flag_letters(known[k]));
        if (d < best_d) { best_d = d; best = known[k]; }
        if (n >= 4 && strncmp(known[k], flag, n) == 0) { prefix = known[k]; prefixes++; }
    }
    if (best && best_d <= (int)(strlen(cli_flag_letters(best)) + 2) / 3 && best_d < (int)letters)
        return cli_bad_flag(flag, "unknown flag: did you mean %s?", best);
    if (prefixes == 1) return cli_bad_flag(flag, "unknown flag: did you mean %s?", prefix);
    return cli_bad_flag(flag, "unknown flag");
}

/* ------------------------------------------------------------------------------------------
   Numbers
   ------------------------------------------------------------------------------------------ */
CLI_FN bool cli_parse_int(const char *s, long lo, long hi, int *out)
{
    char *end;
    long v;
    errno = 0;
    v = strtol(s, &end, 10);
    if (errno || end == s || *end || v < lo || v > hi) return false;
    *out = (int)v;
    return true;
}
/* A finite double (strtod's range), no trailing characters. */
CLI_FN bool cli_parse_double(const char *s, double *out)
{
    char *end;
    double v;
    errno = 0;
    v = strtod(s, &end);
    if (end == s || *end || !isfinite(v)) return false;
    if (errno == ERANGE && fabs(v) > 1.0) return false;    /* overflow; underflow is a tiny number */
    *out = v;
    return true;
}
CLI_FN bool cli_parse_float(const char *s, float *out)
{
    double v;
    if (!cli_parse_double(s, &v) || v > 3.0e38 || v < -3.0e38) return false;
    *out = (float)v;
    return true;
}
CLI_FN bool cli_parse_u64(const char *s, uint64_t *out)
{
    char *end;
    unsigned long long v;
    if (*s == '-' || *s == '+' || !(*s >= '0' && *s <= '9')) return false;
    errno = 0;
    v = strtoull(s, &end, 10);
    if (errno || end == s || *end) return false;
    *out = (uint64_t)v;
    return true;
}
/* n numbers separated by commas, into doubles. */
CLI_FN bool cli_parse_list(const char *s, double *v, int n)
{
    char buf[512], *p = buf, *comma;
    int k;
    if (strlen(s) >= sizeof buf) return false;
    strcpy(buf, s);
    for (k = 0; k < n; ++k) {
        comma = strchr(p, ',');
        if ((comma != NULL) != (k < n - 1)) return false;
        if (comma) *comma = 0;
        if (!cli_parse_double(p, &v[k])) return false;
        if (comma) p = comma + 1;
    }
    return true;
}
/* "X,Y,Z" in float range. */
CLI_FN bool cli_parse_vec3(const char *s, fogrt_vec3 *out)
{
    double v[3];
    if (!cli_parse_list(s, v, 3)) return false;
    if (fabs(v[0]) > 3.0e38 || fabs(v[1]) > 3.0e38 || fabs(v[2]) > 3.0e38) return false;
    out->x = (float)v[0]; out->y = (float)v[1]; out->z = (float)v[2];
    return true;
}
/* "X,Y,Z", a direction: normalised in double, so that 0,1e-30,0 is 0,1,0 (in float its
   square would underflow to 0); false for the zero vector. */
CLI_FN bool cli_parse_direction(const char *s, fogrt_vec3 *out)
{
    double v[3], m, len;
    if (!cli_parse_list(s, v, 3)) return false;
    m = fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2])));
    if (!(m > 0.0)) return false;
    v[0] /= m; v[1] /= m; v[2] /= m;                   /* the largest is 1: no under/overflow */
    len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    out->x = (float)(v[0] / len); out->y = (float)(v[1] / len); out->z = (float)(v[2] / len);
    return true;
}
CLI_FN bool cli_parse_onoff(const char *s, bool *out)
{
    if (strcmp(s, "on") == 0) { *out = true; return true; }
    if (strcmp(s, "off") == 0) { *out = false; return true; }
    return false;
}
/* "0.9" or "0.9,0.8,0.7", each in [0, 1] */
CLI_FN bool cli_parse_albedo(const char *s, fogrt_vec3 *out)
{
    double v[3];
    if (strchr(s, ',')) { if (!cli_parse_list(s, v, 3)) return false; }
    else { if (!cli_parse_double(s, &v[0])) return false; v[1] = v[2] = v[0]; }
    if (v[0] < 0 || v[0] > 1 || v[1] < 0 || v[1] > 1 || v[2] < 0 || v[2] > 1) return false;
    out->x = (float)v[0]; out->y = (float)v[1]; out->z = (float)v[2];
    return true;
}
/* "2" or "1,0.5,0.2": radiance, each finite and >= 0 */
CLI_FN bool cli_parse_emission(const char *s, fogrt_vec3 *out)
{
    double v[3];
    if (strchr(s, ',')) { if (!cli_parse_list(s, v, 3)) return false; }
    else { if (!cli_parse_double(s, &v[0])) return false; v[1] = v[2] = v[0]; }
    if (!(v[0] >= 0 && v[0] <= 3.0e38 && v[1] >= 0 && v[1] <= 3.0e38 && v[2] >= 0 && v[2] <= 3.0e38)) return false;
    out->x = (float)v[0]; out->y = (float)v[1]; out->z = (float)v[2];
    return true;
}
CLI_FN bool cli_ends_with(const char *s, const char *ext)
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

/* ------------------------------------------------------------------------------------------
   The flags both programs take
   ------------------------------------------------------------------------------------------ */
/* The fog flags: the world's before any --medium, after --medium NAME those of NAME's medium. */
typedef struct cli_fog {
    float g; bool g_set, paper_g;        /* --g, -g */
    float g2, w; bool two_lobes;         /* --g G1,G2,W (appendix G) */
    fogrt_phase_type phase; bool phase_set;   /* --phase (G) */
    fogrt_vec3 emission; bool emission_set;   /* --emission (G) */
    float density; bool density_set;     /* --density (R,G,B: the largest) */
    fogrt_vec3 density_rgb; bool chromatic;   /* --density R,G,B: sigma_t per channel (G) */
    fogrt_vec3 albedo; bool albedo_set;  /* --albedo */
} cli_fog;
/* --medium NAME (appendix H), with the fog flags and --interface that follow it; the shape
   NAME is found to be once the scene is loaded. */
typedef struct cli_medium {
    const char *name;
    bool interface;                      /* --interface */
    cli_fog fog;
    bool found; fogrt_shape_kind kind; uint32_t index;
} cli_medium;
#define CLI_MAX_MEDIA 64

typedef struct cli_common {
    int width, height;                   /* -r */
    int threads;                         /* -t, 0 = all */
    int light_samples;                   /* -l */
    int max_depth;                       /* -m */
    bool hemisphere;                     /* -H */
    cli_fog fog;                         /* the world's fog: the fog flags before any --medium */
    cli_medium media[CLI_MAX_MEDIA];     /* --medium NAME ... in the order given */
    int media_count;
    fogrt_integrator integrator;         /* --integrator */
    fogrt_fresnel fresnel;               /* --fresnel */
    uint64_t seed;                       /* --seed */
    float exposure_ev;                   /* --exposure, in stops */
} cli_common;

static const char *const cli_common_names[] = {
    "-r", "-t", "-l", "-m", "-H", "-g", "--g", "--density", "--albedo", "--phase", "--emission", "--medium",
    "--interface", "--integrator", "--fresnel", "--seed", "--exposure", "-h", "--help", NULL
};

/* The build that left out appendix G of fogrt.h (media beyond the paper), for the one line
   that refuses its flags. */
#if defined(FOGRT_MINIMAL)
#define CLI_NO_MEDIA_MACRO "FOGRT_MINIMAL"
#elif defined(FOGRT_NO_MEDIUM)
#define CLI_NO_MEDIA_MACRO "FOGRT_NO_MEDIUM"
#else
#define CLI_NO_MEDIA_MACRO "FOGRT_NO_MEDIA"
#endif
/* ... and the one that left out appendix H (media inside shapes), for --medium's line. */
#if defined(FOGRT_NO_MEDIA)
#define CLI_NO_SHAPES_MACRO CLI_NO_MEDIA_MACRO   /* (fogrt.h: FOGRT_NO_MEDIA implies FOGRT_NO_SHAPES) */
#else
#define CLI_NO_SHAPES_MACRO "FOGRT_NO_SHAPES"
#endif

/* The defaults (the image size is the program's: fogrt 800x600, the preview 320x240). */
CLI_FN void cli_common_defaults(cli_common *c, int width, int height)
{
    memset(c, 0, sizeof *c);
    c->width = width; c->height = height;
    c->light_samples = 1;
    c->max_depth = 64;
    c->integrator = FOGRT_INTEGRATOR_PATH;
    c->fresnel = FOGRT_FRESNEL_SCHLICK;
}

#define CLI_NEED(n) do { if (!cli_has(A, (n))) return cli_bad_flag(a, "needs %d value%s", (n), (n) > 1 ? "s" : ""); } while (0)
/* --medium NAME and --interface: a new medium, whose fog flags follow; its surface an
   interface. Returns 0, 2 or -1 as cli_common_flag. */
CLI_FN int cli_medium_flag(cli_arg *A, cli_common *c)
{
    const char *a = A->name, *v = "";
    int i;
    if (!cli_is(A, "--medium") && !cli_is(A, "--interface")) return -1;
    if (cli_is(A, "--medium")) CLI_NEED(1);
    if (cli_is(A, "--medium")) v = cli_next(A);
#ifdef FOGRT_NO_SHAPES
    (void)c; (void)i; (void)v;
    return cli_bad_flag(a, "needs appendix H of fogrt.h (media inside shapes): this %s was built with %s", cli_prog, CLI_NO_SHAPES_MACRO);
#else
    if (cli_is(A, "--interface")) {
        if (c->media_count == 0) return cli_bad_flag(a, "must follow --medium NAME: it makes NAME's surface an interface (invisible, bounding its medium)");
        c->media[c->media_count - 1].interface = true;
        return 0;
    }
    if (!v[0]) return cli_bad_flag(a, "needs the name of an object of the scene (a node, material or geometry name)");
    for (i = 0; i < c->media_count; ++i)
        if (strcmp(c->media[i].name, v) == 0) return cli_bad_flag(a, "'%s' is given twice: one --medium per object", v);
    if (c->media_count == CLI_MAX_MEDIA) return cli_bad_flag(a, "at most %d objects may hold media", CLI_MAX_MEDIA);
    memset(&c->media[c->media_count], 0, sizeof c->media[0]);
    c->media[c->media_count++].name = v;
    return 0;
#endif
}
/* --density S (grey fog) or R,G,B (sigma_t per channel, appendix G); density is then the
   largest channel. Returns 0, or 2 with the message printed. */
CLI_FN int cli_density_flag(const char *a, const char *v, cli_fog *f)
{
    if (strchr(v, ',')) {                         /* per channel: chromatic fog */
#ifdef FOGRT_NO_MEDIA
        return cli_bad_flag(a, "R,G,B (sigma_t per channel) needs appendix G of fogrt.h: this %s was built with %s", cli_prog, CLI_NO_MEDIA_MACRO);
#endif
        if (!cli_parse_emission(v, &f->density_rgb))
            return cli_bad_flag(a, "density must be S or R,G,B, each a finite number >= 0 (float: at most 3.4e38), got '%s'", v);
        f->density = f->density_rgb.x > f->density_rgb.y ? f->density_rgb.x : f->density_rgb.y;
        if (f->density_rgb.z > f->density) f->density = f->density_rgb.z;
        f->chromatic = true;
    } else if (!cli_parse_float(v, &f->density) || f->density < 0) {
        return cli_bad_flag(a, "density must be S or R,G,B, each a finite number >= 0 (float: at most 3.4e38), got '%s'", v);
    } else {
        f->chromatic = false;
    }
    f->density_set = true;
    return 0;
}
/* The fog flags, into f: the world's fog or the last --medium's. Returns 0, 2 or -1 as
   cli_common_flag. */
CLI_FN int cli_fog_flag(cli_arg *A, cli_fog *f)
{
    const char *a = A->name, *v;
    if (cli_is(A, "-g") || cli_is(A, "--g")) {
        double l[3];
        CLI_NEED(1); v = cli_next(A);
        if (strchr(v, ',')) {                     /* two lobes: w HG(G1) + (1 - w) HG(G2) */
#ifdef FOGRT_NO_MEDIA
            return cli_bad_flag(a, "two lobes G1,G2,W need appendix G of fogrt.h: this %s was built with %s", cli_prog, CLI_NO_MEDIA_MACRO);
#endif
            if (!cli_parse_list(v, l, 3) || !(l[0] >= -1 && l[0] <= 1 && l[1] >= -1 && l[1] <= 1 && l[2] >= 0 && l[2] <= 1))
                return cli_bad_flag(a, "two lobes must be G1,G2,W with G1 and G2 in [-1, 1] and W in [0, 1], got '%s'", v);
            f->g = (float)l[0]; f->g2 = (float)l[1]; f->w = (float)l[2]; f->two_lobes = true;
        } else if (!cli_parse_float(v, &f->g) || f->g < -1 || f->g > 1) {
            return cli_bad_flag(a, "g must be a number in [-1, 1] (or G1,G2,W for two lobes), got '%s'", v);
        } else {
            f->two_lobes = false;
        }
        f->g_set = true;
        if (cli_is(A, "-g")) f->paper_g = true;
        return 0;
    }
    if (cli_is(A, "--density")) {
        CLI_NEED(1);
        return cli_density_flag(a, cli_next(A), f);
    }
    if (cli_is(A, "--albedo")) {
        CLI_NEED(1); v = cli_next(A);
        if (!cli_parse_albedo(v, &f->albedo)) return cli_bad_flag(a, "albedo must be a number in [0, 1] or r,g,b with each in [0, 1], got '%s'", v);
        f->albedo_set = true;
        return 0;
    }
    if (cli_is(A, "--phase") || cli_is(A, "--emission")) {
        CLI_NEED(1); v = cli_next(A);
#ifdef FOGRT_NO_MEDIA
        return cli_bad_flag(a, "needs appendix G of fogrt.h (media beyond the paper): this %s was built with %s", cli_prog, CLI_NO_MEDIA_MACRO);
#else
        if (cli_is(A, "--phase")) {
            if (strcmp(v, "hg") == 0) f->phase = FOGRT_PHASE_HG;
            else if (strcmp(v, "rayleigh") == 0) f->phase = FOGRT_PHASE_RAYLEIGH;
            else return cli_bad_flag(a, "must be hg or rayleigh, got '%s'", v);
            f->phase_set = true;
            return 0;
        }
        if (!cli_parse_emission(v, &f->emission))
            return cli_bad_flag(a, "emission must be R,G,B (or one number for all three), each finite and >= 0, got '%s'", v);
        f->emission_set = true;
        return 0;
#endif
    }
    return -1;
}

/* Parses one common flag at the cursor. Returns 0 (taken), 2 (refused, message printed) or
   -1 (not a common flag). -h is the caller's. The fog flags after --medium NAME are NAME's. */
CLI_FN int cli_common_flag(cli_arg *A, cli_common *c)
{
    const char *a = A->name, *v;
    int k;
    if ((k = cli_medium_flag(A, c)) >= 0) return k;
    if ((k = cli_fog_flag(A, c->media_count ? &c->media[c->media_count - 1].fog : &c->fog)) >= 0) return k;
    if (cli_is(A, "-r")) {
        const char *w, *h;
        CLI_NEED(2);
        w = cli_next(A); h = cli_next(A);
        if (!cli_parse_int(w, 1, CLI_MAX_SIDE, &c->width) || !cli_parse_int(h, 1, CLI_MAX_SIDE, &c->height))
            return cli_bad_flag(a, "width and height must be integers in [1, %d], got '%s %s'", CLI_MAX_SIDE, w, h);
        return 0;
    }
    if (cli_is(A, "-t")) {
        CLI_NEED(1); v = cli_next(A);
        if (!cli_parse_int(v, 0, 4096, &c->threads)) return cli_bad_flag(a, "threads must be an integer in [0, 4096], got '%s'", v);
        return 0;
    }
    if (cli_is(A, "-l")) {
        CLI_NEED(1); v = cli_next(A);
        if (!cli_parse_int(v, 1, 1 << 16, &c->light_samples)) return cli_bad_flag(a, "light samples must be an integer in [1, 65536], got '%s'", v);
        return 0;
    }
    if (cli_is(A, "-m")) {
        CLI_NEED(1); v = cli_next(A);
        if (!cli_parse_int(v, 0, 1 << 20, &c->max_depth))
            return cli_bad_flag(a, "maximum ray depth must be an integer in [0, 1048576] (0 = emission only), got '%s'", v);
        return 0;
    }
    if (cli_is(A, "-H")) { c->hemisphere = true; return 0; }
    if (cli_is(A, "--integrator")) {
        CLI_NEED(1); v = cli_next(A);
        if (strcmp(v, "path") == 0) c->integrator = FOGRT_INTEGRATOR_PATH;
        else if (strcmp(v, "direct") == 0) c->integrator = FOGRT_INTEGRATOR_DIRECT;
        else return cli_bad_flag(a, "must be path or direct, got '%s'", v);
        return 0;
    }
    if (cli_is(A, "--fresnel")) {
        CLI_NEED(1); v = cli_next(A);
        if (strcmp(v, "schlick") == 0) c->fresnel = FOGRT_FRESNEL_SCHLICK;
        else if (strcmp(v, "exact") == 0) c->fresnel = FOGRT_FRESNEL_EXACT;
        else return cli_bad_flag(a, "must be schlick or exact, got '%s'", v);
        return 0;
    }
    if (cli_is(A, "--seed")) {
        CLI_NEED(1); v = cli_next(A);
        if (!cli_parse_u64(v, &c->seed)) return cli_bad_flag(a, "seed must be a non-negative integer, got '%s'", v);
        return 0;
    }
    if (cli_is(A, "--exposure")) {
        CLI_NEED(1); v = cli_next(A);
        if (!cli_parse_float(v, &c->exposure_ev) || c->exposure_ev < -64 || c->exposure_ev > 64)
            return cli_bad_flag(a, "exposure must be a number of stops in [-64, 64] (the image is multiplied by 2^EV), got '%s'", v);
        return 0;
    }
#undef CLI_NEED
    return -1;
}

/* What the fog flags ask, checked once they are all parsed (exit 2): --phase rayleigh with
   two lobes, the world's or a medium's; a --medium followed by nothing, or by fog flags
   without the --density that makes its medium. */
CLI_FN int cli_common_media_check(const cli_common *c)
{
    char flag[96];
    int i;
    for (i = -1; i < c->media_count; ++i) {
        const cli_fog *f = i < 0 ? &c->fog : &c->media[i].fog;
        bool any = f->g_set || f->phase_set || f->emission_set || f->density_set || f->albedo_set;
        if (f->phase_set && f->phase == FOGRT_PHASE_RAYLEIGH && f->two_lobes)
            return cli_bad_flag("--phase", "rayleigh cannot be combined with two lobes (--g G1,G2,W): the lobes are Henyey-Greenstein's");
        if (i >= 0) snprintf(flag, sizeof flag, "--medium %.80s", c->media[i].name);
        if (i >= 0 && !any && !c->media[i].interface)
            return cli_bad_flag(flag, "no fog flag (--density, --albedo, --g, --phase, --emission) or --interface follows it");
        if (i >= 0 && any && !f->density_set && !f->paper_g)
            return cli_bad_flag(flag, "its fog flags need --density, the density of its medium (0 leaves it empty)");
    }
    return 0;
}
CLI_FN void cli_common_media_apply(const cli_fog *f, fogrt_medium_desc *md)
{
    if (f->density_set) {                       /* S replaces the scene's, R,G,B sets each channel */
        fogrt_vec3 none = {0.0f, 0.0f, 0.0f};
        md->sigma_t_rgb = f->chromatic ? f->density_rgb : none;
    }
    if (f->g_set) { md->phase = f->two_lobes ? FOGRT_PHASE_HG2 : FOGRT_PHASE_HG; md->g2 = f->g2; md->w = f->w; }
    if (f->phase_set && (f->phase == FOGRT_PHASE_RAYLEIGH || md->phase == FOGRT_PHASE_RAYLEIGH)) md->phase = f->phase;
    if (f->emission_set) md->emission = f->emission;
}

/* The help lines of the common flags, the same words in both programs. */
CLI_FN void cli_common_usage(FILE *f, int width, int height)
{
    fprintf(f,
        "  -r W H         image size in pixels, each in [1, %d] (default %d %d)\n"
        "  -t N           threads (default 0 = OMP_NUM_THREADS, else every processor; at most\n"
        "                 4 per processor and at most %d; fewer, with a warning, when the\n"
        "                 system cannot start that many; OMP_STACKSIZE, when set, must be at\n"
        "                 least %dK: a render thread needs about 32 KiB)\n"
        "  -l N           samples per area light at each light-sampling step (default 1)\n"
        "  -m N           maximum ray depth: bounces after the camera ray, N >= 0; 0 = emission\n"
        "                 only (default 64; Russian roulette ends paths earlier)\n"
        "  -H             hemisphere sampling: no light sampling, emitters found by hitting them\n"
        "                 (point and spot lights then contribute nothing) (default off)\n"
        "  -g G           Henyey-Greenstein g in [-1, 1], as in the paper's renderer; like the\n"
        "                 paper it also switches fog on (density 0.2) when the scene has none\n"
        "                 and --density is not given (default: the scene's)\n"
        "  --g G          Henyey-Greenstein g in [-1, 1], > 0 forward (default: the scene's:\n"
        "                 0.6; .dae files 0)\n"
        "  --density S    extinction sigma_t >= 0 per scene unit, the paper's lambda (default:\n"
        "                 the scene's own: 0.3 for the default scene and OBJ/PLY, 0 for .dae)\n"
        "  --albedo A     single-scattering albedo in [0, 1], a scalar or r,g,b (default: the\n"
        "                 scene's: 0.9; .dae files 0.9)\n"
        "  --g G1,G2,W    (also -g) two Henyey-Greenstein lobes, W HG(G1) + (1 - W) HG(G2), G1\n"
        "                 and G2 in [-1, 1], W in [0, 1] (default: one lobe, --g G)\n"
        "  --density R,G,B\n"
        "                 sigma_t per colour channel, each >= 0: chromatic fog, each channel\n"
        "                 attenuated and scattered at its own rate (default: one number, grey)\n"
        "  --phase P      the fog's phase function: hg (Henyey-Greenstein, --g) or rayleigh\n"
        "                 (3/(16 pi) (1 + cos^2), --g unused) (default hg)\n"
        "  --emission E   radiance the fog emits, R,G,B or one number, each >= 0, added as\n"
        "                 sigma_a E per unit length with sigma_a = density x (1 - albedo)\n"
        "                 (default 0: no emission)\n"
        "  --medium NAME  the fog flags that follow (up to the next --medium) describe a medium\n"
        "                 inside the closed object NAME instead of the world's fog: a node name\n"
        "                 of a .dae (else a material, else a geometry name), an o name of an\n"
        "                 OBJ (else usemtl, else g); a name several objects share is refused.\n"
        "                 Needs --density (its albedo 0.9 and g 0 unless given); NAME must be\n"
        "                 glass or refractive, or an --interface, for rays to enter it\n"
        "                 (default: no media in objects)\n"
        "  --interface    after --medium NAME: NAME's surface only bounds its medium (it\n"
        "                 neither reflects nor refracts: a fog volume of NAME's shape; without\n"
        "                 --density NAME is invisible) (default: NAME keeps its material)\n"
        "  --integrator I path (global illumination, the paper's Algorithm 1) or direct (one\n"
        "                 bounce, the paper's baseline) (default path)\n"
        "  --fresnel F    schlick or exact (default schlick)\n"
        "  --seed N       random seed (default 0); the image is the same on any thread count\n"
        "  --exposure EV  8-bit output brightness in stops: the image is multiplied by 2^EV\n"
        "                 before the sRGB curve, EV in [-64, 64] (default 0); PFM and EXR\n"
        "                 are never scaled\n"
        "  -h             this help (also --help)\n"
        "  --help         the same as -h\n",
        CLI_MAX_SIDE, width, height, CLI_MAX_THREADS, CLI_MIN_STACK_KIB);
}

/* ------------------------------------------------------------------------------------------
   Threads
   ------------------------------------------------------------------------------------------ */
/* OMP_STACKSIZE (or GOMP_STACKSIZE) as libgomp reads it: a number, optionally followed by
   B, K, M or G (K when none). Returns false when unset or not a size libgomp would take. */
CLI_FN bool cli_omp_stacksize(const char **name, unsigned long long *bytes)
{
    const char *s = getenv(*name = "OMP_STACKSIZE");
    char *end;
    unsigned long long v, unit = 1024;
    if (!s) s = getenv(*name = "GOMP_STACKSIZE");
    if (!s) return false;
    while (*s == ' ' || *s == '\t') ++s;
    if (!(*s >= '0' && *s <= '9')) return false;
    errno = 0;
    v = strtoull(s, &end, 10);
    if (errno) return false;
    while (*end == ' ' || *end == '\t') ++end;
    switch (*end) {
    case 'b': case 'B': unit = 1; ++end; break;
    case 'k': case 'K': unit = 1024; ++end; break;
    case 'm': case 'M': unit = 1024ull * 1024; ++end; break;
    case 'g': case 'G': unit = 1024ull * 1024 * 1024; ++end; break;
    default: break;
    }
    while (*end == ' ' || *end == '\t') ++end;
    if (*end) return false;
    *bytes = v > ULLONG_MAX / unit ? ULLONG_MAX : v * unit;
    return true;
}

typedef struct cli_probe { pthread_mutex_t mu; pthread_cond_t cv; bool go; } cli_probe;
static void *cli_probe_main(void *arg)
{
    cli_probe *p = (cli_probe *)arg;
    pthread_mutex_lock(&p->mu);
    while (!p->go) pthread_cond_wait(&p->cv, &p->mu);
    pthread_mutex_unlock(&p->mu);
    return NULL;
}
/* How many of n extra threads (with this stack size, 0 = the default) the system lets us
   have at once: started, all kept waiting, then released. *err: the first failure. */
CLI_FN int cli_probe_threads(int n, size_t stack, int *err)
{
    cli_probe p;
    pthread_t *t = (pthread_t *)malloc(sizeof(pthread_t) * (size_t)(n > 0 ? n : 1));
    pthread_attr_t attr;
    int k = 0, i;
    *err = 0;
    if (!t) { *err = ENOMEM; return 0; }
    pthread_mutex_init(&p.mu, NULL);
    pthread_cond_init(&p.cv, NULL);
    p.go = false;
    pthread_attr_init(&attr);
    if (stack) pthread_attr_setstacksize(&attr, stack);
    for (k = 0; k < n; ++k)
        if ((*err = pthread_create(&t[k], &attr, cli_probe_main, &p)) != 0) break;
    pthread_mutex_lock(&p.mu);
    p.go = true;
    pthread_cond_broadcast(&p.cv);
    pthread_mutex_unlock(&p.mu);
    for (i = 0; i < k; ++i) pthread_join(t[i], NULL);
    pthread_attr_destroy(&attr);
    pthread_cond_destroy(&p.cv);
    pthread_mutex_destroy(&p.mu);
    free(t);
    return k;
}

/* The processors and the thread cap: 4 per processor, at most CLI_MAX_THREADS. */
CLI_FN int cli_thread_cap(int *procs_out)
{
#ifdef _OPENMP
    int procs = omp_get_num_procs();
#else
    long sc = sysconf(_SC_NPROCESSORS_ONLN);
    int procs = sc > 0 && sc < 1 << 20 ? (int)sc : 1;
#endif
    if (procs < 1) procs = 1;
    if (procs_out) *procs_out = procs;
    return 4 * procs < CLI_MAX_THREADS ? 4 * procs : CLI_MAX_THREADS;
}

/* A parallel region without a thread count (the library's roulette pilot is one) takes
   OMP_NUM_THREADS, and with 100000 libgomp overflows the stack starting that team.
   omp_set_num_threads (cli_resolve_threads) mends it only for the thread that calls it: a
   thread the program starts itself (the preview's render thread, which rebuilds the scene)
   begins from the environment again. So when OMP_NUM_THREADS is above the cap the program
   starts again with it lowered, before any OpenMP work; FOGRT_OMP_NUM_THREADS_WAS keeps the
   value given, for the warning. Call first in main. */
CLI_FN void cli_sane_omp_env(char **argv)
{
#if defined(_OPENMP) && defined(__linux__)
    const char *s = getenv("OMP_NUM_THREADS");
    char *end, buf[32];
    long long v;
    int cap;
    if (!s || getenv("FOGRT_OMP_NUM_THREADS_WAS")) return;
    errno = 0;
    v = strtoll(s, &end, 10);                      /* the first entry of a list such as 8,2 */
    cap = cli_thread_cap(NULL);
    if (end == s || !(errno == ERANGE || v > cap)) return;
    if (setenv("FOGRT_OMP_NUM_THREADS_WAS", s, 1) != 0) return;
    snprintf(buf, sizeof buf, "%d", cap);
    if (setenv("OMP_NUM_THREADS", buf, 1) != 0) return;
    execv("/proc/self/exe", argv);
    unsetenv("FOGRT_OMP_NUM_THREADS_WAS");          /* no re-start: go on as we are */
#else
    (void)argv;
#endif
}

/* The thread count to render with: -t N, or with -t 0 OMP_NUM_THREADS (else every
   processor); at most 4 per processor and CLI_MAX_THREADS; lowered, with a warning, to as
   many as the system can start. Returns >= 1, or 0 after a message (a stack too small to
   render on: exit 2). */
/* The main thread renders too, and threads started without OMP_STACKSIZE get this much:
   a stack limit (ulimit -s) below CLI_MIN_STACK_KIB is refused. Call it from a main whose
   own frame is small (fogrt's main calls the rest of the program after it). Returns false
   after a message. */
CLI_FN bool cli_check_stack(void)
{
    struct rlimit rl;
    if (getrlimit(RLIMIT_STACK, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY && rl.rlim_cur < (rlim_t)CLI_MIN_STACK_KIB * 1024) {
        fprintf(stderr, "%s: the stack limit (ulimit -s) is %lu KiB: rendering needs at least %d KiB (ulimit -s %d)\n",
                cli_prog, (unsigned long)(rl.rlim_cur / 1024), CLI_MIN_STACK_KIB, CLI_MIN_STACK_KIB);
        return false;
    }
    return true;
}

CLI_FN int cli_resolve_threads(int requested)
{
    {
#ifdef _OPENMP
    int procs, want, cap, got, err;
    const char *name, *was = getenv("FOGRT_OMP_NUM_THREADS_WAS");
    unsigned long long stack = 0;
    bool from_env = requested == 0;
    cap = cli_thread_cap(&procs);
    if (was) {
        if (from_env)
            fprintf(stderr, "%s: OMP_NUM_THREADS=%s: using %d threads (at most 4 per processor, %d processors, and at most %d)\n",
                    cli_prog, was, cap, procs, CLI_MAX_THREADS);
        unsetenv("FOGRT_OMP_NUM_THREADS_WAS");
    }
    if (cli_omp_stacksize(&name, &stack) && stack < (unsigned long long)CLI_MIN_STACK_KIB * 1024) {
        fprintf(stderr, "%s: %s=%s: a render thread needs more stack than that (about 32 KiB; at least %dK is required): "
                "unset it or set it to %dK or more\n", cli_prog, name, getenv(name), CLI_MIN_STACK_KIB, CLI_MIN_STACK_KIB);
        return 0;
    }
    want = requested > 0 ? requested : omp_get_max_threads();
    if (want < 1) want = 1;
    if (want > cap) {
        if (from_env)
            fprintf(stderr, "%s: OMP_NUM_THREADS=%s: using %d threads (at most 4 per processor, %d processors, and at most %d)\n",
                    cli_prog, getenv("OMP_NUM_THREADS") ? getenv("OMP_NUM_THREADS") : "?", cap, procs, CLI_MAX_THREADS);
        else
            fprintf(stderr, "%s: -t %d: using %d threads (at most 4 per processor, %d processors, and at most %d)\n",
                    cli_prog, requested, cap, procs, CLI_MAX_THREADS);
        want = cap;
    }
    if (want > 1) {
        got = cli_probe_threads(want - 1, (size_t)stack, &err) + 1;
        if (got < want) {
            fprintf(stderr, "%s: warning: the system could start only %d of %d threads (%s): rendering with %d\n",
                    cli_prog, got, want, strerror(err), got);
            want = got;
        }
    }
    /* the default of every parallel region from here on, the library's own included (a
       build's roulette pilot runs one without asking for a thread count) */
    omp_set_num_threads(want);
    return want;
#else
    (void)requested;
    return 1;
#endif
    }
}

/* omp_set_num_threads holds only for the thread that calls it: a thread the program starts
   itself (the preview's render thread) begins from the environment's count again, and a
   parallel region there without a thread count (a rebuild's roulette pilot) would ask for
   threads the system could not start (libgomp then exits: OMP_STACKSIZE=100000G). Such a
   thread calls this first with cli_resolve_threads' count. */
CLI_FN void cli_thread_default(int threads)
{
#ifdef _OPENMP
    if (threads >= 1) omp_set_num_threads(threads);
#else
    (void)threads;
#endif
}

/* ------------------------------------------------------------------------------------------
   Files: identity, kind, and writing outputs safely
   ------------------------------------------------------------------------------------------ */
CLI_FN const char *cli_file_kind(mode_t m)
{
    if (S_ISDIR(m)) return "a directory";
    if (S_ISFIFO(m)) return "a FIFO";
    if (S_ISCHR(m)) return "a character device";
    if (S_ISBLK(m)) return "a block device";
    if (S_ISSOCK(m)) return "a socket";
    return "not a regular file";
}

/* A file of the run, as the system knows it: an existing file by device and inode (so a
   symlink or a hard link is the file it names), a file still to be made by its resolved
   directory and name (symlinks followed as far as they go). */
typedef struct cli_file {
    const char *flag, *name;     /* "-f" and the path as given, for messages */
    bool exists, device;         /* device: a character device (/dev/null), never damaged */
    dev_t dev;
    ino_t ino;
    char where[2 * PATH_MAX + 2];  /* a missing file's resolved directory / name */
} cli_file;

CLI_FN void cli_identify(cli_file *f, const char *flag, const char *name)
{
    struct stat st;
    char cur[PATH_MAX], link[PATH_MAX], dir[PATH_MAX], *real;
    const char *slash;
    int hops;
    memset(f, 0, sizeof *f);
    f->flag = flag; f->name = name;
    if (stat(name, &st) == 0) {
        f->exists = true;
        f->device = S_ISCHR(st.st_mode);
        f->dev = st.st_dev; f->ino = st.st_ino;
        return;
    }
    snprintf(cur, sizeof cur, "%s", name);
    for (hops = 0; hops < 40 && lstat(cur, &st) == 0 && S_ISLNK(st.st_mode); ++hops) {   /* a dangling link */
        ssize_t n = readlink(cur, link, sizeof link - 1);
        if (n <= 0) break;
        link[n] = 0;
        if (link[0] != '/' && (slash = strrchr(cur, '/')) != NULL) {
            size_t dl = (size_t)(slash - cur) + 1, ll = strlen(link);   /* keeps "dir/" */
            if (dl + ll >= sizeof cur) break;
            memcpy(cur + dl, link, ll + 1);
        } else {
            memcpy(cur, link, strlen(link) + 1);
        }
    }
    slash = strrchr(cur, '/');
    if (!slash) snprintf(dir, sizeof dir, ".");
    else if (slash == cur) snprintf(dir, sizeof dir, "/");
    else snprintf(dir, sizeof dir, "%.*s", (int)(slash - cur), cur);
    real = realpath(dir, NULL);
    {
        const char *d = real ? real : dir, *b = slash ? slash + 1 : cur;
        size_t dl = strlen(d), bl = strlen(b);
        if (dl + 1 + bl < sizeof f->where) {
            memcpy(f->where, d, dl);
            f->where[dl] = '/';
            memcpy(f->where + dl + 1, b, bl + 1);
        } else {
            memcpy(f->where, name, strlen(name) < sizeof f->where ? strlen(name) + 1 : 0);
        }
    }
    free(real);
}
CLI_FN bool cli_same_file(const cli_file *a, const cli_file *b)
{
    if (a->exists != b->exists) return false;
    if (a->exists) return a->dev == b->dev && a->ino == b->ino;
    return strcmp(a->where, b->where) == 0;
}
/* No output may be an input or another output (character devices such as /dev/null are
   outputs that nothing reads back). Returns 0, or 2 after one line naming both. */
CLI_FN int cli_check_aliases(const cli_file *in, int nin, const cli_file *out, int nout)
{
    int i, j;
    for (i = 0; i < nout; ++i) {
        if (out[i].exists && out[i].device) continue;
        for (j = 0; j < nin; ++j)
            if (cli_same_file(&out[i], &in[j])) {
                fprintf(stderr, "%s: %s %s: is the same file as the input %s%s%s: an output may not replace an input of the run\n",
                        cli_prog, out[i].flag, out[i].name, in[j].flag, in[j].flag[0] ? " " : "", in[j].name);
                return 2;
            }
        for (j = 0; j < i; ++j)
            if (cli_same_file(&out[i], &out[j])) {
                fprintf(stderr, "%s: %s %s: is the same file as the output %s %s: two outputs of the run may not share a file\n",
                        cli_prog, out[i].flag, out[i].name, out[j].flag, out[j].name);
                return 2;
            }
    }
    return 0;
}

/* What a file that is not a scene (or camera file) is, from its first bytes; NULL when it
   may be one. text_only: a NUL among them makes it "a binary file" (a camera file is text;
   a scene may be a binary PLY, which starts with a text header anyway). */
CLI_FN const char *cli_sniff_kind(const char *path, bool text_only)
{
    unsigned char b[16];
    size_t n, i;
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    n = fread(b, 1, sizeof b, f);
    fclose(f);
    if (n >= 8 && memcmp(b, "\211PNG\r\n\032\n", 8) == 0) return "a PNG image";
    if (n >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF) return "a JPEG image";
    if (n >= 3 && b[0] == 'P' && (b[1] == 'F' || b[1] == 'f') && (b[2] == '\n' || b[2] == ' ' || b[2] == '\r')) return "a PFM image";
    if (n >= 3 && b[0] == 'P' && b[1] >= '1' && b[1] <= '6' && (b[2] == '\n' || b[2] == ' ' || b[2] == '\r')) return "a PNM (PPM/PGM/PBM) image";
    if (n >= 10 && (memcmp(b, "#?RADIANCE", 10) == 0 || memcmp(b, "#?RGBE", 6) == 0)) return "a Radiance HDR image";
    if (n >= 4 && b[0] == 0x76 && b[1] == 0x2F && b[2] == 0x31 && b[3] == 0x01) return "an OpenEXR image";
    if (n >= 6 && (memcmp(b, "GIF87a", 6) == 0 || memcmp(b, "GIF89a", 6) == 0)) return "a GIF image";
    if (n >= 4 && (memcmp(b, "II*", 4) == 0 || memcmp(b, "MM\0*", 4) == 0)) return "a TIFF image";
    if (n >= 4 && memcmp(b, "\177ELF", 4) == 0) return "an executable (ELF)";
    if (n >= 4 && memcmp(b, "%PDF", 4) == 0) return "a PDF document";
    if (n >= 4 && memcmp(b, "PK\003\004", 4) == 0) return "a ZIP archive";
    if (n >= 2 && b[0] == 0x1F && b[1] == 0x8B) return "a gzip file";
    if (n >= 4 && memcmp(b, "glTF", 4) == 0) return "a binary glTF scene (fogrt does not read glTF)";
    for (i = 0; text_only && i < n; ++i)          /* a NUL in the first bytes: not text */
        if (b[i] == 0) return "a binary file";
    return NULL;
}

/* ---- writing: encoded in memory, written to a temporary file in the same directory,
   fsync'ed, closed and renamed over the target; every step checked ---- */
typedef struct cli_membuf { unsigned char *data; size_t size, cap; bool failed; } cli_membuf;

CLI_FN void cli_membuf_put(cli_membuf *b, const void *p, size_t n)
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
/* stb_image_write's callback */
CLI_FN void cli_membuf_stb(void *context, void *data, int size)
{
    if (size > 0) cli_membuf_put((cli_membuf *)context, data, (size_t)size);
}

/* The temporary file being written, for the signal handler to remove on a second Ctrl-C. */
static volatile sig_atomic_t cli_temp_live = 0;
static char cli_temp_path[PATH_MAX + 64];

/* Where an output goes. A symlink is followed (its target is replaced, not the link); an
   existing character device (/dev/null, /dev/full) is written in place; a regular file or a
   new name is written through a temporary file next to it. */
typedef struct cli_output {
    const char *flag, *name;       /* for messages: "-f", the path as given */
    char path[PATH_MAX];           /* the file actually replaced */
    bool direct;
} cli_output;

static void cli_split_dir(const char *path, char *dir, size_t n, const char **base)
{
    const char *slash = strrchr(path, '/');
    if (!slash) { snprintf(dir, n, "."); *base = path; }
    else if (slash == path) { snprintf(dir, n, "/"); *base = slash + 1; }
    else { snprintf(dir, n, "%.*s", (int)(slash - path), path); *base = slash + 1; }
}
static int cli_make_temp(const cli_output *t)
{
    char dir[PATH_MAX];
    const char *base;
    int fd;
    cli_split_dir(t->path, dir, sizeof dir, &base);
    if ((size_t)snprintf(cli_temp_path, sizeof cli_temp_path, "%s/.%s.tmp-XXXXXX", dir, base) >= sizeof cli_temp_path) {
        errno = ENAMETOOLONG;
        return -1;
    }
    fd = mkstemp(cli_temp_path);
    if (fd >= 0) cli_temp_live = 1;
    return fd;
}
CLI_FN void cli_drop_temp(void)
{
    if (cli_temp_live) { unlink(cli_temp_path); cli_temp_live = 0; }
}
static bool cli_out_fail(const cli_output *t, const char *what)
{
    fprintf(stderr, "%s: %s%s%s: %s: %s\n", cli_prog, t->flag, t->flag[0] ? " " : "", t->name, what, strerror(errno));
    return false;
}
/* Checks before rendering that the output can be written (so a long render never ends in a
   lost image): the same steps as the real write, on an empty temporary file. */
CLI_FN bool cli_prepare_output(cli_output *t, const char *flag, const char *name)
{
    struct stat st;
    int fd;
    t->flag = flag; t->name = name; t->direct = false;
    if (strlen(name) >= sizeof t->path) { errno = ENAMETOOLONG; return cli_out_fail(t, "cannot write"); }
    snprintf(t->path, sizeof t->path, "%s", name);
    if (stat(name, &st) == 0) {
        if (S_ISREG(st.st_mode)) {
            char *real = realpath(name, NULL);
            if (real) { snprintf(t->path, sizeof t->path, "%s", real); free(real); }
        } else if (S_ISCHR(st.st_mode)) {
            t->direct = true;
            fd = open(name, O_WRONLY | O_NOCTTY);
            if (fd < 0) return cli_out_fail(t, "cannot write");
            close(fd);
            return true;
        } else {
            fprintf(stderr, "%s: %s %s: is %s, not a regular file\n", cli_prog, flag, name, cli_file_kind(st.st_mode));
            return false;
        }
    } else if (errno != ENOENT) {
        return cli_out_fail(t, "cannot write");
    }
    fd = cli_make_temp(t);
    if (fd < 0) { cli_temp_live = 0; return cli_out_fail(t, "cannot write"); }
    close(fd);
    cli_drop_temp();
    return true;
}
static bool cli_write_all(int fd, const unsigned char *p, size_t n)
{
    while (n > 0) {
        ssize_t k = write(fd, p, n > ((size_t)1 << 30) ? ((size_t)1 << 30) : n);
        if (k < 0 && errno == EINTR) continue;
        if (k <= 0) { if (k == 0) errno = EIO; return false; }
        p += k; n -= (size_t)k;
    }
    return true;
}
/* Writes b to the prepared output; one message naming the file on failure, and the old
   file, if any, is left as it was. */
CLI_FN bool cli_write_output(cli_output *t, const cli_membuf *b)
{
    struct stat st;
    mode_t mode, mask;
    int fd, e;
    if (t->direct) {
        fd = open(t->path, O_WRONLY | O_NOCTTY | O_TRUNC);
        if (fd < 0) return cli_out_fail(t, "cannot write");
        if (!cli_write_all(fd, b->data, b->size)) { e = errno; close(fd); errno = e; return cli_out_fail(t, "write failed"); }
        if (close(fd) != 0) return cli_out_fail(t, "write failed");
        return true;
    }
    mask = umask(0); umask(mask);
    mode = stat(t->path, &st) == 0 ? (st.st_mode & 07777) : (mode_t)(0666 & ~mask);
    fd = cli_make_temp(t);
    if (fd < 0) { cli_temp_live = 0; return cli_out_fail(t, "cannot write"); }
    if (fchmod(fd, mode) != 0 || !cli_write_all(fd, b->data, b->size) ||
        (fsync(fd) != 0 && errno != EINVAL && errno != EROFS)) {
        e = errno; close(fd); cli_drop_temp(); errno = e;
        return cli_out_fail(t, "write failed");
    }
    if (close(fd) != 0) { e = errno; cli_drop_temp(); errno = e; return cli_out_fail(t, "write failed"); }
    if (rename(cli_temp_path, t->path) != 0) { e = errno; cli_drop_temp(); errno = e; return cli_out_fail(t, "could not replace the file"); }
    cli_temp_live = 0;
    return true;
}

/* A linear PFM (little endian, bottom row first) of rgb (rows from the top) into out. */
CLI_FN bool cli_encode_pfm(int W, int H, const float *rgb, cli_membuf *out)
{
    char header[64];
    int y, n = snprintf(header, sizeof header, "PF\n%d %d\n-1.0\n", W, H);
    cli_membuf_put(out, header, (size_t)n);
    for (y = H - 1; y >= 0; --y) {
        const float *row = rgb + (size_t)y * (size_t)W * 3;
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
        size_t i;
        for (i = 0; i < (size_t)W * 3; ++i) {
            unsigned char b[4], t;
            memcpy(b, &row[i], 4);
            t = b[0]; b[0] = b[3]; b[3] = t; t = b[1]; b[1] = b[2]; b[2] = t;
            cli_membuf_put(out, b, 4);
        }
#else
        cli_membuf_put(out, row, sizeof(float) * 3 * (size_t)W);
#endif
    }
    return !out->failed;
}

/* ------------------------------------------------------------------------------------------
   Media inside the scene's objects (--medium NAME): the names the loader reports, NAME found
   among them, the media and interfaces handed to the scene, the build's refusals
   ------------------------------------------------------------------------------------------ */
/* A shape the loader added (fogrt_load_options.on_shape) and its node, material and
   geometry names ("" for none). */
typedef struct cli_shape { fogrt_shape_kind kind; uint32_t index; char *name[3]; } cli_shape;
typedef struct cli_shapes {
    cli_shape *items; size_t count, cap;
    bool oom;
    const char *level[3];        /* what the three names are in the scene's format */
    const char *scene;           /* the scene file, or "the default scene", for messages */
} cli_shapes;

CLI_FN void cli_shapes_init(cli_shapes *S, const char *scene)
{
    static const char *const dae[3] = { "node", "material", "geometry" };
    static const char *const obj[3] = { "object (o)", "material (usemtl)", "group (g)" };
    int k;
    memset(S, 0, sizeof *S);
    for (k = 0; k < 3; ++k) S->level[k] = scene && cli_ends_with(scene, ".obj") ? obj[k] : dae[k];
    S->scene = scene ? scene : "the default scene";
}
CLI_FN void cli_shapes_free(cli_shapes *S)
{
    size_t i;
    int k;
    for (i = 0; i < S->count; ++i)
        for (k = 0; k < 3; ++k) free(S->items[i].name[k]);
    free(S->items);
    S->items = NULL; S->count = S->cap = 0;
}
/* fogrt_load_options.on_shape: keeps a copy of the names (the loader's live only during the
   call). Running out of memory is remembered and told by cli_apply_media. */
CLI_FN void cli_on_shape(void *user, fogrt_shape_kind kind, uint32_t index, const char *node, const char *material,
                         const char *geometry)
{
    cli_shapes *S = (cli_shapes *)user;
    const char *n[3];
    cli_shape *sh;
    int k;
    n[0] = node; n[1] = material; n[2] = geometry;
    if (S->oom) return;
    if (S->count == S->cap) {
        size_t cap = S->cap ? 2 * S->cap : 64;
        cli_shape *p = (cli_shape *)realloc(S->items, cap * sizeof *p);
        if (!p) { S->oom = true; return; }
        S->items = p; S->cap = cap;
    }
    sh = &S->items[S->count];
    sh->kind = kind; sh->index = index;
    for (k = 0; k < 3; ++k) {
        size_t len = strlen(n[k]) + 1;
        sh->name[k] = (char *)malloc(len);
        if (sh->name[k]) memcpy(sh->name[k], n[k], len);
        else S->oom = true;
    }
    if (S->oom) { for (k = 0; k < 3; ++k) free(sh->name[k]); return; }
    S->count++;
}

/* A name as a message may quote it: control bytes and bytes that are not well-formed UTF-8
   become '?', so a scene file never writes raw bytes to the terminal. */
CLI_FN void cli_put_name(cli_membuf *b, const char *name)
{
    const unsigned char *p = (const unsigned char *)name;
    while (*p) {
        int n = *p < 0x80 ? 0 : (*p & 0xE0) == 0xC0 && *p >= 0xC2 ? 1 : (*p & 0xF0) == 0xE0 ? 2 : (*p & 0xF8) == 0xF0 && *p <= 0xF4 ? 3 : -1, k;
        for (k = 1; k <= n; ++k) if ((p[k] & 0xC0) != 0x80) n = -1;
        if (n < 0 || (n == 0 && (*p < 0x20 || *p == 0x7F))) { cli_membuf_put(b, "?", 1); p++; continue; }
        cli_membuf_put(b, p, (size_t)n + 1);
        p += n + 1;
    }
}
CLI_FN void cli_put(cli_membuf *b, const char *fmt, ...)
{
    char tmp[256];
    va_list ap;
    int n;
    va_start(ap, fmt);
    n = vsnprintf(tmp, sizeof tmp, fmt, ap);
    va_end(ap);
    if (n > 0) cli_membuf_put(b, tmp, (size_t)n < sizeof tmp ? (size_t)n : sizeof tmp - 1);
}
/* Prints the message being built as one line on stderr and frees it. */
CLI_FN void cli_put_line(cli_membuf *b)
{
    cli_membuf_put(b, "\n", 1);
    if (!b->failed) fwrite(b->data, 1, b->size, stderr);
    else fprintf(stderr, "%s: out of memory\n", cli_prog);
    free(b->data);
    memset(b, 0, sizeof *b);
}
/* "mesh 3 (node a, material red)": a shape and its other names than level's. */
CLI_FN void cli_put_shape(cli_membuf *b, const cli_shapes *S, const cli_shape *sh, int level)
{
    int k, told = 0;
    cli_put(b, "%s %u", sh->kind == FOGRT_SHAPE_MESH ? "mesh" : "sphere", (unsigned)sh->index);
    for (k = 0; k < 3; ++k) {
        if (k == level || !sh->name[k][0]) continue;
        cli_put(b, "%s%s ", told++ ? ", " : " (", S->level[k]);
        cli_put_name(b, sh->name[k]);
    }
    if (told) cli_put(b, ")");
}
/* The scene's names, level by level, each once (at most 24 a level). */
CLI_FN void cli_put_names(cli_membuf *b, const cli_shapes *S)
{
    int k;
    for (k = 0; k < 3; ++k) {
        size_t i, j, shown = 0, more = 0;
        for (i = 0; i < S->count; ++i) {
            const char *n = S->items[i].name[k];
            for (j = 0; j < i && strcmp(S->items[j].name[k], n) != 0; ++j) {}
            if (!n[0] || j < i) continue;
            if (shown == 24) { more++; continue; }
            cli_put(b, shown++ ? ", " : "; %s names: ", S->level[k]);
            cli_put_name(b, n);
        }
        if (more) cli_put(b, " and %lu more", (unsigned long)more);
    }
}
/* The shape NAME names: a node name first, then a material name, then a geometry name
   (OBJ: object, usemtl, group); one shape at the first level that has the name. Returns 0
   (*out its place in S) or 2 after one line: no such name (the scene's names listed), or a
   name several shapes share at its level (they are listed). */
CLI_FN int cli_find_shape(const cli_shapes *S, const char *name, size_t *out)
{
    cli_membuf b;
    size_t i, n = 0, first = 0;
    int level;
    memset(&b, 0, sizeof b);
    for (level = 0; level < 3 && n == 0; ++level)
        for (i = 0; i < S->count; ++i)
            if (strcmp(S->items[i].name[level], name) == 0 && n++ == 0) first = i;
    if (n == 1) { *out = first; return 0; }
    cli_put(&b, "%s: --medium ", cli_prog);
    cli_put_name(&b, name);
    if (n > 1) {
        level--;
        cli_put(&b, ": %u objects of %s share the %s name ", (unsigned)n, S->scene, S->level[level]);
        cli_put_name(&b, name);
        for (i = first; i < S->count; ++i) {
            if (strcmp(S->items[i].name[level], name) != 0) continue;
            cli_put(&b, i == first ? ": " : ", ");
            cli_put_shape(&b, S, &S->items[i], level);
        }
        cli_put(&b, "; give a name only one of them has");
    } else {
        for (i = 0; i < S->count && !S->items[i].name[0][0] && !S->items[i].name[1][0] && !S->items[i].name[2][0]; ++i) {}
        if (i == S->count) cli_put(&b, ": %s has no named objects (a .dae names its nodes, materials and geometries, an OBJ its o, usemtl and g)", S->scene);
        else {
            cli_put(&b, ": %s has no %s, %s or %s named ", S->scene, S->level[0], S->level[1], S->level[2]);
            cli_put_name(&b, name);
            cli_put_names(&b, S);
        }
    }
    cli_put_line(&b);
    return 2;
}

#ifndef FOGRT_NO_SHAPES
/* The medium of --medium NAME: fogrt's defaults for a fog a scene does not have (albedo
   0.9, g 0), changed by its flags (-g alone: the paper's density 0.2). */
CLI_FN fogrt_medium_desc cli_medium_desc(const cli_fog *f)
{
    fogrt_medium_desc md;
    memset(&md, 0, sizeof md);
    md.albedo.x = md.albedo.y = md.albedo.z = 0.9f;
    md.sigma_t = f->density_set ? f->density : 0.2f;
    if (f->albedo_set) md.albedo = f->albedo;
    if (f->g_set) md.g = f->g;
    cli_common_media_apply(f, &md);
    return md;
}
/* One --medium handed to the scene: its surface an interface, its medium inside. */
CLI_FN fogrt_result cli_set_medium(fogrt_scene *scene, const cli_medium *m, uint32_t *iface)
{
    fogrt_result r = FOGRT_RESULT_OK;
    if (m->interface && *iface == UINT32_MAX) {
        fogrt_material_desc md;
        memset(&md, 0, sizeof md);
        md.type = FOGRT_BSDF_INTERFACE;
        r = fogrt_scene_add_material(scene, &md, iface);
    }
    if (!r && m->interface) r = fogrt_scene_set_shape_material(scene, m->kind, m->index, *iface);
    if (!r && (m->fog.density_set || m->fog.paper_g)) {
        fogrt_medium_desc md = cli_medium_desc(&m->fog);
        r = fogrt_scene_set_interior(scene, m->kind, m->index, &md);
    }
    return r;
}
#endif
/* Every --medium: its object found by name in S (the loader's names), two --medium of one
   object refused, then the interfaces and media handed to the scene. Returns 0, 2 after one
   line (a name not found or shared, a medium the scene refuses) or 1 (out of memory). */
CLI_FN int cli_apply_media(fogrt_scene *scene, cli_common *c, const cli_shapes *S)
{
    int i, j, st;
    if (c->media_count == 0) return 0;
    if (S->oom) { fprintf(stderr, "%s: --medium: out of memory keeping the scene's names\n", cli_prog); return 1; }
    for (i = 0; i < c->media_count; ++i) {
        cli_medium *m = &c->media[i];
        size_t k;
        if ((st = cli_find_shape(S, m->name, &k)) != 0) return st;
        m->found = true; m->kind = S->items[k].kind; m->index = S->items[k].index;
        for (j = 0; j < i; ++j)
            if (c->media[j].kind == m->kind && c->media[j].index == m->index) {
                cli_membuf b;
                memset(&b, 0, sizeof b);
                cli_put(&b, "%s: --medium ", cli_prog); cli_put_name(&b, m->name);
                cli_put(&b, ": names the same object as --medium "); cli_put_name(&b, c->media[j].name);
                cli_put(&b, " (%s %u): one --medium per object", m->kind == FOGRT_SHAPE_MESH ? "mesh" : "sphere", (unsigned)m->index);
                cli_put_line(&b);
                return 2;
            }
    }
#ifndef FOGRT_NO_SHAPES
    {
        uint32_t iface = UINT32_MAX;
        for (i = 0; i < c->media_count; ++i) {
            fogrt_result r = cli_set_medium(scene, &c->media[i], &iface);
            if (r) {
                cli_membuf b;
                memset(&b, 0, sizeof b);
                cli_put(&b, "%s: --medium ", cli_prog); cli_put_name(&b, c->media[i].name);
                cli_put(&b, ": %s", fogrt_scene_last_error(scene)[0] ? fogrt_scene_last_error(scene) : fogrt_result_string(r));
                cli_put_line(&b);
                return r == FOGRT_RESULT_OUT_OF_MEMORY ? 1 : 2;
            }
        }
    }
#else
    (void)scene;
#endif
    return 0;
}
/* A build the scene refused while --medium is in force: the core's message, which numbers
   the shapes it names ("mesh 3", "sphere 0"), told by the --medium flags of those shapes
   (else by every --medium). One line; returns 2 (1: out of memory). */
CLI_FN int cli_media_build_failed(const cli_common *c, const char *msg, fogrt_result r)
{
    cli_membuf b;
    const char *p;
    int named = 0, i;
    memset(&b, 0, sizeof b);
    cli_put(&b, "%s: ", cli_prog);
    for (p = msg; *p; ++p) {
        bool mesh = strncmp(p, "mesh ", 5) == 0, sphere = strncmp(p, "sphere ", 7) == 0;
        unsigned long v;
        char *end;
        if (!mesh && !sphere) continue;
        v = strtoul(p + (mesh ? 5 : 7), &end, 10);
        if (end == p + (mesh ? 5 : 7)) continue;
        for (i = 0; i < c->media_count; ++i)
            if (c->media[i].found && c->media[i].kind == (mesh ? FOGRT_SHAPE_MESH : FOGRT_SHAPE_SPHERE) && c->media[i].index == v) {
                cli_put(&b, named++ ? " and --medium " : "--medium ");
                cli_put_name(&b, c->media[i].name);
            }
    }
    for (i = 0; !named && i < c->media_count; ++i) {     /* no shape named: every --medium */
        cli_put(&b, i ? " and --medium " : "--medium ");
        cli_put_name(&b, c->media[i].name);
    }
    cli_put(&b, ": %s", msg[0] ? msg : fogrt_result_string(r));
    cli_put_line(&b);
    return r == FOGRT_RESULT_OUT_OF_MEMORY ? 1 : 2;
}
/* "; media in objects: Sphere1 (density 2), box (interface, empty)" for the header and
   summary lines (nothing without --medium). */
CLI_FN void cli_describe_media(const cli_common *c, char *buf, size_t n)
{
    size_t len;
    int i;
    buf[0] = '\0';
    for (i = 0; i < c->media_count; ++i) {
        const cli_medium *m = &c->media[i];
        bool filled = m->fog.density_set || m->fog.paper_g;
        len = strlen(buf);
        snprintf(buf + len, n - len, "%s%s (%s%s", i ? ", " : "; media in objects: ", m->name, m->interface ? "interface, " : "",
                 filled ? "density " : "empty)");
        len = strlen(buf);
        if (filled) snprintf(buf + len, n - len, "%g)", (double)(m->fog.density_set ? m->fog.density : 0.2f));
    }
}

#endif /* FOGRT_CLI_COMMON_H */
