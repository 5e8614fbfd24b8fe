/* coursework.h - the functions a student writes in fogrt's coursework kit (docs/coursework.md).

   Each step's skeleton (examples/coursework/stepN_*.c) includes this header and defines that
   step's functions; `make check-step STEP=N` links the file with the checker
   (examples/coursework/check_step.c), which calls them with numbers it chooses and judges
   the answers with the statistics fogrt judges itself with. The declarations below are the
   contract: the checker calls exactly these signatures, so a misspelt name or a changed
   argument shows up as a compile or link error, not as a mysterious statistical failure.

   Everything is float, as in fogrt.h: the uniform numbers u the checker passes lie in
   [0, 1 - 2^-24], the range fogrt_rng_float produces (never 1, but 0 happens). You may
   compute in double inside. You may call any public fogrt.h function that is not the
   answer itself (vector helpers are yours to write; fogrt_reflect is fine in step 5).

   Conventions (the same as fogrt.h's):
   - Directions wo and wi both point away from the interaction point; a ray arriving there
     travels along d = -wo.
   - Henyey-Greenstein: mu = cos(angle between d and wi); g > 0 scatters forward, along d.
   - BSDFs work in the local shading frame: the normal is +z.                              */
#ifndef FOGRT_COURSEWORK_H
#define FOGRT_COURSEWORK_H

#include "fogrt.h"

/* ---- Step 1: free-flight distance sampling (paper section 3.1, eq. 4-6) ------------------
   The distance t to the next collision with fog is exponentially distributed with rate
   sigma_t (the paper's lambda): invert eq. 6's CDF with u in [0, 1). The pdf is the
   density of that distribution at t (zero for t < 0). Both must stay finite for u = 0,
   u = 1 - 2^-24 and sigma_t between 1e-6 and 1e6.                                          */
float cw_sample_free_flight(float sigma_t, float u);
float cw_free_flight_pdf(float sigma_t, float t);

/* ---- Step 2: transmittance (paper section 3.2, eq. 7-8) -------------------------------------
   cw_transmittance: the fraction of light left after `distance` through homogeneous fog,
   eq. 8 (sigma_t = 0: clear air; distance = +infinity allowed).
   cw_transmittance_estimate: an unbiased one-sample estimate of the same number using only
   a free-flight sample (your step 1 function, or fogrt_sample_exponential) drawn with u:
   its mean over many u must be the transmittance. (This is how a path tracer can answer a
   shadow query in fog without knowing eq. 8.)                                               */
float cw_transmittance(float sigma_t, float distance);
float cw_transmittance_estimate(float sigma_t, float distance, float u);

/* ---- Step 3: the Henyey-Greenstein phase function (paper section 3.3, eq. 9-12) -----------
   cw_hg_phase:      eq. 9, per steradian, as a function of mu = cos(theta).
   cw_sample_hg_mu:  eq. 10-11, the inverse-CDF sample of mu for one uniform u (|g| < 1,
                     including g = 0 exactly), in the paper's direction: mu rises with u,
                     mu = -1 at u = 0 (texts that write mu falling in u, as PBRT-v3 does,
                     sample the same distribution, but the checks hold you to this one).
   cw_sample_hg:     a full unit direction wi around the propagation direction d = -wo:
                     mu from u1 (eq. 11), the azimuth phi from u2 (eq. 12).                 */
float cw_hg_phase(float g, float mu);
float cw_sample_hg_mu(float g, float u);
fogrt_vec3 cw_sample_hg(float g, fogrt_vec3 wo, float u1, float u2);

/* ---- Step 4: the BVH split choice (paper section 2.1, eq. 1-2) -------------------------------
   A node's primitives are split by a plane. Its candidates come from binning: along each
   axis the centroid range is cut into n_bins equal slices; bin k holds count[a][k]
   primitives and box[a][k] is the box around them (an empty bin has count 0 and lo > hi:
   do not use its box). Plane k of axis a puts bins 0..k-1 on the left, k..n_bins-1 on the
   right (k = 1..n_bins-1).
   cw_split_cost: the heuristic's cost of one split:
     CW_SAH     the surface area heuristic with traversal and intersection costs 1:
                1 + (N_l A_l + N_r A_r) / A, A the surface area of the parent's box;
     CW_VOLUME  the paper's heuristic, eq. 1: H = N_l V_l + N_r V_r (V the volume).
   cw_best_split: the cheapest plane over all three axes (eq. 2) under that heuristic; a
   plane with no primitive on one side is not a split. Return the axis and the plane, and
   its cost; plane = -1 if no plane splits the node.                                         */
