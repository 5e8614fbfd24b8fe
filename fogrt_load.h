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
    FOGRT_LOAD_MALLOC(sz) / FOGRT_LOAD_FREE(p)   both or neither; the default allocator
    FOGRT_LOAD_MAX_DEPTH        deepest <node> nesting accepted (default 128)
    FOGRT_LOAD_MAX_FILE_BYTES   default of fogrt_load_options.max_file_bytes (1 GiB)
    FOGRT_LOAD_MAX_TRIANGLES    default of fogrt_load_options.max_triangles (8388608 = 2^23)

    MEMORY
    ======
    Every allocation and free of the loader goes through fogrt_load_options.allocator
    (alloc_fn, free_fn, user_data, the same struct as the core's; NULL functions:
    FOGRT_LOAD_MALLOC / FOGRT_LOAD_FREE). The scene's own memory goes through the scene's
    allocator. Peak loader memory is bounded by the input: about 1 byte per file byte (the
    private copy) plus, per triangle, about 16 bytes (PLY), 20 (OBJ) or 65 (OBJ with normals);
    a .dae geometry instanced by many nodes is parsed and held once, and each instance is
    transformed into one scratch buffer while it is handed to the scene. A file that asks for
    more than max_triangles triangles (all instances counted), or a file larger than
    max_file_bytes, is refused before it is read or expanded (FOGRT_RESULT_TOO_LARGE, with
    the count and the limit in the message).

    FILES
    =====
    A path must name a regular file: a FIFO, device, socket or directory is refused at once
    (POSIX: opened with O_NONBLOCK and checked with fstat before any read, so a FIFO never
    blocks). The size is checked before reading, so /dev/zero or a huge sparse file costs
    nothing.

    ERRORS
    ======
    Every loader returns a fogrt_result and fills a fogrt_load_report. On failure the report
    names the file, the 1-based line (0 when no line applies) and a one-line message, so
    "file:line: message" can be printed as is. A malformed or truncated file gives
    FOGRT_RESULT_PARSE_ERROR, a missing file FOGRT_RESULT_IO_ERROR. Loading is all or
    nothing: the whole file is parsed and checked (against the scene's own limits too, such
    as coordinates within +-1e30) before the first fogrt_scene_add_* call, so a file that
    fails leaves the scene exactly as it was (barring out-of-memory inside fogrt itself).
    A glass or refraction material in a fogrt built with FOGRT_NO_GLASS is refused with
    FOGRT_RESULT_UNSUPPORTED, naming the material, before anything is added. Warnings (a
    microfacet alpha clamped, an unsupported light type skipped, ...) are counted in
    report.warnings and go to options.logger once the load has succeeded: a refusal is its
    one message.

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
      <microfacet> is fogrt's rough metal with the file's alpha, eta and k (its unused
      <reflectance> ignored, as CS184 does).
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
    triangulated; o, g and usemtl give names (NAMES, below) and everything else (vt, s,
    mtllib, l, p) is ignored. A UTF-8
    byte-order mark is skipped; lines may end in LF, CRLF or CR. A file without a single
    'v' statement is not an OBJ mesh (parse error). PLY: ascii,
    binary_little_endian and binary_big_endian; a "vertex" element with x y z (and optionally
    nx ny nz; every other property is skipped), a "face" element with a vertex_indices (or
    vertex_index) list; other elements are skipped. Without normals in the file, smooth
    area-weighted vertex normals are computed, unless the mesh is flat (every face facing the
    same way: its smooth normals are its face normals, so it is added without any). With the
    default placement the mesh is scaled
    uniformly and moved to stand on the floor of fogrt's default Cornell box (see
    fogrt_load_options.place), so `fogrt_scene_add_default` + `fogrt_load_ply` renders any
    model in one go.

    NAMES
    =====
    A program that fills shapes with media (fogrt_scene_set_interior) or makes them interfaces
    (fogrt_scene_set_shape_material) by name sets options.on_shape: once the load has
    succeeded, it is called for every mesh and sphere the load added, in the order they were
    added, with the scene's number of the shape and three names ("" where there is none):
      .dae  node      the <node> that instances the geometry: its name attribute, else its id
            material  the <material> bound to the geometry's first primitive list (name, else
                      id); "" for the default grey
            geometry  the <geometry> (name, else id): shared by every node that instances it
            A CGL <area> light added as an emissive rectangle is a mesh named by its node.
      OBJ   node      the `o` object name, material the `usemtl` name in force at the mesh's
                      first face, geometry the `g` group name (each the rest of its line,
                      blanks trimmed; `o` starts without a group). With on_shape set, every
                      `o` or `g` statement followed by faces starts a mesh of its own, so
                      that each object or group can hold a medium; a name used by two such
                      statements names two meshes. Without on_shape an OBJ is one mesh, as
                      always. Either way the vertices, normals, placement and triangle order
                      are the same.
      PLY   one mesh, without names.
    A load that fails calls on_shape for nothing.

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
     use_material, material     OBJ/PLY: the material of the mesh; else a new diffuse 0.75 grey
     allocator                  the loader's memory; NULL functions: FOGRT_LOAD_MALLOC / _FREE
     max_file_bytes             larger files are refused unread; 0: FOGRT_LOAD_MAX_FILE_BYTES
     max_triangles              files asking for more are refused early; 0: FOGRT_LOAD_MAX_TRIANGLES
     on_shape, on_shape_user    the names of every mesh and sphere the load adds (see NAMES above);
                                NULL: none asked for, and an OBJ stays one mesh */
/* on_shape: called once per mesh or sphere the load added, after the whole load succeeded,
   with the number the scene gave it (the index fogrt_scene_set_interior and
   fogrt_scene_set_shape_material take) and its names, NUL-terminated, "" for none. The
   strings live until the callback returns. */
typedef void (*fogrt_load_shape_fn)(void *user, fogrt_shape_kind kind, uint32_t index,
                                    const char *node, const char *material, const char *geometry);
typedef struct fogrt_load_options {
    int image_width, image_height;
    fogrt_logger logger;
    bool no_camera;
    fogrt_load_place place;
    fogrt_vec3 fit_min, fit_max;
    bool use_material;
    uint32_t material;
    fogrt_allocator allocator;
    uint64_t max_file_bytes;
    uint32_t max_triangles;
    fogrt_load_shape_fn on_shape;
    void *on_shape_user;
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
#if defined(__unix__) || defined(__APPLE__)
#include <sys/types.h>
#include <sys/stat.h>
#include <fcntl.h>
#include <unistd.h>
#define FOGRT__LD_POSIX 1
#endif

#if defined(FOGRT_LOAD_MALLOC) != defined(FOGRT_LOAD_FREE)
#error "fogrt_load: define both FOGRT_LOAD_MALLOC and FOGRT_LOAD_FREE, or neither"
#endif
#ifndef FOGRT_LOAD_MALLOC
#define FOGRT_LOAD_MALLOC(sz) malloc(sz)
#define FOGRT_LOAD_FREE(p) free(p)
#endif
#ifndef FOGRT_LOAD_MAX_DEPTH
#define FOGRT_LOAD_MAX_DEPTH 128
#endif
#ifndef FOGRT_LOAD_MAX_FILE_BYTES
#define FOGRT_LOAD_MAX_FILE_BYTES ((uint64_t)1 << 30)
#endif
#ifndef FOGRT_LOAD_MAX_TRIANGLES
#define FOGRT_LOAD_MAX_TRIANGLES (1u << 23)
#endif
/* The scene refuses coordinates beyond this (fogrt.h, fogrt_scene_add_mesh / _add_sphere);
   the loader checks them first, so that a refused file changes nothing. */
#define FOGRT__LD_MAX_COORD 1e30

#if defined(__GNUC__) || defined(__clang__)
#define FOGRT__LD static __attribute__((unused))
#define FOGRT__LD_PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define FOGRT__LD static
#define FOGRT__LD_PRINTF(f, a)
#endif
#if defined(FOGRT_STATIC) && (defined(__GNUC__) || defined(__clang__))
#define FOGRT__LD_PUBLIC static __attribute__((unused))
#elif defined(FOGRT_STATIC)
#define FOGRT__LD_PUBLIC static
#else
#define FOGRT__LD_PUBLIC
#endif

#define FOGRT__LD_TRY(expr) do { fogrt_result r_ = (expr); if (r_ != FOGRT_RESULT_OK) return r_; } while (0)
#define FOGRT__LD_PARSE FOGRT_RESULT_PARSE_ERROR
#define FOGRT__LD_CLIP(n) ((int)((n) > 40 ? 40 : (n)))   /* at most 40 characters of a name in a message */

/* ------------------------------------------------------------------------------------------
   1. The loader context: input buffer, report, and the scene under construction
   Everything is parsed into these arrays first; the commit step hands them to fogrt at the
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
    uint32_t *idx;                    /* 3 per triangle */
    uint32_t nv, nt;
    bool smooth;                      /* nrm holds computed smooth normals only (OBJ/PLY) */
} fogrt__ld_meshbuf;
/* A parsed <geometry> <mesh>, in its own (local) coordinates, shared by every node that
   instances it. Triangle t came from primitive list tlist[t] (its material is bound per
   instance); open[v] marks vertices of connected parts with open edges (their smooth
   normals are negated, see fogrt__ld_open_parts). */
typedef struct fogrt__ld_geom {
    int32_t el;
    fogrt__ld_meshbuf m;
    uint32_t *tlist;
    int32_t *lists; uint32_t *list_tris; uint32_t list_count;
    unsigned char *open;
} fogrt__ld_geom;
typedef struct fogrt__ld_inst { uint32_t geom, mat_first; int line; int32_t node; double M[16]; } fogrt__ld_inst;
typedef struct fogrt__ld_sphere { fogrt_vec3 c; float r; uint32_t mat; int32_t node, geom; } fogrt__ld_sphere;
typedef struct fogrt__ld_rect { fogrt_vec3 p[4]; fogrt_vec3 colour; int32_t node; } fogrt__ld_rect;
/* A shape for options.on_shape: its names (offsets into the loader's names, 0 = "") in the
   order node, material, geometry; for an OBJ mesh of its own, its first triangle. */
typedef struct fogrt__ld_shape { fogrt_shape_kind kind; uint32_t name[3], first; } fogrt__ld_shape;

typedef struct fogrt__ld {
    const char *name;
    char *buf; size_t len;            /* private NUL-terminated copy of the input */
    fogrt_load_options opt;           /* with the defaults filled in */
    fogrt_load_report *rep;
    /* XML */
    fogrt__ld_el *el; uint32_t el_count, el_cap;
    fogrt__ld_xattr *at; uint32_t at_count, at_cap;
    int32_t root;
    uint32_t *ids; uint32_t ids_cap;  /* hash table of element index + 1 (0 = empty) */
    /* the scene under construction */
    fogrt__ld_mat *mats; uint32_t mat_count, mat_cap;
    fogrt__ld_geom *geoms; uint32_t geom_count, geom_cap;
    fogrt__ld_inst *insts; uint32_t inst_count, inst_cap;
    uint32_t *inst_mats; uint32_t inst_mat_count, inst_mat_cap;
    uint64_t tri_total;               /* triangles asked for so far (every instance) */
    fogrt__ld_sphere *sph; uint32_t sph_count, sph_cap;
    fogrt_light_desc *lights; uint32_t light_count, light_cap;
    fogrt__ld_rect *rects; uint32_t rect_count, rect_cap;
    fogrt_vec3 env; bool has_env;
    bool has_camera;
    double cam_dir[3];                /* CS184's c (unnormalised) */
    float frame_tan_half_y;
    double bmin[3], bmax[3]; bool has_bounds;
    /* names for options.on_shape (only when it is set) */
    int32_t node;                     /* .dae: the <node> whose instance is being read */
    char *names; uint32_t names_len, names_cap;   /* NUL-terminated, offset 0 is "" */
    fogrt__ld_shape *shapes; uint32_t shape_count, shape_cap;
    uint32_t first_mesh, first_sphere;   /* the scene's numbers of the first ones added */
    /* warnings, held back until the load succeeds (a refusal is one message, nothing else) */
    char *warn; uint32_t warn_len, warn_cap; bool warn_oom;
} fogrt__ld;

/* ---- messages ---- */
/* A message quotes bytes of the file: control bytes and bytes that are not well-formed UTF-8
   become '?', so a binary file never writes raw bytes to the user's terminal. */
FOGRT__LD void fogrt__ld_printable(char *msg) {
    unsigned char *p = (unsigned char *)msg;
    while (*p) {
        int len = 0, k;
        if (*p >= 0x20 && *p < 0x7F) { ++p; continue; }
        if (*p >= 0xC2 && *p <= 0xDF) len = 2;
        else if (*p >= 0xE0 && *p <= 0xEF) len = 3;
        else if (*p >= 0xF0 && *p <= 0xF4) len = 4;
        for (k = 1; k < len; ++k)
            if ((p[k] & 0xC0) != 0x80) { len = 0; break; }
        if (len == 0) { *p++ = '?'; continue; }
        p += len;
    }
}
/* Records the first error (file:line: message) and returns the result code. */
FOGRT__LD FOGRT__LD_PRINTF(4, 5) fogrt_result fogrt__ld_fail(fogrt__ld *L, fogrt_result res, int line, const char *fmt, ...) {
    va_list ap;
    if (L->rep->message[0] == 0) {
        L->rep->line = line;
        va_start(ap, fmt);
        vsnprintf(L->rep->message, sizeof L->rep->message, fmt, ap);
        va_end(ap);
        fogrt__ld_printable(L->rep->message);
    }
    return res;
}
FOGRT__LD fogrt_result fogrt__ld_oom(fogrt__ld *L) {
    return fogrt__ld_fail(L, FOGRT_RESULT_OUT_OF_MEMORY, 0, "out of memory");
}
FOGRT__LD fogrt_result fogrt__ld_grow(fogrt__ld *L, void **arr, uint32_t *cap, uint64_t need, size_t elem);
/* A warning: counted, and kept (as "file:line: warning: ...") for options.logger, which hears
   it only if the load succeeds (fogrt__ld_flush_warnings). */
FOGRT__LD FOGRT__LD_PRINTF(3, 4) void fogrt__ld_warn(fogrt__ld *L, int line, const char *fmt, ...) {
    char msg[256], full[600];
    va_list ap;
    uint32_t n;
    bool had_error;
    L->rep->warnings++;
    if (!L->opt.logger.func) return;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    fogrt__ld_printable(msg);
    if (line > 0) snprintf(full, sizeof full, "%s:%d: warning: %s", L->name, line, msg);
    else snprintf(full, sizeof full, "%s: warning: %s", L->name, msg);
    n = (uint32_t)strlen(full) + 1;
    had_error = L->rep->message[0] != 0;
    if (fogrt__ld_grow(L, (void **)&L->warn, &L->warn_cap, (uint64_t)L->warn_len + n, 1)) {
        if (!had_error) { L->rep->message[0] = 0; L->rep->line = 0; }   /* a later error, if any, is the one to report */
        L->warn_oom = true;
        return;
    }
    memcpy(L->warn + L->warn_len, full, n);
    L->warn_len += n;
}
FOGRT__LD void fogrt__ld_flush_warnings(fogrt__ld *L) {
    uint32_t at;
    for (at = 0; at < L->warn_len; at += (uint32_t)strlen(L->warn + at) + 1)
        L->opt.logger.func(FOGRT_LOG_WARNING, L->warn + at, L->opt.logger.user_data);
}
/* Called before the first change to the scene: a warning that could not be kept is an
   out-of-memory failure like any other. */
FOGRT__LD fogrt_result fogrt__ld_ready(fogrt__ld *L) {
    return L->warn_oom ? fogrt__ld_oom(L) : FOGRT_RESULT_OK;
}
/* The triangle budget: every triangle a file asks for is counted here first. */
FOGRT__LD fogrt_result fogrt__ld_count_tris(fogrt__ld *L, uint64_t more, int line) {
    L->tri_total += more;
    if (L->tri_total <= L->opt.max_triangles) return FOGRT_RESULT_OK;
    return fogrt__ld_fail(L, FOGRT_RESULT_TOO_LARGE, line, "the file asks for %llu triangles, more than the limit of %u (fogrt_load_options.max_triangles)",
                          (unsigned long long)L->tri_total, L->opt.max_triangles);
}

/* ---- memory: everything goes through options.allocator ---- */
FOGRT__LD void *fogrt__ld_malloc(fogrt__ld *L, size_t size) {
    const fogrt_allocator *a = &L->opt.allocator;
    if (size == 0) size = 1;
    return a->alloc_fn ? a->alloc_fn(size, a->user_data) : FOGRT_LOAD_MALLOC(size);
}
FOGRT__LD void fogrt__ld_free(fogrt__ld *L, void *p) {
    const fogrt_allocator *a = &L->opt.allocator;
    if (!p) return;
    if (a->free_fn) a->free_fn(p, a->user_data);
    else FOGRT_LOAD_FREE(p);
}
/* count elements of elem bytes (never more than a quarter of the address space), or NULL
   with the error recorded. */
FOGRT__LD void *fogrt__ld_alloc(fogrt__ld *L, uint64_t count, size_t elem) {
    void *p;
    if (count == 0) count = 1;
    if (count > (uint64_t)SIZE_MAX / 4 / elem) { fogrt__ld_fail(L, FOGRT_RESULT_TOO_LARGE, 0, "too large"); return NULL; }
    p = fogrt__ld_malloc(L, (size_t)(count * elem));
    if (!p) fogrt__ld_oom(L);
    return p;
}
/* Grows *arr to hold at least need elements (doubling, or exactly need if that is more;
   allocate, copy, free). */
FOGRT__LD fogrt_result fogrt__ld_grow(fogrt__ld *L, void **arr, uint32_t *cap, uint64_t need, size_t elem) {
    uint64_t c = *cap ? 2 * (uint64_t)*cap : 16;
    void *p;
    if (need <= *cap) return FOGRT_RESULT_OK;
    if (c < need) c = need;          /* a big jump (a known count) is taken exactly */
    if (c > 0xFFFFFFF0u) return fogrt__ld_fail(L, FOGRT_RESULT_TOO_LARGE, 0, "too many elements");
    p = fogrt__ld_alloc(L, c, elem);
    if (!p) return FOGRT_RESULT_OUT_OF_MEMORY;
    if (*arr) memcpy(p, *arr, (size_t)*cap * elem);
    fogrt__ld_free(L, *arr);
    *arr = p;
    *cap = (uint32_t)c;
    return FOGRT_RESULT_OK;
}
#define FOGRT__LD_PUSH(L, arr, count, cap) \
    fogrt__ld_grow((L), (void **)&(arr), &(cap), (uint64_t)(count) + 1, sizeof *(arr))

/* ---- names for options.on_shape: collected before the first scene call (so that running out
   of memory changes nothing), handed over once the load has succeeded ---- */
/* Copies the name [s, s + len) into L->names; *out its offset (0: the empty name). */
FOGRT__LD fogrt_result fogrt__ld_name(fogrt__ld *L, const char *s, uint32_t len, uint32_t *out) {
    *out = 0;
    if (!s || len == 0) return FOGRT_RESULT_OK;
    FOGRT__LD_TRY(fogrt__ld_grow(L, (void **)&L->names, &L->names_cap, (uint64_t)L->names_len + len + 2, 1));
    if (L->names_len == 0) L->names[L->names_len++] = '\0';
    *out = L->names_len;
    memcpy(L->names + L->names_len, s, len);
    L->names[L->names_len + len] = '\0';
    L->names_len += len + 1;
    return FOGRT_RESULT_OK;
}
FOGRT__LD fogrt_result fogrt__ld_push_shape(fogrt__ld *L, fogrt_shape_kind kind, const uint32_t name[3], uint32_t first) {
    fogrt__ld_shape *S;
    FOGRT__LD_TRY(FOGRT__LD_PUSH(L, L->shapes, L->shape_count, L->shape_cap));
    S = &L->shapes[L->shape_count++];
    S->kind = kind; S->first = first;
    memcpy(S->name, name, sizeof S->name);
    return FOGRT_RESULT_OK;
}
/* options.on_shape for every shape added, numbered from the scene's first ones. */
FOGRT__LD void fogrt__ld_report_shapes(const fogrt__ld *L) {
    uint32_t i, mesh = L->first_mesh, sphere = L->first_sphere;
    for (i = 0; L->opt.on_shape && i < L->shape_count; ++i) {
        const fogrt__ld_shape *S = &L->shapes[i];
        const char *n = L->names ? L->names : "";
        L->opt.on_shape(L->opt.on_shape_user, S->kind, S->kind == FOGRT_SHAPE_MESH ? mesh++ : sphere++,
                        n + S->name[0], n + S->name[1], n + S->name[2]);
    }
}
/* Where the shapes of this load start: the scene's counts before its first one is added. */
FOGRT__LD void fogrt__ld_first_shapes(fogrt__ld *L, const fogrt_scene *scene) {
    fogrt_scene_info info;
    fogrt_scene_get_info(scene, &info);
    L->first_mesh = info.mesh_count;
    L->first_sphere = info.sphere_count;
}

FOGRT__LD void fogrt__ld_free_mesh(fogrt__ld *L, fogrt__ld_meshbuf *m) {
    fogrt__ld_free(L, m->pos); fogrt__ld_free(L, m->nrm); fogrt__ld_free(L, m->idx);
    memset(m, 0, sizeof *m);
}
FOGRT__LD void fogrt__ld_destroy(fogrt__ld *L) {
    uint32_t i;
    for (i = 0; i < L->geom_count; ++i) {
        fogrt__ld_geom *g = &L->geoms[i];
        fogrt__ld_free_mesh(L, &g->m);
        fogrt__ld_free(L, g->tlist); fogrt__ld_free(L, g->lists); fogrt__ld_free(L, g->list_tris); fogrt__ld_free(L, g->open);
    }
    fogrt__ld_free(L, L->buf); fogrt__ld_free(L, L->el); fogrt__ld_free(L, L->at); fogrt__ld_free(L, L->ids);
    fogrt__ld_free(L, L->mats); fogrt__ld_free(L, L->geoms); fogrt__ld_free(L, L->insts); fogrt__ld_free(L, L->inst_mats);
    fogrt__ld_free(L, L->sph); fogrt__ld_free(L, L->lights); fogrt__ld_free(L, L->rects); fogrt__ld_free(L, L->warn);
    fogrt__ld_free(L, L->names); fogrt__ld_free(L, L->shapes);
    memset(L, 0, sizeof *L);
}

/* ------------------------------------------------------------------------------------------
   2. Input: a private NUL-terminated copy of the memory given, or of a regular file
   ------------------------------------------------------------------------------------------ */
