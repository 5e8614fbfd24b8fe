/* fogrt_load.h - v0.1 - scene files for fogrt: CS184 COLLADA (.dae), OBJ and PLY - MIT license

    An optional companion of fogrt.h. It reads the Blender-exported COLLADA scenes of the
    UC Berkeley CS184 path tracer (with their <extra><technique profile="CGL"> extension)
    the way CS184 reads them, and OBJ / PLY meshes, and fills a fogrt_scene through the
    public fogrt.h API only. fogrt.h itself never needs this file: the core stays libc + libm.
    This file uses libc, libm and <stdio.h>.

    DO THIS
    =======
    In exactly one C file, after the fogrt implementation (or anywhere fogrt.h is visible):

        #define FOGRT_LOAD_IMPLEMENTATION
        #include "fogrt_load.h"

    QUICK START
    ===========
        fogrt_load_options opt = {0};            // zero = defaults
        fogrt_load_report rep;
        opt.image_width = 480; opt.image_height = 360;   // the camera is framed for this size
        if (fogrt_load_file(scene, "CBbunny.dae", &opt, &rep) != FOGRT_RESULT_OK)
            fprintf(stderr, "%s:%d: %s\n", rep.file, rep.line, rep.message);

    OPTIONS (define before including the implementation)
    =======
    FOGRT_LOAD_MALLOC(sz) / FOGRT_LOAD_REALLOC(p,sz) / FOGRT_LOAD_FREE(p)   all three or none
    FOGRT_LOAD_MAX_DEPTH   deepest <node> nesting accepted (default 128)

    ERRORS
    ======
    Every loader returns a fogrt_result and fills a fogrt_load_report. On failure the report
    names the file, the 1-based line (0 when no line applies) and a one-line message, so
    "file:line: message" can be printed as is. A malformed or truncated file gives
    FOGRT_RESULT_PARSE_ERROR, a missing file FOGRT_RESULT_IO_ERROR. Loading is all or
    nothing: the whole file is parsed and checked before the first fogrt_scene_add_* call,
    so a file that fails leaves the scene exactly as it was (barring out-of-memory inside
    fogrt itself). Warnings (a microfacet material replaced, an unsupported light type
    skipped, ...) go to options.logger and are counted in report.warnings.

    CS184 COLLADA: WHAT IS READ, AND WHERE FOGRT DIFFERS
    ====================================================
    Same as CS184 (its conventions):
    - asset/up_axis: Y_UP as is; Z_UP maps (x,y,z) to (-x,z,y); X_UP maps it to (y,x,-z). A
      file without up_axis is read as Y_UP (the COLLADA default) with a warning.
    - <matrix> is row-major; fewer than 16 numbers are zero-filled, not rejected; scanning
      of a node's transforms stops at its first <matrix>.
    - url / target references go through one global table of every id in the document.
    - <polylist> and <triangles> with their input offsets; <vcount> gives polygon sizes.
    - CGL spheres: <geometry> without <mesh> whose CGL technique has <sphere><radius>; the
      radius is scaled by the length of the node's transformed X axis.
    - Materials: the CGL technique of the effect wins, and among its children the last one
      of emission / mirror / microfacet / refraction / glass wins; else the phong (then
      lambert) diffuse colour; else diffuse grey 0.5. A textured diffuse is grey 0.5.
    - Shading normals are recomputed from connectivity: the normalised area-weighted sum of
      the incident triangles' winding normals. A connected part with open (boundary) edges,
      such as the Cornell walls, gets the negated normal, which is what CS184 computes for
      those planar quads (pointing into the box). File normals are ignored, as in CS184.
    - Camera: the DAE camera's position and orientation are not used, only the direction c =
      normalize(M (0,0,-1,1)). The eye is put at C + 1.5 |E| c where C and E are the centre
      and the diagonal of the bounding box of all geometry (lights excluded), looking at C
      with +Y up. The file's xfov / yfov (or aspect_ratio) are fitted to a 4:3 frame exactly
      as CS184 fits them to its 800x600 window (the narrower direction is widened).
    - Lights: the CGL technique wins over technique_common; the light type is the first child
      element of the chosen technique; <color> is the intensity / radiance.
    Deliberately different (physics, or fogrt's own model):
    - Framing at every resolution: CS184 keeps its focal length in pixels, so `-r W H` crops
      or widens the view. fogrt keeps the 4:3 frame of the 800x600 window whole at every
      resolution: wider images add room at the sides, taller ones above and below
      (fogrt_load_fit_fov). 480x360 and 800x600 therefore show the same picture.
    - Point and spot lights fall off as 1/r^2; area lights are sampled with the correct
      1/r^2 pdf; diffuse is reflectance/pi (fogrt's integrator does all of this).
    - n-gons are fan-triangulated (CS184 keeps only the first triangle of each polygon).
      Every <polylist>, <triangles> and <polygons> of a mesh is read (P31 reads the first
      polylist only); each list's material symbol is bound through <instance_material>,
      falling back to the first one (CS184 binds the first one to the whole mesh).
    - The index stride is the largest input offset + 1 (the COLLADA rule; CS184 counts the
      recognised inputs, which misreads files with extra inputs such as COLOR).
    - <translate>, <rotate> (axis x y z, angle in degrees) and <scale> compose in document
      order as the COLLADA spec says (CS184's versions of these are broken).
    - A node whose transform mirrors (negative determinant) has its triangles re-wound so
      their front side stays the front side.
    - Lights and emitters. The emissive mesh is the light: it is sampled for next-event
      estimation and seen by rays, and emits from the front (counter-clockwise) side only.
      A CGL <area> light becomes an emissive rectangle (centre = node origin, emitting along
      local -Z, side lengths = the node's X and Y scale, radiance = its colour) only when
      the file has no emissive mesh; otherwise it describes the same lamp and is not added
      twice. <point>: a point light of intensity = colour. <ambient>: constant radiance from
      the upper (+Y) hemisphere. <directional>: not supported by fogrt, skipped with a
      warning. <spot>: see below.
    - Spot lights. Blender writes the FULL cone angle in falloff_angle (degrees) and its
      "spot blend" (0..1) in falloff_exponent. fogrt uses
          cutoff = falloff_angle / 2                    (half-angle where light ends)
          beam   = cutoff * (1 - clamp(blend, 0, 1))    (half-angle of full intensity)
          I(theta) = colour * clamp((cutoff - theta) / (cutoff - beam), 0, 1) / r^2
      with theta the angle from the spot axis (local -Z): full inside the beam, linear in
      the angle down to zero at the cutoff. Missing values take the COLLADA defaults
      (falloff_angle 180, falloff_exponent 0). The paper's renderer used a hard cone at the
      cutoff without 1/r^2.

    OBJ AND PLY
    ===========
    OBJ: v, vn and f (v, v/t, v//n, v/t/n, negative = relative indices); polygons are fan-
    triangulated; everything else (vt, o, g, s, usemtl, mtllib, l, p) is ignored. PLY: ascii,
    binary_little_endian and binary_big_endian; a "vertex" element with x y z (and optionally
    nx ny nz; every other property is skipped), a "face" element with a vertex_indices (or
    vertex_index) list; other elements are skipped. Without normals in the file, smooth
    area-weighted vertex normals are computed. With the default placement the mesh is scaled
    uniformly and moved to stand on the floor of fogrt's default Cornell box (see
    fogrt_load_options.place), so `fogrt_scene_add_default` + `fogrt_load_ply` renders any
    model in one go.

    LICENSE
    =======
    MIT, the same as fogrt.h.
*/
#ifndef FOGRT_LOAD_H_INCLUDED
#define FOGRT_LOAD_H_INCLUDED

#include "fogrt.h"

#ifndef FOGRT_LOAD_API
#define FOGRT_LOAD_API FOGRT_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

typedef enum fogrt_load_place {
    FOGRT_LOAD_PLACE_DEFAULT = 0,   /* = CORNELL for OBJ/PLY */
    FOGRT_LOAD_PLACE_CORNELL,       /* scale and move the mesh into fit_min..fit_max, on its floor */
    FOGRT_LOAD_PLACE_AS_IS,         /* use the file's coordinates */
    FOGRT_LOAD_PLACE_NUM,
    FOGRT_LOAD_PLACE_FORCE_U32 = 0x7FFFFFFF
} fogrt_load_place;

/* fogrt_load_options (all zero = defaults)
     image_width, image_height  the image the camera is framed for (.dae); 0: 800 x 600
     logger                     warnings and notes; NULL: silent
     no_camera                  .dae: do not set the camera
     place                      OBJ/PLY placement (CORNELL)
     fit_min, fit_max           OBJ/PLY: the box the mesh is fitted into (both zero: the free
                                floor area of the default Cornell box, see FOGRT_LOAD_FIT_*);
                                the mesh stands on fit_min.y, centred in x and z
     use_material, material     OBJ/PLY: the material of the mesh; else a new diffuse 0.75 grey */
typedef struct fogrt_load_options {
    int image_width, image_height;
    fogrt_logger logger;
    bool no_camera;
    fogrt_load_place place;
    fogrt_vec3 fit_min, fit_max;
    bool use_material;
    uint32_t material;
} fogrt_load_options;

/* The default box OBJ/PLY models are fitted into: the free front-left corner of the floor of
   fogrt_scene_add_default's Cornell box (x, z in [-1, 1], y in [0, 1.5]), clear of its walls,
   its two spheres, the spot light's cone and the ceiling lamp. */
#define FOGRT_LOAD_FIT_MIN_X (-0.8f)
#define FOGRT_LOAD_FIT_MIN_Y 0.0f
#define FOGRT_LOAD_FIT_MIN_Z 0.15f
#define FOGRT_LOAD_FIT_MAX_X (-0.2f)
#define FOGRT_LOAD_FIT_MAX_Y 0.7f
#define FOGRT_LOAD_FIT_MAX_Z 0.75f

/* What a loader did, or why it failed. */
typedef struct fogrt_load_report {
    /* failure (result != OK): "file:line: message" */
    char file[256];
    int line;                      /* 1-based; 0 when no line applies */
    char message[256];
    /* what was added to the scene */
    uint32_t triangles, spheres, materials;
    uint32_t point_lights, spot_lights;
    uint32_t area_rectangles;      /* CGL <area> lights added as emissive rectangles */
    uint32_t area_lights_merged;   /* CGL <area> lights not added: the file has an emissive mesh */
    uint32_t emissive_triangles;
    bool ambient;                  /* an <ambient> light set the environment */
    uint32_t warnings;
    /* OBJ / PLY: counts declared in the file */
    uint32_t vertices, faces;
    /* .dae camera (has_camera: the file had one; the camera is set either way) */
    bool has_camera;
    fogrt_camera_desc camera;      /* the camera given to fogrt_scene_set_camera */
    float frame_tan_half_y;        /* framing: tan of half the vertical fov of the 4:3 frame */
    float frame_aspect;            /* 4/3 */
} fogrt_load_report;

/* Loads by extension: .dae, .obj, .ply (case-insensitive). */
FOGRT_LOAD_API fogrt_result fogrt_load_file(fogrt_scene *scene, const char *path,
                                            const fogrt_load_options *options, fogrt_load_report *report);

/* CS184 COLLADA scene: geometry, materials, lights and the CS184 camera. */
FOGRT_LOAD_API fogrt_result fogrt_load_dae(fogrt_scene *scene, const char *path,
                                           const fogrt_load_options *options, fogrt_load_report *report);
/* OBJ / PLY mesh, placed per options.place. */
FOGRT_LOAD_API fogrt_result fogrt_load_obj(fogrt_scene *scene, const char *path,
                                           const fogrt_load_options *options, fogrt_load_report *report);
FOGRT_LOAD_API fogrt_result fogrt_load_ply(fogrt_scene *scene, const char *path,
                                           const fogrt_load_options *options, fogrt_load_report *report);

/* The same from memory (size bytes at data, need not be NUL-terminated); name is used in
   messages (NULL: "<memory>"). */
FOGRT_LOAD_API fogrt_result fogrt_load_dae_memory(fogrt_scene *scene, const void *data, size_t size,
                                                  const char *name, const fogrt_load_options *options,
                                                  fogrt_load_report *report);
FOGRT_LOAD_API fogrt_result fogrt_load_obj_memory(fogrt_scene *scene, const void *data, size_t size,
                                                  const char *name, const fogrt_load_options *options,
                                                  fogrt_load_report *report);
FOGRT_LOAD_API fogrt_result fogrt_load_ply_memory(fogrt_scene *scene, const void *data, size_t size,
                                                  const char *name, const fogrt_load_options *options,
                                                  fogrt_load_report *report);

/* Framing: sets camera->fov_deg and fov_is_horizontal so that a frame of aspect frame_aspect
   and vertical half-angle tangent frame_tan_half_y fits whole into a width x height image,
   touching two opposite edges (the vertical fov is kept when the image is at least as wide
   as the frame, else the horizontal one). width or height <= 0: the frame's own aspect. */
FOGRT_LOAD_API void fogrt_load_fit_fov(float frame_tan_half_y, float frame_aspect, int width, int height,
                                       fogrt_camera_desc *camera);

/* A CS184 camera settings file (what its GUI dumps and `-c FILE` reads): hFov vFov ar nClip
   fClip / pos target / phi theta r minR maxR / c2w (9) / screenW screenH screenDist
   [/ focalDistance lensRadius]. Fills *camera (position, look_at, up from c2w's second
   column, lens) framed for width x height: the saved screen size and its focal length in
   pixels give the frame. */
FOGRT_LOAD_API fogrt_result fogrt_load_camera_file(const char *path, int width, int height,
                                                   fogrt_camera_desc *camera, fogrt_load_report *report);
FOGRT_LOAD_API fogrt_result fogrt_load_camera_memory(const void *data, size_t size, const char *name,
                                                     int width, int height, fogrt_camera_desc *camera,
                                                     fogrt_load_report *report);

#ifdef __cplusplus
}
#endif
#endif /* FOGRT_LOAD_H_INCLUDED */

/* ============================================================================================
   Implementation
   ============================================================================================ */
#ifdef FOGRT_LOAD_IMPLEMENTATION
#ifndef FOGRT_LOAD_IMPLEMENTATION_INCLUDED
#define FOGRT_LOAD_IMPLEMENTATION_INCLUDED

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <stdarg.h>
#include <math.h>
#include <float.h>
#include <errno.h>

#if defined(FOGRT_LOAD_MALLOC) != defined(FOGRT_LOAD_FREE) || defined(FOGRT_LOAD_MALLOC) != defined(FOGRT_LOAD_REALLOC)
#error "fogrt_load: define all of FOGRT_LOAD_MALLOC, FOGRT_LOAD_REALLOC and FOGRT_LOAD_FREE, or none"
#endif
#ifndef FOGRT_LOAD_MALLOC
#define FOGRT_LOAD_MALLOC(sz) malloc(sz)
#define FOGRT_LOAD_REALLOC(p, sz) realloc(p, sz)
#define FOGRT_LOAD_FREE(p) free(p)
#endif
#ifndef FOGRT_LOAD_MAX_DEPTH
#define FOGRT_LOAD_MAX_DEPTH 128
#endif

#if defined(__GNUC__) || defined(__clang__)
#define FOGRT__LD static __attribute__((unused))
#define FOGRT__LD_PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define FOGRT__LD static
#define FOGRT__LD_PRINTF(f, a)
#endif
#ifdef FOGRT_STATIC
#define FOGRT__LD_PUBLIC static
#else
#define FOGRT__LD_PUBLIC
#endif

#define FOGRT__LD_TRY(expr) do { fogrt_result r_ = (expr); if (r_ != FOGRT_RESULT_OK) return r_; } while (0)

/* ------------------------------------------------------------------------------------------
   1. The loader context: input buffer, report, and the scene under construction
   Everything is parsed into these arrays first; fogrt__ld_commit hands them to fogrt at the
   very end, so a file that fails to parse never touches the scene.
   ------------------------------------------------------------------------------------------ */
typedef struct fogrt__ld_el {          /* one XML element */
    const char *name; uint32_t name_len;
    uint32_t attr_first, attr_count;
    int32_t parent, first_child, last_child, next;
    const char *text; uint32_t text_len; /* first non-blank text run directly inside */
    int line, text_line;
} fogrt__ld_el;
typedef struct fogrt__ld_xattr { const char *name, *value; uint32_t name_len, value_len; } fogrt__ld_xattr;

typedef struct fogrt__ld_mat { fogrt_material_desc desc; int32_t key; } fogrt__ld_mat;
typedef struct fogrt__ld_meshbuf {
    float *pos, *nrm;                 /* 3 per vertex */
    uint32_t *idx, *tmat;             /* 3 per triangle; local material per triangle */
    uint32_t nv, nt;
} fogrt__ld_meshbuf;
typedef struct fogrt__ld_sphere { fogrt_vec3 c; float r; uint32_t mat; } fogrt__ld_sphere;
typedef struct fogrt__ld_rect { fogrt_vec3 p[4]; fogrt_vec3 colour; } fogrt__ld_rect;

typedef struct fogrt__ld {
    const char *name;
    char *buf; size_t len;            /* private NUL-terminated copy of the input */
    fogrt_load_options opt;
    fogrt_load_report *rep;
    /* XML */
    fogrt__ld_el *el; uint32_t el_count, el_cap;
    fogrt__ld_xattr *at; uint32_t at_count, at_cap;
    int32_t root;
    uint32_t *ids; uint32_t ids_cap;  /* hash table of element index + 1 (0 = empty) */
    /* the scene under construction */
    fogrt__ld_mat *mats; uint32_t mat_count, mat_cap;
    fogrt__ld_meshbuf *meshes; uint32_t mesh_count, mesh_cap;
    fogrt__ld_sphere *sph; uint32_t sph_count, sph_cap;
    fogrt_light_desc *lights; uint32_t light_count, light_cap;
    fogrt__ld_rect *rects; uint32_t rect_count, rect_cap;
    fogrt_vec3 env; bool has_env;
    bool has_camera;
    double cam_dir[3];                /* CS184's c (unnormalised) */
    float frame_tan_half_y;
    double bmin[3], bmax[3]; bool has_bounds;
    uint32_t warned_flags;
} fogrt__ld;