#define CW_MAX_BINS 32
enum { CW_SAH = 0, CW_VOLUME = 1 };
typedef struct cw_aabb { float lo[3], hi[3]; } cw_aabb;
typedef struct cw_bins {
    int n_bins;
    int count[3][CW_MAX_BINS];
    cw_aabb box[3][CW_MAX_BINS];
} cw_bins;
typedef struct cw_split { int axis, plane; float cost; } cw_split;

float cw_split_cost(int heuristic, const cw_aabb *parent, const cw_aabb *left, int n_left,
                    const cw_aabb *right, int n_right);
cw_split cw_best_split(int heuristic, const cw_aabb *parent, const cw_bins *bins);

/* ---- Step 5: BSDF sampling (paper sections 2.2 and 4.2, eq. 3) ------------------------------
   White materials (reflectance and transmittance 1), local frame with the normal along +z,
   wo.z != 0 (wo.z < 0: wo is below the surface; for glass, inside it).
   A sample holds the direction wi (unit), its pdf (per steradian for diffuse; for the
   specular lobes, the probability of choosing that lobe), and the weight f |cos| / pdf the
   path's throughput is multiplied by (eq. 3 and 13).
     diffuse  cosine-weighted on wo's side of the surface, f = 1/pi; return 0 if no sample.
     mirror   the perfect reflection of wo.
     glass    index eta inside (the side opposite +z) relative to outside; reflect with the
              probability F of Schlick's approximation, else refract (Snell); on total
              internal reflection always reflect.
   cw_fresnel_schlick(eta, cos_i): Schlick's F for light meeting the surface with
   cos_i = wo.z (> 0 outside, < 0 inside); 1 on total internal reflection.               */
typedef struct cw_bsdf_sample {
    fogrt_vec3 wi;
    float pdf;
    float weight;
} cw_bsdf_sample;

int cw_sample_diffuse(fogrt_vec3 wo, float u1, float u2, cw_bsdf_sample *s);
float cw_diffuse_pdf(fogrt_vec3 wo, fogrt_vec3 wi);
int cw_sample_mirror(fogrt_vec3 wo, cw_bsdf_sample *s);
float cw_fresnel_schlick(float eta, float cos_i);
int cw_sample_glass(float eta, fogrt_vec3 wo, float u_lobe, cw_bsdf_sample *s);

/* ---- Steps 6-8 work on a built scene with fogrt's public building blocks (fogrt.h, "Building
   blocks of an integrator"): fogrt_scene_intersect, fogrt_scene_surface, fogrt_surface_offset,
   fogrt_scene_light_total, fogrt_scene_sample_light, fogrt_scene_light_pdf,
   fogrt_scene_visible, fogrt_scene_get_medium; and for sampling your own steps 1, 3 and 5 or
   fogrt's (fogrt_sample_exponential, fogrt_sample_hg, fogrt_hg_pdf, fogrt_sample_bsdf,
   fogrt_bsdf_eval, fogrt_bsdf_pdf, fogrt_transmittance). Random numbers come from the rng
   the checker passes (fogrt_rng_float). The checker's scenes have diffuse surfaces only (no
   mirrors or glass), no environment light, and fog (when there is any) fills all space, so
   a camera ray starts in the fog exactly when the medium's sigma_t > 0.
   A surface from fogrt_scene_surface gives the BSDF's local frame (s, t, n): a world
   direction w is (dot(w, s), dot(w, t), dot(w, n)) there; n is on the side the ray came from.

   ---- Step 6: direct lighting at a vertex by light sampling (paper section 2.3, eq. 3) -----
   The light that comes straight from the lights to a scattering vertex and leaves it toward
   wo (unit, pointing back along the ray that arrived there), estimated with ONE sample of
   EVERY light (lights 0 .. fogrt_scene_light_total() - 1; three numbers from rng for each):
        sum over the lights of   f(wo, wi) Le T / pdf    (0 when the sample fails or is blocked)
   with wi, Le, pdf and dist from fogrt_scene_sample_light, visibility from
   fogrt_scene_visible, T the transmittance of eq. 8 over dist (1 without fog), and
     cw_direct_surface  at the surface point sf: f = BSDF x |cos| between wi and sf->n (the
                        checker's surfaces are diffuse: reflectance / pi on wo's side of the
                        surface, 0 behind it);
     cw_direct_fog      at the point p in the fog: f = the HG phase function (eq. 9) of the
                        scene's medium at the angle between the propagation direction -wo and
                        wi; no cosine. The fog's albedo is not yours to apply here: the caller
                        multiplies by it at the collision, as Algorithm 1 does.
   A point or spot light (ls.is_delta) has pdf 1 and Le = I / r^2.                          */