/* Sets up a context (defaults filled in) and the report. */
FOGRT__LD fogrt_result fogrt__ld_init(fogrt__ld *L, const char *name, const fogrt_load_options *opt, fogrt_load_report *rep) {
    memset(L, 0, sizeof *L);
    memset(rep, 0, sizeof *rep);
    L->rep = rep;
    L->name = name ? name : "<memory>";
    snprintf(rep->file, sizeof rep->file, "%s", L->name);
    if (opt) L->opt = *opt;
    if (!L->opt.max_file_bytes) L->opt.max_file_bytes = FOGRT_LOAD_MAX_FILE_BYTES;
    if (!L->opt.max_triangles) L->opt.max_triangles = FOGRT_LOAD_MAX_TRIANGLES;
    L->root = -1;
    L->node = -1;
    if ((L->opt.allocator.alloc_fn == NULL) != (L->opt.allocator.free_fn == NULL)) {
        memset(&L->opt.allocator, 0, sizeof L->opt.allocator);   /* so destroy frees nothing wrongly */
        return fogrt__ld_fail(L, FOGRT_RESULT_INVALID_ARGUMENT, 0, "options.allocator: set both alloc_fn and free_fn, or neither");
    }
    return FOGRT_RESULT_OK;
}
/* The size of a file against options.max_file_bytes (and the loader's own 2 GiB ceiling),
   with the real limit in the message. */
FOGRT__LD fogrt_result fogrt__ld_check_size(fogrt__ld *L, uint64_t size) {
    uint64_t lim = L->opt.max_file_bytes;
    char unit[32] = "";
    if (size <= lim && size < (uint64_t)0x7FFFFFF0u) return FOGRT_RESULT_OK;
    if (lim > (uint64_t)0x7FFFFFF0u) lim = 0x7FFFFFF0u;
    if (lim >= ((uint64_t)1 << 30)) snprintf(unit, sizeof unit, "%.4g GiB, ", (double)lim / 1073741824.0);
    else if (lim >= ((uint64_t)1 << 20)) snprintf(unit, sizeof unit, "%.4g MiB, ", (double)lim / 1048576.0);
    return fogrt__ld_fail(L, FOGRT_RESULT_TOO_LARGE, 0, "file is %llu bytes, more than the limit of %llu bytes (%sfogrt_load_options.max_file_bytes)",
                          (unsigned long long)size, (unsigned long long)lim, unit);
}
/* The input buffer: size bytes plus a NUL, so strtod always stops. */
FOGRT__LD fogrt_result fogrt__ld_new_buf(fogrt__ld *L, uint64_t size) {
    FOGRT__LD_TRY(fogrt__ld_check_size(L, size));
    L->buf = (char *)fogrt__ld_malloc(L, (size_t)size + 1);
    if (!L->buf) return fogrt__ld_oom(L);
    L->len = (size_t)size;
    L->buf[L->len] = 0;
    return FOGRT_RESULT_OK;
}
FOGRT__LD fogrt_result fogrt__ld_copy(fogrt__ld *L, const void *data, size_t size) {
    if (!data && size) return fogrt__ld_fail(L, FOGRT_RESULT_INVALID_ARGUMENT, 0, "no data");
    FOGRT__LD_TRY(fogrt__ld_new_buf(L, size));
    if (size) memcpy(L->buf, data, size);
    return FOGRT_RESULT_OK;
}
FOGRT__LD fogrt_result fogrt__ld_cannot_open(fogrt__ld *L, const char *why) {
    return fogrt__ld_fail(L, FOGRT_RESULT_IO_ERROR, 0, "cannot open: %s", why);
}
#ifdef FOGRT__LD_POSIX
/* What a non-regular file is, for the message. */
FOGRT__LD const char *fogrt__ld_file_kind(mode_t m) {
    if (S_ISFIFO(m)) return "a FIFO";
    if (S_ISDIR(m)) return "a directory";
    if (S_ISCHR(m)) return "a character device";
    if (S_ISBLK(m)) return "a block device";
    return "not a regular file";
}
/* POSIX: opened without blocking (a FIFO would block in open), checked with fstat, then
   read once to its size: a non-regular file is refused before a single read. */
FOGRT__LD fogrt_result fogrt__ld_read_path(fogrt__ld *L, const char *path) {
    struct stat st;
    size_t got = 0;
    fogrt_result r = FOGRT_RESULT_OK;
    int fd = open(path, O_RDONLY | O_NONBLOCK);
    if (fd < 0) return fogrt__ld_cannot_open(L, strerror(errno));
    if (fstat(fd, &st) != 0) r = fogrt__ld_cannot_open(L, strerror(errno));
    else if (!S_ISREG(st.st_mode))
        r = fogrt__ld_fail(L, FOGRT_RESULT_IO_ERROR, 0, "refused: %s, not a regular file", fogrt__ld_file_kind(st.st_mode));
    else r = fogrt__ld_new_buf(L, (uint64_t)st.st_size);
    while (!r && got < L->len) {
        ssize_t n = read(fd, L->buf + got, L->len - got);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) r = fogrt__ld_fail(L, FOGRT_RESULT_IO_ERROR, 0, "read error: %s", strerror(errno));
        if (n <= 0) break;
        got += (size_t)n;
    }
    close(fd);
    if (!r && got < L->len) r = fogrt__ld_fail(L, FOGRT_RESULT_IO_ERROR, 0, "read error: the file shrank while it was read");
    return r;
}
#else
/* Plain C: the size from fseek/ftell before reading. */
FOGRT__LD fogrt_result fogrt__ld_read_path(fogrt__ld *L, const char *path) {
    fogrt_result r;
    long size;
    FILE *f = fopen(path, "rb");
    if (!f) return fogrt__ld_cannot_open(L, strerror(errno));
    size = fseek(f, 0, SEEK_END) == 0 ? ftell(f) : -1L;
    if (size < 0 || fseek(f, 0, SEEK_SET) != 0) r = fogrt__ld_fail(L, FOGRT_RESULT_IO_ERROR, 0, "refused: not a regular file (cannot seek)");
    else r = fogrt__ld_new_buf(L, (uint64_t)size);
    if (!r && fread(L->buf, 1, L->len, f) != L->len) r = fogrt__ld_fail(L, FOGRT_RESULT_IO_ERROR, 0, "read error");
    fclose(f);
    return r;
}
#endif
/* The input of every entry point: the file at path, else size bytes at data. */
FOGRT__LD fogrt_result fogrt__ld_open(fogrt__ld *L, bool from_file, const char *path, const void *data, size_t size) {
    if (!from_file) return fogrt__ld_copy(L, data, size);
    return path ? fogrt__ld_read_path(L, path) : fogrt__ld_cannot_open(L, "no path");
}

/* ------------------------------------------------------------------------------------------
   3. Numbers
   strtod on the private NUL-terminated copy; every number must be finite as a float.
   ------------------------------------------------------------------------------------------ */
FOGRT__LD bool fogrt__ld_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

/* Line of position p, counting newlines from a known (base, base_line). */
FOGRT__LD int fogrt__ld_line_at(const char *base, int base_line, const char *p) {
    int line = base_line;
    for (; base < p; ++base) if (*base == '\n') line++;
    return line;
}

/* Length of the token at s (up to a blank, '<' or e; at most 16) for messages. */
FOGRT__LD int fogrt__ld_toklen(const char *s, const char *e) {
    int n = 0;
    while (s + n < e && n < 16 && s[n] != '<' && s[n] != 0 && !(s[n] == ' ' || s[n] == '\t' || s[n] == '\n' || s[n] == '\r')) n++;
    return n;
}

/* Parses one number starting exactly at *s (no leading blanks), not beyond e. */
FOGRT__LD bool fogrt__ld_strtof(const char **s, const char *e, float *out) {
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
                                        float *out, uint64_t max, uint64_t *n) {
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
                                       uint32_t *out, uint64_t max, uint64_t *n) {
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
   4. A minimal XML reader
   Elements, attributes, text, comments, CDATA, <?...?> and <!DOCTYPE>; the five predefined
   entities and numeric character references in attribute values. No namespaces, no DTD.
   The tree is kept as arrays of elements and attributes pointing into the buffer.
   ------------------------------------------------------------------------------------------ */
FOGRT__LD bool fogrt__ld_starts(const char *p, const char *end, const char *lit) {
    size_t n = strlen(lit);
    return (size_t)(end - p) >= n && memcmp(p, lit, n) == 0;
}
/* First occurrence of lit in [p, end), or NULL. */
FOGRT__LD const char *fogrt__ld_find(const char *p, const char *end, const char *lit) {
    size_t n = strlen(lit);
    for (; (size_t)(end - p) >= n; ++p)
        if (*p == lit[0] && memcmp(p, lit, n) == 0) return p;
    return NULL;
}
FOGRT__LD int fogrt__ld_count_lines(const char *p, const char *q) {
    int n = 0;
    for (; p < q; ++p) if (*p == '\n') n++;
    return n;
}
FOGRT__LD bool fogrt__ld_name_char(char c) {
    return !fogrt__ld_space(c) && c != '/' && c != '>' && c != '<' && c != '=' && c != '"' && c != '\'' && c != 0;
}

/* Writes code point cp (1 .. 0x10FFFF) as UTF-8 at out; returns the bytes written (1-4). */
FOGRT__LD uint32_t fogrt__ld_utf8(uint32_t cp, char *out) {
    if (cp < 0x80) { out[0] = (char)cp; return 1; }
    if (cp < 0x800) { out[0] = (char)(0xC0 | (cp >> 6)); out[1] = (char)(0x80 | (cp & 63)); return 2; }
    if (cp < 0x10000) {
        out[0] = (char)(0xE0 | (cp >> 12)); out[1] = (char)(0x80 | ((cp >> 6) & 63)); out[2] = (char)(0x80 | (cp & 63));
        return 3;
    }
    out[0] = (char)(0xF0 | (cp >> 18)); out[1] = (char)(0x80 | ((cp >> 12) & 63));
    out[2] = (char)(0x80 | ((cp >> 6) & 63)); out[3] = (char)(0x80 | (cp & 63));
    return 4;
}
FOGRT__LD int fogrt__ld_digit(char c, bool hex) {
    if (c >= '0' && c <= '9') return c - '0';
    if (hex && c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (hex && c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}
/* One reference at s[0] == '&' (n bytes available): &lt; &gt; &amp; &quot; &apos; &#N;
   &#xH;. Writes its character(s) at out; returns the reference's length, 0 if it is none.
   A reference is at least as long as its UTF-8 output, so decoding in place is safe. */
FOGRT__LD uint32_t fogrt__ld_reference(const char *s, uint32_t n, char *out, uint32_t *written) {
    static const char *names[5] = { "lt;", "gt;", "amp;", "quot;", "apos;" };
    static const char chars[5] = { '<', '>', '&', '"', '\'' };
    uint32_t j = 2, cp = 0, digits = 0, k;
    bool hex;
    for (k = 0; k < 5; ++k) {
        uint32_t len = (uint32_t)strlen(names[k]);
        if (n - 1 >= len && memcmp(s + 1, names[k], len) == 0) { out[0] = chars[k]; *written = 1; return 1 + len; }
    }
    if (n < 3 || s[1] != '#') return 0;
    hex = s[2] == 'x' || s[2] == 'X';
    if (hex) ++j;
    for (; j < n && digits < 8; ++j, ++digits) {
        int v = fogrt__ld_digit(s[j], hex);
        if (v < 0) break;
        cp = cp * (hex ? 16u : 10u) + (uint32_t)v;
    }
    if (digits == 0 || j >= n || s[j] != ';' || cp == 0 || cp > 0x10FFFF) return 0;
    *written = fogrt__ld_utf8(cp, out);
    return j + 1;
}
/* Decodes the references in s[0..len) in place; returns the new length. */
FOGRT__LD uint32_t fogrt__ld_decode(char *s, uint32_t len) {
    uint32_t i = 0, o = 0;
    while (i < len) {
        uint32_t w = 0, used = s[i] == '&' ? fogrt__ld_reference(s + i, len - i, s + o, &w) : 0;
        if (used) { i += used; o += w; }
        else s[o++] = s[i++];
    }
    return o;
}

/* The reader's position: p in the buffer, its line, and the innermost open element. */
typedef struct fogrt__ld_xml { char *p, *end; int line; int32_t cur; } fogrt__ld_xml;

FOGRT__LD void fogrt__ld_xml_blanks(fogrt__ld_xml *X) {
    while (X->p < X->end && fogrt__ld_space(*X->p)) { if (*X->p == '\n') X->line++; ++X->p; }
}
FOGRT__LD char *fogrt__ld_xml_name(fogrt__ld_xml *X) {
    while (X->p < X->end && fogrt__ld_name_char(*X->p)) ++X->p;
    return X->p;
}
/* Sets the text of the open element (its first non-blank run) if it has none yet. */
FOGRT__LD void fogrt__ld_xml_set_text(fogrt__ld *L, const fogrt__ld_xml *X, const char *s, const char *e, int line) {
    fogrt__ld_el *el = &L->el[X->cur];
    if (el->text) return;
    el->text = s; el->text_len = (uint32_t)(e - s); el->text_line = line;
}

/* A run of character data up to the next '<'. */
FOGRT__LD fogrt_result fogrt__ld_xml_text(fogrt__ld *L, fogrt__ld_xml *X) {
    char *s = X->p;
    int sline = X->line;
    bool blank = true;
    for (; X->p < X->end && *X->p != '<'; ++X->p) {
        if (*X->p == '\n') X->line++;
        else if (!fogrt__ld_space(*X->p)) blank = false;
    }
    if (blank) return FOGRT_RESULT_OK;
    if (X->cur < 0) return fogrt__ld_fail(L, FOGRT__LD_PARSE, sline, "text outside the root element");
    fogrt__ld_xml_set_text(L, X, s, X->p, sline);
    return FOGRT_RESULT_OK;
}

/* Markup that is not an element: <!-- -->, <![CDATA[ ]]> (text), <? ?>, <!DOCTYPE [..]>.
   *done is false when p is at an element tag instead. */
FOGRT__LD fogrt_result fogrt__ld_xml_markup(fogrt__ld *L, fogrt__ld_xml *X, bool *done) {
    static const char *open[3] = { "<!--", "<![CDATA[", "<?" }, *close[3] = { "-->", "]]>", "?>" };
    static const char *what[3] = { "comment not closed (missing '-->')", "CDATA section not closed (missing ']]>')",
                                   "'<?' not closed (missing '?>')" };
    int k, depth = 0;
    char *q;
    *done = true;
    for (k = 0; k < 3; ++k) {
        const char *e;
        size_t n = strlen(open[k]);
        if (!fogrt__ld_starts(X->p, X->end, open[k])) continue;
        e = fogrt__ld_find(X->p + n, X->end, close[k]);
        if (!e) return fogrt__ld_fail(L, FOGRT__LD_PARSE, X->line, "%s", what[k]);
        if (k == 1) {                                  /* CDATA is text */
            if (X->cur < 0) return fogrt__ld_fail(L, FOGRT__LD_PARSE, X->line, "CDATA outside the root element");
            fogrt__ld_xml_set_text(L, X, X->p + n, e, X->line);
        }
        X->line += fogrt__ld_count_lines(X->p, e);
        X->p = L->buf + (e - L->buf) + strlen(close[k]);
        return FOGRT_RESULT_OK;
    }
    if (!fogrt__ld_starts(X->p, X->end, "<!")) { *done = false; return FOGRT_RESULT_OK; }
    for (q = X->p + 2; q < X->end && !(*q == '>' && depth == 0); ++q) {   /* <!DOCTYPE ...> with an optional [...] */
        if (*q == '[') depth++;
        else if (*q == ']' && depth > 0) depth--;
        else if (*q == '\n') X->line++;
    }
    if (q >= X->end) return fogrt__ld_fail(L, FOGRT__LD_PARSE, X->line, "'<!' declaration not closed");
    X->p = q + 1;
    return FOGRT_RESULT_OK;
}

/* </name>: must close the open element. */
FOGRT__LD fogrt_result fogrt__ld_xml_end_tag(fogrt__ld *L, fogrt__ld_xml *X) {
    char *n = X->p + 2, *q;
    const fogrt__ld_el *e;
    X->p = n;
    q = fogrt__ld_xml_name(X);
    if (X->cur < 0)
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, X->line, "closing tag </%.*s> without an opening tag", FOGRT__LD_CLIP(q - n), n);
    e = &L->el[X->cur];
    if ((uint32_t)(q - n) != e->name_len || memcmp(n, e->name, e->name_len) != 0)
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, X->line, "closing tag </%.*s> does not match <%.*s> opened at line %d",
                              FOGRT__LD_CLIP(q - n), n, FOGRT__LD_CLIP(e->name_len), e->name, e->line);
    fogrt__ld_xml_blanks(X);
    if (X->p >= X->end || *X->p != '>')
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, X->line, "expected '>' to end </%.*s>", FOGRT__LD_CLIP(e->name_len), e->name);
    X->p++;
    X->cur = e->parent;
    return FOGRT_RESULT_OK;
}

/* One attribute name="value" (or 'value') of element id, value decoded in place. */
FOGRT__LD fogrt_result fogrt__ld_xml_attr(fogrt__ld *L, fogrt__ld_xml *X, int32_t id) {
    char *an = X->p, *vs, quote;
    uint32_t alen;
    fogrt__ld_xattr *a;
    if (fogrt__ld_xml_name(X) == an)
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, X->line, "unexpected character '%c' in a tag", *an ? *an : '?');
    alen = (uint32_t)(X->p - an);
    fogrt__ld_xml_blanks(X);
    if (X->p >= X->end || *X->p != '=') return fogrt__ld_fail(L, FOGRT__LD_PARSE, X->line, "attribute '%.*s' has no value", FOGRT__LD_CLIP(alen), an);
    X->p++;
    fogrt__ld_xml_blanks(X);
    if (X->p >= X->end || (*X->p != '"' && *X->p != '\''))
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, X->line, "attribute '%.*s': value not quoted", FOGRT__LD_CLIP(alen), an);
    quote = *X->p++;
    for (vs = X->p; X->p < X->end && *X->p != quote; ++X->p) {
        if (*X->p == '<') return fogrt__ld_fail(L, FOGRT__LD_PARSE, X->line, "'<' inside the value of attribute '%.*s'", FOGRT__LD_CLIP(alen), an);
        if (*X->p == '\n') X->line++;
    }
    if (X->p >= X->end)
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, X->line, "unexpected end of file in the value of attribute '%.*s'", FOGRT__LD_CLIP(alen), an);
    FOGRT__LD_TRY(FOGRT__LD_PUSH(L, L->at, L->at_count, L->at_cap));
    a = &L->at[L->at_count++];
    a->name = an; a->name_len = alen;
    a->value = vs; a->value_len = fogrt__ld_decode(vs, (uint32_t)(X->p - vs));
    L->el[id].attr_count++;
    X->p++;
    return FOGRT_RESULT_OK;
}

/* A new element named [n, q), appended to the open element's children. */
FOGRT__LD fogrt_result fogrt__ld_xml_new_el(fogrt__ld *L, fogrt__ld_xml *X, const char *n, const char *q, int32_t *out) {
    fogrt__ld_el *e;
    int32_t id, cur = X->cur;
    FOGRT__LD_TRY(FOGRT__LD_PUSH(L, L->el, L->el_count, L->el_cap));
    id = (int32_t)L->el_count++;
    e = &L->el[id];
    memset(e, 0, sizeof *e);
    e->name = n; e->name_len = (uint32_t)(q - n);
    e->attr_first = L->at_count;
    e->parent = cur; e->first_child = e->last_child = e->next = -1;
    e->line = X->line;
    if (cur < 0) L->root = id;
    else {
        if (L->el[cur].last_child >= 0) L->el[L->el[cur].last_child].next = id;
        else L->el[cur].first_child = id;
        L->el[cur].last_child = id;
    }
    *out = id;
    return FOGRT_RESULT_OK;
}

/* <name attr="v" ...> or <name .../>. */
FOGRT__LD fogrt_result fogrt__ld_xml_start_tag(fogrt__ld *L, fogrt__ld_xml *X) {
    char *n = X->p + 1, *q;
    int32_t id;
    X->p = n;
    q = fogrt__ld_xml_name(X);
    if (q == n) return fogrt__ld_fail(L, FOGRT__LD_PARSE, X->line, "expected an element name after '<'");
    if (X->cur < 0 && L->root >= 0) return fogrt__ld_fail(L, FOGRT__LD_PARSE, X->line, "a second root element <%.*s>", FOGRT__LD_CLIP(q - n), n);
    FOGRT__LD_TRY(fogrt__ld_xml_new_el(L, X, n, q, &id));
    for (;;) {
        fogrt__ld_xml_blanks(X);
        if (X->p >= X->end)
            return fogrt__ld_fail(L, FOGRT__LD_PARSE, X->line, "unexpected end of file inside the tag <%.*s> (line %d)",
                                  FOGRT__LD_CLIP(L->el[id].name_len), L->el[id].name, L->el[id].line);
        if (*X->p == '>') { X->p++; X->cur = id; return FOGRT_RESULT_OK; }
        if (*X->p == '/') {
            if (X->p + 1 < X->end && X->p[1] == '>') { X->p += 2; return FOGRT_RESULT_OK; }
            return fogrt__ld_fail(L, FOGRT__LD_PARSE, X->line, "expected '/>'");
        }
        FOGRT__LD_TRY(fogrt__ld_xml_attr(L, X, id));
    }
}