FOGRT__LD void fogrt__ld_message(fogrt__ld *L, int line, const char *fmt, va_list ap)
{
    fogrt_load_report *r = L->rep;
    r->line = line;
    vsnprintf(r->message, sizeof r->message, fmt, ap);
}
/* Records the first error (file:line: message) and returns the result code. */
FOGRT__LD FOGRT__LD_PRINTF(4, 5) fogrt_result fogrt__ld_fail(fogrt__ld *L, fogrt_result res, int line, const char *fmt, ...)
{
    va_list ap;
    if (L->rep->message[0] == 0) {
        va_start(ap, fmt);
        fogrt__ld_message(L, line, fmt, ap);
        va_end(ap);
    }
    return res;
}
#define FOGRT__LD_PARSE FOGRT_RESULT_PARSE_ERROR
FOGRT__LD FOGRT__LD_PRINTF(3, 4) void fogrt__ld_warn(fogrt__ld *L, int line, const char *fmt, ...)
{
    char msg[256], full[600];
    va_list ap;
    L->rep->warnings++;
    if (!L->opt.logger.func) return;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (line > 0) snprintf(full, sizeof full, "%s:%d: warning: %s", L->name, line, msg);
    else snprintf(full, sizeof full, "%s: warning: %s", L->name, msg);
    L->opt.logger.func(FOGRT_LOG_WARNING, full, L->opt.logger.user_data);
}
FOGRT__LD fogrt_result fogrt__ld_oom(fogrt__ld *L)
{
    return fogrt__ld_fail(L, FOGRT_RESULT_OUT_OF_MEMORY, 0, "out of memory");
}

/* Grows *arr to hold need elements (doubling). */
FOGRT__LD fogrt_result fogrt__ld_grow(fogrt__ld *L, void **arr, uint32_t *cap, uint64_t need, size_t elem)
{
    uint64_t c = *cap ? *cap : 16;
    void *p;
    if (need <= *cap) return FOGRT_RESULT_OK;
    while (c < need) c *= 2;
    if (c > 0xFFFFFFF0u || c * elem > (uint64_t)SIZE_MAX / 2) return fogrt__ld_fail(L, FOGRT_RESULT_TOO_LARGE, 0, "too many elements");
    p = FOGRT_LOAD_REALLOC(*arr, (size_t)(c * elem));
    if (!p) return fogrt__ld_oom(L);
    *arr = p;
    *cap = (uint32_t)c;
    return FOGRT_RESULT_OK;
}
#define FOGRT__LD_PUSH(L, arr, count, cap) \
    fogrt__ld_grow((L), (void **)&(arr), &(cap), (uint64_t)(count) + 1, sizeof *(arr))

FOGRT__LD void *fogrt__ld_alloc(fogrt__ld *L, uint64_t count, size_t elem)
{
    void *p;
    if (count == 0) count = 1;
    if (count > (uint64_t)SIZE_MAX / 4 / elem) { fogrt__ld_fail(L, FOGRT_RESULT_TOO_LARGE, 0, "too large"); return NULL; }
    p = FOGRT_LOAD_MALLOC((size_t)(count * elem));
    if (!p) fogrt__ld_oom(L);
    return p;
}

FOGRT__LD void fogrt__ld_free_mesh(fogrt__ld_meshbuf *m)
{
    FOGRT_LOAD_FREE(m->pos); FOGRT_LOAD_FREE(m->nrm); FOGRT_LOAD_FREE(m->idx); FOGRT_LOAD_FREE(m->tmat);
    memset(m, 0, sizeof *m);
}
FOGRT__LD void fogrt__ld_destroy(fogrt__ld *L)
{
    uint32_t i;
    for (i = 0; i < L->mesh_count; ++i) fogrt__ld_free_mesh(&L->meshes[i]);
    FOGRT_LOAD_FREE(L->buf); FOGRT_LOAD_FREE(L->el); FOGRT_LOAD_FREE(L->at); FOGRT_LOAD_FREE(L->ids);
    FOGRT_LOAD_FREE(L->mats); FOGRT_LOAD_FREE(L->meshes); FOGRT_LOAD_FREE(L->sph);
    FOGRT_LOAD_FREE(L->lights); FOGRT_LOAD_FREE(L->rects);
    memset(L, 0, sizeof *L);
}

/* Sets up a context: copies the input (adding a NUL so strtod always stops). */
FOGRT__LD fogrt_result fogrt__ld_init(fogrt__ld *L, const void *data, size_t size, const char *name,
                                      const fogrt_load_options *opt, fogrt_load_report *rep)
{
    memset(L, 0, sizeof *L);
    memset(rep, 0, sizeof *rep);
    L->rep = rep;
    L->name = name ? name : "<memory>";
    snprintf(rep->file, sizeof rep->file, "%s", L->name);
    if (opt) L->opt = *opt;
    L->root = -1;
    if (size > (size_t)0x7FFFFFF0u) return fogrt__ld_fail(L, FOGRT_RESULT_TOO_LARGE, 0, "file larger than 2 GB");
    if (!data && size) return fogrt__ld_fail(L, FOGRT_RESULT_INVALID_ARGUMENT, 0, "no data");
    L->buf = (char *)FOGRT_LOAD_MALLOC(size + 1);
    if (!L->buf) return fogrt__ld_oom(L);
    if (size) memcpy(L->buf, data, size);
    L->buf[size] = 0;
    L->len = size;
    return FOGRT_RESULT_OK;
}

/* Reads a whole file into memory. */
FOGRT__LD fogrt_result fogrt__ld_read_file(const char *path, char **out, size_t *out_size, fogrt_load_report *rep)
{
    FILE *f;
    char *data = NULL;
    size_t size = 0, cap = 0, n;
    memset(rep, 0, sizeof *rep);
    snprintf(rep->file, sizeof rep->file, "%s", path ? path : "(null)");
    *out = NULL; *out_size = 0;
    f = path ? fopen(path, "rb") : NULL;
    if (!f) {
        snprintf(rep->message, sizeof rep->message, "cannot open: %s", path ? strerror(errno) : "no path");
        return FOGRT_RESULT_IO_ERROR;
    }
    for (;;) {
        if (size == cap) {
            char *p;
            cap = cap ? cap * 2 : 65536;
            if (cap > (size_t)0x7FFFFFF0u) {
                FOGRT_LOAD_FREE(data); fclose(f);
                snprintf(rep->message, sizeof rep->message, "file larger than 2 GB");
                return FOGRT_RESULT_TOO_LARGE;
            }
            p = (char *)FOGRT_LOAD_REALLOC(data, cap);
            if (!p) {
                FOGRT_LOAD_FREE(data); fclose(f);
                snprintf(rep->message, sizeof rep->message, "out of memory");
                return FOGRT_RESULT_OUT_OF_MEMORY;
            }
            data = p;
        }
        n = fread(data + size, 1, cap - size, f);
        size += n;
        if (n == 0) break;
    }
    if (ferror(f)) {
        FOGRT_LOAD_FREE(data); fclose(f);
        snprintf(rep->message, sizeof rep->message, "read error");
        return FOGRT_RESULT_IO_ERROR;
    }
    fclose(f);
    if (!data) { data = (char *)FOGRT_LOAD_MALLOC(1); if (!data) return FOGRT_RESULT_OUT_OF_MEMORY; }
    *out = data; *out_size = size;
    return FOGRT_RESULT_OK;
}

/* ------------------------------------------------------------------------------------------
   2. Numbers
   strtod on the private NUL-terminated copy; every number must be finite as a float.
   ------------------------------------------------------------------------------------------ */
FOGRT__LD bool fogrt__ld_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

/* Line of position p, counting newlines from a known (base, base_line). */
FOGRT__LD int fogrt__ld_line_at(const char *base, int base_line, const char *p)
{
    int line = base_line;
    for (; base < p; ++base) if (*base == '\n') line++;
    return line;
}

/* Length of the token at s (up to a blank, '<' or e; at most 16) for messages. */
FOGRT__LD int fogrt__ld_toklen(const char *s, const char *e)
{
    int n = 0;
    while (s + n < e && n < 16 && s[n] != '<' && s[n] != 0 && !(s[n] == ' ' || s[n] == '\t' || s[n] == '\n' || s[n] == '\r')) n++;
    return n;
}

/* Parses one number starting exactly at *s (no leading blanks), not beyond e. */
FOGRT__LD bool fogrt__ld_strtof(const char **s, const char *e, float *out)
{
    char *q;
    double d;
    const char *p = *s;
    if (p >= e) return false;
    /* strtod also reads "inf", "nan" and hex floats; only plain decimal numbers are accepted */
    if (!((*p >= '0' && *p <= '9') || *p == '-' || *p == '+' || *p == '.')) return false;
    d = strtod(p, &q);
    if (q == p || q > e) return false;
    if (memchr(p, 'x', (size_t)(q - p)) || memchr(p, 'X', (size_t)(q - p))) return false;   /* hex */
    if (!(d == d) || d > (double)FLT_MAX || d < -(double)FLT_MAX) return false;
    *out = (float)d;
    *s = q;
    return true;
}

/* Parses whitespace-separated floats from [s, e) into out[0..max). Stops after max numbers
   (the rest is ignored). *n = numbers read. An unreadable token is an error at its line. */
FOGRT__LD fogrt_result fogrt__ld_floats(fogrt__ld *L, const char *s, const char *e, int line,
                                        float *out, uint64_t max, uint64_t *n)
{
    const char *base = s;
    uint64_t k = 0;
    while (k < max) {
        while (s < e && fogrt__ld_space(*s)) ++s;
        if (s >= e) break;
        {
            const char *t = s;
            if (!fogrt__ld_strtof(&s, e, &out[k]) || (s < e && !fogrt__ld_space(*s)))
                return fogrt__ld_fail(L, FOGRT__LD_PARSE, fogrt__ld_line_at(base, line, t),
                                      "expected a finite number, found '%.*s'", fogrt__ld_toklen(t, e), t);
        }
        k++;
    }
    *n = k;
    return FOGRT_RESULT_OK;
}

/* Parses whitespace-separated non-negative integers (< 2^32 - 1). */
FOGRT__LD fogrt_result fogrt__ld_uints(fogrt__ld *L, const char *s, const char *e, int line,
                                       uint32_t *out, uint64_t max, uint64_t *n)
{
    const char *base = s;
    uint64_t k = 0;
    while (k < max) {
        uint64_t v = 0;
        const char *t;
        while (s < e && fogrt__ld_space(*s)) ++s;
        if (s >= e) break;
        t = s;
        while (s < e && *s >= '0' && *s <= '9') {
            v = v * 10 + (uint64_t)(*s - '0');
            if (v >= 0xFFFFFFFFu)
                return fogrt__ld_fail(L, FOGRT__LD_PARSE, fogrt__ld_line_at(base, line, t), "index too large");
            ++s;
        }
        if (s == t || (s < e && !fogrt__ld_space(*s)))
            return fogrt__ld_fail(L, FOGRT__LD_PARSE, fogrt__ld_line_at(base, line, t),
                                  "expected a non-negative integer, found '%.*s'", fogrt__ld_toklen(t, e), t);
        out[k++] = (uint32_t)v;
    }
    *n = k;
    return FOGRT_RESULT_OK;
}

/* At most how many numbers a text of len bytes can hold (each needs a character and a blank). */
FOGRT__LD uint64_t fogrt__ld_max_numbers(uint32_t len) { return ((uint64_t)len + 1) / 2; }

/* ------------------------------------------------------------------------------------------
   3. A minimal XML reader
   Elements, attributes, text, comments, CDATA, <?...?> and <!DOCTYPE>; the five predefined
   entities and numeric character references in attribute values. No namespaces, no DTD.
   The tree is kept as arrays of elements and attributes pointing into the buffer.
   ------------------------------------------------------------------------------------------ */
FOGRT__LD bool fogrt__ld_starts(const char *p, const char *end, const char *lit)
{
    size_t n = strlen(lit);
    return (size_t)(end - p) >= n && memcmp(p, lit, n) == 0;
}
/* First occurrence of lit in [p, end), or NULL. */
FOGRT__LD const char *fogrt__ld_find(const char *p, const char *end, const char *lit)
{
    size_t n = strlen(lit);
    for (; (size_t)(end - p) >= n; ++p)
        if (*p == lit[0] && memcmp(p, lit, n) == 0) return p;
    return NULL;
}
FOGRT__LD int fogrt__ld_count_lines(const char *p, const char *q)
{
    int n = 0;
    for (; p < q; ++p) if (*p == '\n') n++;
    return n;
}
FOGRT__LD bool fogrt__ld_name_char(char c)
{
    return !fogrt__ld_space(c) && c != '/' && c != '>' && c != '<' && c != '=' && c != '"' && c != '\'' && c != 0;
}

/* Decodes &lt; &gt; &amp; &quot; &apos; &#N; &#xH; in place; returns the new length. */
FOGRT__LD uint32_t fogrt__ld_decode(char *s, uint32_t len)
{
    uint32_t i = 0, o = 0;
    while (i < len) {
        if (s[i] == '&') {
            static const char *names[5] = { "lt;", "gt;", "amp;", "quot;", "apos;" };
            static const char chars[5] = { '<', '>', '&', '"', '\'' };
            int k;
            bool done = false;
            for (k = 0; k < 5 && !done; ++k) {
                size_t n = strlen(names[k]);
                if (len - i - 1 >= n && memcmp(s + i + 1, names[k], n) == 0) {
                    s[o++] = chars[k]; i += 1 + (uint32_t)n; done = true;
                }
            }
            if (!done && i + 2 < len && s[i + 1] == '#') {
                uint32_t j = i + 2, cp = 0, digits = 0;
                bool hex = s[j] == 'x' || s[j] == 'X';
                if (hex) ++j;
                while (j < len && digits < 8) {
                    char c = s[j];
                    int v = c >= '0' && c <= '9' ? c - '0' : hex && c >= 'a' && c <= 'f' ? c - 'a' + 10
                          : hex && c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
                    if (v < 0) break;
                    cp = cp * (hex ? 16u : 10u) + (uint32_t)v; ++digits; ++j;
                }
                if (digits > 0 && j < len && s[j] == ';' && cp > 0 && cp <= 0x10FFFF) {
                    /* UTF-8; the reference is at least 4 bytes long, the output at most 4 */
                    if (cp < 0x80) s[o++] = (char)cp;
                    else if (cp < 0x800) { s[o++] = (char)(0xC0 | (cp >> 6)); s[o++] = (char)(0x80 | (cp & 63)); }
                    else if (cp < 0x10000) { s[o++] = (char)(0xE0 | (cp >> 12)); s[o++] = (char)(0x80 | ((cp >> 6) & 63)); s[o++] = (char)(0x80 | (cp & 63)); }
                    else { s[o++] = (char)(0xF0 | (cp >> 18)); s[o++] = (char)(0x80 | ((cp >> 12) & 63)); s[o++] = (char)(0x80 | ((cp >> 6) & 63)); s[o++] = (char)(0x80 | (cp & 63)); }
                    i = j + 1;
                    done = true;
                }
            }
            if (done) continue;
        }
        s[o++] = s[i++];
    }
    return o;
}

FOGRT__LD fogrt_result fogrt__ld_xml_parse(fogrt__ld *L)
{
    char *p = L->buf, *end = L->buf + L->len;
    int line = 1;
    int32_t cur = -1;
    if (end - p >= 3 && (unsigned char)p[0] == 0xEF && (unsigned char)p[1] == 0xBB && (unsigned char)p[2] == 0xBF) p += 3;
    while (p < end) {
        if (*p != '<') {                                   /* a text run */
            char *s = p;
            int sline = line;
            bool blank = true;
            while (p < end && *p != '<') {
                if (*p == '\n') line++;
                else if (!fogrt__ld_space(*p)) blank = false;
                ++p;
            }
            if (!blank) {
                if (cur < 0) return fogrt__ld_fail(L, FOGRT__LD_PARSE, sline, "text outside the root element");
                if (!L->el[cur].text) { L->el[cur].text = s; L->el[cur].text_len = (uint32_t)(p - s); L->el[cur].text_line = sline; }
            }
            continue;
        }
        if (fogrt__ld_starts(p, end, "<!--")) {           /* comment */
            const char *q = fogrt__ld_find(p + 4, end, "-->");
            if (!q) return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "comment not closed (missing '-->')");
            line += fogrt__ld_count_lines(p, q);
            p = (char *)q + 3;
            continue;
        }
        if (fogrt__ld_starts(p, end, "<![CDATA[")) {      /* CDATA: text */
            const char *q = fogrt__ld_find(p + 9, end, "]]>");
            if (!q) return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "CDATA section not closed (missing ']]>')");
            if (cur < 0) return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "CDATA outside the root element");
            if (!L->el[cur].text) { L->el[cur].text = p + 9; L->el[cur].text_len = (uint32_t)(q - (p + 9)); L->el[cur].text_line = line; }
            line += fogrt__ld_count_lines(p, q);
            p = (char *)q + 3;
            continue;
        }
        if (fogrt__ld_starts(p, end, "<?")) {             /* declaration / processing instruction */
            const char *q = fogrt__ld_find(p + 2, end, "?>");
            if (!q) return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "'<?' not closed (missing '?>')");
            line += fogrt__ld_count_lines(p, q);
            p = (char *)q + 2;
            continue;
        }
        if (fogrt__ld_starts(p, end, "<!")) {             /* <!DOCTYPE ...> with an optional [...] */
            char *q = p + 2;
            int depth = 0;
            while (q < end && !(*q == '>' && depth == 0)) {
                if (*q == '[') depth++;
                else if (*q == ']' && depth > 0) depth--;
                else if (*q == '\n') line++;
                ++q;
            }
            if (q >= end) return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "'<!' declaration not closed");
            p = q + 1;
            continue;
        }
        if (p + 1 < end && p[1] == '/') {                 /* end tag */
            char *n = p + 2, *q = n;
            fogrt__ld_el *e;
            while (q < end && fogrt__ld_name_char(*q)) ++q;
            if (cur < 0) return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "closing tag </%.*s> without an opening tag", (int)(q - n > 40 ? 40 : q - n), n);
            e = &L->el[cur];
            if ((uint32_t)(q - n) != e->name_len || memcmp(n, e->name, e->name_len) != 0)
                return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "closing tag </%.*s> does not match <%.*s> opened at line %d",
                                      (int)(q - n > 40 ? 40 : q - n), n, (int)(e->name_len > 40 ? 40 : e->name_len), e->name, e->line);
            while (q < end && fogrt__ld_space(*q)) { if (*q == '\n') line++; ++q; }
            if (q >= end || *q != '>') return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "expected '>' to end </%.*s>", (int)(e->name_len > 40 ? 40 : e->name_len), e->name);
            p = q + 1;
            cur = e->parent;
            continue;
        }
        {                                                  /* start tag */
            char *n = p + 1, *q = n;
            int32_t id;
            fogrt__ld_el *e;
            bool open;
            while (q < end && fogrt__ld_name_char(*q)) ++q;
            if (q == n) return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "expected an element name after '<'");
            if (cur < 0 && L->root >= 0) return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "a second root element <%.*s>", (int)(q - n > 40 ? 40 : q - n), n);
            FOGRT__LD_TRY(FOGRT__LD_PUSH(L, L->el, L->el_count, L->el_cap));
            id = (int32_t)L->el_count++;
            e = &L->el[id];
            memset(e, 0, sizeof *e);
            e->name = n; e->name_len = (uint32_t)(q - n);
            e->attr_first = L->at_count;
            e->parent = cur; e->first_child = e->last_child = e->next = -1;
            e->line = line;
            for (;;) {                                     /* attributes */
                char *an, *vs, quote;
                uint32_t alen;
                while (q < end && fogrt__ld_space(*q)) { if (*q == '\n') line++; ++q; }
                if (q >= end) return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "unexpected end of file inside the tag <%.*s> (line %d)",
                                                    (int)(L->el[id].name_len > 40 ? 40 : L->el[id].name_len), L->el[id].name, L->el[id].line);
                if (*q == '>') { ++q; open = true; break; }
                if (*q == '/') {
                    if (q + 1 < end && q[1] == '>') { q += 2; open = false; break; }
                    return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "expected '/>'");
                }
                an = q;
                while (q < end && fogrt__ld_name_char(*q)) ++q;
                if (q == an) return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "unexpected character '%c' in a tag", *q ? *q : '?');
                alen = (uint32_t)(q - an);
                while (q < end && fogrt__ld_space(*q)) { if (*q == '\n') line++; ++q; }
                if (q >= end || *q != '=') return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "attribute '%.*s' has no value", (int)(alen > 40 ? 40 : alen), an);
                ++q;
                while (q < end && fogrt__ld_space(*q)) { if (*q == '\n') line++; ++q; }
                if (q >= end || (*q != '"' && *q != '\'')) return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "attribute '%.*s': value not quoted", (int)(alen > 40 ? 40 : alen), an);
                quote = *q++;
                vs = q;
                while (q < end && *q != quote) {
                    if (*q == '<') return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "'<' inside the value of attribute '%.*s'", (int)(alen > 40 ? 40 : alen), an);
                    if (*q == '\n') line++;
                    ++q;
                }
                if (q >= end) return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "unexpected end of file in the value of attribute '%.*s'", (int)(alen > 40 ? 40 : alen), an);
                FOGRT__LD_TRY(FOGRT__LD_PUSH(L, L->at, L->at_count, L->at_cap));
                L->at[L->at_count].name = an; L->at[L->at_count].name_len = alen;
                L->at[L->at_count].value = vs;
                L->at[L->at_count].value_len = fogrt__ld_decode(vs, (uint32_t)(q - vs));
                L->at_count++;
                L->el[id].attr_count++;
                ++q;
            }
            e = &L->el[id];
            if (cur >= 0) {
                if (L->el[cur].last_child >= 0) L->el[L->el[cur].last_child].next = id;
                else L->el[cur].first_child = id;
                L->el[cur].last_child = id;
            } else {
                L->root = id;
            }
            if (open) cur = id;
            p = q;
        }
    }
    if (L->len > 0 && L->buf[L->len - 1] == '\n' && line > 1) line--;   /* name the last line, not the one after it */
    if (cur >= 0)
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "unexpected end of file: <%.*s> opened at line %d is not closed",
                              (int)(L->el[cur].name_len > 40 ? 40 : L->el[cur].name_len), L->el[cur].name, L->el[cur].line);
    if (L->root < 0) return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "no XML element found");
    return FOGRT_RESULT_OK;
}

