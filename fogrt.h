/* fogrt.h - v0.1 - a Monte Carlo path tracer for scenes filled with homogeneous fog - MIT license

    fogrt renders triangle meshes and spheres inside one homogeneous participating medium
    ("fog") by path tracing. It implements, step by step and in the open, the model of the
    paper "Volumetric Ray Tracer in Homogeneous Media" (a CS184-based renderer): exponential
    free-flight sampling, Beer-Lambert attenuation, the Henyey-Greenstein phase function,
    the paper's Algorithm 1 with Russian roulette and next-event estimation, and its
    one-bounce direct lighting baseline. The file reads top to bottom like a book; see the
    chapter list at the start of the implementation.

    DO THIS
    =======
    In exactly one C or C++ file, before including this header:

        #define FOGRT_IMPLEMENTATION
        #include "fogrt.h"

    Everywhere else include it without the define. Link with -lm. Compile with -fopenmp to
    render on all cores (optional; without it fogrt renders on one thread).

    QUICK START
    ===========
        fogrt_scene *scene = NULL;
        fogrt_scene_create(NULL, &scene);          // NULL desc: default allocator
        fogrt_scene_add_default(scene);            // the fog-filled Cornell box
        fogrt_scene_build(scene, NULL);            // BVH + feature analysis
        fogrt_image img;
        fogrt_image_alloc(&img, 320, 240, NULL);   // NULL: default allocator
        fogrt_render_desc rd = fogrt_render_defaults();   // read back, change, pass on
        rd.max_depth = 16;
        fogrt_render(scene, &rd, &img, 64, NULL);   // add 64 samples per pixel
        float *rgb = malloc(sizeof(float) * 3 * 320 * 240);
        fogrt_image_resolve(&img, rgb);             // linear RGB mean
        fogrt_write_pfm("fog.pfm", 320, 240, rgb);
        fogrt_image_free(&img);
        fogrt_scene_destroy(scene);

    OPTIONS (define before including the implementation)
    =======
    FOGRT_API              prefix of every public declaration (default: extern)
    FOGRT_STATIC           make every function static (private to one translation unit)
    FOGRT_MALLOC(sz,u) / FOGRT_FREE(p,u)   default allocator (both or neither; default libc)
    FOGRT_ASSERT(c)        programmer-error check (default: assert)
    FOGRT_MINIMAL          compile Part I, the paper's renderer, with the API around it (Part
                           II, the appendix of speed, variance reduction and more, is left out;
                           fogrt_render_defaults() is then fogrt_render_paper_defaults())
    FOGRT_NO_WIDE_BVH      leave out appendix A, the wide BVH (the binary tree is traced)
    FOGRT_NO_LAMPS_IN_FOG  leave out appendix B: equiangular sampling, glow, footprint, expected
                           emission (render desc fields that ask for them fail)
    FOGRT_NO_ESTIMATION    leave out appendix C: environment-map sampling, exact Fresnel, fog in
                           a box, lights by power, the roulette's pilot, stratified pixel
                           positions, per-pixel rates (fogrt_image_sample_rates)
    FOGRT_NO_MEDIA         leave out appendix G, media beyond the paper: the two-lobe HG and
                           Rayleigh phase functions, emitting fog, sigma_t per colour channel
                           (a medium desc that asks for them fails)
    FOGRT_NO_SHAPES        leave out appendix H, media inside shapes (fogrt_scene_set_interior,
                           fogrt_scene_set_shape_material; the interface material fails;
                           implied by FOGRT_NO_MEDIA)
    FOGRT_NO_MICROFACET    leave out appendix I, rough metals (the microfacet material fails)
    FOGRT_NO_MEDIUM        strip the fog: no free-flight, transmittance, phase or equiangular
                           code (fogrt_scene_set_medium with sigma_t > 0 fails; implies
                           FOGRT_NO_MEDIA)
    FOGRT_NO_GLASS         strip the refraction and glass BSDFs, Fresnel and refraction
                           (fogrt_scene_add_material of those types fails)
    FOGRT_NO_EXACT_FRESNEL strip the exact dielectric Fresnel (a render asking for
                           FOGRT_FRESNEL_EXACT fails)
                           One policy for all of these: what needs a stripped feature returns
                           FOGRT_RESULT_UNSUPPORTED and logs one line naming the macro; the
                           stripped public functions are not compiled (make check-compile
                           checks with nm that their code is gone).
    FOGRT_NO_STDIO         strip the PFM/PPM writers (no <stdio.h>)
    FOGRT_TRACE            compile the path event trace (fogrt_trace_path); off: no hook exists
    FOGRT_BVH_BINS         compile-time default for fogrt_build_desc.bins (8)
    FOGRT_WBVH_WIDTH       children per node of the wide BVH, 4 or 8 (8)
    FOGRT_WBVH_LEAF        largest binary subtree the wide BVH makes one leaf, 0..8 (4)
    FOGRT_WBVH_SMALL_SCENE a scene of at most this many primitives merges no leaves (64)
    FOGRT_WBVH_NO_SIMD     plain C99 loops for the wide BVH instead of SSE2 (same results)
    FOGRT_WBVH_NO_AVX2     no AVX2 path for the wide BVH (by default used when the processor
                           has it: chosen at fogrt_scene_build on GCC/Clang x86-64; same results)
    FOGRT_WBVH_MIN_PRIMS   the default layout is wide from this many primitives (1: always)
    FOGRT_MAX_PATH_VERTICES  hard cap on path vertices, a safety net behind Russian roulette
                           (default 100000; never reached in practice, see Russian roulette)

    CONVENTIONS
    ===========
    - Right-handed world, y up by convention (the camera's up vector says which way is up).
    - Units: distances in scene units; sigma_t (the paper's lambda) per scene unit.
    - Colours are linear RGB floats. Light intensity is radiant intensity (W/sr per channel);
      emission is radiance.
    - Directions: wo and wi both point AWAY from the interaction point (pbrt, Mitsuba). The
      ray arriving at a point travels along d = -wo.
    - Henyey-Greenstein: g > 0 scatters FORWARD, i.e. toward the propagation direction d;
      the mean cosine between d and the new direction equals g.
    - BSDF functions work in a local shading frame whose normal is +z. wo.z < 0 means the
      ray arrives from the back (inside a refractive object).
    - Triangles: counter-clockwise winding (seen from the front) gives the front side. Area
      lights emit from the front side only. Reflecting surfaces are two-sided. Refractive
      surfaces use the front (outward) side to tell entering from leaving.
    - The medium fills all space outside refractive objects (or, bounded, its box outside
      them): a ray that refracts into a glass or refraction object travels without fog until
      it leaves it. Unbounded, the camera sits in the fog; bounded, it may be outside.
    - Environment maps are equirectangular as CS184 maps them: theta = acos(y) down the rows
      from +y, phi = atan2(-z, x) + pi across the columns.

    ERRORS AND LOGGING
    ==================
    Every fallible call returns fogrt_result (FOGRT_RESULT_OK == 0); fogrt_result_string()
    names it. Bad data (negative density, |g| > 1, NaN positions, ...) returns an error and
    leaves the scene as it was. A NULL pointer where one is required is a programmer error
    and hits FOGRT_ASSERT. An optional logger in fogrt_scene_desc receives one-line messages
    (warnings and errors naming the parameter); fogrt is silent without it.

    MEMORY
    ======
    All memory comes from the allocator in fogrt_scene_desc (NULL functions = FOGRT_MALLOC).
    The scene copies the arrays it is given. The image (accumulation buffer) is a plain
    struct the caller may fill with its own arrays or allocate with fogrt_image_alloc. No
    globals, no hidden state: every random number comes from a stream derived from
    (seed, pixel, sample index), so an image is the same bit for bit on 1 or N threads.

    WHAT FOGRT DOES NOT DO
    ======================
    Heterogeneous media (sigma_t is the same everywhere), textures, rough dielectrics,
    spectral rendering, instancing, motion blur, GPU. Nested refractive objects are tracked
    only in a scene with media inside shapes (Part II, H); elsewhere leaving any refractive
    object puts the ray back into the fog.

    LICENSE
    =======
    MIT, see the end of the file.
*/
#ifndef FOGRT_H_INCLUDED
#ifdef FOGRT_MINIMAL            /* Part I alone: every appendix of Part II removed */
#ifndef FOGRT_NO_WIDE_BVH
#define FOGRT_NO_WIDE_BVH
#endif
#ifndef FOGRT_NO_LAMPS_IN_FOG
#define FOGRT_NO_LAMPS_IN_FOG
#endif
#ifndef FOGRT_NO_ESTIMATION
#define FOGRT_NO_ESTIMATION
#endif
#ifndef FOGRT_NO_MEDIA
#define FOGRT_NO_MEDIA
#endif
#ifndef FOGRT_NO_MICROFACET
#define FOGRT_NO_MICROFACET
#endif
#endif
#if defined(FOGRT_NO_MEDIUM) && !defined(FOGRT_NO_MEDIA)
#define FOGRT_NO_MEDIA           /* media beyond the paper (G) need the fog */
#endif
#if defined(FOGRT_NO_MEDIA) && !defined(FOGRT_NO_SHAPES)
#define FOGRT_NO_SHAPES          /* media inside shapes (H) use G's phase functions and emission */
#endif
#if defined(FOGRT_NO_ESTIMATION) && !defined(FOGRT_NO_EXACT_FRESNEL)
#define FOGRT_NO_EXACT_FRESNEL   /* the exact Fresnel is Part II's (C) */
#endif
#define FOGRT_H_INCLUDED

#include <stddef.h>
#include <stdint.h>
#include <stdbool.h>

#ifndef FOGRT_API
#ifdef FOGRT_STATIC
#define FOGRT_API static
#else
#define FOGRT_API extern
#endif
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------------------------------
   Results
   One X-macro list makes both the enum and the message table, so they never drift apart.
   ------------------------------------------------------------------------------------------ */
#define FOGRT__RESULT_LIST(X) \
    X(OK,                "ok") \
    X(OUT_OF_MEMORY,     "out of memory") \
    X(INVALID_ARGUMENT,  "invalid argument") \
    X(INVALID_MATERIAL,  "invalid material (index out of range, or a non-finite or negative colour, or ior <= 0, or a microfacet alpha <= 0)") \
    X(INVALID_GEOMETRY,  "invalid geometry (non-finite position, index out of range, or radius <= 0)") \
    X(INVALID_LIGHT,     "invalid light (non-finite or negative intensity, or bad angles)") \
    X(INVALID_CAMERA,    "invalid camera (fov outside (0,180), eye equals target, or negative lens)") \
    X(INVALID_MEDIUM,    "invalid medium (sigma_t negative or non-finite, albedo outside [0,1], |g| > 1, or a bad phase, emission or sigma_t_rgb)") \
    X(TOO_LARGE,         "too large (more primitives, lights or pixels than fogrt can index)") \
    X(NOT_BUILT,         "scene not built: call fogrt_scene_build after the last change") \
    X(EMPTY_SCENE,       "the scene has no geometry and no light") \
    X(IO_ERROR,          "file could not be opened, read or written") \
    X(PARSE_ERROR,       "file is malformed") \
    X(UNSUPPORTED,       "feature not supported (or stripped at compile time)") \
    X(CANCELLED,         "cancelled by the progress callback")

typedef enum fogrt_result {
#define FOGRT__RESULT_ENUM(name, text) FOGRT_RESULT_##name,
    FOGRT__RESULT_LIST(FOGRT__RESULT_ENUM)
#undef FOGRT__RESULT_ENUM
    FOGRT_RESULT_NUM,
    FOGRT_RESULT_FORCE_U32 = 0x7FFFFFFF
} fogrt_result;

/* A short English sentence for a result code (never NULL). */
FOGRT_API const char *fogrt_result_string(fogrt_result result);

/* ------------------------------------------------------------------------------------------
   Small value types
   ------------------------------------------------------------------------------------------ */
typedef struct fogrt_vec3 { float x, y, z; } fogrt_vec3;

typedef struct fogrt_allocator {
    void *(*alloc_fn)(size_t size, void *user_data);  /* NULL: FOGRT_MALLOC */
    void (*free_fn)(void *ptr, void *user_data);      /* NULL: FOGRT_FREE */
    void *user_data;
} fogrt_allocator;

typedef enum fogrt_log_level {
    FOGRT_LOG_DEFAULT = 0, FOGRT_LOG_ERROR, FOGRT_LOG_WARNING, FOGRT_LOG_INFO,
    FOGRT_LOG_NUM, FOGRT_LOG_FORCE_U32 = 0x7FFFFFFF
} fogrt_log_level;

typedef struct fogrt_logger {
    void (*func)(fogrt_log_level level, const char *message, void *user_data); /* NULL: silent */
    void *user_data;
} fogrt_logger;

/* ------------------------------------------------------------------------------------------
   Scene description
   ------------------------------------------------------------------------------------------ */
typedef struct fogrt_scene fogrt_scene;   /* opaque; create with fogrt_scene_create */

/* fogrt_scene_desc (all zero = defaults)
     allocator   NULL functions: FOGRT_MALLOC / FOGRT_FREE
     logger      NULL: silent                                                              */
typedef struct fogrt_scene_desc {
    fogrt_allocator allocator;
    fogrt_logger logger;
} fogrt_scene_desc;

FOGRT_API fogrt_result fogrt_scene_create(const fogrt_scene_desc *desc, fogrt_scene **out_scene);
FOGRT_API void fogrt_scene_destroy(fogrt_scene *scene);   /* NULL is a no-op */

/* The paper's four BSDFs (diffuse, mirror, refraction, glass), a rough metal (Part II, I) and
   an interface (Part II, H). The ones that only reflect come before FOGRT_BSDF_REFRACTION:
   the renderer tells the two kinds apart by that order. */
typedef enum fogrt_bsdf_type {
    FOGRT_BSDF_DEFAULT = 0,   /* = diffuse */
    FOGRT_BSDF_DIFFUSE,       /* Lambertian, f = reflectance / pi */
    FOGRT_BSDF_MIRROR,        /* perfect specular reflection, tinted by reflectance */
    FOGRT_BSDF_MICROFACET,    /* rough conductor: Beckmann microfacets of width alpha, the
                                 complex index eta + i k per channel (CS184's; Part II, I) */
    FOGRT_BSDF_REFRACTION,    /* specular transmission only; total internal reflection reflects */
    FOGRT_BSDF_GLASS,         /* reflect with probability F (Fresnel), else refract */
    FOGRT_BSDF_INTERFACE,     /* index-matched: light passes straight through (the surface of a
                                 fog volume of any shape, fogrt_scene_set_interior; Part II, H) */
    FOGRT_BSDF_NUM,
    FOGRT_BSDF_FORCE_U32 = 0x7FFFFFFF
} fogrt_bsdf_type;

/* fogrt_material_desc
     type           FOGRT_BSDF_DEFAULT = diffuse
     reflectance    diffuse albedo / mirror and glass reflection tint (zero is black, not a default)
     transmittance  refraction and glass transmission tint
     emission       radiance emitted from the front side; non-zero makes every primitive
                    with this material an area light
     ior            index of refraction inside the object relative to outside; 0 = 1.5
     alpha          microfacet: Beckmann width, the rms slope of the microfacets (> 0; used
                    clamped to [1e-4, 1e3]): 0.05 nearly polished, 0.5 rough
     eta, k         microfacet: the metal's complex index of refraction eta + i k per colour
                    channel (>= 0), whose Fresnel reflectance colours it (reflectance is not
                    read); eta = k = 0 reflects everything at every angle                   */
typedef struct fogrt_material_desc {
    fogrt_bsdf_type type;
    fogrt_vec3 reflectance;
    fogrt_vec3 transmittance;
    fogrt_vec3 emission;
    float ior;
    float alpha;
    fogrt_vec3 eta;
    fogrt_vec3 k;
} fogrt_material_desc;

FOGRT_API fogrt_result fogrt_scene_add_material(fogrt_scene *scene, const fogrt_material_desc *desc,
                                                uint32_t *out_material_id);

/* fogrt_mesh_desc
     positions            3 floats per vertex (required)
     normals              3 floats per vertex, optional shading normals (NULL: flat shading)
     vertex_count
     indices              3 per triangle; NULL: vertices 0,1,2 / 3,4,5 / ... form the triangles
     triangle_count
     material             material id of every triangle ...
     triangle_materials   ... unless this per-triangle array is given                       */
typedef struct fogrt_mesh_desc {
    const float *positions;
    const float *normals;
    uint32_t vertex_count;
    const uint32_t *indices;
    uint32_t triangle_count;
    uint32_t material;
    const uint32_t *triangle_materials;
} fogrt_mesh_desc;

/* Adds a mesh. Degenerate (zero-area) triangles are kept but can never be hit. */
FOGRT_API fogrt_result fogrt_scene_add_mesh(fogrt_scene *scene, const fogrt_mesh_desc *desc);
FOGRT_API fogrt_result fogrt_scene_add_sphere(fogrt_scene *scene, fogrt_vec3 center, float radius,
                                              uint32_t material);

typedef enum fogrt_light_type {
    FOGRT_LIGHT_DEFAULT = 0,  /* = point */
    FOGRT_LIGHT_POINT,
    FOGRT_LIGHT_SPOT,
    FOGRT_LIGHT_NUM,
    FOGRT_LIGHT_FORCE_U32 = 0x7FFFFFFF
} fogrt_light_type;

/* fogrt_light_desc: point and spot lights (area lights are emissive materials).
     position, intensity  radiant intensity I (per channel); irradiance falls off as I / r^2
     direction            spot axis (need not be unit length)
     cutoff_deg           spot: half-angle where the intensity reaches zero (0..180)
     beam_deg             spot: half-angle of full intensity (0..cutoff). Between the two the
                          intensity falls linearly in the angle:
                          I(theta) = I * clamp((cutoff - theta) / (cutoff - beam), 0, 1)
                          (beam == cutoff: a hard-edged cone)
     radius               > 0: the light becomes a small spherical emitter of this radius, the
                          paper's proposed fix for hard-edged spot shadows: uniform radiance
                          I(theta) / (pi radius^2), so that from afar it gives the same I / r^2,
                          but soft shadows, and bounded light near it (no 1/r^2 spike in the
                          fog). It is sampled by solid angle and lights the scene through
                          next-event estimation only (camera rays do not see the sphere).   */
typedef struct fogrt_light_desc {
    fogrt_light_type type;
    fogrt_vec3 position;
    fogrt_vec3 direction;
    fogrt_vec3 intensity;
    float cutoff_deg;
    float beam_deg;
    float radius;
} fogrt_light_desc;

FOGRT_API fogrt_result fogrt_scene_add_light(fogrt_scene *scene, const fogrt_light_desc *desc);

/* Constant radiance arriving from infinity (rays that escape). upper_hemisphere_only: only
   rays escaping with an upward (+y) direction see it (the CS184 <ambient> light).         */
FOGRT_API fogrt_result fogrt_scene_set_environment(fogrt_scene *scene, fogrt_vec3 radiance,
                                                   bool upper_hemisphere_only);
/* An environment map: radiance from infinity by direction, an equirectangular image of
   width x height linear RGB floats (3 per pixel, row 0 at the top) times scale, mapped as
   CS184 maps its -e map: theta = acos(y) runs down the rows from +y, phi = atan2(-z, x) + pi
   across the columns. It replaces the constant environment, is sampled by next-event
   estimation in proportion to luminance x sin(theta), and is combined with BSDF and phase
   sampling by MIS. The scene copies the image; NULL rgb removes the map.               */
#ifndef FOGRT_NO_ESTIMATION
FOGRT_API fogrt_result fogrt_scene_set_environment_map(fogrt_scene *scene, int width, int height,
                                                       const float *rgb, float scale);   /* Part II, C */
#endif

/* fogrt_camera_desc
     position, look_at    eye and target (must differ)
     up                   zero: +y
     fov_deg              field of view; 0 = 45
     fov_is_horizontal    false: fov_deg is the vertical fov; true: horizontal
     lens_radius          0 = pinhole; > 0 thin lens
     focal_distance       thin lens: distance of the plane in focus; 0 = |look_at - position|  */
typedef struct fogrt_camera_desc {
    fogrt_vec3 position;
    fogrt_vec3 look_at;
    fogrt_vec3 up;
    float fov_deg;
    bool fov_is_horizontal;
    float lens_radius;
    float focal_distance;
} fogrt_camera_desc;

FOGRT_API fogrt_result fogrt_scene_set_camera(fogrt_scene *scene, const fogrt_camera_desc *desc);

/* fogrt_medium_desc: the one homogeneous medium of the scene.
     sigma_t   extinction coefficient sigma_t = sigma_a + sigma_s (the paper's lambda), per
               scene unit; 0 = no medium (the renderer then pays nothing for fog)
     albedo    single-scattering albedo sigma_s / sigma_t per channel, in [0,1]
     g         Henyey-Greenstein asymmetry in [-1,1]; g > 0 forward. |g| >= FOGRT_HG_G_MAX
               (0.9999) is clamped to +-FOGRT_HG_G_MAX and a warning is logged
     bounded   false: the fog fills all space (outside refractive objects); true: only the
               axis-aligned box [bounds_min, bounds_max]. Rays leave the fog at the box and
               reach the environment with the transmittance of their path inside; the camera
               may sit outside it. A scene with an environment light and unbounded fog gets
               the box of its geometry at fogrt_scene_build (logged), since fog filling all
               space would hide the sky completely.
   Part II, G (zeroed: Henyey-Greenstein with g and no emission, the paper's medium):
     phase     FOGRT_PHASE_HG (0): HG(g); FOGRT_PHASE_HG2: two lobes, w HG(g) + (1 - w) HG(g2)
               (forward and back scattering of droplets); FOGRT_PHASE_RAYLEIGH:
               3 / (16 pi) (1 + mu^2), for haze (g, g2 and w unused)
     g2, w     the second lobe's asymmetry in [-1, 1] (clamped as g is) and the first lobe's
               weight in [0, 1]; validated whatever the phase, read by FOGRT_PHASE_HG2 only
     emission  radiance Le the fog emits (linear RGB, >= 0), added as sigma_a Le per unit
               length with sigma_a = sigma_t (1 - albedo): unbounded fog of any albedo below 1
               seen from inside looks Le, an absorbing slab of optical depth tau Le (1 - e^-tau)
     sigma_t_rgb  sigma_t per colour channel (each >= 0, finite): chromatic fog, whose light
               of each channel is attenuated and scattered at that channel's rate (coloured
               haze). Zero: sigma_t for all three. Set, it replaces sigma_t, which reads back
               as its largest component; three equal components are grey fog of that sigma_t
               (stored as sigma_t, this field zeroed), rendered as such bit for bit
   Fog with another phase function, emission or sigma_t per channel is rendered by the full
   integrator (Part II, E) also under fogrt_render_paper_defaults(): Part I knows grey HG fog
   alone.                                                                                     */
typedef enum fogrt_phase_type {
    FOGRT_PHASE_HG = 0,        /* Henyey-Greenstein (3.3) */
    FOGRT_PHASE_HG2,           /* two HG lobes (G) */
    FOGRT_PHASE_RAYLEIGH,      /* Rayleigh (G) */
    FOGRT_PHASE_NUM,
    FOGRT_PHASE_FORCE_U32 = 0x7FFFFFFF
} fogrt_phase_type;
typedef struct fogrt_medium_desc {
    float sigma_t;
    fogrt_vec3 albedo;
    float g;
    bool bounded;
    fogrt_vec3 bounds_min, bounds_max;
    fogrt_phase_type phase;    /* G */
    float g2, w;               /* G: FOGRT_PHASE_HG2's second lobe and the first lobe's weight */
    fogrt_vec3 emission;       /* G: Le, radiance */
    fogrt_vec3 sigma_t_rgb;    /* G: sigma_t per channel (zero: sigma_t in all three) */
} fogrt_medium_desc;

#define FOGRT_HG_G_MAX 0.9999f

FOGRT_API fogrt_result fogrt_scene_set_medium(fogrt_scene *scene, const fogrt_medium_desc *desc);

/* Media inside shapes (Part II, H; FOGRT_NO_SHAPES leaves them out). A closed mesh or a
   sphere may hold a homogeneous medium of its own, filling the space its surface encloses:
   with a refractive or glass material that is a filled glass (smoke in a glass sphere), with
   FOGRT_BSDF_INTERFACE a fog volume of that shape (concave ones too). Shapes are meshes,
   numbered from 0 in the order fogrt_scene_add_mesh added them (fogrt_scene_info's
   mesh_count), and spheres, numbered in the order fogrt_scene_add_sphere added them.
   desc NULL takes the medium out again. The desc is checked as fogrt_scene_set_medium's
   (bounded must be false). Media may nest (a filled glass inside the room's fog, a shape
   inside a shape); fogrt_scene_build refuses a medium on a mesh with an open edge and two
   media whose shapes overlap without one holding the other, and finds the medium the camera
   is in. The world's medium (fogrt_scene_set_medium) fills the space no shape holds; the
   inside of a refractive shape without a medium of its own is empty (as in Part I), that of
   an interface shape without one is its surroundings' medium (the shape is invisible). A
   shape's surface must not lie in another surface (a fog box standing exactly on the floor):
   a ray crossing both there meets them in either order.
   A scene with such media is rendered by H's path tracer (light sampling and MIS as
   Algorithm 1, shadow rays through interface surfaces with each medium's transmittance). */
typedef enum fogrt_shape_kind { FOGRT_SHAPE_MESH = 0, FOGRT_SHAPE_SPHERE, FOGRT_SHAPE_NUM } fogrt_shape_kind;
#ifndef FOGRT_NO_SHAPES
FOGRT_API fogrt_result fogrt_scene_set_interior(fogrt_scene *scene, fogrt_shape_kind kind, uint32_t index,
                                               const fogrt_medium_desc *desc);   /* Part II, H */
/* Gives every triangle of mesh index (or sphere index) the material: a shape that a loader
   added can become an interface (FOGRT_BSDF_INTERFACE) once its number is known, without
   adding it again. */
FOGRT_API fogrt_result fogrt_scene_set_shape_material(fogrt_scene *scene, fogrt_shape_kind kind, uint32_t index,
                                                     uint32_t material);   /* Part II, H */
#endif

/* Adds the embedded default scene: the CS184 Cornell box (walls x = +-1, z = +-1, floor
   y = 0, ceiling y = 1.5, red left wall, blue right wall, ceiling area light), a diffuse
   sphere, a glass sphere, a spot light, fog (sigma_t 0.3, albedo 0.9, g 0.6) and a camera.
   (Built with FOGRT_NO_MEDIUM: the same scene without fog; with FOGRT_NO_GLASS the glass
   sphere is a mirror.) */
FOGRT_API fogrt_result fogrt_scene_add_default(fogrt_scene *scene);

/* ------------------------------------------------------------------------------------------
   Build: BVH and feature analysis
   ------------------------------------------------------------------------------------------ */
typedef enum fogrt_bvh_heuristic {
    FOGRT_BVH_DEFAULT = 0,    /* = SAH */
    FOGRT_BVH_SAH,            /* surface area heuristic: c_trav + c_int (A_l N_l + A_r N_r) / A */
    FOGRT_BVH_VOLUME,         /* the paper's volume heuristic: H = N_l V_l + N_r V_r */
    FOGRT_BVH_NUM,
    FOGRT_BVH_FORCE_U32 = 0x7FFFFFFF
} fogrt_bvh_heuristic;

#ifndef FOGRT_BVH_BINS
#define FOGRT_BVH_BINS 8
#endif

/* fogrt_build_desc. Start from fogrt_build_defaults(): every field then means what it says
   (a desc that did not come from it is refused; NULL means the defaults).
     heuristic       SAH
     bins            FOGRT_BVH_BINS (8); 1..64 (1: one candidate plane per axis, at the
                     middle of the centroid bounds)
     c_trav, c_int   traversal and intersection cost of the SAH, 1 and 1
     max_leaf_size   4 (>= 1): largest leaf; a node is also split when the SAH prefers it
     layout          default: wide (it pays at every size, from a 14-primitive box up:
                     docs/benchmarks.md, "Wide BVH"); wide: the binary tree collapsed to 8
                     children per node for tracing; binary: traced as built. fogrt_scene_get_bvh and
                     fogrt_bvh_sah_cost describe the binary tree.
     roulette_pilot  true: the build ends with the roulette's pilot (Part II, C: one or two
                     passes of 12288 camera paths in a scene with a light, tens of
                     milliseconds), which sets the roulette's k for the scene's renders;
                     false: k = 1 (q = throughput), for a build timed alone or a scene
                     rebuilt every frame
     release_binary  false; true: with the wide layout, the binary tree is freed as soon as
                     the wide tree holds what it needs of it (about 24 bytes per primitive
                     less, also at the build's peak); fogrt_scene_get_bvh then gives no
                     tree and fogrt_bvh_sah_cost 0. For a program that only renders (the
                     fogrt command)
     resolved        set by fogrt_build_defaults(): the fields hold their real values      */
typedef enum fogrt_bvh_layout {
    FOGRT_BVH_LAYOUT_DEFAULT = 0,   /* wide from FOGRT_WBVH_MIN_PRIMS (1) primitives, else binary */
    FOGRT_BVH_LAYOUT_BINARY,        /* trace the binary tree of the build (2.1) */
    FOGRT_BVH_LAYOUT_WIDE,          /* collapse it to 8 children per node (Part II, A): faster */
    FOGRT_BVH_LAYOUT_NUM,
    FOGRT_BVH_LAYOUT_FORCE_U32 = 0x7FFFFFFF
} fogrt_bvh_layout;

typedef struct fogrt_build_desc {
    fogrt_bvh_heuristic heuristic;
    int bins;
    float c_trav;
    float c_int;
    int max_leaf_size;
    fogrt_bvh_layout layout;
    bool roulette_pilot;
    bool release_binary;
    bool resolved;
} fogrt_build_desc;

/* The defaults, resolved: read them back, change what you need, pass the desc on. */
FOGRT_API fogrt_build_desc fogrt_build_defaults(void);
/* NULL desc: the defaults. */
FOGRT_API fogrt_result fogrt_scene_build(fogrt_scene *scene, const fogrt_build_desc *desc);

/* BVH node, 32 bytes (tinybvh's layout). A leaf iff prim_count > 0; its primitives are
   prim_index[left_first .. left_first + prim_count). An inner node's children are nodes
   left_first and left_first + 1. Node 0 is the root; node 1 is unused, so that every
   sibling pair starts on an even index. Primitive ids: triangles first (0..T-1), then
   spheres (T..T+S-1).                                                                      */
typedef struct fogrt_bvh_node {
    float bmin[3]; uint32_t left_first;
    float bmax[3]; uint32_t prim_count;
} fogrt_bvh_node;

#ifndef FOGRT_MINIMAL   /* inspection (Part II): the tree, its cost, memory, a brute-force query */
FOGRT_API void fogrt_scene_get_bvh(const fogrt_scene *scene, const fogrt_bvh_node **nodes,
                                   uint32_t *node_count, const uint32_t **prim_index);
/* SAH cost of the built tree (1 per inner node, 1 per primitive in a leaf, each weighted by
   its box's surface area relative to the root): lets the SAH and the volume heuristic be
   compared on equal terms, whatever c_trav and c_int the build used. */
FOGRT_API float fogrt_bvh_sah_cost(const fogrt_scene *scene);
#endif

/* What the built scene uses (0 before its first build); the integrator skips everything else. */
enum {
    FOGRT_FEATURE_MEDIUM      = 1u << 0,  /* sigma_t > 0 */
    FOGRT_FEATURE_FRESNEL     = 1u << 1,  /* a glass material is used */
    FOGRT_FEATURE_REFRACTION  = 1u << 2,  /* a refraction or glass material is used */
    FOGRT_FEATURE_AREA_LIGHTS = 1u << 3,
    FOGRT_FEATURE_POINT_LIGHTS= 1u << 4,  /* point or spot */
    FOGRT_FEATURE_SPOT_LIGHTS = 1u << 5,
    FOGRT_FEATURE_ENVIRONMENT = 1u << 6,
    FOGRT_FEATURE_SPHERES     = 1u << 7,
    FOGRT_FEATURE_TRIANGLES   = 1u << 8
};
FOGRT_API uint32_t fogrt_scene_get_features(const fogrt_scene *scene);

/* Counts and read-back, for tools and tests. */
typedef struct fogrt_scene_info {
    uint32_t triangle_count, sphere_count, material_count;
    uint32_t mesh_count;         /* fogrt_scene_add_mesh calls that added triangles */
    uint32_t light_count;        /* point + spot lights */
    uint32_t area_light_count;   /* emissive meshes + emissive spheres (after build) */
    fogrt_vec3 bounds_min, bounds_max;   /* of all geometry (after build) */
    bool has_environment;
    bool built;
} fogrt_scene_info;
FOGRT_API void fogrt_scene_get_info(const fogrt_scene *scene, fogrt_scene_info *info);
/* The message of the last call on this scene that failed (what the logger was told), or ""
   before any failed: the precise reason, also without a logger. */
FOGRT_API const char *fogrt_scene_last_error(const fogrt_scene *scene);
FOGRT_API fogrt_result fogrt_scene_get_material(const fogrt_scene *scene, uint32_t id, fogrt_material_desc *out);
FOGRT_API fogrt_result fogrt_scene_get_light(const fogrt_scene *scene, uint32_t index, fogrt_light_desc *out);
FOGRT_API void fogrt_scene_get_camera(const fogrt_scene *scene, fogrt_camera_desc *out);
FOGRT_API void fogrt_scene_get_medium(const fogrt_scene *scene, fogrt_medium_desc *out);
/* Material of triangle i (i < triangle_count) or sphere i - triangle_count. */
FOGRT_API uint32_t fogrt_scene_get_prim_material(const fogrt_scene *scene, uint32_t prim);
#ifndef FOGRT_MINIMAL
/* Bytes the scene's arrays hold: geometry, materials and lights, and once built the BVH(s)
   and the light and environment tables (used sizes; spare capacity not counted). */
FOGRT_API size_t fogrt_scene_get_memory(const fogrt_scene *scene);
#endif

/* ------------------------------------------------------------------------------------------
   Ray queries (after fogrt_scene_build)
   ------------------------------------------------------------------------------------------ */
typedef struct fogrt_hit {
    float t;            /* distance along the (unit) direction */
    uint32_t prim;      /* primitive id (triangles first, then spheres) */
    float u, v;         /* barycentrics of vertices 1 and 2 (triangles) */
} fogrt_hit;

/* Closest hit with tmin < t < tmax; d must be unit length. Returns false on a miss. */
FOGRT_API bool fogrt_scene_intersect(const fogrt_scene *scene, fogrt_vec3 o, fogrt_vec3 d,
                                     float tmin, float tmax, fogrt_hit *hit);
/* Any hit with tmin < t < tmax (shadow rays). */
FOGRT_API bool fogrt_scene_occluded(const fogrt_scene *scene, fogrt_vec3 o, fogrt_vec3 d,
                                    float tmin, float tmax);
#ifndef FOGRT_MINIMAL
/* The same closest-hit answer by testing every primitive: the reference for BVH tests. */
FOGRT_API bool fogrt_scene_intersect_brute(const fogrt_scene *scene, fogrt_vec3 o, fogrt_vec3 d,
                                           float tmin, float tmax, fogrt_hit *hit);
#endif

/* ------------------------------------------------------------------------------------------
   Building blocks of an integrator (after fogrt_scene_build): Part I's Algorithm 1 is made
   of them, and with fogrt_render_desc.radiance an integrator of your own can be too.
   ------------------------------------------------------------------------------------------ */
/* The surface point a ray (o, unit d) hit, as a scattering vertex sees it. */
typedef struct fogrt_surface {
    fogrt_vec3 p;           /* the hit point */
    fogrt_vec3 ng;          /* geometric normal: on the ray's side for reflective BSDFs, outward
                               for refractive ones (then dot(-d, ng) < 0 means "from inside") */
    fogrt_vec3 s, t, n;     /* shading frame, n the shading normal: the BSDF functions take a
                               direction w as (dot(w, s), dot(w, t), dot(w, n)) */
    fogrt_material_desc material;
    bool front;             /* d arrived against the outward normal: emission counts only then */
} fogrt_surface;
FOGRT_API void fogrt_scene_surface(const fogrt_scene *scene, fogrt_vec3 o, fogrt_vec3 d, const fogrt_hit *hit,
                                   fogrt_surface *out);
/* The origin of a ray leaving surface point sf along w: p pushed off the surface to w's side,
   so that the new ray does not hit the surface it starts on. */
FOGRT_API fogrt_vec3 fogrt_surface_offset(const fogrt_scene *scene, const fogrt_surface *sf, fogrt_vec3 w);

/* A light sample seen from a point (paper eq. 3 with light sampling, section 2.3). */
typedef struct fogrt_light_sample {
    fogrt_vec3 wi;          /* unit direction toward the sampled point of the light */
    float dist;             /* distance to that point */
    fogrt_vec3 Le;          /* radiance arriving along -wi; for a point or spot light I / r^2 */
    float pdf;              /* solid-angle density of wi; 1 for point and spot lights */
    bool is_delta;          /* point or spot light: no other sampler can find it (no MIS) */
} fogrt_light_sample;
/* How many lights there are to sample: the point and spot lights, then the area lights
   (emissive meshes and spheres), numbered in that order. */
FOGRT_API uint32_t fogrt_scene_light_total(const fogrt_scene *scene);
/* Samples light `light` (< fogrt_scene_light_total) as seen from p, with three uniforms in
   [0, 1). False when p gets nothing from that sample (behind an emitter, outside a spot). */
FOGRT_API bool fogrt_scene_sample_light(const fogrt_scene *scene, uint32_t light, fogrt_vec3 p, float u1,
                                        float u2, float u3, fogrt_light_sample *out);
/* The solid-angle density with which fogrt_scene_sample_light would have produced the point
   that the ray from `from` hit (hit, sf from fogrt_scene_surface): MIS's partner of BSDF and
   phase sampling. 0 when that surface is not an area light. */
FOGRT_API float fogrt_scene_light_pdf(const fogrt_scene *scene, fogrt_vec3 from, const fogrt_hit *hit,
                                      const fogrt_surface *sf);
/* Whether nothing blocks the light sample ls taken from p: sf is the surface p lies on (for
   the shadow ray's offset), NULL for a point in the fog. Visibility only: the fog's
   transmittance (3.2) is the caller's to multiply. */
FOGRT_API bool fogrt_scene_visible(const fogrt_scene *scene, const fogrt_surface *sf, fogrt_vec3 p,
                                   const fogrt_light_sample *ls);

/* Ray-triangle (Moller-Trumbore) and ray-sphere tests on their own. */
FOGRT_API bool fogrt_intersect_triangle(fogrt_vec3 v0, fogrt_vec3 v1, fogrt_vec3 v2, fogrt_vec3 o,
                                        fogrt_vec3 d, float tmin, float tmax, float *t, float *u, float *v);
FOGRT_API bool fogrt_intersect_sphere(fogrt_vec3 center, float radius, fogrt_vec3 o, fogrt_vec3 d,
                                      float tmin, float tmax, float *t);

/* ------------------------------------------------------------------------------------------
   Sampling routines: pure functions of their uniform numbers u in [0,1).
   Naming: fogrt_sample_X (the sampler), fogrt_X_pdf (its density), fogrt_X_cdf (its CDF).
   ------------------------------------------------------------------------------------------ */
#ifndef FOGRT_NO_MEDIUM
/* Free flight (paper eq. 4-6): t = -ln(1 - u) / sigma_t, written with log1p.
   sigma_t = 0 returns +infinity (the ray never collides).                                  */
FOGRT_API float fogrt_sample_exponential(float sigma_t, float u);
FOGRT_API float fogrt_exponential_pdf(float sigma_t, float t);        /* sigma_t exp(-sigma_t t) */
FOGRT_API float fogrt_exponential_cdf(float sigma_t, float t);        /* 1 - exp(-sigma_t t) */
/* The same CDF under a second name, so that code calling it by that name compiles. */
FOGRT_API float fogrt_invert_exponential(float sigma_t, float t);
/* Beer-Lambert transmittance (paper eq. 7-8): T = exp(-sigma_t d). */
FOGRT_API float fogrt_transmittance(float sigma_t, float distance);

/* Henyey-Greenstein (paper eq. 9-12), physics convention: mu = cos(d, new direction).
   p(mu) = (1 - g^2) / (4 pi (1 + g^2 - 2 g mu)^1.5)  per steradian.                        */
FOGRT_API float fogrt_hg_phase(float g, float mu);
/* Inverse-CDF sample of mu, in a form with no division by g (exact at g = 0, stable at
   |g| -> 1): mu = (2u - (1-g))/D + 2g(1-g)(1+g)u(1-u)/D^2 with D = (1-g) + 2gu.             */
FOGRT_API float fogrt_sample_hg_mu(float g, float u);
/* Full direction sample around the propagation direction d = -wo; returns wi (unit) and the
   pdf (per steradian, equal to the phase function, so the sample weight is exactly 1).
   sin(theta) comes from 1 - mu and 1 + mu formed without cancellation, so directions within
   a few 1e-7 rad of the peak keep their angle even where mu rounds to +-1.                 */
FOGRT_API fogrt_vec3 fogrt_sample_hg(float g, fogrt_vec3 wo, float u1, float u2, float *pdf);
/* Phase function / pdf for outward wo and wi: uses mu = -dot(wo, wi). */
FOGRT_API float fogrt_hg_pdf(float g, fogrt_vec3 wo, fogrt_vec3 wi);
#ifndef FOGRT_NO_LAMPS_IN_FOG
/* Part II, B. Equiangular distance sampling along a ray toward a point light (Kulla and Fajardo 2012):
   the light at distance h from the ray's line, its closest approach at t = delta; samples
   t in [a, b] (b may be +infinity) with pdf proportional to 1 / (h^2 + (t - delta)^2), which
   cancels the light's 1/r^2. h must be > 0. Computed in double: t and the pdf are exact to
   float resolution for h down to 1e-7 of |t - delta| (tests/test_sampling.c).             */
FOGRT_API float fogrt_sample_equiangular(float delta, float h, float a, float b, float u, float *pdf);
FOGRT_API float fogrt_equiangular_pdf(float delta, float h, float a, float b, float t);
/* The glow around a lamp: a point light in fog, seen from x, shines along every direction
   wi that passes near it, with radiance proportional to (pi - alpha) / sin(alpha), alpha the
   angle between wi and the direction to the light (single scattering in clear, isotropic
   fog: the integral of 1/r^2 along the ray). Samples wi around to_light (unit) with that
   density, p(wi) = (pi - alpha) / (pi^3 sin(alpha)): alpha = pi (1 - sqrt(1 - u1)), the
   azimuth 2 pi u2. The pdf is infinite only exactly at alpha = 0 (returned as a large
   finite number there).                                                                    */
FOGRT_API fogrt_vec3 fogrt_sample_glow(fogrt_vec3 to_light, float u1, float u2, float *pdf);
FOGRT_API float fogrt_glow_pdf(fogrt_vec3 to_light, fogrt_vec3 wi);
#endif
#ifndef FOGRT_NO_MEDIA
/* Part II, G. The phase functions beyond HG, in 3.3's conventions (mu = cos(d, wi) with
   d = -wo; p per steradian; each sampler returns wi with pdf equal to p, so its sample
   weight is exactly 1).
   Two HG lobes: p(mu) = w HG(g1, mu) + (1 - w) HG(g2, mu), w in [0, 1]. The sampler picks
   lobe 1 when u1 < w and reuses u1, rescaled, for that lobe's mu.                          */
FOGRT_API float fogrt_hg2_phase(float g1, float g2, float w, float mu);
FOGRT_API fogrt_vec3 fogrt_sample_hg2(float g1, float g2, float w, fogrt_vec3 wo, float u1, float u2, float *pdf);
FOGRT_API float fogrt_hg2_pdf(float g1, float g2, float w, fogrt_vec3 wo, fogrt_vec3 wi);
/* Rayleigh: p(mu) = 3 / (16 pi) (1 + mu^2). Its CDF (mu^3 + 3 mu + 4) / 8 = u is a cubic
   with one real root, mu = 2 sinh(asinh(4u - 2) / 3): exact at u = 0 (-1), 1/2 (0) and 1
   (1), odd about u = 1/2.                                                                  */
FOGRT_API float fogrt_rayleigh_phase(float mu);
FOGRT_API float fogrt_sample_rayleigh_mu(float u);
FOGRT_API fogrt_vec3 fogrt_sample_rayleigh(fogrt_vec3 wo, float u1, float u2, float *pdf);
FOGRT_API float fogrt_rayleigh_pdf(fogrt_vec3 wo, fogrt_vec3 wi);
/* The phase function of a medium desc (its phase, g, g2 and w), as the renderer uses it. */
FOGRT_API float fogrt_phase(const fogrt_medium_desc *medium, float mu);
FOGRT_API fogrt_vec3 fogrt_sample_phase(const fogrt_medium_desc *medium, fogrt_vec3 wo, float u1, float u2, float *pdf);
FOGRT_API float fogrt_phase_pdf(const fogrt_medium_desc *medium, fogrt_vec3 wo, fogrt_vec3 wi);
#endif
#endif

/* Cosine-weighted hemisphere around +z (concentric disk map, then lift). pdf = cos/pi. */
FOGRT_API fogrt_vec3 fogrt_sample_cosine_hemisphere(float u1, float u2);
FOGRT_API float fogrt_cosine_hemisphere_pdf(float cos_theta);
/* Uniform direction on the unit sphere. pdf = 1 / (4 pi). */
FOGRT_API fogrt_vec3 fogrt_sample_uniform_sphere(float u1, float u2);
FOGRT_API float fogrt_uniform_sphere_pdf(void);
/* Uniform point on a triangle: returns barycentrics (b1, b2) of v1 and v2; pdf = 1/area. */
FOGRT_API void fogrt_sample_triangle(float u1, float u2, float *b1, float *b2);
/* Direction from p toward a sphere, uniform in the cone of directions the sphere subtends
   (solid angle sampling). Returns the unit direction; *pdf per steradian. If p is inside
   the sphere, samples the uniform sphere of directions instead.                            */
FOGRT_API fogrt_vec3 fogrt_sample_sphere_solid_angle(fogrt_vec3 center, float radius, fogrt_vec3 p,
                                                     float u1, float u2, float *pdf);
FOGRT_API float fogrt_sphere_solid_angle_pdf(fogrt_vec3 center, float radius, fogrt_vec3 p);
/* Spot light profile: fraction of full intensity at angle theta (cos_theta) from the axis. */
FOGRT_API float fogrt_spot_falloff(float cutoff_deg, float beam_deg, float cos_theta);

/* Mirror wo about n (both unit): 2 (wo.n) n - wo. */
FOGRT_API fogrt_vec3 fogrt_reflect(fogrt_vec3 n, fogrt_vec3 wo);
#ifndef FOGRT_NO_GLASS
/* Fresnel reflectance of a dielectric; eta = n_inside / n_outside; cos_i > 0 on the outside
   (incident medium ior 1), cos_i < 0 from inside. Both return 1 on total internal
   reflection; eta = 1 (no interface) gives 0 at every angle for the exact form.           */
FOGRT_API float fogrt_fresnel_schlick(float eta, float cos_i);
#ifndef FOGRT_NO_EXACT_FRESNEL
FOGRT_API float fogrt_fresnel_dielectric(float eta, float cos_i);
#endif
/* Refract wo through a surface with normal n (wo on either side; eta = n_inside/n_outside,
   the inside being opposite n). Returns false on total internal reflection.             */
FOGRT_API bool fogrt_refract(fogrt_vec3 n, float eta, fogrt_vec3 wo, fogrt_vec3 *wi);
#endif

/* ------------------------------------------------------------------------------------------
   BSDFs, in the local shading frame (normal = +z)
   ------------------------------------------------------------------------------------------ */
typedef enum fogrt_fresnel {
    FOGRT_FRESNEL_DEFAULT = 0,  /* = Schlick, as in the paper */
    FOGRT_FRESNEL_SCHLICK,
    FOGRT_FRESNEL_EXACT,        /* exact unpolarised dielectric Fresnel */
    FOGRT_FRESNEL_NUM,
    FOGRT_FRESNEL_FORCE_U32 = 0x7FFFFFFF
} fogrt_fresnel;

typedef struct fogrt_bsdf_sample {
    fogrt_vec3 wi;      /* sampled direction (unit) */
    fogrt_vec3 weight;  /* f |cos| / pdf */
    float pdf;          /* per steradian, or the discrete probability for a delta lobe */
    bool is_delta;      /* a specular lobe (mirror, refraction) */
    bool is_transmission;
} fogrt_bsdf_sample;

/* Samples wi given wo; u_lobe chooses between reflection and refraction (glass), u1 and u2
   the direction. Returns false if no direction was produced (e.g. wo on the horizon).    */
FOGRT_API bool fogrt_sample_bsdf(const fogrt_material_desc *m, fogrt_fresnel fresnel,
                                 fogrt_vec3 wo, float u_lobe, float u1, float u2,
                                 fogrt_bsdf_sample *out);
/* f(wo, wi) without the cosine; zero for the specular BSDFs (they are deltas). */
FOGRT_API fogrt_vec3 fogrt_bsdf_eval(const fogrt_material_desc *m, fogrt_vec3 wo, fogrt_vec3 wi);
/* pdf of fogrt_sample_bsdf producing wi; zero for the specular BSDFs. */
FOGRT_API float fogrt_bsdf_pdf(const fogrt_material_desc *m, fogrt_vec3 wo, fogrt_vec3 wi);

/* ------------------------------------------------------------------------------------------
   Random numbers: PCG32 (O'Neill), one small state per stream
   ------------------------------------------------------------------------------------------ */
typedef struct fogrt_rng { uint64_t state, inc; } fogrt_rng;
FOGRT_API void fogrt_rng_seed(fogrt_rng *rng, uint64_t seed, uint64_t stream);
FOGRT_API uint32_t fogrt_rng_u32(fogrt_rng *rng);
/* Uniform float in [0, 1 - 2^-24]: never 1. */
FOGRT_API float fogrt_rng_float(fogrt_rng *rng);

/* ------------------------------------------------------------------------------------------
   Rendering
   ------------------------------------------------------------------------------------------ */
typedef enum fogrt_integrator {
    FOGRT_INTEGRATOR_DEFAULT = 0,  /* = path */
    FOGRT_INTEGRATOR_PATH,         /* global illumination, the paper's Algorithm 1 */
    FOGRT_INTEGRATOR_DIRECT,       /* one-bounce direct lighting, the paper's baseline */
    FOGRT_INTEGRATOR_NUM,
    FOGRT_INTEGRATOR_FORCE_U32 = 0x7FFFFFFF
} fogrt_integrator;

typedef struct fogrt_progress {
    int rows_done, rows_total;     /* of the current fogrt_render call */
    int samples_per_pixel;         /* added by the current call */
} fogrt_progress;

/* fogrt_render_desc. Start from fogrt_render_defaults(): every field then means what it
   says (max_depth 0 is emission only, nee false is no light sampling). A desc that did not
   come from it (resolved false: a zeroed struct) is refused with a log line, since zero
   is a meaningful value for half of these fields; NULL means the defaults.
     width, height     image size; must match the image (0: the image's size)
     integrator        path (the paper's Algorithm 1), or direct (its one-bounce baseline)
     fresnel           Schlick
     max_depth         64: bounces (surface or fog scattering events) after the camera ray;
                       0 = emission only (CS184 -m 0), -1 = unlimited (roulette still ends
                       every path)
     min_depth         0: light that bounced fewer times is not counted (CS184 -o 0 is
                       min_depth = max_depth: only light that bounced exactly max_depth times)
     rr_depth          3: Russian roulette starts after this many bounces (0: from the first)
     nee               true: next-event estimation (light sampling); false: light is found
                       only by hitting it, the paper's "without importance sampling"
     mis               true: multiple importance sampling between light and BSDF/phase
                       sampling; false: emitters found by BSDF/phase sampling do not count
     equiangular       true: point and spot lights in fog are gathered along every fog
                       segment by equiangular sampling (not in the paper); false: found only
                       by next-event estimation at fog collisions, as the paper does
     glow              true: at scattering points in fog, some of the new directions aim
                       at the glow around point and spot lights (Part II, E d': half when
                       they are all the light, less as area lights add theirs), which keeps
                       paths that pass next to a lamp from being rare, huge samples; needs
                       nee and equiangular (not in the paper)
     footprint         true: a fifth of the directions aimed at a spot light's glow aim at
                       the plane its cone lights most instead (the lit floor under it, found
                       when the scene is built; half through the lamp's cone, half at the
                       lit patch as the vertex sees it; Part II, B and E d'); needs glow (not
                       in the paper)
     light_by_power    false (CS184): every light is sampled at every vertex; true: one
                       light per vertex, chosen in proportion to its power (radiant flux),
                       its sample divided by that probability: one shadow ray instead of
                       one per light, for scenes with many lights (docs/benchmarks.md)
     light_samples     1 (>= 1): samples per area light at each next-event estimate (CS184 -l)
     seed              0: base seed of every random stream
     threads           0 = all OpenMP threads; at most FOGRT_MAX_THREADS (256) and 4 per
                       processor (more are cut to that); ignored without OpenMP
     sample_rate       NULL: every pixel gets the call's spp samples. Else width x height
                       rates (rows from the top, each finite, 0 to FOGRT_MAX_SAMPLE_RATE):
                       pixel p gets spp x rate[p] samples on average, the fraction decided
                       by a coin of its own (adaptive sampling, unbiased when the rates
                       come from fogrt_image_sample_rates as Part II, C says)
     progress          optional; called between row blocks; return false to cancel
     cancel            optional: the render stops within a sample (of every thread) once *cancel
                       is non-zero, as when cancelled (a signal handler's flag, say)
     radiance          optional: an estimator of your own (docs/coursework.md, steps 6-8): the
                       radiance one sample finds along the camera ray (o, unit d), drawing its
                       random numbers from rng; fogrt_render calls it instead of its
                       integrators (user_data is passed on), and keeps the image, the threads
                       and the error estimate as always
     resolved          set by fogrt_render_defaults(): the fields hold their real values   */
typedef struct fogrt_render_desc {
    int width, height;
    fogrt_integrator integrator;
    fogrt_fresnel fresnel;
    int max_depth;
    int min_depth;
    int rr_depth;
    bool nee;
    bool mis;
    bool equiangular;
    bool glow;
    bool footprint;
    bool light_by_power;
    bool expected_emission;    /* fog: a ray adds T Le of the emitter it reaches, and T times the point
                                  and spot lights' light at the surface it reaches, collided or not (Part II, E b and b') */
    int light_samples;
    uint64_t seed;
    int threads;
    const float *sample_rate;
    bool (*progress)(const fogrt_progress *progress, void *user_data);
    void *user_data;
    const volatile int *cancel;
    fogrt_vec3 (*radiance)(const fogrt_scene *scene, fogrt_vec3 o, fogrt_vec3 d, fogrt_rng *rng, void *user_data);
    bool resolved;
} fogrt_render_desc;

/* The defaults, resolved: read them back, change what you need, pass the desc on. */
FOGRT_API fogrt_render_desc fogrt_render_defaults(void);
/* The paper's method alone: Part I's Algorithm 1 with light sampling and MIS (equiangular,
   glow, footprint, light_by_power and expected_emission off). Under FOGRT_MINIMAL the
   defaults above are these. A scene with fog in a box or an environment map is still
   rendered by Part II's integrator (with these settings: the same method), since Part I
   knows neither. */
FOGRT_API fogrt_render_desc fogrt_render_paper_defaults(void);

/* Accumulation buffer owned by the caller: per pixel the sum of sample radiance (RGB), the
   sum of squared sample luminance (both in double: no finite sample can overflow them), and
   the sample count. Adding samples is progressive.
   The samples of a pixel are dealt round-robin to FOGRT_IMAGE_STREAMS independent streams
   (sample index i to stream i mod 4), each with its own random scramble of a stratified
   pattern of pixel positions; per stream the image keeps the luminance sum and the count,
   and the error estimate compares the streams (fogrt_image_pixel_variance). 84 bytes per
   pixel from fogrt_image_alloc: 24 RGB sum, 8 sum of squares, 4 count, 32 stream sums,
   16 stream counts. An image filled by the caller may leave stream_sum and stream_count
   NULL: fogrt_render then keeps no stream sums and the estimate falls back to the sample
   variance (which overestimates the error of stratified samples). */
#define FOGRT_IMAGE_STREAMS 4
#define FOGRT_MAX_THREADS 256
typedef struct fogrt_image {
    int width, height;
    double *sum;         /* 3 * width * height: sum of sample radiance (RGB) */
    double *sum_sq;      /* width * height: sum of squared sample luminance */
    uint32_t *count;     /* width * height; at most 2^32 - 1 (fogrt_render refuses a call that would pass it) */
    double *stream_sum;      /* FOGRT_IMAGE_STREAMS * width * height: per pixel, each stream's luminance sum */
    uint32_t *stream_count;  /* FOGRT_IMAGE_STREAMS * width * height: per pixel, each stream's samples */
    uint64_t rejected;   /* non-finite samples seen and dropped */
    uint64_t rated_spp;  /* spp asked for so far with sample rates (where each pixel's count stands) */
    fogrt_allocator allocator;   /* what fogrt_image_alloc used; fogrt_image_free uses it too */
} fogrt_image;

/* allocator NULL: FOGRT_MALLOC. The image remembers it for fogrt_image_free. */
FOGRT_API fogrt_result fogrt_image_alloc(fogrt_image *img, int width, int height, const fogrt_allocator *allocator);
FOGRT_API void fogrt_image_free(fogrt_image *img);
FOGRT_API void fogrt_image_clear(fogrt_image *img);
/* Mean radiance per pixel, 3 floats per pixel, rows from the top. */
FOGRT_API void fogrt_image_resolve(const fogrt_image *img, float *rgb);

typedef struct fogrt_error_estimate {
    double relative_error;   /* sqrt(sum_p Var[mean_p]) / sqrt(sum_p mean_p^2), luminance */
    double mean_luminance;
    uint64_t samples;
    uint64_t rejected;
} fogrt_error_estimate;
/* The render's own estimate of its relative RMS error, from the per-pixel variances below. */
FOGRT_API void fogrt_image_error(const fogrt_image *img, fogrt_error_estimate *out);
/* The estimated variance of pixel `pixel`'s mean luminance (index y * width + x): from the
   spread of its stream means, unbiased for stratified samples too; 0 below 2 samples. */
FOGRT_API double fogrt_image_pixel_variance(const fogrt_image *img, size_t pixel);
/* Adaptive sampling: per-pixel sample rates (mean 1) for fogrt_render_desc.sample_rate, from
   the noise of the samples img holds so far, each pixel's rate from its neighbours' noise
   alone (never its own). Call it once, after samples taken with every pixel alike (say 8
   spp), and keep the rates for the rest of the render: the image then stays unbiased
   (Part II, C says why). rates: width x height floats. OUT_OF_MEMORY, or INVALID_ARGUMENT
   for an image without samples; an image without noise gets rates of 1. */
#define FOGRT_MAX_SAMPLE_RATE 64.0f
#ifndef FOGRT_NO_ESTIMATION
FOGRT_API fogrt_result fogrt_image_sample_rates(const fogrt_image *img, float *rates);   /* Part II, C */
#endif

typedef struct fogrt_render_stats {
    uint64_t camera_rays;    /* samples taken */
    uint64_t rays;           /* all rays traced (camera, bounce and shadow) */
    uint64_t rejected;       /* non-finite samples dropped in this call */
    bool black;              /* after this call every pixel of the image is black */
} fogrt_render_stats;

/* Adds samples_per_pixel samples to every pixel of img. The same (seed, pixel, sample
   index) always gives the same sample, so splitting the samples over calls or threads
   does not change the image.                                                              */
FOGRT_API fogrt_result fogrt_render(const fogrt_scene *scene, const fogrt_render_desc *desc,
                                    fogrt_image *img, int samples_per_pixel, fogrt_render_stats *stats);
/* One radiance sample along a ray (for tests and custom cameras). */
FOGRT_API fogrt_vec3 fogrt_trace(const fogrt_scene *scene, const fogrt_render_desc *desc,
                                 fogrt_vec3 o, fogrt_vec3 d, fogrt_rng *rng, uint64_t *ray_count);
/* The samplers a render with desc runs in the built scene, in Algorithm 1's order, as one
   line ("free flight, equiangular, light sampling + MIS, glow, ..."): what a render's
   summary shows. buf (size bytes) is always terminated; returns buf. */
FOGRT_API const char *fogrt_render_samplers(const fogrt_scene *scene, const fogrt_render_desc *desc, char *buf,
                                            size_t size);
/* Camera ray through image position (px, py) in pixels (0..width, 0..height, y down). */
FOGRT_API void fogrt_camera_ray(const fogrt_scene *scene, int width, int height, float px, float py,
                                float lens_u1, float lens_u2, fogrt_vec3 *o, fogrt_vec3 *d);

/* ------------------------------------------------------------------------------------------
   Following one path, event by event (define FOGRT_TRACE before the implementation)
   fogrt_trace_path renders one pixel sample exactly as fogrt_render does (the same random
   stream) and calls back at every step of Algorithm 1. Without FOGRT_TRACE the hooks are
   not compiled at all: the renderer does not pay for them (make callgrind shows it).
   ------------------------------------------------------------------------------------------ */
typedef enum fogrt_trace_kind {
    FOGRT_TRACE_CAMERA,        /* the camera ray: p = origin, d = direction */
    FOGRT_TRACE_FREE_FLIGHT,   /* eq. 6: u[0] -> t; t_max = the surface (inf: none); flag: a fog collision */
    FOGRT_TRACE_SURFACE,       /* the ray reached primitive prim at p; bsdf */
    FOGRT_TRACE_ESCAPE,        /* the ray left the scene along d */
    FOGRT_TRACE_LIGHT_SAMPLE,  /* next-event estimation (eq. 3) toward light: d = wi, t = distance,
                                  Le, pdf, f (phase or BSDF |cos|), pdf_other (BSDF/phase pdf of wi),
                                  transmittance (eq. 8, 0 if blocked), mis_weight; value = f Le T w / pdf */
    FOGRT_TRACE_EQUIANGULAR,   /* a point on the segment for light: u[0] -> t, pdf; then the light sample
                                  fields as above; value includes sigma_s T(t) / pdf */
    FOGRT_TRACE_PHASE_SAMPLE,  /* eq. 11-12: u[0] -> cos_theta, u[1] -> phi; pdf; d = the new direction */
    FOGRT_TRACE_BSDF_SAMPLE,   /* u[0] picks the lobe (fresnel: its F), u[1], u[2] the direction;
                                  lobe; pdf; value = the weight f |cos| / pdf; d = the new direction */
    FOGRT_TRACE_GLOW_SAMPLE,   /* the mixed direction of E d': flag: u[0] chose the glow of light
                                  light (else the phase function or BSDF), source "footprint"
                                  when it chose that lamp's footprint on a plane; d; pdf = the
                                  mixture's pdf, pdf_other = the phase/BSDF pdf; value = the weight */
    FOGRT_TRACE_ROULETTE,      /* continue with probability q if u[0] < q; flag: survived */
    FOGRT_TRACE_CONTRIBUTION,  /* value (beta included) added to the pixel; source names it; flag: false
                                  when min_depth drops it */
    FOGRT_TRACE_END,           /* value = the sample's radiance */
    FOGRT_TRACE_NUM,
    FOGRT_TRACE_FORCE_U32 = 0x7FFFFFFF
} fogrt_trace_kind;

typedef enum fogrt_trace_lobe {
    FOGRT_LOBE_DIFFUSE, FOGRT_LOBE_REFLECT, FOGRT_LOBE_REFRACT, FOGRT_LOBE_GLOSSY   /* glossy: the rough metal */
} fogrt_trace_lobe;

typedef struct fogrt_trace_event {
    fogrt_trace_kind kind;
    int bounce;                /* scattering events before this one */
    fogrt_vec3 p, d;
    fogrt_vec3 beta;           /* the path throughput after the step */
    fogrt_vec3 value, Le, f;
    float u[3];
    float t, t_max, pdf, pdf_other, cos_theta, phi, transmittance, mis_weight, q, fresnel;
    uint32_t light;            /* light index: point and spot lights first, then area lights */
    uint32_t prim;
    fogrt_bsdf_type bsdf;
    fogrt_trace_lobe lobe;
    bool flag;
    const char *source;        /* contribution: "emission", "environment", "light sample", "light behind"
                                  (E b': the surface behind a fog collision), "equiangular";
                                  glow sample: "footprint" or NULL */
} fogrt_trace_event;

typedef void (*fogrt_trace_fn)(const fogrt_trace_event *event, void *user_data);

#if defined(FOGRT_TRACE) && !defined(FOGRT_MINIMAL)
/* Part II, D. Renders sample number sample_index of pixel (x, y) of a width x height image
   (the same sample fogrt_render adds there, with the full integrator) and calls fn at each
   event. Returns its radiance. */
FOGRT_API fogrt_vec3 fogrt_trace_path(const fogrt_scene *scene, const fogrt_render_desc *desc, int width,
                                      int height, int x, int y, uint32_t sample_index, fogrt_trace_fn fn,
                                      void *user_data);
#ifndef FOGRT_NO_STDIO
/* One readable line (no newline) for an event, naming the paper's equation it applies. */
FOGRT_API void fogrt_trace_describe(const fogrt_trace_event *event, char *buffer, size_t size);
#endif
#endif

/* ------------------------------------------------------------------------------------------
   Output helpers (no dependencies)
   ------------------------------------------------------------------------------------------ */
typedef enum fogrt_tonemap {
    FOGRT_TONEMAP_DEFAULT = 0,   /* = sRGB */
    FOGRT_TONEMAP_SRGB,          /* clamp to [0,1], sRGB curve */
    FOGRT_TONEMAP_GAMMA22,       /* clamp to [0,1], x^(1/2.2) */
    FOGRT_TONEMAP_NUM,
    FOGRT_TONEMAP_FORCE_U32 = 0x7FFFFFFF
} fogrt_tonemap;
/* Linear RGB floats to 8-bit RGB. exposure in stops (EV, as fogrt's and the preview's
   --exposure): the image is multiplied by 2^exposure first (0: as it is). NaN maps to 0. */
FOGRT_API void fogrt_tonemap_rgb8(const float *rgb, int width, int height, float exposure,
                                  fogrt_tonemap mode, unsigned char *out);
#ifndef FOGRT_NO_STDIO
/* Little-endian PFM (linear float, rows stored bottom-up as the format wants). */
FOGRT_API fogrt_result fogrt_write_pfm(const char *path, int width, int height, const float *rgb);
/* Binary PPM (P6) from 8-bit RGB. */
FOGRT_API fogrt_result fogrt_write_ppm(const char *path, int width, int height, const unsigned char *rgb8);
#endif

#ifdef __cplusplus
}
#endif
#endif /* FOGRT_H_INCLUDED */

/* ------------------------------------------------------------------------------------------
   The implementation's set-up: headers, the allocator and assertion hooks, the compiler
   glue, and the declarations of the seams to Part II (none of it is the method; Part I, the
   paper, starts below)
   ------------------------------------------------------------------------------------------ */
#ifdef FOGRT_IMPLEMENTATION
#ifndef FOGRT_IMPLEMENTATION_INCLUDED
#define FOGRT_IMPLEMENTATION_INCLUDED
#include <math.h>
#include <string.h>
#include <float.h>
#ifndef FOGRT_NO_STDIO
#include <stdio.h>
#endif
#ifdef _OPENMP
#include <omp.h>
#endif
#if defined(FOGRT_MALLOC) && !defined(FOGRT_FREE) || !defined(FOGRT_MALLOC) && defined(FOGRT_FREE)
#error "fogrt: define both FOGRT_MALLOC and FOGRT_FREE, or neither"
#endif
#ifndef FOGRT_MALLOC
#include <stdlib.h>
#define FOGRT_MALLOC(size, user) ((void)(user), malloc(size))
#define FOGRT_FREE(ptr, user) ((void)(user), free(ptr))
#endif
#ifndef FOGRT_ASSERT
#include <assert.h>
#define FOGRT_ASSERT(c) assert(c)
#endif
#ifndef FOGRT_MAX_PATH_VERTICES
#define FOGRT_MAX_PATH_VERTICES 100000
#endif
/* Private functions are static and "maybe unused" (features stripped at compile time leave
   no warnings). The few small functions of the BVH's inner loops and a few integrator steps
   are forced inline: at -O2 gcc otherwise keeps them as calls, which costs about a quarter
   of the traversal time, and made a fog-free render pay for the fog code of their callers
   (docs/benchmarks.md, "Forced inlining"). */
#if defined(__GNUC__) || defined(__clang__)
#define FOGRT__UNUSED __attribute__((unused))
#define FOGRT__INLINE __attribute__((always_inline, unused))
#define FOGRT__NOINLINE __attribute__((noinline, unused))
#else
#define FOGRT__UNUSED
#define FOGRT__INLINE
#define FOGRT__NOINLINE
#endif
#define FOGRT__PRIVATE static FOGRT__UNUSED
#define FOGRT__HOT static inline FOGRT__INLINE
/* OpenMP: a directive as a statement, and the runtime's counts; a build without OpenMP
   gets no directive and one thread. */
#ifdef _OPENMP
#define FOGRT__OMP(directive) _Pragma(#directive)
#define FOGRT__OMP_THREAD() omp_get_thread_num()
#define FOGRT__OMP_MAX_THREADS() omp_get_max_threads()
#define FOGRT__OMP_PROCS() omp_get_num_procs()
#else
#define FOGRT__OMP(directive)
#define FOGRT__OMP_THREAD() 0
#define FOGRT__OMP_MAX_THREADS() 1
#define FOGRT__OMP_PROCS() 1
#endif
#ifdef FOGRT_STATIC
#define FOGRT__PUBLIC static FOGRT__UNUSED
#else
#define FOGRT__PUBLIC
#endif

/* Checks of what lies beyond Part I: a build without a feature refuses it. */
FOGRT__PRIVATE fogrt_result fogrt__beyond_material(const fogrt_scene *s, const fogrt_material_desc *m);
FOGRT__PRIVATE fogrt_result fogrt__beyond_medium(const fogrt_scene *s, const fogrt_medium_desc *m);
FOGRT__PRIVATE fogrt_result fogrt__beyond_build(const fogrt_scene *s, const fogrt_build_desc *d);
FOGRT__PRIVATE fogrt_result fogrt__beyond_render(const fogrt_scene *s, const fogrt_render_desc *d);
FOGRT__PRIVATE fogrt_result fogrt__beyond_image(const fogrt_scene *s, const fogrt_render_desc *d, const fogrt_image *img);
FOGRT__PRIVATE fogrt_result fogrt__check_count_room(const fogrt_scene *s, const fogrt_render_desc *d,
                                                    const fogrt_image *img, int spp);
/* The seams: what Part I calls of Part II (numbered as in Part I's opening comment). */
struct fogrt__settings;
struct fogrt__job;
#ifndef FOGRT_NO_WIDE_BVH
FOGRT__HOT bool fogrt__wide_traverse(const fogrt_scene *s, fogrt_vec3 o, fogrt_vec3 d, float tmin, float tmax,
                                      fogrt_hit *hit, bool any_hit, bool *done);                  /* 1 (A) */
FOGRT__PRIVATE uint32_t fogrt__wide_leaf_keep(const fogrt_build_desc *d, uint32_t n);                /* 2 (A) */
struct fogrt__build; struct fogrt__bjob;
FOGRT__PRIVATE bool fogrt__split_binned_lanes(struct fogrt__build *b, const struct fogrt__bjob *job, fogrt_bvh_node *child,
                                          struct fogrt__bjob *left, struct fogrt__bjob *right, bool *halve, uint32_t *left_count);
FOGRT__PRIVATE void *fogrt__alloc_big(const fogrt_allocator *a, size_t size);                     /* 2 (A) */
FOGRT__PRIVATE uint32_t fogrt__sliver_refs(const fogrt_scene *s, uint32_t n, uint32_t leaf_keep);      /* 2 (A) */
FOGRT__PRIVATE void fogrt__sliver_split_refs(const fogrt_scene *s, struct fogrt__build *b, uint32_t n, uint32_t m);
#define FOGRT__ALLOC_BUILD fogrt__alloc_big
#define FOGRT__REFS(s, n, leaf_keep) fogrt__sliver_refs(s, n, leaf_keep)
#define FOGRT__SPLIT_REFS(s, b, n, m) fogrt__sliver_split_refs(s, b, n, m)
#else
#define FOGRT__ALLOC_BUILD fogrt__alloc
#define FOGRT__REFS(s, n, leaf_keep) (n)
#define FOGRT__SPLIT_REFS(s, b, n, m) ((void)0)
#endif
#ifndef FOGRT_MINIMAL
FOGRT__PRIVATE bool fogrt__appendix_build(fogrt_scene *s, const fogrt_build_desc *d, uint32_t n);        /* 3 */
FOGRT__PRIVATE void fogrt__appendix_release(fogrt_scene *s);                                             /* 4 */
FOGRT__PRIVATE void fogrt__appendix_scene_free(fogrt_scene *s);                                          /* 4 (C, H) */
#ifndef FOGRT_NO_MEDIUM
FOGRT__HOT bool fogrt__fog_box_span(const fogrt_scene *s, fogrt_vec3 o, fogrt_vec3 d, float tmax,
                                  float *a, float *b);                                            /* 6 (C) */
#endif
#ifndef FOGRT_NO_MEDIA
FOGRT__PRIVATE fogrt_result fogrt__media_check(const fogrt_scene *s, fogrt_medium_desc *m);    /* 6 (G) */
#endif
FOGRT__PRIVATE bool fogrt__full_wanted(const fogrt_scene *s, const struct fogrt__settings *st);      /* 7 (E) */
struct fogrt__walk; struct fogrt__path;
FOGRT__PRIVATE fogrt_vec3 fogrt__full_radiance(const fogrt_scene *s, const struct fogrt__settings *st, struct fogrt__walk *w);
FOGRT__HOT bool fogrt__full_next_event(const fogrt_scene *s, const struct fogrt__settings *st, struct fogrt__path *P,
                                        int limit);                                              /* 7a */
FOGRT__HOT void fogrt__full_light_step(const fogrt_scene *s, const struct fogrt__settings *st, struct fogrt__path *P);
FOGRT__HOT bool fogrt__full_scatter(const fogrt_scene *s, const struct fogrt__settings *st, struct fogrt__path *P);
FOGRT__HOT float fogrt__full_roulette_q(const struct fogrt__settings *st, struct fogrt__path *P, float u);   /* 7d */
FOGRT__PRIVATE void fogrt__full_samplers(const fogrt_scene *s, const struct fogrt__settings *st, char *buf, size_t size);
FOGRT__PRIVATE void fogrt__say(char *buf, size_t size, bool yes, const char *name);
#endif
#ifndef FOGRT_NO_MICROFACET
/* Out of line: inlined into 2.2's BSDF calls they made those too large for gcc to inline
   into the integrator, and a scene without rough metals paid 0.3% (make callgrind). */
static FOGRT__NOINLINE bool fogrt__mf_sample(const fogrt_material_desc *m, fogrt_vec3 wo, float u1, float u2,
                                               fogrt_bsdf_sample *out);                           /* 5 (I) */
static FOGRT__NOINLINE fogrt_vec3 fogrt__mf_eval(const fogrt_material_desc *m, fogrt_vec3 wo, fogrt_vec3 wi);
static FOGRT__NOINLINE float fogrt__mf_pdf(const fogrt_material_desc *m, fogrt_vec3 wo, fogrt_vec3 wi);
#define FOGRT__MF_SEAM(type, call) if ((type) == FOGRT_BSDF_MICROFACET) return call
#else   /* no rough metal can be added (fogrt__beyond_material): its seams compile to nothing */
#define FOGRT__MF_SEAM(type, call)
#endif
#ifndef FOGRT_NO_ESTIMATION
FOGRT__PRIVATE void fogrt__stratified_position(uint64_t base, uint64_t pix, uint32_t index, float *jx, float *jy);   /* 8 (C) */
FOGRT__PRIVATE uint32_t fogrt__rated_spp(const struct fogrt__job *job, size_t pix);
#endif

/* ==========================================================================================

      IMPLEMENTATION, PART I: THE PAPER

   The renderer that "Volumetric Ray Tracer in Homogeneous Media" describes, in the paper's
   order and with its numbering (docs/paper-map.md maps every equation and every line of
   Algorithm 1 to a function here and to the test that checks it):
     I.1  Configuration, vectors, random numbers      (what everything else needs)
     I.2  The scene's storage                         (what the chapters read)
     2.1  The BVH: binned build with the SAH or the paper's volume heuristic (eq. 1-2), traversal
     2.2  The four BSDFs, with Schlick's Fresnel
     2.3  The Monte Carlo estimator (eq. 3): lights, light sampling, MIS
     3.1  Exponential fog particle sampling: free flight (eq. 4-6)
     3.2  Light attenuation through fog (eq. 7-8)
     3.3  Fog scattering: Henyey-Greenstein (eq. 9-12)
     3.4  The global illumination pipeline: Algorithm 1 (eq. 13) and the one-bounce baseline
     I.3  Running it: the scene's validation, the camera, the build, rendering with its error
          estimate, output, the default scene
   Read Part I alone and you have the whole method; fogrt_render_paper_defaults() runs it.

   Part II, after it, is an appendix, one idea a chapter (A the wide BVH, B lamps in fog, C
   sampling and estimation, D the path trace, E the full integrator, F inspection, G media
   beyond the paper, H media inside shapes, I rough metals), which fogrt_render_defaults()
   uses. After it come the API around the method (getters, building blocks, image storage,
   8-bit output) and the checks of what a build left out, which every build keeps;
   FOGRT_MINIMAL compiles Part I and those two, without Part II.

   Part I reaches Part II only at these eight seams: twenty-two one-line calls, each marked
   "SEAM n" where it stands (their declarations are in the set-up above):
     1. fogrt__traverse            the wide tree, when the build made one (A)
     2. fogrt_scene_build          how small a binary node may stay, for the wide tree (A);
        fogrt__bvh_split_binned    and a node's whole binned split in SIMD lanes (A);
        fogrt__build_tree          and huge pages for the build's two big arrays, and the
                                   boxes of long slivers cut into pieces (A)
     3. fogrt_scene_build          Part II's tables: wide tree, HG table, footprints, pilot
     4. fogrt__free_built          their release; fogrt_scene_destroy: what Part II's calls set
                                   on the scene (C's environment map, H's media)
     5. fogrt__fresnel             the exact dielectric Fresnel (C);
        fogrt_sample_bsdf, fogrt_bsdf_eval, fogrt_bsdf_pdf: the rough metal (I)
     6. fogrt__fog_transmittance   fog bounded by a box (C); fogrt__check_medium: G's medium fields
     7. fogrt__radiance            Part II's path state (E), for every setting beyond the paper;
        7a-7d: Algorithm 1's steps then hand the path to E's: the next event (B, C, G, H), light
        at a vertex (B, C, H), the new direction (B, G, H), roulette's q (C's pilot)
     8. fogrt__pixel_ray           stratified pixel positions (C); fogrt__render_row: rates
   ========================================================================================== */
/* ------------------------------------------------------------------------------------------
   I.1 Configuration, vectors, random numbers
   ------------------------------------------------------------------------------------------ */
#define FOGRT__PI      3.14159265358979323846f
#define FOGRT__PI_D    3.14159265358979323846
#define FOGRT__INV_PI  0.31830988618379067154f
#define FOGRT__INV_4PI 0.07957747154594766788f
#define FOGRT__ONE_MINUS_EPS 0.99999994f      /* the largest float below 1, 1 - 2^-24 */

/* Ternary min/max: gcc turns fminf/fmaxf into library calls in hot loops. */
#define FOGRT__MIN(a, b) ((a) < (b) ? (a) : (b))
#define FOGRT__MAX(a, b) ((a) > (b) ? (a) : (b))
#define FOGRT__CLAMP(x, lo, hi) FOGRT__MIN(FOGRT__MAX(x, lo), hi)
#define FOGRT__DEF(val, def) ((val) == 0 ? (def) : (val))   /* "zero means default" */
#define FOGRT__MAX_PRIMS (1u << 28)   /* triangles + spheres: keeps every index and size in range */

FOGRT__PRIVATE void *fogrt__alloc(const fogrt_allocator *a, size_t size) {
    if (a && a->alloc_fn) return a->alloc_fn(size, a->user_data);
    return FOGRT_MALLOC(size, a ? a->user_data : NULL);
}
FOGRT__PRIVATE void fogrt__free(const fogrt_allocator *a, void *ptr) {
    if (!ptr) return;
    if (a && a->free_fn) a->free_fn(ptr, a->user_data);
    else FOGRT_FREE(ptr, a ? a->user_data : NULL);
}
FOGRT__PRIVATE bool fogrt__finite(float x) { return x - x == 0.0f; }  /* false for NaN, +-Inf */
/* Coordinates must be finite and at most 1e30 in size, so that squared distances and box
   areas stay finite in float. */
#define FOGRT__MAX_COORD 1e30f
FOGRT__PRIVATE bool fogrt__coord_ok(float x) { return fabsf(x) <= FOGRT__MAX_COORD; }  /* NaN: no */

typedef fogrt_vec3 fogrt__v3;
FOGRT__PRIVATE fogrt__v3 fogrt__v(float x, float y, float z) {
    fogrt__v3 r = { x, y, z };
    return r;
}
FOGRT__PRIVATE fogrt__v3 fogrt__add(fogrt__v3 a, fogrt__v3 b) {
    return fogrt__v(a.x + b.x, a.y + b.y, a.z + b.z);
}
FOGRT__PRIVATE fogrt__v3 fogrt__sub(fogrt__v3 a, fogrt__v3 b) {
    return fogrt__v(a.x - b.x, a.y - b.y, a.z - b.z);
}
FOGRT__PRIVATE fogrt__v3 fogrt__mul(fogrt__v3 a, fogrt__v3 b) {
    return fogrt__v(a.x * b.x, a.y * b.y, a.z * b.z);
}
FOGRT__PRIVATE fogrt__v3 fogrt__scale(fogrt__v3 a, float s) {
    return fogrt__v(a.x * s, a.y * s, a.z * s);
}
FOGRT__PRIVATE fogrt__v3 fogrt__madd(fogrt__v3 a, fogrt__v3 b, float s) {
    return fogrt__v(a.x + b.x * s, a.y + b.y * s, a.z + b.z * s);
}
FOGRT__PRIVATE fogrt__v3 fogrt__neg(fogrt__v3 a) { return fogrt__v(-a.x, -a.y, -a.z); }
FOGRT__PRIVATE float fogrt__dot(fogrt__v3 a, fogrt__v3 b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
FOGRT__PRIVATE fogrt__v3 fogrt__cross(fogrt__v3 a, fogrt__v3 b) {
    return fogrt__v(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
FOGRT__HOT float fogrt__length(fogrt__v3 a) { return sqrtf(fogrt__dot(a, a)); }
FOGRT__HOT fogrt__v3 fogrt__normalize(fogrt__v3 a) {
    float len = fogrt__length(a);
    return len > 0.0f ? fogrt__scale(a, 1.0f / len) : fogrt__v(0.0f, 0.0f, 1.0f);
}
FOGRT__PRIVATE float fogrt__max3(fogrt__v3 a) { return FOGRT__MAX(a.x, FOGRT__MAX(a.y, a.z)); }
FOGRT__PRIVATE float fogrt__luminance(fogrt__v3 c) {
    return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
}
FOGRT__PRIVATE bool fogrt__v3_finite(fogrt__v3 a) {
    return fogrt__finite(a.x) && fogrt__finite(a.y) && fogrt__finite(a.z);
}
FOGRT__PRIVATE bool fogrt__is_black(fogrt__v3 a) {
    return a.x == 0.0f && a.y == 0.0f && a.z == 0.0f;
}
FOGRT__PRIVATE float fogrt__comp(fogrt__v3 a, int axis) {
    return axis == 0 ? a.x : (axis == 1 ? a.y : a.z);
}

/* Orthonormal basis around a unit vector n (Duff et al. 2017, "Building an Orthonormal
   Basis, Revisited"): no branch on a threshold, exact for n = +-z, any axis-parallel n. */
typedef struct fogrt__frame { fogrt__v3 s, t, n; } fogrt__frame;
FOGRT__PRIVATE fogrt__frame fogrt__frame_from_z(fogrt__v3 n) {
    fogrt__frame f;
    float sign = copysignf(1.0f, n.z);
    float a = -1.0f / (sign + n.z);
    float b = n.x * n.y * a;
    f.s = fogrt__v(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    f.t = fogrt__v(b, sign + n.y * n.y * a, -n.y);
    f.n = n;
    return f;
}
FOGRT__PRIVATE fogrt__v3 fogrt__to_local(const fogrt__frame *f, fogrt__v3 v) {
    return fogrt__v(fogrt__dot(v, f->s), fogrt__dot(v, f->t), fogrt__dot(v, f->n));
}
FOGRT__PRIVATE fogrt__v3 fogrt__to_world(const fogrt__frame *f, fogrt__v3 v) {
    return fogrt__add(fogrt__add(fogrt__scale(f->s, v.x), fogrt__scale(f->t, v.y)),
                      fogrt__scale(f->n, v.z));
}
/* The direction at polar angle theta (given by its cosine and sine) from the frame's n and
   azimuth 2 pi u: how every sampler of a cone or lobe (HG eq. 12, spheres) turns its two
   angles into a direction. */
FOGRT__HOT fogrt__v3 fogrt__direction_at(const fogrt__frame *f, float cos_theta,
                                         float sin_theta, float u) {
    float phi = 2.0f * FOGRT__PI * u;
    return fogrt__normalize(
            fogrt__to_world(f, fogrt__v(sin_theta * cosf(phi), sin_theta * sinf(phi), cos_theta)));
}

/* Random numbers: PCG32 (M. O'Neill, pcg-random.org), one stream per (pixel, sample). */
FOGRT__PUBLIC uint32_t fogrt_rng_u32(fogrt_rng *rng) {
    uint64_t old = rng->state;
    uint32_t xorshifted = (uint32_t)(((old >> 18u) ^ old) >> 27u), rot = (uint32_t)(old >> 59u);
    rng->state = old * 6364136223846793005ULL + rng->inc;
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
}
FOGRT__PUBLIC void fogrt_rng_seed(fogrt_rng *rng, uint64_t seed, uint64_t stream) {
    rng->state = 0u;
    rng->inc = (stream << 1u) | 1u;
    (void)fogrt_rng_u32(rng);
    rng->state += seed;
    (void)fogrt_rng_u32(rng);
}
FOGRT__PUBLIC float fogrt_rng_float(fogrt_rng *rng) {
    return (float)(fogrt_rng_u32(rng) >> 8) *
           5.9604644775390625e-8f; /* 24 bits times 2^-24: [0, 1 - 2^-24] */
}
/* A 64-bit mix (SplitMix64 finaliser) to turn (seed, pixel) into a well spread state. */
FOGRT__PRIVATE uint64_t fogrt__hash64(uint64_t x) {
    x += 0x9E3779B97F4A7C15ULL;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
    return x ^ (x >> 31);
}
/* ------------------------------------------------------------------------------------------
   I.2 The scene's storage: what the paper's chapters read (its validation: I.3)
   ------------------------------------------------------------------------------------------ */
/* A primitive as the traversal sees it, in BVH order: a triangle stores v0 and its two edges
   (Moller-Trumbore needs nothing else); a sphere stores its centre in a and radius in b.x. */
typedef struct fogrt__prim {
    fogrt__v3 a, b, c;
    uint32_t id;
} fogrt__prim;

/* An area light: all emissive triangles of one mesh, or one emissive sphere. */
typedef struct fogrt__area_light {
    uint32_t first, count;    /* range in scene->light_prims / light_cdf (triangles) */
    uint32_t sphere;          /* sphere index (primitive id - triangle count), or UINT32_MAX */
    float area;               /* total area */
} fogrt__area_light;

struct fogrt__x;   /* Part II's tables (wide tree, lamps in fog, maps, pilot), or NULL */
struct fogrt_scene {
    fogrt_allocator allocator;
    fogrt_logger logger;
    fogrt_material_desc *materials;
    uint32_t material_count, material_cap;
    /* triangles, in the order they were added: 3 vertices, 3 normals, flags */
    fogrt__v3 *tri_v, *tri_n;  /* 3 per triangle; the normals valid where tri_has_n */
    uint8_t *tri_has_n;
    uint32_t *tri_material, *tri_mesh;
    uint32_t tri_count, tri_cap, mesh_count;
    fogrt__v3 *sph_c;          /* spheres: centres, radii, materials */
    float *sph_r;
    uint32_t *sph_material;
    uint32_t sph_count, sph_cap;
    fogrt_light_desc *lights;  /* point and spot lights */
    uint32_t light_count, light_cap;
    float *spot_cos;           /* built: per point or spot light, cos(cutoff) and cos(beam) */
    /* environment: a constant radiance, or a map (3 floats per pixel, CS184's mapping) */
    fogrt__v3 env;
    bool env_upper_only, has_env;
    struct fogrt__env_map *env_map;     /* Part II's environment map (C), or NULL */
    fogrt_camera_desc camera;
    bool has_camera;
    fogrt_medium_desc medium;
    /* built data (fogrt_scene_build) */
    bool built;
    fogrt_bvh_node *nodes;
    uint32_t node_count;
    uint32_t *prim_index;
    fogrt__prim *prims;        /* prim_count, in BVH order (parallel to prim_index) */
    fogrt__area_light *area_lights;
    uint32_t area_light_count;
    uint32_t *light_prims;     /* the emissive triangles of each area light, and their CDF */
    float *light_cdf;
    uint32_t *prim_light;      /* per primitive id: area light index or UINT32_MAX */
    uint32_t features;
    fogrt__v3 bmin, bmax;
    float eps;                 /* absolute ray offset floor, relative to the scene size */
    float r2_min;              /* smallest squared distance to a point light (2.3) */
    struct fogrt__x *x;        /* Part II's state: NULL under FOGRT_MINIMAL */
    struct fogrt__shapes *shapes;   /* Part II's media inside shapes (H), or NULL */
    char *error;               /* the last failure's message: points at error_text (writable */
    char error_text[256];      /*   through a const scene, as a log line is) */
};
/* ------------------------------------------------------------------------------------------
   2.1 Bounding Volume Hierarchy (paper eq. 1-2)
   The tree is built top down. Each node splits its primitives by a plane through one of
   `bins` equal slices of their centroids' bounds, on the axis and at the plane whose
   heuristic is least. The paper's heuristic (eq. 1) weighs both sides by their volumes,
     H_i = N_l V_l + N_r V_r,  i in {x, y, z}  (eq. 2: the axis split along),
   and splits until a node holds at most max_leaf_size primitives; the default, the surface
   area heuristic, weighs them by their surface areas and also stops where splitting costs
   more than a leaf:  c_trav + c_int (A_l N_l + A_r N_r) / A  against  c_int N.
   Each node is binned in one pass over its primitives for all three axes (a bin keeps the
   box and the count of the primitives whose centroid falls in it); the planes are priced
   by sweeping the bins from both ends, and one more pass moves the primitives of the left
   side to the front. Past FOGRT__BVH_SAH_DEPTH levels (only reached by adversarial inputs)
   nodes are halved without the heuristic, so the depth stays below FOGRT__BVH_MAX_DEPTH,
   the size of the traversal stack. Node 0 is the root, node 1 is unused (so that the two
   children of a node are neighbours), and a split appends its two children.
   ------------------------------------------------------------------------------------------ */
typedef struct fogrt__aabb { fogrt__v3 lo, hi; } fogrt__aabb;
FOGRT__PRIVATE fogrt__aabb fogrt__aabb_empty(void) {
    fogrt__aabb b = { { FLT_MAX, FLT_MAX, FLT_MAX }, { -FLT_MAX, -FLT_MAX, -FLT_MAX } };
    return b;
}
FOGRT__HOT void fogrt__aabb_union(fogrt__aabb *b, const fogrt__aabb *o) {   /* o may be empty */
    b->lo.x = FOGRT__MIN(b->lo.x, o->lo.x);
    b->lo.y = FOGRT__MIN(b->lo.y, o->lo.y);
    b->lo.z = FOGRT__MIN(b->lo.z, o->lo.z);
    b->hi.x = FOGRT__MAX(b->hi.x, o->hi.x);
    b->hi.y = FOGRT__MAX(b->hi.y, o->hi.y);
    b->hi.z = FOGRT__MAX(b->hi.z, o->hi.z);
}
FOGRT__HOT void fogrt__aabb_grow(fogrt__aabb *b, fogrt__v3 p) {   /* the union with the point */
    fogrt__aabb point = { p, p };
    fogrt__aabb_union(b, &point);
}
FOGRT__PRIVATE float fogrt__aabb_area(const fogrt__aabb *b) {     /* 0 for the empty box */
    fogrt__v3 e = fogrt__sub(b->hi, b->lo);
    return e.x < 0.0f ? 0.0f : 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
}
FOGRT__PRIVATE float fogrt__aabb_volume(const fogrt__aabb *b) {
    fogrt__v3 e = fogrt__sub(b->hi, b->lo);
    return e.x < 0.0f ? 0.0f : e.x * e.y * e.z;
}
FOGRT__HOT fogrt__v3 fogrt__aabb_centre(const fogrt__aabb *b) {
    return fogrt__scale(fogrt__add(b->lo, b->hi), 0.5f);
}

#define FOGRT__BVH_SAH_DEPTH 56
#define FOGRT__BVH_MAX_DEPTH 96   /* 56 + 32 halvings of at most 2^32 primitives, and margin */
#define FOGRT__BVH_MAX_BINS 64    /* fogrt_build_desc.bins is at most this */

typedef struct fogrt__build {
    fogrt_build_desc desc;
    fogrt__aabb *box;      /* per primitive, in the order of idx (reordered with it) */
    fogrt_bvh_node *nodes;
    uint32_t *idx;
    uint32_t node_count;
    uint32_t leaf_keep;    /* nodes of at most this many primitives stay leaves, unpriced */
} fogrt__build;
/* A node waiting on the build's stack, with the bounds of its primitives' centroids. */
typedef struct fogrt__bjob {
    uint32_t node, depth;
    fogrt__aabb cb;
} fogrt__bjob;

/* The heuristic's measure of one side: N A (SAH) or N V (the paper's eq. 1). */
FOGRT__PRIVATE float fogrt__side_cost(const fogrt_build_desc *d, uint32_t n,
                                      const fogrt__aabb *box) {
    return (float)n *
           (d->heuristic == FOGRT_BVH_VOLUME ? fogrt__aabb_volume(box) : fogrt__aabb_area(box));
}
FOGRT__PRIVATE void fogrt__node_set_box(fogrt_bvh_node *node, const fogrt__aabb *b) {
    for (int k = 0; k < 3; ++k) node->bmin[k] = fogrt__comp(b->lo, k);
    for (int k = 0; k < 3; ++k) node->bmax[k] = fogrt__comp(b->hi, k);
}
/* Box and centroid bounds of count primitives (the root, and the halved nodes). */
FOGRT__PRIVATE void fogrt__boxes_bounds(const fogrt__aabb *box, uint32_t count,
                                        fogrt_bvh_node *node, fogrt__aabb *cb) {
    fogrt__aabb b = fogrt__aabb_empty();
    *cb = fogrt__aabb_empty();
    for (uint32_t i = 0; i < count; ++i) {
        fogrt__aabb_union(&b, &box[i]);
        fogrt__aabb_grow(cb, fogrt__aabb_centre(&box[i]));
    }
    fogrt__node_set_box(node, &b);
}

/* The bins of one node: on axis a, bin k holds the primitives whose centroid falls in the
   k-th of nb equal slices of the centroid bounds; box is the box of those primitives. */
typedef struct fogrt__bins {
    fogrt__aabb box[3][FOGRT__BVH_MAX_BINS];
    uint32_t n[3][FOGRT__BVH_MAX_BINS];
    fogrt__v3 origin, scale;
    int nb;
} fogrt__bins;
/* The bin of a centroid on axis ax: (c - origin) scale, clamped to [0, nb - 1] and
   truncated; a NaN (a flat axis: 0 x infinity) lands in bin 0. */
FOGRT__HOT int fogrt__bin_of(const fogrt__bins *bins, fogrt__v3 c, int ax) {
    float f = (fogrt__comp(c, ax) - fogrt__comp(bins->origin, ax)) * fogrt__comp(bins->scale, ax);
    f = f > 0.0f ? f : 0.0f;
    f = f < (float)(bins->nb - 1) ? f : (float)(bins->nb - 1);
    return (int)f;
}
/* Empty bins over the centroid bounds cb: no more bins than primitives (at least 2, so
   bins = 1 prices the single plane through the middle). An axis on which every centroid
   has the same coordinate gets scale 0 (no plane to try there). Then every primitive goes
   into its bin on each axis. */
FOGRT__PRIVATE void fogrt__bins_fill(fogrt__bins *bins, const fogrt_build_desc *d,
                                     const fogrt__aabb *cb, const fogrt__aabb *box,
                                     uint32_t count) {
    float sc[3];
    int nb = count < (uint32_t)d->bins ? (int)count : d->bins;
    if (nb == 1) nb = 2;
    for (int ax = 0; ax < 3; ++ax) {
        float lo = fogrt__comp(cb->lo, ax), hi = fogrt__comp(cb->hi, ax);
        sc[ax] = (float)nb / (hi - lo);
        if (!(hi > lo && sc[ax] > 0.0f && sc[ax] < FLT_MAX)) sc[ax] = 0.0f;
        for (int k = 0; k < nb; ++k) bins->box[ax][k] = fogrt__aabb_empty();
    }
    memset(bins->n, 0, sizeof bins->n);
    bins->nb = nb;
    bins->origin = cb->lo;
    bins->scale = fogrt__v(sc[0], sc[1], sc[2]);
    for (uint32_t i = 0; i < count; ++i) {
        fogrt__v3 c = fogrt__aabb_centre(&box[i]);
        for (int ax = 0; ax < 3; ++ax) {
            int k = fogrt__bin_of(bins, c, ax);
            fogrt__aabb_union(&bins->box[ax][k], &box[i]);
            bins->n[ax][k]++;
        }
    }
}
/* The cheapest plane of one axis: sweep from the left and from the right to price the
   nb - 1 planes between the bins (plane k: bins 0..k-1 on the left). Improves *best, and
   *best_k, where a plane with primitives on both sides is cheaper. */
FOGRT__PRIVATE bool fogrt__bins_sweep(const fogrt_build_desc *d, const fogrt__bins *bins, int ax,
                                      uint32_t count, float *best, int *best_k) {
    fogrt__aabb b = fogrt__aabb_empty();
    uint32_t left_n = 0, right_n = 0;
    float left_cost[FOGRT__BVH_MAX_BINS];
    bool improved = false;
    for (int k = 0; k < bins->nb - 1; ++k) {
        left_n += bins->n[ax][k];
        fogrt__aabb_union(&b, &bins->box[ax][k]);
        left_cost[k] = fogrt__side_cost(d, left_n, &b);
    }
    b = fogrt__aabb_empty();
    for (int k = bins->nb - 1; k > 0; --k) {
        right_n += bins->n[ax][k];
        fogrt__aabb_union(&b, &bins->box[ax][k]);
        if (right_n == 0 || right_n == count) continue;
        float cost = left_cost[k - 1] + fogrt__side_cost(d, right_n, &b);
        if (cost < *best) {
            *best = cost;
            *best_k = k;
            improved = true;
        }
    }
    return improved;
}
/* The leaf rule: with the SAH, split when it is cheaper than a leaf, and always above the
   largest leaf size; with the volume heuristic, split down to the largest leaf size. */
FOGRT__PRIVATE bool fogrt__split_pays(const fogrt_build_desc *d, const fogrt_bvh_node *node,
                                      uint32_t count, float best) {
    if (count > (uint32_t)d->max_leaf_size) return true;
    if (d->heuristic == FOGRT_BVH_VOLUME) return false;
    fogrt__aabb box = { { node->bmin[0], node->bmin[1], node->bmin[2] },
                        { node->bmax[0], node->bmax[1], node->bmax[2] } };
    return d->c_trav + d->c_int * best / FOGRT__MAX(fogrt__aabb_area(&box), FLT_MIN) <
           d->c_int * (float)count;
}
/* The primitives whose bin on axis ax is below k to the front (with their indices), growing
   both sides' centroid bounds; the children's boxes are the unions of their bins. Returns
   the number on the left. */
FOGRT__PRIVATE uint32_t fogrt__bins_partition(const fogrt__bins *bins, fogrt__aabb *box,
                                              uint32_t *id, uint32_t count, int ax, int k,
                                              fogrt_bvh_node *child, fogrt__bjob *left,
                                              fogrt__bjob *right) {
    fogrt__aabb side[2];
    uint32_t lo = 0, hi = count;
    side[0] = side[1] = left->cb = right->cb = fogrt__aabb_empty();
    for (int j = 0; j < bins->nb; ++j) fogrt__aabb_union(&side[j >= k], &bins->box[ax][j]);
    fogrt__node_set_box(&child[0], &side[0]);
    fogrt__node_set_box(&child[1], &side[1]);
    while (lo < hi) {
        fogrt__v3 c = fogrt__aabb_centre(&box[lo]);
        if (fogrt__bin_of(bins, c, ax) < k) {
            fogrt__aabb_grow(&left->cb, c);
            ++lo;
        } else {
            fogrt__aabb t = box[lo];
            uint32_t tid = id[lo];
            fogrt__aabb_grow(&right->cb, c);
            --hi;
            box[lo] = box[hi];
            box[hi] = t;
            id[lo] = id[hi];
            id[hi] = tid;
        }
    }
    return lo;
}
/* The binned split of job's node into child[0] and child[1]. Returns the number of
   primitives on the left, or 0 when the node stays a leaf, or must be halved instead
   (*halve: its centroids coincide but it is too big). */
FOGRT__PRIVATE uint32_t fogrt__bvh_split_binned(fogrt__build *b, const fogrt__bjob *job,
                                                fogrt_bvh_node *child, fogrt__bjob *left,
                                                fogrt__bjob *right, bool *halve) {
    const fogrt_bvh_node *node = &b->nodes[job->node];
    uint32_t first = node->left_first, count = node->prim_count;
    fogrt__bins bins;
    float best = FLT_MAX;
    int best_ax = -1, best_k = 0;
#ifndef FOGRT_NO_WIDE_BVH
    uint32_t wide_left_count;
    if (fogrt__split_binned_lanes(b, job, child, left, right, halve, &wide_left_count)) /* SEAM 2 */
        return wide_left_count;
#endif
    fogrt__bins_fill(&bins, &b->desc, &job->cb, b->box + first, count);
    for (int ax = 0; ax < 3; ++ax)
        if (fogrt__comp(bins.scale, ax) > 0.0f &&
            fogrt__bins_sweep(&b->desc, &bins, ax, count, &best, &best_k))
            best_ax = ax;
    if (best_ax < 0) {                                   /* all centroids coincide */
        *halve = count > (uint32_t)b->desc.max_leaf_size;
        return 0;
    }
    if (!fogrt__split_pays(&b->desc, node, count, best)) return 0;
    return fogrt__bins_partition(&bins, b->box + first, b->idx + first, count, best_ax, best_k,
                                 child, left, right);
}
/* Split job's node into the next two nodes, or leave it a leaf (returns false). */
FOGRT__PRIVATE bool fogrt__bvh_split(fogrt__build *b, const fogrt__bjob *job, fogrt__bjob *left,
                                     fogrt__bjob *right) {
    fogrt_bvh_node *node = &b->nodes[job->node], *child = &b->nodes[b->node_count];
    uint32_t first = node->left_first, count = node->prim_count, left_count = 0;
    bool halve = job->depth >= FOGRT__BVH_SAH_DEPTH;
    if (count <= 1 || count <= b->leaf_keep) return false;
    if (!halve) left_count = fogrt__bvh_split_binned(b, job, child, left, right, &halve);
    if (halve) {                                         /* balanced, the bounds by a pass */
        left_count = count / 2;
        fogrt__boxes_bounds(b->box + first, left_count, &child[0], &left->cb);
        fogrt__boxes_bounds(b->box + first + left_count, count - left_count, &child[1], &right->cb);
    }
    if (left_count == 0) return false;
    FOGRT_ASSERT(left_count < count);
    child[0].left_first = first;
    child[0].prim_count = left_count;
    child[1].left_first = first + left_count;
    child[1].prim_count = count - left_count;
    left->node = b->node_count;
    right->node = b->node_count + 1;
    left->depth = right->depth = job->depth + 1;
    node->left_first = b->node_count;
    node->prim_count = 0;
    b->node_count += 2;
    return true;
}
/* The tree over b->box[0 .. prim_count) (b->idx their primitive ids), depth first with an
   explicit stack. */
FOGRT__PRIVATE void fogrt__bvh_build(fogrt__build *b, uint32_t prim_count) {
    fogrt__bjob stack[FOGRT__BVH_MAX_DEPTH + 2];
    uint32_t sp = 1;
    fogrt_bvh_node *root = &b->nodes[0];
    memset(&b->nodes[1], 0, sizeof b->nodes[1]);
    root->left_first = 0;
    root->prim_count = prim_count;
    stack[0].node = stack[0].depth = 0;
    fogrt__boxes_bounds(b->box, prim_count, root, &stack[0].cb);
    b->node_count = 2;
    while (sp > 0) {
        fogrt__bjob job = stack[--sp];
        FOGRT_ASSERT(sp + 2 <= FOGRT__BVH_MAX_DEPTH + 2);
        if (fogrt__bvh_split(b, &job, &stack[sp + 1], &stack[sp]))
            sp += 2; /* the left child on top */
    }
}
/* ------------------------------------------------------------------------------------------
   2.1 (continued) Ray queries: primitives and BVH traversal
   ------------------------------------------------------------------------------------------ */
/* Moller-Trumbore with the edges precomputed. Every test is written so that a NaN (from a
   degenerate, zero-area triangle) fails it: degenerate triangles are never hit. A ray
   parallel to the triangle's plane (|cos| below 1e-6, where the distance is numerically
   meaningless) misses it too. */
FOGRT__HOT bool fogrt__hit_triangle(fogrt__v3 o, fogrt__v3 d, fogrt__v3 v0, fogrt__v3 e1,
                                    fogrt__v3 e2, float tmin, float tmax, float *t, float *u,
                                    float *v) {
    fogrt__v3 pvec = fogrt__cross(d, e2);
    float det = fogrt__dot(e1, pvec);
    if (!(det * det > 1e-12f * fogrt__dot(e1, e1) * fogrt__dot(e2, e2))) return false;
    float inv_det = 1.0f / det;
    fogrt__v3 tvec = fogrt__sub(o, v0);
    float uu = fogrt__dot(tvec, pvec) * inv_det;
    if (!(uu >= 0.0f && uu <= 1.0f)) return false;
    fogrt__v3 qvec = fogrt__cross(tvec, e1);
    float vv = fogrt__dot(d, qvec) * inv_det;
    if (!(vv >= 0.0f && uu + vv <= 1.0f)) return false;
    float tt = fogrt__dot(e2, qvec) * inv_det;
    if (!(tt > tmin && tt < tmax)) return false;
    *t = tt;
    *u = uu;
    *v = vv;
    return true;
}
/* Ray-sphere for a unit direction. The discriminant is formed as r^2 - |oc - b d|^2 (the
   squared distance of the centre from the line), which does not cancel for distant spheres,
   and the nearer root comes from q = -b - sign(b) sqrt(disc) (no cancellation either). */
FOGRT__HOT bool fogrt__hit_sphere(fogrt__v3 o, fogrt__v3 d, fogrt__v3 c, float r, float tmin,
                                  float tmax, float *t) {
    fogrt__v3 oc = fogrt__sub(o, c);
    float b = fogrt__dot(oc, d);
    fogrt__v3 f = fogrt__madd(oc, d, -b);
    float disc = r * r - fogrt__dot(f, f);
    if (!(disc >= 0.0f)) return false;
    float sq = sqrtf(disc), cc = fogrt__dot(oc, oc) - r * r;
    float q = b > 0.0f ? -(b + sq) : (sq - b), t0 = q, t1 = q != 0.0f ? cc / q : q;
    if (t0 > t1) {
        float tmp = t0;
        t0 = t1;
        t1 = tmp;
    }
    float nearest = t0 > tmin && t0 < tmax ? t0 : t1;   /* the nearer root in range, if any */
    if (!(nearest > tmin && nearest < tmax)) return false;
    *t = nearest;
    return true;
}

/* The reciprocal of a direction component, never a division by zero: +-0 (and anything
   too small to invert) becomes +-infinity with the sign of the zero. */
FOGRT__PRIVATE float fogrt__safe_rcp(float x) {
    return fabsf(x) > 1e-30f ? 1.0f / x : copysignf(INFINITY, x);
}

/* A ray prepared for the box tests: its origin and reciprocal direction. */
typedef struct fogrt__ray { fogrt__v3 o, inv; } fogrt__ray;

/* Slab test: entry distance of the ray into the node's box, or FLT_MAX on a miss. On each
   axis the near face is bmin where the direction is positive, bmax where it is negative.
   An axis-parallel ray whose origin lies exactly on a slab's face forms 0 * infinity = NaN
   for that face; every comparison below is written so that a NaN bound is ignored (the
   ray is inside that slab), as in pbrt. The exit distance is widened by 2 ulps so a ray
   grazing a face is not lost to rounding. */
FOGRT__HOT float fogrt__slab(const fogrt_bvh_node *n, const fogrt__ray *r, float tmin, float tmax) {
    float t0 = tmin, t1 = tmax;
    for (int a = 0; a < 3; ++a) {
        float inv = fogrt__comp(r->inv, a), o = fogrt__comp(r->o, a);
        float tn = ((inv < 0.0f ? n->bmax[a] : n->bmin[a]) - o) * inv;
        float tf = ((inv < 0.0f ? n->bmin[a] : n->bmax[a]) - o) * inv;
        t0 = tn > t0 ? tn : t0;
        t1 = tf < t1 ? tf : t1;
    }
    return t0 <= t1 * 1.00000024f ? t0 : FLT_MAX;
}

/* Culling slack: a box is skipped only when its entry lies beyond the closest hit by more
   than 1e-5 (relative, about 100 ulps). The box's entry distance and the triangle's hit
   distance are rounded separately, so near a shared edge the box that holds the truly
   closest triangle can appear to start a few ulps after a neighbour's hit; a strict test
   then skips it and returns the neighbour (about 1 ray in 2000 on the CS184 bunny, found
   by bench/wide_dev.c). The slack gives the brute-force answer there and costs nothing
   measurable; a hit itself still needs t < tmax exactly. */
#define FOGRT__CULL_SLACK 1e-5f
FOGRT__HOT float fogrt__cull(float tmax) {   /* tmax, widened; +-inf and NaN unchanged */
    return tmax * (tmax > 0.0f ? 1.0f + FOGRT__CULL_SLACK : 1.0f - FOGRT__CULL_SLACK);
}
/* Iterative traversal of the binary tree with a fixed stack: visit the nearer child first,
   push the farther, and skip a popped node whose entry lies beyond the closest hit found so
   far. any_hit: return at the first hit (shadow rays). */
FOGRT__PRIVATE bool fogrt__bvh2_traverse(const fogrt_scene *s, fogrt__v3 o, fogrt__v3 d, float tmin,
                                         float tmax, fogrt_hit *hit, bool any_hit) {
    uint32_t stack[FOGRT__BVH_MAX_DEPTH + 2], sp = 0, tri_count = s->tri_count;
    float stack_t[FOGRT__BVH_MAX_DEPTH + 2];
    const fogrt_bvh_node *nodes = s->nodes, *node = &nodes[0];
    bool found = false;
    float cull = fogrt__cull(tmax);                      /* tmax with the slack, kept with it */
    if (!s->built || s->tri_count + s->sph_count == 0) return false;
    fogrt__ray r = { o, { fogrt__safe_rcp(d.x), fogrt__safe_rcp(d.y), fogrt__safe_rcp(d.z) } };
    if (fogrt__slab(node, &r, tmin, tmax) == FLT_MAX) return false;
    for (;;) {
        if (node->prim_count > 0) {                      /* leaf: test its primitives */
            uint32_t end = node->left_first + node->prim_count;
            for (uint32_t i = node->left_first; i < end; ++i) {
                const fogrt__prim *p = &s->prims[i];
                float t, u = 0.0f, v = 0.0f;
                bool h = p->id < tri_count ? fogrt__hit_triangle(o, d, p->a, p->b, p->c, tmin, tmax,
                                                                 &t, &u, &v)
                                           : fogrt__hit_sphere(o, d, p->a, p->b.x, tmin, tmax, &t);
                if (h) {
                    found = true;
                    tmax = t;
                    cull = fogrt__cull(t);
                    if (any_hit) return true;
                    hit->t = t;
                    hit->prim = p->id;
                    hit->u = u;
                    hit->v = v;
                }
            }
        } else {                                         /* inner: order the two children */
            const fogrt_bvh_node *c1 = &nodes[node->left_first], *c2 = c1 + 1;
            float d1 = fogrt__slab(c1, &r, tmin, cull), d2 = fogrt__slab(c2, &r, tmin, cull);
            if (d1 > d2) {
                float td = d1;
                const fogrt_bvh_node *tn = c1;
                d1 = d2;
                d2 = td;
                c1 = c2;
                c2 = tn;
            }
            if (d1 != FLT_MAX) {
                if (d2 != FLT_MAX) {
                    stack_t[sp] = d2;
                    stack[sp++] = (uint32_t)(c2 - nodes);
                }
                node = c1;
                continue;
            }
        }
        /* pop the next node that can still hold a closer hit */
        for (;;) {
            if (sp == 0) return found;
            --sp;
            if (stack_t[sp] <= cull) break;
        }
        node = &nodes[stack[sp]];
    }
}

/* The scene's ray query: the binary tree above, or the wide tree of Part II (A) when the
   build made one. */
FOGRT__PRIVATE bool fogrt__traverse(const fogrt_scene *s, fogrt__v3 o, fogrt__v3 d, float tmin,
                                    float tmax, fogrt_hit *hit, bool any_hit) {
#ifndef FOGRT_NO_WIDE_BVH
    bool done, found = fogrt__wide_traverse(s, o, d, tmin, tmax, hit, any_hit, &done);  /* SEAM 1 */
    if (done) return found;
#endif
    return fogrt__bvh2_traverse(s, o, d, tmin, tmax, hit, any_hit);
}
/* ------------------------------------------------------------------------------------------
   2.2 The Bidirectional Scattering Distribution Function: diffuse, mirror, refraction, glass
   All four BSDFs work in the local shading frame (normal +z). Diffuse and mirror reflect on
   both sides (they answer on the side wo is on); refraction and glass use the sign of wo.z
   to tell entering (wo.z > 0) from leaving (wo.z < 0). A rough metal (Part II, I) reflects
   on both sides too, and like diffuse has a density that light sampling and MIS use.
   ------------------------------------------------------------------------------------------ */
FOGRT__PRIVATE void fogrt__concentric_disk(float u1, float u2, float *x, float *y) {
    float a = 2.0f * u1 - 1.0f, b = 2.0f * u2 - 1.0f;
    *x = *y = 0.0f;
    if (a == 0.0f && b == 0.0f) return;
    bool wide = fabsf(a) > fabsf(b);
    float r = wide ? a : b, phi = wide ? (FOGRT__PI / 4.0f) * (b / a)
                                       : FOGRT__PI / 2.0f - (FOGRT__PI / 4.0f) * (a / b);
    *x = r * cosf(phi);
    *y = r * sinf(phi);
}
/* Cosine-weighted hemisphere: the disk lifted to the hemisphere (Malley). pdf = cos / pi. */
FOGRT__PUBLIC fogrt_vec3 fogrt_sample_cosine_hemisphere(float u1, float u2) {
    float x, y;   /* a point of the unit disk */
    fogrt__concentric_disk(u1, u2, &x, &y);
    return fogrt__v(x, y, sqrtf(FOGRT__MAX(0.0f, 1.0f - x * x - y * y)));
}
FOGRT__PUBLIC float fogrt_cosine_hemisphere_pdf(float cos_theta) {
    return cos_theta > 0.0f ? cos_theta * FOGRT__INV_PI : 0.0f;
}
FOGRT__PUBLIC fogrt_vec3 fogrt_reflect(fogrt_vec3 n, fogrt_vec3 wo) {
    return fogrt__sub(fogrt__scale(n, 2.0f * fogrt__dot(wo, n)), wo);
}
#ifndef FOGRT_NO_GLASS
/* Schlick: F = R0 + (1 - R0)(1 - c)^5 with R0 = ((eta-1)/(eta+1))^2, and c the cosine on the
   optically thinner side: the incident cosine when entering, the transmitted one when
   leaving (using cos_i there would be wrong). Total internal reflection is tested first. */
FOGRT__PUBLIC float fogrt_fresnel_schlick(float eta, float cos_i) {
    float r0 = (eta - 1.0f) / (eta + 1.0f), c;
    r0 *= r0;
    cos_i = FOGRT__CLAMP(cos_i, -1.0f, 1.0f);
    if (eta < 1.0f) {                                   /* make the inside the denser side */
        cos_i = -cos_i;
        eta = 1.0f / eta;
    }
    if (cos_i >= 0.0f) {
        c = cos_i;
    } else {                                            /* leaving: n = eta -> n = 1 */
        float sin2_t = (1.0f - cos_i * cos_i) * eta * eta;
        if (sin2_t >= 1.0f) return 1.0f;                /* total internal reflection */
        c = sqrtf(1.0f - sin2_t);
    }
    float m = 1.0f - c;
    return r0 + (1.0f - r0) * m * m * m * m * m;
}
/* Snell's law: wi = -wo/eta + (cos_i/eta - cos_t) n, after flipping n (and eta) to wo's side. */
FOGRT__PUBLIC bool fogrt_refract(fogrt_vec3 n, float eta, fogrt_vec3 wo, fogrt_vec3 *wi) {
    float cos_i = fogrt__dot(n, wo);
    if (cos_i < 0.0f) {
        eta = 1.0f / eta;
        cos_i = -cos_i;
        n = fogrt__neg(n);
    }
    float sin2_i = FOGRT__MAX(0.0f, 1.0f - cos_i * cos_i), sin2_t = sin2_i / (eta * eta);
    if (sin2_t >= 1.0f) return false;
    float cos_t = sqrtf(1.0f - sin2_t);
    *wi = fogrt__normalize(
            fogrt__add(fogrt__scale(wo, -1.0f / eta), fogrt__scale(n, cos_i / eta - cos_t)));
    return true;
}
FOGRT__PRIVATE float fogrt__fresnel(fogrt_fresnel mode, float eta, float cos_i) {
    (void)mode;   /* unread without exact Fresnel, which fogrt_render then refuses */
#ifndef FOGRT_NO_EXACT_FRESNEL
    if (mode == FOGRT_FRESNEL_EXACT) return fogrt_fresnel_dielectric(eta, cos_i);   /* SEAM 5 (C) */
#endif
    return fogrt_fresnel_schlick(eta, cos_i);
}
/* Refraction and glass: reflect with probability F (glass) or only on total internal
   reflection (refraction), else refract. The probability is the lobe's discrete pdf. */
FOGRT__PRIVATE void fogrt__sample_dielectric(const fogrt_material_desc *m, fogrt_fresnel fresnel,
                                             fogrt__v3 wo, float u_lobe, fogrt_bsdf_sample *out) {
    fogrt__v3 wt;
    float eta = FOGRT__DEF(m->ior, 1.5f);
    bool can_refract = fogrt_refract(fogrt__v(0.0f, 0.0f, 1.0f), eta, wo, &wt);
    float F = m->type == FOGRT_BSDF_GLASS ? fogrt__fresnel(fresnel, eta, wo.z) : 0.0f;
    if (!can_refract) F = 1.0f;
    out->is_delta = true;
    if (u_lobe < F) {                                    /* reflect with probability F */
        out->wi = fogrt__v(-wo.x, -wo.y, wo.z);
        out->weight = m->type == FOGRT_BSDF_GLASS ? m->reflectance : m->transmittance;
        out->pdf = F;
    } else {                                             /* refract with probability 1 - F */
        out->wi = wt;
        out->weight = m->transmittance;
        out->pdf = 1.0f - F;
        out->is_transmission = true;
    }
}
#endif /* FOGRT_NO_GLASS */
FOGRT__PRIVATE fogrt_bsdf_type fogrt__bsdf_type(const fogrt_material_desc *m) {
    return m->type == FOGRT_BSDF_DEFAULT ? FOGRT_BSDF_DIFFUSE : m->type;
}
FOGRT__PRIVATE bool fogrt__bsdf_is_delta(fogrt_bsdf_type t) {
    return t != FOGRT_BSDF_DIFFUSE && t != FOGRT_BSDF_MICROFACET;
}
FOGRT__PUBLIC bool fogrt_sample_bsdf(const fogrt_material_desc *m, fogrt_fresnel fresnel,
                                     fogrt_vec3 wo, float u_lobe, float u1, float u2,
                                     fogrt_bsdf_sample *out) {
    fogrt_bsdf_type type = fogrt__bsdf_type(m);
    memset(out, 0, sizeof *out);
    if (wo.z == 0.0f) return false;                      /* exactly on the horizon */
    if (type == FOGRT_BSDF_MIRROR) {
        out->wi = fogrt__v(-wo.x, -wo.y, wo.z);
        out->weight = m->reflectance;
        out->pdf = 1.0f;
        out->is_delta = true;
        return true;
    }
#ifndef FOGRT_NO_GLASS
    if (type == FOGRT_BSDF_REFRACTION || type == FOGRT_BSDF_GLASS) {
        fogrt__sample_dielectric(m, fresnel, wo, u_lobe, out);
        return true;
    }
#else
    if (type == FOGRT_BSDF_REFRACTION || type == FOGRT_BSDF_GLASS) return false;   /* stripped */
#endif
    if (type == FOGRT_BSDF_INTERFACE) {              /* H's interface: index-matched, straight on */
        out->wi = fogrt__neg(wo);
        out->weight = fogrt__v(1.0f, 1.0f, 1.0f);
        out->pdf = 1.0f;
        out->is_delta = out->is_transmission = true;
        return true;
    }
    FOGRT__MF_SEAM(type, fogrt__mf_sample(m, wo, u1, u2, out));   /* SEAM 5 (I) */
    (void)u_lobe;                                        /* diffuse: cosine-weighted */
    (void)fresnel;
    fogrt__v3 wi = fogrt_sample_cosine_hemisphere(u1, u2);
    if (wi.z <= 0.0f) return false;
    if (wo.z < 0.0f) wi.z = -wi.z;                       /* on wo's side */
    out->wi = wi;
    out->weight = m->reflectance;                        /* (rho/pi) cos / (cos/pi) = rho */
    out->pdf = fabsf(wi.z) * FOGRT__INV_PI;
    return true;
}
/* Diffuse, or zero (the delta BSDFs, or wo and wi on opposite sides). Forced inline: light
   sampling evaluates it once per sample. */
FOGRT__HOT fogrt__v3 fogrt__bsdf_f(const fogrt_material_desc *m, fogrt__v3 wo, fogrt__v3 wi) {
    if (fogrt__bsdf_type(m) != FOGRT_BSDF_DIFFUSE || !(wo.z * wi.z > 0.0f)) {
        FOGRT__MF_SEAM(m->type, fogrt__mf_eval(m, wo, wi));   /* SEAM 5 (I) */
        return fogrt__v(0.0f, 0.0f, 0.0f);
    }
    return fogrt__scale(m->reflectance, FOGRT__INV_PI);
}
FOGRT__PUBLIC fogrt_vec3 fogrt_bsdf_eval(const fogrt_material_desc *m, fogrt_vec3 wo,
                                         fogrt_vec3 wi) {
    return fogrt__bsdf_f(m, wo, wi);
}
FOGRT__PUBLIC float fogrt_bsdf_pdf(const fogrt_material_desc *m, fogrt_vec3 wo, fogrt_vec3 wi) {
    if (fogrt__bsdf_type(m) != FOGRT_BSDF_DIFFUSE || !(wo.z * wi.z > 0.0f)) {
        FOGRT__MF_SEAM(m->type, fogrt__mf_pdf(m, wo, wi));   /* SEAM 5 (I) */
        return 0.0f;
    }
    return fabsf(wi.z) * FOGRT__INV_PI;
}
/* ------------------------------------------------------------------------------------------
   2.3 Monte Carlo sampling (paper eq. 3): lights, light sampling, MIS
   The light a vertex reflects, eq. 3, is estimated from sampled directions: f L cos / p.
   Directions come two ways: from the BSDF (or the phase function in fog), and toward the
   lights ("importance sampling" in the paper's section 4.2; next-event estimation). At every
   scattering vertex (a surface or a point in the fog) each light is sampled and a shadow
   ray decides visibility (in fog it also carries the transmittance of 3.2). An area light
   can be found both ways, so the two are combined by multiple importance sampling (power
   heuristic, Veach 1997), counting the light_samples samples per light:
   w_light = (n p_light)^2 / ((n p_light)^2 + p_bsdf^2).
   The lights are numbered as one list: the point and spot lights first, then the area
   lights (emissive meshes and spheres), so one function samples any of them.
   Point lights: irradiance I / r^2 is unbounded as r -> 0, so r^2 is clamped from below at
   (1e-4 x scene diagonal)^2 (a documented bias that only touches points that close), and a
   point exactly at the light receives nothing from it (its direction is undefined). A light
   with a radius is a spherical emitter instead and has no such spike.
   ------------------------------------------------------------------------------------------ */
/* What the integrators read from a render desc. */
typedef struct fogrt__settings {
    fogrt_render_desc desc;    /* checked: nee, mis, min_depth, rr_depth, light_samples, ... */
    int max_depth;             /* -1 (no limit) as the largest int */
    fogrt_integrator integrator;
} fogrt__settings;

/* A scattering vertex: a point in the medium, or a surface point with its shading frame. */
typedef struct fogrt__vertex {
    fogrt__v3 p, wo;
    bool in_medium;            /* the vertex lies in the fog (shadow rays are attenuated) */
    bool is_medium;            /* a fog scattering event (else a surface) */
    fogrt__frame frame;        /* surface: shading frame */
    fogrt__v3 ng;              /* surface: geometric normal on the side of wo */
    const fogrt_material_desc *m;
} fogrt__vertex;
FOGRT__PUBLIC fogrt_vec3 fogrt_sample_uniform_sphere(float u1, float u2) {
    float z = 1.0f - 2.0f * u1;
    float r = sqrtf(FOGRT__MAX(0.0f, (1.0f - z) * (1.0f + z)));
    float phi = 2.0f * FOGRT__PI * u2;
    return fogrt__v(r * cosf(phi), r * sinf(phi), z);
}
FOGRT__PUBLIC float fogrt_uniform_sphere_pdf(void) { return FOGRT__INV_4PI; }
/* Uniform on a triangle: b0 = 1 - sqrt(u1), b1 = sqrt(u1)(1 - u2), b2 = sqrt(u1) u2. */
FOGRT__PUBLIC void fogrt_sample_triangle(float u1, float u2, float *b1, float *b2) {
    float su = sqrtf(FOGRT__MAX(0.0f, u1));
    *b1 = su * (1.0f - u2);
    *b2 = su * u2;
}
/* Cone of directions subtended by a sphere: cos(theta_max) = sqrt(1 - r^2/d^2). 1 - cos is
   formed as sin^2 / (1 + cos), which stays accurate for a small or distant sphere. */
FOGRT__PRIVATE float fogrt__sphere_one_minus_cos_max(fogrt__v3 c, float r, fogrt__v3 p,
                                                     float *dist) {
    fogrt__v3 pc = fogrt__sub(c, p);
    float d2 = fogrt__dot(pc, pc);
    *dist = sqrtf(d2);
    if (d2 <= r * r) return -1.0f;                       /* inside (or on) the sphere */
    float sin2_max = r * r / d2, cos_max = sqrtf(FOGRT__MAX(0.0f, 1.0f - sin2_max));
    return sin2_max / (1.0f + cos_max);
}
/* The direction whose angle theta from the frame's axis has 1 - cos theta = omc, at azimuth
   2 pi u: sin theta from omc (2 - omc), which stays accurate next to the axis. Drawing omc
   uniformly in [0, 1 - cos theta_max) samples a cone uniformly (spheres here, spot lights'
   footprints below). */
FOGRT__HOT fogrt__v3 fogrt__in_cone(const fogrt__frame *f, float omc, float u) {
    return fogrt__direction_at(f, 1.0f - omc, sqrtf(FOGRT__MAX(0.0f, omc * (2.0f - omc))), u);
}
FOGRT__PUBLIC fogrt_vec3 fogrt_sample_sphere_solid_angle(fogrt_vec3 center, float radius,
                                                         fogrt_vec3 p, float u1, float u2,
                                                         float *pdf) {
    float dist, omc = fogrt__sphere_one_minus_cos_max(center, radius, p, &dist);
    if (omc <= 0.0f) {   /* inside: every direction sees the sphere */
        if (pdf) *pdf = FOGRT__INV_4PI;
        return fogrt_sample_uniform_sphere(u1, u2);
    }
    fogrt__frame f = fogrt__frame_from_z(fogrt__scale(fogrt__sub(center, p), 1.0f / dist));
    if (pdf) *pdf = 1.0f / (2.0f * FOGRT__PI * omc);
    return fogrt__in_cone(&f, u1 * omc, u2);
}
FOGRT__PUBLIC float fogrt_sphere_solid_angle_pdf(fogrt_vec3 center, float radius, fogrt_vec3 p) {
    float dist, omc = fogrt__sphere_one_minus_cos_max(center, radius, p, &dist);
    return omc <= 0.0f ? FOGRT__INV_4PI : 1.0f / (2.0f * FOGRT__PI * omc);
}
/* Spot profile: full inside the beam, linear in the angle down to zero at the cutoff. */
FOGRT__PUBLIC float fogrt_spot_falloff(float cutoff_deg, float beam_deg, float cos_theta) {
    float theta = acosf(FOGRT__CLAMP(cos_theta, -1.0f, 1.0f)) * (180.0f / FOGRT__PI);
    if (!(cutoff_deg > beam_deg)) return theta <= cutoff_deg ? 1.0f : 0.0f;   /* hard cone */
    return FOGRT__CLAMP((cutoff_deg - theta) / (cutoff_deg - beam_deg), 0.0f, 1.0f);
}

/* The same profile for a light of a built scene, from its two cosines (s->spot_cos: the
   cutoff's, the beam's): outside the band between them, by a margin far above acosf's
   rounding, it is 0 or 1 without the acos. */
FOGRT__PRIVATE float fogrt__spot_profile(const fogrt_light_desc *l, const float *cosines,
                                         float cos_theta) {
    if (cos_theta < cosines[0] - 1e-4f) return 0.0f;
    if (cos_theta > cosines[1] + 1e-4f) return 1.0f;
    return fogrt_spot_falloff(l->cutoff_deg, l->beam_deg, cos_theta);
}
FOGRT__PRIVATE float fogrt__power_heuristic(float a, float b) {
    if (!(a > 0.0f)) return 0.0f;
    float r = b / a;
    if (!(r == r)) return 0.0f;
    return 1.0f / (1.0f + r * r);     /* = a^2 / (a^2 + b^2), without overflow */
}
/* Distance to push a new ray's origin off a surface: scale-aware, a few ulps of |p|. */
FOGRT__PRIVATE float fogrt__offset_size(const fogrt_scene *s, fogrt__v3 p) {
    return s->eps + 1e-5f * FOGRT__MAX(fabsf(p.x), FOGRT__MAX(fabsf(p.y), fabsf(p.z)));
}
FOGRT__PRIVATE fogrt__v3 fogrt__offset(const fogrt_scene *s, fogrt__v3 p, fogrt__v3 n,
                                       fogrt__v3 w) {
    float e = fogrt__offset_size(s, p);
    return fogrt__madd(p, n, fogrt__dot(w, n) > 0.0f ? e : -e);
}

/* What the vertex sends toward -wi from light arriving along wi: f |cos| at a surface (in
   world space, with the geometric-side test against light leaks), the phase function in the
   fog. *pdf is the density with which BSDF / phase sampling would have chosen wi. */
FOGRT__HOT fogrt__v3 fogrt__vertex_f(const fogrt_scene *s, const fogrt__vertex *v, fogrt__v3 wi,
                                     float *pdf) {
    (void)s;                                             /* read by the fog's branch only */
#ifndef FOGRT_NO_MEDIUM
    if (v->is_medium) {
        float p = fogrt_hg_pdf(s->medium.g, v->wo, wi);
        *pdf = p;
        return fogrt__v(p, p, p);
    }
#endif
    *pdf = 0.0f;
    if (fogrt__dot(wi, v->ng) <= 0.0f) return fogrt__v(0.0f, 0.0f, 0.0f);
    fogrt__v3 wo_l = fogrt__to_local(&v->frame, v->wo), wi_l = fogrt__to_local(&v->frame, wi);
    *pdf = fogrt_bsdf_pdf(v->m, wo_l, wi_l);
    return fogrt__scale(fogrt__bsdf_f(v->m, wo_l, wi_l), fabsf(wi_l.z));
}

/* Point or spot light l seen from x: for a point light simply I(theta) / r^2 along the
   direction to it. A light with a radius is a sphere of radiance I(theta)/(pi R^2), sampled
   uniformly in the cone it subtends (inside it: every direction). The spot profile is
   evaluated from the light's centre. Returns false when x gets nothing. (Forced inline:
   as calls, with Part II's second caller, they cost a fog-free render time.) */
FOGRT__HOT bool fogrt__sample_point_light(const fogrt_scene *s, const fogrt_light_desc *l,
                                          fogrt__v3 x, const float *u, fogrt_light_sample *ls) {
    fogrt__v3 to = fogrt__sub(l->position, x), I = l->intensity;
    float d2 = fogrt__dot(to, to), pdf, t;
    if (!(d2 > 0.0f)) return false;                    /* x is the light: no direction */
    float d = sqrtf(d2);
    if (l->type == FOGRT_LIGHT_SPOT)
        I = fogrt__scale(I, fogrt__spot_profile(l, s->spot_cos + 2 * (l - s->lights),
                                                -fogrt__dot(to, l->direction) / d));
    if (fogrt__is_black(I)) return false;
    ls->pdf = 1.0f;
    ls->is_delta = true;
    if (!(l->radius > 0.0f)) {
        ls->wi = fogrt__scale(to, 1.0f / d);
        ls->dist = d;
        ls->Le = fogrt__scale(I, 1.0f / FOGRT__MAX(d2, s->r2_min));
        return true;
    }
    ls->wi = fogrt_sample_sphere_solid_angle(l->position, l->radius, x, u[0], u[1], &pdf);
    if (d <= l->radius) t = 0.0f;                        /* inside the emitter */
    else if (!fogrt__hit_sphere(x, ls->wi, l->position, l->radius, 0.0f, INFINITY, &t))
        t = fogrt__dot(to, ls->wi);
    ls->dist = t;
    ls->Le = fogrt__scale(I, 1.0f / (FOGRT__PI * l->radius * l->radius * pdf));
    return true;
}

/* Discrete sampling from a CDF (a mesh light's triangles by area, the environment map's
   rows and columns): the index of the first CDF entry above u in cdf[0..n), and the fraction of u
   inside that entry (for a continuous position within it). */
FOGRT__PRIVATE int fogrt__cdf_find(const float *cdf, int n, float u, float *frac) {
    int lo = 0, hi = n - 1;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (cdf[mid] <= u) lo = mid + 1;
        else hi = mid;
    }
    float c0 = lo ? cdf[lo - 1] : 0.0f;
    *frac = cdf[lo] > c0 ? FOGRT__CLAMP((u - c0) / (cdf[lo] - c0), 0.0f, FOGRT__ONE_MINUS_EPS)
                         : 0.5f;
    return lo;
}
/* A point y on a mesh light: a triangle chosen by area (fogrt__cdf_find), then a uniform
   point on it. *ny is its geometric normal. */
FOGRT__HOT uint32_t fogrt__sample_mesh_point(const fogrt_scene *s, const fogrt__area_light *a,
                                             const float *u, fogrt__v3 *y, fogrt__v3 *ny) {
    float b1, b2, frac;
    uint32_t tri = s->light_prims[a->first + (uint32_t)fogrt__cdf_find(s->light_cdf + a->first,
                                                                       (int)a->count, u[0], &frac)];
    const fogrt__v3 *v = &s->tri_v[3 * tri];
    fogrt_sample_triangle(u[1], u[2], &b1, &b2);
    *y = fogrt__add(v[0], fogrt__add(fogrt__scale(fogrt__sub(v[1], v[0]), b1),
                                     fogrt__scale(fogrt__sub(v[2], v[0]), b2)));
    *ny = fogrt__normalize(fogrt__cross(fogrt__sub(v[1], v[0]), fogrt__sub(v[2], v[0])));
    return tri;
}
/* Area light a seen from p: an emissive sphere is sampled in the cone it subtends, a mesh
   by area (pdf 1/A, turned into solid angle). False when the sample is unusable: the back
   of a one-sided emitter, or p inside an emitting sphere. */
FOGRT__HOT bool fogrt__sample_area_light(const fogrt_scene *s, const fogrt__area_light *a,
                                         fogrt__v3 p, const float *u, fogrt_light_sample *ls) {
    fogrt__v3 y, ny;
    ls->is_delta = false;
    if (a->sphere != UINT32_MAX) {
        fogrt__v3 c = s->sph_c[a->sphere];
        float r = s->sph_r[a->sphere], t;
        if (fogrt__dot(fogrt__sub(p, c), fogrt__sub(p, c)) <= r * r)
            return false; /* emits outward only */
        ls->wi = fogrt_sample_sphere_solid_angle(c, r, p, u[1], u[2], &ls->pdf);
        if (!fogrt__hit_sphere(p, ls->wi, c, r, 0.0f, INFINITY, &t))
            t = fogrt__dot(fogrt__sub(c, p), ls->wi);
        ls->dist = t;
        ls->Le = s->materials[s->sph_material[a->sphere]].emission;
        return ls->pdf > 0.0f && !fogrt__is_black(ls->Le);
    }
    ls->Le = s->materials[s->tri_material[fogrt__sample_mesh_point(s, a, u, &y, &ny)]].emission;
    fogrt__v3 to = fogrt__sub(y, p);
    float d2 = fogrt__dot(to, to);
    if (!(d2 > 0.0f)) return false;
    ls->dist = sqrtf(d2);
    ls->wi = fogrt__scale(to, 1.0f / ls->dist);
    float cos_l = -fogrt__dot(ls->wi, ny);
    if (!(cos_l > 0.0f)) return false;                   /* the back of a one-sided emitter */
    ls->pdf = d2 / (cos_l * a->area);                    /* area pdf 1/A -> solid angle */
    return ls->pdf > 0.0f && !fogrt__is_black(ls->Le);
}
/* The solid-angle pdf with which light sampling would have chosen the emitter point y (on
   primitive prim, geometric normal ny) from p: the MIS partner of BSDF sampling. */
FOGRT__PRIVATE float fogrt__area_light_pdf(const fogrt_scene *s, uint32_t prim, fogrt__v3 p,
                                           fogrt__v3 y, fogrt__v3 ny) {
    uint32_t li = s->prim_light[prim];
    if (li == UINT32_MAX) return 0.0f;
    const fogrt__area_light *a = &s->area_lights[li];
    if (a->sphere != UINT32_MAX) {
        fogrt__v3 c = s->sph_c[a->sphere];
        float r = s->sph_r[a->sphere];
        if (fogrt__dot(fogrt__sub(p, c), fogrt__sub(p, c)) <= r * r) return 0.0f;
        return fogrt_sphere_solid_angle_pdf(c, r, p);
    }
    fogrt__v3 to = fogrt__sub(y, p);
    float d2 = fogrt__dot(to, to), cos_l = fabsf(fogrt__dot(fogrt__normalize(to), ny));
    return cos_l > 0.0f ? d2 / (cos_l * a->area) : 0.0f;
}
/* One numbering of all lights (point and spot, then area), so that one call samples any. */
FOGRT__PUBLIC uint32_t fogrt_scene_light_total(const fogrt_scene *s) {
    return s->light_count + s->area_light_count;
}
FOGRT__PUBLIC bool fogrt_scene_sample_light(const fogrt_scene *s, uint32_t light, fogrt_vec3 p,
                                            float u1, float u2, float u3, fogrt_light_sample *ls) {
    FOGRT_ASSERT(s && s->built && ls && light < fogrt_scene_light_total(s));
    float u[3] = { u1, u2, u3 };
    if (light < s->light_count) return fogrt__sample_point_light(s, &s->lights[light], p, u, ls);
    return fogrt__sample_area_light(s, &s->area_lights[light - s->light_count], p, u, ls);
}
/* The environment's radiance in direction d (a constant; Part II, C, adds maps). */
FOGRT__PRIVATE fogrt__v3 fogrt__env_radiance(const fogrt_scene *s, fogrt__v3 d) {
    return s->env_upper_only && !(d.y > 0.0f) ? fogrt__v(0.0f, 0.0f, 0.0f) : s->env;
}
/* ------------------------------------------------------------------------------------------
   3.1 Exponential fog particle sampling: free flight (paper eq. 4-6)
   Fog particles are spread uniformly, so collisions along a ray are a Poisson process with
   rate lambda = sigma_t: no collision within t has probability exp(-sigma_t t) (eq. 4), a
   collision has 1 - exp(-sigma_t t) (eq. 5), the CDF of the exponential distribution (eq.
   6), whose density is sigma_t exp(-sigma_t t). Inverting the CDF at a uniform u gives the
   paper's t = -ln(1 - u) / sigma_t. u < 1 always (the RNG never returns 1), so t is finite;
   the tail beyond 16.6 mean free paths is cut (bias ~ 6e-8). Below u = 2^-8, log1p(-u)
   keeps the digits that ln(1 - u) would lose; above it 1 - u is exact for the renderer's
   uniforms (multiples of 2^-24), and logf is cheaper.
   ------------------------------------------------------------------------------------------ */
#ifndef FOGRT_NO_MEDIUM
FOGRT__PUBLIC float fogrt_sample_exponential(float sigma_t, float u) {
    if (!(sigma_t > 0.0f)) return INFINITY;            /* no medium: never collide */
    u = FOGRT__MIN(u, FOGRT__ONE_MINUS_EPS);
    return -(u < 0.00390625f ? log1pf(-u) : logf(1.0f - u)) / sigma_t;
}
FOGRT__PUBLIC float fogrt_exponential_pdf(float sigma_t, float t) {
    if (!(sigma_t > 0.0f) || t < 0.0f) return 0.0f;
    return sigma_t * expf(-sigma_t * t);
}
FOGRT__PUBLIC float fogrt_exponential_cdf(float sigma_t, float t) {
    if (!(sigma_t > 0.0f) || t <= 0.0f) return 0.0f;
    return -expm1f(-sigma_t * t);
}
#endif /* FOGRT_NO_MEDIUM */
/* ------------------------------------------------------------------------------------------
   3.2 Light attenuation through fog (paper eq. 7-8)
   dL = -sigma_t L dt (eq. 7) integrates, in a homogeneous medium, to L = L0 exp(-sigma_t t)
   (eq. 8): Beer-Lambert. The fraction exp(-sigma_t t) is the transmittance T(t). A shadow
   ray through fog carries it in closed form; a path's free flight (3.1) needs no T at all,
   since the collision's pdf sigma_t T cancels it.
   ------------------------------------------------------------------------------------------ */
#ifndef FOGRT_NO_MEDIUM
/* Beer-Lambert: the fraction of light that crosses a distance without colliding. */
FOGRT__PUBLIC float fogrt_transmittance(float sigma_t, float distance) {
    if (!(sigma_t > 0.0f) || !(distance > 0.0f)) return 1.0f;
    return expf(-sigma_t * distance);   /* underflows to 0 for optical depth > ~87: correct */
}
/* Eq. 8 along o + t d for t in [0, dist]: exp(-sigma_t x the length in fog). */
FOGRT__HOT float fogrt__fog_transmittance(const fogrt_scene *s, fogrt__v3 o, fogrt__v3 d,
                                          float dist) {
    (void)o;                                             /* o, d: read by Part II's bounded fog */
    (void)d;
#ifndef FOGRT_MINIMAL
    float a, b;
    if (s->x && !fogrt__fog_box_span(s, o, d, dist, &a, &b)) return 1.0f; /* SEAM 6: fog in a box */
    if (s->x) dist = b - a;
#endif
    return fogrt_transmittance(s->medium.sigma_t, dist);
}
#endif

/* Visibility times transmittance (eq. 8) between the vertex and the light sample's point.
   The shadow ray starts at the offset origin and aims at the target itself, stopping a ray
   offset short of it (the target may lie on a surface: the emitter). */
FOGRT__HOT float fogrt__shadow(const fogrt_scene *s, const fogrt__vertex *v,
                               const fogrt_light_sample *ls, uint64_t *rays) {
    fogrt__v3 o = v->is_medium ? v->p : fogrt__offset(s, v->p, v->ng, ls->wi);
    ++*rays;
    if (!(ls->dist < INFINITY)) {                        /* toward the environment */
        if (fogrt__traverse(s, o, ls->wi, 0.0f, INFINITY, NULL, true)) return 0.0f;
    } else {
        fogrt__v3 y = fogrt__madd(v->p, ls->wi, ls->dist), to = fogrt__sub(y, o);
        float len = fogrt__length(to), tmax = len - fogrt__offset_size(s, y);
        if (tmax > 0.0f &&
            fogrt__traverse(s, o, fogrt__scale(to, 1.0f / len), 0.0f, tmax, NULL, true))
            return 0.0f;
    }
#ifndef FOGRT_NO_MEDIUM
    if (v->in_medium) return fogrt__fog_transmittance(s, v->p, ls->wi, ls->dist);
#endif
    return 1.0f;
}
/* ------------------------------------------------------------------------------------------
   3.3 Fog scattering: the Henyey-Greenstein phase function (paper eq. 9-12)
   ------------------------------------------------------------------------------------------ */
#ifndef FOGRT_NO_MEDIUM
FOGRT__PRIVATE float fogrt__clamp_g(float g) {
    if (!(g == g)) return 0.0f;
    return FOGRT__CLAMP(g, -FOGRT_HG_G_MAX, FOGRT_HG_G_MAX);
}
/* p(mu) = (1 - g^2) / (4 pi (1 + g^2 - 2 g mu)^(3/2)). The base 1 + g^2 - 2 g mu is written
   as a sum of non-negative terms, so it does not cancel near the peak when |g| -> 1:
   g >= 0: (1 - g)^2 + 2g(1 - mu);  g < 0: (1 + g)^2 - 2g(1 + mu).  The arguments are 1 - mu
   and 1 + mu, so a caller that knows them exactly (the sampler) loses nothing.            */
FOGRT__PRIVATE float fogrt__hg_phase_pm(float g, float one_minus_mu, float one_plus_mu) {
    float base = g >= 0.0f ? (1.0f - g) * (1.0f - g) + 2.0f * g * one_minus_mu
                           : (1.0f + g) * (1.0f + g) - 2.0f * g * one_plus_mu;
    return FOGRT__INV_4PI * (1.0f - g) * (1.0f + g) / (base * sqrtf(base));
}
FOGRT__PUBLIC float fogrt_hg_phase(float g, float mu) {
    mu = FOGRT__CLAMP(mu, -1.0f, 1.0f);
    return fogrt__hg_phase_pm(fogrt__clamp_g(g), 1.0f - mu, 1.0f + mu);
}
/* D = (1 - g) + 2 g u, as a sum of two non-negative terms: for g < 0 and u -> 1 the direct
   form would cancel, so it is written (1 + g) - 2 g (1 - u) there. */
FOGRT__PRIVATE float fogrt__hg_D(float g, float u) {
    return g >= 0.0f ? (1.0f - g) + 2.0f * g * u : (1.0f + g) - 2.0f * g * (1.0f - u);
}
/* Eq. 10-11: the inverse of HG's CDF. As the paper writes it (one_minus_mu NULL),
     mu = (1 + g^2 - s^2) / (2 g),  s = (1 - g^2) / D,  D = 1 - g + 2 g u,
   it divides 0 by 0 at g = 0 (the limit is isotropic, 2u - 1), and for small |g| subtracts
   nearly equal numbers and divides the rounding by 2g: its error grows like 1e-7 / |g|
   (test_hg_eq11_matches_stable_form). The renderer asks for 1 - mu and 1 + mu, and gets eq. 11
   rearranged: 2 g (1 - mu) = s^2 - (1 - g)^2 and 2 g (1 + mu) = (1 + g)^2 - s^2, each a
   difference of squares, with 1 + g - D = 2 g (1 - u) and D - (1 - g) = 2 g u, give
     1 - mu = (1 - g)^2 (1 - u) (1 + g + D) / D^2,   1 + mu = (1 + g)^2 u (1 - g + D) / D^2:
   no division by g and nothing that cancels. Near the peak (|g| -> 1) mu itself rounds to
   +-1 long before the angle is 0 (at g = 0.99 one sample in 2000 would land on the peak
   direction); sin(theta) = sqrt((1 - mu)(1 + mu)) from these keeps its full precision. */
FOGRT__PRIVATE float fogrt__sample_hg_mu_eq11(float g, float u, float *one_minus_mu,
                                              float *one_plus_mu) {
    if (one_minus_mu) {                       /* the cancellation-free branch: eq. 11 rearranged */
        float D = fogrt__hg_D(g, u), D2 = D * D;
        *one_minus_mu = FOGRT__CLAMP((1.0f - g) * (1.0f - g) * (1.0f - u) * (1.0f + g + D) / D2,
                                     0.0f, 2.0f);
        *one_plus_mu = FOGRT__CLAMP((1.0f + g) * (1.0f + g) * u * (1.0f - g + D) / D2, 0.0f, 2.0f);
        /* mu from the nearer end: no rounding */
        return *one_minus_mu < *one_plus_mu ? 1.0f - *one_minus_mu : *one_plus_mu - 1.0f;
    }
    if (g == 0.0f) return 2.0f * u - 1.0f;
    float s = (1.0f - g * g) / (1.0f - g + 2.0f * g * u);
    return FOGRT__CLAMP((1.0f + g * g - s * s) / (2.0f * g), -1.0f, 1.0f);
}
/* The same inverse as mu, expanded so that nothing divides by g:
     mu = (2u - (1 - g)) / D + 2 g (1 - g)(1 + g) u (1 - u) / D^2.
   g = 0 gives mu = 2u - 1 (isotropic) with no special branch; u = 0 gives -1, u -> 1 gives 1. */
FOGRT__PUBLIC float fogrt_sample_hg_mu(float g, float u) {
    g = fogrt__clamp_g(g);
    u = FOGRT__CLAMP(u, 0.0f, 1.0f);
    float D = fogrt__hg_D(g, u);
    float mu = (2.0f * u - (1.0f - g)) / D +
               2.0f * g * (1.0f - g) * (1.0f + g) * u * (1.0f - u) / (D * D);
    return FOGRT__CLAMP(mu, -1.0f, 1.0f);
}
/* The same for a unit wo (the integrator's, which skips the normalisation). */
FOGRT__PRIVATE fogrt__v3 fogrt__sample_hg_unit(float g, fogrt__v3 wo, float u1, float u2,
                                               float *pdf) {
    fogrt__frame f = fogrt__frame_from_z(fogrt__neg(wo));   /* z: propagation */
    float one_minus_mu, one_plus_mu, mu;
    g = fogrt__clamp_g(g);
    mu = fogrt__sample_hg_mu_eq11(g, FOGRT__CLAMP(u1, 0.0f, 1.0f), &one_minus_mu, &one_plus_mu);
    if (pdf) *pdf = fogrt__hg_phase_pm(g, one_minus_mu, one_plus_mu);
    return fogrt__direction_at(&f, mu, sqrtf(one_minus_mu * one_plus_mu), u2);
}
FOGRT__PUBLIC fogrt_vec3 fogrt_sample_hg(float g, fogrt_vec3 wo, float u1, float u2, float *pdf) {
    return fogrt__sample_hg_unit(g, fogrt__normalize(wo), u1, u2, pdf);
}
/* mu = cos(d, wi) with d = -wo. Near the peaks 1 - mu and 1 + mu are taken from the chord
   lengths, |wi + wo|^2 / 2 and |wi - wo|^2 / 2, which keep their precision where a rounded
   dot product would not (at g = 0.999 the phase function changes 12% per ulp of mu there). */
FOGRT__PUBLIC float fogrt_hg_pdf(float g, fogrt_vec3 wo, fogrt_vec3 wi) {
    fogrt__v3 a = fogrt__add(wi, wo), b = fogrt__sub(wi, wo);
    return fogrt__hg_phase_pm(fogrt__clamp_g(g), FOGRT__CLAMP(0.5f * fogrt__dot(a, a), 0.0f, 2.0f),
                              FOGRT__CLAMP(0.5f * fogrt__dot(b, b), 0.0f, 2.0f));
}
#endif /* FOGRT_NO_MEDIUM */
/* ------------------------------------------------------------------------------------------
   3.4 The global illumination pipeline: Algorithm 1 (eq. 13) and the one-bounce baseline
   Algorithm 1 is written as a recursion; fogrt__algorithm1 below runs it as a loop (the
   recursion's tail call), keeping the product of the weights of eq. 13 as the throughput
   beta = prod f cos / pdf, so that the light found at depth k counts beta_k Le. Every render
   runs it; with Part II's state on the walk each step hands on at its seam (7a-7d). Its
   steps carry the numbers of the algorithm's lines:
     2     "ray depth > 0 and coin flip(p)": the depth limit, and Russian roulette after
           rr_depth bounces: go on with probability q = min(0.95, max(beta)), weight 1/q;
     3-4   intersect the BVH (t_i), sample a fog collision t_fog (3.1), keep the nearer;
     5-10  light sampling at the vertex: in fog over the sphere of directions (6), at a
           surface over the hemisphere (9), each light's sample weighted by MIS (2.3);
     11-20 the new direction: HG in fog (15, 3.3), the BSDF on a surface (19, 2.2);
     13,22 the weight of eq. 13: f cos / pdf (HG: p / p = 1; the fog's albedo sigma_s /
           sigma_t at a collision, since transmittance and free-flight pdf cancel);
     12,23 one bounce more.
   Light reached by the ray itself (an emitter hit, or the sky) is added with the MIS weight
   of BSDF sampling, so that the two estimates of an area light add up to one. The fog fills
   all space outside refractive objects (a ray that refracts into one leaves it until it
   refracts out). Light that bounced fewer than min_depth times is not counted (CS184's -o 0).
   ------------------------------------------------------------------------------------------ */
/* A ray's hit as a surface point: the point, its geometric normal and its shading normal. */
FOGRT__HOT void fogrt__surface_frame(const fogrt_scene *s, fogrt__v3 o, fogrt__v3 d,
                                     const fogrt_hit *h, fogrt__v3 *p, fogrt__v3 *ng,
                                     fogrt__v3 *ns) {
    *p = fogrt__madd(o, d, h->t);
    if (h->prim < s->tri_count) {
        const fogrt__v3 *v = &s->tri_v[3 * h->prim];
        *ng = fogrt__normalize(fogrt__cross(fogrt__sub(v[1], v[0]), fogrt__sub(v[2], v[0])));
        *ns = *ng;
        if (s->tri_has_n[h->prim]) {   /* interpolated shading normal, on the side of ng */
            const fogrt__v3 *n = &s->tri_n[3 * h->prim];
            fogrt__v3 sn =
                    fogrt__add(fogrt__scale(n[0], 1.0f - h->u - h->v),
                               fogrt__add(fogrt__scale(n[1], h->u), fogrt__scale(n[2], h->v)));
            if (fogrt__dot(sn, sn) > 0.0f) {
                sn = fogrt__normalize(sn);
                *ns = fogrt__dot(sn, *ng) < 0.0f ? fogrt__neg(sn) : sn;
            }
        }
    } else {
        fogrt__v3 c = s->sph_c[h->prim - s->tri_count];
        float r = s->sph_r[h->prim - s->tri_count];
        *ng = fogrt__normalize(fogrt__sub(*p, c));
        *p = fogrt__madd(c, *ng, r);               /* re-project: removes the hit's rounding */
        *ns = *ng;
    }
}
/* A surface vertex at p (normals ng, ns from fogrt__surface_frame) for the ray arriving
   along -wo: reflective BSDFs are two-sided (the frame turns to wo's side), refractive ones
   keep the outward normal, so wo.z < 0 in the frame means "inside". Returns whether wo is
   on the front side. */
FOGRT__HOT bool fogrt__surface_vertex_set(fogrt__vertex *v, const fogrt_material_desc *m,
                                          fogrt__v3 wo, fogrt__v3 p, fogrt__v3 ng, fogrt__v3 ns,
                                          bool in_medium) {
    fogrt_bsdf_type type = fogrt__bsdf_type(m);
    bool entering = fogrt__dot(wo, ng) > 0.0f;
    if (type < FOGRT_BSDF_REFRACTION) {                  /* reflects only: two-sided */
        if (!entering) {
            ng = fogrt__neg(ng);
            ns = fogrt__neg(ns);
        }
        if (fogrt__dot(wo, ns) <= 0.0f) ns = ng;
    }
    v->p = p;
    v->frame = fogrt__frame_from_z(ns);
    v->ng = ng;
    v->wo = wo;
    v->m = m;
    v->is_medium = false;
    v->in_medium = in_medium;
    return entering;
}
/* Lines 19-20: a new direction from the BSDF at surface vertex v, in world space. A shading
   normal can send a direction through the geometric surface: such a sample is dropped. */
FOGRT__HOT bool fogrt__sample_surface(const fogrt__settings *st, const fogrt__vertex *v,
                                      const float *u, fogrt_bsdf_sample *bs, fogrt__v3 *wi,
                                      float *cos_o) {
    fogrt__v3 wo_l = fogrt__to_local(&v->frame, v->wo);
    *cos_o = wo_l.z;
    if (!fogrt_sample_bsdf(v->m, st->desc.fresnel, wo_l, u[0], u[1], u[2], bs)) return false;
    *wi = fogrt__normalize(fogrt__to_world(&v->frame, bs->wi));
    float side = fogrt__dot(*wi, v->ng) * fogrt__dot(v->wo, v->ng);
    return bs->is_transmission ? side < 0.0f : side > 0.0f;
}
/* Lines 5-10: light sampling at a scattering vertex v, every light (area lights
   light_samples times), each sample f Le T w / (n pdf) with w the MIS weight (1 for a point
   or spot light, which BSDF sampling can never hit). */
FOGRT__PRIVATE fogrt__v3 fogrt__nee(const fogrt_scene *s, const fogrt__settings *st,
                                    const fogrt__vertex *v, fogrt_rng *rng, uint64_t *rays) {
    fogrt__v3 L = fogrt__v(0.0f, 0.0f, 0.0f);
    uint32_t total = s->light_count + s->area_light_count;
    for (uint32_t i = 0; i < total; ++i) {
        int n = i < s->light_count && !(s->lights[i].radius > 0.0f) ? 1 : st->desc.light_samples;
        for (int j = 0; j < n; ++j) {
            fogrt_light_sample ls;
            float pdf_b, tr, u[3];
            u[0] = fogrt_rng_float(rng);
            u[1] = fogrt_rng_float(rng);
            u[2] = fogrt_rng_float(rng);
            if (!fogrt_scene_sample_light(s, i, v->p, u[0], u[1], u[2], &ls)) continue;
            fogrt__v3 f = fogrt__vertex_f(s, v, ls.wi, &pdf_b);
            if (fogrt__is_black(f) || (tr = fogrt__shadow(s, v, &ls, rays)) == 0.0f) continue;
            float w = ls.is_delta || !st->desc.mis
                              ? 1.0f
                              : fogrt__power_heuristic((float)n * ls.pdf, pdf_b);
            L = fogrt__add(L, fogrt__scale(fogrt__mul(f, ls.Le), tr * w / (ls.pdf * (float)n)));
        }
    }
    return L;
}
/* The MIS weight of emission that the ray found by BSDF or phase sampling from prev_p with
   density prev_pdf (1 after a camera ray or a specular bounce, which light sampling cannot
   produce; 0 with MIS off, where light sampling alone counts area lights). */
FOGRT__PRIVATE float fogrt__emission_weight(const fogrt_scene *s, const fogrt__settings *st,
                                            bool prev_delta, float prev_pdf, fogrt__v3 prev_p,
                                            const fogrt_hit *hit, fogrt__v3 p, fogrt__v3 ng) {
    if (prev_delta || !st->desc.nee) return 1.0f;
    if (!st->desc.mis) return 0.0f;
    return fogrt__power_heuristic(prev_pdf,
                                  (float)st->desc.light_samples *
                                          fogrt__area_light_pdf(s, hit->prim, prev_p, p, ng));
}
/* Algorithm 1's state between two vertices: the ray, the throughput beta, the light
   gathered, the vertex just found, and what MIS needs of the vertex the ray left. */
struct fogrt__path;
typedef struct fogrt__walk {
    fogrt__v3 o, d, beta, L, prev_p;
    float prev_pdf;            /* the density with which the ray's direction was chosen */
    bool prev_delta;           /* camera ray or specular bounce: emission counts in full */
    bool in_fog;               /* the ray travels in fog */
    int depth;                 /* scattering events so far */
    fogrt__vertex v;           /* the vertex the ray reached */
    fogrt_rng *rng;
    uint64_t *rays;            /* rays traced, for the render's statistics */
    struct fogrt__path *x;     /* Part II's state of the path (E), or NULL: the paper's steps */
} fogrt__walk;

/* Lines 3-4, 5 and 14 (a fog particle), 8 and 18 (an object): the next vertex along the
   ray, with the emission the ray reaches on the way. Returns false when the path ends
   there (it left the scene, or hit a black diffuse surface). limit: the depth at which the
   path stops (Part II's steps skip what only a deeper path would use). */
FOGRT__PRIVATE bool fogrt__next_vertex(const fogrt_scene *s, const fogrt__settings *st,
                                       fogrt__walk *w, int limit) {
#ifndef FOGRT_MINIMAL
    if (w->x) return fogrt__full_next_event(s, st, w->x, limit); /* SEAM 7a: E's next event */
#endif
    (void)limit;
    fogrt_hit hit;
    float t_fog = INFINITY;
    ++*w->rays;
    bool found = fogrt__traverse(s, w->o, w->d, 0.0f, INFINITY, &hit, false);         /* 3: t_i */
#ifndef FOGRT_NO_MEDIUM
    if (w->in_fog)
        t_fog = fogrt_sample_exponential(s->medium.sigma_t, fogrt_rng_float(w->rng)); /* 4 */
#endif
    fogrt__vertex *v = &w->v;
    if (t_fog < (found ? hit.t : INFINITY)) {                                          /* 5, 14 */
        w->beta = fogrt__mul(w->beta, s->medium.albedo);
        v->p = fogrt__madd(w->o, w->d, t_fog);
        v->wo = fogrt__neg(w->d);
        v->is_medium = true;
        v->in_medium = true;
        v->m = NULL;
        v->ng = fogrt__v(0.0f, 0.0f, 0.0f);
        return true;
    }
    if (!found) { /* the sky */
        if (s->has_env && w->depth >= st->desc.min_depth)
            w->L = fogrt__add(w->L, fogrt__mul(w->beta, fogrt__env_radiance(s, w->d)));
        return false;
    }
    const fogrt_material_desc *m =
            &s->materials[fogrt_scene_get_prim_material(s, hit.prim)]; /* 8, 18 */
    fogrt__v3 p, ng, ns;
    fogrt__surface_frame(s, w->o, w->d, &hit, &p, &ng, &ns);
    if (!fogrt__is_black(m->emission) && fogrt__dot(w->d, ng) < 0.0f &&
        w->depth >= st->desc.min_depth) {
        float mis =
                fogrt__emission_weight(s, st, w->prev_delta, w->prev_pdf, w->prev_p, &hit, p, ng);
        w->L = fogrt__add(w->L, fogrt__scale(fogrt__mul(w->beta, m->emission), mis));
    }
    if (fogrt__bsdf_type(m) == FOGRT_BSDF_DIFFUSE && fogrt__is_black(m->reflectance)) return false;
    (void)fogrt__surface_vertex_set(v, m, fogrt__neg(w->d), p, ng, ns, w->in_fog);
    return true;
}
/* Fog, or a surface whose BSDF light sampling can reach (line 9: "if not specular"). */
FOGRT__PRIVATE bool fogrt__scatters(const fogrt__vertex *v) {
    return v->is_medium || !fogrt__bsdf_is_delta(fogrt__bsdf_type(v->m));
}
/* Lines 5-10: the light sampled at a scattering vertex (6 in fog, 9 on a surface). */
FOGRT__PRIVATE void fogrt__light_at_vertex(const fogrt_scene *s, const fogrt__settings *st,
                                           fogrt__walk *w) {
#ifndef FOGRT_MINIMAL
    if (w->x) { /* SEAM 7b: E's light step */
        fogrt__full_light_step(s, st, w->x);
        return;
    }
#endif
    if (st->desc.nee && fogrt__scatters(&w->v) && w->depth + 1 >= st->desc.min_depth)
        w->L = fogrt__add(w->L, fogrt__mul(w->beta, fogrt__nee(s, st, &w->v, w->rng, w->rays)));
}
/* Lines 11-22: the new direction, inverse HG in fog (15-17, eq. 11-12), the BSDF on an
   object (19-21), and the weight of eq. 13 (line 22), f |cos theta| / pdf. In fog that
   weight is p / pdf = 1: eq. 12 samples the phase function exactly. Returns false when no
   direction could be drawn. */
FOGRT__PRIVATE bool fogrt__new_direction(const fogrt_scene *s, const fogrt__settings *st,
                                         fogrt__walk *w) {
#ifndef FOGRT_MINIMAL
    if (w->x) return fogrt__full_scatter(s, st, w->x);                    /* SEAM 7c: E's scatter */
#endif
    const fogrt__vertex *v = &w->v;
    float u[3];
    u[0] = fogrt_rng_float(w->rng);
    u[1] = fogrt_rng_float(w->rng);
    u[2] = fogrt_rng_float(w->rng);
#ifndef FOGRT_NO_MEDIUM
    if (v->is_medium) {
        w->d = fogrt__sample_hg_unit(s->medium.g, v->wo, u[1], u[2], &w->prev_pdf);
        w->prev_delta = false;
        w->o = w->prev_p = v->p;
        return true;
    }
#endif
    fogrt_bsdf_sample bs;
    fogrt__v3 wi;
    float cos_o;
    if (!fogrt__sample_surface(st, v, u, &bs, &wi, &cos_o)) return false;
    /* Eq. 13, f |cos theta| / pdf, theta between the sampled w_i (bs.wi, shading frame) and the
       normal: the paper's "hitting ray" is w_i, the ray that hits what sends back L_i. Mirror and
       glass: f and pdf hold the same Dirac delta, so their sampler reports the ratio, as usual. */
    fogrt__v3 f = fogrt_bsdf_eval(v->m, fogrt__to_local(&v->frame, v->wo), bs.wi);
    fogrt__v3 weight = bs.is_delta ? bs.weight : fogrt__scale(f, fabsf(bs.wi.z) / bs.pdf);
    w->beta = fogrt__mul(w->beta, weight);
    w->prev_pdf = bs.pdf;
    w->prev_delta = bs.is_delta;
    if (bs.is_transmission)                             /* into or out of a refractive object */
        w->in_fog = !(fogrt__dot(v->wo, v->ng) > 0.0f) && (s->features & FOGRT_FEATURE_MEDIUM);
    w->d = wi;
    w->o = fogrt__offset(s, v->p, v->ng, wi);
    w->prev_p = v->p;
    return true;
}
/* Line 2's coin flip, after lines 12 and 23 (one bounce more): after rr_depth bounces the
   path goes on with probability q = min(0.95, max(beta)), weighted 1/q (unbiased: the
   path's expected value is unchanged). */
FOGRT__PRIVATE bool fogrt__roulette(const fogrt__settings *st, fogrt__walk *w) {
    ++w->depth;                                                          /* 12, 23 */
    if (w->depth <= st->desc.rr_depth) return true;
    float q = FOGRT__MIN(0.95f, fogrt__max3(w->beta));
    float u = fogrt_rng_float(w->rng);
#ifndef FOGRT_MINIMAL
    if (w->x) q = fogrt__full_roulette_q(st, w->x, u); /* SEAM 7d: the pilot's q (C) */
#endif
    if (!(u < q)) return false;
    w->beta = fogrt__scale(w->beta, 1.0f / q);
    return true;
}

/* The walk of a camera ray from o along d. */
FOGRT__PRIVATE void fogrt__walk_start(fogrt__walk *w, const fogrt_scene *s, fogrt__v3 o,
                                      fogrt__v3 d, fogrt_rng *rng, uint64_t *rays) {
    memset(w, 0, sizeof *w);
    w->o = o;
    w->d = d;
    w->prev_p = o;
    w->beta = fogrt__v(1.0f, 1.0f, 1.0f);
    w->prev_pdf = 1.0f;
    w->prev_delta = true;
    w->in_fog = (s->features & FOGRT_FEATURE_MEDIUM) != 0;   /* the camera is in the fog */
    w->rng = rng;
    w->rays = rays;
}
/* Algorithm 1, the loop every render runs. one_bounce: the paper's baseline instead
   (section 4.3): the camera ray is followed through mirrors and glass to the first
   scattering vertex, which samples the lights and takes one more step that only adds the
   emission it finds (its MIS half). */
FOGRT__PRIVATE fogrt__v3 fogrt__algorithm1(const fogrt_scene *s, const fogrt__settings *st,
                                           fogrt__walk *w, bool one_bounce) {
    int limit = st->max_depth;                                           /* 2: ray depth > 0 */
    for (uint32_t vertex = 0; vertex < FOGRT_MAX_PATH_VERTICES; ++vertex) {
        if (!fogrt__next_vertex(s, st, w, limit)) break;                 /* 3-5, 8, 14, 18 */
        if (w->depth >= limit || fogrt__is_black(w->beta)) break;        /* 2: ray depth > 0 */
        fogrt__light_at_vertex(s, st, w);                                /* 5-10 */
        if (one_bounce && fogrt__scatters(&w->v))                        /* the baseline: */
            limit = w->depth + 1;                                        /* one step more */
        if (!fogrt__new_direction(s, st, w)) break;                      /* 11-22 */
        if (!fogrt__roulette(st, w)) break;                    /* 2: coin flip(p); 12, 23 */
    }
    return w->L;
}

/* ------------------------------------------------------------------------------------------
   I.3 Running it: the scene and its validation
   Every add_* call validates all of its input before it changes anything, so an error
   leaves the scene exactly as it was.
   ------------------------------------------------------------------------------------------ */
FOGRT__PRIVATE void fogrt__log(const fogrt_scene *s, fogrt_log_level level, const char *msg) {
    if (s && s->logger.func) s->logger.func(level, msg, s->logger.user_data);
}
FOGRT__PRIVATE fogrt_result fogrt__fail(const fogrt_scene *s, fogrt_result r, const char *msg) {
    fogrt__log(s, FOGRT_LOG_ERROR, msg);
    if (s && s->error) {                                 /* the message, cut to fit */
        size_t n = FOGRT__MIN(strlen(msg), sizeof s->error_text - 1);
        memcpy(s->error, msg, n);
        s->error[n] = '\0';
    }
    return r;
}
/* A validation rule, in the manner of sokol_gfx's _SG_VALIDATE: if cond holds, the call
   fails with FOGRT_RESULT_<result> and msg (in a function whose scene is named s). */
#define FOGRT__REFUSE_IF(cond, result, msg) \
    do { if (cond) return fogrt__fail(s, FOGRT_RESULT_##result, msg); } while (0)
#define FOGRT__PASS(call) do {                \
        fogrt_result r_ = (call);             \
        if (r_ != FOGRT_RESULT_OK) return r_; \
    } while (0)

/* Move *ptr to a new array of new_cap elements, keeping its first used elements. Returns
   false when out of memory, leaving the old array untouched. */
FOGRT__PRIVATE bool fogrt__reserve(fogrt_scene *s, void **ptr, uint32_t used, uint32_t new_cap,
                                   size_t elem) {
    void *p = fogrt__alloc(&s->allocator, (size_t)new_cap * elem);
    if (!p) return false;
    if (*ptr) {
        memcpy(p, *ptr, (size_t)used * elem);
        fogrt__free(&s->allocator, *ptr);
    }
    *ptr = p;
    return true;
}
FOGRT__PRIVATE uint32_t fogrt__grow_cap(uint32_t cap, uint32_t need) {
    uint64_t c = cap ? cap : 16;
    while (c < need) c *= 2;
    return c > 0x7FFFFFFFu ? 0x7FFFFFFFu : (uint32_t)c;
}
FOGRT__PUBLIC fogrt_result fogrt_scene_create(const fogrt_scene_desc *desc,
                                              fogrt_scene **out_scene) {
    fogrt_scene_desc d;
    FOGRT_ASSERT(out_scene);
    *out_scene = NULL;
    memset(&d, 0, sizeof d);
    if (desc) d = *desc;
    if ((d.allocator.alloc_fn == NULL) != (d.allocator.free_fn == NULL))
        return FOGRT_RESULT_INVALID_ARGUMENT;           /* both allocator functions or neither */
    fogrt_scene *s = (fogrt_scene *)fogrt__alloc(&d.allocator, sizeof *s);
    if (!s) return FOGRT_RESULT_OUT_OF_MEMORY;
    memset(s, 0, sizeof *s);
    s->allocator = d.allocator;
    s->logger = d.logger;
    s->error = s->error_text;
    *out_scene = s;
    return FOGRT_RESULT_OK;
}
/* Drops the built data without freeing it (fogrt_scene_build keeps it until the new build
   has succeeded), or frees it. */
FOGRT__PRIVATE void fogrt__forget_built(fogrt_scene *s) {
    s->nodes = NULL;
    s->prims = NULL;
    s->area_lights = NULL;
    s->prim_index = s->light_prims = s->prim_light = NULL;
    s->light_cdf = s->spot_cos = NULL;
    s->node_count = s->area_light_count = 0;
    s->x = NULL;
    s->built = false;
}
FOGRT__PRIVATE void fogrt__free_built(fogrt_scene *s) {
#ifndef FOGRT_MINIMAL
    fogrt__appendix_release(s);                                 /* SEAM 4 */
#endif
    void *built[] = { s->nodes, s->prim_index, s->prims, s->area_lights,
                      s->light_prims, s->light_cdf, s->prim_light, s->spot_cos };
    for (size_t i = 0; i < sizeof built / sizeof built[0]; ++i)
        fogrt__free(&s->allocator, built[i]);
    fogrt__forget_built(s);
}
FOGRT__PUBLIC void fogrt_scene_destroy(fogrt_scene *s) {
    if (!s) return;
    fogrt_allocator a = s->allocator;
    fogrt__free_built(s);
    void *added[] = { s->materials, s->tri_v, s->tri_n, s->tri_has_n, s->tri_material,
                      s->tri_mesh, s->sph_c, s->sph_r, s->sph_material };
    for (size_t i = 0; i < sizeof added / sizeof added[0]; ++i) fogrt__free(&a, added[i]);
#ifndef FOGRT_MINIMAL
    fogrt__appendix_scene_free(s);                       /* SEAM 4: what Part II set on the scene */
#endif
    fogrt__free(&a, s->lights);
    fogrt__free(&a, s);
}
FOGRT__PRIVATE bool fogrt__colour_ok(fogrt__v3 c) {
    return fogrt__v3_finite(c) && c.x >= 0.0f && c.y >= 0.0f && c.z >= 0.0f;
}
FOGRT__PUBLIC fogrt_result fogrt_scene_add_material(fogrt_scene *s, const fogrt_material_desc *desc,
                                                    uint32_t *out_id) {
    FOGRT_ASSERT(s && desc);
    fogrt_material_desc m = *desc;
    FOGRT__REFUSE_IF((unsigned)m.type >= (unsigned)FOGRT_BSDF_NUM, INVALID_MATERIAL,
                     "material.type: unknown BSDF type");
    FOGRT__REFUSE_IF(!fogrt__colour_ok(m.reflectance) || !fogrt__colour_ok(m.transmittance) ||
                     !fogrt__colour_ok(m.emission), INVALID_MATERIAL,
                     "material.reflectance/transmittance/emission: negative or not finite");
    FOGRT__REFUSE_IF(!fogrt__finite(m.ior) || m.ior < 0.0f, INVALID_MATERIAL,
                     "material.ior: must be > 0 (0 means the default 1.5)");
    if (m.type == FOGRT_BSDF_DEFAULT) m.type = FOGRT_BSDF_DIFFUSE;
    FOGRT__PASS(fogrt__beyond_material(s, &m));
    m.ior = FOGRT__DEF(m.ior, 1.5f);
    if (s->material_count == 0xFFFFFFFEu)
        return fogrt__fail(s, FOGRT_RESULT_TOO_LARGE, "too many materials");
    if (s->material_count + 1 > s->material_cap) {
        uint32_t cap = fogrt__grow_cap(s->material_cap, s->material_count + 1);
        if (!fogrt__reserve(s, (void **)&s->materials, s->material_count, cap, sizeof m))
            return FOGRT_RESULT_OUT_OF_MEMORY;
        s->material_cap = cap;
    }
    s->materials[s->material_count] = m;
    if (out_id) *out_id = s->material_count;
    s->material_count++;
    s->built = false;
    return FOGRT_RESULT_OK;
}

/* Everything a mesh must satisfy, checked before anything is copied. */
FOGRT__PRIVATE fogrt_result fogrt__check_mesh(const fogrt_scene *s, const fogrt_mesh_desc *desc) {
    uint32_t n = desc->triangle_count;
    if (!desc->positions)
        return fogrt__fail(s, FOGRT_RESULT_INVALID_ARGUMENT, "mesh.positions: NULL");
    FOGRT__REFUSE_IF((uint64_t)s->tri_count + s->sph_count + n > FOGRT__MAX_PRIMS, TOO_LARGE,
                     "mesh.triangle_count: too many triangles");
    FOGRT__REFUSE_IF(!desc->indices && (uint64_t)n * 3 > desc->vertex_count, INVALID_GEOMETRY,
                     "mesh.vertex_count: fewer than 3 * triangle_count vertices and no indices");
    for (uint32_t i = 0; i < (uint64_t)desc->vertex_count * 3; ++i) {
        FOGRT__REFUSE_IF(!fogrt__coord_ok(desc->positions[i]), INVALID_GEOMETRY,
                         "mesh.positions: not finite or beyond +-1e30");
        FOGRT__REFUSE_IF(desc->normals && !fogrt__finite(desc->normals[i]), INVALID_GEOMETRY,
                         "mesh.normals: not finite");
    }
    if (desc->indices)
        for (uint32_t i = 0; i < (uint64_t)n * 3; ++i)
            FOGRT__REFUSE_IF(desc->indices[i] >= desc->vertex_count, INVALID_GEOMETRY,
                             "mesh.indices: index out of range");
    for (uint32_t i = 0; i < n; ++i) {
        uint32_t mat = desc->triangle_materials ? desc->triangle_materials[i] : desc->material;
        FOGRT__REFUSE_IF(mat >= s->material_count, INVALID_MATERIAL,
                         "mesh.material: material id out of range");
    }
    return FOGRT_RESULT_OK;
}
/* Room for n more triangles in every per-triangle array. The normals' array exists only
   once a mesh has normals: without it a triangle takes 45 bytes instead of 81. */
FOGRT__PRIVATE bool fogrt__reserve_triangles(fogrt_scene *s, uint32_t n, bool normals) {
    uint32_t c = s->tri_count;
    if (c + n > s->tri_cap) {
        uint32_t cap = fogrt__grow_cap(s->tri_cap, c + n);
        /* On failure the arrays that did grow hold the old data; tri_cap is the smallest. */
        if (!fogrt__reserve(s, (void **)&s->tri_v, c * 3, cap * 3, sizeof(fogrt__v3)) ||
            (s->tri_n &&
             !fogrt__reserve(s, (void **)&s->tri_n, c * 3, cap * 3, sizeof(fogrt__v3))) ||
            !fogrt__reserve(s, (void **)&s->tri_has_n, c, cap, 1) ||
            !fogrt__reserve(s, (void **)&s->tri_material, c, cap, sizeof(uint32_t)) ||
            !fogrt__reserve(s, (void **)&s->tri_mesh, c, cap, sizeof(uint32_t)))
            return false;
        s->tri_cap = cap;
    }
    if (normals && !s->tri_n) {                         /* the first mesh with normals */
        if (!fogrt__reserve(s, (void **)&s->tri_n, 0, s->tri_cap * 3, sizeof(fogrt__v3)))
            return false;
        memset(s->tri_n, 0, sizeof(fogrt__v3) * 3 * (size_t)c);
    }
    return true;
}
FOGRT__PUBLIC fogrt_result fogrt_scene_add_mesh(fogrt_scene *s, const fogrt_mesh_desc *desc) {
    FOGRT_ASSERT(s && desc);
    uint32_t n = desc->triangle_count, first = s->tri_count;
    if (n == 0) return FOGRT_RESULT_OK;
    FOGRT__PASS(fogrt__check_mesh(s, desc));
    if (!fogrt__reserve_triangles(s, n, desc->normals != NULL)) return FOGRT_RESULT_OUT_OF_MEMORY;
    for (uint32_t i = 0; i < n; ++i) {
        uint32_t t = first + i;
        for (uint32_t k = 0; k < 3; ++k) {
            uint32_t vi = desc->indices ? desc->indices[3 * i + k] : 3 * i + k;
            const float *p = desc->positions + 3 * (size_t)vi;
            s->tri_v[3 * t + k] = fogrt__v(p[0], p[1], p[2]);
            if (s->tri_n) {                                 /* zeros for a mesh without normals */
                const float *q = desc->normals ? desc->normals + 3 * (size_t)vi : NULL;
                s->tri_n[3 * t + k] = q ? fogrt__v(q[0], q[1], q[2]) : fogrt__v(0.0f, 0.0f, 0.0f);
            }
        }
        s->tri_has_n[t] = desc->normals != NULL;
        s->tri_material[t] =
                desc->triangle_materials ? desc->triangle_materials[i] : desc->material;
        s->tri_mesh[t] = s->mesh_count;
    }
    s->tri_count += n;
    s->mesh_count++;
    s->built = false;
    return FOGRT_RESULT_OK;
}
FOGRT__PUBLIC fogrt_result fogrt_scene_add_sphere(fogrt_scene *s, fogrt_vec3 center, float radius,
                                                  uint32_t material) {
    FOGRT_ASSERT(s);
    if (!fogrt__coord_ok(center.x) || !fogrt__coord_ok(center.y) || !fogrt__coord_ok(center.z) ||
        !fogrt__coord_ok(radius) || !(radius > 0.0f))
        return fogrt__fail(
                s, FOGRT_RESULT_INVALID_GEOMETRY,
                "sphere.center or sphere.radius not finite or beyond 1e30, or sphere.radius <= 0");
    FOGRT__REFUSE_IF(material >= s->material_count, INVALID_MATERIAL,
                     "sphere.material: material id out of range");
    FOGRT__REFUSE_IF((uint64_t)s->tri_count + s->sph_count + 1 > FOGRT__MAX_PRIMS, TOO_LARGE,
                     "too many spheres");
    if (s->sph_count + 1 > s->sph_cap) {
        uint32_t cap = fogrt__grow_cap(s->sph_cap, s->sph_count + 1), c = s->sph_count;
        if (!fogrt__reserve(s, (void **)&s->sph_c, c, cap, sizeof(fogrt__v3)) ||
            !fogrt__reserve(s, (void **)&s->sph_r, c, cap, sizeof(float)) ||
            !fogrt__reserve(s, (void **)&s->sph_material, c, cap, sizeof(uint32_t)))
            return FOGRT_RESULT_OUT_OF_MEMORY;
        s->sph_cap = cap;
    }
    s->sph_c[s->sph_count] = center;
    s->sph_r[s->sph_count] = radius;
    s->sph_material[s->sph_count] = material;
    s->sph_count++;
    s->built = false;
    return FOGRT_RESULT_OK;
}
FOGRT__PUBLIC fogrt_result fogrt_scene_add_light(fogrt_scene *s, const fogrt_light_desc *desc) {
    FOGRT_ASSERT(s && desc);
    fogrt_light_desc l = *desc;
    if (l.type == FOGRT_LIGHT_DEFAULT) l.type = FOGRT_LIGHT_POINT;
    FOGRT__REFUSE_IF((unsigned)l.type >= (unsigned)FOGRT_LIGHT_NUM, INVALID_LIGHT,
                     "light.type: unknown light type");
    FOGRT__REFUSE_IF(!fogrt__v3_finite(l.position), INVALID_LIGHT, "light.position: not finite");
    FOGRT__REFUSE_IF(!fogrt__colour_ok(l.intensity), INVALID_LIGHT,
                     "light.intensity: negative or not finite");
    FOGRT__REFUSE_IF(!fogrt__finite(l.radius) || l.radius < 0.0f, INVALID_LIGHT,
                     "light.radius: negative or not finite");
    if (l.type == FOGRT_LIGHT_SPOT) {
        FOGRT__REFUSE_IF(!fogrt__v3_finite(l.direction) ||
                                 fogrt__dot(l.direction, l.direction) == 0.0f,
                         INVALID_LIGHT, "light.direction: zero or not finite");
        FOGRT__REFUSE_IF(!(l.cutoff_deg >= 0.0f && l.cutoff_deg <= 180.0f), INVALID_LIGHT,
                         "light.cutoff_deg: outside [0, 180]");
        FOGRT__REFUSE_IF(!(l.beam_deg >= 0.0f && l.beam_deg <= l.cutoff_deg), INVALID_LIGHT,
                         "light.beam_deg: outside [0, cutoff_deg]");
        l.direction = fogrt__normalize(l.direction);
    }
    if (s->light_count + 1 > s->light_cap) {
        uint32_t cap = fogrt__grow_cap(s->light_cap, s->light_count + 1);
        if (!fogrt__reserve(s, (void **)&s->lights, s->light_count, cap, sizeof l))
            return FOGRT_RESULT_OUT_OF_MEMORY;
        s->light_cap = cap;
    }
    s->lights[s->light_count++] = l;
    s->built = false;
    return FOGRT_RESULT_OK;
}
FOGRT__PUBLIC fogrt_result fogrt_scene_set_environment(fogrt_scene *s, fogrt_vec3 radiance,
                                                       bool upper_only) {
    FOGRT_ASSERT(s);
    FOGRT__REFUSE_IF(!fogrt__colour_ok(radiance), INVALID_ARGUMENT,
                     "environment radiance: negative or not finite");
    s->env = radiance;
    s->env_upper_only = upper_only;
    s->has_env = !fogrt__is_black(radiance) || s->env_map;
    s->built = false;
    return FOGRT_RESULT_OK;
}
FOGRT__PUBLIC fogrt_result fogrt_scene_set_camera(fogrt_scene *s, const fogrt_camera_desc *desc) {
    FOGRT_ASSERT(s && desc);
    fogrt_camera_desc c = *desc;
    if (fogrt__is_black(c.up)) c.up = fogrt__v(0.0f, 1.0f, 0.0f);
    c.fov_deg = FOGRT__DEF(c.fov_deg, 45.0f);
    FOGRT__REFUSE_IF(!fogrt__v3_finite(c.position) || !fogrt__v3_finite(c.look_at) ||
                             !fogrt__v3_finite(c.up),
                     INVALID_CAMERA, "camera.position/look_at/up: not finite");
    float m = FOGRT__MAX(fabsf(c.up.x), FOGRT__MAX(fabsf(c.up.y), fabsf(c.up.z)));
    c.up = fogrt__normalize(fogrt__scale(c.up, 1.0f / m));   /* any length: its direction */
    fogrt__v3 fwd = fogrt__sub(c.look_at, c.position);
    FOGRT__REFUSE_IF(!fogrt__finite(fogrt__dot(fwd, fwd)), INVALID_CAMERA,
                     "camera: look_at - position too long for float: its squared length overflows");
    FOGRT__REFUSE_IF(fogrt__dot(fwd, fwd) == 0.0f, INVALID_CAMERA,
                     "camera.look_at: equals camera.position");
    fogrt__v3 up = fogrt__cross(fogrt__normalize(fwd), fogrt__normalize(c.up));
    FOGRT__REFUSE_IF(fogrt__dot(up, up) < 1e-12f, INVALID_CAMERA,
                     "camera.up: parallel to the view direction");
    FOGRT__REFUSE_IF(!(c.fov_deg > 0.0f && c.fov_deg < 180.0f), INVALID_CAMERA,
                     "camera.fov_deg: outside (0, 180)");
    FOGRT__REFUSE_IF(!fogrt__finite(c.lens_radius) || c.lens_radius < 0.0f ||
                             !fogrt__finite(c.focal_distance) || c.focal_distance < 0.0f,
                     INVALID_CAMERA, "camera.lens_radius/focal_distance: negative or not finite");
    if (c.focal_distance == 0.0f) c.focal_distance = fogrt__length(fwd);
    s->camera = c;
    s->has_camera = true;
    return FOGRT_RESULT_OK;
}

/* Checks a medium and clamps |g| to FOGRT_HG_G_MAX (with a warning). */
FOGRT__PRIVATE fogrt_result fogrt__check_medium(const fogrt_scene *s, fogrt_medium_desc *m) {
    FOGRT__REFUSE_IF(!fogrt__finite(m->sigma_t) || m->sigma_t < 0.0f, INVALID_MEDIUM,
                     "medium.sigma_t: negative or not finite");
    FOGRT__REFUSE_IF(!fogrt__colour_ok(m->albedo) || fogrt__max3(m->albedo) > 1.0f, INVALID_MEDIUM,
                     "medium.albedo: outside [0, 1]");
    FOGRT__REFUSE_IF(!(m->g >= -1.0f && m->g <= 1.0f), INVALID_MEDIUM, "medium.g: outside [-1, 1]");
    FOGRT__PASS(fogrt__beyond_medium(s, m));
    if (fabsf(m->g) >= FOGRT_HG_G_MAX && fabsf(m->g) != FOGRT_HG_G_MAX) {
        m->g = copysignf(FOGRT_HG_G_MAX, m->g);
        fogrt__log(s, FOGRT_LOG_WARNING,
                   "medium.g: |g| > 0.9999 clamped to 0.9999 (FOGRT_HG_G_MAX)");
    }
#ifndef FOGRT_NO_MEDIA
    return fogrt__media_check(s, m);                   /* SEAM 6: G's medium fields */
#else
    return FOGRT_RESULT_OK;
#endif
}
FOGRT__PUBLIC fogrt_result fogrt_scene_set_medium(fogrt_scene *s, const fogrt_medium_desc *desc) {
    FOGRT_ASSERT(s && desc);
    fogrt_medium_desc m = *desc;
    FOGRT__PASS(fogrt__check_medium(s, &m));
    s->medium = m;
    s->built = false;
    return FOGRT_RESULT_OK;
}
/* ------------------------------------------------------------------------------------------
   I.3 The camera: pinhole or thin lens (the paper's section 4.2)
   ------------------------------------------------------------------------------------------ */
typedef struct fogrt__camera {
    fogrt__v3 pos, right, up, fwd;
    float tan_x, tan_y, lens, focal;
} fogrt__camera;
FOGRT__PRIVATE fogrt__camera fogrt__camera_setup(const fogrt_scene *s, int width, int height) {
    fogrt__camera c;
    fogrt_camera_desc d = s->camera;
    float aspect = (float)width / (float)FOGRT__MAX(height, 1);
    if (!s->has_camera) {                       /* no camera: look at the scene from +z */
        fogrt__v3 centre = fogrt__scale(fogrt__add(s->bmin, s->bmax), 0.5f);
        float r = 0.5f * fogrt__length(fogrt__sub(s->bmax, s->bmin));
        memset(&d, 0, sizeof d);
        d.look_at = centre;
        d.position = fogrt__add(centre, fogrt__v(0.0f, 0.0f, 2.5f * FOGRT__MAX(r, 1e-3f)));
        d.up = fogrt__v(0.0f, 1.0f, 0.0f);
        d.fov_deg = 45.0f;
    }
    c.pos = d.position;
    c.fwd = fogrt__normalize(fogrt__sub(d.look_at, d.position));
    c.right = fogrt__normalize(fogrt__cross(c.fwd, d.up));
    c.up = fogrt__cross(c.right, c.fwd);
    float t = tanf(0.5f * d.fov_deg * FOGRT__PI / 180.0f);
    c.tan_x = d.fov_is_horizontal ? t : t * aspect;
    c.tan_y = d.fov_is_horizontal ? t / aspect : t;
    c.lens = d.lens_radius;
    c.focal = d.focal_distance > 0.0f ? d.focal_distance
                                      : fogrt__length(fogrt__sub(d.look_at, d.position));
    return c;
}
FOGRT__PRIVATE void fogrt__camera_generate(const fogrt__camera *c, int width, int height, float px,
                                           float py, float lu1, float lu2, fogrt__v3 *o,
                                           fogrt__v3 *d) {
    float x = (2.0f * px / (float)width - 1.0f) * c->tan_x;
    float y = (1.0f - 2.0f * py / (float)height) * c->tan_y;
    fogrt__v3 dir = fogrt__normalize(
            fogrt__add(c->fwd, fogrt__add(fogrt__scale(c->right, x), fogrt__scale(c->up, y))));
    *o = c->pos;
    if (c->lens > 0.0f) {        /* thin lens: aim through the focus point from a lens sample */
        fogrt__v3 focus = fogrt__madd(c->pos, dir, c->focal / fogrt__dot(dir, c->fwd));
        float lx, ly;
        fogrt__concentric_disk(lu1, lu2, &lx, &ly);
        *o = fogrt__add(c->pos, fogrt__add(fogrt__scale(c->right, lx * c->lens),
                                           fogrt__scale(c->up, ly * c->lens)));
        dir = fogrt__normalize(fogrt__sub(focus, *o));
    }
    *d = dir;
}

/* ------------------------------------------------------------------------------------------
   I.3 The scene build: bounds, the tree, the light tables
   fogrt_scene_build turns what was added into what the renderer reads: the BVH (2.1)
   over every primitive, the primitives in BVH order in the form the traversal wants, one
   table per area light (2.3), the ray offset scale, and whether there is fog.
   ------------------------------------------------------------------------------------------ */
FOGRT__PRIVATE float fogrt__tri_area(const fogrt_scene *s, uint32_t t) {
    const fogrt__v3 *v = &s->tri_v[3 * t];
    return 0.5f * fogrt__length(fogrt__cross(fogrt__sub(v[1], v[0]), fogrt__sub(v[2], v[0])));
}
/* An emissive triangle that can be sampled: emission and a non-zero area. */
FOGRT__PRIVATE bool fogrt__tri_emits(const fogrt_scene *s, uint32_t t) {
    return !fogrt__is_black(s->materials[s->tri_material[t]].emission) &&
           fogrt__tri_area(s, t) > 0.0f;
}
FOGRT__PRIVATE bool fogrt__sphere_emits(const fogrt_scene *s, uint32_t i) {
    return !fogrt__is_black(s->materials[s->sph_material[i]].emission);
}
/* Whether any material emits (if none, no triangle needs looking at). */
FOGRT__PRIVATE bool fogrt__some_material_emits(const fogrt_scene *s) {
    for (uint32_t i = 0; i < s->material_count; ++i)
        if (!fogrt__is_black(s->materials[i].emission)) return true;
    return false;
}
/* Emissive triangles of one mesh form one light; a CDF over their areas picks one. */
FOGRT__PRIVATE uint32_t fogrt__mesh_lights(fogrt_scene *s, uint32_t tri_count) {
    uint32_t g = 0, k = 0, prev_mesh = UINT32_MAX;
    for (uint32_t i = 0; i < tri_count; ++i) {
        if (!fogrt__tri_emits(s, i)) continue;
        if (s->tri_mesh[i] != prev_mesh) {               /* a new mesh: a new light */
            fogrt__area_light *N = &s->area_lights[g++];
            N->first = k;
            N->count = 0;
            N->sphere = UINT32_MAX;
            N->area = 0.0f;
            prev_mesh = s->tri_mesh[i];
        }
        fogrt__area_light *L = &s->area_lights[g - 1];
        L->area += fogrt__tri_area(s, i);
        L->count++;
        s->light_prims[k] = i;
        s->light_cdf[k] = L->area;         /* running sum, normalised below */
        s->prim_light[i] = g - 1;
        k++;
    }
    for (uint32_t i = 0; i < g; ++i) {
        fogrt__area_light *L = &s->area_lights[i];
        for (k = 0; k < L->count; ++k) s->light_cdf[L->first + k] /= L->area;
        s->light_cdf[L->first + L->count - 1] = 1.0f;
    }
    return g;
}
FOGRT__PRIVATE bool fogrt__build_lights(fogrt_scene *s) {
    uint32_t i, n_tri = 0, n_groups = 0, n_sph = 0, prev_mesh = UINT32_MAX;
    uint32_t n_prims = s->tri_count + s->sph_count,
             tri_count = fogrt__some_material_emits(s) ? s->tri_count : 0;
    for (i = 0; i < tri_count; ++i) {
        if (!fogrt__tri_emits(s, i)) continue;
        if (s->tri_mesh[i] != prev_mesh) {
            n_groups++;
            prev_mesh = s->tri_mesh[i];
        }
        n_tri++;
    }
    for (i = 0; i < s->sph_count; ++i) n_sph += fogrt__sphere_emits(s, i);
    s->prim_light =
            (uint32_t *)fogrt__alloc(&s->allocator, sizeof(uint32_t) * (n_prims ? n_prims : 1));
    s->area_lights = (fogrt__area_light *)fogrt__alloc(
            &s->allocator, sizeof(fogrt__area_light) * (n_groups + n_sph + 1));
    s->light_prims = (uint32_t *)fogrt__alloc(&s->allocator, sizeof(uint32_t) * (n_tri + 1));
    s->light_cdf = (float *)fogrt__alloc(&s->allocator, sizeof(float) * (n_tri + 1));
    if (!s->prim_light || !s->area_lights || !s->light_prims || !s->light_cdf) return false;
    for (i = 0; i < n_prims; ++i) s->prim_light[i] = UINT32_MAX;
    uint32_t g = fogrt__mesh_lights(s, tri_count);
    for (i = 0; i < s->sph_count; ++i) {      /* an emissive sphere is a light of its own */
        if (!fogrt__sphere_emits(s, i)) continue;
        fogrt__area_light *L = &s->area_lights[g];
        L->first = L->count = 0;
        L->sphere = i;
        L->area = 4.0f * FOGRT__PI * s->sph_r[i] * s->sph_r[i];
        s->prim_light[s->tri_count + i] = g++;
    }
    s->area_light_count = g;
    return true;
}

/* The box of primitive i (triangles first, then spheres). */
FOGRT__PRIVATE fogrt__aabb fogrt__prim_box(const fogrt_scene *s, uint32_t i) {
    fogrt__aabb bb = fogrt__aabb_empty();
    if (i < s->tri_count) {
        for (uint32_t k = 0; k < 3; ++k) fogrt__aabb_grow(&bb, s->tri_v[3 * i + k]);
    } else {
        fogrt__v3 c = s->sph_c[i - s->tri_count];
        float r = s->sph_r[i - s->tri_count];
        bb.lo = fogrt__sub(c, fogrt__v(r, r, r));
        bb.hi = fogrt__add(c, fogrt__v(r, r, r));
    }
    return bb;
}
/* The build's record of every primitive (its box), the scene's bounds, and the sizes
   derived from them: the ray offset floor and the point-light distance clamp (2.3). */
FOGRT__PRIVATE void fogrt__bounds(fogrt_scene *s, fogrt__build *b, uint32_t n) {
    fogrt__aabb sb = fogrt__aabb_empty();
    for (uint32_t i = 0; i < n; ++i) {
        fogrt__aabb box = fogrt__prim_box(s, i);
        b->box[i] = box;
        fogrt__aabb_union(&sb, &box);
        s->prim_index[i] = i;
    }
    if (n == 0) sb.lo = sb.hi = fogrt__v(0, 0, 0);
    s->bmin = sb.lo;
    s->bmax = sb.hi;
    float diag = fogrt__length(fogrt__sub(s->bmax, s->bmin));
    if (!(diag > 0.0f)) diag = 1.0f;
    s->eps = 1e-6f * diag;
    s->r2_min = (1e-4f * diag) * (1e-4f * diag);
}
/* Primitives in BVH order, in the form the traversal wants. */
FOGRT__PRIVATE void fogrt__pack_prims(fogrt_scene *s, uint32_t n) {
    for (uint32_t i = 0; i < n; ++i) {
        uint32_t id = s->prim_index[i];
        fogrt__prim *p = &s->prims[i];
        p->id = id;
        if (id < s->tri_count) {
            const fogrt__v3 *v = &s->tri_v[3 * id];
            p->a = v[0];
            p->b = fogrt__sub(v[1], v[0]);
            p->c = fogrt__sub(v[2], v[0]);
        } else {
            p->a = s->sph_c[id - s->tri_count];
            p->b = fogrt__v(s->sph_r[id - s->tri_count], 0.0f, 0.0f);
            p->c = fogrt__v(0.0f, 0.0f, 0.0f);
        }
    }
}
FOGRT__PUBLIC fogrt_build_desc fogrt_build_defaults(void) {
    /* heuristic, bins, c_trav, c_int, max_leaf_size, layout, roulette_pilot,
       release_binary, resolved */
    static const fogrt_build_desc d = {
        FOGRT_BVH_SAH, FOGRT_BVH_BINS, 1.0f, 1.0f, 4, FOGRT_BVH_LAYOUT_DEFAULT, true, false, true
    };
    return d;
}
/* The desc (NULL: the defaults), checked. Like the render desc it must come from
   fogrt_build_defaults(): in a zeroed desc, c_trav 0 would mean "traversal is free". */
FOGRT__PRIVATE fogrt_result fogrt__resolve_build(const fogrt_scene *s, const fogrt_build_desc *in,
                                                 fogrt_build_desc *d) {
    *d = in ? *in : fogrt_build_defaults();
    FOGRT__REFUSE_IF(!d->resolved, INVALID_ARGUMENT, "build desc: not from fogrt_build_defaults()");
    if ((unsigned)d->heuristic >= (unsigned)FOGRT_BVH_NUM ||
        (unsigned)d->layout >= (unsigned)FOGRT_BVH_LAYOUT_NUM || d->bins < 1 || d->bins > 64 ||
        d->max_leaf_size < 1 || !(d->c_trav >= 0.0f) || !(d->c_int >= 0.0f) ||
        !fogrt__finite(d->c_trav) || !fogrt__finite(d->c_int))
        return fogrt__fail(s, FOGRT_RESULT_INVALID_ARGUMENT,
                           "build desc: heuristic, layout, bins (1..64), max_leaf_size (>= 1), "
                           "c_trav or c_int out of range");
    if (d->heuristic == FOGRT_BVH_DEFAULT) d->heuristic = FOGRT_BVH_SAH;
    return fogrt__beyond_build(s, d);
}
/* The tree, and the primitives in BVH order in the form the traversal reads. leaf_keep:
   nodes of at most this many primitives stay leaves (0: the heuristic decides). Returns
   false when out of memory. */
FOGRT__PRIVATE bool fogrt__build_tree(fogrt_scene *s, const fogrt_build_desc *d, uint32_t n,
                                      uint32_t leaf_keep) {
    fogrt__build b;
    uint32_t m = FOGRT__REFS(s, n, leaf_keep); /* SEAM 2: references: n, and long slivers' pieces */
    memset(&b, 0, sizeof b);
    b.desc = *d;
    b.box = (fogrt__aabb *)FOGRT__ALLOC_BUILD(
            &s->allocator, sizeof(fogrt__aabb) * (m + 1)); /* SEAM 2: huge pages */
    s->nodes = (fogrt_bvh_node *)FOGRT__ALLOC_BUILD(&s->allocator,
                                                    sizeof(fogrt_bvh_node) * (2 * (size_t)m + 2));
    s->prim_index = (uint32_t *)fogrt__alloc(&s->allocator, sizeof(uint32_t) * (m + 1));
    if (!leaf_keep)    /* else Part II's wide tree (A) will hold the primitives itself */
        s->prims = (fogrt__prim *)fogrt__alloc(&s->allocator, sizeof(fogrt__prim) * (n + 1));
    bool ok = b.box && s->nodes && s->prim_index && (leaf_keep || s->prims);
    if (ok) {
        memset(&b.box[m], 0, sizeof b.box[m]); /* a spare box: lane loads may read past the last */
        fogrt__bounds(s, &b, n);
        b.nodes = s->nodes;
        b.idx = s->prim_index;
        b.leaf_keep = leaf_keep;
        FOGRT__SPLIT_REFS(s, &b, n, m);                 /* SEAM 2 */
        if (n > 0) fogrt__bvh_build(&b, m);
        else {
            memset(s->nodes, 0, 2 * sizeof(fogrt_bvh_node));
            b.node_count = 2;
        }
        s->node_count = b.node_count;
        if (s->prims) fogrt__pack_prims(s, n);
    }
    fogrt__free(&s->allocator, b.box);
    return ok;
}
/* The spot cones' cosines, once. */
FOGRT__PRIVATE bool fogrt__build_spots(fogrt_scene *s) {
    if (s->light_count == 0) return true;
    s->spot_cos = (float *)fogrt__alloc(&s->allocator, sizeof(float) * 2 * s->light_count);
    if (!s->spot_cos) return false;
    for (uint32_t i = 0; i < s->light_count; ++i) {
        s->spot_cos[2 * i] = cosf(s->lights[i].cutoff_deg * (FOGRT__PI / 180.0f));
        s->spot_cos[2 * i + 1] = cosf(s->lights[i].beam_deg * (FOGRT__PI / 180.0f));
    }
    return true;
}
/* The build, into fresh arrays: the scene as it was comes back if it fails. */
FOGRT__PRIVATE bool fogrt__build_all(fogrt_scene *s, const fogrt_build_desc *d, uint32_t n) {
    uint32_t leaf_keep = 0;
#ifndef FOGRT_NO_WIDE_BVH
    leaf_keep = fogrt__wide_leaf_keep(d, n);            /* SEAM 2: what the wide tree needs of it */
#endif
    fogrt__forget_built(s);
    if (!fogrt__build_lights(s) || !fogrt__build_tree(s, d, n, leaf_keep) || !fogrt__build_spots(s))
        return false;
    s->features = 0u; /* the fog's bit; the report: fogrt_scene_get_features */
#ifndef FOGRT_NO_MEDIUM
    if (s->medium.sigma_t > 0.0f) s->features = FOGRT_FEATURE_MEDIUM;
#endif
    s->built = true;
#ifndef FOGRT_MINIMAL
    if (!fogrt__appendix_build(s, d, n)) return false;         /* SEAM 3: Part II's tables */
#endif
    return true;
}
FOGRT__PUBLIC fogrt_result fogrt_scene_build(fogrt_scene *s, const fogrt_build_desc *desc) {
    fogrt_build_desc d;
    FOGRT_ASSERT(s);
    FOGRT__PASS(fogrt__resolve_build(s, desc, &d));
    uint32_t n = s->tri_count + s->sph_count;
    FOGRT__REFUSE_IF(n == 0 && s->light_count == 0 && !s->has_env, EMPTY_SCENE,
                     "scene: no geometry and no light");
    fogrt_scene old = *s;
    if (!fogrt__build_all(s, &d, n)) {
        fogrt__free_built(s);
        *s = old;                                       /* the scene as it was, built or not */
        return FOGRT_RESULT_OUT_OF_MEMORY;
    }
    fogrt__free_built(&old);                            /* the previous build's data */
    if (s->area_light_count == 0 && s->light_count == 0 && !s->has_env)
        fogrt__log(s, FOGRT_LOG_WARNING,
                   "scene: nothing emits light (no light, emissive material or environment): every "
                   "image will be black");
    return FOGRT_RESULT_OK;
}

/* ------------------------------------------------------------------------------------------
   I.3 Rendering, the error estimate, and output
   Every pixel accumulates, in double, the sum of its sample radiance and of its squared
   luminance: a double cannot overflow for any finite float sample (2^32 samples of 3.4e38,
   squared, stay below 1e87), so the image and its error estimate stay finite.
   A pixel's samples go round-robin to FOGRT_IMAGE_STREAMS streams. The streams are
   independent of each other, which is what the error estimate needs: the spread of the
   stream means measures the error of their average whatever the correlation inside one
   stream (Part II, C, makes each stream a stratified pattern).
   ------------------------------------------------------------------------------------------ */
/* The paper's method: Algorithm 1 with light sampling and MIS, Schlick's Fresnel. */
FOGRT__PUBLIC fogrt_render_desc fogrt_render_paper_defaults(void) {
    static const fogrt_render_desc d = {
        0, 0,                                           /* width, height: the image's */
        FOGRT_INTEGRATOR_PATH, FOGRT_FRESNEL_SCHLICK,
        64, 0, 3,                                       /* max_depth, min_depth, rr_depth */
        /* nee, mis, equiangular, glow, footprint, light_by_power, expected_emission */
        true, true, false, false, false, false, false,
        1, 0, 0,                                        /* light_samples, seed, threads */
        NULL,                                           /* sample_rate: every pixel alike */
        NULL, NULL, NULL, NULL,                         /* progress, user_data, cancel, radiance */
        true                                            /* resolved */
    };
    return d;
}
/* The settings the integrators read, from a desc (NULL: the defaults) that must come from a
   fogrt_render_*defaults(): a zeroed one would silently mean "max depth 0, no light sampling". */
FOGRT__PRIVATE fogrt_result fogrt__resolve_render(const fogrt_scene *s, const fogrt_render_desc *in,
                                                  fogrt__settings *st, fogrt_render_desc *out) {
    fogrt_render_desc d = in ? *in : fogrt_render_defaults();
    FOGRT__REFUSE_IF(!d.resolved, INVALID_ARGUMENT,
                     "render desc: not from fogrt_render_defaults() (a zeroed desc would mean "
                     "max_depth 0 and no light sampling)");
    if (d.max_depth < -1 || d.min_depth < 0 || d.rr_depth < 0 || d.light_samples < 1 ||
        (unsigned)d.integrator >= (unsigned)FOGRT_INTEGRATOR_NUM ||
        (unsigned)d.fresnel >= (unsigned)FOGRT_FRESNEL_NUM)
        return fogrt__fail(s, FOGRT_RESULT_INVALID_ARGUMENT,
                           "render desc: max_depth (>= -1), min_depth (>= 0), rr_depth (>= 0), "
                           "light_samples (>= 1), integrator or fresnel out of range");
    FOGRT__PASS(fogrt__beyond_render(s, &d));
    st->desc = d;
    st->max_depth = d.max_depth < 0 ? 0x7FFFFFFF : d.max_depth;
    st->integrator = d.integrator == FOGRT_INTEGRATOR_DIRECT ? FOGRT_INTEGRATOR_DIRECT
                                                             : FOGRT_INTEGRATOR_PATH;
    if (out) *out = d;
    return FOGRT_RESULT_OK;
}
/* One sample of the radiance arriving at o along -d. */
FOGRT__PRIVATE fogrt__v3 fogrt__radiance(const fogrt_scene *s, const fogrt__settings *st,
                                         fogrt__v3 o, fogrt__v3 d, fogrt_rng *rng, uint64_t *rays) {
    if (st->desc.radiance)
        return st->desc.radiance(s, o, d, rng, st->desc.user_data); /* the caller's */
    fogrt__walk w;
    fogrt__walk_start(&w, s, o, d, rng, rays);
#ifndef FOGRT_MINIMAL
    if (fogrt__full_wanted(s, st))
        return fogrt__full_radiance(s, st, &w); /* SEAM 7: E's state for the walk */
#endif
    return fogrt__algorithm1(s, st, &w, st->integrator == FOGRT_INTEGRATOR_DIRECT);
}
FOGRT__PUBLIC void fogrt_image_resolve(const fogrt_image *img, float *rgb) {
    FOGRT_ASSERT(img && rgb);
    size_t n = (size_t)img->width * (size_t)img->height;
    for (size_t i = 0; i < n; ++i) {
        double inv = img->count[i] ? 1.0 / (double)img->count[i] : 0.0;
        rgb[3 * i + 0] = (float)(img->sum[3 * i + 0] * inv);
        rgb[3 * i + 1] = (float)(img->sum[3 * i + 1] * inv);
        rgb[3 * i + 2] = (float)(img->sum[3 * i + 2] * inv);
    }
}
FOGRT__PRIVATE double fogrt__luminance_d(double r, double g, double b) {
    return 0.2126 * r + 0.7152 * g + 0.0722 * b;
}
/* The variance of one pixel's mean luminance m. With R streams holding n_r samples and
   means m_r (n = sum n_r, m = sum n_r m_r / n), the between-stream spread
     V = sum_r n_r (m_r - m)^2 / ((R - 1) n)
   is unbiased for Var[m] when the streams are independent and equally filled, whatever the
   correlation inside one stream (stratified positions make it negative, and the sample
   variance s^2 / n would then overestimate the error). For independent samples it is
   unbiased for any n_r (the between-group sum of squares of an analysis of variance), and
   with one sample per stream it is exactly s^2 / n. Streams without samples are left out;
   an image without stream sums gets the plain s^2 / n. Rejected samples count as zeros,
   as in the mean. */
FOGRT__PUBLIC double fogrt_image_pixel_variance(const fogrt_image *img, size_t pixel) {
    FOGRT_ASSERT(img);
    double c = img->count[pixel], mean;
    if (c < 2.0) return 0.0;
    if (img->stream_sum && img->stream_count) {
        const double *S = img->stream_sum + (size_t)FOGRT_IMAGE_STREAMS * pixel;
        const uint32_t *N = img->stream_count + (size_t)FOGRT_IMAGE_STREAMS * pixel;
        double total = 0.0, n = 0.0, ssb = 0.0;
        int used = 0;
        for (int r = 0; r < FOGRT_IMAGE_STREAMS; ++r) {
            total += S[r];
            n += (double)N[r];
            used += N[r] > 0;
        }
        if (used < 2) return 0.0;
        mean = total / n;
        for (int r = 0; r < FOGRT_IMAGE_STREAMS; ++r)
            if (N[r] > 0) {
                double d = S[r] / (double)N[r] - mean;
                ssb += (double)N[r] * d * d;
            }
        return ssb / ((double)(used - 1) * n);
    }
    const double *sum = img->sum + 3 * pixel;
    mean = fogrt__luminance_d(sum[0], sum[1], sum[2]) / c;
    double var = (img->sum_sq[pixel] / c - mean * mean) / (c - 1.0);
    return var > 0.0 ? var : 0.0;   /* rounding can make a noise-free pixel slightly negative */
}
/* Relative RMS error of the image, estimated from the samples themselves: the variance of
   each pixel's mean (above), summed, against the sum of the squared means:
     relative error = sqrt(sum_p Var[mean_p]) / sqrt(sum_p mean_p^2).
   It falls as 1/sqrt(samples) (faster where stratification helps): this is the number to
   plot against seconds. */
FOGRT__PUBLIC void fogrt_image_error(const fogrt_image *img, fogrt_error_estimate *out) {
    double var_sum = 0.0, mean_sq_sum = 0.0, lum_sum = 0.0;
    FOGRT_ASSERT(img && out);
    memset(out, 0, sizeof *out);
    size_t n = (size_t)img->width * (size_t)img->height;
    for (size_t i = 0; i < n; ++i) {
        double c = img->count[i];
        if (c < 1.0) continue;
        double mean =
                fogrt__luminance_d(img->sum[3 * i], img->sum[3 * i + 1], img->sum[3 * i + 2]) / c;
        lum_sum += mean;
        mean_sq_sum += mean * mean;
        out->samples += img->count[i];
        var_sum += fogrt_image_pixel_variance(img, i);
    }
    out->relative_error = mean_sq_sum > 0.0 ? sqrt(var_sum / mean_sq_sum) : 0.0;
    if (!(out->relative_error < DBL_MAX)) out->relative_error = DBL_MAX;   /* never NaN or Inf */
    out->mean_luminance = n ? lum_sum / (double)n : 0.0;
    out->rejected = img->rejected;
}

/* What one fogrt_render call needs on every thread. */
typedef struct fogrt__job {
    const fogrt_scene *s;
    fogrt__settings st;
    fogrt__camera cam;
    fogrt_image *img;
    uint64_t base;
    int spp;
} fogrt__job;
/* The camera ray of sample `index` of pixel (x, y), and the sample's random stream. Every
   sample has its own stream, derived from (seed, pixel, sample index): the image does not
   depend on the thread that renders it. The pixel filter is a box: the ray goes through a
   uniform point of the pixel (jx, jy), stratified per stream by Part II (C). */
FOGRT__PRIVATE void fogrt__pixel_ray(const fogrt__job *job, int width, int height, int x, int y,
                                     uint32_t index, fogrt_rng *rng, fogrt__v3 *o, fogrt__v3 *d,
                                     float *jx, float *jy) {
    uint64_t pix = (uint64_t)y * (uint64_t)width + (uint64_t)x, key = (pix << 32) | (uint64_t)index;
    fogrt_rng_seed(rng, fogrt__hash64(key ^ job->base), 0);
#ifndef FOGRT_NO_ESTIMATION
    fogrt__stratified_position(job->base, pix, index, jx, jy);                 /* SEAM 8 */
#else
    *jx = fogrt_rng_float(rng);
    *jy = fogrt_rng_float(rng);
#endif
    float l1 = fogrt_rng_float(rng), l2 = fogrt_rng_float(rng);
    fogrt__camera_generate(&job->cam, width, height, (float)x + *jx, (float)y + *jy, l1, l2, o, d);
}

/* One row of pixels, spp samples each (or as many as their rates say). The NaN firewall:
   a non-finite sample is counted, never added (a zero in the mean, in its stream's mean
   too). Sample `index` adds its luminance to stream index mod FOGRT_IMAGE_STREAMS. */
FOGRT__PRIVATE void fogrt__render_row(const fogrt__job *job, int y, uint64_t *rays,
                                      uint64_t *rejected, uint64_t *samples,
                                      const volatile int *cancel) {
    fogrt_image *img = job->img;
    int width = img->width, height = img->height;
    bool streams = img->stream_sum && img->stream_count;
    for (int x = 0; x < width; ++x) {
        size_t pix = (size_t)y * (size_t)width + (size_t)x;
#ifndef FOGRT_NO_ESTIMATION
        uint32_t spp = job->st.desc.sample_rate ? fogrt__rated_spp(job, pix)
                                                : (uint32_t)job->spp; /* SEAM 8: rates (C) */
#else
        uint32_t spp = (uint32_t)job->spp;
#endif
        for (uint32_t k = 0; k < spp; ++k) {
            uint32_t index = img->count[pix] + k;
            if (cancel && *cancel) {                     /* stop here: what is done stays counted */
                spp = k;
                x = width;
                break;
            }
            size_t slot = (size_t)FOGRT_IMAGE_STREAMS * pix + index % FOGRT_IMAGE_STREAMS;
            fogrt_rng rng;
            fogrt__v3 o, d;
            float jx, jy;
            fogrt__pixel_ray(job, width, height, x, y, index, &rng, &o, &d, &jx, &jy);
            fogrt__v3 Lr = fogrt__radiance(job->s, &job->st, o, d, &rng, rays);
            if (streams) ++img->stream_count[slot];
            if (!fogrt__v3_finite(Lr)) {
                ++*rejected;
                continue;
            }
            double lum = fogrt__luminance_d(Lr.x, Lr.y, Lr.z);
            img->sum[3 * pix + 0] += (double)Lr.x;
            img->sum[3 * pix + 1] += (double)Lr.y;
            img->sum[3 * pix + 2] += (double)Lr.z;
            img->sum_sq[pix] += lum * lum;
            if (streams) img->stream_sum[slot] += lum;
        }
        *samples += spp;
        img->count[pix] += spp;
    }
}
FOGRT__PRIVATE bool fogrt__report(const fogrt_render_desc *d, int rows_done, int rows_total,
                                  int spp) {
    fogrt_progress p = { rows_done, rows_total, spp };
    return d->progress(&p, d->user_data);
}
FOGRT__PRIVATE fogrt_result fogrt__check_image(const fogrt_scene *s, const fogrt_render_desc *d,
                                               const fogrt_image *img, int spp) {
    if (!s->built)
        return fogrt__fail(s, FOGRT_RESULT_NOT_BUILT,
                           "render: the scene changed since fogrt_scene_build");
    if (img->width <= 0 || img->height <= 0 || !img->sum || !img->sum_sq || !img->count ||
        (d->width && d->width != img->width) || (d->height && d->height != img->height))
        return fogrt__fail(s, FOGRT_RESULT_INVALID_ARGUMENT,
                           "render: image size does not match render desc width/height");
    if (spp < 0)
        return fogrt__fail(s, FOGRT_RESULT_INVALID_ARGUMENT, "render: samples_per_pixel < 0");
    FOGRT__PASS(fogrt__check_count_room(s, d, img, spp));
    return fogrt__beyond_image(s, d, img);
}

/* The threads to render with: the desc's count, or OpenMP's, cut to FOGRT_MAX_THREADS and
   4 per processor (an absurd OMP_NUM_THREADS would otherwise crash the runtime). */
FOGRT__PRIVATE int fogrt__threads(int asked) {
    int n = asked > 0 ? asked : FOGRT__OMP_MAX_THREADS();
    return FOGRT__MIN(n, FOGRT__MIN(FOGRT_MAX_THREADS, 4 * FOGRT__OMP_PROCS()));
}
FOGRT__PRIVATE bool fogrt__cancel_asked(const fogrt_render_desc *d) {
    return d->cancel && *d->cancel;
}
/* One parallel loop over the rows, handed out one at a time (rows differ in cost). The
   progress callback runs on the calling thread (OpenMP thread 0) whenever another block of
   rows is done; if it asks to stop, the rows not yet started are skipped. Returns false
   when cancelled. */
FOGRT__PRIVATE bool fogrt__render_rows(const fogrt__job *job, const fogrt_render_desc *d,
                                       uint64_t *rays_out, uint64_t *rejected_out,
                                       uint64_t *samples_out) {
    uint64_t rays = 0, rejected = 0, samples = 0;
    int y, height = job->img->height, block = height >= 32 ? height / 32 : 1;
    int rows_done = 0, cancelled = 0, last_report = 0, nthreads = fogrt__threads(d->threads);
    (void)nthreads;                                      /* read by OpenMP only */
    FOGRT__OMP(omp parallel for schedule(dynamic, 1) num_threads(nthreads)
               reduction(+ : rays, rejected, samples))
    for (y = 0; y < height; ++y) {
        int stop, done;
        FOGRT__OMP(omp atomic read)
        stop = cancelled;
        if (stop || fogrt__cancel_asked(d)) continue;
        fogrt__render_row(job, y, &rays, &rejected, &samples, d->cancel);
        FOGRT__OMP(omp atomic capture)
        done = ++rows_done;
        if (FOGRT__OMP_THREAD() != 0) continue;
        if (d->progress && (done - last_report >= block || done == height)) {
            last_report = done;
            stop = !fogrt__report(d, done, height, job->spp);
            FOGRT__OMP(omp atomic write)
            cancelled = stop;
        }
    }
    *rays_out = rays;
    *rejected_out = rejected;
    *samples_out = samples;
    if (cancelled || fogrt__cancel_asked(d)) return false;
    return !(d->progress && last_report != height &&
             !fogrt__report(d, height, height, job->spp)); /* the final report */
}
FOGRT__PUBLIC fogrt_result fogrt_render(const fogrt_scene *s, const fogrt_render_desc *desc,
                                        fogrt_image *img, int spp, fogrt_render_stats *stats) {
    fogrt__job job;
    fogrt_render_desc d;
    fogrt_result result;
    uint64_t rays = 0, rejected = 0, samples = 0;
    FOGRT_ASSERT(s && img);
    if (stats) memset(stats, 0, sizeof *stats);
    if ((result = fogrt__resolve_render(s, desc, &job.st, &d)) != FOGRT_RESULT_OK) return result;
    if ((result = fogrt__check_image(s, &d, img, spp)) != FOGRT_RESULT_OK) return result;
    job.s = s;
    job.img = img;
    job.spp = spp;
    job.cam = fogrt__camera_setup(s, img->width, img->height);
    job.base = fogrt__hash64(d.seed);
    if (spp > 0 && !fogrt__render_rows(&job, &d, &rays, &rejected, &samples))
        result = FOGRT_RESULT_CANCELLED;
    if (d.sample_rate && result == FOGRT_RESULT_OK)
        img->rated_spp += (uint64_t)spp; /* for the rates (C) */
    img->rejected += rejected;
    if (stats) {
        size_t i = 0, n = 3 * (size_t)img->width * (size_t)img->height;
        stats->camera_rays = samples;
        stats->rays = rays;
        stats->rejected = rejected;
        while (i < n && img->sum[i] == 0.0) ++i;
        stats->black = i == n;
    }
    return result;
}

#ifndef FOGRT_NO_STDIO
FOGRT__PUBLIC fogrt_result fogrt_write_pfm(const char *path, int width, int height,
                                           const float *rgb) {
    float one = 1.0f;
    unsigned char first;
    if (!path || !rgb || width <= 0 || height <= 0) return FOGRT_RESULT_INVALID_ARGUMENT;
    FILE *f = fopen(path, "wb");
    if (!f) return FOGRT_RESULT_IO_ERROR;
    memcpy(&first, &one, 1);                                     /* 0 on a little-endian machine */
    /* the scale's sign: the byte order */
    bool ok = fprintf(f, "PF\n%d %d\n%s\n", width, height, first == 0 ? "-1.0" : "1.0") > 0;
    for (int y = height - 1; y >= 0 && ok; --y)                  /* PFM stores bottom row first */
        ok = fwrite(rgb + (size_t)y * (size_t)width * 3, sizeof(float) * 3, (size_t)width, f) ==
             (size_t)width;
    if (fclose(f) != 0) ok = false;
    return ok ? FOGRT_RESULT_OK : FOGRT_RESULT_IO_ERROR;
}
#endif

/* ------------------------------------------------------------------------------------------
   I.3 The default scene: the CS184 Cornell box, filled with fog
   ------------------------------------------------------------------------------------------ */
FOGRT__PRIVATE fogrt_result fogrt__add_default(fogrt_scene *s);
/* All of the default scene or nothing: a failure midway takes back what was added. */
FOGRT__PUBLIC fogrt_result fogrt_scene_add_default(fogrt_scene *s) {
    FOGRT_ASSERT(s);
    fogrt_scene keep = *s;
    fogrt_result r = fogrt__add_default(s);
    if (r != FOGRT_RESULT_OK) {
        s->material_count = keep.material_count;
        s->tri_count = keep.tri_count;
        s->mesh_count = keep.mesh_count;
        s->sph_count = keep.sph_count;
        s->light_count = keep.light_count;
        s->camera = keep.camera;
        s->has_camera = keep.has_camera;
        s->medium = keep.medium;
        s->built = keep.built;
    }
    return r;
}
/* The box: x in [-1, 1], y in [0, 1.5], z in [-1, 1], open toward +z (the camera). Each quad
   (a, b, c, d) is counter-clockwise seen from its front, two triangles (a, b, c), (a, c, d);
   the lamp is a square just below the ceiling, facing down. */
static const float fogrt__default_quads[6][12] = {
    { -1, 0, -1,   -1, 0, 1,   1, 0, 1,   1, 0, -1 },                        /* floor */
    { -1, 1.5f, -1,   1, 1.5f, -1,   1, 1.5f, 1,   -1, 1.5f, 1 },            /* ceiling */
    { -1, 0, -1,   1, 0, -1,   1, 1.5f, -1,   -1, 1.5f, -1 },                /* back */
    { -1, 0, -1,   -1, 1.5f, -1,   -1, 1.5f, 1,   -1, 0, 1 },                /* left */
    { 1, 0, -1,   1, 0, 1,   1, 1.5f, 1,   1, 1.5f, -1 },                    /* right */
    { -0.35f, 1.49f, -0.35f,   0.35f, 1.49f, -0.35f,                         /* lamp */
      0.35f, 1.49f, 0.35f,   -0.35f, 1.49f, 0.35f } };
/* The default scene's lamp, camera and fog. */
FOGRT__PRIVATE fogrt_result fogrt__add_default_view(fogrt_scene *s) {
    fogrt_light_desc ld;
    fogrt_camera_desc cd;
    /* The spot light: high on the left, aimed at the floor right of centre; its cone shows
       in the fog. */
    memset(&ld, 0, sizeof ld);
    ld.type = FOGRT_LIGHT_SPOT;
    ld.position = fogrt__v(-0.8f, 1.4f, 0.6f);
    ld.direction = fogrt__sub(fogrt__v(0.3f, 0.0f, 0.0f), ld.position);
    ld.intensity = fogrt__v(16.0f, 20.0f, 26.0f);
    ld.cutoff_deg = 16.0f;
    ld.beam_deg = 11.0f;
    ld.radius = 0.02f;
    FOGRT__PASS(fogrt_scene_add_light(s, &ld));
    memset(&cd, 0, sizeof cd);
    cd.position = fogrt__v(0.0f, 0.75f, 3.6f);
    cd.look_at = fogrt__v(0.0f, 0.7f, 0.0f);
    cd.fov_deg = 38.0f;
    FOGRT__PASS(fogrt_scene_set_camera(s, &cd));
#ifndef FOGRT_NO_MEDIUM   /* a build without fog gets the same box, without fog */
    fogrt_medium_desc fd;
    memset(&fd, 0, sizeof fd);
    fd.sigma_t = 0.3f;
    fd.albedo = fogrt__v(0.9f, 0.9f, 0.9f);
    fd.g = 0.6f;
    FOGRT__PASS(fogrt_scene_set_medium(s, &fd));
#endif
    return FOGRT_RESULT_OK;
}
FOGRT__PRIVATE fogrt_result fogrt__add_default(fogrt_scene *s) {
    /* white, red, blue, matte: reflectance; the lamp: black, emitting (r, g, b, then emission) */
    static const float diffuse[5][6] = { { 0.73f, 0.73f, 0.73f, 0, 0, 0 },
                                         { 0.65f, 0.06f, 0.05f, 0, 0, 0 },
                                         { 0.08f, 0.12f, 0.60f, 0, 0, 0 },
                                         { 0.60f, 0.55f, 0.45f, 0, 0, 0 },
                                         { 0, 0, 0, 8.5f, 6.0f, 2.0f } };
    static const uint32_t idx[6] = { 0, 1, 2, 0, 2, 3 };
    static const uint32_t wall[6] = { 0, 0, 0, 1, 2, 4 };                /* the quads' materials */
    uint32_t base = s->material_count, glass;
    fogrt_material_desc md;
    fogrt_mesh_desc mesh;
    memset(&md, 0, sizeof md);
    md.type = FOGRT_BSDF_DIFFUSE;
    for (int i = 0; i < 5; ++i) {
        md.reflectance = fogrt__v(diffuse[i][0], diffuse[i][1], diffuse[i][2]);
        md.emission = fogrt__v(diffuse[i][3], diffuse[i][4], diffuse[i][5]);
        FOGRT__PASS(fogrt_scene_add_material(s, &md, NULL));
    }
    memset(&md, 0, sizeof md);
#ifndef FOGRT_NO_GLASS
    md.type = FOGRT_BSDF_GLASS;
    md.ior = 1.5f;
#else
    md.type = FOGRT_BSDF_MIRROR;                  /* a build without glass: a mirror sphere */
#endif
    md.reflectance = fogrt__v(1.0f, 1.0f, 1.0f);
    md.transmittance = fogrt__v(1.0f, 1.0f, 1.0f);
    FOGRT__PASS(fogrt_scene_add_material(s, &md, &glass));
    memset(&mesh, 0, sizeof mesh);
    mesh.vertex_count = 4;
    mesh.indices = idx;
    mesh.triangle_count = 2;
    for (int i = 0; i < 6; ++i) {
        mesh.positions = fogrt__default_quads[i];
        mesh.material = base + wall[i];
        FOGRT__PASS(fogrt_scene_add_mesh(s, &mesh));
    }
    FOGRT__PASS(fogrt_scene_add_sphere(s, fogrt__v(-0.45f, 0.35f, -0.35f), 0.35f, base + 3));
    FOGRT__PASS(fogrt_scene_add_sphere(s, fogrt__v(0.45f, 0.35f, 0.25f), 0.35f, glass));
    return fogrt__add_default_view(s);
}

#ifndef FOGRT_MINIMAL
/* ==========================================================================================

      PART II: BEYOND THE PAPER

   An appendix: none of it is needed to render the paper's images, and FOGRT_MINIMAL leaves
   it out whole. Each chapter opens with what it adds, what it costs, and the table of
   docs/benchmarks.md that holds its measured gain:
     A. The wide BVH and its SIMD kernels            (table "Wide BVH")
     B. Lamps in fog: equiangular sampling, the glow and footprint of a lamp, the light
        behind a fog collision, expected emission, HG per unit angle   (table "Lamps in fog")
     C. Sampling and estimation: environment-map sampling, exact Fresnel, fog in a box,
        lights chosen by power, the roulette's pilot, stratified pixel streams, per-pixel
        rates                       (tables "Roulette pilot", "Stratified pixel positions",
                                                     "Pixel rates", "Lights by power")
     D. The path trace: one event per step of a path, for fogrt_trace_path (FOGRT_TRACE)
     E. The full integrator: Algorithm 1 with B and C's steps added, as fogrt_render_defaults()
        runs it                                      (table "Strip cost")
     F. Inspecting a scene: its tree, the tree's cost, a brute-force query, its memory
     G. Media beyond the paper: the two-lobe HG and Rayleigh phase functions, emitting fog,
        sigma_t per colour channel                   (table "Strip cost")
     I. Rough metals: CS184's microfacet conductor, Beckmann with Smith's shadowing and the
        conductor's Fresnel, sampled by its normals  (table "Strip cost")
   ========================================================================================== */
#if !defined(FOGRT_NO_MEDIUM) && !defined(FOGRT_NO_LAMPS_IN_FOG)
#define FOGRT__LAMPS 1             /* appendix B is compiled */
#endif
struct fogrt__wbvh;
struct fogrt__footprint;
struct fogrt__hg_table;
/* A homogeneous medium as the full integrator's steps read it: the world's fog (the scene's
   medium), or with H the medium inside a shape. A path holds the one its ray is in. */
typedef struct fogrt__med {
    fogrt_medium_desc d;
    fogrt__v3 sigma;           /* sigma_t per channel (sigma_t three times in grey fog) */
    fogrt__v3 sigma_n;         /* sigma over its largest component (the collision densities' scale) */
    fogrt__v3 emit;            /* G: sigma_a Le / sigma_t = (1 - albedo) Le, per collision */
    bool chroma;               /* G: sigma_t differs between the colour channels */
    bool emits;                /* G: the medium emits */
    bool world;                /* the scene's fog: C's box bounds it, B's tables are for it */
} fogrt__med;
FOGRT__PRIVATE void fogrt__med_set(fogrt__med *r, const fogrt_medium_desc *m, bool world) {
    float top;
    r->d = *m;
    r->chroma = !fogrt__is_black(m->sigma_t_rgb);
    r->sigma = r->chroma ? m->sigma_t_rgb : fogrt__v(m->sigma_t, m->sigma_t, m->sigma_t);
    top = fogrt__max3(r->sigma);
    r->sigma_n = top > 0.0f ? fogrt__scale(r->sigma, 1.0f / top) : r->sigma;
    r->emit = fogrt__mul(fogrt__sub(fogrt__v(1.0f, 1.0f, 1.0f), m->albedo), m->emission);
    r->emits = top > 0.0f && !fogrt__is_black(r->emit);
    r->world = world;
}
/* Part II's per-scene state, made by fogrt_scene_build (seam 3) and released with the
   built data (seam 4). */
struct fogrt__x {
    struct fogrt__wbvh *wide;  /* A: the wide tree, or NULL */
    float *env_cdf;            /* C: per row the CDF over its columns (w), then the rows' CDF (h) */
    double env_total;          /* C: sum of luminance x sin(theta) over the map */
    float *light_pick;         /* C: the light list's CDF by power (fogrt__light_pick) */
    bool fog_bounded;          /* C: the fog fills only [fog_lo, fog_hi] */
    fogrt__v3 fog_lo, fog_hi;
    float rr_k;                /* C: the roulette's survival factor (fogrt__roulette_pilot) */
    float glow_share;          /* B: the share of scattered directions aimed at the glow (E d') */
    struct fogrt__footprint *footprints;   /* B: per point or spot light, the plane its cone lights most, or NULL */
    struct fogrt__hg_table *hg;   /* B: HG per unit angle for the medium's g, with lamps in fog */
#ifndef FOGRT_NO_SHAPES
    struct fogrt__hbuilt *h;   /* H: media inside shapes, or NULL */
#endif
    fogrt__med world;          /* the world's fog (sigma_t 0 without one) */
#ifndef FOGRT_NO_MEDIA
    bool media;                /* G: the fog has another phase function than HG, emits, or has
                                  sigma_t per channel (the path's steps are G's: fogrt__media_start) */
#endif
};
#ifndef FOGRT_NO_MEDIA
/* G's steps, which the full integrator (E) calls before their chapter. */
struct fogrt__path;
FOGRT__PRIVATE fogrt__v3 fogrt__media_sample(const fogrt_medium_desc *m, fogrt__v3 wo, float u1, float u2, float *pdf);
FOGRT__PRIVATE float fogrt__media_pdf(const fogrt_medium_desc *m, fogrt__v3 wo, fogrt__v3 wi);
FOGRT__PRIVATE void fogrt__media_emission(const fogrt_scene *s, const struct fogrt__settings *st, struct fogrt__path *P,
                                          fogrt__v3 beta, float t_end, bool collided);
FOGRT__PRIVATE void fogrt__media_build(fogrt_scene *s);
FOGRT__PRIVATE void fogrt__media_start(const fogrt_scene *s, struct fogrt__path *P);
FOGRT__PRIVATE fogrt__v3 fogrt__media_light(const fogrt_scene *s, const struct fogrt__path *P, const fogrt__vertex *v,
                                            const fogrt_light_sample *ls, float *pdf_b, float *tr);
struct fogrt__med;
FOGRT__PRIVATE fogrt__v3 fogrt__chroma_collision(const struct fogrt__med *m, float t, float pdf);
FOGRT__PRIVATE bool fogrt__media_next_event(const fogrt_scene *s, const struct fogrt__settings *st, struct fogrt__path *P,
                                            int limit);
#endif
#ifndef FOGRT_NO_SHAPES
/* H's steps, which E's dispatch and the build call before their chapter. */
FOGRT__PRIVATE bool fogrt__shapes_build(fogrt_scene *s);
FOGRT__PRIVATE void fogrt__shapes_release(fogrt_scene *s);
FOGRT__PRIVATE void fogrt__h_start(const fogrt_scene *s, struct fogrt__path *P);
FOGRT__PRIVATE bool fogrt__h_next_event(const fogrt_scene *s, const struct fogrt__settings *st, struct fogrt__path *P,
                                        int limit);
FOGRT__PRIVATE void fogrt__h_enter(const fogrt_scene *s, struct fogrt__path *P, uint32_t med);
FOGRT__PRIVATE uint32_t fogrt__h_cross(const fogrt_scene *s, uint32_t prim, uint32_t med);
FOGRT__PRIVATE bool fogrt__h_boundary(const fogrt_scene *s, struct fogrt__path *P, uint32_t prim,
                                      const fogrt_material_desc *m, fogrt__v3 p, fogrt__v3 ng);
FOGRT__PRIVATE fogrt__v3 fogrt__h_shadow(const fogrt_scene *s, const fogrt__vertex *v, uint32_t med,
                                         const fogrt_light_sample *ls, uint64_t *rays);
#endif

#ifndef FOGRT_NO_WIDE_BVH
/* ------------------------------------------------------------------------------------------
   A. The wide BVH
   What it adds: 8 (or 4) children per node, their boxes tested side by side in SIMD lanes
   (SSE, AVX2 where the processor has it), huge pages for the big arrays, 2.1's binned
   split of a node in SSE lanes (the same tree as Part I's, built faster: seam 2), and long
   slivers' boxes cut into pieces (seam 2, below fogrt__wide_leaf_keep).
   What it costs: nothing where the binary tree is chosen (fogrt_build_desc.layout); a
   sliver's pieces cost references, build time and memory, and only slivers get them.
   Its gain: docs/benchmarks.md, tables "Wide BVH" and "Slivers".


   The binary tree of 2.1 is good (few boxes and few triangles per ray), but each step
   of its traversal tests two boxes, one after the other, and branches on the outcome; an
   incoherent ray mispredicts many of those branches, and on a big mesh every step is also a
   cache miss. A wide BVH keeps the same boxes and removes levels:
     1. Collapse. Each wide node takes up to W children (W = 8 by default, FOGRT_WBVH_WIDTH
        4 for four) from the binary tree: start with a binary node's two children and
        repeatedly replace the child with the largest surface area by its own two children
        until W are collected. A binary subtree of at most 4 primitives is not opened but
        becomes one leaf (FOGRT_WBVH_LEAF: one packet), and a lane left unopened when the
        node is full becomes a leaf of two packets when it holds at most 8 primitives,
        rather than a wide node of two leaf lanes (which half the wide nodes were: on the
        1M mesh this halves the wide nodes, 98,700 to 48,800). The tree gets about three
        times shallower (W = 8). Merging pays where the primitives are small next to the
        scene: four neighbouring triangles of a mesh have about the box one of them has. In
        a scene of a few big primitives (a Cornell box: walls and spheres) the merged box of
        two walls holds most of the room, and most rays would test the packet. So a scene of
        at most FOGRT_WBVH_SMALL_SCENE (64) primitives merges nothing: its binary tree is the
        SAH's alone and each binary leaf is one lane (docs/benchmarks.md, "Wide BVH").
     2. Structure of arrays. A node stores all W minimum x, then all W minimum y, and so on,
        so its W slab tests are the same instructions on W lanes: SSE does four at once,
        AVX2 all eight.
     3. Leaf packets. A leaf's primitives are copied into a packet of four, again structure
        of arrays (four v0.x, then four v0.y, ...), and one packet is tested with the
        Moller-Trumbore test of 2.1 on four lanes at once. The test first compares
        u, v and t times det (no division yet) with bounds times |det|, loosened by 2^-20
        so that it never rejects a lane the exact test takes; only a packet with a lane
        left then pays the division and the exact tests (docs/benchmarks.md, "Wide BVH").
     4. Traversal: test the W boxes of the current node, go on with the nearest child hit,
        push the others, farthest first, with their entry distances (sorted where they are
        pushed, on the stack); any-hit rays push them unsorted. Closest and any hit are
        compiled as two traversals, so neither tests which it is in its loop.

   The answers are those of fogrt__bvh2_traverse. Every box test is fogrt__slab's (the same
   operations in the same order on each lane: the same entry distance, the same NaN rules,
   the same 2-ulp widening of the exit distance) and every triangle test is
   fogrt__hit_triangle's (the same float operations, so bit for bit the same t, u and v).
   The wide tree tests a subset of the binary tree's boxes (a collapsed node's own box
   contains its children's, so leaving it out loses no ray), and a popped box is skipped only
   when it starts more than 1e-5 (relative) beyond the closest hit so far (see
   fogrt__cull in 2.1). What can differ:
     - two hits at exactly the same t (a ray through a shared edge) may be found in another
       order, so another primitive is named at the same t;
     - with FOGRT_WBVH_LEAF > 0 a merged leaf's box is larger than its parts, so a ray that
       runs exactly along a triangle edge can be tested against a triangle whose own binary
       leaf box it just misses by rounding; it then reports the hit that brute force also
       finds (bench/wide_dev.c counts these; FOGRT_WBVH_LEAF 0 removes them).

   Memory (W = 8): a node is 256 bytes (48 floats of boxes, 16 words of child references),
   about one per 20 triangles; a packet of 4 primitives is 176 bytes (1M mesh: 12.5 and 54
   bytes per triangle). The collapse first lays the nodes out as small records, then gives
   nodes and packets blocks of exactly the size used. Both arrays start on a cache line and
   ask for huge pages (below); the binary tree's packed primitives of 2.1 are not
   made for the wide layout. The nodes are made before the packets, and need the binary
   tree's nodes, the packets only where each leaf's primitives begin, so with
   fogrt_build_desc.release_binary the binary nodes go before the packets take their room
   (a fan of 8M slivers peaks at 0.95 GB in fogrt instead of 1.13: the binary tree is 24
   bytes per primitive, the packets 50 there).

   SIMD: FOGRT_WBVH_SSE (set below: on by default where the compiler targets SSE2,
   that is every x86-64) selects the SSE intrinsics; FOGRT_WBVH_NO_SIMD forces the plain C99
   loops, which compute exactly the same values lane by lane. On top of SSE, the AVX2 path
   (FOGRT_WBVH_AVX2, W = 8) tests a node's 8 boxes in one pass of 8-lane instructions instead
   of two of 4 (the same operations per lane, in the same order, without fused multiply-add,
   so the same bits). The compiler need not target AVX2: on GCC and Clang the AVX2 functions
   carry __attribute__((target("avx2"))), fogrt__wbvh_build asks the processor once
   (__builtin_cpu_supports) and stores the answer in the tree, and the traversal picks its
   loop by it. The loop is written once (fogrt__wbvh_walk, forced inline) with the path as
   a constant argument; each path's entry inlines it with its own box test. A function for
   AVX2 can inline ordinary ones but not the reverse, so the AVX2 box test is not forced
   inline: it is inlined where it is called, in the AVX2 entries. bench/wide_dev.c checks
   the two paths against each other bit for bit.
   ------------------------------------------------------------------------------------------ */

/* The big arrays of the build and of the wide tree ask Linux for transparent huge pages
   (2 MB): fewer page faults while they are filled, and fewer TLB misses when rays wander
   over a big tree. It is only advice, given for the whole 2 MB pages inside the block,
   whatever allocator returned it; elsewhere, or with FOGRT_NO_HUGEPAGES, this compiles to a
   plain allocation. */
#if defined(__linux__) && !defined(FOGRT_NO_HUGEPAGES)
#include <sys/mman.h>
#if defined(MADV_HUGEPAGE)
#define FOGRT__MADV_HUGEPAGE MADV_HUGEPAGE
#elif !defined(__cplusplus)
int madvise(void *addr, size_t length, int advice);   /* hidden by a strict -std=c99 */
#define FOGRT__MADV_HUGEPAGE 14                        /* its value on Linux */
#endif
#endif
FOGRT__PRIVATE void *fogrt__alloc_big(const fogrt_allocator *a, size_t size) {
    void *p = fogrt__alloc(a, size);
#ifdef FOGRT__MADV_HUGEPAGE
    const uintptr_t page = (uintptr_t)2 << 20;
    uintptr_t lo = ((uintptr_t)p + page - 1) & ~(page - 1), hi = ((uintptr_t)p + size) & ~(page - 1);
    if (p && hi > lo) (void)madvise((void *)lo, (size_t)(hi - lo), FOGRT__MADV_HUGEPAGE);
#endif
    return p;
}

/* SIMD: FOGRT_WBVH_SSE (on by default where the compiler targets SSE2, that is every x86-64)
   selects SSE intrinsics in this chapter; FOGRT_WBVH_NO_SIMD forces plain C99 loops
   that compute exactly the same values lane by lane. */
#if !defined(FOGRT_WBVH_SSE) && !defined(FOGRT_WBVH_NO_SIMD) && \
    (defined(__SSE2__) || defined(_M_X64) || (defined(_M_IX86_FP) && _M_IX86_FP >= 2))
#define FOGRT_WBVH_SSE 1
#endif
#ifdef FOGRT_WBVH_NO_SIMD
#undef FOGRT_WBVH_SSE
#endif
/* AVX2 (this chapter's 8-lane box and triangle tests, on top of SSE): FOGRT_WBVH_AVX2 is 1
   where the compiler targets AVX2 anyway (-mavx2, -march=native on a recent x86), 2 where
   GCC or Clang compile for x86-64 without it: the AVX2 functions then get
   __attribute__((target("avx2"))) and the scene build asks the processor once
   (__builtin_cpu_supports) whether to use them. FOGRT_WBVH_NO_AVX2 (or FOGRT_WBVH_NO_SIMD)
   keeps the SSE path; every path gives the same answers. */
#if defined(FOGRT_WBVH_SSE) && !defined(FOGRT_WBVH_AVX2) && !defined(FOGRT_WBVH_NO_AVX2)
#if defined(__AVX2__)
#define FOGRT_WBVH_AVX2 1
#elif defined(__x86_64__) && ((defined(__clang__) && __clang_major__ >= 4) || \
                              (!defined(__clang__) && defined(__GNUC__) && __GNUC__ >= 5))
#define FOGRT_WBVH_AVX2 2
#endif
#endif
#if defined(FOGRT_WBVH_NO_AVX2) || !defined(FOGRT_WBVH_SSE)
#undef FOGRT_WBVH_AVX2
#endif
#ifdef FOGRT_WBVH_SSE
#include <emmintrin.h>
#endif

#ifndef FOGRT_WBVH_MIN_PRIMS
#define FOGRT_WBVH_MIN_PRIMS 1    /* wide at every size: see fogrt_build_desc (an empty scene stays binary) */
#endif
#ifndef FOGRT_WBVH_WIDTH
#define FOGRT_WBVH_WIDTH 8        /* children per wide node: 4 or 8 (8 measured faster) */
#endif
#ifndef FOGRT_WBVH_LEAF
#define FOGRT_WBVH_LEAF 4         /* largest binary subtree made one leaf (4: one packet, 8: two); 0: binary leaves only */
#endif
#if FOGRT_WBVH_LEAF < 0 || FOGRT_WBVH_LEAF > 8
#error "fogrt: FOGRT_WBVH_LEAF must be 0..8 (at most two packets)"
#endif
#if FOGRT_WBVH_WIDTH != 4 && FOGRT_WBVH_WIDTH != 8
#error "fogrt: FOGRT_WBVH_WIDTH must be 4 or 8"
#endif
#define FOGRT__WBVH_W FOGRT_WBVH_WIDTH
#define FOGRT__WBVH_LEAF FOGRT_WBVH_LEAF
/* A lane still unopened when its wide node is full becomes a leaf of up to two packets
   rather than a wide node of its own when it holds at most this many primitives (else
   half the wide nodes would choose between two packets). */
#ifndef FOGRT__WBVH_LEAF2
#define FOGRT__WBVH_LEAF2 (FOGRT__WBVH_LEAF > 0 ? 8 : 0)
#endif
/* A scene of at most this many primitives gets neither kind of merged leaf: its tree is
   the SAH's alone (see step 1 above). */
#ifndef FOGRT_WBVH_SMALL_SCENE
#define FOGRT_WBVH_SMALL_SCENE 64
#endif
#ifndef FOGRT__WBVH_STAT
#define FOGRT__WBVH_STAT(what) ((void)0)   /* a counting hook for bench/wide_dev.c */
#endif
#define FOGRT__WBVH_EMPTY 0xFFFFFFFFu             /* count[] of a lane with no child */
/* Each wide level pushes at most W - 1 children and uses up at least one binary level. */
#define FOGRT__WBVH_STACK ((FOGRT__BVH_MAX_DEPTH + 2) * (FOGRT__WBVH_W - 1) + 2)
/* The AVX2 path (FOGRT_WBVH_AVX2, above) takes the 8 lanes of a node at once, so it
   exists for W = 8 only. FOGRT__AVX2_FN marks its functions: compiled for AVX2 with
   target("avx2") when the rest of the file is not (they are then never forced inline: a
   function for AVX2 cannot be inlined into one that is not, only the reverse). */
#if defined(FOGRT_WBVH_AVX2) && FOGRT__WBVH_W == 8
#define FOGRT__WBVH_HAS_AVX2 1
#include <immintrin.h>
#if FOGRT_WBVH_AVX2 == 2
#define FOGRT__AVX2_FN static inline __attribute__((target("avx2"), unused))
#else
#define FOGRT__AVX2_FN FOGRT__HOT
#endif
#endif

/* A wide node. Lane i is child i: its box is lo/hi[axis][i] (box[0..2] = minimum x, y, z,
   box[3..5] = maximum x, y, z); count[i] = 0 means an inner child (wide node child[i]),
   count[i] > 0 a leaf of that many primitives starting at packet child[i], and
   FOGRT__WBVH_EMPTY an unused lane (always after the used ones). An unused lane's box is
   empty, minimum +inf and maximum -inf: every ray leaves it (t1 = -inf) before entering
   it (t0 = +inf), whatever its direction, so the slab tests need no other check. */
typedef struct fogrt__wnode {
    float box[6][FOGRT__WBVH_W];
    uint32_t child[FOGRT__WBVH_W];
    uint32_t count[FOGRT__WBVH_W];
} fogrt__wnode;

/* Four primitives of one leaf, structure-of-arrays: lane j holds a triangle's v0 and edges,
   and k = 1e-12 |e1|^2 |e2|^2, the threshold of fogrt__hit_triangle's degeneracy test,
   computed once here (the same product, so the same value). A sphere lane stores its
   centre in v0 and its radius in e1[0] (and zero in e2, so the triangle test, run on all
   four lanes, always fails there); an unused lane is all zero with id FOGRT__WBVH_EMPTY. */
typedef struct fogrt__wtri {
    float v0[3][4], e1[3][4], e2[3][4], k[4];
    uint32_t id[4];
} fogrt__wtri;

typedef struct fogrt__wbvh {
    fogrt__wnode *nodes; uint32_t node_count;
    fogrt__wtri *tris; uint32_t tri_packets;
    void *nodes_mem, *tris_mem;   /* the blocks holding nodes and tris, which start on a cache line */
    bool avx2;                    /* traced by the AVX2 path (the build asks the processor) */
} fogrt__wbvh;

FOGRT__PRIVATE void fogrt__wbvh_free(fogrt__wbvh *w, const fogrt_allocator *a) {
    fogrt__free(a, w->nodes_mem);
    fogrt__free(a, w->tris_mem);
    memset(w, 0, sizeof *w);
}
/* size bytes starting on a 64-byte cache line (so that a 256-byte node spans 4 lines, not
   5), inside a block of the allocator stored in *mem. */
FOGRT__PRIVATE void *fogrt__wbvh_alloc_lines(const fogrt_allocator *a, size_t size, void **mem) {
    *mem = fogrt__alloc_big(a, size + 64);
    return *mem ? (void *)(((uintptr_t)*mem + 63) & ~(uintptr_t)63) : NULL;
}

FOGRT__PRIVATE size_t fogrt__wbvh_bytes(const fogrt__wbvh *w) {
    return sizeof(fogrt__wnode) * (size_t)w->node_count + sizeof(fogrt__wtri) * (size_t)w->tri_packets;
}

FOGRT__PRIVATE float fogrt__wbvh_node_area(const fogrt_bvh_node *n) {
    fogrt__aabb b;
    b.lo = fogrt__v(n->bmin[0], n->bmin[1], n->bmin[2]);
    b.hi = fogrt__v(n->bmax[0], n->bmax[1], n->bmax[2]);
    return fogrt__aabb_area(&b);
}

/* Copy the primitives prim_index[first .. first + count) into packets from w->tris[*next],
   straight from the scene's triangles and spheres (v0 and the edges as fogrt__pack_prims
   forms them, so the triangle test sees the same floats). */
FOGRT__PRIVATE void fogrt__wbvh_pack_leaf(const fogrt_scene *s, fogrt__wbvh *w, uint32_t first, uint32_t count,
                                          uint32_t *next) {
    uint32_t i;
    for (i = 0; i < count; ++i) {
        uint32_t id = s->prim_index[first + i], j = i % 4;
        fogrt__wtri *q = &w->tris[*next + i / 4];
        fogrt__v3 a, b, c;
        if (j == 0) {                                   /* a new packet: all lanes unused */
            memset(q, 0, sizeof *q);
            q->id[0] = q->id[1] = q->id[2] = q->id[3] = FOGRT__WBVH_EMPTY;
        }
        q->id[j] = id;
        if (id < s->tri_count) {
            const fogrt__v3 *v = &s->tri_v[3 * id];
            a = v[0]; b = fogrt__sub(v[1], v[0]); c = fogrt__sub(v[2], v[0]);
            q->k[j] = 1e-12f * fogrt__dot(b, b) * fogrt__dot(c, c);
        } else {                                        /* centre, and the radius in e1.x */
            a = s->sph_c[id - s->tri_count];
            b = fogrt__v(s->sph_r[id - s->tri_count], 0.0f, 0.0f); c = fogrt__v(0.0f, 0.0f, 0.0f);
        }
        q->v0[0][j] = a.x; q->v0[1][j] = a.y; q->v0[2][j] = a.z;
        q->e1[0][j] = b.x; q->e1[1][j] = b.y; q->e1[2][j] = b.z;
        q->e2[0][j] = c.x; q->e2[1][j] = c.y; q->e2[2][j] = c.z;
    }
    *next += (count + 3) / 4;
}

/* The primitives below binary node b if there are at most limit of them (their count,
   from the subtree sizes of fogrt__wbvh_sizes; a binary leaf always counts), else 0. */
FOGRT__PRIVATE uint32_t fogrt__wbvh_small(const fogrt_bvh_node *bn, const uint32_t *size, uint32_t b, uint32_t limit) {
    if (bn[b].prim_count > 0) return bn[b].prim_count;
    return limit >= 2 && size[b] <= limit ? size[b] : 0;
}
/* Where the primitives below binary node b start in s->prim_index: a subtree's primitives
   are contiguous there, the left child's first, so they start at its leftmost leaf. */
FOGRT__PRIVATE uint32_t fogrt__wbvh_first(const fogrt_bvh_node *bn, uint32_t b) {
    while (bn[b].prim_count == 0) b = bn[b].left_first;
    return bn[b].left_first;
}

/* The lanes of the wide node being filled: lane j stands for binary node lane[j]; small[j]
   > 0 makes it a leaf of that many primitives; area[j] is its box's surface area (0 for a
   leaf: a leaf is never opened). */
typedef struct fogrt__wlanes {
    uint32_t lane[FOGRT__WBVH_W], small[FOGRT__WBVH_W], count;
    float area[FOGRT__WBVH_W];
    uint32_t leaf, leaf2;      /* the merge limits: FOGRT__WBVH_LEAF and _LEAF2, or 0 in a small scene */
} fogrt__wlanes;
FOGRT__PRIVATE void fogrt__wbvh_lane(const fogrt_bvh_node *bn, const uint32_t *size, fogrt__wlanes *L, uint32_t j,
                                     uint32_t node) {
    L->lane[j] = node;
    L->small[j] = fogrt__wbvh_small(bn, size, node, L->leaf);
    L->area[j] = L->small[j] ? 0.0f : fogrt__wbvh_node_area(&bn[node]);
}
/* Step 1 for binary node b: start with its two children (a small root is one leaf), then
   open the lane with the largest surface area (the one a ray is most likely to enter) into
   its two children, keeping the tree's left-to-right order, until W lanes are collected or
   none can be opened. */
FOGRT__PRIVATE void fogrt__wbvh_collect(const fogrt_bvh_node *bn, const uint32_t *size, uint32_t b, fogrt__wlanes *L) {
    uint32_t j;
    if (fogrt__wbvh_small(bn, size, b, L->leaf)) {
        fogrt__wbvh_lane(bn, size, L, 0, b); L->count = 1;   /* only a small root gets here */
        return;
    }
    fogrt__wbvh_lane(bn, size, L, 0, bn[b].left_first);
    fogrt__wbvh_lane(bn, size, L, 1, bn[b].left_first + 1);
    L->count = 2;
    while (L->count < FOGRT__WBVH_W) {
        int open = -1;
        float best = -1.0f;
        uint32_t child;
        for (j = 0; j < L->count; ++j)
            if (!L->small[j] && L->area[j] > best) { best = L->area[j]; open = (int)j; }
        if (open < 0) break;
        child = bn[L->lane[open]].left_first;
        for (j = L->count; j > (uint32_t)open + 1; --j) {
            L->lane[j] = L->lane[j - 1]; L->small[j] = L->small[j - 1]; L->area[j] = L->area[j - 1];
        }
        fogrt__wbvh_lane(bn, size, L, (uint32_t)open, child);
        fogrt__wbvh_lane(bn, size, L, (uint32_t)open + 1, child + 1);
        L->count++;
    }
    for (j = 0; j < L->count; ++j)          /* a lane left with two packets' worth: a leaf */
        if (!L->small[j]) L->small[j] = fogrt__wbvh_small(bn, size, L->lane[j], L->leaf2);
}
/* The number of primitives below every binary node (one pass from the last node back:
   children come after their parent; node 1 is unused). NULL when out of memory. */
FOGRT__PRIVATE uint32_t *fogrt__wbvh_sizes(const fogrt_scene *s, const fogrt_allocator *a) {
    uint32_t i = s->node_count;
    uint32_t *size = (uint32_t *)fogrt__alloc(a, sizeof(uint32_t) * (size_t)s->node_count);
    if (!size) return NULL;
    size[1] = 0;
    while (i-- > 0) {
        const fogrt_bvh_node *n = &s->nodes[i];
        if (i != 1) size[i] = n->prim_count > 0 ? n->prim_count : size[n->left_first] + size[n->left_first + 1];
    }
    return size;
}
/* The wide nodes are first laid out as records (lane j's binary node, child and count;
   no boxes), for which the subtree sizes bound the room: a wide node is made for the root
   and for binary subtrees of more than FOGRT__WBVH_LEAF2 primitives only. The nodes and
   packets then get blocks of exactly the size counted. */
typedef struct fogrt__wrec { uint32_t lane[FOGRT__WBVH_W], child[FOGRT__WBVH_W], count[FOGRT__WBVH_W]; } fogrt__wrec;
FOGRT__PRIVATE uint32_t fogrt__wbvh_bound(const fogrt_scene *s, const uint32_t *size, uint32_t leaf2) {
    uint32_t i, big = 1;
    for (i = 2; i < s->node_count; ++i) big += s->nodes[i].prim_count == 0 && size[i] > leaf2;
    return big;
}
/* Whether the scene is small enough to build without merged leaves (FOGRT_WBVH_SMALL_SCENE). */
FOGRT__PRIVATE bool fogrt__wbvh_small_scene(uint32_t prims) { return prims <= FOGRT_WBVH_SMALL_SCENE; }
/* Step 1 for every wide node, from a stack: the records rec[0 .. *nodes) in the order the
   nodes will be stored, and the number of packets; leaf and leaf2 are the merge limits
   (FOGRT__WBVH_LEAF and FOGRT__WBVH_LEAF2, or 0 in a small scene). */
FOGRT__PRIVATE void fogrt__wbvh_layout(const fogrt_scene *s, const uint32_t *size, uint32_t leaf, uint32_t leaf2,
                                       fogrt__wrec *rec, uint32_t cap, uint32_t *nodes, uint32_t *packets) {
    uint32_t stack_b[FOGRT__BVH_MAX_DEPTH * FOGRT__WBVH_W + 2], stack_w[FOGRT__BVH_MAX_DEPTH * FOGRT__WBVH_W + 2];
    uint32_t sp = 0, j;
    *nodes = 1; *packets = 0;
    stack_b[sp] = 0; stack_w[sp++] = 0;
    while (sp > 0) {
        fogrt__wlanes L;
        fogrt__wrec *r;
        --sp;
        r = &rec[stack_w[sp]];
        L.leaf = leaf; L.leaf2 = leaf2;
        fogrt__wbvh_collect(s->nodes, size, stack_b[sp], &L);
        for (j = 0; j < FOGRT__WBVH_W; ++j) {
            r->lane[j] = L.lane[j < L.count ? j : 0];
            if (j >= L.count) { r->child[j] = 0; r->count[j] = FOGRT__WBVH_EMPTY; }
            else if (L.small[j]) { r->child[j] = *packets; r->count[j] = L.small[j]; *packets += (L.small[j] + 3) / 4; }
            else {
                FOGRT_ASSERT(*nodes < cap && sp < FOGRT__BVH_MAX_DEPTH * FOGRT__WBVH_W + 2);
                r->child[j] = (*nodes)++; r->count[j] = 0;
                stack_b[sp] = L.lane[j]; stack_w[sp++] = r->child[j];
            }
        }
    }
}
/* Whether this processor runs the AVX2 path: asked once per build where the file is not
   compiled for AVX2 anyway (the answer is cached by the compiler's runtime). */
FOGRT__PRIVATE bool fogrt__wbvh_avx2_usable(void) {
#if defined(FOGRT__WBVH_HAS_AVX2) && FOGRT_WBVH_AVX2 == 2
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") != 0;
#elif defined(FOGRT__WBVH_HAS_AVX2)
    return true;
#else
    return false;
#endif
}
/* A wide node's lanes from its record: boxes from the binary nodes, children and counts. A
   leaf lane's child is its first packet; start[that packet] receives where the leaf's
   primitives begin in s->prim_index, which is all fogrt__wbvh_packets needs of the binary
   tree. */
FOGRT__PRIVATE void fogrt__wbvh_node_fill(const fogrt_scene *s, fogrt__wnode *wn, const fogrt__wrec *r, uint32_t *start) {
    uint32_t j;
    int k;
    for (j = 0; j < FOGRT__WBVH_W; ++j) {
        const fogrt_bvh_node *bj = &s->nodes[r->lane[j]];
        bool used = r->count[j] != FOGRT__WBVH_EMPTY;
        for (k = 0; k < 3; ++k) {    /* an unused lane: the empty box no ray enters */
            wn->box[k][j] = used ? bj->bmin[k] : INFINITY;
            wn->box[3 + k][j] = used ? bj->bmax[k] : -INFINITY;
        }
        wn->child[j] = r->child[j]; wn->count[j] = r->count[j];
        if (used && wn->count[j] > 0) start[wn->child[j]] = fogrt__wbvh_first(s->nodes, r->lane[j]);
    }
}
/* The wide nodes from the scene's binary tree: each wide node collects its lanes (step 1
   above); a lane with at most FOGRT_WBVH_LEAF (4) primitives below it becomes one leaf, one
   full packet (the binary tree's leaves hold about 2 primitives, so this halves the packets
   and the nodes); the others become new wide nodes, handled the same way from a stack.
   Then each node gets its lanes' boxes, and *start (allocated here, one entry per packet)
   where each leaf's primitives begin. Returns false when out of memory (w then has no nodes). */
FOGRT__PRIVATE bool fogrt__wbvh_nodes(const fogrt_scene *s, fogrt__wbvh *w, const fogrt_allocator *a, uint32_t **start) {
    uint32_t *size, i, cap, leaf, leaf2;
    bool small;
    fogrt__wrec *rec = NULL;
    *start = NULL;
    if (!(size = fogrt__wbvh_sizes(s, a))) return false;
    small = fogrt__wbvh_small_scene(s->tri_count + s->sph_count);
    leaf = small ? 0u : (uint32_t)FOGRT__WBVH_LEAF;
    leaf2 = small ? 0u : (uint32_t)FOGRT__WBVH_LEAF2;
    cap = fogrt__wbvh_bound(s, size, leaf2);
    if ((rec = (fogrt__wrec *)fogrt__alloc(a, sizeof(fogrt__wrec) * cap)) != NULL)
        fogrt__wbvh_layout(s, size, leaf, leaf2, rec, cap, &w->node_count, &w->tri_packets);
    fogrt__free(a, size);
    if (rec) {
        w->nodes = (fogrt__wnode *)fogrt__wbvh_alloc_lines(a, sizeof(fogrt__wnode) * w->node_count, &w->nodes_mem);
        *start = (uint32_t *)fogrt__alloc(a, sizeof(uint32_t) * (w->tri_packets ? w->tri_packets : 1u));
    }
    if (!w->nodes || !*start) {
        fogrt__free(a, rec); fogrt__free(a, *start); *start = NULL;
        fogrt__wbvh_free(w, a);
        return false;
    }
    for (i = 0; i < w->node_count; ++i) fogrt__wbvh_node_fill(s, &w->nodes[i], &rec[i], *start);
    fogrt__free(a, rec);
    return true;
}
/* Each leaf's packets, from start (fogrt__wbvh_nodes), s->prim_index and the primitives
   themselves. Returns false when out of memory. */
FOGRT__PRIVATE bool fogrt__wbvh_packets(const fogrt_scene *s, fogrt__wbvh *w, const fogrt_allocator *a, const uint32_t *start) {
    uint32_t i, j;
    w->tris = (fogrt__wtri *)fogrt__wbvh_alloc_lines(a, sizeof(fogrt__wtri) * (w->tri_packets ? w->tri_packets : 1u), &w->tris_mem);
    if (!w->tris) return false;
    for (i = 0; i < w->node_count; ++i)
        for (j = 0; j < FOGRT__WBVH_W; ++j) {
            const fogrt__wnode *wn = &w->nodes[i];
            uint32_t next = wn->child[j];
            if (wn->count[j] != FOGRT__WBVH_EMPTY && wn->count[j] > 0) fogrt__wbvh_pack_leaf(s, w, start[next], wn->count[j], &next);
        }
    return true;
}
/* The wide tree of a built binary tree: its nodes, then its packets. With release (the
   scene itself, or NULL), the binary tree's nodes are freed as soon as the wide nodes have
   their boxes, before the packets take their room, and prim_index after the packets: the
   build's peak is then the wide tree and the scene, without the binary tree (fogrt_build_desc
   .release_binary). Returns false when out of memory (w is then empty). */
FOGRT__PRIVATE bool fogrt__wbvh_make(const fogrt_scene *s, fogrt__wbvh *w, const fogrt_allocator *a, fogrt_scene *release) {
    uint32_t *start;
    bool ok;
    memset(w, 0, sizeof *w);
    w->avx2 = fogrt__wbvh_avx2_usable();
    if (!s->nodes || !s->prim_index || s->tri_count + s->sph_count == 0) return true;   /* nothing to trace */
    if (!fogrt__wbvh_nodes(s, w, a, &start)) return false;
    if (release) { fogrt__free(a, release->nodes); release->nodes = NULL; release->node_count = 0; }
    ok = fogrt__wbvh_packets(s, w, a, start);
    fogrt__free(a, start);
    if (release) { fogrt__free(a, release->prim_index); release->prim_index = NULL; }
    if (!ok) fogrt__wbvh_free(w, a);
    return ok;
}
FOGRT__PRIVATE bool fogrt__wbvh_build(const fogrt_scene *s, fogrt__wbvh *w, const fogrt_allocator *a) {
    return fogrt__wbvh_make(s, w, a, NULL);
}
/* The scene's wide tree: built by fogrt_scene_build (seam 3), released with the rest of
   the built data (seam 4). */
FOGRT__PRIVATE bool fogrt__wide_build(fogrt_scene *s, bool release_binary) {
    s->x->wide = (fogrt__wbvh *)fogrt__alloc(&s->allocator, sizeof *s->x->wide);
    if (!s->x->wide) return false;
    return fogrt__wbvh_make(s, s->x->wide, &s->allocator, release_binary ? s : NULL);
}
FOGRT__PRIVATE void fogrt__wide_release(fogrt_scene *s) {
    if (!s->x->wide) return;
    fogrt__wbvh_free(s->x->wide, &s->allocator);
    fogrt__free(&s->allocator, s->x->wide);
    s->x->wide = NULL;
}

/* The ray as the wide traversal reads it: the origin, the reciprocal direction (chapter
   10's, so the same values) and the rows of box[] holding the near and far face per axis:
   the minimum unless the ray goes down that axis. */
typedef struct fogrt__wray { fogrt__v3 o, inv; int near_row[3], far_row[3]; } fogrt__wray;
FOGRT__HOT void fogrt__wray_setup(fogrt__wray *r, fogrt__v3 o, fogrt__v3 d) {
    int a;
    r->o = o;
    r->inv = fogrt__v(fogrt__safe_rcp(d.x), fogrt__safe_rcp(d.y), fogrt__safe_rcp(d.z));
    for (a = 0; a < 3; ++a) {
        bool negative = fogrt__comp(r->inv, a) < 0.0f;
        r->near_row[a] = negative ? 3 + a : a;
        r->far_row[a] = negative ? a : 3 + a;
    }
}

/* The W slab tests of one node: bit i of the result is set when the ray enters child i
   between tmin and tmax, and t[i] is then its entry distance. Per lane these are exactly the
   operations of fogrt__slab: near and far face by the sign of the direction, t0 = the
   largest entry (a NaN entry ignored), t1 = the smallest exit, hit iff t0 <= t1 (1 + 2 ulp). */
#ifdef FOGRT_WBVH_SSE
FOGRT__HOT unsigned fogrt__wbvh_slabs(const fogrt__wnode *n, const fogrt__wray *r, float tmin, float tmax,
                                      float *t) {
    unsigned mask = 0;
    int g;
    for (g = 0; g < FOGRT__WBVH_W; g += 4) {
        __m128 t0 = _mm_set1_ps(tmin), t1 = _mm_set1_ps(tmax), tn, tf, o, inv;
        o = _mm_set1_ps(r->o.x); inv = _mm_set1_ps(r->inv.x);
        tn = _mm_mul_ps(_mm_sub_ps(_mm_loadu_ps(&n->box[r->near_row[0]][g]), o), inv);
        tf = _mm_mul_ps(_mm_sub_ps(_mm_loadu_ps(&n->box[r->far_row[0]][g]), o), inv);
        t0 = _mm_max_ps(tn, t0); t1 = _mm_min_ps(tf, t1);      /* max(a, b) = a > b ? a : b */
        o = _mm_set1_ps(r->o.y); inv = _mm_set1_ps(r->inv.y);
        tn = _mm_mul_ps(_mm_sub_ps(_mm_loadu_ps(&n->box[r->near_row[1]][g]), o), inv);
        tf = _mm_mul_ps(_mm_sub_ps(_mm_loadu_ps(&n->box[r->far_row[1]][g]), o), inv);
        t0 = _mm_max_ps(tn, t0); t1 = _mm_min_ps(tf, t1);
        o = _mm_set1_ps(r->o.z); inv = _mm_set1_ps(r->inv.z);
        tn = _mm_mul_ps(_mm_sub_ps(_mm_loadu_ps(&n->box[r->near_row[2]][g]), o), inv);
        tf = _mm_mul_ps(_mm_sub_ps(_mm_loadu_ps(&n->box[r->far_row[2]][g]), o), inv);
        t0 = _mm_max_ps(tn, t0); t1 = _mm_min_ps(tf, t1);
        _mm_storeu_ps(&t[g], t0);
        mask |= (unsigned)_mm_movemask_ps(_mm_cmple_ps(t0, _mm_mul_ps(t1, _mm_set1_ps(1.00000024f)))) << g;
    }
    return mask;
}
#else
FOGRT__HOT unsigned fogrt__wbvh_slabs(const fogrt__wnode *n, const fogrt__wray *r, float tmin, float tmax,
                                      float *t) {
    float t1[FOGRT__WBVH_W];
    unsigned mask = 0;
    int i, a;
    const float o[3] = { r->o.x, r->o.y, r->o.z }, inv[3] = { r->inv.x, r->inv.y, r->inv.z };
    for (i = 0; i < FOGRT__WBVH_W; ++i) { t[i] = tmin; t1[i] = tmax; }
    for (a = 0; a < 3; ++a)                               /* x, then y, then z, as fogrt__slab */
        for (i = 0; i < FOGRT__WBVH_W; ++i) {
            float tn = (n->box[r->near_row[a]][i] - o[a]) * inv[a];
            float tf = (n->box[r->far_row[a]][i] - o[a]) * inv[a];
            t[i] = tn > t[i] ? tn : t[i];
            t1[i] = tf < t1[i] ? tf : t1[i];
        }
    for (i = 0; i < FOGRT__WBVH_W; ++i)
        mask |= (unsigned)(t[i] <= t1[i] * 1.00000024f) << i;
    return mask;
}
#endif
#ifdef FOGRT__WBVH_HAS_AVX2
/* The same W = 8 slab tests in one pass of 8-lane AVX instructions (the SSE version above
   makes two passes of 4): the same operations in the same order, so the same bits. */
FOGRT__AVX2_FN unsigned fogrt__wbvh_slabs8(const fogrt__wnode *n, const fogrt__wray *r, float tmin, float tmax,
                                           float *t) {
    __m256 t0 = _mm256_set1_ps(tmin), t1 = _mm256_set1_ps(tmax), tn, tf, o, inv;
    o = _mm256_set1_ps(r->o.x); inv = _mm256_set1_ps(r->inv.x);
    tn = _mm256_mul_ps(_mm256_sub_ps(_mm256_loadu_ps(n->box[r->near_row[0]]), o), inv);
    tf = _mm256_mul_ps(_mm256_sub_ps(_mm256_loadu_ps(n->box[r->far_row[0]]), o), inv);
    t0 = _mm256_max_ps(tn, t0); t1 = _mm256_min_ps(tf, t1);
    o = _mm256_set1_ps(r->o.y); inv = _mm256_set1_ps(r->inv.y);
    tn = _mm256_mul_ps(_mm256_sub_ps(_mm256_loadu_ps(n->box[r->near_row[1]]), o), inv);
    tf = _mm256_mul_ps(_mm256_sub_ps(_mm256_loadu_ps(n->box[r->far_row[1]]), o), inv);
    t0 = _mm256_max_ps(tn, t0); t1 = _mm256_min_ps(tf, t1);
    o = _mm256_set1_ps(r->o.z); inv = _mm256_set1_ps(r->inv.z);
    tn = _mm256_mul_ps(_mm256_sub_ps(_mm256_loadu_ps(n->box[r->near_row[2]]), o), inv);
    tf = _mm256_mul_ps(_mm256_sub_ps(_mm256_loadu_ps(n->box[r->far_row[2]]), o), inv);
    t0 = _mm256_max_ps(tn, t0); t1 = _mm256_min_ps(tf, t1);
    _mm256_storeu_ps(t, t0);
    return (unsigned)_mm256_movemask_ps(_mm256_cmp_ps(t0, _mm256_mul_ps(t1, _mm256_set1_ps(1.00000024f)), _CMP_LE_OS));
}
#endif
/* The box test of the chosen path. */
FOGRT__HOT unsigned fogrt__wbvh_test(const fogrt__wnode *n, const fogrt__wray *r, float tmin, float tmax, float *t,
                                     bool avx2) {
#ifdef FOGRT__WBVH_HAS_AVX2
    if (avx2) return fogrt__wbvh_slabs8(n, r, tmin, tmax, t);
#endif
    (void)avx2;
    return fogrt__wbvh_slabs(n, r, tmin, tmax, t);
}

/* One packet against the ray: fogrt__hit_triangle on all four lanes. Returns the mask of
   lanes hit in (tmin, tmax) and their t, u, v. */
#ifdef FOGRT_WBVH_SSE
FOGRT__HOT unsigned fogrt__wbvh_tri4(const fogrt__wtri *q, fogrt__v3 o, fogrt__v3 d, float tmin, float tmax,
                                     float *t, float *u, float *v) {
#define FOGRT__L(x) _mm_loadu_ps(x)
    const __m128 dx = _mm_set1_ps(d.x), dy = _mm_set1_ps(d.y), dz = _mm_set1_ps(d.z);
    const __m128 e1x = FOGRT__L(q->e1[0]), e1y = FOGRT__L(q->e1[1]), e1z = FOGRT__L(q->e1[2]);
    const __m128 e2x = FOGRT__L(q->e2[0]), e2y = FOGRT__L(q->e2[1]), e2z = FOGRT__L(q->e2[2]);
    const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f);
    __m128 px, py, pz, det, inv_det, tx, ty, tz, qx, qy, qz, uu, vv, tt, ok;
    /* pvec = d x e2, det = e1 . pvec */
    px = _mm_sub_ps(_mm_mul_ps(dy, e2z), _mm_mul_ps(dz, e2y));
    py = _mm_sub_ps(_mm_mul_ps(dz, e2x), _mm_mul_ps(dx, e2z));
    pz = _mm_sub_ps(_mm_mul_ps(dx, e2y), _mm_mul_ps(dy, e2x));
    det = _mm_add_ps(_mm_add_ps(_mm_mul_ps(e1x, px), _mm_mul_ps(e1y, py)), _mm_mul_ps(e1z, pz));
    ok = _mm_cmpgt_ps(_mm_mul_ps(det, det), FOGRT__L(q->k));
    if (!_mm_movemask_ps(ok)) return 0;
    /* tvec = o - v0, qvec = tvec x e1; U = tvec . pvec, V = d . qvec, T = e2 . qvec are u, v, t
       times det */
    tx = _mm_sub_ps(_mm_set1_ps(o.x), FOGRT__L(q->v0[0]));
    ty = _mm_sub_ps(_mm_set1_ps(o.y), FOGRT__L(q->v0[1]));
    tz = _mm_sub_ps(_mm_set1_ps(o.z), FOGRT__L(q->v0[2]));
    uu = _mm_add_ps(_mm_add_ps(_mm_mul_ps(tx, px), _mm_mul_ps(ty, py)), _mm_mul_ps(tz, pz));
    qx = _mm_sub_ps(_mm_mul_ps(ty, e1z), _mm_mul_ps(tz, e1y));
    qy = _mm_sub_ps(_mm_mul_ps(tz, e1x), _mm_mul_ps(tx, e1z));
    qz = _mm_sub_ps(_mm_mul_ps(tx, e1y), _mm_mul_ps(ty, e1x));
    vv = _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, qx), _mm_mul_ps(dy, qy)), _mm_mul_ps(dz, qz));
    tt = _mm_add_ps(_mm_add_ps(_mm_mul_ps(e2x, qx), _mm_mul_ps(e2y, qy)), _mm_mul_ps(e2z, qz));
    {   /* Before dividing: the same tests on U, V, T with their signs made det's and a slack
           of 2^-20 (16 roundings) on the side of passing, so a lane that fails here fails
           the exact tests below too; most packets end here without a division. */
        const __m128 slack = _mm_set1_ps(9.5367432e-7f), abs_mask = _mm_castsi128_ps(_mm_set1_epi32(0x7FFFFFFF));
        const __m128 sign = _mm_and_ps(det, _mm_set1_ps(-0.0f)), adet = _mm_xor_ps(det, sign);
        const __m128 us = _mm_xor_ps(uu, sign), vs = _mm_xor_ps(vv, sign), ts = _mm_xor_ps(tt, sign);
        const __m128 lo = _mm_mul_ps(adet, _mm_set1_ps(-9.5367432e-7f));             /* -2^-20 |det| */
        const __m128 bmin = _mm_mul_ps(_mm_set1_ps(tmin), adet), bmax = _mm_mul_ps(_mm_set1_ps(tmax), adet);
        __m128 pre = _mm_and_ps(ok, _mm_and_ps(_mm_cmpge_ps(us, lo), _mm_cmpge_ps(vs, lo)));
        pre = _mm_and_ps(pre, _mm_cmple_ps(_mm_add_ps(us, vs), _mm_mul_ps(adet, _mm_set1_ps(1.00000095f))));
        pre = _mm_and_ps(pre, _mm_cmpgt_ps(ts, _mm_sub_ps(bmin, _mm_mul_ps(_mm_and_ps(bmin, abs_mask), slack))));
        pre = _mm_and_ps(pre, _mm_cmplt_ps(ts, _mm_add_ps(bmax, _mm_mul_ps(_mm_and_ps(bmax, abs_mask), slack))));
        if (!_mm_movemask_ps(pre)) return 0;
    }
    /* fogrt__hit_triangle's values and tests, bit for bit: u, v, t = U, V, T x (1 / det) */
    inv_det = _mm_div_ps(one, det);
    uu = _mm_mul_ps(uu, inv_det);
    vv = _mm_mul_ps(vv, inv_det);
    tt = _mm_mul_ps(tt, inv_det);
    ok = _mm_and_ps(ok, _mm_and_ps(_mm_cmpge_ps(uu, zero), _mm_cmple_ps(uu, one)));
    ok = _mm_and_ps(ok, _mm_and_ps(_mm_cmpge_ps(vv, zero), _mm_cmple_ps(_mm_add_ps(uu, vv), one)));
    ok = _mm_and_ps(ok, _mm_and_ps(_mm_cmpgt_ps(tt, _mm_set1_ps(tmin)), _mm_cmplt_ps(tt, _mm_set1_ps(tmax))));
    _mm_storeu_ps(t, tt); _mm_storeu_ps(u, uu); _mm_storeu_ps(v, vv);
    return (unsigned)_mm_movemask_ps(ok);
#undef FOGRT__L
}
#else
FOGRT__HOT unsigned fogrt__wbvh_tri4(const fogrt__wtri *q, fogrt__v3 o, fogrt__v3 d, float tmin, float tmax,
                                     float *t, float *u, float *v) {
    unsigned mask = 0;
    int j;
    for (j = 0; j < 4; ++j) {
        float px = d.y * q->e2[2][j] - d.z * q->e2[1][j];
        float py = d.z * q->e2[0][j] - d.x * q->e2[2][j];
        float pz = d.x * q->e2[1][j] - d.y * q->e2[0][j];
        float det = q->e1[0][j] * px + q->e1[1][j] * py + q->e1[2][j] * pz, inv_det;
        float tx = o.x - q->v0[0][j], ty = o.y - q->v0[1][j], tz = o.z - q->v0[2][j], qx, qy, qz;
        if (!(det * det > q->k[j])) continue;
        inv_det = 1.0f / det;
        u[j] = (tx * px + ty * py + tz * pz) * inv_det;
        if (!(u[j] >= 0.0f && u[j] <= 1.0f)) continue;
        qx = ty * q->e1[2][j] - tz * q->e1[1][j];
        qy = tz * q->e1[0][j] - tx * q->e1[2][j];
        qz = tx * q->e1[1][j] - ty * q->e1[0][j];
        v[j] = (d.x * qx + d.y * qy + d.z * qz) * inv_det;
        if (!(v[j] >= 0.0f && u[j] + v[j] <= 1.0f)) continue;
        t[j] = (q->e2[0][j] * qx + q->e2[1][j] * qy + q->e2[2][j] * qz) * inv_det;
        if (t[j] > tmin && t[j] < tmax) mask |= 1u << j;
    }
    return mask;
}
#endif

FOGRT__HOT unsigned fogrt__wbvh_ctz(unsigned m) {       /* index of the lowest set bit (m != 0) */
#if defined(__GNUC__) || defined(__clang__)
    return (unsigned)__builtin_ctz(m);
#else
    unsigned i = 0;
    while (!(m & 1u)) { m >>= 1; ++i; }
    return i;
#endif
}

/* The primitives of one leaf (count of them, packets from first): the closest hit in
   (tmin, *tmax), found as fogrt__traverse finds it (in leaf order, so of two hits at the same
   distance the earlier primitive wins). Returns true on a hit, with *tmax lowered to it. */
FOGRT__HOT bool fogrt__wbvh_leaf(const fogrt_scene *s, const fogrt__wbvh *w, uint32_t first, uint32_t count,
                                 fogrt__v3 o, fogrt__v3 d, float tmin, float *tmax, fogrt_hit *hit, bool any_hit) {
    uint32_t p, end = first + (count + 3) / 4;
    bool found = false;
    for (p = first; p < end; ++p) {
        const fogrt__wtri *q = &w->tris[p];
        float t[4], u[4], v[4];
        FOGRT__WBVH_STAT(packet);
        unsigned m = fogrt__wbvh_tri4(q, o, d, tmin, *tmax, t, u, v), j;
        if (s->sph_count > 0) {                        /* sphere lanes, tested one by one */
            for (j = 0; j < 4; ++j)
                if (q->id[j] != FOGRT__WBVH_EMPTY && q->id[j] >= s->tri_count &&
                    fogrt__hit_sphere(o, d, fogrt__v(q->v0[0][j], q->v0[1][j], q->v0[2][j]), q->e1[0][j],
                                      tmin, *tmax, &t[j])) {
                    u[j] = v[j] = 0.0f;
                    m |= 1u << j;
                }
        }
        if (!m) continue;
        if (any_hit) return true;
        {   /* the nearest lane; on equal t the first, as sequential tests would keep it */
            unsigned best = fogrt__wbvh_ctz(m);
            for (m &= m - 1; m; m &= m - 1) {
                j = fogrt__wbvh_ctz(m);
                if (t[j] < t[best]) best = j;
            }
            *tmax = t[best];
            hit->t = t[best]; hit->prim = q->id[best]; hit->u = u[best]; hit->v = v[best];
            found = true;
        }
    }
    return found;
}

/* A hint to the cache: fetch a pushed child's node or packet while the nearer one is
   traversed (on a big mesh nearly every node visit is a cache miss). */
#if (defined(__GNUC__) || defined(__clang__)) && !defined(FOGRT_WBVH_NO_PREFETCH)
#define FOGRT__WBVH_PREFETCH(w, child, count) do { \
        const char *p_ = (count) ? (const char *)&(w)->tris[child] : (const char *)&(w)->nodes[child]; \
        __builtin_prefetch(p_); __builtin_prefetch(p_ + 64); __builtin_prefetch(p_ + 128); \
        if (!(count) && sizeof(fogrt__wnode) > 192) __builtin_prefetch(p_ + 192); \
    } while (0)
/* A node's child[] and count[] (its last 64 bytes), fetched together with its boxes: they
   are read only after the box test, and asked for then they would miss the cache on their own. */
#define FOGRT__WBVH_PREFETCH_LINKS(n) __builtin_prefetch((n)->child)
#else
#define FOGRT__WBVH_PREFETCH(w, child, count) ((void)0)
#define FOGRT__WBVH_PREFETCH_LINKS(n) ((void)0)
#endif

/* The traversal: fogrt__traverse's contract (closest hit in (tmin, tmax), or with any_hit
   the first hit found; hit is written only on a hit). Test the current node's W boxes, visit
   the nearest child hit next and push the others, farthest first, with their entry
   distances; a popped child whose entry lies beyond the closest hit found so far is skipped. */
typedef struct fogrt__wentry { float t; uint32_t ref, cnt; } fogrt__wentry;   /* a pushed child */
/* More than one lane of node n hit (the lanes in mask m): push them all and pop the one to
   descend into. For the closest hit each lane is inserted at its place among the lanes of
   this node already pushed (insertion sort on the stack, stable: on equal distance the left
   child comes first, as fogrt__traverse orders them), so the nearest is on top; for any hit
   the order does not matter and the sort is skipped. */
FOGRT__HOT fogrt__wentry fogrt__wbvh_push(const fogrt__wbvh *w, const fogrt__wnode *n, const float *t, unsigned m,
                                          bool any_hit, fogrt__wentry *stack, uint32_t *sp) {
    uint32_t base = *sp, i = base;
    unsigned rest = m & (m - 1);
    if (!any_hit && !(rest & (rest - 1))) {    /* exactly two lanes, the common case: no sort */
        unsigned a = fogrt__wbvh_ctz(m), b = fogrt__wbvh_ctz(rest);
        unsigned nr = t[b] < t[a] ? b : a, fr = a + b - nr;   /* equal: the left lane first */
        fogrt__wentry e;
        e.t = t[fr]; e.ref = n->child[fr]; e.cnt = n->count[fr];
        FOGRT__WBVH_PREFETCH(w, e.ref, e.cnt);
        stack[(*sp)++] = e;
        e.t = t[nr]; e.ref = n->child[nr]; e.cnt = n->count[nr];
        return e;                             /* read next: a hint would come too late */
    }
    for (; m; m &= m - 1) {
        unsigned l = fogrt__wbvh_ctz(m);
        fogrt__wentry e;
        e.t = t[l]; e.ref = n->child[l]; e.cnt = n->count[l];
        FOGRT__WBVH_PREFETCH(w, e.ref, e.cnt);
        for (i = *sp; !any_hit && i > base && stack[i - 1].t <= e.t; --i) stack[i] = stack[i - 1];
        stack[i] = e;
        ++*sp;
    }
    (void)w;
    return stack[--*sp];
}
/* The traversal loop, one body for both paths: avx2 (a constant in each caller below)
   picks the box test. tcull is fogrt__cull(tmax), updated when tmax shrinks. */
FOGRT__HOT bool fogrt__wbvh_walk(const fogrt_scene *s, const fogrt__wbvh *w, fogrt__v3 o, fogrt__v3 d,
                                 float tmin, float tmax, fogrt_hit *hit, bool any_hit, bool avx2) {
    fogrt__wentry stack[FOGRT__WBVH_STACK];
    uint32_t sp = 0, ref = 0, cnt = 0;
    float tcull = fogrt__cull(tmax);
    fogrt__wray r;
    bool found = false;
    fogrt__wray_setup(&r, o, d);
    for (;;) {
        while (cnt == 0) {             /* down through wide nodes, testing each one's W boxes */
            const fogrt__wnode *n = &w->nodes[ref];
            float t[FOGRT__WBVH_W];
            FOGRT__WBVH_STAT(node);
            FOGRT__WBVH_PREFETCH_LINKS(n);
            unsigned m = fogrt__wbvh_test(n, &r, tmin, tcull, t, avx2);
            if (m & (m - 1)) {
                fogrt__wentry e = fogrt__wbvh_push(w, n, t, m, any_hit, stack, &sp);
                ref = e.ref; cnt = e.cnt;
            } else if (m) {                              /* one child hit: the common case */
                unsigned first = fogrt__wbvh_ctz(m);
                ref = n->child[first]; cnt = n->count[first];
            } else {
                break;                                   /* none: cnt is still 0 */
            }
        }
        if (cnt > 0 && fogrt__wbvh_leaf(s, w, ref, cnt, o, d, tmin, &tmax, hit, any_hit)) {
            found = true;
            if (any_hit) return true;
            tcull = fogrt__cull(tmax);
        }
        /* pop the next child that can still hold a closer hit */
        for (;;) {
            if (sp == 0) return found;
            --sp;
            if (any_hit || stack[sp].t <= tcull) break;   /* any hit: tcull has not moved since the push */
        }
        ref = stack[sp].ref; cnt = stack[sp].cnt;
    }
}
/* The four traversals: closest or any hit, SSE (or plain C) or AVX2 boxes; each its own
   function, so that the AVX2 ones can carry the target attribute. */
#define FOGRT__WBVH_ENTRY(qual, name, any, avx2) \
    qual bool name(const fogrt_scene *s, const fogrt__wbvh *w, fogrt__v3 o, fogrt__v3 d, float tmin, float tmax, \
                   fogrt_hit *hit) { return fogrt__wbvh_walk(s, w, o, d, tmin, tmax, hit, any, avx2); }
FOGRT__WBVH_ENTRY(FOGRT__PRIVATE, fogrt__wbvh_closest, false, false)
FOGRT__WBVH_ENTRY(FOGRT__PRIVATE, fogrt__wbvh_any, true, false)
#ifdef FOGRT__WBVH_HAS_AVX2
FOGRT__WBVH_ENTRY(FOGRT__AVX2_FN, fogrt__wbvh_closest_avx2, false, true)
FOGRT__WBVH_ENTRY(FOGRT__AVX2_FN, fogrt__wbvh_any_avx2, true, true)
#endif
#undef FOGRT__WBVH_ENTRY
FOGRT__HOT bool fogrt__wbvh_traverse(const fogrt_scene *s, const fogrt__wbvh *w, fogrt__v3 o, fogrt__v3 d,
                                     float tmin, float tmax, fogrt_hit *hit, bool any_hit) {
    if (!s->built || w->node_count == 0) return false;
#ifdef FOGRT__WBVH_HAS_AVX2
    if (w->avx2) return any_hit ? fogrt__wbvh_any_avx2(s, w, o, d, tmin, tmax, hit)
                                : fogrt__wbvh_closest_avx2(s, w, o, d, tmin, tmax, hit);
#endif
    return any_hit ? fogrt__wbvh_any(s, w, o, d, tmin, tmax, hit) : fogrt__wbvh_closest(s, w, o, d, tmin, tmax, hit);
}


/* The layout to trace: the wide tree when asked for, or by default from FOGRT_WBVH_MIN_PRIMS
   primitives (below that the binary tree is as fast). */
FOGRT__PRIVATE bool fogrt__wants_wide(const fogrt_build_desc *d, uint32_t n) {
    return d->layout == FOGRT_BVH_LAYOUT_WIDE || (d->layout == FOGRT_BVH_LAYOUT_DEFAULT && n >= FOGRT_WBVH_MIN_PRIMS);
}
/* Seam 2: with the wide layout, the binary tree need not split nodes of at most
   FOGRT_WBVH_LEAF primitives (and max_leaf_size): the collapse makes each one leaf packet
   whatever its shape, so the wide tree is the same and the build skips its most numerous
   nodes. */
FOGRT__PRIVATE uint32_t fogrt__wide_leaf_keep(const fogrt_build_desc *d, uint32_t n) {
    if (!fogrt__wants_wide(d, n) || fogrt__wbvh_small_scene(n)) return 0;
    return FOGRT__MIN((uint32_t)d->max_leaf_size, (uint32_t)FOGRT__WBVH_LEAF);
}
/* Seam 2, too: long slivers (pre-splitting, as Embree's builders do). A triangle's box can
   be far larger than the triangle: a sliver running diagonally, such as the thousands of
   long thin triangles of a fan around one vertex, has a box of about its length squared
   and next to no area, and the boxes of a fan's slivers all overlap near their shared
   vertex, so every ray there tests them all. Such a triangle enters the tree as several
   references, each with the box of the part of it inside one of k equal slabs of its box
   (across its longest side): each part's box is about 1/k of the length across, so the
   boxes a ray meets shrink about k-fold (what a fan gains and what its build costs:
   docs/benchmarks.md, "Slivers"). A reference finds the whole triangle's hits,
   so the answers do not change, only which boxes lead there.
   Which: k = (box area / triangle area) / FOGRT__WBVH_SPLIT_RATIO, at most
   FOGRT__WBVH_SPLIT_MAX; a well-shaped triangle's box is 4 to 12 times its area (the CS184
   bunny's at most 11), and the thin triangles near the poles of make bench's 1M-triangle
   sphere a few hundred times, so ordinary meshes are not cut at all and build the same tree
   (a fan's slivers: 10^4 to 10^6). How
   many: the extra references are at most as many as the primitives, and a scene never gets
   past FOGRT__WBVH_SPLIT_REFS references in all (each costs about 70 bytes of build and
   tree: an 8M-triangle fan stays as it is); when the slivers want more, each gets its share
   of the budget in proportion to what it wants (spread in triangle order). Only with the
   wide layout (the binary layout packs one primitive per reference). */
#define FOGRT__WBVH_SPLIT_RATIO 1024.0f
#define FOGRT__WBVH_SPLIT_MAX 16u
#define FOGRT__WBVH_SPLIT_REFS (1u << 22)
/* The pieces triangle t wants (1: none), and its box and slab axis. */
FOGRT__PRIVATE uint32_t fogrt__split_want(const fogrt_scene *s, uint32_t t, fogrt__aabb *box, int *axis) {
    const fogrt__v3 *v = &s->tri_v[3 * t];
    fogrt__v3 c = fogrt__cross(fogrt__sub(v[1], v[0]), fogrt__sub(v[2], v[0])), e;
    float area, r, A;
    box->lo = fogrt__v(FOGRT__MIN(v[0].x, FOGRT__MIN(v[1].x, v[2].x)), FOGRT__MIN(v[0].y, FOGRT__MIN(v[1].y, v[2].y)),
                       FOGRT__MIN(v[0].z, FOGRT__MIN(v[1].z, v[2].z)));
    box->hi = fogrt__v(FOGRT__MAX(v[0].x, FOGRT__MAX(v[1].x, v[2].x)), FOGRT__MAX(v[0].y, FOGRT__MAX(v[1].y, v[2].y)),
                       FOGRT__MAX(v[0].z, FOGRT__MAX(v[1].z, v[2].z)));
    e = fogrt__sub(box->hi, box->lo);
    A = 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
    /* Most triangles are far from a sliver: squared areas decide that without a root (the
       triangle's area is |c| / 2); a NaN goes on to the exact test below. */
    if (A * A < 0.25f * FOGRT__WBVH_SPLIT_RATIO * FOGRT__WBVH_SPLIT_RATIO * fogrt__dot(c, c)) return 1;
    area = fogrt__tri_area(s, t);
    *axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
    if (!(area > 0.0f && fogrt__comp(e, *axis) < FLT_MAX)) return 1;   /* no area, or a box past float */
    r = fogrt__aabb_area(box) / (FOGRT__WBVH_SPLIT_RATIO * area);
    return r >= (float)FOGRT__WBVH_SPLIT_MAX ? FOGRT__WBVH_SPLIT_MAX : (r >= 1.0f ? (uint32_t)r : 1u);
}
/* The extra references every sliver wants, summed, and the budget for them. */
FOGRT__PRIVATE uint64_t fogrt__split_wanted(const fogrt_scene *s, uint32_t n, uint64_t *budget) {
    uint64_t want = 0;
    uint32_t t;
    fogrt__aabb box;
    int axis;
    *budget = n < FOGRT__WBVH_SPLIT_REFS ? FOGRT__MIN((uint64_t)n, (uint64_t)(FOGRT__WBVH_SPLIT_REFS - n)) : 0u;
    for (t = 0; *budget > 0 && t < s->tri_count; ++t) want += fogrt__split_want(s, t, &box, &axis) - 1u;
    return want;
}
FOGRT__PRIVATE uint32_t fogrt__sliver_refs(const fogrt_scene *s, uint32_t n, uint32_t leaf_keep) {
    uint64_t budget, want;
    if (!leaf_keep) return n;                          /* the binary layout packs one primitive per reference */
    want = fogrt__split_wanted(s, n, &budget);
    return n + (uint32_t)FOGRT__MIN(want, budget);
}
/* The box of the part of triangle v between the planes a and b across axis ax: its corners
   between them and where its edges cross them. The crossings are rounded, so the box is
   widened by 8 ulps of the triangle's coordinates, within the triangle's own box. */
FOGRT__PRIVATE fogrt__aabb fogrt__split_piece(const fogrt__v3 *v, const fogrt__aabb *whole, int ax, float a, float b) {
    fogrt__aabb r = fogrt__aabb_empty();
    int i, j, k;
    for (i = 0; i < 3; ++i) {
        fogrt__v3 p = v[i], q = v[(i + 1) % 3];
        float pa = fogrt__comp(p, ax), qa = fogrt__comp(q, ax);
        if (pa >= a && pa <= b) fogrt__aabb_grow(&r, p);
        for (j = 0; j < 2; ++j) {
            float c = j ? b : a;
            if ((pa < c && qa > c) || (pa > c && qa < c)) fogrt__aabb_grow(&r, fogrt__madd(p, fogrt__sub(q, p), (c - pa) / (qa - pa)));
        }
    }
    for (k = 0; k < 3; ++k) {
        float lo = fogrt__comp(whole->lo, k), hi = fogrt__comp(whole->hi, k);
        float pad = 8.0f * FLT_EPSILON * FOGRT__MAX(fabsf(lo), fabsf(hi));
        float rlo = FOGRT__MAX(lo, (k == ax ? a : fogrt__comp(r.lo, k)) - pad);
        float rhi = FOGRT__MIN(hi, (k == ax ? b : fogrt__comp(r.hi, k)) + pad);
        if (!(rlo <= rhi)) { rlo = lo; rhi = hi; }      /* nothing found (rounding): the whole extent */
        if (k == 0) { r.lo.x = rlo; r.hi.x = rhi; } else if (k == 1) { r.lo.y = rlo; r.hi.y = rhi; } else { r.lo.z = rlo; r.hi.z = rhi; }
    }
    return r;
}
/* Triangle t's k references: its own (box[t]) and k - 1 more from b->box[*next]. */
FOGRT__PRIVATE void fogrt__split_tri(const fogrt_scene *s, fogrt__build *b, uint32_t t, uint32_t k, const fogrt__aabb *whole,
                                     int ax, uint32_t *next) {
    float lo = fogrt__comp(whole->lo, ax), hi = fogrt__comp(whole->hi, ax), a = lo;
    uint32_t j;
    for (j = 0; j < k; ++j) {
        float c = j + 1 == k ? hi : lo + (hi - lo) * (float)(j + 1) / (float)k;
        uint32_t r = j == 0 ? t : (*next)++;
        b->box[r] = fogrt__split_piece(&s->tri_v[3 * t], whole, ax, a, c);
        b->idx[r] = t;
        a = c;
    }
}
/* Seam 2: the m - n extra references of fogrt__sliver_refs, shared out by the slivers' wants
   (each gets floor of its running share, so the shares add up to the budget exactly). */
FOGRT__PRIVATE void fogrt__sliver_split_refs(const fogrt_scene *s, fogrt__build *b, uint32_t n, uint32_t m) {
    uint64_t budget, want, before = 0, extra = m - n;
    uint32_t t, next = n;
    fogrt__aabb box;
    int axis;
    if (m == n) return;
    want = fogrt__split_wanted(s, n, &budget);
    for (t = 0; t < s->tri_count; ++t) {
        uint64_t w = fogrt__split_want(s, t, &box, &axis) - 1u, k;
        if (w == 0) continue;
        k = want <= extra ? w : (before + w) * extra / want - before * extra / want;
        before += w;
        if (k > 0) fogrt__split_tri(s, b, t, (uint32_t)k + 1u, &box, axis, &next);
    }
    FOGRT_ASSERT(next == m);
    (void)budget;
}
/* Seam 2, too: Part I's binned split of a node (2.1: binning, sweep, partition, child
   boxes) in SSE lanes, a box's corner in one register. Part I keeps each box as six floats
   and works one coordinate at a time; here a bin is two 4-float records, and a primitive's
   centre, its three bin numbers, a bin's growth and a side's box are one instruction each
   (docs/benchmarks.md, "Wide BVH": the build's instructions). The split is Part I's bit for
   bit, so the trees are the same (tests/test_bvh.c compares them node for node): every lane
   computes what Part I computes, in the same order and with the same operand first (min
   and max of an equal pair keep the second, which decides the sign of a zero), and the
   costs are Part I's expressions. Lane 3 of a box loaded at its lo and its hi holds the
   next float of the box array, never a coordinate (the array has a spare box at its end);
   it is never stored. */
#ifdef FOGRT_WBVH_SSE
typedef struct fogrt__xbin { float lo[4], hi[4]; } fogrt__xbin;
/* The bins of one node: axis ax's bin k at ax * FOGRT__BVH_MAX_BINS + k. */
typedef struct fogrt__xbins {
    fogrt__xbin bin[3 * FOGRT__BVH_MAX_BINS];
    uint32_t n[3 * FOGRT__BVH_MAX_BINS];
    float scale[4];
    __m128 org, sc;
    int nb;
} fogrt__xbins;
/* A box as the binning reads it: two registers, loaded at its lo and at its hi. */
typedef struct fogrt__xlh { __m128 l, h; } fogrt__xlh;
FOGRT__HOT fogrt__xlh fogrt__lanes_lh(const fogrt__aabb *b) {
    fogrt__xlh r;
    r.l = _mm_loadu_ps(&b->lo.x); r.h = _mm_loadu_ps(&b->hi.x);
    return r;
}
FOGRT__PRIVATE fogrt__aabb fogrt__lanes_box(__m128 lo, __m128 hi) {
    fogrt__aabb b;
    float l[4], h[4];
    _mm_storeu_ps(l, lo); _mm_storeu_ps(h, hi);
    b.lo = fogrt__v(l[0], l[1], l[2]);
    b.hi = fogrt__v(h[0], h[1], h[2]);
    return b;
}
/* fogrt__bins_fill's set-up: as many bins, the same scales. False when every axis has
   scale 0 (all centroids coincide: no plane to try). */
FOGRT__PRIVATE bool fogrt__xbins_init(fogrt__xbins *x, const fogrt_build_desc *d, const fogrt__aabb *cb, uint32_t count) {
    int ax, k, nb = count < (uint32_t)d->bins ? (int)count : d->bins;
    if (nb == 1) nb = 2;
    x->scale[3] = 0.0f;
    for (ax = 0; ax < 3; ++ax) {
        float lo = fogrt__comp(cb->lo, ax), hi = fogrt__comp(cb->hi, ax);
        x->scale[ax] = (float)nb / (hi - lo);
        if (!(hi > lo && x->scale[ax] > 0.0f && x->scale[ax] < FLT_MAX)) x->scale[ax] = 0.0f;
        for (k = ax * FOGRT__BVH_MAX_BINS; k < ax * FOGRT__BVH_MAX_BINS + nb; ++k) {
            _mm_storeu_ps(x->bin[k].lo, _mm_set1_ps(FLT_MAX));
            _mm_storeu_ps(x->bin[k].hi, _mm_set1_ps(-FLT_MAX));
            x->n[k] = 0;
        }
    }
    x->nb = nb;
    x->org = _mm_setr_ps(cb->lo.x, cb->lo.y, cb->lo.z, 0.0f);
    x->sc = _mm_loadu_ps(x->scale);
    return x->scale[0] > 0.0f || x->scale[1] > 0.0f || x->scale[2] > 0.0f;
}
/* A box [l, h] into bin k (of the flat numbering). */
FOGRT__HOT void fogrt__xbins_add(fogrt__xbin *bin, uint32_t *n, uint32_t k, __m128 l, __m128 h) {
    _mm_storeu_ps(bin[k].lo, _mm_min_ps(_mm_loadu_ps(bin[k].lo), l));
    _mm_storeu_ps(bin[k].hi, _mm_max_ps(_mm_loadu_ps(bin[k].hi), h));
    n[k]++;
}
/* One primitive into its bin on each axis: fogrt__bin_of in three lanes (the clamps as
   max then min with the operands in its order, so a NaN lands in bin 0 there too), each
   lane's bin offset by its axis. The three axes are written out: a loop over them costs as
   much as the binning itself. */
FOGRT__HOT void fogrt__xbins_put(fogrt__xbins *x, fogrt__xlh b, __m128 org, __m128 sc, __m128 top) {
    const __m128i axis = _mm_setr_epi32(0, FOGRT__BVH_MAX_BINS, 2 * FOGRT__BVH_MAX_BINS, 0);
    __m128 c = _mm_mul_ps(_mm_add_ps(b.l, b.h), _mm_set1_ps(0.5f));    /* the centre */
    __m128 f = _mm_mul_ps(_mm_sub_ps(c, org), sc);
    __m128i k = _mm_add_epi32(_mm_cvttps_epi32(_mm_min_ps(_mm_max_ps(f, _mm_setzero_ps()), top)), axis);
    fogrt__xbins_add(x->bin, x->n, (uint32_t)_mm_cvtsi128_si32(k), b.l, b.h);
    fogrt__xbins_add(x->bin, x->n, (uint32_t)_mm_cvtsi128_si32(_mm_shuffle_epi32(k, 1)), b.l, b.h);
    fogrt__xbins_add(x->bin, x->n, (uint32_t)_mm_cvtsi128_si32(_mm_shuffle_epi32(k, 2)), b.l, b.h);
}
/* Every primitive into its bins. Neighbouring primitives mostly share their bins, and each
   update of a bin waits for the one before; so a big node bins its second half into a
   second set, side by side with the first, and merges it in at the end. The same bins bit
   for bit: min and max of the ordered list (an equal pair keeps the later one) may be taken
   over its two halves and then of the two, because the first half comes first. The
   lanes' constants live in locals, not reloaded after every store to the bins.
   Each box is loaded one step before it is binned. A load from the boxes can be held up
   by the stores to the bins before it (the processor first matches a load against them by
   the low 12 bits of the address, and the boxes sweep through every such address): loaded
   a step early, that wait overlaps the binning of the box before instead of stalling it,
   which makes the binning of big nodes faster and no longer dependent on where the stack
   lies against the boxes (docs/benchmarks.md, "Wide BVH"). count is at least 1. */
#define FOGRT__X_TWO_SETS 64
FOGRT__PRIVATE void fogrt__xbins_fill(fogrt__xbins *x, const fogrt__aabb *box, uint32_t count) {
    const __m128 org = x->org, sc = x->sc, top = _mm_set1_ps((float)(x->nb - 1));
    fogrt__xbins y;
    fogrt__xlh a, b, next_a, next_b;
    uint32_t i, half = count >= FOGRT__X_TWO_SETS ? count / 2 : 0;
    int ax, k;
    if (half == 0) {
        a = fogrt__lanes_lh(&box[0]);
        for (i = 1; i < count; ++i) {
            next_a = fogrt__lanes_lh(&box[i]);
            fogrt__xbins_put(x, a, org, sc, top);
            a = next_a;
        }
        fogrt__xbins_put(x, a, org, sc, top);
        return;
    }
    for (ax = 0; ax < 3; ++ax)
        for (k = ax * FOGRT__BVH_MAX_BINS; k < ax * FOGRT__BVH_MAX_BINS + x->nb; ++k) {
            y.bin[k] = x->bin[k];                        /* empty */
            y.n[k] = 0;
        }
    a = fogrt__lanes_lh(&box[0]); b = fogrt__lanes_lh(&box[half]);
    for (i = 1; i < half; ++i) {
        next_a = fogrt__lanes_lh(&box[i]); next_b = fogrt__lanes_lh(&box[half + i]);
        fogrt__xbins_put(x, a, org, sc, top);
        fogrt__xbins_put(&y, b, org, sc, top);
        a = next_a; b = next_b;
    }
    fogrt__xbins_put(x, a, org, sc, top);
    fogrt__xbins_put(&y, b, org, sc, top);
    if (count & 1) fogrt__xbins_put(&y, fogrt__lanes_lh(&box[count - 1]), org, sc, top);
    for (ax = 0; ax < 3; ++ax)
        for (k = ax * FOGRT__BVH_MAX_BINS; k < ax * FOGRT__BVH_MAX_BINS + x->nb; ++k) {
            _mm_storeu_ps(x->bin[k].lo, _mm_min_ps(_mm_loadu_ps(x->bin[k].lo), _mm_loadu_ps(y.bin[k].lo)));
            _mm_storeu_ps(x->bin[k].hi, _mm_max_ps(_mm_loadu_ps(x->bin[k].hi), _mm_loadu_ps(y.bin[k].hi)));
            x->n[k] += y.n[k];
        }
}
/* fogrt__side_cost of n primitives in the box [lo, hi], with fogrt__aabb_area's and
   fogrt__aabb_volume's expressions. */
FOGRT__HOT float fogrt__lanes_side_cost(const fogrt_build_desc *d, uint32_t n, __m128 lo, __m128 hi) {
    float e[4];
    _mm_storeu_ps(e, _mm_sub_ps(hi, lo));
    if (e[0] < 0.0f) return 0.0f;                        /* the empty box: n times 0 */
    return (float)n * (d->heuristic == FOGRT_BVH_VOLUME ? e[0] * e[1] * e[2]
                                                        : 2.0f * (e[0] * e[1] + e[1] * e[2] + e[2] * e[0]));
}
/* fogrt__bins_sweep on the lane records of axis ax. */
FOGRT__PRIVATE bool fogrt__xbins_sweep(const fogrt_build_desc *d, const fogrt__xbins *x, int ax, uint32_t count,
                                       float *best, int *best_k) {
    const fogrt__xbin *bin = &x->bin[ax * FOGRT__BVH_MAX_BINS];
    const uint32_t *n = &x->n[ax * FOGRT__BVH_MAX_BINS];
    __m128 lo = _mm_set1_ps(FLT_MAX), hi = _mm_set1_ps(-FLT_MAX);
    uint32_t left_n = 0, right_n = 0;
    float left_cost[FOGRT__BVH_MAX_BINS];
    bool improved = false;
    int k;
    for (k = 0; k < x->nb - 1; ++k) {
        left_n += n[k];
        lo = _mm_min_ps(lo, _mm_loadu_ps(bin[k].lo)); hi = _mm_max_ps(hi, _mm_loadu_ps(bin[k].hi));
        left_cost[k] = fogrt__lanes_side_cost(d, left_n, lo, hi);
    }
    lo = _mm_set1_ps(FLT_MAX); hi = _mm_set1_ps(-FLT_MAX);
    for (k = x->nb - 1; k > 0; --k) {
        float cost;
        right_n += n[k];
        lo = _mm_min_ps(lo, _mm_loadu_ps(bin[k].lo)); hi = _mm_max_ps(hi, _mm_loadu_ps(bin[k].hi));
        if (right_n == 0 || right_n == count) continue;
        cost = left_cost[k - 1] + fogrt__lanes_side_cost(d, right_n, lo, hi);
        if (cost < *best) { *best = cost; *best_k = k; improved = true; }
    }
    return improved;
}
/* The children's boxes: the unions of the bins of axis ax on either side of plane k, in
   bin order (as fogrt__bins_partition forms them). */
FOGRT__PRIVATE void fogrt__xbins_child_boxes(const fogrt__xbins *x, int ax, int k, fogrt_bvh_node *child) {
    const fogrt__xbin *bin = &x->bin[ax * FOGRT__BVH_MAX_BINS];
    __m128 lo = _mm_set1_ps(FLT_MAX), hi = _mm_set1_ps(-FLT_MAX);
    fogrt__aabb b;
    int j;
    for (j = 0; j < x->nb; ++j) {
        if (j == k) {
            b = fogrt__lanes_box(lo, hi);
            fogrt__node_set_box(&child[0], &b);
            lo = _mm_set1_ps(FLT_MAX); hi = _mm_set1_ps(-FLT_MAX);
        }
        lo = _mm_min_ps(lo, _mm_loadu_ps(bin[j].lo)); hi = _mm_max_ps(hi, _mm_loadu_ps(bin[j].hi));
    }
    b = fogrt__lanes_box(lo, hi);
    fogrt__node_set_box(&child[1], &b);
}
/* A box as two registers, its bytes 0-15 (lo, hi.x) and 8-23 (lo.z, hi): every load and
   store stays inside its box, so a load after the partition's stores to the neighbouring
   box is never held up by them (a load across two earlier stores must wait for both to
   reach the cache). */
FOGRT__HOT void fogrt__lanes_load(const fogrt__aabb *b, __m128 *a, __m128 *z) {
    *a = _mm_loadu_ps(&b->lo.x);
    *z = _mm_loadu_ps(&b->lo.z);
}
FOGRT__HOT void fogrt__lanes_store(fogrt__aabb *b, __m128 a, __m128 z) {
    _mm_storeu_ps(&b->lo.x, a);
    _mm_storeu_ps(&b->lo.z, z);
}
/* fogrt__bins_partition's pass on the lanes: the primitives of bins below k on axis ax to
   the front, growing both sides' centroid bounds; the same moves as Part I's, with the box
   under test kept in registers. A centroid's bin is below k exactly when its position,
   clamped at 0, is (k is a whole number from 1 to nb - 1), so one comparison stands for
   the bin number. count is at least 1. */
FOGRT__PRIVATE uint32_t fogrt__xbins_partition(const fogrt__xbins *x, fogrt__aabb *box, uint32_t *id, uint32_t count,
                                               int ax, int k, fogrt__bjob *left, fogrt__bjob *right) {
    const __m128 org = x->org, sc = x->sc, kk = _mm_set1_ps((float)k), zero = _mm_setzero_ps(), half = _mm_set1_ps(0.5f);
    __m128 llo = _mm_set1_ps(FLT_MAX), lhi = _mm_set1_ps(-FLT_MAX), rlo = llo, rhi = lhi, a, z;
    uint32_t l = 0, r = count;
    fogrt__lanes_load(&box[0], &a, &z);
    for (;;) {
        __m128 c = _mm_mul_ps(_mm_add_ps(a, _mm_shuffle_ps(z, z, _MM_SHUFFLE(0, 3, 2, 1))), half);
        __m128 f = _mm_max_ps(_mm_mul_ps(_mm_sub_ps(c, org), sc), zero);
        if ((_mm_movemask_ps(_mm_cmplt_ps(f, kk)) >> ax) & 1) {
            llo = _mm_min_ps(llo, c); lhi = _mm_max_ps(lhi, c);
            if (++l == r) break;
            fogrt__lanes_load(&box[l], &a, &z);
        } else {
            __m128 a2, z2;
            uint32_t tid = id[l];
            rlo = _mm_min_ps(rlo, c); rhi = _mm_max_ps(rhi, c);
            if (--r == l) break;
            fogrt__lanes_load(&box[r], &a2, &z2);
            fogrt__lanes_store(&box[r], a, z);
            fogrt__lanes_store(&box[l], a2, z2);
            id[l] = id[r]; id[r] = tid;
            a = a2; z = z2;
        }
    }
    left->cb = fogrt__lanes_box(llo, lhi);
    right->cb = fogrt__lanes_box(rlo, rhi);
    return l;
}
#endif
/* The seam: fogrt__bvh_split_binned's answer (*left_count, *halve) from the lanes, or false
   without SSE (Part I's scalar split then runs). */
FOGRT__PRIVATE bool fogrt__split_binned_lanes(fogrt__build *b, const fogrt__bjob *job, fogrt_bvh_node *child,
                                          fogrt__bjob *left, fogrt__bjob *right, bool *halve, uint32_t *left_count) {
#ifdef FOGRT_WBVH_SSE
    const fogrt_bvh_node *node = &b->nodes[job->node];
    uint32_t first = node->left_first, count = node->prim_count;
    fogrt__xbins x;
    float best = FLT_MAX;
    int ax, best_ax = -1, best_k = 0;
    *left_count = 0;
    if (fogrt__xbins_init(&x, &b->desc, &job->cb, count)) {
        fogrt__xbins_fill(&x, b->box + first, count);
        for (ax = 0; ax < 3; ++ax)
            if (x.scale[ax] > 0.0f && fogrt__xbins_sweep(&b->desc, &x, ax, count, &best, &best_k)) best_ax = ax;
    }
    if (best_ax < 0) {                                   /* all centroids coincide */
        *halve = count > (uint32_t)b->desc.max_leaf_size;
        return true;
    }
    if (!fogrt__split_pays(&b->desc, node, count, best)) return true;
    fogrt__xbins_child_boxes(&x, best_ax, best_k, child);
    *left_count = fogrt__xbins_partition(&x, b->box + first, b->idx + first, count, best_ax, best_k, left, right);
    return true;
#else
    (void)b; (void)job; (void)child; (void)left; (void)right; (void)halve; (void)left_count;
    return false;                                       /* Part I's scalar split */
#endif
}
/* Seam 1: the wide tree when there is one (*done), else Part I's binary tree. */
FOGRT__HOT bool fogrt__wide_traverse(const fogrt_scene *s, fogrt__v3 o, fogrt__v3 d, float tmin, float tmax,
                                      fogrt_hit *hit, bool any_hit, bool *done) {
    *done = s->x && s->x->wide && s->x->wide->node_count;
    return *done && fogrt__wbvh_traverse(s, s->x->wide, o, d, tmin, tmax, hit, any_hit);
}
#endif /* FOGRT_NO_WIDE_BVH */


#ifdef FOGRT__LAMPS
/* ------------------------------------------------------------------------------------------
   B. Lamps in fog
   What it adds: point and spot lights in fog, the lamps of the paper's own scenes, found
   by more than the light sample at each collision: equiangular sampling gathers a lamp's
   light along every fog segment (with the phase function, from a table of HG per unit
   angle); the glow around a lamp and the floor a spot lights (its footprint) are aimed at
   by some of the scattered directions; the lamps' light at the surface behind a collision
   counts T times (b' of E), and so does an emitter the ray reaches (expected emission).
   What it costs: nothing in a scene without lamps in fog (the table and the footprints are
   built only there). Its gain: docs/benchmarks.md, table "Lamps in fog".
   ------------------------------------------------------------------------------------------ */
#ifndef FOGRT_NO_MEDIUM
/* HG per unit angle. Seen along a ray, light from a point lamp scatters toward the ray's
   origin at every point of it, each with its own scattering angle psi; in the equiangular
   angle (below) psi grows linearly along the ray, so the phase function to integrate is
   HG(cos psi) per unit psi, not per steradian. That density has no closed-form inverse, so
   each scene keeps a table of it for its g: N bins in psi, spaced geometrically away from
   HG's peak (psi = 0 for g >= 0, pi for g < 0) from x0 = 1e-3 (1 - |g|) on, where HG falls
   like psi^-3, and evenly closer in, where it is flat: the distance d to the peak is
   x0 (exp(y / s) - 1) with y = i / N, so a bin is found from d without a search (one
   log1p). With N = 1024 neighbouring edges differ by at most 1.1% in d, and HG stays within
   2% of its bin's mean. The cumulative C(psi) is that of a piecewise-constant density whose
   bins hold HG's exact mass (Simpson's rule in double). Sampling from the table is exact for
   that density, so estimators that use it stay unbiased whatever the table's resolution;
   the resolution only decides how close to HG the density is. The same edges carry a second
   cumulative, K, for the glow (below): the light along a direction at angle alpha from
   the lamp is proportional to G(alpha) / sin(alpha) with G(alpha) = C(pi) - C(alpha) (the
   scattering angles from alpha to pi), so the glow's density per unit alpha is G, averaged
   per bin. Inverting a cumulative starts from a second index, the bin where each of N even
   steps of it begins, and ends with a search of the few bins in between. */
#define FOGRT__HGT_N 1024
typedef struct fogrt__hg_table {
    double x0, s;                       /* the warp: d = x0 (exp(y / s) - 1) */
    bool back;                          /* g < 0: the peak at pi, d = pi - psi */
    double edge[FOGRT__HGT_N + 1];      /* 0 = edge[0] < ... < edge[N] = pi */
    double c[FOGRT__HGT_N + 1];         /* C at the edges: HG(cos psi) per unit psi */
    double k[FOGRT__HGT_N + 1];         /* K at the edges: G(alpha) per unit alpha */
    uint16_t c_start[FOGRT__HGT_N + 1], k_start[FOGRT__HGT_N + 1];   /* the inverse's index */
    float k_norm;                       /* 1 / (2 pi K(pi)): the glow's density per steradian (below) */
    float inv_x0, sn;                   /* 1 / x0 and s N: the bin guess of fogrt__hgt_bin */
} fogrt__hg_table;
FOGRT__PRIVATE double fogrt__hg_angle(double g, double psi) {   /* HG(cos psi), base formed without cancellation */
    double s = sin(0.5 * psi), base = (1.0 - g) * (1.0 - g) + 4.0 * g * s * s;
    return (1.0 - g) * (1.0 + g) / (4.0 * FOGRT__PI_D * base * sqrt(base));
}
FOGRT__PRIVATE double fogrt__hgt_dist(const fogrt__hg_table *t, int i) {   /* distance of edge i (from the peak side) */
    return i >= FOGRT__HGT_N ? FOGRT__PI_D : t->x0 * expm1((double)i / FOGRT__HGT_N / t->s);
}
FOGRT__PRIVATE void fogrt__hgt_index(const double *cum, uint16_t *start) {
    int i = 0, j;
    for (j = 0; j <= FOGRT__HGT_N; ++j) {                 /* first bin whose top reaches j/N of the total */
        double v = cum[FOGRT__HGT_N] * j / FOGRT__HGT_N;
        while (i < FOGRT__HGT_N - 1 && cum[i + 1] < v) ++i;
        start[j] = (uint16_t)i;
    }
}
FOGRT__PRIVATE void fogrt__hg_table_build(fogrt__hg_table *t, float g) {
    int i, j;
    g = fogrt__clamp_g(g);
    t->back = g < 0.0f;
    t->x0 = FOGRT__MAX(1e-7, 1e-3 * (1.0 - fabs((double)g)));
    t->s = 1.0 / log1p(FOGRT__PI_D / t->x0);
    for (i = 0; i <= FOGRT__HGT_N; ++i)
        t->edge[i] = t->back ? FOGRT__PI_D - fogrt__hgt_dist(t, FOGRT__HGT_N - i) : fogrt__hgt_dist(t, i);
    t->edge[0] = 0.0; t->edge[FOGRT__HGT_N] = FOGRT__PI_D;
    t->c[0] = 0.0;
    for (i = 0; i < FOGRT__HGT_N; ++i) {                  /* Simpson, 16 intervals per bin */
        double a = t->edge[i], w = (t->edge[i + 1] - a) / 16.0, m = fogrt__hg_angle(g, a) + fogrt__hg_angle(g, a + 16.0 * w);
        for (j = 1; j < 16; ++j) m += (j & 1 ? 4.0 : 2.0) * fogrt__hg_angle(g, a + w * j);
        t->c[i + 1] = t->c[i] + m * w / 3.0;
    }
    t->k[0] = 0.0;
    for (i = 0; i < FOGRT__HGT_N; ++i)
        t->k[i + 1] = t->k[i] + (t->c[FOGRT__HGT_N] - 0.5 * (t->c[i] + t->c[i + 1])) * (t->edge[i + 1] - t->edge[i]);
    fogrt__hgt_index(t->c, t->c_start);
    fogrt__hgt_index(t->k, t->k_start);
    t->k_norm = (float)(1.0 / (2.0 * FOGRT__PI_D * t->k[FOGRT__HGT_N]));
    t->inv_x0 = (float)(1.0 / t->x0); t->sn = (float)(t->s * FOGRT__HGT_N);
}
/* ln(x) for x >= 1, to 1.2e-5: the exponent from the float's bits, a polynomial for the
   mantissa. A bin is 0.008 or more wide in ln units, so this only guesses the bin, and the
   exact edges decide (fogrt__hgt_bin); a library log1pf here cost a tenth of a spot-lit
   render's time. */
FOGRT__HOT float fogrt__fast_log(float x) {
    uint32_t bits;
    float m;
    int e;
    memcpy(&bits, &x, sizeof bits);
    e = (int)((bits >> 23) & 255u) - 127;
    bits = (bits & 0x007FFFFFu) | 0x3F800000u;            /* the mantissa, in [1, 2) */
    memcpy(&m, &bits, sizeof m);
    m -= 1.0f;
    return (float)e * 0.69314718f +
           m * (0.99949556f + m * (-0.49190896f + m * (0.28947478f + m * (-0.13606275f + m * 0.03215845f))));
}
/* The bin holding angle x: guessed from the warp, then moved until the exact edges hold x. */
FOGRT__PRIVATE int fogrt__hgt_bin(const fogrt__hg_table *t, double x) {
    double d = t->back ? FOGRT__PI_D - x : x;
    int j = (int)(fogrt__fast_log(1.0f + (float)FOGRT__MAX(d, 0.0) * t->inv_x0) * t->sn), i;
    j = FOGRT__CLAMP(j, 0, FOGRT__HGT_N - 1);
    i = t->back ? FOGRT__HGT_N - 1 - j : j;
    while (i > 0 && x < t->edge[i]) --i;
    while (i < FOGRT__HGT_N - 1 && x >= t->edge[i + 1]) ++i;
    return i;
}
/* A cumulative cum over the edges (C or K): its value at x and the density there, and its
   inverse at v. */
FOGRT__PRIVATE double fogrt__hgt_at(const fogrt__hg_table *t, const double *cum, double x, double *density) {
    int i = fogrt__hgt_bin(t, x);
    double d = (cum[i + 1] - cum[i]) / (t->edge[i + 1] - t->edge[i]);
    if (density) *density = d;
    return cum[i] + d * (FOGRT__CLAMP(x, t->edge[i], t->edge[i + 1]) - t->edge[i]);
}
FOGRT__PRIVATE double fogrt__hgt_invert(const fogrt__hg_table *t, const double *cum, const uint16_t *start, double v,
                                        double *density) {
    int j = FOGRT__CLAMP((int)(v / cum[FOGRT__HGT_N] * FOGRT__HGT_N), 0, FOGRT__HGT_N - 1);
    int lo = start[j], hi = FOGRT__MAX((int)start[j + 1], lo), i;
    double d;
    while (lo < hi) { int mid = (lo + hi + 1) / 2; if (cum[mid] <= v) lo = mid; else hi = mid - 1; }
    i = lo;
    d = (cum[i + 1] - cum[i]) / (t->edge[i + 1] - t->edge[i]);
    while (!(d > 0.0) && i + 1 < FOGRT__HGT_N) { ++i; d = (cum[i + 1] - cum[i]) / (t->edge[i + 1] - t->edge[i]); }
    if (density) *density = d;
    return d > 0.0 ? FOGRT__CLAMP(t->edge[i] + (v - cum[i]) / d, t->edge[i], t->edge[i + 1]) : t->edge[i];
}
#endif /* FOGRT_NO_MEDIUM */
#ifndef FOGRT_NO_MEDIUM
/* Equiangular: with theta the angle seen from the light, t = delta + h tan(theta) and theta is
   uniform between theta_a = atan((a - delta)/h) and theta_b = atan((b - delta)/h). Near the
   ray's line (h much smaller than |t - delta|) theta sits next to +-pi/2, where a float angle
   would lose the digits tan needs; in double the result is exact to float resolution down to
   h ~ 1e-7 |t - delta|. The pdf, h / ((theta_b - theta_a)(h^2 + (t - delta)^2)), is written
   as 1 / ((theta_b - theta_a)(h + (t - delta)^2 / h)) so h^2 cannot underflow.            */
FOGRT__PRIVATE double fogrt__equiangular_span(double delta, double h, double a, double b, double *theta_a) {
    *theta_a = atan2(a - delta, h);
    return atan2(b - delta, h) - *theta_a;
}
FOGRT__PRIVATE float fogrt__equiangular_density(double span, float delta, float h, float t) {
    double dt = (double)t - (double)delta;
    return (float)(1.0 / (span * ((double)h + dt * (dt / (double)h))));
}
FOGRT__PUBLIC float fogrt_sample_equiangular(float delta, float h, float a, float b, float u, float *pdf) {
    double theta_a, span = fogrt__equiangular_span(delta, h, a, b, &theta_a), x;
    float t;
    if (!(span > 0.0) || !(h > 0.0f)) { if (pdf) *pdf = 0.0f; return a; }
    x = theta_a + (double)u * span;
    /* b = inf gives theta_b = pi/2 exactly in double, where tan is huge but positive: keep
       the angle strictly below it so t stays finite and ordered */
    if (!(b < INFINITY)) x = FOGRT__MIN(x, 1.5707963267948957);
    t = u > 0.0f ? (float)FOGRT__CLAMP((double)delta + (double)h * tan(x), (double)a, (double)b) : a;
    if (pdf) *pdf = fogrt__equiangular_density(span, delta, h, t);   /* at the t returned */
    return t;
}
FOGRT__PUBLIC float fogrt_equiangular_pdf(float delta, float h, float a, float b, float t) {
    double theta_a, span = fogrt__equiangular_span(delta, h, a, b, &theta_a);
    if (!(span > 0.0) || !(h > 0.0f) || t < a || t > b) return 0.0f;
    return fogrt__equiangular_density(span, delta, h, t);
}
/* The glow density from the angle alpha and its supplement beta = pi - alpha, both exact
   (each from a chord): (pi - alpha) / sin(alpha) = beta / sin(beta) tends to 1 at the
   antipode, and 1 / pi^3 normalises it (the integral over the sphere is 2 pi (pi^2 / 2)). */
#define FOGRT__INV_PI3 0.032251534433199495f
FOGRT__PRIVATE float fogrt__glow_density(float alpha, float beta) {
    float s = sinf(FOGRT__MIN(alpha, beta));
    if (beta < 1e-4f) return FOGRT__INV_PI3;             /* beta / sin(beta) = 1 + beta^2/6 */
    return beta / FOGRT__MAX(s, 1e-30f) * FOGRT__INV_PI3;
}
FOGRT__PUBLIC fogrt_vec3 fogrt_sample_glow(fogrt_vec3 to_light, float u1, float u2, float *pdf) {
    fogrt__frame f = fogrt__frame_from_z(fogrt__normalize(to_light));
    float r = sqrtf(FOGRT__MAX(0.0f, 1.0f - FOGRT__CLAMP(u1, 0.0f, 1.0f)));   /* beta = pi r */
    float alpha = FOGRT__PI * (1.0f - r), beta = FOGRT__PI * r;
    if (pdf) *pdf = fogrt__glow_density(alpha, beta);
    return fogrt__direction_at(&f, cosf(alpha), sinf(FOGRT__MIN(alpha, beta)), u2);
}
FOGRT__PUBLIC float fogrt_glow_pdf(fogrt_vec3 to_light, fogrt_vec3 wi) {
    fogrt__v3 a = fogrt__sub(wi, to_light), b = fogrt__add(wi, to_light);
    float la = fogrt__length(a), lb = fogrt__length(b);
    return fogrt__glow_density(2.0f * atan2f(la, lb), 2.0f * atan2f(lb, la));
}
/* The two samplers above with the phase function in them, as the renderer uses them (the
   table above for the scene's g; at g = 0 they are the closed forms, to the table's
   resolution).
   Equiangular with HG: the scattering angle at x(t) is psi = theta + pi/2 (theta the
   equiangular angle: mu = -sin(theta) between the light's travel and the way back along
   the ray), so sampling psi from C between psi_a and psi_b gives t with pdf proportional to
   HG(mu(t)) / r(t)^2: the phase function and the 1/r^2 both cancel in the weight. */
/* atan2(y, x) for y, x >= 0, in [0, pi/2]: atan(r) = r P(r^2) on r = min/max in [0, 1]
   (P of degree 8, fitted here for the least relative error: 1.5e-8 in exact arithmetic, 2
   ulp in float), and pi/2 minus it when y > x. A small angle keeps its relative precision,
   as atan2f's does; the library's atanf, correctly rounded, is slower (docs/benchmarks.md,
   "Lamps in fog"). */
FOGRT__PRIVATE float fogrt__atan2_pos(float y, float x) {
    bool swap = y > x;
    float r = swap ? x / y : (x > 0.0f ? y / x : 0.0f), z = r * r, p;
    p = 2.850117773e-03f;
    p = p * z - 1.606949849e-02f; p = p * z + 4.269285931e-02f;
    p = p * z - 7.504401478e-02f; p = p * z + 1.064098099e-01f;
    p = p * z - 1.420365558e-01f; p = p * z + 1.999262067e-01f;
    p = p * z - 3.333307340e-01f; p = p * z + 9.999999848e-01f;
    p *= r;
    return swap ? 1.57079632679f - p : p;
}
/* Angles near 0 and pi keep their digits when each is formed as its distance to the nearer
   end: psi = pi/2 + atan((t - delta) / h) is atan2(h, delta - t) below pi/2 and pi minus
   atan2(h, t - delta) above, and fogrt__atan2_pos keeps its relative precision for small
   angles (so HG's peak, at psi = 0 for g >= 0 and pi for g < 0, is resolved as in double,
   at a fraction of double atan2's cost). */
FOGRT__PRIVATE double fogrt__psi_of(float t, float delta, float h) {
    float y = (float)((double)t - (double)delta);
    return y <= 0.0f ? (double)fogrt__atan2_pos(h, -y) : FOGRT__PI_D - (double)fogrt__atan2_pos(h, y);
}
/* cos x and sin x of an angle in [0, pi], each from the distance to the nearer end. */
FOGRT__PRIVATE void fogrt__cos_sin(double x, float *c, float *s) {
    float r = (float)(x <= 0.5 * FOGRT__PI_D ? x : FOGRT__PI_D - x);
    *s = sinf(r);
    *c = x <= 0.5 * FOGRT__PI_D ? cosf(r) : -cosf(r);
}
FOGRT__HOT float fogrt__sample_equiangular_hg(const fogrt__hg_table *T, float delta, float h, float a, float b,
                                              float u, float *pdf) {
    double ca = fogrt__hgt_at(T, T->c, fogrt__psi_of(a, delta, h), NULL), cb, psi, dens, dt;
    float t, cp, sp;
    cb = b < INFINITY ? fogrt__hgt_at(T, T->c, fogrt__psi_of(b, delta, h), NULL) : T->c[FOGRT__HGT_N];
    *pdf = 0.0f;
    if (!(cb > ca) || !(h > 0.0f)) return a;
    psi = fogrt__hgt_invert(T, T->c, T->c_start, ca + (double)u * (cb - ca), &dens);
    fogrt__cos_sin(psi, &cp, &sp);                          /* t = delta - h cot(psi); psi = 0 gives a */
    t = sp > 0.0f ? (float)FOGRT__CLAMP((double)delta - (double)h * (double)cp / (double)sp, (double)a, (double)b)
                  : (cp > 0.0f ? a : b);
    dt = (double)t - (double)delta;                        /* the pdf at the t returned */
    *pdf = (float)(dens / ((cb - ca) * ((double)h + dt * (dt / (double)h))));
    return t;
}
/* The glow with HG: alpha from K (density G per unit alpha, then 1 / (2 pi sin alpha) per
   steradian). */
FOGRT__PRIVATE float fogrt__glow_hg_density(const fogrt__hg_table *T, double sin_alpha, double dens) {   /* per steradian */
    return (float)dens * T->k_norm / FOGRT__MAX((float)sin_alpha, 1e-30f);
}
/* *pdf: the density at the angle drawn (the direction returned is that angle to float
   rounding), which spares fogrt__glow_hg_pdf's atan2 and table look-up. */
FOGRT__PRIVATE fogrt__v3 fogrt__sample_glow_hg(const fogrt__hg_table *T, fogrt__v3 to_light, float u1, float u2, float *pdf) {
    fogrt__frame f = fogrt__frame_from_z(to_light);
    double dens, alpha = fogrt__hgt_invert(T, T->k, T->k_start, (double)u1 * T->k[FOGRT__HGT_N], &dens);
    float ca, sa;
    fogrt__cos_sin(alpha, &ca, &sa);
    *pdf = fogrt__glow_hg_density(T, (double)sa, dens);
    return fogrt__direction_at(&f, ca, sa, u2);
}
/* alpha from the chords |wi - l| = 2 sin(alpha/2) and |wi + l| = 2 cos(alpha/2), as the
   angle to the nearer end (fogrt__psi_of); sin(alpha) is half their product. */
FOGRT__PRIVATE float fogrt__glow_hg_pdf(const fogrt__hg_table *T, fogrt__v3 to_light, fogrt__v3 wi) {
    fogrt__v3 a = fogrt__sub(wi, to_light), b = fogrt__add(wi, to_light);
    float la = fogrt__length(a), lb = fogrt__length(b);
    double alpha = la <= lb ? 2.0 * (double)fogrt__atan2_pos(la, lb) : FOGRT__PI_D - 2.0 * (double)fogrt__atan2_pos(lb, la), dens;
    (void)fogrt__hgt_at(T, T->k, alpha, &dens);
    return fogrt__glow_hg_density(T, 0.5 * (double)la * (double)lb, dens);
}
/* The footprint of a spot light on a plane (E d' aims at it), sampled two ways.
   Through the lamp's cone: a direction drawn
   uniformly in the lamp's cone meets the plane at y; seen from x, the direction is y - x.
   Its density per steradian at x is the cone's, 1 / (2 pi (1 - cos cutoff)), turned into
   area on the plane (cos_y / |y - l|^2, cos_y between the plane's normal and the way to the
   lamp l) and back into solid angle at x (|y - x|^2 / cos_x, cos_x between the normal and
   the direction). A cone direction that misses the plane (it runs parallel or away) gives
   no direction: the sampler fails, and its density integrates to the share of the cone that
   meets the plane. Where the lamp lights a floor, a vertex in the fog above it finds the lit
   disk with this, which phase sampling reaches by chance and the glow (which aims at the
   lamp itself) seldom. But the points drawn are spread as the lamp's light is, not as the
   disk looks from x: from a vertex near the floor the nearby part of the disk fills most
   of the view and gets few of them, and the weights (cos_y / |y - x|^2) vary widely. So
   the second way aims at the disk as x sees it: directions uniform in the cone that a
   sphere around the lit patch subtends from x (the sphere sampler's cone, above), for
   half the footprint's samples where x lies outside that sphere (inside it, all go
   through the lamp's cone). The sphere need not hold the patch exactly (it is found from
   16 points of its rim): the density below is exact for any sphere. Its gain:
   docs/benchmarks.md, table "Footprint". */
#define FOGRT__FOOTPRINT_CAP 0.5f       /* the share of the footprint's samples aimed through the sphere */
typedef struct fogrt__footprint {
    fogrt__v3 light;           /* the lamp's position */
    fogrt__frame cone;         /* around its unit axis (cone.n) */
    float one_minus_cos;       /* 1 - cos(cutoff), from the angle: exact for narrow cones */
    fogrt__v3 p, n;            /* a point of the plane, its unit normal on the lamp's side */
    fogrt__v3 center;          /* a sphere around the lit patch (radius 0: none, the cone's rim */
    float radius;              /*   does not meet the plane all round) */
    float near_plane;          /* a vertex closer than this to the plane does not aim at it */
    bool on;                   /* a plane was found (fogrt__find_footprints, below) */
} fogrt__footprint;
/* Where the lamp's direction w meets the plane (also the rim points of fogrt__footprint_bound's
   bound); false when w runs parallel to the plane or away from it. */
FOGRT__PRIVATE bool fogrt__footprint_hit(const fogrt__footprint *F, fogrt__v3 w, fogrt__v3 *y) {
    float dn = fogrt__dot(w, F->n), t;
    if (!(dn < 0.0f)) return false;
    t = fogrt__dot(fogrt__sub(F->p, F->light), F->n) / dn;
    if (!(t > 0.0f) || !fogrt__finite(t)) return false;
    *y = fogrt__madd(F->light, w, t);
    return true;
}
FOGRT__PRIVATE bool fogrt__sample_footprint_cone(const fogrt__footprint *F, fogrt__v3 x, float u1, float u2, fogrt__v3 *wi) {
    float len2;
    fogrt__v3 y, xy;
    if (!fogrt__footprint_hit(F, fogrt__in_cone(&F->cone, u1 * F->one_minus_cos, u2), &y)) return false;
    xy = fogrt__sub(y, x);
    len2 = fogrt__dot(xy, xy);
    if (!(len2 > 0.0f) || !fogrt__finite(len2)) return false;
    *wi = fogrt__scale(xy, 1.0f / sqrtf(len2));
    return true;
}
/* The density of fogrt__sample_footprint_cone at wi: the ray x + t wi meets the plane at y
   (t > 0), y must lie in the cone and the lamp on its side of the plane. Written so that no
   intermediate overflows; 0 where the result would not be finite (grazing directions from
   a point next to the plane, where the true density is astronomically large on a vanishing
   set of directions). */
FOGRT__PRIVATE float fogrt__footprint_cone_pdf(const fogrt__footprint *F, fogrt__v3 x, fogrt__v3 wi) {
    float dn = fogrt__dot(wi, F->n), t, d2, d, cos_y, pdf;
    fogrt__v3 ly;
    if (dn == 0.0f) return 0.0f;
    t = fogrt__dot(fogrt__sub(F->p, x), F->n) / dn;
    if (!(t > 0.0f) || !fogrt__finite(t)) return 0.0f;
    ly = fogrt__sub(fogrt__madd(x, wi, t), F->light);   /* y - l */
    d2 = fogrt__dot(ly, ly);
    if (!(d2 > 0.0f) || !fogrt__finite(d2)) return 0.0f;
    d = sqrtf(d2);
    cos_y = -fogrt__dot(ly, F->n) / d;
    if (!(cos_y > 0.0f) || fogrt__dot(ly, F->cone.n) < (1.0f - F->one_minus_cos) * d) return 0.0f;
    pdf = (cos_y / (2.0f * FOGRT__PI * F->one_minus_cos * d2)) * (t / fabsf(dn)) * t;
    return fogrt__finite(pdf) ? pdf : 0.0f;
}
/* The second way: the cone the sphere subtends from x, its axis and 1 - cos of its
   half-angle; false where x is inside the sphere (or there is none). */
FOGRT__PRIVATE bool fogrt__footprint_sphere(const fogrt__footprint *F, fogrt__v3 x, fogrt__v3 *axis, float *omc) {
    float dist;
    if (!(F->radius > 0.0f)) return false;
    *omc = fogrt__sphere_one_minus_cos_max(F->center, F->radius, x, &dist);
    if (!(*omc > 0.0f) || !(dist > 0.0f)) return false;
    *axis = fogrt__scale(fogrt__sub(F->center, x), 1.0f / dist);
    return true;
}
/* Both ways mixed: FOGRT__FOOTPRINT_CAP of the samples through the sphere, where x sees it
   from outside, the rest through the lamp's cone; the density is the same mixture. A
   direction is inside the sphere's cone when 1 - cos of its angle to the axis, half the
   squared chord |wi - axis|^2 (exact for small angles), is at most omc. */
FOGRT__PRIVATE bool fogrt__sample_footprint(const fogrt__footprint *F, fogrt__v3 x, float u1, float u2, fogrt__v3 *wi) {
    fogrt__v3 axis;
    float omc;
    if (!fogrt__footprint_sphere(F, x, &axis, &omc)) return fogrt__sample_footprint_cone(F, x, u1, u2, wi);
    if (u1 < FOGRT__FOOTPRINT_CAP) {                     /* the sphere light's sampler */
        *wi = fogrt_sample_sphere_solid_angle(F->center, F->radius, x, u1 / FOGRT__FOOTPRINT_CAP, u2, NULL);
        return true;
    }
    return fogrt__sample_footprint_cone(F, x, (u1 - FOGRT__FOOTPRINT_CAP) / (1.0f - FOGRT__FOOTPRINT_CAP), u2, wi);
}
FOGRT__PRIVATE float fogrt__footprint_pdf(const fogrt__footprint *F, fogrt__v3 x, fogrt__v3 wi) {
    fogrt__v3 axis, chord;
    float omc, sphere = 0.0f;
    if (!fogrt__footprint_sphere(F, x, &axis, &omc)) return fogrt__footprint_cone_pdf(F, x, wi);
    chord = fogrt__sub(wi, axis);
    if (0.5f * fogrt__dot(chord, chord) <= omc) sphere = 1.0f / (2.0f * FOGRT__PI * omc);
    return FOGRT__FOOTPRINT_CAP * sphere + (1.0f - FOGRT__FOOTPRINT_CAP) * fogrt__footprint_cone_pdf(F, x, wi);
}
#endif
#ifndef FOGRT_NO_MEDIUM
/* The footprints of E d' (above), found once per build of a scene with lamps in fog.
   For each spot light, 64 rays stratified over its cone (8 x 8 cells in cos theta and
   azimuth, one ray at each centre) find what it lights. The plane that most of them meet
   (triangles with normals within 0.8 degrees of each other and offsets within 1e-4 of the
   scene's size) is the footprint's, when at least a quarter of the rays meet it and the
   lamp is not on it. A point light, or a cone that lights curved or scattered things, has
   none, and d' aims at its glow alone. A footprint also gets a sphere around its lit patch
   (fogrt__footprint_bound), when the whole rim of the cone meets the plane. Returns false
   when out of memory. */
#define FOGRT__FOOTPRINT_GRID 8        /* the rays: a grid of 8 x 8 over the cone */
#define FOGRT__FOOTPRINT_SHARE 0.2f    /* the share of a lamp's glow samples aimed at its footprint */
#define FOGRT__FOOTPRINT_RIM 16        /* points of the cone's rim on the plane that the sphere holds */
/* The sphere around the lit patch (above): the centroid of 16 points where the cone's
   rim meets the plane, and their largest distance from it, 2% more (the rim between them
   bulges a little past the points when the cone meets the plane at a slant). No sphere
   when part of the rim misses the plane: the patch is then unbounded. */
FOGRT__PRIVATE void fogrt__footprint_bound(fogrt__footprint *F) {
    fogrt__v3 rim[FOGRT__FOOTPRINT_RIM], c = fogrt__v(0.0f, 0.0f, 0.0f);
    float r = 0.0f;
    int j;
    F->radius = 0.0f;
    for (j = 0; j < FOGRT__FOOTPRINT_RIM; ++j) {
        fogrt__v3 w = fogrt__in_cone(&F->cone, F->one_minus_cos, ((float)j + 0.5f) / (float)FOGRT__FOOTPRINT_RIM);
        if (!fogrt__footprint_hit(F, w, &rim[j])) return;
        c = fogrt__add(c, rim[j]);
    }
    c = fogrt__scale(c, 1.0f / (float)FOGRT__FOOTPRINT_RIM);
    for (j = 0; j < FOGRT__FOOTPRINT_RIM; ++j) r = FOGRT__MAX(r, fogrt__length(fogrt__sub(rim[j], c)));
    if (!(r > 0.0f) || !fogrt__finite(r) || !fogrt__v3_finite(c)) return;
    F->center = c;
    F->radius = 1.02f * r;
}
FOGRT__PRIVATE bool fogrt__find_footprints(fogrt_scene *s) {
    enum { RAYS = FOGRT__FOOTPRINT_GRID * FOGRT__FOOTPRINT_GRID };
    float tol = 1e-4f * fogrt__length(fogrt__sub(s->bmax, s->bmin));
    uint32_t i;
    s->x->footprints = (fogrt__footprint *)fogrt__alloc(&s->allocator, sizeof(fogrt__footprint) * s->light_count);
    if (!s->x->footprints) return false;
    memset(s->x->footprints, 0, sizeof(fogrt__footprint) * s->light_count);
    for (i = 0; i < s->light_count; ++i) {
        const fogrt_light_desc *l = &s->lights[i];
        fogrt__footprint *F = &s->x->footprints[i];
        fogrt__v3 n[RAYS], q[RAYS];                      /* per ray that meets a triangle: its plane */
        int hits = 0, j, k, best = 0, best_count = 0;
        float half = 0.5f * l->cutoff_deg * (FOGRT__PI / 180.0f);
        if (l->type != FOGRT_LIGHT_SPOT) continue;
        F->light = l->position;
        F->cone = fogrt__frame_from_z(l->direction);
        F->one_minus_cos = 2.0f * sinf(half) * sinf(half);
        if (!(F->one_minus_cos > 0.0f)) continue;
        for (j = 0; j < RAYS; ++j) {
            float omc = ((float)(j / FOGRT__FOOTPRINT_GRID) + 0.5f) / (float)FOGRT__FOOTPRINT_GRID * F->one_minus_cos;
            float u2 = ((float)(j % FOGRT__FOOTPRINT_GRID) + 0.5f) / (float)FOGRT__FOOTPRINT_GRID;
            fogrt__v3 w = fogrt__in_cone(&F->cone, omc, u2), nn;
            const fogrt__v3 *v;
            fogrt_hit h;
            if (!fogrt__traverse(s, l->position, w, 0.0f, INFINITY, &h, false) || h.prim >= s->tri_count) continue;
            v = &s->tri_v[3 * h.prim];
            nn = fogrt__cross(fogrt__sub(v[1], v[0]), fogrt__sub(v[2], v[0]));
            if (!(fogrt__dot(nn, nn) > 0.0f)) continue;
            nn = fogrt__normalize(nn);
            n[hits] = fogrt__dot(nn, fogrt__sub(l->position, v[0])) < 0.0f ? fogrt__neg(nn) : nn;
            q[hits++] = v[0];
        }
        for (j = 0; j < hits; ++j) {                     /* the plane most rays meet */
            int count = 0;
            for (k = 0; k < hits; ++k)
                count += fogrt__dot(n[j], n[k]) > 0.9999f && fabsf(fogrt__dot(n[j], fogrt__sub(q[k], q[j]))) <= tol;
            if (count > best_count) { best_count = count; best = j; }
        }
        if (4 * best_count < RAYS) continue;
        F->p = q[best]; F->n = n[best];
        F->near_plane = tol;
        F->on = fogrt__dot(F->n, fogrt__sub(l->position, F->p)) > tol;
        if (F->on) fogrt__footprint_bound(F);
    }
    return true;
}
#endif
#ifndef FOGRT_NO_MEDIUM
/* The part [*a, *b] of the ray o + t d (t in [*a, *b] on entry) inside a spot light's cone:
   the forward nappe of a cone with a half-angle below 90 degrees is convex, so a line meets
   it in one interval. Its ends are among the roots of the quadratic "on the cone surface"
   and the plane through the apex; the inside test at the midpoints picks the interval.
   The two common cases need no sorting (fogrt__clip_to_cone_quadratic, first).
   cos_c is the cosine of the cutoff (s->spot_cos, 2.3). Returns false when the ray
   misses the cone. */
/* The common cases, from the quadratic A t^2 + 2 B t + C >= 0 of the double cone (da and wa
   the direction's and the origin's components along the axis): a line steeper than the
   cone (A < 0) is inside between the two roots only, all in one nappe (it could change
   nappes only at the apex, along a direction inside the cone); a line along the cone
   (A > 0) is inside beyond the roots, the far side in the forward nappe when it runs the
   spot's way. Returns 1 with [*a, *b] clipped, 0 for a miss, -1 when the general case
   must decide (A = 0, or no real root with A > 0, which rounding alone can make). */
FOGRT__HOT int fogrt__clip_to_cone_quadratic(float A, float B, float C, float da, float wa, float *a, float *b) {
    float disc = B * B - A * C, q, r0, r1, lo, hi;
    if (A == 0.0f) return -1;
    if (!(disc >= 0.0f)) return A < 0.0f ? 0 : -1;      /* A < 0: misses both nappes (most rays) */
    q = sqrtf(disc); r0 = (-B + q) / A; r1 = (-B - q) / A;   /* r0 <= r1 when A < 0, r1 <= r0 when A > 0 */
    if (A < 0.0f) {
        if (!(wa + 0.5f * (r0 + r1) * da >= 0.0f)) return 0;   /* the backward nappe */
        lo = r0; hi = r1;
    } else if (da > 0.0f) { lo = r0; hi = INFINITY; }
    else { lo = -INFINITY; hi = r1; }
    lo = FOGRT__MAX(lo, *a); hi = FOGRT__MIN(hi, *b);
    if (!(hi > lo)) return 0;
    *a = lo; *b = hi;
    return 1;
}
FOGRT__HOT bool fogrt__clip_to_cone(const fogrt_light_desc *l, float cos_c, fogrt__v3 o, fogrt__v3 d, float *a, float *b) {
    fogrt__v3 w = fogrt__sub(o, l->position);
    float c2 = cos_c * cos_c;
    float da = fogrt__dot(d, l->direction), wa = fogrt__dot(w, l->direction);
    float A = da * da - c2, B = da * wa - c2 * fogrt__dot(d, w), C = wa * wa - c2 * fogrt__dot(w, w);
    float t[6], lo = FLT_MAX, hi = -FLT_MAX, end = *b;
    int n = 0, i, j;
    if (l->cutoff_deg >= 90.0f) return true;           /* not convex: keep the whole segment */
    if ((i = fogrt__clip_to_cone_quadratic(A, B, C, da, wa, a, b)) >= 0) return i != 0;
    t[n++] = *a;
    if (A != 0.0f) {
        float disc = B * B - A * C;
        if (disc >= 0.0f) { float q = sqrtf(disc); t[n++] = (-B - q) / A; t[n++] = (-B + q) / A; }
    } else if (B != 0.0f) {
        t[n++] = -C / (2.0f * B);
    }
    if (da != 0.0f) t[n++] = -wa / da;
    if (!(end < INFINITY)) { float far_t = 1.0f; for (i = 0; i < n; ++i) far_t = FOGRT__MAX(far_t, 2.0f * fabsf(t[i]) + 1.0f); end = far_t; }
    t[n++] = end;
    for (i = 1; i < n; ++i)                               /* insertion sort, at most 6 values */
        for (j = i; j > 0 && t[j] < t[j - 1]; --j) { float tmp = t[j]; t[j] = t[j - 1]; t[j - 1] = tmp; }
    for (i = 0; i + 1 < n; ++i) {
        float t0 = FOGRT__MAX(t[i], *a), t1 = FOGRT__MIN(t[i + 1], end), tm, ax;
        fogrt__v3 x;
        if (!(t1 > t0)) continue;
        tm = 0.5f * (t0 + t1);
        x = fogrt__madd(w, d, tm);
        ax = fogrt__dot(x, l->direction);
        if (ax >= 0.0f && ax * ax >= c2 * fogrt__dot(x, x)) { lo = FOGRT__MIN(lo, t0); hi = FOGRT__MAX(hi, t1); }
    }
    if (!(hi > lo)) return false;
    *a = lo;
    *b = (hi >= end && !(*b < INFINITY)) ? INFINITY : hi;
    return true;
}
#endif

#endif /* FOGRT__LAMPS */

/* ------------------------------------------------------------------------------------------
   C. Sampling and estimation
   What it adds: environment maps sampled by their brightness; the exact dielectric
   Fresnel; fog bounded by a box; one light per vertex chosen by power; the roulette's
   survival scaled per scene by a pilot; pixel positions stratified per stream; per-pixel
   sample rates from the first samples' noise (adaptive sampling, unbiased).
   What it costs: each only where a scene or a desc asks for it, except the pilot (a
   fraction of a second at build) and the stratified positions (a few integer operations
   per sample). Their gains: docs/benchmarks.md, tables "Roulette pilot", "Stratified pixel
   positions", "Pixel rates" and "Lights by power".
   ------------------------------------------------------------------------------------------ */
#ifndef FOGRT_NO_GLASS
#ifndef FOGRT_NO_EXACT_FRESNEL
/* Exact unpolarised Fresnel of a dielectric: the mean of the s and p reflectances. The
   transmitted cosine comes from cos_t^2 = (cos_i^2 + eta^2 - 1) / eta^2, which does not
   round 1 - cos_i^2 to 1 at grazing angles (so eta = 1 gives cos_t = cos_i and F = 0). */
FOGRT__PUBLIC float fogrt_fresnel_dielectric(float eta, float cos_i) {
    float cos2_t, cos_t, r_par, r_perp;
    cos_i = FOGRT__CLAMP(cos_i, -1.0f, 1.0f);
    if (cos_i < 0.0f) { eta = 1.0f / eta; cos_i = -cos_i; }   /* from inside */
    if (eta == 1.0f) return 0.0f;                             /* no interface */
    cos2_t = (cos_i * cos_i + (eta - 1.0f) * (eta + 1.0f)) / (eta * eta);
    if (cos2_t <= 0.0f) return 1.0f;                          /* total internal reflection */
    cos_t = sqrtf(cos2_t);
    r_par = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return 0.5f * (r_par * r_par + r_perp * r_perp);
}
#endif
#endif
/* An environment map (C): 3 floats a pixel, w x h pixels in CS184's mapping. */
struct fogrt__env_map { float *rgb; int w, h; };
#ifndef FOGRT_NO_ESTIMATION
/* Environment maps: the map replaces the constant environment (the scene keeps the pixels,
   times scale), is looked up in CS184's mapping, and is sampled by next-event estimation in
   proportion to luminance x sin(theta). */
FOGRT__PRIVATE void fogrt__env_map_free(fogrt_scene *s) {
    if (s->env_map) fogrt__free(&s->allocator, s->env_map->rgb);
    fogrt__free(&s->allocator, s->env_map);
    s->env_map = NULL;
}
FOGRT__PUBLIC fogrt_result fogrt_scene_set_environment_map(fogrt_scene *s, int width, int height, const float *rgb, float scale) {
    size_t i, n;
    float *copy;
    struct fogrt__env_map *map;
    FOGRT_ASSERT(s);
    if (!rgb) {
        fogrt__env_map_free(s);
        s->has_env = !fogrt__is_black(s->env);
        s->built = false;
        return FOGRT_RESULT_OK;
    }
    if (width < 1 || height < 1 || (uint64_t)width * (uint64_t)height > ((uint64_t)1 << 28))
        return fogrt__fail(s, FOGRT_RESULT_INVALID_ARGUMENT, "environment map: width and height must be >= 1 and width x height at most 2^28");
    if (!fogrt__finite(scale) || !(scale >= 0.0f))
        return fogrt__fail(s, FOGRT_RESULT_INVALID_ARGUMENT, "environment map: scale negative or not finite");
    n = (size_t)width * (size_t)height * 3;
    for (i = 0; i < n; ++i)
        if (!fogrt__finite(rgb[i]) || rgb[i] < 0.0f || !fogrt__finite(rgb[i] * scale))
            return fogrt__fail(s, FOGRT_RESULT_INVALID_ARGUMENT, "environment map: a pixel is negative or not finite (after scale)");
    copy = (float *)fogrt__alloc(&s->allocator, sizeof(float) * n);
    map = (struct fogrt__env_map *)fogrt__alloc(&s->allocator, sizeof *map);
    if (!copy || !map) { fogrt__free(&s->allocator, copy); fogrt__free(&s->allocator, map); return FOGRT_RESULT_OUT_OF_MEMORY; }
    for (i = 0; i < n; ++i) copy[i] = rgb[i] * scale;
    fogrt__env_map_free(s);
    map->rgb = copy; map->w = width; map->h = height;
    s->env_map = map;
    s->has_env = true;
    s->built = false;
    return FOGRT_RESULT_OK;
}
FOGRT__PRIVATE size_t fogrt__env_pixel(const fogrt_scene *s, fogrt__v3 d, float *sin_theta) {
    float y = acosf(FOGRT__CLAMP(d.y, -1.0f, 1.0f)) * FOGRT__INV_PI;
    float x = (atan2f(-d.z, d.x) + FOGRT__PI) * (0.5f * FOGRT__INV_PI);
    int w = s->env_map->w, h = s->env_map->h;
    int i = FOGRT__CLAMP((int)(x * (float)w), 0, w - 1), j = FOGRT__CLAMP((int)(y * (float)h), 0, h - 1);
    *sin_theta = sqrtf(FOGRT__MAX(0.0f, (1.0f - d.y) * (1.0f + d.y)));
    return (size_t)j * (size_t)w + (size_t)i;
}
FOGRT__PRIVATE fogrt__v3 fogrt__env_map_radiance(const fogrt_scene *s, fogrt__v3 d) {
    float sin_t;
    const float *c;
    if (!s->env_map) return fogrt__env_radiance(s, d);
    c = s->env_map->rgb + 3 * fogrt__env_pixel(s, d, &sin_t);
    return fogrt__v(c[0], c[1], c[2]);
}
/* The environment map (CS184's mapping): direction <-> (x, y) in [0,1)^2 of the image,
   theta = pi y from +y, phi = 2 pi x with phi = atan2(-z, x) + pi. The sampling density of
   a pixel is its table weight over the total, per unit (x, y); per solid angle it is divided
   by the Jacobian d omega / dx dy = 2 pi^2 sin(theta). */
FOGRT__PRIVATE fogrt__v3 fogrt__env_dir(float x, float y, float *sin_theta) {
    float theta = FOGRT__PI * y, phi = 2.0f * FOGRT__PI * x;
    *sin_theta = sinf(theta);
    return fogrt__v(-*sin_theta * cosf(phi), cosf(theta), *sin_theta * sinf(phi));
}
/* The probability (per unit x, y) of pixel p in the sampling tables. */
FOGRT__PRIVATE float fogrt__env_cell_pdf(const fogrt_scene *s, size_t p) {
    size_t w = (size_t)s->env_map->w, h = (size_t)s->env_map->h;
    const float *rows = s->x->env_cdf + w * h;
    size_t i = p % w, j = p / w;
    const float *cdf = s->x->env_cdf + j * w;
    float pr = rows[j] - (j ? rows[j - 1] : 0.0f), pc = cdf[i] - (i ? cdf[i - 1] : 0.0f);
    return pr * pc * (float)w * (float)h;
}
FOGRT__PRIVATE float fogrt__env_pdf(const fogrt_scene *s, fogrt__v3 d) {
    float sin_t;
    size_t p;
    if (!s->env_map || !(s->x->env_total > 0.0)) return 0.0f;
    p = fogrt__env_pixel(s, d, &sin_t);
    return sin_t > 0.0f ? fogrt__env_cell_pdf(s, p) / (2.0f * FOGRT__PI * FOGRT__PI * sin_t) : 0.0f;
}
FOGRT__PRIVATE bool fogrt__sample_env(const fogrt_scene *s, const float *u, fogrt_light_sample *ls) {
    float fy, fx, sin_t;
    int w = s->env_map->w, h = s->env_map->h;
    int j = fogrt__cdf_find(s->x->env_cdf + (size_t)w * (size_t)h, h, u[0], &fy);
    int i = fogrt__cdf_find(s->x->env_cdf + (size_t)j * (size_t)w, w, u[1], &fx);
    size_t p = (size_t)j * (size_t)w + (size_t)i;
    ls->wi = fogrt__env_dir(((float)i + fx) / (float)w, ((float)j + fy) / (float)h, &sin_t);
    ls->dist = INFINITY;
    ls->is_delta = false;
    ls->pdf = sin_t > 0.0f ? fogrt__env_cell_pdf(s, p) / (2.0f * FOGRT__PI * FOGRT__PI * sin_t) : 0.0f;
    const float *c = s->env_map->rgb + 3 * p;
    ls->Le = fogrt__v(c[0], c[1], c[2]);
    return ls->pdf > 0.0f && !fogrt__is_black(ls->Le);
}

/* The one light list: lights 0 .. light_count-1 are the point and spot lights, then the
   area lights, and last the environment map when there is one. A point light is sampled once (it is one direction), any other light
   light_samples times; a point light needs two uniforms (the sphere of a light with a
   radius), an area light three (the triangle, then the point on it). */
/* The environment map's sampling tables: the weight of pixel (i, j) is its luminance times
   sin(theta) at the row's centre (the solid angle a row covers); per row a CDF over its
   columns, then a CDF over the rows. */
/* The environment map's CDFs: rows, and columns within each row. */
FOGRT__PRIVATE bool fogrt__build_env(fogrt_scene *s) {
    double total = 0.0;
    float *rows;
    s->x->env_total = 0.0;
    if (!s->env_map) return true;
    int i, j, w = s->env_map->w, h = s->env_map->h;
    s->x->env_cdf = (float *)fogrt__alloc(&s->allocator, sizeof(float) * ((size_t)w * (size_t)h + (size_t)h));
    if (!s->x->env_cdf) return false;
    rows = s->x->env_cdf + (size_t)w * (size_t)h;
    for (j = 0; j < h; ++j) {
        float *cdf = s->x->env_cdf + (size_t)j * (size_t)w;
        double sin_t = sin(3.14159265358979323846 * ((double)j + 0.5) / (double)h), row = 0.0;
        for (i = 0; i < w; ++i) {
            const float *c = s->env_map->rgb + 3 * ((size_t)j * (size_t)w + (size_t)i);
            row += (double)fogrt__luminance(fogrt__v(c[0], c[1], c[2])) * sin_t;
            cdf[i] = (float)row;
        }
        for (i = 0; i < w; ++i) cdf[i] = row > 0.0 ? (float)((double)cdf[i] / row) : (float)(i + 1) / (float)w;
        cdf[w - 1] = 1.0f;
        total += row;
        rows[j] = (float)total;
    }
    for (j = 0; j < h; ++j) rows[j] = total > 0.0 ? (float)((double)rows[j] / total) : (float)(j + 1) / (float)h;
    rows[h - 1] = 1.0f;
    s->x->env_total = total;
    return true;
}
#endif

#ifndef FOGRT_NO_MEDIUM
/* The part [*a, *b] of the ray segment o + t d, t in [0, tmax], that lies in the fog: all of
   it, or with bounded fog its part inside the box (a slab test like 2.1's, NaN-safe
   for axis-parallel rays on a face). False when the segment misses the fog. */
FOGRT__HOT bool fogrt__fog_box_span(const fogrt_scene *s, fogrt__v3 o, fogrt__v3 d, float tmax, float *a, float *b) {
    int k;
    *a = 0.0f; *b = tmax;
    if (!s->x->fog_bounded) return true;
    for (k = 0; k < 3; ++k) {
        float inv = fogrt__safe_rcp(fogrt__comp(d, k)), oc = fogrt__comp(o, k);
        float t0 = (fogrt__comp(s->x->fog_lo, k) - oc) * inv, t1 = (fogrt__comp(s->x->fog_hi, k) - oc) * inv;
        if (t0 > t1) { float t = t0; t0 = t1; t1 = t; }
        if (t0 > *a) *a = t0;                            /* NaN bounds are ignored */
        if (t1 < *b) *b = t1;
    }
    return *b > *a;
}
#endif
#ifndef FOGRT_NO_ESTIMATION
/* Where the fog is: the medium's box, or with an environment light and no box the box of
   the geometry (fog filling all space would hide the sky), or everywhere. */
FOGRT__PRIVATE void fogrt__fog_bounds(fogrt_scene *s, uint32_t n) {
    s->x->fog_bounded = s->medium.bounded;
    s->x->fog_lo = s->medium.bounds_min; s->x->fog_hi = s->medium.bounds_max;
    if (s->medium.bounded || !(s->features & FOGRT_FEATURE_MEDIUM) || !s->has_env || n == 0) return;
    s->x->fog_bounded = true;
    s->x->fog_lo = s->bmin; s->x->fog_hi = s->bmax;
    fogrt__log(s, FOGRT_LOG_WARNING, "medium: the scene has an environment light and the fog no bounds: the fog fills the box of the geometry");
}
#endif
/* The one light list: lights 0 .. light_count-1 are the point and spot lights, then the
   area lights, and last the environment map when there is one. A point light is sampled once (it is one direction), any other light
   light_samples times; a point light needs two uniforms (the sphere of a light with a
   radius), an area light three (the triangle, then the point on it). */
FOGRT__PRIVATE uint32_t fogrt__light_total(const fogrt_scene *s) {
#ifndef FOGRT_NO_ESTIMATION
    return s->light_count + s->area_light_count + (s->env_map && s->x->env_total > 0.0 ? 1u : 0u);
#else
    return s->light_count + s->area_light_count;        /* the map is found by escaping rays only */
#endif
}
/* Choosing lights by power (render desc light_by_power): each light's radiant flux,
   estimated as luminance x emitting area x pi for an area light, intensity x the solid
   angle it lights for a point or spot light, and for the environment map its mean radiance
   x pi x the sphere around the geometry's box. The table is the CDF of these over the light
   list (uniform when all are 0). */
FOGRT__PRIVATE float fogrt__light_power(const fogrt_scene *s, uint32_t i, float radius) {
    if (i < s->light_count) {
        const fogrt_light_desc *l = &s->lights[i];
        float solid = 4.0f * FOGRT__PI;
        if (l->type == FOGRT_LIGHT_SPOT) solid = 2.0f * FOGRT__PI * (1.0f - cosf(FOGRT__MIN(l->cutoff_deg, 180.0f) * (FOGRT__PI / 180.0f)));
        return fogrt__luminance(l->intensity) * solid;
    }
    i -= s->light_count;
    if (i < s->area_light_count) {
        const fogrt__area_light *a = &s->area_lights[i];
        uint32_t m = a->sphere != UINT32_MAX ? s->sph_material[a->sphere] : s->tri_material[s->light_prims[a->first]];
        return fogrt__luminance(s->materials[m].emission) * a->area * FOGRT__PI;
    }
    return (float)(s->x->env_total * FOGRT__PI_D / (2.0 * (double)s->env_map->w * (double)s->env_map->h)) *   /* mean radiance */
           FOGRT__PI * 4.0f * FOGRT__PI * radius * radius;
}
FOGRT__PRIVATE float fogrt__light_radius(const fogrt_scene *s) {    /* of the sphere around the geometry */
    return FOGRT__MAX(0.5f * fogrt__length(fogrt__sub(s->bmax, s->bmin)), 1e-6f);
}
#ifdef FOGRT__LAMPS
/* The share c of d' (E): half the point and spot lights' share of the light's power, 1/2
   when they are all of it. */
FOGRT__PRIVATE float fogrt__glow_share_of(const fogrt_scene *s) {
    uint32_t i, n = fogrt__light_total(s);
    double total = 0.0, lamps = 0.0;
    if (n < 2) return 0.5f;
    for (i = 0; i < n; ++i) {
        double w = (double)FOGRT__MAX(fogrt__light_power(s, i, fogrt__light_radius(s)), 0.0f);
        total += w;
        if (i < s->light_count) lamps += w;
    }
    return total > 0.0 ? (float)(0.5 * lamps / total) : 0.5f;
}
#endif
#ifndef FOGRT_NO_ESTIMATION
FOGRT__PRIVATE bool fogrt__build_light_pick(fogrt_scene *s) {
    uint32_t i, n = fogrt__light_total(s);
    double total = 0.0, run = 0.0;
    if (n < 2) return true;
    s->x->light_pick = (float *)fogrt__alloc(&s->allocator, sizeof(float) * n);
    if (!s->x->light_pick) return false;
    for (i = 0; i < n; ++i) {                            /* the powers, then their running sum */
        s->x->light_pick[i] = FOGRT__MAX(fogrt__light_power(s, i, fogrt__light_radius(s)), 0.0f);
        total += (double)s->x->light_pick[i];
    }
    for (i = 0; i < n; ++i) {
        run += total > 0.0 ? (double)s->x->light_pick[i] : 1.0;
        s->x->light_pick[i] = (float)(run / (total > 0.0 ? total : (double)n));
    }
    s->x->light_pick[n - 1] = 1.0f;
    return true;
}
#endif
FOGRT__PRIVATE int fogrt_light_sample_count(const fogrt_scene *s, const fogrt__settings *st, uint32_t i) {
    return i < s->light_count && !(s->lights[i].radius > 0.0f) ? 1 : st->desc.light_samples;
}
FOGRT__PRIVATE void fogrt__draw(const fogrt_scene *s, uint32_t light, fogrt_rng *rng, float *u) {
    u[0] = fogrt_rng_float(rng); u[1] = fogrt_rng_float(rng);
    u[2] = light < s->light_count ? 0.0f : fogrt_rng_float(rng);
}
FOGRT__PRIVATE bool fogrt__sample_light(const fogrt_scene *s, uint32_t i, fogrt__v3 x, const float *u, fogrt_light_sample *ls) {
    if (i < s->light_count) return fogrt__sample_point_light(s, &s->lights[i], x, u, ls);
    if (i - s->light_count < s->area_light_count) return fogrt__sample_area_light(s, &s->area_lights[i - s->light_count], x, u, ls);
#ifndef FOGRT_NO_ESTIMATION
    return fogrt__sample_env(s, u, ls);
#else
    return false;
#endif
}
/* The probability that next-event estimation picks light i: 1 when every light is sampled. */
FOGRT__PRIVATE float fogrt__pick_prob(const fogrt_scene *s, bool by_power, uint32_t i) {
    if (!by_power) return 1.0f;
    return s->x->light_pick[i] - (i ? s->x->light_pick[i - 1] : 0.0f);
}

#ifndef FOGRT_NO_ESTIMATION
/* Adaptive sampling (not in the paper). The error above is a sum over pixels, and pixels
   are not equally noisy: in the paper's spot-lit box the lit cone, the floor it lights
   and the bunny's edges are noisier than the dim fog around them. With the same cost per
   sample, spending n_p samples on pixel p with n_p proportional to its standard deviation
   sigma_p (per sample) makes sum_p sigma_p^2 / n_p, the error's numerator, least for a
   given total: the gain over equal n_p is mean(sigma^2) / mean(sigma)^2.
   The catch is bias. A pixel whose count follows its own samples (stop once it looks
   converged) is biased: a pixel that has not yet met its rare bright path looks quiet,
   stops, and stays dark. The count is harmless only when it is independent of the
   samples it divides, and the rates here keep it so:
     - the pixels are split like a chessboard, (x + y) even and odd, and a pixel's rate
       reads only the other colour's noise: the noise around it (a box of pixels holding
       about 8192 samples, at least 3 x 3) and that colour's means for the normalisation;
     - the rates are made once, from samples taken with every pixel alike, and then kept
       (made again later, they would read samples whose counts read this pixel's).
   So a pixel's count depends on samples of other pixels only, which are independent of
   its own (each pixel, each sample, has its own random stream): its mean stays an
   average of samples whose number was fixed without looking at them. The rounding of
   spp x rate to a count is a coin of its own (fogrt__rated_spp).
   The noise is sigma^2 = Var[mean] x n from the streams (so stratification counts). One
   rare path can make one pixel's estimate thousands of times its neighbours'; capped at
   16 times the colour's mean before the boxes sum them, such a pixel no longer drags its
   box along. rate = max(sigma_box, 0.3 x mean) / mean, so no pixel falls below about a
   third of the even rate, in case the box saw none of its rare light yet. Its gain:
   docs/benchmarks.md, table "Pixel rates". */
FOGRT__PRIVATE void fogrt__sat_build(double *sat, const double *v, int W, int H) {
    int x, y;
    memset(sat, 0, sizeof(double) * (size_t)(W + 1));
    for (y = 0; y < H; ++y) {
        double row = 0.0;
        double *o = sat + (size_t)(y + 1) * (size_t)(W + 1), *up = o - (W + 1);
        o[0] = 0.0;
        for (x = 0; x < W; ++x) { row += v[(size_t)y * (size_t)W + (size_t)x]; o[x + 1] = up[x + 1] + row; }
    }
}
FOGRT__PRIVATE double fogrt__sat_box(const double *sat, int W, int x0, int y0, int x1, int y1) {
    size_t w = (size_t)W + 1;
    return sat[(size_t)(y1 + 1) * w + (size_t)(x1 + 1)] - sat[(size_t)y0 * w + (size_t)(x1 + 1)]
         - sat[(size_t)(y1 + 1) * w + (size_t)x0] + sat[(size_t)y0 * w + (size_t)x0];
}
/* out: on the pixels of colour c, v capped at cap (v NULL: 1, to count them); 0 elsewhere. */
FOGRT__PRIVATE void fogrt__colour_layer(double *out, const double *v, int W, int H, int c, double cap) {
    int x, y;
    for (y = 0; y < H; ++y)
        for (x = 0; x < W; ++x) {
            size_t i = (size_t)y * (size_t)W + (size_t)x;
            out[i] = ((x + y) & 1) != c ? 0.0 : v ? FOGRT__MIN(v[i], cap) : 1.0;
        }
}
/* Step 1: each colour's noise per sample, its mean, then capped at 16 times it, in two
   summed-area tables per colour (the noise, and how many of its pixels); v + n is scratch. */
FOGRT__PRIVATE void fogrt__rate_tables(const fogrt_image *img, double *v, double *sat_v, double *sat_n, double *count) {
    int W = img->width, H = img->height, x, y, c;
    size_t i, n = (size_t)W * (size_t)H, cells = (size_t)(W + 1) * (size_t)(H + 1);
    double vmean[2] = {0.0, 0.0};
    for (y = 0; y < H; ++y)
        for (x = 0; x < W; ++x) {
            i = (size_t)y * (size_t)W + (size_t)x; c = (x + y) & 1;
            v[i] = fogrt_image_pixel_variance(img, i) * (double)img->count[i];
            if (!(v[i] < DBL_MAX)) v[i] = DBL_MAX / 4.0;
            vmean[c] += v[i]; count[c] += 1.0;
        }
    for (c = 0; c < 2; ++c) vmean[c] = count[c] > 0.0 ? vmean[c] / count[c] : 0.0;
    for (c = 0; c < 2; ++c) {
        fogrt__colour_layer(v + n, v, W, H, c, 16.0 * vmean[c]);
        fogrt__sat_build(sat_v + (size_t)c * cells, v + n, W, H);
        fogrt__colour_layer(v + n, NULL, W, H, c, 0.0);
        fogrt__sat_build(sat_n + (size_t)c * cells, v + n, W, H);
    }
}
/* Step 2: each pixel's noise from the other colour's pixels in the box of radius r around
   it; amean[c] sums colour c's. */
FOGRT__PRIVATE void fogrt__rate_boxes(int W, int H, int r, double *v, const double *sat_v, const double *sat_n, double *amean) {
    size_t cells = (size_t)(W + 1) * (size_t)(H + 1);
    int x, y;
    for (y = 0; y < H; ++y)
        for (x = 0; x < W; ++x) {
            int o = 1 - ((x + y) & 1);          /* the other colour */
            int x0 = FOGRT__MAX(x - r, 0), x1 = FOGRT__MIN(x + r, W - 1);
            int y0 = FOGRT__MAX(y - r, 0), y1 = FOGRT__MIN(y + r, H - 1);
            double k = fogrt__sat_box(sat_n + (size_t)o * cells, W, x0, y0, x1, y1);
            double sum = fogrt__sat_box(sat_v + (size_t)o * cells, W, x0, y0, x1, y1);
            size_t i = (size_t)y * (size_t)W + (size_t)x;
            v[i] = k > 0.0 ? sqrt(FOGRT__MAX(sum, 0.0) / k) : 0.0;
            amean[(x + y) & 1] += v[i];
        }
}
/* Step 3: a pixel of colour c is normalised by what the other colour's noise gave colour c. */
FOGRT__PRIVATE void fogrt__rate_normalise(int W, int H, const double *v, const double *count, double *amean, float *rates) {
    double norm[2] = {0.0, 0.0};
    int x, y, c;
    size_t i;
    for (c = 0; c < 2; ++c) amean[c] = count[c] > 0.0 ? amean[c] / count[c] : 0.0;
    for (y = 0; y < H; ++y)
        for (x = 0; x < W; ++x) {
            c = (x + y) & 1; i = (size_t)y * (size_t)W + (size_t)x;
            norm[c] += FOGRT__MAX(v[i], 0.3 * amean[c]);
        }
    for (y = 0; y < H; ++y)
        for (x = 0; x < W; ++x) {
            double a;
            c = (x + y) & 1; i = (size_t)y * (size_t)W + (size_t)x;
            a = norm[c] > 0.0 && amean[c] > 0.0 ? FOGRT__MAX(v[i], 0.3 * amean[c]) * count[c] / norm[c] : 1.0;
            rates[i] = (float)FOGRT__MIN(a, (double)FOGRT_MAX_SAMPLE_RATE);
        }
}
FOGRT__PUBLIC fogrt_result fogrt_image_sample_rates(const fogrt_image *img, float *rates) {
    int W, H, r;
    size_t n, i, cells;
    double samples = 0.0, count[2] = {0.0, 0.0}, amean[2] = {0.0, 0.0};
    double *v, *sat_v, *sat_n, side;
    FOGRT_ASSERT(img && rates);
    W = img->width; H = img->height;
    n = (size_t)W * (size_t)H;
    cells = (size_t)(W + 1) * (size_t)(H + 1);
    for (i = 0; i < n; ++i) samples += img->count[i];
    if (samples <= 0.0) return FOGRT_RESULT_INVALID_ARGUMENT;
    v = (double *)fogrt__alloc(&img->allocator, sizeof(double) * n * 2);
    sat_v = (double *)fogrt__alloc(&img->allocator, sizeof(double) * cells * 2);
    sat_n = (double *)fogrt__alloc(&img->allocator, sizeof(double) * cells * 2);
    if (v && sat_v && sat_n) {
        fogrt__rate_tables(img, v, sat_v, sat_n, count);
        side = sqrt(8192.0 / (samples / (double)n));   /* the box: about 8192 samples at this image's mean count */
        r = side > 3.0 ? (int)ceil((side - 1.0) / 2.0) : 1;
        if (r > W + H) r = W + H;
        fogrt__rate_boxes(W, H, r, v, sat_v, sat_n, amean);
        fogrt__rate_normalise(W, H, v, count, amean, rates);
    }
    fogrt__free(&img->allocator, v); fogrt__free(&img->allocator, sat_v); fogrt__free(&img->allocator, sat_n);
    return v && sat_v && sat_n ? FOGRT_RESULT_OK : FOGRT_RESULT_OUT_OF_MEMORY;
}

/* The stratified pixel positions. Sobol's first two dimensions form a (0,2)-sequence: for
   every k, each aligned block of 2^k points puts exactly one point in every elementary box
   of area 2^-k of the unit square (points 0..3 one per quadrant, and so on). They are
   easiest to write, and to scramble, with the bits reversed (the first binary digit of a
   coordinate in bit 0): the first dimension is then the index itself (van der Corput),
   the second XORs, for every set bit k of the index, the column w_k = w_{k-1} ^ (w_{k-1}
   << 1), w_0 = 1 (bit i of w_k is binomial(k, i) mod 2: the matrix of the polynomial x + 1). */
FOGRT__PRIVATE uint32_t fogrt__sobol2_reversed(uint32_t index) {
    uint32_t w = 1u, y = 0u;
    for (; index; index >>= 1, w ^= w << 1)
        if (index & 1u) y ^= w;
    return y;
}
FOGRT__PRIVATE uint32_t fogrt__reverse_bits(uint32_t x) {
    x = (x << 16) | (x >> 16);
    x = ((x & 0x00FF00FFu) << 8) | ((x >> 8) & 0x00FF00FFu);
    x = ((x & 0x0F0F0F0Fu) << 4) | ((x >> 4) & 0x0F0F0F0Fu);
    x = ((x & 0x33333333u) << 2) | ((x >> 2) & 0x33333333u);
    return ((x & 0x55555555u) << 1) | ((x >> 1) & 0x55555555u);
}
/* A random nested (Owen-type) scramble of a bit-reversed coordinate, returned as a 32-bit
   fraction. Nested means: each digit k is flipped or not depending only on the seed and
   the digits before it, so points sharing their first digits are moved together and every
   elementary interval goes to an elementary interval: the (0,2) structure survives. In the
   reversed form any bijection whose bit k depends only on bits 0..k is such a scramble, and
   three cheap ones compose to a well-mixed one: adding a number (carries run only upward),
   multiplying by an odd number, and x ^= x * (an even number) (the product's bit k comes
   from bits below k). The first step adds a uniform random 32-bit number, so whatever
   follows, each point alone is uniform over [0, 1): the pixel estimate stays unbiased.
   It is a cheap stand-in for Owen's scramble by one random bit per tree node: it draws
   from fewer permutations, but is as stratified (the even constants are the golden-ratio
   and MurmurHash3 mixing constants with their last bit cleared). */
FOGRT__PRIVATE uint32_t fogrt__nested_scramble(uint32_t reversed, uint64_t seed) {
    uint32_t x = reversed + (uint32_t)seed;
    x ^= x * 0x9E3779B8u;
    x *= (uint32_t)(seed >> 32) | 1u;
    x ^= x * 0x85EBCA6Au;
    x ^= x * 0xC2B2AE34u;
    return fogrt__reverse_bits(x);
}
/* The position in pixel `pix` of sample `index`: stream index mod FOGRT_IMAGE_STREAMS, point
   index / FOGRT_IMAGE_STREAMS of that stream's sequence, scrambled with seeds drawn from
   (seed, pixel, stream). A function of (seed, pixel, index) only, so batches and threads do
   not change it, and a later batch continues each stream's sequence. */
FOGRT__PRIVATE void fogrt__stratified_position(uint64_t base, uint64_t pix, uint32_t index, float *jx, float *jy) {
    uint32_t point = index / FOGRT_IMAGE_STREAMS, stream = index % FOGRT_IMAGE_STREAMS;
    uint64_t key = fogrt__hash64(base ^ fogrt__hash64(0x5354524154494649ULL ^ (pix * FOGRT_IMAGE_STREAMS + stream)));
    uint32_t ux = fogrt__nested_scramble(point, key);
    uint32_t uy = fogrt__nested_scramble(fogrt__sobol2_reversed(point), fogrt__hash64(key));
    *jx = (float)(ux >> 8) * 5.9604644775390625e-8f;   /* the top 24 bits: [0, 1 - 2^-24] */
    *jy = (float)(uy >> 8) * 5.9604644775390625e-8f;
}

/* How many samples pixel pix takes in this call. After B spp asked for with rates, the
   pixel has had floor(B x rate + u) of them, u a uniform of its own drawn from (seed,
   pixel) alone, never from its radiance: the mean count is B x rate exactly, and it does
   not depend on how B was split over calls (the image is the same for any batches). */
FOGRT__PRIVATE uint32_t fogrt__rated_spp(const fogrt__job *job, size_t pix) {
    double u = (double)(fogrt__hash64(job->base ^ fogrt__hash64(0x52415445ULL ^ (uint64_t)pix)) >> 11) * (1.0 / 9007199254740992.0);
    double r = (double)job->st.desc.sample_rate[pix], b = (double)job->img->rated_spp;
    double n = floor((b + (double)job->spp) * r + u) - floor(b * r + u);
    double room = (double)(0xFFFFFFFFu - job->img->count[pix]);
    return n <= 0.0 ? 0u : (uint32_t)(n < room ? n : room);
}
#endif /* FOGRT_NO_ESTIMATION */

/* ------------------------------------------------------------------------------------------
   The state of a path in Part II: what the trace (D) reports and the full integrator (E)
   follows.
   ------------------------------------------------------------------------------------------ */
/* The full integrator's settings: Part I's, and what the desc asks of Part II. */
typedef struct fogrt__xs {
    bool equiangular, glow, footprint, by_power, expected_emission;
#ifndef FOGRT_NO_MEDIA
    bool hero_pdf;             /* G, chroma: weigh by the hero channel's density alone, not the
                                  channels' mean: the wrong estimator, which fogrt never sets, for
                                  the negative control of tests/test_chroma.c */
#endif
    float rr_k;                /* the roulette survives with min(0.95, rr_k x throughput) (e) */
    bool rr_probe;             /* the pilot (C): note each path's first roulette */
#ifdef FOGRT_TRACE
    fogrt_trace_fn trace;      /* fogrt_trace_path's callback (NULL in fogrt_render) */
    void *trace_user;
#endif
} fogrt__xs;

/* The lamps whose glow the next direction may aim at (d'), at the path's current vertex. */
#define FOGRT__GLOW_MAX 4      /* lamps a vertex aims at, at most (the first that qualify) */
typedef struct fogrt__glow {
    int n;
    uint8_t fp;                /* bit k: the footprint of lamp[k] is aimed at too */
    uint32_t lamp[FOGRT__GLOW_MAX];
    fogrt__v3 dir[FOGRT__GLOW_MAX];   /* unit, from the vertex to each of them */
} fogrt__glow;

/* The state of a path as the full integrator follows it: Part I's walk (the ray, the
   throughput, the light gathered, the vertex), which Algorithm 1's loop steps, and what
   Part II's steps keep besides. */
typedef struct fogrt__path {
    fogrt__walk w;             /* Part I's state; w.x points back here */
    float rr_scale;            /* roulette reads beta x this: the mixed sampling's pdf / the
                                  phase or BSDF pdf after a step d', else 1 */
    bool entering;             /* surface: wo is on the front side of the geometry */
    fogrt_bsdf_type type;      /* surface: the BSDF of v */
    fogrt__glow glow;          /* the lamps v may aim at (d') */
    float seg_tr;              /* the fog's transmittance over the ray to the surface it reached (b') */
    const fogrt__xs *xs;
    const fogrt__med *m;       /* the medium the ray travels in (the world's, or H's) */
    bool (*next_event)(const fogrt_scene *s, const fogrt__settings *st, struct fogrt__path *P, int limit);
#ifndef FOGRT_NO_MEDIA
    bool media_light;          /* G: a light sample needs fogrt__media_light (another phase, chroma) */
    bool chroma;               /* G: sigma_t per channel */
    int hero;                  /* G, chroma: the channel whose sigma_t samples every free flight */
    fogrt__v3 r;               /* G, chroma: each channel's density of the path's free flights so
                                  far, relative to one another (fogrt__chroma_mix) */
#endif
#ifndef FOGRT_NO_SHAPES
    uint32_t med;              /* H: the index of m in H's table */
    uint32_t prim;             /* H: the surface of the vertex (a refraction crosses it) */
    bool crossed;              /* H: the ray passed an interface: the next event goes on beyond it */
#endif
    float probe_lum, probe_b;  /* the pilot (xs->rr_probe): luminance gathered, throughput x */
    uint64_t probe_rays;       /*   rr_scale, and rays traced when the path met its first roulette */
    bool probed;
} fogrt__path;

/* A trace hook (D): with FOGRT_TRACE a call to one of the fogrt__trace_* functions when a
   callback is set, without it nothing at all. */
#ifdef FOGRT_TRACE
#define FOGRT__HOOK(call) do { if (P->xs->trace) call; } while (0)
#else
#define FOGRT__HOOK(call) ((void)0)
#endif

/* ------------------------------------------------------------------------------------------
   D. The path trace (FOGRT_TRACE)
   What it adds: fogrt_trace_path, one pixel sample rendered as fogrt_render renders it, with
   every step of its path (free flight, surface, light sample, scattering, roulette, ...)
   handed to a callback: what the tests and examples/fogrt_cli_trace.c read a path by.
   What it costs: nothing without FOGRT_TRACE (the hooks in E compile to nothing); compiled
   in, a render without a callback pays a test per hook (docs/benchmarks.md, table "Strip
   cost").
   ------------------------------------------------------------------------------------------ */
#ifdef FOGRT_TRACE
/* Tracing a path (FOGRT_TRACE): each hook below fills one fogrt_trace_event and hands it to
   the callback. None of this exists without FOGRT_TRACE. */
FOGRT__PRIVATE fogrt_trace_event fogrt__event(fogrt_trace_kind kind, const fogrt__path *P) {
    fogrt_trace_event e;
    memset(&e, 0, sizeof e);
    e.kind = kind;
    e.bounce = P->w.depth;
    e.p = P->w.o; e.d = P->w.d; e.beta = P->w.beta;
    return e;
}
FOGRT__PRIVATE void fogrt__emit(const fogrt__path *P, const fogrt_trace_event *e) {
    if (P->xs->trace) P->xs->trace(e, P->xs->trace_user);
}
FOGRT__PRIVATE void fogrt__trace_free_flight(const fogrt__path *P, float u, float t,
                                             float t_surface, bool collided) {
    fogrt_trace_event e = fogrt__event(FOGRT_TRACE_FREE_FLIGHT, P);
    e.u[0] = u; e.t = t; e.t_max = t_surface; e.flag = collided;
    fogrt__emit(P, &e);
}
FOGRT__PRIVATE void fogrt__trace_surface(const fogrt__path *P, uint32_t prim) {
    fogrt_trace_event e = fogrt__event(FOGRT_TRACE_SURFACE, P);
    e.p = P->w.v.p; e.prim = prim; e.bsdf = P->type;
    fogrt__emit(P, &e);
}
FOGRT__PRIVATE void fogrt__trace_simple(const fogrt__path *P, fogrt_trace_kind kind) {
    fogrt_trace_event e = fogrt__event(kind, P);
    fogrt__emit(P, &e);
}
FOGRT__PRIVATE void fogrt__trace_light(const fogrt__path *P, const fogrt__vertex *v,
                                       uint32_t light, const fogrt_light_sample *ls, fogrt__v3 f, float pdf_b,
                                       float tr, float w, fogrt__v3 value) {
    fogrt_trace_event e = fogrt__event(FOGRT_TRACE_LIGHT_SAMPLE, P);
    e.p = v->p; e.d = ls->wi; e.t = ls->dist; e.Le = ls->Le; e.pdf = ls->pdf; e.f = f; e.pdf_other = pdf_b;
    e.transmittance = tr; e.mis_weight = w; e.value = value; e.light = light;
    fogrt__emit(P, &e);
}
FOGRT__PRIVATE void fogrt__trace_equiangular(const fogrt__path *P, uint32_t light,
                                             float u, float t, float pdf, fogrt__v3 weight) {
    fogrt_trace_event e = fogrt__event(FOGRT_TRACE_EQUIANGULAR, P);
    e.light = light; e.u[0] = u; e.t = t; e.pdf = pdf; e.value = weight;
    fogrt__emit(P, &e);
}
#ifndef FOGRT_NO_MEDIUM
FOGRT__PRIVATE void fogrt__trace_phase(const fogrt__path *P, const fogrt_medium_desc *m, float u1, float u2) {
    fogrt_trace_event e = fogrt__event(FOGRT_TRACE_PHASE_SAMPLE, P);
    e.u[0] = u1; e.u[1] = u2; e.cos_theta = fogrt_sample_hg_mu(m->g, u1); e.phi = 2.0f * FOGRT__PI * u2;
    if (m->phase != FOGRT_PHASE_HG) e.cos_theta = -fogrt__dot(P->w.v.wo, P->w.d);   /* G's phases: the angle drawn */
    e.pdf = P->w.prev_pdf;
    fogrt__emit(P, &e);
}
#endif
FOGRT__PRIVATE void fogrt__trace_glow(const fogrt__path *P, const float *u, bool glow,
                                      bool footprint, uint32_t light, float pdf_b, float pdf, fogrt__v3 weight) {
    fogrt_trace_event e = fogrt__event(FOGRT_TRACE_GLOW_SAMPLE, P);
    memcpy(e.u, u, sizeof e.u);
    e.source = footprint ? "footprint" : NULL;
    e.p = P->w.v.p; e.flag = glow; e.light = light; e.pdf = pdf; e.pdf_other = pdf_b; e.value = weight;
    fogrt__emit(P, &e);
}
FOGRT__PRIVATE void fogrt__trace_bsdf(const fogrt__settings *st, const fogrt__path *P, const float *u,
                                      const fogrt_bsdf_sample *bs, float cos_o) {
    fogrt_trace_event e = fogrt__event(FOGRT_TRACE_BSDF_SAMPLE, P);
    memcpy(e.u, u, sizeof e.u);
    e.p = P->w.v.p; e.bsdf = P->type; e.pdf = bs->pdf; e.value = bs->weight;
    e.lobe = bs->is_transmission ? FOGRT_LOBE_REFRACT : bs->is_delta ? FOGRT_LOBE_REFLECT
           : P->type == FOGRT_BSDF_MICROFACET ? FOGRT_LOBE_GLOSSY : FOGRT_LOBE_DIFFUSE;
#ifndef FOGRT_NO_GLASS
    if (P->type == FOGRT_BSDF_GLASS) e.fresnel = fogrt__fresnel(st->desc.fresnel, FOGRT__DEF(P->w.v.m->ior, 1.5f), cos_o);
#else
    (void)cos_o;
#endif
    fogrt__emit(P, &e);
}
FOGRT__PRIVATE void fogrt__trace_roulette(const fogrt__path *P, float q, float u, bool survived) {
    fogrt_trace_event e = fogrt__event(FOGRT_TRACE_ROULETTE, P);
    e.q = q; e.u[0] = u; e.flag = survived;
    if (survived) e.beta = fogrt__scale(e.beta, 1.0f / q);   /* the weight it goes on with */
    fogrt__emit(P, &e);
}
FOGRT__PRIVATE void fogrt__trace_gather(const fogrt__path *P, fogrt__v3 c, bool counted,
                                        const char *source) {
    fogrt_trace_event e;
    if (fogrt__is_black(c)) return;                     /* only light that adds something */
    e = fogrt__event(FOGRT_TRACE_CONTRIBUTION, P);
    e.value = c; e.flag = counted; e.source = source;
    fogrt__emit(P, &e);
}
#endif


/* ------------------------------------------------------------------------------------------
   E. The full integrator
   What it adds: the steps of B and C inside Part I's Algorithm 1, as fogrt_render_defaults()
   runs it. It has no loop of its own: fogrt__full_radiance_xs puts Part I's walk inside the
   path state below (fogrt__path) and runs fogrt__algorithm1, whose four steps hand the
   path to the functions here at seams 7a-7d. What it costs: nothing for a feature a scene
   does not use (make callgrind; table "Strip cost"). The steps, named as the seams
   reach them:
     a. (seam 7a, fogrt__next_vertex) fogrt__free_flight: in fog, sample a collision distance t (3.1). If t comes before
        the surface, the event is a fog collision and the path weight is multiplied by the
        albedo sigma_s/sigma_t (transmittance and pdf cancel); otherwise the ray reaches the
        surface with probability T and weight T/T = 1. Point and spot lights are gathered
        along the way by equiangular sampling with the phase function (B).
     b. fogrt__surface_emission: add the emission the ray reaches (weighted by MIS when
        next-event estimation could have found it too; in fog by T, whether or not the
        free flight collided first: expected emission, B), and fogrt__surface_event: set up
        the surface's frame.
     b'. fogrt__light_behind (B): after a fog collision, the light of point and spot lights
        sampled at the surface behind it, times T; step c counts it T times when the ray
        gets there.
     c. (seam 7b, fogrt__light_at_vertex) fogrt__full_light_step: at the scattering vertex, fog or surface, sample the lights (2.3),
        one chosen by power where asked (C).
     d. (seam 7c, fogrt__new_direction) fogrt__full_scatter: the new direction:
        Henyey-Greenstein in the fog (3.3), the BSDF on a surface (2.2).
     d'. fogrt__scatter_glow (B): near point and spot lights in fog, some of the new
        directions aim at the glow around a lamp instead, so that the paths that pass next
        to it are common and light, not rare and huge; some of those aimed at a spot light
        aim at the floor it lights (its footprint).
     e. (seam 7d, fogrt__roulette) fogrt__full_roulette_q: Russian roulette's q, scaled by the
        scene's pilot (C).
   A scene without fog never enters step a: it pays one well-predicted branch per bounce.
   The one-bounce baseline is the same loop with its rule (fogrt__algorithm1's one_bounce).
   ------------------------------------------------------------------------------------------ */
/* The fog's phase function where E samples or evaluates it: Henyey-Greenstein (3.3), or
   with another phase (G) G's. In a build without G these are 3.3's calls as they were; with
   it, one compare where a fog vertex samples or evaluates (make callgrind). */
FOGRT__HOT fogrt__v3 fogrt__fog_vertex_f(const fogrt_scene *s, const fogrt__med *m, const fogrt__vertex *v, fogrt__v3 wi,
                                         float *pdf) {
#ifndef FOGRT_NO_MEDIA
    if (v->is_medium && (m->d.phase != FOGRT_PHASE_HG || !m->world)) {   /* (Part I's reads the world's g) */
        float p = fogrt__media_pdf(&m->d, v->wo, wi);
        *pdf = p;
        return fogrt__v(p, p, p);
    }
#else
    (void)m;
#endif
    return fogrt__vertex_f(s, v, wi, pdf);
}
#ifndef FOGRT_NO_MEDIUM
FOGRT__HOT fogrt__v3 fogrt__fog_phase_sample(const fogrt__med *m, fogrt__v3 wo, float u1, float u2, float *pdf) {
#ifndef FOGRT_NO_MEDIA
    if (m->d.phase != FOGRT_PHASE_HG) return fogrt__media_sample(&m->d, wo, u1, u2, pdf);
#endif
    return fogrt__sample_hg_unit(m->d.g, wo, u1, u2, pdf);
}
/* Where the ray o + t d, t in [0, tmax], is in medium m: [a, b]; the world's fog may be
   bounded by a box (C). False: it misses it. */
FOGRT__HOT bool fogrt__med_span(const fogrt_scene *s, const fogrt__med *m, fogrt__v3 o, fogrt__v3 d, float tmax,
                                float *a, float *b) {
    if (m->world) return fogrt__fog_box_span(s, o, d, tmax, a, b);
    *a = 0.0f;
    *b = tmax;
    return true;
}
#endif
typedef bool (*fogrt__step)(const fogrt_scene *s, const fogrt__settings *st, fogrt__path *P, int limit);
FOGRT__PRIVATE fogrt__step fogrt__next_event_of(const fogrt_scene *s);
/* Part II's state for the walk w that Part I started: w moves into the path, and
   Algorithm 1 then steps P->w. */
FOGRT__HOT void fogrt__path_start(const fogrt_scene *s, fogrt__path *P, const fogrt__xs *xs, const fogrt__walk *w) {
    memset(P, 0, sizeof *P);
    P->w = *w;
    P->w.x = P;
    P->rr_scale = 1.0f;
    P->type = FOGRT_BSDF_DIFFUSE;
    P->xs = xs;
    P->m = &s->x->world;
    P->next_event = fogrt__next_event_of(s);            /* a + b: the paper's medium, G's or H's */
#ifndef FOGRT_NO_SHAPES
    if (s->x->h) {                                       /* H: the medium the camera is in */
        fogrt__h_start(s, P);
        return;
    }
#endif
#ifndef FOGRT_NO_MEDIA
    if (s->x->media) fogrt__media_start(s, P);          /* G: which steps need it, the hero channel */
#else
    (void)s;
#endif
}
/* Light that reaches the camera after `bounces` scattering events (min_depth drops the
   shorter paths: CS184's -o 0). source says what it is, for the trace. */
FOGRT__PRIVATE void fogrt__gather(fogrt__path *P, const fogrt__settings *st, int bounces, fogrt__v3 c, const char *source) {
    if (bounces >= st->desc.min_depth) P->w.L = fogrt__add(P->w.L, c);
    FOGRT__HOOK(fogrt__trace_gather(P, c, bounces >= st->desc.min_depth, source));
    (void)source;
}
FOGRT__PRIVATE bool fogrt__is_scattering(const fogrt__path *P) {
    return P->w.v.is_medium || !fogrt__bsdf_is_delta(P->type);
}
#ifdef FOGRT__LAMPS
/* The lamps whose glow (B) a scattering vertex in fog may aim its next direction
   at (d'): every point and spot light. At most FOGRT__GLOW_MAX, the first
   ones; none on a mirror or glass surface, outside the fog, or with the glow switched off.
   A lamp with a footprint is also aimed at through it, unless the vertex lies on its plane
   (directions from there only graze it). */
FOGRT__PRIVATE void fogrt__glow_setup(const fogrt_scene *s, const fogrt__path *P, const fogrt__vertex *v, fogrt__glow *g,
                                      bool scattering) {
    uint32_t i;
    g->n = 0;
    g->fp = 0;
    if (!P->xs->glow || !scattering || !v->in_medium || !P->m->world || !(s->medium.sigma_t > 0.0f) ||
        !(s->x->glow_share > 0.0f)) return;                 /* (B's tables are the world fog's) */
    for (i = 0; i < s->light_count && g->n < FOGRT__GLOW_MAX; ++i) {
        const fogrt_light_desc *l = &s->lights[i];
        fogrt__v3 w = fogrt__sub(l->position, v->p);
        if (!(fogrt__dot(w, w) > 0.0f)) continue;
        g->dir[g->n] = fogrt__normalize(w);
#ifndef FOGRT_NO_MEDIUM
        if (P->xs->footprint && s->x->footprints && s->x->footprints[i].on &&
            fabsf(fogrt__dot(fogrt__sub(v->p, s->x->footprints[i].p), s->x->footprints[i].n)) > s->x->footprints[i].near_plane)
            g->fp |= (uint8_t)(1u << g->n);
#endif
        g->lamp[g->n++] = i;
    }
}
/* The density of the mixed direction sampling of d' at wi: with c = glow_share (half the
   point and spot lights' share of the scene's light power, C: 1/2 when they are
   all the light), 1 - c the phase function or BSDF (pdf_b), c the glows of the vertex's
   lamps, each chosen with equal probability; a lamp with a footprint gives
   FOGRT__FOOTPRINT_SHARE of its part to it. */
FOGRT__PRIVATE float fogrt__glow_mix_known(const fogrt_scene *s, const fogrt__vertex *v, const fogrt__glow *g, fogrt__v3 wi, float pdf_b,
                                           int known, float pdf_known) {
    /* known >= 0: wi was drawn from that lamp's glow, whose density there is pdf_known */
    float sum = 0.0f;
    int k;
#ifndef FOGRT_NO_MEDIUM
    for (k = 0; k < g->n; ++k) {
        float pg = k == known ? pdf_known : fogrt__glow_hg_pdf(s->x->hg, g->dir[k], wi);
        if (g->fp & (1u << k))                      /* part of the lamp's share: its footprint */
            pg = (1.0f - FOGRT__FOOTPRINT_SHARE) * pg + FOGRT__FOOTPRINT_SHARE * fogrt__footprint_pdf(&s->x->footprints[g->lamp[k]], v->p, wi);
        sum += pg;
    }
#else
    (void)s; (void)v; (void)wi; (void)k; (void)known; (void)pdf_known;
#endif
    return (1.0f - s->x->glow_share) * pdf_b + s->x->glow_share * sum / (float)FOGRT__MAX(g->n, 1);
}
FOGRT__PRIVATE float fogrt__glow_mix(const fogrt_scene *s, const fogrt__vertex *v, const fogrt__glow *g, fogrt__v3 wi, float pdf_b) {
    return fogrt__glow_mix_known(s, v, g, wi, pdf_b, -1, 0.0f);
}
#endif
/* One light sample's share of the light reflected at v (eq. 13): f Le T V w / (n pdf),
   with w the MIS weight (1 for a delta light, or with MIS off). */
#ifdef FOGRT_TRACE
FOGRT__PRIVATE void fogrt__trace_light(const fogrt__path *P, const fogrt__vertex *v,
                                       uint32_t light, const fogrt_light_sample *ls, fogrt__v3 f, float pdf_b,
                                       float tr, float w, fogrt__v3 value);
#endif
FOGRT__HOT fogrt__v3 fogrt__light_contribution(const fogrt_scene *s, const fogrt__settings *st, const fogrt__path *P,
                                               const fogrt__vertex *v, const fogrt__glow *g, uint32_t light,
                                               const fogrt_light_sample *ls, float n, bool media) {
    /* n: the samples taken of this light, times the probability it was picked (by power);
       media (a constant): the path may be in G's media, which the paper's fog steps are not */
    fogrt__v3 f, c = fogrt__v(0.0f, 0.0f, 0.0f);
    float pdf_b, tr = 0.0f, w = 0.0f;
#ifndef FOGRT_NO_MEDIA
    if (media && P->media_light) f = fogrt__media_light(s, P, v, ls, &pdf_b, &tr);   /* G: another phase function, T per channel */
    else
#else
    (void)media;
#endif
    {
        f = fogrt__vertex_f(s, v, ls->wi, &pdf_b);
        if (!fogrt__is_black(f)) tr = fogrt__shadow(s, v, ls, P->w.rays);
    }
    if (tr != 0.0f) {
#ifdef FOGRT__LAMPS
        if (g && g->n > 0 && !ls->is_delta && st->desc.mis) pdf_b = fogrt__glow_mix(s, v, g, ls->wi, pdf_b);   /* how scattering picks wi */
#else
        (void)g;
#endif
        w = ls->is_delta || !st->desc.mis ? 1.0f : fogrt__power_heuristic((float)n * ls->pdf, pdf_b);
        c = fogrt__scale(fogrt__mul(f, ls->Le), tr * w / (ls->pdf * (float)n));
    }
    FOGRT__HOOK(fogrt__trace_light(P, v, light, ls, f, pdf_b, tr, w, c));
    (void)light;
    return c;
}
/* Next-event estimation at vertex v (CS184 style: every light is sampled, area lights with
   light_samples samples each; or, with light_by_power, one light picked by power and its
   samples divided by the probability of the pick). At a fog vertex the point and spot lights
   are left out when the equiangular estimator (a) gathers them along the ray
   instead: the two never count the same light twice (a pick of one of them adds nothing
   there). The point and spot lights' share is scaled by lamp_scale (the T of
   b'), and with lamps_only the other lights are left out. Returns the reflected radiance,
   before the path weight. */
FOGRT__PRIVATE fogrt__v3 fogrt__sample_light_n(const fogrt_scene *s, const fogrt__settings *st, const fogrt__path *P,
                                               uint32_t i, float pick) {
    fogrt__v3 L = fogrt__v(0.0f, 0.0f, 0.0f);
    int j, n = fogrt_light_sample_count(s, st, i);
    for (j = 0; j < n; ++j) {
        fogrt_light_sample ls;
        float u[3];
        fogrt__draw(s, i, P->w.rng, u);
        if (fogrt__sample_light(s, i, P->w.v.p, u, &ls))
            L = fogrt__add(L, fogrt__light_contribution(s, st, P, &P->w.v, &P->glow, i, &ls, (float)n * pick, true));
    }
    return L;
}
FOGRT__HOT fogrt__v3 fogrt__sample_lights(const fogrt_scene *s, const fogrt__settings *st, const fogrt__path *P,
                                               float lamp_scale, bool lamps_only) {
    fogrt__v3 L = fogrt__v(0.0f, 0.0f, 0.0f);
    bool gathered = P->w.v.is_medium && P->xs->equiangular && P->m->world;   /* by equiangular sampling (a) */
    uint32_t i = gathered ? s->light_count : 0, first = i, total = fogrt__light_total(s);
    if (lamps_only) total = s->light_count;
    if (P->xs->by_power) {                                  /* one light, chosen by power */
        float frac;
        i = (uint32_t)fogrt__cdf_find(s->x->light_pick, (int)fogrt__light_total(s), fogrt_rng_float(P->w.rng), &frac);
        if (i < first || i >= total) return L;
        return fogrt__scale(fogrt__sample_light_n(s, st, P, i, fogrt__pick_prob(s, P->xs->by_power, i)), i < s->light_count ? lamp_scale : 1.0f);
    }
    for (; i < total; ++i)
        L = fogrt__add(L, fogrt__scale(fogrt__sample_light_n(s, st, P, i, 1.0f), i < s->light_count ? lamp_scale : 1.0f));
    return L;
}
#ifndef FOGRT_NO_MEDIUM

/* A scattering vertex in the fog at p, wo the way back. Only what a fog vertex reads is set
   (no shading frame): zeroing the whole struct shows in a spot-lit render's time
   (docs/benchmarks.md, "Levers dropped"). */
FOGRT__PRIVATE void fogrt__fog_vertex(fogrt__vertex *v, fogrt__v3 p, fogrt__v3 wo) {
    v->p = p; v->wo = wo;
    v->is_medium = true; v->in_medium = true;
    v->ng = fogrt__v(0.0f, 0.0f, 0.0f); v->m = NULL;
}
/* Single scattering from point and spot lights along one fog segment [0, t_max] of the
   ray, by equiangular sampling with the phase function: per light, a distance t with pdf ~
   HG(mu(t)) / r^2 (fogrt__sample_equiangular_hg, B; plain equiangular when g = 0), then
   the light seen from the fog point x(t) as at any fog vertex (2.3), weighted by
   sigma_s T(t) / pdf(t). A spot light only lights its cone: only the part of the ray inside
   it is sampled. With light_by_power, one point or spot light per segment, by power. */
#ifdef FOGRT__LAMPS
/* The point and spot lights a segment gathers, [*first, *last): all of them, or with
   light_by_power one, picked among them by power. Returns the probability of the pick. */
FOGRT__HOT float fogrt__equiangular_lights(const fogrt_scene *s, const fogrt__settings *st, const fogrt__path *P,
                                           uint32_t *first, uint32_t *last) {
    float top, frac;
    (void)st;
    *first = 0; *last = s->light_count;
    if (!P->xs->by_power || s->light_count < 2 || !(s->x->light_pick[s->light_count - 1] > 0.0f)) return 1.0f;
    top = s->x->light_pick[s->light_count - 1];
    *first = (uint32_t)fogrt__cdf_find(s->x->light_pick, (int)s->light_count, fogrt_rng_float(P->w.rng) * top, &frac);
    *last = *first + 1;
    return fogrt__pick_prob(s, P->xs->by_power, *first) / top;
}
/* The weight of a point drawn at distance t into the fog with density pdf: sigma_t T(t) / pdf
   (times the albedo: sigma_s T / pdf), per channel in chromatic fog (G). */
FOGRT__HOT fogrt__v3 fogrt__equiangular_weight(const fogrt_scene *s, bool chroma, float t, float pdf) {
    float w;
#ifndef FOGRT_NO_MEDIA
    if (chroma) return fogrt__chroma_collision(&s->x->world, t, pdf);
#else
    (void)chroma;
#endif
    w = s->medium.sigma_t * fogrt_transmittance(s->medium.sigma_t, t) / pdf;
    return fogrt__v(w, w, w);
}
/* media and chroma (constants: the paper's fog, G's media and chromatic fog get a copy each):
   the path may be in G's media; sigma_t per channel in the weights (G). */
FOGRT__HOT fogrt__v3 fogrt__equiangular(const fogrt_scene *s, const fogrt__settings *st, const fogrt__path *P,
                                        float t_min, float t_max, bool media, bool chroma) {
    fogrt__v3 L = fogrt__v(0.0f, 0.0f, 0.0f);
    float pick;
    uint32_t i, last;
    fogrt__vertex v;
    fogrt__fog_vertex(&v, P->w.o, fogrt__neg(P->w.d));
    pick = fogrt__equiangular_lights(s, st, P, &i, &last);
    for (; i < last; ++i) {
        const fogrt_light_desc *l = &s->lights[i];
        int j, n = fogrt_light_sample_count(s, st, i);
        for (j = 0; j < n; ++j) {
            fogrt__v3 oc = fogrt__sub(l->position, P->w.o);
            fogrt_light_sample ls;
            float u[3], t, pdf_t, t_lo = t_min, t_hi = t_max, h;
            u[0] = fogrt_rng_float(P->w.rng); u[1] = fogrt_rng_float(P->w.rng); u[2] = fogrt_rng_float(P->w.rng);
            if (l->type == FOGRT_LIGHT_SPOT && !fogrt__clip_to_cone(l, s->spot_cos[2 * i], P->w.o, P->w.d, &t_lo, &t_hi)) continue;
            h = FOGRT__MAX(fogrt__length(fogrt__cross(oc, P->w.d)), sqrtf(s->r2_min));  /* ray through the light */
            t = fogrt__sample_equiangular_hg(s->x->hg, fogrt__dot(oc, P->w.d), h, t_lo, t_hi, u[0], &pdf_t);
            if (!(pdf_t > 0.0f)) continue;
            v.p = fogrt__madd(P->w.o, P->w.d, t);
            FOGRT__HOOK(fogrt__trace_equiangular(P, i, u[0], t, pdf_t, fogrt__equiangular_weight(s, chroma, t - t_min, pdf_t)));
            if (!fogrt__sample_point_light(s, l, v.p, u + 1, &ls)) continue;
            L = fogrt__add(L, fogrt__mul(fogrt__mul(fogrt__light_contribution(s, st, P, &v, NULL, i, &ls, (float)n * pick, media), s->medium.albedo),
                                         fogrt__equiangular_weight(s, chroma, t - t_min, pdf_t)));
        }
    }
    return L;
}
#endif

/* a. Free flight through the fog (eq. 4-6): does the ray collide before t_surface? The
   distance is sampled from where the ray is in the fog (t = a, 0 unless the fog is bounded
   and the ray starts outside its box) to where it leaves it (b). On a collision the vertex
   is set and the weight takes the albedo. may_scatter: the path may still bounce (else the
   equiangular lights, which are light after one more bounce, are not gathered). media (a
   constant): the path may be in G's media. */
FOGRT__HOT bool fogrt__free_flight(const fogrt_scene *s, const fogrt__settings *st, fogrt__path *P,
                                   float t_surface, bool may_scatter, float *tr, bool media) {
    const fogrt__med *m = P->m;
    float u, t, a, b;
    if (!P->w.in_fog) return false;
    u = fogrt_rng_float(P->w.rng);
    if (!fogrt__med_span(s, m, P->w.o, P->w.d, t_surface, &a, &b)) return false;   /* misses the fog's box */
    *tr = b < INFINITY ? fogrt_transmittance(m->d.sigma_t, b - a) : 0.0f;
    t = a + fogrt_sample_exponential(m->d.sigma_t, u);
    FOGRT__HOOK(fogrt__trace_free_flight(P, u, t, b, t < b));
#ifdef FOGRT__LAMPS
    if (st->desc.nee && P->xs->equiangular && s->light_count > 0 && may_scatter && m->world)
        fogrt__gather(P, st, P->w.depth + 1, fogrt__mul(P->w.beta, fogrt__equiangular(s, st, P, a, b, media, false)), "equiangular");
#else
    (void)st; (void)may_scatter; (void)media;
#endif
    if (!(t < b)) return false;                          /* leaves the fog or reaches the surface: T / T = 1 */
    P->w.beta = fogrt__mul(P->w.beta, m->d.albedo);     /* sigma_s T / (sigma_t T) */
    fogrt__fog_vertex(&P->w.v, fogrt__madd(P->w.o, P->w.d, t), fogrt__neg(P->w.d));
    P->glow.n = 0;
    return true;
}
#endif

/* The emission the ray reaches (the Le of eq. 3), weighted by MIS when next-event estimation
   could have found it too, and by tr, the fog's transmittance up to it. With
   expected_emission (the default; not in the paper) it is added whether or not the free
   flight collides first: the surface is reached with probability tr, so the paper's way,
   Le with weight 1 there and nothing on a collision, has the same mean, but a lamp seen
   through fog then flickers between Le and 0 (at tr = 0.2 its pixels' variance is 4 Le^2
   per sample); tr Le is that mean without the noise (the cross-check's fog boxes: 2.7 to 6
   times less variance at equal samples). It can cost where the fog itself carries as much
   light as the lamp: in a white furnace (albedo 1 in a glowing enclosure) the paper's way
   gives every path exactly 1, this one only on average. expected_emission off, the caller
   passes tr = 1 when the ray reached the surface and 0 when it collided. */
FOGRT__HOT void fogrt__surface_emission(const fogrt_scene *s, const fogrt__settings *st, fogrt__path *P,
                                        const fogrt_material_desc *m, const fogrt_hit *hit, fogrt__v3 p,
                                        fogrt__v3 ng, fogrt__v3 beta, float tr) {
    float w = 1.0f;
    if (fogrt__is_black(m->emission) || !(tr > 0.0f) || !(fogrt__dot(P->w.d, ng) < 0.0f)) return;   /* the front side emits */
    if (!P->w.prev_delta && st->desc.nee)
        w = st->desc.mis ? fogrt__power_heuristic(P->w.prev_pdf, (float)st->desc.light_samples *
                                             fogrt__pick_prob(s, P->xs->by_power, s->light_count + s->prim_light[hit->prim]) *
                                             fogrt__area_light_pdf(s, hit->prim, P->w.prev_p, p, ng)) : 0.0f;
    fogrt__gather(P, st, P->w.depth, fogrt__scale(fogrt__mul(beta, m->emission), w * tr), "emission");
}
/* b. The surface the ray reached, at p with normals ng, ns (fogrt__surface_frame; its
   emission was added by fogrt__next_event): its shading frame. Returns false when the path
   ends here (the depth limit, or a black diffuse surface). */
FOGRT__HOT bool fogrt__surface_vertex(fogrt__path *P, const fogrt_material_desc *m, int limit, fogrt__v3 p,
                                          fogrt__v3 ng, fogrt__v3 ns);
FOGRT__HOT bool fogrt__surface_event(const fogrt__settings *st, fogrt__path *P, const fogrt_material_desc *m,
                                     uint32_t prim, int limit, fogrt__v3 p, fogrt__v3 ng, fogrt__v3 ns) {
    bool goes_on = fogrt__surface_vertex(P, m, limit, p, ng, ns);   /* sets v.p and the type first */
    FOGRT__HOOK(fogrt__trace_surface(P, prim));
    (void)st; (void)prim;                                /* read by the trace hook only */
    return goes_on;
}
/* The vertex itself: its BSDF, sides and frame (also set up on the side by b' below). */
FOGRT__HOT bool fogrt__surface_vertex(fogrt__path *P, const fogrt_material_desc *m, int limit, fogrt__v3 p,
                                          fogrt__v3 ng, fogrt__v3 ns) {
    P->w.v.p = p;
    P->type = fogrt__bsdf_type(m);
    if (P->w.depth >= limit || (P->type == FOGRT_BSDF_DIFFUSE && fogrt__is_black(m->reflectance))) return false;
    P->entering = fogrt__surface_vertex_set(&P->w.v, m, fogrt__neg(P->w.d), p, ng, ns, P->w.in_fog);
    P->glow.n = 0;
    return true;
}

FOGRT__HOT fogrt__v3 fogrt__sample_lights(const fogrt_scene *s, const fogrt__settings *st, const fogrt__path *P,
                                               float lamp_scale, bool lamps_only);
/* b'. The light of point and spot lights at the surface behind a fog collision (with
   expected_emission; not in the paper). The light that next-event estimation finds at a
   surface flickers the way a lamp seen through fog does: the ray gets to the surface with
   probability T, so the paper's estimate is that light or nothing. In the spot-lit fog
   (the paper's scene) the floor and the bunny in the beam, seen through fog, flickered so.
   So the light of point and spot lights sampled at the surface counts T times, always:
   here, behind a collision (the surface's vertex is set up on the side, then the fog vertex
   put back), and at the surface itself in step c when the ray gets there (fogrt__full_light_step
   scales their share by T). Its mean is the paper's; the path still goes on from one of
   the two, as in the paper. Area lights and the sky keep the paper's way: their own light
   sample is noisy enough that the extra shadow ray does not pay (docs/benchmarks.md,
   "Levers dropped"). Where T is below 1/16 the sample
   behind the collision is taken with probability 16 T and counts 1/16: dense fog does not
   cost a shadow ray per bounce for surfaces it hides. */
#define FOGRT__BEHIND_MIN 0.0625f

#ifdef FOGRT__LAMPS
/* Whether to take that sample behind this collision (the roulette draw, when T is small). */
FOGRT__PRIVATE bool fogrt__light_behind_wanted(const fogrt_scene *s, const fogrt__settings *st, fogrt__path *P) {
    float tr = P->seg_tr;
    if (!P->xs->expected_emission || !st->desc.nee || s->light_count == 0 || !(tr > 0.0f)) return false;
    return tr >= FOGRT__BEHIND_MIN || fogrt_rng_float(P->w.rng) * FOGRT__BEHIND_MIN < tr;
}
/* The sample itself, at the surface point p with normals ng, ns (fogrt__surface_frame). */
FOGRT__HOT void fogrt__light_behind(const fogrt_scene *s, const fogrt__settings *st, fogrt__path *P,
                                    const fogrt_material_desc *m, fogrt__v3 p, fogrt__v3 ng, fogrt__v3 ns,
                                    fogrt__v3 beta, int limit) {
    fogrt__vertex keep = P->w.v;
    fogrt__glow keep_glow = P->glow;
    fogrt_bsdf_type type = P->type;
    bool entering = P->entering;
    if (fogrt__surface_vertex(P, m, limit, p, ng, ns) && fogrt__is_scattering(P)) {
        fogrt__glow_setup(s, P, &P->w.v, &P->glow, P->type == FOGRT_BSDF_DIFFUSE);
        fogrt__gather(P, st, P->w.depth + 1, fogrt__mul(beta, fogrt__sample_lights(s, st, P, FOGRT__MAX(P->seg_tr, FOGRT__BEHIND_MIN), true)),
                      "light behind");
    }
    P->w.v = keep; P->glow = keep_glow; P->type = type; P->entering = entering;
}
#endif

/* A ray that leaves the scene: the environment's light, also as tr Le. */
FOGRT__PRIVATE void fogrt__escape(const fogrt_scene *s, const fogrt__settings *st, fogrt__path *P, fogrt__v3 beta,
                                  float tr) {
    if (s->has_env && tr > 0.0f) {
        float w = 1.0f;                                 /* a map is also sampled by NEE: MIS */
#ifndef FOGRT_NO_ESTIMATION
        if (s->env_map && !P->w.prev_delta && st->desc.nee)
            w = st->desc.mis ? fogrt__power_heuristic(P->w.prev_pdf, (float)st->desc.light_samples * fogrt__env_pdf(s, P->w.d) *
                                                 fogrt__pick_prob(s, P->xs->by_power, fogrt__light_total(s) - 1)) : 0.0f;
#endif
#ifndef FOGRT_NO_ESTIMATION
        fogrt__gather(P, st, P->w.depth, fogrt__scale(fogrt__mul(beta, fogrt__env_map_radiance(s, P->w.d)), w * tr), "environment");
#else
        fogrt__gather(P, st, P->w.depth, fogrt__scale(fogrt__mul(beta, fogrt__env_radiance(s, P->w.d)), w * tr), "environment");
#endif
    }
}
#ifndef FOGRT_NO_MEDIUM
/* A ray that collided in the fog before its end (hit, or NULL: it escapes): what the end
   still adds, tr Le (b), and the lights behind the surface (b'). The path goes on at
   the collision. */
FOGRT__HOT bool fogrt__collided(const fogrt_scene *s, const fogrt__settings *st, fogrt__path *P,
                                const fogrt_hit *hit, fogrt__v3 beta, float tr, int limit) {
    if (hit) {
        const fogrt_material_desc *m = &s->materials[fogrt_scene_get_prim_material(s, hit->prim)];
        fogrt__v3 p, ng, ns;
#ifdef FOGRT__LAMPS
        bool behind = fogrt__light_behind_wanted(s, st, P);
#else
        bool behind = false;
#endif
        if (!behind && (fogrt__is_black(m->emission) || !(tr > 0.0f))) return true;   /* nothing to add there */
        fogrt__surface_frame(s, P->w.o, P->w.d, hit, &p, &ng, &ns);
#ifdef FOGRT__LAMPS
        if (behind) fogrt__light_behind(s, st, P, m, p, ng, ns, beta, limit);               /* b' */
#else
        (void)limit;
#endif
        fogrt__surface_emission(s, st, P, m, hit, p, ng, beta, tr);
    } else {
        fogrt__escape(s, st, P, beta, tr);
    }
    return true;
}
#endif
/* Where a ray that did not collide ends: an emitting surface's tr Le (b), then the
   surface event; or the environment. Inlined twice in fogrt__next_event: in the fog (tr
   the transmittance) and in clear air (tr = 1, so that code is a fog-free build's). */
FOGRT__HOT bool fogrt__ray_end(const fogrt_scene *s, const fogrt__settings *st, fogrt__path *P, bool found,
                               const fogrt_hit *hit, fogrt__v3 beta, float tr, int limit) {
    if (found) {
        const fogrt_material_desc *m = &s->materials[fogrt_scene_get_prim_material(s, hit->prim)];
        fogrt__v3 p, ng, ns;
        fogrt__surface_frame(s, P->w.o, P->w.d, hit, &p, &ng, &ns);    /* once, for both */
        fogrt__surface_emission(s, st, P, m, hit, p, ng, beta, tr);
#ifndef FOGRT_NO_SHAPES
        if (s->x->h && fogrt__h_boundary(s, P, hit->prim, m, p, ng)) return true;   /* H: an interface, passed */
#endif
        return fogrt__surface_event(st, P, m, hit->prim, limit, p, ng, ns);
    }
    fogrt__escape(s, st, P, beta, tr);
    FOGRT__HOOK(fogrt__trace_simple(P, FOGRT_TRACE_ESCAPE));
    return false;
}
#ifndef FOGRT_NO_MEDIUM
/* a + b in the fog: the free flight, then what the end of the ray adds. media (a constant:
   each caller gets its own copy): the path is in G's media (another phase function, or
   emitting fog, whose light this adds along the way). */
FOGRT__HOT bool fogrt__fog_event(const fogrt_scene *s, const fogrt__settings *st, fogrt__path *P, bool found,
                                 const fogrt_hit *hit, int limit, bool media) {
    const fogrt__v3 beta = P->w.beta;                     /* before a collision's albedo */
    float tr = 1.0f;                                    /* the fog's transmittance to the end of the ray */
    bool collided = fogrt__free_flight(s, st, P, found ? hit->t : INFINITY, P->w.depth < limit, &tr, media);
    P->seg_tr = tr;
#ifndef FOGRT_NO_MEDIA
    if (media && P->m->emits) fogrt__media_emission(s, st, P, beta, found ? hit->t : INFINITY, collided);   /* G */
#endif
    if (!P->xs->expected_emission) tr = collided ? 0.0f : 1.0f;   /* the paper's: Le when reached */
    if (collided) return fogrt__collided(s, st, P, found ? hit : NULL, beta, tr, limit);
    return fogrt__ray_end(s, st, P, found, hit, beta, tr, limit);
}
#endif
/* a + b: follow the ray to its next event, a fog collision or a surface. False when the
   path ends: the ray escaped (the environment is added), or the surface ends it. */
FOGRT__PRIVATE bool fogrt__next_event(const fogrt_scene *s, const fogrt__settings *st, fogrt__path *P, int limit) {
    fogrt_hit hit;
    bool found;
    ++*P->w.rays;
    found = fogrt__traverse(s, P->w.o, P->w.d, 0.0f, INFINITY, &hit, false);
    P->seg_tr = 1.0f;
#ifndef FOGRT_NO_MEDIUM
    if (P->w.in_fog) return fogrt__fog_event(s, st, P, found, &hit, limit, false);   /* (a fog-free ray skips it) */
#endif
    return fogrt__ray_end(s, st, P, found, &hit, P->w.beta, 1.0f, limit);
}
/* The path's a + b: G's (fogrt__media_next_event) in G's media, H's through media inside
   shapes, chosen once per path, so that the paper's medium pays no test per segment. */
FOGRT__PRIVATE fogrt__step fogrt__next_event_of(const fogrt_scene *s) {
#ifndef FOGRT_NO_SHAPES
    if (s->x->h) return fogrt__h_next_event;
#endif
#ifndef FOGRT_NO_MEDIA
    if (s->x->media) return fogrt__media_next_event;
#else
    (void)s;
#endif
    return fogrt__next_event;
}

/* c. Light sampling at the scattering vertex (next-event estimation, 2.3); a mirror
   or glass vertex cannot be reached by a light sample and is skipped. */
FOGRT__HOT void fogrt__full_light_step(const fogrt_scene *s, const fogrt__settings *st, fogrt__path *P) {
#ifdef FOGRT__LAMPS
    if (P->xs->glow) fogrt__glow_setup(s, P, &P->w.v, &P->glow, fogrt__is_scattering(P) && (P->w.v.is_medium || P->type == FOGRT_BSDF_DIFFUSE));
#endif
    if (st->desc.nee && fogrt__is_scattering(P))             /* lamps at a surface seen through fog: T times (b') */
        fogrt__gather(P, st, P->w.depth + 1, fogrt__mul(P->w.beta, fogrt__sample_lights(s, st, P,
                      P->w.v.is_medium || !P->xs->expected_emission ? 1.0f : P->seg_tr, false)), "light sample");
}

/* d. The new direction from a surface: sample the BSDF in the shading frame. */
FOGRT__HOT bool fogrt__scatter_surface(const fogrt_scene *s, const fogrt__settings *st, fogrt__path *P) {
    fogrt_bsdf_sample bs;
    float u[3], cos_o;
    u[0] = fogrt_rng_float(P->w.rng); u[1] = fogrt_rng_float(P->w.rng); u[2] = fogrt_rng_float(P->w.rng);
    if (!fogrt__sample_surface(st, &P->w.v, u, &bs, &P->w.d, &cos_o)) return false;
    P->w.beta = fogrt__mul(P->w.beta, bs.weight);
    P->w.prev_pdf = bs.pdf; P->w.prev_delta = bs.is_delta;
    /* Refraction moves the ray into or out of the object: fog exists only outside (or, with
       H, the medium on the other side of the surface). */
#ifndef FOGRT_NO_SHAPES
    if (bs.is_transmission && s->x->h) fogrt__h_enter(s, P, fogrt__h_cross(s, P->prim, P->med));
    else
#endif
    if (bs.is_transmission) P->w.in_fog = !P->entering && (s->features & FOGRT_FEATURE_MEDIUM) != 0;
    P->w.o = fogrt__offset(s, P->w.v.p, P->w.v.ng, P->w.d);
    FOGRT__HOOK(fogrt__trace_bsdf(st, P, u, &bs, cos_o));
    return true;
}
#ifdef FOGRT__LAMPS
#ifdef FOGRT_TRACE
FOGRT__PRIVATE void fogrt__trace_glow(const fogrt__path *P, const float *u, bool glow,
                                      bool footprint, uint32_t light, float pdf_b, float pdf, fogrt__v3 weight);
#endif
/* d'. Aiming at the glow of a lamp (not in the paper). Next to a point or spot light the fog
   glows: a direction that passes at distance h from the lamp gathers about 1/h of its light
   along the way (equiangular sampling, step a, finds it exactly). Phase or BSDF sampling
   finds those directions by chance, and then with a huge weight: in a spot-lit fog, the
   pixels whose paths pass next to the lamp come out 1000 times the median. So at a vertex
   that has lamps to aim at (fogrt__glow_setup, above) the direction is drawn from a
   mixture: with probability 1 - c the phase function or BSDF as usual, else the glow of one
   of the lamps (B), whose density G(alpha) / sin(alpha) follows the 1/h (G holds the
   fog's phase function, B; in isotropic fog G is pi - alpha). c is half the lamps'
   share of the scene's light power (1/2 when they are all the light): where an area lamp
   gives most of the light, aiming half the paths at a weak spot would cost more than it
   gains (docs/benchmarks.md, "Lamps in fog"). The
   weight is f / pdf with the mixture's pdf (fogrt__glow_mix): at most 1 / (1 - c) where the
   phase function rules, and finite where the glow does. Light sampling at the same vertex uses
   the mixture's pdf in its MIS weight, so the two still add up to one.
   A spot light also lights a patch of floor, which then lights the rest of the room: in the
   paper's spot-lit box half the image's noise comes from the few paths that happen to reach
   that patch and take the spot's light sample there. So FOGRT__FOOTPRINT_SHARE (a fifth) of
   the samples aimed at a spot's glow aim at its footprint instead (B: the plane its
   cone lights most, found at build; half of them through the lamp's cone, half
   at a sphere around the lit patch as the vertex sees it); where that sampler fails (its
   cone direction misses the plane) the path ends, which its density, part of the
   mixture's, has accounted for. Its gain: docs/benchmarks.md, tables "Lamps in fog" and
   "Footprint". */
FOGRT__PRIVATE bool fogrt__scatter_glow(const fogrt_scene *s, const fogrt__settings *st, fogrt__path *P) {
    fogrt__v3 f, wi, wo_l;
    fogrt_bsdf_sample bs;
    uint32_t light = 0;
    float u[3], pdf_b, pdf, pdf_k = 0.0f;
    int k = -1;
    bool glow, footprint = false;
    u[0] = fogrt_rng_float(P->w.rng); u[1] = fogrt_rng_float(P->w.rng); u[2] = fogrt_rng_float(P->w.rng);
    glow = u[0] < s->x->glow_share;
    if (glow) {
        float uk = u[0] / s->x->glow_share * (float)P->glow.n;   /* the lamp k, then in [k, k + 1): what of it */
        k = FOGRT__MIN((int)uk, P->glow.n - 1);
        light = P->glow.lamp[k];
        if ((P->glow.fp & (1u << k)) && uk - (float)k < FOGRT__FOOTPRINT_SHARE) {   /* its footprint */
            footprint = true;
            if (!fogrt__sample_footprint(&s->x->footprints[light], P->w.v.p, u[1], u[2], &wi)) return false;
            pdf_k = fogrt__glow_hg_pdf(s->x->hg, P->glow.dir[k], wi);
        } else {
            wi = fogrt__sample_glow_hg(s->x->hg, P->glow.dir[k], u[1], u[2], &pdf_k);
        }
    } else if (P->w.v.is_medium) {                        /* the phase function at the angle drawn */
        wi = fogrt__fog_phase_sample(P->m, P->w.v.wo, u[1], u[2], &pdf_b);
    } else {
        wo_l = fogrt__to_local(&P->w.v.frame, P->w.v.wo);
        if (!fogrt_sample_bsdf(P->w.v.m, st->desc.fresnel, wo_l, 0.5f, u[1], u[2], &bs)) return false;
        wi = fogrt__normalize(fogrt__to_world(&P->w.v.frame, bs.wi));
    }
    if (!glow && P->w.v.is_medium) f = fogrt__v(pdf_b, pdf_b, pdf_b);
    else f = fogrt__fog_vertex_f(s, P->m, &P->w.v, wi, &pdf_b);   /* phase, or f |cos| (0 through the surface) */
    if (fogrt__is_black(f)) return false;
    pdf = fogrt__glow_mix_known(s, &P->w.v, &P->glow, wi, pdf_b, k, pdf_k);
    if (!(pdf > 0.0f)) return false;
    P->w.d = wi;
    P->w.beta = fogrt__mul(P->w.beta, fogrt__scale(f, 1.0f / pdf));
    P->w.prev_pdf = pdf; P->w.prev_delta = false;
    P->rr_scale = pdf / pdf_b;                           /* > 0: f > 0 needs pdf_b > 0 */
    P->w.o = P->w.v.is_medium ? P->w.v.p : fogrt__offset(s, P->w.v.p, P->w.v.ng, wi);
    FOGRT__HOOK(fogrt__trace_glow(P, u, glow, footprint, light, pdf_b, pdf, fogrt__scale(f, 1.0f / pdf)));
    (void)light; (void)footprint;                        /* read by the trace hook only */
    return true;
}
#endif

/* d. The new direction: Henyey-Greenstein in the fog (eq. 11-12, weight p / pdf = 1), the
   BSDF on a surface; near a lamp, the mixture of d'. */
FOGRT__HOT bool fogrt__full_scatter(const fogrt_scene *s, const fogrt__settings *st, fogrt__path *P) {
    P->w.prev_p = P->w.v.p;
    P->rr_scale = 1.0f;                                  /* (d' sets it for the roulette after it) */

#ifndef FOGRT_NO_MEDIUM
    if (!P->w.v.in_medium) return fogrt__scatter_surface(s, st, P);   /* (a vertex outside the fog: only d) */
#ifdef FOGRT__LAMPS
    if (P->glow.n > 0) return fogrt__scatter_glow(s, st, P);
#endif
    if (P->w.v.is_medium) {
        float u1 = fogrt_rng_float(P->w.rng), u2 = fogrt_rng_float(P->w.rng);
        P->w.d = fogrt__fog_phase_sample(P->m, P->w.v.wo, u1, u2, &P->w.prev_pdf);
        P->w.prev_delta = false;
        P->w.o = P->w.v.p;
        FOGRT__HOOK(fogrt__trace_phase(P, &P->m->d, u1, u2));
        return true;
    }
#endif
    return fogrt__scatter_surface(s, st, P);
}

/* e. Russian roulette after rr_depth bounces: continue with probability q, weight 1/q;
   q = min(0.95, k x throughput), k in [1, 4] chosen for the scene by its pilot (chapter
   15): the k that makes variance x time least. */
FOGRT__HOT float fogrt__full_roulette_q(const fogrt__settings *st, fogrt__path *P, float u) {
    if (P->xs->rr_probe && !P->probed) {                 /* the pilot: the path's first roulette */
        P->probed = true;
        P->probe_lum = fogrt__luminance(P->w.L);
        P->probe_rays = *P->w.rays;
        P->probe_b = fogrt__max3(P->w.beta) * P->rr_scale;
    }
    float q = FOGRT__MIN(0.95f, P->xs->rr_k * fogrt__max3(P->w.beta) * P->rr_scale);
    FOGRT__HOOK(fogrt__trace_roulette(P, q, u, u < q));
    (void)st; (void)u;                                   /* read by the trace hook only */
    return q;
}

/* Point or spot lights in fog: what the glow of d' needs (without them the glow's checks
   are skipped at every vertex). */
FOGRT__PRIVATE bool fogrt__lamps_in_fog(const fogrt_scene *s) {
    return (s->features & FOGRT_FEATURE_MEDIUM) && s->light_count > 0;
}
#ifndef FOGRT_NO_ESTIMATION
/* The roulette's pilot (not in the paper). Russian roulette that keeps a path with
   probability q = throughput spends the same effort on every path of equal throughput,
   whatever the rest of the path is worth. fogrt keeps that shape and scales it by one
   number for the scene, q = min(0.95, k x throughput), with k chosen for the most
   efficiency (1 / (variance x time)), the trade that Arvo and Kirk's analysis of roulette
   makes. A pilot of camera paths, rendered with the k being tried, measures per sample:
     G  the luminance a path gathered after its first roulette (0 if it never got there),
        b its throughput x rr_scale there (so it survived with q = min(0.95, k b)), c the
        rays it traced after it, and all its rays;
     V  the spread of the samples about their pixel's mean: the noise. Every sample of a
        pilot pixel starts at the pixel's centre, so V holds no detail of the image.
   Had the roulette used k' instead, a path that survived would weigh q / q' as much and
   survive q' / q as often, so its part of the second moment would be G^2 q / q' and its
   cost c q' / q. Summed over the samples (M = sum G^2 q / q', C = sum c q' / q, M0 and C0
   the same at k' = k, T all the rays), variance x time with k' is about
     (V - M0 + M) (T - C0 + C),
   and the pilot takes the k' in 1, 1.1, ..., 4 that makes it least. The model sees only
   the first roulette (the later ones change with k' too), so when it finds k' > 1 the
   pilot runs again with that k and chooses once more. It finds k well above 1 where the
   deep vertices matter (the paper's spot-lit fog, whose deep vertices see the lit cone; a
   box with glass, whose caustics are found late), and about 1 in fog where paths after
   the roulette add little noise for their cost. The k' tried start at 1: below it a
   closed form of this model was too crude, so those scenes keep q = throughput. And k, like
   q, is fixed before a path is drawn, so the estimate stays unbiased. The pilot is 64 x 48
   pixels x 16 paths with the default settings, run by fogrt_scene_build in every scene
   with a light, with a fixed seed, its rows in parallel, each summed alone and then all in
   row order: the same k on every run, thread count and split of the samples. Cost: 12288
   paths a pass. Its gain: docs/benchmarks.md, table "Roulette pilot". */
#define FOGRT__PILOT_W 64
#define FOGRT__PILOT_MAX_SAH 1000.0f          /* no pilot in trees whose rays cost more */
#define FOGRT__PILOT_H 48
#define FOGRT__PILOT_SPP 16
#define FOGRT__PILOT_K 31                       /* the k' tried: 1, 1.1, ..., 4 */
#define FOGRT__PILOT_KJ(j) (1.0 + 0.1 * (double)(j))
typedef struct fogrt__pilot_sums { double M[FOGRT__PILOT_K], C[FOGRT__PILOT_K], M0, C0, V, T; } fogrt__pilot_sums;
/* One row of the pilot: its sums (above), rendered with the roulette's k = P->xs->rr_k. */
FOGRT__PRIVATE fogrt__pilot_sums fogrt__pilot_row(const fogrt_scene *s, const fogrt__settings *st,
                                                  const fogrt__xs *xs, const fogrt__camera *cam, int y) {
    fogrt__pilot_sums r;
    int x, i, j;
    memset(&r, 0, sizeof r);
    for (x = 0; x < FOGRT__PILOT_W; ++x) {
        double sum = 0.0, sum2 = 0.0, n = 0.0;          /* this pixel's samples */
        for (i = 0; i < FOGRT__PILOT_SPP; ++i) {
            uint64_t key = ((uint64_t)(y * FOGRT__PILOT_W + x) << 8) | (uint64_t)i, rays = 0;
            fogrt_rng rng;
            fogrt__v3 o, d, L;
            fogrt__walk w;
            fogrt__path P;
            double l, q, g2;
            fogrt_rng_seed(&rng, fogrt__hash64(key ^ 0x50494C4F54ULL), 0);
            fogrt__camera_generate(cam, FOGRT__PILOT_W, FOGRT__PILOT_H, (float)x + 0.5f, (float)y + 0.5f, 0.5f, 0.5f,
                                   &o, &d);
            fogrt__walk_start(&w, s, o, d, &rng, &rays);
            fogrt__path_start(s, &P, xs, &w);
            L = fogrt__algorithm1(s, st, &P.w, false);
            /* after the first roulette: the luminance gathered, the rays traced, the throughput */
            float after = P.probed ? fogrt__luminance(L) - P.probe_lum : 0.0f;
            uint64_t rays_after = P.probed ? rays - P.probe_rays : 0;
            float b = P.probed ? P.probe_b : 0.0f;
            l = (double)fogrt__luminance(L);
            if (!fogrt__v3_finite(L) || !(fabs(l) < 1e30) || !(fabsf(after) < 1e30f)) continue;
            sum += l; sum2 += l * l; n += 1.0;
            r.T += (double)rays;
            if (!(b > 0.0f)) continue;                   /* no roulette met */
            q = FOGRT__MIN(0.95, (double)xs->rr_k * (double)b);
            g2 = (double)after * (double)after;
            r.M0 += g2; r.C0 += (double)rays_after;
            for (j = 0; j < FOGRT__PILOT_K; ++j) {
                double q2 = FOGRT__MIN(0.95, FOGRT__PILOT_KJ(j) * (double)b);
                r.M[j] += g2 * q / q2; r.C[j] += (double)rays_after * q2 / q;
            }
        }
        if (n > 1.0) r.V += FOGRT__MAX(sum2 - sum * sum / n, 0.0) * n / (n - 1.0);
    }
    return r;
}
/* One pass of the pilot with k = P->xs->rr_k: its rows in parallel, each summed alone and
   then all in row order (so the same k on any thread count); returns the k' chosen. */
FOGRT__PRIVATE float fogrt__pilot_pass(const fogrt_scene *s, const fogrt__settings *st, const fogrt__xs *xs,
                                      const fogrt__camera *cam) {
    fogrt__pilot_sums row[FOGRT__PILOT_H], a;
    double best = 0.0;
    int y, j, jbest = 0;
    int nthreads = fogrt__threads(0);
    (void)nthreads;                                      /* read by OpenMP only */
    FOGRT__OMP(omp parallel for schedule(dynamic, 1) num_threads(nthreads))
    for (y = 0; y < FOGRT__PILOT_H; ++y) row[y] = fogrt__pilot_row(s, st, xs, cam, y);
    memset(&a, 0, sizeof a);
    for (y = 0; y < FOGRT__PILOT_H; ++y) {
        a.M0 += row[y].M0; a.C0 += row[y].C0; a.V += row[y].V; a.T += row[y].T;
        for (j = 0; j < FOGRT__PILOT_K; ++j) { a.M[j] += row[y].M[j]; a.C[j] += row[y].C[j]; }
    }
    for (j = 0; j < FOGRT__PILOT_K; ++j) {
        double f = (a.V - a.M0 + a.M[j]) * (a.T - a.C0 + a.C[j]);
        if (j == 0 || f < best) { best = f; jbest = j; }
    }
    return (float)FOGRT__PILOT_KJ(jbest);
}
FOGRT__PRIVATE void fogrt__full_settings(const fogrt_scene *s, const fogrt__settings *st, fogrt__xs *xs);
FOGRT__PRIVATE float fogrt__roulette_pilot(const fogrt_scene *s) {
    fogrt__settings st;
    fogrt__xs xs;
    fogrt__camera cam;
    float k;
    if (fogrt__light_total(s) == 0 || fogrt__resolve_render(s, NULL, &st, NULL) != FOGRT_RESULT_OK ||
        st.desc.rr_depth >= st.max_depth) return 1.0f;
    fogrt__full_settings(s, &st, &xs);
    xs.rr_k = 1.0f; xs.rr_probe = true;
    cam = fogrt__camera_setup(s, FOGRT__PILOT_W, FOGRT__PILOT_H);
    k = fogrt__pilot_pass(s, &st, &xs, &cam);
    if (k > 1.0f) {                                      /* again, around the k found */
        xs.rr_k = k;
        k = fogrt__pilot_pass(s, &st, &xs, &cam);
    }
    return k;
}
#endif /* FOGRT_NO_ESTIMATION */
/* The full integrator's settings for a render desc (Part I's settings hold the desc). */
FOGRT__PRIVATE void fogrt__full_settings(const fogrt_scene *s, const fogrt__settings *st, fogrt__xs *xs) {
    const fogrt_render_desc *d = &st->desc;
    xs->equiangular = d->equiangular;
    xs->glow = d->glow && d->nee && d->equiangular && fogrt__lamps_in_fog(s);
    xs->footprint = xs->glow && d->footprint;
    xs->expected_emission = d->expected_emission;
#ifndef FOGRT_NO_MEDIA
    xs->hero_pdf = false;
#endif
    xs->by_power = d->light_by_power && s->x->light_pick && fogrt__light_total(s) > 1;
    xs->rr_k = FOGRT__MAX(s->x->rr_k, 1.0f);      /* 1 before the pilot has run */
    xs->rr_probe = false;
#ifdef FOGRT_TRACE
    xs->trace = NULL; xs->trace_user = NULL;
#endif
}
/* The samplers the full integrator runs (fogrt_render_samplers), in the loop's order. */
FOGRT__PRIVATE void fogrt__full_samplers(const fogrt_scene *s, const fogrt__settings *st, char *buf, size_t size) {
    const fogrt_render_desc *d = &st->desc;
    fogrt__xs xs;
    bool world = (s->features & FOGRT_FEATURE_MEDIUM) != 0, shapes = false, lamps = world && s->light_count > 0;
    fogrt__full_settings(s, st, &xs);
#ifndef FOGRT_NO_SHAPES
    shapes = s->x->h != NULL;
#endif
    fogrt__say(buf, size, world || shapes, "free flight");
    fogrt__say(buf, size, s->x->fog_bounded, "fog in a box");
    fogrt__say(buf, size, shapes, "media in shapes");
#ifndef FOGRT_NO_MEDIA
    fogrt__say(buf, size, s->x->world.chroma, "hero channel");
    fogrt__say(buf, size, s->x->world.emits, "emitting fog");
#endif
    fogrt__say(buf, size, d->nee && xs.equiangular && lamps, "equiangular");
    fogrt__say(buf, size, xs.expected_emission && (world || shapes), "expected emission");
    fogrt__say(buf, size, d->nee, d->mis ? "light sampling + MIS" : "light sampling");
    fogrt__say(buf, size, d->nee && xs.by_power, "lights by power");
    fogrt__say(buf, size, d->nee && s->env_map != NULL, "environment-map sampling");
    fogrt__say(buf, size, d->nee && xs.expected_emission && lamps, "light behind collisions");
    fogrt__say(buf, size, xs.glow, "glow");
    bool spot = false;
    for (uint32_t i = 0; i < s->light_count; ++i) spot |= s->lights[i].type == FOGRT_LIGHT_SPOT;
    fogrt__say(buf, size, xs.footprint && spot, "footprint");
    fogrt__say(buf, size, world || shapes, s->medium.phase == FOGRT_PHASE_HG || !world ? "HG" : "phase function");
    fogrt__say(buf, size, true, "BSDF");
    fogrt__say(buf, size, st->max_depth > d->rr_depth, xs.rr_k > 1.0f ? "roulette (pilot's k)" : "roulette");
}
/* Seam 7: the full integrator for every desc that asks for more than the paper, and for
   fog in a box or G's media (which Part I does not know). */
FOGRT__PRIVATE bool fogrt__full_wanted(const fogrt_scene *s, const fogrt__settings *st) {
    const fogrt_render_desc *d = &st->desc;
#ifndef FOGRT_NO_SHAPES
    if (s->x->h) return true;                           /* H */
#endif
#ifndef FOGRT_NO_MEDIA
    if (s->x->media) return true;
#endif
    return d->equiangular || d->glow || d->footprint || d->light_by_power || d->expected_emission ||
           s->x->fog_bounded || s->env_map;
}
/* One sample of the full integrator with settings xs: Part I's Algorithm 1, stepping the
   walk w inside Part II's path state. */
FOGRT__PRIVATE fogrt__v3 fogrt__full_radiance_xs(const fogrt_scene *s, const fogrt__settings *st, const fogrt__xs *xs,
                                              const fogrt__walk *w) {
    fogrt__path P;
    fogrt__path_start(s, &P, xs, w);
    return fogrt__algorithm1(s, st, &P.w, st->integrator == FOGRT_INTEGRATOR_DIRECT);
}
FOGRT__PRIVATE fogrt__v3 fogrt__full_radiance(const fogrt_scene *s, const fogrt__settings *st, fogrt__walk *w) {
    fogrt__xs xs;
    fogrt__full_settings(s, st, &xs);
    return fogrt__full_radiance_xs(s, st, &xs, w);
}
/* Seam 7a: the next event, by the steps chosen for the path (E's, G's or H's). */
FOGRT__HOT bool fogrt__full_next_event(const fogrt_scene *s, const fogrt__settings *st, fogrt__path *P, int limit) {
    return P->next_event(s, st, P, limit);
}

/* Seams 3 and 4: Part II's tables, made after Part I's build (the tree and the lights),
   and released with it. The footprints and the pilot trace rays in the finished scene. */
FOGRT__PRIVATE bool fogrt__appendix_build(fogrt_scene *s, const fogrt_build_desc *d, uint32_t n) {
    struct fogrt__x *x = (struct fogrt__x *)fogrt__alloc(&s->allocator, sizeof *x);
#ifndef FOGRT_NO_ESTIMATION
    /* The pilot's rays cost what the tree's do. Where the SAH cost says a ray visits some
       thousand nodes (slivers that all overlap: a fan of a million triangles around one
       vertex; 10 to 30 in ordinary scenes), its fixed number of paths would take minutes
       before any of the render's own limits apply, so it is not run (k = 1). Priced before
       the binary tree may be released (A), and only where the pilot has a light to trace
       towards (without one it answers k = 1 at once: the price is a walk over every node). */
    bool pilot = d->roulette_pilot && (s->light_count > 0 || s->area_light_count > 0 || s->env_map) &&
                 fogrt_bvh_sah_cost(s) <= FOGRT__PILOT_MAX_SAH;
#endif
    if (!x) return false;
    memset(x, 0, sizeof *x);
    s->x = x;
    x->rr_k = 1.0f;
    fogrt__med_set(&x->world, &s->medium, true);
    if (!(s->features & FOGRT_FEATURE_MEDIUM)) memset(&x->world, 0, sizeof x->world);
    x->world.world = true;
#ifndef FOGRT_NO_MEDIA
    fogrt__media_build(s);                              /* G */
#endif
#ifndef FOGRT_NO_SHAPES
    if (!fogrt__shapes_build(s)) return false;          /* H */
#endif
#ifndef FOGRT_NO_WIDE_BVH
    if (fogrt__wants_wide(d, n)) {                      /* A: the wide tree replaces the packed primitives */
        if (!fogrt__wide_build(s, d->release_binary)) return false;
        fogrt__free(&s->allocator, s->prims); s->prims = NULL;
    }
#else
    (void)d;
#endif
#ifndef FOGRT_NO_ESTIMATION
    if (!fogrt__build_env(s)) return false;            /* C */
    fogrt__fog_bounds(s, n);
#else
    (void)n;
#endif
#ifdef FOGRT__LAMPS
    x->glow_share = fogrt__glow_share_of(s);
    if (fogrt__lamps_in_fog(s)) {                       /* B (for another phase than HG, G: g = 0) */
        x->hg = (fogrt__hg_table *)fogrt__alloc(&s->allocator, sizeof *x->hg);
        if (!x->hg) return false;
        fogrt__hg_table_build(x->hg, s->medium.phase == FOGRT_PHASE_HG ? s->medium.g : 0.0f);
    }
#endif
#ifndef FOGRT_NO_ESTIMATION
    if (!fogrt__build_light_pick(s)) return false;     /* C */
#endif
#ifdef FOGRT__LAMPS
    if (fogrt__lamps_in_fog(s) && !fogrt__find_footprints(s)) return false;   /* B */
#endif
#ifndef FOGRT_NO_ESTIMATION
    if (pilot) x->rr_k = fogrt__roulette_pilot(s);                          /* C */
#endif
    return true;
}
FOGRT__PRIVATE void fogrt__appendix_release(fogrt_scene *s) {
    if (!s->x) return;
#ifndef FOGRT_NO_SHAPES
    fogrt__shapes_release(s);
#endif
#ifndef FOGRT_NO_WIDE_BVH
    fogrt__wide_release(s);
#endif
    fogrt__free(&s->allocator, s->x->env_cdf);
    fogrt__free(&s->allocator, s->x->light_pick);
    fogrt__free(&s->allocator, s->x->footprints);
    fogrt__free(&s->allocator, s->x->hg);
    fogrt__free(&s->allocator, s->x);
    s->x = NULL;
}

/* fogrt_trace_path (D): one pixel sample as fogrt_render takes it with the full integrator,
   every step reported. */
#ifdef FOGRT_TRACE
FOGRT__PUBLIC fogrt_vec3 fogrt_trace_path(const fogrt_scene *s, const fogrt_render_desc *desc, int width,
                                          int height, int x, int y, uint32_t sample_index, fogrt_trace_fn fn,
                                          void *user_data) {
    fogrt__job job;
    fogrt__xs xs;
    fogrt_render_desc d = fogrt_render_defaults();
    fogrt_trace_event e;
    fogrt_rng rng;
    uint64_t rays = 0;
    fogrt__v3 L, o, dir;
    FOGRT_ASSERT(s);
    memset(&job, 0, sizeof job);
    memset(&e, 0, sizeof e);
    if (!s->built || fogrt__resolve_render(s, desc, &job.st, &d) != FOGRT_RESULT_OK ||
        width <= 0 || height <= 0 || x < 0 || y < 0 || x >= width || y >= height)
        return fogrt__v(0.0f, 0.0f, 0.0f);
    job.s = s;
    job.cam = fogrt__camera_setup(s, width, height);
    job.base = fogrt__hash64(d.seed);
    fogrt__full_settings(s, &job.st, &xs);
    xs.trace = fn; xs.trace_user = user_data;
    fogrt__pixel_ray(&job, width, height, x, y, sample_index, &rng, &o, &dir, &e.u[0], &e.u[1]);
    if (fn) {
        fogrt__v3 u = fogrt__v(e.u[0], e.u[1], 0.0f);
        memset(&e, 0, sizeof e);
        e.kind = FOGRT_TRACE_CAMERA; e.p = o; e.d = dir; e.beta = fogrt__v(1.0f, 1.0f, 1.0f);
        e.u[0] = u.x; e.u[1] = u.y;
        fn(&e, user_data);
    }
    fogrt__walk w;
    fogrt__walk_start(&w, s, o, dir, &rng, &rays);
    L = fogrt__full_radiance_xs(s, &job.st, &xs, &w);
    memset(&e, 0, sizeof e);
    e.kind = FOGRT_TRACE_END; e.value = L;
    if (fn) fn(&e, user_data);
    return L;
}
#ifndef FOGRT_NO_STDIO
FOGRT__PRIVATE const char *fogrt__bsdf_name(fogrt_bsdf_type t) {
    static const char *names[FOGRT_BSDF_NUM] = { "diffuse", "diffuse", "mirror", "microfacet", "refraction", "glass", "interface" };
    return (unsigned)t < (unsigned)FOGRT_BSDF_NUM ? names[t] : "?";
}
#define FOGRT__V3F(v) (double)(v).x, (double)(v).y, (double)(v).z
/* The events that draw a sample: what was drawn, its pdf and its weight. */
FOGRT__PRIVATE void fogrt__describe_sample(const fogrt_trace_event *e, char *buf, size_t size) {
    static const char *lobes[4] = { "diffuse", "reflect", "refract", "glossy" };
    switch (e->kind) {
    case FOGRT_TRACE_LIGHT_SAMPLE:
        snprintf(buf, size, "light sample (eq. 3) toward light %u: wi = (%.4f, %.4f, %.4f), r = %.4g, Le = (%.4g, %.4g, %.4g), "
                 "pdf %.4g; f = %.4g (bsdf/phase pdf %.4g); T*V (eq. 8) = %.4g; MIS w = %.4f -> (%.4g, %.4g, %.4g)",
                 (unsigned)e->light, FOGRT__V3F(e->d), (double)e->t, FOGRT__V3F(e->Le), (double)e->pdf, (double)e->f.y,
                 (double)e->pdf_other, (double)e->transmittance, (double)e->mis_weight, FOGRT__V3F(e->value)); break;
    case FOGRT_TRACE_EQUIANGULAR:
        snprintf(buf, size, "equiangular toward light %u: u = %.6f -> t = %.5g, pdf %.4g; weight sigma_s T(t) / pdf = %.4g",
                 (unsigned)e->light, (double)e->u[0], (double)e->t, (double)e->pdf, (double)e->value.y); break;
    case FOGRT_TRACE_PHASE_SAMPLE:
        snprintf(buf, size, "phase sample: u1 = %.6f -> cos theta = %.6f (eq. 11), u2 = %.6f -> phi = %.4f (eq. 12); pdf = p = %.4g; new d = (%.4f, %.4f, %.4f)",
                 (double)e->u[0], (double)e->cos_theta, (double)e->u[1], (double)e->phi, (double)e->pdf, FOGRT__V3F(e->d)); break;
    case FOGRT_TRACE_GLOW_SAMPLE:
        snprintf(buf, size, "mixed direction (d'): u0 = %.4f -> %s; u1, u2 = (%.4f, %.4f); pdf = %.4g (phase/BSDF pdf %.4g); weight (%.4g, %.4g, %.4g); new d = (%.4f, %.4f, %.4f)",
                 (double)e->u[0], e->flag ? (e->source ? "the footprint of a lamp's cone on a plane" : "the glow of a lamp") : "the phase function / BSDF", (double)e->u[1], (double)e->u[2],
                 (double)e->pdf, (double)e->pdf_other, FOGRT__V3F(e->value), FOGRT__V3F(e->d)); break;
    case FOGRT_TRACE_BSDF_SAMPLE: {
        char fresnel[40] = "";                           /* glass only: the F it chose by */
        if (e->bsdf == FOGRT_BSDF_GLASS) snprintf(fresnel, sizeof fresnel, ", Fresnel F = %.4g", (double)e->fresnel);
        snprintf(buf, size, "BSDF sample (%s): u = (%.4f, %.4f, %.4f) -> %s%s; pdf %.4g, weight (%.4g, %.4g, %.4g); new d = (%.4f, %.4f, %.4f)",
                 fogrt__bsdf_name(e->bsdf), (double)e->u[0], (double)e->u[1], (double)e->u[2], lobes[e->lobe], fresnel,
                 (double)e->pdf, FOGRT__V3F(e->value), FOGRT__V3F(e->d));
        break;
    }
    default:
        snprintf(buf, size, "unknown event %d", (int)e->kind); break;
    }
}
FOGRT__PUBLIC void fogrt_trace_describe(const fogrt_trace_event *e, char *buf, size_t size) {
    switch (e->kind) {
    case FOGRT_TRACE_CAMERA:
        snprintf(buf, size, "camera ray: pixel offset (%.3f, %.3f), o = (%.4g, %.4g, %.4g), d = (%.4f, %.4f, %.4f)",
                 (double)e->u[0], (double)e->u[1], FOGRT__V3F(e->p), FOGRT__V3F(e->d)); break;
    case FOGRT_TRACE_FREE_FLIGHT:
        snprintf(buf, size, "free flight (eq. 6): u = %.6f -> t = -ln(1 - u) / sigma_t = %.5g; surface at %.5g -> %s",
                 (double)e->u[0], (double)e->t, (double)e->t_max, e->flag ? "FOG COLLISION (weight x albedo)" : "reaches the surface (weight T/T = 1)"); break;
    case FOGRT_TRACE_SURFACE:
        snprintf(buf, size, "surface: primitive %u (%s) at (%.4g, %.4g, %.4g)", (unsigned)e->prim, fogrt__bsdf_name(e->bsdf), FOGRT__V3F(e->p)); break;
    case FOGRT_TRACE_ESCAPE:
        snprintf(buf, size, "escape: the ray leaves the scene along (%.4f, %.4f, %.4f)", FOGRT__V3F(e->d)); break;
    case FOGRT_TRACE_ROULETTE:
        snprintf(buf, size, "Russian roulette: continue with q = %.4f; u = %.4f -> %s", (double)e->q, (double)e->u[0],
                 e->flag ? "survives (weight / q)" : "path ends"); break;
    case FOGRT_TRACE_CONTRIBUTION:
        snprintf(buf, size, "+ %s: (%.5g, %.5g, %.5g) added to the pixel%s", e->source ? e->source : "light",
                 FOGRT__V3F(e->value), e->flag ? "" : " (not counted: below min_depth)"); break;
    case FOGRT_TRACE_END:
        snprintf(buf, size, "= sample radiance (%.5g, %.5g, %.5g)", FOGRT__V3F(e->value)); break;
    default:
        fogrt__describe_sample(e, buf, size); break;
    }
}
#undef FOGRT__V3F
#endif
#endif
/* ------------------------------------------------------------------------------------------
   F. Inspecting a scene (benchmarks and tests)
   What it adds: the BVH as built, its SAH cost (the expected number of node visits and
   primitive tests of a random ray, relative to the root's area), a brute-force ray query to
   check the tree against, and the bytes the scene holds, Part II's tables included.
   What it costs: nothing unless called (the roulette's pilot (C) reads the SAH cost once per
   build). Its figures: docs/benchmarks.md, "make bench" (bytes per triangle) and "Slivers".
   ------------------------------------------------------------------------------------------ */
/* The binary tree's references (its leaves' primitive counts, summed): the primitives, and
   the pieces of long slivers (A). */
FOGRT__PRIVATE size_t fogrt__tree_refs(const fogrt_scene *s) {
    size_t refs = 0;
    uint32_t i;
    for (i = 0; i < s->node_count; ++i) if (i != 1) refs += s->nodes[i].prim_count;
    return refs;
}
FOGRT__PUBLIC size_t fogrt_scene_get_memory(const fogrt_scene *s) {
    size_t t, p, b = sizeof *s, lit = 0;
    uint32_t i;
    FOGRT_ASSERT(s);
    t = s->tri_count;
    p = t + s->sph_count;
    b += sizeof(fogrt_material_desc) * s->material_count + sizeof(fogrt_light_desc) * s->light_count;
    b += t * ((s->tri_n ? 6 : 3) * sizeof(fogrt__v3) + 1 + 2 * sizeof(uint32_t));   /* vertices, normals, flag, ids */
    b += (size_t)s->sph_count * (sizeof(fogrt__v3) + sizeof(float) + sizeof(uint32_t));
    if (s->env_map) b += sizeof(float) * 3 * (size_t)s->env_map->w * (size_t)s->env_map->h;
    if (s->nodes) b += sizeof(fogrt_bvh_node) * s->node_count + fogrt__tree_refs(s) * sizeof(uint32_t);
    if (s->prims) b += p * sizeof(fogrt__prim);         /* 2.1's primitives: the binary layout only */
    if (s->spot_cos) b += sizeof(float) * 2 * s->light_count;
    for (i = 0; s->area_lights && i < s->area_light_count; ++i) lit += s->area_lights[i].count;
    if (s->area_lights) b += sizeof(fogrt__area_light) * s->area_light_count + lit * (sizeof(uint32_t) + sizeof(float));
    if (s->prim_light) b += sizeof(uint32_t) * p;
    if (!s->x) return b;                                /* Part II's tables */
    b += sizeof *s->x;
    if (s->x->env_cdf) b += sizeof(float) * ((size_t)s->env_map->w + 1) * (size_t)s->env_map->h;
    if (s->x->light_pick) b += sizeof(float) * fogrt__light_total(s);
#ifdef FOGRT__LAMPS
    if (s->x->footprints) b += sizeof(fogrt__footprint) * s->light_count;
    if (s->x->hg) b += sizeof *s->x->hg;
#endif
#ifndef FOGRT_NO_WIDE_BVH
    if (s->x->wide) b += fogrt__wbvh_bytes(s->x->wide);
#endif
    return b;
}
FOGRT__PUBLIC void fogrt_scene_get_bvh(const fogrt_scene *s, const fogrt_bvh_node **nodes, uint32_t *node_count,
                                       const uint32_t **prim_index) {
    FOGRT_ASSERT(s);
    if (nodes) *nodes = s->nodes;
    if (node_count) *node_count = s->node_count;
    if (prim_index) *prim_index = s->prim_index;
}
FOGRT__PUBLIC float fogrt_bvh_sah_cost(const fogrt_scene *s) {
    double cost = 0.0, root_area;
    uint32_t i;
    fogrt__aabb rb;
    FOGRT_ASSERT(s);
    if (!s->nodes || s->node_count == 0) return 0.0f;
    rb.lo = fogrt__v(s->nodes[0].bmin[0], s->nodes[0].bmin[1], s->nodes[0].bmin[2]);
    rb.hi = fogrt__v(s->nodes[0].bmax[0], s->nodes[0].bmax[1], s->nodes[0].bmax[2]);
    root_area = (double)FOGRT__MAX(fogrt__aabb_area(&rb), FLT_MIN);
    for (i = 0; i < s->node_count; ++i) {
        const fogrt_bvh_node *n = &s->nodes[i];
        fogrt__aabb nb;
        if (i == 1) continue;
        nb.lo = fogrt__v(n->bmin[0], n->bmin[1], n->bmin[2]);
        nb.hi = fogrt__v(n->bmax[0], n->bmax[1], n->bmax[2]);
        cost += (double)fogrt__aabb_area(&nb) / root_area * (n->prim_count > 0 ? 1.0 * n->prim_count : 1.0);
    }
    return (float)cost;
}
FOGRT__PUBLIC bool fogrt_scene_intersect_brute(const fogrt_scene *s, fogrt_vec3 o, fogrt_vec3 d, float tmin, float tmax, fogrt_hit *hit) {
    uint32_t i;
    bool found = false;
    FOGRT_ASSERT(s);
    for (i = 0; i < s->tri_count + s->sph_count; ++i) {
        float t, u = 0.0f, v = 0.0f;
        bool h;
        if (i < s->tri_count) {
            const fogrt__v3 *tv = &s->tri_v[3 * i];
            h = fogrt__hit_triangle(o, d, tv[0], fogrt__sub(tv[1], tv[0]), fogrt__sub(tv[2], tv[0]), tmin, tmax, &t, &u, &v);
        } else {
            h = fogrt__hit_sphere(o, d, s->sph_c[i - s->tri_count], s->sph_r[i - s->tri_count], tmin, tmax, &t);
        }
        if (h) {
            found = true; tmax = t;
            if (hit) { hit->t = t; hit->prim = i; hit->u = u; hit->v = v; }
        }
    }
    return found;
}

#ifndef FOGRT_NO_MEDIA
/* ------------------------------------------------------------------------------------------
   G. Media beyond the paper
   What it adds: two phase functions besides Henyey-Greenstein, fog that emits light, and fog
   whose sigma_t differs per colour channel.
     - Two HG lobes, w HG(g) + (1 - w) HG(g2): a real droplet scatters mostly forward and a
       little backward, which one HG lobe cannot do at once. Rayleigh, 3 / (16 pi) (1 + mu^2):
       particles much smaller than the wavelength (haze). Each is sampled exactly (pdf =
       phase function, sample weight 1) and used wherever the full integrator (E) samples or
       evaluates the phase function: scattering, next-event estimation and its MIS weights,
       equiangular and glow sampling. B's table of HG per unit angle is HG's, so for these
       phases the build makes it for g = 0: equiangular and glow sampling then take their
       plain forms (the densities 1 / r^2 and (pi - alpha) / sin alpha, to the table's
       resolution, exactly as in isotropic fog), with the phase function left in the weight
       (a table of the phase function itself would be the next step). This keeps E free of
       a test of the phase in B's inner loops.
     - Emission: the fog adds sigma_a Le per unit length (sigma_a = sigma_t (1 - albedo),
       pbrt-v4's convention), in the full integrator (also under the paper's render desc:
       Part I knows neither, seam 7 sends such media to E).
     - Chromatic fog: sigma_t per channel, one hero channel per path sampling its free
       flights and one-sample spectral MIS in the weights (below, "Chromatic media").
   A path in any of these media takes G's step a + b (fogrt__media_next_event), chosen once
   per path, and its light samples G's shadow and phase function (fogrt__media_light).
   What it costs: a scene with the paper's medium pays one compare per camera sample (which
   step a + b), one per light sample and one where a fog vertex samples or evaluates the
   phase function, and renders bit for bit as before (make callgrind: the default scene
   against a FOGRT_NO_MEDIA build; docs/benchmarks.md, table "Strip cost"). Validation of
   the medium desc's fields is seam 6's second use.
   ------------------------------------------------------------------------------------------ */
FOGRT__PRIVATE fogrt_result fogrt__media_check(const fogrt_scene *s, fogrt_medium_desc *m) {
    FOGRT__REFUSE_IF((unsigned)m->phase >= (unsigned)FOGRT_PHASE_NUM, INVALID_MEDIUM,
                     "medium.phase: not FOGRT_PHASE_HG, FOGRT_PHASE_HG2 or FOGRT_PHASE_RAYLEIGH");
    FOGRT__REFUSE_IF(!(m->g2 >= -1.0f && m->g2 <= 1.0f), INVALID_MEDIUM, "medium.g2: outside [-1, 1] or not finite");
    FOGRT__REFUSE_IF(!(m->w >= 0.0f && m->w <= 1.0f), INVALID_MEDIUM, "medium.w: outside [0, 1] or not finite");
    FOGRT__REFUSE_IF(!fogrt__colour_ok(m->emission), INVALID_MEDIUM, "medium.emission: negative or not finite");
    FOGRT__REFUSE_IF(!fogrt__colour_ok(m->sigma_t_rgb), INVALID_MEDIUM, "medium.sigma_t_rgb: a component negative or not finite");
#ifdef FOGRT_NO_ESTIMATION
    FOGRT__REFUSE_IF(m->bounded && !fogrt__is_black(m->sigma_t_rgb), UNSUPPORTED,
                     "medium.bounded: fog in a box needs a build without FOGRT_NO_ESTIMATION and FOGRT_MINIMAL");
#endif
    if (fabsf(m->g2) >= FOGRT_HG_G_MAX && fabsf(m->g2) != FOGRT_HG_G_MAX) {
        m->g2 = copysignf(FOGRT_HG_G_MAX, m->g2);
        fogrt__log(s, FOGRT_LOG_WARNING, "medium.g2: |g2| > 0.9999 clamped to 0.9999 (FOGRT_HG_G_MAX)");
    }
    /* sigma_t per channel replaces sigma_t, which keeps the largest component: Part I tells
       fog from none by it. Three equal components are grey fog, which Part I renders. */
    if (!fogrt__is_black(m->sigma_t_rgb)) {
        m->sigma_t = fogrt__max3(m->sigma_t_rgb);
        if (m->sigma_t_rgb.x == m->sigma_t_rgb.y && m->sigma_t_rgb.y == m->sigma_t_rgb.z) m->sigma_t_rgb = fogrt__v(0.0f, 0.0f, 0.0f);
    }
    return FOGRT_RESULT_OK;
}

/* Two lobes. The lobe is chosen by u1 (lobe 1 below w) and u1 rescaled to the lobe's
   uniform: each lobe then keeps 3.3's exact sampler, and the pdf is the mixture's at the
   direction drawn, the drawn lobe's part from that sampler (exact near its peak), the
   other's from the chords (fogrt_hg_pdf). A weight outside [0, 1] (or NaN) is clamped. */
FOGRT__PUBLIC float fogrt_hg2_phase(float g1, float g2, float w, float mu) {
    w = FOGRT__CLAMP(w, 0.0f, 1.0f);
    return w * fogrt_hg_phase(g1, mu) + (1.0f - w) * fogrt_hg_phase(g2, mu);
}
FOGRT__PUBLIC float fogrt_hg2_pdf(float g1, float g2, float w, fogrt_vec3 wo, fogrt_vec3 wi) {
    w = FOGRT__CLAMP(w, 0.0f, 1.0f);
    return w * fogrt_hg_pdf(g1, wo, wi) + (1.0f - w) * fogrt_hg_pdf(g2, wo, wi);
}
FOGRT__PRIVATE fogrt__v3 fogrt__sample_hg2_unit(float g1, float g2, float w, fogrt__v3 wo, float u1, float u2, float *pdf) {
    bool first;
    float u, p;
    fogrt__v3 wi;
    w = FOGRT__CLAMP(w, 0.0f, 1.0f);
    u1 = FOGRT__CLAMP(u1, 0.0f, 1.0f);
    first = u1 < w;                                      /* w = 0: never; w = 1: always (u1 < 1) */
    u = first ? u1 / w : (u1 - w) / (1.0f - w);
    wi = fogrt__sample_hg_unit(first ? g1 : g2, wo, FOGRT__CLAMP(u, 0.0f, 1.0f), u2, &p);
    if (pdf) *pdf = first ? w * p + (1.0f - w) * fogrt_hg_pdf(g2, wo, wi) : (1.0f - w) * p + w * fogrt_hg_pdf(g1, wo, wi);
    return wi;
}
FOGRT__PUBLIC fogrt_vec3 fogrt_sample_hg2(float g1, float g2, float w, fogrt_vec3 wo, float u1, float u2, float *pdf) {
    return fogrt__sample_hg2_unit(g1, g2, w, fogrt__normalize(wo), u1, u2, pdf);
}

/* Rayleigh. The CDF of mu, F(mu) = (mu^3 + 3 mu + 4) / 8, is increasing, so F(mu) = u is a
   cubic with one real root. With mu = 2 sinh(x) it reads 2 sinh(3x) = 8u - 4 (sinh 3x =
   3 sinh x + 4 sinh^3 x), so mu = 2 sinh(asinh(4u - 2) / 3): no cancellation anywhere
   (Cardano's cube roots would subtract two nearly equal numbers near u = 1/2), odd about
   u = 1/2, and in double exactly -1 and 1 at u = 0 and 1 after rounding to float. */
#define FOGRT__RAYLEIGH_NORM 0.05968310365946075f   /* 3 / (16 pi) */
FOGRT__PUBLIC float fogrt_rayleigh_phase(float mu) {
    mu = FOGRT__CLAMP(mu, -1.0f, 1.0f);
    return FOGRT__RAYLEIGH_NORM * (1.0f + mu * mu);
}
FOGRT__PUBLIC float fogrt_sample_rayleigh_mu(float u) {
    double z = 4.0 * (double)FOGRT__CLAMP(u, 0.0f, 1.0f) - 2.0;
    return FOGRT__CLAMP((float)(2.0 * sinh(asinh(z) / 3.0)), -1.0f, 1.0f);
}
FOGRT__PRIVATE fogrt__v3 fogrt__sample_rayleigh_unit(fogrt__v3 wo, float u1, float u2, float *pdf) {
    fogrt__frame f = fogrt__frame_from_z(fogrt__neg(wo));   /* z: propagation */
    float mu = fogrt_sample_rayleigh_mu(u1);
    if (pdf) *pdf = fogrt_rayleigh_phase(mu);
    return fogrt__direction_at(&f, mu, sqrtf(FOGRT__MAX(0.0f, (1.0f - mu) * (1.0f + mu))), u2);
}
FOGRT__PUBLIC fogrt_vec3 fogrt_sample_rayleigh(fogrt_vec3 wo, float u1, float u2, float *pdf) {
    return fogrt__sample_rayleigh_unit(fogrt__normalize(wo), u1, u2, pdf);
}
FOGRT__PUBLIC float fogrt_rayleigh_pdf(fogrt_vec3 wo, fogrt_vec3 wi) {
    return fogrt_rayleigh_phase(-fogrt__dot(wo, wi));
}

/* The phase function of a medium desc: what E calls for fog that is not the paper's (and
   a desc's HG, so the public functions take any desc). wo is unit here. */
FOGRT__PRIVATE fogrt__v3 fogrt__media_sample(const fogrt_medium_desc *m, fogrt__v3 wo, float u1, float u2, float *pdf) {
    if (m->phase == FOGRT_PHASE_RAYLEIGH) return fogrt__sample_rayleigh_unit(wo, u1, u2, pdf);
    if (m->phase == FOGRT_PHASE_HG2) return fogrt__sample_hg2_unit(m->g, m->g2, m->w, wo, u1, u2, pdf);
    return fogrt__sample_hg_unit(m->g, wo, u1, u2, pdf);
}
FOGRT__PRIVATE float fogrt__media_pdf(const fogrt_medium_desc *m, fogrt__v3 wo, fogrt__v3 wi) {
    if (m->phase == FOGRT_PHASE_RAYLEIGH) return fogrt_rayleigh_pdf(wo, wi);
    if (m->phase == FOGRT_PHASE_HG2) return fogrt_hg2_pdf(m->g, m->g2, m->w, wo, wi);
    return fogrt_hg_pdf(m->g, wo, wi);
}
FOGRT__PUBLIC float fogrt_phase(const fogrt_medium_desc *m, float mu) {
    FOGRT_ASSERT(m);
    if (m->phase == FOGRT_PHASE_RAYLEIGH) return fogrt_rayleigh_phase(mu);
    if (m->phase == FOGRT_PHASE_HG2) return fogrt_hg2_phase(m->g, m->g2, m->w, mu);
    return fogrt_hg_phase(m->g, mu);
}
FOGRT__PUBLIC fogrt_vec3 fogrt_sample_phase(const fogrt_medium_desc *m, fogrt_vec3 wo, float u1, float u2, float *pdf) {
    FOGRT_ASSERT(m);
    return fogrt__media_sample(m, fogrt__normalize(wo), u1, u2, pdf);
}
FOGRT__PUBLIC float fogrt_phase_pdf(const fogrt_medium_desc *m, fogrt_vec3 wo, fogrt_vec3 wi) {
    FOGRT_ASSERT(m);
    return fogrt__media_pdf(m, wo, wi);
}

/* Emission. Along a fog segment of the ray (from where it enters the fog, a, to where it
   leaves it or meets the surface, b) the light the fog adds toward the ray's origin is
     int_a^b T(t) sigma_a Le dt = (sigma_a / sigma_t) Le (1 - T(b - a)),   T(x) = exp(-sigma_t x),
   whatever the free flight then does: the path goes on from the collision (weight albedo)
   or the surface (weight 1), which estimate the rest of the radiance, not this part. So
   with expected_emission (the default) each segment adds beta (1 - albedo) Le (1 - T),
   with no noise of its own; in unbounded fog (b infinite) that is beta (1 - albedo) Le,
   and summed over a path of collisions, sum_k albedo^k (1 - albedo) Le = Le: fog of any
   albedo below 1 seen from inside looks Le. Without it (the paper's way, as for
   emitters) the collision estimator: beta (1 - albedo) Le at each collision, nothing when
   the ray gets through, whose mean over the free flight, with collision density
   sigma_t T(t), is the same integral. beta is the weight before the collision's albedo. */
FOGRT__PRIVATE void fogrt__media_build(fogrt_scene *s) {
    const fogrt__med *w = &s->x->world;
    s->x->media = (s->features & FOGRT_FEATURE_MEDIUM) && (w->d.phase != FOGRT_PHASE_HG || w->emits || w->chroma);
}
FOGRT__PRIVATE void fogrt__media_emission(const fogrt_scene *s, const fogrt__settings *st, fogrt__path *P,
                                          fogrt__v3 beta, float t_end, bool collided) {
    float a, b, w = collided ? 1.0f : 0.0f;
    if (P->xs->expected_emission) {
        if (!fogrt__med_span(s, P->m, P->w.o, P->w.d, t_end, &a, &b)) return;   /* misses the fog's box */
        w = b < INFINITY ? -expm1f(-P->m->d.sigma_t * (b - a)) : 1.0f;
    }
    if (w > 0.0f) fogrt__gather(P, st, P->w.depth, fogrt__scale(fogrt__mul(beta, P->m->emit), w), "fog emission");
}

/* Chromatic media: sigma_t per colour channel, so that each channel's light is attenuated and
   scattered at its own rate (coloured haze). A free flight can follow one rate only, so each
   path picks one channel, the hero, uniformly when it starts, and samples all its free
   flights with the hero's sigma_t. Had channel c been the hero, the path's free flights would
   have had density P_c(x); with the hero drawn at random their density is mean_c P_c(x), and
   the estimate divides the path's contribution f(x) (per channel) by that mean: one-sample MIS
   over the channels with the balance heuristic, the spectral MIS of pbrt-v4's
   VolPathIntegrator and Mitsuba 3's volpathmis. Each channel's estimate is then at most 3
   times what grey fog of that channel's sigma_t gives (f_c / mean P <= 3 f_c / P_c). Dividing
   by the hero's own P_h instead is unbiased only where the hero can sample every path the
   other channels light (never a collision when its sigma_t is 0), and its weight has no
   bound where P_h is small against the others' (xs->hero_pdf: the negative control).
   The path keeps r_c, proportional to P_c (only ratios matter: its largest is kept at 1), and
   its throughput beta = f / mean P, which every other step of E (light sampling, emission,
   roulette) reads as in grey fog. An event of a free flight of density p_c in channel c (a
   collision at t: sigma_t,c T_c(t); crossing a length d: T_c(d)) has density m = sum r_c p_c /
   sum r_c under the mixture, relative to the path so far: beta takes f / m and r takes p
   (fogrt__chroma_mix). With equal components every m is the grey p and beta the grey albedo,
   but such a medium is stored as grey fog (fogrt__media_check) and never comes here.
   What reads sigma_t reads it per channel:
     - shadow rays (light sampling at fog and surface vertices, and at the points equiangular
       sampling draws): T_c, folded into f (fogrt__chroma_shadow);
     - equiangular sampling (B): its density does not depend on sigma_t; its weight is
       sigma_s,c T_c(t) / pdf (fogrt__chroma_collision);
     - expected emission (E b): the emitter or sky a ray reaches adds beta T_c Le whatever its
       free flight does (no distance is sampled there, so no channel's density enters); the
       paper's way adds Le when the flight gets there, with the weight of that crossing;
     - the lamps' light at the surface behind a collision (E b'): beta T_c times it in both
       cases, behind a collision directly (taken with probability min(1, 16 tau), tau the
       largest T_c, as grey fog does with T) and at the surface, when the flight gets there,
       through a lamp scale m (the crossing's weight is T_c / m);
     - the fog's emission (G): (1 - albedo_c) Le_c (1 - T_c) per segment, or the paper's
       collision estimator with the collision's weight;
     - the MIS weights between light sampling and phase or BSDF sampling are those of the
       directions: both strategies share the path's free flights, whose mixture over the
       channels is a common factor, so the weights still add up to one per channel.
   The glow and the footprint (d') aim directions and read no sigma_t. */
/* A path in G's media: whether its light samples need G (so that the paper's medium pays
   one test per light sample, where it had one anyway), and in chromatic fog its hero
   channel. */
FOGRT__PRIVATE void fogrt__media_start(const fogrt_scene *s, fogrt__path *P) {
    P->media_light = s->medium.phase != FOGRT_PHASE_HG || s->x->world.chroma;
    if (s->x->world.chroma) {
        int hero = (int)(3.0f * fogrt_rng_float(P->w.rng));
        P->chroma = true;
        P->hero = FOGRT__MIN(hero, 2);
        P->r = fogrt__v(1.0f, 1.0f, 1.0f);
    }
}
/* T_c(d) per channel (d = +inf: 0 where sigma_t,c > 0, else 1). */
FOGRT__PRIVATE fogrt__v3 fogrt__chroma_tr(const fogrt__med *m, float d) {
    const fogrt__v3 k = m->sigma;
    return fogrt__v(fogrt_transmittance(k.x, d), fogrt_transmittance(k.y, d), fogrt_transmittance(k.z, d));
}
/* 1 - T_c(d) per channel, without cancellation (expm1) for small optical depths. */
FOGRT__PRIVATE float fogrt__chroma_absorbed1(float sigma, float d) {
    if (!(sigma > 0.0f)) return 0.0f;
    return d < INFINITY ? -expm1f(-sigma * d) : 1.0f;
}
FOGRT__PRIVATE fogrt__v3 fogrt__chroma_absorbed(const fogrt__med *m, float d) {
    const fogrt__v3 k = m->sigma;
    return fogrt__v(fogrt__chroma_absorbed1(k.x, d), fogrt__chroma_absorbed1(k.y, d), fogrt__chroma_absorbed1(k.z, d));
}
/* A point drawn at distance t into the fog with density pdf, not by the free flight: its
   weight sigma_t,c T_c(t) / pdf per channel. */
FOGRT__PRIVATE fogrt__v3 fogrt__chroma_collision(const fogrt__med *m, float t, float pdf) {
    return fogrt__scale(fogrt__mul(m->sigma, fogrt__chroma_tr(m, t)), 1.0f / pdf);
}
/* Visibility by Part I's shadow ray (the vertex taken as clear air, so that it adds no grey
   T), then T_c over the ray's length in the fog, as fogrt__fog_transmittance measures it. */
FOGRT__PRIVATE float fogrt__chroma_shadow(const fogrt_scene *s, const fogrt__vertex *v, const fogrt_light_sample *ls,
                                          uint64_t *rays, fogrt__v3 *f) {
    fogrt__vertex clear = *v;
    float a, b;
    clear.in_medium = false;
    if (fogrt__shadow(s, &clear, ls, rays) == 0.0f) return 0.0f;
    if (fogrt__fog_box_span(s, v->p, ls->wi, ls->dist, &a, &b)) *f = fogrt__mul(*f, fogrt__chroma_tr(&s->x->world, b - a));
    return 1.0f;
}
/* A light sample's f (G's phase function at a fog vertex) and visibility times T (T_c in f
   in chromatic fog), for fogrt__light_contribution. */
FOGRT__PRIVATE fogrt__v3 fogrt__media_light(const fogrt_scene *s, const fogrt__path *P, const fogrt__vertex *v,
                                            const fogrt_light_sample *ls, float *pdf_b, float *tr) {
    fogrt__v3 f = fogrt__fog_vertex_f(s, P->m, v, ls->wi, pdf_b);
    if (fogrt__is_black(f)) return f;
#ifndef FOGRT_NO_SHAPES
    if (s->x->h) {                                       /* H: through interfaces, T of each medium */
        f = fogrt__mul(f, fogrt__h_shadow(s, v, P->med, ls, P->w.rays));
        *tr = fogrt__is_black(f) ? 0.0f : 1.0f;
        return f;
    }
#endif
    *tr = P->chroma && v->in_medium ? fogrt__chroma_shadow(s, v, ls, P->w.rays, &f) : fogrt__shadow(s, v, ls, P->w.rays);
    return f;
}
/* One event of a free flight, of density p_c (any scale common to the channels) had channel
   c sampled it: returns m = sum r_c p_c / sum r_c, its density under the mixture relative to
   the path so far, and r takes p. 0 where no channel could have sampled it (the path ends). */
FOGRT__PRIVATE float fogrt__chroma_mix(fogrt__path *P, fogrt__v3 p) {
    fogrt__v3 rp = fogrt__mul(P->r, p);
    float m = (rp.x + rp.y + rp.z) / (P->r.x + P->r.y + P->r.z), top = fogrt__max3(rp);
    if (P->xs->hero_pdf) m = fogrt__comp(p, P->hero);
    if (!(m > 0.0f) || !(top > 0.0f) || !fogrt__finite(m)) return 0.0f;
    P->r = fogrt__scale(rp, 1.0f / top);
    return m;
}
/* The fog's emission along this flight (fogrt__media_emission's, per channel): in closed
   form with expected_emission, else at a collision with its weight k. */
FOGRT__PRIVATE void fogrt__chroma_emission(const fogrt__settings *st, fogrt__path *P, fogrt__v3 beta,
                                           float d, bool collided, fogrt__v3 k) {
    fogrt__v3 w = fogrt__v(0.0f, 0.0f, 0.0f);
    if (P->xs->expected_emission) w = fogrt__chroma_absorbed(P->m, d);
    else if (collided) w = k;
    if (!fogrt__is_black(w)) fogrt__gather(P, st, P->w.depth, fogrt__mul(fogrt__mul(beta, P->m->emit), w), "fog emission");
}
/* E's a and b for chromatic fog: the free flight [a, b] of the ray (as fogrt__free_flight,
   with the hero's sigma_t), the equiangular lights along it, then what the end of the ray
   adds (fogrt__collided, fogrt__ray_end) with beta T_c / tau and tr = tau, tau the largest
   T_c (their product beta T_c is expected emission's), and the new throughput. */
FOGRT__PRIVATE bool fogrt__chroma_next_event(const fogrt_scene *s, const fogrt__settings *st, fogrt__path *P,
                                             bool found, const fogrt_hit *hit, int limit) {
    const fogrt__v3 beta = P->w.beta;                     /* before this flight */
    const fogrt__med *med = P->m;
    fogrt__v3 T, p, k, end = fogrt__v(0.0f, 0.0f, 0.0f);
    float u = fogrt_rng_float(P->w.rng), a, b, t, m, tau;
    bool collided, expected = P->xs->expected_emission;
    if (!fogrt__med_span(s, med, P->w.o, P->w.d, found ? hit->t : INFINITY, &a, &b))   /* misses the fog's box */
        return fogrt__ray_end(s, st, P, found, hit, beta, 1.0f, limit);
    t = a + fogrt_sample_exponential(fogrt__comp(med->sigma, P->hero), u);
    collided = t < b;
    FOGRT__HOOK(fogrt__trace_free_flight(P, u, t, b, collided));
#ifdef FOGRT__LAMPS
    if (st->desc.nee && P->xs->equiangular && s->light_count > 0 && P->w.depth < limit && med->world)
        fogrt__gather(P, st, P->w.depth + 1, fogrt__mul(beta, fogrt__equiangular(s, st, P, a, b, true, true)), "equiangular");
#endif
    T = fogrt__chroma_tr(med, b - a);
    p = collided ? fogrt__mul(med->sigma_n, fogrt__chroma_tr(med, t - a)) : T;
    m = fogrt__chroma_mix(P, p);
    k = m > 0.0f ? fogrt__scale(p, 1.0f / m) : fogrt__v(0.0f, 0.0f, 0.0f);   /* the event's weight per channel */
    if (med->emits) fogrt__chroma_emission(st, P, beta, b - a, collided, k);
    tau = fogrt__max3(T);
    if (tau > 0.0f) end = fogrt__scale(fogrt__mul(beta, T), 1.0f / tau);
    if (collided) {                                     /* sigma_s,c T_c / m = albedo_c k_c */
        P->w.beta = fogrt__mul(fogrt__mul(beta, med->d.albedo), k);
        fogrt__fog_vertex(&P->w.v, fogrt__madd(P->w.o, P->w.d, t), fogrt__neg(P->w.d));
        P->glow.n = 0;
        P->seg_tr = tau;
        return fogrt__collided(s, st, P, found ? hit : NULL, end, expected ? tau : 0.0f, limit);
    }
    P->w.beta = fogrt__mul(beta, k);                      /* T_c / m */
    P->seg_tr = m;                                      /* the lamps at the surface: T_c / m, times m */
    if (!expected) { end = P->w.beta; tau = 1.0f; }       /* the paper's: Le with the crossing's weight */
    return fogrt__ray_end(s, st, P, found, hit, end, tau, limit);
}
/* E's a + b (fogrt__next_event) in G's media: another phase function, emitting fog, or
   chromatic fog. */
FOGRT__PRIVATE bool fogrt__media_next_event(const fogrt_scene *s, const fogrt__settings *st, fogrt__path *P, int limit) {
    fogrt_hit hit;
    bool found;
    ++*P->w.rays;
    found = fogrt__traverse(s, P->w.o, P->w.d, 0.0f, INFINITY, &hit, false);
    P->seg_tr = 1.0f;
    if (!P->w.in_fog) return fogrt__ray_end(s, st, P, found, &hit, P->w.beta, 1.0f, limit);
    if (P->m->chroma) return fogrt__chroma_next_event(s, st, P, found, &hit, limit);
    return fogrt__fog_event(s, st, P, found, &hit, limit, true);
}
#endif /* FOGRT_NO_MEDIA */

#ifndef FOGRT_NO_SHAPES
#include <stdlib.h>   /* qsort */
/* ------------------------------------------------------------------------------------------
   H. Media inside shapes
   What it adds: a homogeneous medium inside any closed mesh or sphere
   (fogrt_scene_set_interior): smoke in a glass, a fog volume of any shape behind an
   index-matched surface (FOGRT_BSDF_INTERFACE, given to a shape already added by
   fogrt_scene_set_shape_material), media inside media, the camera inside any of them.
   What it costs: nothing for a scene without such media (a test of one pointer where a ray
   reaches a surface or refracts). A scene with them runs Algorithm 1 (3.4) with E's steps,
   B's and C's samplers included: H adds only where the path is (the medium it travels in,
   E's fogrt__med, whose fog E's and G's steps read), what a surface does to that (an
   interface is passed, a refraction crosses into the medium on the other side), and shadow
   rays through interfaces. B's samplers (equiangular sampling, the glow, the footprint) work
   in the world's fog, whose tables they read; in a shape's medium the lamps are found by
   light sampling at its collisions.
   Its tests: tests/test_shapes.c, tests/test_compose.c; docs/validation.md, "Media inside
   shapes".

   The media form a tree. Every shape that bounds a medium (one with an interior, or a
   refractive or interface one) has an inside medium and an outside one, the inside of the
   innermost such shape that holds it (or the world's medium). The build finds who holds whom
   by ray parity: a ray from a point crosses the surface of every closed shape that holds the
   point an odd number of times. A path carries the medium it travels in; crossing a
   boundary's surface (refracting through it, or passing an interface) takes it to that
   boundary's other medium. A shadow ray passes interface surfaces only, and collects the
   transmittance (eq. 8) of every medium it crosses.
   ------------------------------------------------------------------------------------------ */
typedef struct fogrt__interior { fogrt_shape_kind kind; uint32_t index; fogrt_medium_desc m; } fogrt__interior;
struct fogrt__shapes { fogrt__interior *items; uint32_t count, cap; };
/* A boundary of the built scene: a shape, its two media (indices into media), its box. */
typedef struct fogrt__boundary {
    fogrt_shape_kind kind;
    uint32_t index, inside, outside, holder;   /* holder: the innermost boundary that holds it, or UINT32_MAX */
    int declared;                              /* its interior's medium index, or -1 */
    bool closed, interface;
    fogrt__aabb box;
} fogrt__boundary;
struct fogrt__hbuilt {
    fogrt__med *media;           /* 0: the world's (sigma_t 0 without fog), 1: empty, then the interiors */
    bool chroma;                 /* some medium's channels differ: a path draws a hero channel */
    fogrt__boundary *bounds;
    uint32_t *mesh_bound, *sph_bound;   /* per mesh and per sphere: its boundary, or UINT32_MAX */
    uint32_t media_count, bound_count, camera_medium;
};
#define FOGRT__H_MAX_CROSSINGS 256   /* surfaces one shadow ray may pass */
#define FOGRT__H_POINTS 16           /* points of a shape tested against the others */

FOGRT__PUBLIC fogrt_result fogrt_scene_set_interior(fogrt_scene *s, fogrt_shape_kind kind, uint32_t index,
                                                   const fogrt_medium_desc *desc) {
    struct fogrt__shapes *sh;
    fogrt_medium_desc m;
    uint32_t i;
    FOGRT_ASSERT(s);
    FOGRT__REFUSE_IF((unsigned)kind >= (unsigned)FOGRT_SHAPE_NUM, INVALID_ARGUMENT, "interior: kind is not FOGRT_SHAPE_MESH or FOGRT_SHAPE_SPHERE");
    FOGRT__REFUSE_IF(index >= (kind == FOGRT_SHAPE_MESH ? s->mesh_count : s->sph_count), INVALID_ARGUMENT,
                     "interior: the scene has no mesh or sphere of that number");
    memset(&m, 0, sizeof m);
    if (desc) {
        m = *desc;
        FOGRT__REFUSE_IF(m.bounded, INVALID_MEDIUM, "interior medium.bounded: a shape's medium is bounded by the shape");
        FOGRT__PASS(fogrt__check_medium(s, &m));
    }
    if (!s->shapes) {
        s->shapes = (struct fogrt__shapes *)fogrt__alloc(&s->allocator, sizeof *s->shapes);
        if (!s->shapes) return FOGRT_RESULT_OUT_OF_MEMORY;
        memset(s->shapes, 0, sizeof *s->shapes);
    }
    sh = s->shapes;
    for (i = 0; i < sh->count && !(sh->items[i].kind == kind && sh->items[i].index == index); ++i) {}
    if (!desc) {                                         /* take it out */
        if (i < sh->count) sh->items[i] = sh->items[--sh->count];
    } else {
        if (i == sh->count && sh->count == sh->cap) {
            uint32_t cap = fogrt__grow_cap(sh->cap, sh->count + 1);
            if (!fogrt__reserve(s, (void **)&sh->items, sh->count, cap, sizeof *sh->items)) return FOGRT_RESULT_OUT_OF_MEMORY;
            sh->cap = cap;
        }
        if (i == sh->count) sh->count++;
        sh->items[i].kind = kind; sh->items[i].index = index; sh->items[i].m = m;
    }
    s->built = false;
    return FOGRT_RESULT_OK;
}
FOGRT__PRIVATE void fogrt__shapes_free(fogrt_scene *s) {
    if (!s->shapes) return;
    fogrt__free(&s->allocator, s->shapes->items);
    fogrt__free(&s->allocator, s->shapes);
    s->shapes = NULL;
}

/* The triangles of mesh j: tri_mesh grows with the triangle index, so a binary search. */
FOGRT__PRIVATE uint32_t fogrt__mesh_first(const fogrt_scene *s, uint32_t j) {
    uint32_t lo = 0, hi = s->tri_count;
    while (lo < hi) { uint32_t mid = lo + (hi - lo) / 2; if (s->tri_mesh[mid] < j) lo = mid + 1; else hi = mid; }
    return lo;
}
FOGRT__PUBLIC fogrt_result fogrt_scene_set_shape_material(fogrt_scene *s, fogrt_shape_kind kind, uint32_t index,
                                                         uint32_t material) {
    uint32_t t, end;
    FOGRT_ASSERT(s);
    FOGRT__REFUSE_IF((unsigned)kind >= (unsigned)FOGRT_SHAPE_NUM, INVALID_ARGUMENT, "shape material: kind is not FOGRT_SHAPE_MESH or FOGRT_SHAPE_SPHERE");
    FOGRT__REFUSE_IF(index >= (kind == FOGRT_SHAPE_MESH ? s->mesh_count : s->sph_count), INVALID_ARGUMENT,
                     "shape material: the scene has no mesh or sphere of that number");
    FOGRT__REFUSE_IF(material >= s->material_count, INVALID_MATERIAL, "shape material: material id out of range");
    if (kind == FOGRT_SHAPE_SPHERE) {
        s->sph_material[index] = material;
    } else {
        end = fogrt__mesh_first(s, index + 1);
        for (t = fogrt__mesh_first(s, index); t < end; ++t) s->tri_material[t] = material;
    }
    s->built = false;
    return FOGRT_RESULT_OK;
}
FOGRT__PRIVATE bool fogrt__transmits(const fogrt_scene *s, uint32_t material) {
    return fogrt__bsdf_type(&s->materials[material]) >= FOGRT_BSDF_REFRACTION;
}

/* Closed: every edge of the mesh's triangles (by its two end points, exactly) is shared by
   an even number of them. An edge is kept as its two points in increasing order. */
typedef struct fogrt__edge { float p[6]; } fogrt__edge;
FOGRT__PRIVATE int fogrt__floats_cmp(const float *p, const float *q, int n) {
    int i;
    for (i = 0; i < n; ++i) if (p[i] != q[i]) return p[i] < q[i] ? -1 : 1;
    return 0;
}
FOGRT__PRIVATE int fogrt__edge_cmp(const void *x, const void *y) {
    return fogrt__floats_cmp(((const fogrt__edge *)x)->p, ((const fogrt__edge *)y)->p, 6);
}
FOGRT__PRIVATE bool fogrt__edge_of(const fogrt_scene *s, uint32_t t, uint32_t k, fogrt__edge *e) {
    fogrt__v3 p = s->tri_v[3 * t + k], q = s->tri_v[3 * t + (k + 1) % 3];
    float a[3], b[3];
    int c;
    a[0] = p.x; a[1] = p.y; a[2] = p.z; b[0] = q.x; b[1] = q.y; b[2] = q.z;
    if ((c = fogrt__floats_cmp(a, b, 3)) == 0) return false;   /* a degenerate triangle's edge */
    memcpy(e->p, c < 0 ? a : b, sizeof a);
    memcpy(e->p + 3, c < 0 ? b : a, sizeof a);
    return true;
}
FOGRT__PRIVATE int fogrt__mesh_closed(const fogrt_scene *s, uint32_t first, uint32_t end) {   /* -1: out of memory */
    fogrt__edge *e = (fogrt__edge *)fogrt__alloc(&s->allocator, sizeof(fogrt__edge) * (3 * (size_t)(end - first) + 1));
    size_t n = 0, i, k;
    uint32_t t;
    if (!e) return -1;
    for (t = first; t < end; ++t)
        for (k = 0; k < 3; ++k) n += fogrt__edge_of(s, t, (uint32_t)k, &e[n]);
    qsort(e, n, sizeof *e, fogrt__edge_cmp);
    for (i = 0; i < n; i = k) {
        for (k = i + 1; k < n && fogrt__edge_cmp(&e[i], &e[k]) == 0; ++k) {}
        if ((k - i) % 2) break;
    }
    fogrt__free(&s->allocator, e);
    return i >= n;
}

/* Whether boundary b (closed) holds point p: inside a sphere, or an odd number of the
   mesh's triangles crossed by a ray from p in a direction no axis-aligned or diagonal
   surface holds. */
FOGRT__PRIVATE bool fogrt__holds(const fogrt_scene *s, const fogrt__boundary *b, fogrt__v3 p) {
    const fogrt__v3 d = { 0.5772f, 0.5774f, 0.5776f };
    uint32_t t, end, crossings = 0;
    if (b->kind == FOGRT_SHAPE_SPHERE) {
        fogrt__v3 pc = fogrt__sub(p, s->sph_c[b->index]);
        return fogrt__dot(pc, pc) < s->sph_r[b->index] * s->sph_r[b->index];
    }
    end = fogrt__mesh_first(s, b->index + 1);
    for (t = fogrt__mesh_first(s, b->index); t < end; ++t) {
        const fogrt__v3 *v = &s->tri_v[3 * t];
        float th, u, w;
        crossings += fogrt__hit_triangle(p, d, v[0], fogrt__sub(v[1], v[0]), fogrt__sub(v[2], v[0]), 0.0f, INFINITY, &th, &u, &w);
    }
    return crossings % 2 == 1;
}
/* Point i of FOGRT__H_POINTS on boundary b's surface: a triangle's centroid, spread over the
   mesh, or a point of the sphere. */
FOGRT__PRIVATE fogrt__v3 fogrt__shape_point(const fogrt_scene *s, const fogrt__boundary *b, uint32_t i) {
    if (b->kind == FOGRT_SHAPE_SPHERE) {
        fogrt__v3 d = fogrt_sample_uniform_sphere(((float)i + 0.5f) / FOGRT__H_POINTS, (float)(i * 7 % FOGRT__H_POINTS) / FOGRT__H_POINTS);
        return fogrt__madd(s->sph_c[b->index], d, s->sph_r[b->index]);
    } else {
        uint32_t first = fogrt__mesh_first(s, b->index), n = fogrt__mesh_first(s, b->index + 1) - first;
        const fogrt__v3 *v = &s->tri_v[3 * (first + (uint32_t)((uint64_t)i * n / FOGRT__H_POINTS))];
        return fogrt__scale(fogrt__add(v[0], fogrt__add(v[1], v[2])), 1.0f / 3.0f);
    }
}
FOGRT__PRIVATE float fogrt__box_volume(const fogrt__aabb *b) {
    fogrt__v3 e = fogrt__sub(b->hi, b->lo);
    return e.x * e.y * e.z;
}
/* The innermost closed boundary other than `except` that holds p, or UINT32_MAX. */
FOGRT__PRIVATE uint32_t fogrt__innermost(const fogrt_scene *s, const fogrt__boundary *B, uint32_t n, fogrt__v3 p, uint32_t except) {
    uint32_t j, best = UINT32_MAX;
    for (j = 0; j < n; ++j)
        if (j != except && B[j].closed && fogrt__holds(s, &B[j], p) &&
            (best == UINT32_MAX || fogrt__box_volume(&B[j].box) < fogrt__box_volume(&B[best].box)))
            best = j;
    return best;
}

/* "<prefix>mesh 3<suffix>": a message naming a shape, without stdio. */
FOGRT__PRIVATE const char *fogrt__shape_msg(char *buf, const char *prefix, const fogrt__boundary *b, const char *suffix) {
    char num[12];
    int n = 0;
    uint32_t v = b->index;
    do { num[n++] = (char)('0' + v % 10); v /= 10; } while (v);
    buf[0] = '\0';
    strncat(buf, prefix, 80);
    strcat(buf, b->kind == FOGRT_SHAPE_MESH ? "mesh " : "sphere ");
    while (n) { size_t l = strlen(buf); buf[l] = num[--n]; buf[l + 1] = '\0'; }
    strncat(buf, suffix, 150);
    return buf;
}
/* Whether the scene has media inside shapes: an interior, or an interface material. */
FOGRT__PRIVATE bool fogrt__shapes_wanted(const fogrt_scene *s) {
    uint32_t i;
    if (s->shapes && s->shapes->count) return true;
    for (i = 0; i < s->material_count && fogrt__bsdf_type(&s->materials[i]) != FOGRT_BSDF_INTERFACE; ++i) {}
    return i < s->material_count;
}
/* Boundary k's fields from the shape: its interior, material, box and closedness. */
FOGRT__PRIVATE int fogrt__boundary_set(const fogrt_scene *s, fogrt__boundary *b, fogrt_shape_kind kind, uint32_t index) {
    const struct fogrt__shapes *sh = s->shapes;
    uint32_t i, first, end;
    b->kind = kind; b->index = index; b->declared = -1; b->holder = UINT32_MAX;
    for (i = 0; sh && i < sh->count; ++i)
        if (sh->items[i].kind == kind && sh->items[i].index == index) b->declared = (int)(2 + i);
    if (kind == FOGRT_SHAPE_SPHERE) {
        fogrt__v3 r = fogrt__v(s->sph_r[index], s->sph_r[index], s->sph_r[index]);
        b->box.lo = fogrt__sub(s->sph_c[index], r); b->box.hi = fogrt__add(s->sph_c[index], r);
        b->interface = fogrt__bsdf_type(&s->materials[s->sph_material[index]]) == FOGRT_BSDF_INTERFACE;
        b->closed = true;
        return 1;
    }
    first = fogrt__mesh_first(s, index); end = fogrt__mesh_first(s, index + 1);
    b->box = fogrt__aabb_empty(); b->interface = false;
    for (i = first; i < end; ++i) {
        fogrt__aabb t = fogrt__prim_box(s, i);
        fogrt__aabb_union(&b->box, &t);
        b->interface |= fogrt__bsdf_type(&s->materials[s->tri_material[i]]) == FOGRT_BSDF_INTERFACE;
    }
    i = (uint32_t)fogrt__mesh_closed(s, first, end);
    b->closed = i == 1;
    return (int)i;   /* -1: out of memory */
}
/* Which meshes and spheres are boundaries: an interior, or a refractive or interface material. */
FOGRT__PRIVATE uint8_t *fogrt__boundary_marks(const fogrt_scene *s) {
    uint8_t *mark = (uint8_t *)fogrt__alloc(&s->allocator, (size_t)s->mesh_count + s->sph_count + 1);
    uint32_t i;
    if (!mark) return NULL;
    memset(mark, 0, (size_t)s->mesh_count + s->sph_count + 1);
    for (i = 0; i < s->tri_count; ++i) mark[s->tri_mesh[i]] |= fogrt__transmits(s, s->tri_material[i]);
    for (i = 0; i < s->sph_count; ++i) mark[s->mesh_count + i] = fogrt__transmits(s, s->sph_material[i]);
    for (i = 0; s->shapes && i < s->shapes->count; ++i)
        mark[(s->shapes->items[i].kind == FOGRT_SHAPE_SPHERE ? s->mesh_count : 0) + s->shapes->items[i].index] = 1;
    return mark;
}
/* The innermost boundary that holds boundary k, the same from every point of k's surface:
   else the two overlap. */
FOGRT__PRIVATE fogrt_result fogrt__find_holder(const fogrt_scene *s, fogrt__boundary *B, uint32_t n, uint32_t k) {
    char msg[256], buf[128];
    uint32_t i, h;
    B[k].holder = fogrt__innermost(s, B, n, fogrt__shape_point(s, &B[k], 0), k);
    for (i = 1; i < FOGRT__H_POINTS; ++i) {
        if ((h = fogrt__innermost(s, B, n, fogrt__shape_point(s, &B[k], i), k)) == B[k].holder) continue;
        h = h == UINT32_MAX ? B[k].holder : h;
        fogrt__shape_msg(buf, " and ", &B[h], " overlap: media inside shapes must nest (one inside the other) or lie apart");
        return fogrt__fail(s, FOGRT_RESULT_INVALID_GEOMETRY, fogrt__shape_msg(msg, "media inside shapes: ", &B[k], buf));
    }
    return FOGRT_RESULT_OK;
}
/* Every boundary of the scene, closed or not, with its holder; refuses a medium on an open
   mesh and overlapping media. *out (count *n) is the caller's to free. */
FOGRT__PRIVATE fogrt_result fogrt__find_boundaries(const fogrt_scene *s, fogrt__boundary **out, uint32_t *n_out) {
    uint8_t *mark = fogrt__boundary_marks(s);
    fogrt__boundary *B;
    uint32_t i, n = 0, total = s->mesh_count + s->sph_count;
    char msg[256];
    fogrt_result r = FOGRT_RESULT_OK;
    *out = NULL; *n_out = 0;
    if (!mark) return FOGRT_RESULT_OUT_OF_MEMORY;
    for (i = 0; i < total; ++i) n += mark[i];
    B = (fogrt__boundary *)fogrt__alloc(&s->allocator, sizeof *B * (n + 1));
    for (i = 0, n = 0; B && i < total && r == FOGRT_RESULT_OK; ++i) {
        fogrt__boundary *b = &B[n];
        int c;
        if (!mark[i]) continue;
        c = fogrt__boundary_set(s, b, i < s->mesh_count ? FOGRT_SHAPE_MESH : FOGRT_SHAPE_SPHERE, i < s->mesh_count ? i : i - s->mesh_count);
        if (c < 0) r = FOGRT_RESULT_OUT_OF_MEMORY;
        else if (b->declared >= 0 && !b->closed)
            r = fogrt__fail(s, FOGRT_RESULT_INVALID_GEOMETRY, fogrt__shape_msg(msg, "interior of ", b, ": the mesh has an open edge (a medium needs a closed surface)"));
        ++n;
    }
    for (i = 0; B && i < n && r == FOGRT_RESULT_OK; ++i) r = fogrt__find_holder(s, B, n, i);
    fogrt__free(&s->allocator, mark);
    if (!B) return FOGRT_RESULT_OUT_OF_MEMORY;
    if (r != FOGRT_RESULT_OK) { fogrt__free(&s->allocator, B); return r; }
    *out = B; *n_out = n;
    return FOGRT_RESULT_OK;
}
/* The build's check (before anything is built, so that a refused scene stays as it was). */
FOGRT__PRIVATE fogrt_result fogrt__shapes_check(const fogrt_scene *s) {
    fogrt__boundary *B;
    uint32_t n;
    fogrt_result r;
    if (!fogrt__shapes_wanted(s)) return FOGRT_RESULT_OK;
    if ((r = fogrt__find_boundaries(s, &B, &n)) == FOGRT_RESULT_OK) fogrt__free(&s->allocator, B);
    return r;
}
/* The media and the two media of every boundary, innermost last: a boundary's outside is
   its holder's inside (or the world's), its inside its own medium, else its outside (an
   interface: invisible) or nothing (a refractive shape: empty inside, as in Part I). */
FOGRT__PRIVATE void fogrt__resolve_media(struct fogrt__hbuilt *h) {
    uint32_t k, pass;
    for (pass = 0; pass <= h->bound_count; ++pass)          /* the holders' first: depth passes */
        for (k = 0; k < h->bound_count; ++k) {
            fogrt__boundary *b = &h->bounds[k];
            b->outside = b->holder == UINT32_MAX ? 0u : h->bounds[b->holder].inside;
            b->inside = b->declared >= 0 ? (uint32_t)b->declared : (b->interface ? b->outside : 1u);
        }
}
FOGRT__PRIVATE void fogrt__shapes_release(fogrt_scene *s) {
    struct fogrt__hbuilt *h = s->x->h;
    if (!h) return;
    fogrt__free(&s->allocator, h->media);
    fogrt__free(&s->allocator, h->bounds);
    fogrt__free(&s->allocator, h->mesh_bound); fogrt__free(&s->allocator, h->sph_bound);
    fogrt__free(&s->allocator, h);
    s->x->h = NULL;
}
/* A medium inside a shape whose surface lets no ray through (it neither refracts nor is an
   interface) is never seen: one warning saying what to do. */
FOGRT__PRIVATE void fogrt__warn_unseen(const fogrt_scene *s, const fogrt__boundary *b) {
    char msg[256];
    bool through = false;
    if (b->declared < 0) return;
    if (b->kind == FOGRT_SHAPE_SPHERE) {
        through = fogrt__transmits(s, s->sph_material[b->index]);
    } else {
        uint32_t end = fogrt__mesh_first(s, b->index + 1);
        for (uint32_t t = fogrt__mesh_first(s, b->index); t < end && !through; ++t)
            through = fogrt__transmits(s, s->tri_material[t]);
    }
    if (through) return;
    fogrt__log(s, FOGRT_LOG_WARNING, fogrt__shape_msg(msg, "the medium inside ", b,
               " cannot be seen: its surface is opaque, so no ray enters it; give it a refractive"
               " material or make it an interface (fogrt's --interface)"));
}
/* H's tables (x->h stays NULL for a scene without media inside shapes). False: out of memory. */
FOGRT__PRIVATE bool fogrt__shapes_build(fogrt_scene *s) {
    struct fogrt__hbuilt *h;
    uint32_t i, b, nm = 2 + (s->shapes ? s->shapes->count : 0);
    fogrt__camera cam;
    if (!fogrt__shapes_wanted(s)) return true;
    h = s->x->h = (struct fogrt__hbuilt *)fogrt__alloc(&s->allocator, sizeof *h);
    if (!h) return false;
    memset(h, 0, sizeof *h);
    h->media = (fogrt__med *)fogrt__alloc(&s->allocator, sizeof *h->media * nm);
    h->mesh_bound = (uint32_t *)fogrt__alloc(&s->allocator, sizeof(uint32_t) * ((size_t)s->mesh_count + 1));
    h->sph_bound = (uint32_t *)fogrt__alloc(&s->allocator, sizeof(uint32_t) * ((size_t)s->sph_count + 1));
    if (!h->media || !h->mesh_bound || !h->sph_bound ||
        fogrt__find_boundaries(s, &h->bounds, &h->bound_count) != FOGRT_RESULT_OK) return false;
    h->media_count = nm;
    memset(h->media, 0, sizeof *h->media * 2);
    h->media[0] = s->x->world;                          /* the world's fog, bounded by C's box */
    for (i = 2; i < nm; ++i) fogrt__med_set(&h->media[i], &s->shapes->items[i - 2].m, false);
    for (i = 0; i < nm; ++i) h->chroma |= h->media[i].chroma;
    for (i = 0; i < s->mesh_count; ++i) h->mesh_bound[i] = UINT32_MAX;
    for (i = 0; i < s->sph_count; ++i) h->sph_bound[i] = UINT32_MAX;
    for (b = 0; b < h->bound_count; ++b)
        *(h->bounds[b].kind == FOGRT_SHAPE_MESH ? &h->mesh_bound[h->bounds[b].index] : &h->sph_bound[h->bounds[b].index]) = b;
    fogrt__resolve_media(h);
    for (b = 0; b < h->bound_count; ++b) fogrt__warn_unseen(s, &h->bounds[b]);
    cam = fogrt__camera_setup(s, 1, 1);                 /* where the camera is: its medium */
    b = fogrt__innermost(s, h->bounds, h->bound_count, cam.pos, UINT32_MAX);
    h->camera_medium = b == UINT32_MAX ? 0u : h->bounds[b].inside;
    return true;
}

/* The medium on the other side of primitive prim's surface, from medium med. */
FOGRT__PRIVATE uint32_t fogrt__h_cross(const fogrt_scene *s, uint32_t prim, uint32_t med) {
    const struct fogrt__hbuilt *h = s->x->h;
    uint32_t b = prim < s->tri_count ? h->mesh_bound[s->tri_mesh[prim]] : h->sph_bound[prim - s->tri_count];
    if (b == UINT32_MAX) return med;
    return med == h->bounds[b].inside ? h->bounds[b].outside : h->bounds[b].inside;
}
FOGRT__PRIVATE bool fogrt__is_interface(const fogrt_scene *s, uint32_t prim) {
    return fogrt__bsdf_type(&s->materials[fogrt_scene_get_prim_material(s, prim)]) == FOGRT_BSDF_INTERFACE;
}
/* The transmittance (eq. 8), per channel, of medium k along o + t d for t in [0, len]: the
   world's fog only where its box is (C). */
FOGRT__PRIVATE fogrt__v3 fogrt__h_tr(const fogrt_scene *s, uint32_t k, fogrt__v3 o, fogrt__v3 d, float len) {
    const fogrt__med *m = &s->x->h->media[k];
    float a, b;
    if (!fogrt__med_span(s, m, o, d, len, &a, &b)) return fogrt__v(1.0f, 1.0f, 1.0f);
    fogrt__v3 c = m->sigma;
    return fogrt__v(fogrt_transmittance(c.x, b - a), fogrt_transmittance(c.y, b - a), fogrt_transmittance(c.z, b - a));
}
/* Lines 7 and 10 through media: whether the light sample is visible from the vertex (in
   medium med), times the transmittance of each medium on the way; interface surfaces let the
   shadow ray through (into the medium on their other side), every other surface stops it. */
FOGRT__PRIVATE fogrt__v3 fogrt__h_shadow(const fogrt_scene *s, const fogrt__vertex *v, uint32_t med,
                                         const fogrt_light_sample *ls, uint64_t *rays) {
    fogrt__v3 o = v->is_medium ? v->p : fogrt__offset(s, v->p, v->ng, ls->wi);
    fogrt__v3 T = fogrt__v(1.0f, 1.0f, 1.0f);
    bool far = !(ls->dist < INFINITY);                   /* toward the environment */
    fogrt__v3 y = far ? fogrt__v(0.0f, 0.0f, 0.0f) : fogrt__madd(v->p, ls->wi, ls->dist);
    for (int k = 0; k < FOGRT__H_MAX_CROSSINGS && fogrt__max3(T) > 0.0f; ++k) {
        fogrt_hit hit;
        fogrt__v3 dir = ls->wi, p, ng, ns;
        float len = INFINITY, tmax = INFINITY;
        if (!far) {
            fogrt__v3 to = fogrt__sub(y, o);
            len = fogrt__length(to);
            tmax = len - fogrt__offset_size(s, y);
            dir = fogrt__scale(to, 1.0f / len);
        }
        ++*rays;
        if (!(tmax > 0.0f) || !fogrt__traverse(s, o, dir, 0.0f, tmax, &hit, false))
            return fogrt__mul(T, fogrt__h_tr(s, med, o, dir, len));
        if (!fogrt__is_interface(s, hit.prim)) break;
        T = fogrt__mul(T, fogrt__h_tr(s, med, o, dir, hit.t));
        med = fogrt__h_cross(s, hit.prim, med);
        fogrt__surface_frame(s, o, dir, &hit, &p, &ng, &ns);
        o = fogrt__offset(s, p, ng, dir);
    }
    return fogrt__v(0.0f, 0.0f, 0.0f);
}
/* The path now travels in medium med. */
FOGRT__PRIVATE void fogrt__h_enter(const fogrt_scene *s, fogrt__path *P, uint32_t med) {
    P->med = med;
    P->m = &s->x->h->media[med];
    P->w.in_fog = fogrt__max3(P->m->sigma) > 0.0f;
}
/* A path's start: the medium the camera is in; G's steps for every medium (another phase,
   emission, sigma_t per channel), with a hero channel where some medium is chromatic. */
FOGRT__PRIVATE void fogrt__h_start(const fogrt_scene *s, fogrt__path *P) {
    const struct fogrt__hbuilt *h = s->x->h;
    fogrt__h_enter(s, P, h->camera_medium);
    P->media_light = true;                               /* shadow rays through the media */
    if (h->chroma) {
        int hero = (int)(3.0f * fogrt_rng_float(P->w.rng));
        P->chroma = true;
        P->hero = FOGRT__MIN(hero, 2);
        P->r = fogrt__v(1.0f, 1.0f, 1.0f);
    }
}
/* The surface the ray reached at p (primitive prim, material m): the vertex's surface (a
   refraction from it crosses it), or an interface, which the ray passes into the medium on
   its other side without a vertex (returns true). */
FOGRT__PRIVATE bool fogrt__h_boundary(const fogrt_scene *s, fogrt__path *P, uint32_t prim,
                                      const fogrt_material_desc *m, fogrt__v3 p, fogrt__v3 ng) {
    P->prim = prim;
    if (fogrt__bsdf_type(m) != FOGRT_BSDF_INTERFACE) return false;
    fogrt__h_enter(s, P, fogrt__h_cross(s, prim, P->med));
    P->w.o = fogrt__offset(s, p, ng, P->w.d);
    P->crossed = true;
    return true;
}
/* Lines 3-5, 8, 14, 18 through media inside shapes: E's next event (G's steps) in the
   medium the ray is in, again past each interface the ray crosses, until a vertex. */
FOGRT__PRIVATE bool fogrt__h_next_event(const fogrt_scene *s, const fogrt__settings *st, fogrt__path *P, int limit) {
    for (int k = 0; k < FOGRT__H_MAX_CROSSINGS; ++k) {
        P->crossed = false;
        if (!fogrt__media_next_event(s, st, P, limit)) return false;
        if (!P->crossed) return true;
    }
    return false;
}
#endif /* FOGRT_NO_SHAPES */

#ifndef FOGRT_NO_MICROFACET
/* ------------------------------------------------------------------------------------------
   I. Rough metals
   What it adds: FOGRT_BSDF_MICROFACET, the rough conductor of CS184's assignment 3-2. The
   surface is made of tiny mirrors whose normals h follow Beckmann's distribution of width
   alpha (the rms slope of the surface),
       D(h) = exp(-tan^2 theta_h / alpha^2) / (pi alpha^2 cos^4 theta_h),
   which hide one another as Smith's model of that distribution says (height-correlated),
       G(wo, wi) = 1 / (1 + Lambda(wo) + Lambda(wi)),
       Lambda(w) = (exp(-a^2) / (a sqrt(pi)) - erfc(a)) / 2,   a = 1 / (alpha tan theta),
   and reflect as a metal of complex index eta + i k per colour channel (F, the conductor's
   Fresnel reflectance at the angle between wo and h):
       f(wo, wi) = F G D / (4 |cos theta_o| |cos theta_i|),   h = normalize(wo + wi).
   It is sampled by importance: a normal h drawn from D(h) cos theta_h (tan^2 theta_h =
   -alpha^2 ln(1 - u1), phi = 2 pi u2), and wi = wo mirrored about h. The mirroring's
   Jacobian makes the density over wi D cos theta_h / (4 wo.h); the weight f cos / pdf =
   F G wo.h / (cos theta_o cos theta_h) has no D, so it stays near F as alpha -> 0, where
   the lobe closes on the mirror direction. A normal facing away from wo, or a wi below the
   surface, gives no sample: the density over the directions that remain integrates to
   less than 1 by just that share, so the estimate stays unbiased. Light sampling and MIS
   take eval and pdf as they take diffuse's. Like diffuse and mirror it reflects on both
   sides (wo.z < 0 mirrors the lobe), which the enum's order tells Part I.
   The formulas are evaluated in float with the cases where a term would overflow or divide
   by zero (grazing directions, alpha -> 0, eta = k = 0) taken first; alpha is used clamped
   to [1e-4, 1e3], eta and k to at most 1e4.
   What it costs: a scene without a rough metal pays a compare per BSDF sample, and per
   eval or pdf of a type other than diffuse (seam 5), which FOGRT_NO_MICROFACET removes:
   +0.06% instructions in a fog-filled box with diffuse and mirror spheres, +0.13% in the
   default scene (make callgrind; docs/benchmarks.md, "Strip cost"). The images are the
   same bit for bit.
   ------------------------------------------------------------------------------------------ */
#define FOGRT__MF_ALPHA_MIN 1e-4f
#define FOGRT__MF_ALPHA_MAX 1e3f
#define FOGRT__MF_INDEX_MAX 1e4f
#define FOGRT__INV_SQRT_PI 0.56418958354775628695f

/* Refuses what the formulas cannot take: alpha not above 0, a negative or infinite index. */
FOGRT__PRIVATE fogrt_result fogrt__mf_check(const fogrt_scene *s, const fogrt_material_desc *m) {
    FOGRT__REFUSE_IF(!(m->alpha > 0.0f) || !fogrt__finite(m->alpha), INVALID_MATERIAL,
                     "material.alpha: a microfacet material needs a finite Beckmann width > 0");
    FOGRT__REFUSE_IF(!fogrt__colour_ok(m->eta) || !fogrt__colour_ok(m->k), INVALID_MATERIAL,
                     "material.eta/k: negative or not finite");
    return FOGRT_RESULT_OK;
}
FOGRT__PRIVATE float fogrt__mf_alpha(const fogrt_material_desc *m) {
    float a = m->alpha;   /* NaN, from a desc that never went through the checks: the smallest */
    return a >= FOGRT__MF_ALPHA_MIN ? (a <= FOGRT__MF_ALPHA_MAX ? a : FOGRT__MF_ALPHA_MAX) : FOGRT__MF_ALPHA_MIN;
}
/* Beckmann's D at the unit normal h (h.z > 0). tan^2 theta_h comes from h.x and h.y, not
   from 1 - h.z^2, which loses the digits that a small alpha magnifies. Where exp underflows
   D is 0, which also keeps h.z^4 away from underflow (h.z^2 > 1e-8 there for every alpha
   allowed). */
FOGRT__PRIVATE float fogrt__mf_d(float alpha, fogrt__v3 h) {
    float a2 = alpha * alpha, c2 = h.z * h.z, e;
    if (!(c2 > 0.0f)) return 0.0f;
    e = expf(-(h.x * h.x + h.y * h.y) / (c2 * a2));
    return e > 0.0f ? e / (FOGRT__PI * a2 * c2 * c2) : 0.0f;
}
/* Smith's Lambda for Beckmann at the unit direction w (w.z > 0). Beyond a = 6 it is below
   1e-17 (nothing hides a direction that steep); a grazing direction is all hidden. */
FOGRT__PRIVATE float fogrt__mf_lambda(float alpha, fogrt__v3 w) {
    float s2 = w.x * w.x + w.y * w.y, a;
    if (!(s2 > 0.0f)) return 0.0f;
    a = w.z / (alpha * sqrtf(s2));
    if (a > 6.0f) return 0.0f;
    if (!(a > 1e-30f)) return 1e30f;
    return 0.5f * (expf(-a * a) * FOGRT__INV_SQRT_PI / a - erfcf(a));
}
/* Smith's shadowing-masking G of the pair, height-correlated (one Lambda each). */
FOGRT__PRIVATE float fogrt__mf_g(float alpha, fogrt__v3 wo, fogrt__v3 wi) {
    return 1.0f / (1.0f + fogrt__mf_lambda(alpha, wo) + fogrt__mf_lambda(alpha, wi));
}
/* The unpolarised Fresnel reflectance of a conductor eta + i k at cos theta = c in [0, 1]:
   the mean of the s and p reflectances. With a + i b = sqrt((eta + i k)^2 - sin^2 theta),
       Rs = ((a - c)^2 + b^2) / ((a + c)^2 + b^2),
       Rp = Rs ((a c - s^2)^2 + b^2 c^2) / ((a c + s^2)^2 + b^2 c^2),
   written as sums of squares so that a nearly index-matched metal (eta near 1, k = 0),
   whose F is tiny, keeps its digits and its reciprocity. At normal incidence Rp = Rs (0/0
   when eta = k = 0, where F = 1). */
FOGRT__PRIVATE float fogrt__mf_fresnel1(float eta, float k, float c) {
    float s2, t0, ab2, a, b2, rs, rp_n, rp_d;
    eta = eta <= FOGRT__MF_INDEX_MAX ? eta : FOGRT__MF_INDEX_MAX;
    k = k <= FOGRT__MF_INDEX_MAX ? k : FOGRT__MF_INDEX_MAX;
    c = FOGRT__CLAMP(c, 0.0f, 1.0f);
    s2 = (1.0f - c) * (1.0f + c);
    t0 = eta * eta - k * k - s2;                         /* a^2 - b^2 */
    ab2 = sqrtf(t0 * t0 + 4.0f * eta * eta * k * k);     /* a^2 + b^2 */
    a = sqrtf(FOGRT__MAX(0.0f, 0.5f * (ab2 + t0)));
    b2 = FOGRT__MAX(0.0f, 0.5f * (ab2 - t0));
    rs = ((a - c) * (a - c) + b2) / ((a + c) * (a + c) + b2);   /* > 0: a + c > 0 or b2 >= s2 > 0 */
    rp_n = (a * c - s2) * (a * c - s2) + b2 * c * c;
    rp_d = (a * c + s2) * (a * c + s2) + b2 * c * c;
    return FOGRT__CLAMP(0.5f * (rs + (rp_d > 0.0f ? rs * rp_n / rp_d : rs)), 0.0f, 1.0f);
}
FOGRT__PRIVATE fogrt__v3 fogrt__mf_fresnel(const fogrt_material_desc *m, float c) {
    return fogrt__v(fogrt__mf_fresnel1(m->eta.x, m->k.x, c), fogrt__mf_fresnel1(m->eta.y, m->k.y, c),
                    fogrt__mf_fresnel1(m->eta.z, m->k.z, c));
}
/* The half vector of wo and wi turned to +z (both on one side: wo.z wi.z > 0), with both
   directions turned alike. False if there is none. */
FOGRT__PRIVATE bool fogrt__mf_half(fogrt__v3 *wo, fogrt__v3 *wi, fogrt__v3 *h) {
    float len2;
    if (!(wo->z * wi->z > 0.0f)) return false;
    if (wo->z < 0.0f) { wo->z = -wo->z; wi->z = -wi->z; }
    *h = fogrt__add(*wo, *wi);
    len2 = fogrt__dot(*h, *h);
    if (!(len2 > 0.0f)) return false;
    *h = fogrt__scale(*h, 1.0f / sqrtf(len2));
    return true;
}
FOGRT__PRIVATE fogrt_vec3 fogrt__mf_eval(const fogrt_material_desc *m, fogrt_vec3 wo, fogrt_vec3 wi) {
    float alpha = fogrt__mf_alpha(m), d, g, s;
    fogrt__v3 h;
    if (!fogrt__mf_half(&wo, &wi, &h)) return fogrt__v(0.0f, 0.0f, 0.0f);
    d = fogrt__mf_d(alpha, h);
    g = fogrt__mf_g(alpha, wo, wi);
    if (!(d > 0.0f) || !(g > 0.0f)) return fogrt__v(0.0f, 0.0f, 0.0f);
    s = d * g / (4.0f * wo.z * wi.z);
    return fogrt__scale(fogrt__mf_fresnel(m, fogrt__dot(wo, h)), s < 1e30f ? s : 1e30f);   /* grazing both ways */
}
FOGRT__PRIVATE float fogrt__mf_pdf(const fogrt_material_desc *m, fogrt_vec3 wo, fogrt_vec3 wi) {
    fogrt__v3 h;
    float oh, p;
    if (!fogrt__mf_half(&wo, &wi, &h)) return 0.0f;
    oh = fogrt__dot(wo, h);                              /* > 0: wo and wi on one side */
    if (!(oh > 0.0f)) return 0.0f;
    p = fogrt__mf_d(fogrt__mf_alpha(m), h) * h.z / (4.0f * oh);
    return p < 1e30f ? p : 1e30f;
}
FOGRT__PRIVATE bool fogrt__mf_sample(const fogrt_material_desc *m, fogrt_vec3 wo, float u1, float u2,
                                       fogrt_bsdf_sample *out) {
    float alpha = fogrt__mf_alpha(m), side = wo.z < 0.0f ? -1.0f : 1.0f;
    float t2 = -alpha * alpha * log1pf(-u1), c = 1.0f / sqrtf(1.0f + t2), s = sqrtf(t2 / (1.0f + t2));
    float phi = 2.0f * FOGRT__PI * u2, oh, g;
    fogrt__v3 h = fogrt__v(s * cosf(phi), s * sinf(phi), c), wi;
    wo.z *= side;
    oh = fogrt__dot(wo, h);
    if (!(oh > 0.0f)) return false;                      /* a facet that wo sees from behind */
    wi = fogrt__sub(fogrt__scale(h, 2.0f * oh), wo);
    if (!(wi.z > 0.0f)) return false;                    /* reflected into the surface */
    g = fogrt__mf_g(alpha, wo, wi);
    out->weight = fogrt__scale(fogrt__mf_fresnel(m, oh), g / wo.z * (oh / c));   /* F G wo.h / (cos_o cos_h) */
    wo.z *= side; wi.z *= side;
    out->wi = wi;
    out->pdf = fogrt__mf_pdf(m, wo, wi);               /* as MIS will evaluate it */
    return out->pdf > 0.0f;
}
#endif /* FOGRT_NO_MICROFACET */

/* SEAM 4: what Part II's calls set on the scene, freed with it (C's map, H's media). */
FOGRT__PRIVATE void fogrt__appendix_scene_free(fogrt_scene *s) {
#ifndef FOGRT_NO_ESTIMATION
    fogrt__env_map_free(s);
#endif
#ifndef FOGRT_NO_SHAPES
    fogrt__shapes_free(s);
#endif
    (void)s;
}
#endif /* FOGRT_MINIMAL */

/* ==========================================================================================

      AFTER BOTH PARTS: THE API AROUND THE METHOD

   What every build has besides the method itself, FOGRT_MINIMAL too: the full build's preset,
   result names, the image's storage, the scene's getters, the public building blocks of an
   integrator, 8-bit output, and the checks of what a build left out. None of it is the
   method, and Part I calls few of these functions (a primitive's material, the preset a NULL
   desc means, and the fogrt__beyond_* checks); they stand here so that Part I reads as the
   method alone.
   ========================================================================================== */
/* The full build's preset, the names of result codes, and the image's storage. */
/* Part II's defaults: lamps in fog (B) on, as far as the build has them. */
FOGRT__PUBLIC fogrt_render_desc fogrt_render_defaults(void) {
    fogrt_render_desc d = fogrt_render_paper_defaults();
#ifndef FOGRT_NO_LAMPS_IN_FOG
    d.equiangular = d.glow = d.footprint = d.expected_emission = true;
#endif
    return d;
}
#ifndef FOGRT_NO_MEDIUM
/* fogrt_exponential_cdf (3.1) under a second name, so that code calling that name compiles. */
FOGRT__PUBLIC float fogrt_invert_exponential(float sigma_t, float t) {
    return fogrt_exponential_cdf(sigma_t, t);
}
#endif
FOGRT__PUBLIC const char *fogrt_result_string(fogrt_result result) {
    static const char *names[FOGRT_RESULT_NUM] = {
#define FOGRT__RESULT_TEXT(name, text) text,
        FOGRT__RESULT_LIST(FOGRT__RESULT_TEXT)
#undef FOGRT__RESULT_TEXT
    };
    if ((unsigned)result >= (unsigned)FOGRT_RESULT_NUM) return "unknown result code";
    return names[result];
}
FOGRT__PUBLIC fogrt_result fogrt_image_alloc(fogrt_image *img, int width, int height, const fogrt_allocator *a) {
    FOGRT_ASSERT(img);
    memset(img, 0, sizeof *img);
    if (a) img->allocator = *a;
    if (width <= 0 || height <= 0) return FOGRT_RESULT_INVALID_ARGUMENT;
    if ((uint64_t)width * (uint64_t)height > ((uint64_t)1 << 31) / 16) return FOGRT_RESULT_TOO_LARGE;
    /* the largest array, the stream sums, must fit in a size_t (32-bit platforms) */
    if ((uint64_t)width * (uint64_t)height * (uint64_t)(sizeof(double) * FOGRT_IMAGE_STREAMS) > (uint64_t)(size_t)-1)
        return FOGRT_RESULT_TOO_LARGE;
    size_t n = (size_t)width * (size_t)height;
    img->sum = (double *)fogrt__alloc(&img->allocator, sizeof(double) * 3 * n);
    img->sum_sq = (double *)fogrt__alloc(&img->allocator, sizeof(double) * n);
    img->count = (uint32_t *)fogrt__alloc(&img->allocator, sizeof(uint32_t) * n);
    img->stream_sum = (double *)fogrt__alloc(&img->allocator, sizeof(double) * FOGRT_IMAGE_STREAMS * n);
    img->stream_count = (uint32_t *)fogrt__alloc(&img->allocator, sizeof(uint32_t) * FOGRT_IMAGE_STREAMS * n);
    if (!img->sum || !img->sum_sq || !img->count || !img->stream_sum || !img->stream_count) {
        fogrt_image_free(img);
        return FOGRT_RESULT_OUT_OF_MEMORY;
    }
    img->width = width; img->height = height;
    fogrt_image_clear(img);
    return FOGRT_RESULT_OK;
}
FOGRT__PUBLIC void fogrt_image_free(fogrt_image *img) {
    if (!img) return;
    fogrt_allocator a = img->allocator;
    fogrt__free(&a, img->sum); fogrt__free(&a, img->sum_sq); fogrt__free(&a, img->count);
    fogrt__free(&a, img->stream_sum); fogrt__free(&a, img->stream_count);
    memset(img, 0, sizeof *img);
    img->allocator = a;
}
FOGRT__PUBLIC void fogrt_image_clear(fogrt_image *img) {
    FOGRT_ASSERT(img);
    size_t n = (size_t)img->width * (size_t)img->height;
    if (img->sum) memset(img->sum, 0, sizeof(double) * 3 * n);
    if (img->sum_sq) memset(img->sum_sq, 0, sizeof(double) * n);
    if (img->count) memset(img->count, 0, sizeof(uint32_t) * n);
    if (img->stream_sum) memset(img->stream_sum, 0, sizeof(double) * FOGRT_IMAGE_STREAMS * n);
    if (img->stream_count) memset(img->stream_count, 0, sizeof(uint32_t) * FOGRT_IMAGE_STREAMS * n);
    img->rejected = 0;
    img->rated_spp = 0;
}
/* The scene's getters, and the report of what it uses. */
FOGRT__PUBLIC const char *fogrt_scene_last_error(const fogrt_scene *s) { FOGRT_ASSERT(s); return s->error; }
FOGRT__PUBLIC uint32_t fogrt_scene_get_prim_material(const fogrt_scene *s, uint32_t prim) {
    FOGRT_ASSERT(s);
    if (prim < s->tri_count) return s->tri_material[prim];
    if (prim - s->tri_count < s->sph_count) return s->sph_material[prim - s->tri_count];
    return UINT32_MAX;
}
FOGRT__PUBLIC void fogrt_scene_get_info(const fogrt_scene *s, fogrt_scene_info *info) {
    FOGRT_ASSERT(s && info);
    memset(info, 0, sizeof *info);
    info->triangle_count = s->tri_count; info->sphere_count = s->sph_count; info->mesh_count = s->mesh_count;
    info->material_count = s->material_count;
    info->light_count = s->light_count; info->area_light_count = s->area_light_count;
    info->bounds_min = s->bmin; info->bounds_max = s->bmax;
    info->has_environment = s->has_env; info->built = s->built;
}
FOGRT__PUBLIC fogrt_result fogrt_scene_get_material(const fogrt_scene *s, uint32_t id, fogrt_material_desc *out) {
    FOGRT_ASSERT(s && out);
    if (id >= s->material_count) return FOGRT_RESULT_INVALID_ARGUMENT;
    *out = s->materials[id];
    return FOGRT_RESULT_OK;
}
FOGRT__PUBLIC fogrt_result fogrt_scene_get_light(const fogrt_scene *s, uint32_t index, fogrt_light_desc *out) {
    FOGRT_ASSERT(s && out);
    if (index >= s->light_count) return FOGRT_RESULT_INVALID_ARGUMENT;
    *out = s->lights[index];
    return FOGRT_RESULT_OK;
}
FOGRT__PUBLIC void fogrt_scene_get_camera(const fogrt_scene *s, fogrt_camera_desc *out) { FOGRT_ASSERT(s && out); *out = s->camera; }
FOGRT__PUBLIC void fogrt_scene_get_medium(const fogrt_scene *s, fogrt_medium_desc *out) { FOGRT_ASSERT(s && out); *out = s->medium; }
/* Whether a primitive uses a material of this type: the materials are looked at first, so
   that a scene without one does not scan its million triangles. */
FOGRT__PRIVATE bool fogrt__material_used(const fogrt_scene *s, fogrt_bsdf_type type) {
    uint32_t i = 0;
    for (; i < s->material_count && fogrt__bsdf_type(&s->materials[i]) != type; ++i) {}
    if (i == s->material_count) return false;
    for (uint32_t t = 0; t < s->tri_count; ++t) if (fogrt__bsdf_type(&s->materials[s->tri_material[t]]) == type) return true;
    for (uint32_t k = 0; k < s->sph_count; ++k) if (fogrt__bsdf_type(&s->materials[s->sph_material[k]]) == type) return true;
    return false;
}
/* What the scene uses: the fog's bit from the build (the integrator reads it to skip every
   fog step), and the rest as a report (the code they name runs only where a primitive or
   light of that kind exists anyway: no glass, no Fresnel; no spheres, no sphere test; no
   light, no shadow ray). make callgrind measures both claims against the strip macros. */
FOGRT__PUBLIC uint32_t fogrt_scene_get_features(const fogrt_scene *s) {
    FOGRT_ASSERT(s);
    uint32_t f = s->features;
    if (!s->built) return f;
    if (fogrt__material_used(s, FOGRT_BSDF_GLASS)) f |= FOGRT_FEATURE_FRESNEL | FOGRT_FEATURE_REFRACTION;
    if (fogrt__material_used(s, FOGRT_BSDF_REFRACTION)) f |= FOGRT_FEATURE_REFRACTION;
    if (s->area_light_count) f |= FOGRT_FEATURE_AREA_LIGHTS;
    for (uint32_t i = 0; i < s->light_count; ++i) {
        f |= FOGRT_FEATURE_POINT_LIGHTS;
        if (s->lights[i].type == FOGRT_LIGHT_SPOT) f |= FOGRT_FEATURE_SPOT_LIGHTS;
    }
    if (s->has_env) f |= FOGRT_FEATURE_ENVIRONMENT;
    if (s->sph_count) f |= FOGRT_FEATURE_SPHERES;
    if (s->tri_count) f |= FOGRT_FEATURE_TRIANGLES;
    return f;
}
/* The building blocks of an integrator of one's own (the README's "your own integrator",
   docs/coursework.md): Part I's ray queries, surface vertex, offset, light pdf, shadow ray,
   camera ray and radiance, as public calls. */
FOGRT__PUBLIC bool fogrt_intersect_triangle(fogrt_vec3 v0, fogrt_vec3 v1, fogrt_vec3 v2, fogrt_vec3 o,
                                            fogrt_vec3 d, float tmin, float tmax, float *t, float *u, float *v) {
    return fogrt__hit_triangle(o, d, v0, fogrt__sub(v1, v0), fogrt__sub(v2, v0), tmin, tmax, t, u, v);
}
FOGRT__PUBLIC bool fogrt_intersect_sphere(fogrt_vec3 center, float radius, fogrt_vec3 o, fogrt_vec3 d,
                                          float tmin, float tmax, float *t) {
    return fogrt__hit_sphere(o, d, center, radius, tmin, tmax, t);
}
FOGRT__PUBLIC bool fogrt_scene_intersect(const fogrt_scene *s, fogrt_vec3 o, fogrt_vec3 d, float tmin, float tmax, fogrt_hit *hit) {
    fogrt_hit tmp;
    FOGRT_ASSERT(s);
    return fogrt__traverse(s, o, d, tmin, tmax, hit ? hit : &tmp, false);
}
FOGRT__PUBLIC bool fogrt_scene_occluded(const fogrt_scene *s, fogrt_vec3 o, fogrt_vec3 d, float tmin, float tmax) {
    fogrt_hit tmp;
    FOGRT_ASSERT(s);
    return fogrt__traverse(s, o, d, tmin, tmax, &tmp, true);
}
FOGRT__PUBLIC void fogrt_scene_surface(const fogrt_scene *s, fogrt_vec3 o, fogrt_vec3 d, const fogrt_hit *hit,
                                       fogrt_surface *out) {
    fogrt__vertex v;
    fogrt__v3 p, ng, ns;
    FOGRT_ASSERT(s && s->built && hit && out && hit->prim < s->tri_count + s->sph_count);
    fogrt__surface_frame(s, o, d, hit, &p, &ng, &ns);
    out->front = fogrt__surface_vertex_set(&v, &s->materials[fogrt_scene_get_prim_material(s, hit->prim)],
                                           fogrt__neg(d), p, ng, ns, false);
    out->p = p; out->ng = v.ng; out->material = *v.m;
    out->s = v.frame.s; out->t = v.frame.t; out->n = v.frame.n;
}
FOGRT__PUBLIC fogrt_vec3 fogrt_surface_offset(const fogrt_scene *s, const fogrt_surface *sf, fogrt_vec3 w) {
    return fogrt__offset(s, sf->p, sf->ng, w);
}
FOGRT__PUBLIC float fogrt_scene_light_pdf(const fogrt_scene *s, fogrt_vec3 from, const fogrt_hit *hit,
                                          const fogrt_surface *sf) {
    return fogrt__area_light_pdf(s, hit->prim, from, sf->p, sf->ng);
}
FOGRT__PUBLIC bool fogrt_scene_visible(const fogrt_scene *s, const fogrt_surface *sf, fogrt_vec3 p,
                                       const fogrt_light_sample *ls) {
    fogrt__vertex v;
    uint64_t rays = 0;
    memset(&v, 0, sizeof v);
    v.p = p;
    v.is_medium = sf == NULL;                 /* no offset in the fog; no transmittance either way */
    if (sf) v.ng = sf->ng;
    return fogrt__shadow(s, &v, ls, &rays) > 0.0f;
}
FOGRT__PUBLIC void fogrt_camera_ray(const fogrt_scene *s, int width, int height, float px, float py,
                                    float lens_u1, float lens_u2, fogrt_vec3 *o, fogrt_vec3 *d) {
    FOGRT_ASSERT(s && o && d);
    fogrt__camera c = fogrt__camera_setup(s, width, height);
    fogrt__camera_generate(&c, width, height, px, py, lens_u1, lens_u2, o, d);
}
FOGRT__PUBLIC fogrt_vec3 fogrt_trace(const fogrt_scene *s, const fogrt_render_desc *desc, fogrt_vec3 o, fogrt_vec3 d,
                                     fogrt_rng *rng, uint64_t *ray_count) {
    fogrt__settings st;
    uint64_t rays = 0;
    FOGRT_ASSERT(s && rng);
    if (!s->built || fogrt__resolve_render(s, desc, &st, NULL) != FOGRT_RESULT_OK) return fogrt__v(0.0f, 0.0f, 0.0f);
    o = fogrt__radiance(s, &st, o, fogrt__normalize(d), rng, &rays);
    if (ray_count) *ray_count += rays;
    return o;
}
/* One more name in a list of samplers. */
FOGRT__PRIVATE void fogrt__say(char *buf, size_t size, bool yes, const char *name) {
    size_t n = strlen(buf);
    if (!yes || n + 1 >= size) return;
    if (n) strncat(buf, ", ", size - n - 1);
    strncat(buf, name, size - strlen(buf) - 1);
}
FOGRT__PUBLIC const char *fogrt_render_samplers(const fogrt_scene *s, const fogrt_render_desc *desc, char *buf,
                                                size_t size) {
    fogrt__settings st;
    FOGRT_ASSERT(s && buf && size > 0);
    buf[0] = '\0';
    if (!s->built || fogrt__resolve_render(s, desc, &st, NULL) != FOGRT_RESULT_OK) return buf;
    const fogrt_render_desc *d = &st.desc;
    fogrt__say(buf, size, st.integrator == FOGRT_INTEGRATOR_DIRECT, "one bounce");
#ifndef FOGRT_MINIMAL
    if (fogrt__full_wanted(s, &st)) {
        fogrt__full_samplers(s, &st, buf, size);
        return buf;
    }
#endif
    bool fog = (s->features & FOGRT_FEATURE_MEDIUM) != 0;
    fogrt__say(buf, size, fog, "free flight");
    fogrt__say(buf, size, d->nee, d->mis ? "light sampling + MIS" : "light sampling");
    fogrt__say(buf, size, fog, "HG");
    fogrt__say(buf, size, true, "BSDF");
    fogrt__say(buf, size, st.max_depth > d->rr_depth, "roulette");
    return buf;
}
/* 8-bit output. */
/* The sRGB curve: 12.92 x below 0.0031308, else 1.055 x^(1/2.4) - 0.055. */
FOGRT__PUBLIC void fogrt_tonemap_rgb8(const float *rgb, int width, int height, float exposure,
                                      fogrt_tonemap mode, unsigned char *out) {
    size_t n = (size_t)FOGRT__MAX(width, 0) * (size_t)FOGRT__MAX(height, 0) * 3;
    float e = exp2f(fogrt__finite(exposure) ? FOGRT__CLAMP(exposure, -64.0f, 64.0f) : 0.0f);
    for (size_t i = 0; i < n; ++i) {
        float x = rgb[i] * e;
        if (!(x > 0.0f)) x = 0.0f;                   /* also NaN -> 0 */
        if (x > 1.0f) x = 1.0f;
        if (mode == FOGRT_TONEMAP_GAMMA22) x = powf(x, 1.0f / 2.2f);
        else x = x <= 0.0031308f ? 12.92f * x : 1.055f * powf(x, 1.0f / 2.4f) - 0.055f;
        out[i] = (unsigned char)(x * 255.0f + 0.5f);
    }
}
#ifndef FOGRT_NO_STDIO
FOGRT__PUBLIC fogrt_result fogrt_write_ppm(const char *path, int width, int height, const unsigned char *rgb8) {
    if (!path || !rgb8 || width <= 0 || height <= 0) return FOGRT_RESULT_INVALID_ARGUMENT;
    FILE *f = fopen(path, "wb");
    if (!f) return FOGRT_RESULT_IO_ERROR;
    bool ok = fprintf(f, "P6\n%d %d\n255\n", width, height) > 0;
    ok = ok && fwrite(rgb8, 3, (size_t)width * (size_t)height, f) == (size_t)width * (size_t)height;
    if (fclose(f) != 0) ok = false;
    return ok ? FOGRT_RESULT_OK : FOGRT_RESULT_IO_ERROR;
}
#endif

/* ------------------------------------------------------------------------------------------
   Checks of what lies beyond Part I
   A desc that asks for what a build left out (FOGRT_MINIMAL, FOGRT_NO_<APPENDIX>, or Part I's
   own FOGRT_NO_MEDIUM and FOGRT_NO_GLASS) fails with FOGRT_RESULT_UNSUPPORTED and one line
   naming the macro. Part I runs these checks on every desc it takes; in a full build they
   pass everything but the scene's media inside shapes (H), checked before a build.
   ------------------------------------------------------------------------------------------ */
/* A pixel counts its samples in 32 bits: a render that would take one past 2^32 - 1 is
   refused before it starts (the count would wrap and the mean jump by orders of magnitude).
   With rates a pixel takes at most spp x rate + 1 samples in the call. */
FOGRT__PRIVATE fogrt_result fogrt__check_count_room(const fogrt_scene *s, const fogrt_render_desc *d,
                                                    const fogrt_image *img, int spp) {
    size_t n = (size_t)img->width * (size_t)img->height;
    for (size_t i = 0; i < n; ++i) {
        double rate = d->sample_rate ? (double)d->sample_rate[i] : 0.0;
        double most = d->sample_rate ? ceil((double)spp * rate) + 1.0 : (double)spp;
        if ((double)img->count[i] + most > 4294967295.0)
            return fogrt__fail(s, FOGRT_RESULT_TOO_LARGE,
                               "render: samples_per_pixel more would take a pixel's sample count "
                               "past 2^32 - 1, the most it counts (render into a new or cleared "
                               "image)");
    }
    return FOGRT_RESULT_OK;
}
FOGRT__PRIVATE fogrt_result fogrt__beyond_material(const fogrt_scene *s, const fogrt_material_desc *m) {
#ifdef FOGRT_NO_GLASS
    FOGRT__REFUSE_IF(m->type == FOGRT_BSDF_REFRACTION || m->type == FOGRT_BSDF_GLASS, UNSUPPORTED,
                     "material.type: refraction and glass need a build without FOGRT_NO_GLASS");
#endif
#ifdef FOGRT_NO_SHAPES
    FOGRT__REFUSE_IF(m->type == FOGRT_BSDF_INTERFACE, UNSUPPORTED,
                     "material.type: interface needs a build without FOGRT_NO_SHAPES, FOGRT_NO_MEDIA and FOGRT_MINIMAL");
#endif
#ifdef FOGRT_NO_MICROFACET
    FOGRT__REFUSE_IF(m->type == FOGRT_BSDF_MICROFACET, UNSUPPORTED,
                     "material.type: microfacet needs a build without FOGRT_NO_MICROFACET and FOGRT_MINIMAL");
#else
    if (m->type == FOGRT_BSDF_MICROFACET) return fogrt__mf_check(s, m);   /* I */
#endif
    (void)s; (void)m;
    return FOGRT_RESULT_OK;
}
FOGRT__PRIVATE bool fogrt__box_ok(fogrt__v3 lo, fogrt__v3 hi) {
    return fogrt__coord_ok(lo.x) && fogrt__coord_ok(lo.y) && fogrt__coord_ok(lo.z) &&
           fogrt__coord_ok(hi.x) && fogrt__coord_ok(hi.y) && fogrt__coord_ok(hi.z) &&
           lo.x < hi.x && lo.y < hi.y && lo.z < hi.z;
}
FOGRT__PRIVATE fogrt_result fogrt__beyond_medium(const fogrt_scene *s, const fogrt_medium_desc *m) {
    FOGRT__REFUSE_IF(m->bounded && !fogrt__box_ok(m->bounds_min, m->bounds_max), INVALID_MEDIUM,
                     "medium.bounds_min/bounds_max: not finite, beyond 1e30, or min not below max on every axis");
#ifdef FOGRT_NO_ESTIMATION
    FOGRT__REFUSE_IF(m->bounded && m->sigma_t > 0.0f, UNSUPPORTED,
                     "medium.bounded: fog in a box needs a build without FOGRT_NO_ESTIMATION and FOGRT_MINIMAL");
#endif
#ifdef FOGRT_NO_MEDIUM
    FOGRT__REFUSE_IF(m->sigma_t > 0.0f, UNSUPPORTED, "medium: fogrt was compiled with FOGRT_NO_MEDIUM");
#endif
#ifdef FOGRT_NO_MEDIA
    FOGRT__REFUSE_IF(m->phase || m->g2 != 0.0f || m->w != 0.0f || !fogrt__is_black(m->emission) || !fogrt__is_black(m->sigma_t_rgb),
                     UNSUPPORTED, "medium.phase/g2/w/emission/sigma_t_rgb: media beyond the paper need a build without FOGRT_NO_MEDIA, FOGRT_NO_MEDIUM and FOGRT_MINIMAL");
#endif
    (void)s; (void)m;
    return FOGRT_RESULT_OK;
}
FOGRT__PRIVATE fogrt_result fogrt__beyond_build(const fogrt_scene *s, const fogrt_build_desc *d) {
#ifdef FOGRT_NO_WIDE_BVH
    FOGRT__REFUSE_IF(d->layout == FOGRT_BVH_LAYOUT_WIDE, UNSUPPORTED,
                     "build desc: layout wide needs a build without FOGRT_NO_WIDE_BVH (and FOGRT_MINIMAL)");
#endif
    (void)d;
#ifndef FOGRT_NO_SHAPES
    return fogrt__shapes_check(s);                       /* H */
#else
    (void)s;
    return FOGRT_RESULT_OK;
#endif
}

FOGRT__PRIVATE fogrt_result fogrt__beyond_render(const fogrt_scene *s, const fogrt_render_desc *d) {
#ifdef FOGRT_NO_EXACT_FRESNEL
    FOGRT__REFUSE_IF(d->fresnel == FOGRT_FRESNEL_EXACT, UNSUPPORTED,
                     "render desc: fresnel exact needs a build without FOGRT_NO_EXACT_FRESNEL, FOGRT_NO_ESTIMATION and FOGRT_MINIMAL");
#endif
#ifdef FOGRT_NO_LAMPS_IN_FOG
    FOGRT__REFUSE_IF(d->equiangular || d->glow || d->footprint || d->expected_emission, UNSUPPORTED,
                     "render desc: equiangular, glow, footprint and expected_emission need a build without FOGRT_NO_LAMPS_IN_FOG and FOGRT_MINIMAL (start from fogrt_render_paper_defaults())");
#endif
#ifdef FOGRT_NO_ESTIMATION
    FOGRT__REFUSE_IF(d->light_by_power || d->sample_rate, UNSUPPORTED,
                     "render desc: light_by_power and sample_rate need a build without FOGRT_NO_ESTIMATION and FOGRT_MINIMAL");
#endif
    (void)s; (void)d;
    return FOGRT_RESULT_OK;
}

/* The per-pixel rates (C): checked against the image's size. */
FOGRT__PRIVATE fogrt_result fogrt__beyond_image(const fogrt_scene *s, const fogrt_render_desc *d, const fogrt_image *img) {
    size_t n = d->sample_rate ? (size_t)img->width * (size_t)img->height : 0;
    for (size_t i = 0; i < n; ++i)
        FOGRT__REFUSE_IF(!(d->sample_rate[i] >= 0.0f && d->sample_rate[i] <= FOGRT_MAX_SAMPLE_RATE), INVALID_ARGUMENT,
                         "render desc: a sample_rate is NaN, negative or above FOGRT_MAX_SAMPLE_RATE (64)");
    return FOGRT_RESULT_OK;
}

#endif /* FOGRT_IMPLEMENTATION_INCLUDED */
#endif /* FOGRT_IMPLEMENTATION */

/*
   REVISION HISTORY
   0.1  first release: SAH/volume BVH, four BSDFs, homogeneous fog with HG, path tracing with
        NEE + MIS, one-bounce baseline, point/spot/area lights, pinhole and thin-lens cameras.

   LICENSE (MIT)
   Copyright (c) 2026 the fogrt authors

   Permission is hereby granted, free of charge, to any person obtaining a copy of this
   software and associated documentation files (the "Software"), to deal in the Software
   without restriction, including without limitation the rights to use, copy, modify, merge,
   publish, distribute, sublicense, and/or sell copies of the Software, and to permit persons
   to whom the Software is furnished to do so, subject to the following conditions:

   The above copyright notice and this permission notice shall be included in all copies or
   substantial portions of the Software.

   THE SOFTWARE IS PROVIDED "AS IS", WITHOUT WARRANTY OF ANY KIND, EXPRESS OR IMPLIED,
   INCLUDING BUT NOT LIMITED TO THE WARRANTIES OF MERCHANTABILITY, FITNESS FOR A PARTICULAR
   PURPOSE AND NONINFRINGEMENT. IN NO EVENT SHALL THE AUTHORS OR COPYRIGHT HOLDERS BE LIABLE
   FOR ANY CLAIM, DAMAGES OR OTHER LIABILITY, WHETHER IN AN ACTION OF CONTRACT, TORT OR
   OTHERWISE, ARISING FROM, OUT OF OR IN CONNECTION WITH THE SOFTWARE OR THE USE OR OTHER
   DEALINGS IN THE SOFTWARE.
*/