FOGRT__LD fogrt_result fogrt__ld_xml_parse(fogrt__ld *L) {
    fogrt__ld_xml X;
    const fogrt__ld_el *open;
    X.p = L->buf; X.end = L->buf + L->len; X.line = 1; X.cur = -1;
    if (fogrt__ld_starts(X.p, X.end, "\xEF\xBB\xBF")) X.p += 3;    /* UTF-8 byte-order mark */
    while (X.p < X.end) {
        bool done;
        if (*X.p != '<') FOGRT__LD_TRY(fogrt__ld_xml_text(L, &X));
        else {
            FOGRT__LD_TRY(fogrt__ld_xml_markup(L, &X, &done));
            if (done) continue;
            if (X.p + 1 < X.end && X.p[1] == '/') FOGRT__LD_TRY(fogrt__ld_xml_end_tag(L, &X));
            else FOGRT__LD_TRY(fogrt__ld_xml_start_tag(L, &X));
        }
    }
    if (L->len > 0 && L->buf[L->len - 1] == '\n' && X.line > 1) X.line--;   /* name the last line, not the one after it */
    if (X.cur >= 0) {
        open = &L->el[X.cur];
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, X.line, "unexpected end of file: <%.*s> opened at line %d is not closed",
                              FOGRT__LD_CLIP(open->name_len), open->name, open->line);
    }
    if (L->root < 0) return fogrt__ld_fail(L, FOGRT__LD_PARSE, X.line, "no XML element found");
    return FOGRT_RESULT_OK;
}
/* ---- tree queries ---- */
FOGRT__LD bool fogrt__ld_is(const fogrt__ld *L, int32_t e, const char *name) {
    size_t n = strlen(name);
    return e >= 0 && L->el[e].name_len == n && memcmp(L->el[e].name, name, n) == 0;
}
FOGRT__LD int32_t fogrt__ld_child(const fogrt__ld *L, int32_t e, const char *name) {
    int32_t c;
    if (e < 0) return -1;
    for (c = L->el[e].first_child; c >= 0; c = L->el[c].next)
        if (fogrt__ld_is(L, c, name)) return c;
    return -1;
}
FOGRT__LD int32_t fogrt__ld_next_named(const fogrt__ld *L, int32_t c, const char *name) {
    for (c = c >= 0 ? L->el[c].next : -1; c >= 0; c = L->el[c].next)
        if (fogrt__ld_is(L, c, name)) return c;
    return -1;
}
/* Walks a slash-separated path of first children ("optics/technique_common/perspective"). */
FOGRT__LD int32_t fogrt__ld_path(const fogrt__ld *L, int32_t e, const char *path) {
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
FOGRT__LD const char *fogrt__ld_attr(const fogrt__ld *L, int32_t e, const char *name, uint32_t *len) {
    uint32_t i;
    size_t n = strlen(name);
    if (e < 0) return NULL;
    for (i = 0; i < L->el[e].attr_count; ++i) {
        const fogrt__ld_xattr *a = &L->at[L->el[e].attr_first + i];
        if (a->name_len == n && memcmp(a->name, name, n) == 0) { if (len) *len = a->value_len; return a->value; }
    }
    return NULL;
}
FOGRT__LD bool fogrt__ld_attr_is(const fogrt__ld *L, int32_t e, const char *name, const char *value) {
    uint32_t len;
    const char *v = fogrt__ld_attr(L, e, name, &len);
    return v && len == strlen(value) && memcmp(v, value, len) == 0;
}
/* Integer attribute; false when absent. A malformed value is an error (*res). */
FOGRT__LD bool fogrt__ld_attr_uint(fogrt__ld *L, int32_t e, const char *name, uint64_t *out, fogrt_result *res) {
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

FOGRT__LD uint32_t fogrt__ld_hash(const char *s, uint32_t n) {
    uint32_t h = 2166136261u, i;
    for (i = 0; i < n; ++i) { h ^= (unsigned char)s[i]; h *= 16777619u; }
    return h;
}
/* One global table of every id in the document (the first element with an id wins). */
FOGRT__LD fogrt_result fogrt__ld_build_ids(fogrt__ld *L) {
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
                uint32_t klen = 0;
                const char *kv = fogrt__ld_attr(L, (int32_t)k, "id", &klen);
                if (kv && klen == len && memcmp(kv, v, len) == 0) break;   /* duplicate: keep the first */
            }
        }
    }
    return FOGRT_RESULT_OK;
}
/* Resolves "#id" (or "id") to an element, or -1. */
FOGRT__LD int32_t fogrt__ld_lookup(const fogrt__ld *L, const char *v, uint32_t len) {
    uint32_t h;
    if (!v || !L->ids) return -1;
    if (len && v[0] == '#') { ++v; --len; }
    for (h = fogrt__ld_hash(v, len) & (L->ids_cap - 1); L->ids[h]; h = (h + 1) & (L->ids_cap - 1)) {
        uint32_t klen = 0, k = L->ids[h] - 1;
        const char *kv = fogrt__ld_attr(L, (int32_t)k, "id", &klen);
        if (kv && klen == len && memcmp(kv, v, len) == 0) return (int32_t)k;
    }
    return -1;
}
/* Follows the attribute attr ("url", "target", "source") of e to its element. */
FOGRT__LD int32_t fogrt__ld_ref(const fogrt__ld *L, int32_t e, const char *attr) {
    uint32_t len;
    const char *v = fogrt__ld_attr(L, e, attr, &len);
    return v ? fogrt__ld_lookup(L, v, len) : -1;
}

/* Reads between min_n and max_n floats from the text of element e (error if fewer than min_n). */
FOGRT__LD fogrt_result fogrt__ld_el_floats(fogrt__ld *L, int32_t e, float *out, uint32_t min_n, uint32_t max_n, uint32_t *n) {
    uint64_t k = 0;
    const fogrt__ld_el *x = &L->el[e];
    if (x->text) FOGRT__LD_TRY(fogrt__ld_floats(L, x->text, x->text + x->text_len, x->text_line, out, max_n, &k));
    if (k < min_n)
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, x->line, "<%.*s> needs %u number%s, found %u",
                              FOGRT__LD_CLIP(x->name_len), x->name, min_n, min_n == 1 ? "" : "s", (unsigned)k);
    if (n) *n = (uint32_t)k;
    return FOGRT_RESULT_OK;
}
FOGRT__LD fogrt_result fogrt__ld_no_child(fogrt__ld *L, int32_t e, const char *name) {
    return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[e].line, "<%.*s> needs a <%s> child", FOGRT__LD_CLIP(L->el[e].name_len), L->el[e].name, name);
}
/* Reads a colour (3 floats, a 4th alpha ignored), >= 0, from child `name` of e. Returns
   false (without error) if the child is missing and required is false. */
FOGRT__LD fogrt_result fogrt__ld_child_vec3(fogrt__ld *L, int32_t e, const char *name, bool required, bool non_negative,
                                            fogrt_vec3 *out, bool *found) {
    float v[4];
    int32_t c = fogrt__ld_child(L, e, name);
    if (found) *found = c >= 0;
    if (c < 0) return required ? fogrt__ld_no_child(L, e, name) : FOGRT_RESULT_OK;
    FOGRT__LD_TRY(fogrt__ld_el_floats(L, c, v, 3, 4, NULL));
    if (non_negative && (v[0] < 0 || v[1] < 0 || v[2] < 0))
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[c].line, "<%s> must not be negative", name);
    out->x = v[0]; out->y = v[1]; out->z = v[2];
    return FOGRT_RESULT_OK;
}
FOGRT__LD fogrt_result fogrt__ld_child_float(fogrt__ld *L, int32_t e, const char *name, bool required, float *out, bool *found) {
    int32_t c = fogrt__ld_child(L, e, name);
    if (found) *found = c >= 0;
    if (c < 0) return required ? fogrt__ld_no_child(L, e, name) : FOGRT_RESULT_OK;
    return fogrt__ld_el_floats(L, c, out, 1, 1, NULL);
}

/* ------------------------------------------------------------------------------------------
   5. Small linear algebra: 4x4 row-major matrices in double precision
   ------------------------------------------------------------------------------------------ */
FOGRT__LD void fogrt__ld_identity(double m[16]) {
    int i;
    for (i = 0; i < 16; ++i) m[i] = (i % 5 == 0) ? 1.0 : 0.0;
}
FOGRT__LD void fogrt__ld_mul(const double a[16], const double b[16], double out[16]) {
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
FOGRT__LD void fogrt__ld_xform4(const double m[16], double x, double y, double z, double w, double out[4]) {
    int i;
    for (i = 0; i < 4; ++i) out[i] = m[4 * i] * x + m[4 * i + 1] * y + m[4 * i + 2] * z + m[4 * i + 3] * w;
}
FOGRT__LD double fogrt__ld_det3(const double m[16]) {
    return m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) + m[2] * (m[4] * m[9] - m[5] * m[8]);
}
FOGRT__LD double fogrt__ld_len3(const double v[3]) { return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }
/* Double to float vector, failing when it does not fit a finite float. */
FOGRT__LD bool fogrt__ld_to_vec3(const double d[3], fogrt_vec3 *out) {
    int i;
    for (i = 0; i < 3; ++i) if (!(d[i] == d[i]) || d[i] > (double)FLT_MAX || d[i] < -(double)FLT_MAX) return false;
    out->x = (float)d[0]; out->y = (float)d[1]; out->z = (float)d[2];
    return true;
}
FOGRT__LD fogrt_vec3 fogrt__ld_v3(float x, float y, float z) { fogrt_vec3 v; v.x = x; v.y = y; v.z = z; return v; }
FOGRT__LD bool fogrt__ld_black(fogrt_vec3 c) { return c.x == 0.0f && c.y == 0.0f && c.z == 0.0f; }

/* Within the scene's coordinate limit (finite and at most 1e30 in size). */
FOGRT__LD bool fogrt__ld_coord_ok(double x) { return x >= -FOGRT__LD_MAX_COORD && x <= FOGRT__LD_MAX_COORD; }
FOGRT__LD bool fogrt__ld_to_coord3(const double d[3], fogrt_vec3 *out) {
    return fogrt__ld_coord_ok(d[0]) && fogrt__ld_coord_ok(d[1]) && fogrt__ld_coord_ok(d[2]) && fogrt__ld_to_vec3(d, out);
}

/* ------------------------------------------------------------------------------------------
   6. Mesh helpers shared by all formats: smooth normals, compaction, placement
   ------------------------------------------------------------------------------------------ */
FOGRT__LD int fogrt__ld_cmp_u64(const void *a, const void *b) {
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}
FOGRT__LD uint32_t fogrt__ld_find_root(uint32_t *parent, uint32_t v) {
    while (parent[v] != v) { parent[v] = parent[parent[v]]; v = parent[v]; }
    return v;
}
/* Joins the vertices of every edge (union-find) and lists the edges as sorted (a, b) keys. */
FOGRT__LD size_t fogrt__ld_edges(const fogrt__ld_meshbuf *m, uint64_t *edges, uint32_t *parent) {
    uint32_t t, i, v;
    size_t ne = 0;
    for (v = 0; v < m->nv; ++v) parent[v] = v;
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
    return ne;
}
/* open[v] = 1 for the vertices of connected parts that have an open edge (an edge used by
   one triangle only). CS184's boundary walk gives such parts (its planar Cornell quads) the
   negated smooth normal; fogrt__ld_smooth_normals does the same. *out = NULL if m is empty. */
FOGRT__LD fogrt_result fogrt__ld_open_parts(fogrt__ld *L, const fogrt__ld_meshbuf *m, unsigned char **out) {
    uint64_t *edges = (uint64_t *)fogrt__ld_alloc(L, (uint64_t)m->nt * 3, sizeof(uint64_t));
    uint32_t *parent = (uint32_t *)fogrt__ld_alloc(L, m->nv, sizeof(uint32_t));
    unsigned char *open = (unsigned char *)fogrt__ld_alloc(L, m->nv, 1), *part;
    size_t ne, k;
    uint32_t v;
    *out = NULL;
    part = (unsigned char *)fogrt__ld_alloc(L, m->nv, 1);
    if (!edges || !parent || !open || !part) {
        fogrt__ld_free(L, edges); fogrt__ld_free(L, parent); fogrt__ld_free(L, open); fogrt__ld_free(L, part);
        return FOGRT_RESULT_OUT_OF_MEMORY;
    }
    memset(part, 0, m->nv);
    ne = fogrt__ld_edges(m, edges, parent);
    for (k = 0; k < ne;) {
        size_t run = 1;
        while (k + run < ne && edges[k + run] == edges[k]) run++;
        if (run == 1) part[fogrt__ld_find_root(parent, (uint32_t)(edges[k] >> 32))] = 1;
        k += run;
    }
    for (v = 0; v < m->nv; ++v) open[v] = part[fogrt__ld_find_root(parent, v)];
    fogrt__ld_free(L, edges); fogrt__ld_free(L, parent); fogrt__ld_free(L, part);
    *out = open;
    return FOGRT_RESULT_OK;
}

/* cross(b - a, c - a) of the triangle with vertex indices id, in double. */
FOGRT__LD void fogrt__ld_face_normal(const float *pos, const uint32_t *id, double n[3]) {
    const float *a = pos + 3 * (size_t)id[0], *b = pos + 3 * (size_t)id[1], *c = pos + 3 * (size_t)id[2];
    double e1[3], e2[3];
    int i;
    for (i = 0; i < 3; ++i) { e1[i] = (double)b[i] - (double)a[i]; e2[i] = (double)c[i] - (double)a[i]; }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
}
/* Smooth vertex normals as CS184 computes them: the normalised sum over the incident
   triangles of cross(b - a, c - a) (area weighted, following the winding), negated where
   open[v] (may be NULL). acc: scratch of 3 * nv doubles. Writes nrm (3 * nv floats). */
FOGRT__LD void fogrt__ld_smooth_normals(const float *pos, const uint32_t *idx, uint32_t nv, uint32_t nt,
                                        const unsigned char *open, double *acc, float *nrm) {
    uint32_t t, v, i;
    memset(acc, 0, (size_t)nv * 3 * sizeof(double));
    for (t = 0; t < nt; ++t) {
        const uint32_t *id = idx + 3 * (size_t)t;
        double n[3];
        fogrt__ld_face_normal(pos, id, n);
        for (v = 0; v < 3; ++v) for (i = 0; i < 3; ++i) acc[3 * (size_t)id[v] + i] += n[i];
    }
    for (v = 0; v < nv; ++v) {
        double *n = acc + 3 * (size_t)v, len = fogrt__ld_len3(n), s = open && open[v] ? -1.0 : 1.0;
        if (len > 0.0 && len < HUGE_VAL) {
            for (i = 0; i < 3; ++i) nrm[3 * (size_t)v + i] = (float)(s * n[i] / len);
        } else {                      /* isolated or cancelling: any unit vector will do */
            nrm[3 * (size_t)v] = 0.0f; nrm[3 * (size_t)v + 1] = 1.0f; nrm[3 * (size_t)v + 2] = 0.0f;
        }
    }
}

/* Drops the vertices no triangle uses (keeps normals in step), so bounds and normals see
   only real geometry. */
FOGRT__LD fogrt_result fogrt__ld_compact(fogrt__ld *L, fogrt__ld_meshbuf *m) {
    uint32_t *map, v, t, n = 0;
    map = (uint32_t *)fogrt__ld_alloc(L, m->nv, sizeof(uint32_t));
    if (!map) return FOGRT_RESULT_OUT_OF_MEMORY;
    for (v = 0; v < m->nv; ++v) map[v] = UINT32_MAX;
    for (t = 0; t < 3 * m->nt; ++t) map[m->idx[t]] = 0;
    for (v = 0; v < m->nv; ++v)
        if (map[v] == 0) {
            map[v] = n;
            memmove(m->pos + 3 * (size_t)n, m->pos + 3 * (size_t)v, 3 * sizeof(float));
            if (m->nrm) memmove(m->nrm + 3 * (size_t)n, m->nrm + 3 * (size_t)v, 3 * sizeof(float));
            n++;
        }
    for (t = 0; t < 3 * m->nt; ++t) m->idx[t] = map[m->idx[t]];
    m->nv = n;
    fogrt__ld_free(L, map);
    return FOGRT_RESULT_OK;
}

FOGRT__LD void fogrt__ld_grow_bounds(fogrt__ld *L, const float p[3], float pad) {
    int i;
    for (i = 0; i < 3; ++i) {
        double lo = (double)p[i] - (double)pad, hi = (double)p[i] + (double)pad;
        if (!L->has_bounds || lo < L->bmin[i]) L->bmin[i] = lo;
        if (!L->has_bounds || hi > L->bmax[i]) L->bmax[i] = hi;
    }
    L->has_bounds = true;
}

/* The box of the n points at pos (n > 0), in double. */
FOGRT__LD void fogrt__ld_box(const float *pos, uint32_t n, double lo[3], double hi[3]) {
    uint32_t v;
    int i;
    for (i = 0; i < 3; ++i) lo[i] = hi[i] = (double)pos[i];
    for (v = 1; v < n; ++v)
        for (i = 0; i < 3; ++i) {
            double x = (double)pos[3 * (size_t)v + (size_t)i];
            if (x < lo[i]) lo[i] = x;
            if (x > hi[i]) hi[i] = x;
        }
}
/* OBJ/PLY placement: uniform scale into the fit box, standing on its floor, centred in x, z.
   In double precision, so that models of any size (even near FLT_MAX or with a denormal
   extent) end up inside the box. */
FOGRT__LD void fogrt__ld_place(fogrt__ld *L, fogrt__ld_meshbuf *m) {
    double lo[3], hi[3], s = -1.0, c[3], box[3], mid[3];
    uint32_t v;
    int i;
    fogrt_vec3 fmin = L->opt.fit_min, fmax = L->opt.fit_max;
    if (fmin.x == 0 && fmin.y == 0 && fmin.z == 0 && fmax.x == 0 && fmax.y == 0 && fmax.z == 0) {
        fmin = fogrt__ld_v3(FOGRT_LOAD_FIT_MIN_X, FOGRT_LOAD_FIT_MIN_Y, FOGRT_LOAD_FIT_MIN_Z);
        fmax = fogrt__ld_v3(FOGRT_LOAD_FIT_MAX_X, FOGRT_LOAD_FIT_MAX_Y, FOGRT_LOAD_FIT_MAX_Z);
    }
    if (m->nv == 0) return;
    fogrt__ld_box(m->pos, m->nv, lo, hi);
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
            float *p = m->pos + 3 * (size_t)v + (size_t)i;
            *p = (float)(((double)*p - c[i]) * s + mid[i]);
        }
}
/* ------------------------------------------------------------------------------------------
   7. COLLADA: materials (CGL technique, else phong / lambert diffuse, else grey 0.5)
   ------------------------------------------------------------------------------------------ */
/* The CGL technique of element e: its first <extra>, the first <technique profile="CGL">. */
FOGRT__LD int32_t fogrt__ld_cgl(const fogrt__ld *L, int32_t e) {
    int32_t extra = fogrt__ld_child(L, e, "extra"), t;
    for (t = fogrt__ld_child(L, extra, "technique"); t >= 0; t = fogrt__ld_next_named(L, t, "technique"))
        if (fogrt__ld_attr_is(L, t, "profile", "CGL")) return t;
    return -1;
}

FOGRT__LD fogrt_material_desc fogrt__ld_diffuse(float r, float g, float b) {
    fogrt_material_desc m;
    memset(&m, 0, sizeof m);
    m.type = FOGRT_BSDF_DIFFUSE;
    m.reflectance = fogrt__ld_v3(r, g, b);
    return m;
}

FOGRT__LD fogrt_result fogrt__ld_ior(fogrt__ld *L, int32_t e, float *ior) {
    FOGRT__LD_TRY(fogrt__ld_child_float(L, e, "ior", true, ior, NULL));
    if (!(*ior > 0.0f)) return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[fogrt__ld_child(L, e, "ior")].line, "<ior> must be > 0");
    return FOGRT_RESULT_OK;
}

/* A CGL <microfacet>: a conductor (eta + i k per channel) with Beckmann roughness alpha,
   loaded as fogrt's microfacet material (fogrt.h, Part II, I). CS184 also looks up a
   <reflectance> child and never uses it; fogrt ignores it too. Warned: an alpha fogrt cannot
   render as written (not above 0, where CS184's Beckmann divides by zero, or beyond 1000)
   is clamped to [1e-4, 1000]. A fogrt built without the material (FOGRT_NO_MICROFACET,
   FOGRT_MINIMAL) gets the nearest of its own BSDFs instead, with a warning: the
   normal-incidence conductor Fresnel F0 = ((eta - 1)^2 + k^2) / ((eta + 1)^2 + k^2) as the
   colour of a mirror (alpha <= 0.25, nearly smooth) or of a diffuse surface (rougher). */
FOGRT__LD fogrt_result fogrt__ld_microfacet(fogrt__ld *L, int32_t c, fogrt_material_desc *m) {
    float alpha;
    fogrt_vec3 e3, k3;
    FOGRT__LD_TRY(fogrt__ld_child_float(L, c, "alpha", true, &alpha, NULL));
    FOGRT__LD_TRY(fogrt__ld_child_vec3(L, c, "eta", true, true, &e3, NULL));
    FOGRT__LD_TRY(fogrt__ld_child_vec3(L, c, "k", true, true, &k3, NULL));
#ifndef FOGRT_NO_MICROFACET
    m->type = FOGRT_BSDF_MICROFACET;
    m->alpha = alpha > 1e-4f ? (alpha < 1e3f ? alpha : 1e3f) : 1e-4f;
    m->eta = e3; m->k = k3;
    if (!(alpha >= 1e-4f && alpha <= 1e3f))
        fogrt__ld_warn(L, L->el[fogrt__ld_child(L, c, "alpha")].line, "<microfacet> alpha %g is outside [1e-4, 1000], where fogrt "
                       "renders Beckmann's roughness: rendered with alpha %g", (double)alpha, (double)m->alpha);
#else
    {
        float f0[3], eta[3], k[3];
        int i;
        eta[0] = e3.x; eta[1] = e3.y; eta[2] = e3.z; k[0] = k3.x; k[1] = k3.y; k[2] = k3.z;
        for (i = 0; i < 3; ++i) {
            double e = (double)eta[i], kk = (double)k[i];
            f0[i] = (float)(((e - 1) * (e - 1) + kk * kk) / ((e + 1) * (e + 1) + kk * kk));
        }
        m->type = alpha <= 0.25f ? FOGRT_BSDF_MIRROR : FOGRT_BSDF_DIFFUSE;
        m->reflectance = fogrt__ld_v3(f0[0], f0[1], f0[2]);
        fogrt__ld_warn(L, L->el[c].line, "<microfacet> (alpha %g): this fogrt was built without rough metals "
                       "(FOGRT_NO_MICROFACET): loaded as a %s of reflectance %.3g %.3g %.3g", (double)alpha,
                       alpha <= 0.25f ? "mirror" : "diffuse", (double)f0[0], (double)f0[1], (double)f0[2]);
    }
#endif
    return FOGRT_RESULT_OK;
}

/* One child of the CGL technique as a material; *known is false for other elements. */
FOGRT__LD fogrt_result fogrt__ld_cgl_bsdf(fogrt__ld *L, int32_t c, fogrt_material_desc *m, bool *known) {
    memset(m, 0, sizeof *m);
    *known = true;
    if (fogrt__ld_is(L, c, "emission")) {
        m->type = FOGRT_BSDF_DIFFUSE;           /* emits, reflects nothing */
        return fogrt__ld_child_vec3(L, c, "radiance", true, true, &m->emission, NULL);
    }
    if (fogrt__ld_is(L, c, "mirror")) {
        m->type = FOGRT_BSDF_MIRROR;
        return fogrt__ld_child_vec3(L, c, "reflectance", true, true, &m->reflectance, NULL);
    }
    if (fogrt__ld_is(L, c, "refraction")) {
        m->type = FOGRT_BSDF_REFRACTION;
        FOGRT__LD_TRY(fogrt__ld_child_vec3(L, c, "transmittance", true, true, &m->transmittance, NULL));
        m->reflectance = m->transmittance;       /* tint of total internal reflection */
        return fogrt__ld_ior(L, c, &m->ior);
    }
    if (fogrt__ld_is(L, c, "glass")) {
        m->type = FOGRT_BSDF_GLASS;
        FOGRT__LD_TRY(fogrt__ld_child_vec3(L, c, "transmittance", true, true, &m->transmittance, NULL));
        FOGRT__LD_TRY(fogrt__ld_child_vec3(L, c, "reflectance", true, true, &m->reflectance, NULL));
        return fogrt__ld_ior(L, c, &m->ior);
    }
    if (fogrt__ld_is(L, c, "microfacet")) return fogrt__ld_microfacet(L, c, m);
    *known = false;
    return FOGRT_RESULT_OK;
}

/* profile_COMMON: the technique with sid "common" (else the first), its phong then lambert
   diffuse colour; else grey 0.5. */