/* ---- tree queries ---- */
FOGRT__LD bool fogrt__ld_is(const fogrt__ld *L, int32_t e, const char *name)
{
    size_t n = strlen(name);
    return e >= 0 && L->el[e].name_len == n && memcmp(L->el[e].name, name, n) == 0;
}
FOGRT__LD int32_t fogrt__ld_child(const fogrt__ld *L, int32_t e, const char *name)
{
    int32_t c;
    if (e < 0) return -1;
    for (c = L->el[e].first_child; c >= 0; c = L->el[c].next)
        if (fogrt__ld_is(L, c, name)) return c;
    return -1;
}
FOGRT__LD int32_t fogrt__ld_next_named(const fogrt__ld *L, int32_t c, const char *name)
{
    for (c = c >= 0 ? L->el[c].next : -1; c >= 0; c = L->el[c].next)
        if (fogrt__ld_is(L, c, name)) return c;
    return -1;
}
/* Walks a slash-separated path of first children ("optics/technique_common/perspective"). */
FOGRT__LD int32_t fogrt__ld_path(const fogrt__ld *L, int32_t e, const char *path)
{
    char part[64];
    while (e >= 0 && *path) {
        size_t n = strcspn(path, "/");
        if (n >= sizeof part) return -1;
        memcpy(part, path, n); part[n] = 0;
        e = fogrt__ld_child(L, e, part);
        path += n;
        if (*path == '/') ++path;
    }
    return e;
}
/* Attribute value (length in *len), or NULL. */
FOGRT__LD const char *fogrt__ld_attr(const fogrt__ld *L, int32_t e, const char *name, uint32_t *len)
{
    uint32_t i;
    size_t n = strlen(name);
    if (e < 0) return NULL;
    for (i = 0; i < L->el[e].attr_count; ++i) {
        const fogrt__ld_xattr *a = &L->at[L->el[e].attr_first + i];
        if (a->name_len == n && memcmp(a->name, name, n) == 0) { if (len) *len = a->value_len; return a->value; }
    }
    return NULL;
}
FOGRT__LD bool fogrt__ld_attr_is(const fogrt__ld *L, int32_t e, const char *name, const char *value)
{
    uint32_t len;
    const char *v = fogrt__ld_attr(L, e, name, &len);
    return v && len == strlen(value) && memcmp(v, value, len) == 0;
}
/* Integer attribute; false when absent. A malformed value is an error (*res). */
FOGRT__LD bool fogrt__ld_attr_uint(fogrt__ld *L, int32_t e, const char *name, uint64_t *out, fogrt_result *res)
{
    uint32_t len, i;
    uint64_t v = 0;
    const char *s = fogrt__ld_attr(L, e, name, &len);
    *res = FOGRT_RESULT_OK;
    if (!s) return false;
    while (len && fogrt__ld_space(*s)) { ++s; --len; }
    while (len && fogrt__ld_space(s[len - 1])) --len;
    if (len == 0 || len > 10) { *res = fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[e].line, "attribute %s: expected a non-negative integer", name); return false; }
    for (i = 0; i < len; ++i) {
        if (s[i] < '0' || s[i] > '9') { *res = fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[e].line, "attribute %s: expected a non-negative integer", name); return false; }
        v = v * 10 + (uint64_t)(s[i] - '0');
    }
    *out = v;
    return true;
}

FOGRT__LD uint32_t fogrt__ld_hash(const char *s, uint32_t n)
{
    uint32_t h = 2166136261u, i;
    for (i = 0; i < n; ++i) { h ^= (unsigned char)s[i]; h *= 16777619u; }
    return h;
}
/* One global table of every id in the document (the first element with an id wins). */
FOGRT__LD fogrt_result fogrt__ld_build_ids(fogrt__ld *L)
{
    uint32_t i, n = 0, cap = 16;
    for (i = 0; i < L->el_count; ++i) if (fogrt__ld_attr(L, (int32_t)i, "id", NULL)) n++;
    while (cap < 2 * n + 2) cap *= 2;
    L->ids = (uint32_t *)fogrt__ld_alloc(L, cap, sizeof(uint32_t));
    if (!L->ids) return FOGRT_RESULT_OUT_OF_MEMORY;
    memset(L->ids, 0, cap * sizeof(uint32_t));
    L->ids_cap = cap;
    for (i = 0; i < L->el_count; ++i) {
        uint32_t len, h, k;
        const char *v = fogrt__ld_attr(L, (int32_t)i, "id", &len);
        if (!v) continue;
        for (h = fogrt__ld_hash(v, len) & (cap - 1);; h = (h + 1) & (cap - 1)) {
            if (L->ids[h] == 0) { L->ids[h] = i + 1; break; }
            k = L->ids[h] - 1;
            {
                uint32_t klen;
                const char *kv = fogrt__ld_attr(L, (int32_t)k, "id", &klen);
                if (klen == len && memcmp(kv, v, len) == 0) break;   /* duplicate: keep the first */
            }
        }
    }
    return FOGRT_RESULT_OK;
}
/* Resolves "#id" (or "id") to an element, or -1. */
FOGRT__LD int32_t fogrt__ld_lookup(const fogrt__ld *L, const char *v, uint32_t len)
{
    uint32_t h;
    if (!v || !L->ids) return -1;
    if (len && v[0] == '#') { ++v; --len; }
    for (h = fogrt__ld_hash(v, len) & (L->ids_cap - 1); L->ids[h]; h = (h + 1) & (L->ids_cap - 1)) {
        uint32_t klen, k = L->ids[h] - 1;
        const char *kv = fogrt__ld_attr(L, (int32_t)k, "id", &klen);
        if (klen == len && memcmp(kv, v, len) == 0) return (int32_t)k;
    }
    return -1;
}
/* Follows the attribute attr ("url", "target", "source") of e to its element. */
FOGRT__LD int32_t fogrt__ld_ref(const fogrt__ld *L, int32_t e, const char *attr)
{
    uint32_t len;
    const char *v = fogrt__ld_attr(L, e, attr, &len);
    return v ? fogrt__ld_lookup(L, v, len) : -1;
}

/* Reads between min_n and max_n floats from the text of element e (error if fewer than min_n). */
FOGRT__LD fogrt_result fogrt__ld_el_floats(fogrt__ld *L, int32_t e, float *out, uint32_t min_n, uint32_t max_n, uint32_t *n)
{
    uint64_t k = 0;
    const fogrt__ld_el *x = &L->el[e];
    if (x->text) FOGRT__LD_TRY(fogrt__ld_floats(L, x->text, x->text + x->text_len, x->text_line, out, max_n, &k));
    if (k < min_n)
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, x->line, "<%.*s> needs %u number%s, found %u",
                              (int)(x->name_len > 40 ? 40 : x->name_len), x->name, min_n, min_n == 1 ? "" : "s", (unsigned)k);
    if (n) *n = (uint32_t)k;
    return FOGRT_RESULT_OK;
}
/* Reads a colour (3 floats, a 4th alpha ignored), >= 0, from child `name` of e. Returns
   false (without error) if the child is missing and required is false. */
FOGRT__LD fogrt_result fogrt__ld_child_vec3(fogrt__ld *L, int32_t e, const char *name, bool required, bool non_negative,
                                            fogrt_vec3 *out, bool *found)
{
    float v[4];
    int32_t c = fogrt__ld_child(L, e, name);
    if (found) *found = c >= 0;
    if (c < 0) {
        if (!required) return FOGRT_RESULT_OK;
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[e].line, "<%.*s> needs a <%s> child",
                              (int)(L->el[e].name_len > 40 ? 40 : L->el[e].name_len), L->el[e].name, name);
    }
    FOGRT__LD_TRY(fogrt__ld_el_floats(L, c, v, 3, 4, NULL));
    if (non_negative && (v[0] < 0 || v[1] < 0 || v[2] < 0))
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[c].line, "<%s> must not be negative", name);
    out->x = v[0]; out->y = v[1]; out->z = v[2];
    return FOGRT_RESULT_OK;
}
FOGRT__LD fogrt_result fogrt__ld_child_float(fogrt__ld *L, int32_t e, const char *name, bool required, float *out, bool *found)
{
    int32_t c = fogrt__ld_child(L, e, name);
    if (found) *found = c >= 0;
    if (c < 0) {
        if (!required) return FOGRT_RESULT_OK;
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[e].line, "<%.*s> needs a <%s> child",
                              (int)(L->el[e].name_len > 40 ? 40 : L->el[e].name_len), L->el[e].name, name);
    }
    return fogrt__ld_el_floats(L, c, out, 1, 1, NULL);
}

/* ------------------------------------------------------------------------------------------
   4. Small linear algebra: 4x4 row-major matrices in double precision
   ------------------------------------------------------------------------------------------ */
FOGRT__LD void fogrt__ld_identity(double m[16])
{
    int i;
    for (i = 0; i < 16; ++i) m[i] = (i % 5 == 0) ? 1.0 : 0.0;
}
FOGRT__LD void fogrt__ld_mul(const double a[16], const double b[16], double out[16])
{
    double r[16];
    int i, j, k;
    for (i = 0; i < 4; ++i)
        for (j = 0; j < 4; ++j) {
            double s = 0.0;
            for (k = 0; k < 4; ++k) s += a[4 * i + k] * b[4 * k + j];
            r[4 * i + j] = s;
        }
    memcpy(out, r, sizeof r);
}
/* m (x, y, z, w): all four output components. */
FOGRT__LD void fogrt__ld_xform4(const double m[16], double x, double y, double z, double w, double out[4])
{
    int i;
    for (i = 0; i < 4; ++i) out[i] = m[4 * i] * x + m[4 * i + 1] * y + m[4 * i + 2] * z + m[4 * i + 3] * w;
}
FOGRT__LD double fogrt__ld_det3(const double m[16])
{
    return m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) + m[2] * (m[4] * m[9] - m[5] * m[8]);
}
FOGRT__LD double fogrt__ld_len3(const double v[3]) { return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }
/* Double to float vector, failing when it does not fit a finite float. */
FOGRT__LD bool fogrt__ld_to_vec3(const double d[3], fogrt_vec3 *out)
{
    int i;
    for (i = 0; i < 3; ++i) if (!(d[i] == d[i]) || d[i] > (double)FLT_MAX || d[i] < -(double)FLT_MAX) return false;
    out->x = (float)d[0]; out->y = (float)d[1]; out->z = (float)d[2];
    return true;
}
FOGRT__LD fogrt_vec3 fogrt__ld_v3(float x, float y, float z) { fogrt_vec3 v; v.x = x; v.y = y; v.z = z; return v; }
FOGRT__LD bool fogrt__ld_black(fogrt_vec3 c) { return c.x == 0.0f && c.y == 0.0f && c.z == 0.0f; }

/* ------------------------------------------------------------------------------------------
   5. Mesh helpers shared by all formats: smooth normals, compaction, placement
   ------------------------------------------------------------------------------------------ */
FOGRT__LD int fogrt__ld_cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}
FOGRT__LD uint32_t fogrt__ld_find_root(uint32_t *parent, uint32_t v)
{
    while (parent[v] != v) { parent[v] = parent[parent[v]]; v = parent[v]; }
    return v;
}

/* Smooth vertex normals as CS184 computes them: the normalised sum over the incident
   triangles of cross(b - a, c - a) (area weighted, following the winding). negate_open: a
   connected part that has open edges (used by one triangle only) gets the negated normal,
   which is what CS184's boundary walk gives for its planar Cornell quads. */
FOGRT__LD fogrt_result fogrt__ld_normals(fogrt__ld *L, fogrt__ld_meshbuf *m, bool negate_open)
{
    uint32_t t, v, i;
    double *acc;
    m->nrm = (float *)fogrt__ld_alloc(L, (uint64_t)m->nv * 3, sizeof(float));
    acc = (double *)fogrt__ld_alloc(L, (uint64_t)m->nv * 3, sizeof(double));
    if (!m->nrm || !acc) { FOGRT_LOAD_FREE(acc); return FOGRT_RESULT_OUT_OF_MEMORY; }
    memset(acc, 0, (size_t)m->nv * 3 * sizeof(double));
    for (t = 0; t < m->nt; ++t) {
        const uint32_t *id = m->idx + 3 * (size_t)t;
        const float *a = m->pos + 3 * (size_t)id[0], *b = m->pos + 3 * (size_t)id[1], *c = m->pos + 3 * (size_t)id[2];
        double e1[3], e2[3], n[3];
        for (i = 0; i < 3; ++i) { e1[i] = (double)b[i] - (double)a[i]; e2[i] = (double)c[i] - (double)a[i]; }
        n[0] = e1[1] * e2[2] - e1[2] * e2[1];
        n[1] = e1[2] * e2[0] - e1[0] * e2[2];
        n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        for (v = 0; v < 3; ++v) for (i = 0; i < 3; ++i) acc[3 * (size_t)id[v] + i] += n[i];
    }
    if (negate_open && m->nt > 0) {
        uint64_t *edges = (uint64_t *)fogrt__ld_alloc(L, (uint64_t)m->nt * 3, sizeof(uint64_t));
        uint32_t *parent = (uint32_t *)fogrt__ld_alloc(L, m->nv, sizeof(uint32_t));
        unsigned char *open = (unsigned char *)fogrt__ld_alloc(L, m->nv, 1);
        size_t ne = 0, k;
        if (!edges || !parent || !open) {
            FOGRT_LOAD_FREE(edges); FOGRT_LOAD_FREE(parent); FOGRT_LOAD_FREE(open); FOGRT_LOAD_FREE(acc);
            return FOGRT_RESULT_OUT_OF_MEMORY;
        }
        for (v = 0; v < m->nv; ++v) { parent[v] = v; open[v] = 0; }
        for (t = 0; t < m->nt; ++t) {
            const uint32_t *id = m->idx + 3 * (size_t)t;
            for (i = 0; i < 3; ++i) {
                uint32_t a = id[i], b = id[(i + 1) % 3], ra, rb;
                if (a == b) continue;
                edges[ne++] = a < b ? ((uint64_t)a << 32 | b) : ((uint64_t)b << 32 | a);
                ra = fogrt__ld_find_root(parent, a); rb = fogrt__ld_find_root(parent, b);
                if (ra != rb) parent[ra] = rb;
            }
        }
        qsort(edges, ne, sizeof *edges, fogrt__ld_cmp_u64);
        for (k = 0; k < ne;) {
            size_t run = 1;
            while (k + run < ne && edges[k + run] == edges[k]) run++;
            if (run == 1) open[fogrt__ld_find_root(parent, (uint32_t)(edges[k] >> 32))] = 1;
            k += run;
        }
        for (v = 0; v < m->nv; ++v)
            if (open[fogrt__ld_find_root(parent, v)])
                for (i = 0; i < 3; ++i) acc[3 * (size_t)v + i] = -acc[3 * (size_t)v + i];
        FOGRT_LOAD_FREE(edges); FOGRT_LOAD_FREE(parent); FOGRT_LOAD_FREE(open);
    }
    for (v = 0; v < m->nv; ++v) {
        double *n = acc + 3 * (size_t)v, len = fogrt__ld_len3(n);
        if (len > 0.0 && len < HUGE_VAL) {
            for (i = 0; i < 3; ++i) m->nrm[3 * (size_t)v + i] = (float)(n[i] / len);
        } else {                      /* isolated or cancelling: any unit vector will do */
            m->nrm[3 * (size_t)v] = 0.0f; m->nrm[3 * (size_t)v + 1] = 1.0f; m->nrm[3 * (size_t)v + 2] = 0.0f;
        }
    }
    FOGRT_LOAD_FREE(acc);
    return FOGRT_RESULT_OK;
}