fogrt_vec3 cw_direct_surface(const fogrt_scene *scene, const fogrt_surface *sf, fogrt_vec3 wo, fogrt_rng *rng);
fogrt_vec3 cw_direct_fog(const fogrt_scene *scene, fogrt_vec3 p, fogrt_vec3 wo, fogrt_rng *rng);

/* ---- Steps 7 and 8: a path tracer of your own, plugged into fogrt_render ------------------
   The function is a fogrt_render_desc.radiance: one sample of the radiance arriving at o
   along -d (d unit), drawing every random number from rng. fogrt_render runs it on its
   threads, for every pixel sample, and keeps the image and its error estimate. user points
   to the checker's settings, which your function must follow (fogrt's render desc has the
   same two fields, and its image is the reference):
     max_depth  the most scattering events (fog collisions and surface bounces) after the
                camera ray; light sampling happens at a vertex only while fewer than
                max_depth events came before it; -1: no limit (the roulette ends paths)
     rr_depth   Russian roulette after each scattering event once more than rr_depth have
                happened: continue with a probability q of your choice (fogrt's is
                min(0.95, the largest component of the throughput)).
   Algorithm 1 (section 3.4): from the camera ray on, the nearer of the surface hit and the
   fog collision (free flight, eq. 6) is the next vertex; at a fog collision the throughput
   is multiplied by the medium's albedo; light sampling there (step 6), then a new direction
   (HG in fog, the BSDF on a surface) with the weight of eq. 13, f cos / pdf; then the
   roulette. A path ends when the ray leaves the scene.
   Emission: a surface with non-zero material.emission emits from its front only
   (fogrt_surface.front).
     Step 7 (cw_path_radiance): without MIS. Light sampling finds every light at every vertex,
       so emission reached by a ray counts only when that ray is the camera ray: otherwise the
       same light would be counted twice.
     Step 8 (cw_mis_radiance): with MIS, power heuristic (cw_mis_weight(pdf_this, pdf_other)
       = pdf_this^2 / (pdf_this^2 + pdf_other^2), 0 when pdf_this is 0). A light sample from
       an area light is weighted with pdf_this = ls.pdf against the density with which the
       BSDF or phase sampling would have picked wi (point and spot lights: weight 1); emission
       reached by a ray that BSDF or phase sampling chose with density pdf from the vertex x
       is weighted with pdf_this = pdf against fogrt_scene_light_pdf(scene, x, hit, sf)
       (the camera ray's emission: weight 1).                                               */
typedef struct cw_path_settings {
    int max_depth;
    int rr_depth;
} cw_path_settings;
fogrt_vec3 cw_path_radiance(const fogrt_scene *scene, fogrt_vec3 o, fogrt_vec3 d, fogrt_rng *rng, void *user);
float cw_mis_weight(float pdf_this, float pdf_other);
fogrt_vec3 cw_mis_radiance(const fogrt_scene *scene, fogrt_vec3 o, fogrt_vec3 d, fogrt_rng *rng, void *user);

/* ---- Step 9 (bonus): equiangular sampling toward a point light ----------------------------
   A ray segment t in [a, b] (b may be +infinity) passes a point light; the light's closest
   approach to the ray's line is at t = delta, at distance h > 0. Sample t with density
   proportional to 1 / (h^2 + (t - delta)^2), which cancels the light's 1 / r^2 (the paper's
   section 5 asks for importance sampling in fog). Return t and store its pdf; the pdf
   function gives the same density at any t (0 outside [a, b]). Convention: t rises with u
   from t = a at u = 0 (the inverse CDF from the near end; sampling from b is the same
   distribution, but the checks hold you to this one).                                      */
float cw_sample_equiangular(float delta, float h, float a, float b, float u, float *pdf);
float cw_equiangular_pdf(float delta, float h, float a, float b, float t);

#endif