FOGRT__LD fogrt_result fogrt__ld_common_diffuse(fogrt__ld *L, int32_t effect, fogrt_material_desc *out) {
    static const char *shaders[2] = { "phong/diffuse/color", "lambert/diffuse/color" };
    int32_t common = fogrt__ld_child(L, effect, "profile_COMMON"), t;
    int i;
    for (t = fogrt__ld_child(L, common, "technique"); t >= 0; t = fogrt__ld_next_named(L, t, "technique"))
        if (fogrt__ld_attr_is(L, t, "sid", "common")) break;
    if (t < 0) t = fogrt__ld_child(L, common, "technique");
    for (i = 0; i < 2 && t >= 0; ++i) {
        int32_t col = fogrt__ld_path(L, t, shaders[i]);
        float v[4];
        if (col < 0) continue;
        FOGRT__LD_TRY(fogrt__ld_el_floats(L, col, v, 3, 4, NULL));
        if (v[0] < 0 || v[1] < 0 || v[2] < 0)
            return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[col].line, "diffuse colour must not be negative");
        *out = fogrt__ld_diffuse(v[0], v[1], v[2]);
        return FOGRT_RESULT_OK;
    }
    *out = fogrt__ld_diffuse(0.5f, 0.5f, 0.5f);
    return FOGRT_RESULT_OK;
}

/* Reads an <effect> into a material description: among the CGL technique's children the
   last recognised one wins; else the profile_COMMON diffuse colour. */
FOGRT__LD fogrt_result fogrt__ld_effect(fogrt__ld *L, int32_t effect, fogrt_material_desc *out) {
    int32_t tech = fogrt__ld_cgl(L, effect), c;
    bool set = false, known;
    fogrt_material_desc m;
    for (c = tech >= 0 ? L->el[tech].first_child : -1; c >= 0; c = L->el[c].next) {
        FOGRT__LD_TRY(fogrt__ld_cgl_bsdf(L, c, &m, &known));
        if (known) { *out = m; set = true; }
    }
    return set ? FOGRT_RESULT_OK : fogrt__ld_common_diffuse(L, effect, out);
}

/* Glass and refraction need the Fresnel / refraction code that FOGRT_NO_GLASS strips. */
FOGRT__LD bool fogrt__ld_is_glass(const fogrt_material_desc *m) {
    return m->type == FOGRT_BSDF_GLASS || m->type == FOGRT_BSDF_REFRACTION;
}
/* "material 'id'" (or "the default material") for messages. */
FOGRT__LD void fogrt__ld_material_name(const fogrt__ld *L, int32_t material, char *out, size_t size) {
    uint32_t len = 0;
    const char *id = fogrt__ld_attr(L, material, "id", &len);
    if (id) snprintf(out, size, "material '%.*s'", FOGRT__LD_CLIP(len), id);
    else snprintf(out, size, "%s", material < 0 ? "the default material" : "a material without id");
}

/* A reference that resolves to nothing (or to the wrong kind of element): one warning at the
   referring element's line naming the attribute's value, the element that holds it, and what
   fogrt does instead, e.g. `<instance_geometry> url "#box" in node "n": not found: skipped`.
   The holder is the element's <node> when it has one, else the element itself. */
FOGRT__LD void fogrt__ld_warn_unresolved(fogrt__ld *L, int32_t e, const char *attr, const char *instead) {
    uint32_t vlen = 0, hlen = 0;
    const char *value = fogrt__ld_attr(L, e, attr, &vlen);
    int32_t holder = e;
    const char *hname;
    while (holder >= 0 && !fogrt__ld_is(L, holder, "node") && !fogrt__ld_attr(L, holder, "id", &hlen)) holder = L->el[holder].parent;
    if (holder < 0) holder = e;
    hname = fogrt__ld_attr(L, holder, "id", &hlen);
    if (!hname) hname = fogrt__ld_attr(L, holder, "name", &hlen);
    fogrt__ld_warn(L, L->el[e].line, "<%.*s> %s \"%.*s\" in <%.*s> \"%.*s\": not found: %s",
                   FOGRT__LD_CLIP(L->el[e].name_len), L->el[e].name, attr, FOGRT__LD_CLIP(value ? vlen : 0), value ? value : "",
                   FOGRT__LD_CLIP(L->el[holder].name_len), L->el[holder].name, FOGRT__LD_CLIP(hname ? hlen : 0), hname ? hname : "", instead);
}

/* Local material index for a <material> element (-1: the default grey), cached. */
FOGRT__LD fogrt_result fogrt__ld_material(fogrt__ld *L, int32_t material, uint32_t *out) {
    uint32_t i;
    fogrt_material_desc m;
    for (i = 0; i < L->mat_count; ++i) if (L->mats[i].key == material) { *out = i; return FOGRT_RESULT_OK; }
    if (material < 0) {
        m = fogrt__ld_diffuse(0.5f, 0.5f, 0.5f);
    } else {
        int32_t effect = fogrt__ld_ref(L, fogrt__ld_child(L, material, "instance_effect"), "url");
        if (effect < 0) {
            int32_t ie = fogrt__ld_child(L, material, "instance_effect");
            if (ie >= 0) fogrt__ld_warn_unresolved(L, ie, "url", "grey 0.5");
            else {
                char name[64];
                fogrt__ld_material_name(L, material, name, sizeof name);
                fogrt__ld_warn(L, L->el[material].line, "%s has no <instance_effect>: grey 0.5", name);
            }
            m = fogrt__ld_diffuse(0.5f, 0.5f, 0.5f);
        } else {
            FOGRT__LD_TRY(fogrt__ld_effect(L, effect, &m));
        }
#ifdef FOGRT_NO_GLASS
        if (fogrt__ld_is_glass(&m)) {
            char what[80];
            fogrt__ld_material_name(L, material, what, sizeof what);
            return fogrt__ld_fail(L, FOGRT_RESULT_UNSUPPORTED, L->el[material].line,
                                  "%s is glass/refraction, which this fogrt was built without (FOGRT_NO_GLASS)", what);
        }
#endif
    }
    FOGRT__LD_TRY(FOGRT__LD_PUSH(L, L->mats, L->mat_count, L->mat_cap));
    L->mats[L->mat_count].desc = m;
    L->mats[L->mat_count].key = material;
    *out = L->mat_count++;
    return FOGRT_RESULT_OK;
}

/* The material bound to a primitive list: the <instance_material> whose symbol is the list's
   material attribute, else the first one (CS184), else grey. */
FOGRT__LD fogrt_result fogrt__ld_bound_material(fogrt__ld *L, int32_t inst, int32_t list, uint32_t *out) {
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
            fogrt__ld_warn_unresolved(L, im, "target", "grey 0.5");
            target = -1;
        }
    }
    return fogrt__ld_material(L, target, out);
}

/* ------------------------------------------------------------------------------------------
   8. COLLADA: geometry (meshes, parsed once per <geometry>, and CGL spheres)
   ------------------------------------------------------------------------------------------ */
/* Triangles being collected for one geometry: 3 indices and the list ordinal each. */
typedef struct fogrt__ld_tris { uint32_t *idx, *list; uint32_t n, cap_i, cap_l; } fogrt__ld_tris;

FOGRT__LD fogrt_result fogrt__ld_add_tri(fogrt__ld *L, fogrt__ld_tris *T, uint32_t a, uint32_t b, uint32_t c, uint32_t list) {
    FOGRT__LD_TRY(fogrt__ld_grow(L, (void **)&T->idx, &T->cap_i, 3 * ((uint64_t)T->n + 1), sizeof(uint32_t)));
    FOGRT__LD_TRY(fogrt__ld_grow(L, (void **)&T->list, &T->cap_l, (uint64_t)T->n + 1, sizeof(uint32_t)));
    T->idx[3 * (size_t)T->n] = a; T->idx[3 * (size_t)T->n + 1] = b; T->idx[3 * (size_t)T->n + 2] = c;
    T->list[T->n++] = list;
    return FOGRT_RESULT_OK;
}

/* One primitive list being read: where the vertex index sits among each corner's inputs. */
typedef struct fogrt__ld_prim {
    int32_t list; uint32_t ordinal;   /* the element and its place among the mesh's lists */
    uint32_t stride, v_off, nv;       /* indices per corner, the VERTEX one, vertices */
    uint64_t count;                   /* polygons */
    const char *kind;                 /* "polylist", "triangles" or "polygons" */
} fogrt__ld_prim;

/* The <input>s: stride = largest offset + 1 (COLLADA), the VERTEX input's offset; count. */
FOGRT__LD fogrt_result fogrt__ld_prim_inputs(fogrt__ld *L, fogrt__ld_prim *P, int32_t vertices) {
    int32_t c, list = P->list;
    uint64_t max_off = 0;
    bool has_vertex = false;
    fogrt_result res;
    for (c = fogrt__ld_child(L, list, "input"); c >= 0; c = fogrt__ld_next_named(L, c, "input")) {
        uint64_t off = 0;
        fogrt__ld_attr_uint(L, c, "offset", &off, &res);
        if (res) return res;
        if (off > 255) return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[c].line, "input offset %u too large", (unsigned)off);
        if (off > max_off) max_off = off;
        if (!fogrt__ld_attr_is(L, c, "semantic", "VERTEX")) continue;
        if (fogrt__ld_ref(L, c, "source") != vertices)
            return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[c].line, "VERTEX input must refer to the mesh's <vertices>");
        has_vertex = true;
        P->v_off = (uint32_t)off;
    }
    if (!has_vertex) return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[list].line, "<%s> has no VERTEX input", P->kind);
    P->stride = (uint32_t)max_off + 1;
    if (!fogrt__ld_attr_uint(L, list, "count", &P->count, &res))
        return res ? res : fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[list].line, "<%s> has no count attribute", P->kind);
    return FOGRT_RESULT_OK;
}

/* Checks the vertex index of every one of `corners` corners at ix. */
FOGRT__LD fogrt_result fogrt__ld_check_corners(fogrt__ld *L, const fogrt__ld_prim *P, const uint32_t *ix, uint64_t corners, int line) {
    uint64_t k;
    for (k = 0; k < corners; ++k)
        if (ix[k * P->stride + P->v_off] >= P->nv)
            return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "vertex index %u out of range (%u vertices)", ix[k * P->stride + P->v_off], P->nv);
    return FOGRT_RESULT_OK;
}
/* Fan-triangulates one polygon of n corners starting at corner `start` of ix: (0, j, j+1). */
FOGRT__LD fogrt_result fogrt__ld_fan(fogrt__ld *L, const fogrt__ld_prim *P, fogrt__ld_tris *T, const uint32_t *ix,
                                     uint64_t start, uint32_t n, uint32_t *skipped) {
    uint32_t j, s = P->stride, o = P->v_off;
    if (n < 3) { (*skipped)++; return FOGRT_RESULT_OK; }
    for (j = 1; j + 1 < n; ++j)
        FOGRT__LD_TRY(fogrt__ld_add_tri(L, T, ix[start * s + o], ix[(start + j) * s + o], ix[(start + j + 1) * s + o], P->ordinal));
    return FOGRT_RESULT_OK;
}

/* At most need indices of a <p> into a buffer (grown to fit); *got = indices read. */
FOGRT__LD fogrt_result fogrt__ld_read_p(fogrt__ld *L, const fogrt__ld_el *pe, uint64_t need, uint32_t **ix, uint32_t *cap, uint64_t *got) {
    *got = 0;
    if (!pe->text) return FOGRT_RESULT_OK;
    FOGRT__LD_TRY(fogrt__ld_grow(L, (void **)ix, cap, need, sizeof(uint32_t)));
    return fogrt__ld_uints(L, pe->text, pe->text + pe->text_len, pe->text_line, *ix, need, got);
}

/* <polygons>: one <p> per polygon. */
FOGRT__LD fogrt_result fogrt__ld_polygons(fogrt__ld *L, const fogrt__ld_prim *P, fogrt__ld_tris *T, uint32_t *skipped) {
    uint32_t *ix = NULL, cap = 0;
    uint64_t np = 0, got;
    int32_t p;
    fogrt_result res = FOGRT_RESULT_OK;
    for (p = fogrt__ld_child(L, P->list, "p"); !res && p >= 0 && np < P->count; p = fogrt__ld_next_named(L, p, "p"), ++np) {
        const fogrt__ld_el *pe = &L->el[p];
        uint64_t corners;
        res = fogrt__ld_read_p(L, pe, fogrt__ld_max_numbers(pe->text_len), &ix, &cap, &got);
        corners = got / P->stride;
        if (!res) res = fogrt__ld_check_corners(L, P, ix, corners, pe->line);
        if (!res) res = fogrt__ld_fan(L, P, T, ix, 0, (uint32_t)corners, skipped);
    }
    fogrt__ld_free(L, ix);
    if (!res && np < P->count)
        res = fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[P->list].line, "<polygons count=\"%u\"> has only %u <p>", (unsigned)P->count, (unsigned)np);
    return res;
}

/* <polylist>'s <vcount>: the corners of each polygon, *corners their sum. */
FOGRT__LD fogrt_result fogrt__ld_vcount(fogrt__ld *L, const fogrt__ld_prim *P, uint32_t **out, uint64_t *corners) {
    int32_t vc = fogrt__ld_child(L, P->list, "vcount");
    const fogrt__ld_el *ve;
    uint64_t got = 0, k;
    fogrt_result res;
    uint32_t *vcount;
    if (vc < 0) return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[P->list].line, "<polylist> has no <vcount>");
    ve = &L->el[vc];
    if (P->count > fogrt__ld_max_numbers(ve->text_len))
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, ve->line, "<vcount> has fewer than count=%u numbers", (unsigned)P->count);
    vcount = (uint32_t *)fogrt__ld_alloc(L, P->count, sizeof(uint32_t));
    if (!vcount) return FOGRT_RESULT_OUT_OF_MEMORY;
    res = fogrt__ld_uints(L, ve->text, ve->text + ve->text_len, ve->text_line, vcount, P->count, &got);
    if (!res && got < P->count) res = fogrt__ld_fail(L, FOGRT__LD_PARSE, ve->line, "<vcount> has %u numbers, count says %u", (unsigned)got, (unsigned)P->count);
    if (res) { fogrt__ld_free(L, vcount); return res; }
    for (*corners = 0, k = 0; k < P->count; ++k) *corners += vcount[k];
    *out = vcount;
    return FOGRT_RESULT_OK;
}

/* <triangles> (3 corners each) and <polylist> (vcount corners each): one <p> for all. */
FOGRT__LD fogrt_result fogrt__ld_one_p(fogrt__ld *L, const fogrt__ld_prim *P, fogrt__ld_tris *T, uint32_t *skipped) {
    int32_t p = fogrt__ld_child(L, P->list, "p");
    const fogrt__ld_el *pe;
    uint32_t *vcount = NULL, *ix = NULL, cap = 0, poly;
    uint64_t corners = 3 * P->count, need, got = 0, start;
    fogrt_result res = FOGRT_RESULT_OK;
    if (p < 0) return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[P->list].line, "primitive list with count %u has no <p>", (unsigned)P->count);
    pe = &L->el[p];
    if (fogrt__ld_is(L, P->list, "polylist")) FOGRT__LD_TRY(fogrt__ld_vcount(L, P, &vcount, &corners));
    need = corners > fogrt__ld_max_numbers(pe->text_len) ? UINT64_MAX : corners * P->stride;
    if (need > fogrt__ld_max_numbers(pe->text_len))
        res = fogrt__ld_fail(L, FOGRT__LD_PARSE, pe->line, "<p> is too short for %u polygons", (unsigned)P->count);
    if (!res) res = fogrt__ld_read_p(L, pe, need, &ix, &cap, &got);
    if (!res && got < need)
        res = fogrt__ld_fail(L, FOGRT__LD_PARSE, pe->line, "<p> has %llu indices, %llu needed", (unsigned long long)got, (unsigned long long)need);
    if (!res) res = fogrt__ld_check_corners(L, P, ix, corners, pe->line);
    for (poly = 0, start = 0; !res && poly < P->count; ++poly) {
        uint32_t n = vcount ? vcount[poly] : 3;
        res = fogrt__ld_fan(L, P, T, ix, start, n, skipped);
        start += n;
    }
    fogrt__ld_free(L, vcount); fogrt__ld_free(L, ix);
    return res;
}

/* The POSITION <float_array> of a mesh: exactly `count` floats (CS184); without count, all. */
FOGRT__LD fogrt_result fogrt__ld_positions(fogrt__ld *L, int32_t mesh, int32_t *vertices, float **raw, uint32_t *nv) {
    int32_t in, src, fa;
    uint64_t count = 0, got = 0, k;
    const fogrt__ld_el *fe;
    fogrt_result res;
    *vertices = fogrt__ld_child(L, mesh, "vertices");
    if (*vertices < 0) return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[mesh].line, "<mesh> has no <vertices>");
    for (in = fogrt__ld_child(L, *vertices, "input"); in >= 0; in = fogrt__ld_next_named(L, in, "input"))
        if (fogrt__ld_attr_is(L, in, "semantic", "POSITION")) break;
    if (in < 0) return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[*vertices].line, "<vertices> has no POSITION input");
    src = fogrt__ld_ref(L, in, "source");
    fa = fogrt__ld_child(L, src, "float_array");
    if (src < 0 || fa < 0) return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[in].line, "POSITION source not found or without <float_array>");
    fe = &L->el[fa];
    if (!fogrt__ld_attr_uint(L, fa, "count", &count, &res)) {
        if (res) return res;
        count = fogrt__ld_max_numbers(fe->text_len);
    } else if (count > fogrt__ld_max_numbers(fe->text_len)) {
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, fe->line, "<float_array count=\"%llu\"> holds fewer numbers", (unsigned long long)count);
    }
    *raw = (float *)fogrt__ld_alloc(L, count, sizeof(float));
    if (!*raw) return FOGRT_RESULT_OUT_OF_MEMORY;
    res = fe->text ? fogrt__ld_floats(L, fe->text, fe->text + fe->text_len, fe->text_line, *raw, count, &got) : FOGRT_RESULT_OK;
    if (!res && fogrt__ld_attr(L, fa, "count", NULL) && got < count)
        res = fogrt__ld_fail(L, FOGRT__LD_PARSE, fe->line, "<float_array> has %llu numbers, count says %llu", (unsigned long long)got, (unsigned long long)count);
    for (k = 0; !res && k < got; ++k)
        if (!fogrt__ld_coord_ok((double)(*raw)[k]))
            res = fogrt__ld_fail(L, FOGRT__LD_PARSE, fe->line, "position coordinate %g is beyond fogrt's limit of 1e30", (double)(*raw)[k]);
    *nv = (uint32_t)(got / 3);
    return res;
}

/* Every primitive list of a mesh into T (lists[] records each list's element). */
FOGRT__LD fogrt_result fogrt__ld_mesh_lists(fogrt__ld *L, int32_t mesh, int32_t vertices, uint32_t nv, fogrt__ld_tris *T,
                                            fogrt__ld_geom *g) {
    int32_t c;
    uint32_t skipped = 0, cap = 0;
    for (c = L->el[mesh].first_child; c >= 0; c = L->el[c].next) {
        fogrt__ld_prim P;
        memset(&P, 0, sizeof P);
        P.list = c; P.nv = nv;
        P.kind = fogrt__ld_is(L, c, "polylist") ? "polylist" : fogrt__ld_is(L, c, "triangles") ? "triangles"
               : fogrt__ld_is(L, c, "polygons") ? "polygons" : NULL;
        if (!P.kind) {
            if (fogrt__ld_is(L, c, "lines") || fogrt__ld_is(L, c, "linestrips") || fogrt__ld_is(L, c, "tristrips") || fogrt__ld_is(L, c, "trifans"))
                fogrt__ld_warn(L, L->el[c].line, "<%.*s> is not supported: skipped", FOGRT__LD_CLIP(L->el[c].name_len), L->el[c].name);
            continue;
        }
        FOGRT__LD_TRY(fogrt__ld_prim_inputs(L, &P, vertices));
        if (P.count == 0) continue;
        FOGRT__LD_TRY(FOGRT__LD_PUSH(L, g->lists, g->list_count, cap));
        P.ordinal = g->list_count;
        g->lists[g->list_count++] = c;
        if (strcmp(P.kind, "polygons") == 0) FOGRT__LD_TRY(fogrt__ld_polygons(L, &P, T, &skipped));
        else FOGRT__LD_TRY(fogrt__ld_one_p(L, &P, T, &skipped));
    }
    if (skipped) fogrt__ld_warn(L, L->el[mesh].line, "%u polygons with fewer than 3 corners skipped", skipped);
    return FOGRT_RESULT_OK;
}

/* Parses a <mesh> once into g: positions (unused ones dropped), triangles, per-list counts
   and the open parts for the normals. */
FOGRT__LD fogrt_result fogrt__ld_parse_geom(fogrt__ld *L, int32_t mesh, fogrt__ld_geom *g) {
    int32_t vertices;
    uint32_t nv = 0, t;
    fogrt__ld_tris T;
    memset(&T, 0, sizeof T);
    fogrt_result res;
    FOGRT__LD_TRY(fogrt__ld_positions(L, mesh, &vertices, &g->m.pos, &nv));
    res = fogrt__ld_mesh_lists(L, mesh, vertices, nv, &T, g);
    g->m.nv = nv; g->m.idx = T.idx; g->m.nt = T.n; g->tlist = T.list;   /* owned by g (and L) even on failure */
    if (res || T.n == 0) return res;
    g->list_tris = (uint32_t *)fogrt__ld_alloc(L, g->list_count, sizeof(uint32_t));
    if (!g->list_tris) return FOGRT_RESULT_OUT_OF_MEMORY;
    memset(g->list_tris, 0, (size_t)g->list_count * sizeof(uint32_t));
    for (t = 0; t < T.n; ++t) g->list_tris[T.list[t]]++;
    FOGRT__LD_TRY(fogrt__ld_compact(L, &g->m));
    return fogrt__ld_open_parts(L, &g->m, &g->open);
}

/* The parsed form of <geometry> element geom (with <mesh> child mesh), parsed on first use. */
FOGRT__LD fogrt_result fogrt__ld_geom_of(fogrt__ld *L, int32_t geom, int32_t mesh, uint32_t *out) {
    uint32_t i;
    fogrt__ld_geom *g;
    for (i = 0; i < L->geom_count; ++i) if (L->geoms[i].el == geom) { *out = i; return FOGRT_RESULT_OK; }
    FOGRT__LD_TRY(FOGRT__LD_PUSH(L, L->geoms, L->geom_count, L->geom_cap));
    g = &L->geoms[L->geom_count++];        /* owned by L from here on, even half-parsed */
    memset(g, 0, sizeof *g);
    g->el = geom;
    *out = L->geom_count - 1;
    return fogrt__ld_parse_geom(L, mesh, g);
}

/* A node instancing a mesh: the shared geometry, the node's transform M and the material
   bound to each of the geometry's lists. Costs no triangle memory. */