/* Drops the vertices no triangle uses (keeps normals in step), so bounds and normals see
   only real geometry. */
FOGRT__LD fogrt_result fogrt__ld_compact(fogrt__ld *L, fogrt__ld_meshbuf *m)
{
    uint32_t *map, v, t, n = 0;
    map = (uint32_t *)fogrt__ld_alloc(L, m->nv, sizeof(uint32_t));
    if (!map) return FOGRT_RESULT_OUT_OF_MEMORY;
    for (v = 0; v < m->nv; ++v) map[v] = UINT32_MAX;
    for (t = 0; t < 3 * m->nt; ++t) if (map[m->idx[t]] == UINT32_MAX) map[m->idx[t]] = 0;
    for (v = 0; v < m->nv; ++v)
        if (map[v] == 0) {
            map[v] = n;
            memmove(m->pos + 3 * (size_t)n, m->pos + 3 * (size_t)v, 3 * sizeof(float));
            if (m->nrm) memmove(m->nrm + 3 * (size_t)n, m->nrm + 3 * (size_t)v, 3 * sizeof(float));
            n++;
        }
    for (t = 0; t < 3 * m->nt; ++t) m->idx[t] = map[m->idx[t]];
    m->nv = n;
    FOGRT_LOAD_FREE(map);
    return FOGRT_RESULT_OK;
}

FOGRT__LD void fogrt__ld_grow_bounds(fogrt__ld *L, const float p[3], float pad)
{
    int i;
    for (i = 0; i < 3; ++i) {
        double lo = (double)p[i] - (double)pad, hi = (double)p[i] + (double)pad;
        if (!L->has_bounds || lo < L->bmin[i]) L->bmin[i] = lo;
        if (!L->has_bounds || hi > L->bmax[i]) L->bmax[i] = hi;
    }
}
FOGRT__LD void fogrt__ld_mesh_bounds(fogrt__ld *L, const fogrt__ld_meshbuf *m)
{
    uint32_t v;
    for (v = 0; v < m->nv; ++v) { fogrt__ld_grow_bounds(L, m->pos + 3 * (size_t)v, 0.0f); L->has_bounds = true; }
}

/* OBJ/PLY placement: uniform scale into the fit box, standing on its floor, centred in x, z.
   In double precision, so that models of any size (even near FLT_MAX or with a denormal
   extent) end up inside the box. */
FOGRT__LD void fogrt__ld_place(fogrt__ld *L, fogrt__ld_meshbuf *m)
{
    double lo[3], hi[3], s = -1.0, c[3], box[3], mid[3];
    uint32_t v;
    int i;
    fogrt_vec3 fmin = L->opt.fit_min, fmax = L->opt.fit_max;
    if (fmin.x == 0 && fmin.y == 0 && fmin.z == 0 && fmax.x == 0 && fmax.y == 0 && fmax.z == 0) {
        fmin = fogrt__ld_v3(FOGRT_LOAD_FIT_MIN_X, FOGRT_LOAD_FIT_MIN_Y, FOGRT_LOAD_FIT_MIN_Z);
        fmax = fogrt__ld_v3(FOGRT_LOAD_FIT_MAX_X, FOGRT_LOAD_FIT_MAX_Y, FOGRT_LOAD_FIT_MAX_Z);
    }
    if (m->nv == 0) return;
    for (i = 0; i < 3; ++i) { lo[i] = hi[i] = (double)m->pos[i]; }
    for (v = 1; v < m->nv; ++v)
        for (i = 0; i < 3; ++i) {
            double x = (double)m->pos[3 * (size_t)v + i];
            if (x < lo[i]) lo[i] = x;
            if (x > hi[i]) hi[i] = x;
        }
    box[0] = (double)fmax.x - (double)fmin.x; box[1] = (double)fmax.y - (double)fmin.y; box[2] = (double)fmax.z - (double)fmin.z;
    for (i = 0; i < 3; ++i) {
        double ext = hi[i] - lo[i];
        if (ext > 0.0 && box[i] > 0.0 && (s < 0.0 || box[i] / ext < s)) s = box[i] / ext;
    }
    if (!(s > 0.0)) s = 1.0;                         /* a single point: keep its size */
    c[0] = 0.5 * (lo[0] + hi[0]); c[1] = lo[1]; c[2] = 0.5 * (lo[2] + hi[2]);
    mid[0] = 0.5 * ((double)fmin.x + (double)fmax.x); mid[1] = (double)fmin.y; mid[2] = 0.5 * ((double)fmin.z + (double)fmax.z);
    for (v = 0; v < m->nv; ++v)
        for (i = 0; i < 3; ++i) {
            float *p = m->pos + 3 * (size_t)v + i;
            *p = (float)(((double)*p - c[i]) * s + mid[i]);
        }
}

/* ------------------------------------------------------------------------------------------
   6. COLLADA: materials (CGL technique, else phong / lambert diffuse, else grey 0.5)
   ------------------------------------------------------------------------------------------ */
/* The CGL technique of element e: its first <extra>, the first <technique profile="CGL">. */
FOGRT__LD int32_t fogrt__ld_cgl(const fogrt__ld *L, int32_t e)
{
    int32_t extra = fogrt__ld_child(L, e, "extra"), t;
    for (t = fogrt__ld_child(L, extra, "technique"); t >= 0; t = fogrt__ld_next_named(L, t, "technique"))
        if (fogrt__ld_attr_is(L, t, "profile", "CGL")) return t;
    return -1;
}

FOGRT__LD fogrt_material_desc fogrt__ld_diffuse(float r, float g, float b)
{
    fogrt_material_desc m;
    memset(&m, 0, sizeof m);
    m.type = FOGRT_BSDF_DIFFUSE;
    m.reflectance = fogrt__ld_v3(r, g, b);
    return m;
}

FOGRT__LD fogrt_result fogrt__ld_ior(fogrt__ld *L, int32_t e, float *ior)
{
    FOGRT__LD_TRY(fogrt__ld_child_float(L, e, "ior", true, ior, NULL));
    if (!(*ior > 0.0f)) return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[fogrt__ld_child(L, e, "ior")].line, "<ior> must be > 0");
    return FOGRT_RESULT_OK;
}

/* Reads an <effect> into a material description. */
FOGRT__LD fogrt_result fogrt__ld_effect(fogrt__ld *L, int32_t effect, fogrt_material_desc *out)
{
    int32_t tech = fogrt__ld_cgl(L, effect), c, common, t;
    bool set = false;
    fogrt_material_desc m;
    for (c = tech >= 0 ? L->el[tech].first_child : -1; c >= 0; c = L->el[c].next) {
        memset(&m, 0, sizeof m);
        if (fogrt__ld_is(L, c, "emission")) {
            m.type = FOGRT_BSDF_DIFFUSE;           /* emits, reflects nothing */
            FOGRT__LD_TRY(fogrt__ld_child_vec3(L, c, "radiance", true, true, &m.emission, NULL));
        } else if (fogrt__ld_is(L, c, "mirror")) {
            m.type = FOGRT_BSDF_MIRROR;
            FOGRT__LD_TRY(fogrt__ld_child_vec3(L, c, "reflectance", true, true, &m.reflectance, NULL));
        } else if (fogrt__ld_is(L, c, "refraction")) {
            m.type = FOGRT_BSDF_REFRACTION;
            FOGRT__LD_TRY(fogrt__ld_child_vec3(L, c, "transmittance", true, true, &m.transmittance, NULL));
            FOGRT__LD_TRY(fogrt__ld_ior(L, c, &m.ior));
            m.reflectance = m.transmittance;       /* tint of total internal reflection */
        } else if (fogrt__ld_is(L, c, "glass")) {
            m.type = FOGRT_BSDF_GLASS;
            FOGRT__LD_TRY(fogrt__ld_child_vec3(L, c, "transmittance", true, true, &m.transmittance, NULL));
            FOGRT__LD_TRY(fogrt__ld_child_vec3(L, c, "reflectance", true, true, &m.reflectance, NULL));
            FOGRT__LD_TRY(fogrt__ld_ior(L, c, &m.ior));
        } else if (fogrt__ld_is(L, c, "microfacet")) {
            /* A conductor (eta + i k per channel) with Beckmann roughness alpha. fogrt has no
               microfacet BSDF: use the normal-incidence conductor Fresnel
               F0 = ((eta - 1)^2 + k^2) / ((eta + 1)^2 + k^2) as the colour of a mirror
               (alpha <= 0.25, nearly smooth) or of a diffuse surface (rougher). */
            float alpha, f0[3];
            fogrt_vec3 eta, k;
            int i;
            FOGRT__LD_TRY(fogrt__ld_child_float(L, c, "alpha", true, &alpha, NULL));
            FOGRT__LD_TRY(fogrt__ld_child_vec3(L, c, "eta", true, true, &eta, NULL));
            FOGRT__LD_TRY(fogrt__ld_child_vec3(L, c, "k", true, true, &k, NULL));
            for (i = 0; i < 3; ++i) {
                double e = (double)(i == 0 ? eta.x : i == 1 ? eta.y : eta.z), kk = (double)(i == 0 ? k.x : i == 1 ? k.y : k.z);
                f0[i] = (float)(((e - 1) * (e - 1) + kk * kk) / ((e + 1) * (e + 1) + kk * kk));
            }
            m.type = alpha <= 0.25f ? FOGRT_BSDF_MIRROR : FOGRT_BSDF_DIFFUSE;
            m.reflectance = fogrt__ld_v3(f0[0], f0[1], f0[2]);
            fogrt__ld_warn(L, L->el[c].line, "<microfacet> (alpha %g) is not supported by fogrt: loaded as a %s of reflectance %.3g %.3g %.3g",
                           (double)alpha, alpha <= 0.25f ? "mirror" : "diffuse", (double)f0[0], (double)f0[1], (double)f0[2]);
        } else {
            continue;
        }
        *out = m;                                  /* the last recognised child wins */
        set = true;
    }
    if (set) return FOGRT_RESULT_OK;
    /* profile_COMMON: the technique with sid "common" (else the first), phong then lambert */
    common = fogrt__ld_child(L, effect, "profile_COMMON");
    for (t = fogrt__ld_child(L, common, "technique"); t >= 0; t = fogrt__ld_next_named(L, t, "technique"))
        if (fogrt__ld_attr_is(L, t, "sid", "common")) break;
    if (t < 0) t = fogrt__ld_child(L, common, "technique");
    if (t >= 0) {
        static const char *shaders[2] = { "phong/diffuse/color", "lambert/diffuse/color" };
        int i;
        for (i = 0; i < 2; ++i) {
            int32_t col = fogrt__ld_path(L, t, shaders[i]);
            float v[4];
            if (col < 0) continue;
            FOGRT__LD_TRY(fogrt__ld_el_floats(L, col, v, 3, 4, NULL));
            if (v[0] < 0 || v[1] < 0 || v[2] < 0)
                return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[col].line, "diffuse colour must not be negative");
            *out = fogrt__ld_diffuse(v[0], v[1], v[2]);
            return FOGRT_RESULT_OK;
        }
    }
    *out = fogrt__ld_diffuse(0.5f, 0.5f, 0.5f);
    return FOGRT_RESULT_OK;
}

/* Local material index for a <material> element (-1: the default grey), cached. */
FOGRT__LD fogrt_result fogrt__ld_material(fogrt__ld *L, int32_t material, uint32_t *out)
{
    uint32_t i;
    fogrt_material_desc m;
    for (i = 0; i < L->mat_count; ++i) if (L->mats[i].key == material) { *out = i; return FOGRT_RESULT_OK; }
    if (material < 0) {
        m = fogrt__ld_diffuse(0.5f, 0.5f, 0.5f);
    } else {
        int32_t effect = fogrt__ld_ref(L, fogrt__ld_child(L, material, "instance_effect"), "url");
        if (effect < 0) {
            fogrt__ld_warn(L, L->el[material].line, "material has no resolvable <instance_effect>: grey 0.5");
            m = fogrt__ld_diffuse(0.5f, 0.5f, 0.5f);
        } else {
            FOGRT__LD_TRY(fogrt__ld_effect(L, effect, &m));
        }
    }
    FOGRT__LD_TRY(FOGRT__LD_PUSH(L, L->mats, L->mat_count, L->mat_cap));
    L->mats[L->mat_count].desc = m;
    L->mats[L->mat_count].key = material;
    *out = L->mat_count++;
    return FOGRT_RESULT_OK;
}

/* The material bound to a primitive list: the <instance_material> whose symbol is the list's
   material attribute, else the first one (CS184), else grey. */
FOGRT__LD fogrt_result fogrt__ld_bound_material(fogrt__ld *L, int32_t inst, int32_t list, uint32_t *out)
{
    int32_t tc = fogrt__ld_path(L, inst, "bind_material/technique_common");
    int32_t first = fogrt__ld_child(L, tc, "instance_material"), im, target = -1;
    uint32_t slen;
    const char *sym = fogrt__ld_attr(L, list, "material", &slen);
    for (im = first; sym && im >= 0; im = fogrt__ld_next_named(L, im, "instance_material")) {
        uint32_t len;
        const char *s = fogrt__ld_attr(L, im, "symbol", &len);
        if (s && len == slen && memcmp(s, sym, len) == 0) break;
    }
    if (!sym || im < 0) im = first;
    if (im >= 0) {
        target = fogrt__ld_ref(L, im, "target");
        if (target < 0 || !fogrt__ld_is(L, target, "material")) {
            fogrt__ld_warn(L, L->el[im].line, "instance_material target not found: grey 0.5");
            target = -1;
        }
    }
    return fogrt__ld_material(L, target, out);
}

/* ------------------------------------------------------------------------------------------
   7. COLLADA: geometry (meshes and CGL spheres)
   ------------------------------------------------------------------------------------------ */
typedef struct fogrt__ld_tris { uint32_t *idx, *mat; uint32_t n, cap_i, cap_m; } fogrt__ld_tris;

FOGRT__LD fogrt_result fogrt__ld_add_tri(fogrt__ld *L, fogrt__ld_tris *T, uint32_t a, uint32_t b, uint32_t c, uint32_t mat)
{
    FOGRT__LD_TRY(fogrt__ld_grow(L, (void **)&T->idx, &T->cap_i, 3 * ((uint64_t)T->n + 1), sizeof(uint32_t)));
    FOGRT__LD_TRY(fogrt__ld_grow(L, (void **)&T->mat, &T->cap_m, (uint64_t)T->n + 1, sizeof(uint32_t)));
    T->idx[3 * (size_t)T->n] = a; T->idx[3 * (size_t)T->n + 1] = b; T->idx[3 * (size_t)T->n + 2] = c;
    T->mat[T->n++] = mat;
    return FOGRT_RESULT_OK;
}

/* Fan-triangulates the polygons of one <polylist>, <triangles> or <polygons>. */
FOGRT__LD fogrt_result fogrt__ld_prims(fogrt__ld *L, int32_t list, int32_t inst, int32_t vertices, uint32_t nv,
                                       fogrt__ld_tris *T, uint32_t *skipped)
{
    int32_t c, p, vc;
    uint64_t max_off = 0, v_off = 0, count = 0, corners = 0, k, need, got;
    bool has_vertex = false, is_polylist = fogrt__ld_is(L, list, "polylist"), is_polygons = fogrt__ld_is(L, list, "polygons");
    uint32_t mat, *vcount = NULL, *ix = NULL, stride, poly, start;
    fogrt_result res;
    const fogrt__ld_el *pe;
    for (c = fogrt__ld_child(L, list, "input"); c >= 0; c = fogrt__ld_next_named(L, c, "input")) {
        uint64_t off = 0;
        fogrt__ld_attr_uint(L, c, "offset", &off, &res);
        if (res) return res;
        if (off > 255) return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[c].line, "input offset %u too large", (unsigned)off);
        if (off > max_off) max_off = off;
        if (fogrt__ld_attr_is(L, c, "semantic", "VERTEX")) {
            if (fogrt__ld_ref(L, c, "source") != vertices)
                return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[c].line, "VERTEX input must refer to the mesh's <vertices>");
            has_vertex = true;
            v_off = off;
        }
    }
    if (!has_vertex) return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[list].line, "<%s> has no VERTEX input", is_polylist ? "polylist" : is_polygons ? "polygons" : "triangles");
    stride = (uint32_t)max_off + 1;
    if (!fogrt__ld_attr_uint(L, list, "count", &count, &res)) {
        if (res) return res;
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[list].line, "<%s> has no count attribute", is_polylist ? "polylist" : is_polygons ? "polygons" : "triangles");
    }
    if (count == 0) return FOGRT_RESULT_OK;
    FOGRT__LD_TRY(fogrt__ld_bound_material(L, inst, list, &mat));

    if (is_polygons) {                      /* one <p> per polygon */
        uint32_t buf_cap = 0;
        uint64_t np = 0;
        for (p = fogrt__ld_child(L, list, "p"); p >= 0 && np < count; p = fogrt__ld_next_named(L, p, "p"), ++np) {
            pe = &L->el[p];
            need = fogrt__ld_max_numbers(pe->text_len);
            if (pe->text) {
                res = fogrt__ld_grow(L, (void **)&ix, &buf_cap, need, sizeof(uint32_t));
                if (!res) res = fogrt__ld_uints(L, pe->text, pe->text + pe->text_len, pe->text_line, ix, need, &got);
            } else { got = 0; res = FOGRT_RESULT_OK; }
            if (res) { FOGRT_LOAD_FREE(ix); return res; }
            corners = got / stride;
            for (k = 0; k < corners; ++k)
                if (ix[k * stride + v_off] >= nv) {
                    uint32_t bad = ix[k * stride + v_off];
                    FOGRT_LOAD_FREE(ix);
                    return fogrt__ld_fail(L, FOGRT__LD_PARSE, pe->line, "vertex index %u out of range (%u vertices)", bad, nv);
                }
            if (corners < 3) { (*skipped)++; continue; }
            for (k = 1; k + 1 < corners; ++k) {
                res = fogrt__ld_add_tri(L, T, ix[v_off], ix[k * stride + v_off], ix[(k + 1) * stride + v_off], mat);
                if (res) { FOGRT_LOAD_FREE(ix); return res; }
            }
        }
        FOGRT_LOAD_FREE(ix);
        if (np < count) return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[list].line, "<polygons count=\"%u\"> has only %u <p>", (unsigned)count, (unsigned)np);
        return FOGRT_RESULT_OK;
    }

    p = fogrt__ld_child(L, list, "p");
    if (p < 0) return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[list].line, "primitive list with count %u has no <p>", (unsigned)count);
    pe = &L->el[p];
    if (is_polylist) {                      /* corners per polygon */
        const fogrt__ld_el *ve;
        vc = fogrt__ld_child(L, list, "vcount");
        if (vc < 0) return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[list].line, "<polylist> has no <vcount>");
        ve = &L->el[vc];
        if (count > fogrt__ld_max_numbers(ve->text_len))
            return fogrt__ld_fail(L, FOGRT__LD_PARSE, ve->line, "<vcount> has fewer than count=%u numbers", (unsigned)count);
        vcount = (uint32_t *)fogrt__ld_alloc(L, count, sizeof(uint32_t));
        if (!vcount) return FOGRT_RESULT_OUT_OF_MEMORY;
        res = fogrt__ld_uints(L, ve->text, ve->text + ve->text_len, ve->text_line, vcount, count, &got);
        if (!res && got < count) res = fogrt__ld_fail(L, FOGRT__LD_PARSE, ve->line, "<vcount> has %u numbers, count says %u", (unsigned)got, (unsigned)count);
        if (res) { FOGRT_LOAD_FREE(vcount); return res; }
        for (k = 0; k < count; ++k) corners += vcount[k];
    } else {
        corners = 3 * count;
    }
    need = corners > fogrt__ld_max_numbers(pe->text_len) ? UINT64_MAX : corners * stride;
    if (need > fogrt__ld_max_numbers(pe->text_len)) {
        FOGRT_LOAD_FREE(vcount);
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, pe->line, "<p> is too short for %u polygons", (unsigned)count);
    }
    ix = (uint32_t *)fogrt__ld_alloc(L, need, sizeof(uint32_t));
    if (!ix) { FOGRT_LOAD_FREE(vcount); return FOGRT_RESULT_OUT_OF_MEMORY; }
    res = fogrt__ld_uints(L, pe->text, pe->text + pe->text_len, pe->text_line, ix, need, &got);
    if (!res && got < need)
        res = fogrt__ld_fail(L, FOGRT__LD_PARSE, pe->line, "<p> has %llu indices, %llu needed", (unsigned long long)got, (unsigned long long)need);
    for (k = 0; !res && k < corners; ++k)
        if (ix[k * stride + v_off] >= nv)
            res = fogrt__ld_fail(L, FOGRT__LD_PARSE, pe->line, "vertex index %u out of range (%u vertices)", ix[k * stride + v_off], nv);
    for (poly = 0, start = 0; !res && poly < count; ++poly) {
        uint32_t n = vcount ? vcount[poly] : 3, j;
        if (n < 3) { (*skipped)++; start += n; continue; }
        for (j = 1; !res && j + 1 < n; ++j)      /* fan: (0, j, j+1) */
            res = fogrt__ld_add_tri(L, T, ix[(size_t)start * stride + v_off], ix[(size_t)(start + j) * stride + v_off],
                                    ix[(size_t)(start + j + 1) * stride + v_off], mat);
        start += n;
    }
    FOGRT_LOAD_FREE(vcount); FOGRT_LOAD_FREE(ix);
    return res;
}

