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
                     including g = 0 exactly).
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

/* ---- Step 9 (bonus): equiangular sampling toward a point light ----------------------------
   A ray segment t in [a, b] (b may be +infinity) passes a point light; the light's closest
   approach to the ray's line is at t = delta, at distance h > 0. Sample t with density
   proportional to 1 / (h^2 + (t - delta)^2), which cancels the light's 1 / r^2 (the paper's
   section 5 asks for importance sampling in fog). Return t and store its pdf; the pdf
   function gives the same density at any t (0 outside [a, b]).                            */
float cw_sample_equiangular(float delta, float h, float a, float b, float u, float *pdf);
float cw_equiangular_pdf(float delta, float h, float a, float b, float t);

#endif