FOGRT__LD fogrt_result fogrt__ld_mesh_instance(fogrt__ld *L, int32_t geom, int32_t mesh, int32_t inst, const double M[16], int node_line) {
    uint32_t gi, k;
    fogrt__ld_inst *I;
    const fogrt__ld_geom *g;
    FOGRT__LD_TRY(fogrt__ld_geom_of(L, geom, mesh, &gi));
    g = &L->geoms[gi];
    if (g->m.nt == 0) return FOGRT_RESULT_OK;
    FOGRT__LD_TRY(fogrt__ld_count_tris(L, g->m.nt, node_line));
    FOGRT__LD_TRY(FOGRT__LD_PUSH(L, L->insts, L->inst_count, L->inst_cap));
    FOGRT__LD_TRY(fogrt__ld_grow(L, (void **)&L->inst_mats, &L->inst_mat_cap, (uint64_t)L->inst_mat_count + g->list_count, sizeof(uint32_t)));
    I = &L->insts[L->inst_count++];
    I->geom = gi; I->mat_first = L->inst_mat_count; I->line = node_line; I->node = L->node;
    memcpy(I->M, M, sizeof I->M);
    for (k = 0; k < L->geoms[gi].list_count; ++k)
        FOGRT__LD_TRY(fogrt__ld_bound_material(L, inst, L->geoms[gi].lists[k], &L->inst_mats[L->inst_mat_count++]));
    return FOGRT_RESULT_OK;
}

/* World position of local vertex p under M (divided by w). */
FOGRT__LD void fogrt__ld_world(const double M[16], const float *p, double q[3]) {
    double h[4];
    fogrt__ld_xform4(M, (double)p[0], (double)p[1], (double)p[2], 1.0, h);
    q[0] = h[0] / h[3]; q[1] = h[1] / h[3]; q[2] = h[2] / h[3];
}

/* A CGL sphere: centre M (0,0,0,1), radius scaled by the length of the transformed X axis. */
FOGRT__LD fogrt_result fogrt__ld_sphere_instance(fogrt__ld *L, int32_t geom, int32_t rad, int32_t inst, const double M[16], int node_line) {
    float r, cp[3];
    double c[3], x[3], rr;
    fogrt__ld_sphere s;
    const float origin[3] = { 0.0f, 0.0f, 0.0f };
    FOGRT__LD_TRY(fogrt__ld_el_floats(L, rad, &r, 1, 1, NULL));
    fogrt__ld_world(M, origin, c);
    x[0] = M[0]; x[1] = M[4]; x[2] = M[8];    /* image of the X axis */
    rr = (double)r * fogrt__ld_len3(x);
    if (!fogrt__ld_to_coord3(c, &s.c)) return fogrt__ld_fail(L, FOGRT__LD_PARSE, node_line, "sphere centre is not finite or beyond fogrt's limit of 1e30");
    if (!(rr > 0.0) || rr > FOGRT__LD_MAX_COORD)
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[rad].line, "sphere radius (times the node's X scale) must be > 0 and at most 1e30");
    s.r = (float)rr;
    s.node = L->node; s.geom = geom;
    FOGRT__LD_TRY(fogrt__ld_bound_material(L, inst, -1, &s.mat));
    FOGRT__LD_TRY(FOGRT__LD_PUSH(L, L->sph, L->sph_count, L->sph_cap));
    L->sph[L->sph_count++] = s;
    cp[0] = s.c.x; cp[1] = s.c.y; cp[2] = s.c.z;
    fogrt__ld_grow_bounds(L, cp, s.r);
    return FOGRT_RESULT_OK;
}

FOGRT__LD fogrt_result fogrt__ld_geometry(fogrt__ld *L, int32_t inst, const double M[16], int node_line) {
    int32_t geom = fogrt__ld_ref(L, inst, "url"), mesh, rad;
    if (geom < 0 || !fogrt__ld_is(L, geom, "geometry")) {
        fogrt__ld_warn_unresolved(L, inst, "url", "skipped");
        return FOGRT_RESULT_OK;
    }
    mesh = fogrt__ld_child(L, geom, "mesh");
    if (mesh >= 0) return fogrt__ld_mesh_instance(L, geom, mesh, inst, M, node_line);
    rad = fogrt__ld_path(L, fogrt__ld_cgl(L, geom), "sphere/radius");
    if (rad >= 0) return fogrt__ld_sphere_instance(L, geom, rad, inst, M, node_line);
    fogrt__ld_warn(L, L->el[geom].line, "geometry is neither a <mesh> nor a CGL sphere: skipped");
    return FOGRT_RESULT_OK;
}
/* ------------------------------------------------------------------------------------------
   9. COLLADA: lights and the camera
   ------------------------------------------------------------------------------------------ */
#define FOGRT__LD_DEG (180.0 / 3.14159265358979323846)

/* CGL <area>: a rectangle centred at the node origin o with edges M(-1,0,0) and M(0,1,0),
   emitting along dir = M(0,0,-1). */
FOGRT__LD fogrt_result fogrt__ld_area_light(fogrt__ld *L, int32_t type, const double M[16], const double o[4],
                                            const double dir[3], fogrt_vec3 colour, int node_line) {
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
        if (!fogrt__ld_to_coord3(q, &r.p[k]))
            return fogrt__ld_fail(L, FOGRT__LD_PARSE, node_line, "area light corner is not finite or beyond fogrt's limit of 1e30");
    }
    if (n[0] * dir[0] + n[1] * dir[1] + n[2] * dir[2] < 0.0) {   /* mirrored node: keep -Z the front */
        fogrt_vec3 x = r.p[1]; r.p[1] = r.p[3]; r.p[3] = x;
    }
    r.colour = colour;
    r.node = L->node;
    FOGRT__LD_TRY(FOGRT__LD_PUSH(L, L->rects, L->rect_count, L->rect_cap));
    L->rects[L->rect_count++] = r;
    return FOGRT_RESULT_OK;
}

/* Blender's spot: falloff_angle is the FULL cone (degrees), falloff_exponent its blend. */
FOGRT__LD fogrt_result fogrt__ld_spot(fogrt__ld *L, int32_t type, const double dir[3], int node_line, fogrt_light_desc *d) {
    float angle = 180.0f, blend = 0.0f;
    bool found;
    FOGRT__LD_TRY(fogrt__ld_child_float(L, type, "falloff_angle", false, &angle, &found));
    if (found && !(angle > 0.0f && angle <= 360.0f))
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[fogrt__ld_child(L, type, "falloff_angle")].line, "falloff_angle must be in (0, 360] degrees");
    FOGRT__LD_TRY(fogrt__ld_child_float(L, type, "falloff_exponent", false, &blend, NULL));
    blend = blend < 0.0f ? 0.0f : blend > 1.0f ? 1.0f : blend;
    if (!fogrt__ld_to_vec3(dir, &d->direction) || fogrt__ld_black(d->direction))
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, node_line, "spot light direction (the node's -Z axis) is zero");
    d->type = FOGRT_LIGHT_SPOT;
    d->cutoff_deg = 0.5f * angle;                    /* falloff_angle is the full cone */
    d->beam_deg = d->cutoff_deg * (1.0f - blend);    /* Blender's spot blend */
    return FOGRT_RESULT_OK;
}

/* The light's type element: the first child of its CGL technique (which wins over
   technique_common); -1 (after a warning) when it is missing or not one fogrt has. */
FOGRT__LD int32_t fogrt__ld_light_type(fogrt__ld *L, int32_t light) {
    int32_t tech = fogrt__ld_cgl(L, light), type;
    if (tech < 0) tech = fogrt__ld_child(L, light, "technique_common");
    type = tech >= 0 ? L->el[tech].first_child : -1;
    if (type < 0) fogrt__ld_warn(L, L->el[light].line, "light without a technique: skipped");
    else if (fogrt__ld_is(L, type, "directional")) fogrt__ld_warn(L, L->el[type].line, "<directional> lights are not supported by fogrt: skipped");
    else if (!fogrt__ld_is(L, type, "point") && !fogrt__ld_is(L, type, "spot") && !fogrt__ld_is(L, type, "area") && !fogrt__ld_is(L, type, "ambient"))
        fogrt__ld_warn(L, L->el[type].line, "unknown light type <%.*s>: skipped", FOGRT__LD_CLIP(L->el[type].name_len), L->el[type].name);
    else return type;
    return -1;
}

FOGRT__LD fogrt_result fogrt__ld_light(fogrt__ld *L, int32_t inst, const double M[16], int node_line) {
    int32_t light = fogrt__ld_ref(L, inst, "url"), type;
    fogrt_vec3 colour, pos;
    fogrt_light_desc d;
    double o[4], dir[3];
    if (light < 0 || !fogrt__ld_is(L, light, "light")) {
        fogrt__ld_warn_unresolved(L, inst, "url", "skipped");
        return FOGRT_RESULT_OK;
    }
    type = fogrt__ld_light_type(L, light);
    if (type < 0) return FOGRT_RESULT_OK;
    FOGRT__LD_TRY(fogrt__ld_child_vec3(L, type, "color", true, true, &colour, NULL));
    fogrt__ld_xform4(M, 0, 0, 0, 1, o);               /* position: not divided by w (CS184) */
    if (!fogrt__ld_to_vec3(o, &pos)) return fogrt__ld_fail(L, FOGRT__LD_PARSE, node_line, "light position is not finite");
    dir[0] = -M[2]; dir[1] = -M[6]; dir[2] = -M[10];  /* local -Z */
    if (fogrt__ld_is(L, type, "ambient")) {
        L->env.x += colour.x; L->env.y += colour.y; L->env.z += colour.z;
        if (!(L->env.x <= FLT_MAX && L->env.y <= FLT_MAX && L->env.z <= FLT_MAX))
            return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[type].line, "ambient light colours add up to infinity");
        L->has_env = true;
        return FOGRT_RESULT_OK;
    }
    if (fogrt__ld_is(L, type, "area")) return fogrt__ld_area_light(L, type, M, o, dir, colour, node_line);
    memset(&d, 0, sizeof d);
    d.type = FOGRT_LIGHT_POINT;
    d.position = pos;
    d.intensity = colour;
    if (fogrt__ld_is(L, type, "spot")) FOGRT__LD_TRY(fogrt__ld_spot(L, type, dir, node_line, &d));
    FOGRT__LD_TRY(FOGRT__LD_PUSH(L, L->lights, L->light_count, L->light_cap));
    L->lights[L->light_count++] = d;
    return FOGRT_RESULT_OK;
}

FOGRT__LD fogrt_result fogrt__ld_camera(fogrt__ld *L, int32_t inst, const double M[16]) {
    int32_t cam = fogrt__ld_ref(L, inst, "url"), persp;
    float xfov = 50.0f, yfov = 0.0f, aspect = 0.0f;
    bool has_y, has_a;
    double c[4], th, tv;
    if (L->has_camera) {
        fogrt__ld_warn(L, L->el[inst].line, "more than one camera: the first one is used");
        return FOGRT_RESULT_OK;
    }
    if (cam < 0 || !fogrt__ld_is(L, cam, "camera")) {
        fogrt__ld_warn_unresolved(L, inst, "url", "skipped");
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
FOGRT__LD void fogrt__ld_place_camera(fogrt__ld *L, fogrt_camera_desc *cam) {
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
   10. COLLADA: nodes, transforms and the document
   ------------------------------------------------------------------------------------------ */
/* Rotation by v[3] degrees about the axis v[0..2] into the row-major t (false: zero axis).
   Rodrigues: R = cos I + sin [a]x + (1 - cos) a a^T. */
FOGRT__LD bool fogrt__ld_rotation(const float v[4], double t[16]) {
    double a[3], len, ang, cs, sn;
    int i;
    a[0] = (double)v[0]; a[1] = (double)v[1]; a[2] = (double)v[2];
    len = fogrt__ld_len3(a);
    if (!(len > 0.0)) return false;
    for (i = 0; i < 3; ++i) a[i] /= len;
    ang = (double)v[3] / FOGRT__LD_DEG; cs = cos(ang); sn = sin(ang);
    t[0] = cs + (1 - cs) * a[0] * a[0];        t[1] = (1 - cs) * a[0] * a[1] - sn * a[2]; t[2] = (1 - cs) * a[0] * a[2] + sn * a[1];
    t[4] = (1 - cs) * a[1] * a[0] + sn * a[2]; t[5] = cs + (1 - cs) * a[1] * a[1];        t[6] = (1 - cs) * a[1] * a[2] - sn * a[0];
    t[8] = (1 - cs) * a[2] * a[0] - sn * a[1]; t[9] = (1 - cs) * a[2] * a[1] + sn * a[0]; t[10] = cs + (1 - cs) * a[2] * a[2];
    return true;
}
/* The node's own transform: <translate>, <rotate>, <scale>, <matrix> post-multiplied in
   document order (COLLADA), stopping at the first <matrix> (CS184). */
FOGRT__LD fogrt_result fogrt__ld_node_transform(fogrt__ld *L, int32_t node, double out[16]) {
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
            FOGRT__LD_TRY(fogrt__ld_el_floats(L, c, v, 4, 4, &n));
            if (!fogrt__ld_rotation(v, t)) { fogrt__ld_warn(L, L->el[c].line, "<rotate> with a zero axis: ignored"); continue; }
        } else if (fogrt__ld_is(L, c, "lookat") || fogrt__ld_is(L, c, "skew")) {
            fogrt__ld_warn(L, L->el[c].line, "<%.*s> is ignored (as in CS184)", FOGRT__LD_CLIP(L->el[c].name_len), L->el[c].name);
            continue;
        } else {
            continue;
        }
        fogrt__ld_mul(out, t, out);
    }
    return FOGRT_RESULT_OK;
}

FOGRT__LD fogrt_result fogrt__ld_node(fogrt__ld *L, int32_t node, const double parent[16], int depth) {
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
    L->node = node;                                   /* names the shape it adds */
    if (ic >= 0) return fogrt__ld_camera(L, ic, world);
    if (il >= 0) return fogrt__ld_light(L, il, world, L->el[node].line);
    if (ig >= 0) return fogrt__ld_geometry(L, ig, world, L->el[node].line);
    return FOGRT_RESULT_OK;
}

/* asset/up_axis as the correction G that pre-multiplies every node. */
FOGRT__LD fogrt_result fogrt__ld_up_axis(fogrt__ld *L, double G[16]) {
    int32_t up = fogrt__ld_path(L, L->root, "asset/up_axis");
    const char *s;
    uint32_t n;
    fogrt__ld_identity(G);
    if (up < 0) {
        fogrt__ld_warn(L, L->el[L->root].line, "no <asset><up_axis>: Y_UP assumed (the COLLADA default)");
        return FOGRT_RESULT_OK;
    }
    s = L->el[up].text; n = L->el[up].text_len;
    while (n && fogrt__ld_space(*s)) { ++s; --n; }
    while (n && fogrt__ld_space(s[n - 1])) --n;
    if (n == 4 && memcmp(s, "Z_UP", 4) == 0) {          /* (x, y, z) -> (-x, z, y) */
        G[0] = -1; G[5] = 0; G[6] = 1; G[9] = 1; G[10] = 0;
    } else if (n == 4 && memcmp(s, "X_UP", 4) == 0) {   /* (x, y, z) -> (y, x, -z) */
        G[0] = 0; G[1] = 1; G[4] = 1; G[5] = 0; G[10] = -1;
    } else if (!(n == 4 && memcmp(s, "Y_UP", 4) == 0)) {
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[up].line, "up_axis must be X_UP, Y_UP or Z_UP");
    }
    return FOGRT_RESULT_OK;
}

FOGRT__LD fogrt_result fogrt__ld_dae_parse(fogrt__ld *L) {
    int32_t vs, c, inst;
    double G[16];
    FOGRT__LD_TRY(fogrt__ld_xml_parse(L));
    if (!fogrt__ld_is(L, L->root, "COLLADA"))
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, L->el[L->root].line, "not a COLLADA document (root element <%.*s>)",
                              FOGRT__LD_CLIP(L->el[L->root].name_len), L->el[L->root].name);
    FOGRT__LD_TRY(fogrt__ld_build_ids(L));
    FOGRT__LD_TRY(fogrt__ld_up_axis(L, G));
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
   11. COLLADA: checking everything against the scene's limits, then handing it to fogrt
   ------------------------------------------------------------------------------------------ */
/* Every instance's world vertices lie within the scene's limits; they make the bounds. */
FOGRT__LD fogrt_result fogrt__ld_check_instances(fogrt__ld *L) {
    uint32_t i, v;
    for (i = 0; i < L->inst_count; ++i) {
        const fogrt__ld_inst *I = &L->insts[i];
        const fogrt__ld_meshbuf *m = &L->geoms[I->geom].m;
        for (v = 0; v < m->nv; ++v) {
            double q[3];
            fogrt_vec3 w;
            float p[3];
            fogrt__ld_world(I->M, m->pos + 3 * (size_t)v, q);
            if (!fogrt__ld_to_coord3(q, &w))
                return fogrt__ld_fail(L, FOGRT__LD_PARSE, I->line, "the node's transform puts vertex %u at (%g, %g, %g): not finite or beyond fogrt's limit of 1e30",
                                      v, q[0], q[1], q[2]);
            p[0] = w.x; p[1] = w.y; p[2] = w.z;
            fogrt__ld_grow_bounds(L, p, 0.0f);
        }
    }
    return FOGRT_RESULT_OK;
}

/* CS184's camera from the bounds; it must be finite and not sit on its target. */
FOGRT__LD fogrt_result fogrt__ld_dae_camera(fogrt__ld *L) {
    fogrt_camera_desc *c = &L->rep->camera;
    float dx, dy, dz;
    fogrt__ld_place_camera(L, c);
    dx = c->look_at.x - c->position.x; dy = c->look_at.y - c->position.y; dz = c->look_at.z - c->position.z;
    if (!(c->position.x - c->position.x == 0.0f && c->position.y - c->position.y == 0.0f && c->position.z - c->position.z == 0.0f)
        || (dx == 0.0f && dy == 0.0f && dz == 0.0f))
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, 0, "the scene's bounding box is too large (or too far out) to place CS184's camera");
    L->rep->has_camera = L->has_camera;
    L->rep->frame_tan_half_y = L->frame_tan_half_y;
    L->rep->frame_aspect = 4.0f / 3.0f;
    return FOGRT_RESULT_OK;
}

FOGRT__LD fogrt_result fogrt__ld_rejected(fogrt__ld *L, fogrt_result r, const char *what) {
    return fogrt__ld_fail(L, r, 0, "fogrt rejected the %s: %s", what, fogrt_result_string(r));
}

/* Scratch for handing one instance to the scene: sized for the largest geometry, and
   allocated before the first scene call (so a failed allocation changes nothing). */
typedef struct fogrt__ld_scratch { float *pos, *nrm; uint32_t *idx, *tmat; double *acc; } fogrt__ld_scratch;

FOGRT__LD fogrt_result fogrt__ld_scratch_alloc(fogrt__ld *L, fogrt__ld_scratch *S) {
    uint32_t i, nv = 0, nt = 0;
    for (i = 0; i < L->geom_count; ++i) {
        if (L->geoms[i].m.nv > nv) nv = L->geoms[i].m.nv;
        if (L->geoms[i].m.nt > nt) nt = L->geoms[i].m.nt;
    }
    S->pos = (float *)fogrt__ld_alloc(L, 3 * (uint64_t)nv, sizeof(float));
    S->nrm = S->pos ? (float *)fogrt__ld_alloc(L, 3 * (uint64_t)nv, sizeof(float)) : NULL;
    S->idx = S->nrm ? (uint32_t *)fogrt__ld_alloc(L, 3 * (uint64_t)nt, sizeof(uint32_t)) : NULL;
    S->tmat = S->idx ? (uint32_t *)fogrt__ld_alloc(L, nt, sizeof(uint32_t)) : NULL;
    S->acc = S->tmat ? (double *)fogrt__ld_alloc(L, 3 * (uint64_t)nv, sizeof(double)) : NULL;
    return S->acc ? FOGRT_RESULT_OK : FOGRT_RESULT_OUT_OF_MEMORY;
}
FOGRT__LD void fogrt__ld_scratch_free(fogrt__ld *L, fogrt__ld_scratch *S) {
    fogrt__ld_free(L, S->pos); fogrt__ld_free(L, S->nrm); fogrt__ld_free(L, S->idx); fogrt__ld_free(L, S->tmat); fogrt__ld_free(L, S->acc);
}

/* One instance: world positions (checked before), mirrored transforms re-wound, materials
   bound, smooth normals from the world triangles. */
FOGRT__LD fogrt_result fogrt__ld_commit_instance(fogrt__ld *L, fogrt_scene *scene, const fogrt__ld_inst *I, const uint32_t *ids,
                                                 fogrt__ld_scratch *S) {
    const fogrt__ld_geom *g = &L->geoms[I->geom];
    const fogrt__ld_meshbuf *m = &g->m;
    bool mirror = fogrt__ld_det3(I->M) < 0.0;
    uint32_t v, t;
    fogrt_mesh_desc d;
    fogrt_result r;
    for (v = 0; v < m->nv; ++v) {
        double q[3];
        fogrt__ld_world(I->M, m->pos + 3 * (size_t)v, q);
        S->pos[3 * (size_t)v] = (float)q[0]; S->pos[3 * (size_t)v + 1] = (float)q[1]; S->pos[3 * (size_t)v + 2] = (float)q[2];
    }
    for (t = 0; t < m->nt; ++t) {
        const uint32_t *src = m->idx + 3 * (size_t)t;
        uint32_t *dst = S->idx + 3 * (size_t)t;
        dst[0] = src[0]; dst[1] = src[mirror ? 2 : 1]; dst[2] = src[mirror ? 1 : 2];
        S->tmat[t] = ids[L->inst_mats[I->mat_first + g->tlist[t]]];
    }
    fogrt__ld_smooth_normals(S->pos, S->idx, m->nv, m->nt, g->open, S->acc, S->nrm);
    memset(&d, 0, sizeof d);
    d.positions = S->pos; d.normals = S->nrm; d.vertex_count = m->nv;
    d.indices = S->idx; d.triangle_count = m->nt; d.triangle_materials = S->tmat;
    r = fogrt_scene_add_mesh(scene, &d);
    if (r) return fogrt__ld_rejected(L, r, "mesh");
    L->rep->triangles += m->nt;
    return FOGRT_RESULT_OK;
}

/* Triangles whose bound material emits, over all instances. */
FOGRT__LD uint32_t fogrt__ld_emissive_tris(const fogrt__ld *L) {
    uint32_t i, k, n = 0;
    for (i = 0; i < L->inst_count; ++i) {
        const fogrt__ld_inst *I = &L->insts[i];
        const fogrt__ld_geom *g = &L->geoms[I->geom];
        for (k = 0; k < g->list_count; ++k)
            if (!fogrt__ld_black(L->mats[L->inst_mats[I->mat_first + k]].desc.emission)) n += g->list_tris[k];
    }
    return n;
}

/* The materials; glass and refraction first, so that a fogrt built with FOGRT_NO_GLASS
   refuses the file (UNSUPPORTED) before anything else is added. */