/* A <mesh>: positions from <vertices>/POSITION, every primitive list, world transform M. */
FOGRT__LD fogrt_result fogrt__ld_mesh(fogrt__ld *L, int32_t mesh, int32_t inst, const double M[16], int node_line)
{
    int32_t vertices = fogrt__ld_child(L, mesh, "vertices"), in, src, fa, c;
    uint64_t count = 0, got;
    float *raw = NULL;
    uint32_t nv, v, skipped = 0, t;
    fogrt__ld_tris T;
    fogrt__ld_meshbuf m;
    fogrt_result res;
    const fogrt__ld_el *fe;
    memset(&T, 0, sizeof T);
    memset(&m, 0, sizeof m);
    if (vertices < 0) return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[mesh].line, "<mesh> has no <vertices>");
    for (in = fogrt__ld_child(L, vertices, "input"); in >= 0; in = fogrt__ld_next_named(L, in, "input"))
        if (fogrt__ld_attr_is(L, in, "semantic", "POSITION")) break;
    if (in < 0) return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[vertices].line, "<vertices> has no POSITION input");
    src = fogrt__ld_ref(L, in, "source");
    fa = fogrt__ld_child(L, src, "float_array");
    if (src < 0 || fa < 0) return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[in].line, "POSITION source not found or without <float_array>");
    fe = &L->el[fa];
    /* exactly `count` floats are taken (CS184); without count, all of them */
    if (!fogrt__ld_attr_uint(L, fa, "count", &count, &res)) {
        if (res) return res;
        count = fogrt__ld_max_numbers(fe->text_len);
    } else if (count > fogrt__ld_max_numbers(fe->text_len)) {
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, fe->line, "<float_array count=\"%llu\"> holds fewer numbers", (unsigned long long)count);
    }
    raw = (float *)fogrt__ld_alloc(L, count, sizeof(float));
    if (!raw) return FOGRT_RESULT_OUT_OF_MEMORY;
    res = fe->text ? fogrt__ld_floats(L, fe->text, fe->text + fe->text_len, fe->text_line, raw, count, &got) : FOGRT_RESULT_OK;
    if (!fe->text) got = 0;
    if (!res && fogrt__ld_attr(L, fa, "count", NULL) && got < count)
        res = fogrt__ld_fail(L, FOGRT__LD_PARSE, fe->line, "<float_array> has %llu numbers, count says %llu", (unsigned long long)got, (unsigned long long)count);
    if (res) { FOGRT_LOAD_FREE(raw); return res; }
    nv = (uint32_t)(got / 3);
    for (c = L->el[mesh].first_child; c >= 0 && !res; c = L->el[c].next) {
        if (fogrt__ld_is(L, c, "polylist") || fogrt__ld_is(L, c, "triangles") || fogrt__ld_is(L, c, "polygons"))
            res = fogrt__ld_prims(L, c, inst, vertices, nv, &T, &skipped);
        else if (fogrt__ld_is(L, c, "lines") || fogrt__ld_is(L, c, "linestrips") || fogrt__ld_is(L, c, "tristrips") || fogrt__ld_is(L, c, "trifans"))
            fogrt__ld_warn(L, L->el[c].line, "<%.*s> is not supported: skipped", (int)L->el[c].name_len, L->el[c].name);
    }
    if (!res && skipped) fogrt__ld_warn(L, L->el[mesh].line, "%u polygons with fewer than 3 corners skipped", skipped);
    if (res || T.n == 0) {
        FOGRT_LOAD_FREE(raw); FOGRT_LOAD_FREE(T.idx); FOGRT_LOAD_FREE(T.mat);
        return res;
    }
    /* world positions (divided by w), mirrored transforms re-wound, unused vertices dropped */
    m.pos = raw; m.nv = nv; m.idx = T.idx; m.nt = T.n; m.tmat = T.mat;
    for (v = 0; v < nv; ++v) {
        double p[4], q[3];
        fogrt_vec3 w;
        fogrt__ld_xform4(M, (double)raw[3 * (size_t)v], (double)raw[3 * (size_t)v + 1], (double)raw[3 * (size_t)v + 2], 1.0, p);
        q[0] = p[0] / p[3]; q[1] = p[1] / p[3]; q[2] = p[2] / p[3];
        if (!fogrt__ld_to_vec3(q, &w)) {
            fogrt__ld_free_mesh(&m);
            return fogrt__ld_fail(L, FOGRT__LD_PARSE, node_line, "the node's transform sends vertex %u to infinity", v);
        }
        raw[3 * (size_t)v] = w.x; raw[3 * (size_t)v + 1] = w.y; raw[3 * (size_t)v + 2] = w.z;
    }
    if (fogrt__ld_det3(M) < 0.0)
        for (t = 0; t < m.nt; ++t) { uint32_t x = m.idx[3 * (size_t)t + 1]; m.idx[3 * (size_t)t + 1] = m.idx[3 * (size_t)t + 2]; m.idx[3 * (size_t)t + 2] = x; }
    res = fogrt__ld_compact(L, &m);
    if (!res) res = fogrt__ld_normals(L, &m, true);
    if (!res) res = FOGRT__LD_PUSH(L, L->meshes, L->mesh_count, L->mesh_cap);
    if (res) { fogrt__ld_free_mesh(&m); return res; }
    fogrt__ld_mesh_bounds(L, &m);
    L->meshes[L->mesh_count++] = m;
    return FOGRT_RESULT_OK;
}

FOGRT__LD fogrt_result fogrt__ld_geometry(fogrt__ld *L, int32_t inst, const double M[16], int node_line)
{
    int32_t geom = fogrt__ld_ref(L, inst, "url"), mesh, tech, rad;
    if (geom < 0 || !fogrt__ld_is(L, geom, "geometry")) {
        fogrt__ld_warn(L, L->el[inst].line, "instance_geometry url not found: skipped");
        return FOGRT_RESULT_OK;
    }
    mesh = fogrt__ld_child(L, geom, "mesh");
    if (mesh >= 0) return fogrt__ld_mesh(L, mesh, inst, M, node_line);
    tech = fogrt__ld_cgl(L, geom);
    rad = fogrt__ld_path(L, tech, "sphere/radius");
    if (rad >= 0) {                          /* CGL sphere */
        float r;
        double c[4], x[3], cc[3], rr;
        fogrt__ld_sphere s;
        uint32_t mat;
        FOGRT__LD_TRY(fogrt__ld_el_floats(L, rad, &r, 1, 1, NULL));
        fogrt__ld_xform4(M, 0, 0, 0, 1, c);
        cc[0] = c[0] / c[3]; cc[1] = c[1] / c[3]; cc[2] = c[2] / c[3];
        x[0] = M[0]; x[1] = M[4]; x[2] = M[8];    /* image of the X axis */
        rr = (double)r * fogrt__ld_len3(x);
        if (!fogrt__ld_to_vec3(cc, &s.c)) return fogrt__ld_fail(L, FOGRT__LD_PARSE, node_line, "sphere centre is not finite");
        if (!(rr > 0.0) || rr > (double)FLT_MAX) return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[rad].line, "sphere radius (times the node's X scale) must be > 0");
        s.r = (float)rr;
        FOGRT__LD_TRY(fogrt__ld_bound_material(L, inst, -1, &mat));
        s.mat = mat;
        FOGRT__LD_TRY(FOGRT__LD_PUSH(L, L->sph, L->sph_count, L->sph_cap));
        L->sph[L->sph_count++] = s;
        {
            float cp[3];
            cp[0] = s.c.x; cp[1] = s.c.y; cp[2] = s.c.z;
            fogrt__ld_grow_bounds(L, cp, s.r);
        }
        L->has_bounds = true;
        return FOGRT_RESULT_OK;
    }
    fogrt__ld_warn(L, L->el[geom].line, "geometry is neither a <mesh> nor a CGL sphere: skipped");
    return FOGRT_RESULT_OK;
}

/* ------------------------------------------------------------------------------------------
   8. COLLADA: lights and the camera
   ------------------------------------------------------------------------------------------ */
#define FOGRT__LD_DEG (180.0 / 3.14159265358979323846)

FOGRT__LD fogrt_result fogrt__ld_light(fogrt__ld *L, int32_t inst, const double M[16], int node_line)
{
    int32_t light = fogrt__ld_ref(L, inst, "url"), tech, type;
    fogrt_vec3 colour, pos;
    double o[4], dir[3];
    if (light < 0 || !fogrt__ld_is(L, light, "light")) {
        fogrt__ld_warn(L, L->el[inst].line, "instance_light url not found: skipped");
        return FOGRT_RESULT_OK;
    }
    tech = fogrt__ld_cgl(L, light);                   /* CGL wins over technique_common */
    if (tech < 0) tech = fogrt__ld_child(L, light, "technique_common");
    type = tech >= 0 ? L->el[tech].first_child : -1;  /* the type is the first child's tag */
    if (type < 0) {
        fogrt__ld_warn(L, L->el[light].line, "light without a technique: skipped");
        return FOGRT_RESULT_OK;
    }
    if (fogrt__ld_is(L, type, "directional")) {
        fogrt__ld_warn(L, L->el[type].line, "<directional> lights are not supported by fogrt: skipped");
        return FOGRT_RESULT_OK;
    }
    if (!fogrt__ld_is(L, type, "point") && !fogrt__ld_is(L, type, "spot") && !fogrt__ld_is(L, type, "area") && !fogrt__ld_is(L, type, "ambient")) {
        fogrt__ld_warn(L, L->el[type].line, "unknown light type <%.*s>: skipped", (int)(L->el[type].name_len > 40 ? 40 : L->el[type].name_len), L->el[type].name);
        return FOGRT_RESULT_OK;
    }
    FOGRT__LD_TRY(fogrt__ld_child_vec3(L, type, "color", true, true, &colour, NULL));
    fogrt__ld_xform4(M, 0, 0, 0, 1, o);               /* position: not divided by w (CS184) */
    if (!fogrt__ld_to_vec3(o, &pos)) return fogrt__ld_fail(L, FOGRT__LD_PARSE, node_line, "light position is not finite");
    dir[0] = -M[2]; dir[1] = -M[6]; dir[2] = -M[10];  /* local -Z */
    if (fogrt__ld_is(L, type, "ambient")) {
        L->env.x += colour.x; L->env.y += colour.y; L->env.z += colour.z;
        if (!(L->env.x <= FLT_MAX && L->env.y <= FLT_MAX && L->env.z <= FLT_MAX))
            return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[type].line, "ambient light colours add up to infinity");
        L->has_env = true;
    } else if (fogrt__ld_is(L, type, "area")) {
        /* rectangle: centre = origin, edges M(-1,0,0) and M(0,1,0), emitting along M(0,0,-1) */
        double dx[3], dy[3], n[3];
        fogrt__ld_rect r;
        int k, i;
        dx[0] = -M[0]; dx[1] = -M[4]; dx[2] = -M[8];
        dy[0] = M[1]; dy[1] = M[5]; dy[2] = M[9];
        n[0] = dx[1] * dy[2] - dx[2] * dy[1]; n[1] = dx[2] * dy[0] - dx[0] * dy[2]; n[2] = dx[0] * dy[1] - dx[1] * dy[0];
        if (!(fogrt__ld_len3(n) > 0.0)) {
            fogrt__ld_warn(L, L->el[type].line, "area light with zero area: skipped");
            return FOGRT_RESULT_OK;
        }
        for (k = 0; k < 4; ++k) {
            double su = (k == 1 || k == 2) ? 0.5 : -0.5, sv = (k >= 2) ? 0.5 : -0.5, q[3];
            for (i = 0; i < 3; ++i) q[i] = o[i] + su * dx[i] + sv * dy[i];
            if (!fogrt__ld_to_vec3(q, &r.p[k])) return fogrt__ld_fail(L, FOGRT__LD_PARSE, node_line, "area light corner is not finite");
        }
        if (n[0] * dir[0] + n[1] * dir[1] + n[2] * dir[2] < 0.0) {   /* mirrored node: keep -Z the front */
            fogrt_vec3 x = r.p[1]; r.p[1] = r.p[3]; r.p[3] = x;
        }
        r.colour = colour;
        FOGRT__LD_TRY(FOGRT__LD_PUSH(L, L->rects, L->rect_count, L->rect_cap));
        L->rects[L->rect_count++] = r;
    } else {
        fogrt_light_desc d;
        memset(&d, 0, sizeof d);
        d.type = FOGRT_LIGHT_POINT;
        d.position = pos;
        d.intensity = colour;
        if (fogrt__ld_is(L, type, "spot")) {
            float angle = 180.0f, blend = 0.0f;
            bool found;
            int32_t fa;
            FOGRT__LD_TRY(fogrt__ld_child_float(L, type, "falloff_angle", false, &angle, &found));
            fa = fogrt__ld_child(L, type, "falloff_angle");
            if (found && !(angle > 0.0f && angle <= 360.0f))
                return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[fa].line, "falloff_angle must be in (0, 360] degrees");
            FOGRT__LD_TRY(fogrt__ld_child_float(L, type, "falloff_exponent", false, &blend, NULL));
            blend = blend < 0.0f ? 0.0f : blend > 1.0f ? 1.0f : blend;
            if (!fogrt__ld_to_vec3(dir, &d.direction) || fogrt__ld_black(d.direction))
                return fogrt__ld_fail(L, FOGRT__LD_PARSE, node_line, "spot light direction (the node's -Z axis) is zero");
            d.type = FOGRT_LIGHT_SPOT;
            d.cutoff_deg = 0.5f * angle;                   /* falloff_angle is the full cone */
            d.beam_deg = d.cutoff_deg * (1.0f - blend);    /* Blender's spot blend */
        }
        FOGRT__LD_TRY(FOGRT__LD_PUSH(L, L->lights, L->light_count, L->light_cap));
        L->lights[L->light_count++] = d;
    }
    return FOGRT_RESULT_OK;
}

/* The camera: only the direction c = M (0,0,-1,1) and the field of view are used. */
FOGRT__LD fogrt_result fogrt__ld_camera(fogrt__ld *L, int32_t inst, const double M[16])
{
    int32_t cam = fogrt__ld_ref(L, inst, "url"), persp;
    float xfov = 50.0f, yfov = 0.0f, aspect = 0.0f;
    bool has_y, has_a;
    double c[4], th, tv;
    if (L->has_camera) {
        fogrt__ld_warn(L, L->el[inst].line, "more than one camera: the first one is used");
        return FOGRT_RESULT_OK;
    }
    if (cam < 0 || !fogrt__ld_is(L, cam, "camera")) {
        fogrt__ld_warn(L, L->el[inst].line, "instance_camera url not found: skipped");
        return FOGRT_RESULT_OK;
    }
    persp = fogrt__ld_path(L, cam, "optics/technique_common/perspective");
    if (persp < 0) {
        fogrt__ld_warn(L, L->el[cam].line, "camera without <perspective>: xfov 50 is used");
        has_y = has_a = false;
    } else {
        FOGRT__LD_TRY(fogrt__ld_child_float(L, persp, "xfov", false, &xfov, NULL));
        FOGRT__LD_TRY(fogrt__ld_child_float(L, persp, "yfov", false, &yfov, &has_y));
        FOGRT__LD_TRY(fogrt__ld_child_float(L, persp, "aspect_ratio", false, &aspect, &has_a));
        if (!(xfov > 0.0f && xfov < 180.0f) || (has_y && !(yfov > 0.0f && yfov < 180.0f)))
            return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[persp].line, "camera fov must be in (0, 180) degrees");
        if (has_a && !(aspect > 0.0f))
            return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[persp].line, "camera aspect_ratio must be > 0");
        if (!has_y && !has_a) fogrt__ld_warn(L, L->el[persp].line, "camera has neither yfov nor aspect_ratio: 4:3 assumed");
    }
    /* vertical fov from yfov, else from xfov and the aspect ratio; then CS184's fit to 4:3 */
    th = tan(0.5 * (double)xfov / FOGRT__LD_DEG);
    tv = has_y ? tan(0.5 * (double)yfov / FOGRT__LD_DEG) : th / (has_a ? (double)aspect : 4.0 / 3.0);
    if (th / tv < 4.0 / 3.0) th = tv * 4.0 / 3.0;      /* widen the horizontal fov */
    else tv = th * 3.0 / 4.0;                           /* or the vertical one */
    (void)th;
    if (!(tv > 0.0 && tv < 1e6)) return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[cam].line, "camera field of view out of range");
    L->frame_tan_half_y = (float)tv;
    fogrt__ld_xform4(M, 0, 0, -1, 1, c);
    L->cam_dir[0] = c[0]; L->cam_dir[1] = c[1]; L->cam_dir[2] = c[2];
    L->has_camera = true;
    return FOGRT_RESULT_OK;
}

/* CS184's camera placement: orbit at 1.5 |diagonal| from the bounding-box centre along c. */
FOGRT__LD void fogrt__ld_place_camera(fogrt__ld *L, fogrt_camera_desc *cam)
{
    double C[3] = { 0, 0, 0 }, E[3] = { 0, 0, 0 }, c[3], len, r, horiz;
    int i;
    if (L->has_bounds)
        for (i = 0; i < 3; ++i) { C[i] = 0.5 * (L->bmin[i] + L->bmax[i]); E[i] = L->bmax[i] - L->bmin[i]; }
    r = 1.5 * fogrt__ld_len3(E);
    if (!(r > 0.0)) r = 1.0;
    if (!L->has_camera) {                             /* CS184's defaults: xfov 50 on a 4:3 screen */
        L->cam_dir[0] = 0; L->cam_dir[1] = 0; L->cam_dir[2] = 1;
        L->frame_tan_half_y = (float)(tan(25.0 / FOGRT__LD_DEG) * 0.75);
    }
    memcpy(c, L->cam_dir, sizeof c);
    len = fogrt__ld_len3(c);
    if (!(len > 0.0) || len > 1e300) {
        fogrt__ld_warn(L, 0, "camera direction is zero: looking along -z");
        c[0] = 0; c[1] = 0; c[2] = 1; len = 1;
    }
    for (i = 0; i < 3; ++i) c[i] /= len;
    horiz = sqrt(c[0] * c[0] + c[2] * c[2]);
    if (horiz < 1e-3) {                               /* straight up or down: tilt a little (CS184 adds an epsilon) */
        double az = horiz > 0.0 ? atan2(c[0], c[2]) : 0.0, s = c[1] >= 0.0 ? 1.0 : -1.0;
        c[0] = 1e-3 * sin(az); c[2] = 1e-3 * cos(az); c[1] = s * sqrt(1.0 - 1e-6);
    }
    memset(cam, 0, sizeof *cam);
    cam->look_at = fogrt__ld_v3((float)C[0], (float)C[1], (float)C[2]);
    cam->position = fogrt__ld_v3((float)(C[0] + r * c[0]), (float)(C[1] + r * c[1]), (float)(C[2] + r * c[2]));
    cam->up = fogrt__ld_v3(0.0f, 1.0f, 0.0f);
    fogrt_load_fit_fov(L->frame_tan_half_y, 4.0f / 3.0f,
                       L->opt.image_width > 0 ? L->opt.image_width : 800, L->opt.image_height > 0 ? L->opt.image_height : 600, cam);
}

/* ------------------------------------------------------------------------------------------
   9. COLLADA: nodes, transforms and the document
   ------------------------------------------------------------------------------------------ */
/* The node's own transform: <translate>, <rotate>, <scale>, <matrix> post-multiplied in
   document order (COLLADA), stopping at the first <matrix> (CS184). */
FOGRT__LD fogrt_result fogrt__ld_node_transform(fogrt__ld *L, int32_t node, double out[16])
{
    int32_t c;
    fogrt__ld_identity(out);
    for (c = L->el[node].first_child; c >= 0; c = L->el[c].next) {
        double t[16];
        float v[16];
        uint32_t n;
        int i;
        fogrt__ld_identity(t);
        if (fogrt__ld_is(L, c, "matrix")) {
            for (i = 0; i < 16; ++i) v[i] = 0.0f;     /* a short matrix is zero-filled */
            FOGRT__LD_TRY(fogrt__ld_el_floats(L, c, v, 0, 16, &n));
            for (i = 0; i < 16; ++i) t[i] = (double)v[i];
            fogrt__ld_mul(out, t, out);
            break;
        } else if (fogrt__ld_is(L, c, "translate")) {
            FOGRT__LD_TRY(fogrt__ld_el_floats(L, c, v, 3, 3, &n));
            t[3] = (double)v[0]; t[7] = (double)v[1]; t[11] = (double)v[2];
        } else if (fogrt__ld_is(L, c, "scale")) {
            FOGRT__LD_TRY(fogrt__ld_el_floats(L, c, v, 3, 3, &n));
            t[0] = (double)v[0]; t[5] = (double)v[1]; t[10] = (double)v[2];
        } else if (fogrt__ld_is(L, c, "rotate")) {
            double a[3], len, ang, cs, sn;
            FOGRT__LD_TRY(fogrt__ld_el_floats(L, c, v, 4, 4, &n));
            a[0] = (double)v[0]; a[1] = (double)v[1]; a[2] = (double)v[2];
            len = fogrt__ld_len3(a);
            if (!(len > 0.0)) { fogrt__ld_warn(L, L->el[c].line, "<rotate> with a zero axis: ignored"); continue; }
            for (i = 0; i < 3; ++i) a[i] /= len;
            ang = (double)v[3] / FOGRT__LD_DEG; cs = cos(ang); sn = sin(ang);
            /* Rodrigues: R = cos I + sin [a]x + (1 - cos) a a^T */
            t[0] = cs + (1 - cs) * a[0] * a[0];        t[1] = (1 - cs) * a[0] * a[1] - sn * a[2]; t[2] = (1 - cs) * a[0] * a[2] + sn * a[1];
            t[4] = (1 - cs) * a[1] * a[0] + sn * a[2]; t[5] = cs + (1 - cs) * a[1] * a[1];        t[6] = (1 - cs) * a[1] * a[2] - sn * a[0];
            t[8] = (1 - cs) * a[2] * a[0] - sn * a[1]; t[9] = (1 - cs) * a[2] * a[1] + sn * a[0]; t[10] = cs + (1 - cs) * a[2] * a[2];
        } else if (fogrt__ld_is(L, c, "lookat") || fogrt__ld_is(L, c, "skew")) {
            fogrt__ld_warn(L, L->el[c].line, "<%.*s> is ignored (as in CS184)", (int)L->el[c].name_len, L->el[c].name);
            continue;
        } else {
            continue;
        }
        fogrt__ld_mul(out, t, out);
    }
    return FOGRT_RESULT_OK;
}

FOGRT__LD fogrt_result fogrt__ld_node(fogrt__ld *L, int32_t node, const double parent[16], int depth)
{
    double local[16], world[16];
    int32_t c, ic, il, ig;
    int kinds;
    if (depth > FOGRT_LOAD_MAX_DEPTH)
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[node].line, "nodes nested deeper than %d", FOGRT_LOAD_MAX_DEPTH);
    FOGRT__LD_TRY(fogrt__ld_node_transform(L, node, local));
    fogrt__ld_mul(parent, local, world);              /* world = parent x node */
    for (c = fogrt__ld_child(L, node, "node"); c >= 0; c = fogrt__ld_next_named(L, c, "node"))
        FOGRT__LD_TRY(fogrt__ld_node(L, c, world, depth + 1));   /* children first, as CS184 */
    ic = fogrt__ld_child(L, node, "instance_camera");
    il = fogrt__ld_child(L, node, "instance_light");
    ig = fogrt__ld_child(L, node, "instance_geometry");
    kinds = (ic >= 0) + (il >= 0) + (ig >= 0);
    if (kinds > 1 || (ig >= 0 && fogrt__ld_next_named(L, ig, "instance_geometry") >= 0))
        fogrt__ld_warn(L, L->el[node].line, "node with several instances: only the first camera, else light, else geometry is used (CS184)");
    if (fogrt__ld_child(L, node, "instance_node") >= 0)
        fogrt__ld_warn(L, L->el[node].line, "<instance_node> is not supported: ignored");
    if (ic >= 0) return fogrt__ld_camera(L, ic, world);
    if (il >= 0) return fogrt__ld_light(L, il, world, L->el[node].line);
    if (ig >= 0) return fogrt__ld_geometry(L, ig, world, L->el[node].line);
    return FOGRT_RESULT_OK;
}

FOGRT__LD fogrt_result fogrt__ld_dae_parse(fogrt__ld *L)
{
    int32_t up, vs, c, inst;
    double G[16];
    FOGRT__LD_TRY(fogrt__ld_xml_parse(L));
    if (!fogrt__ld_is(L, L->root, "COLLADA"))
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[L->root].line, "not a COLLADA document (root element <%.*s>)",
                              (int)(L->el[L->root].name_len > 40 ? 40 : L->el[L->root].name_len), L->el[L->root].name);
    FOGRT__LD_TRY(fogrt__ld_build_ids(L));
    /* up_axis: the correction G pre-multiplies every node */
    fogrt__ld_identity(G);
    up = fogrt__ld_path(L, L->root, "asset/up_axis");
    if (up < 0) {
        fogrt__ld_warn(L, L->el[L->root].line, "no <asset><up_axis>: Y_UP assumed (the COLLADA default)");
    } else {
        const char *s = L->el[up].text;
        uint32_t n = L->el[up].text_len;
        while (n && fogrt__ld_space(*s)) { ++s; --n; }
        while (n && fogrt__ld_space(s[n - 1])) --n;
        if (n == 4 && memcmp(s, "Z_UP", 4) == 0) {          /* (x, y, z) -> (-x, z, y) */
            G[0] = -1; G[5] = 0; G[6] = 1; G[9] = 1; G[10] = 0;
        } else if (n == 4 && memcmp(s, "X_UP", 4) == 0) {   /* (x, y, z) -> (y, x, -z) */
            G[0] = 0; G[1] = 1; G[4] = 1; G[5] = 0; G[10] = -1;
        } else if (!(n == 4 && memcmp(s, "Y_UP", 4) == 0)) {
            return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[up].line, "up_axis must be X_UP, Y_UP or Z_UP");
        }
    }
    inst = fogrt__ld_path(L, L->root, "scene/instance_visual_scene");
    if (inst < 0) return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[L->root].line, "no <scene><instance_visual_scene>");
    vs = fogrt__ld_ref(L, inst, "url");
    if (vs < 0 || !fogrt__ld_is(L, vs, "visual_scene"))
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[inst].line, "instance_visual_scene url does not name a <visual_scene>");
    for (c = fogrt__ld_child(L, vs, "node"); c >= 0; c = fogrt__ld_next_named(L, c, "node"))
        FOGRT__LD_TRY(fogrt__ld_node(L, c, G, 0));
    return FOGRT_RESULT_OK;
}

/* ------------------------------------------------------------------------------------------
   10. Handing the parsed scene to fogrt
   ------------------------------------------------------------------------------------------ */
FOGRT__LD fogrt_result fogrt__ld_rejected(fogrt__ld *L, fogrt_result r, const char *what)
{
    return fogrt__ld_fail(L, r, 0, "fogrt rejected the %s: %s", what, fogrt_result_string(r));
}

FOGRT__LD fogrt_result fogrt__ld_commit(fogrt__ld *L, fogrt_scene *scene, bool set_camera)
{
    uint32_t i, t, *ids = NULL, emissive = 0;
    fogrt_result r = FOGRT_RESULT_OK;
    fogrt_load_report *rep = L->rep;
    ids = (uint32_t *)fogrt__ld_alloc(L, L->mat_count, sizeof(uint32_t));
    if (!ids) return FOGRT_RESULT_OUT_OF_MEMORY;
    for (i = 0; i < L->mesh_count; ++i)
        for (t = 0; t < L->meshes[i].nt; ++t)
            if (!fogrt__ld_black(L->mats[L->meshes[i].tmat[t]].desc.emission)) emissive++;
    for (i = 0; i < L->mat_count && !r; ++i) {
        r = fogrt_scene_add_material(scene, &L->mats[i].desc, &ids[i]);
        if (r) r = fogrt__ld_rejected(L, r, "material");
        else rep->materials++;
    }
    for (i = 0; i < L->mesh_count && !r; ++i) {
        fogrt__ld_meshbuf *m = &L->meshes[i];
        fogrt_mesh_desc d;
        for (t = 0; t < m->nt; ++t) m->tmat[t] = ids[m->tmat[t]];
        memset(&d, 0, sizeof d);
        d.positions = m->pos; d.normals = m->nrm; d.vertex_count = m->nv;
        d.indices = m->idx; d.triangle_count = m->nt; d.triangle_materials = m->tmat;
        r = fogrt_scene_add_mesh(scene, &d);
        if (r) r = fogrt__ld_rejected(L, r, "mesh");
        else rep->triangles += m->nt;
    }
    for (i = 0; i < L->sph_count && !r; ++i) {
        r = fogrt_scene_add_sphere(scene, L->sph[i].c, L->sph[i].r, ids[L->sph[i].mat]);
        if (r) r = fogrt__ld_rejected(L, r, "sphere");
        else rep->spheres++;
    }
    rep->emissive_triangles = emissive;
    if (emissive > 0) rep->area_lights_merged = L->rect_count;   /* the emissive mesh is the lamp */
    for (i = 0; i < L->rect_count && !r && emissive == 0; ++i) {
        fogrt_material_desc md;
        fogrt_mesh_desc d;
        uint32_t id, idx[6] = { 0, 1, 2, 0, 2, 3 };
        float pos[12];
        int k;
        memset(&md, 0, sizeof md);
        md.type = FOGRT_BSDF_DIFFUSE;
        md.emission = L->rects[i].colour;
        for (k = 0; k < 4; ++k) { pos[3 * k] = L->rects[i].p[k].x; pos[3 * k + 1] = L->rects[i].p[k].y; pos[3 * k + 2] = L->rects[i].p[k].z; }
        r = fogrt_scene_add_material(scene, &md, &id);
        if (r) { r = fogrt__ld_rejected(L, r, "area light material"); break; }
        rep->materials++;
        memset(&d, 0, sizeof d);
        d.positions = pos; d.vertex_count = 4; d.indices = idx; d.triangle_count = 2; d.material = id;
        r = fogrt_scene_add_mesh(scene, &d);
        if (r) r = fogrt__ld_rejected(L, r, "area light rectangle");
        else { rep->area_rectangles++; rep->triangles += 2; rep->emissive_triangles += 2; }
    }
    for (i = 0; i < L->light_count && !r; ++i) {
        r = fogrt_scene_add_light(scene, &L->lights[i]);
        if (r) r = fogrt__ld_rejected(L, r, "light");
        else if (L->lights[i].type == FOGRT_LIGHT_SPOT) rep->spot_lights++;
        else rep->point_lights++;
    }
    if (!r && L->has_env) {
        r = fogrt_scene_set_environment(scene, L->env, true);
        if (r) r = fogrt__ld_rejected(L, r, "ambient light");
        else rep->ambient = true;
    }
    if (!r && set_camera) {
        r = fogrt_scene_set_camera(scene, &rep->camera);
        if (r) r = fogrt__ld_rejected(L, r, "camera");
    }
    FOGRT_LOAD_FREE(ids);
    return r;
}

/* ------------------------------------------------------------------------------------------
   11. Public entry points: COLLADA
   ------------------------------------------------------------------------------------------ */
FOGRT__LD_PUBLIC void fogrt_load_fit_fov(float frame_tan_half_y, float frame_aspect, int width, int height,
                                         fogrt_camera_desc *camera)
{
    double a = (width > 0 && height > 0) ? (double)width / height : (double)frame_aspect;
    if (!(frame_aspect > 0.0f)) frame_aspect = 4.0f / 3.0f;
    if (a >= (double)frame_aspect * (1.0 - 1e-6)) {   /* wide image: the frame's height fills it */
        camera->fov_is_horizontal = false;
        camera->fov_deg = (float)(2.0 * atan((double)frame_tan_half_y) * FOGRT__LD_DEG);
    } else {                          /* tall image: the frame's width fills it */
        camera->fov_is_horizontal = true;
        camera->fov_deg = (float)(2.0 * atan((double)frame_tan_half_y * (double)frame_aspect) * FOGRT__LD_DEG);
    }
}

FOGRT__LD_PUBLIC fogrt_result fogrt_load_dae_memory(fogrt_scene *scene, const void *data, size_t size, const char *name,
                                                    const fogrt_load_options *options, fogrt_load_report *report)
{
    fogrt__ld L;
    fogrt_load_report dummy;
    fogrt_result r;
    if (!report) report = &dummy;
    r = fogrt__ld_init(&L, data, size, name, options, report);
    if (!r) r = fogrt__ld_dae_parse(&L);
    if (!r) {
        fogrt_camera_desc *c = &report->camera;
        float dx, dy, dz;
        fogrt__ld_place_camera(&L, c);
        dx = c->look_at.x - c->position.x; dy = c->look_at.y - c->position.y; dz = c->look_at.z - c->position.z;
        if (!(c->position.x - c->position.x == 0.0f && c->position.y - c->position.y == 0.0f && c->position.z - c->position.z == 0.0f)
            || (dx == 0.0f && dy == 0.0f && dz == 0.0f))
            r = fogrt__ld_fail(&L, FOGRT__LD_PARSE, 0, "the scene's bounding box is too large (or too far out) to place CS184's camera");
    }
    if (!r) {
        report->has_camera = L.has_camera;
        report->frame_tan_half_y = L.frame_tan_half_y;
        report->frame_aspect = 4.0f / 3.0f;
        r = fogrt__ld_commit(&L, scene, !L.opt.no_camera);
    }
    fogrt__ld_destroy(&L);
    return r;
}