FOGRT__LD fogrt_result fogrt__ld_commit_materials(fogrt__ld *L, fogrt_scene *scene, uint32_t *ids) {
    uint32_t pass, i;
    for (pass = 0; pass < 2; ++pass)
        for (i = 0; i < L->mat_count; ++i) {
            fogrt_result r;
            if (fogrt__ld_is_glass(&L->mats[i].desc) != (pass == 0)) continue;
            r = fogrt_scene_add_material(scene, &L->mats[i].desc, &ids[i]);
            if (r == FOGRT_RESULT_UNSUPPORTED) {
                char what[80];
                fogrt__ld_material_name(L, L->mats[i].key, what, sizeof what);
                return fogrt__ld_fail(L, r, L->mats[i].key >= 0 ? L->el[L->mats[i].key].line : 0,
                                      "%s is glass/refraction, which this fogrt was built without (FOGRT_NO_GLASS)", what);
            }
            if (r) return fogrt__ld_rejected(L, r, "material");
            L->rep->materials++;
        }
    return FOGRT_RESULT_OK;
}

/* A CGL <area> light as an emissive rectangle (two triangles). */
FOGRT__LD fogrt_result fogrt__ld_commit_rect(fogrt__ld *L, fogrt_scene *scene, const fogrt__ld_rect *rect) {
    fogrt_material_desc md;
    fogrt_mesh_desc d;
    uint32_t id, idx[6] = { 0, 1, 2, 0, 2, 3 };
    float pos[12];
    int k;
    fogrt_result r;
    memset(&md, 0, sizeof md);
    md.type = FOGRT_BSDF_DIFFUSE;
    md.emission = rect->colour;
    for (k = 0; k < 4; ++k) { pos[3 * k] = rect->p[k].x; pos[3 * k + 1] = rect->p[k].y; pos[3 * k + 2] = rect->p[k].z; }
    r = fogrt_scene_add_material(scene, &md, &id);
    if (r) return fogrt__ld_rejected(L, r, "area light material");
    L->rep->materials++;
    memset(&d, 0, sizeof d);
    d.positions = pos; d.vertex_count = 4; d.indices = idx; d.triangle_count = 2; d.material = id;
    r = fogrt_scene_add_mesh(scene, &d);
    if (r) return fogrt__ld_rejected(L, r, "area light rectangle");
    L->rep->area_rectangles++; L->rep->triangles += 2; L->rep->emissive_triangles += 2;
    return FOGRT_RESULT_OK;
}

/* Spheres, area rectangles (only without an emissive mesh: else it is the lamp), point and
   spot lights, the ambient light and the camera. */
FOGRT__LD fogrt_result fogrt__ld_commit_rest(fogrt__ld *L, fogrt_scene *scene, const uint32_t *ids, bool set_camera) {
    fogrt_load_report *rep = L->rep;
    fogrt_result r = FOGRT_RESULT_OK;
    uint32_t i;
    for (i = 0; i < L->sph_count && !r; ++i) {
        r = fogrt_scene_add_sphere(scene, L->sph[i].c, L->sph[i].r, ids[L->sph[i].mat]);
        if (r) r = fogrt__ld_rejected(L, r, "sphere");
        else rep->spheres++;
    }
    if (rep->emissive_triangles > 0) rep->area_lights_merged = L->rect_count;
    for (i = 0; i < L->rect_count && !r && rep->area_lights_merged == 0; ++i) r = fogrt__ld_commit_rect(L, scene, &L->rects[i]);
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
    return r;
}

FOGRT__LD fogrt_result fogrt__ld_commit(fogrt__ld *L, fogrt_scene *scene, bool set_camera) {
    uint32_t i, *ids;
    fogrt__ld_scratch S;
    fogrt_result r;
    memset(&S, 0, sizeof S);
    ids = (uint32_t *)fogrt__ld_alloc(L, L->mat_count, sizeof(uint32_t));
    r = ids ? fogrt__ld_scratch_alloc(L, &S) : FOGRT_RESULT_OUT_OF_MEMORY;
    L->rep->emissive_triangles = fogrt__ld_emissive_tris(L);
    if (!r) r = fogrt__ld_ready(L);
    if (!r) r = fogrt__ld_commit_materials(L, scene, ids);       /* the first call into the scene */
    for (i = 0; i < L->inst_count && !r; ++i) r = fogrt__ld_commit_instance(L, scene, &L->insts[i], ids, &S);
    if (!r) r = fogrt__ld_commit_rest(L, scene, ids, set_camera);
    fogrt__ld_scratch_free(L, &S);
    fogrt__ld_free(L, ids);
    return r;
}

/* The name of a .dae element for options.on_shape: its name attribute, else its id. */
FOGRT__LD fogrt_result fogrt__ld_el_name(fogrt__ld *L, int32_t e, uint32_t *out) {
    uint32_t len = 0;
    const char *s = e >= 0 ? fogrt__ld_attr(L, e, "name", &len) : NULL;
    if (!s && e >= 0) s = fogrt__ld_attr(L, e, "id", &len);
    return fogrt__ld_name(L, s, len, out);
}
FOGRT__LD fogrt_result fogrt__ld_dae_shape(fogrt__ld *L, fogrt_shape_kind kind, int32_t node, int32_t material, int32_t geometry) {
    uint32_t name[3];
    FOGRT__LD_TRY(fogrt__ld_el_name(L, node, &name[0]));
    FOGRT__LD_TRY(fogrt__ld_el_name(L, material, &name[1]));
    FOGRT__LD_TRY(fogrt__ld_el_name(L, geometry, &name[2]));
    return fogrt__ld_push_shape(L, kind, name, 0);
}
/* The names of every shape the commit adds: each instance, each sphere, and the area
   rectangles when they are added (no emissive mesh). */
FOGRT__LD fogrt_result fogrt__ld_dae_names(fogrt__ld *L) {
    uint32_t i;
    if (!L->opt.on_shape) return FOGRT_RESULT_OK;
    for (i = 0; i < L->inst_count; ++i) {
        const fogrt__ld_inst *I = &L->insts[i];
        FOGRT__LD_TRY(fogrt__ld_dae_shape(L, FOGRT_SHAPE_MESH, I->node, L->mats[L->inst_mats[I->mat_first]].key, L->geoms[I->geom].el));
    }
    for (i = 0; i < L->sph_count; ++i)
        FOGRT__LD_TRY(fogrt__ld_dae_shape(L, FOGRT_SHAPE_SPHERE, L->sph[i].node, L->mats[L->sph[i].mat].key, L->sph[i].geom));
    if (fogrt__ld_emissive_tris(L) == 0)
        for (i = 0; i < L->rect_count; ++i) FOGRT__LD_TRY(fogrt__ld_dae_shape(L, FOGRT_SHAPE_MESH, L->rects[i].node, -1, -1));
    return FOGRT_RESULT_OK;
}

/* A whole .dae: parse, check, place the camera, collect the names, commit. */
FOGRT__LD fogrt_result fogrt__ld_dae(fogrt__ld *L, fogrt_scene *scene) {
    FOGRT__LD_TRY(fogrt__ld_dae_parse(L));
    FOGRT__LD_TRY(fogrt__ld_check_instances(L));
    FOGRT__LD_TRY(fogrt__ld_dae_camera(L));
    FOGRT__LD_TRY(fogrt__ld_dae_names(L));
    fogrt__ld_first_shapes(L, scene);
    return fogrt__ld_commit(L, scene, !L->opt.no_camera);
}

FOGRT__LD_PUBLIC void fogrt_load_fit_fov(float frame_tan_half_y, float frame_aspect, int width, int height,
                                         fogrt_camera_desc *camera) {
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

/* ------------------------------------------------------------------------------------------
   12. OBJ and PLY: one mesh, placed, with file or computed normals
   ------------------------------------------------------------------------------------------ */
/* Normals: the file's, normalised, where it has a usable one (nonzero), else the computed
   smooth normal (computed only when some vertex needs it). Takes ownership of file_nrm. */
FOGRT__LD fogrt_result fogrt__ld_fix_normals(fogrt__ld *L, fogrt__ld_meshbuf *m, float *file_nrm) {
    uint32_t v, missing = 0;
    double *acc;
    for (v = 0; file_nrm && v < m->nv; ++v) {
        float *f = file_nrm + 3 * (size_t)v;
        double len = sqrt((double)f[0] * (double)f[0] + (double)f[1] * (double)f[1] + (double)f[2] * (double)f[2]);
        if (len > 0.0 && len < HUGE_VAL) { f[0] = (float)((double)f[0] / len); f[1] = (float)((double)f[1] / len); f[2] = (float)((double)f[2] / len); }
        else { f[0] = f[1] = f[2] = 0.0f; missing++; }
    }
    m->nrm = file_nrm;
    if (file_nrm && missing == 0) return FOGRT_RESULT_OK;
    m->smooth = !file_nrm;
    if (!m->nrm) m->nrm = (float *)fogrt__ld_alloc(L, 3 * (uint64_t)m->nv, sizeof(float));
    acc = m->nrm ? (double *)fogrt__ld_alloc(L, 3 * (uint64_t)m->nv, sizeof(double)) : NULL;
    if (!acc) return FOGRT_RESULT_OUT_OF_MEMORY;
    if (!file_nrm) fogrt__ld_smooth_normals(m->pos, m->idx, m->nv, m->nt, NULL, acc, m->nrm);
    else {                            /* the smooth normal only where the file's is zero */
        float *smooth = (float *)fogrt__ld_alloc(L, 3 * (uint64_t)m->nv, sizeof(float));
        if (!smooth) { fogrt__ld_free(L, acc); return FOGRT_RESULT_OUT_OF_MEMORY; }
        fogrt__ld_smooth_normals(m->pos, m->idx, m->nv, m->nt, NULL, acc, smooth);
        for (v = 0; v < m->nv; ++v)
            if (m->nrm[3 * (size_t)v] == 0.0f && m->nrm[3 * (size_t)v + 1] == 0.0f && m->nrm[3 * (size_t)v + 2] == 0.0f)
                memcpy(m->nrm + 3 * (size_t)v, smooth + 3 * (size_t)v, 3 * sizeof(float));
        fogrt__ld_free(L, smooth);
    }
    fogrt__ld_free(L, acc);
    return FOGRT_RESULT_OK;
}

/* Whether every face that has an area faces the same way, to within 1e-6 radians (in the
   coordinates the scene will hold): a flat mesh. Its smooth normals are then its face
   normals, which the renderer computes anyway, so it is added without normals: 36 bytes
   less per triangle in the scene (a fan of 8M slivers: 288 MB). */
FOGRT__LD bool fogrt__ld_flat(const fogrt__ld_meshbuf *m) {
    double ref[3] = { 0.0, 0.0, 0.0 }, n[3], len;
    bool have = false;
    uint32_t t;
    for (t = 0; t < m->nt; ++t) {
        fogrt__ld_face_normal(m->pos, m->idx + 3 * (size_t)t, n);
        len = fogrt__ld_len3(n);
        if (!(len > 0.0 && len < HUGE_VAL)) continue;       /* no area: never hit */
        if (have && n[0] * ref[0] + n[1] * ref[1] + n[2] * ref[2] < (1.0 - 5e-13) * len) return false;
        if (!have) { ref[0] = n[0] / len; ref[1] = n[1] / len; ref[2] = n[2] / len; have = true; }
    }
    return have;
}
/* A flat mesh's computed normals go (fogrt__ld_flat); the file's stay. */
FOGRT__LD void fogrt__ld_drop_flat_normals(fogrt__ld *L, fogrt__ld_meshbuf *m) {
    if (m->smooth && fogrt__ld_flat(m)) { fogrt__ld_free(L, m->nrm); m->nrm = NULL; }
}

/* An OBJ split into a mesh per object or group (options.on_shape): each part's vertices are
   gathered into scratch arrays sized for the whole mesh, remap[v] being vertex v's number in
   the part (UINT32_MAX: not in it), so that each part costs its own size, not the whole's. */
typedef struct fogrt__ld_parts { float *pos, *nrm; uint32_t *idx, *remap; } fogrt__ld_parts;

FOGRT__LD void fogrt__ld_parts_free(fogrt__ld *L, fogrt__ld_parts *P) {
    fogrt__ld_free(L, P->pos); fogrt__ld_free(L, P->nrm); fogrt__ld_free(L, P->idx); fogrt__ld_free(L, P->remap);
}
FOGRT__LD uint32_t fogrt__ld_part_end(const fogrt__ld *L, const fogrt__ld_meshbuf *m, uint32_t k) {
    return k + 1 < L->shape_count ? L->shapes[k + 1].first : m->nt;
}
FOGRT__LD fogrt_result fogrt__ld_parts_alloc(fogrt__ld *L, const fogrt__ld_meshbuf *m, fogrt__ld_parts *P) {
    uint32_t k, most = 0, v;
    memset(P, 0, sizeof *P);
    for (k = 0; k < L->shape_count; ++k)
        if (fogrt__ld_part_end(L, m, k) - L->shapes[k].first > most) most = fogrt__ld_part_end(L, m, k) - L->shapes[k].first;
    P->pos = (float *)fogrt__ld_alloc(L, 3 * (uint64_t)m->nv, sizeof(float));
    P->nrm = P->pos ? (float *)fogrt__ld_alloc(L, 3 * (uint64_t)m->nv, sizeof(float)) : NULL;
    P->idx = P->nrm ? (uint32_t *)fogrt__ld_alloc(L, 3 * (uint64_t)most, sizeof(uint32_t)) : NULL;
    P->remap = P->idx ? (uint32_t *)fogrt__ld_alloc(L, m->nv, sizeof(uint32_t)) : NULL;
    if (!P->remap) return FOGRT_RESULT_OUT_OF_MEMORY;
    for (v = 0; v < m->nv; ++v) P->remap[v] = UINT32_MAX;
    return FOGRT_RESULT_OK;
}
/* Part k as a mesh description of its own (the scratch is left ready for the next part). */
FOGRT__LD void fogrt__ld_part(const fogrt__ld *L, const fogrt__ld_meshbuf *m, uint32_t k, fogrt__ld_parts *P, fogrt_mesh_desc *d) {
    uint32_t first = L->shapes[k].first, end = fogrt__ld_part_end(L, m, k), t, nv = 0;
    for (t = 3 * first; t < 3 * end; ++t) {
        uint32_t v = m->idx[t];
        if (P->remap[v] == UINT32_MAX) {
            memcpy(P->pos + 3 * (size_t)nv, m->pos + 3 * (size_t)v, 3 * sizeof(float));
            if (m->nrm) memcpy(P->nrm + 3 * (size_t)nv, m->nrm + 3 * (size_t)v, 3 * sizeof(float));
            P->remap[v] = nv++;
        }
        P->idx[t - 3 * first] = P->remap[v];
    }
    for (t = 3 * first; t < 3 * end; ++t) P->remap[m->idx[t]] = UINT32_MAX;
    d->positions = P->pos; d->normals = m->nrm ? P->nrm : NULL; d->vertex_count = nv;
    d->indices = P->idx; d->triangle_count = end - first;
}
/* The mesh's material: options.material, else a new diffuse 0.75 grey. */
FOGRT__LD fogrt_result fogrt__ld_mesh_material(fogrt__ld *L, fogrt_scene *scene, uint32_t *mat) {
    fogrt_material_desc md = fogrt__ld_diffuse(0.75f, 0.75f, 0.75f);
    fogrt_result r;
    if (L->opt.use_material) { *mat = L->opt.material; return FOGRT_RESULT_OK; }
    r = fogrt_scene_add_material(scene, &md, mat);
    if (r) return fogrt__ld_rejected(L, r, "material");
    L->rep->materials = 1;
    return FOGRT_RESULT_OK;
}
/* Places the mesh (already compacted), checks it against the scene's limits and adds it
   with its material (and its normals, unless they were computed and it is flat): whole, or
   with options.on_shape a mesh per OBJ object or group. */
FOGRT__LD fogrt_result fogrt__ld_commit_mesh(fogrt__ld *L, fogrt_scene *scene, fogrt__ld_meshbuf *m) {
    const uint32_t unnamed[3] = { 0, 0, 0 };
    fogrt__ld_parts P;
    fogrt_mesh_desc d;
    uint32_t mat = 0, v, k;
    fogrt_result r;
    if (L->opt.place != FOGRT_LOAD_PLACE_AS_IS) fogrt__ld_place(L, m);
    for (v = 0; v < 3 * m->nv; ++v)
        if (!fogrt__ld_coord_ok((double)m->pos[v]))
            return fogrt__ld_fail(L, FOGRT__LD_PARSE, 0, "placed vertex %u lies beyond fogrt's limit of 1e30 (see options.fit_min/fit_max)", v / 3);
    if (m->nt == 0) fogrt__ld_warn(L, 0, "the file has no faces: nothing added");
    if (fogrt__ld_ready(L) || m->nt == 0) return fogrt__ld_ready(L);
    fogrt__ld_drop_flat_normals(L, m);
    if (L->opt.on_shape && L->shape_count == 0) FOGRT__LD_TRY(fogrt__ld_push_shape(L, FOGRT_SHAPE_MESH, unnamed, 0));
    memset(&P, 0, sizeof P);
    r = L->shape_count > 1 ? fogrt__ld_parts_alloc(L, m, &P) : FOGRT_RESULT_OK;
    fogrt__ld_first_shapes(L, scene);
    if (!r) r = fogrt__ld_mesh_material(L, scene, &mat);             /* the first call into the scene */
    memset(&d, 0, sizeof d);
    d.positions = m->pos; d.normals = m->nrm; d.vertex_count = m->nv;
    d.indices = m->idx; d.triangle_count = m->nt;
    for (k = 0; !r && k < (L->shape_count > 1 ? L->shape_count : 1); ++k) {
        if (L->shape_count > 1) fogrt__ld_part(L, m, k, &P, &d);
        d.material = mat;
        r = fogrt_scene_add_mesh(scene, &d);
        if (r) r = fogrt__ld_rejected(L, r, "mesh");
    }
    fogrt__ld_parts_free(L, &P);
    if (!r) L->rep->triangles = m->nt;
    return r;
}

/* Compacts, normals (file or computed), places, adds. Takes ownership of file_nrm. */
FOGRT__LD fogrt_result fogrt__ld_finish_mesh(fogrt__ld *L, fogrt_scene *scene, fogrt__ld_meshbuf *m, float *file_nrm) {
    fogrt_result r;
    m->nrm = file_nrm;                  /* compaction keeps file normals in step */
    r = fogrt__ld_compact(L, m);
    file_nrm = m->nrm; m->nrm = NULL;
    if (!r) r = fogrt__ld_fix_normals(L, m, file_nrm);
    else fogrt__ld_free(L, file_nrm);
    if (!r) r = fogrt__ld_commit_mesh(L, scene, m);
    fogrt__ld_free_mesh(L, m);
    return r;
}

/* Both mesh formats load the same way: parse into a mesh buffer, then place and commit it. */
typedef fogrt_result (*fogrt__ld_mesh_parser)(fogrt__ld *L, fogrt__ld_meshbuf *m, float **file_nrm);
FOGRT__LD fogrt_result fogrt__ld_mesh_file(fogrt__ld *L, fogrt_scene *scene, fogrt__ld_mesh_parser parse) {
    fogrt__ld_meshbuf m;
    float *file_nrm = NULL;
    fogrt_result r;
    memset(&m, 0, sizeof m);
    r = parse(L, &m, &file_nrm);
    fogrt__ld_free(L, L->buf);          /* the text is not needed any more: free it before */
    L->buf = NULL;                      /* the normals' scratch is allocated */
    if (!r) return fogrt__ld_finish_mesh(L, scene, &m, file_nrm);
    fogrt__ld_free_mesh(L, &m);
    fogrt__ld_free(L, file_nrm);
    return r;
}

/* ---- OBJ ---- */
/* The next line of [*p, end): [*ls, *le) without its ending; LF, CRLF and CR all end one. */
FOGRT__LD bool fogrt__obj_line(const char **p, const char *end, const char **ls, const char **le) {
    const char *q = *p;
    if (q >= end) return false;
    *ls = q;
    while (q < end && *q != '\n' && *q != '\r') ++q;
    *le = q;
    if (q < end && *q == '\r') ++q;
    if (q < end && *q == '\n' && (q == *le || q[-1] == '\r')) ++q;
    *p = q;
    return true;
}
FOGRT__LD bool fogrt__obj_blank(char c) { return c == ' ' || c == '\t' || c == '\f' || c == '\v'; }
/* The statement keyword of a line ([*kw, *kw + *kl)), the rest after it in *q; false for a
   blank or comment line. */
FOGRT__LD bool fogrt__obj_keyword(const char *ls, const char *le, const char **kw, size_t *kl, const char **q) {
    const char *s = ls;
    while (s < le && fogrt__obj_blank(*s)) ++s;
    if (s >= le || *s == '#') return false;
    *kw = s;
    while (s < le && !fogrt__obj_blank(*s)) ++s;
    *kl = (size_t)(s - *kw);
    *q = s;
    return true;
}
FOGRT__LD bool fogrt__obj_is(const char *kw, size_t kl, const char *name) { return kl == strlen(name) && memcmp(kw, name, kl) == 0; }
/* Blank-separated words in [q, le). */
FOGRT__LD uint32_t fogrt__obj_words(const char *q, const char *le) {
    uint32_t n = 0;
    while (q < le) {
        while (q < le && fogrt__obj_blank(*q)) ++q;
        if (q >= le) break;
        n++;
        while (q < le && !fogrt__obj_blank(*q)) ++q;
    }
    return n;
}

/* The mesh being read, and the counts of the first pass (exact array sizes). */
typedef struct fogrt__obj {
    float *vp, *vn;                   /* positions, file normals */
    uint32_t *tv, *tn;                /* per triangle corner: position index, normal index */
    uint32_t nvp, nvn, nt, faces;
    uint64_t want_v, want_n, want_t;  /* the first pass's counts */
    bool all_normals;                 /* every face so far gave normals (tn is kept) */
    uint32_t name[3];                 /* with options.on_shape: o, usemtl and g in force */
    bool in_part;                     /* the faces so far belong to the last shape started */
} fogrt__obj;

/* Pass 1: counts v, vn and the triangles of f (words - 2), so the arrays are exact and a
   file asking for too many triangles is refused before anything is allocated. */
FOGRT__LD fogrt_result fogrt__obj_count(fogrt__ld *L, const char *p, const char *end, fogrt__obj *O) {
    const char *ls, *le, *kw, *q;
    size_t kl;
    int line = 0, first_v = 0;
    while (fogrt__obj_line(&p, end, &ls, &le)) {
        line++;
        if (!fogrt__obj_keyword(ls, le, &kw, &kl, &q)) continue;
        if (fogrt__obj_is(kw, kl, "v")) { O->want_v++; if (!first_v) first_v = line; }
        else if (fogrt__obj_is(kw, kl, "vn")) O->want_n++;
        else if (fogrt__obj_is(kw, kl, "f")) {
            uint32_t w = fogrt__obj_words(q, le);
            O->want_t += w > 2 ? w - 2 : 0;
            if (O->want_t > L->opt.max_triangles) return fogrt__ld_count_tris(L, O->want_t, line);
        }
    }
    if (O->want_v == 0)
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, 1, "no vertex ('v') statement in %d line%s: not an OBJ mesh", line, line == 1 ? "" : "s");
    if (O->want_v >= 0xFFFFFFF0u || O->want_n >= 0xFFFFFFF0u) return fogrt__ld_fail(L, FOGRT_RESULT_TOO_LARGE, first_v, "too many vertices");
    return fogrt__ld_count_tris(L, O->want_t, line);
}