/* ------------------------------------------------------------------------------------------
   12. OBJ and PLY: one mesh, placed, with file or computed normals
   ------------------------------------------------------------------------------------------ */
/* Normalises file normals; a zero or missing one takes the computed smooth normal. */
FOGRT__LD fogrt_result fogrt__ld_fix_normals(fogrt__ld *L, fogrt__ld_meshbuf *m, float *file_nrm)
{
    uint32_t v;
    FOGRT__LD_TRY(fogrt__ld_normals(L, m, false));
    if (!file_nrm) return FOGRT_RESULT_OK;
    for (v = 0; v < m->nv; ++v) {
        float *f = file_nrm + 3 * (size_t)v;
        double len = sqrt((double)f[0] * (double)f[0] + (double)f[1] * (double)f[1] + (double)f[2] * (double)f[2]);
        if (len > 0.0 && len < HUGE_VAL) {
            m->nrm[3 * (size_t)v] = (float)((double)f[0] / len); m->nrm[3 * (size_t)v + 1] = (float)((double)f[1] / len); m->nrm[3 * (size_t)v + 2] = (float)((double)f[2] / len);
        }
    }
    return FOGRT_RESULT_OK;
}

/* Places the single mesh (already compacted) and adds it with its material. */
FOGRT__LD fogrt_result fogrt__ld_commit_mesh(fogrt__ld *L, fogrt_scene *scene, fogrt__ld_meshbuf *m)
{
    fogrt_mesh_desc d;
    uint32_t mat;
    fogrt_result r;
    if (L->opt.place != FOGRT_LOAD_PLACE_AS_IS) fogrt__ld_place(L, m);
    if (m->nt == 0) fogrt__ld_warn(L, 0, "the file has no faces: nothing added");
    if (m->nt == 0) return FOGRT_RESULT_OK;
    if (L->opt.use_material) {
        mat = L->opt.material;
    } else {
        fogrt_material_desc md = fogrt__ld_diffuse(0.75f, 0.75f, 0.75f);
        r = fogrt_scene_add_material(scene, &md, &mat);
        if (r) return fogrt__ld_rejected(L, r, "material");
        L->rep->materials = 1;
    }
    memset(&d, 0, sizeof d);
    d.positions = m->pos; d.normals = m->nrm; d.vertex_count = m->nv;
    d.indices = m->idx; d.triangle_count = m->nt; d.material = mat;
    r = fogrt_scene_add_mesh(scene, &d);
    if (r) return fogrt__ld_rejected(L, r, "mesh");
    L->rep->triangles = m->nt;
    return FOGRT_RESULT_OK;
}

/* u64 -> u32 hash map for (position, normal) pairs. */
typedef struct fogrt__ld_map { uint64_t *keys; uint32_t *vals; uint32_t cap; } fogrt__ld_map;
FOGRT__LD uint32_t fogrt__ld_mix(uint64_t k)
{
    k ^= k >> 33; k *= 0xff51afd7ed558ccdULL; k ^= k >> 33; k *= 0xc4ceb9fe1a85ec53ULL; k ^= k >> 33;
    return (uint32_t)k;
}

/* OBJ: v, vn, f. Returns the mesh before placement. */
FOGRT__LD fogrt_result fogrt__ld_obj_parse(fogrt__ld *L, fogrt__ld_meshbuf *out, float **out_file_nrm)
{
    char *p = L->buf, *end = L->buf + L->len;
    int line = 0;
    float *vp = NULL, *vn = NULL;
    uint32_t nvp = 0, cap_vp = 0, nvn = 0, cap_vn = 0;
    uint32_t *tv = NULL, *tn = NULL, cap_tv = 0, cap_tn = 0, nt = 0;
    uint32_t *fv = NULL, *fn = NULL, cap_fv = 0, cap_fn = 0;
    bool all_normals = true;
    fogrt_result r = FOGRT_RESULT_OK;
    uint32_t faces = 0;
    while (p < end && !r) {
        char *le = (char *)memchr(p, '\n', (size_t)(end - p)), *q, *kw;
        size_t kl;
        if (!le) le = end;
        line++;
        q = p;
        p = le < end ? le + 1 : end;
        while (q < le && (*q == ' ' || *q == '\t' || *q == '\r')) ++q;
        if (q >= le || *q == '#') continue;
        kw = q;
        while (q < le && *q != ' ' && *q != '\t' && *q != '\r') ++q;
        kl = (size_t)(q - kw);
        if ((kl == 1 && kw[0] == 'v') || (kl == 2 && kw[0] == 'v' && kw[1] == 'n')) {
            bool is_n = kl == 2;
            float x[3];
            int k;
            for (k = 0; k < 3; ++k) {
                while (q < le && (*q == ' ' || *q == '\t')) ++q;
                if (!fogrt__ld_strtof((const char **)&q, le, &x[k]) || (q < le && !fogrt__ld_space(*q))) {
                    r = fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "'%s' needs 3 finite numbers", is_n ? "vn" : "v");
                    break;
                }
            }
            if (r) break;
            if (is_n) {
                r = fogrt__ld_grow(L, (void **)&vn, &cap_vn, 3 * ((uint64_t)nvn + 1), sizeof(float));
                if (!r) { memcpy(vn + 3 * (size_t)nvn, x, sizeof x); nvn++; }
            } else {
                r = fogrt__ld_grow(L, (void **)&vp, &cap_vp, 3 * ((uint64_t)nvp + 1), sizeof(float));
                if (!r) { memcpy(vp + 3 * (size_t)nvp, x, sizeof x); nvp++; }
            }
        } else if (kl == 1 && kw[0] == 'f') {
            uint32_t n = 0, k;
            for (;;) {
                long long idx[3] = { 0, 0, 0 };
                int part = 0;
                while (q < le && (*q == ' ' || *q == '\t' || *q == '\r')) ++q;
                if (q >= le) break;
                for (;;) {                               /* v[/[t][/n]] */
                    bool neg = false, any = false;
                    long long val = 0;
                    if (q < le && (*q == '-' || *q == '+')) { neg = *q == '-'; ++q; }
                    while (q < le && *q >= '0' && *q <= '9') {
                        val = val * 10 + (*q - '0');
                        if (val > 0xFFFFFFFFLL) break;
                        any = true; ++q;
                    }
                    if (val > 0xFFFFFFFFLL || (!any && part == 0) || (!any && neg)) {
                        r = fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "bad face vertex '%.*s'", fogrt__ld_toklen(q, le), q);
                        break;
                    }
                    if (any) idx[part] = neg ? -val : val;
                    if (q < le && *q == '/' && part < 2) { ++q; ++part; continue; }
                    break;
                }
                if (r) break;
                if (q < le && !fogrt__ld_space(*q)) { r = fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "bad face vertex near '%.*s'", fogrt__ld_toklen(q, le), q); break; }
                /* resolve: 1-based, negative = relative to the end */
                {
                    long long v = idx[0] < 0 ? (long long)nvp + idx[0] : idx[0] - 1;
                    long long nn = idx[2] < 0 ? (long long)nvn + idx[2] : idx[2] - 1;
                    if (idx[0] == 0 || v < 0 || v >= (long long)nvp) {
                        r = fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "vertex index %lld out of range (%u vertices so far)", idx[0], nvp);
                        break;
                    }
                    if (idx[2] != 0 && (nn < 0 || nn >= (long long)nvn)) {
                        r = fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "normal index %lld out of range (%u normals so far)", idx[2], nvn);
                        break;
                    }
                    r = fogrt__ld_grow(L, (void **)&fv, &cap_fv, (uint64_t)n + 1, sizeof(uint32_t));
                    if (!r) r = fogrt__ld_grow(L, (void **)&fn, &cap_fn, (uint64_t)n + 1, sizeof(uint32_t));
                    if (r) break;
                    fv[n] = (uint32_t)v;
                    fn[n] = idx[2] != 0 ? (uint32_t)nn : UINT32_MAX;
                    if (idx[2] == 0) all_normals = false;
                    n++;
                }
            }
            if (r) break;
            if (n < 3) { r = fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "face with fewer than 3 vertices"); break; }
            faces++;
            for (k = 1; k + 1 < n && !r; ++k) {          /* fan */
                r = fogrt__ld_grow(L, (void **)&tv, &cap_tv, 3 * ((uint64_t)nt + 1), sizeof(uint32_t));
                if (!r) r = fogrt__ld_grow(L, (void **)&tn, &cap_tn, 3 * ((uint64_t)nt + 1), sizeof(uint32_t));
                if (r) break;
                tv[3 * (size_t)nt] = fv[0]; tv[3 * (size_t)nt + 1] = fv[k]; tv[3 * (size_t)nt + 2] = fv[k + 1];
                tn[3 * (size_t)nt] = fn[0]; tn[3 * (size_t)nt + 1] = fn[k]; tn[3 * (size_t)nt + 2] = fn[k + 1];
                nt++;
            }
        }
        /* everything else (vt, vp, o, g, s, usemtl, mtllib, l, p, ...) is ignored */
    }
    FOGRT_LOAD_FREE(fv); FOGRT_LOAD_FREE(fn);
    L->rep->vertices = nvp;
    L->rep->faces = faces;
    memset(out, 0, sizeof *out);
    *out_file_nrm = NULL;
    if (!r && nt > 0 && all_normals && nvn > 0) {
        /* one fogrt vertex per distinct (position, normal) pair */
        fogrt__ld_map map;
        uint32_t i, cap = 16, nv = 0;
        float *pos, *nrm;
        if (6 * (uint64_t)nt > 0x40000000u) { FOGRT_LOAD_FREE(vn); FOGRT_LOAD_FREE(tn); FOGRT_LOAD_FREE(vp); FOGRT_LOAD_FREE(tv); return fogrt__ld_fail(L, FOGRT_RESULT_TOO_LARGE, 0, "too many triangles"); }
        while (cap < 6 * (uint64_t)nt) cap *= 2;
        map.cap = cap;
        map.keys = (uint64_t *)fogrt__ld_alloc(L, cap, sizeof(uint64_t));
        map.vals = (uint32_t *)fogrt__ld_alloc(L, cap, sizeof(uint32_t));
        pos = (float *)fogrt__ld_alloc(L, 9 * (uint64_t)nt, sizeof(float));
        nrm = (float *)fogrt__ld_alloc(L, 9 * (uint64_t)nt, sizeof(float));
        if (!map.keys || !map.vals || !pos || !nrm) {
            FOGRT_LOAD_FREE(map.keys); FOGRT_LOAD_FREE(map.vals); FOGRT_LOAD_FREE(pos); FOGRT_LOAD_FREE(nrm);
            r = FOGRT_RESULT_OUT_OF_MEMORY;
        } else {
            for (i = 0; i < cap; ++i) map.keys[i] = UINT64_MAX;
            for (i = 0; i < 3 * nt; ++i) {
                uint64_t key = (uint64_t)tv[i] << 32 | tn[i];
                uint32_t h = fogrt__ld_mix(key) & (cap - 1);
                while (map.keys[h] != UINT64_MAX && map.keys[h] != key) h = (h + 1) & (cap - 1);
                if (map.keys[h] == UINT64_MAX) {
                    map.keys[h] = key; map.vals[h] = nv;
                    memcpy(pos + 3 * (size_t)nv, vp + 3 * (size_t)tv[i], 3 * sizeof(float));
                    memcpy(nrm + 3 * (size_t)nv, vn + 3 * (size_t)tn[i], 3 * sizeof(float));
                    nv++;
                }
                tv[i] = map.vals[h];
            }
            FOGRT_LOAD_FREE(map.keys); FOGRT_LOAD_FREE(map.vals);
            FOGRT_LOAD_FREE(vp);
            vp = pos; nvp = nv;
            *out_file_nrm = nrm;
        }
    }
    FOGRT_LOAD_FREE(vn); FOGRT_LOAD_FREE(tn);
    if (r) { FOGRT_LOAD_FREE(vp); FOGRT_LOAD_FREE(tv); FOGRT_LOAD_FREE(*out_file_nrm); *out_file_nrm = NULL; return r; }
    out->pos = vp; out->nv = nvp; out->idx = tv; out->nt = nt;
    if (!out->pos) { out->pos = (float *)fogrt__ld_alloc(L, 1, sizeof(float)); if (!out->pos) return FOGRT_RESULT_OUT_OF_MEMORY; }
    if (!out->idx) { out->idx = (uint32_t *)fogrt__ld_alloc(L, 1, sizeof(uint32_t)); if (!out->idx) return FOGRT_RESULT_OUT_OF_MEMORY; }
    return FOGRT_RESULT_OK;
}

/* Compacts, normals (file or computed), places, adds. Takes ownership of m and file_nrm. */
FOGRT__LD fogrt_result fogrt__ld_finish_mesh(fogrt__ld *L, fogrt_scene *scene, fogrt__ld_meshbuf *m, float *file_nrm)
{
    fogrt_result r;
    m->nrm = file_nrm;                  /* compaction keeps file normals in step */
    r = fogrt__ld_compact(L, m);
    if (!r) {
        file_nrm = m->nrm; m->nrm = NULL;
        r = fogrt__ld_fix_normals(L, m, file_nrm);
        FOGRT_LOAD_FREE(file_nrm);
    }
    if (!r) r = fogrt__ld_commit_mesh(L, scene, m);
    fogrt__ld_free_mesh(m);
    return r;
}

/* Both mesh formats load the same way: parse into a mesh buffer, then place and commit it. */
typedef fogrt_result (*fogrt__ld_mesh_parser)(fogrt__ld *L, fogrt__ld_meshbuf *m, float **file_nrm);
FOGRT__LD fogrt_result fogrt__ld_load_mesh(fogrt_scene *scene, const void *data, size_t size, const char *name,
                                        const fogrt_load_options *options, fogrt_load_report *report,
                                        fogrt__ld_mesh_parser parse)
{
    fogrt__ld L;
    fogrt_load_report dummy;
    fogrt__ld_meshbuf m;
    float *file_nrm = NULL;
    fogrt_result r;
    if (!report) report = &dummy;
    memset(&m, 0, sizeof m);
    r = fogrt__ld_init(&L, data, size, name, options, report);
    if (!r) r = parse(&L, &m, &file_nrm);
    if (!r) r = fogrt__ld_finish_mesh(&L, scene, &m, file_nrm);
    fogrt__ld_destroy(&L);
    return r;
}

FOGRT__LD_PUBLIC fogrt_result fogrt_load_obj_memory(fogrt_scene *scene, const void *data, size_t size, const char *name,
                                                    const fogrt_load_options *options, fogrt_load_report *report)
{
    return fogrt__ld_load_mesh(scene, data, size, name, options, report, fogrt__ld_obj_parse);
}

/* ---- PLY ---- */
enum { FOGRT__PLY_ASCII = 1, FOGRT__PLY_LE, FOGRT__PLY_BE };
enum { FOGRT__PLY_NONE = 0, FOGRT__PLY_X, FOGRT__PLY_Y, FOGRT__PLY_Z, FOGRT__PLY_NX, FOGRT__PLY_NY, FOGRT__PLY_NZ, FOGRT__PLY_INDICES };
typedef struct fogrt__ply_prop { int type, count_type; bool list; int role; } fogrt__ply_prop;
typedef struct fogrt__ply_elem { char name[32]; uint64_t count; uint32_t first, nprops; int line; } fogrt__ply_elem;
typedef struct fogrt__ply_reader { const char *p, *end, *data; int format, line; fogrt__ld *L; } fogrt__ply_reader;

/* Type name -> size in bytes (negative: float types), 0 if unknown. */
FOGRT__LD int fogrt__ply_type(const char *s, size_t n)
{
    static const char *names[16] = { "char", "int8", "uchar", "uint8", "short", "int16", "ushort", "uint16",
                                     "int", "int32", "uint", "uint32", "float", "float32", "double", "float64" };
    static const int types[16] = { 1, 1, 11, 11, 2, 2, 12, 12, 4, 4, 14, 14, -4, -4, -8, -8 };  /* 10+: unsigned */
    int i;
    for (i = 0; i < 16; ++i) if (strlen(names[i]) == n && memcmp(names[i], s, n) == 0) return types[i];
    return 0;
}
FOGRT__LD int fogrt__ply_size(int type) { return type < 0 ? -type : type > 10 ? type - 10 : type; }

/* Reads one value of the given type. */
FOGRT__LD fogrt_result fogrt__ply_read(fogrt__ply_reader *R, int type, double *out)
{
    if (R->format == FOGRT__PLY_ASCII) {
        const char *s = R->p;
        float f;
        while (s < R->end && fogrt__ld_space(*s)) { if (*s == '\n') R->line++; ++s; }
        R->p = s;
        if (s >= R->end)       /* at the end: name the last line, not the one after its newline */
            return fogrt__ld_fail(R->L, FOGRT__LD_PARSE, R->line - (s > R->data && s[-1] == '\n' ? 1 : 0), "unexpected end of file in the data");
        if (type > 0) {                                   /* integers: exact, in range */
            char *q;
            long long v;
            errno = 0;
            v = strtoll(s, &q, 10);
            if (q == s || errno || (q < R->end && !fogrt__ld_space(*q)))
                return fogrt__ld_fail(R->L, FOGRT__LD_PARSE, R->line, "expected an integer, found '%.*s'", fogrt__ld_toklen(s, R->end), s);
            *out = (double)v;
            R->p = q;
        } else {
            if (!fogrt__ld_strtof(&s, R->end, &f) || (s < R->end && !fogrt__ld_space(*s)))
                return fogrt__ld_fail(R->L, FOGRT__LD_PARSE, R->line, "expected a finite number, found '%.*s'", fogrt__ld_toklen(R->p, R->end), R->p);
            *out = (double)f;
            R->p = s;
        }
        return FOGRT_RESULT_OK;
    } else {
        int size = fogrt__ply_size(type), i;
        unsigned char b[8];
        if ((size_t)(R->end - R->p) < (size_t)size)
            return fogrt__ld_fail(R->L, FOGRT__LD_PARSE, R->line, "binary data truncated at byte %lu", (unsigned long)(R->p - R->L->buf));
        for (i = 0; i < size; ++i) b[i] = (unsigned char)R->p[R->format == FOGRT__PLY_LE ? i : size - 1 - i];
        R->p += size;
        if (type == -4) { float f; memcpy(&f, b, 4); *out = (double)f; }
        else if (type == -8) { double d; memcpy(&d, b, 8); *out = d; }
        else {
            uint64_t u = 0;
            for (i = size - 1; i >= 0; --i) u = u << 8 | b[i];
            if (type < 10 && (u >> (8 * size - 1)) & 1) *out = (double)u - ldexp(1.0, 8 * size);   /* signed */
            else *out = (double)u;
        }
        if (!(*out == *out) || *out > (double)FLT_MAX || *out < -(double)FLT_MAX)
            return fogrt__ld_fail(R->L, FOGRT__LD_PARSE, R->line, "non-finite number in the binary data (byte %lu)", (unsigned long)(R->p - R->L->buf));
        return FOGRT_RESULT_OK;
    }
}

FOGRT__LD fogrt_result fogrt__ply_parse(fogrt__ld *L, fogrt__ld_meshbuf *out, float **out_file_nrm)
{
    const char *p = L->buf, *end = L->buf + L->len;
    int line = 0, format = 0;
    fogrt__ply_elem el[16];
    fogrt__ply_prop props[128];
    uint32_t nel = 0, nprops = 0, e, i;
    uint64_t vcount = 0;
    bool have_vertex = false, header_done = false;
    fogrt__ply_reader R;
    fogrt_result r = FOGRT_RESULT_OK;
    float *pos = NULL, *nrm = NULL;
    uint32_t *tri = NULL, cap_tri = 0, nt = 0, *face = NULL, cap_face = 0, skipped = 0;
    memset(out, 0, sizeof *out);
    *out_file_nrm = NULL;
    /* header: one keyword per line until end_header */
    while (p < end && !header_done) {
        const char *le = (const char *)memchr(p, '\n', (size_t)(end - p)), *q, *tok[6];
        size_t len[6];
        int nt_ = 0;
        if (!le) return fogrt__ld_fail(L, FOGRT__LD_PARSE, line + 1, "header not terminated by end_header");
        line++;
        for (q = p; q < le && nt_ < 6;) {
            while (q < le && (*q == ' ' || *q == '\t' || *q == '\r')) ++q;
            if (q >= le) break;
            tok[nt_] = q;
            while (q < le && *q != ' ' && *q != '\t' && *q != '\r') ++q;
            len[nt_] = (size_t)(q - tok[nt_]);
            nt_++;
        }
        p = le + 1;
#define FOGRT__PLY_IS(k, s) (len[k] == strlen(s) && memcmp(tok[k], s, len[k]) == 0)
        if (line == 1) {
            if (nt_ != 1 || !FOGRT__PLY_IS(0, "ply")) return fogrt__ld_fail(L, FOGRT__LD_PARSE, 1, "not a PLY file (first line must be 'ply')");
            continue;
        }
        if (nt_ == 0 || FOGRT__PLY_IS(0, "comment") || FOGRT__PLY_IS(0, "obj_info")) continue;
        if (FOGRT__PLY_IS(0, "format")) {
            if (nt_ < 2) return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "format needs a name");
            if (FOGRT__PLY_IS(1, "ascii")) format = FOGRT__PLY_ASCII;
            else if (FOGRT__PLY_IS(1, "binary_little_endian")) format = FOGRT__PLY_LE;
            else if (FOGRT__PLY_IS(1, "binary_big_endian")) format = FOGRT__PLY_BE;
            else return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "unknown format '%.*s'", (int)(len[1] > 30 ? 30 : len[1]), tok[1]);
        } else if (FOGRT__PLY_IS(0, "element")) {
            char num[24];
            char *q2;
            unsigned long long c;
            if (nt_ != 3 || len[2] >= sizeof num || tok[2][0] < '0' || tok[2][0] > '9') return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "expected 'element NAME COUNT'");
            if (nel == 16) return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "too many elements (at most 16)");
            memcpy(num, tok[2], len[2]); num[len[2]] = 0;
            c = strtoull(num, &q2, 10);
            if (*q2 || c > 0xFFFFFFF0ull) return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "bad element count");
            memset(&el[nel], 0, sizeof el[nel]);
            snprintf(el[nel].name, sizeof el[nel].name, "%.*s", (int)(len[1] > 31 ? 31 : len[1]), tok[1]);
            el[nel].count = c;
            el[nel].first = nprops;
            el[nel].line = line;
            if (strcmp(el[nel].name, "vertex") == 0) {
                if (have_vertex) return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "a second vertex element");
                have_vertex = true; vcount = c;
            }
            nel++;
        } else if (FOGRT__PLY_IS(0, "property")) {
            fogrt__ply_prop pr;
            const char *name;
            size_t nlen;
            fogrt__ply_elem *pe = nel ? &el[nel - 1] : NULL;
            if (!pe) return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "property before any element");
            if (nprops == 128) return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "too many properties (at most 128)");
            memset(&pr, 0, sizeof pr);
            if (nt_ >= 2 && FOGRT__PLY_IS(1, "list")) {
                if (nt_ != 5) return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "expected 'property list COUNT_TYPE ITEM_TYPE NAME'");
                pr.list = true;
                pr.count_type = fogrt__ply_type(tok[2], len[2]);
                pr.type = fogrt__ply_type(tok[3], len[3]);
                if (pr.count_type <= 0 || pr.type == 0) return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "bad list property types");
                name = tok[4]; nlen = len[4];
            } else {
                if (nt_ != 3) return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "expected 'property TYPE NAME'");
                pr.type = fogrt__ply_type(tok[1], len[1]);
                if (pr.type == 0) return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "unknown property type '%.*s'", (int)(len[1] > 20 ? 20 : len[1]), tok[1]);
                name = tok[2]; nlen = len[2];
            }
#define FOGRT__PLY_NAME(s) (nlen == strlen(s) && memcmp(name, s, nlen) == 0)
            if (strcmp(pe->name, "vertex") == 0 && !pr.list) {
                pr.role = FOGRT__PLY_NAME("x") ? FOGRT__PLY_X : FOGRT__PLY_NAME("y") ? FOGRT__PLY_Y : FOGRT__PLY_NAME("z") ? FOGRT__PLY_Z
                        : FOGRT__PLY_NAME("nx") ? FOGRT__PLY_NX : FOGRT__PLY_NAME("ny") ? FOGRT__PLY_NY : FOGRT__PLY_NAME("nz") ? FOGRT__PLY_NZ : FOGRT__PLY_NONE;
            } else if (strcmp(pe->name, "face") == 0 && pr.list && (FOGRT__PLY_NAME("vertex_indices") || FOGRT__PLY_NAME("vertex_index"))) {
                pr.role = FOGRT__PLY_INDICES;
                if (pr.type < 0) return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "vertex indices must have an integer type");
            }
#undef FOGRT__PLY_NAME
            props[nprops++] = pr;
            pe->nprops++;
        } else if (FOGRT__PLY_IS(0, "end_header")) {
            header_done = true;
        } else {
            return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "unknown header line '%.*s'", (int)(len[0] > 20 ? 20 : len[0]), tok[0]);
        }
#undef FOGRT__PLY_IS
    }
    if (!header_done) return fogrt__ld_fail(L, FOGRT__LD_PARSE, line > 0 ? line : 1, "header not terminated by end_header");
    if (!format) return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "no format line in the header");
    if (!have_vertex) return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "no vertex element");
    {   /* the vertex element needs x, y, z */
        int roles = 0;
        for (e = 0; e < nel; ++e)
            if (strcmp(el[e].name, "vertex") == 0)
                for (i = 0; i < el[e].nprops; ++i) roles |= 1 << props[el[e].first + i].role;
        if ((roles & 0xE) != 0xE) return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "the vertex element needs x, y and z");
        if ((roles & 0x70) == 0x70) {
            nrm = (float *)fogrt__ld_alloc(L, vcount * 3, sizeof(float));
            if (!nrm) return FOGRT_RESULT_OUT_OF_MEMORY;
        }
    }
    /* every element needs data: refuse counts the file cannot hold before allocating */
    if (vcount > (uint64_t)(end - p) / (format == FOGRT__PLY_ASCII ? 2 : 3)) {
        FOGRT_LOAD_FREE(nrm);
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "%llu vertices declared, but the file is too short", (unsigned long long)vcount);
    }
    pos = (float *)fogrt__ld_alloc(L, vcount * 3, sizeof(float));
    if (!pos) { FOGRT_LOAD_FREE(nrm); return FOGRT_RESULT_OUT_OF_MEMORY; }
    R.p = p; R.end = end; R.data = p; R.format = format; R.line = line + 1; R.L = L;   /* data starts on the next line */
    for (e = 0; e < nel && !r; ++e) {
        uint64_t k;
        bool is_vertex = strcmp(el[e].name, "vertex") == 0, is_face = strcmp(el[e].name, "face") == 0;
        for (k = 0; k < el[e].count && el[e].nprops > 0 && !r; ++k) {   /* no properties: no data */
            for (i = 0; i < el[e].nprops && !r; ++i) {
                const fogrt__ply_prop *pr = &props[el[e].first + i];
                double v, n;
                uint64_t j;
                if (pr->list) {
                    int start_line = R.line;
                    r = fogrt__ply_read(&R, pr->count_type, &n);
                    if (r) break;
                    if (n < 0 || n != floor(n)) { r = fogrt__ld_fail(L, FOGRT__LD_PARSE, R.line, "bad list length %g", n); break; }
                    if (n > (double)(uint64_t)(R.end - R.p)) { r = fogrt__ld_fail(L, FOGRT__LD_PARSE, R.line, "a list of %g items runs past the end of the file (truncated?)", n); break; }
                    if (is_face && pr->role == FOGRT__PLY_INDICES) {
                        r = fogrt__ld_grow(L, (void **)&face, &cap_face, (uint64_t)n + 1, sizeof(uint32_t));
                        for (j = 0; j < (uint64_t)n && !r; ++j) {
                            r = fogrt__ply_read(&R, pr->type, &v);
                            if (!r && (v < 0 || v >= (double)vcount || v != floor(v)))
                                r = fogrt__ld_fail(L, FOGRT__LD_PARSE, R.line, "vertex index %g out of range (%llu vertices)", v, (unsigned long long)vcount);
                            if (!r) face[j] = (uint32_t)v;
                        }
                        if (r) break;
                        if (n < 3) { skipped++; continue; }
                        for (j = 1; j + 1 < (uint64_t)n && !r; ++j) {   /* fan */
                            r = fogrt__ld_grow(L, (void **)&tri, &cap_tri, 3 * ((uint64_t)nt + 1), sizeof(uint32_t));
                            if (r) break;
                            tri[3 * (size_t)nt] = face[0]; tri[3 * (size_t)nt + 1] = face[j]; tri[3 * (size_t)nt + 2] = face[j + 1];
                            nt++;
                        }
                        (void)start_line;
                    } else {
                        for (j = 0; j < (uint64_t)n && !r; ++j) r = fogrt__ply_read(&R, pr->type, &v);
                    }
                } else {
                    r = fogrt__ply_read(&R, pr->type, &v);
                    if (r || !is_vertex || pr->role == FOGRT__PLY_NONE) continue;
                    if (pr->role <= FOGRT__PLY_Z) pos[3 * k + (uint64_t)(pr->role - FOGRT__PLY_X)] = (float)v;
                    else if (nrm) nrm[3 * k + (uint64_t)(pr->role - FOGRT__PLY_NX)] = (float)v;
                }
            }
        }
        if (is_face) L->rep->faces = (uint32_t)el[e].count;
    }
    FOGRT_LOAD_FREE(face);
    if (!r && skipped) fogrt__ld_warn(L, 0, "%u faces with fewer than 3 vertices skipped", skipped);
    L->rep->vertices = (uint32_t)vcount;
    if (r) { FOGRT_LOAD_FREE(pos); FOGRT_LOAD_FREE(nrm); FOGRT_LOAD_FREE(tri); return r; }
    if (!tri) { tri = (uint32_t *)fogrt__ld_alloc(L, 1, sizeof(uint32_t)); if (!tri) { FOGRT_LOAD_FREE(pos); FOGRT_LOAD_FREE(nrm); return FOGRT_RESULT_OUT_OF_MEMORY; } }
    out->pos = pos; out->nv = (uint32_t)vcount; out->idx = tri; out->nt = nt;
    *out_file_nrm = nrm;
    return FOGRT_RESULT_OK;
}

FOGRT__LD_PUBLIC fogrt_result fogrt_load_ply_memory(fogrt_scene *scene, const void *data, size_t size, const char *name,
                                                    const fogrt_load_options *options, fogrt_load_report *report)
{
    return fogrt__ld_load_mesh(scene, data, size, name, options, report, fogrt__ply_parse);
}

/* ------------------------------------------------------------------------------------------
   13. CS184 camera settings files, and the file-based entry points
   ------------------------------------------------------------------------------------------ */
FOGRT__LD_PUBLIC fogrt_result fogrt_load_camera_memory(const void *data, size_t size, const char *name,
                                                       int width, int height, fogrt_camera_desc *camera,
                                                       fogrt_load_report *report)
{
    fogrt__ld L;
    fogrt_load_report dummy;
    fogrt_result r;
    float v[30];
    uint64_t n = 0;
    if (!report) report = &dummy;
    r = fogrt__ld_init(&L, data, size, name, NULL, report);
    if (!r) r = fogrt__ld_floats(&L, L.buf, L.buf + L.len, 1, v, 30, &n);
    if (!r && n < 28)
        r = fogrt__ld_fail(&L, FOGRT__LD_PARSE, fogrt__ld_line_at(L.buf, 1, L.buf + L.len - (L.len > 0 && L.buf[L.len - 1] == '\n')),
                           "camera file has %u numbers; CS184's format needs 28 (or 30 with the lens)", (unsigned)n);
    if (!r) {
        /* 0-4 hFov vFov ar nClip fClip, 5-7 pos, 8-10 target, 11-15 phi theta r minR maxR,
           16-24 c2w row-major (columns: right, up, back), 25-27 screenW screenH screenDist,
           28-29 focalDistance lensRadius */
        float sw = v[25], sh = v[26], sd = v[27];
        memset(camera, 0, sizeof *camera);
        camera->position = fogrt__ld_v3(v[5], v[6], v[7]);
        camera->look_at = fogrt__ld_v3(v[8], v[9], v[10]);
        camera->up = fogrt__ld_v3(v[17], v[20], v[23]);
        if (!(sw > 0 && sh > 0 && sd > 0))
            r = fogrt__ld_fail(&L, FOGRT__LD_PARSE, 5, "screenW, screenH and screenDist must be > 0");
        else if (v[5] == v[8] && v[6] == v[9] && v[7] == v[10])
            r = fogrt__ld_fail(&L, FOGRT__LD_PARSE, 2, "camera position equals its target");
        else if (n >= 30 && (v[28] < 0 || v[29] < 0))
            r = fogrt__ld_fail(&L, FOGRT__LD_PARSE, 6, "focal distance and lens radius must not be negative");
        if (!r) {
            if (n >= 30) { camera->focal_distance = v[28]; camera->lens_radius = v[29]; }
            fogrt_load_fit_fov(0.5f * sh / sd, sw / sh, width, height, camera);
            report->camera = *camera;
            report->frame_tan_half_y = 0.5f * sh / sd;
            report->frame_aspect = sw / sh;
            report->has_camera = true;
        }
    }
    fogrt__ld_destroy(&L);
    return r;
}

typedef fogrt_result (*fogrt__ld_mem_fn)(fogrt_scene *, const void *, size_t, const char *,
                                         const fogrt_load_options *, fogrt_load_report *);
FOGRT__LD fogrt_result fogrt__ld_from_file(fogrt__ld_mem_fn fn, fogrt_scene *scene, const char *path,
                                           const fogrt_load_options *options, fogrt_load_report *report)
{
    char *data;
    size_t size;
    fogrt_load_report dummy;
    fogrt_result r;
    if (!report) report = &dummy;
    r = fogrt__ld_read_file(path, &data, &size, report);
    if (r) return r;
    r = fn(scene, data, size, path, options, report);
    FOGRT_LOAD_FREE(data);
    return r;
}
FOGRT__LD_PUBLIC fogrt_result fogrt_load_dae(fogrt_scene *scene, const char *path, const fogrt_load_options *options, fogrt_load_report *report)
{
    return fogrt__ld_from_file(fogrt_load_dae_memory, scene, path, options, report);
}
FOGRT__LD_PUBLIC fogrt_result fogrt_load_obj(fogrt_scene *scene, const char *path, const fogrt_load_options *options, fogrt_load_report *report)
{
    return fogrt__ld_from_file(fogrt_load_obj_memory, scene, path, options, report);
}
FOGRT__LD_PUBLIC fogrt_result fogrt_load_ply(fogrt_scene *scene, const char *path, const fogrt_load_options *options, fogrt_load_report *report)
{
    return fogrt__ld_from_file(fogrt_load_ply_memory, scene, path, options, report);
}
FOGRT__LD_PUBLIC fogrt_result fogrt_load_camera_file(const char *path, int width, int height,
                                                     fogrt_camera_desc *camera, fogrt_load_report *report)
{
    char *data;
    size_t size;
    fogrt_load_report dummy;
    fogrt_result r;
    if (!report) report = &dummy;
    r = fogrt__ld_read_file(path, &data, &size, report);
    if (r) return r;
    r = fogrt_load_camera_memory(data, size, path, width, height, camera, report);
    FOGRT_LOAD_FREE(data);
    return r;
}

/* Lower-case extension of path ("" if none). */
FOGRT__LD bool fogrt__ld_ext_is(const char *path, const char *ext)
{
    const char *dot = strrchr(path, '.');
    size_t i, n = strlen(ext);
    if (!dot || strlen(dot + 1) != n) return false;
    for (i = 0; i < n; ++i) {
        char c = dot[1 + i];
        if (c >= 'A' && c <= 'Z') c = (char)(c - 'A' + 'a');
        if (c != ext[i]) return false;
    }
    return true;
}
FOGRT__LD_PUBLIC fogrt_result fogrt_load_file(fogrt_scene *scene, const char *path, const fogrt_load_options *options,
                                              fogrt_load_report *report)
{
    fogrt_load_report dummy;
    if (!report) report = &dummy;
    if (path && fogrt__ld_ext_is(path, "dae")) return fogrt_load_dae(scene, path, options, report);
    if (path && fogrt__ld_ext_is(path, "obj")) return fogrt_load_obj(scene, path, options, report);
    if (path && fogrt__ld_ext_is(path, "ply")) return fogrt_load_ply(scene, path, options, report);
    memset(report, 0, sizeof *report);
    snprintf(report->file, sizeof report->file, "%s", path ? path : "(null)");
    snprintf(report->message, sizeof report->message, "unknown scene type (expected .dae, .obj or .ply)");
    return FOGRT_RESULT_INVALID_ARGUMENT;
}

#endif /* FOGRT_LOAD_IMPLEMENTATION_INCLUDED */
#endif /* FOGRT_LOAD_IMPLEMENTATION */