/* v x y z / vn x y z */
FOGRT__LD fogrt_result fogrt__obj_vertex(fogrt__ld *L, fogrt__obj *O, const char *q, const char *le, int line, bool is_n) {
    float x[3];
    int k;
    for (k = 0; k < 3; ++k) {
        while (q < le && fogrt__obj_blank(*q)) ++q;
        if (!fogrt__ld_strtof(&q, le, &x[k]) || (q < le && !fogrt__ld_space(*q)))
            return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "'%s' needs 3 finite numbers", is_n ? "vn" : "v");
        if (!is_n && L->opt.place == FOGRT_LOAD_PLACE_AS_IS && !fogrt__ld_coord_ok((double)x[k]))
            return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "coordinate %g is beyond fogrt's limit of 1e30", (double)x[k]);
    }
    if (is_n) memcpy(O->vn + 3 * (size_t)O->nvn++, x, sizeof x);
    else memcpy(O->vp + 3 * (size_t)O->nvp++, x, sizeof x);
    return FOGRT_RESULT_OK;
}

/* A signed index at *s (digits optional): false when it has a sign without digits or
   passes 2^32. *any: whether digits were there. */
FOGRT__LD bool fogrt__obj_index(const char **s, const char *le, long long *out, bool *any) {
    bool neg = false;
    long long val = 0;
    *any = false;
    if (*s < le && (**s == '-' || **s == '+')) { neg = **s == '-'; ++*s; }
    for (; *s < le && **s >= '0' && **s <= '9' && val <= 0xFFFFFFFFLL; ++*s, *any = true) val = val * 10 + (**s - '0');
    *out = neg ? -val : val;
    return val <= 0xFFFFFFFFLL && (*any || !neg);
}
/* One face corner v[/[t][/n]] at *q: idx[0] = v, idx[2] = n (0: none), as written. */
FOGRT__LD fogrt_result fogrt__obj_corner_text(fogrt__ld *L, const char **q, const char *le, int line, long long idx[3]) {
    int part;
    const char *s = *q;
    idx[0] = idx[1] = idx[2] = 0;
    for (part = 0; part < 3; ++part) {
        bool any;
        long long val;
        if (!fogrt__obj_index(&s, le, &val, &any) || (!any && part == 0))
            return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "bad face vertex '%.*s'", fogrt__ld_toklen(s, le), s);
        if (any) idx[part] = val;
        if (!(s < le && *s == '/' && part < 2)) break;
        ++s;
    }
    if (s < le && !fogrt__ld_space(*s))
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "bad face vertex near '%.*s'", fogrt__ld_toklen(s, le), s);
    *q = s;
    return FOGRT_RESULT_OK;
}
/* The corner resolved: 1-based, negative = relative to the end; *n = UINT32_MAX: no normal. */
FOGRT__LD fogrt_result fogrt__obj_corner(fogrt__ld *L, const fogrt__obj *O, const char **q, const char *le, int line,
                                         uint32_t *v, uint32_t *n) {
    long long idx[3], vi, ni;
    FOGRT__LD_TRY(fogrt__obj_corner_text(L, q, le, line, idx));
    vi = idx[0] < 0 ? (long long)O->nvp + idx[0] : idx[0] - 1;
    ni = idx[2] < 0 ? (long long)O->nvn + idx[2] : idx[2] - 1;
    if (idx[0] == 0 || vi < 0 || vi >= (long long)O->nvp)
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "vertex index %lld out of range (%u vertices so far)", idx[0], O->nvp);
    if (idx[2] != 0 && (ni < 0 || ni >= (long long)O->nvn))
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "normal index %lld out of range (%u normals so far)", idx[2], O->nvn);
    *v = (uint32_t)vi;
    *n = idx[2] != 0 ? (uint32_t)ni : UINT32_MAX;
    return FOGRT_RESULT_OK;
}

/* f c0 c1 c2 ...: fan-triangulated as it is read, (c0, c[k-1], c[k]). */
FOGRT__LD fogrt_result fogrt__obj_face(fogrt__ld *L, fogrt__obj *O, const char *q, const char *le, int line) {
    uint32_t n = 0, v0 = 0, n0 = 0, vprev = 0, nprev = 0, v = 0, nn = 0;
    bool has_n = true;
    for (;;) {
        while (q < le && fogrt__obj_blank(*q)) ++q;
        if (q >= le) break;
        FOGRT__LD_TRY(fogrt__obj_corner(L, O, &q, le, line, &v, &nn));
        has_n = has_n && nn != UINT32_MAX;
        if (n >= 2) {
            uint32_t *t = O->tv + 3 * (size_t)O->nt;
            t[0] = v0; t[1] = vprev; t[2] = v;
            if (O->tn) { t = O->tn + 3 * (size_t)O->nt; t[0] = n0; t[1] = nprev; t[2] = nn; }
            O->nt++;
        }
        if (n == 0) { v0 = v; n0 = nn; }
        vprev = v; nprev = nn; n++;
    }
    if (n < 3) return fogrt__ld_fail(L, FOGRT__LD_PARSE, line, "face with fewer than 3 vertices");
    O->faces++;
    if (!has_n && O->tn) { fogrt__ld_free(L, O->tn); O->tn = NULL; }   /* the file normals cannot be used */
    if (!has_n) O->all_normals = false;
    return FOGRT_RESULT_OK;
}

/* With options.on_shape: o, g and usemtl name what follows (the rest of the line, blanks
   trimmed); an o or a g ends the current mesh, and the next face starts one. */
FOGRT__LD fogrt_result fogrt__obj_name(fogrt__ld *L, fogrt__obj *O, const char *kw, size_t kl, const char *q, const char *le) {
    int k = fogrt__obj_is(kw, kl, "o") ? 0 : fogrt__obj_is(kw, kl, "usemtl") ? 1 : fogrt__obj_is(kw, kl, "g") ? 2 : -1;
    if (k < 0) return FOGRT_RESULT_OK;
    while (q < le && fogrt__obj_blank(*q)) ++q;
    while (le > q && fogrt__obj_blank(le[-1])) --le;
    FOGRT__LD_TRY(fogrt__ld_name(L, q, (uint32_t)(le - q), &O->name[k]));
    if (k == 0) O->name[2] = 0;                  /* an object starts without a group */
    if (k != 1) O->in_part = false;
    return FOGRT_RESULT_OK;
}
/* Pass 2: the statements. Everything but v, vn and f (and o, g, usemtl with on_shape: vt,
   vp, s, mtllib, l, p, ...) is ignored. */
FOGRT__LD fogrt_result fogrt__obj_statements(fogrt__ld *L, const char *p, const char *end, fogrt__obj *O) {
    const char *ls, *le, *kw, *q;
    size_t kl;
    int line = 0;
    while (fogrt__obj_line(&p, end, &ls, &le)) {
        line++;
        if (!fogrt__obj_keyword(ls, le, &kw, &kl, &q)) continue;
        if (fogrt__obj_is(kw, kl, "v") || fogrt__obj_is(kw, kl, "vn")) FOGRT__LD_TRY(fogrt__obj_vertex(L, O, q, le, line, kl == 2));
        else if (fogrt__obj_is(kw, kl, "f")) {
            if (L->opt.on_shape && !O->in_part) FOGRT__LD_TRY(fogrt__ld_push_shape(L, FOGRT_SHAPE_MESH, O->name, O->nt));
            O->in_part = true;
            FOGRT__LD_TRY(fogrt__obj_face(L, O, q, le, line));
        }
        else if (L->opt.on_shape) FOGRT__LD_TRY(fogrt__obj_name(L, O, kw, kl, q, le));
    }
    return FOGRT_RESULT_OK;
}

/* u64 -> u32 hash table for (position, normal) pairs, grown as it fills. */
typedef struct fogrt__ld_map { uint64_t *keys; uint32_t *vals; uint32_t cap, count; } fogrt__ld_map;
FOGRT__LD uint32_t fogrt__ld_mix(uint64_t k) {
    k ^= k >> 33; k *= 0xff51afd7ed558ccdULL; k ^= k >> 33; k *= 0xc4ceb9fe1a85ec53ULL; k ^= k >> 33;
    return (uint32_t)k;
}
FOGRT__LD uint32_t fogrt__ld_map_slot(const fogrt__ld_map *map, uint64_t key) {
    uint32_t h = fogrt__ld_mix(key) & (map->cap - 1);
    while (map->keys[h] != UINT64_MAX && map->keys[h] != key) h = (h + 1) & (map->cap - 1);
    return h;
}
/* (Re)builds the table with cap slots (a power of two), keeping its entries. */
FOGRT__LD fogrt_result fogrt__ld_map_resize(fogrt__ld *L, fogrt__ld_map *map, uint32_t cap) {
    fogrt__ld_map n;
    uint32_t i;
    n.cap = cap; n.count = map->count;
    n.keys = (uint64_t *)fogrt__ld_alloc(L, cap, sizeof(uint64_t));
    n.vals = n.keys ? (uint32_t *)fogrt__ld_alloc(L, cap, sizeof(uint32_t)) : NULL;
    if (!n.vals) { fogrt__ld_free(L, n.keys); return FOGRT_RESULT_OUT_OF_MEMORY; }
    for (i = 0; i < cap; ++i) n.keys[i] = UINT64_MAX;
    for (i = 0; i < map->cap; ++i)
        if (map->keys[i] != UINT64_MAX) {
            uint32_t h = fogrt__ld_map_slot(&n, map->keys[i]);
            n.keys[h] = map->keys[i]; n.vals[h] = map->vals[i];
        }
    fogrt__ld_free(L, map->keys); fogrt__ld_free(L, map->vals);
    *map = n;
    return FOGRT_RESULT_OK;
}

/* One fogrt vertex per distinct (position, normal) pair: tv becomes the new vertex index,
   O->vp / O->vn the new positions / normals. */
FOGRT__LD fogrt_result fogrt__obj_unify(fogrt__ld *L, fogrt__obj *O) {
    fogrt__ld_map map;
    uint32_t i;
    float *pos, *nrm;
    memset(&map, 0, sizeof map);
    FOGRT__LD_TRY(fogrt__ld_map_resize(L, &map, 1024));
    for (i = 0; i < 3 * O->nt; ++i) {
        uint64_t key = (uint64_t)O->tv[i] << 32 | O->tn[i];
        uint32_t h = fogrt__ld_map_slot(&map, key);
        if (map.keys[h] == UINT64_MAX) {
            map.keys[h] = key; map.vals[h] = map.count++;
            if (2 * (uint64_t)map.count > map.cap && fogrt__ld_map_resize(L, &map, 2 * map.cap)) break;
        }
        O->tv[i] = map.vals[fogrt__ld_map_slot(&map, key)];
    }
    fogrt__ld_free(L, O->tn); O->tn = NULL;
    pos = i == 3 * O->nt ? (float *)fogrt__ld_alloc(L, 3 * (uint64_t)map.count, sizeof(float)) : NULL;
    nrm = pos ? (float *)fogrt__ld_alloc(L, 3 * (uint64_t)map.count, sizeof(float)) : NULL;
    if (!nrm) { fogrt__ld_free(L, pos); fogrt__ld_free(L, map.keys); fogrt__ld_free(L, map.vals); return FOGRT_RESULT_OUT_OF_MEMORY; }
    for (i = 0; i < map.cap; ++i)
        if (map.keys[i] != UINT64_MAX) {
            memcpy(pos + 3 * (size_t)map.vals[i], O->vp + 3 * (size_t)(map.keys[i] >> 32), 3 * sizeof(float));
            memcpy(nrm + 3 * (size_t)map.vals[i], O->vn + 3 * (size_t)(map.keys[i] & 0xFFFFFFFFu), 3 * sizeof(float));
        }
    fogrt__ld_free(L, map.keys); fogrt__ld_free(L, map.vals);
    fogrt__ld_free(L, O->vp); fogrt__ld_free(L, O->vn);
    O->vp = pos; O->vn = nrm; O->nvp = O->nvn = map.count;
    return FOGRT_RESULT_OK;
}

FOGRT__LD void fogrt__obj_free(fogrt__ld *L, fogrt__obj *O) {
    fogrt__ld_free(L, O->vp); fogrt__ld_free(L, O->vn); fogrt__ld_free(L, O->tv); fogrt__ld_free(L, O->tn);
    memset(O, 0, sizeof *O);
}

/* OBJ: v, vn, f. Returns the mesh before placement. */
FOGRT__LD fogrt_result fogrt__ld_obj_parse(fogrt__ld *L, fogrt__ld_meshbuf *out, float **out_file_nrm) {
    const char *p = L->buf, *end = L->buf + L->len;
    fogrt__obj O;
    fogrt_result r;
    memset(&O, 0, sizeof O);
    if (fogrt__ld_starts(p, end, "\xEF\xBB\xBF")) p += 3;     /* UTF-8 byte-order mark */
    FOGRT__LD_TRY(fogrt__obj_count(L, p, end, &O));
    O.vp = (float *)fogrt__ld_alloc(L, 3 * O.want_v, sizeof(float));
    O.vn = O.vp ? (float *)fogrt__ld_alloc(L, 3 * O.want_n, sizeof(float)) : NULL;
    O.tv = O.vn ? (uint32_t *)fogrt__ld_alloc(L, 3 * O.want_t, sizeof(uint32_t)) : NULL;
    O.tn = O.tv && O.want_n ? (uint32_t *)fogrt__ld_alloc(L, 3 * O.want_t, sizeof(uint32_t)) : NULL;
    O.all_normals = O.want_n > 0;
    r = !O.tv || (O.want_n && !O.tn) ? FOGRT_RESULT_OUT_OF_MEMORY : fogrt__obj_statements(L, p, end, &O);
    L->rep->vertices = O.nvp;
    L->rep->faces = O.faces;
    if (!r && O.nt > 0 && O.all_normals) r = fogrt__obj_unify(L, &O);
    if (r) { fogrt__obj_free(L, &O); return r; }
    out->pos = O.vp; out->nv = O.nvp; out->idx = O.tv; out->nt = O.nt;
    *out_file_nrm = O.nt > 0 && O.all_normals ? O.vn : NULL;
    if (!*out_file_nrm) fogrt__ld_free(L, O.vn);
    fogrt__ld_free(L, O.tn);
    return FOGRT_RESULT_OK;
}

/* ---- PLY ---- */
enum { FOGRT__PLY_ASCII = 1, FOGRT__PLY_LE, FOGRT__PLY_BE };
enum { FOGRT__PLY_NONE = 0, FOGRT__PLY_X, FOGRT__PLY_Y, FOGRT__PLY_Z, FOGRT__PLY_NX, FOGRT__PLY_NY, FOGRT__PLY_NZ, FOGRT__PLY_INDICES };
typedef struct fogrt__ply_prop { int type, count_type; bool list; int role; } fogrt__ply_prop;
typedef struct fogrt__ply_elem { char name[32]; uint64_t count; uint32_t first, nprops; int line; } fogrt__ply_elem;
/* The header as read, and the mesh being filled. */
typedef struct fogrt__ply {
    fogrt__ply_elem el[16]; uint32_t nel;
    fogrt__ply_prop props[128]; uint32_t nprops;
    int format, line;                 /* line: the header's last line */
    uint64_t vcount;
    bool have_vertex, header_done;
    const char *data;                 /* the first byte after end_header */
    float *pos, *nrm;
    uint32_t *tri, nt, cap_tri, skipped;
} fogrt__ply;
typedef struct fogrt__ply_reader { const char *p, *end, *data; int format, line; fogrt__ld *L; } fogrt__ply_reader;

/* Type name -> size in bytes (negative: float types), 0 if unknown. */
FOGRT__LD int fogrt__ply_type(const char *s, size_t n) {
    static const char *names[16] = { "char", "int8", "uchar", "uint8", "short", "int16", "ushort", "uint16",
                                     "int", "int32", "uint", "uint32", "float", "float32", "double", "float64" };
    static const int types[16] = { 1, 1, 11, 11, 2, 2, 12, 12, 4, 4, 14, 14, -4, -4, -8, -8 };  /* 10+: unsigned */
    int i;
    for (i = 0; i < 16; ++i) if (strlen(names[i]) == n && memcmp(names[i], s, n) == 0) return types[i];
    return 0;
}
FOGRT__LD int fogrt__ply_size(int type) { return type < 0 ? -type : type > 10 ? type - 10 : type; }

/* One header line split into at most 6 words. */
typedef struct fogrt__ply_words { const char *tok[6]; size_t len[6]; int n; } fogrt__ply_words;
FOGRT__LD void fogrt__ply_split(const char *q, const char *le, fogrt__ply_words *W) {
    W->n = 0;
    while (q < le && W->n < 6) {
        while (q < le && (*q == ' ' || *q == '\t' || *q == '\r')) ++q;
        if (q >= le) break;
        W->tok[W->n] = q;
        while (q < le && *q != ' ' && *q != '\t' && *q != '\r') ++q;
        W->len[W->n] = (size_t)(q - W->tok[W->n]);
        W->n++;
    }
}
FOGRT__LD bool fogrt__ply_is(const fogrt__ply_words *W, int k, const char *s) {
    return k < W->n && W->len[k] == strlen(s) && memcmp(W->tok[k], s, W->len[k]) == 0;
}

/* element NAME COUNT */
FOGRT__LD fogrt_result fogrt__ply_element(fogrt__ld *L, fogrt__ply *P, const fogrt__ply_words *W) {
    char num[24], *q2;
    unsigned long long c;
    fogrt__ply_elem *e;
    if (W->n != 3 || W->len[2] >= sizeof num || W->tok[2][0] < '0' || W->tok[2][0] > '9')
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, P->line, "expected 'element NAME COUNT'");
    if (P->nel == 16) return fogrt__ld_fail(L, FOGRT__LD_PARSE, P->line, "too many elements (at most 16)");
    memcpy(num, W->tok[2], W->len[2]); num[W->len[2]] = 0;
    c = strtoull(num, &q2, 10);
    if (*q2 || c > 0xFFFFFFF0ull) return fogrt__ld_fail(L, FOGRT__LD_PARSE, P->line, "bad element count");
    e = &P->el[P->nel];
    memset(e, 0, sizeof *e);
    snprintf(e->name, sizeof e->name, "%.*s", (int)(W->len[1] > 31 ? 31 : W->len[1]), W->tok[1]);
    e->count = c;
    e->first = P->nprops;
    e->line = P->line;
    if (strcmp(e->name, "vertex") == 0) {
        if (P->have_vertex) return fogrt__ld_fail(L, FOGRT__LD_PARSE, P->line, "a second vertex element");
        P->have_vertex = true; P->vcount = c;
    }
    P->nel++;
    return FOGRT_RESULT_OK;
}

/* What a property is for: x y z nx ny nz of "vertex", the index list of "face". */
FOGRT__LD int fogrt__ply_role(const char *elem, const fogrt__ply_prop *pr, const char *name, size_t n) {
    static const char *vnames[6] = { "x", "y", "z", "nx", "ny", "nz" };
    int k;
    if (strcmp(elem, "vertex") == 0 && !pr->list)
        for (k = 0; k < 6; ++k) if (n == strlen(vnames[k]) && memcmp(name, vnames[k], n) == 0) return FOGRT__PLY_X + k;
    if (strcmp(elem, "face") == 0 && pr->list &&
        ((n == 14 && memcmp(name, "vertex_indices", n) == 0) || (n == 12 && memcmp(name, "vertex_index", n) == 0)))
        return FOGRT__PLY_INDICES;
    return FOGRT__PLY_NONE;
}

/* property TYPE NAME / property list COUNT_TYPE ITEM_TYPE NAME */
FOGRT__LD fogrt_result fogrt__ply_property(fogrt__ld *L, fogrt__ply *P, const fogrt__ply_words *W) {
    fogrt__ply_prop pr;
    fogrt__ply_elem *pe = P->nel ? &P->el[P->nel - 1] : NULL;
    int ni;
    if (!pe) return fogrt__ld_fail(L, FOGRT__LD_PARSE, P->line, "property before any element");
    if (P->nprops == 128) return fogrt__ld_fail(L, FOGRT__LD_PARSE, P->line, "too many properties (at most 128)");
    memset(&pr, 0, sizeof pr);
    if (fogrt__ply_is(W, 1, "list")) {
        if (W->n != 5) return fogrt__ld_fail(L, FOGRT__LD_PARSE, P->line, "expected 'property list COUNT_TYPE ITEM_TYPE NAME'");
        pr.list = true;
        pr.count_type = fogrt__ply_type(W->tok[2], W->len[2]);
        pr.type = fogrt__ply_type(W->tok[3], W->len[3]);
        if (pr.count_type <= 0 || pr.type == 0) return fogrt__ld_fail(L, FOGRT__LD_PARSE, P->line, "bad list property types");
        ni = 4;
    } else {
        if (W->n != 3) return fogrt__ld_fail(L, FOGRT__LD_PARSE, P->line, "expected 'property TYPE NAME'");
        pr.type = fogrt__ply_type(W->tok[1], W->len[1]);
        if (pr.type == 0) return fogrt__ld_fail(L, FOGRT__LD_PARSE, P->line, "unknown property type '%.*s'", (int)(W->len[1] > 20 ? 20 : W->len[1]), W->tok[1]);
        ni = 2;
    }
    pr.role = fogrt__ply_role(pe->name, &pr, W->tok[ni], W->len[ni]);
    if (pr.role == FOGRT__PLY_INDICES && pr.type < 0) return fogrt__ld_fail(L, FOGRT__LD_PARSE, P->line, "vertex indices must have an integer type");
    P->props[P->nprops++] = pr;
    pe->nprops++;
    return FOGRT_RESULT_OK;
}

/* One header line after the first. */
FOGRT__LD fogrt_result fogrt__ply_header_line(fogrt__ld *L, fogrt__ply *P, const fogrt__ply_words *W) {
    if (W->n == 0 || fogrt__ply_is(W, 0, "comment") || fogrt__ply_is(W, 0, "obj_info")) return FOGRT_RESULT_OK;
    if (fogrt__ply_is(W, 0, "element")) return fogrt__ply_element(L, P, W);
    if (fogrt__ply_is(W, 0, "property")) return fogrt__ply_property(L, P, W);
    if (fogrt__ply_is(W, 0, "end_header")) { P->header_done = true; return FOGRT_RESULT_OK; }
    if (!fogrt__ply_is(W, 0, "format"))
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, P->line, "unknown header line '%.*s'", (int)(W->len[0] > 20 ? 20 : W->len[0]), W->tok[0]);
    if (W->n < 2) return fogrt__ld_fail(L, FOGRT__LD_PARSE, P->line, "format needs a name");
    if (fogrt__ply_is(W, 1, "ascii")) P->format = FOGRT__PLY_ASCII;
    else if (fogrt__ply_is(W, 1, "binary_little_endian")) P->format = FOGRT__PLY_LE;
    else if (fogrt__ply_is(W, 1, "binary_big_endian")) P->format = FOGRT__PLY_BE;
    else return fogrt__ld_fail(L, FOGRT__LD_PARSE, P->line, "unknown format '%.*s'", (int)(W->len[1] > 30 ? 30 : W->len[1]), W->tok[1]);
    return FOGRT_RESULT_OK;
}

/* Bits of the roles found among the vertex element's properties. */
FOGRT__LD int fogrt__ply_vertex_roles(const fogrt__ply *P) {
    uint32_t e, i;
    int roles = 0;
    for (e = 0; e < P->nel; ++e)
        if (strcmp(P->el[e].name, "vertex") == 0)
            for (i = 0; i < P->el[e].nprops; ++i) roles |= 1 << P->props[P->el[e].first + i].role;
    return roles;
}

/* The header: "ply", then one keyword per line until end_header. */
FOGRT__LD fogrt_result fogrt__ply_header(fogrt__ld *L, fogrt__ply *P) {
    const char *p = L->buf, *end = L->buf + L->len;
    fogrt__ply_words W;
    while (p < end && !P->header_done) {
        const char *le = (const char *)memchr(p, '\n', (size_t)(end - p));
        if (!le) return fogrt__ld_fail(L, FOGRT__LD_PARSE, P->line + 1, "header not terminated by end_header");
        P->line++;
        fogrt__ply_split(p, le, &W);
        p = le + 1;
        if (P->line > 1) FOGRT__LD_TRY(fogrt__ply_header_line(L, P, &W));
        else if (W.n != 1 || !fogrt__ply_is(&W, 0, "ply")) return fogrt__ld_fail(L, FOGRT__LD_PARSE, 1, "not a PLY file (first line must be 'ply')");
    }
    if (!P->header_done) return fogrt__ld_fail(L, FOGRT__LD_PARSE, P->line > 0 ? P->line : 1, "header not terminated by end_header");
    if (!P->format) return fogrt__ld_fail(L, FOGRT__LD_PARSE, P->line, "no format line in the header");
    if (!P->have_vertex) return fogrt__ld_fail(L, FOGRT__LD_PARSE, P->line, "no vertex element");
    if ((fogrt__ply_vertex_roles(P) & 0xE) != 0xE) return fogrt__ld_fail(L, FOGRT__LD_PARSE, P->line, "the vertex element needs x, y and z");
    P->data = p;
    return FOGRT_RESULT_OK;
}

FOGRT__LD uint64_t fogrt__ply_items(const fogrt__ply *P) {
    uint64_t n = 0;
    uint32_t e;
    for (e = 0; e < P->nel; ++e) n += P->el[e].count;
    return n;
}
/* The declared counts against the file's size, before anything is allocated: every value
   takes at least its size in binary, or one character in ascii (a list at least its count),
   so a header asking for more than the file can hold is "file too short". A file cut a little
   short passes this bound and is reported where its data ends. */
FOGRT__LD fogrt_result fogrt__ply_check_size(fogrt__ld *L, const fogrt__ply *P) {
    uint64_t need = 0, have = (uint64_t)(L->buf + L->len - P->data);
    uint32_t e, i;
    for (e = 0; e < P->nel; ++e) {
        uint64_t per = 0;
        for (i = 0; i < P->el[e].nprops; ++i) {
            const fogrt__ply_prop *pr = &P->props[P->el[e].first + i];
            per += P->format == FOGRT__PLY_ASCII ? 1 : (uint64_t)fogrt__ply_size(pr->list ? pr->count_type : pr->type);
        }
        need += per * P->el[e].count;            /* at most 2^32 * 128 * 8: no overflow */
    }
    if (need <= have) return FOGRT_RESULT_OK;
    return fogrt__ld_fail(L, FOGRT__LD_PARSE, P->line, "file too short: the header declares %llu vertices and %llu other items, which need at least %llu bytes of data, but %llu follow",
                          (unsigned long long)P->vcount, (unsigned long long)fogrt__ply_items(P) - P->vcount, (unsigned long long)need, (unsigned long long)have);
}

/* One ascii value: integers exact (strtoll), floats any number strtod reads (the caller
   checks the range of the values it uses). */
FOGRT__LD fogrt_result fogrt__ply_read_ascii(fogrt__ply_reader *R, int type, double *out) {
    const char *s = R->p;
    char *q;
    while (s < R->end && fogrt__ld_space(*s)) { if (*s == '\n') R->line++; ++s; }
    R->p = s;
    if (s >= R->end)       /* at the end: name the last line, not the one after its newline */
        return fogrt__ld_fail(R->L, FOGRT__LD_PARSE, R->line - (s > R->data && s[-1] == '\n' ? 1 : 0), "unexpected end of file in the data");
    errno = 0;
    if (type > 0) *out = (double)strtoll(s, &q, 10);
    else *out = strtod(s, &q);
    if (q == s || (type > 0 && errno) || (q < R->end && !fogrt__ld_space(*q)))
        return fogrt__ld_fail(R->L, FOGRT__LD_PARSE, R->line, "expected %s, found '%.*s'", type > 0 ? "an integer" : "a number",
                              fogrt__ld_toklen(s, R->end), s);
    R->p = q;
    return FOGRT_RESULT_OK;
}
/* One binary value of the given type, in the file's byte order. */
FOGRT__LD fogrt_result fogrt__ply_read_binary(fogrt__ply_reader *R, int type, double *out) {
    int size = fogrt__ply_size(type), i;
    unsigned char b[8];
    uint64_t u = 0;
    if ((size_t)(R->end - R->p) < (size_t)size)
        return fogrt__ld_fail(R->L, FOGRT__LD_PARSE, R->line, "binary data truncated at byte %lu", (unsigned long)(R->p - R->L->buf));
    for (i = 0; i < size; ++i) b[i] = (unsigned char)R->p[R->format == FOGRT__PLY_LE ? i : size - 1 - i];
    R->p += size;
    if (type == -4) { float f; memcpy(&f, b, 4); *out = (double)f; return FOGRT_RESULT_OK; }
    if (type == -8) { memcpy(out, b, 8); return FOGRT_RESULT_OK; }
    for (i = size - 1; i >= 0; --i) u = u << 8 | b[i];
    if (type < 10 && (u >> (8 * size - 1)) & 1) *out = (double)u - ldexp(1.0, 8 * size);   /* signed */
    else *out = (double)u;
    return FOGRT_RESULT_OK;
}
FOGRT__LD fogrt_result fogrt__ply_read(fogrt__ply_reader *R, int type, double *out) {
    return R->format == FOGRT__PLY_ASCII ? fogrt__ply_read_ascii(R, type, out) : fogrt__ply_read_binary(R, type, out);
}

/* A vertex property fogrt uses: x, y, z (finite floats; within 1e30 unless the mesh is
   placed) or nx, ny, nz (finite floats). Others are read and skipped, whatever they hold. */
FOGRT__LD fogrt_result fogrt__ply_vertex_value(fogrt__ld *L, fogrt__ply *P, const fogrt__ply_reader *R, int role, uint64_t k, double v) {
    static const char *names = "x\0y\0z\0nx\0ny\0nz";
    static const int at[6] = { 0, 2, 4, 6, 9, 12 };
    double lim = role <= FOGRT__PLY_Z && L->opt.place == FOGRT_LOAD_PLACE_AS_IS ? FOGRT__LD_MAX_COORD : (double)FLT_MAX;
    if (!(v >= -lim && v <= lim))
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, R->line, "vertex %llu: %s = %g is %s", (unsigned long long)k, names + at[role - FOGRT__PLY_X], v,
                              lim < (double)FLT_MAX ? "beyond fogrt's limit of 1e30" : "not a finite float");
    if (role <= FOGRT__PLY_Z) P->pos[3 * k + (uint64_t)(role - FOGRT__PLY_X)] = (float)v;
    else if (P->nrm) P->nrm[3 * k + (uint64_t)(role - FOGRT__PLY_NX)] = (float)v;
    return FOGRT_RESULT_OK;
}

/* A face's index list, fan-triangulated as it is read: (i0, i[j-1], i[j]). */
FOGRT__LD fogrt_result fogrt__ply_face(fogrt__ld *L, fogrt__ply *P, fogrt__ply_reader *R, const fogrt__ply_prop *pr, uint64_t n) {
    uint64_t j;
    uint32_t first = 0, prev = 0;
    if (n < 3) P->skipped++;
    else {
        FOGRT__LD_TRY(fogrt__ld_count_tris(L, n - 2, R->line));
        FOGRT__LD_TRY(fogrt__ld_grow(L, (void **)&P->tri, &P->cap_tri, 3 * ((uint64_t)P->nt + n - 2), sizeof(uint32_t)));
    }
    for (j = 0; j < n; ++j) {
        double v;
        uint32_t *t;
        FOGRT__LD_TRY(fogrt__ply_read(R, pr->type, &v));
        if (!(v >= 0 && v < (double)P->vcount && v == floor(v)))
            return fogrt__ld_fail(L, FOGRT__LD_PARSE, R->line, "vertex index %g out of range (%llu vertices)", v, (unsigned long long)P->vcount);
        if (j == 0) first = (uint32_t)v;
        if (j >= 2 && n >= 3) {
            t = P->tri + 3 * (size_t)P->nt++;
            t[0] = first; t[1] = prev; t[2] = (uint32_t)v;
        }
        prev = (uint32_t)v;
    }
    return FOGRT_RESULT_OK;
}

/* One property value (or list) of item k of element e. */
FOGRT__LD fogrt_result fogrt__ply_value(fogrt__ld *L, fogrt__ply *P, fogrt__ply_reader *R, const fogrt__ply_prop *pr, bool is_vertex, uint64_t k) {
    double v, n;
    uint64_t j;
    if (!pr->list) {
        FOGRT__LD_TRY(fogrt__ply_read(R, pr->type, &v));
        return is_vertex && pr->role != FOGRT__PLY_NONE ? fogrt__ply_vertex_value(L, P, R, pr->role, k, v) : FOGRT_RESULT_OK;
    }
    FOGRT__LD_TRY(fogrt__ply_read(R, pr->count_type, &n));
    if (!(n >= 0 && n == floor(n))) return fogrt__ld_fail(L, FOGRT__LD_PARSE, R->line, "bad list length %g", n);
    if (n * (R->format == FOGRT__PLY_ASCII ? 1.0 : (double)fogrt__ply_size(pr->type)) > (double)(uint64_t)(R->end - R->p))
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, R->line, "a list of %g items runs past the end of the file (truncated?)", n);
    if (pr->role == FOGRT__PLY_INDICES) return fogrt__ply_face(L, P, R, pr, (uint64_t)n);
    for (j = 0; j < (uint64_t)n; ++j) FOGRT__LD_TRY(fogrt__ply_read(R, pr->type, &v));
    return FOGRT_RESULT_OK;
}

/* The data: every element in header order (elements without properties have no data). */
FOGRT__LD fogrt_result fogrt__ply_data(fogrt__ld *L, fogrt__ply *P) {
    fogrt__ply_reader R;
    uint32_t e, i;
    R.p = P->data; R.end = L->buf + L->len; R.data = P->data; R.format = P->format; R.line = P->line + 1; R.L = L;
    for (e = 0; e < P->nel; ++e) {
        uint64_t k;
        bool is_vertex = strcmp(P->el[e].name, "vertex") == 0, is_face = strcmp(P->el[e].name, "face") == 0;
        if (is_face) FOGRT__LD_TRY(fogrt__ld_grow(L, (void **)&P->tri, &P->cap_tri, 3 * P->el[e].count, sizeof(uint32_t)));
        for (k = 0; k < P->el[e].count && P->el[e].nprops > 0; ++k)
            for (i = 0; i < P->el[e].nprops; ++i)
                FOGRT__LD_TRY(fogrt__ply_value(L, P, &R, &P->props[P->el[e].first + i], is_vertex, k));
        if (is_face) L->rep->faces = (uint32_t)P->el[e].count;
    }
    return FOGRT_RESULT_OK;
}

FOGRT__LD fogrt_result fogrt__ply_parse(fogrt__ld *L, fogrt__ld_meshbuf *out, float **out_file_nrm) {
    fogrt__ply *P = (fogrt__ply *)fogrt__ld_alloc(L, 1, sizeof(fogrt__ply));   /* 3.6 KB: not on the stack */
    fogrt_result r;
    if (!P) return FOGRT_RESULT_OUT_OF_MEMORY;
    memset(P, 0, sizeof *P);
    r = fogrt__ply_header(L, P);
    if (!r) r = fogrt__ply_check_size(L, P);
    if (!r) P->pos = (float *)fogrt__ld_alloc(L, P->vcount * 3, sizeof(float));
    if (!r && !P->pos) r = FOGRT_RESULT_OUT_OF_MEMORY;
    if (!r && (fogrt__ply_vertex_roles(P) & 0x70) == 0x70) {
        P->nrm = (float *)fogrt__ld_alloc(L, P->vcount * 3, sizeof(float));
        if (!P->nrm) r = FOGRT_RESULT_OUT_OF_MEMORY;
    }
    if (!r) r = fogrt__ply_data(L, P);
    if (!r && P->skipped) fogrt__ld_warn(L, 0, "%u faces with fewer than 3 vertices skipped", P->skipped);
    L->rep->vertices = (uint32_t)P->vcount;
    out->pos = P->pos; out->nv = (uint32_t)P->vcount; out->idx = P->tri; out->nt = P->nt;
    *out_file_nrm = P->nrm;
    fogrt__ld_free(L, P);
    if (!r && !out->idx) {
        out->idx = (uint32_t *)fogrt__ld_alloc(L, 1, sizeof(uint32_t));
        if (!out->idx) r = FOGRT_RESULT_OUT_OF_MEMORY;
    }
    return r;
}

/* ------------------------------------------------------------------------------------------
   13. CS184 camera settings files
   ------------------------------------------------------------------------------------------ */
/* What fogrt_scene_set_camera will check, with the camera file's line and the true reason:
   the view direction must be a finite float vector, up not parallel to it, the fov < 180. */
FOGRT__LD fogrt_result fogrt__ld_check_camera(fogrt__ld *L, const fogrt_camera_desc *c) {
    double f[3], u[3], x[3], lf, lu;
    int i;
    f[0] = (double)(c->look_at.x - c->position.x); f[1] = (double)(c->look_at.y - c->position.y); f[2] = (double)(c->look_at.z - c->position.z);
    u[0] = (double)c->up.x; u[1] = (double)c->up.y; u[2] = (double)c->up.z;
    for (i = 0; i < 3; ++i)
        if (!(f[i] >= -(double)FLT_MAX && f[i] <= (double)FLT_MAX))
            return fogrt__ld_fail(L, FOGRT__LD_PARSE, 2, "target - position overflows a float (position and target too far apart)");
    if (u[0] == 0.0 && u[1] == 0.0 && u[2] == 0.0) u[1] = 1.0;   /* the scene's default up */
    lf = fogrt__ld_len3(f); lu = fogrt__ld_len3(u);
    x[0] = f[1] * u[2] - f[2] * u[1]; x[1] = f[2] * u[0] - f[0] * u[2]; x[2] = f[0] * u[1] - f[1] * u[0];
    if (!(fogrt__ld_len3(x) > 1e-6 * lf * lu))
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, 4, "up (the second column of c2w) is parallel to the view direction");
    if (!(c->fov_deg > 0.0f && c->fov_deg < 180.0f))
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, 5, "screenW, screenH and screenDist give a %s field of view of %g degrees; fogrt needs less than 180",
                              c->fov_is_horizontal ? "horizontal" : "vertical", (double)c->fov_deg);
    return FOGRT_RESULT_OK;
}

/* 0-4 hFov vFov ar nClip fClip, 5-7 pos, 8-10 target, 11-15 phi theta r minR maxR,
   16-24 c2w row-major (columns: right, up, back), 25-27 screenW screenH screenDist,
   28-29 focalDistance lensRadius. */
FOGRT__LD fogrt_result fogrt__ld_camera_file(fogrt__ld *L, int width, int height, fogrt_camera_desc *camera) {
    float v[30], sw, sh, sd;
    uint64_t n = 0;
    FOGRT__LD_TRY(fogrt__ld_floats(L, L->buf, L->buf + L->len, 1, v, 30, &n));
    if (n < 28)
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, fogrt__ld_line_at(L->buf, 1, L->buf + L->len - (L->len > 0 && L->buf[L->len - 1] == '\n')),
                              "camera file has %u numbers; CS184's format needs 28 (or 30 with the lens)", (unsigned)n);
    sw = v[25]; sh = v[26]; sd = v[27];
    memset(camera, 0, sizeof *camera);
    camera->position = fogrt__ld_v3(v[5], v[6], v[7]);
    camera->look_at = fogrt__ld_v3(v[8], v[9], v[10]);
    camera->up = fogrt__ld_v3(v[17], v[20], v[23]);
    if (!(sw > 0 && sh > 0 && sd > 0))
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, 5, "screenW, screenH and screenDist must be > 0");
    if (v[5] == v[8] && v[6] == v[9] && v[7] == v[10])
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, 2, "camera position equals its target");
    if (n >= 30 && (v[28] < 0 || v[29] < 0))
        return fogrt__ld_fail(L, FOGRT__LD_PARSE, 6, "focal distance and lens radius must not be negative");
    if (n >= 30) { camera->focal_distance = v[28]; camera->lens_radius = v[29]; }
    fogrt_load_fit_fov(0.5f * sh / sd, sw / sh, width, height, camera);
    FOGRT__LD_TRY(fogrt__ld_check_camera(L, camera));
    L->rep->camera = *camera;
    L->rep->frame_tan_half_y = 0.5f * sh / sd;
    L->rep->frame_aspect = sw / sh;
    L->rep->has_camera = true;
    return FOGRT_RESULT_OK;
}

/* ------------------------------------------------------------------------------------------
   14. Entry points: one path for every format, from a file or from memory
   ------------------------------------------------------------------------------------------ */
enum { FOGRT__LD_DAE, FOGRT__LD_OBJ, FOGRT__LD_PLY, FOGRT__LD_CAMERA };
/* What to read and where it goes: a scene, or (camera files) a camera framed for w x h. */
typedef struct fogrt__ld_job { int format; fogrt_scene *scene; fogrt_camera_desc *camera; int width, height; } fogrt__ld_job;

FOGRT__LD fogrt_result fogrt__ld_entry(const fogrt__ld_job *J, bool from_file, const char *path, const void *data, size_t size,
                                       const char *name, const fogrt_load_options *options, fogrt_load_report *report) {
    fogrt__ld L;
    fogrt_load_report dummy;
    fogrt_result r;
    if (!report) report = &dummy;
    r = fogrt__ld_init(&L, from_file && !path ? "(null)" : name, options, report);
    if (!r) r = fogrt__ld_open(&L, from_file, path, data, size);
    if (!r && J->format == FOGRT__LD_DAE) r = fogrt__ld_dae(&L, J->scene);
    if (!r && J->format == FOGRT__LD_OBJ) r = fogrt__ld_mesh_file(&L, J->scene, fogrt__ld_obj_parse);
    if (!r && J->format == FOGRT__LD_PLY) r = fogrt__ld_mesh_file(&L, J->scene, fogrt__ply_parse);
    if (!r && J->format == FOGRT__LD_CAMERA) r = fogrt__ld_camera_file(&L, J->width, J->height, J->camera);
    if (!r) fogrt__ld_flush_warnings(&L);
    if (!r) fogrt__ld_report_shapes(&L);
    fogrt__ld_destroy(&L);
    return r;
}
FOGRT__LD fogrt_result fogrt__ld_scene_entry(int format, fogrt_scene *scene, bool from_file, const char *path, const void *data, size_t size,
                                             const char *name, const fogrt_load_options *options, fogrt_load_report *report) {
    fogrt__ld_job J;
    memset(&J, 0, sizeof J);
    J.format = format; J.scene = scene;
    return fogrt__ld_entry(&J, from_file, path, data, size, name, options, report);
}
FOGRT__LD fogrt_result fogrt__ld_camera_entry(bool from_file, const char *path, const void *data, size_t size, const char *name,
                                              int width, int height, fogrt_camera_desc *camera, fogrt_load_report *report) {
    fogrt__ld_job J;
    memset(&J, 0, sizeof J);
    J.format = FOGRT__LD_CAMERA; J.camera = camera; J.width = width; J.height = height;
    return fogrt__ld_entry(&J, from_file, path, data, size, name, NULL, report);
}
FOGRT__LD_PUBLIC fogrt_result fogrt_load_camera_memory(const void *data, size_t size, const char *name,
                                                       int width, int height, fogrt_camera_desc *camera,
                                                       fogrt_load_report *report) {
    return fogrt__ld_camera_entry(false, NULL, data, size, name, width, height, camera, report);
}
FOGRT__LD_PUBLIC fogrt_result fogrt_load_camera_file(const char *path, int width, int height,
                                                     fogrt_camera_desc *camera, fogrt_load_report *report) {
    return fogrt__ld_camera_entry(true, path, NULL, 0, path, width, height, camera, report);
}
FOGRT__LD_PUBLIC fogrt_result fogrt_load_dae_memory(fogrt_scene *scene, const void *data, size_t size, const char *name,
                                                    const fogrt_load_options *options, fogrt_load_report *report) {
    return fogrt__ld_scene_entry(FOGRT__LD_DAE, scene, false, NULL, data, size, name, options, report);
}
FOGRT__LD_PUBLIC fogrt_result fogrt_load_obj_memory(fogrt_scene *scene, const void *data, size_t size, const char *name,
                                                    const fogrt_load_options *options, fogrt_load_report *report) {
    return fogrt__ld_scene_entry(FOGRT__LD_OBJ, scene, false, NULL, data, size, name, options, report);
}
FOGRT__LD_PUBLIC fogrt_result fogrt_load_ply_memory(fogrt_scene *scene, const void *data, size_t size, const char *name,
                                                    const fogrt_load_options *options, fogrt_load_report *report) {
    return fogrt__ld_scene_entry(FOGRT__LD_PLY, scene, false, NULL, data, size, name, options, report);
}
FOGRT__LD_PUBLIC fogrt_result fogrt_load_dae(fogrt_scene *scene, const char *path, const fogrt_load_options *options, fogrt_load_report *report) {
    return fogrt__ld_scene_entry(FOGRT__LD_DAE, scene, true, path, NULL, 0, path, options, report);
}
FOGRT__LD_PUBLIC fogrt_result fogrt_load_obj(fogrt_scene *scene, const char *path, const fogrt_load_options *options, fogrt_load_report *report) {
    return fogrt__ld_scene_entry(FOGRT__LD_OBJ, scene, true, path, NULL, 0, path, options, report);
}
FOGRT__LD_PUBLIC fogrt_result fogrt_load_ply(fogrt_scene *scene, const char *path, const fogrt_load_options *options, fogrt_load_report *report) {
    return fogrt__ld_scene_entry(FOGRT__LD_PLY, scene, true, path, NULL, 0, path, options, report);
}

/* Lower-case extension of path is ext. */
FOGRT__LD bool fogrt__ld_ext_is(const char *path, const char *ext) {
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
                                              fogrt_load_report *report) {
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
